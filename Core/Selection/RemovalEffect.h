// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file RemovalEffect.h
 * @brief Before / after measurement of a clean-up (issue 20): what deleting (or hiding) a set
 * of Gaussians does to the reconstruction, measured against the training and test images with
 * the exact rasteriser, per view and in total, with the views that got worse first.
 *
 * Metrics per view are those the trainer logs (Core/Training/Loss.h): the render clamped to
 * [0, 1] against the image, PSNR over every channel and pixel, SSIM (11x11 Gaussian window),
 * L1 mean absolute difference, each summed per 16x16 tile (ViewTileSums.h; the same figures up
 * to the order of the additions); totals are means over the views of a split, as the
 * trainer's /metrics rows are.
 *
 * What is reused, exactly: a view in which no removed Gaussian survives the rasteriser's
 * culls (near plane, degenerate, off screen, invalid) is not rendered again: its "after"
 * image is bit for bit its "before" image (the removed Gaussians were in none of its tile
 * lists, and the kept ones keep their relative order, so every tile blends the same sequence).
 * Deciding this projects only the removed Gaussians. The "before" figures do not depend on
 * the selection: MeasureViewMetrics() computes them once, and previews of several selections
 * pass them in (RemovalEffectOptions::Baseline), so that each preview renders only the views
 * its selection touches, once.
 *
 * Tiles (ViewTileSums.h): with the "before" of a view kept per 16x16 tile (RemovalBaseline),
 * its "after" re-renders only the tiles that list a removed Gaussian (the union of the removed
 * Gaussians' tile rectangles, D) and two tiles around them, and re-measures D and one tile
 * around it (the SSIM window reaches 5 pixels into the neighbouring tiles, whose own windows
 * reach 5 pixels further). Every other tile's pixels are the "before" ones bit for bit (as
 * above, tile by tile), and a re-rendered tile is rendered exactly as in a full render (its
 * list holds the same Gaussians in the same order), so the "after" figures equal those of a
 * full re-render measured per tile, bit for bit. The score pass, which renders every training
 * view anyway, keeps these sums at full resolution (RecordRemovalBaseline()).
 */
#ifndef vis4gs_RemovalEffect_h
#define vis4gs_RemovalEffect_h

#include "ArtifactScores.h" // TrainingImageProvider
#include "Camera.h"
#include "GaussianCloud.h"
#include "ImageIO.h"
#include "Rasterizer.h"
#include "ViewTileSums.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace vis4gs
{

/// One view before and after the removal.
struct RemovalViewEffect
{
  std::size_t CameraIndex = 0;
  std::string Name;
  CameraSplit Split = CameraSplit::Train;
  /// Whether a removed Gaussian takes part in this view (else After == Before, not rendered).
  bool Affected = false;
  /// Whether the view has an image (else its metrics are NaN and it is in no total).
  bool HasImage = false;
  ViewMetrics Before, After;
  double PsnrChange() const { return this->After.Psnr - this->Before.Psnr; }
};

/// Means over the views of one split that have an image.
struct RemovalTotals
{
  std::size_t Views = 0;
  std::size_t AffectedViews = 0;
  ViewMetrics Before, After;
};

struct RemovalEffect
{
  std::size_t Removed = 0; ///< Gaussians removed
  std::size_t Kept = 0;    ///< Gaussians left
  /// Every view measured, the largest PSNR drop first (After - Before ascending; views
  /// without an image last; ties in camera order).
  std::vector<RemovalViewEffect> Views;
  RemovalTotals Train, Test;
  std::size_t ViewsRendered = 0; ///< renders made (before and after), whole or in part
  /// Tiles rendered for the "after" of the affected views with tile reuse, and the tiles of
  /// those views (their ratio is the part of a full re-render that was made).
  std::size_t TilesRendered = 0;
  std::size_t TilesOfTiledViews = 0;
  std::size_t ViewsWithoutImage = 0; ///< views skipped for lack of an image
  double SecondsBefore = 0;          ///< rendering and measuring the "before" state
  double SecondsAfter = 0;           ///< finding the affected views, rendering and measuring them
};

/**
 * The "before" of a clean-up per tile, for every camera, and what it was rendered with:
 * MeasureRemovalEffect() refuses one made with other rasteriser settings or for a cloud of
 * another size.
 */
struct RemovalBaseline
{
  /// One per camera; empty sums for a view not measured (MeasureRemovalEffect() renders it).
  std::vector<ViewTileSums> Views;
  std::size_t Gaussians = 0;
  std::array<double, 3> Background{ 0.0, 0.0, 0.0 };
  int ShDegree = -1;
  double ScaleModifier = 1.0;
  /// Views with sums.
  std::size_t MeasuredViews() const;
};

struct RemovalEffectOptions
{
  /// Rasteriser options (background, SH degree); threads are set from Threads.
  RasterSettings Raster;
  bool TrainViews = true; ///< measure the training views
  bool TestViews = true;  ///< measure the test views
  /// The "before" figures of every camera (MeasureViewMetrics() of the same cloud, cameras and
  /// settings), or empty to compute them here.
  std::vector<ViewMetrics> Baseline;
  /// The "before" per tile (RecordRemovalBaseline(), MeasureRemovalBaseline()), or empty. A view
  /// it holds is not rendered "before", and its "after" re-renders only the tiles the removal
  /// changes. Where it holds a view, it is used instead of Baseline.
  RemovalBaseline TileBaseline;
  /// Measure per tile and re-render only the changed tiles of an affected view (default true);
  /// false renders and measures every affected view whole (the previous implementation, for
  /// tests and benchmarks: the figures agree to about 1e-15 relative, the order of the sums).
  bool ReuseTiles = true;
  int Threads = 0; ///< OpenMP threads; 0 uses OpenMP's default
};

/// A render clamped to [0, 1] as an Image: what the figures are measured on (the trainer and
/// the reference evaluation clamp the same way).
Image ClampedImage(const RasterImage<float>& render);

/// Means of @p figures over the cameras of @p split that were measured (NaN figures are views
/// without an image); NaN, and @p views 0, when there is none.
ViewMetrics MeanViewMetrics(const std::vector<ViewMetrics>& figures,
  const std::vector<Camera>& cameras,
  CameraSplit split,
  std::size_t* views = nullptr);

/// The cloud without the Gaussians where @p removed is non-zero (one byte per Gaussian), every
/// array (ids, extras) kept in order. Throws std::invalid_argument on a size mismatch.
GaussianCloud RemoveGaussians(const GaussianCloud& cloud, const std::vector<std::uint8_t>& removed);

/// The figures of @p cloud in every camera (NaN for views of a split not asked for or without
/// an image): the "before" of any removal, computed once.
std::vector<ViewMetrics> MeasureViewMetrics(const GaussianCloud& cloud,
  const std::vector<Camera>& cameras,
  const RemovalEffectOptions& options,
  const TrainingImageProvider& images);

/**
 * Makes the score pass of @p settings (ComputeGaussianScores() of @p cloud and @p cameras)
 * keep the "before" of a clean-up: its ViewRendered hook (an earlier hook still runs) measures
 * every view it renders per tile into @p baseline, which must outlive the score computation.
 * Only a full-resolution score pass can (LossResolution 1): at a reduced resolution nothing is
 * installed and false is returned, and MeasureRemovalBaseline() renders the "before" instead.
 * Test views and views the scores skip (ViewStride, ViewList) stay empty.
 */
bool RecordRemovalBaseline(ScoreSettings& settings,
  const GaussianCloud& cloud,
  const std::vector<Camera>& cameras,
  RemovalBaseline& baseline);

/**
 * The hook RecordRemovalBaseline() installs, for a caller that passes it on itself (the score
 * filter's SetViewRendered): it resets @p baseline for @p cloud, @p cameras and the score pass's
 * rasteriser settings @p raster, and measures every full-resolution render it is given into it.
 */
ScoreViewRendered RemovalBaselineRecorder(const GaussianCloud& cloud,
  const std::vector<Camera>& cameras,
  const RasterSettings& raster,
  int threads,
  RemovalBaseline& baseline);

/// The "before" per tile of every wanted view with an image, rendered here (what the score
/// pass gives for free at full resolution).
RemovalBaseline MeasureRemovalBaseline(const GaussianCloud& cloud,
  const std::vector<Camera>& cameras,
  const RemovalEffectOptions& options,
  const TrainingImageProvider& images);

/**
 * Measures removing the Gaussians where @p removed is non-zero (one byte per Gaussian of
 * @p cloud). Throws std::invalid_argument on a size mismatch, a baseline of the wrong size or a
 * tile baseline of other settings,
 * std::runtime_error (from @p images) naming an unreadable image and when an image's size
 * differs from its camera's.
 */
RemovalEffect MeasureRemovalEffect(const GaussianCloud& cloud,
  const std::vector<std::uint8_t>& removed,
  const std::vector<Camera>& cameras,
  const RemovalEffectOptions& options,
  const TrainingImageProvider& images);

} // namespace vis4gs

#endif

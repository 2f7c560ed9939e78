// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ScreenSelection.h
 * @brief Screen-space selection modes on the exact CPU rasteriser (Core/Render): Single,
 * Brush and Frame, plus the pixel ray of the Ray mode and the camera frustums of the
 * training views with the number of selected Gaussians each one sees.
 *
 * Pixels are in the rasteriser's convention: (x, y) with row 0 at the TOP, pixel (x, y)
 * sampled at integer coordinates. A Gaussian's blending weight at a pixel is
 * w = alpha * T, exactly as CompositeTiles()/AttributePixels() blend it (same float
 * arithmetic, same early stop at T < 1e-4).
 *
 *  - Single: the Gaussian with the largest weight at the clicked pixel (ties: front first),
 *    taken from the Ray set at that pixel, so always one of its members.
 *  - Ray: every Gaussian whose rasteriser footprint covers the pixel, occluded or not, in
 *    depth order with its alpha and alpha*T (SelectRay()).
 *  - Brush: the Gaussians whose largest weight over the brushed pixels is >= a threshold.
 *  - Frame: the Gaussians whose projected centre (U, V) lies in the rectangle of pixels
 *    [x0, x1] x [y0, y1] (i.e. x0 - 0.5 <= U < x1 + 0.5) and that are visible there: their
 *    largest weight over the rectangle's pixels is >= a threshold (visible INSIDE the
 *    rectangle, not merely somewhere in the view); with IncludeOccluded every projected (not
 *    culled) Gaussian with its centre inside is taken.
 *
 * PrepareSelectionView() projects and bins the scene once per camera (the costly part); the
 * selections then reuse it. ComputeViewMaxWeights() adds, once per camera, every Gaussian's
 * largest weight over the whole image (one exact compositing pass); SelectFrame then decides
 * most candidates from it without replaying pixels (same result, see SelectFrame()).
 */
#ifndef vis4gs_ScreenSelection_h
#define vis4gs_ScreenSelection_h

#include "Camera.h"
#include "GaussianCloud.h"
#include "GaussianOctree.h"
#include "Rasterizer.h"

#include <array>
#include <cstdint>
#include <vector>

namespace vis4gs
{

/// The scene projected and binned for one camera.
struct SelectionView
{
  ViewProjection<float> Projection;
  TileBins Bins;
  RasterSettings Settings;
  /// Largest blending weight w = alpha*T of each Gaussian over every pixel of the image, 0
  /// where it does not blend (ComputeViewMaxWeights()); empty until computed.
  std::vector<float> ViewMaxWeights;
};

/**
 * Fills view.ViewMaxWeights with one exact compositing pass over the whole image
 * (CompositeTiles' per-Gaussian MaxWeight: the same float arithmetic and early stop as
 * MaxWeightsOverPixels() over all pixels). Threads: view.Settings.Threads.
 */
void ComputeViewMaxWeights(SelectionView& view);

/**
 * Inclusive pixel box [x0, x1] x [y0, y1] (clipped to the image) outside which Gaussian
 * @p index cannot blend: its tile rectangle intersected with the box of the ellipse where
 * o e^power >= 1/255, widened by a safety margin for float rounding (1 pixel and 0.1 %);
 * the tile rectangle alone when the 2D covariance is not positive definite. Empty (x0 > x1)
 * for a culled Gaussian.
 */
std::array<int, 4> BlendBox(const ViewProjection<float>& projection, std::size_t index);

/// Projects (without colours) and bins @p cloud for @p camera. Throws like ProjectGaussians().
SelectionView PrepareSelectionView(const GaussianCloud& cloud,
  const Camera& camera,
  int threads = 0);

/// One Gaussian whose rasteriser footprint covers a pixel (see SelectRay()).
struct RayContribution
{
  std::uint32_t Gaussian = 0;     ///< index in the cloud
  std::uint32_t ListPosition = 0; ///< 1-based position in the pixel's tile list (depth order)
  double Depth = 0;               ///< view-space z of the mean
  double Alpha = 0;               ///< alpha = min(0.99, o e^power) >= 1/255
  double Transmittance = 0;       ///< T in front of it along the full composite
  double Weight = 0;              ///< alpha * T
  /// Blended by the compositor (false past its early stop at T < 1e-4: the pixel's colour
  /// does not contain it, yet its footprint covers the pixel).
  bool Blended = false;
};

/**
 * Ray mode at pixel (x, y): every Gaussian whose rasteriser footprint covers the pixel
 * (in the pixel's tile list, i.e. not culled at the near plane and its tile rectangle holds
 * the pixel, and alpha >= 1/255 there), occluded or not, in depth order, with its alpha and
 * alpha*T. T runs over the whole list, in the compositor's float arithmetic: up to the early
 * stop it is bit for bit the compositor's, so SelectSingle() (the largest weight among the
 * blended entries) is always a member of this set. Empty outside the image.
 */
std::vector<RayContribution> SelectRay(const ViewProjection<float>& projection,
  const TileBins& bins,
  int x,
  int y);

/// SelectRay() on a prepared view.
std::vector<RayContribution> SelectRay(const SelectionView& view, int x, int y);

/// The index SelectSingle() takes from a SelectRay() result: the blended entry with the
/// largest weight (ties: front first), or -1.
std::int64_t SingleFromRay(const std::vector<RayContribution>& ray);

/// Index of the Gaussian with the largest weight at pixel (x, y), or -1 when none blends there.
std::int64_t SelectSingle(const SelectionView& view, int x, int y);

/// SelectSingle() on a projection and its tile lists that the caller keeps (see the
/// SelectFrame() overload taking them).
std::int64_t SelectSingle(const ViewProjection<float>& projection,
  const TileBins& bins,
  int x,
  int y);

/**
 * Largest weight of every Gaussian over @p pixels (out-of-image pixels ignored): a dense
 * array, one float per Gaussian, 0 where it does not blend. Parallel over pixels. With
 * @p targets (one flag per Gaussian), only the flagged Gaussians' weights are wanted: each
 * tile's list is walked only up to its last flagged entry (the flagged weights are the same,
 * the others may be too small). Each Gaussian is evaluated only on the requested pixels of
 * its tile that lie in a box containing its BlendBox() (rows of a whole tile, bounding boxes
 * of 16 pixels otherwise): the other pixels cannot blend it, so the weights are those of a
 * replay of every Gaussian on every pixel, bit for bit.
 */
std::vector<float> MaxWeightsOverPixels(const SelectionView& view,
  const std::vector<std::array<int, 2>>& pixels,
  int threads = 0,
  const std::vector<std::uint8_t>* targets = nullptr);

/// The pixels of the image within @p radius (Euclidean, pixel centres) of the polyline
/// @p stroke (a single point is a disk), each once, in row-major order.
std::vector<std::array<int, 2>> BrushPixels(const std::vector<std::array<double, 2>>& stroke,
  double radius,
  int width,
  int height);

/// Indices (ascending) whose largest weight over @p pixels is >= @p threshold (> 0).
std::vector<std::uint32_t> SelectBrush(const SelectionView& view,
  const std::vector<std::array<int, 2>>& pixels,
  double threshold,
  int threads = 0);

/// SelectBrush() on a projection and its tile lists that the caller keeps (see the
/// SelectFrame() overload taking them).
std::vector<std::uint32_t> SelectBrush(const ViewProjection<float>& projection,
  const TileBins& bins,
  const std::vector<std::array<int, 2>>& pixels,
  double threshold,
  int threads = 0);

struct FrameOptions
{
  /// Minimum of the largest weight over the rectangle for a Gaussian to count as visible.
  double WeightThreshold = 0.01;
  /// Take every projected Gaussian with its centre inside, visible or not.
  bool IncludeOccluded = false;
  /// Replays evaluate a Gaussian only on the pixel vectors that meet a box containing its
  /// BlendBox() (outside it the kernel test always fails: no weight, T unchanged), instead of
  /// on every requested pixel of its tile (false: the straightforward replay, kept as the
  /// reference for tests and benchmarks). Same selection. Default on.
  bool CullReplay = true;
  int Threads = 0;
};

/**
 * Indices (ascending) selected by the rectangle [x0, x1] x [y0, y1] (corners in any order,
 * clipped to the image). Visible-only selection without view.ViewMaxWeights replays the
 * compositing of every pixel of the rectangle. With them, a candidate (centre inside) is
 * rejected when its largest weight over the view is below the threshold (its largest weight
 * over the rectangle can only be smaller), accepted when its BlendBox() lies inside the
 * rectangle (the largest weight over the view is then reached inside), and only the remaining
 * candidates, near the rectangle's border, are decided by replaying the rectangle's pixels
 * inside their blend boxes: the same selection as the full replay, at a fraction of its cost.
 */
std::vector<std::uint32_t> SelectFrame(const SelectionView& view,
  int x0,
  int y0,
  int x1,
  int y1,
  const FrameOptions& options = {});

/**
 * Frame selection on a projection and its tile lists that the caller keeps, without view
 * maxima: e.g. the scene view's last full-resolution frame (the RasterWorkspace its CPU
 * drawing path keeps), drawn for the same camera and cloud with unmodified opacities, whether
 * or not colours were computed. Reusing them saves PrepareSelectionView(); the selection is
 * the one SelectFrame() makes on PrepareSelectionView(cloud, camera) without view maxima
 * (only the geometry fields of the projection are read). Throws std::invalid_argument when
 * the bins do not belong to the projection or the threshold is not positive.
 */
std::vector<std::uint32_t> SelectFrame(const ViewProjection<float>& projection,
  const TileBins& bins,
  int x0,
  int y0,
  int x1,
  int y1,
  const FrameOptions& options = {});

/**
 * Whether a Brush or Frame selection of weight threshold @p threshold can be read from
 * @p record (a complete CompositeTiles() record whose Threshold is <= the selection's): then
 * every blend that passes the threshold is in it.
 */
bool RecordAnswers(const PixelWeightRecord& record, double threshold);

/**
 * SelectBrush() from the pixel weights the drawn frame's compositing kept (@p record, of
 * a projection of @p count Gaussians: the frame the tile lists of the other overloads
 * belong to): a Gaussian's largest weight over @p pixels reaches @p threshold exactly when
 * one of its blends there does, and the record holds all of those (RecordAnswers()), so the
 * selection is SelectBrush()'s, without replaying the compositing. Throws
 * std::invalid_argument when RecordAnswers() is false or the threshold is not positive.
 */
std::vector<std::uint32_t> SelectBrush(const PixelWeightRecord& record,
  std::size_t count,
  const std::vector<std::array<int, 2>>& pixels,
  double threshold);

/**
 * SelectFrame() from @p record, the pixel weights kept by the compositing of @p projection's
 * frame: the candidates (centre inside the rectangle) with a kept weight >= the threshold at a
 * pixel of the rectangle; the same selection as the replay (see the Brush overload). Throws
 * std::invalid_argument when RecordAnswers() is false (visible-only frames) or the record is
 * of another image size.
 */
std::vector<std::uint32_t> SelectFrame(const ViewProjection<float>& projection,
  const PixelWeightRecord& record,
  int x0,
  int y0,
  int x1,
  int y1,
  const FrameOptions& options = {});

/// The viewing ray through pixel (x, y) (fractional pixels allowed), for the optional 3D
/// k-sigma ellipsoid test (GaussianOctree::IntersectRay; not the Ray mode, whose set is the
/// drawn footprints, SelectRay()): origin at the camera centre, unit direction R^T ((x -
/// (W-1)/2)/fx, (y - (H-1)/2)/fy, 1) normalised; TMin = 0.
RayQuery PixelRay(const Camera& camera, double x, double y, double sigmas = 3.0);

/**
 * Apex and the four image corners (pixel corners (-0.5, -0.5), (W-0.5, -0.5),
 * (W-0.5, H-0.5), (-0.5, H-0.5), in that order) of @p camera's frustum at view depth
 * @p depth, in world coordinates.
 */
std::array<std::array<double, 3>, 5> CameraFrustum(const Camera& camera, double depth);

/**
 * The view depth at which frustums are drawn when the user has not set one: a tenth of the
 * diagonal of the camera centres' bounding box (for a ring of cameras around an object, about
 * a fifth of the way to it), but at least a tenth of the median distance from the camera
 * centres to the scene's median point (per-axis median of up to 65,536 evenly strided finite
 * means of @p positions, x y z per Gaussian), so that cameras standing close together
 * (forward-facing captures, a single camera) still get frustums in the scene's units, and far
 * floaters move nothing. 1 when both are 0 or not finite.
 */
double AutoFrustumDepth(const std::vector<Camera>& cameras,
  const float* positions,
  std::size_t count);

/**
 * For each camera, the number of Gaussians among @p indices that are visible in it: a
 * non-empty footprint |Omega(g, v)| >= 1 (DESIGN §4, Footprint.h, exact rasteriser mode),
 * whether occluded or not. Only the listed Gaussians are projected.
 */
std::vector<std::uint32_t> CountVisibleInViews(const GaussianCloud& cloud,
  const std::vector<std::uint32_t>& indices,
  const std::vector<Camera>& cameras,
  int threads = 0);

} // namespace vis4gs

#endif

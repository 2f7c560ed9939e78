// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatLevelOfDetail.h
 * @brief The level of detail of the scene view while the camera moves: which Gaussians a
 * moving frame draws when it may draw only a budget of them.
 *
 * A moving frame of the CPU rasteriser costs in proportion to the Gaussians it projects (view
 * transform, EWA projection, SH colour, ~100 B written per Gaussian), whatever its resolution.
 * A moving frame therefore projects only the budget's Gaussians of highest expected
 * contribution to that view (ProjectGaussianSubset, Core/Render/Rasterizer.h): a Gaussian's
 * contribution is its opacity times its projected area, opacity * s_a * s_b / z^2 with s_a,
 * s_b its two largest scales and z the view depth of its centre (the area of its largest
 * cross-section seen from distance z, up to the focal length squared, which is the same for
 * every Gaussian). Gaussians whose 3-sigma sphere lies outside the view's frustum or before
 * the near plane are culled first. The view-independent part (opacity times area, 3-sigma
 * reach) is computed once per scene (PrepareSplatLevelOfDetail); the selection per frame reads
 * 20 bytes per Gaussian and sorts nothing (SelectSplatsForView). The still frame projects
 * every Gaussian again (exact).
 *
 * A selection repeated while the view moves need not read every Gaussian: the preparation also
 * groups the Gaussians into cells of similar mass (within a factor of sqrt 2) and position (a
 * block of the Morton order), each with a bounding sphere and its largest mass, and
 * SelectSplatsInCells examines only the cells that meet the view's frustum and whose largest
 * possible key reaches a floor below the previous selection's boundary; the Gaussians it skips
 * could not have been selected, so its subset is SelectSplatsForView's, Gaussian for Gaussian
 * (it examines every cell again when the floor turns out too high).
 */
#ifndef vis4gs_SplatLevelOfDetail_h
#define vis4gs_SplatLevelOfDetail_h

#include "Camera.h"
#include "GaussianCloud.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace vis4gs
{

/// One Gaussian of a cell (SplatLevelOfDetail::Entries): its position, mass, reach and index.
struct SplatCellEntry
{
  float X, Y, Z, Mass, Reach;
  std::uint32_t Index;
};

/// A cell of Gaussians of similar mass and position: Entries [Begin, End).
struct SplatCell
{
  float Center[3];
  /// Largest distance of an entry's position from Center, and of its 3-sigma sphere's far side
  /// (distance + reach); infinite or NaN for a cell that is never culled.
  float Radius, Extent;
  float MaxMass;
  std::uint32_t Begin, End;
};

/// The view-independent part of the level of detail of one cloud.
struct SplatLevelOfDetail
{
  /// Opacity times the product of the two largest scales, per Gaussian (float, +inf where it
  /// overflows); 0 for a Gaussian with a non-finite parameter (never selected).
  std::vector<float> Mass;
  /// Three times the largest scale (world units), per Gaussian: the radius of the sphere
  /// that holds its 3-sigma ellipsoid, for the frustum cull.
  std::vector<float> Reach;
  /// The Gaussians of positive mass grouped by cell (cell after cell), and the cells; empty
  /// when the preparation was asked for no cells.
  std::vector<SplatCellEntry> Entries;
  std::vector<SplatCell> Cells;
};

/// What SelectSplatsInCells keeps between the selections of one caller.
struct SplatSelectionState
{
  /// Per Gaussian, the keys of a selection from every Gaussian (a level of detail without
  /// cells), and per thread the Gaussians of the examined cells that reach the floor (internal:
  /// kept so that they are not allocated again).
  std::vector<std::uint16_t> Keys;
  std::vector<std::vector<std::uint64_t>> Candidates;
  /// The selection's other buffers (internal), kept for the same reason: per thread the
  /// histogram, the kept Gaussians and those at the boundary; the histograms' sum, all the kept
  /// and boundary Gaussians, and the sort's scratch.
  std::vector<std::vector<std::uint32_t>> Histograms;
  std::vector<std::vector<std::uint64_t>> KeptBy, TiesBy;
  std::vector<std::uint64_t> Total, Kept, Ties, Spare;
  /// The last selection's boundary key (0: none yet): the next one's floor is a little below.
  std::uint32_t Boundary = 0;
  /// Gaussians whose key the last selection computed, and whether it had to examine every
  /// cell again because its floor was above the boundary (benchmarks, tests).
  std::size_t Examined = 0;
  bool Fallback = false;
  /// Wall milliseconds of the last selection's steps: the cells' pass, the filter of the
  /// candidates, their ascending order (benchmarks).
  double StepMs[3] = { 0.0, 0.0, 0.0 };
};

/**
 * Fills @p lod for @p cloud (parallel with OpenMP, @p threads 0 = OpenMP's default), with
 * @p cells the cells of SelectSplatsInCells (at most @p cellSize Gaussians each). A cloud whose
 * arrays do not match its count gets zero masses (nothing is selected).
 */
void PrepareSplatLevelOfDetail(const GaussianCloud& cloud,
  SplatLevelOfDetail& lod,
  int threads = 0,
  bool cells = true,
  std::size_t cellSize = 256);

/**
 * The Gaussians of @p cloud a moving frame of @p camera draws under @p budget, into @p subset
 * (indices, ascending): those in the frustum (view depth z > 0.2 and the 3-sigma sphere
 * within the field of view) ranked by Mass / z^2, quantised to 1/128 relative (the float's
 * top 16 bits: a histogram instead of a sort), ties in index order, the first @p budget
 * kept. With @p budget 0, every Gaussian in the frustum with a positive mass. Returns the
 * number of Gaussians in the frustum. Throws std::invalid_argument when @p lod does not
 * match the cloud.
 *
 * @p margin (radians, default 0) widens the field of view by that angle on every side for a
 * selection kept while the camera turns (SplatMovingSet.h): the Gaussians of the margin's
 * ring are added when their key reaches the budget's boundary key, but the budget counts the
 * view's own frustum only, so that the margin does not thin the visible picture.
 * @p scratch, when given, holds the per-Gaussian keys (2 B each), kept by a caller that
 * selects repeatedly so that they are not allocated and page-faulted again.
 */
std::size_t SelectSplatsForView(const GaussianCloud& cloud,
  const SplatLevelOfDetail& lod,
  const Camera& camera,
  std::size_t budget,
  std::vector<std::uint32_t>& subset,
  int threads = 0,
  double margin = 0.0,
  std::vector<std::uint16_t>* scratch = nullptr);

/**
 * SelectSplatsForView()'s subset (the same Gaussians; the return value is not its count in the
 * frustum but the number of Gaussians examined), reading only the cells of @p lod that meet the
 * frustum (widened by @p margin) and whose largest possible key reaches a floor: a little below
 * @p state's previous boundary (0: every cell in the frustum). When fewer than @p budget
 * Gaussians of the view's own frustum reach the floor it examines every cell in the frustum
 * again (state.Fallback). @p lod without cells: SelectSplatsForView over the whole cloud.
 * Throws std::invalid_argument as SelectSplatsForView does.
 */
std::size_t SelectSplatsInCells(const GaussianCloud& cloud,
  const SplatLevelOfDetail& lod,
  const Camera& camera,
  std::size_t budget,
  std::vector<std::uint32_t>& subset,
  SplatSelectionState& state,
  int threads = 0,
  double margin = 0.0);

/// The ranking key of SelectSplatsForView() for a Gaussian of @p mass at view depth @p z
/// (0 = never selected): the top 16 bits of the float mass / z^2.
std::uint32_t SplatContributionKey(float mass, float z);

} // namespace vis4gs

#endif

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

/// The view-independent part of the level of detail of one cloud.
struct SplatLevelOfDetail
{
  /// Opacity times the product of the two largest scales, per Gaussian (float, +inf where it
  /// overflows); 0 for a Gaussian with a non-finite parameter (never selected).
  std::vector<float> Mass;
  /// Three times the largest scale (world units), per Gaussian: the radius of the sphere
  /// that holds its 3-sigma ellipsoid, for the frustum cull.
  std::vector<float> Reach;
};

/**
 * Fills @p lod for @p cloud (parallel with OpenMP, @p threads 0 = OpenMP's default). A cloud
 * whose arrays do not match its count gets zero masses (nothing is selected).
 */
void PrepareSplatLevelOfDetail(const GaussianCloud& cloud,
  SplatLevelOfDetail& lod,
  int threads = 0);

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

/// The ranking key of SelectSplatsForView() for a Gaussian of @p mass at view depth @p z
/// (0 = never selected): the top 16 bits of the float mass / z^2.
std::uint32_t SplatContributionKey(float mass, float z);

} // namespace vis4gs

#endif

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file FastCoverage.h
 * @brief Visibility of every Gaussian in many views (|Omega(g,v)| >= 1), fused and early-exit,
 * for View Coverage at scale.
 *
 * The result is by construction identical to ProjectGaussians<float>() followed by
 * ComputeFootprints() and the test PixelCount >= 1 (checked Gaussian by Gaussian in the
 * tests on random and stiff scenes), but it is much cheaper:
 *  - the view-independent part of the projection (activated scales, normalised quaternion,
 *    3D covariance, opacity, the finiteness check) is computed once per Gaussian, with the
 *    same float operations in the same order as the rasteriser (no fused multiply-adds);
 *  - the view-dependent part (reference §2.3 steps 2-10) runs per view with the rasteriser's
 *    float arithmetic, including its culls and its clamps;
 *  - instead of counting Omega, the test stops at the first pixel found: the pixel nearest the
 *    projected mean (clamped into the tile rectangle) is tried first, then the rows of the
 *    analytic span bounds of Render/RasterBounds.h (conservative; every candidate pixel is
 *    evaluated with the exact kernel), or every pixel of the rectangle when no bound exists;
 *  - the loop runs over blocks of Gaussians outside and views inside, so the cloud is read
 *    once whatever the number of views;
 *  - with AVX-512 or AVX2 (chosen at run time, exact mode), 16 or 8 Gaussians are projected
 *    at once: each
 *    lane repeats the scalar float operations in the same order (no contraction, correctly
 *    rounded division and square root, the reference's double ndc2Pix), so its culls, conic
 *    and tile rectangle are bit-identical, then evaluates the exact kernel at the pixel of
 *    its clamped tile rectangle nearest the mean. That decides almost every Gaussian (culled,
 *    or visible at that pixel); the rest are re-tested by the scalar search. The counts equal
 *    the scalar path's (kernelIsa = 1) Gaussian by Gaussian, and do not depend on the thread
 *    count (each Gaussian's counter is written by the thread that owns its block).
 * Both footprint modes are supported (alpha footprint; 3-sigma ellipse).
 */
#ifndef vis4gs_FastCoverage_h
#define vis4gs_FastCoverage_h

#include "Camera.h"
#include "Footprint.h"
#include "GaussianCloud.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace vis4gs
{

/**
 * Adds 1 to @p visibleViews[g] for every view of @p cameras in which Gaussian g has a
 * non-empty footprint (mode @p mode). @p visibleViews is resized to cloud.Count if needed.
 * @p scaleModifier is the rasteriser's scale modifier (1 for the scores). Throws like
 * ProjectGaussians for unusable cameras or clouds. @p kernelIsa: 0 = best available
 * (default), 1 = scalar only, 2 = AVX2, 3 = AVX-512 (each falls back to what the machine
 * has); the counts are identical on every path (a knob for tests and benchmarks).
 */
void CountVisibleViews(const GaussianCloud& cloud,
  const std::vector<Camera>& cameras,
  FootprintMode mode,
  std::vector<std::uint32_t>& visibleViews,
  int threads = 0,
  double scaleModifier = 1.0,
  int kernelIsa = 0);

/**
 * Visibility of every Gaussian in one view (1 when |Omega| >= 1), for the tests and for
 * per-view overlays.
 */
std::vector<std::uint8_t> VisibleInView(const GaussianCloud& cloud,
  const Camera& camera,
  FootprintMode mode,
  int threads = 0,
  double scaleModifier = 1.0,
  int kernelIsa = 0);

} // namespace vis4gs

#endif

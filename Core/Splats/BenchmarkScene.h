// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BenchmarkScene.h
 * @brief A deterministic synthetic Gaussian scene of any size for benchmarks and tests of the
 * renderer and the selection modes (the real scenes in shared/data hold at most 46k
 * Gaussians): flattened Gaussians on a sphere of radius 1 (60 %) and on a ground disk at
 * y = 1 (35 %, the camera's "down"), and isotropic floaters in the box [-2, 2]^3 (5 %), with
 * random SH coefficients of the given degree and opacities spread over (0.05, 0.99).
 * Per-Gaussian sizes shrink with n so the screen coverage stays alike: scale ~ 0.02 (n/1e5)^-1/2.
 */
#ifndef vis4gs_BenchmarkScene_h
#define vis4gs_BenchmarkScene_h

#include "Camera.h"
#include "GaussianCloud.h"

#include <cstddef>

namespace vis4gs
{

GaussianCloud MakeBenchmarkScene(std::size_t count, int shDegree, unsigned seed = 1);

/// A camera looking at the origin from distance 3.5 (slightly from above), @p width x
/// @p height, 60 degree vertical field of view, rotated by @p azimuth radians about the y axis.
Camera MakeBenchmarkCamera(int width, int height, double azimuth = 0.0);

} // namespace vis4gs

#endif

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BenchmarkSceneUtils.h
 * @brief Synthetic scenes for the diagnostics benchmark: Gaussians on a noisy sphere shell
 * with a few floaters and needles, cameras on a ring looking at the centre, and the Gaussian
 * initialisation of the reference trainer from a point cloud (isotropic, scale from the mean
 * squared distance to the 3 nearest neighbours, opacity 0.1, SH DC from the colour).
 */
#ifndef vis4gs_BenchmarkSceneUtils_h
#define vis4gs_BenchmarkSceneUtils_h

#include "Camera.h"
#include "GaussianCloud.h"
#include "GaussianMath.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace vis4gs
{
namespace bench
{

/// World-to-camera of a camera at @p c looking at @p target (OpenCV axes, world up +z).
inline Camera LookAt(const double c[3], const double target[3], int width, int height, double fx)
{
  double z[3] = { target[0] - c[0], target[1] - c[1], target[2] - c[2] };
  double n = std::sqrt(z[0] * z[0] + z[1] * z[1] + z[2] * z[2]);
  for (double& v : z)
  {
    v /= n;
  }
  const double up[3] = { 0, 0, 1 };
  double x[3] = {
    z[1] * up[2] - z[2] * up[1], z[2] * up[0] - z[0] * up[2], z[0] * up[1] - z[1] * up[0]
  };
  n = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  for (double& v : x)
  {
    v /= n;
  }
  const double y[3] = {
    z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0]
  };
  Camera cam;
  cam.Width = width;
  cam.Height = height;
  cam.Fx = cam.Fy = fx;
  cam.Cx = width / 2.0;
  cam.Cy = height / 2.0;
  const double* rows[3] = { x, y, z };
  for (int r = 0; r < 3; ++r)
  {
    for (int k = 0; k < 3; ++k)
    {
      cam.WorldToCamera[4 * r + k] = rows[r][k];
    }
    cam.WorldToCamera[4 * r + 3] = -(rows[r][0] * c[0] + rows[r][1] * c[1] + rows[r][2] * c[2]);
  }
  return cam;
}

/// @p views cameras on a slightly wavy ring of radius @p radius around the origin.
inline std::vector<Camera> RingCameras(int views, double radius, int width, int height)
{
  std::vector<Camera> cameras;
  for (int v = 0; v < views; ++v)
  {
    const double a = 6.283185307179586 * v / views;
    const double c[3] = { radius * std::cos(a), radius * std::sin(a), 0.6 * std::sin(3.0 * a) };
    const double t[3] = { 0, 0, 0 };
    cameras.push_back(LookAt(c, t, width, height, 0.9 * width));
    cameras.back().Name = "view" + std::to_string(v);
  }
  return cameras;
}

/**
 * @p n Gaussians: 90% on a sphere shell of radius 1 (anisotropic, tangent-ish), 5% needles,
 * 5% floaters scattered between the shell and the cameras; SH degree 0.
 */
inline GaussianCloud ShellScene(std::size_t n, unsigned seed, double logScale = -4.2)
{
  GaussianCloud cloud;
  cloud.Resize(n, 0);
  std::mt19937 rng(seed);
  std::normal_distribution<float> gauss(0.0f, 1.0f);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  for (std::size_t i = 0; i < n; ++i)
  {
    float p[3] = { gauss(rng), gauss(rng), gauss(rng) };
    const float len = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) + 1e-6f;
    const int kind = static_cast<int>(i % 20);
    float r = 1.0f + 0.02f * gauss(rng);
    if (kind == 19)
    {
      r = 1.3f + 1.2f * uni(rng); // floater
    }
    for (int k = 0; k < 3; ++k)
    {
      cloud.Positions[3 * i + k] = p[k] / len * r;
    }
    const float base = static_cast<float>(logScale) + 0.3f * gauss(rng);
    cloud.LogScales[3 * i + 0] = base + (kind == 18 ? 2.5f : 0.0f);
    cloud.LogScales[3 * i + 1] = base + 0.2f * gauss(rng);
    cloud.LogScales[3 * i + 2] = base - 0.8f - (kind == 18 ? 0.5f : 0.0f);
    for (int k = 0; k < 4; ++k)
    {
      cloud.Rotations[4 * i + k] = gauss(rng);
    }
    cloud.OpacityLogits[i] = 1.0f + 1.5f * gauss(rng);
    const float shade = 0.5f + 0.5f * p[2] / len;
    cloud.SH[3 * i + 0] = static_cast<float>((0.2 + 0.6 * shade - 0.5) / sh::C0);
    cloud.SH[3 * i + 1] = static_cast<float>((0.5 + 0.3 * uni(rng) - 0.5) / sh::C0);
    cloud.SH[3 * i + 2] = static_cast<float>((0.8 - 0.5 * shade - 0.5) / sh::C0);
  }
  return cloud;
}

/// A perturbed copy: positions jittered, log-scales and colours changed (the "ground truth"
/// the images are rendered from, so that loss maps are non-trivial).
inline GaussianCloud Perturbed(const GaussianCloud& cloud, unsigned seed, float amount)
{
  GaussianCloud p = cloud;
  std::mt19937 rng(seed);
  std::normal_distribution<float> gauss(0.0f, 1.0f);
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      p.Positions[3 * i + k] += 0.01f * amount * gauss(rng);
      p.LogScales[3 * i + k] -= 0.3f * amount * std::abs(gauss(rng));
      p.SH[3 * i + k] += 0.3f * amount * gauss(rng);
    }
  }
  return p;
}

/**
 * Gaussians initialised as the reference trainer does from points (reference §1.1): log-scale
 * log(sqrt(max(mean squared distance to the 3 nearest neighbours, 1e-7))) on all three axes,
 * rotation identity, opacity logit logit(0.1), SH DC (rgb - 0.5)/C0. Exact k-NN by brute
 * force (O(n^2); meant for point clouds of a few thousand points).
 */
inline GaussianCloud InitialiseFromPoints(const std::vector<float>& xyz,
  const std::vector<unsigned char>& rgb)
{
  const std::size_t n = xyz.size() / 3;
  GaussianCloud cloud;
  cloud.Resize(n, 0);
#pragma omp parallel for schedule(dynamic, 16)
  for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii)
  {
    const std::size_t i = static_cast<std::size_t>(ii);
    double best[3] = { std::numeric_limits<double>::max(),
      std::numeric_limits<double>::max(),
      std::numeric_limits<double>::max() };
    for (std::size_t j = 0; j < n; ++j)
    {
      if (j == i)
      {
        continue;
      }
      double d = 0;
      for (int k = 0; k < 3; ++k)
      {
        const double e = static_cast<double>(xyz[3 * i + k]) - xyz[3 * j + k];
        d += e * e;
      }
      if (d < best[2])
      {
        best[2] = d;
        std::sort(best, best + 3);
      }
    }
    const int found = static_cast<int>(std::min<std::size_t>(3, n - 1));
    double mean = 0;
    for (int k = 0; k < found; ++k)
    {
      mean += best[k];
    }
    mean = found > 0 ? mean / found : 1e-7;
    const float ls = static_cast<float>(std::log(std::sqrt(std::max(mean, 1e-7))));
    for (int k = 0; k < 3; ++k)
    {
      cloud.Positions[3 * i + k] = xyz[3 * i + k];
      cloud.LogScales[3 * i + k] = ls;
      cloud.SH[3 * i + k] = static_cast<float>((rgb[3 * i + k] / 255.0 - 0.5) / sh::C0);
    }
    cloud.Rotations[4 * i] = 1;
    cloud.OpacityLogits[i] = static_cast<float>(Logit(0.1));
  }
  return cloud;
}

} // namespace bench
} // namespace vis4gs

#endif

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file RasterTestUtils.h
 * @brief Helpers for the rasteriser tests: scene and camera builders, and two deliberately
 * naive reference renderers written independently of the tiled rasteriser:
 *  - NaiveComposite(): per pixel, loop over ALL Gaussians of a projection in one global
 *    (depth, index) order, with the reference's tile-rectangle membership test;
 *  - NaiveRender(): its own preprocessing from the raw parameters (straight formulas of
 *    reference §2.3/2.4, no shared code), then NaiveComposite's per-pixel loop.
 */
#ifndef vis4gs_RasterTestUtils_h
#define vis4gs_RasterTestUtils_h

#include "Camera.h"
#include "GaussianCloud.h"
#include "GaussianMath.h"
#include "RasterKernel.h"
#include "Rasterizer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

namespace vis4gs
{
namespace rastertest
{

/// A look-at camera (OpenCV axes: +x right, +y down, +z forward); @p up is world up.
inline Camera LookAt(int width,
  int height,
  double fx,
  double fy,
  std::array<double, 3> eye,
  std::array<double, 3> target,
  std::array<double, 3> up = { 0, -1, 0 })
{
  auto sub = [](std::array<double, 3> a, std::array<double, 3> b) {
    return std::array<double, 3>{ a[0] - b[0], a[1] - b[1], a[2] - b[2] };
  };
  auto cross = [](std::array<double, 3> a, std::array<double, 3> b)
  {
    return std::array<double, 3>{
      a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]
    };
  };
  auto norm = [](std::array<double, 3> a)
  {
    const double l = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    return std::array<double, 3>{ a[0] / l, a[1] / l, a[2] / l };
  };
  const auto z = norm(sub(target, eye));
  const std::array<double, 3> down{ -up[0], -up[1], -up[2] };
  const auto x = norm(cross(down, z));
  const auto y = cross(z, x);
  Camera cam;
  cam.Name = "test";
  cam.Width = width;
  cam.Height = height;
  cam.Fx = fx;
  cam.Fy = fy;
  cam.Cx = width / 2.0;
  cam.Cy = height / 2.0;
  const std::array<double, 3> rows[3] = { x, y, z };
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      cam.WorldToCamera[4 * r + c] = rows[r][c];
    }
    cam.WorldToCamera[4 * r + 3] =
      -(rows[r][0] * eye[0] + rows[r][1] * eye[1] + rows[r][2] * eye[2]);
  }
  return cam;
}

/// Identity pose camera at the origin looking down +z.
inline Camera AxisCamera(int width, int height, double fx, double fy)
{
  Camera cam;
  cam.Name = "axis";
  cam.Width = width;
  cam.Height = height;
  cam.Fx = fx;
  cam.Fy = fy;
  cam.Cx = width / 2.0;
  cam.Cy = height / 2.0;
  return cam;
}

/// Sets Gaussian @p i of @p cloud (SH: DC from @p rgb, higher coefficients zero).
inline void SetGaussian(GaussianCloud& cloud,
  std::size_t i,
  std::array<float, 3> pos,
  std::array<float, 3> logScale,
  std::array<float, 4> rot,
  float logit,
  std::array<float, 3> rgb)
{
  for (int k = 0; k < 3; ++k)
  {
    cloud.Positions[3 * i + k] = pos[k];
    cloud.LogScales[3 * i + k] = logScale[k];
  }
  for (int k = 0; k < 4; ++k)
  {
    cloud.Rotations[4 * i + k] = rot[k];
  }
  cloud.OpacityLogits[i] = logit;
  const int K = cloud.ShCoefficientCount();
  for (int k = 0; k < 3 * K; ++k)
  {
    cloud.SH[3 * K * i + k] = 0.0f;
  }
  for (int c = 0; c < 3; ++c)
  {
    cloud.SH[3 * K * i + c] = static_cast<float>((rgb[c] - 0.5) / sh::C0);
  }
}

/// Random scene of @p n Gaussians in a box in front of an axis camera (z in [zMin, zMax]),
/// with random anisotropic scales, rotations, opacities and SH up to @p degree.
inline GaussianCloud RandomScene(std::size_t n,
  int degree,
  unsigned seed,
  float zMin = 2.0f,
  float zMax = 8.0f,
  float logScaleMin = -4.0f,
  float logScaleMax = -1.0f)
{
  GaussianCloud cloud;
  cloud.Resize(n, degree);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  const int K = cloud.ShCoefficientCount();
  for (std::size_t i = 0; i < n; ++i)
  {
    const float z = zMin + (zMax - zMin) * u01(rng);
    cloud.Positions[3 * i + 0] = (u01(rng) - 0.5f) * z * 1.2f;
    cloud.Positions[3 * i + 1] = (u01(rng) - 0.5f) * z * 0.9f;
    cloud.Positions[3 * i + 2] = z;
    for (int k = 0; k < 3; ++k)
    {
      cloud.LogScales[3 * i + k] = logScaleMin + (logScaleMax - logScaleMin) * u01(rng);
    }
    for (int k = 0; k < 4; ++k)
    {
      cloud.Rotations[4 * i + k] = u01(rng) * 2.0f - 1.0f;
    }
    cloud.OpacityLogits[i] = u01(rng) * 8.0f - 3.0f;
    for (int k = 0; k < 3 * K; ++k)
    {
      cloud.SH[3 * K * i + k] = (u01(rng) * 2.0f - 1.0f) * (k < 3 ? 1.5f : 0.4f);
    }
  }
  return cloud;
}

/// A per-pixel map for footprint sums with the awkward values: tiny and negative entries, a
/// NaN, an Inf, a -0 and a huge last pixel (packed lanes must never read past the map).
inline std::vector<float> OddMap(int w, int h, unsigned seed)
{
  std::vector<float> map(static_cast<std::size_t>(w) * h);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1, 2);
  for (std::size_t i = 0; i < map.size(); ++i)
  {
    map[i] = u(rng) * (i % 5 == 0 ? 1e-9f : 1.0f);
  }
  map[map.size() / 3] = std::numeric_limits<float>::quiet_NaN();
  map[map.size() / 2] = std::numeric_limits<float>::infinity();
  map[map.size() / 2 + 7] = -0.0f;
  map[map.size() - 1] = 1e30f; // last pixel: packed lanes must never read past the map
  return map;
}

/// Naive per-pixel compositing over a projection: one global (depth, index) order, every
/// Gaussian tested for every pixel (the tile-rectangle test reproduces the binning).
template <typename T>
RasterImage<T> NaiveComposite(const ViewProjection<T>& p, std::array<double, 3> bg)
{
  std::vector<std::uint32_t> order;
  for (std::size_t i = 0; i < p.Gaussians.size(); ++i)
  {
    if (p.Gaussians[i].IsVisible())
    {
      order.push_back(static_cast<std::uint32_t>(i));
    }
  }
  std::stable_sort(order.begin(),
    order.end(),
    [&](std::uint32_t a, std::uint32_t b) { return p.Gaussians[a].Depth < p.Gaussians[b].Depth; });
  RasterImage<T> img;
  img.Width = p.Width;
  img.Height = p.Height;
  const std::size_t np = static_cast<std::size_t>(p.Width) * p.Height;
  img.Color.assign(3 * np, 0);
  img.Alpha.assign(np, 0);
  img.Transmittance.assign(np, 1);
  img.Depth.assign(np, 0);
  img.Contributors.assign(np, 0);
  for (int y = 0; y < p.Height; ++y)
  {
    for (int x = 0; x < p.Width; ++x)
    {
      const int tx = x / raster::TileSize, ty = y / raster::TileSize;
      T Tr = 1, C[3] = { 0, 0, 0 }, D = 0;
      std::uint32_t position = 0, last = 0;
      for (std::uint32_t id : order)
      {
        const auto& g = p.Gaussians[id];
        if (tx < g.TileRect[0] || tx >= g.TileRect[2] || ty < g.TileRect[1] || ty >= g.TileRect[3])
        {
          continue;
        }
        ++position;
        const T dx = g.U - static_cast<T>(x), dy = g.V - static_cast<T>(y);
        const T power = T(-0.5) * (g.ConicA * dx * dx + g.ConicC * dy * dy) - g.ConicB * dx * dy;
        if (power > T(0) || std::isnan(power))
        {
          continue;
        }
        T alpha = std::min(T(0.99), g.Opacity * raster::KernelExp(power));
        if (alpha < T(1) / T(255))
        {
          continue;
        }
        const T Tn = Tr * (T(1) - alpha);
        if (Tn < T(0.0001))
        {
          break;
        }
        for (int c = 0; c < 3; ++c)
        {
          C[c] = C[c] + g.Color[c] * alpha * Tr;
        }
        D = D + g.Depth * alpha * Tr;
        Tr = Tn;
        last = position;
      }
      const std::size_t pix = static_cast<std::size_t>(y) * p.Width + x;
      for (int c = 0; c < 3; ++c)
      {
        img.Color[3 * pix + c] = C[c] + Tr * static_cast<T>(bg[c]);
      }
      img.Transmittance[pix] = Tr;
      img.Alpha[pix] = T(1) - Tr;
      img.Depth[pix] = D;
      img.Contributors[pix] = last;
    }
  }
  return img;
}

/// Independent preprocessing from raw parameters (straight formulas, row-major math,
/// std::exp for the kernel), then the naive per-pixel loop. Mirrors only the *definitions*
/// of reference §2; shares no code with ProjectGaussians().
template <typename T>
ViewProjection<T> NaiveProject(const GaussianCloud& cloud, const Camera& cam, int degree)
{
  ViewProjection<T> p;
  p.Width = cam.Width;
  p.Height = cam.Height;
  p.TilesX = (cam.Width + 15) / 16;
  p.TilesY = (cam.Height + 15) / 16;
  const T tanX = static_cast<T>(cam.Width / (2.0 * cam.Fx));
  const T tanY = static_cast<T>(cam.Height / (2.0 * cam.Fy));
  const T fx = T(cam.Width) / (T(2) * tanX), fy = T(cam.Height) / (T(2) * tanY);
  const auto& m = cam.WorldToCamera;
  const auto c = cam.Center();
  const int K = cloud.ShCoefficientCount();
  p.Gaussians.resize(cloud.Count);
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    auto& g = p.Gaussians[i];
    T mu[3], t[3];
    for (int k = 0; k < 3; ++k)
    {
      mu[k] = cloud.Positions[3 * i + k];
    }
    for (int r = 0; r < 3; ++r)
    {
      t[r] =
        T(m[4 * r]) * mu[0] + T(m[4 * r + 1]) * mu[1] + T(m[4 * r + 2]) * mu[2] + T(m[4 * r + 3]);
    }
    g.Depth = t[2];
    g.Status = ProjectionStatus::NearPlane;
    if (!(t[2] > T(0.2)))
    {
      continue;
    }
    // Pixel mean: ndc2Pix of (t/tan)/(z + 1e-7) = f x/(z + 1e-7) + (W-1)/2 (§2.3 step 9).
    const T u = fx * t[0] / (t[2] + T(1e-7)) + T(cam.Width - 1) / T(2);
    const T v = fy * t[1] / (t[2] + T(1e-7)) + T(cam.Height - 1) / T(2);
    T q[4];
    T qn = 0;
    for (int k = 0; k < 4; ++k)
    {
      q[k] = cloud.Rotations[4 * i + k];
      qn += q[k] * q[k];
    }
    qn = std::max(std::sqrt(qn), T(1e-12));
    for (auto& x : q)
    {
      x /= qn;
    }
    const T w = q[0], x = q[1], y = q[2], z = q[3];
    const T R[3][3] = { { 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y) },
      { 2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x) },
      { 2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y) } };
    T s2[3];
    for (int k = 0; k < 3; ++k)
    {
      const T s = std::exp(T(cloud.LogScales[3 * i + k]));
      s2[k] = s * s;
    }
    T Sig[3][3];
    for (int r = 0; r < 3; ++r)
    {
      for (int cc = 0; cc < 3; ++cc)
      {
        Sig[r][cc] = 0;
        for (int k = 0; k < 3; ++k)
        {
          Sig[r][cc] += R[r][k] * s2[k] * R[cc][k];
        }
      }
    }
    T Rv[3][3];
    for (int r = 0; r < 3; ++r)
    {
      for (int cc = 0; cc < 3; ++cc)
      {
        Rv[r][cc] = T(m[4 * r + cc]);
      }
    }
    // V = Rv Sig Rv^T
    T Vm[3][3];
    for (int r = 0; r < 3; ++r)
    {
      for (int cc = 0; cc < 3; ++cc)
      {
        T s = 0;
        for (int a = 0; a < 3; ++a)
        {
          for (int b = 0; b < 3; ++b)
          {
            s += Rv[r][a] * Sig[a][b] * Rv[cc][b];
          }
        }
        Vm[r][cc] = s;
      }
    }
    const T limx = T(1.3) * tanX, limy = T(1.3) * tanY;
    const T txc = std::clamp(t[0] / t[2], -limx, limx) * t[2];
    const T tyc = std::clamp(t[1] / t[2], -limy, limy) * t[2];
    const T J[2][3] = { { fx / t[2], 0, -fx * txc / (t[2] * t[2]) },
      { 0, fy / t[2], -fy * tyc / (t[2] * t[2]) } };
    T cov[2][2];
    for (int r = 0; r < 2; ++r)
    {
      for (int cc = 0; cc < 2; ++cc)
      {
        T s = 0;
        for (int a = 0; a < 3; ++a)
        {
          for (int b = 0; b < 3; ++b)
          {
            s += J[r][a] * Vm[a][b] * J[cc][b];
          }
        }
        cov[r][cc] = s;
      }
    }
    const T a = cov[0][0] + T(0.3), b = cov[0][1], cc = cov[1][1] + T(0.3);
    const T det = a * cc - b * b;
    g.Status = ProjectionStatus::Degenerate;
    if (det == T(0))
    {
      continue;
    }
    g.ConicA = cc / det;
    g.ConicB = -b / det;
    g.ConicC = a / det;
    const T mid = (a + cc) / 2;
    const T l1 = mid + std::sqrt(std::max(T(0.1), mid * mid - det));
    const int radius = static_cast<int>(std::ceil(T(3) * std::sqrt(l1)));
    g.Radius = radius;
    g.U = u;
    g.V = v;
    auto clampi = [](int x, int hi) { return std::min(hi, std::max(0, x)); };
    g.TileRect[0] = clampi(static_cast<int>((u - radius) / 16), p.TilesX);
    g.TileRect[1] = clampi(static_cast<int>((v - radius) / 16), p.TilesY);
    g.TileRect[2] = clampi(static_cast<int>((u + radius + 15) / 16), p.TilesX);
    g.TileRect[3] = clampi(static_cast<int>((v + radius + 15) / 16), p.TilesY);
    g.Status = ProjectionStatus::OffScreen;
    if ((g.TileRect[2] - g.TileRect[0]) * (g.TileRect[3] - g.TileRect[1]) == 0)
    {
      continue;
    }
    g.Status = ProjectionStatus::Visible;
    const T lo = cloud.OpacityLogits[i];
    g.Opacity = T(1) / (T(1) + std::exp(-lo));
    T d[3] = { mu[0] - T(c[0]), mu[1] - T(c[1]), mu[2] - T(c[2]) };
    const T len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const T X = d[0] / len, Y = d[1] / len, Z = d[2] / len;
    const T basis[16] = { T(sh::C0),
      -T(sh::C1) * Y,
      T(sh::C1) * Z,
      -T(sh::C1) * X,
      T(sh::C2[0]) * X * Y,
      T(sh::C2[1]) * Y * Z,
      T(sh::C2[2]) * (2 * Z * Z - X * X - Y * Y),
      T(sh::C2[3]) * X * Z,
      T(sh::C2[4]) * (X * X - Y * Y),
      T(sh::C3[0]) * Y * (3 * X * X - Y * Y),
      T(sh::C3[1]) * X * Y * Z,
      T(sh::C3[2]) * Y * (4 * Z * Z - X * X - Y * Y),
      T(sh::C3[3]) * Z * (2 * Z * Z - 3 * X * X - 3 * Y * Y),
      T(sh::C3[4]) * X * (4 * Z * Z - X * X - Y * Y),
      T(sh::C3[5]) * Z * (X * X - Y * Y),
      T(sh::C3[6]) * X * (X * X - 3 * Y * Y) };
    const int used = (degree + 1) * (degree + 1);
    for (int ch = 0; ch < 3; ++ch)
    {
      T col = 0;
      for (int k = 0; k < used; ++k)
      {
        col += basis[k] * T(cloud.SH[3 * K * i + 3 * k + ch]);
      }
      g.Color[ch] = std::max(col + T(0.5), T(0));
    }
  }
  return p;
}

/// Max |a - b| over two equally sized arrays.
template <typename A, typename B>
double MaxAbsDiff(const std::vector<A>& a, const std::vector<B>& b)
{
  double m = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    m = std::max(m, std::abs(static_cast<double>(a[i]) - static_cast<double>(b[i])));
  }
  return m;
}

} // namespace rastertest
} // namespace vis4gs

#endif

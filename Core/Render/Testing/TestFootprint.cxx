// SPDX-License-Identifier: BSD-3-Clause
// Footprint statistics |Omega(g,v)| and map sums: the analytic-span fast path equals the
// brute-force definition, and both agree with independent computations.
#include "RasterTestUtils.h"

#include "Footprint.h"
#include "GaussianIO.h"
#include "Rasterizer.h"
#include "Vis4GSTestData.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

using namespace vis4gs;
using namespace vis4gs::rastertest;

namespace
{

// A scene with stiff members: needles, disks, huge, tiny, off-screen-ish, low opacity.
GaussianCloud MixedScene()
{
  GaussianCloud cloud = RandomScene(3000, 0, 31u, 1.0f, 12.0f, -6.0f, 0.5f);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1, 1);
  for (std::size_t i = 0; i < cloud.Count; i += 7)
  {
    // needles and disks
    cloud.LogScales[3 * i + (i % 3)] = -18.0f;
    if (i % 2)
    {
      cloud.LogScales[3 * i + ((i + 1) % 3)] = -18.0f;
    }
  }
  for (std::size_t i = 3; i < cloud.Count; i += 97)
  {
    cloud.LogScales[3 * i] = cloud.LogScales[3 * i + 1] = cloud.LogScales[3 * i + 2] = 2.0f; // huge
  }
  for (std::size_t i = 5; i < cloud.Count; i += 53)
  {
    cloud.OpacityLogits[i] = -5.6f + 0.01f * u(rng); // opacity near 1/255
  }
  return cloud;
}

template <typename T>
void CheckFastEqualsBrute(const ViewProjection<T>& proj,
  FootprintMode mode,
  const std::vector<float>& map)
{
  FootprintOptions fast, brute;
  fast.Mode = brute.Mode = mode;
  brute.BruteForce = true;
  const auto a = ComputeFootprints(proj, fast, map.data());
  const auto b = ComputeFootprints(proj, brute, map.data());
  ASSERT_EQ(a.PixelCount, b.PixelCount);
  for (std::size_t i = 0; i < a.MapSum.size(); ++i)
  {
    ASSERT_NEAR(a.MapSum[i], b.MapSum[i], 1e-9 * (1 + std::abs(b.MapSum[i]))) << i;
  }
  EXPECT_GT(a.TotalPixels, 0u);
  EXPECT_LT(a.EvaluatedPixels, b.EvaluatedPixels);
}

} // namespace

//------------------------------------------------------------------------------
TEST(Footprint, FastPathEqualsBruteForce)
{
  const auto cloud = MixedScene();
  const Camera cam = LookAt(160, 120, 90, 95, { 0.2, -0.1, -0.3 }, { 0, 0, 5 });
  std::vector<float> map(160 * 120);
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u(0, 1);
  for (auto& m : map)
  {
    m = u(rng);
  }
  const auto pf = ProjectGaussians<float>(cloud, cam);
  const auto pd = ProjectGaussians<double>(cloud, cam);
  CheckFastEqualsBrute(pf, FootprintMode::Rasterizer, map);
  CheckFastEqualsBrute(pd, FootprintMode::Rasterizer, map);
  CheckFastEqualsBrute(pf, FootprintMode::Ellipse3Sigma, map);
  CheckFastEqualsBrute(pd, FootprintMode::Ellipse3Sigma, map);
}

//------------------------------------------------------------------------------
// Independent definition: count, for every pixel of the image, the Gaussians whose tile
// rectangle holds the pixel's tile and whose alpha (naive formula) is >= 1/255.
TEST(Footprint, MatchesPerPixelDefinition)
{
  const auto cloud = MixedScene();
  const Camera cam = LookAt(100, 70, 60, 60, { 0, 0, 0 }, { 0, 0, 5 });
  const auto proj = ProjectGaussians<float>(cloud, cam);
  std::vector<float> ones(100 * 70, 1.0f);
  const auto fp = ComputeFootprints(proj, {}, ones.data());
  std::vector<std::uint32_t> count(cloud.Count, 0);
  for (int y = 0; y < 70; ++y)
  {
    for (int x = 0; x < 100; ++x)
    {
      for (std::size_t i = 0; i < cloud.Count; ++i)
      {
        const auto& g = proj.Gaussians[i];
        if (!g.IsVisible() || x / 16 < g.TileRect[0] || x / 16 >= g.TileRect[2] ||
          y / 16 < g.TileRect[1] || y / 16 >= g.TileRect[3])
        {
          continue;
        }
        const float dx = g.U - x, dy = g.V - y;
        const float power = -0.5f * (g.ConicA * dx * dx + g.ConicC * dy * dy) - g.ConicB * dx * dy;
        if (power > 0)
        {
          continue;
        }
        const float alpha = std::min(0.99f, g.Opacity * raster::KernelExp(power));
        count[i] += alpha >= 1.0f / 255.0f;
      }
    }
  }
  EXPECT_EQ(fp.PixelCount, count);
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    EXPECT_EQ(fp.MapSum[i], static_cast<double>(count[i])); // map of ones
  }
}

//------------------------------------------------------------------------------
// For a lone Gaussian nothing occludes it and T never drops below 1e-4 (alpha <= 0.99), so
// Omega is exactly the set of pixels it is blended into.
TEST(Footprint, LoneGaussianOmegaEqualsBlendedPixels)
{
  const auto cloud = MixedScene();
  const Camera cam = LookAt(120, 90, 70, 70, { 0, 0, 0 }, { 0, 0, 5 });
  const auto projAll = ProjectGaussians<float>(cloud, cam);
  const auto fpAll = ComputeFootprints(projAll);
  int checked = 0;
  for (std::size_t i = 0; i < cloud.Count && checked < 40; i += 61)
  {
    if (!projAll.Gaussians[i].IsVisible())
    {
      continue;
    }
    GaussianCloud one;
    one.Resize(1, 0);
    SetGaussian(one,
      0,
      { cloud.Positions[3 * i], cloud.Positions[3 * i + 1], cloud.Positions[3 * i + 2] },
      { cloud.LogScales[3 * i], cloud.LogScales[3 * i + 1], cloud.LogScales[3 * i + 2] },
      { cloud.Rotations[4 * i],
        cloud.Rotations[4 * i + 1],
        cloud.Rotations[4 * i + 2],
        cloud.Rotations[4 * i + 3] },
      cloud.OpacityLogits[i],
      { 0.5f, 0.5f, 0.5f });
    const auto proj = ProjectGaussians<float>(one, cam);
    const auto bins = BinGaussians(proj);
    RasterImage<float> img;
    GaussianWeightStats ws;
    RasterSettings s;
    CompositeTiles(proj, bins, s, img, &ws);
    const auto fp = ComputeFootprints(proj);
    EXPECT_EQ(fp.PixelCount[0], ws.BlendedPixels[0]) << i;
    // And the full scene's footprint of g is the same (occlusion does not matter).
    EXPECT_EQ(fp.PixelCount[0], fpAll.PixelCount[i]);
    ++checked;
  }
  EXPECT_GT(checked, 10);
}

//------------------------------------------------------------------------------
// 3-sigma ellipse of an isotropic Gaussian on the axis: variance var = (f s/z)^2 + 0.3, so the
// pixels with dx^2 + dy^2 <= 9 var.
TEST(Footprint, EllipseModeHandCase)
{
  GaussianCloud cloud;
  cloud.Resize(1, 0);
  const float ls = std::log(0.1f);
  SetGaussian(cloud, 0, { 0, 0, 4 }, { ls, ls, ls }, { 1, 0, 0, 0 }, -3.0f, { 1, 1, 1 });
  const Camera cam = AxisCamera(65, 65, 100, 100); // centre pixel (32, 32)
  const auto proj = ProjectGaussians<double>(cloud, cam);
  FootprintOptions opt;
  opt.Mode = FootprintMode::Ellipse3Sigma;
  const auto fp = ComputeFootprints(proj, opt);
  const double var = std::pow(100 * std::exp(static_cast<double>(ls)) / 4, 2) + 0.3;
  std::uint32_t expected = 0;
  for (int y = 0; y < 65; ++y)
  {
    for (int x = 0; x < 65; ++x)
    {
      expected += (x - 32.0) * (x - 32.0) + (y - 32.0) * (y - 32.0) <= 9 * var;
    }
  }
  EXPECT_EQ(fp.PixelCount[0], expected);
  // Exact mode with opacity sigmoid(-3) = 0.047: alpha >= 1/255 <=> d^2 <= 2 var ln(255 o).
  const auto ex = ComputeFootprints(proj);
  const double o = 1 / (1 + std::exp(3.0));
  std::uint32_t expectedExact = 0;
  for (int y = 0; y < 65; ++y)
  {
    for (int x = 0; x < 65; ++x)
    {
      expectedExact +=
        (x - 32.0) * (x - 32.0) + (y - 32.0) * (y - 32.0) <= 2 * var * std::log(255 * o);
    }
  }
  EXPECT_EQ(ex.PixelCount[0], expectedExact);
  EXPECT_LT(ex.PixelCount[0], fp.PixelCount[0]);
}

//------------------------------------------------------------------------------
TEST(Footprint, FloatAccumulationCloseToDouble)
{
  const auto cloud = RandomScene(2000, 0, 13u, 1.0f, 6.0f, -3.0f, -0.5f);
  const Camera cam = LookAt(200, 150, 120, 120, { 0, 0, 0 }, { 0, 0, 5 });
  const auto proj = ProjectGaussians<float>(cloud, cam);
  std::vector<float> map(200 * 150);
  for (std::size_t i = 0; i < map.size(); ++i)
  {
    map[i] = static_cast<float>(std::sin(0.01 * i) * 0.5 + 0.5);
  }
  const auto d = ComputeFootprints(proj, {}, map.data());
  FootprintOptions fo;
  fo.Accumulation = FootprintAccumulation::Float;
  const auto f = ComputeFootprints(proj, fo, map.data());
  EXPECT_EQ(d.PixelCount, f.PixelCount);
  double worst = 0;
  for (std::size_t i = 0; i < d.MapSum.size(); ++i)
  {
    worst = std::max(worst, std::abs(d.MapSum[i] - f.MapSum[i]) / (1 + d.MapSum[i]));
  }
  EXPECT_LT(worst, 1e-4);
  // Threads do not change anything.
  FootprintOptions one;
  one.Threads = 1;
  const auto d1 = ComputeFootprints(proj, one, map.data());
  EXPECT_EQ(d1.PixelCount, d.PixelCount);
  EXPECT_EQ(d1.MapSum, d.MapSum);
}

//------------------------------------------------------------------------------
// The vectorised float path (packed ellipse boxes, AVX2 rows, the power band that skips the
// exponential) against the scalar span path and the brute-force scan: counts and sums must
// be bit-identical (same pixels, same summation order), for both modes and accumulations,
// any thread count, and maps holding NaN, Inf, -0 and negative values.
namespace
{

bool SameBits(const std::vector<double>& a, const std::vector<double>& b)
{
  return a.size() == b.size() &&
    (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

void CheckAllPathsIdentical(const ViewProjection<float>& proj, const std::vector<float>& map)
{
  for (auto mode : { FootprintMode::Rasterizer, FootprintMode::Ellipse3Sigma })
  {
    for (auto acc : { FootprintAccumulation::Double, FootprintAccumulation::Float })
    {
      FootprintOptions brute, scalar, vec1, vec3;
      brute.Mode = scalar.Mode = vec1.Mode = vec3.Mode = mode;
      brute.Accumulation = scalar.Accumulation = vec1.Accumulation = vec3.Accumulation = acc;
      brute.BruteForce = true;
      scalar.KernelIsa = 1;
      vec1.Threads = 1;
      vec3.Threads = 3;
      const auto b = ComputeFootprints(proj, brute, map.data());
      const auto s = ComputeFootprints(proj, scalar, map.data());
      const auto v1 = ComputeFootprints(proj, vec1, map.data());
      const auto v3 = ComputeFootprints(proj, vec3, map.data());
      const auto counts = ComputeFootprints(proj, vec3, nullptr);
      // vec1/vec3 take the best instruction set (AVX-512 boxes where available); the AVX2
      // boxes must give the same bits.
      FootprintOptions avx2 = vec3;
      avx2.KernelIsa = 2;
      const auto v2 = ComputeFootprints(proj, avx2, map.data());
      ASSERT_EQ(b.PixelCount, v2.PixelCount) << int(mode);
      EXPECT_TRUE(SameBits(b.MapSum, v2.MapSum)) << int(mode);
      ASSERT_EQ(b.PixelCount, s.PixelCount) << int(mode);
      ASSERT_EQ(b.PixelCount, v1.PixelCount) << int(mode);
      ASSERT_EQ(b.PixelCount, v3.PixelCount) << int(mode);
      ASSERT_EQ(b.PixelCount, counts.PixelCount) << int(mode);
      EXPECT_TRUE(SameBits(b.MapSum, s.MapSum)) << int(mode);
      EXPECT_TRUE(SameBits(b.MapSum, v1.MapSum)) << int(mode);
      EXPECT_TRUE(SameBits(b.MapSum, v3.MapSum)) << int(mode);
      EXPECT_EQ(b.TotalPixels, v3.TotalPixels);
      EXPECT_GT(b.TotalPixels, 0u);
    }
  }
}

} // namespace

TEST(Footprint, VectorPathBitIdenticalOnMixedScene)
{
  const auto cloud = MixedScene();
  // Full, 1/4 and 1/8 size: at low resolution almost every ellipse is a packed box.
  for (int scale : { 1, 4, 8 })
  {
    const int w = 160 / scale * 2, h = 120 / scale * 2;
    const Camera cam = LookAt(w, h, 0.56 * w, 0.56 * w, { 0.2, -0.1, -0.3 }, { 0, 0, 5 });
    CheckAllPathsIdentical(ProjectGaussians<float>(cloud, cam), OddMap(w, h, 3u + scale));
  }
}

TEST(Footprint, VectorPathBitIdenticalNearTheAlphaThreshold)
{
  // Opacities from just above 1/255 to 1 and tiny to medium scales at random sub-pixel
  // positions: many pixels have o e^power within rounding of 1/255, the band where the
  // fast path must fall back to the exact exponential.
  GaussianCloud cloud = RandomScene(6000, 0, 77u, 2.0f, 9.0f, -7.0f, -2.5f);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(0, 1);
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    const float o =
      std::exp(std::log(1.0f / 255.0f) * (1.0f - u(rng)) * (i % 3 == 0 ? 0.05f : 1.0f));
    cloud.OpacityLogits[i] = std::log(o / (1.0f - std::min(o, 0.999f)));
  }
  const Camera cam = LookAt(96, 64, 60, 60, { 0, 0, 0 }, { 0, 0, 5 });
  const auto proj = ProjectGaussians<float>(cloud, cam);
  CheckAllPathsIdentical(proj, OddMap(96, 64, 5u));
  // Independent check of the count at the threshold: the kernel applied pixel by pixel.
  FootprintOptions fo;
  const auto st = ComputeFootprints(proj, fo);
  std::uint64_t naive = 0;
  for (const auto& g : proj.Gaussians)
  {
    if (!g.IsVisible())
    {
      continue;
    }
    for (int y = g.TileRect[1] * 16; y < std::min(g.TileRect[3] * 16, 64); ++y)
    {
      for (int x = g.TileRect[0] * 16; x < std::min(g.TileRect[2] * 16, 96); ++x)
      {
        const float p = raster::KernelPower<float>(
          g.U, g.V, g.ConicA, g.ConicB, g.ConicC, static_cast<float>(x), static_cast<float>(y));
        naive += raster::KernelAlpha<float>(g.Opacity, p) >= 0 ? 1 : 0;
      }
    }
  }
  EXPECT_EQ(st.TotalPixels, naive);
}

TEST(Footprint, VectorPathBitIdenticalOnRealScene)
{
  VIS4GS_REQUIRE_SHARED_DATA();
  const GaussianCloud cloud = ReadGaussianPly(vis4gs::testing::SharedDataPath(
    "inria_ply_tiny_kacytran/point_cloud/iteration_7000/point_cloud.ply"));
  ASSERT_GT(cloud.Count, 1000u);
  std::array<double, 3> c{ 0, 0, 0 };
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      c[k] += cloud.Positions[3 * i + k] / static_cast<double>(cloud.Count);
    }
  }
  for (int w : { 320, 80 })
  {
    const int h = w * 3 / 4;
    const Camera cam =
      LookAt(w, h, 0.8 * w, 0.8 * w, { c[0], c[1], c[2] - 4.0 }, { c[0], c[1], c[2] });
    const auto proj = ProjectGaussians<float>(cloud, cam);
    ASSERT_GT(proj.Counts.Visible, 100u);
    CheckAllPathsIdentical(proj, OddMap(w, h, 11u));
  }
}

//------------------------------------------------------------------------------
// Issue 15: |Omega| of an axis-aligned Gaussian from its analytic ellipse, for several sizes
// and opacities. On the axis camera a Gaussian at (x, 0, z) with scales (sx, sy, sz) projects
// (reference §2.3, J = [[f/z, 0, -f x/z^2], [0, f/z, 0]]) to the dilated variances
//   a = (f sx/z)^2 + (f x sz/z^2)^2 + 0.3,   c = (f sy/z)^2 + 0.3,   b = 0,
// centred at u = f x/z + (W-1)/2, v = (H-1)/2. alpha = min(0.99, o e^power) >= 1/255 is
// dx^2/a + dy^2/c <= 2 ln(255 o); the rasteriser evaluates only the pixels of the tile
// rectangle of radius ceil(3 sqrt(lambda_max)), lambda_max = (a+c)/2 + max(sqrt(0.1), |a-c|/2).
// The count of pixel centres inside both is computed here from these formulas alone.
TEST(Footprint, AxisAlignedCountEqualsAnalyticEllipse)
{
  struct Case
  {
    double Sx, Sy, Sz, Opacity, X;
    bool TilesCut; // whether the tile rectangle removes pixels of the alpha ellipse
  };
  const Case cases[] = {
    { 0.05, 0.02, 0.03, 0.3, 0.0, false },   // 2.5 x 1 px, 76 pixels
    { 0.2, 0.08, 0.05, 0.9, 0.0, true },     // 10 x 4 px: alpha reaches past 3 sigma, 1364 of 1372
    { 0.12, 0.3, 0.1, 0.6, 0.37, false },    // off-centre: u not an integer, sz enters a; 2872
    { 1e-9, 1e-9, 1e-9, 0.99, 0.11, false }, // a dilated point: a = c = 0.3; 12 pixels
    { 0.5, 0.5, 0.5, 0.05, -0.2, false },    // large and faint; 9992 pixels
  };
  const int w = 160, h = 128;
  const double f = 200, z = 4;
  const Camera cam = AxisCamera(w, h, f, f);
  for (const Case& k : cases)
  {
    GaussianCloud cloud;
    cloud.Resize(1, 0);
    const float logit = static_cast<float>(std::log(k.Opacity / (1 - k.Opacity)));
    SetGaussian(cloud,
      0,
      { static_cast<float>(k.X), 0.0f, static_cast<float>(z) },
      { static_cast<float>(std::log(k.Sx)),
        static_cast<float>(std::log(k.Sy)),
        static_cast<float>(std::log(k.Sz)) },
      { 1, 0, 0, 0 },
      logit,
      { 0.5f, 0.5f, 0.5f });
    // The stored float values, so that the hand computation sees what the rasteriser sees.
    const double sx = std::exp(static_cast<double>(cloud.LogScales[0]));
    const double sy = std::exp(static_cast<double>(cloud.LogScales[1]));
    const double sz = std::exp(static_cast<double>(cloud.LogScales[2]));
    const double x = cloud.Positions[0];
    const double o = 1 / (1 + std::exp(-static_cast<double>(logit)));
    const double a = std::pow(f * sx / z, 2) + std::pow(f * x * sz / (z * z), 2) + 0.3;
    const double c = std::pow(f * sy / z, 2) + 0.3;
    const double u = f * x / z + (w - 1) / 2.0, v = (h - 1) / 2.0;
    const double lambda = (a + c) / 2 + std::max(std::sqrt(0.1), std::abs(a - c) / 2);
    const double r = std::ceil(3 * std::sqrt(lambda));
    const auto tile = [](double p, int tiles)
    { return std::min(std::max(static_cast<int>(std::trunc(p / 16)), 0), tiles); };
    const int gx = (w + 15) / 16, gy = (h + 15) / 16;
    const int x0 = 16 * tile(u - r, gx), x1 = std::min(16 * tile(u + r + 15, gx), w);
    const int y0 = 16 * tile(v - r, gy), y1 = std::min(16 * tile(v + r + 15, gy), h);
    const double threshold = 2 * std::log(255 * o);
    std::uint32_t expected = 0, ellipse = 0;
    for (int py = 0; py < h; ++py)
    {
      for (int px = 0; px < w; ++px)
      {
        const bool inside = (px - u) * (px - u) / a + (py - v) * (py - v) / c <= threshold;
        ellipse += inside;
        expected += inside && px >= x0 && px < x1 && py >= y0 && py < y1;
      }
    }
    const auto pf = ProjectGaussians<float>(cloud, cam);
    const auto pd = ProjectGaussians<double>(cloud, cam);
    ASSERT_TRUE(pd.Gaussians[0].IsVisible());
    EXPECT_EQ(ComputeFootprints(pd).PixelCount[0], expected) << "sx " << k.Sx;
    EXPECT_EQ(ComputeFootprints(pf).PixelCount[0], expected) << "sx " << k.Sx;
    // The lattice count of the whole ellipse is its area pi sqrt(ac) threshold up to the
    // boundary (a few pixels per unit of perimeter); the tile cut only ever removes pixels.
    const double area = 3.141592653589793 * std::sqrt(a * c) * threshold;
    EXPECT_NEAR(ellipse, area, 2 + 0.1 * area) << "sx " << k.Sx;
    EXPECT_EQ(expected < ellipse, k.TilesCut) << "sx " << k.Sx;
  }
}

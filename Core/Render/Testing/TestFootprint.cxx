// SPDX-License-Identifier: BSD-3-Clause
// Footprint statistics |Omega(g,v)| and map sums: the analytic-span fast path equals the
// brute-force definition, and both agree with independent computations.
#include "RasterTestUtils.h"

#include "Footprint.h"
#include "Rasterizer.h"

#include <gtest/gtest.h>

#include <cmath>
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

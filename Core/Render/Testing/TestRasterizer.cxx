// SPDX-License-Identifier: BSD-3-Clause
// Rasteriser correctness: hand-computed single Gaussians, compositing order, agreement with
// naive per-pixel implementations, order/thread/instruction-set invariance, attribution.
#include "RasterTestUtils.h"

#include "Footprint.h"
#include "RasterInternal.h"
#include "Rasterizer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>

using namespace vis4gs;
using namespace vis4gs::rastertest;

namespace
{

GaussianCloud OneGaussian(std::array<float, 3> pos,
  std::array<float, 3> logScale,
  std::array<float, 4> rot,
  float logit,
  std::array<float, 3> rgb,
  int degree = 0)
{
  GaussianCloud c;
  c.Resize(1, degree);
  SetGaussian(c, 0, pos, logScale, rot, logit, rgb);
  return c;
}

template <typename T>
std::size_t Pix(const RasterImage<T>& img, int x, int y)
{
  return static_cast<std::size_t>(y) * img.Width + x;
}

} // namespace

//------------------------------------------------------------------------------
TEST(RasterKernel, ExpWithinTwoUlp)
{
  double worst = 0;
  for (int i = 0; i <= 2000000; ++i)
  {
    const float x = -87.0f * static_cast<float>(i) / 2000000.0f;
    const float e = raster::KernelExp(x);
    const double ref = std::exp(static_cast<double>(x));
    const double ulp = std::nextafter(static_cast<float>(ref), 1e30f) - static_cast<float>(ref);
    worst = std::max(worst, std::abs(e - ref) / ulp);
  }
  EXPECT_LE(worst, 2.0);
  EXPECT_EQ(raster::KernelExp(0.0f), 1.0f);
  EXPECT_EQ(raster::KernelExp(-100.0f), 0.0f);
  EXPECT_EQ(raster::KernelExp(-std::numeric_limits<float>::infinity()), 0.0f);
}

//------------------------------------------------------------------------------
// Isotropic Gaussian on the optical axis: every quantity by hand.
// W = H = 33, f = 40: the mean projects to pixel (16, 16) exactly. sigma = 0.05 at z = 4:
// 2D variance (40*0.05/4)^2 = 0.25, + 0.3 dilation = 0.55. opacity sigmoid(0) = 0.5.
TEST(Rasterizer, HandComputedIsotropic)
{
  const std::array<float, 3> rgb{ 0.8f, 0.3f, 0.1f };
  const auto cloud = OneGaussian(
    { 0, 0, 4 }, { std::log(0.05f), std::log(0.05f), std::log(0.05f) }, { 1, 0, 0, 0 }, 0.0f, rgb);
  const Camera cam = AxisCamera(33, 33, 40, 40);
  RasterSettings s;
  s.Background = { 0.1, 0.2, 0.3 };
  const auto imgD = Rasterize<double>(cloud, cam, s);
  const auto imgF = Rasterize<float>(cloud, cam, s);
  // The stored log-scale is a float: sigma = exp(float(log 0.05)).
  const double sigma = std::exp(static_cast<double>(std::log(0.05f)));
  const double var = std::pow(40.0 * sigma / 4.0, 2) + 0.3;
  const int pts[][2] = { { 16, 16 }, { 17, 16 }, { 18, 15 }, { 14, 19 }, { 16, 20 } };
  for (const auto& p : pts)
  {
    const double dx = 16.0 - p[0], dy = 16.0 - p[1];
    const double power = -0.5 * (dx * dx + dy * dy) / var;
    double alpha = std::min(0.99, 0.5 * std::exp(power));
    alpha = alpha < 1.0 / 255 ? 0.0 : alpha; // (16, 20): 0.5 e^{-14.5} is skipped
    const std::size_t i = Pix(imgD, p[0], p[1]);
    for (int c = 0; c < 3; ++c)
    {
      // SH DC round trip: 0.5 + C0 * (rgb - 0.5)/C0 (float SH coefficient).
      const double col =
        0.5 + sh::C0 * static_cast<double>(static_cast<float>((rgb[c] - 0.5) / sh::C0));
      const double expected = col * alpha + (1 - alpha) * s.Background[c];
      EXPECT_NEAR(imgD.Color[3 * i + c], expected, 1e-12) << p[0] << "," << p[1];
      EXPECT_NEAR(imgF.Color[3 * i + c], expected, 1e-6) << p[0] << "," << p[1];
    }
    EXPECT_NEAR(imgD.Alpha[i], alpha, 1e-12);
    EXPECT_NEAR(imgD.Depth[i], 4.0 * alpha, 1e-12);
    EXPECT_EQ(imgD.Contributors[i], alpha > 0 ? 1u : 0u);
    EXPECT_EQ(imgF.Contributors[i], alpha > 0 ? 1u : 0u);
  }
  // Radius ceil(3 sqrt(0.55)) = 3; pixels beyond the tile rectangle see nothing.
  const auto proj = ProjectGaussians<double>(cloud, cam, s);
  EXPECT_EQ(proj.Gaussians[0].Radius, 3);
  EXPECT_DOUBLE_EQ(proj.Gaussians[0].U, 16.0);
  EXPECT_DOUBLE_EQ(proj.Gaussians[0].V, 16.0);
  // Far pixel: alpha < 1/255 -> background, 0 contributors.
  const std::size_t far = Pix(imgD, 0, 0);
  EXPECT_EQ(imgD.Contributors[far], 0u);
  EXPECT_DOUBLE_EQ(imgD.Color[3 * far + 2], 0.3);
}

//------------------------------------------------------------------------------
// A rotated anisotropic Gaussian with SH degree 2 seen by an oblique camera: expected pixel
// values from the formulas written out in the test (NaiveProject, double) and the blending
// equation of a single Gaussian.
TEST(Rasterizer, HandComputedGeneral)
{
  GaussianCloud cloud;
  cloud.Resize(1, 2);
  SetGaussian(cloud,
    0,
    { 0.3f, -0.2f, 0.5f },
    { std::log(0.4f), std::log(0.08f), std::log(0.15f) },
    { 0.8f, 0.3f, -0.4f, 0.2f },
    1.2f,
    { 0.6f, 0.5f, 0.4f });
  for (int k = 3; k < 27; ++k)
  {
    cloud.SH[k] = 0.05f * static_cast<float>((k * 7) % 11 - 5);
  }
  const Camera cam = LookAt(80, 60, 70, 75, { 1.0, -0.5, -3.0 }, { 0.2, 0.0, 0.5 });
  RasterSettings s;
  s.Background = { 0.2, 0.7, 0.1 };
  const auto ref = NaiveProject<double>(cloud, cam, 2);
  ASSERT_TRUE(ref.Gaussians[0].IsVisible());
  const auto& g = ref.Gaussians[0];
  const auto projD = ProjectGaussians<double>(cloud, cam, s);
  const auto& h = projD.Gaussians[0];
  EXPECT_NEAR(h.U, g.U, 1e-10);
  EXPECT_NEAR(h.V, g.V, 1e-10);
  EXPECT_NEAR(h.ConicA, g.ConicA, 1e-12 * std::abs(g.ConicA) + 1e-14);
  EXPECT_NEAR(h.ConicB, g.ConicB, 1e-12 * std::abs(g.ConicA) + 1e-14);
  EXPECT_NEAR(h.ConicC, g.ConicC, 1e-12 * std::abs(g.ConicC) + 1e-14);
  EXPECT_EQ(h.Radius, g.Radius);
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(h.Color[c], g.Color[c], 1e-12);
  }
  const auto imgD = Rasterize<double>(cloud, cam, s);
  const auto imgF = Rasterize<float>(cloud, cam, s);
  int checked = 0;
  for (int y = 0; y < cam.Height; ++y)
  {
    for (int x = 0; x < cam.Width; ++x)
    {
      const double dx = g.U - x, dy = g.V - y;
      const double power = -0.5 * (g.ConicA * dx * dx + g.ConicC * dy * dy) - g.ConicB * dx * dy;
      double alpha = std::min(0.99, g.Opacity * std::exp(power));
      const int tx = x / 16, ty = y / 16;
      const bool inRect =
        tx >= g.TileRect[0] && tx < g.TileRect[2] && ty >= g.TileRect[1] && ty < g.TileRect[3];
      if (power > 0 || alpha < 1.0 / 255 || !inRect)
      {
        alpha = 0;
      }
      const std::size_t i = Pix(imgD, x, y);
      for (int c = 0; c < 3; ++c)
      {
        const double expected = g.Color[c] * alpha + (1 - alpha) * s.Background[c];
        ASSERT_NEAR(imgD.Color[3 * i + c], expected, 1e-11) << x << "," << y;
        ASSERT_NEAR(imgF.Color[3 * i + c], expected, 2e-5) << x << "," << y;
      }
      checked += alpha > 0.05;
    }
  }
  EXPECT_GT(checked, 20); // the splat really covers pixels
}

//------------------------------------------------------------------------------
// Two Gaussians on the same pixel: front-to-back blending by view z, whatever the input
// order; and the stop rule: with alpha = 0.99 twice, T would drop below 1e-4, so the second
// Gaussian is not blended.
TEST(Rasterizer, HandComputedOcclusionAndStop)
{
  GaussianCloud cloud;
  cloud.Resize(2, 0);
  const float ls = std::log(0.02f);
  // Back Gaussian first in the input.
  SetGaussian(cloud, 0, { 0, 0, 6 }, { ls, ls, ls }, { 1, 0, 0, 0 }, -0.5f, { 0.1f, 0.9f, 0.2f });
  SetGaussian(cloud, 1, { 0, 0, 3 }, { ls, ls, ls }, { 1, 0, 0, 0 }, 0.7f, { 0.9f, 0.2f, 0.3f });
  const Camera cam = AxisCamera(17, 17, 30, 30); // centre pixel (8, 8)
  RasterSettings s;
  s.Background = { 1, 1, 1 };
  const auto img = Rasterize<double>(cloud, cam, s);
  const auto proj = ProjectGaussians<double>(cloud, cam, s);
  const double o1 = 1 / (1 + std::exp(-static_cast<double>(0.7f))), o0 = 1 / (1 + std::exp(0.5));
  const std::size_t i = Pix(img, 8, 8);
  for (int c = 0; c < 3; ++c)
  {
    const double c1 = proj.Gaussians[1].Color[c], c0 = proj.Gaussians[0].Color[c];
    const double expected = c1 * o1 + c0 * o0 * (1 - o1) + (1 - o1) * (1 - o0) * 1.0;
    EXPECT_NEAR(img.Color[3 * i + c], expected, 1e-12);
  }
  EXPECT_NEAR(img.Depth[i], 3 * o1 + 6 * o0 * (1 - o1), 1e-12);
  EXPECT_EQ(img.Contributors[i], 2u);

  // Opaque: logit 100 -> o = 1 -> alpha = 0.99; T after one = 0.01, next would be 1e-4 - eps.
  cloud.OpacityLogits[0] = 100.0f;
  cloud.OpacityLogits[1] = 100.0f;
  const auto imgF = Rasterize<float>(cloud, cam, s);
  const auto projF = ProjectGaussians<float>(cloud, cam, s);
  const float T1 = 1.0f * (1.0f - 0.99f);
  ASSERT_LT(T1 * (1.0f - 0.99f), 1e-4f); // the reference's stop fires
  EXPECT_EQ(imgF.Contributors[i], 1u);
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_FLOAT_EQ(imgF.Color[3 * i + c], projF.Gaussians[1].Color[c] * 0.99f * 1.0f + T1 * 1.0f);
  }
  EXPECT_FLOAT_EQ(imgF.Transmittance[i], T1);
}

//------------------------------------------------------------------------------
TEST(Rasterizer, NaiveCompositeBitIdentical)
{
  const auto cloud = RandomScene(1500, 3, 11u);
  const Camera cam = LookAt(97, 75, 60, 62, { 0.3, -0.2, -0.5 }, { 0, 0, 5 });
  RasterSettings s;
  s.Background = { 0.25, 0.5, 0.75 };
  {
    const auto proj = ProjectGaussians<float>(cloud, cam, s);
    const auto bins = BinGaussians(proj);
    RasterImage<float> img;
    CompositeTiles(proj, bins, s, img);
    const auto naive = NaiveComposite(proj, s.Background);
    EXPECT_EQ(
      0, std::memcmp(img.Color.data(), naive.Color.data(), img.Color.size() * sizeof(float)));
    EXPECT_EQ(img.Contributors, naive.Contributors);
    EXPECT_EQ(
      0, std::memcmp(img.Depth.data(), naive.Depth.data(), img.Depth.size() * sizeof(float)));
    EXPECT_EQ(0,
      std::memcmp(img.Transmittance.data(),
        naive.Transmittance.data(),
        img.Transmittance.size() * sizeof(float)));
  }
  {
    const auto proj = ProjectGaussians<double>(cloud, cam, s);
    const auto bins = BinGaussians(proj);
    RasterImage<double> img;
    CompositeTiles(proj, bins, s, img);
    const auto naive = NaiveComposite(proj, s.Background);
    EXPECT_EQ(img.Color, naive.Color);
    EXPECT_EQ(img.Contributors, naive.Contributors);
  }
}

//------------------------------------------------------------------------------
// Independent preprocessing (no shared code): double agrees to rounding, float to 1e-5
// except where a threshold decision (alpha vs 1/255, T vs 1e-4) flips.
TEST(Rasterizer, NaiveIndependentAgreement)
{
  const auto cloud = RandomScene(1200, 3, 5u);
  const Camera cam = LookAt(90, 70, 55, 58, { -0.4, 0.3, -0.8 }, { 0.1, 0, 5 });
  RasterSettings s;
  s.Background = { 0.3, 0.3, 0.3 };
  const auto naiveD = NaiveComposite(NaiveProject<double>(cloud, cam, 3), s.Background);
  const auto imgD = Rasterize<double>(cloud, cam, s);
  EXPECT_LT(MaxAbsDiff(imgD.Color, naiveD.Color), 1e-9);
  EXPECT_EQ(imgD.Contributors, naiveD.Contributors);
  const auto imgF = Rasterize<float>(cloud, cam, s);
  std::size_t off = 0;
  for (std::size_t i = 0; i < imgF.Color.size(); ++i)
  {
    off += std::abs(imgF.Color[i] - naiveD.Color[i]) > 1e-5;
  }
  EXPECT_LE(off, imgF.Color.size() / 500) << off << " channel values differ by more than 1e-5";
}

//------------------------------------------------------------------------------
TEST(Rasterizer, ShuffleGivesIdenticalImage)
{
  const auto cloud = RandomScene(3000, 1, 21u);
  std::vector<std::size_t> perm(cloud.Count);
  std::iota(perm.begin(), perm.end(), 0);
  std::mt19937 rng(4);
  std::shuffle(perm.begin(), perm.end(), rng);
  GaussianCloud shuffled;
  shuffled.Resize(cloud.Count, cloud.ShDegree);
  const int K = cloud.ShCoefficientCount();
  for (std::size_t j = 0; j < cloud.Count; ++j)
  {
    const std::size_t i = perm[j];
    std::copy_n(&cloud.Positions[3 * i], 3, &shuffled.Positions[3 * j]);
    std::copy_n(&cloud.LogScales[3 * i], 3, &shuffled.LogScales[3 * j]);
    std::copy_n(&cloud.Rotations[4 * i], 4, &shuffled.Rotations[4 * j]);
    shuffled.OpacityLogits[j] = cloud.OpacityLogits[i];
    std::copy_n(&cloud.SH[3 * K * i], 3 * K, &shuffled.SH[3 * K * j]);
  }
  const Camera cam = LookAt(128, 96, 80, 80, { 0, 0, -1 }, { 0, 0, 5 });
  RasterSettings s;
  s.Background = { 0.1, 0.2, 0.3 };
  const auto a = Rasterize<float>(cloud, cam, s);
  const auto b = Rasterize<float>(shuffled, cam, s);
  EXPECT_EQ(0, std::memcmp(a.Color.data(), b.Color.data(), a.Color.size() * sizeof(float)));
  EXPECT_EQ(a.Contributors, b.Contributors);
  const auto ad = Rasterize<double>(cloud, cam, s);
  const auto bd = Rasterize<double>(shuffled, cam, s);
  EXPECT_EQ(ad.Color, bd.Color);
}

//------------------------------------------------------------------------------
// BinGaussians against a naive binning (every tile tests every visible Gaussian's tile
// rectangle, std::sort on (depth, index)), with many exact depth ties (identity camera: view
// z = world z, quantised to 5 values), culled Gaussians interleaved, several thread counts,
// float and double; plus the empty and single-Gaussian cases.
template <typename T>
void CheckBinsAgainstNaive(const ViewProjection<T>& proj, int threads)
{
  const TileBins bins = BinGaussians(proj, threads);
  ASSERT_EQ(bins.Offsets.size(), bins.TileCount() + 1);
  ASSERT_EQ(bins.Offsets.back(), bins.Ids.size());
  for (int ty = 0; ty < proj.TilesY; ++ty)
  {
    for (int tx = 0; tx < proj.TilesX; ++tx)
    {
      std::vector<std::pair<T, std::uint32_t>> expected;
      for (std::size_t i = 0; i < proj.Gaussians.size(); ++i)
      {
        const auto& g = proj.Gaussians[i];
        if (g.IsVisible() && tx >= g.TileRect[0] && tx < g.TileRect[2] && ty >= g.TileRect[1] &&
          ty < g.TileRect[3])
        {
          expected.emplace_back(g.Depth, static_cast<std::uint32_t>(i));
        }
      }
      std::sort(expected.begin(), expected.end());
      const std::size_t t = static_cast<std::size_t>(ty) * proj.TilesX + tx;
      const std::vector<std::uint32_t> got(
        bins.Ids.begin() + bins.Offsets[t], bins.Ids.begin() + bins.Offsets[t + 1]);
      std::vector<std::uint32_t> want;
      for (const auto& e : expected)
      {
        want.push_back(e.second);
      }
      ASSERT_EQ(got, want) << "tile " << tx << "," << ty << " threads " << threads;
    }
  }
}

TEST(Rasterizer, BinsMatchNaiveOrderWithTies)
{
  auto cloud = RandomScene(2500, 0, 13u, 2.0f, 8.0f, -4.0f, -1.5f);
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    cloud.Positions[3 * i + 2] = 2.0f + static_cast<float>(i % 5) * 1.5f;
    if (i % 7 == 3)
    {
      cloud.Positions[3 * i + 2] = -1.0f; // behind the camera
    }
    if (i % 11 == 5)
    {
      cloud.OpacityLogits[i] = std::numeric_limits<float>::quiet_NaN();
    }
  }
  const Camera cam = AxisCamera(200, 120, 150, 150);
  const auto projF = ProjectGaussians<float>(cloud, cam);
  const auto projD = ProjectGaussians<double>(cloud, cam);
  ASSERT_GT(projF.Counts.Visible, 1500u);
  ASSERT_LT(projF.Counts.Visible, cloud.Count);
  std::size_t ties = 0; // visible Gaussians at depth exactly 2
  for (const auto& g : projF.Gaussians)
  {
    ties += (g.IsVisible() && g.Depth == 2.0f) ? 1 : 0;
  }
  ASSERT_GT(ties, 100u);
  for (int threads : { 1, 2, 3, 5 })
  {
    CheckBinsAgainstNaive(projF, threads);
    CheckBinsAgainstNaive(projD, threads);
  }
  // Only culled Gaussians: empty bins; a single visible one: in every tile of its rectangle.
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    cloud.Positions[3 * i + 2] = -1.0f;
  }
  auto none = ProjectGaussians<float>(cloud, cam);
  EXPECT_EQ(none.Counts.Visible, 0u);
  CheckBinsAgainstNaive(none, 2);
  EXPECT_TRUE(BinGaussians(none, 2).Ids.empty());
  cloud.Positions[3 * 4 + 2] = 3.0f;
  cloud.OpacityLogits[4] = 0.0f;
  auto one = ProjectGaussians<float>(cloud, cam);
  EXPECT_EQ(one.Counts.Visible, 1u);
  CheckBinsAgainstNaive(one, 3);
}

// BinGaussians() keeps the sorted tile rectangles in 16 bits per coordinate when the tile grid
// fits (at most 65535 tiles a side) and in ints beyond: hand-made projections on grids of
// 65535 (the last narrow one) and 70000 tiles a side, rectangles crossing and ending at the
// 16-bit limit, depth ties, culled Gaussians between; float and double, 1-3 threads.
template <typename T>
ViewProjection<T> WideGridProjection(int tilesX, int tilesY)
{
  ViewProjection<T> p;
  p.TilesX = tilesX;
  p.TilesY = tilesY;
  p.Width = 16 * tilesX;
  p.Height = 16 * tilesY;
  for (int i = 0; i < 60; ++i)
  {
    ProjectedGaussian<T> g;
    g.Status = i % 9 == 4 ? ProjectionStatus::NearPlane : ProjectionStatus::Visible;
    g.Radius = g.IsVisible() ? 3 : 0;
    g.Depth = static_cast<T>(1 + i % 4); // ties
    const int x0 =
      std::max(0, std::min(tilesX - 1, i % 3 == 0 ? 65530 - i % 5 : tilesX - 1 - (i * 37) % 12));
    g.TileRect[0] = x0;
    g.TileRect[1] = i % 2;
    g.TileRect[2] = std::min(tilesX, x0 + 1 + i % 7);
    g.TileRect[3] = std::min(tilesY, 1 + i % 2 + i % 3);
    p.Gaussians.push_back(g);
    p.Counts.Visible += g.IsVisible() ? 1 : 0;
  }
  return p;
}

TEST(Rasterizer, BinsMatchNaiveOnTileGridsBeyond16Bits)
{
  for (int tilesX : { 65535, 70000 })
  {
    const auto projF = WideGridProjection<float>(tilesX, 3);
    const auto projD = WideGridProjection<double>(tilesX, 3);
    for (int threads : { 1, 2, 3 })
    {
      CheckBinsAgainstNaive(projF, threads);
      CheckBinsAgainstNaive(projD, threads);
    }
    // Reused scratch across grid sizes gives the same lists as fresh calls.
    TileBins bins;
    BinScratch scratch;
    for (int t : { tilesX, 100, tilesX })
    {
      const auto proj = WideGridProjection<float>(t, 3);
      BinGaussians(proj, 2, bins, scratch);
      const TileBins fresh = BinGaussians(proj, 2);
      EXPECT_EQ(fresh.Offsets, bins.Offsets);
      EXPECT_EQ(fresh.Ids, bins.Ids);
    }
  }
}

//------------------------------------------------------------------------------
// The AVX-512 compositing blends two tile rows per vector when a Gaussian's candidate columns
// in both fit in 8 lanes. A dense scene of tiny, mostly opaque splats (1-6 px, many pixels
// reaching the T < 1e-4 stop, an image whose width and height are not multiples of 16) must
// give the same bits on every instruction set and match the naive per-pixel replay, with the
// same weight statistics and reference work counts; the packed path must actually run (fewer
// kernel vectors evaluated than the one-row-per-vector baseline).
TEST(Rasterizer, NarrowSpansTwoRowsPerVectorBitIdentical)
{
  auto cloud = RandomScene(12000, 1, 21u, 3.0f, 6.0f, -5.5f, -3.3f);
  for (std::size_t i = 0; i < cloud.Count; i += 3)
  {
    cloud.OpacityLogits[i] = 6.0f;
  }
  const Camera cam = LookAt(101, 77, 70, 70, { 0.2, -0.1, -0.5 }, { 0, 0, 5 });
  RasterSettings s;
  s.Background = { 0.1, 0.7, 0.3 };
  s.Threads = 1;
  s.KernelIsa = 1;
  const auto proj = ProjectGaussians<float>(cloud, cam, s);
  const auto bins = BinGaussians(proj);
  RasterImage<float> ref;
  GaussianWeightStats refW;
  RasterWorkCounts refWork;
  CompositeTiles(proj, bins, s, ref, &refW, &refWork);
  const auto naive = NaiveComposite(proj, s.Background);
  ASSERT_EQ(0, std::memcmp(ref.Color.data(), naive.Color.data(), ref.Color.size() * sizeof(float)));
  ASSERT_EQ(ref.Contributors, naive.Contributors);
  std::size_t stopped = 0;
  for (float t : ref.Transmittance)
  {
    stopped += t < 1e-3f ? 1 : 0;
  }
  EXPECT_GT(stopped, ref.Transmittance.size() / 20); // the stop rule is exercised
  const bool has512 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
    __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq");
  for (int isa = 0; isa <= 3; ++isa)
  {
    for (int threads : { 1, 2 })
    {
      s.KernelIsa = isa;
      s.Threads = threads;
      RasterImage<float> img;
      GaussianWeightStats w;
      RasterWorkCounts work;
      CompositeTiles(proj, bins, s, img, &w, &work);
      EXPECT_EQ(
        0, std::memcmp(ref.Color.data(), img.Color.data(), ref.Color.size() * sizeof(float)))
        << "isa " << isa << " threads " << threads;
      EXPECT_EQ(
        0, std::memcmp(ref.Depth.data(), img.Depth.data(), ref.Depth.size() * sizeof(float)));
      EXPECT_EQ(0,
        std::memcmp(ref.Transmittance.data(),
          img.Transmittance.data(),
          ref.Transmittance.size() * sizeof(float)));
      EXPECT_EQ(ref.Contributors, img.Contributors);
      EXPECT_EQ(refW.MaxWeight, w.MaxWeight);
      EXPECT_EQ(refW.BlendedPixels, w.BlendedPixels);
      if (threads == 1)
      {
        EXPECT_EQ(refW.WeightSum, w.WeightSum); // same per-Gaussian summation order
      }
      EXPECT_EQ(refWork.ReferenceEvaluations, work.ReferenceEvaluations);
      if (isa == 3 && has512)
      {
        EXPECT_LT(work.KernelEvaluations, refWork.KernelEvaluations * 9 / 10);
      }
    }
  }
}

//------------------------------------------------------------------------------
// The AVX-512 tile loop computes the candidate columns of 8 rows per vector (RowColumns8);
// every row must get exactly what the scalar SpanBounds::Columns() and the tile clip give:
// same rows kept, same clipped columns. Conics from tiny to huge, means far off the tile and
// beyond the +-2^30 clamp, opacity levels from 1/255 to 1, tile columns around the span.
TEST(Rasterizer, RowColumnsVectorEqualsScalar)
{
  std::mt19937 rng(31u);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::size_t kept = 0, dropped = 0, clipped = 0, clamped = 0, bounds = 0;
  for (int trial = 0; trial < 20000; ++trial)
  {
    const double scale = std::pow(10.0, -6.0 + 12.0 * u01(rng)); // conic magnitude
    const double ang = 6.283185307179586 * u01(rng);
    const double ratio = std::pow(10.0, 4.0 * u01(rng));
    const double l1 = scale, l2 = scale * ratio;
    const double cs = std::cos(ang), sn = std::sin(ang);
    const float a = static_cast<float>(l1 * cs * cs + l2 * sn * sn);
    const float b = static_cast<float>((l1 - l2) * cs * sn);
    const float c = static_cast<float>(l1 * sn * sn + l2 * cs * cs);
    const double far = trial % 97 == 0 ? 3e9 : (trial % 13 == 0 ? 1e5 : 200.0);
    const float u = static_cast<float>((2.0 * u01(rng) - 1.0) * far);
    const float v = static_cast<float>((2.0 * u01(rng) - 1.0) * far);
    const double level = std::log(std::max(1.0 / 255.0, u01(rng)) * 255.0) * -1.0;
    const raster::detail::SpanBounds sb =
      raster::detail::MakeSpanBounds<float>(u, v, a, b, c, std::min(0.0, level));
    if (!sb.Bounded)
    {
      continue;
    }
    ++bounds;
    // Rows around the mean (or anywhere for far means), tiles around the span.
    const int py0 = static_cast<int>(std::floor(std::max(-2e9, std::min(2e9, double(v))))) -
      static_cast<int>(u01(rng) * 24.0);
    const int x0 =
      16 * static_cast<int>(std::floor(std::max(-1e8, std::min(1e8, double(u))) / 16.0)) +
      16 * (static_cast<int>(u01(rng) * 5.0) - 2);
    int lo[8], hi[8];
    const int mask = raster::internal::RowColumnsAvx512(sb, py0, x0, lo, hi);
    if (mask < 0)
    {
      GTEST_SKIP() << "no AVX-512 on this machine";
    }
    for (int l = 0; l < 8; ++l)
    {
      int xa = 0, xb = 0;
      const bool has = sb.Columns(py0 + l, xa, xb);
      clamped += has && (std::abs(xa) >= 1073741824 || std::abs(xb) >= 1073741824) ? 1 : 0;
      const bool ok = has && !(xb < x0 || xa > x0 + 15);
      ASSERT_EQ(ok, ((mask >> l) & 1) != 0) << "trial " << trial << " row " << l;
      if (ok)
      {
        ++kept;
        ASSERT_EQ(std::max(xa - x0, 0), lo[l]) << "trial " << trial << " row " << l;
        ASSERT_EQ(std::min(xb - x0, 15), hi[l]) << "trial " << trial << " row " << l;
        clipped += (xa < x0 || xb > x0 + 15) ? 1 : 0;
      }
      else
      {
        ++dropped;
      }
    }
  }
  EXPECT_GT(bounds, 10000u);
  EXPECT_GT(kept, 10000u);
  EXPECT_GT(dropped, 10000u);
  EXPECT_GT(clipped, 1000u);
  EXPECT_GT(clamped, 0u);
}

//------------------------------------------------------------------------------
TEST(Rasterizer, ThreadsAndInstructionSetsBitIdentical)
{
  const auto cloud = RandomScene(4000, 3, 8u, 1.0f, 10.0f, -5.0f, 0.0f);
  const Camera cam = LookAt(150, 100, 90, 90, { 0, 0, -0.5 }, { 0, 0, 5 });
  RasterSettings s;
  s.Threads = 1;
  s.KernelIsa = 1;
  const auto ref = Rasterize<float>(cloud, cam, s);
  for (int isa = 0; isa <= 3; ++isa)
  {
    for (int threads : { 1, 2, 3 })
    {
      s.KernelIsa = isa;
      s.Threads = threads;
      const auto img = Rasterize<float>(cloud, cam, s);
      EXPECT_EQ(
        0, std::memcmp(ref.Color.data(), img.Color.data(), ref.Color.size() * sizeof(float)))
        << "isa " << isa << " threads " << threads;
      EXPECT_EQ(ref.Contributors, img.Contributors);
    }
  }
}

//------------------------------------------------------------------------------
// The trainer's forward is CompositeTiles() with depth off and the per-Gaussian data kept:
// every other output must be bit-identical to the default pass on every instruction set
// and thread count, double included, and the kept data must equal PrepareCompositeData()
// (also when the buffers are reused for another view).
namespace
{
template <typename T>
void ExpectDepthOffAndKeptDataMatch(const GaussianCloud& cloud,
  const Camera& cam,
  CompositeData<T>& kept)
{
  RasterSettings s;
  s.Threads = 1;
  const auto proj = ProjectGaussians<T>(cloud, cam, s);
  const auto bins = BinGaussians(proj, 1);
  RasterImage<T> ref;
  CompositeTiles(proj, bins, s, ref);
  ASSERT_EQ(ref.Depth.size(), ref.Alpha.size());
  CompositeData<T> expected;
  PrepareCompositeData(proj, 1, expected);
  std::size_t bounded = 0;
  for (const auto& b : expected.Bounds)
  {
    bounded += b.NegTwoL > 0 ? 1 : 0;
  }
  EXPECT_GT(bounded, 0u);
  // PrepareCompositeData() runs an AVX2 encoding of the scalar code where the CPU has it: every
  // span field must equal the scalar definition compiled here (baseline x86-64), bit for bit.
  ASSERT_EQ(expected.Bounds.size(), proj.Gaussians.size());
  const auto bits = [](double x)
  {
    std::uint64_t u;
    std::memcpy(&u, &x, sizeof(u));
    return u;
  };
  for (std::size_t i = 0; i < proj.Gaussians.size(); ++i)
  {
    const auto& g = proj.Gaussians[i];
    raster::detail::SpanBounds want;
    if (g.IsVisible() && g.Opacity >= raster::MinAlpha<T>())
    {
      const double level = std::log(raster::MinAlpha<double>() / static_cast<double>(g.Opacity));
      want = raster::detail::MakeSpanBounds<T>(
        g.U, g.V, g.ConicA, g.ConicB, g.ConicC, std::min(0.0, level));
    }
    // The kept record gives back the whole span with the kernel's mean.
    const raster::detail::SpanBounds got =
      expected.Bounds[i].Expand(expected.Kernels[i].U, expected.Kernels[i].V);
    ASSERT_EQ(want.Bounded, got.Bounded) << i;
    ASSERT_EQ(want.RowMin, got.RowMin) << i;
    ASSERT_EQ(want.RowMax, got.RowMax) << i;
    for (const auto field : { &raster::detail::SpanBounds::U,
           &raster::detail::SpanBounds::V,
           &raster::detail::SpanBounds::A,
           &raster::detail::SpanBounds::B,
           &raster::detail::SpanBounds::Det,
           &raster::detail::SpanBounds::InvA,
           &raster::detail::SpanBounds::BOverA,
           &raster::detail::SpanBounds::NegTwoL })
    {
      ASSERT_EQ(bits(want.*field), bits(got.*field)) << i;
    }
  }
  for (int isa = 0; isa <= 3; ++isa)
  {
    for (int threads : { 1, 2, 3 })
    {
      s.KernelIsa = isa;
      s.Threads = threads;
      RasterImage<T> img;
      CompositeTiles(proj, bins, s, img, nullptr, nullptr, &kept, false);
      EXPECT_TRUE(img.Depth.empty());
      const auto bytes = [](const std::vector<T>& v) { return v.size() * sizeof(T); };
      ASSERT_EQ(img.Color.size(), ref.Color.size());
      EXPECT_EQ(0, std::memcmp(ref.Color.data(), img.Color.data(), bytes(ref.Color)))
        << "isa " << isa << " threads " << threads;
      EXPECT_EQ(0, std::memcmp(ref.Alpha.data(), img.Alpha.data(), bytes(ref.Alpha)));
      EXPECT_EQ(0,
        std::memcmp(ref.Transmittance.data(), img.Transmittance.data(), bytes(ref.Transmittance)));
      EXPECT_EQ(ref.Contributors, img.Contributors);
      ASSERT_EQ(kept.Kernels.size(), expected.Kernels.size());
      ASSERT_EQ(kept.Bounds.size(), expected.Bounds.size());
      EXPECT_EQ(0,
        std::memcmp(kept.Kernels.data(),
          expected.Kernels.data(),
          kept.Kernels.size() * sizeof(kept.Kernels[0])));
      for (std::size_t i = 0; i < kept.Bounds.size(); ++i)
      {
        const auto& a = kept.Bounds[i];
        const auto& b = expected.Bounds[i];
        ASSERT_EQ(a.NegTwoL, b.NegTwoL) << i;
        ASSERT_EQ(a.RowMin, b.RowMin) << i;
        ASSERT_EQ(a.RowMax, b.RowMax) << i;
        ASSERT_EQ(a.Det, b.Det) << i;
      }
    }
  }
  RasterImage<T> img;
  RasterWorkCounts work;
  EXPECT_THROW(
    CompositeTiles(
      proj, bins, s, img, nullptr, &work, static_cast<CompositeData<T>*>(nullptr), false),
    std::invalid_argument);
}
} // namespace

TEST(Rasterizer, DepthOffAndKeptDataBitIdentical)
{
  auto cloud = RandomScene(3000, 3, 21u, 1.0f, 10.0f, -5.0f, 0.0f);
  for (std::size_t i = 0; i < cloud.Count; i += 7)
  {
    cloud.OpacityLogits[i] = 9.0f; // opaque: the transmittance stop is reached
  }
  for (std::size_t i = 3; i < cloud.Count; i += 11)
  {
    cloud.OpacityLogits[i] = -7.0f; // o < 1/255: never blended, no span
  }
  const Camera cam = LookAt(150, 100, 90, 90, { 0, 0, -0.5 }, { 0, 0, 5 });
  CompositeData<float> keptFloat;
  CompositeData<double> keptDouble;
  ExpectDepthOffAndKeptDataMatch<float>(cloud, cam, keptFloat);
  ExpectDepthOffAndKeptDataMatch<double>(cloud, cam, keptDouble);
  // The kept buffers reused for another view that culls other Gaussians (none stale).
  const Camera cam2 = LookAt(61, 47, 40, 40, { 1.5, 0, -0.5 }, { 0, 0, 5 });
  ExpectDepthOffAndKeptDataMatch<float>(cloud, cam2, keptFloat);
}

//------------------------------------------------------------------------------
TEST(Rasterizer, AttributionReproducesPixels)
{
  const auto cloud = RandomScene(2500, 2, 9u);
  const Camera cam = LookAt(64, 48, 40, 40, { 0, 0, 0 }, { 0, 0, 5 });
  RasterSettings s;
  s.Background = { 0.5, 0.4, 0.3 };
  const auto proj = ProjectGaussians<float>(cloud, cam, s);
  const auto bins = BinGaussians(proj);
  RasterImage<float> img;
  GaussianWeightStats weights;
  CompositeTiles(proj, bins, s, img, &weights);
  std::vector<std::array<int, 2>> pixels;
  for (int y = 0; y < cam.Height; ++y)
  {
    for (int x = 0; x < cam.Width; ++x)
    {
      pixels.push_back({ x, y });
    }
  }
  pixels.push_back({ -1, 3 });
  pixels.push_back({ 64, 0 });
  const auto att = AttributePixels(proj, bins, s, pixels);
  ASSERT_EQ(att.size(), pixels.size());
  std::vector<double> maxW(cloud.Count, 0), sumW(cloud.Count, 0);
  std::vector<std::uint32_t> cnt(cloud.Count, 0);
  for (std::size_t q = 0; q + 2 < att.size(); ++q)
  {
    const auto& pa = att[q];
    const std::size_t i = Pix(img, pa.X, pa.Y);
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_EQ(pa.Color[c], static_cast<double>(img.Color[3 * i + c])); // same bits
    }
    EXPECT_EQ(pa.Contributors, img.Contributors[i]);
    EXPECT_EQ(pa.FinalTransmittance, static_cast<double>(img.Transmittance[i]));
    double wsum = 0;
    for (std::size_t k = 0; k < pa.Contributions.size(); ++k)
    {
      const auto& c = pa.Contributions[k];
      if (k > 0)
      {
        EXPECT_GE(pa.Contributions[k - 1].Weight, c.Weight);
      }
      EXPECT_NEAR(c.Weight, c.Alpha * c.Transmittance, 1e-7);
      wsum += c.Weight;
      maxW[c.Gaussian] = std::max(maxW[c.Gaussian], c.Weight);
      sumW[c.Gaussian] += c.Weight;
      ++cnt[c.Gaussian];
    }
    // sum of weights = 1 - T (accumulated alpha)
    EXPECT_NEAR(wsum, 1.0 - pa.FinalTransmittance, 1e-5);
  }
  EXPECT_TRUE(att[att.size() - 1].Contributions.empty());
  EXPECT_EQ(att[att.size() - 2].FinalTransmittance, 1.0);
  for (std::size_t g = 0; g < cloud.Count; ++g)
  {
    EXPECT_FLOAT_EQ(weights.MaxWeight[g], static_cast<float>(maxW[g]));
    EXPECT_NEAR(weights.WeightSum[g], sumW[g], 1e-9);
    EXPECT_EQ(weights.BlendedPixels[g], cnt[g]);
  }
  // Aggregation over a pixel set.
  const std::vector<PixelAttribution> some(att.begin(), att.begin() + 100);
  const auto ranked = RankContributors(some);
  double total = 0, expectedTotal = 0;
  for (std::size_t k = 0; k < ranked.size(); ++k)
  {
    total += ranked[k].WeightSum;
    if (k > 0)
    {
      EXPECT_GE(ranked[k - 1].WeightSum, ranked[k].WeightSum);
    }
  }
  for (const auto& pa : some)
  {
    expectedTotal += 1.0 - pa.FinalTransmittance;
  }
  EXPECT_NEAR(total, expectedTotal, 1e-4);
}

//------------------------------------------------------------------------------
TEST(Rasterizer, ShDegreeAndBackgroundSettings)
{
  const auto cloud = RandomScene(500, 3, 2u);
  const Camera cam = LookAt(40, 30, 25, 25, { 0, 0, 0 }, { 0, 0, 5 });
  RasterSettings s;
  ProjectionCounts counts;
  const auto full = Rasterize<double>(cloud, cam, s, &counts);
  EXPECT_EQ(counts.Visible + counts.OffScreen + counts.NearPlane, cloud.Count);
  s.ShDegree = 3;
  EXPECT_EQ(Rasterize<double>(cloud, cam, s).Color, full.Color);
  s.ShDegree = 7; // clamped to the cloud's 3
  EXPECT_EQ(Rasterize<double>(cloud, cam, s).Color, full.Color);
  s.ShDegree = 0;
  const auto dc = Rasterize<double>(cloud, cam, s);
  EXPECT_GT(MaxAbsDiff(dc.Color, full.Color), 1e-3);
  // Degree-0 rendering of the degree-3 cloud = rendering of its DC-only copy.
  GaussianCloud dcCloud = cloud;
  dcCloud.ShDegree = 0;
  dcCloud.SH.resize(3 * cloud.Count);
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    std::copy_n(&cloud.SH[48 * i], 3, &dcCloud.SH[3 * i]);
  }
  s.ShDegree = -1;
  EXPECT_EQ(Rasterize<double>(dcCloud, cam, s).Color, dc.Color);
  // Background adds exactly T * bg.
  s.Background = { 1, 0.5, 0.25 };
  const auto bg = Rasterize<double>(cloud, cam, s);
  for (std::size_t i = 0; i < bg.Transmittance.size(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(
        bg.Color[3 * i + c], full.Color[3 * i + c] + bg.Transmittance[i] * s.Background[c], 1e-15);
    }
  }
}

//------------------------------------------------------------------------------
TEST(Rasterizer, BadInputThrows)
{
  const auto cloud = RandomScene(10, 0, 1u);
  Camera cam = AxisCamera(0, 10, 10, 10);
  EXPECT_THROW(Rasterize<float>(cloud, cam), std::invalid_argument);
  cam = AxisCamera(10, 10, -1, 10);
  EXPECT_THROW(Rasterize<float>(cloud, cam), std::invalid_argument);
  cam = AxisCamera(10, 10, 10, 10);
  cam.WorldToCamera[3] = std::nan("");
  EXPECT_THROW(Rasterize<float>(cloud, cam), std::invalid_argument);
  GaussianCloud bad = cloud;
  bad.SH.pop_back();
  EXPECT_THROW(Rasterize<float>(bad, AxisCamera(10, 10, 10, 10)), std::invalid_argument);
  bad = cloud;
  bad.Rotations.resize(4);
  EXPECT_THROW(Rasterize<float>(bad, AxisCamera(10, 10, 10, 10)), std::invalid_argument);
  // Without colours, SH may be absent (footprint-only use).
  bad = cloud;
  bad.SH.clear();
  RasterSettings s;
  s.ComputeColors = false;
  EXPECT_NO_THROW(ProjectGaussians<float>(bad, AxisCamera(10, 10, 10, 10), s));
}

//------------------------------------------------------------------------------
// Issue 15: a degree-3 colour computed by hand for one direction. The camera is the identity
// at the origin and the Gaussian sits at (1, 1.5, 3), so the direction from the camera centre
// is d = (2, 3, 6)/7 exactly (|(2, 3, 6)| = 7). With x = 2/7, y = 3/7, z = 6/7 the basis of
// reference §2.4 is, with the reference's literal constants:
//   Y0 = C0, Y1 = -C1 3/7, Y2 = C1 6/7, Y3 = -C1 2/7,
//   Y4 = C2[0] 6/49 (xy), Y5 = C2[1] 18/49 (yz), Y6 = C2[2] 59/49 (2z^2 - x^2 - y^2),
//   Y7 = C2[3] 12/49 (xz), Y8 = C2[4] (-5/49) (x^2 - y^2),
//   Y9 = C3[0] 9/343, Y10 = C3[1] 36/343, Y11 = C3[2] 393/343, Y12 = C3[3] 198/343,
//   Y13 = C3[4] 262/343, Y14 = C3[5] (-30/343), Y15 = C3[6] (-46/343).
// Red has every coefficient 1 (colour 0.5 + sum Y_k = 0.224044861698247), green has
// (-1)^k (k+1)/16 (2.011981865757068), blue only a DC of -3, so 0.5 - 3 C0 < 0 is clamped
// to 0.
TEST(Rasterizer, ShDegree3ColourByHand)
{
  GaussianCloud cloud;
  cloud.Resize(1, 3);
  SetGaussian(cloud, 0, { 1.0f, 1.5f, 3.0f }, { -3, -3, -3 }, { 1, 0, 0, 0 }, 2.0f, { 0, 0, 0 });
  for (int k = 0; k < 16; ++k)
  {
    cloud.SH[3 * k + 0] = 1.0f;
    cloud.SH[3 * k + 1] = static_cast<float>((k % 2 ? -1.0 : 1.0) * (k + 1) / 16.0);
    cloud.SH[3 * k + 2] = k == 0 ? -3.0f : 0.0f;
  }
  const double c0 = 0.28209479177387814, c1 = 0.4886025119029199;
  const double c2[5] = { 1.0925484305920792,
    -1.0925484305920792,
    0.31539156525252005,
    -1.0925484305920792,
    0.5462742152960396 };
  const double c3[7] = { -0.5900435899266435,
    2.890611442640554,
    -0.4570457994644658,
    0.3731763325901154,
    -0.4570457994644658,
    1.445305721320277,
    -0.5900435899266435 };
  const double y[16] = { c0,
    -c1 * 3 / 7,
    c1 * 6 / 7,
    -c1 * 2 / 7,
    c2[0] * 6 / 49,
    c2[1] * 18 / 49,
    c2[2] * 59 / 49,
    c2[3] * 12 / 49,
    c2[4] * -5 / 49,
    c3[0] * 9 / 343,
    c3[1] * 36 / 343,
    c3[2] * 393 / 343,
    c3[3] * 198 / 343,
    c3[4] * 262 / 343,
    c3[5] * -30 / 343,
    c3[6] * -46 / 343 };
  double red = 0.5, green = 0.5;
  for (int k = 0; k < 16; ++k)
  {
    red += y[k];
    green += y[k] * cloud.SH[3 * k + 1];
  }
  EXPECT_NEAR(red, 0.224044861698247, 1e-14);
  EXPECT_NEAR(green, 2.011981865757068, 1e-14);
  const Camera cam = AxisCamera(200, 160, 100, 100);
  const auto pd = ProjectGaussians<double>(cloud, cam);
  const auto pf = ProjectGaussians<float>(cloud, cam);
  ASSERT_TRUE(pd.Gaussians[0].IsVisible());
  ASSERT_TRUE(pf.Gaussians[0].IsVisible());
  // Double: the direction (1, 1.5, 3)/3.5 carries a few ulps; float: ~1e-7 relative.
  EXPECT_NEAR(pd.Gaussians[0].Color[0], red, 1e-14);
  EXPECT_NEAR(pd.Gaussians[0].Color[1], green, 1e-14);
  EXPECT_EQ(pd.Gaussians[0].Color[2], 0.0);
  EXPECT_NEAR(pf.Gaussians[0].Color[0], red, 2e-6);
  EXPECT_NEAR(pf.Gaussians[0].Color[1], green, 2e-6);
  EXPECT_EQ(pf.Gaussians[0].Color[2], 0.0f);
  // Degree 2 drops exactly the seven degree-3 terms.
  RasterSettings s2;
  s2.ShDegree = 2;
  double red2 = 0.5;
  for (int k = 0; k < 9; ++k)
  {
    red2 += y[k];
  }
  EXPECT_NEAR(ProjectGaussians<double>(cloud, cam, s2).Gaussians[0].Color[0], red2, 1e-14);
}

// SPDX-License-Identifier: BSD-3-Clause
// MultiViewRenderer: one prepared cloud rendered into many views must give, view by view, the
// same bits as ProjectGaussians<float> + BinGaussians + CompositeTiles (images, alpha, depth,
// transmittance, n_contrib, status counts) and as ComputeFootprints (counts and map sums), on
// every instruction set and thread count, for random, stiff and real scenes.
#include "RasterTestUtils.h"

#include "Footprint.h"
#include "GaussianIO.h"
#include "GaussianMath.h"
#include "MultiViewRenderer.h"
#include "RasterCompare.h"
#include "Rasterizer.h"
#include "Vis4GSTestData.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <random>

using namespace vis4gs;
using namespace vis4gs::rastertest;

namespace
{

// Stiff members: NaN/Inf parameters, behind the camera, near plane, needles, disks, huge,
// tiny, opacity logits of +-1000 and near 1/255, zero quaternions, far off-screen.
GaussianCloud StiffScene(int degree)
{
  GaussianCloud cloud = RandomScene(4000, degree, 41u, 0.5f, 12.0f, -7.0f, 0.5f);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (std::size_t i = 0; i < cloud.Count; i += 7)
  {
    cloud.LogScales[3 * i + (i % 3)] = -18.0f;
    if (i % 2)
    {
      cloud.LogScales[3 * i + ((i + 1) % 3)] = -18.0f;
    }
  }
  for (std::size_t i = 3; i < cloud.Count; i += 97)
  {
    cloud.LogScales[3 * i] = cloud.LogScales[3 * i + 1] = cloud.LogScales[3 * i + 2] = 3.0f;
  }
  for (std::size_t i = 5; i < cloud.Count; i += 53)
  {
    cloud.OpacityLogits[i] = -5.54f;
  }
  cloud.Positions[3 * 10 + 0] = nan;
  cloud.LogScales[3 * 11 + 1] = inf;
  cloud.Rotations[4 * 12 + 2] = nan;
  cloud.OpacityLogits[13] = -inf;
  cloud.SH[3 * cloud.ShCoefficientCount() * 14 + 1] = nan;
  cloud.Positions[3 * 15 + 2] = -3.0f; // behind
  cloud.Positions[3 * 16 + 2] = 0.2f;  // on the near plane
  cloud.Positions[3 * 17 + 0] = 1e30f; // far off-screen
  cloud.OpacityLogits[18] = 1000.0f;
  cloud.OpacityLogits[19] = -1000.0f;
  for (int k = 0; k < 4; ++k)
  {
    cloud.Rotations[4 * 20 + k] = 0.0f;
  }
  cloud.LogScales[3 * 21] = cloud.LogScales[3 * 21 + 1] = cloud.LogScales[3 * 21 + 2] = 40.0f;
  cloud.LogScales[3 * 22] = cloud.LogScales[3 * 22 + 1] = cloud.LogScales[3 * 22 + 2] = -40.0f;
  return cloud;
}

// One view through both paths: images and footprints bit-identical.
void CheckView(MultiViewRenderer& mv,
  const GaussianCloud& cloud,
  const Camera& cam,
  const RasterSettings& rs,
  bool footprints)
{
  const ViewProjection<float> proj = ProjectGaussians<float>(cloud, cam, rs);
  const TileBins bins = BinGaussians(proj, rs.Threads);
  RasterImage<float> ref;
  CompositeTiles(proj, bins, rs, ref);
  RasterImage<float> img;
  mv.Render(cam, img);
  ASSERT_TRUE(SameCounts(mv.Counts(), proj.Counts));
  ASSERT_EQ(mv.SortedIds().size(), proj.Counts.Visible);
  EXPECT_EQ(img.Width, ref.Width);
  EXPECT_EQ(img.Height, ref.Height);
  EXPECT_TRUE(SameBits(img.Color, ref.Color));
  EXPECT_TRUE(SameBits(img.Alpha, ref.Alpha));
  EXPECT_TRUE(SameBits(img.Transmittance, ref.Transmittance));
  EXPECT_TRUE(SameBits(img.Depth, ref.Depth));
  EXPECT_TRUE(SameBits(img.Contributors, ref.Contributors));
  if (!footprints)
  {
    return;
  }
  const std::vector<float> map = OddMap(cam.Width, cam.Height, 11u + cam.Width);
  for (auto mode : { FootprintMode::Rasterizer, FootprintMode::Ellipse3Sigma })
  {
    for (auto acc : { FootprintAccumulation::Double, FootprintAccumulation::Float })
    {
      for (int isa : { 0, 1, 2 })
      {
        FootprintOptions fo;
        fo.Mode = mode;
        fo.Accumulation = acc;
        fo.KernelIsa = isa;
        fo.Threads = rs.Threads;
        const FootprintStats a = ComputeFootprints(proj, fo, map.data());
        FootprintStats b;
        mv.Footprints(fo, map.data(), b);
        ASSERT_EQ(a.PixelCount, b.PixelCount) << int(mode) << " " << isa;
        EXPECT_TRUE(SameBits(a.MapSum, b.MapSum)) << int(mode) << " " << isa;
        EXPECT_EQ(a.TotalPixels, b.TotalPixels);
        EXPECT_EQ(a.EvaluatedPixels, b.EvaluatedPixels);
      }
    }
  }
  FootprintOptions brute;
  brute.BruteForce = true;
  const FootprintStats a = ComputeFootprints(proj, brute, nullptr);
  FootprintStats b;
  mv.Footprints(brute, nullptr, b);
  EXPECT_EQ(a.PixelCount, b.PixelCount);
  EXPECT_TRUE(b.MapSum.empty());
}

std::vector<Camera> Views(int w, int h)
{
  std::vector<Camera> cams;
  cams.push_back(LookAt(w, h, 0.56 * w, 0.56 * w, { 0.2, -0.1, -0.3 }, { 0, 0, 5 }));
  cams.push_back(LookAt(w, h, 0.9 * w, 0.7 * w, { 3.0, 1.0, 1.0 }, { 0, 0, 6 }));
  cams.push_back(LookAt(w, h, 0.5 * w, 0.5 * w, { 0.0, 0.0, 14.0 }, { 0, 0, 5 }));
  cams.push_back(AxisCamera(w, h, 0.6 * w, 0.6 * w));
  return cams;
}

} // namespace

TEST(MultiViewRenderer, BitIdenticalToRasterizerOnRandomScenes)
{
  for (int degree : { 0, 3 })
  {
    const GaussianCloud cloud = RandomScene(3000, degree, 17u + degree, 1.0f, 10.0f);
    for (int isa : { 0, 1, 2, 3 })
    {
      for (int threads : { 1, 3 })
      {
        RasterSettings rs;
        rs.KernelIsa = isa;
        rs.Threads = threads;
        rs.Background = { 0.1, 0.5, 0.9 };
        MultiViewRenderer mv(cloud, rs);
        for (int scale : { 1, 4 })
        {
          for (const Camera& cam : Views(160 / scale, 120 / scale))
          {
            SCOPED_TRACE(::testing::Message() << "degree " << degree << " isa " << isa
                                              << " threads " << threads << " scale " << scale);
            CheckView(mv, cloud, cam, rs, isa == 0 && threads == 3);
          }
        }
      }
    }
  }
}

TEST(MultiViewRenderer, BitIdenticalOnStiffScene)
{
  for (int degree : { 0, 2 })
  {
    const GaussianCloud cloud = StiffScene(degree);
    for (int isa : { 1, 2, 3 })
    {
      RasterSettings rs;
      rs.KernelIsa = isa;
      rs.Threads = 2;
      rs.ScaleModifier = isa == 2 ? 1.7 : 1.0;
      rs.ShDegree = degree == 2 ? 1 : -1;
      MultiViewRenderer mv(cloud, rs);
      for (const Camera& cam : Views(96, 64))
      {
        SCOPED_TRACE(::testing::Message() << "degree " << degree << " isa " << isa);
        CheckView(mv, cloud, cam, rs, isa == 3);
      }
      EXPECT_GT(mv.Counts().InvalidParameters, 0u);
    }
  }
  // Without colours (footprint-only use).
  const GaussianCloud cloud = StiffScene(1);
  RasterSettings rs;
  rs.ComputeColors = false;
  MultiViewRenderer mv(cloud, rs);
  for (const Camera& cam : Views(80, 60))
  {
    CheckView(mv, cloud, cam, rs, true);
  }
}

TEST(MultiViewRenderer, BitIdenticalOnRealScene)
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
  RasterSettings rs;
  rs.Threads = 2;
  MultiViewRenderer mv(cloud, rs);
  for (int w : { 320, 80 })
  {
    const int h = w * 3 / 4;
    for (double a : { 0.0, 2.0 })
    {
      const Camera cam = LookAt(w,
        h,
        0.8 * w,
        0.8 * w,
        { c[0] + 4.0 * std::sin(a), c[1], c[2] - 4.0 * std::cos(a) },
        { c[0], c[1], c[2] });
      CheckView(mv, cloud, cam, rs, true);
    }
  }
}

// ProjectGaussians<float> runs the 16-lane projection (ProjectionLanes.inc) by default; the
// scalar per-Gaussian code (KernelIsa = -1) is the reference: every field of every Gaussian
// (also of culled ones, whose fields the scalar code fills up to its cull) must be
// bit-identical, on every instruction set and thread count, with and without colours.

TEST(MultiViewRenderer, ProjectGaussiansLanesEqualScalarEveryField)
{
  std::size_t statuses[6] = { 0, 0, 0, 0, 0, 0 };
  for (int degree : { 0, 3 })
  {
    GaussianCloud cloud = StiffScene(degree);
    cloud.Positions[3 * 30 + 0] = 1e19f; // NonFinite covariance (t_x^2 overflows)
    cloud.Positions[3 * 30 + 2] = 1.0f;
    for (std::size_t i = 100; i < 400; i += 3)
    {
      // Huge needles: the 2D covariance is rank one to float precision and det = ac - b^2
      // cancels to exactly 0 for some of them (Degenerate).
      cloud.LogScales[3 * i] = 9.0f + 0.01f * static_cast<float>(i % 7);
      cloud.LogScales[3 * i + 1] = cloud.LogScales[3 * i + 2] = -18.0f;
    }
    for (bool colors : { true, false })
    {
      RasterSettings rs;
      rs.ComputeColors = colors;
      rs.Threads = 1;
      rs.KernelIsa = -1;
      for (const Camera& cam : Views(97, 61))
      {
        const auto ref = ProjectGaussians<float>(cloud, cam, rs);
        for (const auto& g : ref.Gaussians)
        {
          ++statuses[static_cast<int>(g.Status)];
        }
        for (int isa : { 0, 1, 2, 3 })
        {
          for (int threads : { 1, 3 })
          {
            SCOPED_TRACE(::testing::Message() << "degree " << degree << " colors " << colors
                                              << " isa " << isa << " threads " << threads);
            RasterSettings ls = rs;
            ls.KernelIsa = isa;
            ls.Threads = threads;
            ExpectSameProjection(ref, ProjectGaussians<float>(cloud, cam, ls));
          }
        }
      }
    }
  }
  for (int k = 0; k < 6; ++k)
  {
    EXPECT_GT(statuses[k], 0u) << "status " << k << " not exercised";
  }
  // Partial last block and tiny clouds.
  for (std::size_t n : { 1, 15, 17 })
  {
    const GaussianCloud cloud = RandomScene(n, 1, 5u, 1.0f, 10.0f);
    RasterSettings rs;
    rs.KernelIsa = -1;
    const Camera cam = Views(64, 48)[0];
    const auto ref = ProjectGaussians<float>(cloud, cam, rs);
    rs.KernelIsa = 0;
    ExpectSameProjection(ref, ProjectGaussians<float>(cloud, cam, rs));
  }
}

TEST(MultiViewRenderer, ErrorsLikeTheRasterizer)
{
  GaussianCloud bad = RandomScene(10, 0, 1u);
  bad.Rotations.pop_back();
  EXPECT_THROW(MultiViewRenderer(bad, RasterSettings{}), std::invalid_argument);
  const GaussianCloud cloud = RandomScene(10, 0, 1u);
  MultiViewRenderer mv(cloud);
  FootprintStats st;
  EXPECT_THROW(mv.Footprints(FootprintOptions{}, nullptr, st), std::logic_error);
  Camera cam = AxisCamera(0, 10, 10, 10);
  RasterImage<float> img;
  EXPECT_THROW(mv.Render(cam, img), std::invalid_argument);
  // Tile rectangles are kept in 16 bits: a grid of 65535 tiles is the widest, one more is
  // refused with the camera's name.
  EXPECT_NO_THROW(mv.Project(AxisCamera(65535 * 16, 10, 1000, 1000)));
  Camera wide = AxisCamera(65535 * 16 + 1, 10, 1000, 1000);
  wide.Name = "widest";
  try
  {
    mv.Project(wide);
    ADD_FAILURE() << "a grid of 65536 tiles was projected";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("'widest'"), std::string::npos) << e.what();
  }
  // An empty cloud renders the background.
  GaussianCloud empty;
  RasterSettings rs;
  rs.Background = { 0.25, 0.5, 0.75 };
  MultiViewRenderer mve(empty, rs);
  mve.Render(AxisCamera(20, 10, 10, 10), img);
  ASSERT_EQ(img.Color.size(), 600u);
  EXPECT_EQ(img.Color[0], 0.25f);
  EXPECT_EQ(img.Color[599], 0.75f);
}

// The per-Gaussian statistics of compositing (render cost), in input order equal to
// CompositeTiles()', and in sorted order (CompositeInSortedOrder, buffers reused from view to
// view) equal to those at each sorted position's Gaussian.
TEST(MultiViewRenderer, WeightStatisticsInInputAndSortedOrder)
{
  const GaussianCloud cloud = RandomScene(3000, 3, 29u, 1.0f, 10.0f);
  RasterSettings rs;
  rs.Threads = 3;
  MultiViewRenderer mv(cloud, rs);
  GaussianWeightStats sorted;
  sorted.CountEvaluations = true;
  for (const Camera& cam : Views(160, 120))
  {
    const ViewProjection<float> proj = ProjectGaussians<float>(cloud, cam, rs);
    const TileBins bins = BinGaussians(proj, rs.Threads);
    RasterImage<float> refImage;
    GaussianWeightStats ref;
    ref.CountEvaluations = true;
    CompositeTiles(proj, bins, rs, refImage, &ref);

    mv.Project(cam);
    RasterImage<float> image;
    GaussianWeightStats inputOrder;
    inputOrder.CountEvaluations = true;
    mv.Composite(image, &inputOrder);
    EXPECT_TRUE(SameBits(image.Color, refImage.Color));
    EXPECT_TRUE(SameBits(inputOrder.WeightSum, ref.WeightSum));
    EXPECT_TRUE(SameBits(inputOrder.MaxWeight, ref.MaxWeight));
    EXPECT_EQ(inputOrder.BlendedPixels, ref.BlendedPixels);
    EXPECT_EQ(inputOrder.Evaluations, ref.Evaluations);

    RasterImage<float> again;
    mv.CompositeInSortedOrder(again, sorted);
    EXPECT_TRUE(SameBits(again.Color, refImage.Color));
    const std::vector<std::uint32_t>& ids = mv.SortedIds();
    ASSERT_EQ(sorted.WeightSum.size(), ids.size());
    ASSERT_EQ(sorted.Evaluations.size(), ids.size());
    std::size_t drawn = 0;
    for (std::size_t s = 0; s < ids.size(); ++s)
    {
      const std::uint32_t g = ids[s];
      ASSERT_EQ(sorted.Evaluations[s], ref.Evaluations[g]) << s;
      ASSERT_EQ(sorted.WeightSum[s], ref.WeightSum[g]) << s;
      ASSERT_EQ(sorted.MaxWeight[s], ref.MaxWeight[g]) << s;
      ASSERT_EQ(sorted.BlendedPixels[s], ref.BlendedPixels[g]) << s;
      drawn += ref.Evaluations[g] > 0 ? 1 : 0;
    }
    EXPECT_GT(drawn, 100u); // the view draws something, so the comparison means something
  }
}

// One projection composited in several colourings (score overlays): SetColors on a renderer
// that computes no colours gives, bit for bit, the rasteriser's image of a copy of the cloud
// of SH degree 0 whose DC coefficients make those colours.
TEST(MultiViewRenderer, SetColorsEqualsRasterizerOfRecolouredCopy)
{
  const GaussianCloud cloud = RandomScene(3000, 3, 31u, 1.0f, 10.0f);
  RasterSettings noColors;
  noColors.ComputeColors = false;
  noColors.Threads = 3;
  MultiViewRenderer mv(cloud, noColors);
  GaussianCloud copy = cloud;
  copy.ShDegree = 0;
  copy.SH.assign(3 * cloud.Count, 0.0f);
  std::vector<float> rgb(3 * cloud.Count);
  std::mt19937 rng(5u);
  std::uniform_real_distribution<float> unit(-0.2f, 1.2f);
  for (const Camera& cam : Views(160, 120))
  {
    mv.Project(cam);
    for (int colouring = 0; colouring < 2; ++colouring)
    {
      for (std::size_t i = 0; i < cloud.Count; ++i)
      {
        for (int c = 0; c < 3; ++c)
        {
          copy.SH[3 * i + c] = unit(rng);
        }
        const float dir[3] = { 0, 0, 0 };
        float col[3];
        ShColor<float>(&copy.SH[3 * i], 0, dir, col);
        for (int c = 0; c < 3; ++c)
        {
          rgb[3 * i + c] = std::max(col[c], 0.0f); // below 0: the rasteriser's clamp
        }
      }
      mv.SetColors(rgb.data());
      RasterImage<float> image;
      mv.Composite(image);
      RasterSettings rs;
      rs.Threads = 3;
      const RasterImage<float> ref = Rasterize<float>(copy, cam, rs);
      EXPECT_TRUE(SameBits(image.Color, ref.Color)) << colouring;
      EXPECT_TRUE(SameBits(image.Alpha, ref.Alpha)) << colouring;
    }
  }
}

// The preparation made in parts by several renderers in one block of memory (as processes of
// one machine make it, PreparationShare) renders every view as the unshared renderer does, bit
// for bit; so does a Map that gives null (the fallback: each prepares alone). Colours of SH
// degree 0 are part of the shared block; of degree 3, evaluated per view.
TEST(MultiViewRenderer, SharedPreparationEqualsUnshared)
{
  for (int degree : { 0, 3 })
  {
    const GaussianCloud cloud = StiffScene(degree);
    for (int parts : { 2, 3 })
    {
      RasterSettings rs;
      rs.Threads = 1 + parts % 2;
      std::vector<unsigned char> memory;
      int maps = 0, waits = 0;
      std::vector<std::unique_ptr<MultiViewRenderer>> renderers;
      for (int part = 0; part < parts; ++part)
      {
        PreparationShare share;
        share.Part = part;
        share.Parts = parts;
        share.Map = [&](std::size_t bytes) -> void*
        {
          ++maps;
          // One block for all: the first renderer's call sizes it; later ones must ask the same.
          if (memory.empty())
          {
            // Garbage, not zeros: every element must be written by one of the parts.
            memory.assign(bytes + 64, 0xA5);
          }
          EXPECT_EQ(memory.size(), bytes + 64);
          const std::uintptr_t at = reinterpret_cast<std::uintptr_t>(memory.data());
          return memory.data() + (64 - at % 64) % 64;
        };
        share.Wait = [&]() { ++waits; };
        renderers.emplace_back(new MultiViewRenderer(cloud, rs, share));
      }
      EXPECT_EQ(parts, maps);
      EXPECT_EQ(parts, waits);
      PreparationShare refused;
      refused.Parts = 2;
      refused.Part = 1;
      refused.Map = [](std::size_t) -> void* { return nullptr; };
      refused.Wait = [&]() { ADD_FAILURE() << "Wait() after a refused Map()"; };
      MultiViewRenderer alone(cloud, rs, refused);
      MultiViewRenderer unshared(cloud, rs);
      for (const Camera& cam : Views(160, 120))
      {
        RasterImage<float> expected, image;
        unshared.Render(cam, expected);
        for (MultiViewRenderer* mv : { renderers.front().get(), renderers.back().get(), &alone })
        {
          mv->Render(cam, image);
          EXPECT_TRUE(SameBits(image.Color, expected.Color)) << degree << " " << parts;
          EXPECT_TRUE(SameBits(image.Depth, expected.Depth));
          EXPECT_TRUE(SameCounts(mv->Counts(), unshared.Counts()));
          const std::vector<float> map = OddMap(cam.Width, cam.Height, 5u);
          FootprintOptions fo;
          FootprintStats a, b;
          unshared.Footprints(fo, map.data(), a);
          mv->Footprints(fo, map.data(), b);
          EXPECT_EQ(a.PixelCount, b.PixelCount);
          EXPECT_TRUE(SameBits(a.MapSum, b.MapSum));
        }
      }
    }
  }
}

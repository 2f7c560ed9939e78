// SPDX-License-Identifier: BSD-3-Clause
// RasterWorkspace and the buffer-reusing ProjectGaussians/BinGaussians overloads: a sequence of
// renders through one workspace (different clouds, Gaussian counts growing and shrinking,
// image sizes, views where Gaussians change status, float and double, the scalar and the
// 16-lane projection, 1 and 3 threads) must give, call by call, exactly what the allocating
// calls give: every field of every projected Gaussian, the tile lists, every image channel.
#include "RasterTestUtils.h"

#include "GaussianIO.h"
#include "RasterCompare.h"
#include "Rasterizer.h"
#include "Vis4GSTestData.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <string>

using namespace vis4gs;
using namespace vis4gs::rastertest;

namespace
{

template <typename T>
void ExpectSameImage(const RasterImage<T>& ref, const RasterImage<T>& got)
{
  EXPECT_EQ(ref.Width, got.Width);
  EXPECT_EQ(ref.Height, got.Height);
  EXPECT_TRUE(SameBits(ref.Color, got.Color));
  EXPECT_TRUE(SameBits(ref.Alpha, got.Alpha));
  EXPECT_TRUE(SameBits(ref.Transmittance, got.Transmittance));
  EXPECT_TRUE(SameBits(ref.Depth, got.Depth));
  EXPECT_TRUE(SameBits(ref.Contributors, got.Contributors));
}

// A random scene with stiff members: NaN/Inf parameters, behind the camera, needles, huge and
// tiny scales, opacities below 1/255, a zero quaternion.
GaussianCloud MixedScene(std::size_t n, int degree, unsigned seed)
{
  GaussianCloud cloud = RandomScene(n, degree, seed, 0.5f, 12.0f, -7.0f, 0.5f);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (std::size_t i = 0; i < cloud.Count; i += 11)
  {
    cloud.LogScales[3 * i + (i % 3)] = -16.0f; // needles and disks
  }
  for (std::size_t i = 5; i < cloud.Count; i += 41)
  {
    cloud.OpacityLogits[i] = -7.0f; // o < 1/255
  }
  cloud.Positions[3 * 3 + 1] = nan;
  cloud.LogScales[3 * 4] = std::numeric_limits<float>::infinity();
  cloud.Positions[3 * 6 + 2] = -2.0f;
  for (int k = 0; k < 4; ++k)
  {
    cloud.Rotations[4 * 7 + k] = 0.0f;
  }
  cloud.LogScales[3 * 8] = cloud.LogScales[3 * 8 + 1] = cloud.LogScales[3 * 8 + 2] = 4.0f;
  return cloud;
}

struct Step
{
  const GaussianCloud* Cloud;
  Camera Cam;
};

template <typename T>
void RunSequence(const std::vector<Step>& steps, int isa, int threads)
{
  RasterWorkspace<T> ws;
  RasterSettings rs;
  rs.KernelIsa = isa;
  rs.Threads = threads;
  rs.Background = { 0.25, 0.5, 1.0 };
  std::size_t changed = 0;
  std::vector<ProjectionStatus> previous;
  for (std::size_t s = 0; s < steps.size(); ++s)
  {
    SCOPED_TRACE(::testing::Message() << "step " << s << " isa " << isa << " threads " << threads
                                      << (sizeof(T) == 4 ? " float" : " double"));
    const GaussianCloud& cloud = *steps[s].Cloud;
    const Camera& cam = steps[s].Cam;
    const ViewProjection<T> proj = ProjectGaussians<T>(cloud, cam, rs);
    const TileBins bins = BinGaussians(proj, threads);
    RasterImage<T> ref;
    CompositeTiles(proj, bins, rs, ref);
    if (s % 2 == 0)
    {
      ProjectGaussians<T>(cloud, cam, rs, ws.Projection);
      BinGaussians(ws.Projection, threads, ws.Bins, ws.Scratch);
      CompositeTiles(ws.Projection, ws.Bins, rs, ws.Image, nullptr, nullptr, &ws.Composite);
    }
    else
    {
      Rasterize<T>(cloud, cam, rs, ws);
    }
    ExpectSameProjection(proj, ws.Projection);
    EXPECT_EQ(bins.TilesX, ws.Bins.TilesX);
    EXPECT_EQ(bins.TilesY, ws.Bins.TilesY);
    EXPECT_EQ(bins.Offsets, ws.Bins.Offsets);
    EXPECT_EQ(bins.Ids, ws.Bins.Ids);
    ExpectSameImage(ref, ws.Image);
    EXPECT_TRUE(ref.Alpha.size() > 0);
    // The per-Gaussian compositing data kept in the workspace is what a fresh call computes.
    CompositeData<T> fresh;
    PrepareCompositeData(proj, threads, fresh);
    ASSERT_EQ(fresh.Kernels.size(), ws.Composite.Kernels.size());
    EXPECT_EQ(0,
      std::memcmp(fresh.Kernels.data(),
        ws.Composite.Kernels.data(),
        fresh.Kernels.size() * sizeof(fresh.Kernels[0])));
    // Count the Gaussians whose status changed since the previous step of the same cloud
    // (stale fields of a reused buffer would show there).
    if (previous.size() == proj.Gaussians.size())
    {
      for (std::size_t i = 0; i < previous.size(); ++i)
      {
        changed += previous[i] != proj.Gaussians[i].Status ? 1 : 0;
      }
    }
    previous.clear();
    for (const auto& g : proj.Gaussians)
    {
      previous.push_back(g.Status);
    }
  }
  EXPECT_GT(changed, 100u) << "the sequence must move Gaussians between statuses";
}

std::vector<Step> Sequence(const GaussianCloud& big, const GaussianCloud& small)
{
  std::vector<Step> steps;
  steps.push_back({ &big, LookAt(96, 64, 54, 54, { 0.2, -0.1, -0.3 }, { 0, 0, 5 }) });
  steps.push_back({ &big, LookAt(160, 90, 140, 110, { 3.0, 1.0, 1.0 }, { 0, 0, 6 }) });
  steps.push_back({ &big, LookAt(70, 50, 35, 35, { 0.0, 0.0, 14.0 }, { 0, 0, 5 }) });
  steps.push_back({ &small, AxisCamera(96, 64, 58, 58) }); // fewer Gaussians: shrink
  steps.push_back({ &big, AxisCamera(33, 17, 20, 20) });   // more again, within capacity
  steps.push_back({ &big, LookAt(200, 120, 120, 120, { -2.0, 0.5, 0.0 }, { 0, 0, 6 }) });
  steps.push_back({ &big, LookAt(64, 64, 40, 40, { 0.0, 0.0, 9.0 }, { 0, 0, 3 }) });
  return steps;
}

} // namespace

TEST(RasterWorkspace, ReuseIsBitIdenticalOnMixedScenes)
{
  const GaussianCloud big = MixedScene(3000, 3, 17u);
  const GaussianCloud small = MixedScene(700, 1, 23u);
  const std::vector<Step> steps = Sequence(big, small);
  for (int isa : { 0, -1 })
  {
    for (int threads : { 1, 3 })
    {
      RunSequence<float>(steps, isa, threads);
    }
  }
  RunSequence<double>(steps, 0, 2);
}

TEST(RasterWorkspace, ReuseIsBitIdenticalOnRealScene)
{
  const GaussianCloud real = ReadGaussianPly(vis4gs::testing::SharedDataPath(
    "inria_ply_tiny_kacytran/point_cloud/iteration_7000/point_cloud.ply"));
  ASSERT_GT(real.Count, 1000u);
  std::array<double, 3> c{ 0, 0, 0 };
  for (std::size_t i = 0; i < real.Count; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      c[k] += real.Positions[3 * i + k] / static_cast<double>(real.Count);
    }
  }
  const GaussianCloud small = MixedScene(500, 3, 5u);
  std::vector<Step> steps;
  for (int w : { 160, 64, 200 })
  {
    for (double a : { 0.0, 2.5 })
    {
      const int h = w * 3 / 4;
      steps.push_back({ &real,
        LookAt(w,
          h,
          0.8 * w,
          0.8 * w,
          { c[0] + 4.0 * std::sin(a), c[1], c[2] - 4.0 * std::cos(a) },
          { c[0], c[1], c[2] }) });
    }
    steps.push_back({ &small, AxisCamera(w, w / 2, 0.6 * w, 0.6 * w) });
  }
  RunSequence<float>(steps, 0, 2);
}

TEST(RasterWorkspace, BinScratchIsMovable)
{
  const GaussianCloud cloud = MixedScene(400, 0, 9u);
  const Camera cam = AxisCamera(64, 48, 40, 40);
  const ViewProjection<float> proj = ProjectGaussians<float>(cloud, cam);
  BinScratch a;
  TileBins bins;
  BinGaussians(proj, 1, bins, a);
  BinScratch b = std::move(a);
  TileBins again;
  BinGaussians(proj, 1, again, b);
  BinGaussians(proj, 1, again, a); // a moved-from scratch is empty and usable
  EXPECT_EQ(bins.Ids, again.Ids);
  EXPECT_EQ(bins.Offsets, again.Offsets);
  EXPECT_EQ(bins.Ids, BinGaussians(proj, 1).Ids);
}

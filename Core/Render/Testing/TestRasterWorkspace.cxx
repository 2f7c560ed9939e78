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

#include <algorithm>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

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

// With @p keep, the float projections go through the workspace's kept preparation
// (PreparedCloudCache), one cloud version per cloud of the sequence.
template <typename T>
void RunSequence(const std::vector<Step>& steps, int isa, int threads, bool keep = false)
{
  RasterWorkspace<T> ws;
  std::vector<const GaussianCloud*> versions; // version = 1 + position here
  std::size_t switches = 0;
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
    std::uint64_t version = 0;
    if (keep)
    {
      auto it = std::find(versions.begin(), versions.end(), &cloud);
      if (it == versions.end())
      {
        versions.push_back(&cloud);
        it = versions.end() - 1;
      }
      version = static_cast<std::uint64_t>(it - versions.begin()) + 1;
      switches += s == 0 || steps[s - 1].Cloud != &cloud ? 1 : 0;
    }
    // Every third step the kernels are read from the projection in place (the scene view's
    // setting): same images, no kernel array kept, the same spans.
    ws.Composite.KeepKernels = s % 3 != 2;
    if (s % 2 == 0)
    {
      if constexpr (std::is_same<T, float>::value)
      {
        ProjectGaussians(cloud, cam, rs, ws.Projection, ws.Prepared, version);
      }
      else
      {
        ProjectGaussians<T>(cloud, cam, rs, ws.Projection);
      }
      BinGaussians(ws.Projection, threads, ws.Bins, ws.Scratch);
      CompositeTiles(ws.Projection, ws.Bins, rs, ws.Image, nullptr, nullptr, &ws.Composite);
    }
    else
    {
      ws.CloudVersion = version;
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
    if (ws.Composite.KeepKernels)
    {
      ASSERT_EQ(fresh.Kernels.size(), ws.Composite.Kernels.size());
      EXPECT_EQ(0,
        std::memcmp(fresh.Kernels.data(),
          ws.Composite.Kernels.data(),
          fresh.Kernels.size() * sizeof(fresh.Kernels[0])));
    }
    else
    {
      EXPECT_TRUE(ws.Composite.Kernels.empty());
    }
    ASSERT_EQ(fresh.Bounds.size(), ws.Composite.Bounds.size());
    static_assert(sizeof(raster::detail::SpanRecord) == 40, "no padding in the span records");
    EXPECT_EQ(0,
      std::memcmp(fresh.Bounds.data(),
        ws.Composite.Bounds.data(),
        fresh.Bounds.size() * sizeof(fresh.Bounds[0])));
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
  if (keep && std::is_same<T, float>::value && isa >= 0)
  {
    // Prepared once per switch of cloud, reused for every other frame.
    EXPECT_EQ(switches, ws.Prepared.Builds());
    EXPECT_EQ(steps.size() - switches, ws.Prepared.Reuses());
  }
  else
  {
    EXPECT_EQ(0u, ws.Prepared.Builds());
    EXPECT_EQ(0u, ws.Prepared.Reuses());
  }
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

TEST(RasterWorkspace, KeptPreparationIsBitIdenticalOnMixedScenes)
{
  const GaussianCloud big = MixedScene(3000, 3, 17u);
  const GaussianCloud small = MixedScene(700, 1, 23u);
  std::vector<Step> steps = Sequence(big, small);
  // Several frames of the same cloud in a row (the scene view's case) besides the switches.
  steps.insert(steps.begin() + 1, steps[0]);
  steps.push_back({ &big, LookAt(80, 60, 50, 50, { 1.0, 2.0, -1.0 }, { 0, 0, 5 }) });
  for (int isa : { 0, 1, 2, -1 })
  {
    for (int threads : { 1, 3 })
    {
      RunSequence<float>(steps, isa, threads, true);
    }
  }
  RunSequence<double>(steps, 0, 2, true); // double: never kept
}

// The kept preparation follows everything it was computed from; a changed cloud under an
// unchanged version throws instead of rendering stale data.
TEST(RasterWorkspace, KeptPreparationFollowsTheCloud)
{
  GaussianCloud cloud = MixedScene(2000, 2, 41u);
  const Camera cam = LookAt(120, 90, 90, 90, { 0.3, -0.2, -0.5 }, { 0, 0, 5 });
  RasterSettings rs;
  rs.Threads = 2;
  RasterWorkspace<float> ws;
  auto check = [&](const GaussianCloud& c, const RasterSettings& s, std::uint64_t version)
  {
    ws.CloudVersion = version;
    Rasterize<float>(c, cam, s, ws);
    ExpectSameProjection(ProjectGaussians<float>(c, cam, s), ws.Projection);
    const RasterImage<float> ref = Rasterize<float>(c, cam, s);
    ExpectSameImage(ref, ws.Image);
  };
  check(cloud, rs, 1);
  check(cloud, rs, 1);
  EXPECT_EQ(1u, ws.Prepared.Builds());
  EXPECT_EQ(1u, ws.Prepared.Reuses());

  // New parameters under a new version: prepared again.
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    cloud.LogScales[3 * i + 1] += 0.3f;
  }
  check(cloud, rs, 2);
  EXPECT_EQ(2u, ws.Prepared.Builds());

  // New parameters under the same version: the spot check throws, and nothing stale is kept.
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    cloud.OpacityLogits[i] = -cloud.OpacityLogits[i];
  }
  ws.CloudVersion = 2;
  EXPECT_THROW(Rasterize<float>(cloud, cam, rs, ws), std::logic_error);
  check(cloud, rs, 2); // the cache was dropped: prepared again, correct
  EXPECT_EQ(3u, ws.Prepared.Builds());
  // So is a change of 32 consecutive Gaussians (the 64 samples of 2000 are at most 32 apart).
  for (std::size_t i = 100; i < 132; ++i)
  {
    cloud.LogScales[3 * i] += 0.25f;
  }
  ws.CloudVersion = 2;
  EXPECT_THROW(Rasterize<float>(cloud, cam, rs, ws), std::logic_error);
  check(cloud, rs, 3);

  // Same version, but another cloud object, another size, other settings: prepared again.
  std::size_t builds = ws.Prepared.Builds();
  const GaussianCloud copy = cloud;
  check(copy, rs, 3);
  EXPECT_EQ(++builds, ws.Prepared.Builds());
  const GaussianCloud smaller = MixedScene(900, 2, 41u);
  check(smaller, rs, 3);
  EXPECT_EQ(++builds, ws.Prepared.Builds());
  RasterSettings scaled = rs;
  scaled.ScaleModifier = 0.7;
  check(smaller, scaled, 3);
  EXPECT_EQ(++builds, ws.Prepared.Builds());
  RasterSettings degree = scaled;
  degree.ShDegree = 0; // fewer SH coefficients checked for finiteness
  check(smaller, degree, 3);
  EXPECT_EQ(++builds, ws.Prepared.Builds());
  RasterSettings noColors = degree;
  noColors.ComputeColors = false;
  check(smaller, noColors, 3);
  EXPECT_EQ(++builds, ws.Prepared.Builds());
  check(smaller, noColors, 3);
  EXPECT_EQ(builds, ws.Prepared.Builds());

  // Version 0: never kept; Clear() forgets; copies start empty.
  const std::size_t reuses = ws.Prepared.Reuses();
  check(smaller, noColors, 0);
  EXPECT_EQ(builds, ws.Prepared.Builds());
  EXPECT_EQ(reuses, ws.Prepared.Reuses());
  ws.Prepared.Clear();
  check(smaller, noColors, 3);
  EXPECT_EQ(++builds, ws.Prepared.Builds());
  const PreparedCloudCache copied = ws.Prepared;
  EXPECT_EQ(0u, copied.Builds());
  RasterWorkspace<float> moved = std::move(ws);
  EXPECT_EQ(builds, moved.Prepared.Builds());
  moved.CloudVersion = 3;
  Rasterize<float>(smaller, cam, noColors, moved);
  EXPECT_EQ(builds, moved.Prepared.Builds()); // the moved cache is reused
}

TEST(RasterWorkspace, ReuseIsBitIdenticalOnRealScene)
{
  VIS4GS_REQUIRE_SHARED_DATA();
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

// RasterizeTiles(): the chosen tiles are the full render's, bit for bit, whichever tiles are
// chosen (none, one, scattered, all), on a scene with stiff members, float and double.
template <typename T>
void CheckChosenTiles(const GaussianCloud& cloud, const Camera& camera)
{
  const RasterImage<T> full = Rasterize<T>(cloud, camera);
  const int tx = (camera.Width + 15) / 16, ty = (camera.Height + 15) / 16;
  std::vector<std::vector<std::uint8_t>> masks(4, std::vector<std::uint8_t>(tx * ty, 0));
  masks[1][(ty / 2) * tx + tx / 2] = 1;
  for (int t = 0; t < tx * ty; t += 7)
  {
    masks[2][t] = 1;
  }
  std::fill(masks[3].begin(), masks[3].end(), 1);
  RasterWorkspace<T> workspace;
  for (const std::vector<std::uint8_t>& mask : masks)
  {
    RasterizeTiles(cloud, camera, RasterSettings{}, mask, workspace);
    const RasterImage<T>& got = workspace.Image;
    std::size_t compared = 0;
    for (int y = 0; y < camera.Height; ++y)
    {
      for (int x = 0; x < camera.Width; ++x)
      {
        if (!mask[(y / 16) * tx + x / 16])
        {
          continue;
        }
        const std::size_t p = static_cast<std::size_t>(y) * camera.Width + x;
        for (int c = 0; c < 3; ++c)
        {
          ASSERT_EQ(std::memcmp(&full.Color[3 * p + c], &got.Color[3 * p + c], sizeof(T)), 0)
            << "pixel " << x << "," << y;
        }
        ASSERT_EQ(std::memcmp(&full.Alpha[p], &got.Alpha[p], sizeof(T)), 0);
        ASSERT_EQ(std::memcmp(&full.Transmittance[p], &got.Transmittance[p], sizeof(T)), 0);
        ASSERT_EQ(full.Contributors[p], got.Contributors[p]);
        ++compared;
      }
    }
    const std::size_t chosen = static_cast<std::size_t>(std::count(mask.begin(), mask.end(), 1));
    EXPECT_GE(compared, chosen * 16 * 8); // tiles of the last row and column are clipped
    // Culled: the Gaussians that reach no chosen tile (all but none when every tile is chosen).
    const ProjectionCounts& counts = workspace.Projection.Counts;
    const ViewProjection<T> plain = ProjectGaussians<T>(cloud, camera);
    EXPECT_EQ(counts.Visible + counts.OffScreen, plain.Counts.Visible + plain.Counts.OffScreen);
    if (chosen == mask.size())
    {
      EXPECT_EQ(counts.Visible, plain.Counts.Visible);
    }
    else if (chosen <= 1)
    {
      EXPECT_LT(counts.Visible, plain.Counts.Visible / 2);
    }
  }
  EXPECT_THROW(
    KeepTiles(workspace.Projection, std::vector<std::uint8_t>(3, 1)), std::invalid_argument);
}

TEST(RasterWorkspace, ChosenTilesAreTheFullRenderBitForBit)
{
  const GaussianCloud cloud = MixedScene(3000, 3, 29u);
  const Camera camera = AxisCamera(150, 90, 120.0, 118.0);
  CheckChosenTiles<float>(cloud, camera);
  CheckChosenTiles<double>(cloud, camera);
}

// ProjectGaussianSubset (the scene view's moving frames): the projection of a subset equals
// the subset's entries of the whole cloud's projection, every field bit for bit, with the
// kept preparation (gathered from it), without it, on the scalar path, 1 and 3 threads.
TEST(RasterWorkspace, SubsetProjectionEqualsTheWholeProjectionsEntries)
{
  const GaussianCloud cloud = MixedScene(3001, 3, 21);
  const Camera cam = LookAt(96, 64, 80.0, 80.0, { 0.5, -0.3, -1.0 }, { 0.0, 0.0, 6.0 });
  std::vector<std::uint32_t> subset;
  for (std::uint32_t i = 0; i < cloud.Count; ++i)
  {
    if (i % 3 != 1 || i < 10) // every stiff member of MixedScene, then two thirds
    {
      subset.push_back(i);
    }
  }
  for (int isa : { 0, -1 })
  {
    for (int threads : { 1, 3 })
    {
      for (std::uint64_t version : { std::uint64_t(0), std::uint64_t(1) })
      {
        SCOPED_TRACE(::testing::Message()
          << "isa " << isa << " threads " << threads << " version " << version);
        RasterSettings rs;
        rs.KernelIsa = isa;
        rs.Threads = threads;
        ViewProjection<float> expected = ProjectGaussians<float>(cloud, cam, rs);
        std::vector<ProjectedGaussian<float>> kept;
        std::size_t counts[6] = { 0, 0, 0, 0, 0, 0 };
        for (std::uint32_t i : subset)
        {
          kept.push_back(expected.Gaussians[i]);
          ++counts[static_cast<int>(expected.Gaussians[i].Status)];
        }
        expected.Gaussians = kept;
        expected.Counts =
          ProjectionCounts{ counts[0], counts[1], counts[2], counts[3], counts[4], counts[5] };
        ASSERT_GT(counts[0], 100u);
        ASSERT_GT(counts[1] + counts[2], 0u);
        PreparedCloudCache cache;
        ViewProjection<float> got;
        // The whole cloud first (the cache is prepared), then the subset twice (reused).
        ProjectGaussians(cloud, cam, rs, got, cache, version);
        for (int round = 0; round < 2; ++round)
        {
          ProjectGaussianSubset(cloud, subset, cam, rs, got, cache, version);
          ExpectSameProjection(expected, got);
        }
      }
    }
  }
  ViewProjection<float> got;
  PreparedCloudCache cache;
  std::vector<std::uint32_t> bad{ 3, 2 };
  EXPECT_THROW(ProjectGaussianSubset(cloud, bad, cam, {}, got, cache, 1), std::invalid_argument);
  bad = { 0, static_cast<std::uint32_t>(cloud.Count) };
  EXPECT_THROW(ProjectGaussianSubset(cloud, bad, cam, {}, got, cache, 1), std::invalid_argument);
}

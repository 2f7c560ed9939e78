// SPDX-License-Identifier: BSD-3-Clause
#include "SplatMovingSet.h"

#include "GaussianCloud.h"
#include "Rasterizer.h"
#include "SplatLevelOfDetail.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <vector>

namespace vis4gs
{
namespace
{
// A camera at @p centre turned by @p yaw radians about the world's y axis from looking down +z
// (world-to-camera R = rotation by -yaw, t = -R centre), 160x120, 90 degrees wide.
Camera TurnedCamera(double yaw, const double centre[3])
{
  Camera c;
  c.Width = 160;
  c.Height = 120;
  c.Fx = 80;
  c.Fy = 80;
  c.Cx = 80;
  c.Cy = 60;
  const double co = std::cos(yaw), si = std::sin(yaw);
  const double r[3][3] = { { co, 0, -si }, { 0, 1, 0 }, { si, 0, co } };
  for (int i = 0; i < 3; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      c.WorldToCamera[4 * i + k] = r[i][k];
    }
    c.WorldToCamera[4 * i + 3] = -(r[i][0] * centre[0] + r[i][1] * centre[1] + r[i][2] * centre[2]);
  }
  return c;
}

// Random Gaussians of SH degree 3 in front of the origin, within z in [2, 10].
GaussianCloud RandomCloud(std::size_t n, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  GaussianCloud c;
  c.Resize(n, 3);
  for (std::size_t i = 0; i < n; ++i)
  {
    const float z = 6.0f + 4.0f * u(rng);
    c.Positions[3 * i] = 1.5f * z * u(rng);
    c.Positions[3 * i + 1] = 1.0f * z * u(rng);
    c.Positions[3 * i + 2] = z;
    for (int k = 0; k < 3; ++k)
    {
      c.LogScales[3 * i + k] = -3.0f + 1.5f * u(rng);
    }
    for (int k = 0; k < 4; ++k)
    {
      c.Rotations[4 * i + k] = u(rng) + (k == 0 ? 1.5f : 0.0f);
    }
    c.OpacityLogits[i] = 3.0f * u(rng);
    for (std::size_t k = 0; k < 48; ++k)
    {
      c.SH[48 * i + k] = 0.5f * u(rng);
    }
  }
  return c;
}

const double Origin[3] = { 0.0, 0.0, 0.0 };

SplatLevelOfDetail PreparedLod(const GaussianCloud& cloud)
{
  SplatLevelOfDetail lod;
  PrepareSplatLevelOfDetail(cloud, lod, 2);
  return lod;
}

RasterSettings TwoThreads()
{
  RasterSettings settings;
  settings.Threads = 2;
  return settings;
}

// The set's Gaussians in the cloud's order (a rebuild that keeps colours keeps slots instead).
std::vector<std::uint32_t> Ascending(const SplatMovingSet& set)
{
  std::vector<std::uint32_t> v = set.Subset;
  std::sort(v.begin(), v.end());
  return v;
}

// The slot of Gaussian @p index in @p set (its Subset's size when it is not there).
std::size_t SlotOf(const SplatMovingSet& set, std::uint32_t index)
{
  return static_cast<std::size_t>(
    std::find(set.Subset.begin(), set.Subset.end(), index) - set.Subset.begin());
}
}

TEST(SplatMovingSet, ViewChangeAngleOfATurnAndOfATravel)
{
  const Camera a = TurnedCamera(0.0, Origin);
  EXPECT_NEAR(SplatViewChangeAngle(a, a, 5.0), 0.0, 1e-7);
  EXPECT_NEAR(SplatViewChangeAngle(a, TurnedCamera(0.1, Origin), 5.0), 0.1, 1e-9);
  EXPECT_NEAR(SplatViewChangeAngle(a, TurnedCamera(-0.3, Origin), 5.0), 0.3, 1e-9);
  const double moved[3] = { 0.0, 0.2, 0.0 };
  EXPECT_NEAR(SplatViewChangeAngle(a, TurnedCamera(0.0, moved), 4.0), 0.05, 1e-12);
  EXPECT_NEAR(SplatViewChangeAngle(a, TurnedCamera(0.01, moved), 4.0), 0.05, 1e-12);
  EXPECT_TRUE(std::isinf(SplatViewChangeAngle(a, a, 0.0)));
}

TEST(SplatMovingSet, MarginAddsTheRingAboveTheBoundaryWithoutThinningTheView)
{
  const GaussianCloud c = RandomCloud(6000, 3);
  const SplatLevelOfDetail lod = PreparedLod(c);
  const Camera cam = TurnedCamera(0.0, Origin);
  for (std::size_t budget : { std::size_t(500), std::size_t(2000), std::size_t(0) })
  {
    std::vector<std::uint32_t> plain, wide;
    const std::size_t inside = SelectSplatsForView(c, lod, cam, budget, plain, 2);
    EXPECT_EQ(SelectSplatsForView(c, lod, cam, budget, wide, 2, 0.2), inside);
    // Everything of the view's own selection is kept, and the ring brings more.
    EXPECT_TRUE(std::includes(wide.begin(), wide.end(), plain.begin(), plain.end()))
      << "budget " << budget;
    EXPECT_GT(wide.size(), plain.size()) << "budget " << budget;
    // The added ones are outside the view's frustum and inside the widened one, with a key
    // at least the smallest kept inside.
    std::uint32_t lowest = 0xffffffffu;
    for (std::uint32_t i : plain)
    {
      const float* p = &c.Positions[3 * i];
      lowest = std::min(lowest, SplatContributionKey(lod.Mass[i], p[2]));
    }
    const double widened = std::tan(std::atan(1.0) + 0.2);
    for (std::uint32_t i : wide)
    {
      if (std::binary_search(plain.begin(), plain.end(), i))
      {
        continue;
      }
      const float* p = &c.Positions[3 * i];
      const double z = p[2], reach = lod.Reach[i];
      EXPECT_TRUE(std::abs(p[0]) - z > reach * std::sqrt(2.0) - 1e-4 ||
        std::abs(p[1]) - 0.75 * z > reach * 1.25 - 1e-4)
        << i;
      EXPECT_LE(std::abs(p[0]) - widened * z, reach * std::sqrt(1 + widened * widened) + 1e-4);
      EXPECT_GE(std::min<std::uint32_t>(SplatContributionKey(lod.Mass[i], p[2]), 65535), lowest)
        << i;
    }
  }
}

TEST(SplatMovingSet, CompactCloudProjectsLikeTheSubsetOfTheScene)
{
  const GaussianCloud c = RandomCloud(5000, 7);
  const SplatLevelOfDetail lod = PreparedLod(c);
  const Camera cam = TurnedCamera(0.05, Origin);
  RasterSettings settings = TwoThreads();
  SplatMovingSet set;
  ASSERT_TRUE(UpdateSplatMovingSet(c, 1, lod, cam, 1500, settings, 0.0, 0.0, set));
  std::vector<std::uint32_t> expected;
  SelectSplatsForView(c, lod, cam, 1500, expected, 2);
  ASSERT_EQ(set.Subset, expected);
  ASSERT_EQ(set.Compact.Count, expected.size());
  EXPECT_EQ(set.Compact.ShDegree, 0);
  ASSERT_NE(set.Generation, 0u);
  PreparedCloudCache wholeCache, compactCache;
  ViewProjection<float> whole, compact;
  ProjectGaussianSubset(c, set.Subset, cam, settings, whole, wholeCache, 1);
  ProjectGaussians(set.Compact, cam, settings, compact, compactCache, set.Generation);
  ASSERT_EQ(whole.Gaussians.size(), compact.Gaussians.size());
  std::size_t visible = 0;
  for (std::size_t j = 0; j < whole.Gaussians.size(); ++j)
  {
    const auto& a = whole.Gaussians[j];
    const auto& b = compact.Gaussians[j];
    ASSERT_EQ(a.Status, b.Status) << j;
    if (!a.IsVisible())
    {
      continue;
    }
    ++visible;
    // The geometry is the same computation on the same parameters: bit for bit.
    EXPECT_EQ(a.U, b.U);
    EXPECT_EQ(a.V, b.V);
    EXPECT_EQ(a.ConicA, b.ConicA);
    EXPECT_EQ(a.ConicC, b.ConicC);
    EXPECT_EQ(a.Depth, b.Depth);
    EXPECT_EQ(a.Opacity, b.Opacity);
    EXPECT_EQ(a.Radius, b.Radius);
    // The colour goes through the degree-0 term: a few ulps.
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_NEAR(a.Color[k], b.Color[k], 1e-6f * std::max(1.0f, a.Color[k])) << j << " " << k;
    }
  }
  EXPECT_GT(visible, 1000u);
}

TEST(SplatMovingSet, ReusedWhileTheViewMovesLessThanTheAngle)
{
  const GaussianCloud c = RandomCloud(4000, 11);
  const SplatLevelOfDetail lod = PreparedLod(c);
  RasterSettings settings = TwoThreads();
  SplatMovingSet set;
  const double angle = 0.1;
  EXPECT_TRUE(
    UpdateSplatMovingSet(c, 1, lod, TurnedCamera(0.0, Origin), 800, settings, angle, 0.0, set));
  const std::vector<std::uint32_t> first = set.Subset;
  const std::uint64_t generation = set.Generation;
  // Turned by less than the angle: the same set, colours of the first camera.
  EXPECT_FALSE(
    UpdateSplatMovingSet(c, 1, lod, TurnedCamera(0.06, Origin), 800, settings, angle, 0.0, set));
  EXPECT_EQ(set.Subset, first);
  EXPECT_EQ(set.Generation, generation);
  EXPECT_EQ(set.Reuses, 1u);
  // The margin holds Gaussians outside the first view that the turned view sees.
  std::vector<std::uint32_t> turned;
  SelectSplatsForView(c, lod, TurnedCamera(0.06, Origin), 800, turned, 2);
  std::vector<std::uint32_t> plain;
  SelectSplatsForView(c, lod, TurnedCamera(0.0, Origin), 800, plain, 2);
  std::size_t inFirst = 0, inSet = 0;
  for (std::uint32_t i : turned)
  {
    inFirst += std::binary_search(plain.begin(), plain.end(), i) ? 1 : 0;
    inSet += std::binary_search(first.begin(), first.end(), i) ? 1 : 0;
  }
  EXPECT_GT(inSet, inFirst);
  // Beyond the angle, another budget, another version, another SH degree, angle 0: rebuilt.
  EXPECT_TRUE(
    UpdateSplatMovingSet(c, 1, lod, TurnedCamera(0.12, Origin), 800, settings, angle, 0.0, set));
  EXPECT_NE(set.Generation, generation);
  EXPECT_TRUE(
    UpdateSplatMovingSet(c, 1, lod, TurnedCamera(0.12, Origin), 900, settings, angle, 0.0, set));
  EXPECT_TRUE(
    UpdateSplatMovingSet(c, 2, lod, TurnedCamera(0.12, Origin), 900, settings, angle, 0.0, set));
  settings.ShDegree = 1;
  EXPECT_TRUE(
    UpdateSplatMovingSet(c, 2, lod, TurnedCamera(0.12, Origin), 900, settings, angle, 0.0, set));
  EXPECT_FALSE(
    UpdateSplatMovingSet(c, 2, lod, TurnedCamera(0.12, Origin), 900, settings, angle, 0.0, set));
  EXPECT_TRUE(
    UpdateSplatMovingSet(c, 2, lod, TurnedCamera(0.12, Origin), 900, settings, 0.0, 0.0, set));
  EXPECT_TRUE(
    UpdateSplatMovingSet(c, 2, lod, TurnedCamera(0.12, Origin), 900, settings, 0.0, 0.0, set));
  // Travel: 0.2 at the median depth (about 6) is about 0.033 rad.
  const double moved[3] = { 0.2, 0.0, 0.0 };
  EXPECT_TRUE(
    UpdateSplatMovingSet(c, 2, lod, TurnedCamera(0.0, Origin), 900, settings, 0.05, 0.0, set));
  EXPECT_GT(set.Made.Depth, 4.0);
  EXPECT_LT(set.Made.Depth, 8.0);
  EXPECT_FALSE(
    UpdateSplatMovingSet(c, 2, lod, TurnedCamera(0.0, moved), 900, settings, 0.05, 0.0, set));
  const double far[3] = { 0.6, 0.0, 0.0 };
  EXPECT_TRUE(
    UpdateSplatMovingSet(c, 2, lod, TurnedCamera(0.0, far), 900, settings, 0.05, 0.0, set));
  EXPECT_EQ(set.Rebuilds, 9u);
  EXPECT_THROW(
    UpdateSplatMovingSet(c, 2, lod, TurnedCamera(0.0, far), 900, settings, -1.0, 0.0, set),
    std::invalid_argument);
  EXPECT_THROW(
    UpdateSplatMovingSet(c, 2, lod, TurnedCamera(0.0, far), 900, settings, 0.1, -1.0, set),
    std::invalid_argument);
}

TEST(SplatMovingSet, RebuildKeepsTheColoursOfTheGaussiansThatStayWithinTheColourAngle)
{
  const GaussianCloud c = RandomCloud(4000, 13);
  const SplatLevelOfDetail lod = PreparedLod(c);
  RasterSettings settings = TwoThreads();
  // (the colours depend on the camera's centre only: the second one moves it)
  const double moved[3] = { 1.0, 0.0, 0.0 };
  const Camera first = TurnedCamera(0.0, Origin), second = TurnedCamera(0.15, moved);
  // The reference: every colour of the second camera, and of the first.
  SplatMovingSet fresh, old;
  UpdateSplatMovingSet(c, 1, lod, second, 800, settings, 0.1, 0.0, fresh);
  UpdateSplatMovingSet(c, 1, lod, first, 800, settings, 0.1, 0.0, old);
  for (double colorAngle : { 0.3, 0.0 })
  {
    SplatMovingSet set;
    UpdateSplatMovingSet(c, 1, lod, first, 800, settings, 0.1, colorAngle, set);
    EXPECT_EQ(set.ColorRefreshes, 1u);
    ASSERT_TRUE(UpdateSplatMovingSet(c, 1, lod, second, 800, settings, 0.1, colorAngle, set));
    EXPECT_EQ(set.ColorRefreshes, colorAngle > 0 ? 1u : 2u);
    ASSERT_EQ(Ascending(set), fresh.Subset);
    ASSERT_EQ(set.Compact.Count, set.Subset.size());
    std::size_t kept = 0, changed = 0;
    for (std::size_t j = 0; j < set.Subset.size(); ++j)
    {
      // Slot j holds Gaussian i, with the parameters of the cloud's and of fresh's slot f.
      const std::uint32_t i = set.Subset[j];
      const std::size_t f = static_cast<std::size_t>(
        std::lower_bound(fresh.Subset.begin(), fresh.Subset.end(), i) - fresh.Subset.begin());
      for (int q = 0; q < 3; ++q)
      {
        ASSERT_EQ(set.Compact.Positions[3 * j + q], c.Positions[3 * i + q]);
        ASSERT_EQ(set.Compact.LogScales[3 * j + q], c.LogScales[3 * i + q]);
      }
      for (int q = 0; q < 4; ++q)
      {
        ASSERT_EQ(set.Compact.Rotations[4 * j + q], c.Rotations[4 * i + q]);
      }
      ASSERT_EQ(set.Compact.OpacityLogits[j], c.OpacityLogits[i]);
      const auto at = std::lower_bound(old.Subset.begin(), old.Subset.end(), i);
      const bool stayed = at != old.Subset.end() && *at == i;
      const std::size_t k = static_cast<std::size_t>(at - old.Subset.begin());
      // A Gaussian that stays keeps its slot (old is a first build: in the cloud's order).
      if (colorAngle > 0 && stayed)
      {
        ASSERT_TRUE(j == k || k >= set.Subset.size()) << j << " " << k;
      }
      for (int q = 0; q < 3; ++q)
      {
        // Kept: the first camera's colour; evaluated: the second camera's.
        const float expected =
          colorAngle > 0 && stayed ? old.Compact.SH[3 * k + q] : fresh.Compact.SH[3 * f + q];
        ASSERT_EQ(set.Compact.SH[3 * j + q], expected) << j;
      }
      kept += stayed ? 1 : 0;
      changed += stayed && old.Compact.SH[3 * k] != fresh.Compact.SH[3 * f] ? 1 : 0;
    }
    EXPECT_GT(kept, set.Subset.size() / 2);
    EXPECT_LT(kept, set.Subset.size());
    EXPECT_GT(changed, kept / 2); // the view-dependent colours differ between the cameras
  }
  // Beyond the colour angle, every colour is evaluated again.
  SplatMovingSet set;
  UpdateSplatMovingSet(c, 1, lod, first, 800, settings, 0.1, 0.12, set);
  UpdateSplatMovingSet(c, 1, lod, second, 800, settings, 0.1, 0.12, set);
  EXPECT_EQ(set.ColorRefreshes, 2u);
  EXPECT_EQ(set.Compact.SH, fresh.Compact.SH);
}

} // namespace vis4gs

namespace vis4gs
{
TEST(SplatMovingSet, BuildFillsTheSpareBuffersAndPublishMakesThemTheSet)
{
  const GaussianCloud c = RandomCloud(5000, 17);
  const SplatLevelOfDetail lod = PreparedLod(c);
  const RasterSettings settings = TwoThreads();
  const double angle = 0.1;
  const Camera a = TurnedCamera(0.0, Origin), b = TurnedCamera(0.25, Origin);
  SplatMovingSet set;
  ASSERT_TRUE(UpdateSplatMovingSet(c, 1, lod, a, 1000, settings, angle, 0.3, set));
  EXPECT_TRUE(SplatMovingSetReusable(c, 1, a, 1000, settings, angle, set));
  EXPECT_FALSE(SplatMovingSetReusable(c, 1, b, 1000, settings, angle, set));
  // Past a fraction of the angle (the builder's trigger), within the whole angle (still drawn).
  const Camera half = TurnedCamera(0.07, Origin);
  EXPECT_TRUE(SplatMovingSetReusable(c, 1, half, 1000, settings, angle, set));
  EXPECT_FALSE(SplatMovingSetReusable(c, 1, half, 1000, settings, angle, set, 0.5));
  EXPECT_FALSE(SplatMovingSetReusable(c, 2, a, 1000, settings, angle, set)); // another version
  EXPECT_FALSE(SplatMovingSetReusable(c, 1, a, 1000, settings, 0.0, set));   // angle 0
  // A build for b leaves everything a frame reads as it was.
  const std::vector<std::uint32_t> published = set.Subset;
  const std::vector<float> positions = set.Compact.Positions;
  const std::vector<float> colours = set.Compact.SH;
  const std::uint64_t generation = set.Generation;
  const std::size_t rebuilds = set.Rebuilds;
  EXPECT_FALSE(set.Next.Ready);
  BuildSplatMovingSet(c, 1, lod, b, 1000, settings, angle, 0.3, set);
  EXPECT_TRUE(set.Next.Ready);
  EXPECT_EQ(set.Subset, published);
  EXPECT_EQ(set.Compact.Positions, positions);
  EXPECT_EQ(set.Compact.SH, colours);
  EXPECT_EQ(set.Generation, generation);
  EXPECT_EQ(set.Rebuilds, rebuilds);
  // Published, it is b's selection (with the margin), a new generation.
  ASSERT_TRUE(PublishSplatMovingSet(set));
  EXPECT_FALSE(PublishSplatMovingSet(set));
  std::vector<std::uint32_t> expected;
  SelectSplatsForView(c, lod, b, 1000, expected, 2, angle);
  EXPECT_EQ(Ascending(set), expected);
  EXPECT_NE(set.Generation, generation);
  EXPECT_EQ(set.Rebuilds, rebuilds + 1);
  EXPECT_TRUE(SplatMovingSetReusable(c, 1, b, 1000, settings, angle, set));
  // The same as a rebuild by UpdateSplatMovingSet from the same published set.
  SplatMovingSet direct;
  ASSERT_TRUE(UpdateSplatMovingSet(c, 1, lod, a, 1000, settings, angle, 0.3, direct));
  ASSERT_TRUE(UpdateSplatMovingSet(c, 1, lod, b, 1000, settings, angle, 0.3, direct));
  EXPECT_EQ(direct.Subset, set.Subset);
  EXPECT_EQ(direct.Compact.Positions, set.Compact.Positions);
  EXPECT_EQ(direct.Compact.SH, set.Compact.SH);
  EXPECT_THROW(
    BuildSplatMovingSet(c, 1, lod, b, 1000, settings, -1.0, 0.3, set), std::invalid_argument);
}
} // namespace vis4gs

namespace vis4gs
{
TEST(SplatMovingSet, ReservedSetRebuildsWithoutAllocatingAndLikeAnUnreservedOne)
{
  const GaussianCloud c = RandomCloud(6000, 19);
  const SplatLevelOfDetail lod = PreparedLod(c);
  const RasterSettings settings = TwoThreads();
  const double angle = 0.1;
  SplatMovingSet reserved, plain;
  ASSERT_TRUE(ReserveSplatMovingSet(reserved, 3000, 2));
  // Nothing of the set's content: only room.
  EXPECT_TRUE(reserved.Subset.empty());
  EXPECT_TRUE(reserved.Compact.Positions.empty());
  EXPECT_GE(reserved.Subset.capacity(), 3000u);
  EXPECT_GE(reserved.Selected.capacity(), 3000u);
  EXPECT_GE(reserved.Compact.SH.capacity(), 9000u);
  EXPECT_GE(reserved.Next.Patch.Rotations.capacity(), 12000u);
  // A turn of the camera in steps beyond the angle: a rebuild every frame, colours kept for
  // some and evaluated for others.
  const float* buffers[2] = { reserved.Compact.Positions.data(),
    reserved.Next.Patch.Positions.data() };
  for (int f = 0; f < 6; ++f)
  {
    const Camera camera = TurnedCamera(0.12 * f, Origin);
    ASSERT_TRUE(UpdateSplatMovingSet(c, 1, lod, camera, 1000, settings, angle, 0.3, reserved));
    ASSERT_TRUE(UpdateSplatMovingSet(c, 1, lod, camera, 1000, settings, angle, 0.3, plain));
    ASSERT_LE(reserved.Subset.size(), 3000u);
    ASSERT_EQ(reserved.Subset, plain.Subset) << f;
    ASSERT_EQ(reserved.Compact.Positions, plain.Compact.Positions) << f;
    ASSERT_EQ(reserved.Compact.OpacityLogits, plain.Compact.OpacityLogits) << f;
    ASSERT_EQ(reserved.Compact.SH, plain.Compact.SH) << f;
    EXPECT_EQ(reserved.ColorRefreshes, plain.ColorRefreshes);
    // The compact cloud is written in place, or swapped with the patch that holds a whole new
    // one: either of the two reserved buffers, never allocated again.
    const float* data = reserved.Compact.Positions.data();
    EXPECT_TRUE(data == buffers[0] || data == buffers[1]) << f;
  }
  EXPECT_GT(reserved.ColorRefreshes, 1u);
  EXPECT_LT(reserved.ColorRefreshes, 6u);
  // Only before anything is published.
  EXPECT_FALSE(ReserveSplatMovingSet(reserved, 4000, 2));
  EXPECT_LT(reserved.Subset.capacity(), 4000u);
}
} // namespace vis4gs

namespace vis4gs
{
TEST(SplatMovingSet, RebuildsWriteOnlyTheNewGaussiansAndTheProjectionPreparesOnlyThose)
{
  const GaussianCloud c = RandomCloud(8000, 23);
  const SplatLevelOfDetail lod = PreparedLod(c);
  const RasterSettings settings = TwoThreads();
  SplatMovingSet set;
  PreparedCloudCache kept;
  ViewProjection<float> projection;
  // Turns beyond the reuse angle, colours kept (a long colour angle): slots kept, then at last
  // every colour evaluated again (colour angle 0).
  const double yaws[] = { 0.0, 0.12, 0.24, 0.36, 0.25, 0.13, 0.01 };
  std::size_t partial = 0, moves = 0;
  for (std::size_t f = 0; f < sizeof(yaws) / sizeof(yaws[0]); ++f)
  {
    const Camera camera = TurnedCamera(yaws[f], Origin);
    const double colorAngle = f + 1 < sizeof(yaws) / sizeof(yaws[0]) ? 3.0 : 0.0;
    const std::vector<std::uint32_t> before = set.Subset;
    const GaussianCloud compact = set.Compact;
    ASSERT_TRUE(UpdateSplatMovingSet(c, 1, lod, camera, 1200, settings, 0.1, colorAngle, set));
    // The selection (with the margin), each Gaussian once, each slot with its parameters.
    std::vector<std::uint32_t> expected;
    SelectSplatsForView(c, lod, camera, 1200, expected, 2, 0.1);
    ASSERT_EQ(Ascending(set), expected) << f;
    ASSERT_EQ(set.Compact.Count, expected.size());
    std::size_t stayed = 0;
    for (std::size_t j = 0; j < set.Subset.size(); ++j)
    {
      const std::uint32_t i = set.Subset[j];
      for (int q = 0; q < 3; ++q)
      {
        ASSERT_EQ(set.Compact.Positions[3 * j + q], c.Positions[3 * i + q]) << f;
      }
      ASSERT_EQ(set.Compact.OpacityLogits[j], c.OpacityLogits[i]) << f;
      // A Gaussian still in its slot keeps its colour; only the slots listed changed.
      const bool changed =
        std::find(set.Changed.begin(), set.Changed.end(), j) != set.Changed.end();
      if (!set.AllChanged && !changed)
      {
        ASSERT_LT(j, before.size());
        ASSERT_EQ(before[j], i) << f;
        ASSERT_EQ(set.Compact.SH[3 * j], compact.SH[3 * j]) << f;
        ++stayed;
      }
    }
    partial += set.AllChanged ? 0 : 1;
    // (the last publication's moves of Gaussians beyond a shrunk set stay listed in Next)
    moves += set.AllChanged ? 0 : set.Next.MoveFrom.size();
    if (!set.AllChanged)
    {
      EXPECT_GT(stayed, set.Subset.size() / 2) << f;
      EXPECT_LT(set.Changed.size(), set.Subset.size() / 2) << f;
      EXPECT_NE(SlotOf(set, expected.front()), set.Subset.size());
    }
    // The projection with the kept preparation, refreshed for the changed slots only, is a
    // projection with a fresh one, bit for bit.
    const std::size_t builds = kept.Builds();
    ProjectSplatMovingSet(set, camera, settings, projection, kept);
    EXPECT_EQ(kept.Builds(), builds + (f == 0 || set.AllChanged ? 1 : 0)) << f;
    PreparedCloudCache fresh;
    ViewProjection<float> reference;
    ProjectGaussians(set.Compact, camera, settings, reference, fresh, set.Generation);
    ASSERT_EQ(projection.Gaussians.size(), reference.Gaussians.size());
    for (std::size_t j = 0; j < reference.Gaussians.size(); ++j)
    {
      const auto& a = projection.Gaussians[j];
      const auto& b = reference.Gaussians[j];
      ASSERT_EQ(a.Status, b.Status) << f << " " << j;
      ASSERT_EQ(a.U, b.U);
      ASSERT_EQ(a.ConicA, b.ConicA);
      ASSERT_EQ(a.ConicB, b.ConicB);
      ASSERT_EQ(a.Opacity, b.Opacity);
      ASSERT_EQ(a.Color[0], b.Color[0]);
    }
  }
  EXPECT_GE(partial, 4u);
  EXPECT_GT(moves, 0u);
  // The refresh refuses another version than the kept one, and indices beyond the cloud.
  EXPECT_FALSE(RefreshPreparedCloud(kept,
    set.Compact,
    set.Generation + 7,
    set.Generation + 8,
    std::vector<std::uint32_t>{ 0 },
    settings));
  EXPECT_THROW(RefreshPreparedCloud(kept,
                 set.Compact,
                 set.Generation,
                 set.Generation + 8,
                 std::vector<std::uint32_t>{ static_cast<std::uint32_t>(set.Compact.Count) },
                 settings),
    std::invalid_argument);
}
} // namespace vis4gs

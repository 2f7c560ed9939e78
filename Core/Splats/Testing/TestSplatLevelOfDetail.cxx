// SPDX-License-Identifier: BSD-3-Clause
#include "SplatLevelOfDetail.h"

#include "GaussianCloud.h"
#include "GaussianMath.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>
#include <vector>

namespace vis4gs
{
namespace
{
// A camera at the origin looking down +z (identity world-to-camera), 90 degrees wide.
Camera IdentityCamera()
{
  Camera c;
  c.Width = 200;
  c.Height = 100;
  c.Fx = 100; // tan(fov_x / 2) = 1
  c.Fy = 100; // tan(fov_y / 2) = 0.5
  c.Cx = 100;
  c.Cy = 50;
  c.WorldToCamera = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  return c;
}
}

TEST(SplatLevelOfDetail, MassAndReachFromOpacityAndScales)
{
  GaussianCloud c;
  c.Resize(5, 0);
  for (std::size_t i = 0; i < c.Count; ++i)
  {
    c.Rotations[4 * i] = 1.0f;
  }
  const float ls[5][3] = { { 0.0f, std::log(2.0f), std::log(4.0f) },
    { std::log(0.1f), std::log(0.1f), std::log(0.1f) },
    { std::nanf(""), 0, 0 },
    { 0, 0, 0 },
    { 0, 0, 0 } };
  for (int i = 0; i < 5; ++i)
  {
    std::copy_n(ls[i], 3, &c.LogScales[3 * i]);
  }
  c.OpacityLogits = { 0.0f, 3.0f, 0.0f, 0.0f, -std::numeric_limits<float>::infinity() };
  c.Positions[3 * 3] = std::numeric_limits<float>::infinity();
  SplatLevelOfDetail lod;
  PrepareSplatLevelOfDetail(c, lod, 2);
  ASSERT_EQ(lod.Mass.size(), 5u);
  EXPECT_NEAR(lod.Mass[0], 0.5 * 2 * 4, 1e-5);
  EXPECT_NEAR(lod.Reach[0], 12.0, 1e-5);
  EXPECT_NEAR(lod.Mass[1], 0.01 / (1.0 + std::exp(-3.0)), 1e-7);
  EXPECT_NEAR(lod.Reach[1], 0.3, 1e-6);
  for (int i : { 2, 3, 4 })
  {
    EXPECT_EQ(lod.Mass[i], 0.0f) << i; // non-finite parameters are never selected
  }
  c.OpacityLogits.pop_back(); // arrays that do not match the count: nothing is selected
  PrepareSplatLevelOfDetail(c, lod, 1);
  EXPECT_EQ(std::count(lod.Mass.begin(), lod.Mass.end(), 0.0f), 5);
}

TEST(SplatLevelOfDetail, SelectionKeepsTheLargestContributionsInTheFrustum)
{
  // Masses and depths are powers of two, so mass / z^2 is exact and the 16-bit key ranks
  // like the value: the expectation is a plain sort by (contribution desc, index asc).
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> power(-6, 6), depth(0, 4), side(0, 9);
  const std::size_t n = 20000;
  GaussianCloud c;
  c.Resize(n, 0);
  SplatLevelOfDetail lod;
  lod.Mass.resize(n);
  lod.Reach.assign(n, 0.01f);
  std::vector<double> contribution(n, -1.0);
  for (std::size_t i = 0; i < n; ++i)
  {
    const float z =
      i % 97 == 0 ? 0.125f : std::ldexp(1.0f, depth(rng)); // some before the near plane
    const int s = side(rng);
    // Inside: |x| <= z (tan 1), |y| <= z / 2; a tenth just outside, beyond the reach.
    const float x = s == 0 ? 1.2f * z : 0.9f * z * (side(rng) - 4.5f) / 4.5f;
    const float y = s == 1 ? -0.7f * z : 0.4f * z;
    c.Positions[3 * i] = x;
    c.Positions[3 * i + 1] = y;
    c.Positions[3 * i + 2] = z;
    lod.Mass[i] = i % 89 == 0 ? 0.0f : std::ldexp(1.0f, power(rng));
    if (z > 0.2f && s > 1 && lod.Mass[i] > 0)
    {
      contribution[i] = static_cast<double>(lod.Mass[i]) / (static_cast<double>(z) * z);
    }
  }
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(),
    order.end(),
    [&](std::uint32_t a, std::uint32_t b)
    { return contribution[a] != contribution[b] ? contribution[a] > contribution[b] : a < b; });
  const std::size_t inFrustum = static_cast<std::size_t>(
    std::count_if(contribution.begin(), contribution.end(), [](double v) { return v > 0; }));
  ASSERT_GT(inFrustum, n / 2);
  const Camera cam = IdentityCamera();
  for (std::size_t budget : { std::size_t(1),
         std::size_t(1000),
         std::size_t(7777),
         inFrustum - 1,
         inFrustum,
         inFrustum + 10,
         std::size_t(0) })
  {
    std::vector<std::uint32_t> got;
    EXPECT_EQ(SelectSplatsForView(c, lod, cam, budget, got, 2), inFrustum);
    std::vector<std::uint32_t> expected(
      order.begin(), order.begin() + (budget == 0 ? inFrustum : std::min(budget, inFrustum)));
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(got, expected) << "budget " << budget;
  }
  // A large reach brings a Gaussian just outside (x = 1.2 z or y = -0.7 z) into the frustum.
  std::vector<std::uint32_t> got;
  std::size_t probe = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (contribution[i] < 0 && c.Positions[3 * i + 2] > 0.2f && lod.Mass[i] > 0)
    {
      probe = i;
      break;
    }
  }
  lod.Reach[probe] = 10.0f * c.Positions[3 * probe + 2];
  SelectSplatsForView(c, lod, cam, 0, got, 1);
  EXPECT_TRUE(std::binary_search(got.begin(), got.end(), static_cast<std::uint32_t>(probe)));
  lod.Mass.pop_back();
  EXPECT_THROW(SelectSplatsForView(c, lod, cam, 10, got, 1), std::invalid_argument);
}

TEST(SplatLevelOfDetail, KeyOrdersLikeTheContribution)
{
  EXPECT_EQ(SplatContributionKey(0.0f, 1.0f), 0u);
  EXPECT_EQ(SplatContributionKey(std::nanf(""), 1.0f), 0u);
  EXPECT_GE(SplatContributionKey(1e-40f, 1.0f), 1u); // tiny but positive: still selectable
  EXPECT_LT(SplatContributionKey(1.0f, 2.0f), SplatContributionKey(1.0f, 1.0f));
  EXPECT_EQ(SplatContributionKey(4.0f, 2.0f), SplatContributionKey(1.0f, 1.0f));
  EXPECT_LT(SplatContributionKey(1.0f, 1.0f), SplatContributionKey(1.02f, 1.0f));
}

} // namespace vis4gs

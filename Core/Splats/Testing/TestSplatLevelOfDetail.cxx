// SPDX-License-Identifier: BSD-3-Clause
#include "SplatLevelOfDetail.h"

#include "GaussianCloud.h"
#include "GaussianMath.h"

#include <gtest/gtest.h>
#include <omp.h>

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

namespace
{
// Clusters of Gaussians around and behind a camera at the origin, of masses over several
// orders of magnitude, with a few non-finite ones and far floaters.
GaussianCloud ClusteredCloud(std::size_t n, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::normal_distribution<float> g(0.0f, 1.0f);
  std::vector<float> centres;
  for (int k = 0; k < 40; ++k)
  {
    centres.insert(centres.end(), { 8.0f * u(rng), 4.0f * u(rng), 4.0f + 8.0f * u(rng) });
  }
  GaussianCloud c;
  c.Resize(n, 0);
  for (std::size_t i = 0; i < n; ++i)
  {
    const float* centre = &centres[3 * (i % 40)];
    const float spread = i % 500 == 0 ? 50.0f : 0.6f; // (a few far floaters)
    for (int k = 0; k < 3; ++k)
    {
      c.Positions[3 * i + k] = centre[k] + spread * g(rng);
      c.LogScales[3 * i + k] = -4.0f + 1.2f * g(rng) + (i % 777 == 0 ? 3.0f : 0.0f);
    }
    for (int k = 0; k < 4; ++k)
    {
      c.Rotations[4 * i + k] = (k == 0 ? 1.0f : 0.0f) + 0.3f * u(rng);
    }
    c.OpacityLogits[i] = 3.0f * u(rng);
    if (i % 1009 == 0)
    {
      c.Positions[3 * i + 1] = std::numeric_limits<float>::quiet_NaN();
    }
  }
  return c;
}

// At @p centre, turned by @p yaw about the y axis from looking down +z; 160x120, 90 degrees.
Camera YawCamera(double yaw, double cx)
{
  Camera c = IdentityCamera();
  c.Width = 160;
  c.Height = 120;
  c.Fx = c.Fy = 80;
  c.Cx = 80;
  c.Cy = 60;
  const double co = std::cos(yaw), si = std::sin(yaw);
  c.WorldToCamera = { co, 0, -si, -co * cx, 0, 1, 0, 0, si, 0, co, -si * cx, 0, 0, 0, 1 };
  return c;
}
}

TEST(SplatLevelOfDetail, CellSelectionIsTheSelectionOfEveryGaussian)
{
  const std::size_t n = 60000;
  const GaussianCloud c = ClusteredCloud(n, 9);
  SplatLevelOfDetail lod;
  PrepareSplatLevelOfDetail(c, lod, 2, true, 64);
  ASSERT_GT(lod.Cells.size(), 100u);
  // Every Gaussian of positive mass is in exactly one cell, with its own values.
  std::vector<std::uint32_t> inCells, positive;
  for (const SplatCell& cell : lod.Cells)
  {
    ASSERT_LE(cell.End - cell.Begin, 64u);
    for (std::uint32_t j = cell.Begin; j < cell.End; ++j)
    {
      const SplatCellEntry& e = lod.Entries[j];
      inCells.push_back(e.Index);
      EXPECT_EQ(e.Mass, lod.Mass[e.Index]);
      EXPECT_EQ(e.X, c.Positions[3 * e.Index]);
      EXPECT_LE(e.Mass, cell.MaxMass);
    }
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    if (lod.Mass[i] > 0.0f)
    {
      positive.push_back(static_cast<std::uint32_t>(i));
    }
  }
  std::sort(inCells.begin(), inCells.end());
  ASSERT_EQ(inCells, positive);
  // Along a turn and a travel, with the boundary kept between selections (the floor), the
  // subset is the whole cloud's selection, Gaussian for Gaussian.
  bool culled = false;
  for (std::size_t budget : { std::size_t(300), std::size_t(4000), std::size_t(0), n })
  {
    for (double margin : { 0.0, 0.1 })
    {
      SplatSelectionState state;
      for (int step = 0; step < 6; ++step)
      {
        const Camera cam = YawCamera(0.05 * step, 0.1 * step);
        std::vector<std::uint32_t> expected, got;
        SelectSplatsForView(c, lod, cam, budget, expected, 2, margin);
        SelectSplatsInCells(c, lod, cam, budget, got, state, 2, margin);
        ASSERT_EQ(got, expected) << "budget " << budget << " margin " << margin << " step " << step;
        culled = culled || state.Examined < positive.size() / 2;
      }
    }
  }
  EXPECT_TRUE(culled); // (the cells spared reading most Gaussians at least once)
  // A floor above the boundary (a boundary kept from another view): every cell again, the
  // same subset.
  SplatSelectionState state;
  state.Boundary = 0x7f00;
  const Camera cam = YawCamera(0.3, 0.0);
  std::vector<std::uint32_t> expected, got;
  SelectSplatsForView(c, lod, cam, 2000, expected, 2);
  SelectSplatsInCells(c, lod, cam, 2000, got, state, 2);
  EXPECT_TRUE(state.Fallback);
  EXPECT_EQ(got, expected);
  // Without cells it selects from every Gaussian; a level of detail of another cloud throws.
  SplatLevelOfDetail plain;
  PrepareSplatLevelOfDetail(c, plain, 2, false);
  EXPECT_TRUE(plain.Cells.empty());
  SelectSplatsInCells(c, plain, cam, 2000, got, state, 2);
  EXPECT_EQ(got, expected);
  plain.Mass.pop_back();
  EXPECT_THROW(SelectSplatsInCells(c, plain, cam, 10, got, state, 1), std::invalid_argument);
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

// A team smaller than the threads asked (OMP_THREAD_LIMIT, OMP_DYNAMIC, or nested in a parallel
// region as here) selects what a full team selects. The histograms of the threads that did not
// start were left empty (a crash summing them) and the cell selection kept their candidate
// lists from an earlier view (found by Scripts/run-sanitizers.sh thread, OMP_THREAD_LIMIT=1).
TEST(SplatLevelOfDetail, ATeamSmallerThanAskedSelectsLikeAFullTeam)
{
  const GaussianCloud c = ClusteredCloud(60000, 9);
  SplatLevelOfDetail lod;
  PrepareSplatLevelOfDetail(c, lod, 2, true, 64);
  const Camera first = YawCamera(0.0, 0.0), second = YawCamera(0.6, 0.3);
  std::vector<std::uint32_t> expected, expectedCells, got, gotCells, before;
  SelectSplatsForView(c, lod, second, 4000, expected, 1);
  SplatSelectionState fresh;
  SelectSplatsInCells(c, lod, second, 4000, expectedCells, fresh, 1);
  ASSERT_EQ(expectedCells, expected);
  // The candidate lists of a team of 4, at the first view.
  SplatSelectionState state;
  SelectSplatsInCells(c, lod, first, 4000, before, state, 4);
  ASSERT_NE(before, expected);
  int inner = 0;
#pragma omp parallel num_threads(2)
  {
#pragma omp single
    {
#pragma omp parallel num_threads(4)
      {
#pragma omp single
        inner = omp_get_num_threads();
      }
      SelectSplatsForView(c, lod, second, 4000, got, 4);
      SelectSplatsInCells(c, lod, second, 4000, gotCells, state, 4);
    }
  }
  EXPECT_LT(inner, 4) << "the nested region was given every thread: nothing tested";
  EXPECT_EQ(got, expected);
  EXPECT_EQ(gotCells, expected);
}

} // namespace vis4gs

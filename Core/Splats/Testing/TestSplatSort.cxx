// SPDX-License-Identifier: BSD-3-Clause
#include "SplatSort.h"

#include "Rasterizer.h"

#include <gtest/gtest.h>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace vis4gs
{
namespace
{
// Independent expectation: stable sort of the kept indices by depth ascending (the
// rasteriser's front-to-back order), reversed.
std::vector<std::uint32_t> Expected(const std::vector<float>& d, const std::uint8_t* keep = nullptr)
{
  std::vector<std::uint32_t> idx;
  for (std::uint32_t i = 0; i < d.size(); ++i)
  {
    if (std::isfinite(d[i]) && d[i] > 0.2f && (!keep || keep[i]))
    {
      idx.push_back(i);
    }
  }
  std::stable_sort(
    idx.begin(), idx.end(), [&d](std::uint32_t a, std::uint32_t b) { return d[a] < d[b]; });
  std::reverse(idx.begin(), idx.end());
  return idx;
}
}

TEST(SplatSort, RadixEqualsReferenceOrderWithTiesAndCulls)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-5.0f, 50.0f);
  std::vector<float> d(100000);
  for (auto& v : d)
  {
    v = u(rng);
  }
  // Ties, the near plane, and non-finite depths.
  for (int i = 0; i < 1000; ++i)
  {
    d[(i * 97) % d.size()] = 3.25f;
  }
  d[5] = 0.2f;
  d[6] = std::nextafter(0.2f, 1.0f);
  d[7] = std::numeric_limits<float>::quiet_NaN();
  d[8] = std::numeric_limits<float>::infinity();
  d[9] = -std::numeric_limits<float>::infinity();
  d[10] = 1e30f;
  const auto expected = Expected(d);
  for (int threads : { 1, 2, 3, 8 })
  {
    std::vector<std::uint32_t> order;
    SplatSortOptions o;
    o.Threads = threads;
    SortBackToFront(d, order, o);
    ASSERT_EQ(order, expected) << threads << " threads";
  }
  std::vector<std::uint32_t> order;
  SortBackToFrontStd(d, order);
  EXPECT_EQ(order, expected);
  // Spot checks of the contract itself.
  EXPECT_EQ(order.front(), 10u);
  EXPECT_EQ(std::count(order.begin(), order.end(), 5u), 0);
  EXPECT_EQ(std::count(order.begin(), order.end(), 6u), 1);
  EXPECT_EQ(order.back(), 6u);
  for (std::size_t k = 1; k < order.size(); ++k)
  {
    const float a = d[order[k - 1]], b = d[order[k]];
    ASSERT_TRUE(a > b || (a == b && order[k - 1] > order[k]));
  }
}

// OpenMP may give a parallel region fewer threads than its num_threads asks (here: nested in
// an active region, which the default max-active-levels of 1 runs with one thread; in the
// ThreadSanitizer run: OMP_THREAD_LIMIT=1). The compaction's ranges were those of the threads
// asked, so that the Gaussians of the threads that did not start were missing from the order
// (found by Scripts/run-sanitizers.sh thread on the sort worker's test).
TEST(SplatSort, ATeamSmallerThanAskedKeepsEveryGaussian)
{
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-5.0f, 50.0f);
  std::vector<float> d(40000);
  for (auto& v : d)
  {
    v = u(rng);
  }
  const auto expected = Expected(d);
  std::vector<std::uint32_t> order;
  int inner = 0;
#pragma omp parallel num_threads(2)
  {
#pragma omp single
    {
      SplatSortOptions o;
      o.Threads = 8;
#pragma omp parallel num_threads(8)
      {
#pragma omp single
        inner = omp_get_num_threads();
      }
      SortBackToFront(d, order, o);
    }
  }
  EXPECT_LT(inner, 8) << "the nested region was given every thread: nothing tested";
  EXPECT_EQ(order, expected);
}

TEST(SplatSort, MaskEmptyAndSingleDigitKeys)
{
  std::vector<float> d = { 1.0f, 2.0f, 1.0f, 0.5f, 2.0f };
  std::vector<std::uint8_t> keep = { 1, 0, 1, 1, 1 };
  std::vector<std::uint32_t> order;
  SplatSortOptions o;
  o.Keep = keep.data();
  SortBackToFront(d, order, o);
  EXPECT_EQ(order, (std::vector<std::uint32_t>{ 4, 2, 0, 3 }));
  SortBackToFront({}, order);
  EXPECT_TRUE(order.empty());
  // Every key identical: all passes skipped, index order reversed.
  std::vector<float> same(5000, 7.0f);
  SortBackToFront(same, order);
  ASSERT_EQ(order.size(), 5000u);
  EXPECT_EQ(order.front(), 4999u);
  EXPECT_EQ(order.back(), 0u);
  // Everything culled.
  std::vector<float> behind(100, -1.0f);
  SortBackToFront(behind, order);
  EXPECT_TRUE(order.empty());
}

TEST(SplatSort, ViewDepthsMatchTheRasteriserBitForBit)
{
  GaussianCloud cloud;
  cloud.Resize(500, 0);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-3.0f, 3.0f);
  for (auto& v : cloud.Positions)
  {
    v = u(rng);
  }
  std::fill(cloud.LogScales.begin(), cloud.LogScales.end(), -2.0f);
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    cloud.Rotations[4 * i] = 1.0f;
    cloud.Rotations[4 * i + 1] = 0.3f;
  }
  Camera cam;
  cam.Width = 64;
  cam.Height = 48;
  cam.Fx = cam.Fy = 50;
  const double c = std::cos(0.3), s = std::sin(0.3);
  cam.WorldToCamera = { c, 0, s, 0.1, 0, 1, 0, -0.2, -s, 0, c, 6.0, 0, 0, 0, 1 };
  std::vector<float> depths;
  ComputeViewDepths(cloud.Positions.data(), cloud.Count, cam.WorldToCamera, depths, 2);
  RasterSettings settings;
  settings.ComputeColors = false;
  const auto proj = ProjectGaussians<float>(cloud, cam, settings);
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    ASSERT_EQ(depths[i], proj.Gaussians[i].ViewPosition[2]) << i;
    const double exact = -s * cloud.Positions[3 * i] + c * cloud.Positions[3 * i + 2] + 6.0;
    ASSERT_NEAR(depths[i], exact, 1e-5);
  }
}

} // namespace vis4gs

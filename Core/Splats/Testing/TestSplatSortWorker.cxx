// SPDX-License-Identifier: BSD-3-Clause
#include "SplatSortWorker.h"

#include "BenchmarkScene.h"
#include "SplatSort.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace vis4gs
{
namespace
{
std::shared_ptr<const GaussianCloud> Scene(std::size_t n)
{
  return std::make_shared<const GaussianCloud>(MakeBenchmarkScene(n, 0, 3));
}

// Row-major world-to-camera of a camera at distance 3.5 turned by @p azimuth about y: an
// independent construction (not MakeBenchmarkCamera's) of the rotation R_y(a) then +z 3.5.
std::array<double, 16> Orbit(double azimuth)
{
  const double c = std::cos(azimuth), s = std::sin(azimuth);
  return { c, 0, -s, 0, 0, 1, 0, 0, s, 0, c, 3.5, 0, 0, 0, 1 };
}

// The straightforward expectation: depths by hand in double->float, std::sort (one thread),
// then every k-th.
std::vector<std::uint32_t> Expected(const GaussianCloud& cloud,
  const std::array<double, 16>& m,
  const std::vector<std::uint8_t>* keep,
  std::size_t budget)
{
  std::vector<float> depths;
  ComputeViewDepths(cloud.Positions.data(), cloud.Count, m, depths, 1);
  SplatSortOptions options;
  options.Keep = keep ? keep->data() : nullptr;
  std::vector<std::uint32_t> order;
  SortBackToFrontStd(depths, order, options);
  if (budget > 0 && order.size() > budget)
  {
    const std::size_t k = (order.size() + budget - 1) / budget;
    std::vector<std::uint32_t> thinned;
    for (std::size_t i = 0; i < order.size(); i += k)
    {
      thinned.push_back(order[i]);
    }
    order = thinned;
  }
  return order;
}
} // namespace

TEST(SplatSortWorker, ThreadOrderEqualsStraightforwardSortWithKeepAndBudget)
{
  const auto cloud = Scene(20000);
  auto keep = std::make_shared<std::vector<std::uint8_t>>(cloud->Count, 1);
  for (std::size_t i = 0; i < keep->size(); i += 3)
  {
    (*keep)[i] = 0;
  }
  SplatSortWorker worker;
  SplatSortRequest request;
  request.Cloud = cloud;
  request.Keep = keep;
  request.WorldToCamera = Orbit(0.7);
  request.Budget = 5000;
  request.Threads = 2;
  request.SceneKey = 11;
  request.CameraKey = 4;
  worker.Submit(request);
  worker.WaitForLatest();
  SplatSortResult result;
  ASSERT_TRUE(worker.TakeResult(result));
  EXPECT_TRUE(worker.GetLastError().empty());
  const auto expected = Expected(*cloud, Orbit(0.7), keep.get(), 5000);
  ASSERT_GT(expected.size(), 1000u);
  ASSERT_LE(expected.size(), 5000u);
  EXPECT_EQ(result.Order, expected);
  EXPECT_EQ(result.SceneKey, 11u);
  EXPECT_EQ(result.CameraKey, 4u);
  EXPECT_EQ(result.WorldToCamera, Orbit(0.7));
  EXPECT_GE(result.Milliseconds, 0.0);
  // Nothing new until another request finishes.
  EXPECT_FALSE(worker.TakeResult(result));
  EXPECT_EQ(worker.GetSortCount(), 1u);
}

TEST(SplatSortWorker, LatestRequestWinsAndBuffersCirculate)
{
  const auto cloud = Scene(50000);
  SplatSortWorker worker;
  SplatSortResult result;
  for (int round = 0; round < 3; ++round)
  {
    // Requests submitted faster than they are sorted: the last one is the one that counts.
    for (int k = 0; k < 8; ++k)
    {
      SplatSortRequest request;
      request.Cloud = cloud;
      request.WorldToCamera = Orbit(0.1 * k + round);
      request.CameraKey = static_cast<std::uint64_t>(10 * round + k);
      worker.Submit(request);
    }
    worker.WaitForLatest();
    ASSERT_TRUE(worker.TakeResult(result));
    EXPECT_EQ(result.CameraKey, static_cast<std::uint64_t>(10 * round + 7));
    EXPECT_EQ(result.Order, Expected(*cloud, Orbit(0.7 + round), nullptr, 0));
  }
  // At most one sort per submitted request, at least one per round.
  EXPECT_GE(worker.GetSortCount(), 3u);
  EXPECT_LE(worker.GetSortCount(), 24u);
}

TEST(SplatSortWorker, SynchronousSortEqualsWorkerAndEmptyWorkerNeverBlocks)
{
  SplatSortWorker idle;
  idle.WaitForLatest(); // nothing submitted: returns at once
  SplatSortResult none;
  EXPECT_FALSE(idle.TakeResult(none));
  EXPECT_EQ(idle.GetSortCount(), 0u);

  const auto cloud = Scene(10000);
  SplatSortRequest request;
  request.Cloud = cloud;
  request.WorldToCamera = Orbit(2.0);
  std::vector<float> depths;
  SplatSortResult sync;
  SplatSortWorker::Sort(request, depths, sync);
  EXPECT_EQ(sync.Order, Expected(*cloud, Orbit(2.0), nullptr, 0));
}

TEST(SplatSortWorker, DestructorJoinsWithARequestPending)
{
  const auto cloud = Scene(200000);
  for (int k = 0; k < 3; ++k)
  {
    SplatSortWorker worker;
    SplatSortRequest request;
    request.Cloud = cloud;
    request.WorldToCamera = Orbit(k);
    worker.Submit(request);
    worker.Submit(request);
  } // joined here, whether a sort is running or still pending
  SUCCEED();
}

} // namespace vis4gs

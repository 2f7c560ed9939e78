// SPDX-License-Identifier: BSD-3-Clause
// ThreadCount (ThreadCount.h): the one meaning of every `Threads` option of Core, checked
// against OpenMP's own answer and under a changed OpenMP default.
#include "ThreadCount.h"

#include <gtest/gtest.h>

#include <omp.h>

#ifdef __linux__
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <thread>
#include <vector>
#endif

namespace vis4gs
{

TEST(ThreadCount, PositiveRequestIsKept)
{
  EXPECT_EQ(ThreadCount(1), 1);
  EXPECT_EQ(ThreadCount(3), 3);
  EXPECT_EQ(ThreadCount(64), 64);
}

TEST(ThreadCount, ZeroOrNegativeMeansOpenMpDefault)
{
  const int saved = omp_get_max_threads();
  omp_set_num_threads(5);
  EXPECT_EQ(ThreadCount(0), 5);
  EXPECT_EQ(ThreadCount(-2), 5);
  omp_set_num_threads(saved);
  EXPECT_EQ(ThreadCount(0), saved);
  EXPECT_GE(ThreadCount(0), 1);
}

#ifdef __linux__
namespace
{
int OwnNice()
{
  return getpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)));
}
}

TEST(ThreadCount, LowerThreadPriorityIsTheThreadsAndItsTeamsOnly)
{
  // The scene view's frame worker relies on it: the worker's nice value, inherited by the
  // OpenMP team it starts afterwards, and not the caller's.
  const int before = OwnNice();
  int worker = -100;
  std::vector<int> team;
  std::thread t(
    [&]
    {
      if (!LowerThreadPriority(before + 5))
      {
        return;
      }
      worker = OwnNice();
      team.assign(2, -100);
#pragma omp parallel num_threads(2)
      {
        team[static_cast<std::size_t>(omp_get_thread_num())] = OwnNice();
      }
      // Never raised again: a smaller value leaves it as it is.
      EXPECT_TRUE(LowerThreadPriority(1));
      EXPECT_EQ(OwnNice(), worker);
    });
  t.join();
  ASSERT_NE(worker, -100) << "setpriority refused";
  EXPECT_EQ(worker, std::min(19, before + 5));
  EXPECT_EQ(team[0], worker);
  EXPECT_EQ(team[1], worker);
  EXPECT_EQ(OwnNice(), before) << "the caller keeps its priority";
  EXPECT_TRUE(LowerThreadPriority(0));
  EXPECT_EQ(OwnNice(), before);
}
#endif

} // namespace vis4gs

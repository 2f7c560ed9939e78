// SPDX-License-Identifier: BSD-3-Clause
// ThreadCount (ThreadCount.h): the one meaning of every `Threads` option of Core, checked
// against OpenMP's own answer and under a changed OpenMP default.
#include "ThreadCount.h"

#include <gtest/gtest.h>

#include <omp.h>

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

} // namespace vis4gs

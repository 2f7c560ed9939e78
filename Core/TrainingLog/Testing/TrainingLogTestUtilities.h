// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TrainingLogTestUtilities.h
 * @brief Deterministic synthetic clouds and temporary paths for the training-log tests.
 */
#ifndef vis4gs_TrainingLogTestUtilities_h
#define vis4gs_TrainingLogTestUtilities_h

#include "GaussianCloud.h"

#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <unistd.h>
#include <vector>

namespace vis4gs
{
namespace testing
{

/// A unique path in /tmp for this process and @p tag.
inline std::string TempLogPath(const std::string& tag)
{
  return "/tmp/vis4gs_trainlog_" + std::to_string(::getpid()) + "_" + tag + ".h5";
}

/// A cloud whose every value is a function of (seed, row), with the given ids.
inline GaussianCloud MakeCloud(const std::vector<std::int64_t>& ids, int shDegree, unsigned seed)
{
  GaussianCloud c;
  c.Resize(ids.size(), shDegree);
  c.Ids = ids;
  std::mt19937 rng(seed);
  std::normal_distribution<float> normal(0.f, 1.f);
  for (float& v : c.Positions)
  {
    v = normal(rng);
  }
  for (float& v : c.LogScales)
  {
    v = normal(rng) - 4.f;
  }
  for (float& v : c.Rotations)
  {
    v = normal(rng);
  }
  for (float& v : c.OpacityLogits)
  {
    v = normal(rng);
  }
  for (float& v : c.SH)
  {
    v = 0.3f * normal(rng);
  }
  return c;
}

/// Ids 0..n-1 with a fraction removed and some new ids past @p firstNew appended.
inline std::vector<std::int64_t> MakeIds(std::size_t n, std::int64_t firstNew, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<std::int64_t> ids;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (u(rng) > 0.2)
    {
      ids.push_back(static_cast<std::int64_t>(i));
    }
  }
  std::int64_t next = firstNew;
  while (ids.size() < n)
  {
    next += 1 + static_cast<std::int64_t>(u(rng) * 3);
    ids.push_back(next);
  }
  return ids;
}

} // namespace testing
} // namespace vis4gs

#endif

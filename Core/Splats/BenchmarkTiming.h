// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BenchmarkTiming.h
 * @brief Timing helper shared by the benchmark programs of the Gaussian analysis view
 * (Core/Splats, Core/Selection): median wall time and median process CPU time of repeated
 * runs. Header only; not used by the libraries.
 */
#ifndef vis4gs_BenchmarkTiming_h
#define vis4gs_BenchmarkTiming_h

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <functional>
#include <vector>

namespace vis4gs
{

/// Runs a callable repeatedly and keeps the medians of the last TimeMs() call.
class BenchmarkTimer
{
public:
  /// Median wall milliseconds of @p repeats runs of @p f (at least one run); the median CPU
  /// milliseconds of all threads go to LastCpuMs: on 2 otherwise idle cores a run takes at
  /// least half of it, whatever else the machine is doing.
  double TimeMs(int repeats, const std::function<void()>& f)
  {
    std::vector<double> t, c;
    for (int r = 0; r < std::max(1, repeats); ++r)
    {
      const std::clock_t c0 = std::clock();
      const auto a = std::chrono::steady_clock::now();
      f();
      const auto b = std::chrono::steady_clock::now();
      c.push_back(1000.0 * static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
      t.push_back(std::chrono::duration<double, std::milli>(b - a).count());
    }
    std::sort(t.begin(), t.end());
    std::sort(c.begin(), c.end());
    this->LastCpuMs = c[c.size() / 2];
    return t[t.size() / 2];
  }

  /// Median CPU milliseconds (all threads) of the last TimeMs() call.
  double LastCpuMs = 0;
};

/// Prints the load average (figures taken on a busy machine say so).
inline void PrintLoadAverage()
{
  if (std::FILE* f = std::fopen("/proc/loadavg", "r"))
  {
    char line[128] = { 0 };
    if (std::fgets(line, sizeof(line), f))
    {
      std::printf("  load average at start: %s", line);
    }
    std::fclose(f);
  }
}

} // namespace vis4gs

#endif

// SPDX-License-Identifier: BSD-3-Clause
// Per-frame CPU work of the GPU splat renderer at N Gaussians: view depths, back-to-front
// sort (parallel radix vs std::sort), SH colours per degree, geometry packing, display colours.
// Usage: BenchmarkSplats [count=1000000] [threads=2] [repeats=5]
#include "BenchmarkScene.h"
#include "BenchmarkTiming.h"
#include "SplatAttributes.h"
#include "SplatSort.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

int main(int argc, char* argv[])
{
  vis4gs::BenchmarkTimer timer;
  const std::size_t n = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 1000000;
  const int threads = argc > 2 ? std::atoi(argv[2]) : 2;
  const int repeats = argc > 3 ? std::atoi(argv[3]) : 5;
  std::printf(
    "BenchmarkSplats: %zu Gaussians, %d threads, median of %d runs\n", n, threads, repeats);
  const auto cloud = vis4gs::MakeBenchmarkScene(n, 3, 1);
  const auto cam = vis4gs::MakeBenchmarkCamera(1280, 720, 0.4);
  std::vector<float> depths, packed, rgb, rgba;
  std::vector<std::uint8_t> keep;
  std::vector<std::uint32_t> order;
  double t = timer.TimeMs(repeats,
    [&]
    { vis4gs::ComputeViewDepths(cloud.Positions.data(), n, cam.WorldToCamera, depths, threads); });
  std::printf("  view depths              %8.2f ms (CPU %7.1f ms)\n", t, timer.LastCpuMs);
  vis4gs::SplatSortOptions o;
  o.Threads = threads;
  t = timer.TimeMs(repeats, [&] { vis4gs::SortBackToFront(depths, order, o); });
  std::printf("  radix sort (%d threads)   %8.2f ms (CPU %7.1f ms)  (%zu drawn)\n",
    threads,
    t,
    timer.LastCpuMs,
    order.size());
  o.Threads = 1;
  t = timer.TimeMs(repeats, [&] { vis4gs::SortBackToFront(depths, order, o); });
  std::printf("  radix sort (1 thread)    %8.2f ms (CPU %7.1f ms)\n", t, timer.LastCpuMs);
  t = timer.TimeMs(repeats, [&] { vis4gs::SortBackToFrontStd(depths, order); });
  std::printf("  std::sort baseline       %8.2f ms (CPU %7.1f ms)\n", t, timer.LastCpuMs);
  for (int d = 0; d <= 3; ++d)
  {
    t = timer.TimeMs(
      repeats, [&] { vis4gs::EvaluateSplatColors(cloud, cam.Center(), d, rgb, threads); });
    std::printf("  SH colours degree %d      %8.2f ms (CPU %7.1f ms)\n", d, t, timer.LastCpuMs);
  }
  t = timer.TimeMs(repeats, [&] { vis4gs::PackSplatGeometry(cloud, 1.0, packed, threads); });
  std::printf("  pack geometry (once)     %8.2f ms (CPU %7.1f ms)\n", t, timer.LastCpuMs);
  std::vector<double> scores(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    scores[i] = (i % 1000) / 1000.0;
  }
  vis4gs::SplatDisplayOptions disp;
  disp.ScoreColoring = true;
  disp.Scores = scores.data();
  t = timer.TimeMs(
    repeats, [&] { vis4gs::ComputeSplatDisplay(rgb.data(), n, disp, rgba, keep, threads); });
  std::printf("  display colours (score)  %8.2f ms (CPU %7.1f ms)\n", t, timer.LastCpuMs);
  return 0;
}

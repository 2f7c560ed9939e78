// SPDX-License-Identifier: BSD-3-Clause
// Selection latency per mode at N Gaussians (synthetic scene, 1280x720 view).
// Usage: BenchmarkSelection [count=1000000] [threads=2] [repeats=5]
#include "GaussianOctree.h"
#include "ScreenSelection.h"
#include "SyntheticScene.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <vector>

namespace
{
// Median CPU time (all threads) of the last TimeMs() call: on 2 otherwise idle cores a run
// takes at least half of it, whatever else the machine is doing.
double LastCpuMs = 0;

double TimeMs(int repeats, const std::function<void()>& f)
{
  std::vector<double> t, c;
  for (int r = 0; r < repeats; ++r)
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
  LastCpuMs = c[c.size() / 2];
  return t[t.size() / 2];
}
}

int main(int argc, char* argv[])
{
  using namespace vis4gs;
  const std::size_t n = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 1000000;
  const int threads = argc > 2 ? std::atoi(argv[2]) : 2;
  const int repeats = argc > 3 ? std::atoi(argv[3]) : 5;
  std::printf("BenchmarkSelection: %zu Gaussians, 1280x720, %d threads, median of %d runs\n",
    n,
    threads,
    repeats);
  const auto cloud = MakeSyntheticScene(n, 0, 1);
  const auto cam = MakeSyntheticCamera(1280, 720, 0.4);
  SelectionView view;
  double t = TimeMs(repeats, [&] { view = PrepareSelectionView(cloud, cam, threads); });
  std::printf(
    "  prepare view (project+bin, once per camera) %8.2f ms (CPU %7.1f ms)\n", t, LastCpuMs);
  std::int64_t single = -1;
  t = TimeMs(repeats, [&] { single = SelectSingle(view, 640, 360); });
  std::printf(
    "  Single                                      %8.3f ms (CPU %7.1f ms)  (index %lld)\n",
    t,
    LastCpuMs,
    static_cast<long long>(single));
  const auto brush = BrushPixels({ { 500, 300 }, { 700, 420 } }, 10.0, 1280, 720);
  std::vector<std::uint32_t> sel;
  t = TimeMs(repeats, [&] { sel = SelectBrush(view, brush, 0.01, threads); });
  std::printf(
    "  Brush (%zu px stroke)                     %8.2f ms (CPU %7.1f ms)  (%zu selected)\n",
    brush.size(),
    t,
    LastCpuMs,
    sel.size());
  FrameOptions fo;
  fo.Threads = threads;
  for (int half : { 100, 640 })
  {
    const int x0 = 640 - half, x1 = 640 + half - 1, y0 = std::max(0, 360 - half),
              y1 = std::min(719, 360 + half - 1);
    fo.IncludeOccluded = false;
    t = TimeMs(repeats, [&] { sel = SelectFrame(view, x0, y0, x1, y1, fo); });
    std::printf(
      "  Frame %4dx%-4d visible                      %8.2f ms (CPU %7.1f ms)  (%zu selected)\n",
      x1 - x0 + 1,
      y1 - y0 + 1,
      t,
      LastCpuMs,
      sel.size());
    fo.IncludeOccluded = true;
    t = TimeMs(repeats, [&] { sel = SelectFrame(view, x0, y0, x1, y1, fo); });
    std::printf(
      "  Frame %4dx%-4d with occluded                %8.2f ms (CPU %7.1f ms)  (%zu selected)\n",
      x1 - x0 + 1,
      y1 - y0 + 1,
      t,
      LastCpuMs,
      sel.size());
  }
  {
    // The straightforward implementation: attribute every pixel of the 200x200 frame, rank.
    std::vector<std::array<int, 2>> px;
    for (int y = 260; y < 460; ++y)
    {
      for (int x = 540; x < 740; ++x)
      {
        px.push_back({ x, y });
      }
    }
    std::size_t visible = 0;
    t = TimeMs(1,
      [&]
      {
        const auto ranked =
          RankContributors(AttributePixels<float>(view.Projection, view.Bins, view.Settings, px));
        visible = ranked.size();
      });
    std::printf(
      "  Frame  200x200  baseline (AttributePixels)  %8.2f ms (CPU %7.1f ms)  (%zu contributors)\n",
      t,
      LastCpuMs,
      visible);
  }
  GaussianOctree tree;
  t = TimeMs(1, [&] { tree.Build(cloud); });
  std::printf("  octree build (once per scene)               %8.2f ms (CPU %7.1f ms)  (%zu nodes, "
              "depth %d)\n",
    t,
    LastCpuMs,
    tree.GetNodeCount(),
    tree.GetDepth());
  std::vector<RayHit> hits;
  for (int k = 0; k < 3; ++k)
  {
    const auto ray = PixelRay(cam, 440 + 200 * k, 300 + 40 * k, 3.0);
    t = TimeMs(repeats, [&] { hits = tree.IntersectRay(ray); });
    std::printf("  Ray %d (octree)                              %8.3f ms (CPU %7.1f ms)  (%zu "
                "hits, %zu box tests)\n",
      k,
      t,
      LastCpuMs,
      hits.size(),
      tree.GetLastBoxTests());
  }
  const auto ray = PixelRay(cam, 640, 340, 3.0);
  t = TimeMs(1, [&] { hits = IntersectRayBruteForce(cloud, ray); });
  std::printf("  Ray (brute force, baseline)                 %8.2f ms (CPU %7.1f ms)  (%zu hits)\n",
    t,
    LastCpuMs,
    hits.size());
  return 0;
}

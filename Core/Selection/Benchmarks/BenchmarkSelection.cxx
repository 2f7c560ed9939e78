// SPDX-License-Identifier: BSD-3-Clause
// Selection latency per mode at N Gaussians (synthetic scene, 1280x720 view).
// Usage: BenchmarkSelection [count=1000000] [threads=2] [repeats=5] [record]
#include "BenchmarkScene.h"
#include "BenchmarkTiming.h"
#include "GaussianOctree.h"
#include "ScreenSelection.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

int main(int argc, char* argv[])
{
  vis4gs::BenchmarkTimer timer;
  using namespace vis4gs;
  const std::size_t n = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 1000000;
  const int threads = argc > 2 ? std::atoi(argv[2]) : 2;
  const int repeats = argc > 3 ? std::atoi(argv[3]) : 5;
  // "record": stop after the kept blends' figures (the other cases replay whole views).
  const bool recordOnly = argc > 4 && std::string(argv[4]) == "record";
  std::printf("BenchmarkSelection: %zu Gaussians, 1280x720, %d threads, median of %d runs\n",
    n,
    threads,
    repeats);
  PrintLoadAverage();
  const auto cloud = MakeBenchmarkScene(n, 0, 1);
  const auto cam = MakeBenchmarkCamera(1280, 720, 0.4);
  SelectionView view;
  double t = timer.TimeMs(repeats, [&] { view = PrepareSelectionView(cloud, cam, threads); });
  std::printf(
    "  prepare view (project+bin, once per camera) %8.2f ms (CPU %7.1f ms)\n", t, timer.LastCpuMs);
  std::int64_t single = -1;
  t = timer.TimeMs(repeats, [&] { single = SelectSingle(view, 640, 360); });
  std::printf(
    "  Single                                      %8.3f ms (CPU %7.1f ms)  (index %lld)\n",
    t,
    timer.LastCpuMs,
    static_cast<long long>(single));
  const auto brush = BrushPixels({ { 500, 300 }, { 700, 420 } }, 10.0, 1280, 720);
  std::vector<std::uint32_t> sel;
  t = timer.TimeMs(repeats, [&] { sel = SelectBrush(view, brush, 0.01, threads); });
  std::printf(
    "  Brush (%zu px stroke)                     %8.2f ms (CPU %7.1f ms)  (%zu selected)\n",
    brush.size(),
    t,
    timer.LastCpuMs,
    sel.size());
  // Once per camera: every Gaussian's largest weight over the view (one compositing pass).
  SelectionView cached = view;
  t = timer.TimeMs(repeats, [&] { ComputeViewMaxWeights(cached); });
  std::printf(
    "  view maxima (once per camera, cached)       %8.2f ms (CPU %7.1f ms)\n", t, timer.LastCpuMs);
  // The scene view's still frame for this camera (what vtkGaussianSplatMapper's CPU path
  // keeps): projection with colours, tile lists, compositing.
  RasterWorkspace<float> frame;
  {
    RasterSettings drawn;
    drawn.Threads = threads;
    t = timer.TimeMs(1, [&] { Rasterize<float>(cloud, cam, drawn, frame); });
    std::printf("  scene view's full frame (for reference)     %8.2f ms (CPU %7.1f ms)\n",
      t,
      timer.LastCpuMs);
  }
  {
    // The blends the scene view's exact frame keeps for Brush and Frame (PixelWeightRecord):
    // its cost on the compositing, its size, and the lookups against the replays on the same
    // drawn frame (the straightforward path, what the selector did before).
    RasterSettings drawn;
    drawn.Threads = threads;
    RasterImage<float> image;
    t = timer.TimeMs(
      repeats, [&] { CompositeTiles<float>(frame.Projection, frame.Bins, drawn, image); });
    std::printf("  record: compositing of the frame, plain     %8.2f ms (CPU %7.1f ms)\n",
      t,
      timer.LastCpuMs);
    PixelWeightRecord record;
    t = timer.TimeMs(repeats,
      [&]
      {
        CompositeTiles<float>(
          frame.Projection, frame.Bins, drawn, image, nullptr, nullptr, nullptr, true, &record);
      });
    std::printf("  record: compositing keeping w >= %.2f       %8.2f ms (CPU %7.1f ms)  (%zu "
                "blends, %.1f MiB, %.1f a pixel, complete %d)\n",
      static_cast<double>(record.Threshold),
      t,
      timer.LastCpuMs,
      record.Entries(),
      9.0 * static_cast<double>(record.Entries()) / (1 << 20),
      static_cast<double>(record.Entries()) / (1280.0 * 720.0),
      record.Complete ? 1 : 0);
    const std::size_t count = frame.Projection.Gaussians.size();
    std::vector<std::uint32_t> replayed, looked;
    t = timer.TimeMs(
      repeats, [&] { replayed = SelectBrush(frame.Projection, frame.Bins, brush, 0.01, threads); });
    std::printf("  record: Brush, replay on the drawn frame    %8.2f ms (CPU %7.1f ms)  (%zu "
                "selected)\n",
      t,
      timer.LastCpuMs,
      replayed.size());
    t = timer.TimeMs(repeats, [&] { looked = SelectBrush(record, count, brush, 0.01); });
    std::printf(
      "  record: Brush, lookup                       %8.2f ms (CPU %7.1f ms)  (%zu selected, %s)\n",
      t,
      timer.LastCpuMs,
      looked.size(),
      looked == replayed ? "same selection" : "DIFFERENT SELECTION");
    FrameOptions rf;
    rf.Threads = threads;
    for (int half : { 100, 640 })
    {
      const int x0 = 640 - half, x1 = 640 + half - 1, y0 = std::max(0, 360 - half),
                y1 = std::min(719, 360 + half - 1);
      t = timer.TimeMs(
        repeats, [&] { replayed = SelectFrame(frame.Projection, frame.Bins, x0, y0, x1, y1, rf); });
      std::printf("  record: Frame %4dx%-4d, culled replay      %8.2f ms (CPU %7.1f ms)  (%zu "
                  "selected)\n",
        x1 - x0 + 1,
        y1 - y0 + 1,
        t,
        timer.LastCpuMs,
        replayed.size());
      t = timer.TimeMs(
        repeats, [&] { looked = SelectFrame(frame.Projection, record, x0, y0, x1, y1, rf); });
      std::printf("  record: Frame %4dx%-4d, lookup             %8.2f ms (CPU %7.1f ms)  (%zu "
                  "selected, %s)\n",
        x1 - x0 + 1,
        y1 - y0 + 1,
        t,
        timer.LastCpuMs,
        looked.size(),
        looked == replayed ? "same selection" : "DIFFERENT SELECTION");
    }
    if (recordOnly)
    {
      return 0;
    }
  }
  {
    // Single and Brush right after a camera move: before, project + bin first; now on the
    // drawn frame.
    std::vector<std::uint32_t> other;
    t = timer.TimeMs(repeats,
      [&]
      {
        const SelectionView fresh = PrepareSelectionView(cloud, cam, threads);
        single = SelectSingle(fresh, 640, 360);
        other = SelectBrush(fresh, brush, 0.01, threads);
      });
    std::printf("  first Single + Brush after camera move: prepare + select (before) %8.2f ms "
                "(CPU %7.1f ms)\n",
      t,
      timer.LastCpuMs);
    t = timer.TimeMs(repeats,
      [&]
      {
        single = SelectSingle(frame.Projection, frame.Bins, 640, 360);
        other = SelectBrush(frame.Projection, frame.Bins, brush, 0.01, threads);
      });
    std::printf("  first Single + Brush after camera move: drawn frame reused  %8.2f ms (CPU "
                "%7.1f ms)  (%s)\n",
      t,
      timer.LastCpuMs,
      other == sel ? "same Brush selection" : "DIFFERENT SELECTION");
  }
  FrameOptions fo;
  fo.Threads = threads;
  for (int half : { 100, 640 })
  {
    const int x0 = 640 - half, x1 = 640 + half - 1, y0 = std::max(0, 360 - half),
              y1 = std::min(719, 360 + half - 1);
    fo.IncludeOccluded = false;
    fo.CullReplay = false;
    t = timer.TimeMs(repeats, [&] { sel = SelectFrame(view, x0, y0, x1, y1, fo); });
    std::printf("  Frame %4dx%-4d visible, straightforward replay %8.2f ms (CPU %7.1f ms)  (%zu "
                "selected)\n",
      x1 - x0 + 1,
      y1 - y0 + 1,
      t,
      timer.LastCpuMs,
      sel.size());
    fo.CullReplay = true;
    {
      std::vector<std::uint32_t> other;
      t = timer.TimeMs(repeats, [&] { other = SelectFrame(view, x0, y0, x1, y1, fo); });
      std::printf("  Frame %4dx%-4d visible, culled replay        %8.2f ms (CPU %7.1f ms)  (%zu "
                  "selected, %s)\n",
        x1 - x0 + 1,
        y1 - y0 + 1,
        t,
        timer.LastCpuMs,
        other.size(),
        other == sel ? "same selection" : "DIFFERENT SELECTION");
      // First visible-only frame right after a camera move. Before: project + bin for the
      // selection, then replay every pixel of the rectangle. Now: the scene view has just
      // drawn the still frame for this camera (a full-resolution RasterWorkspace, colours
      // included); its projection and tile lists are reused and the replay is culled.
      fo.CullReplay = false;
      t = timer.TimeMs(repeats,
        [&]
        {
          const SelectionView fresh = PrepareSelectionView(cloud, cam, threads);
          other = SelectFrame(fresh, x0, y0, x1, y1, fo);
        });
      fo.CullReplay = true;
      std::printf("  first after camera move: prepare + straightforward replay (before) %8.2f ms "
                  "(CPU %7.1f ms)  (%s)\n",
        t,
        timer.LastCpuMs,
        other == sel ? "same selection" : "DIFFERENT SELECTION");
      t = timer.TimeMs(repeats,
        [&]
        {
          const SelectionView fresh = PrepareSelectionView(cloud, cam, threads);
          other = SelectFrame(fresh, x0, y0, x1, y1, fo);
        });
      std::printf("  first after camera move: prepare + culled replay              %8.2f ms "
                  "(CPU %7.1f ms)  (%s)\n",
        t,
        timer.LastCpuMs,
        other == sel ? "same selection" : "DIFFERENT SELECTION");
      t = timer.TimeMs(
        repeats, [&] { other = SelectFrame(frame.Projection, frame.Bins, x0, y0, x1, y1, fo); });
      std::printf("  first after camera move: drawn frame reused + culled replay   %8.2f ms "
                  "(CPU %7.1f ms)  (%s)\n",
        t,
        timer.LastCpuMs,
        other == sel ? "same selection" : "DIFFERENT SELECTION");
      // What vtkGaussianSelector does for a rectangle of half the view or more: the drawn
      // frame copied into its view, the view maxima, then the cached path.
      t = timer.TimeMs(repeats,
        [&]
        {
          SelectionView adopted;
          adopted.Projection = frame.Projection;
          adopted.Bins = frame.Bins;
          adopted.Settings.ComputeColors = false;
          adopted.Settings.Threads = threads;
          ComputeViewMaxWeights(adopted);
          other = SelectFrame(adopted, x0, y0, x1, y1, fo);
        });
      std::printf("  first after camera move: drawn frame copied + view maxima     %8.2f ms "
                  "(CPU %7.1f ms)  (%s)\n",
        t,
        timer.LastCpuMs,
        other == sel ? "same selection" : "DIFFERENT SELECTION");
    }
    if (!cached.ViewMaxWeights.empty())
    {
      std::vector<std::uint32_t> fast;
      t = timer.TimeMs(repeats, [&] { fast = SelectFrame(cached, x0, y0, x1, y1, fo); });
      std::printf("  Frame %4dx%-4d visible, view maxima cached  %8.2f ms (CPU %7.1f ms)  (%zu "
                  "selected, %s)\n",
        x1 - x0 + 1,
        y1 - y0 + 1,
        t,
        timer.LastCpuMs,
        fast.size(),
        fast == sel ? "same selection" : "DIFFERENT SELECTION");
    }
    fo.IncludeOccluded = true;
    t = timer.TimeMs(repeats, [&] { sel = SelectFrame(view, x0, y0, x1, y1, fo); });
    std::printf(
      "  Frame %4dx%-4d with occluded                %8.2f ms (CPU %7.1f ms)  (%zu selected)\n",
      x1 - x0 + 1,
      y1 - y0 + 1,
      t,
      timer.LastCpuMs,
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
    t = timer.TimeMs(1,
      [&]
      {
        const auto ranked =
          RankContributors(AttributePixels<float>(view.Projection, view.Bins, view.Settings, px));
        visible = ranked.size();
      });
    std::printf(
      "  Frame  200x200  baseline (AttributePixels)  %8.2f ms (CPU %7.1f ms)  (%zu contributors)\n",
      t,
      timer.LastCpuMs,
      visible);
  }
  GaussianOctree tree;
  t = timer.TimeMs(1, [&] { tree.Build(cloud); });
  std::printf("  octree build (once per scene)               %8.2f ms (CPU %7.1f ms)  (%zu nodes, "
              "depth %d)\n",
    t,
    timer.LastCpuMs,
    tree.GetNodeCount(),
    tree.GetDepth());
  std::vector<RayHit> hits;
  for (int k = 0; k < 3; ++k)
  {
    const auto ray = PixelRay(cam, 440 + 200 * k, 300 + 40 * k, 3.0);
    t = timer.TimeMs(repeats, [&] { hits = tree.IntersectRay(ray); });
    std::printf("  Ray %d (octree)                              %8.3f ms (CPU %7.1f ms)  (%zu "
                "hits, %zu box tests)\n",
      k,
      t,
      timer.LastCpuMs,
      hits.size(),
      tree.GetLastBoxTests());
  }
  const auto ray = PixelRay(cam, 640, 340, 3.0);
  t = timer.TimeMs(1, [&] { hits = IntersectRayBruteForce(cloud, ray); });
  std::printf("  Ray (brute force, baseline)                 %8.2f ms (CPU %7.1f ms)  (%zu hits)\n",
    t,
    timer.LastCpuMs,
    hits.size());
  return 0;
}

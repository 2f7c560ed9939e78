// SPDX-License-Identifier: BSD-3-Clause
// Cost of the before/after measurement of a clean-up (issue 20) next to the plain render:
// a synthetic scene of N Gaussians (Core/Splats/BenchmarkScene.h), V views around it, targets
// rendered from another scene of the same kind, selections made by rules and a local blob.
// Rows: the plain render; the "before" of a view from the score pass (what measuring its render
// per tile adds: the marginal cost of RecordRemovalBaseline, and a full-resolution score pass
// of one view with and without it); the "before" rendered on its own; per selection, the
// "after" re-rendered whole vs with tile reuse (the figures must agree bit for bit).
// Usage: BenchmarkRemovalEffect [count=1000000] [views=4] [width=1920] [height=1080]
//        [threads=2] [repeats=3] [sh-degree=3] [score-pass=1]
#include "BenchmarkScene.h"
#include "BenchmarkTiming.h"
#include "Loss.h"
#include "RemovalEffect.h"
#include "SelectionRule.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

int main(int argc, char* argv[])
{
  using namespace vis4gs;
  const std::size_t n = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 1000000;
  const int views = argc > 2 ? std::atoi(argv[2]) : 4;
  const int width = argc > 3 ? std::atoi(argv[3]) : 1920;
  const int height = argc > 4 ? std::atoi(argv[4]) : 1080;
  const int threads = argc > 5 ? std::atoi(argv[5]) : 2;
  const int repeats = argc > 6 ? std::atoi(argv[6]) : 3;
  const int degree = argc > 7 ? std::atoi(argv[7]) : 3;
  const bool scorePass = argc > 8 ? std::atoi(argv[8]) != 0 : true;
  std::printf("BenchmarkRemovalEffect: %zu Gaussians (SH degree %d), %d views of %dx%d, %d "
              "threads, median of %d runs\n",
    n,
    degree,
    views,
    width,
    height,
    threads,
    repeats);
  PrintLoadAverage();
  const GaussianCloud cloud = MakeBenchmarkScene(n, degree, 1);
  std::vector<Camera> cameras;
  std::vector<Image> targets;
  RasterSettings raster;
  raster.Threads = threads;
  {
    const GaussianCloud other = MakeBenchmarkScene(n, degree, 2);
    for (int v = 0; v < views; ++v)
    {
      cameras.push_back(MakeBenchmarkCamera(width, height, 2.0 * M_PI * v / views));
      cameras.back().Name = "view" + std::to_string(v);
      cameras.back().Split = v % 4 == 3 ? CameraSplit::Test : CameraSplit::Train;
      Image target = ClampedImage(Rasterize<float>(other, cameras.back(), raster));
      targets.push_back(std::move(target));
    }
  }
  const TrainingImageProvider images = [&targets](std::size_t v, const Camera&, Image& image)
  {
    image = targets[v];
    return true;
  };
  BenchmarkTimer timer;

  RasterWorkspace<float> workspace;
  double t = timer.TimeMs(repeats,
    [&]
    {
      for (const Camera& c : cameras)
      {
        Rasterize(cloud, c, raster, workspace);
      }
    });
  const double render = t / views;
  std::printf("  plain render, per view                       %9.1f ms (CPU %8.1f ms)\n",
    render,
    timer.LastCpuMs / views);
  std::vector<float> clamped(workspace.Image.Color);
  t = timer.TimeMs(repeats,
    [&]
    {
      volatile double sink = Psnr(clamped.data(), targets.back().Pixels.data(), clamped.size()) +
        Ssim(clamped.data(), targets.back().Pixels.data(), width, height, threads) +
        L1Loss(clamped.data(), targets.back().Pixels.data(), clamped.size());
      (void)sink;
    });
  std::printf(
    "  PSNR + SSIM + L1 of one view                 %9.1f ms (CPU %8.1f ms)\n", t, timer.LastCpuMs);

  t = timer.TimeMs(repeats,
    [&]
    {
      volatile double sink = MeasureViewTiles(
        workspace.Image.Color.data(), targets.back().Pixels.data(), width, height, threads)
                               .Metrics()
                               .Psnr;
      (void)sink;
    });
  const double tiles = t;
  std::printf("  before from the score pass: per-tile figures of its render (marginal) %9.1f ms "
              "(CPU %8.1f ms)  %.2fx a plain render\n",
    t,
    timer.LastCpuMs,
    t / render);

  RemovalEffectOptions options;
  options.Threads = threads;
  options.Raster = raster;
  if (scorePass)
  {
    // One training view's full-resolution blur pass, without and with the baseline recorded.
    ScoreSettings settings;
    settings.Request = { false, true, false, false };
    settings.ViewList = { 0 };
    settings.Threads = threads;
    settings.Raster = raster;
    double plainCpu = 0;
    t = timer.TimeMs(1, [&] { ComputeGaussianScores(cloud, cameras, settings, images); });
    plainCpu = timer.LastCpuMs;
    std::printf(
      "  score pass (blur, full resolution), one view %9.1f ms (CPU %8.1f ms)\n", t, plainCpu);
    // The trade-off: the 1/4-resolution pass of the score target cannot give the "before".
    ScoreSettings quarter = settings;
    quarter.LossResolution = 4;
    t = timer.TimeMs(1, [&] { ComputeGaussianScores(cloud, cameras, quarter, images); });
    std::printf("  score pass (blur, 1/4 resolution), one view  %9.1f ms (CPU %8.1f ms)\n",
      t,
      timer.LastCpuMs);
    RemovalBaseline recorded;
    RecordRemovalBaseline(settings, cloud, cameras, recorded);
    GaussianScores scores;
    t = timer.TimeMs(1, [&] { scores = ComputeGaussianScores(cloud, cameras, settings, images); });
    std::printf("  the same, recording the before               %9.1f ms (CPU %8.1f ms)  hook "
                "%.1f ms: +%.2fx a plain render instead of +%.2fx rendering it again\n",
      t,
      timer.LastCpuMs,
      1000.0 * scores.Timings.ViewHook,
      1000.0 * scores.Timings.ViewHook / render,
      (render + tiles) / render);
  }

  std::vector<ViewMetrics> baseline;
  RemovalBaseline tileBaseline;
  t =
    timer.TimeMs(repeats, [&] { baseline = MeasureViewMetrics(cloud, cameras, options, images); });
  std::printf("  before figures rendered on their own, per view %7.1f ms (CPU %8.1f ms)  %.2fx "
              "a plain render\n",
    t / views,
    timer.LastCpuMs / views,
    t / views / render);
  tileBaseline = MeasureRemovalBaseline(cloud, cameras, options, images);
  std::size_t tileBytes = 0;
  for (const ViewTileSums& v : tileBaseline.Views)
  {
    tileBytes += v.Sums.size() * sizeof(double);
  }
  std::printf("  per-tile before: %.1f KB per view\n", tileBytes / 1024.0 / views);

  SelectionRuleInputs in;
  in.Cloud = &cloud;
  in.Threads = threads;
  struct Selection
  {
    std::string Name;
    std::vector<std::uint8_t> Mask;
  };
  std::vector<Selection> selections;
  for (const char* text : { "scale bottom 0.01%", "scale top 0.1%", "opacity<0.1 and scale>0.01" })
  {
    const SelectionRule rule = SelectionRule::Parse(text);
    t = timer.TimeMs(1, [&] { selections.push_back({ text, rule.Evaluate(in) }); });
    std::printf("  rule '%s' evaluated in %.1f ms (CPU %.1f ms)\n", text, t, timer.LastCpuMs);
  }
  {
    // A local clean-up: every Gaussian within 0.15 of a point on the sphere.
    Selection blob{ "blob r=0.15 at (0.6, -0.2, 0.77)", std::vector<std::uint8_t>(cloud.Count, 0) };
    for (std::size_t i = 0; i < cloud.Count; ++i)
    {
      const float dx = cloud.Positions[3 * i] - 0.6f, dy = cloud.Positions[3 * i + 1] + 0.2f,
                  dz = cloud.Positions[3 * i + 2] - 0.77f;
      blob.Mask[i] = dx * dx + dy * dy + dz * dz < 0.15f * 0.15f ? 1 : 0;
    }
    selections.push_back(std::move(blob));
  }
  for (const Selection& sel : selections)
  {
    std::size_t count = 0;
    for (std::uint8_t m : sel.Mask)
    {
      count += m;
    }
    std::printf("  selection '%s': %zu Gaussians\n", sel.Name.c_str(), count);
    if (count == 0)
    {
      continue;
    }
    RemovalEffect whole, reused;
    options.Baseline = baseline;
    options.TileBaseline = {};
    options.ReuseTiles = false;
    t = timer.TimeMs(
      repeats, [&] { whole = MeasureRemovalEffect(cloud, sel.Mask, cameras, options, images); });
    std::printf("    after, whole re-render, per view           %9.1f ms (CPU %8.1f ms)  %.2fx a "
                "plain render; %zu of %d views changed; train PSNR %.4f -> %.4f dB\n",
      t / views,
      timer.LastCpuMs / views,
      t / views / render,
      whole.Train.AffectedViews + whole.Test.AffectedViews,
      views,
      whole.Train.Before.Psnr,
      whole.Train.After.Psnr);
    options.Baseline.clear();
    options.TileBaseline = tileBaseline;
    options.ReuseTiles = true;
    t = timer.TimeMs(
      repeats, [&] { reused = MeasureRemovalEffect(cloud, sel.Mask, cameras, options, images); });
    double diff = 0;
    for (std::size_t v = 0; v < whole.Views.size(); ++v)
    {
      diff = std::max({ diff,
        std::abs(whole.Views[v].After.Psnr - reused.Views[v].After.Psnr),
        std::abs(whole.Views[v].After.Ssim - reused.Views[v].After.Ssim),
        std::abs(whole.Views[v].After.L1 - reused.Views[v].After.L1) });
    }
    std::printf("    after, tile reuse, per view                %9.1f ms (CPU %8.1f ms)  %.2fx a "
                "plain render; %zu of %zu tiles of the changed views re-rendered (%.1f%%); "
                "largest difference to the whole re-render %g\n",
      t / views,
      timer.LastCpuMs / views,
      t / views / render,
      reused.TilesRendered,
      reused.TilesOfTiledViews,
      reused.TilesOfTiledViews ? 100.0 * reused.TilesRendered / reused.TilesOfTiledViews : 0.0,
      diff);
  }
  return 0;
}

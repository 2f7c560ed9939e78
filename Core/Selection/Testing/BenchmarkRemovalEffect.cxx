// SPDX-License-Identifier: BSD-3-Clause
// Cost of the before/after measurement of a clean-up (issue 20) next to the plain render:
// a synthetic scene of N Gaussians (Core/Splats/BenchmarkScene.h), V views around it, targets
// rendered from another scene of the same kind, selections made by rules.
// Usage: BenchmarkRemovalEffect [count=1000000] [views=4] [width=1920] [height=1080]
//        [threads=2] [repeats=3] [sh-degree=3]
#include "BenchmarkScene.h"
#include "BenchmarkTiming.h"
#include "Loss.h"
#include "RemovalEffect.h"
#include "SelectionRule.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
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

  RemovalEffectOptions options;
  options.Threads = threads;
  options.Raster = raster;
  std::vector<ViewMetrics> baseline;
  t =
    timer.TimeMs(repeats, [&] { baseline = MeasureViewMetrics(cloud, cameras, options, images); });
  std::printf("  before figures (baseline), per view          %9.1f ms (CPU %8.1f ms)  %.2fx "
              "a plain render\n",
    t / views,
    timer.LastCpuMs / views,
    t / views / render);

  SelectionRuleInputs in;
  in.Cloud = &cloud;
  in.Threads = threads;
  for (const char* text : { "opacity<0.1 and scale>0.01", "scale top 0.1%", "isolated r=0.01" })
  {
    const SelectionRule rule = SelectionRule::Parse(text);
    std::vector<std::uint8_t> mask;
    t = timer.TimeMs(repeats, [&] { mask = rule.Evaluate(in); });
    std::size_t count = 0;
    for (std::uint8_t m : mask)
    {
      count += m;
    }
    std::printf(
      "  rule '%s': %zu selected in %.1f ms (CPU %.1f ms)\n", text, count, t, timer.LastCpuMs);
    if (count == 0)
    {
      continue;
    }
    RemovalEffect effect;
    options.Baseline.clear();
    t = timer.TimeMs(
      repeats, [&] { effect = MeasureRemovalEffect(cloud, mask, cameras, options, images); });
    std::printf("    before+after, per view                     %9.1f ms (CPU %8.1f ms)  %.2fx a "
                "plain render; %zu of %d views changed; train PSNR %.4f -> %.4f dB\n",
      t / views,
      timer.LastCpuMs / views,
      t / views / render,
      effect.Train.AffectedViews + effect.Test.AffectedViews,
      views,
      effect.Train.Before.Psnr,
      effect.Train.After.Psnr);
    options.Baseline = baseline;
    t = timer.TimeMs(
      repeats, [&] { effect = MeasureRemovalEffect(cloud, mask, cameras, options, images); });
    std::printf("    after only (baseline reused), per view     %9.1f ms (CPU %8.1f ms)  %.2fx a "
                "plain render\n",
      t / views,
      timer.LastCpuMs / views,
      t / views / render);
  }
  return 0;
}

// SPDX-License-Identifier: BSD-3-Clause
// Trainer benchmark (Documentation/performance-history.md, section "Training"): iterations per
// second with a fixed number of Gaussians (densification off) at a given resolution, with
// the time split into forward, loss, backward and optimiser; then the cost of one
// densify-and-prune and of writing one snapshot of that size.
//
//   BenchmarkTrainer [--gaussians=50000] [--size=256] [--iterations=60] [--threads=2]
//                    [--sh-degree=3] [--warmup-train=0] [--kernel-isa=0]
//
// --kernel-isa=-1 runs the straightforward pair instead of the 16-lane loops: Render's
// CompositeTiles forward and the scalar pixel-by-pixel compositing backward.
//
// The headline configuration keeps the freshly initialised cloud (opacity 0.1 everywhere,
// the worst case for compositing: no pixel saturates). With --warmup-train=N > 0 a second
// configuration is reported as well: the same scene trained with the reference schedule
// (densification from iteration 500 every 100, SH degree +1 every 1000, opacity reset every
// 3000) for N untimed iterations, then the next --iterations iterations timed as they come
// (densification included when one falls inside), i.e. the rate through a real run.
#include "Trainer.h"
#include "TrainingLogWriter.h"

#include "SyntheticScene.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>

using namespace vis4gs;

namespace
{
double CpuSeconds()
{
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

int Arg(int argc, char** argv, const char* name, int def)
{
  const std::string prefix = std::string("--") + name + "=";
  for (int i = 1; i < argc; ++i)
  {
    if (std::strncmp(argv[i], prefix.c_str(), prefix.size()) == 0)
    {
      return std::atoi(argv[i] + prefix.size());
    }
  }
  return def;
}
}

int main(int argc, char** argv)
{
  const int gaussians = Arg(argc, argv, "gaussians", 50000);
  const int size = Arg(argc, argv, "size", 256);
  const int iterations = Arg(argc, argv, "iterations", 60);
  const int threads = Arg(argc, argv, "threads", 2);
  const int degree = Arg(argc, argv, "sh-degree", 3);
  const int warmupTrain = Arg(argc, argv, "warmup-train", 0);
  // -1: the straightforward pair (Render's CompositeTiles forward, scalar backward).
  const int kernelIsa = Arg(argc, argv, "kernel-isa", 0);
  const std::string scene = R"({
    "name": "bench", "seed": 1, "width": )" +
    std::to_string(size) + R"(, "height": )" + std::to_string(size) + R"(,
    "objects": [
      {"type": "torus", "center": [0, 0, 0.4], "major_radius": 0.6, "minor_radius": 0.2, "gaussians": 20000,
       "texture": {"pattern": "checker", "colors": [[0.9, 0.2, 0.1], [0.9, 0.9, 0.7]], "frequency": [24, 6]}},
      {"type": "sphere", "center": [-0.9, 0.6, 0.3], "radius": 0.3, "gaussians": 8000},
      {"type": "plane", "center": [0, 0, 0], "normal": [0, 0, 1], "size": [3, 3], "gaussians": 20000,
       "texture": {"pattern": "checker", "colors": [[0.3, 0.3, 0.3], [0.7, 0.7, 0.7]], "frequency": [12, 12]}}
    ],
    "cameras": [{"path": "orbit", "count": 16, "radius": 3.0, "elevation_deg": 30, "target": [0, 0, 0.3],
                 "fov_deg": 55}],
    "initial_points": {"count": )" +
    std::to_string(gaussians) + R"(, "position_noise": 0.01}
  })";
  SyntheticOptions so;
  so.Threads = threads;
  const SyntheticScene s = MakeSyntheticScene(scene, "bench.json", so);
  TrainingData data;
  data.Name = s.Name;
  data.Cameras = s.Cameras;
  data.Images = s.Images;
  data.PointPositions = s.PointPositions;
  data.PointColors = s.PointColors;

  TrainerOptions o;
  o.Iterations = iterations + 10;
  o.Threads = threads;
  o.KernelIsa = kernelIsa;
  o.ShDegree = degree;
  o.ShIncreaseInterval = 1;    // every SH degree active from iteration `degree` on (worst case)
  o.DensifyFromIter = 1 << 30; // fixed Gaussian count
  o.DensifyUntilIter = 0;
  Trainer t(data, o);
  for (int i = 0; i < 10; ++i)
  {
    t.Step(); // warm-up (and the SH degree ramp)
  }
  const TrainerTimings warm = t.GetTimings();
  const double cpu0 = CpuSeconds();
  for (int i = 0; i < iterations; ++i)
  {
    t.Step();
  }
  const double cpu = CpuSeconds() - cpu0;
  const TrainerTimings& T = t.GetTimings();
  const double total = T.Total - warm.Total;
  std::printf("BenchmarkTrainer: %zu Gaussians, %dx%d, SH degree %d, %d threads, %d iterations, "
              "kernel-isa %d\n",
    t.GetCloud().Count,
    size,
    size,
    degree,
    threads,
    iterations,
    kernelIsa);
  std::printf("  wall: %.2f it/s (%.1f ms/it); process CPU time %.1f ms/it, i.e. %.2f it/s with %d "
              "cores to itself\n",
    iterations / total,
    1000 * total / iterations,
    1000 * cpu / iterations,
    iterations / cpu * threads,
    threads);
  std::printf(
    "  per iteration: forward %.1f ms, loss %.1f ms, backward %.1f ms, optimizer %.1f ms, "
    "statistics %.1f ms\n",
    1000 * (T.Forward - warm.Forward) / iterations,
    1000 * (T.Loss - warm.Loss) / iterations,
    1000 * (T.Backward - warm.Backward) / iterations,
    1000 * (T.Optimizer - warm.Optimizer) / iterations,
    1000 * (T.Densify - warm.Densify) / iterations);

  if (warmupTrain > 0)
  {
    TrainerOptions r;
    r.Threads = threads;
    r.KernelIsa = kernelIsa;
    r.ShDegree = degree;
    r.Iterations = 30000; // the reference schedule
    Trainer real(data, r);
    const std::size_t start = real.GetCloud().Count;
    for (int i = 0; i < warmupTrain; ++i)
    {
      real.Step();
    }
    const TrainerTimings w0 = real.GetTimings();
    const std::size_t before = real.GetCloud().Count;
    const double c0 = CpuSeconds();
    for (int i = 0; i < iterations; ++i)
    {
      real.Step();
    }
    const double c = CpuSeconds() - c0;
    const TrainerTimings& R = real.GetTimings();
    const double tt = R.Total - w0.Total;
    std::printf("After %d iterations of real training (reference schedule, %zu -> %zu Gaussians, "
                "%zu after the timed ones), %d iterations:\n",
      warmupTrain,
      start,
      before,
      real.GetCloud().Count,
      iterations);
    std::printf("  wall: %.2f it/s (%.1f ms/it); process CPU time %.1f ms/it, i.e. %.2f it/s "
                "with %d cores to itself\n",
      iterations / tt,
      1000 * tt / iterations,
      1000 * c / iterations,
      iterations / c * threads,
      threads);
    std::printf(
      "  per iteration: forward %.1f ms, loss %.1f ms, backward %.1f ms, optimizer %.1f ms, "
      "statistics and densification %.1f ms\n",
      1000 * (R.Forward - w0.Forward) / iterations,
      1000 * (R.Loss - w0.Loss) / iterations,
      1000 * (R.Backward - w0.Backward) / iterations,
      1000 * (R.Optimizer - w0.Optimizer) / iterations,
      1000 * (R.Densify - w0.Densify) / iterations);
  }

  // One densify-and-prune of this cloud with every Gaussian above the threshold.
  const std::size_t n = t.GetCloud().Count;
  t.SetGradientStatistics(std::vector<float>(n, 1.0f), std::vector<float>(n, 1.0f));
  auto a = std::chrono::steady_clock::now();
  t.DensifyAndPruneAt(500);
  auto b = std::chrono::steady_clock::now();
  std::printf("  densify-and-prune of %zu Gaussians (all selected): %.1f ms -> %zu Gaussians\n",
    n,
    1000 * std::chrono::duration<double>(b - a).count(),
    t.GetCloud().Count);

  // Writing one snapshot of the grown cloud (with statistics).
  const std::string path = "/tmp/vis4gs_bench_trainer.h5";
  {
    TrainingLogWriter log(path);
    a = std::chrono::steady_clock::now();
    SnapshotStatistics st;
    st.GradAccum.assign(t.GetCloud().Count, 0.5f);
    st.Denom.assign(t.GetCloud().Count, 3.0f);
    log.WriteSnapshot(1, t.GetCloud(), &st);
    log.Close();
    b = std::chrono::steady_clock::now();
  }
  std::printf("  snapshot of %zu Gaussians (SH degree %d, deflate 1): %.1f ms\n",
    t.GetCloud().Count,
    degree,
    1000 * std::chrono::duration<double>(b - a).count());
  std::remove(path.c_str());
  return 0;
}

// SPDX-License-Identifier: BSD-3-Clause
// Writes a small SYNTHETIC training log for the application tests and benchmarks: events
// from Core's synthetic event generator (NOT a real training run), snapshots of the alive
// Gaussians replayed from the events, metrics curves, and a ring of cameras.
// Usage: vis4gsMakeTestLog OUT.h5 [FINAL_GAUSSIANS] [SNAPSHOTS]
#include "SyntheticEventLog.h"
#include "TrainingLogWriter.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <vector>

namespace
{
float Hash(std::int64_t id, int salt)
{
  std::uint64_t x =
    static_cast<std::uint64_t>(id) * 0x9E3779B97F4A7C15ull + salt * 0xBF58476D1CE4E5B9ull;
  x ^= x >> 31;
  x *= 0x94D049BB133111EBull;
  x ^= x >> 29;
  return static_cast<float>((x >> 11) * (1.0 / 9007199254740992.0));
}
}

namespace
{
int MakeLog(int argc, char* argv[]);
}

int main(int argc, char* argv[])
{
  try
  {
    return MakeLog(argc, argv);
  }
  catch (const std::exception& e)
  {
    std::cerr << "vis4gsMakeTestLog: " << e.what() << "\n";
    return 1;
  }
}

namespace
{
int MakeLog(int argc, char* argv[])
{
  if (argc < 2)
  {
    std::cerr << "usage: vis4gsMakeTestLog OUT.h5 [FINAL_GAUSSIANS] [SNAPSHOTS]\n";
    return 1;
  }
  const auto start = std::chrono::steady_clock::now();
  const std::filesystem::path parent = std::filesystem::path(argv[1]).parent_path();
  if (!parent.empty())
  {
    std::filesystem::create_directories(parent);
  }
  const std::int64_t final = argc > 2 ? std::atoll(argv[2]) : 400;
  const int snapshots = argc > 3 ? std::atoi(argv[3]) : 4;
  vis4gs::SyntheticLogParameters p;
  p.InitialGaussians = std::max<std::int64_t>(20, final / 90);
  p.FinalGaussians = final;
  p.TotalGaussians = final * 2 + p.InitialGaussians;
  const vis4gs::SyntheticEventLog log = vis4gs::GenerateSyntheticEventLog(p);
  vis4gs::TrainingLogWriterOptions options;
  options.Scene = "synthetic";
  options.Producer = "vis4gsMakeTestLog (synthetic)";
  options.ShDegree = 0;
  options.Iterations = log.LastIteration;
  vis4gs::TrainingLogWriter writer(argv[1], options);
  for (int k = 0; k <= 60; ++k)
  {
    vis4gs::MetricsRow row;
    row.Iteration = k * log.LastIteration / 60;
    row.Psnr = 18.0 + 10.0 * (1.0 - std::exp(-k / 12.0));
    row.Ssim = 0.5 + 0.4 * (1.0 - std::exp(-k / 15.0));
    row.Lpips = 0.5 * std::exp(-k / 20.0) + 0.1;
    row.Loss = 0.2 * std::exp(-k / 10.0);
    row.L1 = row.Loss;
    row.NumGaussians = 0;
    row.ElapsedSeconds = k;
    writer.AppendMetrics(row);
  }
  writer.AppendEvents(log.Events);
  // Replay the events to know who is alive at each snapshot iteration.
  std::vector<char> alive(static_cast<std::size_t>(p.TotalGaussians + 16), 0);
  for (std::int64_t i = 0; i < log.InitialGaussians; ++i)
  {
    alive[i] = 1;
  }
  std::size_t e = 0;
  for (int s = 0; s < snapshots; ++s)
  {
    const int iteration = s == 0
      ? 0
      : static_cast<int>(static_cast<long long>(log.LastIteration) * s / (snapshots - 1));
    for (; e < log.Events.Size() && log.Events.Iteration[e] <= iteration; ++e)
    {
      const auto kind = log.Events.Kind[e];
      const std::int64_t parent = log.Events.Parent[e], child = log.Events.Child[e];
      if (child >= 0)
      {
        if (static_cast<std::size_t>(child) >= alive.size())
        {
          alive.resize(child + 1, 0);
        }
        alive[child] = 1;
      }
      if (kind == 2 || kind == 3)
      {
        alive[parent] = 0;
      }
    }
    vis4gs::GaussianCloud cloud;
    std::vector<std::int64_t> ids;
    for (std::size_t id = 0; id < alive.size(); ++id)
    {
      if (alive[id])
      {
        ids.push_back(static_cast<std::int64_t>(id));
      }
    }
    cloud.Resize(ids.size(), 0);
    cloud.Ids = ids;
    for (std::size_t i = 0; i < ids.size(); ++i)
    {
      const std::int64_t id = ids[i];
      const float t = 6.2831853f * Hash(id, 1);
      const float r = 1.0f + 0.3f * Hash(id, 2);
      cloud.Positions[3 * i + 0] = r * std::cos(t);
      cloud.Positions[3 * i + 1] = r * std::sin(t);
      cloud.Positions[3 * i + 2] = 0.4f * (Hash(id, 3) - 0.5f);
      for (int c = 0; c < 3; ++c)
      {
        cloud.LogScales[3 * i + c] = -4.0f + Hash(id, 4 + c) - 0.1f * s;
      }
      cloud.Rotations[4 * i] = 1.0f;
      cloud.OpacityLogits[i] = 4.0f * (Hash(id, 8) - 0.5f) + 0.2f * s;
      for (int c = 0; c < 3; ++c)
      {
        cloud.SH[3 * i + c] = Hash(id, 9 + c) - 0.5f;
      }
    }
    writer.WriteSnapshot(iteration, cloud);
  }
  writer.Close();
  std::cout << argv[1] << ": SYNTHETIC log, " << log.Events.Size() << " events, " << final
            << " final Gaussians, " << snapshots << " snapshots, written in "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
            << " s\n";
  return 0;
}
}

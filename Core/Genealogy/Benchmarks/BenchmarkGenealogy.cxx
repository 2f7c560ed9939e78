// SPDX-License-Identifier: BSD-3-Clause
// Benchmark: genealogy (tree, layout, P) and level-of-detail queries on a SYNTHETIC
// Bicycle-sized event log (4.89M final Gaussians, ~10M nodes; see SyntheticEventLog.h).
// Usage: BenchmarkGenealogy [--total=N] [--final=N] [--seed=S] [--queries=Q]
// Prints figures; never run by CTest.
#include "Genealogy.h"
#include "GenealogyLevelOfDetail.h"
#include "SyntheticEventLog.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <random>
#include <string>

namespace
{
double Seconds(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b)
{
  return std::chrono::duration<double>(b - a).count();
}

/// Peak resident set (VmHWM) in MiB; ResetPeak() restarts it (Linux clear_refs 5).
double PeakMiB()
{
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
  {
    if (line.rfind("VmHWM:", 0) == 0)
    {
      return std::atof(line.c_str() + 6) / 1024.0;
    }
  }
  return -1.0;
}
double CurrentMiB()
{
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
  {
    if (line.rfind("VmRSS:", 0) == 0)
    {
      return std::atof(line.c_str() + 6) / 1024.0;
    }
  }
  return -1.0;
}
double CpuSeconds()
{
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
void ResetPeak()
{
  std::ofstream f("/proc/self/clear_refs");
  f << "5";
}

long long Arg(int argc, char* argv[], const char* name, long long fallback)
{
  const std::size_t len = std::strlen(name);
  for (int i = 1; i < argc; ++i)
  {
    if (std::strncmp(argv[i], name, len) == 0 && argv[i][len] == '=')
    {
      return std::atoll(argv[i] + len + 1);
    }
  }
  return fallback;
}
} // namespace

int main(int argc, char* argv[])
{
  using clock = std::chrono::steady_clock;
  vis4gs::SyntheticLogParameters prm;
  prm.TotalGaussians = Arg(argc, argv, "--total", prm.TotalGaussians);
  prm.FinalGaussians = Arg(argc, argv, "--final", prm.FinalGaussians);
  prm.Seed = static_cast<std::uint64_t>(Arg(argc, argv, "--seed", 1));
  const int queries = static_cast<int>(Arg(argc, argv, "--queries", 20));

  auto t0 = clock::now();
  const vis4gs::SyntheticEventLog log = vis4gs::GenerateSyntheticEventLog(prm);
  auto t1 = clock::now();
  std::printf("SYNTHETIC log: %lld initial, %lld clones, %lld splits, %lld prunes, %zu events, "
              "%lld final; generated in %.2f s\n",
    static_cast<long long>(log.InitialGaussians),
    static_cast<long long>(log.Clones),
    static_cast<long long>(log.Splits),
    static_cast<long long>(log.Prunes),
    log.Events.Size(),
    static_cast<long long>(log.FinalGaussians),
    Seconds(t0, t1));

  ResetPeak();
  const double before = CurrentMiB();
  t0 = clock::now();
  const vis4gs::Genealogy g =
    vis4gs::Genealogy::Build(log.InitialGaussians, log.Events, log.LastIteration);
  t1 = clock::now();
  const double peak = PeakMiB();
  std::printf("Genealogy::Build (tree, families, D, T, P, layout, bands): %lld nodes, %lld "
              "families in %.3f s\n",
    static_cast<long long>(g.GetNumberOfNodes()),
    static_cast<long long>(g.GetNumberOfFamilies()),
    Seconds(t0, t1));
  std::printf("  memory: RSS before %.0f MiB (event log %.0f MiB), peak during build %.0f MiB, "
              "genealogy holds %.0f MiB\n",
    before,
    static_cast<double>(log.Events.Size()) * (4 + 1 + 8 + 8) / 1048576.0,
    peak,
    static_cast<double>(g.GetMemorySize()) / 1048576.0);

  double cpu = 0.0;
  for (const auto& ph : g.GetBuildPhases())
  {
    std::printf(
      "    %-32s wall %.3f s  thread CPU %.3f s\n", ph.Name.c_str(), ph.WallSeconds, ph.CpuSeconds);
    cpu += ph.CpuSeconds;
  }
  std::printf("    total thread CPU %.3f s (wall-clock figures include time-sharing with other "
              "processes)\n",
    cpu);

  ResetPeak();
  t0 = clock::now();
  const double c0 = CpuSeconds();
  const vis4gs::GenealogyLevelOfDetail lod(g);
  const double c1 = CpuSeconds();
  t1 = clock::now();
  std::printf("LOD index (%lld cells): wall %.3f s, thread CPU %.3f s, %.0f MiB; process peak "
              "%.0f MiB\n",
    static_cast<long long>(lod.GetNumberOfCells()),
    Seconds(t0, t1),
    c1 - c0,
    static_cast<double>(lod.GetMemorySize()) / 1048576.0,
    PeakMiB());

  std::mt19937_64 rng(9);
  const std::int64_t n = g.GetNumberOfNodes();
  std::vector<std::int64_t> out;
  std::printf("LOD queries (median/max of %d each; result size, entries examined):\n", queries);
  struct Case
  {
    const char* Name;
    double Z;
    std::int64_t Rows; // viewport height in rows; 0 = all
    int Selected;
  };
  const Case cases[] = { { "z=0.10 full view", 0.10, 0, 0 },
    { "z=0.50 full view", 0.50, 0, 0 },
    { "z=1.00 full view", 1.00, 0, 0 },
    { "z=1.50 full view", 1.50, 0, 0 },
    { "z=1.00 full view + 10 selected", 1.00, 0, 10 },
    { "z=1.90 view of 20k rows x 3000 its", 1.90, 20000, 0 },
    { "z=2.00 view of 2000 rows", 2.00, 2000, 0 },
    { "z=1.00 view of 200k rows + 1 selected", 1.00, 200000, 1 } };
  for (const Case& c : cases)
  {
    std::vector<double> times, cpuTimes;
    std::size_t size = 0;
    std::int64_t work = 0;
    for (int q = 0; q < queries; ++q)
    {
      vis4gs::GenealogyViewport v;
      if (c.Rows > 0)
      {
        v.MinRow = static_cast<std::int64_t>(rng() % static_cast<std::uint64_t>(n - c.Rows));
        v.MaxRow = v.MinRow + c.Rows - 1;
        if (c.Z > 1.8 && c.Rows == 20000)
        {
          v.MinIteration = 6000;
          v.MaxIteration = 9000;
        }
      }
      std::vector<std::int64_t> sel;
      for (int s = 0; s < c.Selected; ++s)
      {
        sel.push_back(static_cast<std::int64_t>(rng() % static_cast<std::uint64_t>(n)));
      }
      const auto a = clock::now();
      const double ca = CpuSeconds();
      lod.Query(vis4gs::ZoomThreshold(c.Z), sel, v, out);
      cpuTimes.push_back((CpuSeconds() - ca) * 1e3);
      const auto b = clock::now();
      times.push_back(Seconds(a, b) * 1e3);
      size = std::max(size, out.size());
      work = std::max(work, lod.GetLastQueryWork());
    }
    std::sort(times.begin(), times.end());
    std::sort(cpuTimes.begin(), cpuTimes.end());
    std::printf("  %-40s tau=%.4f  wall median %7.3f max %7.3f ms | CPU median %7.3f max %7.3f "
                "ms (<= %zu nodes, <= %lld entries)\n",
      c.Name,
      vis4gs::ZoomThreshold(c.Z),
      times[times.size() / 2],
      times.back(),
      cpuTimes[cpuTimes.size() / 2],
      cpuTimes.back(),
      size,
      static_cast<long long>(work));
  }
  {
    const auto a = clock::now();
    const double ca = CpuSeconds();
    const auto brute = lod.QueryBruteForce(vis4gs::ZoomThreshold(1.0), {});
    const double cb = CpuSeconds();
    const auto b = clock::now();
    std::printf("  brute-force filter (z=1.00 full view): wall %.1f ms, CPU %.1f ms, %zu nodes\n",
      Seconds(a, b) * 1e3,
      (cb - ca) * 1e3,
      brute.size());
  }
  {
    const std::int64_t deep = g.GetNumberOfNodes() - 1;
    const auto a = clock::now();
    const auto lineage = g.Lineage({ deep, deep / 2, 17 });
    const auto trace = g.TraceToRoot(deep,
      { 0, 7000, 15000, 30000 },
      [](std::int32_t s, std::int64_t id) { return static_cast<double>(s + id); });
    const auto b = clock::now();
    std::printf("Lineage of 3 nodes (%zu nodes) + trace (%zu steps): %.3f ms\n",
      lineage.size(),
      trace.size(),
      Seconds(a, b) * 1e3);
  }
  return 0;
}

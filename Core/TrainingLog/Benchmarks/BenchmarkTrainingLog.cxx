// SPDX-License-Identifier: BSD-3-Clause
// Training-log benchmark: prints the figures recorded in Documentation/performance.md.
//
//   BenchmarkTrainingLog [--dir=/tmp] [--gaussians=5000000] [--events=10000000]
//                    [--history-snapshots=60] [--history-gaussians=500000] [--level=1]
//                    [--snapshot-level=0] [--chunk=4096]
//
// 1. one snapshot of N Gaussians (SH degree 3): read without the SH rest, against reading
//    everything (what a reader without hyperslabs does);
// 2. E events: ReadEvents (with validation) against a bare H5Dread of the four columns;
// 3. history of 100 ids across S snapshots: ReadPropertyHistory against reading every
//    snapshot in full and picking the rows (the straightforward way).
#include "TrainingLogReader.h"
#include "TrainingLogWriter.h"

#include <hdf5.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fcntl.h>
#include <random>
#include <string>
#include <sys/stat.h>

using namespace vis4gs;

namespace
{
double Now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// Process CPU time (all threads), a fairer figure than wall time on a shared machine.
double Cpu()
{
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

double FileMiB(const std::string& path)
{
  struct stat st;
  return ::stat(path.c_str(), &st) == 0 ? static_cast<double>(st.st_size) / (1 << 20) : -1;
}

void DropCache(const std::string& path)
{
  // Best effort: ask the kernel to forget the file's pages (needs no privileges).
  FILE* f = std::fopen(path.c_str(), "rb");
  if (f)
  {
    posix_fadvise(fileno(f), 0, 0, POSIX_FADV_DONTNEED);
    std::fclose(f);
  }
}

GaussianCloud Synthetic(std::size_t n, int degree, unsigned seed, std::int64_t idOffset)
{
  GaussianCloud c;
  c.Resize(n, degree);
  c.Ids.resize(n);
  std::mt19937 rng(seed);
  std::normal_distribution<float> normal(0.f, 1.f);
  std::uniform_int_distribution<int> gap(1, 3);
  std::int64_t id = idOffset;
  for (std::size_t i = 0; i < n; ++i)
  {
    id += gap(rng) - (i == 0 ? 1 : 0);
    c.Ids[i] = id;
  }
  // Trained-looking values: smooth positions, clustered scales, SH rest near zero.
  for (std::size_t i = 0; i < n; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      c.Positions[3 * i + j] = 4.f * normal(rng);
      c.LogScales[3 * i + j] = -4.5f + 0.8f * normal(rng);
    }
    for (int j = 0; j < 4; ++j)
    {
      c.Rotations[4 * i + j] = normal(rng);
    }
    c.OpacityLogits[i] = 1.5f * normal(rng);
  }
  const std::size_t k = static_cast<std::size_t>(c.ShCoefficientCount());
  for (std::size_t i = 0; i < n; ++i)
  {
    for (std::size_t j = 0; j < 3 * k; ++j)
    {
      c.SH[i * 3 * k + j] = (j < 3 ? 0.8f : 0.05f) * normal(rng);
    }
  }
  return c;
}

std::string Arg(int argc, char** argv, const std::string& name, const std::string& fallback)
{
  const std::string prefix = "--" + name + "=";
  for (int i = 1; i < argc; ++i)
  {
    if (std::strncmp(argv[i], prefix.c_str(), prefix.size()) == 0)
    {
      return argv[i] + prefix.size();
    }
  }
  return fallback;
}
} // namespace

int main(int argc, char** argv)
{
  const std::string dir = Arg(argc, argv, "dir", "/tmp");
  const std::size_t gaussians = std::stoull(Arg(argc, argv, "gaussians", "5000000"));
  const std::size_t events = std::stoull(Arg(argc, argv, "events", "10000000"));
  const int snapshots = std::stoi(Arg(argc, argv, "history-snapshots", "60"));
  const std::size_t historyGaussians = std::stoull(Arg(argc, argv, "history-gaussians", "500000"));
  const int level = std::stoi(Arg(argc, argv, "level", "1"));
  const int snapshotLevel = std::stoi(Arg(argc, argv, "snapshot-level", "0"));
  const std::size_t chunk = std::stoull(Arg(argc, argv, "chunk", "4096"));
  const bool keep = Arg(argc, argv, "keep", "0") == "1";
  std::printf("BenchmarkTrainingLog: deflate level %d (+shuffle) for tables, %d for snapshots, "
              "snapshot chunk "
              "%zu rows\n",
    level,
    snapshotLevel,
    chunk);

  TrainingLogWriterOptions options;
  options.DeflateLevel = level;
  options.SnapshotDeflateLevel = snapshotLevel;
  options.SnapshotChunkRows = chunk;

  // 1. One big snapshot.
  if (gaussians > 0)
  {
    const std::string path = dir + "/vis4gs_bench_snapshot.h5";
    GaussianCloud cloud = Synthetic(gaussians, 3, 1, 0);
    double t0 = Now();
    {
      TrainingLogWriter writer(path, options);
      writer.WriteSnapshot(30000, cloud);
    }
    const double write = Now() - t0;
    std::printf(
      "[snapshot] %zu Gaussians, SH degree 3: write %.2f s, file %.0f MiB (raw %.0f MiB)\n",
      gaussians,
      write,
      FileMiB(path),
      static_cast<double>(gaussians) * (8 + 4 * (3 + 3 + 4 + 1 + 48)) / (1 << 20));
    TrainingLogReader reader(path);
    for (int rep = 0; rep < 2; ++rep)
    {
      DropCache(path);
      t0 = Now();
      double c0 = Cpu();
      GaussianCloud dc = reader.ReadSnapshot(30000); // default: no SH rest
      const double tDc = Now() - t0, cDc = Cpu() - c0;
      DropCache(path);
      t0 = Now();
      c0 = Cpu();
      SnapshotReadOptions all;
      all.Arrays = SnapshotAll;
      all.ShDegree = -1;
      GaussianCloud full = reader.ReadSnapshot(30000, all);
      const double tFull = Now() - t0, cFull = Cpu() - c0;
      const bool same = dc.Positions == cloud.Positions && full.SH == cloud.SH;
      std::printf("[snapshot] read without SH rest %.3f s (cpu %.3f s) | read everything "
                  "(baseline) %.3f s (cpu %.3f s) | values %s\n",
        tDc,
        cDc,
        tFull,
        cFull,
        same ? "identical" : "DIFFER");
    }
    if (!keep)
    {
      std::remove(path.c_str());
    }
  }

  // 2. Events.
  if (events > 0)
  {
    const std::string path = dir + "/vis4gs_bench_events.h5";
    EventTable table;
    table.Reserve(events);
    std::mt19937 rng(2);
    const std::int64_t n0 = 200000;
    std::int64_t next = n0;
    std::vector<std::int64_t> alive(static_cast<std::size_t>(n0));
    for (std::int64_t i = 0; i < n0; ++i)
    {
      alive[static_cast<std::size_t>(i)] = i;
    }
    int iteration = 600;
    while (table.Size() < events)
    {
      // One densification: clones, splits (2 children, parent ends), prunes.
      std::uniform_int_distribution<std::size_t> pick(0, alive.size() - 1);
      for (int k = 0; k < 20000 && table.Size() + 3 <= events; ++k)
      {
        const std::size_t r = pick(rng);
        const std::int64_t p = alive[r];
        switch (k % 3)
        {
          case 0:
            table.Append({ iteration, EventKind::Clone, p, next });
            alive.push_back(next++);
            break;
          case 1:
            table.Append({ iteration, EventKind::Split, p, next });
            alive.push_back(next++);
            table.Append({ iteration, EventKind::Split, p, next });
            alive.push_back(next++);
            alive[r] = alive.back();
            alive.pop_back();
            break;
          default:
            table.Append({ iteration, EventKind::Prune, p, -1 });
            alive[r] = alive.back();
            alive.pop_back();
        }
      }
      while (table.Size() < events && table.Size() + 3 > events)
      {
        table.Append({ iteration, EventKind::Prune, alive.back(), -1 });
        alive.pop_back();
      }
      iteration += 100;
    }
    double t0 = Now();
    {
      TrainingLogWriter writer(path, options);
      writer.AppendEvents(table);
    }
    std::printf("[events] %zu events: write %.2f s, file %.0f MiB (raw %.0f MiB)\n",
      table.Size(),
      Now() - t0,
      FileMiB(path),
      table.Size() * 21.0 / (1 << 20));
    for (int rep = 0; rep < 2; ++rep)
    {
      DropCache(path);
      TrainingLogReader reader(path);
      t0 = Now();
      double c0 = Cpu();
      EventTable read = reader.ReadEvents();
      const double tRead = Now() - t0, cRead = Cpu() - c0;
      // Baseline: the four columns read by bare H5Dread calls, no validation.
      DropCache(path);
      t0 = Now();
      c0 = Cpu();
      hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
      H5Pset_file_locking(fapl, false, true); // as the reader, which still has it open
      hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl);
      H5Pclose(fapl);
      EventTable bare;
      bare.Iteration.resize(table.Size());
      bare.Kind.resize(table.Size());
      bare.Parent.resize(table.Size());
      bare.Child.resize(table.Size());
      const char* names[4] = {
        "/events/iteration", "/events/kind", "/events/parent", "/events/child"
      };
      void* outs[4] = {
        bare.Iteration.data(), bare.Kind.data(), bare.Parent.data(), bare.Child.data()
      };
      hid_t types[4] = { H5T_NATIVE_INT32, H5T_NATIVE_UINT8, H5T_NATIVE_INT64, H5T_NATIVE_INT64 };
      for (int c = 0; c < 4; ++c)
      {
        hid_t d = H5Dopen2(f, names[c], H5P_DEFAULT);
        H5Dread(d, types[c], H5S_ALL, H5S_ALL, H5P_DEFAULT, outs[c]);
        H5Dclose(d);
      }
      H5Fclose(f);
      const double tBare = Now() - t0, cBare = Cpu() - c0;
      std::printf("[events] ReadEvents with validation %.3f s (cpu %.3f s) | bare H5Dread of the "
                  "columns %.3f s (cpu %.3f s) | rows %s\n",
        tRead,
        cRead,
        tBare,
        cBare,
        read.Parent == table.Parent && read.Child == table.Child ? "identical" : "DIFFER");
    }
    if (!keep)
    {
      std::remove(path.c_str());
    }
  }

  // 3. History of 100 ids across S snapshots.
  if (snapshots > 0 && historyGaussians > 0)
  {
    const std::string path = dir + "/vis4gs_bench_history.h5";
    double t0 = Now();
    {
      TrainingLogWriter writer(path, options);
      for (int s = 0; s < snapshots; ++s)
      {
        // Each snapshot: ids with random gaps (prunes) starting a little later each time.
        writer.WriteSnapshot(500 * (s + 1),
          Synthetic(historyGaussians, 1, 100 + s, static_cast<std::int64_t>(s) * 1000));
      }
    }
    std::printf(
      "[history] %d snapshots x %zu Gaussians (SH degree 1): write %.1f s, file %.0f MiB\n",
      snapshots,
      historyGaussians,
      Now() - t0,
      FileMiB(path));
    std::mt19937 rng(7);
    std::uniform_int_distribution<std::int64_t> pick(
      0, static_cast<std::int64_t>(historyGaussians) * 2);
    const unsigned arrays = SnapshotPositions | SnapshotLogScales | SnapshotRotations |
      SnapshotOpacityLogits | SnapshotSH;
    for (int rep = 0; rep < 3; ++rep)
    {
      std::vector<std::int64_t> ids;
      if (rep < 2)
      {
        for (int i = 0; i < 100; ++i)
        {
          ids.push_back(pick(rng)); // spread over the whole id range
        }
      }
      else
      {
        const std::int64_t start = pick(rng);
        for (int i = 0; i < 100; ++i)
        {
          ids.push_back(start + 2 * i); // one family: consecutive ids
        }
      }
      DropCache(path);
      TrainingLogReader reader(path);
      t0 = Now();
      double c0 = Cpu();
      PropertyHistory h = reader.ReadPropertyHistory(ids, arrays);
      const double tHistory = Now() - t0, cHistory = Cpu() - c0;
      // Baseline: read every snapshot's arrays in full and pick the rows.
      double tFull = -1, cFull = -1;
      std::size_t fullRows = 0;
      if (rep == 0)
      {
        DropCache(path);
        t0 = Now();
        c0 = Cpu();
        SnapshotReadOptions o;
        o.Arrays = arrays;
        std::vector<std::int64_t> sorted = ids;
        std::sort(sorted.begin(), sorted.end());
        for (int it : reader.GetSnapshotIterations())
        {
          GaussianCloud c = reader.ReadSnapshot(it, o);
          for (std::int64_t id : sorted)
          {
            fullRows += std::binary_search(c.Ids.begin(), c.Ids.end(), id) ? 1 : 0;
          }
        }
        tFull = Now() - t0;
        cFull = Cpu() - c0;
      }
      std::printf("[history] 100 %s ids: ReadPropertyHistory %.3f s (cpu %.3f s, %zu rows)",
        rep < 2 ? "spread" : "consecutive",
        tHistory,
        cHistory,
        h.Size());
      if (tFull >= 0)
      {
        std::printf(" | full snapshot reads (baseline) %.2f s (cpu %.2f s, %zu rows)",
          tFull,
          cFull,
          fullRows);
      }
      std::printf("\n");
      if (rep == 0)
      {
        // The same query again, the file now in the page cache (read by the baseline).
        t0 = Now();
        c0 = Cpu();
        PropertyHistory again = reader.ReadPropertyHistory(ids, arrays);
        std::printf(
          "[history] 100 spread ids again, file in the page cache: ReadPropertyHistory %.3f s "
          "(cpu %.3f s, %zu rows, %s)\n",
          Now() - t0,
          Cpu() - c0,
          again.Size(),
          again.Positions == h.Positions && again.SHDC == h.SHDC ? "same values" : "DIFFER");
      }
    }
    if (!keep)
    {
      std::remove(path.c_str());
    }
  }
  return 0;
}

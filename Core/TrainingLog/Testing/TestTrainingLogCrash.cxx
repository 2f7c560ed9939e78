// SPDX-License-Identifier: BSD-3-Clause
// Crash safety: a writer process is SIGKILL-ed at various moments while it appends; the
// log it leaves must open and read completely up to (at least) its last completed flush.
#include "TrainingLogReader.h"
#include "TrainingLogTestUtilities.h"
#include "TrainingLogWriter.h"

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

using namespace vis4gs;
using vis4gs::testing::MakeCloud;
using vis4gs::testing::TempLogPath;

namespace
{
std::vector<std::int64_t> IdsFor(int snapshot)
{
  // Ids shift as training "prunes" and "clones": 0..n-1 without every 7th, plus new ids.
  std::vector<std::int64_t> ids;
  const std::int64_t n = 20000 + 1000 * snapshot;
  for (std::int64_t i = 0; i < n; ++i)
  {
    if (i % 7 != snapshot % 7)
    {
      ids.push_back(i);
    }
  }
  return ids;
}

/// The child: writes forever, reporting each completed flush on @p fd.
[[noreturn]] void RunWriter(const std::string& path, int fd, bool swmr)
{
  try
  {
    TrainingLogWriterOptions options;
    options.Swmr = swmr;
    options.SnapshotChunkRows = 4096;
    TrainingLogWriter writer(path, options);
    std::int64_t nextChild = 1000000;
    for (int s = 0;; ++s)
    {
      for (int k = 0; k < 100; ++k)
      {
        MetricsRow row;
        row.Iteration = s * 100 + k;
        row.NumGaussians = s;
        row.Loss = s + k * 0.01;
        writer.AppendMetrics(row);
        writer.AppendEvent({ row.Iteration, EventKind::Clone, k, nextChild++ });
      }
      writer.WriteSnapshot(s * 100, MakeCloud(IdsFor(s), 1, static_cast<unsigned>(s)));
      const int done = s;
      if (::write(fd, &done, sizeof(done)) != sizeof(done))
      {
        ::_exit(3);
      }
    }
  }
  catch (...)
  {
    ::_exit(2);
  }
}
} // namespace

//------------------------------------------------------------------------------
TEST(TrainingLogCrash, KilledWriterLeavesReadableLog)
{
  // Kill after 1..3 reported flushes, plus a delay that lands inside the next write.
  // Both layouts: format version 1 (metadata held back between flushes) and 2 (SWMR mode,
  // rows counted in /committed after each flush; the killed file opens in SWMR read mode).
  const int delaysUs[] = { 0, 1500, 7000, 15000, 30000 };
  int run = 0;
  for (bool swmr : { false, true })
    for (int delay : delaysUs)
    {
      SCOPED_TRACE(swmr ? "SWMR" : "version 1");
      const std::string path = TempLogPath("crash" + std::to_string(run));
      int fds[2];
      ASSERT_EQ(::pipe(fds), 0);
      pid_t pid = ::fork();
      ASSERT_GE(pid, 0);
      if (pid == 0)
      {
        ::close(fds[0]);
        RunWriter(path, fds[1], swmr);
      }
      ::close(fds[1]);
      const int wanted = 1 + run % 3;
      int lastFlushed = -1;
      for (int i = 0; i < wanted; ++i)
      {
        int value = -1;
        ASSERT_EQ(::read(fds[0], &value, sizeof(value)), static_cast<ssize_t>(sizeof(value)))
          << "the writer process stopped early";
        lastFlushed = value;
      }
      std::this_thread::sleep_for(std::chrono::microseconds(delay));
      ::kill(pid, SIGKILL);
      int status = 0;
      ::waitpid(pid, &status, 0);
      ASSERT_TRUE(WIFSIGNALED(status)) << "the writer ended on its own, status " << status;
      // Flushes reported after our last read may also be complete.
      int value = -1;
      while (::read(fds[0], &value, sizeof(value)) == static_cast<ssize_t>(sizeof(value)))
      {
        lastFlushed = value;
      }
      ::close(fds[0]);

      TrainingLogReader reader(path);
      // The first choice of the reader; the only way to open a killed SWMR writer's file.
      EXPECT_TRUE(reader.IsSwmrRead());
      EXPECT_EQ(reader.GetHeader().FormatVersion, swmr ? 2 : 1);
      const std::vector<int>& its = reader.GetSnapshotIterations();
      ASSERT_GE(static_cast<int>(its.size()), lastFlushed + 1) << "delay " << delay;
      for (std::size_t s = 0; s < its.size(); ++s)
      {
        ASSERT_EQ(its[s], static_cast<int>(s) * 100);
        SnapshotReadOptions options;
        options.Arrays = SnapshotAll;
        options.ShDegree = -1;
        GaussianCloud c = reader.ReadSnapshot(its[s], options);
        GaussianCloud expected =
          MakeCloud(IdsFor(static_cast<int>(s)), 1, static_cast<unsigned>(s));
        EXPECT_EQ(c.Ids, expected.Ids);
        EXPECT_EQ(c.Positions, expected.Positions);
        EXPECT_EQ(c.SH, expected.SH);
      }
      MetricsTable m = reader.ReadMetrics();
      EXPECT_GE(m.Size(), 100 * its.size());
      for (std::size_t i = 0; i < m.Size(); ++i)
      {
        ASSERT_EQ(m.Iteration[i], static_cast<int>(i));
      }
      EventTable e = reader.ReadEvents(); // validates the ids
      EXPECT_EQ(e.Size(), m.Size());
      std::remove(path.c_str());
      ++run;
    }
}

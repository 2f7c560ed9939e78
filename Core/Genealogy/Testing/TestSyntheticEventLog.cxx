// SPDX-License-Identifier: BSD-3-Clause
// Synthetic event logs: schedule of the reference trainer, totals, determinism, validity.
#include "Genealogy.h"
#include "SyntheticEventLog.h"

#include <gtest/gtest.h>

#include <map>
#include <set>

namespace
{
vis4gs::SyntheticLogParameters Small()
{
  vis4gs::SyntheticLogParameters p;
  p.InitialGaussians = 2000;
  p.FinalGaussians = 100000;
  p.TotalGaussians = 200000;
  p.Seed = 42;
  return p;
}
} // namespace

TEST(SyntheticEventLog, ScheduleAndTotals)
{
  const auto prm = Small();
  const auto log = vis4gs::GenerateSyntheticEventLog(prm);
  const auto& ev = log.Events;
  ASSERT_GT(ev.Size(), 0u);
  EXPECT_EQ(log.LastIteration, 30000);
  // Births = clones + 2 splits; total = initial + births.
  EXPECT_EQ(prm.InitialGaussians + log.Clones + 2 * log.Splits, prm.TotalGaussians);
  EXPECT_EQ(log.FinalGaussians, prm.InitialGaussians + log.Clones + log.Splits - log.Prunes);
  EXPECT_NEAR(
    static_cast<double>(log.FinalGaussians), prm.FinalGaussians, 0.002 * prm.FinalGaussians);
  EXPECT_NEAR(static_cast<double>(log.Splits) / (log.Splits + log.Clones), 0.4, 0.01);

  std::map<std::int32_t, std::int64_t> prunesAt;
  std::set<std::int32_t> iterations;
  std::int64_t clones = 0, splitRows = 0, prunes = 0;
  for (std::size_t r = 0; r < ev.Size(); ++r)
  {
    const std::int32_t it = ev.Iteration[r];
    iterations.insert(it);
    EXPECT_EQ(it % 100, 0);
    EXPECT_GE(it, 600);
    EXPECT_LE(it, 14900);
    if (r > 0)
    {
      ASSERT_GE(it, ev.Iteration[r - 1]);
      // Within a step: clones, then splits, then prunes.
      if (it == ev.Iteration[r - 1])
      {
        ASSERT_GE(ev.Kind[r], ev.Kind[r - 1]) << "row " << r;
      }
    }
    clones += ev.Kind[r] == 1;
    splitRows += ev.Kind[r] == 2;
    if (ev.Kind[r] == 3)
    {
      ++prunes;
      ++prunesAt[it];
    }
  }
  EXPECT_EQ(clones, log.Clones);
  EXPECT_EQ(splitRows, 2 * log.Splits);
  EXPECT_EQ(prunes, log.Prunes);
  EXPECT_EQ(iterations.size(), 144u);
  // Prune bursts right after the opacity resets.
  for (std::int32_t burst : { 3100, 6100, 9100, 12100 })
  {
    EXPECT_GT(prunesAt[burst], 5 * prunesAt[burst + 100]) << burst;
    EXPECT_GT(prunesAt[burst], 5 * prunesAt[burst - 100]) << burst;
  }
  // The log is valid for the genealogy (no unknown parent, no double birth or death).
  const auto g = vis4gs::Genealogy::Build(log.InitialGaussians, ev, log.LastIteration);
  EXPECT_EQ(g.GetNumberOfNodes(), prm.TotalGaussians);
  std::int64_t alive = 0;
  for (std::int32_t d : g.GetDeathIterations())
  {
    alive += d < 0;
  }
  EXPECT_EQ(alive, log.FinalGaussians);
  EXPECT_TRUE(g.GetWarnings().empty());
  // Lineages deeper than a handful of generations exist (recent-parent bias).
  std::int64_t maxDepth = 0;
  for (std::int64_t i = 0; i < g.GetNumberOfNodes(); i += 97)
  {
    std::int64_t depth = 0;
    for (std::int64_t u = g.GetParents()[i]; u >= 0; u = g.GetParents()[u])
    {
      ++depth;
    }
    maxDepth = std::max(maxDepth, depth);
  }
  EXPECT_GE(maxDepth, 8);
}

TEST(SyntheticEventLog, DeterministicPerSeed)
{
  auto prm = Small();
  const auto a = vis4gs::GenerateSyntheticEventLog(prm);
  const auto b = vis4gs::GenerateSyntheticEventLog(prm);
  EXPECT_EQ(a.Events.Parent, b.Events.Parent);
  EXPECT_EQ(a.Events.Child, b.Events.Child);
  prm.Seed = 43;
  const auto c = vis4gs::GenerateSyntheticEventLog(prm);
  EXPECT_NE(a.Events.Parent, c.Events.Parent);
}

TEST(SyntheticEventLog, BadParameters)
{
  auto prm = Small();
  prm.TotalGaussians = prm.FinalGaussians - 1;
  EXPECT_THROW(vis4gs::GenerateSyntheticEventLog(prm), std::runtime_error);
  prm = Small();
  prm.SplitShare = 1.5;
  EXPECT_THROW(vis4gs::GenerateSyntheticEventLog(prm), std::runtime_error);
  prm = Small();
  prm.TotalGaussians = prm.FinalGaussians + 10; // would need negative prunes
  EXPECT_THROW(vis4gs::GenerateSyntheticEventLog(prm), std::runtime_error);
}

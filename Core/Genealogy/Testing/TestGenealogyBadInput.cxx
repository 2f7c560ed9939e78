// SPDX-License-Identifier: BSD-3-Clause
// Genealogy: every bad-input case has a defined result and a message naming the row.
#include "Genealogy.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace
{
using vis4gs::BirthKind;
using vis4gs::EventTable;
using vis4gs::Genealogy;
using vis4gs::GenealogyOptions;

void Add(EventTable& t, std::int32_t it, int kind, std::int64_t parent, std::int64_t child)
{
  t.Iteration.push_back(it);
  t.Kind.push_back(static_cast<std::uint8_t>(kind));
  t.Parent.push_back(parent);
  t.Child.push_back(child);
}

/// Message of the runtime_error thrown by Build (empty when none).
std::string BuildError(std::int64_t n0,
  const EventTable& t,
  std::int32_t last,
  const GenealogyOptions& o = GenealogyOptions())
{
  try
  {
    Genealogy::Build(n0, t, last, o);
  }
  catch (const std::runtime_error& e)
  {
    return e.what();
  }
  return std::string();
}

bool Contains(const std::string& s, const std::string& part)
{
  return s.find(part) != std::string::npos;
}
} // namespace

TEST(GenealogyBadInput, ColumnLengths)
{
  EventTable t;
  Add(t, 1, 1, 0, 1);
  t.Child.push_back(5);
  const std::string m = BuildError(1, t, 10);
  EXPECT_TRUE(Contains(m, "different lengths")) << m;
  EXPECT_TRUE(Contains(m, "child 2")) << m;
}

TEST(GenealogyBadInput, BadRows)
{
  EventTable kind;
  Add(kind, 1, 1, 0, 1);
  Add(kind, 2, 7, 0, 2);
  std::string m = BuildError(1, kind, 10);
  EXPECT_TRUE(Contains(m, "event row 1")) << m;
  EXPECT_TRUE(Contains(m, "unknown kind 7")) << m;

  EventTable neg;
  Add(neg, 1, 1, -3, 1);
  m = BuildError(1, neg, 10);
  EXPECT_TRUE(Contains(m, "event row 0")) << m;
  EXPECT_TRUE(Contains(m, "negative parent")) << m;

  EventTable prune;
  Add(prune, 1, 3, 0, 4);
  m = BuildError(1, prune, 10);
  EXPECT_TRUE(Contains(m, "prune must have child -1")) << m;

  EventTable child;
  Add(child, 1, 2, 0, -1);
  m = BuildError(1, child, 10);
  EXPECT_TRUE(Contains(m, "negative child")) << m;

  EventTable early;
  Add(early, -5, 1, 0, 1);
  m = BuildError(1, early, 10);
  EXPECT_TRUE(Contains(m, "before the initial iteration")) << m;

  EventTable late;
  Add(late, 50, 1, 0, 1);
  m = BuildError(1, late, 10);
  EXPECT_TRUE(Contains(m, "last iteration 10 is before event row 0")) << m;
  EXPECT_EQ(Genealogy::Build(1, late, -1).GetLastIteration(), 50);

  EXPECT_TRUE(Contains(BuildError(-1, EventTable(), 10), "negative number"));
  GenealogyOptions o;
  o.CoarsenInterval = -2;
  EXPECT_TRUE(Contains(BuildError(1, EventTable(), 10, o), "CoarsenInterval"));
}

TEST(GenealogyBadInput, OutOfOrder)
{
  EventTable t;
  Add(t, 300, 1, 1, 2); // needs 1, born at 200 below
  Add(t, 200, 1, 0, 1);
  Add(t, 200, 1, 0, 3);
  Add(t, 400, 3, 2, -1);
  GenealogyOptions strict;
  strict.StrictEventOrder = true;
  const std::string m = BuildError(1, t, 1000, strict);
  EXPECT_TRUE(Contains(m, "event row 1 (iteration 200) comes after row 0 (iteration 300)")) << m;

  // Default: stable sort by iteration (rows 1, 2, 0, 3) and a warning.
  const Genealogy g = Genealogy::Build(1, t, 1000);
  EXPECT_TRUE(g.GetEventsWereReordered());
  ASSERT_EQ(g.GetWarnings().size(), 1u);
  EXPECT_TRUE(Contains(g.GetWarnings()[0], "sorted stably")) << g.GetWarnings()[0];
  EXPECT_EQ(g.GetGaussianIds(), (std::vector<std::int64_t>{ 0, 1, 3, 2 }));
  EXPECT_EQ(g.GetBirthIterations(), (std::vector<std::int32_t>{ 0, 200, 200, 300 }));
  EXPECT_EQ(g.GetDeathIterations()[3], 400);
  EXPECT_EQ(g.GetPruned()[3], 1);
}

TEST(GenealogyBadInput, UnknownParent)
{
  EventTable t;
  Add(t, 100, 1, 0, 1);
  Add(t, 200, 2, 42, 2); // 42 never born
  Add(t, 200, 2, 42, 3);
  Add(t, 300, 3, 43, -1); // 43 never born either
  const std::string m = BuildError(1, t, 1000);
  EXPECT_TRUE(Contains(m, "event row 1 (iteration 200, split)")) << m;
  EXPECT_TRUE(Contains(m, "unknown parent GaussianId 42")) << m;

  GenealogyOptions o;
  o.RepairUnknownParents = true;
  const Genealogy g = Genealogy::Build(1, t, 1000, o);
  ASSERT_EQ(g.GetOrphanRoots().size(), 2u);
  const std::int64_t orphan = g.GetOrphanRoots()[0];
  EXPECT_EQ(g.GetGaussianIds()[orphan], 42);
  EXPECT_EQ(g.GetBirthKinds()[orphan], BirthKind::Root);
  EXPECT_EQ(g.GetParents()[orphan], -1);
  EXPECT_EQ(g.GetBirthIterations()[orphan], 200);
  EXPECT_EQ(g.GetDeathIterations()[orphan], 200); // split at once: zero lifespan
  EXPECT_EQ(g.GetLifespans()[orphan], 0);
  EXPECT_EQ(g.GetDescendantCounts()[orphan], 2);
  EXPECT_EQ(g.GetNumberOfFamilies(), 3);
  const std::int64_t o43 = g.GetOrphanRoots()[1];
  EXPECT_EQ(g.GetGaussianIds()[o43], 43);
  EXPECT_EQ(g.GetPruned()[o43], 1);
  EXPECT_EQ(g.GetWarnings().size(), 2u);
  // Families stacked after the initial one, in creation order.
  EXPECT_EQ(g.GetFamilyBands()[1].RootNode, orphan);
  EXPECT_EQ(g.GetFamilyBands()[1].MinRow, 2);
  EXPECT_EQ(g.GetFamilyBands()[2].MinRow, 5);
}

TEST(GenealogyBadInput, BornTwice)
{
  EventTable t;
  Add(t, 100, 1, 0, 1);
  Add(t, 200, 1, 0, 1); // 1 again
  Add(t, 300, 2, 1, 0); // 0 (initial) again
  Add(t, 300, 2, 1, 2);
  std::string m = BuildError(1, t, 1000);
  EXPECT_TRUE(Contains(m, "event row 1 (iteration 200, clone)")) << m;
  EXPECT_TRUE(Contains(m, "child GaussianId 1 is born twice")) << m;

  GenealogyOptions o;
  o.RepairDuplicateBirths = true;
  const Genealogy g = Genealogy::Build(1, t, 1000, o);
  EXPECT_EQ(g.GetDroppedEventRows(), (std::vector<std::int64_t>{ 1, 2 }));
  EXPECT_EQ(g.GetNumberOfNodes(), 3);
  EXPECT_EQ(g.GetBirthIterations()[1], 100);
  EXPECT_EQ(g.GetDeathIterations()[1], 300); // the remaining split row still ends 1
  EXPECT_EQ(g.GetWarnings().size(), 2u);

  // Repeated initial ids.
  m.clear();
  try
  {
    Genealogy::Build(std::vector<std::int64_t>{ 4, 5, 4 }, EventTable(), 10);
  }
  catch (const std::runtime_error& e)
  {
    m = e.what();
  }
  EXPECT_TRUE(Contains(m, "GaussianId 4 appears twice (positions 0 and 2)")) << m;
  const Genealogy h = Genealogy::Build(std::vector<std::int64_t>{ 4, 5, 4 }, EventTable(), 10, o);
  EXPECT_EQ(h.GetNumberOfNodes(), 2);
  std::string neg;
  try
  {
    Genealogy::Build(std::vector<std::int64_t>{ 4, -5 }, EventTable(), 10);
  }
  catch (const std::runtime_error& e)
  {
    neg = e.what();
  }
  EXPECT_TRUE(Contains(neg, "initial id at position 1 is negative")) << neg;
}

TEST(GenealogyBadInput, EndedTwiceOrUsedAfterDeath)
{
  EventTable t;
  Add(t, 100, 3, 0, -1);
  Add(t, 200, 3, 0, -1);
  std::string m = BuildError(1, t, 1000);
  EXPECT_TRUE(Contains(m, "event row 1 (iteration 200, prune)")) << m;
  EXPECT_TRUE(Contains(m, "already ended at iteration 100 (pruned)")) << m;

  EventTable u;
  Add(u, 100, 2, 0, 1);
  Add(u, 100, 2, 0, 2);
  Add(u, 200, 1, 0, 3);
  m = BuildError(1, u, 1000);
  EXPECT_TRUE(Contains(m, "event row 2 (iteration 200, clone)")) << m;
  EXPECT_TRUE(Contains(m, "already ended at iteration 100 (split)")) << m;

  // Split after a prune in the same interval, coarsened: ended twice.
  EventTable w;
  Add(w, 100, 3, 0, -1);
  Add(w, 200, 2, 0, 1);
  GenealogyOptions o;
  o.CoarsenInterval = 500;
  m = BuildError(1, w, 1000, o);
  EXPECT_TRUE(Contains(m, "already ended at iteration 500 (pruned)")) << m;
  // ... but a clone in the interval of the prune is fine (order inside an interval is lost).
  EventTable x;
  Add(x, 100, 3, 0, -1);
  Add(x, 200, 1, 0, 1);
  const Genealogy g = Genealogy::Build(1, x, 1000, o);
  EXPECT_EQ(g.GetDeathIterations()[0], 500);
  EXPECT_EQ(g.GetPruned()[0], 1);
  EXPECT_EQ(g.GetBirthKinds()[1], BirthKind::Clone);
}

TEST(GenealogyBadInput, ZeroLifespans)
{
  // Born and pruned in the same iteration; a whole family of zero lifespans.
  EventTable t;
  Add(t, 100, 1, 0, 1);
  Add(t, 100, 3, 1, -1);
  Add(t, 100, 3, 0, -1);
  const Genealogy g = Genealogy::Build(std::vector<std::int64_t>{ 0 },
    t,
    1000,
    []
    {
      GenealogyOptions o;
      o.InitialIteration = 100;
      return o;
    }());
  EXPECT_EQ(g.GetLifespans(), (std::vector<std::int32_t>{ 0, 0 }));
  EXPECT_EQ(g.GetFamilyBands()[0].MaxLifespan, 0);
  // T term has a zero denominator: P = 0.4 * D / maxD only.
  EXPECT_DOUBLE_EQ(g.GetPerceptionValues()[0], 0.4);
  EXPECT_DOUBLE_EQ(g.GetPerceptionValues()[1], 0.0);
  for (double p : g.GetPerceptionValues())
  {
    EXPECT_TRUE(std::isfinite(p));
  }
}

TEST(GenealogyBadInput, Empty)
{
  const Genealogy g = Genealogy::Build(0, EventTable(), 0);
  EXPECT_EQ(g.GetNumberOfNodes(), 0);
  EXPECT_EQ(g.GetNumberOfFamilies(), 0);
  EXPECT_TRUE(g.Lineage({}).empty());
  EXPECT_EQ(g.FindNode(0), -1);
  const Genealogy h = Genealogy::Build(3, EventTable(), 50);
  EXPECT_EQ(h.GetNumberOfFamilies(), 3);
  for (double p : h.GetPerceptionValues())
  {
    EXPECT_DOUBLE_EQ(p, 0.6); // single-node families: D term 0, T = max
  }
}

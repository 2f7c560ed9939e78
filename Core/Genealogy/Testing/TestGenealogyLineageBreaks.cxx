// SPDX-License-Identifier: BSD-3-Clause
// Genealogy with lineage breaks (the log's /lineage_breaks): hand-built logs where a trainer
// appended rows outside the logger (the rows before keep their ids, the appended ones are new
// roots) and removed rows (every id alive ends at the break, every row is a new root).
#include "Genealogy.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace
{
using vis4gs::BirthKind;
using vis4gs::EventTable;
using vis4gs::Genealogy;
using vis4gs::GenealogyOptions;
using vis4gs::LineageBreakTable;

void Add(EventTable& t, std::int32_t it, int kind, std::int64_t parent, std::int64_t child)
{
  t.Iteration.push_back(it);
  t.Kind.push_back(static_cast<std::uint8_t>(kind));
  t.Parent.push_back(parent);
  t.Child.push_back(child);
}

void AddBreak(LineageBreakTable& b,
  std::int32_t it,
  std::int64_t row,
  std::int64_t tracked,
  std::int64_t rows,
  std::int64_t kept,
  std::int64_t first)
{
  b.Iteration.push_back(it);
  b.EventRow.push_back(row);
  b.Tracked.push_back(tracked);
  b.Rows.push_back(rows);
  b.Kept.push_back(kept);
  b.FirstNewId.push_back(first);
  b.NewRoots.push_back(rows - kept);
}
} // namespace

// Initial 0, 1. it 10: clone 0 -> 2. Break at 20 before row 1: 3 rows, 2 appended (ids 3, 4
// new roots). it 30: clone 3 -> 5. Break at 40 before row 2 with kept 0: 0..5 end at 40, 4
// rows are new roots 6..9. it 50: split 6 -> 10, 11. Last 60.
TEST(GenealogyLineageBreaks, NewRootsAndEndedIds)
{
  EventTable t;
  Add(t, 10, 1, 0, 2);
  Add(t, 30, 1, 3, 5);
  Add(t, 50, 2, 6, 10);
  Add(t, 50, 2, 6, 11);
  LineageBreakTable breaks;
  AddBreak(breaks, 20, 1, 3, 5, 3, 3);
  AddBreak(breaks, 40, 2, 6, 4, 0, 6);
  GenealogyOptions options;
  options.Breaks = &breaks;
  const Genealogy g = Genealogy::Build(2, t, 60, options);
  ASSERT_EQ(g.GetNumberOfNodes(), 12);
  const std::vector<std::int64_t> ids{ 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11 };
  EXPECT_EQ(g.GetGaussianIds(), ids);
  const std::vector<std::int64_t> roots{ 3, 4, 6, 7, 8, 9 };
  EXPECT_EQ(g.GetBreakRoots(), roots); // node = id here
  const std::vector<std::int32_t> birth{ 0, 0, 10, 20, 20, 30, 40, 40, 40, 40, 50, 50 };
  EXPECT_EQ(g.GetBirthIterations(), birth);
  const std::vector<std::int32_t> death{ 40, 40, 40, 40, 40, 40, 50, -1, -1, -1, -1, -1 };
  EXPECT_EQ(g.GetDeathIterations(), death);
  for (std::int64_t node : roots)
  {
    EXPECT_EQ(g.GetBirthKinds()[node], BirthKind::Root);
    EXPECT_EQ(g.GetParents()[node], -1);
    EXPECT_EQ(g.GetPruned()[node], 0);
  }
  EXPECT_EQ(g.GetParents()[5], 3); // a clone of a new root
  EXPECT_EQ(g.GetParents()[10], 6);
  EXPECT_EQ(g.GetNumberOfFamilies(), 2 + 6);
  EXPECT_TRUE(g.GetWarnings().empty());
}

// A break after the last event (its event row is the table's size), and one without events.
TEST(GenealogyLineageBreaks, AfterTheLastEventAndWithoutEvents)
{
  EventTable t;
  Add(t, 5, 3, 1, -1);
  LineageBreakTable breaks;
  AddBreak(breaks, 7, 1, 2, 4, 2, 3);
  GenealogyOptions options;
  options.Breaks = &breaks;
  Genealogy g = Genealogy::Build(3, t, 9, options);
  EXPECT_EQ(g.GetNumberOfNodes(), 5);
  EXPECT_EQ(g.GetBreakRoots(), (std::vector<std::int64_t>{ 3, 4 }));
  EXPECT_EQ(g.GetBirthIterations()[4], 7);
  EXPECT_EQ(g.GetDeathIterations()[0], -1); // kept: lives on

  g = Genealogy::Build(2, EventTable(), 9, options);
  EXPECT_EQ(g.GetNumberOfNodes(), 4);
  EXPECT_EQ(g.GetGaussianIds()[3], 4);
}

// A new root whose id exists already is an error naming the break.
TEST(GenealogyLineageBreaks, RepeatedIdIsAnError)
{
  EventTable t;
  Add(t, 10, 1, 0, 2);
  LineageBreakTable breaks;
  AddBreak(breaks, 20, 1, 3, 4, 3, 2);
  GenealogyOptions options;
  options.Breaks = &breaks;
  try
  {
    Genealogy::Build(2, t, 60, options);
    FAIL() << "no error";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_NE(std::string(e.what()).find("lineage break 0 (iteration 20)"), std::string::npos)
      << e.what();
  }
}

// SPDX-License-Identifier: BSD-3-Clause
// SortedIdLookup.h: the rows of sorted ids in a sorted id column, checked against a scan of the
// column with a set of the ids (what the linked views did before) on random columns with gaps,
// duplicates, a contiguous range, ids absent or outside the column, and the edge cases.
#include "SortedIdLookup.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <set>
#include <vector>

namespace vis4gs
{
namespace
{
std::vector<std::size_t> Scan(const std::vector<std::int64_t>& column,
  const std::vector<std::int64_t>& ids)
{
  const std::set<std::int64_t> wanted(ids.begin(), ids.end());
  std::vector<std::size_t> rows;
  for (std::size_t i = 0; i < column.size(); ++i)
  {
    if (wanted.count(column[i]))
    {
      rows.push_back(i);
    }
  }
  return rows;
}

std::vector<std::size_t> Lookup(const std::vector<std::int64_t>& column,
  const std::vector<std::int64_t>& ids)
{
  const IdColumnOrder order = InspectIdColumn(column.data(), column.size());
  std::vector<std::size_t> rows;
  ForEachRowOfSortedIds(column.data(),
    column.size(),
    order,
    ids.data(),
    ids.size(),
    [&](std::size_t r) { rows.push_back(r); });
  return rows;
}

// Sorted ids drawn from [lo, hi), about a fraction @p density of them, some repeated.
std::vector<std::int64_t> SortedIds(std::mt19937_64& rng,
  std::int64_t lo,
  std::int64_t hi,
  double density)
{
  std::bernoulli_distribution take(density), twice(0.1);
  std::vector<std::int64_t> ids;
  for (std::int64_t v = lo; v < hi; ++v)
  {
    if (take(rng))
    {
      ids.push_back(v);
      if (twice(rng))
      {
        ids.push_back(v);
      }
    }
  }
  return ids;
}
}

TEST(SortedIdLookup, InspectTellsSortedAndContiguous)
{
  const std::vector<std::int64_t> contiguous{ 7, 8, 9, 10 };
  const std::vector<std::int64_t> gaps{ 0, 2, 3, 9 };
  const std::vector<std::int64_t> repeated{ 1, 2, 2, 3 };
  const std::vector<std::int64_t> unsorted{ 0, 1, 3, 2 };
  IdColumnOrder o = InspectIdColumn(contiguous.data(), contiguous.size());
  EXPECT_TRUE(o.Sorted);
  EXPECT_TRUE(o.Contiguous);
  EXPECT_EQ(o.First, 7);
  o = InspectIdColumn(gaps.data(), gaps.size());
  EXPECT_TRUE(o.Sorted);
  EXPECT_FALSE(o.Contiguous);
  o = InspectIdColumn(repeated.data(), repeated.size());
  EXPECT_TRUE(o.Sorted);
  EXPECT_FALSE(o.Contiguous);
  o = InspectIdColumn(unsorted.data(), unsorted.size());
  EXPECT_FALSE(o.Sorted);
  EXPECT_FALSE(o.Contiguous);
  o = InspectIdColumn(nullptr, 0);
  EXPECT_TRUE(o.Sorted);
}

TEST(SortedIdLookup, EqualsAScanOnRandomColumns)
{
  std::mt19937_64 rng(20261129);
  for (int trial = 0; trial < 200; ++trial)
  {
    // A column with gaps and repeated ids (a filtered snapshot), or a contiguous one.
    const bool contiguous = trial % 3 == 0;
    std::vector<std::int64_t> column;
    std::uniform_int_distribution<int> gap(0, 3), repeat(0, 9);
    std::int64_t v = std::uniform_int_distribution<std::int64_t>(-5, 50)(rng);
    const int n = std::uniform_int_distribution<int>(0, 3000)(rng);
    for (int i = 0; i < n; ++i)
    {
      column.push_back(v);
      v += contiguous ? 1 : (repeat(rng) == 0 ? 0 : gap(rng) + 1);
    }
    ASSERT_EQ(InspectIdColumn(column.data(), column.size()).Contiguous, contiguous || n <= 1)
      << "trial " << trial;
    // Ids around and beyond the column's range, dense or sparse.
    const std::int64_t lo = column.empty() ? -10 : column.front() - 20;
    const std::int64_t hi = column.empty() ? 10 : column.back() + 20;
    const double density = trial % 4 == 0 ? 0.9 : trial % 4 == 1 ? 0.2 : 0.003;
    const std::vector<std::int64_t> ids = SortedIds(rng, lo, hi, density);
    EXPECT_EQ(Lookup(column, ids), Scan(column, ids)) << "trial " << trial;
  }
}

TEST(SortedIdLookup, EdgeCases)
{
  const std::vector<std::int64_t> column{ 3, 5, 5, 5, 8, 20 };
  EXPECT_EQ(Lookup(column, {}), std::vector<std::size_t>{});
  EXPECT_EQ(Lookup(column, { 5 }), (std::vector<std::size_t>{ 1, 2, 3 }));
  EXPECT_EQ(Lookup(column, { 5, 5, 5 }), (std::vector<std::size_t>{ 1, 2, 3 }));
  EXPECT_EQ(Lookup(column, { 1, 2, 4, 21 }), std::vector<std::size_t>{});
  EXPECT_EQ(Lookup(column, { 3, 20 }), (std::vector<std::size_t>{ 0, 5 }));
  EXPECT_EQ(Lookup({}, { 1, 2 }), std::vector<std::size_t>{});
  const std::vector<std::int64_t> range{ 10, 11, 12, 13 };
  EXPECT_EQ(Lookup(range, { 9, 10, 10, 13, 14 }), (std::vector<std::size_t>{ 0, 3 }));
  // An unsorted column gives nothing: the caller looks up another way.
  const std::vector<std::int64_t> unsorted{ 2, 1 };
  EXPECT_EQ(Lookup(unsorted, { 1, 2 }), std::vector<std::size_t>{});
}

} // namespace vis4gs

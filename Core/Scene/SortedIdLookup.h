// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SortedIdLookup.h
 * @brief The rows of a selection's GaussianIds in a scene's id column, in O(selection) when the
 * column is sorted: every linked view (the scene view's markers and highlight, the splat
 * mapper's selected flags, the histogram's orange bars, the frustums' counts, the selection
 * table) looks the hub's ids up after each pick, and a snapshot's ids ascend (a scene's are
 * 0..N-1). Header only.
 *
 * A scan of the whole column per pick cost 70-120 ms of a 4.89M-Gaussian pick; a binary search
 * per id costs log2(N) scattered reads each (about 4M for a 200k-Gaussian Frame). Here the ids,
 * sorted, are searched from the previous one's row on with a galloping (exponential) search:
 * O(k log(N / k)) reads that stay close together, and O(k) with no read of the column at all
 * when the column is contiguous (row = id - first id).
 */
#ifndef vis4gs_SortedIdLookup_h
#define vis4gs_SortedIdLookup_h

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace vis4gs
{

/// What InspectIdColumn() found out about an id column.
struct IdColumnOrder
{
  /// The ids never decrease (duplicates allowed).
  bool Sorted = false;
  /// column[i] == First + i for every row: the row of id v is v - First.
  bool Contiguous = false;
  std::int64_t First = 0;
};

/// One pass over @p column's @p n ids (an empty column is sorted and contiguous).
inline IdColumnOrder InspectIdColumn(const std::int64_t* column, std::size_t n)
{
  IdColumnOrder order;
  order.Sorted = true;
  order.Contiguous = true;
  order.First = n > 0 ? column[0] : 0;
  for (std::size_t i = 1; i < n && order.Sorted; ++i)
  {
    order.Sorted = column[i - 1] <= column[i];
    order.Contiguous = order.Contiguous && column[i] == column[i - 1] + 1;
  }
  order.Contiguous = order.Contiguous && order.Sorted;
  return order;
}

/**
 * Calls @p row(r) for every row r of @p column (@p n ids, sorted: @p order from
 * InspectIdColumn(), with Sorted true) whose id is one of @p ids (@p count of them, ascending;
 * repeated ids count once), in ascending row order: the rows a scan of the column with a set of
 * @p ids would give, in the same order. Ids absent from the column give no row. Does nothing when
 * @p order is not Sorted.
 */
template <typename RowFunction>
void ForEachRowOfSortedIds(const std::int64_t* column,
  std::size_t n,
  const IdColumnOrder& order,
  const std::int64_t* ids,
  std::size_t count,
  RowFunction&& row)
{
  if (!order.Sorted || n == 0)
  {
    return;
  }
  if (order.Contiguous)
  {
    // Ids outside [First, First + n) are absent; the rest are their own rows.
    const std::int64_t* begin = std::lower_bound(ids, ids + count, order.First);
    for (const std::int64_t* it = begin; it != ids + count; ++it)
    {
      if (it != begin && *it == *(it - 1))
      {
        continue;
      }
      const std::int64_t offset = *it - order.First;
      if (offset >= static_cast<std::int64_t>(n))
      {
        break;
      }
      row(static_cast<std::size_t>(offset));
    }
    return;
  }
  std::size_t from = 0; // every row before it holds an id smaller than the next id
  for (std::size_t k = 0; k < count && from < n; ++k)
  {
    const std::int64_t id = ids[k];
    if (k > 0 && id == ids[k - 1])
    {
      continue;
    }
    // Galloping: the first row >= id lies in (from + step / 2, from + step].
    std::size_t lo = from, hi = from, step = 1;
    while (hi < n && column[hi] < id)
    {
      lo = hi + 1;
      hi = from + step;
      step *= 2;
    }
    hi = std::min(hi, n);
    std::size_t at =
      static_cast<std::size_t>(std::lower_bound(column + lo, column + hi, id) - column);
    from = at;
    for (; at < n && column[at] == id; ++at)
    {
      row(at);
    }
  }
}

} // namespace vis4gs

#endif

/*=========================================================================

  Program:   Vis4GS
  Module:    TestVis4GSIdColumn.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
// The rows of sorted GaussianIds in an id column (Vis4GSIdColumn.h), against a scan of the
// column with a set of the ids; the remembered column order is dropped when the column is
// modified, and columns it cannot search are refused (the caller's other path then answers).
#include "Vis4GSIdColumn.h"

#include "vtkIdTypeArray.h"
#include "vtkNew.h"

#include "Vis4GSTestCheck.h"

#include <random>
#include <set>
#include <vector>

namespace
{
vis4gs::testing::CheckCounter Check;

std::vector<vtkIdType> Scan(vtkIdTypeArray* column, const std::vector<vtkIdType>& ids)
{
  const std::set<vtkIdType> wanted(ids.begin(), ids.end());
  std::vector<vtkIdType> rows;
  for (vtkIdType i = 0; i < column->GetNumberOfTuples(); ++i)
  {
    if (wanted.count(column->GetValue(i)))
    {
      rows.push_back(i);
    }
  }
  return rows;
}
}

int TestVis4GSIdColumn(int, char*[])
{
  std::mt19937_64 rng(30);
  std::uniform_int_distribution<int> gap(1, 4);
  std::bernoulli_distribution take(0.05);
  // A snapshot's column: ascending ids with gaps (pruned Gaussians), 200k rows.
  vtkNew<vtkIdTypeArray> column;
  column->SetNumberOfTuples(200000);
  vtkIdType v = 17;
  for (vtkIdType i = 0; i < column->GetNumberOfTuples(); ++i)
  {
    column->SetValue(i, v);
    v += gap(rng);
  }
  std::vector<vtkIdType> ids;
  for (vtkIdType id = 0; id < v + 10; ++id)
  {
    if (take(rng))
    {
      ids.push_back(id);
    }
  }
  std::vector<vtkIdType> rows;
  Check(vis4gs::RowsOfSortedIds(column, ids.data(), static_cast<vtkIdType>(ids.size()), rows),
    "a sorted column is searched");
  Check(!rows.empty() && rows == Scan(column, ids), "rows of a column with gaps equal the scan");
  vis4gs::IdColumnOrder order = vis4gs::IdColumnOrderOf(column);
  Check(order.Sorted && !order.Contiguous, "a column with gaps is sorted, not contiguous");

  // The same column made contiguous: the remembered order must follow the modification.
  for (vtkIdType i = 0; i < column->GetNumberOfTuples(); ++i)
  {
    column->SetValue(i, 1000 + i);
  }
  column->Modified();
  order = vis4gs::IdColumnOrderOf(column);
  Check(order.Sorted && order.Contiguous && order.First == 1000, "modified: contiguous now");
  rows.clear();
  Check(vis4gs::RowsOfSortedIds(column, ids.data(), static_cast<vtkIdType>(ids.size()), rows) &&
      rows == Scan(column, ids),
    "rows of a contiguous column equal the scan");

  // Unsorted now: refused, nothing appended.
  column->SetValue(5, 5);
  column->Modified();
  rows.clear();
  Check(!vis4gs::RowsOfSortedIds(column, ids.data(), static_cast<vtkIdType>(ids.size()), rows) &&
      rows.empty(),
    "an unsorted column is refused");
  Check(!vis4gs::IdColumnOrderOf(column).Sorted, "modified: unsorted now");

  // Ids that do not ascend, and a column of two components, are refused too.
  vtkNew<vtkIdTypeArray> sorted;
  sorted->SetNumberOfTuples(10);
  for (vtkIdType i = 0; i < 10; ++i)
  {
    sorted->SetValue(i, 2 * i);
  }
  const std::vector<vtkIdType> descending{ 8, 4 };
  Check(!vis4gs::RowsOfSortedIds(sorted, descending.data(), 2, rows), "descending ids refused");
  vtkNew<vtkIdTypeArray> pairs;
  pairs->SetNumberOfComponents(2);
  pairs->SetNumberOfTuples(3);
  Check(!vis4gs::RowsOfSortedIds(pairs, descending.data(), 0, rows), "two components refused");
  Check(vis4gs::RowsOfSortedIds(sorted, nullptr, 0, rows) && rows.empty(), "no ids: no rows");
  return Check.ExitCode();
}

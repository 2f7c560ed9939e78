/*=========================================================================

  Program:   Vis4GS
  Module:    Vis4GSIdColumn.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "Vis4GSIdColumn.h"

#include "vtkIdTypeArray.h"
#include "vtkWeakPointer.h"

#include <algorithm>
#include <array>
#include <cstdint>

static_assert(sizeof(vtkIdType) == sizeof(std::int64_t), "GaussianIds are 64-bit vtkIdTypes");

namespace vis4gs
{
//------------------------------------------------------------------------------
IdColumnOrder IdColumnOrderOf(vtkIdTypeArray* column)
{
  if (!column || column->GetNumberOfComponents() != 1)
  {
    return IdColumnOrder();
  }
  // Per thread: the views live on the GUI thread, a script's pipeline on its own. Four
  // columns: the read scene's, the scored scene's (a copy when the scores replaced arrays),
  // and a table's or two.
  struct Cached
  {
    vtkWeakPointer<vtkIdTypeArray> Column;
    vtkMTimeType Time = 0;
    IdColumnOrder Order;
  };
  thread_local std::array<Cached, 4> cache;
  thread_local std::size_t next = 0;
  for (const Cached& c : cache)
  {
    if (c.Column == column && c.Time == column->GetMTime())
    {
      return c.Order;
    }
  }
  Cached& slot = cache[next];
  next = (next + 1) % cache.size();
  slot.Column = column;
  slot.Time = column->GetMTime();
  slot.Order = InspectIdColumn(reinterpret_cast<const std::int64_t*>(column->GetPointer(0)),
    static_cast<std::size_t>(column->GetNumberOfTuples()));
  return slot.Order;
}

//------------------------------------------------------------------------------
bool RowsOfSortedIds(vtkIdTypeArray* column,
  const vtkIdType* ids,
  vtkIdType count,
  std::vector<vtkIdType>& rows)
{
  return ForEachRowOfIds(column, ids, count, [&](vtkIdType r) { rows.push_back(r); });
}
} // namespace vis4gs

/*=========================================================================

  Program:   Vis4GS
  Module:    Vis4GSIdColumn.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @file Vis4GSIdColumn.h
 * @brief The rows of selected GaussianIds in a scene's GaussianId column, in O(selection):
 * shared by the selection hub's IdsToIndices (the scene view, the histogram, the selection
 * table) and the frustums' counts, which look the hub's ids up after every pick.
 *
 * Core's SortedIdLookup.h does the lookup; this keeps what it needs to know about a column
 * (sorted, contiguous) for the last few columns until they are modified, so that a pick does
 * not scan the 4.89M ids again for each view.
 */
#ifndef Vis4GSIdColumn_h
#define Vis4GSIdColumn_h

#include "SortedIdLookup.h"      // For IdColumnOrder
#include "vis4gsIOSceneModule.h" // For export macro
#include "vtkIdTypeArray.h"      // For the inline lookup
#include "vtkType.h"             // For vtkIdType

#include <algorithm>
#include <cstdint>
#include <vector>

namespace vis4gs
{
/**
 * InspectIdColumn() of @p column (a one-component vtkIdTypeArray; otherwise an order that is not
 * Sorted), remembered for the last four columns of the calling thread until their MTime changes.
 */
VIS4GSIOSCENE_EXPORT IdColumnOrder IdColumnOrderOf(vtkIdTypeArray* column);

/**
 * Calls @p row(r) for each row r of @p column holding one of @p ids (@p count of them,
 * ascending), in ascending order (ForEachRowOfSortedIds()), without collecting the rows: the
 * histogram counts a 200,000-Gaussian selection's values this way. Returns false, calling
 * nothing, when @p column is not a sorted one-component vtkIdTypeArray or @p ids do not ascend.
 */
template <typename RowFunction>
bool ForEachRowOfIds(vtkIdTypeArray* column,
  const vtkIdType* ids,
  vtkIdType count,
  RowFunction&& row)
{
  static_assert(sizeof(vtkIdType) == sizeof(std::int64_t), "GaussianIds are 64-bit vtkIdTypes");
  const IdColumnOrder order = IdColumnOrderOf(column);
  if (!order.Sorted || count < 0 || (count > 0 && !ids) || !std::is_sorted(ids, ids + count))
  {
    return false;
  }
  ForEachRowOfSortedIds(reinterpret_cast<const std::int64_t*>(column->GetPointer(0)),
    static_cast<std::size_t>(column->GetNumberOfTuples()),
    order,
    reinterpret_cast<const std::int64_t*>(ids),
    static_cast<std::size_t>(count),
    [&](std::size_t r) { row(static_cast<vtkIdType>(r)); });
  return true;
}

/**
 * Appends to @p rows the rows of @p column holding one of @p ids (@p count of them, ascending),
 * in ascending order (ForEachRowOfSortedIds()). Returns false, appending nothing, when @p column
 * is not a sorted one-component vtkIdTypeArray or @p ids do not ascend: the caller then looks the
 * ids up its own way.
 */
VIS4GSIOSCENE_EXPORT bool RowsOfSortedIds(vtkIdTypeArray* column,
  const vtkIdType* ids,
  vtkIdType count,
  std::vector<vtkIdType>& rows);
} // namespace vis4gs

#endif

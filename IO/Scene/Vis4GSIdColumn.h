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
#include "vtkType.h"             // For vtkIdType

#include <vector>

class vtkIdTypeArray;

namespace vis4gs
{
/**
 * InspectIdColumn() of @p column (a one-component vtkIdTypeArray; otherwise an order that is not
 * Sorted), remembered for the last four columns of the calling thread until their MTime changes.
 */
VIS4GSIOSCENE_EXPORT IdColumnOrder IdColumnOrderOf(vtkIdTypeArray* column);

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

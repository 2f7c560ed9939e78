/*=========================================================================

  Program:   Vis4GS
  Module:    Vis4GSLineageBreaks.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @file Vis4GSLineageBreaks.h
 * @brief The log's /lineage_breaks as field data of the events table: the one list of its
 * columns that vtkGaussianTrainingLogReader writes and vtkGaussianGenealogyAdapter reads.
 */
#ifndef Vis4GSLineageBreaks_h
#define Vis4GSLineageBreaks_h

#include "Vis4GSDataModel.h" // For the EventBreak* names

#include <array>   // For std::array
#include <utility> // For std::pair

namespace vis4gs
{
namespace arrays
{
/// The break columns after EventBreakIteration (an int column of its own), each with its
/// column of @p breaks (a vis4gs::LineageBreakTable of Core/TrainingLog, const or not; a
/// template, so that this module needs no Core/TrainingLog).
template <typename Breaks>
auto LineageBreakIdColumns(Breaks& breaks)
{
  using Column = decltype(&breaks.EventRow);
  return std::array<std::pair<const char*, Column>, 6>{ {
    { EventBreakEventRow, &breaks.EventRow },
    { EventBreakTracked, &breaks.Tracked },
    { EventBreakRows, &breaks.Rows },
    { EventBreakKept, &breaks.Kept },
    { EventBreakFirstNewId, &breaks.FirstNewId },
    { EventBreakNewRoots, &breaks.NewRoots },
  } };
}
} // namespace arrays
} // namespace vis4gs

#endif

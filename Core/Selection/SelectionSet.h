// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SelectionSet.h
 * @brief Sets of selected Gaussians and the replace / add / subtract modifiers shared by every
 * selection mode. A selection is a sorted vector of unique values (Gaussian indices or ids).
 */
#ifndef vis4gs_SelectionSet_h
#define vis4gs_SelectionSet_h

#include <cstdint>
#include <vector>

namespace vis4gs
{

/// How a new selection combines with the current one.
enum class SelectionModifier : std::uint8_t
{
  Replace = 0,  ///< the new selection replaces the current one
  Add = 1,      ///< union
  Subtract = 2, ///< current minus new
  Toggle = 3,   ///< symmetric difference
  Intersect = 4 ///< current and new (a rule applied within an earlier selection)
};

/// Sorts @p values and removes duplicates.
void NormalizeSelection(std::vector<std::int64_t>& values);

/**
 * Combines @p current (sorted, unique) with @p incoming (any order, duplicates allowed) by
 * @p modifier; returns a sorted, unique selection.
 */
std::vector<std::int64_t> CombineSelection(const std::vector<std::int64_t>& current,
  std::vector<std::int64_t> incoming,
  SelectionModifier modifier);

} // namespace vis4gs

#endif

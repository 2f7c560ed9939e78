// SPDX-License-Identifier: BSD-3-Clause
#include "SelectionSet.h"

#include <algorithm>
#include <iterator>

namespace vis4gs
{

//------------------------------------------------------------------------------
void NormalizeSelection(std::vector<std::int64_t>& values)
{
  // A pick's indices come ascending (a scan of the frame): checking is one pass, sorting more.
  if (!std::is_sorted(values.begin(), values.end()))
  {
    std::sort(values.begin(), values.end());
  }
  values.erase(std::unique(values.begin(), values.end()), values.end());
}

//------------------------------------------------------------------------------
std::vector<std::int64_t> CombineSelection(const std::vector<std::int64_t>& current,
  std::vector<std::int64_t> incoming,
  SelectionModifier modifier)
{
  NormalizeSelection(incoming);
  std::vector<std::int64_t> out;
  switch (modifier)
  {
    case SelectionModifier::Replace:
      return incoming;
    case SelectionModifier::Add:
      std::set_union(
        current.begin(), current.end(), incoming.begin(), incoming.end(), std::back_inserter(out));
      break;
    case SelectionModifier::Subtract:
      std::set_difference(
        current.begin(), current.end(), incoming.begin(), incoming.end(), std::back_inserter(out));
      break;
    case SelectionModifier::Toggle:
      std::set_symmetric_difference(
        current.begin(), current.end(), incoming.begin(), incoming.end(), std::back_inserter(out));
      break;
    case SelectionModifier::Intersect:
      std::set_intersection(
        current.begin(), current.end(), incoming.begin(), incoming.end(), std::back_inserter(out));
      break;
  }
  return out;
}

} // namespace vis4gs

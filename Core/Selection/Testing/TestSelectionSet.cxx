// SPDX-License-Identifier: BSD-3-Clause
#include "SelectionSet.h"

#include <gtest/gtest.h>

namespace vis4gs
{

TEST(SelectionSet, Modifiers)
{
  const std::vector<std::int64_t> current{ 1, 3, 5, 7 };
  const std::vector<std::int64_t> incoming{ 7, 2, 3, 3, 9 };
  typedef std::vector<std::int64_t> V;
  EXPECT_EQ(CombineSelection(current, incoming, SelectionModifier::Replace), (V{ 2, 3, 7, 9 }));
  EXPECT_EQ(CombineSelection(current, incoming, SelectionModifier::Add), (V{ 1, 2, 3, 5, 7, 9 }));
  EXPECT_EQ(CombineSelection(current, incoming, SelectionModifier::Subtract), (V{ 1, 5 }));
  EXPECT_EQ(CombineSelection(current, incoming, SelectionModifier::Toggle), (V{ 1, 2, 5, 9 }));
  EXPECT_EQ(CombineSelection(current, incoming, SelectionModifier::Intersect), (V{ 3, 7 }));
  EXPECT_EQ(CombineSelection({}, {}, SelectionModifier::Add), V{});
  EXPECT_EQ(CombineSelection(current, {}, SelectionModifier::Subtract), current);
  EXPECT_EQ(CombineSelection(current, {}, SelectionModifier::Replace), V{});
  V n{ 5, -1, 5, 2 };
  NormalizeSelection(n);
  EXPECT_EQ(n, (V{ -1, 2, 5 }));
}

} // namespace vis4gs

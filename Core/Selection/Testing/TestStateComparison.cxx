// SPDX-License-Identifier: BSD-3-Clause
// Two states compared by id (issue 20): planted births, deaths, moves, opacity and scale
// changes with hand-derived values; thresholds are strict; repeated ids are refused.
#include "StateComparison.h"

#include "GaussianMath.h"
#include "RemovalEffect.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace vis4gs
{
namespace
{
GaussianCloud Cloud(const std::vector<std::int64_t>& ids)
{
  GaussianCloud c;
  c.Resize(ids.size(), 0);
  c.Ids = ids;
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      c.Positions[3 * i + k] = static_cast<float>(ids[i]) + 0.25f * k;
      c.LogScales[3 * i + k] = -2.0f;
    }
    c.Rotations[4 * i] = 1;
    c.OpacityLogits[i] = 0.5f;
  }
  return c;
}

TEST(StateComparison, PlantedChanges)
{
  const GaussianCloud a = Cloud({ 1, 2, 3, 4, 5, 6 });
  // b: 1 died; 2 unchanged; 3 moved by (3, 4, 0) -> 5; 4 opacity logit 0.5 -> -0.5;
  // 5 scale axis y x e^0.3 and axis z x e^-0.5; 6 unchanged; 9 and 7 born (listed out of order).
  GaussianCloud b = Cloud({ 9, 2, 3, 4, 5, 6, 7 });
  b.Positions[3 * 2 + 0] += 3;
  b.Positions[3 * 2 + 1] += 4;
  b.OpacityLogits[3] = -0.5f;
  b.LogScales[3 * 4 + 1] += 0.3f;
  b.LogScales[3 * 4 + 2] -= 0.5f;
  b.Positions[3 * 5 + 0] = std::numeric_limits<float>::infinity();
  GaussianCloud a2 = a;
  a2.Positions[3 * 5 + 0] = std::numeric_limits<float>::infinity(); // same inf: no change

  const StateComparison c = CompareStates(a2, b);
  EXPECT_EQ(c.CountA, 6u);
  EXPECT_EQ(c.CountB, 7u);
  EXPECT_EQ(c.Matched, 5u);
  EXPECT_EQ(c.Died, 1u);
  EXPECT_EQ(c.Born, 2u);
  EXPECT_EQ(c.Moved, 1u);
  EXPECT_EQ(c.OpacityChanged, 1u);
  EXPECT_EQ(c.ScaleChanged, 1u);
  EXPECT_EQ(c.Unchanged, 2u);
  ASSERT_EQ(c.Gaussians.size(), 8u);
  const std::int64_t ids[] = { 1, 2, 3, 4, 5, 6, 7, 9 };
  const char* names[] = {
    "died", "unchanged", "moved", "opacity", "scale", "unchanged", "born", "born"
  };
  for (std::size_t k = 0; k < 8; ++k)
  {
    EXPECT_EQ(c.Gaussians[k].Id, ids[k]);
    EXPECT_EQ(StateChangeName(c.Gaussians[k].Change), names[k]) << "id " << ids[k];
  }
  EXPECT_EQ(c.Gaussians[0].IndexA, 0);
  EXPECT_EQ(c.Gaussians[0].IndexB, -1);
  EXPECT_TRUE(std::isnan(c.Gaussians[0].Move));
  EXPECT_EQ(c.Gaussians[6].IndexB, 6);
  EXPECT_EQ(c.Gaussians[7].IndexB, 0);
  EXPECT_DOUBLE_EQ(c.Gaussians[2].Move, 5.0);
  EXPECT_NEAR(c.Gaussians[3].Opacity, 1 / (1 + std::exp(0.5)) - 1 / (1 + std::exp(-0.5)), 1e-12);
  EXPECT_NEAR(c.Gaussians[4].Scale, -0.5, 1e-6); // the axis of largest |change|, signed
  EXPECT_EQ(c.Gaussians[5].Move, 0.0);

  // Strict thresholds: a move of exactly 5 is not beyond 5, nor a log-scale change of exactly
  // -0.5 (-2 - 0.5 is exact in float) beyond 0.5; an opacity change of 0.2449 is beyond 0.2.
  StateThresholds t;
  t.Move = 5;
  t.Opacity = 0.2;
  t.Scale = 0.5;
  const StateComparison d = CompareStates(a2, b, t);
  EXPECT_EQ(d.Moved, 0u);
  EXPECT_EQ(d.OpacityChanged, 1u);
  EXPECT_EQ(d.ScaleChanged, 0u);
  EXPECT_EQ(d.Unchanged, 4u);
}

TEST(StateComparison, SceneAgainstItsCleanedCopy)
{
  GaussianCloud a = Cloud({ 0, 1, 2, 3, 4 });
  a.Ids.clear(); // a scene without ids: its indices are its ids
  const std::vector<std::uint8_t> removed = { 0, 1, 0, 1, 0 };
  const StateComparison c = CompareStates(a, RemoveGaussians(a, removed));
  EXPECT_EQ(c.Died, 2u);
  EXPECT_EQ(c.Unchanged, 3u);
  EXPECT_EQ(c.Born, 0u);
  EXPECT_EQ(c.Gaussians[1].Change, StateDied);
  EXPECT_EQ(c.Gaussians[3].Change, StateDied);
}

TEST(StateComparison, RefusesRepeatedIdsAndMissingArrays)
{
  const GaussianCloud a = Cloud({ 1, 2, 2 });
  try
  {
    CompareStates(Cloud({ 1 }), a);
    FAIL() << "a repeated id was accepted";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("state B holds id 2 twice"), std::string::npos)
      << e.what();
  }
  GaussianCloud partial = Cloud({ 1, 2 });
  partial.LogScales.clear();
  EXPECT_THROW(CompareStates(partial, a), std::invalid_argument);
}

} // namespace
} // namespace vis4gs

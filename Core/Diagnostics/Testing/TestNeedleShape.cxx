// SPDX-License-Identifier: BSD-3-Clause
#include "NeedleShape.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace vis4gs
{
namespace
{
// Textbook formula on the activated scales, for comparison where it does not overflow.
double NaiveNeedleShape(double a, double b, double c)
{
  const double v[3] = { std::exp(2 * a), std::exp(2 * b), std::exp(2 * c) };
  const double sum = v[0] + v[1] + v[2];
  double h = 0;
  for (double x : v)
  {
    const double q = x / sum;
    if (q > 0)
    {
      h -= q * std::log(q);
    }
  }
  return (3 - std::exp(h)) / 2;
}
constexpr double inf = std::numeric_limits<double>::infinity();
}

TEST(NeedleShape, ReferenceEffectiveRanks)
{
  // Reference §6.1 values (scales, not log-scales).
  auto erank = [](double a, double b, double c)
  {
    const double l[3] = { std::log(a), std::log(b), std::log(c) };
    return EffectiveRank(l);
  };
  EXPECT_NEAR(erank(1, 1, 1), 3.0, 1e-15);
  EXPECT_NEAR(erank(1, 0.5, 0.5), 2.381, 1e-3);
  EXPECT_NEAR(erank(1, 0.3, 0.3), 1.704, 1e-3);
  EXPECT_NEAR(erank(1, 0.1, 0.1), 1.116, 1e-3);
  EXPECT_NEAR(erank(1, 1, 0.1), 2.057, 1e-3);
  EXPECT_NEAR(erank(1, 1, 0.001), 2.000, 1e-3);
  EXPECT_NEAR(erank(1, 0.001, 0.001), 1.00003, 1e-5);
}

TEST(NeedleShape, AgreesWithNaiveFormulaInSafeRange)
{
  for (double a : { -3.0, -0.5, 0.0, 1.2 })
  {
    for (double b : { -2.0, 0.3, 2.0 })
    {
      for (double c : { -1.0, 0.0, 4.0 })
      {
        const double l[3] = { a, b, c };
        EXPECT_NEAR(NeedleShape(l), NaiveNeedleShape(a, b, c), 1e-13) << a << " " << b << " " << c;
      }
    }
  }
}

TEST(NeedleShape, EqualScalesGiveZeroExactly)
{
  for (double v : { -700.0, -30.0, 0.0, 1e-3, 30.0, 700.0, -1000.0, 1000.0 })
  {
    const double l[3] = { v, v, v };
    EXPECT_EQ(NeedleShape(l), 0.0) << v;
    EXPECT_EQ(EffectiveRank(l), 3.0) << v;
  }
}

TEST(NeedleShape, ExtremeLogScalesStayFiniteAndCorrect)
{
  // One dominant axis: s -> 1.
  const double needle[3] = { 700, -700, -700 };
  EXPECT_NEAR(NeedleShape(needle), 1.0, 1e-15);
  // Two equal dominant axes: s -> 1/2 within 1e-12 (a flat disk).
  const double disk[3] = { 700, 700, -700 };
  EXPECT_NEAR(NeedleShape(disk), 0.5, 1e-12);
  const double disk2[3] = { -10, -10, -40 };
  EXPECT_NEAR(NeedleShape(disk2), 0.5, 1e-12);
  // Scales of 1e-30 and 1e30 (log-scales about -69 and +69) in float would overflow sigma^2.
  const double tiny[3] = { std::log(1e-30), std::log(1e-30), std::log(1e30) };
  EXPECT_NEAR(NeedleShape(tiny), 1.0, 1e-15);
  // A ratio of 1e8 on one axis: q of the small axes ~1e-16, s within 1e-14 of 1.
  const double ratio[3] = { 0, -std::log(1e8), -std::log(1e8) };
  EXPECT_NEAR(NeedleShape(ratio), 1.0, 1e-14);
  for (double v : { -700.0, 700.0 })
  {
    for (double w : { -700.0, 0.0, 700.0 })
    {
      const double l[3] = { v, w, 0.0 };
      const double s = NeedleShape(l);
      EXPECT_TRUE(std::isfinite(s));
      EXPECT_GE(s, 0.0);
      EXPECT_LE(s, 1.0);
    }
  }
}

TEST(NeedleShape, InfinitiesAndNaN)
{
  const double oneInf[3] = { inf, 0, 0 };
  EXPECT_EQ(NeedleShape(oneInf), 1.0);
  const double twoInf[3] = { inf, inf, 0 };
  EXPECT_NEAR(NeedleShape(twoInf), 0.5, 1e-15);
  const double minusInf[3] = { -inf, 0, 0 };
  EXPECT_NEAR(NeedleShape(minusInf), 0.5, 1e-15);
  const double allMinusInf[3] = { -inf, -inf, -inf };
  EXPECT_EQ(NeedleShape(allMinusInf), 0.0);
  const double nan[3] = { 0, std::nan(""), 0 };
  EXPECT_TRUE(std::isnan(NeedleShape(nan)));
}

TEST(NeedleShape, BatchMatchesScalarAndLeavesNaN)
{
  const float ls[9] = { 0, 0, 0, 1, -2, 0.5f, std::nanf(""), 0, 0 };
  double s[3], r[3];
  ComputeNeedleShapes(ls, 3, s, r);
  const double g1[3] = { 1, -2, 0.5 };
  EXPECT_EQ(s[0], 0.0);
  EXPECT_EQ(s[1], NeedleShape(g1));
  EXPECT_EQ(r[1], EffectiveRank(g1));
  EXPECT_TRUE(std::isnan(s[2]));
}

} // namespace vis4gs

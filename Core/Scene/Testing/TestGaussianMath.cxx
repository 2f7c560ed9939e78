// SPDX-License-Identifier: BSD-3-Clause
#include "Camera.h"
#include "GaussianCloud.h"
#include "GaussianMath.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

namespace vis4gs
{

TEST(GaussianMath, SigmoidIsFiniteAndMonotoneAtExtremes)
{
  EXPECT_EQ(Sigmoid(0.0), 0.5);
  EXPECT_EQ(Sigmoid(1000.0), 1.0);
  EXPECT_EQ(Sigmoid(-1000.0), 0.0);
  EXPECT_GT(Sigmoid(-100.0), 0.0); // e^-100 is representable in double
  EXPECT_EQ(Sigmoid(-1000.0f), 0.0f);
  EXPECT_FALSE(std::isnan(Sigmoid(-std::numeric_limits<double>::infinity())));
  // Symmetry s(-x) = 1 - s(x) checked against the textbook formula in a safe range.
  for (double x : { -30.0, -2.5, -0.1, 0.7, 4.0 })
  {
    EXPECT_NEAR(Sigmoid(x), 1.0 / (1.0 + std::exp(-x)), 1e-15);
    EXPECT_NEAR(Sigmoid(-x), 1.0 - Sigmoid(x), 1e-15);
  }
  EXPECT_NEAR(Logit(Sigmoid(-2.1972246)), -2.1972246, 1e-12);
}

TEST(GaussianMath, QuaternionToMatrixIsOrthonormalAndZeroSafe)
{
  const double q[4] = { 2.0, -1.0, 0.5, 3.0 };
  const auto r = QuaternionToMatrix(NormalizeQuaternion(q));
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      double dot = 0;
      for (int k = 0; k < 3; ++k)
      {
        dot += r[k * 3 + i] * r[k * 3 + j];
      }
      EXPECT_NEAR(dot, i == j ? 1.0 : 0.0, 1e-14);
    }
  }
  // 90 degrees about z: x axis goes to y.
  const double qz[4] = { std::sqrt(0.5), 0, 0, std::sqrt(0.5) };
  const auto rz = QuaternionToMatrix(NormalizeQuaternion(qz));
  EXPECT_NEAR(rz[3], 1.0, 1e-15);
  EXPECT_NEAR(rz[0], 0.0, 1e-15);
  const double zero[4] = { 0, 0, 0, 0 };
  const auto n = NormalizeQuaternion(zero);
  for (double v : n)
  {
    EXPECT_EQ(v, 0.0);
  }
}

TEST(Camera, CenterAndResize)
{
  Camera c;
  c.Width = 100;
  c.Height = 50;
  c.Fx = 80;
  c.Fy = 90;
  // Rotation 90 degrees about z, translation (1,2,3).
  c.WorldToCamera = { 0, -1, 0, 1, 1, 0, 0, 2, 0, 0, 1, 3, 0, 0, 0, 1 };
  const auto center = c.Center();
  // -R^T t = -( [0 1 0; -1 0 0; 0 0 1] (1,2,3) ) = -(2, -1, 3)
  EXPECT_DOUBLE_EQ(center[0], -2.0);
  EXPECT_DOUBLE_EQ(center[1], 1.0);
  EXPECT_DOUBLE_EQ(center[2], -3.0);
  const Camera half = c.Resized(50, 25);
  EXPECT_DOUBLE_EQ(half.TanHalfFovX(), c.TanHalfFovX());
  EXPECT_DOUBLE_EQ(half.TanHalfFovY(), c.TanHalfFovY());
}

TEST(GaussianCloud, ResizeAndExtras)
{
  GaussianCloud g;
  g.Resize(5, 3);
  EXPECT_EQ(g.SH.size(), 5u * 16u * 3u);
  EXPECT_EQ(g.GetId(4), 4);
  ExtraProperty e;
  e.Name = "nx";
  e.Type = ScalarType::Int16;
  e.Bytes.resize(2 * 5);
  const std::int16_t v = -7;
  std::memcpy(e.Bytes.data() + 2 * 3, &v, 2);
  g.Extra.push_back(e);
  ASSERT_NE(g.FindExtra("nx"), nullptr);
  EXPECT_EQ(g.FindExtra("nx")->GetAsDouble(3), -7.0);
  EXPECT_EQ(g.FindExtra("ny"), nullptr);
}

} // namespace vis4gs

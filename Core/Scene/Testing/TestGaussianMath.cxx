// SPDX-License-Identifier: BSD-3-Clause
#include "Camera.h"
#include "GaussianCloud.h"
#include "GaussianMath.h"
#include "SpecialValues.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

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

TEST(SpecialValues, CountsEveryRowOfTheTable)
{
  // One Gaussian per row of Documentation/special-values.md, plus two ordinary ones.
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  GaussianCloud c;
  c.Resize(12, 1);
  for (std::size_t g = 0; g < c.Count; ++g)
  {
    c.Rotations[4 * g] = 1;
  }
  c.OpacityLogits[0] = inf;
  c.OpacityLogits[1] = -inf;
  c.OpacityLogits[2] = nan;
  c.LogScales[3 * 3] = -inf;
  c.LogScales[3 * 4 + 1] = inf;
  c.LogScales[3 * 5 + 2] = nan;
  c.Positions[3 * 6] = -inf;
  c.Positions[3 * 7 + 1] = nan;
  for (int k = 0; k < 4; ++k)
  {
    c.Rotations[4 * 8 + k] = 0;
  }
  c.Rotations[4 * 9 + 2] = inf;
  c.SH[3 * 4 * 10 + 3 * 2 + 1] = nan; // a degree-1 coefficient of Gaussian 10
  c.Positions[3 * 11] = -0.0f;
  c.LogScales[3 * 11] = std::numeric_limits<float>::denorm_min();

  const SpecialValueCounts geometry = CountSpecialValues(c);
  using GC = GaussianClass;
  auto of = [&](const SpecialValueCounts& s, GC k) { return s.ByClass[static_cast<int>(k)]; };
  EXPECT_EQ(of(geometry, GC::Drawn), 6u);            // 0, 1, 3, 8, 10 and 11
  EXPECT_EQ(of(geometry, GC::NaNParameter), 3u);     // 2, 5, 7
  EXPECT_EQ(of(geometry, GC::InfinitePosition), 1u); // 6
  EXPECT_EQ(of(geometry, GC::InfiniteLogScale), 1u); // 4
  EXPECT_EQ(of(geometry, GC::InfiniteRotation), 1u); // 9
  EXPECT_EQ(geometry.Skipped(), 6u);
  EXPECT_EQ(geometry.NonFiniteSH, 0u); // SH not counted without a degree
  EXPECT_EQ(geometry.OpacityPlusInf, 1u);
  EXPECT_EQ(geometry.OpacityMinusInf, 1u);
  EXPECT_EQ(geometry.LogScaleMinusInf, 1u);
  EXPECT_EQ(geometry.ZeroQuaternion, 1u);
  // The NaN sits in a degree-1 coefficient: a degree-0 render does not use it.
  EXPECT_EQ(CountSpecialValues(c, 0).NonFiniteSH, 0u);
  EXPECT_EQ(CountSpecialValues(c, 1).NonFiniteSH, 1u);
  EXPECT_EQ(CountSpecialValues(c, 3).NonFiniteSH, 1u); // clamped to the cloud's degree
  EXPECT_EQ(DescribeSkipped(geometry, false),
    "6 skipped: 3 with a NaN parameter, 1 with an infinite position, 1 with a log-scale of "
    "+inf, 1 with an infinite rotation component");
  EXPECT_EQ(DescribeSkipped(CountSpecialValues(c, 1), true).substr(0, 11), "7 skipped: ");
  EXPECT_NE(DescribeDrawnSpecials(geometry).find("1 with opacity logit +inf (opacity 1)"),
    std::string::npos);
  GaussianCloud plain;
  plain.Resize(3, 0);
  for (std::size_t g = 0; g < plain.Count; ++g)
  {
    plain.Rotations[4 * g] = 1;
  }
  EXPECT_EQ(DescribeSkipped(CountSpecialValues(plain, 0), true), "");
  EXPECT_EQ(DescribeDrawnSpecials(CountSpecialValues(plain, 0)), "");
}

// Issue 15: the SH constants against the reference's literal values (reference §2.4) and
// the closed forms they round: Y_0 = 1/(2 sqrt(pi)), Y_1 = sqrt(3)/(2 sqrt(pi)), the
// degree-2 and degree-3 factors sqrt(15)/(2 sqrt(pi)), sqrt(5)/(4 sqrt(pi)), ..., with the
// signs of the reference's basis.
TEST(GaussianMath, ShConstantsAreTheReferenceLiterals)
{
  EXPECT_EQ(sh::C0, 0.28209479177387814);
  EXPECT_EQ(sh::C1, 0.4886025119029199);
  const double c2[5] = { 1.0925484305920792,
    -1.0925484305920792,
    0.31539156525252005,
    -1.0925484305920792,
    0.5462742152960396 };
  const double c3[7] = { -0.5900435899266435,
    2.890611442640554,
    -0.4570457994644658,
    0.3731763325901154,
    -0.4570457994644658,
    1.445305721320277,
    -0.5900435899266435 };
  for (int i = 0; i < 5; ++i)
  {
    EXPECT_EQ(sh::C2[i], c2[i]) << "C2[" << i << "]";
  }
  for (int i = 0; i < 7; ++i)
  {
    EXPECT_EQ(sh::C3[i], c3[i]) << "C3[" << i << "]";
  }
  const double sqrtPi = std::sqrt(3.141592653589793);
  const double pi = 3.141592653589793;
  EXPECT_NEAR(sh::C0, 1 / (2 * sqrtPi), 1e-16);
  EXPECT_NEAR(sh::C1, std::sqrt(3.0) / (2 * sqrtPi), 1e-16);
  EXPECT_NEAR(sh::C2[0], std::sqrt(15.0) / (2 * sqrtPi), 1e-15);
  EXPECT_NEAR(sh::C2[2], std::sqrt(5.0) / (4 * sqrtPi), 1e-15);
  EXPECT_NEAR(sh::C2[4], std::sqrt(15.0) / (4 * sqrtPi), 1e-15);
  EXPECT_NEAR(sh::C3[0], -0.25 * std::sqrt(35 / (2 * pi)), 1e-15);
  EXPECT_NEAR(sh::C3[1], 0.5 * std::sqrt(105 / pi), 1e-15);
  EXPECT_NEAR(sh::C3[2], -0.25 * std::sqrt(21 / (2 * pi)), 1e-15);
  EXPECT_NEAR(sh::C3[3], 0.25 * std::sqrt(7 / pi), 1e-15);
  EXPECT_NEAR(sh::C3[5], 0.25 * std::sqrt(105 / pi), 1e-15);
  EXPECT_EQ(sh::C2[1], -sh::C2[0]);
  EXPECT_EQ(sh::C2[3], -sh::C2[0]);
  EXPECT_EQ(sh::C3[4], sh::C3[2]);
  EXPECT_EQ(sh::C3[6], sh::C3[0]);
}

// The one covariance preparation (issue 22) against an independent construction: the
// rotation from the quaternion's axis and angle (Rodrigues' formula, not the quaternion
// product formula) and Sigma = R diag((m s)^2) R^T in double.
TEST(GaussianMath, CovarianceMatchesAxisAngleConstruction)
{
  const float rot[4] = { 2.0f, 0.4f, -1.0f, 0.6f }; // not normalised
  const float logScale[3] = { -1.2f, 0.3f, -3.5f };
  const double m = 1.7;
  const double qn = std::sqrt(4.0 + 0.16 + 1.0 + 0.36);
  const double w = rot[0] / qn;
  const double v[3] = { rot[1] / qn, rot[2] / qn, rot[3] / qn };
  const double vn = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  const double k[3] = { v[0] / vn, v[1] / vn, v[2] / vn };
  const double angle = 2.0 * std::atan2(vn, w);
  const double c = std::cos(angle), s = std::sin(angle);
  const double K[3][3] = { { 0, -k[2], k[1] }, { k[2], 0, -k[0] }, { -k[1], k[0], 0 } };
  double R[3][3];
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      R[i][j] = (i == j ? c : 0.0) + s * K[i][j] + (1 - c) * k[i] * k[j];
    }
  }
  double expected[3][3];
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      expected[i][j] = 0;
      for (int a = 0; a < 3; ++a)
      {
        const double sa = m * std::exp(static_cast<double>(logScale[a]));
        expected[i][j] += R[i][a] * sa * sa * R[j][a];
      }
    }
  }
  const int upper[6][2] = { { 0, 0 }, { 0, 1 }, { 0, 2 }, { 1, 1 }, { 1, 2 }, { 2, 2 } };
  const std::array<double, 6> d = GaussianCovariance<double>(logScale, rot, m);
  const std::array<float, 6> f = GaussianCovariance<float>(logScale, rot, static_cast<float>(m));
  const double scale = std::exp(2 * 0.3) * m * m; // the largest variance
  for (int e = 0; e < 6; ++e)
  {
    const double x = expected[upper[e][0]][upper[e][1]];
    EXPECT_NEAR(d[e], x, 1e-14 * scale) << "element " << e;
    EXPECT_NEAR(f[e], x, 1e-6 * scale) << "element " << e;
  }
  // A zero quaternion is the identity rotation: the diagonal (m s)^2 and no correlation.
  const float zero[4] = { 0, 0, 0, 0 };
  const std::array<double, 6> z = GaussianCovariance<double>(logScale, zero, 1.0);
  EXPECT_DOUBLE_EQ(z[0], std::exp(2.0 * logScale[0]));
  EXPECT_DOUBLE_EQ(z[3], std::exp(2.0 * logScale[1]));
  EXPECT_DOUBLE_EQ(z[5], std::exp(2.0 * logScale[2]));
  EXPECT_EQ(z[1], 0.0);
  EXPECT_EQ(z[2], 0.0);
  EXPECT_EQ(z[4], 0.0);
}

// ShColor against the real SH basis written from the closed forms (not the sh:: table), with
// the reference's signs (Y_1 = -C1 y, +C1 z, -C1 x; the degree-3 signs in the constants): each
// coefficient alone gives Y_i(d) + 0.5, in every channel with its own weight.
TEST(GaussianMath, ShColorIsTheRealShBasis)
{
  const double pi = 3.141592653589793;
  const double dn = std::sqrt(0.3 * 0.3 + 0.5 * 0.5 + 0.8 * 0.8);
  const double dir[3] = { -0.3 / dn, 0.5 / dn, 0.8 / dn };
  const double x = dir[0], y = dir[1], z = dir[2];
  const double Y[16] = { 1 / (2 * std::sqrt(pi)),
    -std::sqrt(3 / pi) / 2 * y,
    std::sqrt(3 / pi) / 2 * z,
    -std::sqrt(3 / pi) / 2 * x,
    std::sqrt(15 / pi) / 2 * x * y,
    -std::sqrt(15 / pi) / 2 * y * z,
    std::sqrt(5 / pi) / 4 * (2 * z * z - x * x - y * y),
    -std::sqrt(15 / pi) / 2 * x * z,
    std::sqrt(15 / pi) / 4 * (x * x - y * y),
    -std::sqrt(35 / (2 * pi)) / 4 * y * (3 * x * x - y * y),
    std::sqrt(105 / pi) / 2 * x * y * z,
    -std::sqrt(21 / (2 * pi)) / 4 * y * (4 * z * z - x * x - y * y),
    std::sqrt(7 / pi) / 4 * z * (2 * z * z - 3 * x * x - 3 * y * y),
    -std::sqrt(21 / (2 * pi)) / 4 * x * (4 * z * z - x * x - y * y),
    std::sqrt(105 / pi) / 4 * z * (x * x - y * y),
    -std::sqrt(35 / (2 * pi)) / 4 * x * (x * x - 3 * y * y) };
  for (int degree = 0; degree <= 3; ++degree)
  {
    const int count = (degree + 1) * (degree + 1);
    for (int i = 0; i < count; ++i)
    {
      float sh[48] = {};
      sh[3 * i] = 1.0f;
      sh[3 * i + 1] = -2.0f;
      sh[3 * i + 2] = 0.25f;
      double out[3];
      ShColor<double>(sh, degree, dir, out);
      EXPECT_NEAR(out[0], 0.5 + Y[i], 4e-15) << "degree " << degree << " coefficient " << i;
      EXPECT_NEAR(out[1], 0.5 - 2 * Y[i], 4e-15) << "degree " << degree << " coefficient " << i;
      EXPECT_NEAR(out[2], 0.5 + 0.25 * Y[i], 4e-15) << "degree " << degree << " coefficient " << i;
    }
  }
  // Coefficients above the degree are not read.
  float sh[48];
  for (float& v : sh)
  {
    v = 1.0f;
  }
  double out[3];
  ShColor<double>(sh, 0, dir, out);
  EXPECT_DOUBLE_EQ(out[0], 0.5 + Y[0]);
}

// ViewColor: the direction from the centre to the Gaussian, the clamp at 0 with the clamped
// channels reported, and a Gaussian at the centre (no direction) keeping only the DC term.
TEST(GaussianMath, ViewColorDirectionAndClamp)
{
  float sh[12] = {};
  sh[0] = 1.0f;         // red: DC only
  sh[3 * 2 + 1] = 5.0f; // green: +C1 z
  sh[2] = -4.0f;        // blue: below zero everywhere
  const float position[3] = { 1.0f, 2.0f, 7.0f };
  const double center[3] = { 1.0, 2.0, 3.0 }; // the Gaussian lies along +z
  double rgb[3];
  const unsigned clamped = ViewColor<double>(sh, 1, position, center, rgb);
  EXPECT_DOUBLE_EQ(rgb[0], 0.5 + sh::C0);
  EXPECT_DOUBLE_EQ(rgb[1], 0.5 + 5.0 * sh::C1);
  EXPECT_EQ(rgb[2], 0.0);
  EXPECT_EQ(clamped, 4u);
  const double atGaussian[3] = { 1.0, 2.0, 7.0 };
  EXPECT_EQ(ViewColor<double>(sh, 1, position, atGaussian, rgb), 4u);
  EXPECT_DOUBLE_EQ(rgb[0], 0.5 + sh::C0);
  EXPECT_DOUBLE_EQ(rgb[1], 0.5);
}

} // namespace vis4gs

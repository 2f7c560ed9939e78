// SPDX-License-Identifier: BSD-3-Clause
// Special values as the reference computes them (Documentation/special-values.md): each test
// compares a special input with an independent finite input whose reference arithmetic is
// the same number, never with our own output of the same input.
#include "RasterTestUtils.h"

#include "GaussianMath.h"
#include "Rasterizer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

using namespace vis4gs;
using namespace vis4gs::rastertest;

namespace
{

const float kInf = std::numeric_limits<float>::infinity();
const float kNaN = std::numeric_limits<float>::quiet_NaN();
const Camera kCam = AxisCamera(64, 48, 40, 40);

GaussianCloud One(std::array<float, 3> logScale,
  float logit,
  std::array<float, 4> q = { 1, 0, 0, 0 })
{
  GaussianCloud c;
  c.Resize(1, 0);
  SetGaussian(c, 0, { 0.05f, -0.02f, 5.0f }, logScale, q, logit, { 0.7f, 0.4f, 0.2f });
  return c;
}

template <typename T>
void ExpectSameImage(const GaussianCloud& a, const GaussianCloud& b, double tol)
{
  ProjectionCounts ca, cb;
  const auto ia = Rasterize<T>(a, kCam, {}, &ca);
  const auto ib = Rasterize<T>(b, kCam, {}, &cb);
  EXPECT_EQ(ca.InvalidParameters, 0u);
  EXPECT_EQ(ca.Visible, cb.Visible);
  EXPECT_LE(MaxAbsDiff(ia.Color, ib.Color), tol);
  EXPECT_EQ(ia.Contributors, ib.Contributors);
}

} // namespace

// Opacity logit +inf: sigmoid = 1 exactly, the same as a finite logit of 1e30.
TEST(SpecialValues, OpacityLogitPlusInfIsOpaque)
{
  const auto inf = One({ -2, -2, -2 }, kInf);
  const auto big = One({ -2, -2, -2 }, 1e30f);
  ExpectSameImage<float>(inf, big, 0.0);
  ExpectSameImage<double>(inf, big, 0.0);
  // Drawn: the centre pixel is covered at the reference's alpha cap 0.99.
  const auto img = Rasterize<double>(inf, kCam);
  EXPECT_GT(img.Contributors[24 * 64 + 34], 0u);
}

// Opacity logit -inf: opacity 0, alpha < 1/255 everywhere: the background image.
TEST(SpecialValues, OpacityLogitMinusInfNeverContributes)
{
  const auto img = Rasterize<double>(One({ -2, -2, -2 }, -kInf), kCam);
  for (auto c : img.Contributors)
  {
    EXPECT_EQ(c, 0u);
  }
  for (auto t : img.Transmittance)
  {
    EXPECT_EQ(t, 1.0);
  }
}

// Log-scale -inf: scale 0, the 2D covariance is the +0.3 dilation only; the same as a
// log-scale of -200 (exp underflows to 0 in float and to ~1e-87 in double, far below 0.3).
TEST(SpecialValues, LogScaleMinusInfIsDilatedPoint)
{
  const auto inf = One({ -kInf, -kInf, -kInf }, 2.0f);
  const auto tiny = One({ -200, -200, -200 }, 2.0f);
  ExpectSameImage<float>(inf, tiny, 0.0);
  ExpectSameImage<double>(inf, tiny, 1e-12);
  // Hand-computed centre pixel of a dilated point: power = -0.5 d^T (0.3 I)^-1 d.
  const auto img = Rasterize<double>(inf, kCam);
  // The cloud stores float positions and logits: use exactly those values.
  const double u = 40.0 * double(0.05f) / 5.0 + 32.0 - 0.5;
  const double v = 40.0 * double(-0.02f) / 5.0 + 24.0 - 0.5;
  const int px = 32, py = 23;
  const double dx = px - u, dy = py - v;
  const double alpha =
    std::min(0.99, Sigmoid(double(2.0f)) * std::exp(-0.5 * (dx * dx + dy * dy) / 0.3));
  // 1e-7: the pipeline carries some per-Gaussian values in float even in double mode.
  EXPECT_NEAR(img.Transmittance[py * 64 + px], 1.0 - alpha, 1e-7);
}

// Zero quaternion: F.normalize keeps it zero, the rotation matrix is the identity.
TEST(SpecialValues, ZeroQuaternionIsIdentity)
{
  ExpectSameImage<double>(One({ -2, -3, -2.5f }, 2.0f, { 0, 0, 0, 0 }),
    One({ -2, -3, -2.5f }, 2.0f, { 1, 0, 0, 0 }),
    0.0);
}

// Signed zeros and denormals are ordinary numbers.
TEST(SpecialValues, SignedZeroAndDenormal)
{
  const float den = std::numeric_limits<float>::denorm_min();
  ExpectSameImage<double>(One({ -2, -2, -2 }, -0.0f), One({ -2, -2, -2 }, 0.0f), 0.0);
  ExpectSameImage<double>(One({ -2, -2, -2 }, den, { 1, -0.0f, den, 0 }),
    One({ -2, -2, -2 }, 0.0f, { 1, 0, 0, 0 }),
    1e-12);
}

// No answer in the reference: skipped and counted.
TEST(SpecialValues, NoAnswerSkipped)
{
  const float p[3] = { 0, 0, 1 }, ls[3] = { 0, 0, 0 }, q[4] = { 1, 0, 0, 0 };
  EXPECT_EQ(ClassifyGaussian(p, ls, q, kInf), GaussianClass::Drawn);
  EXPECT_EQ(ClassifyGaussian(p, ls, q, kNaN), GaussianClass::NaNParameter);
  const float pInf[3] = { 0, kInf, 1 }, lsInf[3] = { 0, kInf, 0 }, lsNeg[3] = { -kInf, 0, 0 };
  const float qInf[4] = { 1, 0, -kInf, 0 };
  EXPECT_EQ(ClassifyGaussian(pInf, ls, q, 0.0f), GaussianClass::InfinitePosition);
  EXPECT_EQ(ClassifyGaussian(p, lsInf, q, 0.0f), GaussianClass::InfiniteLogScale);
  EXPECT_EQ(ClassifyGaussian(p, lsNeg, q, 0.0f), GaussianClass::Drawn);
  EXPECT_EQ(ClassifyGaussian(p, ls, qInf, 0.0f), GaussianClass::InfiniteRotation);
  ProjectionCounts c;
  Rasterize<float>(One({ -2, kInf, -2 }, 2.0f), kCam, {}, &c);
  EXPECT_EQ(c.InvalidParameters, 1u);
}

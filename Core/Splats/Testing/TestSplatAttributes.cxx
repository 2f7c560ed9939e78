// SPDX-License-Identifier: BSD-3-Clause
#include "SplatAttributes.h"

#include "GaussianMath.h"
#include "Rasterizer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace vis4gs
{
namespace
{
GaussianCloud RandomCloud(std::size_t n, int degree, unsigned seed)
{
  GaussianCloud cloud;
  cloud.Resize(n, degree);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (std::size_t i = 0; i < n; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      cloud.Positions[3 * i + k] = 2.0f * u(rng);
      cloud.LogScales[3 * i + k] = -3.0f + u(rng);
    }
    for (int k = 0; k < 4; ++k)
    {
      cloud.Rotations[4 * i + k] = u(rng);
    }
    cloud.OpacityLogits[i] = 3.0f * u(rng);
  }
  for (auto& v : cloud.SH)
  {
    v = u(rng);
  }
  return cloud;
}
}

TEST(SplatAttributes, CovarianceAgainstDoubleFormula)
{
  auto cloud = RandomCloud(200, 0, 1);
  std::vector<float> packed;
  PackSplatGeometry(cloud, 1.5, packed, 2);
  ASSERT_EQ(packed.size(), 200u * SplatGeometryFloats);
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    const float* p = &packed[i * SplatGeometryFloats];
    double q[4];
    for (int k = 0; k < 4; ++k)
    {
      q[k] = cloud.Rotations[4 * i + k];
    }
    const auto R = QuaternionToMatrix<double>(NormalizeQuaternion<double>(q));
    double s2[3];
    for (int k = 0; k < 3; ++k)
    {
      const double s = 1.5 * std::exp(static_cast<double>(cloud.LogScales[3 * i + k]));
      s2[k] = s * s;
    }
    auto sig = [&](int r, int c)
    {
      return R[3 * r] * R[3 * c] * s2[0] + R[3 * r + 1] * R[3 * c + 1] * s2[1] +
        R[3 * r + 2] * R[3 * c + 2] * s2[2];
    };
    const double expected[6] = { sig(0, 0), sig(0, 1), sig(0, 2), sig(1, 1), sig(1, 2), sig(2, 2) };
    const double scale = sig(0, 0) + sig(1, 1) + sig(2, 2);
    const int slot[6] = { 4, 5, 6, 7, 8, 9 };
    for (int k = 0; k < 6; ++k)
    {
      ASSERT_NEAR(p[slot[k]], expected[k], 1e-6 * scale) << i << " " << k;
    }
    EXPECT_EQ(p[0], cloud.Positions[3 * i]);
    EXPECT_NEAR(p[3], 1.0 / (1.0 + std::exp(-static_cast<double>(cloud.OpacityLogits[i]))), 1e-7);
    EXPECT_EQ(p[10], 1.0f);
  }
}

TEST(SplatAttributes, AxisAlignedAndInvalidGaussians)
{
  GaussianCloud cloud;
  cloud.Resize(4, 0);
  const float ls[4][3] = {
    { 0.0f, std::log(2.0f), std::log(0.5f) }, { 0, 0, 0 }, { 100.0f, 0, 0 }, { 0, 0, 0 }
  };
  for (int i = 0; i < 4; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      cloud.LogScales[3 * i + k] = ls[i][k];
    }
    cloud.Rotations[4 * i] = 2.0f; // unnormalised identity
  }
  cloud.Positions[3] = std::numeric_limits<float>::quiet_NaN();    // Gaussian 1: NaN mean
  cloud.OpacityLogits[3] = std::numeric_limits<float>::infinity(); // Gaussian 3: Inf logit (drawn)
  std::vector<float> packed;
  PackSplatGeometry(cloud, 1.0, packed);
  const float* g = &packed[0];
  EXPECT_FLOAT_EQ(g[4], 1.0f);
  EXPECT_FLOAT_EQ(g[7], 4.0f);
  EXPECT_FLOAT_EQ(g[9], 0.25f);
  EXPECT_EQ(g[5], 0.0f);
  EXPECT_EQ(g[6], 0.0f);
  EXPECT_EQ(g[8], 0.0f);
  EXPECT_FLOAT_EQ(g[3], 0.5f);
  EXPECT_EQ(g[10], 1.0f);
  EXPECT_EQ(packed[1 * SplatGeometryFloats + 10], 0.0f); // NaN mean
  EXPECT_EQ(packed[2 * SplatGeometryFloats + 10], 0.0f); // exp(200) overflows float
  // +inf logit: drawn with opacity exactly 1, as the reference's sigmoid gives
  // (Documentation/special-values.md).
  EXPECT_EQ(packed[3 * SplatGeometryFloats + 10], 1.0f);
  EXPECT_EQ(packed[3 * SplatGeometryFloats + 3], 1.0f);
  GaussianCloud bad = cloud;
  bad.Rotations.pop_back();
  EXPECT_THROW(PackSplatGeometry(bad, 1.0, packed), std::invalid_argument);
}

TEST(SplatAttributes, ShColoursMatchTheRasteriser)
{
  for (int degree = 0; degree <= 3; ++degree)
  {
    auto cloud = RandomCloud(300, degree, 10 + degree);
    Camera cam;
    cam.Width = 80;
    cam.Height = 60;
    cam.Fx = cam.Fy = 40;
    cam.WorldToCamera = { 1, 0, 0, 0.2, 0, 1, 0, -0.1, 0, 0, 1, 8.0, 0, 0, 0, 1 };
    const auto proj = ProjectGaussians<float>(cloud, cam);
    std::vector<float> rgb;
    EvaluateSplatColors(cloud, cam.Center(), -1, rgb, 2);
    int compared = 0;
    for (std::size_t i = 0; i < cloud.Count; ++i)
    {
      if (!proj.Gaussians[i].IsVisible())
      {
        continue;
      }
      ++compared;
      for (int c = 0; c < 3; ++c)
      {
        ASSERT_NEAR(rgb[3 * i + c], proj.Gaussians[i].Color[c], 2e-6) << degree << " " << i;
      }
    }
    EXPECT_GT(compared, 100);
  }
  // Hand case: degree 1, Gaussian straight ahead along +z from the camera: d = (0, 0, 1),
  // colour = C0 f0 + C1 f2 + 0.5 (the -y and -x terms vanish).
  GaussianCloud one;
  one.Resize(1, 1);
  one.Positions = { 0, 0, 5 };
  for (int k = 0; k < 4; ++k)
  {
    for (int c = 0; c < 3; ++c)
    {
      one.SH[3 * k + c] = 0.1f * (k + 1) + 0.01f * c;
    }
  }
  std::vector<float> rgb;
  EvaluateSplatColors(one, { 0, 0, 0 }, -1, rgb);
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(rgb[c], sh::C0 * one.SH[c] + sh::C1 * one.SH[6 + c] + 0.5, 1e-6);
  }
  // Degree 0 requested: only the DC term; strongly negative colours clamp at 0.
  EvaluateSplatColors(one, { 0, 0, 0 }, 0, rgb);
  EXPECT_NEAR(rgb[0], sh::C0 * one.SH[0] + 0.5, 1e-6);
  one.SH[0] = -10.0f;
  EvaluateSplatColors(one, { 0, 0, 0 }, 0, rgb);
  EXPECT_EQ(rgb[0], 0.0f);
  // A Gaussian at the camera centre gets only the DC term (no NaN).
  EvaluateSplatColors(one, { 0, 0, 5 }, -1, rgb);
  EXPECT_TRUE(std::isfinite(rgb[1]));
  EXPECT_NEAR(rgb[1], sh::C0 * one.SH[1] + 0.5, 1e-6);
}

TEST(SplatAttributes, ViridisEndsAndLuminanceIncreases)
{
  const auto a = Viridis(0.0), b = Viridis(1.0), m = Viridis(0.5);
  EXPECT_FLOAT_EQ(a[0], 0.267004f);
  EXPECT_FLOAT_EQ(b[1], 0.906157f);
  // t = 0.5 is table position 127.5: linear between samples 112 and 128 ...
  EXPECT_NEAR(m[0], 0.149039 + (0.127568 - 0.149039) * 15.5 / 16, 1e-6);
  // ... and within 0.004 of the full table (entries 127 and 128 averaged).
  EXPECT_NEAR(m[0], 0.5 * (0.128729 + 0.127568), 0.004);
  EXPECT_NEAR(m[1], 0.5 * (0.563265 + 0.566949), 0.004);
  EXPECT_NEAR(m[2], 0.5 * (0.551229 + 0.550556), 0.004);
  EXPECT_EQ(Viridis(-3.0), a);
  EXPECT_EQ(Viridis(std::nan("")), a);
  EXPECT_EQ(Viridis(7.0), b);
  double last = -1;
  for (int k = 0; k <= 100; ++k)
  {
    const auto c = Viridis(k / 100.0);
    const double lum = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    EXPECT_GT(lum, last);
    last = lum;
  }
}

TEST(SplatAttributes, OverlaySuspiciousEndIsTheBrightEnd)
{
  EXPECT_EQ(SuspiciousEndOf("ViewCoverage"), SuspiciousEnd::Low);
  for (const char* name : { "BlurScore", "NeedleScore", "NeedleShape" })
  {
    EXPECT_EQ(SuspiciousEndOf(name), SuspiciousEnd::High) << name;
  }
  EXPECT_EQ(SuspiciousEndOf("Opacity"), SuspiciousEnd::None);
  EXPECT_EQ(SuspiciousEndOf(""), SuspiciousEnd::None);
  auto lum = [](const std::array<float, 3>& c)
  { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; };
  // Against a black background the suspicious end is the brightest colour of the map, and
  // the luminance falls monotonically away from it (so the map stays perceptually ordered).
  for (SuspiciousEnd end : { SuspiciousEnd::Low, SuspiciousEnd::High, SuspiciousEnd::None })
  {
    const double suspicious = end == SuspiciousEnd::Low ? 0.2 : 0.8;
    const double other = end == SuspiciousEnd::Low ? 0.8 : 0.2;
    EXPECT_EQ(OverlayColor(suspicious, 0.2, 0.8, end), Viridis(1.0));
    EXPECT_EQ(OverlayColor(other, 0.2, 0.8, end), Viridis(0.0));
    double last = lum(OverlayColor(suspicious, 0.2, 0.8, end));
    for (int k = 1; k <= 50; ++k)
    {
      const double v = suspicious + (other - suspicious) * k / 50.0;
      const double l = lum(OverlayColor(v, 0.2, 0.8, end));
      EXPECT_LT(l, last) << v;
      last = l;
    }
    // The brightest colour is at least 8 times the luminance of the darkest: what the eye
    // finds against black.
    EXPECT_GT(lum(Viridis(1.0)), 8 * lum(Viridis(0.0)));
  }
  // Clamping, NaN and an empty range.
  EXPECT_EQ(OverlayColor(-5, 0, 1, SuspiciousEnd::Low), Viridis(1.0));
  EXPECT_EQ(OverlayColor(5, 0, 1, SuspiciousEnd::Low), Viridis(0.0));
  EXPECT_EQ(OverlayColor(std::nan(""), 0, 1, SuspiciousEnd::High), Viridis(0.0));
  EXPECT_EQ(OverlayColor(0.5, 0.5, 0.5, SuspiciousEnd::High), Viridis(1.0));
  EXPECT_EQ(OverlayColor(0.4, 0.5, 0.5, SuspiciousEnd::High), Viridis(0.0));
  // ComputeSplatDisplay uses the same map.
  const double scores[2] = { 0.0, 0.25 };
  SplatDisplayOptions o;
  o.ScoreColoring = true;
  o.Scores = scores;
  o.Suspicious = SuspiciousEnd::Low;
  std::vector<float> rgba;
  std::vector<std::uint8_t> keep;
  ComputeSplatDisplay(nullptr, 2, o, rgba, keep);
  for (int ch = 0; ch < 3; ++ch)
  {
    EXPECT_EQ(rgba[ch], Viridis(1.0)[ch]);
    EXPECT_EQ(rgba[4 + ch], Viridis(0.75)[ch]);
  }
}

TEST(SplatAttributes, DisplayModes)
{
  const float colors[9] = { 0.2f, 0.4f, 0.6f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f };
  const double scores[3] = { 0.0, 0.5, std::nan("") };
  SplatDisplayOptions o;
  std::vector<float> rgba;
  std::vector<std::uint8_t> keep;
  ComputeSplatDisplay(colors, 3, o, rgba, keep);
  EXPECT_EQ(rgba[0], 0.2f);
  EXPECT_EQ(rgba[3], 1.0f);
  EXPECT_EQ(keep, (std::vector<std::uint8_t>{ 1, 1, 1 }));
  o.ScoreColoring = true;
  o.Scores = scores;
  o.ColorRange = { 0.0, 1.0 };
  ComputeSplatDisplay(colors, 3, o, rgba, keep);
  EXPECT_EQ(rgba[0], Viridis(0.0)[0]);
  EXPECT_EQ(rgba[5], Viridis(0.5)[1]);
  EXPECT_EQ(rgba[8], 0.5f); // NaN colour
  o.HideOutsideRange = true;
  o.VisibleRange = { 0.25, 1.0 };
  ComputeSplatDisplay(colors, 3, o, rgba, keep);
  EXPECT_EQ(keep, (std::vector<std::uint8_t>{ 0, 1, 0 }));
  // Highlight and dim.
  const std::uint8_t selected[3] = { 1, 0, 0 };
  SplatDisplayOptions h;
  h.Selected = selected;
  h.DimUnselected = true;
  ComputeSplatDisplay(colors, 3, h, rgba, keep);
  EXPECT_NEAR(rgba[0], 0.2f + 0.7f * (1.0f - 0.2f), 1e-6);
  EXPECT_EQ(rgba[3], 1.0f);
  EXPECT_EQ(rgba[7], 0.15f);
  const float grey = 0.2126f;
  EXPECT_NEAR(rgba[4], 1.0f + 0.8f * (grey - 1.0f), 1e-6);
  // Deferred true colours: the change to apply instead of the colour, the same opacities
  // and keep; no colours needed.
  const double hideScores[3] = { 1.0, 1.0, 0.0 };
  h.Scores = hideScores;
  h.HideOutsideRange = true;
  h.VisibleRange = { 0.5, 2.0 };
  std::vector<float> direct;
  std::vector<std::uint8_t> directKeep;
  ComputeSplatDisplay(colors, 3, h, direct, directKeep);
  h.DeferTrueColor = true;
  ComputeSplatDisplay(nullptr, 3, h, rgba, keep);
  EXPECT_EQ(keep, directKeep);
  EXPECT_EQ(keep, (std::vector<std::uint8_t>{ 1, 1, 0 }));
  EXPECT_EQ(rgba[0], SplatDisplayHighlighted);
  EXPECT_EQ(rgba[4], SplatDisplayDimmed);
  EXPECT_EQ(rgba[8], SplatDisplayDimmed);
  for (int i = 0; i < 3; ++i)
  {
    EXPECT_EQ(rgba[4 * i + 1], 0.0f);
    EXPECT_EQ(rgba[4 * i + 2], 0.0f);
    EXPECT_EQ(rgba[4 * i + 3], direct[4 * i + 3]);
  }
  h.Selected = nullptr;
  h.DimUnselected = false;
  ComputeSplatDisplay(nullptr, 3, h, rgba, keep);
  EXPECT_EQ(rgba[0], SplatDisplayUnchanged);
  EXPECT_EQ(rgba[3], 1.0f);
  SplatDisplayOptions missing;
  missing.ScoreColoring = true;
  EXPECT_THROW(ComputeSplatDisplay(colors, 3, missing, rgba, keep), std::invalid_argument);
}

} // namespace vis4gs

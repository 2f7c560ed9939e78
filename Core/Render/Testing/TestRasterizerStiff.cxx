// SPDX-License-Identifier: BSD-3-Clause
// Stiff and extreme inputs: each case has a documented behaviour (Core/Render/README.md)
// that the test pins down.
#include "RasterTestUtils.h"

#include "Footprint.h"
#include "Rasterizer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

using namespace vis4gs;
using namespace vis4gs::rastertest;

namespace
{

const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

GaussianCloud One(std::array<float, 3> pos,
  std::array<float, 3> s,
  std::array<float, 4> q = { 1, 0, 0, 0 },
  float logit = 2.0f,
  std::array<float, 3> rgb = { 0.7f, 0.4f, 0.2f })
{
  GaussianCloud c;
  c.Resize(1, 0);
  SetGaussian(c, 0, pos, { std::log(s[0]), std::log(s[1]), std::log(s[2]) }, q, logit, rgb);
  return c;
}

template <typename T>
bool AllFiniteImage(const RasterImage<T>& img)
{
  for (T v : img.Color)
  {
    if (!std::isfinite(v))
    {
      return false;
    }
  }
  for (T v : img.Depth)
  {
    if (!std::isfinite(v))
    {
      return false;
    }
  }
  return true;
}

template <typename T>
bool IsBackground(const RasterImage<T>& img, std::array<double, 3> bg)
{
  for (std::size_t i = 0; i < img.Transmittance.size(); ++i)
  {
    if (img.Transmittance[i] != T(1) || img.Contributors[i] != 0)
    {
      return false;
    }
    for (int c = 0; c < 3; ++c)
    {
      if (img.Color[3 * i + c] != static_cast<T>(bg[c]))
      {
        return false;
      }
    }
  }
  return true;
}

const Camera kCam = AxisCamera(64, 48, 40, 40);

} // namespace

//------------------------------------------------------------------------------
// Scale ratios of 1e8: needles and disks render as dilated lines; float and double agree.
TEST(RasterizerStiff, ScaleRatio1e8)
{
  const float c30 = std::cos(0.2618f), s30 = std::sin(0.2618f);
  const GaussianCloud cases[] = {
    One({ 0.1f, 0, 5 }, { 1.0f, 1e-8f, 1e-8f }, { c30, 0, 0, s30 }), // needle in the image plane
    One({ 0.1f, 0, 5 }, { 1e-8f, 1e-8f, 1.0f }, { c30, s30, 0, 0 }), // needle along the view ray
    One({ 0, 0.1f, 5 }, { 1.0f, 1.0f, 1e-8f }),                      // disk face-on
    One({ 0, 0.1f, 5 }, { 1.0f, 1e-8f, 1.0f }, { 0.9f, 0.1f, 0.3f, 0 }), // disk nearly edge-on
  };
  for (const auto& cloud : cases)
  {
    ProjectionCounts counts;
    const auto d = Rasterize<double>(cloud, kCam, {}, &counts);
    EXPECT_EQ(counts.Visible, 1u);
    const auto f = Rasterize<float>(cloud, kCam);
    EXPECT_TRUE(AllFiniteImage(d));
    EXPECT_TRUE(AllFiniteImage(f));
    EXPECT_LT(MaxAbsDiff(f.Color, d.Color), 1e-5);
    const auto naive = NaiveComposite(NaiveProject<double>(cloud, kCam, 0), {});
    EXPECT_LT(MaxAbsDiff(naive.Color, d.Color), 1e-9);
    double covered = 0;
    for (double a : d.Alpha)
    {
      covered += a > 0;
    }
    EXPECT_GT(covered, 3); // the dilation keeps even a 1e-8 axis at least a pixel wide
  }
}

//------------------------------------------------------------------------------
// Scale 1e-12: the 3D covariance vanishes and the splat is the dilation kernel alone
// (variance 0.3 px^2): alpha = o e^{-d^2/0.6}.
TEST(RasterizerStiff, TinyScale1em12)
{
  const auto cloud = One({ 0, 0, 3 }, { 1e-12f, 1e-12f, 1e-12f }, { 1, 0, 0, 0 }, 0.0f);
  const Camera cam = AxisCamera(33, 33, 40, 40); // centre pixel (16, 16)
  for (int mode = 0; mode < 2; ++mode)
  {
    std::vector<double> alpha;
    if (mode == 0)
    {
      const auto img = Rasterize<double>(cloud, cam);
      alpha.assign(img.Alpha.begin(), img.Alpha.end());
    }
    else
    {
      const auto img = Rasterize<float>(cloud, cam);
      alpha.assign(img.Alpha.begin(), img.Alpha.end());
    }
    const double tol = mode == 0 ? 1e-12 : 1e-6;
    EXPECT_NEAR(alpha[16 * 33 + 16], 0.5, tol);
    EXPECT_NEAR(alpha[16 * 33 + 17], 0.5 * std::exp(-0.5 / 0.3), tol);
    EXPECT_NEAR(alpha[17 * 33 + 17], 0.5 * std::exp(-1.0 / 0.3), tol);
    EXPECT_EQ(alpha[16 * 33 + 19], 0.0); // 0.5 e^{-15} < 1/255
  }
  const auto proj = ProjectGaussians<double>(cloud, cam);
  EXPECT_EQ(proj.Gaussians[0].Radius, 3); // ceil(3 sqrt(0.3 + sqrt(0.1))) = ceil(2.35)
}

//------------------------------------------------------------------------------
// Scale 1e6: an isotropic Gaussian covering the whole image renders o*c + (1-o)*bg
// everywhere; when the float covariance overflows (det = Inf), float mode skips and counts it
// (NonFinite) while double renders it.
TEST(RasterizerStiff, HugeScale1e6)
{
  RasterSettings s;
  s.Background = { 0.0, 0.5, 1.0 };
  const auto cloud = One({ 0, 0, 5 }, { 1e6f, 1e6f, 1e6f }, { 1, 0, 0, 0 }, 0.0f);
  ProjectionCounts counts;
  const auto f = Rasterize<float>(cloud, kCam, s, &counts);
  EXPECT_EQ(counts.Visible, 1u);
  const auto proj = ProjectGaussians<float>(cloud, kCam, s);
  for (std::size_t i = 0; i < f.Alpha.size(); ++i)
  {
    ASSERT_NEAR(f.Alpha[i], 0.5, 1e-6);
    for (int c = 0; c < 3; ++c)
    {
      ASSERT_NEAR(
        f.Color[3 * i + c], 0.5 * proj.Gaussians[0].Color[c] + 0.5 * s.Background[c], 1e-6);
    }
  }
  // Larger focal length: a = (f s / z)^2 = 4e20, det = 1.6e41 overflows float.
  const Camera tele = AxisCamera(64, 48, 1e5, 1e5);
  const auto ff = Rasterize<float>(cloud, tele, s, &counts);
  EXPECT_EQ(counts.NonFinite, 1u);
  EXPECT_TRUE(IsBackground(ff, s.Background));
  const auto dd = Rasterize<double>(cloud, tele, s, &counts);
  EXPECT_EQ(counts.Visible, 1u);
  EXPECT_NEAR(dd.Alpha[0], 0.5, 1e-12);
  // Anisotropic, rotated huge Gaussian: float cancellation in det; whatever the verdict, the
  // outputs are finite and the Gaussian is counted exactly once.
  const auto rot = One({ 0.2f, 0.1f, 5 }, { 1e6f, 3e5f, 1e-3f }, { 0.7f, 0.3f, 0.5f, 0.2f }, 1.0f);
  const auto fr = Rasterize<float>(rot, tele, s, &counts);
  EXPECT_EQ(counts.Visible + counts.Degenerate + counts.NonFinite, 1u);
  EXPECT_TRUE(AllFiniteImage(fr));
  EXPECT_TRUE(AllFiniteImage(Rasterize<double>(rot, tele, s)));
  // Log-scale 60 (s = 1e26): s^2 overflows float -> NonFinite; double renders.
  GaussianCloud big = cloud;
  big.LogScales = { 60, 60, 60 };
  Rasterize<float>(big, kCam, s, &counts);
  EXPECT_EQ(counts.NonFinite, 1u);
  Rasterize<double>(big, kCam, s, &counts);
  EXPECT_EQ(counts.Visible, 1u);
}

//------------------------------------------------------------------------------
TEST(RasterizerStiff, BehindCameraAndNearPlane)
{
  RasterSettings s;
  s.Background = { 0.3, 0.6, 0.9 };
  ProjectionCounts counts;
  // Behind the camera, large enough to cover the image if it were projected.
  auto img = Rasterize<float>(One({ 0, 0, -5 }, { 3, 3, 3 }), kCam, s, &counts);
  EXPECT_EQ(counts.NearPlane, 1u);
  EXPECT_TRUE(IsBackground(img, s.Background));
  // Straddling the near plane with the centre in front (z = 0.3, extent 1): rendered, as in
  // the reference (only the centre is tested).
  img = Rasterize<float>(One({ 0, 0, 0.3f }, { 1, 1, 1 }), kCam, s, &counts);
  EXPECT_EQ(counts.Visible, 1u);
  EXPECT_TRUE(AllFiniteImage(img));
  EXPECT_GT(img.Alpha[24 * 64 + 32], 0.5);
  // Centre just behind the near plane (z = 0.15), extending far in front: culled.
  img = Rasterize<float>(One({ 0, 0, 0.15f }, { 1, 1, 1 }), kCam, s, &counts);
  EXPECT_EQ(counts.NearPlane, 1u);
  EXPECT_TRUE(IsBackground(img, s.Background));
  // Exactly on the plane: culled (t_z <= 0.2); just beyond: rendered.
  Rasterize<float>(One({ 0, 0, 0.2f }, { 0.1f, 0.1f, 0.1f }), kCam, s, &counts);
  EXPECT_EQ(counts.NearPlane, 1u);
  Rasterize<float>(
    One({ 0, 0, std::nextafter(0.2f, 1.0f) }, { 0.1f, 0.1f, 0.1f }), kCam, s, &counts);
  EXPECT_EQ(counts.Visible, 1u);
  // Camera inside a Gaussian's centre (t = 0): culled, no division by zero.
  Rasterize<double>(One({ 0, 0, 0 }, { 1, 1, 1 }), kCam, s, &counts);
  EXPECT_EQ(counts.NearPlane, 1u);
}

//------------------------------------------------------------------------------
// Grazing angles: a Gaussian far outside the frustum (x/z = 20, Jacobian clamped at
// 1.3 tan(fov/2)) whose footprint still reaches the image; and a disk seen exactly edge-on.
TEST(RasterizerStiff, GrazingAngles)
{
  const auto cloud = One({ 20, 0, 1 }, { 10, 10, 10 }, { 1, 0, 0, 0 }, 1.0f);
  ProjectionCounts counts;
  const auto d = Rasterize<double>(cloud, kCam, {}, &counts);
  EXPECT_EQ(counts.Visible, 1u);
  const auto proj = ProjectGaussians<double>(cloud, kCam);
  EXPECT_GT(proj.Gaussians[0].U, 800.0);
  const auto naive = NaiveComposite(NaiveProject<double>(cloud, kCam, 0), {});
  EXPECT_LT(MaxAbsDiff(naive.Color, d.Color), 1e-9);
  const auto f = Rasterize<float>(cloud, kCam);
  EXPECT_LT(MaxAbsDiff(f.Color, d.Color), 1e-5);
  double covered = 0;
  for (double a : d.Alpha)
  {
    covered += a > 0;
  }
  EXPECT_GT(covered, 100);
  // Edge-on disk (normal along x, camera looks along z from the side).
  const auto disk = One({ 0, 0, 4 }, { 1e-7f, 1, 1 });
  const auto e = Rasterize<double>(disk, kCam);
  const auto ef = Rasterize<float>(disk, kCam);
  EXPECT_TRUE(AllFiniteImage(e));
  EXPECT_LT(MaxAbsDiff(ef.Color, e.Color), 1e-5);
  // The dilated line: column 31/32 covered, column 36 not.
  EXPECT_GT(e.Alpha[24 * 64 + 32], 0.1);
  EXPECT_EQ(e.Alpha[24 * 64 + 36], 0.0);
}

//------------------------------------------------------------------------------
// Quaternion (0,0,0,0): normalisation floors the norm at 1e-12, the zero quaternion stays
// zero, and the rotation formula of a zero quaternion is the identity matrix: the Gaussian
// renders axis-aligned, exactly like the identity quaternion.
TEST(RasterizerStiff, ZeroQuaternion)
{
  const auto zero = One({ 0.1f, -0.1f, 4 }, { 0.5f, 0.05f, 0.2f }, { 0, 0, 0, 0 });
  const auto ident = One({ 0.1f, -0.1f, 4 }, { 0.5f, 0.05f, 0.2f }, { 1, 0, 0, 0 });
  ProjectionCounts counts;
  const auto a = Rasterize<float>(zero, kCam, {}, &counts);
  EXPECT_EQ(counts.Visible, 1u);
  const auto b = Rasterize<float>(ident, kCam);
  EXPECT_EQ(0, std::memcmp(a.Color.data(), b.Color.data(), a.Color.size() * sizeof(float)));
  // A tiny non-zero quaternion is normalised like any other.
  const auto tiny = One({ 0.1f, -0.1f, 4 }, { 0.5f, 0.05f, 0.2f }, { 0, 1e-20f, 0, 0 });
  const auto rx = One({ 0.1f, -0.1f, 4 }, { 0.5f, 0.05f, 0.2f }, { 0, 1, 0, 0 });
  EXPECT_LT(
    MaxAbsDiff(Rasterize<double>(tiny, kCam).Color, Rasterize<double>(rx, kCam).Color), 1e-12);
}

//------------------------------------------------------------------------------
// Opacity logit +100: o = 1, alpha capped at 0.99. Logit -100: o = 3.7e-44 (float denormal):
// binned like any visible Gaussian (as in the reference) but alpha < 1/255 everywhere.
TEST(RasterizerStiff, OpacityLogitExtremes)
{
  RasterSettings s;
  s.Background = { 1, 1, 1 };
  const Camera cam = AxisCamera(33, 33, 40, 40);
  const auto opaque = One({ 0, 0, 4 }, { 0.05f, 0.05f, 0.05f }, { 1, 0, 0, 0 }, 100.0f);
  const auto img = Rasterize<float>(opaque, cam, s);
  const auto proj = ProjectGaussians<float>(opaque, cam, s);
  EXPECT_EQ(proj.Gaussians[0].Opacity, 1.0f);
  EXPECT_FLOAT_EQ(img.Alpha[16 * 33 + 16], 0.99f);
  EXPECT_FLOAT_EQ(
    img.Color[3 * (16 * 33 + 16)], proj.Gaussians[0].Color[0] * 0.99f + (1.0f - 0.99f));
  const auto clear = One({ 0, 0, 4 }, { 0.05f, 0.05f, 0.05f }, { 1, 0, 0, 0 }, -100.0f);
  ProjectionCounts counts;
  const auto img2 = Rasterize<float>(clear, cam, s, &counts);
  EXPECT_EQ(counts.Visible, 1u);
  EXPECT_TRUE(IsBackground(img2, s.Background));
  const auto fp = ComputeFootprints(ProjectGaussians<float>(clear, cam, s));
  EXPECT_EQ(fp.PixelCount[0], 0u);
  EXPECT_TRUE(IsBackground(Rasterize<double>(clear, cam, s), s.Background));
}

//------------------------------------------------------------------------------
// NaN/Inf parameters the reference has no answer for (vis4gs::ClassifyGaussian): skipped and
// counted; the rest of the image is bit-identical to the
// image of the valid Gaussians alone.
TEST(RasterizerStiff, NonFiniteParametersSkippedAndCounted)
{
  const auto valid = RandomScene(300, 3, 17u);
  GaussianCloud cloud = valid;
  const std::size_t n0 = valid.Count;
  const int bad = 12;
  GaussianCloud extra = RandomScene(bad, 3, 99u);
  // Inject one non-finite value per extra Gaussian, in every parameter kind.
  extra.Positions[0] = kNaN;
  extra.Positions[3 + 1] = kInf;
  extra.LogScales[3 * 2 + 2] = kNaN;
  extra.LogScales[3 * 3] = kInf;
  extra.Rotations[4 * 4 + 1] = kInf;
  extra.Rotations[4 * 5] = kNaN;
  extra.Rotations[4 * 6 + 3] = -kInf;
  extra.OpacityLogits[7] = kNaN;
  extra.Positions[3 * 8] = -kInf;
  extra.SH[48 * 9 + 1] = kNaN;   // DC
  extra.SH[48 * 10 + 30] = kInf; // degree 3
  extra.Positions[3 * 11 + 2] = -kInf;
  cloud.Count = n0 + bad;
  cloud.Positions.insert(cloud.Positions.end(), extra.Positions.begin(), extra.Positions.end());
  cloud.LogScales.insert(cloud.LogScales.end(), extra.LogScales.begin(), extra.LogScales.end());
  cloud.Rotations.insert(cloud.Rotations.end(), extra.Rotations.begin(), extra.Rotations.end());
  cloud.OpacityLogits.insert(
    cloud.OpacityLogits.end(), extra.OpacityLogits.begin(), extra.OpacityLogits.end());
  cloud.SH.insert(cloud.SH.end(), extra.SH.begin(), extra.SH.end());
  const Camera cam = LookAt(80, 60, 50, 50, { 0, 0, 0 }, { 0, 0, 5 });
  RasterSettings s;
  s.Background = { 0.2, 0.3, 0.4 };
  ProjectionCounts counts;
  const auto img = Rasterize<float>(cloud, cam, s, &counts);
  EXPECT_EQ(counts.InvalidParameters, static_cast<std::size_t>(bad));
  const auto ref = Rasterize<float>(valid, cam, s);
  EXPECT_EQ(0, std::memcmp(img.Color.data(), ref.Color.data(), img.Color.size() * sizeof(float)));
  EXPECT_EQ(img.Contributors, ref.Contributors);
  EXPECT_TRUE(AllFiniteImage(img));
  const auto imgD = Rasterize<double>(cloud, cam, s, &counts);
  EXPECT_EQ(counts.InvalidParameters, static_cast<std::size_t>(bad));
  EXPECT_TRUE(AllFiniteImage(imgD));
  // Only the parameters a render uses count: at SH degree 0 the degree-3 Inf is harmless.
  s.ShDegree = 0;
  Rasterize<float>(cloud, cam, s, &counts);
  EXPECT_EQ(counts.InvalidParameters, static_cast<std::size_t>(bad - 1));
  // Footprints and attribution never see them.
  const auto proj = ProjectGaussians<float>(cloud, cam, s);
  const auto fp = ComputeFootprints(proj);
  for (int k = 0; k < bad; ++k)
  {
    if (k != 10)
    {
      EXPECT_EQ(fp.PixelCount[n0 + k], 0u);
    }
  }
}

//------------------------------------------------------------------------------
TEST(RasterizerStiff, GaussianCoveringWholeImage)
{
  GaussianCloud cloud = RandomScene(200, 0, 3u);
  const std::size_t n = cloud.Count;
  GaussianCloud big = One({ 0, 0, 1.5f }, { 5, 5, 5 }, { 1, 0, 0, 0 }, -1.0f);
  cloud.Count = n + 1;
  cloud.Positions.insert(cloud.Positions.end(), big.Positions.begin(), big.Positions.end());
  cloud.LogScales.insert(cloud.LogScales.end(), big.LogScales.begin(), big.LogScales.end());
  cloud.Rotations.insert(cloud.Rotations.end(), big.Rotations.begin(), big.Rotations.end());
  cloud.OpacityLogits.push_back(big.OpacityLogits[0]);
  cloud.SH.insert(cloud.SH.end(), big.SH.begin(), big.SH.end());
  const Camera cam = LookAt(100, 80, 60, 60, { 0, 0, 0 }, { 0, 0, 5 });
  const auto proj = ProjectGaussians<float>(cloud, cam);
  const auto& g = proj.Gaussians[n];
  EXPECT_EQ(g.TileRect[0], 0);
  EXPECT_EQ(g.TileRect[1], 0);
  EXPECT_EQ(g.TileRect[2], proj.TilesX);
  EXPECT_EQ(g.TileRect[3], proj.TilesY);
  const auto img = Rasterize<float>(cloud, cam);
  for (std::size_t i = 0; i < img.Alpha.size(); ++i)
  {
    ASSERT_GE(img.Contributors[i], 1u);
    ASSERT_GT(img.Alpha[i], 0.2f);
  }
  const auto fp = ComputeFootprints(proj);
  EXPECT_EQ(fp.PixelCount[n], 100u * 80u);
  const auto naive = NaiveComposite(proj, {});
  EXPECT_EQ(0, std::memcmp(img.Color.data(), naive.Color.data(), img.Color.size() * sizeof(float)));
}

//------------------------------------------------------------------------------
// One million identical Gaussians on one pixel (equal depths: ties by index): T halves per
// Gaussian (o = 0.5), the 14th would drop T below 1e-4, so 13 blend and the rest is skipped.
TEST(RasterizerStiff, MillionGaussiansOnOnePixel)
{
  const std::size_t n = 1000000;
  GaussianCloud cloud;
  cloud.Resize(n, 0);
  const float ls = std::log(1e-4f);
  for (std::size_t i = 0; i < n; ++i)
  {
    SetGaussian(cloud, i, { 0, 0, 2 }, { ls, ls, ls }, { 1, 0, 0, 0 }, 0.0f, { 0.9f, 0.5f, 0.1f });
  }
  const Camera cam = AxisCamera(49, 49, 40, 40); // centre pixel (24, 24), radius 3: one tile
  RasterSettings s;
  s.Background = { 0, 0, 1 };
  const auto proj = ProjectGaussians<float>(cloud, cam, s);
  const auto bins = BinGaussians(proj);
  EXPECT_EQ(bins.Ids.size(), n);
  EXPECT_EQ(bins.Ids[0], 0u);
  EXPECT_EQ(bins.Ids[n - 1], static_cast<std::uint32_t>(n - 1));
  RasterImage<float> img;
  CompositeTiles(proj, bins, s, img);
  const std::size_t centre = 24 * 49 + 24;
  EXPECT_EQ(img.Contributors[centre], 13u);
  const double T13 = std::pow(0.5, 13);
  EXPECT_NEAR(img.Transmittance[centre], T13, 1e-9);
  const float c0 = proj.Gaussians[0].Color[0];
  EXPECT_NEAR(img.Color[3 * centre], c0 * (1 - T13), 1e-6);
  EXPECT_NEAR(img.Color[3 * centre + 2], proj.Gaussians[0].Color[2] * (1 - T13) + T13, 1e-6);
  const auto att = AttributePixels(proj, bins, s, { { 24, 24 } });
  ASSERT_EQ(att[0].Contributions.size(), 13u);
  EXPECT_EQ(att[0].Contributions[0].Gaussian, 0u); // ranked: largest weight 0.5 first
  EXPECT_DOUBLE_EQ(att[0].Contributions[0].Weight, 0.5);
  // Footprints ignore occlusion: every Gaussian has the same footprint.
  const auto fp = ComputeFootprints(proj);
  EXPECT_EQ(fp.PixelCount[0], fp.PixelCount[n - 1]);
  EXPECT_GE(fp.PixelCount[0], 1u);
}

// SPDX-License-Identifier: BSD-3-Clause
// View Coverage, Blur and Needle scores (DESIGN §4): hand-computed small cases, omega
// normalisation, exact vs brute-force footprints, and the stiff cases (zero-area footprints,
// empty views, views without images, NaN/Inf Gaussians, behind the camera, huge and tiny
// scales, opacity logits at +-1000). Footprints in the expectations are counted here by a
// plain scan of the tile rectangle with the rasteriser's kernel (the definition of Omega).
#include "ArtifactScores.h"
#include "ArtifactScoresTestScenes.h"
#include "BenchmarkSceneUtils.h"
#include "FastCoverage.h"
#include "NeedleShape.h"
#include "RasterKernel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>

namespace
{

using vis4gs::Camera;
using vis4gs::GaussianCloud;
using vis4gs_test::MakeCamera;
using vis4gs_test::OffsetImages;
using vis4gs_test::SetGaussian;

// Footprint sizes by a plain scan of each tile rectangle (the definition of Omega).
std::vector<std::uint32_t> NaiveFootprints(const GaussianCloud& cloud, const Camera& camera)
{
  vis4gs::RasterSettings settings;
  const auto proj = vis4gs::ProjectGaussians<float>(cloud, camera, settings);
  std::vector<std::uint32_t> count(cloud.Count, 0);
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    const auto& g = proj.Gaussians[i];
    if (!g.IsVisible())
    {
      continue;
    }
    for (int y = g.TileRect[1] * 16; y < std::min(g.TileRect[3] * 16, camera.Height); ++y)
    {
      for (int x = g.TileRect[0] * 16; x < std::min(g.TileRect[2] * 16, camera.Width); ++x)
      {
        const float power = vis4gs::raster::KernelPower<float>(
          g.U, g.V, g.ConicA, g.ConicB, g.ConicC, static_cast<float>(x), static_cast<float>(y));
        count[i] += vis4gs::raster::KernelAlpha<float>(g.Opacity, power) >= 0 ? 1 : 0;
      }
    }
  }
  return count;
}

double Shape(const GaussianCloud& cloud, std::size_t i)
{
  const double ls[3] = {
    cloud.LogScales[3 * i], cloud.LogScales[3 * i + 1], cloud.LogScales[3 * i + 2]
  };
  return vis4gs::NeedleShape(ls);
}

} // namespace

TEST(ArtifactScores, SingleGaussianByHand)
{
  GaussianCloud cloud;
  cloud.Resize(1, 0);
  SetGaussian(cloud, 0, 0.1f, -0.05f, 5, std::log(0.3f), std::log(0.1f), std::log(0.08f), 1.5f);
  const std::vector<Camera> cameras{ MakeCamera() };
  const float c = 0.25f;
  OffsetImages images{ &cloud, { c }, {} };
  const auto scores = vis4gs::ComputeGaussianScores(cloud, cameras, {}, images);
  const double omega = NaiveFootprints(cloud, cameras[0])[0];
  ASSERT_GT(omega, 20);
  const double lossPrime = 0.8 * c * omega; // L = 0.8 c on every pixel
  EXPECT_EQ(scores.ViewCoverage[0], 1.0);
  EXPECT_NEAR(scores.BlurScore[0], 1.0 * lossPrime, 1e-5 * lossPrime); // omega(g,v) = 1
  EXPECT_NEAR(scores.NeedleScore[0], Shape(cloud, 0) * lossPrime, 1e-5 * lossPrime);
  EXPECT_GT(Shape(cloud, 0), 0.2);
  EXPECT_EQ(scores.NeedleShape[0], Shape(cloud, 0));
  EXPECT_EQ(scores.Flags[0], 0);
  EXPECT_EQ(scores.ViewsUsed, 1u);
  EXPECT_EQ(scores.ViewsScored, 1u);
  EXPECT_TRUE(scores.Warnings.empty());
}

TEST(ArtifactScores, TwoViewsAndOmegaNormalisation)
{
  // A at z = 5 is seen by both views; B at z = 9.9 is 0.1 in front of view 1's camera
  // (near-plane cull there) and seen by view 0 only.
  GaussianCloud cloud;
  cloud.Resize(2, 0);
  SetGaussian(cloud, 0, 0, 0, 5, std::log(0.4f), std::log(0.2f), std::log(0.2f), 2.0f);
  SetGaussian(cloud, 1, 0.5f, 0.3f, 9.9f, std::log(0.05f), std::log(0.05f), std::log(0.05f), 3.0f);
  const std::vector<Camera> cameras{ MakeCamera(), MakeCamera(10, true) };
  const float c0 = 0.1f, c1 = 0.4f;
  OffsetImages images{ &cloud, { c0, c1 }, {} };
  const auto s = vis4gs::ComputeGaussianScores(cloud, cameras, {}, images);
  const auto f0 = NaiveFootprints(cloud, cameras[0]);
  const auto f1 = NaiveFootprints(cloud, cameras[1]);
  ASSERT_GT(f0[0], 0u);
  ASSERT_GT(f0[1], 0u);
  ASSERT_GT(f1[0], 0u);
  ASSERT_EQ(f1[1], 0u);
  const double max0 = std::max(f0[0], f0[1]), max1 = f1[0];
  const double lA0 = 0.8 * c0 * f0[0], lA1 = 0.8 * c1 * f1[0], lB0 = 0.8 * c0 * f0[1];
  EXPECT_EQ(s.ViewCoverage[0], 1.0);
  EXPECT_EQ(s.ViewCoverage[1], 0.5);
  const double blurA = 0.5 * (f0[0] / max0 * lA0 + f1[0] / max1 * lA1);
  const double blurB = f0[1] / max0 * lB0;
  EXPECT_NEAR(s.BlurScore[0], blurA, 1e-5 * blurA);
  EXPECT_NEAR(s.BlurScore[1], blurB, 1e-5 * blurB);
  EXPECT_NEAR(s.NeedleScore[0], Shape(cloud, 0) * 0.5 * (lA0 + lA1), 1e-5 * (lA0 + lA1));
  EXPECT_NEAR(s.NeedleScore[1], Shape(cloud, 1) * lB0, 1e-6 * lB0);
  EXPECT_LT(f0[1], f0[0]); // B is the smaller: omega < 1
  EXPECT_EQ(s.CoverageViews[1], 1u);
  EXPECT_EQ(s.ScoredViews[1], 1u);
}

TEST(ArtifactScores, FastFootprintsEqualBruteForce)
{
  GaussianCloud cloud;
  const std::size_t n = 400;
  cloud.Resize(n, 0);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1, 1);
  for (std::size_t i = 0; i < n; ++i)
  {
    SetGaussian(cloud,
      i,
      1.5f * u(rng),
      u(rng),
      5 + 2 * u(rng),
      -2.5f + 1.5f * u(rng),
      -2.5f + 1.5f * u(rng),
      -2.5f + 1.5f * u(rng),
      3 * u(rng));
    for (int k = 0; k < 4; ++k)
    {
      cloud.Rotations[4 * i + k] = u(rng);
    }
  }
  const std::vector<Camera> cameras{ MakeCamera(), MakeCamera(10, true), MakeCamera(-1) };
  OffsetImages images{ &cloud, { 0.1f, 0.2f, 0.3f }, {} };
  vis4gs::ScoreSettings fast, brute;
  brute.BruteForceFootprints = true;
  const auto a = vis4gs::ComputeGaussianScores(cloud, cameras, fast, images);
  const auto b = vis4gs::ComputeGaussianScores(cloud, cameras, brute, images);
  EXPECT_EQ(a.CoverageViews, b.CoverageViews);
  EXPECT_EQ(a.ScoredViews, b.ScoredViews);
  EXPECT_EQ(a.BlurScore, b.BlurScore);
  EXPECT_EQ(a.NeedleScore, b.NeedleScore);
  // And the per-view counts equal the plain scan.
  for (std::size_t v = 0; v < cameras.size(); ++v)
  {
    vis4gs::FootprintOptions options;
    const auto proj = vis4gs::ProjectGaussians<float>(cloud, cameras[v]);
    EXPECT_EQ(
      vis4gs::ComputeFootprints(proj, options).PixelCount, NaiveFootprints(cloud, cameras[v]));
  }
  // Coverage computed alone equals coverage computed with the blur pass.
  vis4gs::ScoreSettings coverageOnly;
  coverageOnly.Request = { true, false, false, false };
  EXPECT_EQ(
    vis4gs::ComputeGaussianScores(cloud, cameras, coverageOnly).CoverageViews, a.CoverageViews);
}

TEST(ArtifactScores, StiffGaussiansAreFlaggedAndDoNotPoison)
{
  // 0: normal; 1: NaN position; 2: +Inf log-scale; 3: behind the camera; 4: opacity logit
  // -1000 (o = 0: zero-area footprint); 5: opacity logit +1000 (o = 1); 6: huge (log-scale
  // 30); 7: tiny (log-scale -30, the 0.3 px^2 dilation keeps it about a pixel wide).
  GaussianCloud cloud;
  cloud.Resize(8, 0);
  for (std::size_t i = 0; i < 8; ++i)
  {
    SetGaussian(cloud, i, 0.2f * (static_cast<float>(i) - 4), 0.1f, 5, -2.5f, -3, -3.5f, 1);
  }
  cloud.Positions[3 * 1] = std::numeric_limits<float>::quiet_NaN();
  cloud.LogScales[3 * 2 + 1] = std::numeric_limits<float>::infinity();
  cloud.Positions[3 * 3 + 2] = -5;
  cloud.OpacityLogits[4] = -1000;
  cloud.OpacityLogits[5] = 1000;
  for (int k = 0; k < 3; ++k)
  {
    cloud.LogScales[3 * 6 + k] = 30;
    cloud.LogScales[3 * 7 + k] = -30;
  }
  const std::vector<Camera> cameras{ MakeCamera(), MakeCamera(-2) };
  OffsetImages images{ &cloud, { 0.2f, 0.3f }, {} };
  const auto s = vis4gs::ComputeGaussianScores(cloud, cameras, {}, images);
  for (std::size_t i = 0; i < 8; ++i)
  {
    EXPECT_TRUE(std::isfinite(s.ViewCoverage[i])) << i;
    EXPECT_TRUE(std::isfinite(s.BlurScore[i])) << i;
    EXPECT_TRUE(std::isfinite(s.NeedleScore[i])) << i;
    EXPECT_GE(s.BlurScore[i], 0) << i;
  }
  for (std::size_t i : { 1, 2, 3, 4 })
  {
    EXPECT_EQ(s.ViewCoverage[i], 0.0) << i;
    EXPECT_EQ(s.BlurScore[i], 0.0) << i;
    EXPECT_EQ(s.NeedleScore[i], 0.0) << i;
    EXPECT_TRUE(s.Flags[i] & vis4gs::NoVisibleCoverageView) << i;
    EXPECT_TRUE(s.Flags[i] & vis4gs::NoVisibleScoredView) << i;
  }
  EXPECT_EQ(s.Flags[1] & vis4gs::InvalidParameters, vis4gs::InvalidParameters);
  EXPECT_EQ(s.Flags[2] & vis4gs::InvalidParameters, vis4gs::InvalidParameters);
  EXPECT_EQ(s.Flags[3] & vis4gs::InvalidParameters, 0);
  EXPECT_EQ(s.InvalidCount, 2u);
  EXPECT_TRUE(std::isnan(s.NeedleShape[1]) == false); // NaN position, finite log-scales
  for (std::size_t i : { 0, 5, 7 })
  {
    EXPECT_EQ(s.ViewCoverage[i], 1.0) << i;
    EXPECT_GT(s.BlurScore[i], 0.0) << i;
    EXPECT_EQ(s.Flags[i], 0) << i;
  }
  // The normal Gaussian's needle score does not depend on the stiff ones (it does not use
  // omega, and the loss map is a constant): same value with Gaussian 0 alone.
  GaussianCloud alone;
  alone.Resize(1, 0);
  SetGaussian(alone, 0, 0.2f * -4, 0.1f, 5, -2.5f, -3, -3.5f, 1);
  OffsetImages aloneImages{ &alone, { 0.2f, 0.3f }, {} };
  const auto a = vis4gs::ComputeGaussianScores(alone, cameras, {}, aloneImages);
  EXPECT_NEAR(a.NeedleScore[0], s.NeedleScore[0], 1e-6 * a.NeedleScore[0]);
  EXPECT_EQ(a.ViewCoverage[0], s.ViewCoverage[0]);
  // Every footprint equals the plain scan, stiff Gaussians included.
  for (const Camera& camera : cameras)
  {
    const auto proj = vis4gs::ProjectGaussians<float>(cloud, camera);
    EXPECT_EQ(vis4gs::ComputeFootprints(proj).PixelCount, NaiveFootprints(cloud, camera));
  }
}

TEST(ArtifactScores, SpecialValuesTheReferenceDrawsAreScoredLikeTheirLimits)
{
  // Documentation/special-values.md: an opacity logit of +-inf, a log-scale of -inf and a zero
  // quaternion are drawn by the reference (opacity 1 / 0, scale 0, identity rotation), so
  // their scores equal those of the finite stand-ins the renderer draws identically
  // (TestSpecialValues), and they are not flagged.
  const float inf = std::numeric_limits<float>::infinity();
  GaussianCloud special, limits;
  for (GaussianCloud* c : { &special, &limits })
  {
    c->Resize(5, 0);
    for (std::size_t i = 0; i < 5; ++i)
    {
      SetGaussian(*c, i, 0.25f * (static_cast<float>(i) - 2), 0.05f, 5, -2.5f, -3, -3.5f, 1);
    }
  }
  special.OpacityLogits[0] = inf;
  limits.OpacityLogits[0] = 1e30f;
  special.OpacityLogits[1] = -inf;
  limits.OpacityLogits[1] = -1e30f;
  special.LogScales[3 * 2 + 1] = -inf;
  limits.LogScales[3 * 2 + 1] = -200;
  for (int k = 0; k < 4; ++k)
  {
    special.Rotations[4 * 3 + k] = 0;
    limits.Rotations[4 * 3 + k] = k == 0 ? 1.0f : 0.0f;
  }
  const std::vector<Camera> cameras{ MakeCamera(), MakeCamera(-1), MakeCamera(9, true) };
  const OffsetImages imagesA{ &special, { 0.1f, -0.2f, 0.3f }, {} };
  const OffsetImages imagesB{ &limits, { 0.1f, -0.2f, 0.3f }, {} };
  const auto a = vis4gs::ComputeGaussianScores(special, cameras, {}, imagesA);
  const auto b = vis4gs::ComputeGaussianScores(limits, cameras, {}, imagesB);
  EXPECT_EQ(a.InvalidCount, 0u);
  for (std::size_t i = 0; i < 5; ++i)
  {
    EXPECT_EQ(a.Flags[i], b.Flags[i]) << i;
    EXPECT_EQ(a.Flags[i] & vis4gs::InvalidParameters, 0) << i;
    EXPECT_EQ(a.ViewCoverage[i], b.ViewCoverage[i]) << i;
    EXPECT_EQ(a.BlurScore[i], b.BlurScore[i]) << i;
    EXPECT_EQ(a.NeedleScore[i], b.NeedleScore[i]) << i;
  }
  // The opaque one is seen as often as the ordinary Gaussian 4; the transparent one
  // by none.
  EXPECT_GT(a.ViewCoverage[4], 0.0);
  EXPECT_EQ(a.ViewCoverage[0], a.ViewCoverage[4]);
  EXPECT_EQ(a.ViewCoverage[1], 0.0);
  EXPECT_EQ(a.ViewCoverage[2], a.ViewCoverage[4]);
}

TEST(ArtifactScores, EmptyViewsAndViewsWithoutImages)
{
  GaussianCloud cloud;
  cloud.Resize(2, 0);
  SetGaussian(cloud, 0, 0, 0, 5, -2, -2, -2.5f, 2);
  SetGaussian(cloud, 1, 0.3f, 0, 4, -2.5f, -2, -2, 2);
  // View 1 looks away from every Gaussian (empty view); view 2 has no image.
  const std::vector<Camera> cameras{ MakeCamera(), MakeCamera(-1, true), MakeCamera(-1) };
  OffsetImages images{ &cloud, { 0.3f, 0.3f, 0.3f }, { false, false, true } };
  const auto s = vis4gs::ComputeGaussianScores(cloud, cameras, {}, images);
  EXPECT_EQ(s.ViewsUsed, 3u);
  EXPECT_EQ(s.ViewsScored, 2u);
  EXPECT_EQ(s.ViewsWithoutImage, 1u);
  ASSERT_EQ(s.Warnings.size(), 1u);
  EXPECT_NE(s.Warnings[0].find("1 of 3 training views have no image"), std::string::npos);
  const auto f0 = NaiveFootprints(cloud, cameras[0]);
  for (std::size_t i = 0; i < 2; ++i)
  {
    // Coverage counts views without images (visible in views 0 and 2 of 3) ...
    EXPECT_NEAR(s.ViewCoverage[i], 2.0 / 3.0, 1e-15);
    // ... blur and needle average over the one scored view where it is visible.
    EXPECT_EQ(s.ScoredViews[i], 1u);
    const double l = 0.8 * 0.3f * f0[i];
    EXPECT_NEAR(s.NeedleScore[i], Shape(cloud, i) * l, 1e-5 * l);
  }
  // A scene where every view is empty: everything 0 and flagged, no division by zero.
  const std::vector<Camera> away{ MakeCamera(-1, true) };
  const auto e = vis4gs::ComputeGaussianScores(cloud, away, {}, images);
  EXPECT_EQ(e.NoCoverageViewCount, 2u);
  EXPECT_EQ(e.NoScoredViewCount, 2u);
  EXPECT_EQ(e.BlurScore, std::vector<double>(2, 0.0));
  // No cameras at all.
  vis4gs::ScoreSettings coverageOnly;
  coverageOnly.Request = { true, false, false, false };
  const auto none = vis4gs::ComputeGaussianScores(cloud, {}, coverageOnly);
  EXPECT_EQ(none.ViewCoverage, std::vector<double>(2, 0.0));
}

TEST(ArtifactScores, OnlyWhatIsRequested)
{
  GaussianCloud cloud;
  cloud.Resize(3, 0);
  for (std::size_t i = 0; i < 3; ++i)
  {
    SetGaussian(cloud, i, 0.3f * i, 0, 5, -2, -3, -4, 1);
  }
  // Needle shape alone: no cameras, no images.
  vis4gs::ScoreSettings shapeOnly;
  shapeOnly.Request = { false, false, false, true };
  const auto a = vis4gs::ComputeGaussianScores(cloud, {}, shapeOnly);
  EXPECT_EQ(a.NeedleShape.size(), 3u);
  EXPECT_TRUE(a.ViewCoverage.empty() && a.BlurScore.empty() && a.NeedleScore.empty());
  // Coverage alone: no image provider needed, nothing rendered, no image loaded.
  vis4gs::ScoreSettings coverageOnly;
  coverageOnly.Request = { true, false, false, false };
  const auto b = vis4gs::ComputeGaussianScores(cloud, { MakeCamera() }, coverageOnly);
  EXPECT_EQ(b.ViewCoverage, std::vector<double>(3, 1.0));
  EXPECT_EQ(b.Timings.Rendering, 0.0);
  EXPECT_EQ(b.Timings.Images, 0.0);
  EXPECT_TRUE(b.NeedleShape.empty() && b.BlurScore.empty());
  // Blur without images is an error.
  vis4gs::ScoreSettings blur;
  EXPECT_THROW(vis4gs::ComputeGaussianScores(cloud, { MakeCamera() }, blur), std::invalid_argument);
}

TEST(ArtifactScores, OcclusionAwareCoverage)
{
  // An opaque wall (large, opacity 1) at z = 3 hides a small Gaussian at z = 6 in view 0;
  // view 1 (behind the small one, looking back) sees the small one in front.
  GaussianCloud cloud;
  cloud.Resize(2, 0);
  SetGaussian(cloud, 0, 0, 0, 3, 1, 1, -3, 1000);
  SetGaussian(cloud, 1, 0, 0, 6, -2.5f, -2.5f, -2.5f, 2);
  const std::vector<Camera> cameras{ MakeCamera(), MakeCamera(9, true) };
  vis4gs::ScoreSettings plain, occluded;
  plain.Request = occluded.Request = { true, false, false, false };
  occluded.OcclusionThreshold = 0.01;
  const auto p = vis4gs::ComputeGaussianScores(cloud, cameras, plain);
  const auto o = vis4gs::ComputeGaussianScores(cloud, cameras, occluded);
  EXPECT_EQ(p.ViewCoverage[1], 1.0);
  EXPECT_EQ(o.ViewCoverage[1], 0.5);
  EXPECT_EQ(o.ViewCoverage[0], 1.0);
  // Shared with the score pass, the same result.
  occluded.Request = { true, true, false, false };
  OffsetImages images{ &cloud, { 0.1f, 0.1f }, {} };
  EXPECT_EQ(
    vis4gs::ComputeGaussianScores(cloud, cameras, occluded, images).ViewCoverage, o.ViewCoverage);
}

TEST(ArtifactScores, ViewSubsets)
{
  std::vector<Camera> cameras;
  for (int i = 0; i < 6; ++i)
  {
    cameras.push_back(MakeCamera(-0.1 * i));
  }
  cameras[1].Split = vis4gs::CameraSplit::Test;
  vis4gs::ScoreSettings s;
  EXPECT_EQ(vis4gs::SelectViews(cameras, s), (std::vector<std::size_t>{ 0, 2, 3, 4, 5 }));
  s.ViewStride = 2;
  EXPECT_EQ(vis4gs::SelectViews(cameras, s), (std::vector<std::size_t>{ 0, 3, 5 }));
  s.ViewList = { 4, 2 };
  EXPECT_EQ(vis4gs::SelectViews(cameras, s), (std::vector<std::size_t>{ 4, 2 }));
  s.ViewList = { 1 };
  EXPECT_THROW(vis4gs::SelectViews(cameras, s), std::invalid_argument);
  s.ViewList = { 9 };
  EXPECT_THROW(vis4gs::SelectViews(cameras, s), std::invalid_argument);
  s.ViewList = { 2, 2 };
  EXPECT_THROW(vis4gs::SelectViews(cameras, s), std::invalid_argument);
  s.ViewList.clear();
  s.ViewStride = 0;
  EXPECT_THROW(vis4gs::SelectViews(cameras, s), std::invalid_argument);
}

TEST(ArtifactScores, ApproximationsStayClose)
{
  GaussianCloud cloud;
  cloud.Resize(1, 0);
  SetGaussian(cloud, 0, 0, 0, 5, std::log(0.5f), std::log(0.3f), std::log(0.3f), 2);
  const std::vector<Camera> cameras{ MakeCamera(0, false, 128, 96) };
  OffsetImages images{ &cloud, { 0.2f }, {} };
  const auto exact = vis4gs::ComputeGaussianScores(cloud, cameras, {}, images);
  // Float accumulation: relative error at the float rounding level.
  vis4gs::ScoreSettings f;
  f.Accumulation = vis4gs::FootprintAccumulation::Float;
  const auto fl = vis4gs::ComputeGaussianScores(cloud, cameras, f, images);
  EXPECT_NEAR(fl.NeedleScore[0], exact.NeedleScore[0], 1e-4 * exact.NeedleScore[0]);
  // Half resolution: L' is scaled by the area ratio, so it estimates the full sum closely
  // for a footprint of thousands of pixels.
  vis4gs::ScoreSettings half;
  half.LossResolution = 2;
  const auto h = vis4gs::ComputeGaussianScores(cloud, cameras, half, images);
  EXPECT_NEAR(h.NeedleScore[0], exact.NeedleScore[0], 0.1 * exact.NeedleScore[0]);
  // 3-sigma ellipse: a different but similar region (power >= -4.5 vs alpha >= 1/255).
  vis4gs::ScoreSettings ellipse;
  ellipse.Footprint = vis4gs::FootprintMode::Ellipse3Sigma;
  const auto e = vis4gs::ComputeGaussianScores(cloud, cameras, ellipse, images);
  EXPECT_NEAR(e.NeedleScore[0], exact.NeedleScore[0], 0.3 * exact.NeedleScore[0]);
  EXPECT_NE(e.NeedleScore[0], exact.NeedleScore[0]);
  // Bad settings.
  vis4gs::ScoreSettings bad;
  bad.LossResolution = 3;
  EXPECT_THROW(vis4gs::ComputeGaussianScores(cloud, cameras, bad, images), std::invalid_argument);
  bad.LossResolution = 1;
  bad.OcclusionThreshold = 2;
  EXPECT_THROW(vis4gs::ComputeGaussianScores(cloud, cameras, bad, images), std::invalid_argument);
}

TEST(ArtifactScores, ImageOfTheWrongSizeIsAnError)
{
  GaussianCloud cloud;
  cloud.Resize(1, 0);
  SetGaussian(cloud, 0, 0, 0, 5, -2, -2, -2, 2);
  auto provider = [](std::size_t, const Camera&, vis4gs::Image& image)
  {
    image.Width = 10;
    image.Height = 10;
    image.Pixels.assign(300, 0.5f);
    return true;
  };
  try
  {
    vis4gs::ComputeGaussianScores(cloud, { MakeCamera() }, {}, provider);
    FAIL() << "no exception";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_NE(std::string(e.what()).find("10x10 but the camera is 64x48"), std::string::npos)
      << e.what();
  }
}

TEST(ArtifactScores, FastCoverageEqualsProjectionAndFootprints)
{
  // Random anisotropic Gaussians with stiff ones mixed in, seen from several cameras (some
  // Gaussians cross the near plane, some leave the image, some are huge or tiny, some have
  // opacities near 1/255). The fused early-exit visibility must equal PixelCount >= 1.
  GaussianCloud cloud;
  const std::size_t n = 3000;
  cloud.Resize(n, 0);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1, 1);
  for (std::size_t i = 0; i < n; ++i)
  {
    SetGaussian(cloud,
      i,
      4 * u(rng),
      3 * u(rng),
      3 + 4 * u(rng),
      -3 + 3 * u(rng),
      -3 + 3 * u(rng),
      -4 + 4 * u(rng),
      -5.5f + 8 * (u(rng) + 1) / 2);
    for (int k = 0; k < 4; ++k)
    {
      cloud.Rotations[4 * i + k] = u(rng);
    }
    switch (i % 50)
    {
      case 0:
        cloud.LogScales[3 * i] = 40;
        break;
      case 1:
        cloud.LogScales[3 * i + 1] = -60;
        cloud.LogScales[3 * i + 2] = -60;
        break;
      case 2:
        cloud.OpacityLogits[i] = -1000;
        break;
      case 3:
        cloud.OpacityLogits[i] = 1000;
        break;
      case 4:
        cloud.Positions[3 * i + 2] = 0.2f;
        break;
      case 5:
        cloud.Rotations[4 * i] = cloud.Rotations[4 * i + 1] = cloud.Rotations[4 * i + 2] =
          cloud.Rotations[4 * i + 3] = 0;
        break;
      case 6:
        cloud.OpacityLogits[i] = std::nanf("");
        break;
      case 7:
        cloud.OpacityLogits[i] = -5.54f;
        break; // o just above / below 1/255
      default:
        break;
    }
  }
  const std::vector<Camera> cameras{ MakeCamera(),
    MakeCamera(10, true),
    MakeCamera(-3, false, 37, 23),
    MakeCamera(0, false, 200, 150) };
  for (auto mode : { vis4gs::FootprintMode::Rasterizer, vis4gs::FootprintMode::Ellipse3Sigma })
  {
    std::size_t visible = 0;
    for (const Camera& camera : cameras)
    {
      vis4gs::FootprintOptions options;
      options.Mode = mode;
      const auto counts =
        vis4gs::ComputeFootprints(vis4gs::ProjectGaussians<float>(cloud, camera), options)
          .PixelCount;
      const auto fast = vis4gs::VisibleInView(cloud, camera, mode);
      // The scalar test (kernelIsa 1) and other thread counts give the same answers as the
      // vectorised block test (default on AVX2 machines).
      const auto scalar = vis4gs::VisibleInView(cloud, camera, mode, 1, 1.0, 1);
      const auto threads3 = vis4gs::VisibleInView(cloud, camera, mode, 3, 1.0, 2);
      ASSERT_EQ(fast.size(), n);
      EXPECT_EQ(fast, scalar);
      EXPECT_EQ(fast, threads3);
      for (std::size_t i = 0; i < n; ++i)
      {
        ASSERT_EQ(fast[i] != 0, counts[i] >= 1) << "Gaussian " << i << " mode " << int(mode);
        visible += fast[i];
      }
    }
    EXPECT_GT(visible, n / 2);
  }
}

TEST(ArtifactScores, FastCoverageVectorEqualsScalarOnShellScene)
{
  // The benchmark's scene (sphere shell, needles, floaters leaving the image, low
  // opacities) at full and reduced resolution, with cameras at several distances (the
  // closest ones put Gaussians behind the near plane): the vectorised block test (one pixel
  // per lane, then the scalar search for undecided lanes) equals the scalar test and the
  // projection + footprint counts, for every Gaussian, whatever the thread count.
  const GaussianCloud cloud = vis4gs::bench::ShellScene(20011, 3, -4.5);
  std::vector<Camera> cameras = vis4gs::bench::RingCameras(5, 3.0, 160, 90);
  const std::vector<Camera> near = vis4gs::bench::RingCameras(3, 1.1, 64, 48);
  cameras.insert(cameras.end(), near.begin(), near.end());
  std::vector<std::uint32_t> vec, scalar, vec1;
  vis4gs::CountVisibleViews(cloud, cameras, vis4gs::FootprintMode::Rasterizer, vec, 0, 1.0, 0);
  vis4gs::CountVisibleViews(cloud, cameras, vis4gs::FootprintMode::Rasterizer, scalar, 2, 1.0, 1);
  vis4gs::CountVisibleViews(cloud, cameras, vis4gs::FootprintMode::Rasterizer, vec1, 1, 1.0, 2);
  EXPECT_EQ(vec, scalar);
  EXPECT_EQ(vec, vec1);
  std::vector<std::uint32_t> reference(cloud.Count, 0);
  for (const Camera& camera : cameras)
  {
    const auto counts =
      vis4gs::ComputeFootprints(vis4gs::ProjectGaussians<float>(cloud, camera)).PixelCount;
    for (std::size_t i = 0; i < cloud.Count; ++i)
    {
      reference[i] += counts[i] >= 1 ? 1 : 0;
    }
  }
  EXPECT_EQ(vec, reference);
  std::size_t partial = 0;
  for (std::uint32_t k : vec)
  {
    partial += (k > 0 && k < cameras.size()) ? 1 : 0;
  }
  EXPECT_GT(partial, cloud.Count / 10); // the views disagree for many Gaussians
}

TEST(ArtifactScores, ScoresDoNotDependOnThreadCount)
{
  const GaussianCloud cloud = vis4gs::bench::ShellScene(3001, 4, -4.0);
  const std::vector<Camera> cameras = vis4gs::bench::RingCameras(3, 3.0, 96, 64);
  OffsetImages images{ &cloud, { 0.1f, 0.2f, 0.3f }, {} };
  vis4gs::ScoreSettings one, three;
  one.Threads = 1;
  three.Threads = 3;
  one.LossResolution = three.LossResolution = 2;
  one.CoverageResolution = 1;
  three.CoverageResolution = 1;
  const auto a = vis4gs::ComputeGaussianScores(cloud, cameras, one, images);
  const auto b = vis4gs::ComputeGaussianScores(cloud, cameras, three, images);
  EXPECT_EQ(a.CoverageViews, b.CoverageViews);
  EXPECT_EQ(a.ScoredViews, b.ScoredViews);
  EXPECT_EQ(a.BlurScore, b.BlurScore);
  EXPECT_EQ(a.NeedleScore, b.NeedleScore);
  double blurTotal = 0;
  for (double v : a.BlurScore)
  {
    blurTotal += v;
  }
  EXPECT_GT(blurTotal, 0);
}

TEST(ArtifactScores, SharedProjectionGivesIdenticalScores)
{
  // The blur/needle pass through Render/MultiViewRenderer.h (view-independent preparation
  // once, vectorised projection shared by compositing and footprints) against the per-view
  // ProjectGaussians + CompositeTiles + ComputeFootprints path: every score bit-identical,
  // for every resolution factor, footprint mode, accumulation, SH degree, kernel
  // instruction set and thread count; with stiff Gaussians and cameras close enough to put
  // Gaussians behind the near plane.
  for (int degree : { 0, 2 })
  {
    GaussianCloud cloud = vis4gs::bench::ShellScene(3001, 7 + degree, -4.2);
    if (degree > 0)
    {
      GaussianCloud shDegree;
      shDegree.Resize(cloud.Count, degree);
      shDegree.Positions = cloud.Positions;
      shDegree.LogScales = cloud.LogScales;
      shDegree.Rotations = cloud.Rotations;
      shDegree.OpacityLogits = cloud.OpacityLogits;
      for (std::size_t i = 0; i < shDegree.SH.size(); ++i)
      {
        shDegree.SH[i] = 0.3f * std::sin(0.37f * static_cast<float>(i));
      }
      cloud = shDegree;
    }
    cloud.Positions[3 * 5] = std::numeric_limits<float>::quiet_NaN();
    cloud.LogScales[3 * 6 + 1] = 30.0f;
    cloud.OpacityLogits[7] = -1000.0f;
    std::vector<Camera> cameras = vis4gs::bench::RingCameras(3, 3.0, 96, 64);
    const std::vector<Camera> near = vis4gs::bench::RingCameras(2, 1.1, 64, 48);
    cameras.insert(cameras.end(), near.begin(), near.end());
    // Varied images (every pixel a different loss), the third view without one.
    auto images = [](std::size_t index, const Camera& camera, vis4gs::Image& image)
    {
      if (index == 2)
      {
        return false;
      }
      image.Width = camera.Width;
      image.Height = camera.Height;
      image.Channels = 3;
      image.Pixels.resize(static_cast<std::size_t>(camera.Width) * camera.Height * 3);
      for (std::size_t k = 0; k < image.Pixels.size(); ++k)
      {
        image.Pixels[k] = 0.5f + 0.5f * std::sin(0.71f * static_cast<float>(k) + index);
      }
      return true;
    };
    int variant = 0;
    for (int factor : { 1, 4 })
    {
      for (auto mode : { vis4gs::FootprintMode::Rasterizer, vis4gs::FootprintMode::Ellipse3Sigma })
      {
        for (auto acc :
          { vis4gs::FootprintAccumulation::Double, vis4gs::FootprintAccumulation::Float })
        {
          ++variant;
          vis4gs::ScoreSettings shared, perView;
          shared.LossResolution = perView.LossResolution = factor;
          shared.CoverageResolution = perView.CoverageResolution = factor;
          shared.Footprint = perView.Footprint = mode;
          shared.Accumulation = perView.Accumulation = acc;
          shared.Threads = 1 + variant % 3;
          perView.Threads = 2;
          shared.KernelIsa = variant % 2;
          shared.Raster.KernelIsa = variant % 4;
          shared.Raster.Background = perView.Raster.Background = { 0.2, 0.1, 0.0 };
          perView.SharedProjection = false;
          const auto a = vis4gs::ComputeGaussianScores(cloud, cameras, shared, images);
          const auto b = vis4gs::ComputeGaussianScores(cloud, cameras, perView, images);
          SCOPED_TRACE(::testing::Message() << "degree " << degree << " variant " << variant);
          EXPECT_EQ(a.CoverageViews, b.CoverageViews);
          EXPECT_EQ(a.ScoredViews, b.ScoredViews);
          ASSERT_EQ(a.BlurScore.size(), cloud.Count);
          EXPECT_EQ(0, std::memcmp(a.BlurScore.data(), b.BlurScore.data(), cloud.Count * 8));
          EXPECT_EQ(0, std::memcmp(a.NeedleScore.data(), b.NeedleScore.data(), cloud.Count * 8));
          EXPECT_EQ(a.Flags, b.Flags);
          std::size_t scored = 0;
          for (std::uint32_t k : a.ScoredViews)
          {
            scored += k > 0 ? 1 : 0;
          }
          EXPECT_GT(scored, cloud.Count / 2);
        }
      }
    }
  }
}

//------------------------------------------------------------------------------
// Issue 15: blur and needle scores with a non-constant loss map.
namespace
{

// Whether pixel (x, y) is in Omega(g) of Gaussian @p i (tile rectangle, kernel, alpha test).
bool InFootprint(const vis4gs::ViewProjection<float>& proj, std::size_t i, int x, int y)
{
  const auto& g = proj.Gaussians[i];
  if (!g.IsVisible() || x / 16 < g.TileRect[0] || x / 16 >= g.TileRect[2] ||
    y / 16 < g.TileRect[1] || y / 16 >= g.TileRect[3])
  {
    return false;
  }
  const float power = vis4gs::raster::KernelPower<float>(
    g.U, g.V, g.ConicA, g.ConicB, g.ConicC, static_cast<float>(x), static_cast<float>(y));
  return vis4gs::raster::KernelAlpha<float>(g.Opacity, power) >= 0;
}

// Needle shape by hand from the scales (DESIGN §4): q_k = s_k^2 / sum s^2,
// H = -sum q log q, s = (3 - e^H) / 2.
double ShapeByHand(const GaussianCloud& cloud, std::size_t i)
{
  double s2[3], sum = 0;
  for (int k = 0; k < 3; ++k)
  {
    s2[k] = std::exp(2.0 * cloud.LogScales[3 * i + k]);
    sum += s2[k];
  }
  double h = 0;
  for (double v : s2)
  {
    h -= v / sum * std::log(v / sum);
  }
  return (3 - std::exp(h)) / 2;
}

// A: anisotropic, left of the axis; B: A's mirror image (x -> -x); C: on the axis, below.
// All axis-aligned with one colour and opacity 0.27, whose alpha footprint (2.9 sigma) lies
// inside the 3-sigma tile rectangle, so that mirroring the scene mirrors every footprint.
// On a 96x64 view the render is mirror-symmetric about the column x = 47.5.
GaussianCloud MirrorScene()
{
  GaussianCloud cloud;
  cloud.Resize(3, 0);
  SetGaussian(cloud, 0, -1.43f, 0.2f, 5, std::log(0.3f), std::log(0.15f), std::log(0.1f), -1);
  SetGaussian(cloud, 1, 1.43f, 0.2f, 5, std::log(0.3f), std::log(0.15f), std::log(0.1f), -1);
  SetGaussian(cloud, 2, 0, -0.4f, 5, std::log(0.2f), std::log(0.2f), std::log(0.05f), -1);
  return cloud;
}

// The render plus a positive linear ramp per channel (non-constant L1, a Laplacian of 0
// away from the borders), optionally mirrored, plus @p hot added to pixel (hx, hy).
vis4gs::Image RampImage(const GaussianCloud& cloud,
  const Camera& camera,
  bool mirrored,
  int hx = -1,
  int hy = -1,
  float hot = 0)
{
  const auto render = vis4gs::Rasterize<float>(cloud, camera);
  vis4gs::Image image;
  image.Width = camera.Width;
  image.Height = camera.Height;
  image.Pixels = render.Color;
  for (int y = 0; y < camera.Height; ++y)
  {
    for (int x = 0; x < camera.Width; ++x)
    {
      const int rx = mirrored ? camera.Width - 1 - x : x;
      for (int c = 0; c < 3; ++c)
      {
        image.At(x, y, c) += 0.05f + 0.004f * (c + 1) * rx + 0.002f * y;
      }
    }
  }
  if (hx >= 0)
  {
    for (int c = 0; c < 3; ++c)
    {
      image.At(hx, hy, c) += hot;
    }
  }
  return image;
}

vis4gs::GaussianScores ScoresWith(const GaussianCloud& cloud,
  const Camera& camera,
  const vis4gs::Image& image,
  double lambda)
{
  vis4gs::ScoreSettings settings;
  settings.Lambda = lambda;
  return vis4gs::ComputeGaussianScores(cloud,
    { camera },
    settings,
    [&](std::size_t, const Camera&, vis4gs::Image& out)
    {
      out = image;
      return true;
    });
}

} // namespace

// One hot pixel: adding d to every channel of image pixel p (where the image already exceeds
// the render, so |render - image| grows by exactly d) raises the loss map by
//   lambda = 0:   d at p only (L = L1);
//   lambda = 0.2: 0.8 d + 0.2 |4 d| = 1.6 d at p and 0.2 |d| at its four neighbours (the
//                 four-neighbour Laplacian of the ramp is 0, that of the spike is -4d, +d).
// With one view, E_B(g) = omega(g) L'(g) and E_N(g) = s(g) L'(g), L' the sum of L over
// Omega(g): a Gaussian whose footprint holds p and its neighbours gains omega*dL' and
// s*dL'; a Gaussian whose footprint holds none of them is unchanged, bit for bit.
TEST(ArtifactScores, HotPixelChangesOnlyTheScoresOfTheGaussiansCoveringIt)
{
  const GaussianCloud cloud = MirrorScene();
  const Camera camera = MakeCamera(0, false, 96, 64);
  const auto proj = vis4gs::ProjectGaussians<float>(cloud, camera, {});
  const auto omega = NaiveFootprints(cloud, camera);
  const double maxOmega = *std::max_element(omega.begin(), omega.end());
  ASSERT_GT(omega[2], 30u);
  ASSERT_LT(omega[2], maxOmega); // C's blur weight omega is below 1, A's is 1
  const int around[5][2] = { { 0, 0 }, { -1, 0 }, { 1, 0 }, { 0, -1 }, { 0, 1 } };
  // The outside pixel (5, 5) and its neighbours are in no footprint.
  for (const auto& d : around)
  {
    for (std::size_t g = 0; g < 3; ++g)
    {
      ASSERT_FALSE(InFootprint(proj, g, 5 + d[0], 5 + d[1]));
    }
  }
  const float hot = 0.25f;
  for (double lambda : { 0.0, 0.2 })
  {
    const auto base = ScoresWith(cloud, camera, RampImage(cloud, camera, false), lambda);
    for (std::size_t g = 0; g < 3; ++g)
    {
      EXPECT_GT(base.BlurScore[g], 0) << g; // the ramp gives every footprint a loss
    }
    const auto outside =
      ScoresWith(cloud, camera, RampImage(cloud, camera, false, 5, 5, hot), lambda);
    EXPECT_EQ(outside.BlurScore, base.BlurScore) << lambda;
    EXPECT_EQ(outside.NeedleScore, base.NeedleScore) << lambda;
    // At p: (1 - lambda) d + lambda 4 d; at its four neighbours: lambda d each.
    const double dLoss = (1 - lambda) * hot + lambda * 4 * hot + 4 * lambda * hot;
    for (std::size_t target : { 0u, 2u })
    {
      const int px = static_cast<int>(std::lround(proj.Gaussians[target].U));
      const int py = static_cast<int>(std::lround(proj.Gaussians[target].V));
      for (const auto& d : around)
      {
        for (std::size_t g = 0; g < 3; ++g)
        {
          ASSERT_EQ(InFootprint(proj, g, px + d[0], py + d[1]), g == target);
        }
      }
      const auto inside =
        ScoresWith(cloud, camera, RampImage(cloud, camera, false, px, py, hot), lambda);
      const double w = omega[target] / maxOmega;
      const double blurChange = inside.BlurScore[target] - base.BlurScore[target];
      const double needleChange = inside.NeedleScore[target] - base.NeedleScore[target];
      std::printf("lambda %.1f, Gaussian %zu (omega %.4f): blur +%.9g (predicted %.9g), "
                  "needle +%.9g (predicted %.9g)\n",
        lambda,
        target,
        w,
        blurChange,
        w * dLoss,
        needleChange,
        ShapeByHand(cloud, target) * dLoss);
      EXPECT_NEAR(blurChange, w * dLoss, 1e-5 * dLoss) << lambda;
      EXPECT_NEAR(needleChange, ShapeByHand(cloud, target) * dLoss, 1e-5 * dLoss) << lambda;
      for (std::size_t g = 0; g < 3; ++g)
      {
        if (g != target)
        {
          EXPECT_EQ(inside.BlurScore[g], base.BlurScore[g]) << g << " " << lambda;
          EXPECT_EQ(inside.NeedleScore[g], base.NeedleScore[g]) << g << " " << lambda;
        }
      }
    }
  }
}

// A flipped image: the scene is mirror-symmetric (B is A's mirror, C its own) and so is the
// render, so the loss map of the mirrored image is the mirrored loss map (L1 and the
// four-neighbour Laplacian with replicated edges commute with the mirror). Predicted: A and B
// swap their blur and needle scores, C keeps its own; the ramp makes A's and B's differ.
TEST(ArtifactScores, FlippedImageSwapsTheScoresOfMirroredGaussians)
{
  const GaussianCloud cloud = MirrorScene();
  const Camera camera = MakeCamera(0, false, 96, 64);
  const auto omega = NaiveFootprints(cloud, camera);
  ASSERT_EQ(omega[0], omega[1]);
  for (double lambda : { 0.0, 0.2 })
  {
    const auto s = ScoresWith(cloud, camera, RampImage(cloud, camera, false), lambda);
    const auto f = ScoresWith(cloud, camera, RampImage(cloud, camera, true), lambda);
    std::printf("lambda %.1f: blur A %.9g B %.9g C %.9g; flipped: A %.9g B %.9g C %.9g\n",
      lambda,
      s.BlurScore[0],
      s.BlurScore[1],
      s.BlurScore[2],
      f.BlurScore[0],
      f.BlurScore[1],
      f.BlurScore[2]);
    EXPECT_GT(std::abs(s.BlurScore[0] - s.BlurScore[1]), 0.1 * s.BlurScore[0]) << lambda;
    EXPECT_NEAR(f.BlurScore[0], s.BlurScore[1], 1e-5 * s.BlurScore[1]) << lambda;
    EXPECT_NEAR(f.BlurScore[1], s.BlurScore[0], 1e-5 * s.BlurScore[0]) << lambda;
    EXPECT_NEAR(f.BlurScore[2], s.BlurScore[2], 1e-5 * s.BlurScore[2]) << lambda;
    EXPECT_NEAR(f.NeedleScore[0], s.NeedleScore[1], 1e-5 * s.NeedleScore[1]) << lambda;
    EXPECT_NEAR(f.NeedleScore[1], s.NeedleScore[0], 1e-5 * s.NeedleScore[0]) << lambda;
    EXPECT_NEAR(f.NeedleScore[2], s.NeedleScore[2], 1e-5 * s.NeedleScore[2]) << lambda;
    EXPECT_EQ(f.ViewCoverage, s.ViewCoverage);
  }
}

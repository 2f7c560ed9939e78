// SPDX-License-Identifier: BSD-3-Clause
// Synthetic scenes: cameras look where they should, images show the objects, everything is
// reproducible from the seed, and bad descriptions give clear errors.
#include "SyntheticScene.h"

#include "GaussianMath.h"
#include "Rasterizer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace vis4gs;

namespace
{
const char* Tiny = R"({
  "name": "tiny", "seed": 3, "width": 48, "height": 40, "background": [0.1, 0.1, 0.1],
  "objects": [
    {"type": "sphere", "center": [0, 0, 0], "radius": 0.5, "gaussians": 800,
     "texture": {"pattern": "checker", "colors": [[1, 0, 0], [0, 0, 1]], "frequency": [8, 4]}},
    {"type": "torus", "center": [0, 0, 0], "major_radius": 0.9, "minor_radius": 0.1, "gaussians": 600},
    {"type": "box", "center": [0, 0, -0.8], "size": [2, 2, 0.1], "gaussians": 600},
    {"type": "cylinder", "center": [1, 1, 0], "radius": 0.02, "height": 1.0, "gaussians": 100},
    {"type": "plane", "center": [0, 0, -1], "normal": [0, 0, 1], "size": [4, 4], "gaussians": 300},
    {"type": "shell", "radius": 8, "gaussians": 500, "init_weight": 0}
  ],
  "cameras": [
    {"path": "orbit", "count": 6, "radius": 3, "elevation_deg": 25, "target": [0, 0, 0]},
    {"path": "arc", "count": 3, "radius": 3, "azimuth_deg": 45, "split": "test"}
  ],
  "initial_points": {"count": 300, "position_noise": 0.01, "outlier_fraction": 0.1,
                     "outlier_box": [[-1, -1, -1], [1, 1, 1]]}
})";
}

TEST(SyntheticScene, BuildsCamerasImagesAndPoints)
{
  const SyntheticScene s = MakeSyntheticScene(Tiny, "tiny.json");
  EXPECT_EQ(s.Name, "tiny");
  EXPECT_EQ(s.Truth.Count, 2900u);
  ASSERT_EQ(s.Cameras.size(), 9u);
  ASSERT_EQ(s.Images.size(), 9u);
  EXPECT_EQ(s.Cameras[0].Split, CameraSplit::Train);
  EXPECT_EQ(s.Cameras[8].Split, CameraSplit::Test);
  EXPECT_EQ(s.PointPositions.size(), 900u);
  EXPECT_EQ(s.PointColors.size(), 900u);
  for (const Camera& c : s.Cameras)
  {
    EXPECT_EQ(c.Width, 48);
    EXPECT_EQ(c.Height, 40);
    // The target (origin) projects to the image centre, in front of the camera.
    const auto& M = c.WorldToCamera;
    const double t[3] = { M[3], M[7], M[11] };
    ASSERT_GT(t[2], 0.0);
    EXPECT_NEAR(c.Fx * t[0] / t[2], 0.0, 1e-9);
    EXPECT_NEAR(c.Fy * t[1] / t[2], 0.0, 1e-9);
    // World up (+z) points to image up (-y).
    EXPECT_LT(M[6], 0.0);
    const auto ctr = c.Center();
    EXPECT_NEAR(std::sqrt(ctr[0] * ctr[0] + ctr[1] * ctr[1] + ctr[2] * ctr[2]), 3.0, 1e-9);
  }
  // The centre pixel shows the red/blue sphere; a corner shows the background or the shell.
  const auto& img = s.Images[0];
  const std::size_t centre = 3 * (20 * 48 + 24);
  EXPECT_GT(img[centre] + img[centre + 2], 0.8);
  EXPECT_LT(img[centre + 1], 0.2);
  // Outliers lie in their box; surface points near the surfaces.
  for (std::size_t i = 0; i < 300; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_LT(std::abs(s.PointPositions[3 * i + k]), 2.1f);
      EXPECT_GE(s.PointColors[3 * i + k], 0.0f);
      EXPECT_LE(s.PointColors[3 * i + k], 1.0f);
    }
  }
}

TEST(SyntheticScene, GroundTruthGaussiansAreFlatAndOnTheSurface)
{
  const SyntheticScene s = MakeSyntheticScene(Tiny, "tiny.json");
  for (std::size_t i = 0; i < 800; ++i)
  {
    const float* p = &s.Truth.Positions[3 * i];
    EXPECT_NEAR(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), 0.5, 1e-5);
    // Third axis (thin) along the sphere's normal.
    const float* q = &s.Truth.Rotations[4 * i];
    const auto R = QuaternionToMatrix<double>(
      NormalizeQuaternion<double>(std::array<double, 4>{ q[0], q[1], q[2], q[3] }.data()));
    const double n[3] = { R[2], R[5], R[8] };
    EXPECT_NEAR(std::abs(n[0] * p[0] + n[1] * p[1] + n[2] * p[2]) / 0.5, 1.0, 1e-5);
    EXPECT_LT(s.Truth.LogScales[3 * i + 2], s.Truth.LogScales[3 * i]);
  }
}

TEST(SyntheticScene, Reproducible)
{
  const SyntheticScene a = MakeSyntheticScene(Tiny, "tiny.json");
  const SyntheticScene b = MakeSyntheticScene(Tiny, "tiny.json");
  EXPECT_EQ(a.Truth.Positions, b.Truth.Positions);
  EXPECT_EQ(a.Images, b.Images);
  EXPECT_EQ(a.PointPositions, b.PointPositions);
  SyntheticOptions o;
  o.Width = 24;
  o.Height = 20;
  const SyntheticScene c = MakeSyntheticScene(Tiny, "tiny.json", o);
  EXPECT_EQ(c.Cameras[0].Width, 24);
  EXPECT_NEAR(c.Cameras[0].TanHalfFovX(), a.Cameras[0].TanHalfFovX(), 1e-12);
}

TEST(SyntheticScene, BadDescriptionsNameTheProblem)
{
  auto message = [](const std::string& text)
  {
    try
    {
      MakeSyntheticScene(text, "bad.json");
    }
    catch (const std::runtime_error& e)
    {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("{").find("bad.json: not valid JSON"), std::string::npos);
  EXPECT_NE(message(R"({"objects": []})").find("'objects'"), std::string::npos);
  EXPECT_NE(
    message(R"({"objects": [{"type": "cone"}], "cameras": []})").find("unknown type 'cone'"),
    std::string::npos);
  EXPECT_NE(
    message(R"({"objects": [{"type": "sphere", "radius": -1}], "cameras": []})").find("objects[0]"),
    std::string::npos);
  EXPECT_NE(
    message(R"({"objects": [{"type": "sphere"}], "cameras": [{"path": "spiral"}]})").find("spiral"),
    std::string::npos);
  EXPECT_NE(message(R"({"objects": [{"type": "sphere"}], "cameras": []})").find("no cameras"),
    std::string::npos);
  EXPECT_NE(message(R"({"objects": [{"type": "sphere", "center": [1, 2]}], "cameras": []})")
              .find("'center'"),
    std::string::npos);
}

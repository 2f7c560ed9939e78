// SPDX-License-Identifier: BSD-3-Clause
#include "SplatCamera.h"

#include "Rasterizer.h"

#include <gtest/gtest.h>

#include <cmath>

namespace vis4gs
{
namespace
{
Camera TiltedCamera()
{
  // R = Rx(0.4) Ry(-0.7), t = (0.3, -0.2, 5).
  const double a = 0.4, b = -0.7;
  const double Rx[9] = { 1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a) };
  const double Ry[9] = { std::cos(b), 0, std::sin(b), 0, 1, 0, -std::sin(b), 0, std::cos(b) };
  Camera c;
  c.Name = "tilted";
  c.Width = 120;
  c.Height = 80;
  c.Fx = c.Fy = 100;
  c.Cx = 60;
  c.Cy = 40;
  const double t[3] = { 0.3, -0.2, 5.0 };
  for (int r = 0; r < 3; ++r)
  {
    for (int col = 0; col < 3; ++col)
    {
      double s = 0;
      for (int k = 0; k < 3; ++k)
      {
        s += Rx[3 * r + k] * Ry[3 * k + col];
      }
      c.WorldToCamera[4 * r + col] = s;
    }
    c.WorldToCamera[4 * r + 3] = t[r];
  }
  return c;
}
}

TEST(SplatCamera, LookAtRoundTrip)
{
  const Camera c = TiltedCamera();
  const auto l = CameraToLookAt(c, 2.5);
  EXPECT_NEAR(l.ViewAngle, 2 * std::atan(40.0 / 100.0) * 180 / 3.14159265358979323846, 1e-12);
  EXPECT_EQ(l.PixelAspect, 1.0);
  const auto center = c.Center();
  for (int k = 0; k < 3; ++k)
  {
    EXPECT_NEAR(l.Position[k], center[k], 1e-12);
  }
  const Camera back = LookAtToCamera(l, c.Width, c.Height);
  for (int k = 0; k < 16; ++k)
  {
    EXPECT_NEAR(back.WorldToCamera[k], c.WorldToCamera[k], 1e-12) << k;
  }
  EXPECT_NEAR(back.Fy, c.Fy, 1e-9);
  EXPECT_NEAR(back.Fx, c.Fx, 1e-9);
  // A point ahead projects to the same pixel through both.
  const std::array<double, 3> p{ 0.5, 0.3, -0.4 };
  const auto a = ProjectToPixel(c, p), b2 = ProjectToPixel(back, p);
  EXPECT_NEAR(a[0], b2[0], 1e-9);
  EXPECT_NEAR(a[1], b2[1], 1e-9);
}

TEST(SplatCamera, ProjectionMatchesTheRasteriser)
{
  const Camera c = TiltedCamera();
  GaussianCloud cloud;
  cloud.Resize(3, 0);
  cloud.Positions = { 0.5f, 0.3f, -0.4f, -0.2f, 0.1f, 0.2f, 0.0f, 0.0f, 0.0f };
  for (int i = 0; i < 3; ++i)
  {
    cloud.Rotations[4 * i] = 1;
    for (int k = 0; k < 3; ++k)
    {
      cloud.LogScales[3 * i + k] = -4;
    }
  }
  const auto proj = ProjectGaussians<double>(cloud, c);
  for (int i = 0; i < 3; ++i)
  {
    ASSERT_TRUE(proj.Gaussians[i].IsVisible());
    const auto uv = ProjectToPixel(
      c, { cloud.Positions[3 * i], cloud.Positions[3 * i + 1], cloud.Positions[3 * i + 2] });
    EXPECT_NEAR(uv[0], proj.Gaussians[i].U, 1e-6);
    EXPECT_NEAR(uv[1], proj.Gaussians[i].V, 1e-6);
  }
}

TEST(SplatCamera, GLConventions)
{
  // A GL view that looks down -z from (0, 0, 5): OpenCV W2C flips y and z.
  const std::array<double, 16> view{ 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, -5, 0, 0, 0, 1 };
  const auto w2c = GLViewToWorldToCamera(view);
  const std::array<double, 16> expected{ 1, 0, 0, 0, 0, -1, 0, 0, 0, 0, -1, 5, 0, 0, 0, 1 };
  EXPECT_EQ(w2c, expected);
  const auto P = GLProjectionMatrix(200, 100, 150, 120, 0.1, 10);
  EXPECT_DOUBLE_EQ(P[0], 1.5);
  EXPECT_DOUBLE_EQ(P[5], 2.4);
  EXPECT_DOUBLE_EQ(P[14], -1);
  // Near plane maps to -1, far plane to +1.
  auto ndcZ = [&P](double z) { return (P[10] * z + P[11]) / (P[14] * z); };
  EXPECT_NEAR(ndcZ(-0.1), -1, 1e-12);
  EXPECT_NEAR(ndcZ(-10), 1, 1e-12);
  // Non-square pixels are reported.
  Camera c = TiltedCamera();
  c.Fx = 150;
  EXPECT_NEAR(CameraToLookAt(c).PixelAspect, 1.5, 1e-15);
}

TEST(SplatCamera, Errors)
{
  Camera c = TiltedCamera();
  c.Fy = 0;
  EXPECT_THROW(CameraToLookAt(c), std::invalid_argument);
  c = TiltedCamera();
  c.WorldToCamera[3] = std::nan("");
  EXPECT_THROW(CameraToLookAt(c), std::invalid_argument);
  CameraLookAt l;
  EXPECT_THROW(LookAtToCamera(l, 0, 10), std::invalid_argument);
  l.FocalPoint = l.Position;
  EXPECT_THROW(LookAtToCamera(l, 10, 10), std::invalid_argument);
  l = CameraLookAt();
  l.ViewUp = { 0, 0, 1 }; // parallel to the view direction
  EXPECT_THROW(LookAtToCamera(l, 10, 10), std::invalid_argument);
  l = CameraLookAt();
  l.ViewAngle = 180;
  EXPECT_THROW(LookAtToCamera(l, 10, 10), std::invalid_argument);
}

} // namespace vis4gs

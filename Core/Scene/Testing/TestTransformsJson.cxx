// SPDX-License-Identifier: BSD-3-Clause
// transforms*.json (NeRF-synthetic / instant-ngp): poses and intrinsics against hand-derived
// projections, the fl_x and camera_angle_x paths, per-frame overrides, missing images, splits
// and bad input.
#include "ImageIO.h"
#include "SceneTestUtils.h"
#include "TransformsJson.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <sys/stat.h>

namespace vis4gs
{
namespace
{

using testing::TempDir;
using testing::WriteFile;

// Pixel of world point @p x through @p cam, by hand from the matrix and intrinsics.
std::array<double, 3> Project(const Camera& cam, const std::array<double, 3>& x)
{
  const auto& m = cam.WorldToCamera;
  double c[3];
  for (int r = 0; r < 3; ++r)
  {
    c[r] = m[r * 4] * x[0] + m[r * 4 + 1] * x[1] + m[r * 4 + 2] * x[2] + m[r * 4 + 3];
  }
  return { cam.Fx * c[0] / c[2] + cam.Cx, cam.Fy * c[1] / c[2] + cam.Cy, c[2] };
}

void WriteRgba(const std::string& path, int w, int h)
{
  std::vector<unsigned char> px(static_cast<std::size_t>(w) * h * 4, 128);
  WritePng8(path, w, h, 4, px.data());
}

// Frame "a": OpenGL camera at (0,0,4) with identity rotation (looks down -z at the origin).
// Frame "b": at (4,0,0), rotated 90 degrees about y (looks down -x at the origin).
const char* Frames = R"("frames": [
  {"file_path": "./train/a", "transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,4],[0,0,0,1]]},
  {"file_path": "./train/b.png", "transform_matrix": [[0,0,1,4],[0,1,0,0],[-1,0,0,0],[0,0,0,1]]}
])";

TEST(TransformsJson, HandDerivedProjectionFromCameraAngle)
{
  TempDir dir;
  ::mkdir((dir / "train").c_str(), 0755);
  WriteRgba(dir / "train/a.png", 8, 6);
  WriteRgba(dir / "train/b.png", 8, 6);
  // fx = 0.5 * 8 / tan(atan(0.4)) = 10.
  const double ax = 2 * std::atan(0.4);
  WriteFile(
    dir / "transforms.json", "{\"camera_angle_x\": " + std::to_string(ax) + ", " + Frames + "}");
  const auto res = LoadTransformsDataset(dir.Path);
  ASSERT_EQ(res.Cameras.size(), 2u);
  EXPECT_TRUE(res.Warnings.empty());
  const Camera& a = res.Cameras[0];
  EXPECT_EQ(a.Name, "a");
  EXPECT_EQ(a.Width, 8);
  EXPECT_EQ(a.Height, 6);
  EXPECT_NEAR(a.Fx, 10, 1e-5);
  EXPECT_NEAR(a.Fy, 10, 1e-5);
  EXPECT_DOUBLE_EQ(a.Cx, 4);
  EXPECT_DOUBLE_EQ(a.Cy, 3);
  EXPECT_EQ(a.Split, CameraSplit::Train);
  EXPECT_EQ(a.ImagePath, dir / "./train/a.png");
  // OpenCV camera coords of (0.5, 0.25, 0): (0.5, -0.25, 4).
  auto p = Project(a, { 0.5, 0.25, 0 });
  EXPECT_NEAR(p[0], 10 * 0.5 / 4 + 4, 1e-5);
  EXPECT_NEAR(p[1], 10 * -0.25 / 4 + 3, 1e-5);
  EXPECT_NEAR(p[2], 4, 1e-12);
  const auto ca = a.Center();
  EXPECT_NEAR(ca[2], 4, 1e-12);
  // Camera b's right is world -z, up is +y: (0, 0.25, 0.5) -> (-0.5, -0.25, 4).
  p = Project(res.Cameras[1], { 0, 0.25, 0.5 });
  EXPECT_NEAR(p[0], 10 * -0.5 / 4 + 4, 1e-5);
  EXPECT_NEAR(p[1], 10 * -0.25 / 4 + 3, 1e-5);
  EXPECT_NEAR(p[2], 4, 1e-12);
}

TEST(TransformsJson, FocalAndAnglePathsAgreeAndFramesOverride)
{
  TempDir dir;
  const double ax = 2 * std::atan(0.4), ay = 2 * std::atan(0.25);
  WriteFile(dir / "angle.json",
    "{\"w\": 8, \"h\": 6, \"camera_angle_x\": " + std::to_string(ax) +
      ", \"camera_angle_y\": " + std::to_string(ay) + ", " + Frames + "}");
  WriteFile(dir / "focal.json",
    std::string("{\"w\": 8, \"h\": 6, \"fl_x\": 10, \"fl_y\": 12, \"cx\": 4, \"cy\": 3, ") +
      R"("frames": [{"file_path": "a", "transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,4],[0,0,0,1]]},
      {"file_path": "b", "fl_x": 20, "cx": 5, "w": 16, "h": 12,
       "transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,4],[0,0,0,1]]}]})");
  TransformsOptions opt;
  opt.RequireImages = false;
  const auto angle = ReadTransformsJson(dir / "angle.json", opt);
  const auto focal = ReadTransformsJson(dir / "focal.json", opt);
  ASSERT_EQ(angle.Cameras.size(), 2u);
  ASSERT_EQ(focal.Cameras.size(), 2u);
  // fy = 0.5 * 6 / 0.25 = 12.
  EXPECT_NEAR(angle.Cameras[0].Fx, focal.Cameras[0].Fx, 1e-5);
  EXPECT_NEAR(angle.Cameras[0].Fy, focal.Cameras[0].Fy, 1e-5);
  for (int k = 0; k < 16; ++k)
  {
    EXPECT_DOUBLE_EQ(angle.Cameras[0].WorldToCamera[k], focal.Cameras[0].WorldToCamera[k]);
  }
  const Camera& b = focal.Cameras[1];
  EXPECT_EQ(b.Width, 16);
  EXPECT_EQ(b.Height, 12);
  EXPECT_DOUBLE_EQ(b.Fx, 20);
  EXPECT_DOUBLE_EQ(b.Fy, 12); // top-level fl_y still applies
  EXPECT_DOUBLE_EQ(b.Cx, 5);
  EXPECT_DOUBLE_EQ(b.Cy, 3);
}

TEST(TransformsJson, MissingImagesOneWarningAndSplits)
{
  TempDir dir;
  ::mkdir((dir / "train").c_str(), 0755);
  WriteRgba(dir / "train/a.png", 8, 6);
  const std::string body = std::string("{\"camera_angle_x\": 0.7, \"k1\": 0.1, ") + Frames + "}";
  WriteFile(dir / "transforms_train.json", body);
  WriteFile(dir / "transforms_test.json", body);
  WriteFile(dir / "transforms_val.json", "not even json");
  const auto res = LoadTransformsDataset(dir.Path);
  ASSERT_EQ(res.Cameras.size(), 2u); // b.png is missing in both files
  EXPECT_EQ(res.Cameras[0].Split, CameraSplit::Train);
  EXPECT_EQ(res.Cameras[1].Split, CameraSplit::Test);
  EXPECT_EQ(res.Cameras[0].Name, "a");
  EXPECT_EQ(res.Cameras[1].Name, "train_a"); // the same stem in both splits
  // Per file: one missing-images warning naming the count, one distortion warning.
  ASSERT_EQ(res.Warnings.size(), 4u);
  EXPECT_NE(res.Warnings[0].find("1 of 2 frames skipped"), std::string::npos);
  EXPECT_NE(res.Warnings[0].find("transforms_train.json"), std::string::npos);
  EXPECT_NE(res.Warnings[1].find("ignored"), std::string::npos);
  EXPECT_TRUE(IsTransformsJson(dir / "transforms_train.json"));
  EXPECT_FALSE(IsTransformsJson(dir / "transforms_val.json"));
  EXPECT_TRUE(IsTransformsFolder(dir.Path));
}

TEST(TransformsJson, BadInputNamesTheFile)
{
  TempDir dir;
  const std::vector<std::pair<std::string, std::string>> cases = {
    { "[1, 2]", "'frames'" },
    { "{\"frames\": 3}", "'frames'" },
    { "{\"frames\": [{\"transform_matrix\": []}]}", "file_path" },
    { R"({"w": 8, "h": 6, "fl_x": 1, "frames": [{"file_path": "a", "transform_matrix": [[1,0]]}]})",
      "transform_matrix" },
    { R"({"w": 8, "h": 6, "fl_x": 1, "frames": [{"file_path": "a",
        "transform_matrix": [[2,0,0,0],[0,1,0,0],[0,0,1,0]]}]})",
      "orthonormal" },
    { R"({"w": 8, "h": 6, "frames": [{"file_path": "a",
        "transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,0]]}]})",
      "camera_angle_x" },
    { R"({"w": 8, "h": 6, "fl_x": -1, "frames": [{"file_path": "a",
        "transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,0]]}]})",
      "positive" },
    { R"({"w": 0.5, "h": 6, "fl_x": 1, "frames": [{"file_path": "a",
        "transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,0]]}]})",
      "'w'" },
    { "{\"frames\": [", "not valid JSON" },
  };
  TransformsOptions opt;
  opt.RequireImages = false;
  for (const auto& c : cases)
  {
    WriteFile(dir / "bad.json", c.first);
    EXPECT_THROW_WITH(ReadTransformsJson(dir / "bad.json", opt), "bad.json", c.second);
  }
  EXPECT_THROW_WITH(LoadTransformsDataset(dir.Path), "transforms");
  EXPECT_THROW_WITH(ReadTransformsJson(dir / "absent.json"), "absent.json");
  // A frame naming a garbage image without w/h: the image reader's error names the file.
  WriteFile(dir / "g.png", "garbage");
  WriteFile(dir / "g.json",
    R"({"fl_x": 1, "frames": [{"file_path": "g", "transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,0]]}]})");
  EXPECT_THROW_WITH(ReadTransformsJson(dir / "g.json"), "g.png");
}

} // namespace
} // namespace vis4gs

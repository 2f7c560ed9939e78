// SPDX-License-Identifier: BSD-3-Clause
// COLMAP (binary and text), cameras.json and the dataset loader, on the real statue dataset
// and on hand-derived cases, including every bad-input case of issue 3.
#include "CameraJson.h"
#include "Colmap.h"
#include "ColmapDataset.h"
#include "GaussianMath.h"
#include "SceneTestUtils.h"
#include "Vis4GSTestData.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include <sys/stat.h>

namespace vis4gs
{
namespace
{

using testing::FileBytes;
using testing::TempDir;
using testing::WriteFile;

const std::string Statue = testing::SharedDataPath("colmap_statue_bartoszek");
const std::string StatueSparse = Statue + "/sparse/0";
const std::string StatueRadial = Statue + "/sparse_original_simple_radial/0";

void MakeDir(const std::string& p)
{
  ::mkdir(p.c_str(), 0755);
}

void ExpectModelsEqual(const ColmapModel& a, const ColmapModel& b)
{
  ASSERT_EQ(a.Cameras.size(), b.Cameras.size());
  for (std::size_t i = 0; i < a.Cameras.size(); ++i)
  {
    EXPECT_EQ(a.Cameras[i].Id, b.Cameras[i].Id);
    EXPECT_EQ(a.Cameras[i].ModelId, b.Cameras[i].ModelId);
    EXPECT_EQ(a.Cameras[i].Width, b.Cameras[i].Width);
    EXPECT_EQ(a.Cameras[i].Height, b.Cameras[i].Height);
    EXPECT_EQ(a.Cameras[i].Params, b.Cameras[i].Params);
  }
  ASSERT_EQ(a.Images.size(), b.Images.size());
  for (std::size_t i = 0; i < a.Images.size(); ++i)
  {
    const auto& x = a.Images[i];
    const auto& y = b.Images[i];
    EXPECT_EQ(x.Id, y.Id);
    EXPECT_EQ(x.Q, y.Q);
    EXPECT_EQ(x.T, y.T);
    EXPECT_EQ(x.CameraId, y.CameraId);
    EXPECT_EQ(x.Name, y.Name);
    ASSERT_EQ(x.Points2D.size(), y.Points2D.size());
    for (std::size_t k = 0; k < x.Points2D.size(); ++k)
    {
      EXPECT_EQ(x.Points2D[k].X, y.Points2D[k].X);
      EXPECT_EQ(x.Points2D[k].Y, y.Points2D[k].Y);
      EXPECT_EQ(x.Points2D[k].Point3DId, y.Points2D[k].Point3DId);
    }
  }
  ASSERT_EQ(a.Points3D.size(), b.Points3D.size());
  for (std::size_t i = 0; i < a.Points3D.size(); ++i)
  {
    const auto& x = a.Points3D[i];
    const auto& y = b.Points3D[i];
    EXPECT_EQ(x.Id, y.Id);
    EXPECT_EQ(x.Xyz, y.Xyz);
    EXPECT_EQ(x.Rgb, y.Rgb);
    EXPECT_EQ(x.Error, y.Error);
    ASSERT_EQ(x.Track.size(), y.Track.size());
    for (std::size_t k = 0; k < x.Track.size(); ++k)
    {
      EXPECT_EQ(x.Track[k].ImageId, y.Track[k].ImageId);
      EXPECT_EQ(x.Track[k].Point2DIdx, y.Track[k].Point2DIdx);
    }
  }
}

//------------------------------------------------------------------------------
TEST(Colmap, ReadsStatueBinaryModel)
{
  VIS4GS_REQUIRE_SHARED_DATA();
  const ColmapModel m = ReadColmapModel(StatueSparse);
  ASSERT_EQ(m.Cameras.size(), 23u);
  ASSERT_EQ(m.Images.size(), 23u);
  EXPECT_EQ(m.Points3D.size(), 1443u);
  std::size_t observations = 0;
  for (const auto& im : m.Images)
  {
    observations += im.Points2D.size();
  }
  EXPECT_EQ(observations, 16646u);
  for (const auto& c : m.Cameras)
  {
    EXPECT_EQ(FindColmapModel(c.ModelId)->Name, std::string("PINHOLE"));
    EXPECT_EQ(c.Width, 1000u);
    EXPECT_GE(c.Height, 650u); // 656..662 in this dataset
    EXPECT_LE(c.Height, 670u);
    EXPECT_GT(c.Params[0], 1900);
    EXPECT_LT(c.Params[0], 2200);
    EXPECT_FALSE(IsDistorted(c));
  }
  // Independent decode of the first camera record at its fixed offsets.
  const auto bytes = FileBytes(StatueSparse + "/cameras.bin");
  std::int32_t id, model;
  std::uint64_t w, h;
  double fx;
  std::memcpy(&id, bytes.data() + 8, 4);
  std::memcpy(&model, bytes.data() + 12, 4);
  std::memcpy(&w, bytes.data() + 16, 8);
  std::memcpy(&h, bytes.data() + 24, 8);
  std::memcpy(&fx, bytes.data() + 32, 8);
  EXPECT_EQ(m.Cameras[0].Id, id);
  EXPECT_EQ(model, 1);
  EXPECT_EQ(m.Cameras[0].Height, h);
  EXPECT_EQ(m.Cameras[0].Params[0], fx);
  EXPECT_EQ(bytes.size(), 8u + 23u * (24 + 32));
  // Every point's track refers to registered images.
  for (const auto& p : m.Points3D)
  {
    EXPECT_GE(p.Track.size(), 2u);
  }
}

TEST(Colmap, ReadsSimpleRadialOriginal)
{
  VIS4GS_REQUIRE_SHARED_DATA();
  const ColmapModel m = ReadColmapModel(StatueRadial);
  ASSERT_EQ(m.Cameras.size(), 23u);
  const ColmapModel u = ReadColmapModel(StatueSparse);
  for (const auto& c : m.Cameras)
  {
    EXPECT_EQ(FindColmapModel(c.ModelId)->Name, std::string("SIMPLE_RADIAL"));
    EXPECT_EQ(c.Width, 3031u);
    EXPECT_EQ(c.Height, 2006u);
    ASSERT_EQ(c.Params.size(), 4u);
  }
  const Camera cam = ToCamera(m.Cameras[0], m.Images[0]);
  EXPECT_EQ(cam.Model, "SIMPLE_RADIAL");
  EXPECT_EQ(cam.Fx, m.Cameras[0].Params[0]);
  EXPECT_EQ(cam.Fy, m.Cameras[0].Params[0]);
  EXPECT_EQ(cam.Cx, m.Cameras[0].Params[1]);
  ASSERT_EQ(cam.Distortion.size(), 1u);
  EXPECT_EQ(cam.Distortion[0], m.Cameras[0].Params[3]);
  EXPECT_EQ(IsDistorted(m.Cameras[0]), m.Cameras[0].Params[3] != 0.0);
  // Same images and points as the undistorted model.
  EXPECT_EQ(m.Points3D.size(), u.Points3D.size());
}

TEST(Colmap, BinaryWriteReproducesTheFilesAndTextReadsBackEqual)
{
  VIS4GS_REQUIRE_SHARED_DATA();
  TempDir dir;
  const ColmapModel m = ReadColmapModel(StatueSparse);
  MakeDir(dir / "bin");
  WriteColmapModel(dir / "bin", m, ColmapFormat::Binary);
  for (const char* f : { "cameras.bin", "images.bin", "points3D.bin" })
  {
    EXPECT_EQ(FileBytes(dir / (std::string("bin/") + f)), FileBytes(StatueSparse + "/" + f)) << f;
  }
  MakeDir(dir / "txt");
  WriteColmapModel(dir / "txt", m, ColmapFormat::Text);
  const ColmapModel t = ReadColmapModel(dir / "txt"); // no .bin there: reads the text files
  ExpectModelsEqual(m, t);
  // Cameras from text and binary are identical.
  for (std::size_t i = 0; i < m.Images.size(); ++i)
  {
    const auto ci = ToCamera(m.Cameras[i], m.Images[i]);
    EXPECT_EQ(ci.WorldToCamera, ToCamera(t.Cameras[i], t.Images[i]).WorldToCamera);
  }
}

TEST(Colmap, HandWrittenTextWithEveryModel)
{
  // One camera per standard model, parameters 100+k; hand-derived pinhole mapping.
  std::string cams = "# comment\n\n";
  for (int id = 0; id <= 10; ++id)
  {
    const ColmapCameraModel* model = FindColmapModel(id);
    ASSERT_NE(model, nullptr);
    cams += std::to_string(id + 1) + " " + model->Name + " 640 480";
    for (int k = 0; k < model->NumParams; ++k)
    {
      cams += " " + std::to_string(100 + k);
    }
    cams += "\r\n";
  }
  const auto parsed = ParseColmapCameras(cams.data(), cams.size(), ColmapFormat::Text, "c.txt");
  ASSERT_EQ(parsed.size(), 11u);
  const int expectedParams[11] = { 3, 4, 4, 5, 8, 8, 12, 5, 4, 5, 12 };
  for (int id = 0; id <= 10; ++id)
  {
    const ColmapCamera& c = parsed[id];
    EXPECT_EQ(c.ModelId, id);
    ASSERT_EQ(static_cast<int>(c.Params.size()), expectedParams[id]);
    ColmapImage im;
    im.Name = "dir/frame.001.png";
    im.Q = { 0, 0, 0, 2 }; // unnormalised: 180 deg about z
    im.T = { 1, 2, 3 };
    const Camera cam = ToCamera(c, im);
    const bool single = id == 0 || id == 2 || id == 3 || id == 8 || id == 9;
    EXPECT_EQ(cam.Fx, 100);
    EXPECT_EQ(cam.Fy, single ? 100 : 101);
    EXPECT_EQ(cam.Cx, single ? 101 : 102);
    EXPECT_EQ(cam.Cy, single ? 102 : 103);
    EXPECT_EQ(
      cam.Distortion.size(), static_cast<std::size_t>(expectedParams[id] - (single ? 3 : 4)));
    EXPECT_EQ(cam.Name, "frame"); // up to the first '.', as the trainer's image_name
    EXPECT_EQ(cam.ImagePath, "dir/frame.001.png");
    // R = diag(-1, -1, 1), t = (1, 2, 3); centre = -R^T t = (1, 2, -3).
    EXPECT_NEAR(cam.WorldToCamera[0], -1, 1e-15);
    EXPECT_NEAR(cam.WorldToCamera[5], -1, 1e-15);
    EXPECT_NEAR(cam.WorldToCamera[10], 1, 1e-15);
    EXPECT_EQ(cam.WorldToCamera[3], 1);
    const auto ctr = cam.Center();
    EXPECT_NEAR(ctr[0], 1, 1e-15);
    EXPECT_NEAR(ctr[1], 2, 1e-15);
    EXPECT_NEAR(ctr[2], -3, 1e-15);
    // Pinhole/zero-distortion models are not distorted; fisheye ones always are.
    EXPECT_EQ(IsDistorted(c), id >= 2);
  }
  ColmapCamera zero = parsed[4]; // OPENCV with zero distortion is a pinhole
  std::fill(zero.Params.begin() + 4, zero.Params.end(), 0.0);
  EXPECT_FALSE(IsDistorted(zero));
  ColmapCamera fisheye = parsed[5];
  std::fill(fisheye.Params.begin() + 4, fisheye.Params.end(), 0.0);
  EXPECT_TRUE(IsDistorted(fisheye));

  // images.txt with an empty 2D-points line and one with points; points3D.txt.
  const std::string ims = "# header\n1 1 0 0 0 0 0 0 1 a.png\n\n"
                          "2 0.5 0.5 0.5 0.5 1 2 3 2 b.png\n10.5 20.5 7 1 2 -1\n";
  const auto images = ParseColmapImages(ims.data(), ims.size(), ColmapFormat::Text, "i.txt");
  ASSERT_EQ(images.size(), 2u);
  EXPECT_EQ(images[0].Points2D.size(), 0u);
  ASSERT_EQ(images[1].Points2D.size(), 2u);
  EXPECT_EQ(images[1].Points2D[0].Point3DId, 7);
  EXPECT_EQ(images[1].Points2D[1].Point3DId, -1);
  EXPECT_EQ(images[1].Name, "b.png");
  const std::string pts = "5 1 2 3 255 0 10 0.25 1 0 2 1\n";
  const auto points = ParseColmapPoints3D(pts.data(), pts.size(), ColmapFormat::Text, "p.txt");
  ASSERT_EQ(points.size(), 1u);
  EXPECT_EQ(points[0].Rgb[0], 255);
  EXPECT_EQ(points[0].Track.size(), 2u);
  EXPECT_EQ(points[0].Error, 0.25);
}

TEST(ColmapErrors, TruncatedAndOversizedBinaryFiles)
{
  VIS4GS_REQUIRE_SHARED_DATA();
  for (const char* f : { "cameras.bin", "images.bin", "points3D.bin" })
  {
    const auto bytes = FileBytes(StatueSparse + "/" + f);
    // 300 cut points spread over the file, plus the first 100 bytes one by one.
    for (std::size_t k = 0; k < 400; ++k)
    {
      const std::size_t len = k < 100 ? k : (bytes.size() - 1) * (k - 100) / 300;
      if (len >= bytes.size())
      {
        continue;
      }
      const std::string name = std::string("cut_") + f;
      bool threw = false;
      try
      {
        if (f[0] == 'c')
        {
          ParseColmapCameras(bytes.data(), len, ColmapFormat::Binary, name);
        }
        else if (f[0] == 'i')
        {
          ParseColmapImages(bytes.data(), len, ColmapFormat::Binary, name);
        }
        else
        {
          ParseColmapPoints3D(bytes.data(), len, ColmapFormat::Binary, name);
        }
      }
      catch (const std::runtime_error& e)
      {
        threw = true;
        EXPECT_NE(std::string(e.what()).find(name), std::string::npos);
      }
      EXPECT_TRUE(threw) << f << " cut at " << len;
    }
  }
  // A count far larger than the file fails before allocating.
  auto bytes = FileBytes(StatueSparse + "/images.bin");
  const std::uint64_t huge = 1ull << 60;
  std::memcpy(bytes.data(), &huge, 8);
  EXPECT_THROW_WITH(ParseColmapImages(bytes.data(), bytes.size(), ColmapFormat::Binary, "i.bin"),
    "i.bin",
    "declares 1152921504606846976 images");
  // Unknown model id.
  auto cams = FileBytes(StatueSparse + "/cameras.bin");
  const std::int32_t badModel = 11;
  std::memcpy(cams.data() + 12, &badModel, 4);
  EXPECT_THROW_WITH(ParseColmapCameras(cams.data(), cams.size(), ColmapFormat::Binary, "c.bin"),
    "c.bin",
    "unknown camera model id 11");
}

TEST(ColmapErrors, BadText)
{
  auto cams = [](const std::string& t)
  { return ParseColmapCameras(t.data(), t.size(), ColmapFormat::Text, "cameras.txt"); };
  EXPECT_THROW_WITH(cams("1 PINHOLE 640 480 1 2 3\n"), "cameras.txt", "line 1", "needs 4");
  EXPECT_THROW_WITH(cams("# c\n1 FANCY 640 480 1 2 3\n"), "line 2", "unknown camera model 'FANCY'");
  EXPECT_THROW_WITH(cams("1 PINHOLE 640 abc 1 2 3 4\n"), "'abc'", "height");
  EXPECT_THROW_WITH(cams("1 PINHOLE 640 0 1 2 3 4\n"), "not plausible");
  EXPECT_THROW_WITH(cams("1 PINHOLE 640 480 1 nan 3 4\n"), "not finite");
  auto images = [](const std::string& t)
  { return ParseColmapImages(t.data(), t.size(), ColmapFormat::Text, "images.txt"); };
  EXPECT_THROW_WITH(images("1 1 0 0 0 0 0 0 1\n\n"), "images.txt", "line 1", "NAME");
  EXPECT_THROW_WITH(images("1 1 0 0 0 0 0 0 1 a.png\n1 2\n"), "line 2", "triples");
  EXPECT_THROW_WITH(images("1 0 0 0 0 0 0 0 1 a.png\n\n"), "quaternion is zero");
  auto points = [](const std::string& t)
  { return ParseColmapPoints3D(t.data(), t.size(), ColmapFormat::Text, "points3D.txt"); };
  EXPECT_THROW_WITH(points("1 0 0 0 256 0 0 0\n"), "colour 256");
  EXPECT_THROW_WITH(points("1 0 0 0 1 2 3 0 4\n"), "expected");
  // An image that refers to a missing camera.
  TempDir dir;
  WriteFile(dir / "cameras.txt", "1 PINHOLE 640 480 500 500 320 240\n");
  WriteFile(dir / "images.txt", "1 1 0 0 0 0 0 0 2 a.png\n\n");
  EXPECT_THROW_WITH(ReadColmapModel(dir.Path), "images.txt", "'a.png'", "camera 2");
  EXPECT_THROW_WITH(ReadColmapModel(dir / "nothing"), "no COLMAP model");
}

//------------------------------------------------------------------------------
TEST(ColmapDataset, StatueSortedSplitAndScaled)
{
  VIS4GS_REQUIRE_SHARED_DATA();
  const Dataset ds = LoadColmapDataset(Statue);
  ASSERT_EQ(ds.Cameras.size(), 23u);
  EXPECT_FALSE(ds.Distorted);
  EXPECT_TRUE(ds.Warnings.empty());
  EXPECT_EQ(ds.PointPositions.size(), 3u * 1443);
  EXPECT_EQ(ds.PointColors.size(), 3u * 1443);
  EXPECT_EQ(ds.Cameras.front().Name, "DSC_5283");
  EXPECT_EQ(ds.Cameras.back().Name, "DSC_5305");
  for (std::size_t i = 1; i < ds.Cameras.size(); ++i)
  {
    EXPECT_LT(ds.Cameras[i - 1].Name, ds.Cameras[i].Name);
    EXPECT_EQ(ds.Cameras[i].Split, CameraSplit::Train); // no eval: all train
  }
  EXPECT_EQ(ds.Cameras[0].ImagePath, Statue + "/images/DSC_5283.jpg");
  EXPECT_EQ(ds.Cameras[0].Width, 1000); // <= 1600: not scaled by default

  DatasetOptions o;
  o.Eval = true;
  o.Resolution = 2;
  const Dataset half = LoadColmapDataset(Statue, o);
  int tests = 0;
  for (std::size_t i = 0; i < half.Cameras.size(); ++i)
  {
    const Camera& c = half.Cameras[i];
    EXPECT_EQ(c.Split == CameraSplit::Test, i % 8 == 0) << i;
    tests += c.Split == CameraSplit::Test;
    const Camera& full = ds.Cameras[i];
    EXPECT_EQ(c.Name, full.Name);
    EXPECT_EQ(c.Width, 500);
    // Python round, half to even: 657/2 = 328.5 -> 328, 659/2 = 329.5 -> 330.
    const int h = full.Height;
    const int q = h / 2;
    EXPECT_EQ(c.Height, h % 2 == 0 ? q : (q % 2 == 0 ? q : q + 1)) << h;
    // Field of view kept.
    EXPECT_NEAR(c.TanHalfFovX(), full.TanHalfFovX(), 1e-12);
    EXPECT_NEAR(c.TanHalfFovY(), full.TanHalfFovY(), 1e-12);
    EXPECT_EQ(c.WorldToCamera, full.WorldToCamera);
    EXPECT_EQ(half.OriginalSizes[i].first, 1000);
  }
  EXPECT_EQ(tests, 3); // indices 0, 8, 16
}

TEST(ColmapDataset, TrainingResolutionLikeTheTrainer)
{
  using P = std::pair<int, int>;
  EXPECT_EQ(TrainingResolution(1000, 657, -1), P(1000, 657));
  EXPECT_EQ(TrainingResolution(3031, 2006, -1), P(1600, 1058)); // int(2006 / (3031/1600))
  EXPECT_EQ(TrainingResolution(3031, 2006, 1), P(3031, 2006));
  EXPECT_EQ(TrainingResolution(3031, 2006, 4), P(758, 502));  // round(757.75), round(501.5)
  EXPECT_EQ(TrainingResolution(3031, 2006, 8), P(379, 251));  // round(378.875), round(250.75)
  EXPECT_EQ(TrainingResolution(1000, 657, 800), P(800, 525)); // target width, int(525.6)
  EXPECT_EQ(TrainingResolution(1000, 657, 3), P(3, 1));       // 3 is a target width, not /3
  EXPECT_THROW(TrainingResolution(1000, 657, 0), std::invalid_argument);
  EXPECT_THROW(TrainingResolution(1000, 657, -2), std::invalid_argument);
}

TEST(ColmapDataset, DistortedDatasetWarnsOnceAndImagesFolders)
{
  VIS4GS_REQUIRE_SHARED_DATA();
  TempDir dir;
  MakeDir(dir / "sparse");
  MakeDir(dir / "sparse/0");
  WriteColmapModel(dir / "sparse/0", ReadColmapModel(StatueRadial), ColmapFormat::Binary);
  DatasetOptions o;
  o.RequireImages = false;
  const Dataset ds = LoadColmapDataset(dir.Path, o);
  EXPECT_TRUE(ds.Distorted);
  ASSERT_EQ(ds.Warnings.size(), 2u); // distortion (once for 23 cameras) + down-scaling
  EXPECT_NE(
    ds.Warnings[0].find("23 cameras use a distorted model (SIMPLE_RADIAL)"), std::string::npos);
  EXPECT_NE(ds.Warnings[1].find("1600"), std::string::npos);
  EXPECT_EQ(ds.Cameras[0].Width, 1600);
  EXPECT_EQ(ds.Cameras[0].Distortion.size(), 1u);
  // A camera without its image is an error naming the camera and the file.
  MakeDir(dir / "images");
  EXPECT_THROW_WITH(
    LoadColmapDataset(dir.Path), "camera 'DSC_", "has no image file", dir / "images/DSC_");
  // images_4 is used for --resolution 4 when it exists.
  MakeDir(dir / "images_4");
  o.Resolution = 4;
  const Dataset q = LoadColmapDataset(dir.Path, o);
  EXPECT_EQ(q.ImageFolder, dir / "images_4");
  EXPECT_EQ(q.Cameras[0].Width, 758);
  EXPECT_THROW_WITH(LoadColmapDataset(dir / "missing"), "does not exist");
}

//------------------------------------------------------------------------------
TEST(CameraJson, HandDerivedCamera)
{
  // Camera-to-world rotation: 90 degrees about z (columns are the camera axes in world
  // coordinates), centre (1, 2, 3). World-to-camera R = C2W^T, t = -R C.
  const std::string json = R"([{"id": 0, "img_name": "DSC0001", "width": 800, "height": 600,
    "position": [1.0, 2.0, 3.0], "rotation": [[0, -1, 0], [1, 0, 0], [0, 0, 1]],
    "fy": 700.5, "fx": 710.25}])";
  const auto cams = ReadCamerasJsonFromMemory(json.data(), json.size(), "cameras.json");
  ASSERT_EQ(cams.size(), 1u);
  const Camera& c = cams[0];
  EXPECT_EQ(c.Name, "DSC0001");
  EXPECT_EQ(c.Width, 800);
  EXPECT_EQ(c.Fx, 710.25);
  EXPECT_EQ(c.Fy, 700.5);
  EXPECT_EQ(c.Cx, 400);
  EXPECT_EQ(c.Cy, 300);
  const std::array<double, 16> expected{ 0, 1, 0, -2, -1, 0, 0, 1, 0, 0, 1, -3, 0, 0, 0, 1 };
  EXPECT_EQ(c.WorldToCamera, expected);
  const auto ctr = c.Center();
  EXPECT_EQ(ctr[0], 1);
  EXPECT_EQ(ctr[1], 2);
  EXPECT_EQ(ctr[2], 3);
}

TEST(CameraJson, RoundTripOfTheStatueCameras)
{
  VIS4GS_REQUIRE_SHARED_DATA();
  TempDir dir;
  const Dataset ds = LoadColmapDataset(Statue);
  WriteCamerasJson(dir / "cameras.json", ds.Cameras);
  const auto back = ReadCamerasJson(dir / "cameras.json");
  ASSERT_EQ(back.size(), ds.Cameras.size());
  for (std::size_t i = 0; i < back.size(); ++i)
  {
    EXPECT_EQ(back[i].Name, ds.Cameras[i].Name);
    EXPECT_EQ(back[i].Width, ds.Cameras[i].Width);
    EXPECT_EQ(back[i].Fx, ds.Cameras[i].Fx);
    for (int k = 0; k < 16; ++k)
    {
      EXPECT_NEAR(back[i].WorldToCamera[k], ds.Cameras[i].WorldToCamera[k], 1e-12);
    }
  }
}

TEST(CameraJson, BadFiles)
{
  auto read = [](const std::string& t)
  { return ReadCamerasJsonFromMemory(t.data(), t.size(), "cameras.json"); };
  const std::string good = R"({"id": 0, "img_name": "a", "width": 8, "height": 6,
    "position": [0, 0, 0], "rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "fy": 7, "fx": 7})";
  EXPECT_EQ(read("[" + good + "]").size(), 1u);
  EXPECT_THROW_WITH(read("[" + good), "cameras.json", "not valid JSON");
  EXPECT_THROW_WITH(read(good), "expected a JSON list");
  EXPECT_THROW_WITH(read("[1]"), "camera 0 is not an object");
  std::string noFx = good;
  noFx.replace(noFx.find(", \"fx\": 7"), 9, "");
  EXPECT_THROW_WITH(read("[" + good + "," + noFx + "]"), "camera 1 ('a')", "missing 'fx'");
  std::string badRot = good;
  badRot.replace(badRot.find("[[1, 0, 0]"), 10, "[[2, 0, 0]");
  EXPECT_THROW_WITH(read("[" + badRot + "]"), "not a rotation matrix");
  std::string badW = good;
  badW.replace(badW.find("\"width\": 8"), 10, "\"width\": -8");
  EXPECT_THROW_WITH(read("[" + badW + "]"), "'width' must be a positive integer");
  std::string strFx = good;
  strFx.replace(strFx.find("\"fx\": 7"), 7, "\"fx\": \"7\"");
  EXPECT_THROW_WITH(read("[" + strFx + "]"), "'fx' is not a number");
  EXPECT_THROW_WITH(ReadCamerasJson("/nonexistent/cameras.json"), "/nonexistent/cameras.json");
}

} // namespace
} // namespace vis4gs

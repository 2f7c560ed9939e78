// SPDX-License-Identifier: BSD-3-Clause
#include "TrainingData.h"

#include "ColmapDataset.h"
#include "ImageIO.h"
#include "SceneFile.h"
#include "SyntheticScene.h"
#include "TransformsJson.h"

#include <cmath>
#include <iostream>
#include <random>
#include <stdexcept>

namespace vis4gs
{

namespace
{

// Points of the original trainer's synthetic-scene start (100,000 in [-1.3, 1.3]^3 with grey
// colours SH2RGB(U[0,1)/255) ~ 0.5); we take 10,000 (our CPU trainer's scale), seeded.
constexpr int RandomPointCount = 10000;
constexpr float RandomCubeHalfSide = 1.3f;

// The training images of data.Cameras, composited on the background, at the cameras' size.
void LoadImages(TrainingData& data, double bgValue)
{
  data.Background = { bgValue, bgValue, bgValue };
  const std::array<float, 3> bg = {
    static_cast<float>(bgValue), static_cast<float>(bgValue), static_cast<float>(bgValue)
  };
  for (const Camera& cam : data.Cameras)
  {
    Image img = LoadTrainingImage(cam, bg);
    if (img.Width != cam.Width || img.Height != cam.Height || img.Channels != 3)
    {
      throw std::runtime_error(cam.ImagePath + ": image of camera '" + cam.Name +
        "' could not be brought to " + std::to_string(cam.Width) + "x" +
        std::to_string(cam.Height) + " RGB");
    }
    data.Images.push_back(std::move(img.Pixels));
  }
}

TrainingData LoadTransformsTrainingData(const std::string& path,
  const TrainingDataOptions& options,
  double bgValue)
{
  TransformsCameras tc = LoadTransformsDataset(path, /*requireImages=*/true);
  for (const std::string& w : tc.Warnings)
  {
    std::cerr << "warning: " << w << "\n";
  }
  if (tc.Cameras.empty())
  {
    throw std::runtime_error(path + ": no frame with an image file to train on");
  }
  TrainingData data;
  data.Name = path;
  for (Camera& cam : tc.Cameras)
  {
    // Without --eval the original trainer trains on the test views too.
    if (!options.Eval)
    {
      cam.Split = CameraSplit::Train;
    }
    const auto size = TrainingResolution(cam.Width, cam.Height, options.Resolution);
    data.Cameras.push_back(cam.Resized(size.first, size.second));
  }
  LoadImages(data, bgValue);
  std::mt19937 rng(0);
  std::uniform_real_distribution<float> u(-RandomCubeHalfSide, RandomCubeHalfSide);
  std::uniform_real_distribution<float> shs(0.0f, 1.0f / 255.0f);
  const float c0 = 0.28209479177387814f;
  for (int i = 0; i < RandomPointCount; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      data.PointPositions.push_back(u(rng));
    }
    for (int k = 0; k < 3; ++k)
    {
      data.PointColors.push_back(shs(rng) * c0 + 0.5f);
    }
  }
  return data;
}

} // namespace

TrainingData LoadTrainingData(const std::string& path, const TrainingDataOptions& options)
{
  TrainingData data;
  const double bgValue = options.WhiteBackground ? 1.0 : 0.0;
  if (IsTransformsFolder(path) || IsTransformsJson(path))
  {
    return LoadTransformsTrainingData(path, options, bgValue);
  }
  if (detail::LowerExtension(path) == ".json")
  {
    SyntheticOptions so;
    so.Threads = options.Threads;
    if (options.Resolution > 0)
    {
      // Read the description's size first (cheap: no images), then scale.
      SyntheticOptions probe;
      probe.RenderImages = false;
      const SyntheticScene s = LoadSyntheticScene(path, probe);
      so.Width = options.Resolution;
      so.Height = std::max(1,
        static_cast<int>(std::lround(static_cast<double>(s.Cameras.front().Height) *
          options.Resolution / s.Cameras.front().Width)));
    }
    SyntheticScene scene = LoadSyntheticScene(path, so);
    data.Name = scene.Name;
    data.Cameras = std::move(scene.Cameras);
    data.Images = std::move(scene.Images);
    data.PointPositions = std::move(scene.PointPositions);
    data.PointColors = std::move(scene.PointColors);
    data.Background = scene.Background;
    if (options.WhiteBackground)
    {
      data.Background = { 1, 1, 1 };
    }
    return data;
  }
  if (!detail::IsDirectory(path))
  {
    throw std::runtime_error(
      path + ": not a COLMAP dataset folder nor a scene description (.json)");
  }
  DatasetOptions dopt;
  dopt.Eval = options.Eval;
  dopt.Resolution = options.Resolution;
  const Dataset ds = LoadColmapDataset(path, dopt);
  if (ds.PointPositions.empty())
  {
    throw std::runtime_error(path + ": points3D holds no points to initialise the Gaussians from");
  }
  data.Name = path;
  data.Cameras = ds.Cameras;
  LoadImages(data, bgValue);
  data.PointPositions = ds.PointPositions;
  data.PointColors.resize(ds.PointColors.size());
  for (std::size_t i = 0; i < ds.PointColors.size(); ++i)
  {
    data.PointColors[i] = ds.PointColors[i] / 255.0f;
  }
  return data;
}

} // namespace vis4gs

// SPDX-License-Identifier: BSD-3-Clause
#include "TrainingData.h"

#include "ColmapDataset.h"
#include "ImageIO.h"
#include "SceneFile.h"
#include "SyntheticScene.h"

#include <cmath>
#include <stdexcept>

namespace vis4gs
{

TrainingData LoadTrainingData(const std::string& path, const TrainingDataOptions& options)
{
  TrainingData data;
  const double bgValue = options.WhiteBackground ? 1.0 : 0.0;
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
  data.Background = { bgValue, bgValue, bgValue };
  data.Cameras = ds.Cameras;
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
  data.PointPositions = ds.PointPositions;
  data.PointColors.resize(ds.PointColors.size());
  for (std::size_t i = 0; i < ds.PointColors.size(); ++i)
  {
    data.PointColors[i] = ds.PointColors[i] / 255.0f;
  }
  return data;
}

} // namespace vis4gs

// SPDX-License-Identifier: BSD-3-Clause
#include "ColmapDataset.h"
#include "Colmap.h"
#include "SceneFile.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

namespace vis4gs
{

//------------------------------------------------------------------------------
std::pair<int, int> TrainingResolution(int width, int height, int resolution)
{
  if (width <= 0 || height <= 0)
  {
    throw std::invalid_argument("TrainingResolution: image size must be positive");
  }
  if (resolution == 1 || resolution == 2 || resolution == 4 || resolution == 8)
  {
    // Python's round(): half to even, which nearbyint does in the default rounding mode.
    const int w = static_cast<int>(std::nearbyint(width / static_cast<double>(resolution)));
    const int h = static_cast<int>(std::nearbyint(height / static_cast<double>(resolution)));
    return { std::max(w, 1), std::max(h, 1) };
  }
  double scale;
  if (resolution == -1)
  {
    scale = width > 1600 ? width / 1600.0 : 1.0;
  }
  else if (resolution > 0)
  {
    scale = width / static_cast<double>(resolution);
  }
  else
  {
    throw std::invalid_argument(
      "resolution must be -1, 1, 2, 4, 8 or a target width, got " + std::to_string(resolution));
  }
  // int() truncates, as the trainer does.
  const int w = static_cast<int>(width / scale);
  const int h = static_cast<int>(height / scale);
  return { std::max(w, 1), std::max(h, 1) };
}

//------------------------------------------------------------------------------
Dataset LoadColmapDataset(const std::string& root, const DatasetOptions& options)
{
  if (!detail::IsDirectory(root))
  {
    throw std::runtime_error(root + ": dataset folder does not exist");
  }
  if (options.LlffHold < 1)
  {
    throw std::invalid_argument("LoadColmapDataset: LlffHold must be at least 1");
  }
  Dataset ds;
  ds.Root = root;
  ds.SparseFolder = root + "/sparse/0";
  if (!detail::IsDirectory(ds.SparseFolder))
  {
    ds.SparseFolder = root + "/sparse";
    if (!detail::IsDirectory(ds.SparseFolder))
    {
      throw std::runtime_error(root + ": no COLMAP model (looked for sparse/0 and sparse)");
    }
  }
  const ColmapModel model = ReadColmapModel(ds.SparseFolder, false);
  if (model.Images.empty())
  {
    throw std::runtime_error(ds.SparseFolder + ": the COLMAP model has no registered images");
  }

  ds.ImageFolder = !options.Images.empty() && options.Images[0] == '/'
    ? options.Images
    : root + "/" + options.Images;
  const int r = options.Resolution;
  if (r == 2 || r == 4 || r == 8)
  {
    const std::string scaled = ds.ImageFolder + "_" + std::to_string(r);
    if (detail::IsDirectory(scaled))
    {
      ds.ImageFolder = scaled;
    }
  }

  std::map<int, const ColmapCamera*> cameras;
  for (const auto& c : model.Cameras)
  {
    cameras[c.Id] = &c;
  }
  std::vector<Camera> cams;
  std::vector<std::pair<int, int>> sizes;
  std::set<std::string> distortedModels;
  std::size_t distortedCount = 0;
  bool downscaled = false;
  for (const auto& im : model.Images)
  {
    const ColmapCamera& cc = *cameras.at(im.CameraId);
    Camera cam = ToCamera(cc, im);
    if (IsDistorted(cc))
    {
      distortedModels.insert(cam.Model);
      ++distortedCount;
    }
    cam.ImagePath = ds.ImageFolder + "/" + im.Name;
    if (options.RequireImages && !detail::IsRegularFile(cam.ImagePath))
    {
      throw std::runtime_error(cam.ImagePath + ": camera '" + cam.Name + "' (COLMAP image id " +
        std::to_string(im.Id) + ") has no image file");
    }
    const auto size = TrainingResolution(cam.Width, cam.Height, options.Resolution);
    downscaled = downscaled || (options.Resolution == -1 && cam.Width > 1600);
    sizes.emplace_back(cam.Width, cam.Height);
    cams.push_back(cam.Resized(size.first, size.second));
  }
  // Sort by image name (the trainer sorts by image_name; ties keep COLMAP order).
  std::vector<std::size_t> order(cams.size());
  for (std::size_t i = 0; i < order.size(); ++i)
  {
    order[i] = i;
  }
  std::stable_sort(order.begin(),
    order.end(),
    [&cams](std::size_t a, std::size_t b) { return cams[a].Name < cams[b].Name; });
  for (std::size_t i = 0; i < order.size(); ++i)
  {
    Camera cam = cams[order[i]];
    cam.Split = options.Eval && i % static_cast<std::size_t>(options.LlffHold) == 0
      ? CameraSplit::Test
      : CameraSplit::Train;
    ds.Cameras.push_back(std::move(cam));
    ds.OriginalSizes.push_back(sizes[order[i]]);
  }

  if (distortedCount)
  {
    std::string models;
    for (const auto& m : distortedModels)
    {
      models += (models.empty() ? "" : ", ") + m;
    }
    ds.Distorted = true;
    ds.Warnings.push_back(ds.SparseFolder + ": " + std::to_string(distortedCount) +
      " cameras use a distorted model (" + models +
      "); Vis4GS renders pinhole cameras and ignores the distortion parameters. Undistort the "
      "images (colmap image_undistorter) for exact results.");
  }
  if (downscaled)
  {
    ds.Warnings.push_back(root +
      ": images wider than 1600 px are scaled down to 1600 px wide, as the trainer does by "
      "default (set the resolution to 1 to keep the full size).");
  }

  ds.PointPositions.reserve(3 * model.Points3D.size());
  ds.PointColors.reserve(3 * model.Points3D.size());
  for (const auto& p : model.Points3D)
  {
    for (int c = 0; c < 3; ++c)
    {
      ds.PointPositions.push_back(static_cast<float>(p.Xyz[c]));
      ds.PointColors.push_back(p.Rgb[c]);
    }
  }
  return ds;
}

} // namespace vis4gs

// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSSceneCameras.h"

#include "TrainingLogReader.h"

#include "CameraJson.h"
#include "ColmapDataset.h"
#include "TransformsJson.h"

#include <filesystem>
#include <iostream>
#include <map>

std::vector<vis4gs::Camera> Vis4GSFindSceneCameras(const std::string& scene,
  const std::string& cameras)
{
  namespace fs = std::filesystem;
  std::string path = cameras;
  if (path.empty())
  {
    const fs::path dir = fs::path(scene).parent_path();
    for (const fs::path& p :
      { dir / "cameras.json", dir.parent_path().parent_path() / "cameras.json" })
    {
      if (fs::is_regular_file(p))
      {
        path = p.string();
        break;
      }
    }
  }
  if (path.empty())
  {
    return {};
  }
  if (vis4gs::IsTransformsFolder(path) || vis4gs::IsTransformsJson(path))
  {
    // Rendering needs no images: keep frames whose image is missing when w/h are given.
    vis4gs::TransformsCameras tc = vis4gs::LoadTransformsDataset(path, false);
    for (const std::string& w : tc.Warnings)
    {
      std::cerr << "warning: " << w << "\n";
    }
    return std::move(tc.Cameras);
  }
  if (fs::is_directory(path))
  {
    vis4gs::DatasetOptions options;
    options.RequireImages = false;
    return vis4gs::LoadColmapDataset(path, options).Cameras;
  }
  return vis4gs::ReadCamerasJson(path);
}

bool Vis4GSLoadViewImage(std::size_t, const vis4gs::Camera& camera, vis4gs::Image& image)
{
  return vis4gs::LoadCameraImage(nullptr, camera, image);
}

void Vis4GSAttachImagesByName(std::vector<vis4gs::Camera>& cameras, const std::string& folder)
{
  if (!std::filesystem::is_directory(folder))
  {
    throw std::runtime_error(folder + ": --images is not a folder");
  }
  std::map<std::string, std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder))
  {
    const std::string name = entry.path().filename().string();
    files.emplace(name.substr(0, name.find('.')), entry.path().string());
  }
  for (vis4gs::Camera& c : cameras)
  {
    const auto it = files.find(c.Name);
    c.ImagePath = it == files.end() ? std::string() : it->second;
  }
}

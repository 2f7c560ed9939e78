// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSSceneCameras.h"

#include "TrainingLogReader.h"

#include "vtkGaussianCameraReader.h"

#include <filesystem>
#include <map>
#include <stdexcept>

void Vis4GSSceneCameraRules(vtkGaussianCameraReader* reader)
{
  // Rendering and measuring need no image: a camera without one is measured without it.
  reader->RequireImagesOff();
  // cameras.json keeps its cameras' own image paths (--images matches files by name instead);
  // a COLMAP dataset still finds its images/ ("" is its default folder).
  reader->SetImageFolder("");
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

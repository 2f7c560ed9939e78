// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSStateFiles.h"

#include "GaussianIO.h"
#include "ImageIO.h"
#include "vtkGaussianSession.h" // IsTrainingLogFile: a log by its content

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <stdexcept>

bool Vis4GSIsLogPath(const std::string& path)
{
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(),
    extension.end(),
    extension.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  // By content too: a live log is LOG.h5.tmp while its trainer writes it (issue 32).
  return extension == ".h5" || extension == ".hdf5" ||
    vtkGaussianSession::IsTrainingLogFile(path.c_str());
}

//------------------------------------------------------------------------------
vis4gs::GaussianCloud Vis4GSReadSceneWithIds(const std::string& path, const std::string& command)
{
  vis4gs::GaussianReadReport report;
  vis4gs::GaussianCloud cloud = vis4gs::ReadGaussianScene(path, {}, &report);
  for (const std::string& w : report.Warnings)
  {
    std::cerr << "vis4gs " << command << ": warning: " << w << "\n";
  }
  if (const vis4gs::ExtraProperty* id = cloud.FindExtra("id"))
  {
    cloud.Ids.resize(cloud.Count);
    for (std::size_t i = 0; i < cloud.Count; ++i)
    {
      const double v = id->GetAsDouble(i);
      if (!(v == std::floor(v)) || std::abs(v) > 9.0e15)
      {
        throw std::runtime_error(
          path + ": vertex " + std::to_string(i) + ": id " + std::to_string(v) + " is no integer");
      }
      cloud.Ids[i] = static_cast<std::int64_t>(v);
    }
  }
  return cloud;
}

vis4gs::TrainingImageProvider Vis4GSLogImages(std::shared_ptr<vis4gs::TrainingLogReader> log)
{
  return [log](std::size_t, const vis4gs::Camera& camera, vis4gs::Image& image)
  { return vis4gs::LoadCameraImage(log.get(), camera, image); };
}

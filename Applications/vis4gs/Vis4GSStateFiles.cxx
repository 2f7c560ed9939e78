// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSStateFiles.h"

#include "GaussianIO.h"
#include "ImageIO.h"

#include <cmath>
#include <filesystem>
#include <iostream>
#include <stdexcept>

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
  {
    const std::string prefix = "/images/";
    std::error_code ec;
    if (log && camera.ImagePath.rfind(prefix, 0) == 0 &&
      !std::filesystem::is_regular_file(camera.ImagePath, ec))
    {
      int width = 0, height = 0;
      const std::vector<unsigned char> bytes =
        log->ReadImage(camera.ImagePath.substr(prefix.size()), width, height);
      image = vis4gs::PrepareTrainingImage(
        vis4gs::ImageFromBytes(bytes.data(), width, height, 3), camera);
      return true;
    }
    if (camera.ImagePath.empty() || !std::filesystem::is_regular_file(camera.ImagePath, ec))
    {
      return false;
    }
    image = vis4gs::LoadTrainingImage(camera);
    return true;
  };
}

/*=========================================================================

  Program:   Vis4GS
  Module:    Vis4GSTrainingImages.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "Vis4GSTrainingImages.h"

#include "ImageIO.h"
#include "TrainingLogReader.h"
#include "Vis4GSDataModel.h"

#include "vtkFieldData.h"
#include "vtkStringArray.h"
#include "vtkTable.h"

#include <exception>
#include <filesystem>
#include <map>
#include <memory>
#include <system_error>

namespace
{
// Files of @p folder by name up to the first '.' (the trainer's image_name).
std::map<std::string, std::string> ImagesByName(const std::string& folder)
{
  std::map<std::string, std::string> files;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec))
  {
    if (entry.is_regular_file(ec))
    {
      const std::string name = entry.path().filename().string();
      files.emplace(name.substr(0, name.find('.')), entry.path().string());
    }
  }
  return files;
}
}

//------------------------------------------------------------------------------
bool Vis4GSMatchImagesByName(std::vector<vis4gs::Camera>& cameras,
  const std::string& folder,
  std::string& error)
{
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec))
  {
    error = folder + ": not a folder";
    return false;
  }
  const auto files = ImagesByName(folder);
  for (vis4gs::Camera& camera : cameras)
  {
    const auto it = files.find(camera.Name);
    camera.ImagePath = it == files.end() ? std::string() : it->second;
  }
  return true;
}

//------------------------------------------------------------------------------
bool Vis4GSTrainingImages(vtkTable* table,
  const std::string& imageDirectory,
  const std::array<float, 3>& background,
  std::vector<vis4gs::Camera>& cameras,
  vis4gs::TrainingImageProvider& images,
  std::string& error)
{
  if (!imageDirectory.empty() && !Vis4GSMatchImagesByName(cameras, imageDirectory, error))
  {
    error = "ImageDirectory '" + imageDirectory + "' is not a folder.";
    return false;
  }
  std::shared_ptr<const vis4gs::TrainingLogReader> log;
  if (table)
  {
    auto* name = vtkStringArray::SafeDownCast(
      table->GetFieldData()->GetAbstractArray(vis4gs::arrays::CameraTrainingLogFile));
    if (name && name->GetNumberOfValues() == 1)
    {
      try
      {
        log = std::make_shared<const vis4gs::TrainingLogReader>(name->GetValue(0));
      }
      catch (const std::exception& e)
      {
        error = std::string("The training log of the cameras cannot be read: ") + e.what();
        return false;
      }
    }
  }
  images = [background, log](std::size_t, const vis4gs::Camera& camera, vis4gs::Image& image)
  { return vis4gs::LoadCameraImage(log.get(), camera, image, background); };
  return true;
}

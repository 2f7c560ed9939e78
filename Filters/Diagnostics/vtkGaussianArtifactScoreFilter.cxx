/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianArtifactScoreFilter.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianArtifactScoreFilter.h"

#include "ArtifactScores.h"
#include "ImageIO.h"
#include "Vis4GSDataModel.h"

#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkTable.h"
#include "vtkUnsignedCharArray.h"

#include <filesystem>
#include <map>
#include <system_error>
#include <vector>

vtkStandardNewMacro(vtkGaussianArtifactScoreFilter);

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

void AddArray(vtkPolyData* output, const char* name, const std::vector<double>& values)
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  std::copy(values.begin(), values.end(), array->GetPointer(0));
  output->GetPointData()->AddArray(array);
}
}

//------------------------------------------------------------------------------
vtkGaussianArtifactScoreFilter::vtkGaussianArtifactScoreFilter()
{
  this->SetNumberOfInputPorts(2);
}

//------------------------------------------------------------------------------
void vtkGaussianArtifactScoreFilter::SetCamerasData(vtkTable* cameras)
{
  this->SetInputData(1, cameras);
}

//------------------------------------------------------------------------------
void vtkGaussianArtifactScoreFilter::SetCamerasConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

//------------------------------------------------------------------------------
int vtkGaussianArtifactScoreFilter::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
    return 1;
  }
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkTable");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkGaussianArtifactScoreFilter::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkTable* table = vtkTable::GetData(inputVector[1]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  output->ShallowCopy(input);
  this->NumberOfViewsUsed = 0;
  this->NumberOfViewsWithoutImage = 0;
  this->NumberOfFlaggedGaussians = 0;

  vis4gs::ScoreSettings settings;
  settings.Request.ViewCoverage = this->ComputeViewCoverage;
  settings.Request.Blur = this->ComputeBlurScore;
  settings.Request.Needle = this->ComputeNeedleScore;
  settings.Request.NeedleShape = this->ComputeNeedleShape;
  settings.LossResolution = this->LossResolution;
  settings.CoverageResolution = this->CoverageResolution;
  settings.ViewStride = this->ViewStride;
  settings.Footprint = this->FootprintMode == 1 ? vis4gs::FootprintMode::Ellipse3Sigma
                                                : vis4gs::FootprintMode::Rasterizer;
  settings.Accumulation = this->FloatAccumulation ? vis4gs::FootprintAccumulation::Float
                                                  : vis4gs::FootprintAccumulation::Double;
  settings.OcclusionThreshold = this->OcclusionThreshold;
  settings.Lambda = this->Lambda;
  const bool needCameras =
    settings.Request.ViewCoverage || settings.Request.Blur || settings.Request.Needle;
  const bool needImages = settings.Request.Blur || settings.Request.Needle;

  vis4gs::GaussianCloud cloud;
  std::string error;
  if (!vis4gs::PolyDataToGaussianCloud(input, cloud, &error))
  {
    vtkErrorMacro("The input is not a Gaussian scene: " << error);
    return 0;
  }
  std::vector<vis4gs::Camera> cameras;
  if (needCameras)
  {
    if (!table)
    {
      vtkErrorMacro("ViewCoverage, BlurScore and NeedleScore need the camera table on input "
                    "port 1 (SetCamerasData / SetCamerasConnection).");
      return 0;
    }
    if (!vis4gs::TableToCameras(table, cameras, &error))
    {
      vtkErrorMacro("The camera table is not usable: " << error);
      return 0;
    }
  }
  if (needImages && !this->ImageDirectory.empty())
  {
    std::error_code ec;
    if (!std::filesystem::is_directory(this->ImageDirectory, ec))
    {
      vtkErrorMacro("ImageDirectory '" << this->ImageDirectory << "' is not a folder.");
      return 0;
    }
    const auto files = ImagesByName(this->ImageDirectory);
    for (vis4gs::Camera& camera : cameras)
    {
      const auto it = files.find(camera.Name);
      camera.ImagePath = it == files.end() ? std::string() : it->second;
    }
  }
  const auto background = settings.Raster.Background;
  vis4gs::TrainingImageProvider images;
  if (needImages)
  {
    images = [background](std::size_t, const vis4gs::Camera& camera, vis4gs::Image& image)
    {
      std::error_code ec;
      if (camera.ImagePath.empty() || !std::filesystem::is_regular_file(camera.ImagePath, ec))
      {
        return false;
      }
      image = vis4gs::LoadTrainingImage(camera,
        { static_cast<float>(background[0]),
          static_cast<float>(background[1]),
          static_cast<float>(background[2]) });
      return true;
    };
  }
  auto progress = [this](std::size_t done, std::size_t total)
  { this->UpdateProgress(total > 0 ? static_cast<double>(done) / total : 1.0); };

  vis4gs::GaussianScores scores;
  try
  {
    scores = vis4gs::ComputeGaussianScores(cloud, cameras, settings, images, progress);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Scores failed: " << e.what());
    return 0;
  }
  for (const std::string& warning : scores.Warnings)
  {
    vtkWarningMacro(<< warning);
  }
  this->NumberOfViewsUsed = static_cast<vtkIdType>(scores.ViewsUsed);
  this->NumberOfViewsWithoutImage = static_cast<vtkIdType>(scores.ViewsWithoutImage);

  if (settings.Request.ViewCoverage)
  {
    AddArray(output, vis4gs::arrays::ViewCoverage, scores.ViewCoverage);
  }
  if (settings.Request.Blur)
  {
    AddArray(output, vis4gs::arrays::BlurScore, scores.BlurScore);
  }
  if (settings.Request.Needle)
  {
    AddArray(output, vis4gs::arrays::NeedleScore, scores.NeedleScore);
  }
  if (settings.Request.NeedleShape)
  {
    AddArray(output, vis4gs::arrays::NeedleShape, scores.NeedleShape);
  }
  if (needCameras)
  {
    vtkNew<vtkUnsignedCharArray> flags;
    flags->SetName("NoVisibleView");
    flags->SetNumberOfTuples(static_cast<vtkIdType>(scores.Flags.size()));
    for (std::size_t i = 0; i < scores.Flags.size(); ++i)
    {
      flags->SetValue(static_cast<vtkIdType>(i), scores.Flags[i]);
      this->NumberOfFlaggedGaussians += scores.Flags[i] != 0 ? 1 : 0;
    }
    output->GetPointData()->AddArray(flags);
  }
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkGaussianArtifactScoreFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ComputeViewCoverage: " << (this->ComputeViewCoverage ? "On" : "Off") << "\n";
  os << indent << "ComputeBlurScore: " << (this->ComputeBlurScore ? "On" : "Off") << "\n";
  os << indent << "ComputeNeedleScore: " << (this->ComputeNeedleScore ? "On" : "Off") << "\n";
  os << indent << "ComputeNeedleShape: " << (this->ComputeNeedleShape ? "On" : "Off") << "\n";
  os << indent << "ImageDirectory: " << this->ImageDirectory << "\n";
  os << indent << "LossResolution: " << this->LossResolution << "\n";
  os << indent << "CoverageResolution: " << this->CoverageResolution << "\n";
  os << indent << "ViewStride: " << this->ViewStride << "\n";
  os << indent << "FootprintMode: " << this->FootprintMode << "\n";
  os << indent << "FloatAccumulation: " << (this->FloatAccumulation ? "On" : "Off") << "\n";
  os << indent << "OcclusionThreshold: " << this->OcclusionThreshold << "\n";
  os << indent << "Lambda: " << this->Lambda << "\n";
  os << indent << "NumberOfViewsUsed: " << this->NumberOfViewsUsed << "\n";
  os << indent << "NumberOfViewsWithoutImage: " << this->NumberOfViewsWithoutImage << "\n";
  os << indent << "NumberOfFlaggedGaussians: " << this->NumberOfFlaggedGaussians << "\n";
}

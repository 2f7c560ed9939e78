/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianCameraReader.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianCameraReader.h"

#include "Vis4GSDataModel.h"

#include "CameraJson.h"
#include "ColmapDataset.h"
#include "ImageIO.h"
#include "TransformsJson.h"

#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkTable.h"

#include <filesystem>
#include <stdexcept>
#include <system_error>

#include <sys/stat.h>

vtkStandardNewMacro(vtkGaussianCameraReader);

//------------------------------------------------------------------------------
vtkGaussianCameraReader::vtkGaussianCameraReader()
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
int vtkGaussianCameraReader::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** vtkNotUsed(inputVector),
  vtkInformationVector* outputVector)
{
  vtkTable* output = vtkTable::GetData(outputVector, 0);
  this->Distorted = false;
  if (this->FileName.empty())
  {
    vtkErrorMacro("No FileName set.");
    return 0;
  }
  std::vector<vis4gs::Camera> cameras;
  try
  {
    struct stat st;
    if (vis4gs::IsTransformsFolder(this->FileName) || vis4gs::IsTransformsJson(this->FileName))
    {
      vis4gs::TransformsCameras tc =
        vis4gs::LoadTransformsDataset(this->FileName, this->RequireImages);
      for (const auto& w : tc.Warnings)
      {
        vtkWarningMacro(<< w);
      }
      cameras = std::move(tc.Cameras);
    }
    else if (::stat(this->FileName.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
    {
      vis4gs::DatasetOptions options;
      options.Eval = this->Eval;
      options.LlffHold = this->LLFFHold;
      options.Resolution = this->Resolution;
      options.Images = this->ImageFolder.empty() ? "images" : this->ImageFolder;
      options.RequireImages = this->RequireImages;
      vis4gs::Dataset ds = vis4gs::LoadColmapDataset(this->FileName, options);
      for (const auto& w : ds.Warnings)
      {
        vtkWarningMacro(<< w);
      }
      this->Distorted = ds.Distorted;
      cameras = std::move(ds.Cameras);
    }
    else
    {
      cameras = vis4gs::ReadCamerasJson(this->FileName);
      std::string folder = this->ImageFolder;
      if (!folder.empty() && folder[0] != '/')
      {
        const auto slash = this->FileName.find_last_of('/');
        folder = (slash == std::string::npos ? std::string(".") : this->FileName.substr(0, slash)) +
          "/" + folder;
      }
      if (!folder.empty() && ::stat(folder.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
      {
        // Without RequireImages (rendering) an empty or partial images/ beside the file is
        // no reason to refuse the cameras.
        vis4gs::AttachImages(cameras, folder, this->RequireImages);
      }
    }
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  vis4gs::CamerasToTable(cameras, output);
  return 1;
}

//------------------------------------------------------------------------------
std::string vtkGaussianCameraReader::FindSceneCamerasFile(const std::string& scene)
{
  namespace fs = std::filesystem;
  // Two folders up lexically, also from a relative path of one part or none ("x.ply":
  // "../../cameras.json"), where parent_path() would run out and name the working folder.
  const fs::path dir = fs::path(scene).parent_path();
  const fs::path up = ((dir.empty() ? fs::path(".") : dir) / ".." / "..").lexically_normal();
  for (const fs::path& candidate : { dir / "cameras.json", up / "cameras.json" })
  {
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec))
    {
      return candidate.string();
    }
  }
  return std::string();
}

//------------------------------------------------------------------------------
void vtkGaussianCameraReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "Eval: " << this->Eval << "\n";
  os << indent << "LLFFHold: " << this->LLFFHold << "\n";
  os << indent << "Resolution: " << this->Resolution << "\n";
  os << indent << "ImageFolder: " << this->ImageFolder << "\n";
  os << indent << "RequireImages: " << this->RequireImages << "\n";
  os << indent << "Distorted: " << this->Distorted << "\n";
}

/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianSceneReader.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianSceneReader.h"

#include "Vis4GSDataModel.h"

#include "GaussianIO.h"
#include "SceneIds.h"

#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"

#include <stdexcept>

vtkStandardNewMacro(vtkGaussianSceneReader);

//------------------------------------------------------------------------------
vtkGaussianSceneReader::vtkGaussianSceneReader()
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
int vtkGaussianSceneReader::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** vtkNotUsed(inputVector),
  vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  this->FileSHDegree = 0;
  this->FileFormat.clear();
  this->NumberOfNonFiniteGaussians = 0;
  if (this->FileName.empty())
  {
    vtkErrorMacro("No FileName set.");
    return 0;
  }
  vis4gs::GaussianReadOptions options;
  options.MaxShDegree = this->MaxSHDegree;
  options.LoadSH = this->LoadSH;
  options.LoadScales = this->LoadScales;
  options.LoadRotations = this->LoadRotations;
  options.LoadOpacities = this->LoadOpacities;
  options.LoadExtras = this->LoadExtras;
  const bool optionalIds = this->IdPropertyOptional && !this->IdProperty.empty();
  options.IdProperty = optionalIds ? std::string() : this->IdProperty;
  vis4gs::GaussianReadReport report;
  vis4gs::GaussianCloud cloud;
  this->UpdateProgress(0.0);
  try
  {
    cloud = vis4gs::ReadGaussianScene(this->FileName, options, &report);
    if (optionalIds)
    {
      vis4gs::IdsFromExtraProperty(cloud, this->IdProperty, this->FileName);
    }
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  for (const auto& w : report.Warnings)
  {
    vtkWarningMacro(<< w);
  }
  this->FileSHDegree = report.FileShDegree;
  this->FileFormat = report.Format;
  this->NumberOfNonFiniteGaussians = static_cast<vtkIdType>(report.NonFiniteGaussians);
  this->UpdateProgress(0.8);
  vis4gs::PolyDataOptions pdOptions;
  pdOptions.ActivatedArrays = this->ActivatedArrays;
  vis4gs::GaussianCloudToPolyData(std::move(cloud), output, pdOptions); // no copy
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkGaussianSceneReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "MaxSHDegree: " << this->MaxSHDegree << "\n";
  os << indent << "LoadSH: " << this->LoadSH << "\n";
  os << indent << "LoadScales: " << this->LoadScales << "\n";
  os << indent << "LoadRotations: " << this->LoadRotations << "\n";
  os << indent << "LoadOpacities: " << this->LoadOpacities << "\n";
  os << indent << "LoadExtras: " << this->LoadExtras << "\n";
  os << indent << "ActivatedArrays: " << this->ActivatedArrays << "\n";
  os << indent << "IdProperty: " << this->IdProperty << "\n";
  os << indent << "IdPropertyOptional: " << this->IdPropertyOptional << "\n";
  os << indent << "FileSHDegree: " << this->FileSHDegree << "\n";
  os << indent << "FileFormat: " << this->FileFormat << "\n";
  os << indent << "NumberOfNonFiniteGaussians: " << this->NumberOfNonFiniteGaussians << "\n";
}

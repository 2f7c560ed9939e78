/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianPLYWriter.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianPLYWriter.h"

#include "Vis4GSDataModel.h"

#include "GaussianIO.h"

#include "vtkErrorCode.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"

#include <stdexcept>

vtkStandardNewMacro(vtkGaussianPLYWriter);

//------------------------------------------------------------------------------
vtkPolyData* vtkGaussianPLYWriter::GetInput()
{
  return vtkPolyData::SafeDownCast(this->Superclass::GetInput());
}

//------------------------------------------------------------------------------
int vtkGaussianPLYWriter::FillInputPortInformation(int vtkNotUsed(port), vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

//------------------------------------------------------------------------------
void vtkGaussianPLYWriter::WriteData()
{
  if (this->FileName.empty())
  {
    vtkErrorMacro("No FileName set.");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return;
  }
  vis4gs::GaussianCloud cloud;
  std::string error;
  if (!vis4gs::PolyDataToGaussianCloud(this->GetInput(), cloud, &error, this->WriteExtraArrays))
  {
    vtkErrorMacro(<< this->FileName << ": cannot write the Gaussian scene: " << error);
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }
  if (!this->WriteIds)
  {
    cloud.Ids.clear();
  }
  vis4gs::SceneWriteOptions options;
  options.Format = this->FileFormat == BINARY_BIG_ENDIAN ? vis4gs::PlyFormat::BinaryBigEndian
    : this->FileFormat == ASCII                          ? vis4gs::PlyFormat::Ascii
                                                         : vis4gs::PlyFormat::BinaryLittleEndian;
  options.IdProperty = this->IdPropertyName;
  try
  {
    // A name ending in .glb, .gltf, .spz, .compressed.ply or .splat picks that format.
    this->WriteReport = vis4gs::WriteGaussianScene(this->FileName, cloud, options);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< this->FileName << ": " << e.what());
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
  }
}

//------------------------------------------------------------------------------
void vtkGaussianPLYWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "FileFormat: " << this->FileFormat << "\n";
  os << indent << "WriteIds: " << this->WriteIds << "\n";
  os << indent << "IdPropertyName: " << this->IdPropertyName << "\n";
  os << indent << "WriteExtraArrays: " << this->WriteExtraArrays << "\n";
  os << indent << "WriteReport: " << this->WriteReport << "\n";
}

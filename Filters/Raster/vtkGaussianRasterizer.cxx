/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianRasterizer.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianRasterizer.h"

#include "Rasterizer.h"
#include "SpecialValues.h"
#include "Vis4GSDataModel.h"

#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTable.h"
#include "vtkUnsignedIntArray.h"

#include <algorithm>
#include <exception>
#include <vector>

vtkStandardNewMacro(vtkGaussianRasterizer);

namespace
{

//------------------------------------------------------------------------------
// Picks the camera by name or index; false with a message when it does not exist.
bool PickCamera(const std::vector<vis4gs::Camera>& cameras,
  const std::string& name,
  int index,
  vis4gs::Camera& camera,
  std::string& error)
{
  if (!name.empty())
  {
    for (const auto& c : cameras)
    {
      if (c.Name == name)
      {
        camera = c;
        return true;
      }
    }
    error =
      "no camera named '" + name + "' among the " + std::to_string(cameras.size()) + " cameras";
    return false;
  }
  if (index < 0 || static_cast<std::size_t>(index) >= cameras.size())
  {
    error = "camera index " + std::to_string(index) + " is out of range (" +
      std::to_string(cameras.size()) + " cameras)";
    return false;
  }
  camera = cameras[static_cast<std::size_t>(index)];
  return true;
}

//------------------------------------------------------------------------------
template <typename T, typename ArrayT>
void FillOutput(const vis4gs::RasterImage<T>& img, vtkImageData* output)
{
  const int W = img.Width, H = img.Height;
  const vtkIdType n = static_cast<vtkIdType>(W) * H;
  vtkNew<ArrayT> rgb;
  rgb->SetName("RGB");
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(n);
  vtkNew<ArrayT> alpha;
  alpha->SetName("Alpha");
  alpha->SetNumberOfTuples(n);
  vtkNew<ArrayT> depth;
  depth->SetName("Depth");
  depth->SetNumberOfTuples(n);
  vtkNew<vtkUnsignedIntArray> contrib;
  contrib->SetName("Contributors");
  contrib->SetNumberOfTuples(n);
  for (int j = 0; j < H; ++j)
  {
    const int y = H - 1 - j; // VTK rows grow upwards, camera rows downwards
    for (int x = 0; x < W; ++x)
    {
      const std::size_t src = static_cast<std::size_t>(y) * W + x;
      const vtkIdType dst = static_cast<vtkIdType>(j) * W + x;
      for (int c = 0; c < 3; ++c)
      {
        rgb->SetTypedComponent(dst, c, img.Color[3 * src + c]);
      }
      alpha->SetValue(dst, img.Alpha[src]);
      depth->SetValue(dst, img.Depth[src]);
      contrib->SetValue(dst, img.Contributors[src]);
    }
  }
  output->GetPointData()->SetScalars(rgb);
  output->GetPointData()->AddArray(alpha);
  output->GetPointData()->AddArray(depth);
  output->GetPointData()->AddArray(contrib);
}

} // namespace

//------------------------------------------------------------------------------
vtkGaussianRasterizer::vtkGaussianRasterizer()
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(1);
}

//------------------------------------------------------------------------------
void vtkGaussianRasterizer::SetCamerasData(vtkTable* cameras)
{
  this->SetInputData(1, cameras);
}

//------------------------------------------------------------------------------
void vtkGaussianRasterizer::SetCamerasConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

//------------------------------------------------------------------------------
int vtkGaussianRasterizer::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), port == 0 ? "vtkPolyData" : "vtkTable");
  return 1;
}

//------------------------------------------------------------------------------
int vtkGaussianRasterizer::RequestInformation(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  // The size comes from the camera table, which may not be produced yet: use it when it is
  // there (or the Width/Height override); RequestData sets the final extent either way.
  int w = this->Width, h = this->Height;
  vtkTable* table = vtkTable::GetData(inputVector[1]);
  if ((w == 0 || h == 0) && table && table->GetNumberOfRows() > 0)
  {
    std::vector<vis4gs::Camera> cameras;
    std::string error;
    vis4gs::Camera cam;
    if (vis4gs::TableToCameras(table, cameras, &error) &&
      PickCamera(cameras, this->CameraName, this->CameraIndex, cam, error))
    {
      w = w ? w : cam.Width;
      h = h ? h : cam.Height;
    }
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const int extent[6] = { 0, std::max(w, 1) - 1, 0, std::max(h, 1) - 1, 0, 0 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::SPACING(), 1.0, 1.0, 1.0);
  outInfo->Set(vtkDataObject::ORIGIN(), 0.0, 0.0, 0.0);
  vtkDataObject::SetPointDataActiveScalarInfo(
    outInfo, this->Precision == DOUBLE ? VTK_DOUBLE : VTK_FLOAT, 3);
  return 1;
}

//------------------------------------------------------------------------------
int vtkGaussianRasterizer::RequestUpdateExtent(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** vtkNotUsed(inputVector),
  vtkInformationVector* vtkNotUsed(outputVector))
{
  return 1; // inputs are not images: nothing to request
}

//------------------------------------------------------------------------------
int vtkGaussianRasterizer::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkTable* table = vtkTable::GetData(inputVector[1]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  this->NumberOfVisibleGaussians = 0;
  this->NumberOfInvalidGaussians = 0;
  this->SpecialValuesSummary.clear();
  if (!input || !table)
  {
    vtkErrorMacro("Needs a Gaussian scene on port 0 and the camera table on port 1.");
    return 0;
  }
  vis4gs::GaussianCloud cloud;
  std::string error;
  if (!vis4gs::PolyDataToGaussianCloud(input, cloud, &error))
  {
    vtkErrorMacro("The input is not a Gaussian scene: " << error);
    return 0;
  }
  std::vector<vis4gs::Camera> cameras;
  if (!vis4gs::TableToCameras(table, cameras, &error))
  {
    vtkErrorMacro("The camera table is not usable: " << error);
    return 0;
  }
  vis4gs::Camera camera;
  if (!PickCamera(cameras, this->CameraName, this->CameraIndex, camera, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  if (camera.Width > 0 && camera.Height > 0 && (this->Width > 0 || this->Height > 0))
  {
    camera = camera.Resized(this->Width > 0 ? this->Width : camera.Width,
      this->Height > 0 ? this->Height : camera.Height);
  }
  if (cloud.SH.empty() && cloud.Count > 0)
  {
    vtkErrorMacro("The Gaussian scene has no SH array: colours cannot be rendered.");
    return 0;
  }
  vis4gs::RasterSettings settings;
  settings.Background = { this->Background[0], this->Background[1], this->Background[2] };
  settings.ShDegree = this->SHDegree;
  settings.ScaleModifier = this->ScaleModifier;
  settings.Threads = this->NumberOfThreads;
  vis4gs::ProjectionCounts counts;
  try
  {
    const int extent[6] = { 0, camera.Width - 1, 0, camera.Height - 1, 0, 0 };
    if (this->Precision == DOUBLE)
    {
      const auto img = vis4gs::Rasterize<double>(cloud, camera, settings, &counts);
      output->SetExtent(const_cast<int*>(extent));
      FillOutput<double, vtkDoubleArray>(img, output);
    }
    else
    {
      const auto img = vis4gs::Rasterize<float>(cloud, camera, settings, &counts);
      output->SetExtent(const_cast<int*>(extent));
      FillOutput<float, vtkFloatArray>(img, output);
    }
    outputVector->GetInformationObject(0)->Set(
      vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Rasterisation failed: " << e.what());
    return 0;
  }
  output->SetSpacing(1.0, 1.0, 1.0);
  output->SetOrigin(0.0, 0.0, 0.0);
  this->NumberOfVisibleGaussians = static_cast<vtkIdType>(counts.Visible);
  this->NumberOfInvalidGaussians =
    static_cast<vtkIdType>(counts.InvalidParameters + counts.NonFinite);
  {
    // One memory-bound pass over the cloud, small next to the render.
    const vis4gs::SpecialValueCounts special =
      vis4gs::CountSpecialValues(cloud, this->SHDegree < 0 ? cloud.ShDegree : this->SHDegree);
    const std::string skipped = vis4gs::DescribeSkipped(special, true);
    const std::string drawn = vis4gs::DescribeDrawnSpecials(special);
    this->SpecialValuesSummary = skipped + (!skipped.empty() && !drawn.empty() ? "; " : "") + drawn;
    if (!skipped.empty())
    {
      vtkWarningMacro(<< "Gaussians the reference cannot draw: " << skipped);
    }
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkGaussianRasterizer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CameraIndex: " << this->CameraIndex << "\n";
  os << indent << "CameraName: " << this->CameraName << "\n";
  os << indent << "Width: " << this->Width << "\n";
  os << indent << "Height: " << this->Height << "\n";
  os << indent << "Background: " << this->Background[0] << " " << this->Background[1] << " "
     << this->Background[2] << "\n";
  os << indent << "SHDegree: " << this->SHDegree << "\n";
  os << indent << "Precision: " << (this->Precision == DOUBLE ? "Double" : "Float") << "\n";
  os << indent << "ScaleModifier: " << this->ScaleModifier << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "NumberOfVisibleGaussians: " << this->NumberOfVisibleGaussians << "\n";
  os << indent << "NumberOfInvalidGaussians: " << this->NumberOfInvalidGaussians << "\n";
  os << indent << "SpecialValuesSummary: " << this->SpecialValuesSummary << "\n";
}

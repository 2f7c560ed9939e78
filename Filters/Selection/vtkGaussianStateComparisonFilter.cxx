/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianStateComparisonFilter.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianStateComparisonFilter.h"

#include "RemovalEffect.h"
#include "StateComparison.h"
#include "Vis4GSDataModel.h"
#include "Vis4GSTrainingImages.h"

#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkUnsignedCharArray.h"

#include <cmath>
#include <exception>
#include <limits>
#include <string>
#include <vector>

namespace
{
/// Both states measured in every camera of @p cameraTable into @p output (the class comment's
/// columns); false with the reason in @p error. Returns the cameras measured in @p measured.
bool MeasureBothStates(const vis4gs::GaussianCloud* clouds,
  vtkTable* cameraTable,
  const std::string& imageDirectory,
  int threads,
  vtkTable* output,
  vtkIdType& measured,
  std::string& error)
{
  std::vector<vis4gs::Camera> cameras;
  if (!vis4gs::TableToCameras(cameraTable, cameras, &error))
  {
    error = "The camera table is not usable: " + error;
    return false;
  }
  vis4gs::TrainingImageProvider images;
  if (!Vis4GSTrainingImages(cameraTable, imageDirectory, { 0.f, 0.f, 0.f }, cameras, images, error))
  {
    return false;
  }
  vis4gs::RemovalEffectOptions options;
  options.Threads = threads;
  std::vector<vis4gs::ViewMetrics> figures[2];
  try
  {
    for (int s = 0; s < 2; ++s)
    {
      figures[s] = vis4gs::MeasureViewMetrics(clouds[s], cameras, options, images);
    }
  }
  catch (const std::exception& e)
  {
    error = e.what();
    return false;
  }
  const vtkIdType rows = static_cast<vtkIdType>(cameras.size());
  vtkNew<vtkIdTypeArray> camera;
  camera->SetName("Camera");
  vtkNew<vtkStringArray> name, split;
  name->SetName("Name");
  split->SetName("Split");
  camera->SetNumberOfTuples(rows);
  name->SetNumberOfValues(rows);
  split->SetNumberOfValues(rows);
  const char* columns[] = { "PSNR_A", "SSIM_A", "L1_A", "PSNR_B", "SSIM_B", "L1_B" };
  vtkNew<vtkDoubleArray> values[6];
  for (int k = 0; k < 6; ++k)
  {
    values[k]->SetName(columns[k]);
    values[k]->SetNumberOfTuples(rows);
  }
  measured = 0;
  for (vtkIdType r = 0; r < rows; ++r)
  {
    const std::size_t i = static_cast<std::size_t>(r);
    camera->SetValue(r, r);
    name->SetValue(r, cameras[i].Name);
    split->SetValue(r, cameras[i].Split == vis4gs::CameraSplit::Train ? "train" : "test");
    for (int s = 0; s < 2; ++s)
    {
      const vis4gs::ViewMetrics& m = figures[s][i];
      values[3 * s]->SetValue(r, m.Psnr);
      values[3 * s + 1]->SetValue(r, m.Ssim);
      values[3 * s + 2]->SetValue(r, m.L1);
    }
    measured += std::isfinite(figures[0][i].L1) ? 1 : 0;
  }
  output->AddColumn(camera);
  output->AddColumn(name);
  output->AddColumn(split);
  for (auto& column : values)
  {
    output->AddColumn(column);
  }
  return true;
}
}

vtkStandardNewMacro(vtkGaussianStateComparisonFilter);

//------------------------------------------------------------------------------
vtkGaussianStateComparisonFilter::vtkGaussianStateComparisonFilter()
{
  this->SetNumberOfInputPorts(3);
  this->SetNumberOfOutputPorts(2);
}

//------------------------------------------------------------------------------
void vtkGaussianStateComparisonFilter::SetCamerasData(vtkTable* cameras)
{
  this->SetInputData(2, cameras);
}

vtkTable* vtkGaussianStateComparisonFilter::GetViewsOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(1));
}

//------------------------------------------------------------------------------
int vtkGaussianStateComparisonFilter::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 2)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkTable");
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    return 1;
  }
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

int vtkGaussianStateComparisonFilter::FillOutputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkTable");
  return 1;
}

//------------------------------------------------------------------------------
int vtkGaussianStateComparisonFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkTable* output = vtkTable::GetData(outputVector, 0);
  vtkTable* views = vtkTable::GetData(outputVector, 1);
  this->NumberOfViewsMeasured = 0;
  vis4gs::GaussianCloud clouds[2];
  for (int port = 0; port < 2; ++port)
  {
    std::string error;
    if (!vis4gs::PolyDataToGaussianCloud(
          vtkPolyData::GetData(inputVector[port]), clouds[port], &error))
    {
      vtkErrorMacro("State " << (port == 0 ? "A" : "B") << " is not a Gaussian scene: " << error);
      return 0;
    }
  }
  vis4gs::StateThresholds thresholds;
  thresholds.Move = this->MoveThreshold;
  thresholds.Opacity = this->OpacityThreshold;
  thresholds.Scale = this->ScaleThreshold;
  vis4gs::StateComparison c;
  try
  {
    c = vis4gs::CompareStates(clouds[0], clouds[1], thresholds);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  const vtkIdType rows = static_cast<vtkIdType>(c.Gaussians.size());
  vtkNew<vtkIdTypeArray> ids;
  ids->SetName(vis4gs::arrays::GaussianId);
  vtkNew<vtkUnsignedCharArray> change;
  change->SetName("Change");
  vtkNew<vtkStringArray> status;
  status->SetName("Status");
  vtkNew<vtkDoubleArray> move, opacity, scale;
  move->SetName("Move");
  opacity->SetName("OpacityChange");
  scale->SetName("ScaleChange");
  ids->SetNumberOfTuples(rows);
  change->SetNumberOfTuples(rows);
  status->SetNumberOfValues(rows);
  move->SetNumberOfTuples(rows);
  opacity->SetNumberOfTuples(rows);
  scale->SetNumberOfTuples(rows);
  for (vtkIdType r = 0; r < rows; ++r)
  {
    const vis4gs::GaussianStateDifference& d = c.Gaussians[static_cast<std::size_t>(r)];
    ids->SetValue(r, static_cast<vtkIdType>(d.Id));
    change->SetValue(r, d.Change);
    status->SetValue(r, vis4gs::StateChangeName(d.Change));
    move->SetValue(r, d.Move);
    opacity->SetValue(r, d.Opacity);
    scale->SetValue(r, d.Scale);
  }
  output->AddColumn(ids);
  output->AddColumn(change);
  output->AddColumn(status);
  output->AddColumn(move);
  output->AddColumn(opacity);
  output->AddColumn(scale);
  this->NumberMatched = static_cast<vtkIdType>(c.Matched);
  this->NumberBorn = static_cast<vtkIdType>(c.Born);
  this->NumberDied = static_cast<vtkIdType>(c.Died);
  this->NumberMoved = static_cast<vtkIdType>(c.Moved);
  this->NumberOpacityChanged = static_cast<vtkIdType>(c.OpacityChanged);
  this->NumberScaleChanged = static_cast<vtkIdType>(c.ScaleChanged);
  this->NumberUnchanged = static_cast<vtkIdType>(c.Unchanged);
  vtkTable* cameras = inputVector[2]->GetNumberOfInformationObjects() > 0
    ? vtkTable::GetData(inputVector[2])
    : nullptr;
  if (this->MeasureViews && cameras && cameras->GetNumberOfRows() > 0)
  {
    std::string error;
    if (!MeasureBothStates(clouds,
          cameras,
          this->ImageDirectory,
          this->NumberOfThreads,
          views,
          this->NumberOfViewsMeasured,
          error))
    {
      vtkErrorMacro(<< error);
      return 0;
    }
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkGaussianStateComparisonFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MoveThreshold: " << this->MoveThreshold << "\n";
  os << indent << "OpacityThreshold: " << this->OpacityThreshold << "\n";
  os << indent << "ScaleThreshold: " << this->ScaleThreshold << "\n";
  os << indent << "MeasureViews: " << this->MeasureViews << "\n";
  os << indent << "ImageDirectory: " << this->ImageDirectory << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "NumberOfViewsMeasured: " << this->NumberOfViewsMeasured << "\n";
  os << indent << "NumberMatched: " << this->NumberMatched << "\n";
  os << indent << "NumberBorn: " << this->NumberBorn << "\n";
  os << indent << "NumberDied: " << this->NumberDied << "\n";
  os << indent << "NumberMoved: " << this->NumberMoved << "\n";
  os << indent << "NumberOpacityChanged: " << this->NumberOpacityChanged << "\n";
  os << indent << "NumberScaleChanged: " << this->NumberScaleChanged << "\n";
  os << indent << "NumberUnchanged: " << this->NumberUnchanged << "\n";
}

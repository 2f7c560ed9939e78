/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianFineTuneFilter.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianFineTuneFilter.h"

#include "FineTune.h"
#include "RemovalEffect.h"
#include "Vis4GSDataModel.h"
#include "Vis4GSTrainingImages.h"

#include "vtkCallbackCommand.h"
#include "vtkDataArray.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkGaussianRemovalEffectFilter.h"
#include "vtkGaussianTrainingLogReader.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkTable.h"

#include <algorithm>
#include <chrono>
#include <exception>
#include <vector>

vtkStandardNewMacro(vtkGaussianFineTuneFilter);

//------------------------------------------------------------------------------
vtkGaussianFineTuneFilter::vtkGaussianFineTuneFilter()
{
  this->SetNumberOfInputPorts(3);
  this->SetNumberOfOutputPorts(2);
}

//------------------------------------------------------------------------------
vtkGaussianFineTuneFilter::~vtkGaussianFineTuneFilter() = default;

//------------------------------------------------------------------------------
void vtkGaussianFineTuneFilter::SetCamerasData(vtkTable* cameras)
{
  this->SetInputData(1, cameras);
}

//------------------------------------------------------------------------------
void vtkGaussianFineTuneFilter::SetCamerasConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

//------------------------------------------------------------------------------
void vtkGaussianFineTuneFilter::SetRemovalFiguresData(vtkTable* figures)
{
  this->SetInputData(2, figures);
}

//------------------------------------------------------------------------------
void vtkGaussianFineTuneFilter::SetRemovalFiguresConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(2, output);
}

//------------------------------------------------------------------------------
vtkTable* vtkGaussianFineTuneFilter::GetFiguresOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(1));
}

//------------------------------------------------------------------------------
void vtkGaussianFineTuneFilter::SetRemovedIds(vtkIdTypeArray* ids)
{
  if (this->RemovedIds != ids)
  {
    this->RemovedIds = ids;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkIdTypeArray* vtkGaussianFineTuneFilter::GetRemovedIds()
{
  return this->RemovedIds;
}

//------------------------------------------------------------------------------
int vtkGaussianFineTuneFilter::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), port == 0 ? "vtkPolyData" : "vtkTable");
  if (port == 2)
  {
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkGaussianFineTuneFilter::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkPolyData" : "vtkTable");
  return 1;
}

//------------------------------------------------------------------------------
int vtkGaussianFineTuneFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkTable* cameraTable = vtkTable::GetData(inputVector[1]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkTable* figures = vtkTable::GetData(outputVector, 1);
  this->NumberOfRemoved = 0;
  this->LastIteration = -1;
  this->TrainSeconds = this->MeasureSeconds = 0;

  vis4gs::GaussianCloud snapshot;
  std::string error;
  if (!vis4gs::PolyDataToGaussianCloud(input, snapshot, &error))
  {
    vtkErrorMacro("The input is not a Gaussian scene: " << error);
    return 0;
  }
  if (snapshot.Ids.size() != snapshot.Count)
  {
    vtkErrorMacro("The input has no " << vis4gs::arrays::GaussianId << " array.");
    return 0;
  }
  int source = this->SourceIteration;
  if (source < 0)
  {
    vtkInformation* dataInfo = input->GetInformation();
    if (!dataInfo->Has(vtkDataObject::DATA_TIME_STEP()))
    {
      vtkErrorMacro("SourceIteration is not set and the input has no DATA_TIME_STEP (connect "
                    "vtkGaussianTrainingLogReader's snapshot, or set SourceIteration).");
      return 0;
    }
    source = static_cast<int>(dataInfo->Get(vtkDataObject::DATA_TIME_STEP()));
  }

  // The Gaussians to delete.
  std::vector<std::uint8_t> removed(snapshot.Count, 0);
  if (this->RemovedIds)
  {
    std::vector<std::int64_t> ids(static_cast<std::size_t>(this->RemovedIds->GetNumberOfValues()));
    for (std::size_t k = 0; k < ids.size(); ++k)
    {
      ids[k] = this->RemovedIds->GetValue(static_cast<vtkIdType>(k));
    }
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    std::size_t found = 0;
    for (std::size_t i = 0; i < snapshot.Count; ++i)
    {
      removed[i] = std::binary_search(ids.begin(), ids.end(), snapshot.Ids[i]) ? 1 : 0;
      found += removed[i];
    }
    if (found != ids.size())
    {
      vtkErrorMacro(
        "RemovedIds lists " << ids.size() - found << " GaussianIds that the input does not hold.");
      return 0;
    }
  }
  else
  {
    vtkDataArray* mask = input->GetPointData()->GetArray(this->RemovalArrayName.c_str());
    if (!mask || mask->GetNumberOfComponents() != 1)
    {
      vtkErrorMacro("The input has no one-component point-data array '"
        << this->RemovalArrayName << "' marking the Gaussians to delete (RemovalArrayName).");
      return 0;
    }
    for (std::size_t i = 0; i < snapshot.Count; ++i)
    {
      removed[i] = mask->GetTuple1(static_cast<vtkIdType>(i)) != 0 ? 1 : 0;
    }
  }

  std::vector<vis4gs::Camera> cameras;
  if (!vis4gs::TableToCameras(cameraTable, cameras, &error))
  {
    vtkErrorMacro("The camera table is not usable: " << error);
    return 0;
  }
  // The images as the score and removal filters find them (Vis4GSTrainingImages); the log the
  // camera table names also gives the repaired log its scene name and whether it embeds them.
  vis4gs::TrainingImageProvider images;
  if (!Vis4GSTrainingImages(
        cameraTable, this->ImageDirectory, { 0.f, 0.f, 0.f }, cameras, images, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  vis4gs::FineTuneOptions options;
  options.Producer = this->Producer;
  options.EmbedImages = false;
  auto* logName = vtkStringArray::SafeDownCast(
    cameraTable->GetFieldData()->GetAbstractArray(vis4gs::arrays::CameraTrainingLogFile));
  if (logName && logName->GetNumberOfValues() == 1)
  {
    vtkNew<vtkGaussianTrainingLogReader> log;
    log->SetFileName(logName->GetValue(0).c_str());
    // Its error is reported here, as this filter's (an observer keeps it from being printed).
    std::string logError;
    vtkNew<vtkCallbackCommand> onError;
    onError->SetClientData(&logError);
    onError->SetCallback([](vtkObject*, unsigned long, void* client, void* message)
      { *static_cast<std::string*>(client) += message ? static_cast<const char*>(message) : ""; });
    log->AddObserver(vtkCommand::ErrorEvent, onError);
    if (!vtkDemandDrivenPipeline::SafeDownCast(log->GetExecutive())->UpdateInformation())
    {
      vtkErrorMacro("The training log of the cameras cannot be read: " << logError);
      return 0;
    }
    options.Scene = log->GetSceneName();
    options.EmbedImages = log->HasImages();
  }

  options.Scene = this->SceneName.empty() ? options.Scene : this->SceneName;
  options.EmbedImages = this->EmbedImages < 0 ? options.EmbedImages : this->EmbedImages == 1;
  options.MetricsInterval = this->MetricsInterval;
  options.Iterations = this->Iterations;
  options.WarmupIterations = this->WarmupIterations;
  options.FreePositions = this->FreePositions;
  options.Densify = this->Densify;
  options.Seed = this->Seed;
  options.Threads = this->NumberOfThreads;
  options.LogPath = this->OutputLogFileName;
  // The source and deleted states' figures given (a removal preview of this deletion).
  vtkTable* given =
    this->GetNumberOfInputConnections(2) > 0 ? vtkTable::GetData(inputVector[2]) : nullptr;
  std::vector<vis4gs::ViewMetrics> givenSource, givenDeleted;
  if (given)
  {
    std::vector<vis4gs::RemovalViewEffect> views;
    if (!vtkGaussianRemovalEffectFilter::ViewsOfTable(given, views, &error))
    {
      vtkErrorMacro("The removal figures (input port 2) are not usable: " << error);
      return 0;
    }
    givenSource.assign(cameras.size(), vis4gs::ViewMetrics());
    givenDeleted.assign(cameras.size(), vis4gs::ViewMetrics());
    for (const vis4gs::RemovalViewEffect& view : views)
    {
      if (view.CameraIndex >= cameras.size() || cameras[view.CameraIndex].Name != view.Name)
      {
        vtkErrorMacro("The removal figures (input port 2) are of other cameras: their view '"
          << view.Name << "' is not camera " << view.CameraIndex << " of the camera table.");
        return 0;
      }
      if (view.HasImage)
      {
        givenSource[view.CameraIndex] = view.Before;
        givenDeleted[view.CameraIndex] = view.After;
      }
    }
    options.Measure = false;
  }
  options.Progress = [this](int done, int total)
  {
    this->UpdateProgress(static_cast<double>(done) / total);
    return !this->AbortExecute;
  };
  vis4gs::FineTuneResult result;
  try
  {
    result = vis4gs::FineTune(snapshot, source, removed, cameras, images, options);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("The fine-tune failed: " << e.what());
    return 0;
  }
  if (given && !result.Cancelled)
  {
    result.Source = std::move(givenSource);
    result.Deleted = std::move(givenDeleted);
    const auto t0 = std::chrono::steady_clock::now();
    try
    {
      vis4gs::RemovalEffectOptions measure;
      measure.Threads = this->NumberOfThreads;
      result.RepairedFigures =
        vis4gs::MeasureViewMetrics(result.Repaired, cameras, measure, images);
    }
    catch (const std::exception& e)
    {
      vtkErrorMacro("Measuring the repaired scene failed: " << e.what());
      return 0;
    }
    result.MeasureSeconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  this->NumberOfRemoved = static_cast<vtkIdType>(result.Pruned.size());
  this->LastIteration = result.LastIteration;
  this->TrainSeconds = result.TrainSeconds;
  this->MeasureSeconds = result.MeasureSeconds;
  if (result.Cancelled)
  {
    return 1; // aborted: empty outputs, no log
  }
  vis4gs::GaussianCloudToPolyData(std::move(result.Repaired), output);

  const std::vector<std::string>& columns = vis4gs::FineTuneFigureColumns();
  const std::vector<vis4gs::FineTuneFigureRow> rows = vis4gs::FineTuneFigureRows(result, cameras);
  const vtkIdType n = static_cast<vtkIdType>(rows.size());
  vtkNew<vtkStringArray> view, split;
  view->SetName(columns[0].c_str());
  split->SetName(columns[1].c_str());
  view->SetNumberOfValues(n);
  split->SetNumberOfValues(n);
  std::vector<vtkSmartPointer<vtkDoubleArray>> values;
  for (std::size_t c = 2; c < columns.size(); ++c)
  {
    values.push_back(vtkSmartPointer<vtkDoubleArray>::New());
    values.back()->SetName(columns[c].c_str());
    values.back()->SetNumberOfTuples(n);
  }
  for (vtkIdType r = 0; r < n; ++r)
  {
    const vis4gs::FineTuneFigureRow& row = rows[static_cast<std::size_t>(r)];
    view->SetValue(r, row.View);
    split->SetValue(r, row.Split);
    for (std::size_t k = 0; k < values.size(); ++k)
    {
      values[k]->SetValue(r, row.Values[k]);
    }
  }
  figures->AddColumn(view);
  figures->AddColumn(split);
  for (vtkDoubleArray* column : values)
  {
    figures->AddColumn(column);
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkGaussianFineTuneFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RemovalArrayName: " << this->RemovalArrayName << "\n";
  os << indent << "RemovedIds: "
     << (this->RemovedIds ? std::to_string(this->RemovedIds->GetNumberOfValues()) + " ids"
                          : std::string("(none)"))
     << "\n";
  os << indent << "SourceIteration: " << this->SourceIteration << "\n";
  os << indent << "Iterations: " << this->Iterations << "\n";
  os << indent << "WarmupIterations: " << this->WarmupIterations << "\n";
  os << indent << "FreePositions: " << this->FreePositions << "\n";
  os << indent << "Densify: " << this->Densify << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "OutputLogFileName: " << this->OutputLogFileName << "\n";
  os << indent << "ImageDirectory: " << this->ImageDirectory << "\n";
  os << indent << "Producer: " << this->Producer << "\n";
  os << indent << "SceneName: " << this->SceneName << "\n";
  os << indent << "EmbedImages: " << this->EmbedImages << "\n";
  os << indent << "MetricsInterval: " << this->MetricsInterval << "\n";
  os << indent << "NumberOfRemoved: " << this->NumberOfRemoved << "\n";
  os << indent << "LastIteration: " << this->LastIteration << "\n";
  os << indent << "TrainSeconds: " << this->TrainSeconds << "\n";
  os << indent << "MeasureSeconds: " << this->MeasureSeconds << "\n";
}

/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianFineTuneFilter.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianFineTuneFilter.h"

#include "FineTune.h"
#include "Vis4GSDataModel.h"
#include "Vis4GSTrainingImages.h"

#include "vtkCallbackCommand.h"
#include "vtkDataArray.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
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
#include <exception>
#include <vector>

vtkStandardNewMacro(vtkGaussianFineTuneFilter);

//------------------------------------------------------------------------------
vtkGaussianFineTuneFilter::vtkGaussianFineTuneFilter()
{
  this->SetNumberOfInputPorts(2);
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

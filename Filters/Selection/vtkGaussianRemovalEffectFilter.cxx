/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianRemovalEffectFilter.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianRemovalEffectFilter.h"

#include "RemovalEffect.h"
#include "Vis4GSDataModel.h"
#include "Vis4GSTrainingImages.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTable.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <exception>
#include <tuple>
#include <vector>

vtkStandardNewMacro(vtkGaussianRemovalEffectFilter);
vtkCxxSetObjectMacro(vtkGaussianRemovalEffectFilter, RemovedIds, vtkIdTypeArray);

namespace
{
const char* SplitName(vis4gs::CameraSplit split)
{
  return split == vis4gs::CameraSplit::Train ? "train" : "test";
}

// The six figure columns of both outputs, in before-after.csv's order.
struct FigureColumns
{
  vtkNew<vtkDoubleArray> Columns[6];
  explicit FigureColumns(vtkTable* table)
  {
    const char* names[] = { vis4gs::arrays::RemovalPsnrBefore,
      vis4gs::arrays::RemovalPsnrAfter,
      vis4gs::arrays::RemovalSsimBefore,
      vis4gs::arrays::RemovalSsimAfter,
      vis4gs::arrays::RemovalL1Before,
      vis4gs::arrays::RemovalL1After };
    for (int c = 0; c < 6; ++c)
    {
      this->Columns[c]->SetName(names[c]);
      table->AddColumn(this->Columns[c]);
    }
  }
  void Insert(const vis4gs::ViewMetrics& before, const vis4gs::ViewMetrics& after)
  {
    const double values[] = {
      before.Psnr, after.Psnr, before.Ssim, after.Ssim, before.L1, after.L1
    };
    for (int c = 0; c < 6; ++c)
    {
      this->Columns[c]->InsertNextValue(values[c]);
    }
  }
};
}

// The "before" per tile of the last update and what it was measured for.
struct vtkGaussianRemovalEffectFilter::vtkInternals
{
  vis4gs::RemovalBaseline Baseline;
  using Key = std::tuple<vtkPolyData*,
    vtkMTimeType,
    vtkTable*,
    vtkMTimeType,
    std::string,
    std::array<double, 3>,
    int,
    bool,
    bool>;
  Key For;
  bool Valid = false;
};

//------------------------------------------------------------------------------
vtkGaussianRemovalEffectFilter::vtkGaussianRemovalEffectFilter()
  : Internals(new vtkInternals)
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(2);
}

//------------------------------------------------------------------------------
vtkGaussianRemovalEffectFilter::~vtkGaussianRemovalEffectFilter()
{
  this->SetRemovedIds(nullptr);
  delete this->Internals;
}

//------------------------------------------------------------------------------
vtkMTimeType vtkGaussianRemovalEffectFilter::GetMTime()
{
  const vtkMTimeType own = this->Superclass::GetMTime();
  return this->RemovedIds ? std::max(own, this->RemovedIds->GetMTime()) : own;
}

//------------------------------------------------------------------------------
int vtkGaussianRemovalEffectFilter::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), port == 0 ? "vtkPolyData" : "vtkTable");
  return 1;
}

//------------------------------------------------------------------------------
int vtkGaussianRemovalEffectFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkTable* table = vtkTable::GetData(inputVector[1]);
  vtkTable* views = vtkTable::GetData(outputVector, 0);
  vtkTable* totals = vtkTable::GetData(outputVector, 1);
  this->NumberRemoved = this->NumberKept = 0;
  this->NumberOfViewsRendered = this->NumberOfTilesRendered = 0;
  this->NumberOfTilesOfTiledViews = this->NumberOfViewsWithoutImage = 0;
  this->SecondsBefore = this->SecondsAfter = 0;
  this->BaselineReused = false;

  vis4gs::GaussianCloud cloud;
  std::string error;
  if (!vis4gs::PolyDataToGaussianCloud(input, cloud, &error))
  {
    vtkErrorMacro("The input is not a Gaussian scene: " << error);
    return 0;
  }
  std::vector<std::uint8_t> removed(cloud.Count, 0);
  if (this->RemovedIds)
  {
    std::vector<std::int64_t> ids(static_cast<std::size_t>(this->RemovedIds->GetNumberOfTuples()));
    for (std::size_t i = 0; i < ids.size(); ++i)
    {
      ids[i] = this->RemovedIds->GetValue(static_cast<vtkIdType>(i));
    }
    std::sort(ids.begin(), ids.end());
    for (std::size_t i = 0; i < cloud.Count; ++i)
    {
      removed[i] = std::binary_search(ids.begin(), ids.end(), cloud.GetId(i)) ? 1 : 0;
    }
  }
  else
  {
    vtkDataArray* marks = input->GetPointData()->GetArray(this->RemovalArrayName.c_str());
    if (!marks || marks->GetNumberOfComponents() != 1)
    {
      vtkErrorMacro("The input has no one-component point-data array '"
        << this->RemovalArrayName << "' marking the Gaussians to remove, and no RemovedIds.");
      return 0;
    }
    for (std::size_t i = 0; i < cloud.Count; ++i)
    {
      removed[i] = marks->GetTuple1(static_cast<vtkIdType>(i)) != 0 ? 1 : 0;
    }
  }
  std::vector<vis4gs::Camera> cameras;
  if (!table || !vis4gs::TableToCameras(table, cameras, &error))
  {
    vtkErrorMacro(
      "The camera table (input port 1) is not usable: " << (table ? error : std::string("none")));
    return 0;
  }
  vis4gs::RemovalEffectOptions options;
  options.Raster.Background = { this->Background[0], this->Background[1], this->Background[2] };
  options.Raster.ShDegree = this->SHDegree;
  options.TrainViews = this->TrainViews;
  options.TestViews = this->TestViews;
  options.ReuseTiles = this->ReuseTiles;
  options.Threads = this->Threads;
  vis4gs::TrainingImageProvider images;
  const std::array<float, 3> background = { static_cast<float>(this->Background[0]),
    static_cast<float>(this->Background[1]),
    static_cast<float>(this->Background[2]) };
  if (!Vis4GSTrainingImages(table, this->ImageDirectory, background, cameras, images, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  // The marks array is part of the input: a new selection by marks is a new input, whose
  // "before" is measured again; a selection by RemovedIds keeps it.
  const vtkInternals::Key key{ input,
    input->GetMTime(),
    table,
    table->GetMTime(),
    this->ImageDirectory,
    options.Raster.Background,
    this->SHDegree,
    this->TrainViews,
    this->TestViews };
  vis4gs::RemovalEffect effect;
  double baselineSeconds = 0;
  std::size_t baselineViews = 0;
  try
  {
    if (this->ReuseTiles)
    {
      this->BaselineReused = this->Internals->Valid && this->Internals->For == key &&
        this->Internals->Baseline.Gaussians == cloud.Count;
      if (!this->BaselineReused)
      {
        this->Internals->Valid = false;
        const auto t0 = std::chrono::steady_clock::now();
        this->Internals->Baseline = vis4gs::MeasureRemovalBaseline(cloud, cameras, options, images);
        baselineSeconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        baselineViews = this->Internals->Baseline.MeasuredViews();
        this->Internals->For = key;
        this->Internals->Valid = true;
      }
      options.TileBaseline = this->Internals->Baseline;
    }
    effect = vis4gs::MeasureRemovalEffect(cloud, removed, cameras, options, images);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Measuring the removal failed: " << e.what());
    return 0;
  }
  this->NumberRemoved = static_cast<vtkIdType>(effect.Removed);
  this->NumberKept = static_cast<vtkIdType>(effect.Kept);
  this->NumberOfViewsRendered = static_cast<vtkIdType>(effect.ViewsRendered + baselineViews);
  this->NumberOfTilesRendered = static_cast<vtkIdType>(effect.TilesRendered);
  this->NumberOfTilesOfTiledViews = static_cast<vtkIdType>(effect.TilesOfTiledViews);
  this->NumberOfViewsWithoutImage = static_cast<vtkIdType>(effect.ViewsWithoutImage);
  this->SecondsBefore = effect.SecondsBefore + baselineSeconds;
  this->SecondsAfter = effect.SecondsAfter;

  vtkNew<vtkStringArray> name, split, totalSplit;
  vtkNew<vtkIdTypeArray> camera, affected, totalViews, totalAffected;
  name->SetName(vis4gs::arrays::RemovalView);
  camera->SetName(vis4gs::arrays::RemovalCamera);
  split->SetName(vis4gs::arrays::RemovalSplit);
  affected->SetName(vis4gs::arrays::RemovalAffected);
  views->AddColumn(name);
  views->AddColumn(camera);
  views->AddColumn(split);
  views->AddColumn(affected);
  FigureColumns viewFigures(views);
  for (const vis4gs::RemovalViewEffect& v : effect.Views)
  {
    name->InsertNextValue(v.Name);
    camera->InsertNextValue(static_cast<vtkIdType>(v.CameraIndex));
    split->InsertNextValue(SplitName(v.Split));
    affected->InsertNextValue(v.Affected ? 1 : 0);
    viewFigures.Insert(v.Before, v.After);
  }
  totalSplit->SetName(vis4gs::arrays::RemovalSplit);
  totalViews->SetName(vis4gs::arrays::RemovalViews);
  totalAffected->SetName(vis4gs::arrays::RemovalAffected);
  totals->AddColumn(totalSplit);
  totals->AddColumn(totalViews);
  totals->AddColumn(totalAffected);
  FigureColumns totalFigures(totals);
  for (const auto& [splitValue, t] : { std::make_pair(vis4gs::CameraSplit::Train, &effect.Train),
         std::make_pair(vis4gs::CameraSplit::Test, &effect.Test) })
  {
    totalSplit->InsertNextValue(SplitName(splitValue));
    totalViews->InsertNextValue(static_cast<vtkIdType>(t->Views));
    totalAffected->InsertNextValue(static_cast<vtkIdType>(t->AffectedViews));
    totalFigures.Insert(t->Before, t->After);
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkGaussianRemovalEffectFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RemovalArrayName: " << this->RemovalArrayName << "\n";
  os << indent << "RemovedIds: " << this->RemovedIds << "\n";
  os << indent << "ImageDirectory: " << this->ImageDirectory << "\n";
  os << indent << "TrainViews: " << this->TrainViews << "\n";
  os << indent << "TestViews: " << this->TestViews << "\n";
  os << indent << "Background: " << this->Background[0] << " " << this->Background[1] << " "
     << this->Background[2] << "\n";
  os << indent << "SHDegree: " << this->SHDegree << "\n";
  os << indent << "ReuseTiles: " << this->ReuseTiles << "\n";
  os << indent << "Threads: " << this->Threads << "\n";
  os << indent << "NumberRemoved: " << this->NumberRemoved << "\n";
  os << indent << "NumberKept: " << this->NumberKept << "\n";
  os << indent << "NumberOfViewsRendered: " << this->NumberOfViewsRendered << "\n";
  os << indent << "NumberOfTilesRendered: " << this->NumberOfTilesRendered << "\n";
  os << indent << "NumberOfTilesOfTiledViews: " << this->NumberOfTilesOfTiledViews << "\n";
  os << indent << "NumberOfViewsWithoutImage: " << this->NumberOfViewsWithoutImage << "\n";
  os << indent << "SecondsBefore: " << this->SecondsBefore << "\n";
  os << indent << "SecondsAfter: " << this->SecondsAfter << "\n";
  os << indent << "BaselineReused: " << this->BaselineReused << "\n";
}

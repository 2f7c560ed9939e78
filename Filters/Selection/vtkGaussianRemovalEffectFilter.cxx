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
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
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
#include <cmath>
#include <exception>
#include <memory>
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
const char* const FigureNames[6] = { vis4gs::arrays::RemovalPsnrBefore,
  vis4gs::arrays::RemovalPsnrAfter,
  vis4gs::arrays::RemovalSsimBefore,
  vis4gs::arrays::RemovalSsimAfter,
  vis4gs::arrays::RemovalL1Before,
  vis4gs::arrays::RemovalL1After };

// The six figure columns of @p table, or false.
bool FiguresOf(vtkTable* table, vtkDoubleArray* columns[6])
{
  for (int c = 0; c < 6; ++c)
  {
    columns[c] =
      table ? vtkDoubleArray::SafeDownCast(table->GetColumnByName(FigureNames[c])) : nullptr;
    if (!columns[c])
    {
      return false;
    }
  }
  return true;
}

// Row @p r's figures before (@p after false) or after.
vis4gs::ViewMetrics MetricsOf(vtkDoubleArray* const columns[6], vtkIdType r, bool after)
{
  const int k = after ? 1 : 0;
  vis4gs::ViewMetrics m;
  m.Psnr = columns[k]->GetValue(r);
  m.Ssim = columns[2 + k]->GetValue(r);
  m.L1 = columns[4 + k]->GetValue(r);
  return m;
}

template <class T>
T* Column(vtkTable* table, const char* name)
{
  return table ? T::SafeDownCast(table->GetColumnByName(name)) : nullptr;
}

struct FigureColumns
{
  vtkNew<vtkDoubleArray> Columns[6];
  explicit FigureColumns(vtkTable* table)
  {
    for (int c = 0; c < 6; ++c)
    {
      this->Columns[c]->SetName(FigureNames[c]);
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

// Renders the "before" of the wanted views with an image that @p baseline lacks (the score pass
// keeps only the training views it renders). Returns the number of views rendered.
std::size_t CompleteBaseline(vis4gs::RemovalBaseline& baseline,
  const vis4gs::GaussianCloud& cloud,
  const std::vector<vis4gs::Camera>& cameras,
  const vis4gs::RemovalEffectOptions& options,
  const vis4gs::TrainingImageProvider& images)
{
  std::vector<std::size_t> missing;
  std::vector<vis4gs::Camera> subset;
  for (std::size_t v = 0; v < cameras.size(); ++v)
  {
    if (baseline.Views[v].Empty())
    {
      missing.push_back(v);
      subset.push_back(cameras[v]);
    }
  }
  if (missing.empty())
  {
    return 0;
  }
  vis4gs::RemovalBaseline part = vis4gs::MeasureRemovalBaseline(cloud,
    subset,
    options,
    [&images, &missing](std::size_t i, const vis4gs::Camera& camera, vis4gs::Image& image)
    { return images(missing[i], camera, image); });
  std::size_t rendered = 0;
  for (std::size_t i = 0; i < missing.size(); ++i)
  {
    if (!part.Views[i].Empty())
    {
      baseline.Views[missing[i]] = std::move(part.Views[i]);
      ++rendered;
    }
  }
  return rendered;
}

// @p image (rows top first) into @p out's point-data array @p name, rows bottom first.
void AddImage(const vis4gs::Image& image, const char* name, vtkImageData* out)
{
  vtkNew<vtkFloatArray> pixels;
  pixels->SetName(name);
  pixels->SetNumberOfComponents(3);
  pixels->SetNumberOfTuples(static_cast<vtkIdType>(image.Width) * image.Height);
  float* to = pixels->GetPointer(0);
  for (int y = 0; y < image.Height; ++y)
  {
    const float* row =
      image.Pixels.data() + static_cast<std::size_t>(image.Height - 1 - y) * image.Width * 3;
    std::copy(row,
      row + static_cast<std::size_t>(image.Width) * 3,
      to + static_cast<std::size_t>(y) * image.Width * 3);
  }
  out->GetPointData()->AddArray(pixels);
}
}

// The "before" per tile of the last update and what it was measured for, and the tables of the
// last measurement (kept when only PreviewView changes).
struct vtkGaussianRemovalEffectFilter::vtkInternals
{
  std::shared_ptr<const vis4gs::RemovalBaseline> Given;
  std::shared_ptr<const vis4gs::RemovalBaseline> Baseline;
  using Key = std::tuple<vtkPolyData*,
    vtkMTimeType,
    vtkTable*,
    vtkMTimeType,
    std::string,
    std::array<double, 3>,
    int,
    bool,
    bool,
    const vis4gs::RemovalBaseline*>;
  Key For;
  bool Valid = false;
  struct Measurement
  {
    Key For;
    std::vector<std::uint8_t> Removed;
    bool ReuseTiles = true;
    vtkNew<vtkTable> Views, Totals;
    vtkIdType Counts[8] = {};
    double Seconds[2] = {};
    bool BaselineReused = false;
    bool Valid = false;
  } Last;
};

//------------------------------------------------------------------------------
vtkGaussianRemovalEffectFilter::vtkGaussianRemovalEffectFilter()
  : Internals(new vtkInternals)
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(3);
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
void vtkGaussianRemovalEffectFilter::SetBaseline(
  std::shared_ptr<const vis4gs::RemovalBaseline> baseline)
{
  if (baseline != this->Internals->Given)
  {
    this->Internals->Given = std::move(baseline);
    this->Modified();
  }
}

std::shared_ptr<const vis4gs::RemovalBaseline> vtkGaussianRemovalEffectFilter::GetBaseline() const
{
  return this->Internals->Given;
}

std::shared_ptr<const vis4gs::RemovalBaseline> vtkGaussianRemovalEffectFilter::GetMeasuredBaseline()
  const
{
  return this->ReuseTiles && this->Internals->Valid ? this->Internals->Baseline : nullptr;
}

//------------------------------------------------------------------------------
vtkImageData* vtkGaussianRemovalEffectFilter::GetPreviewOutput()
{
  return vtkImageData::SafeDownCast(this->GetOutputDataObject(2));
}

//------------------------------------------------------------------------------
int vtkGaussianRemovalEffectFilter::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), port == 0 ? "vtkPolyData" : "vtkTable");
  return 1;
}

//------------------------------------------------------------------------------
int vtkGaussianRemovalEffectFilter::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 2 ? "vtkImageData" : "vtkTable");
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
  vtkImageData* preview = vtkImageData::GetData(outputVector, 2);
  this->NumberRemoved = this->NumberKept = 0;
  this->NumberOfViewsRendered = this->NumberOfTilesRendered = 0;
  this->NumberOfTilesOfTiledViews = this->NumberOfViewsWithoutImage = 0;
  this->NumberOfBaselineViewsReused = this->NumberOfBaselineViewsRendered = 0;
  this->SecondsBefore = this->SecondsAfter = 0;
  this->BaselineReused = false;
  vtkInternals& d = *this->Internals;

  std::string error;
  // The scene's own arrays when they are one (no copy of the Gaussians).
  const std::shared_ptr<const vis4gs::GaussianCloud> shared =
    vis4gs::GaussianCloudOf(input, &error);
  if (!shared)
  {
    vtkErrorMacro("The input is not a Gaussian scene: " << error);
    return 0;
  }
  const vis4gs::GaussianCloud& cloud = *shared;
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
  if (this->PreviewView >= static_cast<vtkIdType>(cameras.size()))
  {
    vtkErrorMacro("PreviewView " << this->PreviewView << " is not a camera of the table (it has "
                                 << cameras.size() << ").");
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
    this->TestViews,
    d.Given.get() };
  // Measures the removal into the tables, the "before" per tile kept for the next update.
  auto measure = [&]() -> bool
  {
    // (An empty one is none: the score pass leaves it so when it renders no view in full.)
    const vis4gs::RemovalBaseline* given =
      this->ReuseTiles && d.Given && !d.Given->Views.empty() ? d.Given.get() : nullptr;
    // (Other rasteriser settings are refused by MeasureRemovalEffect, naming them.)
    if (given && (given->Views.size() != cameras.size() || given->Gaussians != cloud.Count))
    {
      vtkErrorMacro("The given \"before\" (SetBaseline) is not of this input: it holds "
        << given->Views.size() << " views of " << given->Gaussians << " Gaussians, the input has "
        << cameras.size() << " cameras and " << cloud.Count << " Gaussians.");
      return false;
    }
    vis4gs::RemovalEffect effect;
    double baselineSeconds = 0;
    std::size_t baselineViews = 0;
    try
    {
      if (this->ReuseTiles)
      {
        this->BaselineReused =
          d.Valid && d.For == key && d.Baseline && d.Baseline->Gaussians == cloud.Count;
        if (!this->BaselineReused)
        {
          d.Valid = false;
          const auto t0 = std::chrono::steady_clock::now();
          auto made = std::make_shared<vis4gs::RemovalBaseline>();
          if (given)
          {
            *made = *given;
            this->NumberOfBaselineViewsReused = static_cast<vtkIdType>(given->MeasuredViews());
            baselineViews = CompleteBaseline(*made, cloud, cameras, options, images);
          }
          else
          {
            *made = vis4gs::MeasureRemovalBaseline(cloud, cameras, options, images);
            baselineViews = made->MeasuredViews();
          }
          baselineSeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          d.Baseline = std::move(made);
          d.For = key;
          d.Valid = true;
        }
        else
        {
          this->NumberOfBaselineViewsReused = static_cast<vtkIdType>(d.Baseline->MeasuredViews());
        }
        options.TileBaseline = *d.Baseline;
      }
      effect = vis4gs::MeasureRemovalEffect(cloud, removed, cameras, options, images);
    }
    catch (const std::exception& e)
    {
      vtkErrorMacro("Measuring the removal failed: " << e.what());
      return false;
    }
    this->NumberRemoved = static_cast<vtkIdType>(effect.Removed);
    this->NumberKept = static_cast<vtkIdType>(effect.Kept);
    this->NumberOfBaselineViewsRendered = static_cast<vtkIdType>(baselineViews);
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
    return true;
  };
  vtkInternals::Measurement& last = d.Last;
  vtkIdType* counts[8] = { &this->NumberRemoved,
    &this->NumberKept,
    &this->NumberOfViewsRendered,
    &this->NumberOfTilesRendered,
    &this->NumberOfTilesOfTiledViews,
    &this->NumberOfViewsWithoutImage,
    &this->NumberOfBaselineViewsReused,
    &this->NumberOfBaselineViewsRendered };
  if (last.Valid && last.For == key && last.ReuseTiles == this->ReuseTiles &&
    last.Removed == removed)
  {
    // Only PreviewView (or a setting the figures do not depend on) changed.
    views->ShallowCopy(last.Views);
    totals->ShallowCopy(last.Totals);
    for (int k = 0; k < 8; ++k)
    {
      *counts[k] = last.Counts[k];
    }
    this->SecondsBefore = last.Seconds[0];
    this->SecondsAfter = last.Seconds[1];
    this->BaselineReused = last.BaselineReused;
  }
  else
  {
    last.Valid = false;
    if (!measure())
    {
      return 0;
    }
    last.For = key;
    last.Removed = std::move(removed);
    last.ReuseTiles = this->ReuseTiles;
    last.Views->ShallowCopy(views);
    last.Totals->ShallowCopy(totals);
    for (int k = 0; k < 8; ++k)
    {
      last.Counts[k] = *counts[k];
    }
    last.Seconds[0] = this->SecondsBefore;
    last.Seconds[1] = this->SecondsAfter;
    last.BaselineReused = this->BaselineReused;
    last.Valid = true;
  }

  if (this->PreviewView >= 0)
  {
    // The renders the figures are measured on (RemovalEffect.h: clamped, the same settings).
    const vis4gs::Camera& camera = cameras[static_cast<std::size_t>(this->PreviewView)];
    vis4gs::RasterSettings raster = options.Raster;
    raster.Threads = this->Threads;
    const vis4gs::Image before =
      vis4gs::ClampedImage(vis4gs::Rasterize<float>(cloud, camera, raster));
    const vis4gs::Image after = vis4gs::ClampedImage(
      vis4gs::Rasterize<float>(vis4gs::RemoveGaussians(cloud, last.Removed), camera, raster));
    preview->SetDimensions(before.Width, before.Height, 1);
    AddImage(before, GetPreviewBeforeArrayName(), preview);
    AddImage(after, GetPreviewAfterArrayName(), preview);
    vtkNew<vtkIdTypeArray> index;
    index->SetName(vis4gs::arrays::RemovalCamera);
    index->InsertNextValue(this->PreviewView);
    vtkNew<vtkStringArray> name;
    name->SetName(vis4gs::arrays::RemovalView);
    name->InsertNextValue(camera.Name);
    preview->GetFieldData()->AddArray(index);
    preview->GetFieldData()->AddArray(name);
  }
  return 1;
}

//------------------------------------------------------------------------------
bool vtkGaussianRemovalEffectFilter::PreviewImage(vtkImageData* preview,
  bool before,
  vis4gs::Image& image)
{
  image = vis4gs::Image();
  auto* pixels = preview ? vtkFloatArray::SafeDownCast(preview->GetPointData()->GetArray(
                             before ? GetPreviewBeforeArrayName() : GetPreviewAfterArrayName()))
                         : nullptr;
  if (!pixels || pixels->GetNumberOfComponents() != 3)
  {
    return false;
  }
  int dims[3];
  preview->GetDimensions(dims);
  image.Width = dims[0];
  image.Height = dims[1];
  image.Channels = 3;
  const std::size_t row = static_cast<std::size_t>(image.Width) * 3;
  image.Pixels.resize(row * static_cast<std::size_t>(image.Height));
  for (int y = 0; y < image.Height; ++y)
  {
    const float* from =
      pixels->GetPointer(0) + static_cast<std::size_t>(image.Height - 1 - y) * row;
    std::copy(from, from + row, image.Pixels.data() + static_cast<std::size_t>(y) * row);
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkGaussianRemovalEffectFilter::ViewsOfTable(vtkTable* views,
  std::vector<vis4gs::RemovalViewEffect>& rows,
  std::string* error)
{
  rows.clear();
  auto* name = Column<vtkStringArray>(views, vis4gs::arrays::RemovalView);
  auto* camera = Column<vtkIdTypeArray>(views, vis4gs::arrays::RemovalCamera);
  auto* split = Column<vtkStringArray>(views, vis4gs::arrays::RemovalSplit);
  auto* affected = Column<vtkIdTypeArray>(views, vis4gs::arrays::RemovalAffected);
  vtkDoubleArray* figures[6];
  if (!name || !camera || !split || !affected || !FiguresOf(views, figures))
  {
    if (error)
    {
      *error = "not a removal effect table (its columns are view, camera, split, affected and "
               "the figures before and after)";
    }
    return false;
  }
  for (vtkIdType r = 0; r < views->GetNumberOfRows(); ++r)
  {
    vis4gs::RemovalViewEffect e;
    e.CameraIndex = static_cast<std::size_t>(camera->GetValue(r));
    e.Name = name->GetValue(r);
    e.Split = split->GetValue(r) == "test" ? vis4gs::CameraSplit::Test : vis4gs::CameraSplit::Train;
    e.Affected = affected->GetValue(r) != 0;
    e.Before = MetricsOf(figures, r, false);
    e.After = MetricsOf(figures, r, true);
    e.HasImage = !std::isnan(e.Before.Psnr); // (RemovalEffect.cxx: NaN figures without one)
    rows.push_back(std::move(e));
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkGaussianRemovalEffectFilter::GetEffect(vis4gs::RemovalEffect& effect, std::string* error)
{
  effect = vis4gs::RemovalEffect();
  vtkTable* totals = vtkTable::SafeDownCast(this->GetOutputDataObject(1));
  auto* totalViews = Column<vtkIdTypeArray>(totals, vis4gs::arrays::RemovalViews);
  auto* totalAffected = Column<vtkIdTypeArray>(totals, vis4gs::arrays::RemovalAffected);
  vtkDoubleArray* figures[6];
  if (!ViewsOfTable(vtkTable::SafeDownCast(this->GetOutputDataObject(0)), effect.Views, error) ||
    !totalViews || !totalAffected || !FiguresOf(totals, figures) || totals->GetNumberOfRows() != 2)
  {
    if (error)
    {
      *error = "the removal effect has not been measured";
    }
    return false;
  }
  for (vtkIdType r = 0; r < 2; ++r)
  {
    vis4gs::RemovalTotals& total = r == 0 ? effect.Train : effect.Test;
    total.Views = static_cast<std::size_t>(totalViews->GetValue(r));
    total.AffectedViews = static_cast<std::size_t>(totalAffected->GetValue(r));
    total.Before = MetricsOf(figures, r, false);
    total.After = MetricsOf(figures, r, true);
  }
  effect.Removed = static_cast<std::size_t>(this->NumberRemoved);
  effect.Kept = static_cast<std::size_t>(this->NumberKept);
  effect.ViewsRendered =
    static_cast<std::size_t>(this->NumberOfViewsRendered - this->NumberOfBaselineViewsRendered);
  effect.TilesRendered = static_cast<std::size_t>(this->NumberOfTilesRendered);
  effect.TilesOfTiledViews = static_cast<std::size_t>(this->NumberOfTilesOfTiledViews);
  effect.ViewsWithoutImage = static_cast<std::size_t>(this->NumberOfViewsWithoutImage);
  effect.SecondsBefore = this->SecondsBefore;
  effect.SecondsAfter = this->SecondsAfter;
  return true;
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
  os << indent << "PreviewView: " << this->PreviewView << "\n";
  os << indent << "Baseline: "
     << (this->Internals->Given ? std::to_string(this->Internals->Given->MeasuredViews()) + " views"
                                : std::string("(none)"))
     << "\n";
  os << indent << "NumberRemoved: " << this->NumberRemoved << "\n";
  os << indent << "NumberKept: " << this->NumberKept << "\n";
  os << indent << "NumberOfViewsRendered: " << this->NumberOfViewsRendered << "\n";
  os << indent << "NumberOfTilesRendered: " << this->NumberOfTilesRendered << "\n";
  os << indent << "NumberOfTilesOfTiledViews: " << this->NumberOfTilesOfTiledViews << "\n";
  os << indent << "NumberOfViewsWithoutImage: " << this->NumberOfViewsWithoutImage << "\n";
  os << indent << "SecondsBefore: " << this->SecondsBefore << "\n";
  os << indent << "SecondsAfter: " << this->SecondsAfter << "\n";
  os << indent << "NumberOfBaselineViewsReused: " << this->NumberOfBaselineViewsReused << "\n";
  os << indent << "NumberOfBaselineViewsRendered: " << this->NumberOfBaselineViewsRendered << "\n";
  os << indent << "BaselineReused: " << this->BaselineReused << "\n";
}

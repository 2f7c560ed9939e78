/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianTrainingLogReader.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianTrainingLogReader.h"

#include "GaussianMath.h"
#include "TrainingLogReader.h"
#include "Vis4GSDataModel.h"
#include "Vis4GSLineageBreaks.h"
#include "Vis4GSRequestedPort.h"

#include "vtkDemandDrivenPipeline.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

class vtkGaussianTrainingLogReader::vtkInternals
{
public:
  std::unique_ptr<vis4gs::TrainingLogReader> Log;
  std::string OpenedName;
  bool OpenedRepair = false;
  std::vector<int> Iterations;
  std::vector<std::string> Lacks;
  std::vector<std::string> Repairs;
  vis4gs::TrainingLogHeader Header;
  bool HasCameras = false;
  bool HasMetrics = false;
  bool HasEvents = false;
  bool HasImages = false;
  std::vector<std::string> ImageNames;
};

vtkStandardNewMacro(vtkGaussianTrainingLogReader);

namespace
{
template <typename ArrayT, typename T>
vtkSmartPointer<ArrayT> MakeColumn(const char* name,
  const std::vector<T>& values,
  int components = 1)
{
  auto array = vtkSmartPointer<ArrayT>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size() / components));
  std::copy(values.begin(), values.end(), array->GetPointer(0));
  return array;
}

/// The measured columns of a metrics row, in the log's order (the merged table's Test* too).
const char* const MeasuredColumns[6] = { vis4gs::arrays::MetricLoss,
  vis4gs::arrays::MetricL1,
  vis4gs::arrays::MetricPSNR,
  vis4gs::arrays::MetricSSIM,
  vis4gs::arrays::MetricLPIPS,
  vis4gs::arrays::MetricElapsed };

/// The metrics port for the timeline: one row per iteration, the test columns Test*.
void MergedMetrics(const vis4gs::MetricsTable& train,
  const vis4gs::MetricsTable& test,
  vtkTable* output)
{
  // One row per iteration: the train rows in order, then test-only iterations, sorted.
  std::map<int, std::size_t> testRow;
  for (std::size_t i = 0; i < test.Size(); ++i)
  {
    testRow.emplace(test.Iteration[i], i);
  }
  struct Row
  {
    int Iteration;
    long long Train; // row in train or -1
    long long Test;  // row in test or -1
  };
  std::vector<Row> rows;
  std::map<int, bool> trainHas;
  for (std::size_t i = 0; i < train.Size(); ++i)
  {
    auto t = testRow.find(train.Iteration[i]);
    const bool first = trainHas.emplace(train.Iteration[i], true).second;
    rows.push_back({ train.Iteration[i],
      static_cast<long long>(i),
      t != testRow.end() && first ? static_cast<long long>(t->second) : -1 });
  }
  for (const auto& t : testRow)
  {
    if (!trainHas.count(t.first))
    {
      rows.push_back({ t.first, -1, static_cast<long long>(t.second) });
    }
  }
  std::stable_sort(
    rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.Iteration < b.Iteration; });
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<int> iterations;
  std::vector<vtkIdType> counts;
  std::vector<double> columns[11];
  for (const Row& r : rows)
  {
    iterations.push_back(r.Iteration);
    counts.push_back(r.Train >= 0 ? train.NumGaussians[static_cast<std::size_t>(r.Train)]
                                  : test.NumGaussians[static_cast<std::size_t>(r.Test)]);
    if (r.Train >= 0)
    {
      const std::size_t i = static_cast<std::size_t>(r.Train);
      const double v[6] = { train.Loss[i],
        train.L1[i],
        train.Psnr[i],
        train.Ssim[i],
        train.Lpips[i],
        train.ElapsedSeconds[i] };
      for (int c = 0; c < 6; ++c)
      {
        columns[c].push_back(v[c]);
      }
    }
    else
    {
      for (int c = 0; c < 6; ++c)
      {
        columns[c].push_back(c == 5 ? test.ElapsedSeconds[static_cast<std::size_t>(r.Test)] : nan);
      }
    }
    if (r.Test >= 0)
    {
      const std::size_t i = static_cast<std::size_t>(r.Test);
      const double v[5] = { test.Loss[i], test.L1[i], test.Psnr[i], test.Ssim[i], test.Lpips[i] };
      for (int c = 0; c < 5; ++c)
      {
        columns[6 + c].push_back(v[c]);
      }
    }
    else
    {
      for (int c = 0; c < 5; ++c)
      {
        columns[6 + c].push_back(nan);
      }
    }
  }
  namespace names = vis4gs::arrays;
  output->AddColumn(MakeColumn<vtkIntArray>(names::MetricIteration, iterations));
  output->AddColumn(MakeColumn<vtkIdTypeArray>(names::MetricGaussians, counts));
  for (int c = 0; c < 11; ++c)
  {
    const std::string name = c < 6 ? std::string(MeasuredColumns[c])
                                   : std::string(names::MetricTestPrefix) + MeasuredColumns[c - 6];
    output->AddColumn(MakeColumn<vtkDoubleArray>(name.c_str(), columns[c]));
  }
}

/// The metrics port as the log holds it (MetricsAsLogged): the train rows, then the test rows.
void LoggedMetrics(const vis4gs::MetricsTable& train,
  const vis4gs::MetricsTable& test,
  vtkTable* output)
{
  std::vector<int> iterations;
  std::vector<vtkIdType> counts;
  std::vector<int> split;
  std::vector<double> columns[6];
  for (const vis4gs::MetricsTable* table : { &train, &test })
  {
    for (std::size_t i = 0; i < table->Size(); ++i)
    {
      iterations.push_back(table->Iteration[i]);
      counts.push_back(static_cast<vtkIdType>(table->NumGaussians[i]));
      split.push_back(table == &test ? 1 : 0);
      const double v[6] = { table->Loss[i],
        table->L1[i],
        table->Psnr[i],
        table->Ssim[i],
        table->Lpips[i],
        table->ElapsedSeconds[i] };
      for (int c = 0; c < 6; ++c)
      {
        columns[c].push_back(v[c]);
      }
    }
  }
  namespace names = vis4gs::arrays;
  output->AddColumn(MakeColumn<vtkIntArray>(names::MetricIteration, iterations));
  output->AddColumn(MakeColumn<vtkIdTypeArray>(names::MetricGaussians, counts));
  for (int c = 0; c < 6; ++c)
  {
    output->AddColumn(MakeColumn<vtkDoubleArray>(MeasuredColumns[c], columns[c]));
  }
  output->AddColumn(MakeColumn<vtkIntArray>(names::CameraSplit, split));
}
} // namespace

//------------------------------------------------------------------------------
vtkGaussianTrainingLogReader::vtkGaussianTrainingLogReader()
  : Internals(new vtkInternals)
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(4);
}

//------------------------------------------------------------------------------
vtkGaussianTrainingLogReader::~vtkGaussianTrainingLogReader()
{
  this->SetFileName(nullptr);
  delete this->Internals;
}

//------------------------------------------------------------------------------
void vtkGaussianTrainingLogReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "Iteration: " << this->Iteration << "\n";
  os << indent << "LoadSHRest: " << this->LoadSHRest << "\n";
  os << indent << "LoadScales: " << this->LoadScales << "\n";
  os << indent << "LoadRotations: " << this->LoadRotations << "\n";
  os << indent << "LoadOpacities: " << this->LoadOpacities << "\n";
  os << indent << "LoadSH: " << this->LoadSH << "\n";
  os << indent << "LoadStatistics: " << this->LoadStatistics << "\n";
  os << indent << "MetricsAsLogged: " << this->MetricsAsLogged << "\n";
  os << indent << "Repair: " << this->Repair << "\n";
  os << indent << "LoadedIteration: " << this->LoadedIteration << "\n";
  os << indent << "SnapshotReads: " << this->SnapshotReads << "\n";
  const vtkInternals& d = *this->Internals;
  os << indent << "Producer: " << d.Header.Producer << "\n";
  os << indent << "SceneName: " << d.Header.Scene << "\n";
  os << indent << "PlannedIterations: " << d.Header.Iterations << "\n";
  os << indent << "TrainerSHDegree: " << d.Header.ShDegree << "\n";
  os << indent << "HasCameras: " << d.HasCameras << "\n";
  os << indent << "HasMetrics: " << d.HasMetrics << "\n";
  os << indent << "HasEvents: " << d.HasEvents << "\n";
  os << indent << "HasImages: " << d.HasImages << "\n";
  os << indent << "NumberOfEmbeddedImages: " << d.ImageNames.size() << "\n";
  os << indent << "NumberOfSnapshots: " << d.Iterations.size() << "\n";
  os << indent << "NumberOfLacks: " << d.Lacks.size() << "\n";
  os << indent << "NumberOfRepairs: " << d.Repairs.size() << "\n";
}

//------------------------------------------------------------------------------
int vtkGaussianTrainingLogReader::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkPolyData" : "vtkTable");
  return 1;
}

//------------------------------------------------------------------------------
vtkPolyData* vtkGaussianTrainingLogReader::GetGaussiansOutput()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(0));
}
vtkTable* vtkGaussianTrainingLogReader::GetCamerasOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(1));
}
vtkTable* vtkGaussianTrainingLogReader::GetMetricsOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(2));
}
vtkTable* vtkGaussianTrainingLogReader::GetEventsOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(3));
}

//------------------------------------------------------------------------------
int vtkGaussianTrainingLogReader::GetNumberOfSnapshots()
{
  return static_cast<int>(this->Internals->Iterations.size());
}
int vtkGaussianTrainingLogReader::GetSnapshotIteration(int i)
{
  const auto& its = this->Internals->Iterations;
  return i >= 0 && i < static_cast<int>(its.size()) ? its[static_cast<std::size_t>(i)] : -1;
}
int vtkGaussianTrainingLogReader::FindNearestSnapshot(int iteration)
{
  this->ReopenClosedFile();
  return this->Internals->Log ? this->Internals->Log->FindNearestSnapshot(iteration) : -1;
}
vtkIdType vtkGaussianTrainingLogReader::GetSnapshotSize(int iteration)
{
  this->ReopenClosedFile();
  const auto& its = this->Internals->Iterations;
  if (!this->Internals->Log || !std::binary_search(its.begin(), its.end(), iteration))
  {
    return 0;
  }
  return static_cast<vtkIdType>(this->Internals->Log->GetSnapshotSize(iteration));
}
int vtkGaussianTrainingLogReader::GetNumberOfLacks()
{
  return static_cast<int>(this->Internals->Lacks.size());
}
const char* vtkGaussianTrainingLogReader::GetLack(int i)
{
  const auto& v = this->Internals->Lacks;
  return i >= 0 && i < static_cast<int>(v.size()) ? v[static_cast<std::size_t>(i)].c_str()
                                                  : nullptr;
}
int vtkGaussianTrainingLogReader::GetNumberOfRepairs()
{
  return static_cast<int>(this->Internals->Repairs.size());
}
const char* vtkGaussianTrainingLogReader::GetRepair(int i)
{
  const auto& v = this->Internals->Repairs;
  return i >= 0 && i < static_cast<int>(v.size()) ? v[static_cast<std::size_t>(i)].c_str()
                                                  : nullptr;
}

//------------------------------------------------------------------------------
const char* vtkGaussianTrainingLogReader::GetProducer()
{
  return this->Internals->Header.Producer.c_str();
}
const char* vtkGaussianTrainingLogReader::GetSceneName()
{
  return this->Internals->Header.Scene.c_str();
}
int vtkGaussianTrainingLogReader::GetPlannedIterations()
{
  return this->Internals->Header.Iterations;
}
int vtkGaussianTrainingLogReader::GetTrainerSHDegree()
{
  return this->Internals->Header.ShDegree;
}
bool vtkGaussianTrainingLogReader::HasCameras()
{
  return this->Internals->HasCameras;
}
bool vtkGaussianTrainingLogReader::HasMetrics()
{
  return this->Internals->HasMetrics;
}
bool vtkGaussianTrainingLogReader::HasEvents()
{
  return this->Internals->HasEvents;
}
bool vtkGaussianTrainingLogReader::HasImages()
{
  return this->Internals->HasImages;
}
int vtkGaussianTrainingLogReader::GetNumberOfEmbeddedImages()
{
  return static_cast<int>(this->Internals->ImageNames.size());
}
const char* vtkGaussianTrainingLogReader::GetEmbeddedImageName(int i)
{
  const auto& v = this->Internals->ImageNames;
  return i >= 0 && i < static_cast<int>(v.size()) ? v[static_cast<std::size_t>(i)].c_str()
                                                  : nullptr;
}

//------------------------------------------------------------------------------
void vtkGaussianTrainingLogReader::CloseFile()
{
  this->Internals->Log.reset();
}

void vtkGaussianTrainingLogReader::ReopenClosedFile()
{
  if (!this->Internals->Log && !this->Internals->OpenedName.empty())
  {
    this->OpenLog();
  }
}

//------------------------------------------------------------------------------
bool vtkGaussianTrainingLogReader::OpenLog()
{
  vtkInternals& d = *this->Internals;
  if (!this->FileName || !*this->FileName)
  {
    vtkErrorMacro(<< "No FileName set.");
    return false;
  }
  try
  {
    // Reopened at each RequestInformation: a log still being written shows its new snapshots.
    vis4gs::TrainingLogReaderOptions options;
    options.Repair = this->Repair;
    // Closed first: a second open of a file this process has open shares the first one's
    // metadata cache, and so would not see what a running writer added since.
    d.Log.reset();
    d.Log.reset(new vis4gs::TrainingLogReader(this->FileName, options));
    d.OpenedName = this->FileName;
    d.OpenedRepair = this->Repair;
    d.Iterations = d.Log->GetSnapshotIterations();
    d.Lacks = d.Log->GetLacks();
    d.Repairs = d.Log->GetRepairs();
    d.Header = d.Log->GetHeader();
    d.HasCameras = d.Log->HasCameras();
    d.HasMetrics = d.Log->HasMetrics();
    d.HasEvents = d.Log->HasEvents();
    d.HasImages = d.Log->HasImages();
    d.ImageNames = d.Log->GetImageNames();
  }
  catch (const std::exception& e)
  {
    d.Log.reset();
    d.Iterations.clear();
    d.Lacks.clear();
    d.Repairs.clear();
    d.Header = vis4gs::TrainingLogHeader();
    d.HasCameras = d.HasMetrics = d.HasEvents = d.HasImages = false;
    d.ImageNames.clear();
    vtkErrorMacro(<< e.what());
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
vtkTypeBool vtkGaussianTrainingLogReader::ProcessRequest(vtkInformation* request,
  vtkInformationVector** inInfo,
  vtkInformationVector* outInfo)
{
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_INFORMATION()))
  {
    return this->RequestInformation(request, outInfo);
  }
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA_NOT_GENERATED()))
  {
    // Only the requested output is produced; the others keep their data and stay out of date.
    vis4gs::MarkOtherPortsNotGenerated(request, outInfo);
    return 1;
  }
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA()))
  {
    return this->RequestData(request, outInfo);
  }
  return this->Superclass::ProcessRequest(request, inInfo, outInfo);
}

//------------------------------------------------------------------------------
int vtkGaussianTrainingLogReader::RequestInformation(vtkInformation* vtkNotUsed(request),
  vtkInformationVector* outInfo)
{
  if (!this->OpenLog())
  {
    return 0;
  }
  const std::vector<int>& its = this->Internals->Iterations;
  vtkInformation* info = outInfo->GetInformationObject(0);
  if (its.empty())
  {
    info->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    info->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
    return 1;
  }
  std::vector<double> steps(its.begin(), its.end());
  info->Set(
    vtkStreamingDemandDrivenPipeline::TIME_STEPS(), steps.data(), static_cast<int>(steps.size()));
  double range[2] = { steps.front(), steps.back() };
  info->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  return 1;
}

//------------------------------------------------------------------------------
int vtkGaussianTrainingLogReader::RequestData(vtkInformation* request,
  vtkInformationVector* outInfo)
{
  vtkInternals& d = *this->Internals;
  if ((!d.Log || d.OpenedName != (this->FileName ? this->FileName : "") ||
        d.OpenedRepair != this->Repair) &&
    !this->OpenLog())
  {
    return 0;
  }
  const int port = vis4gs::RequestedOutputPort(request);
  auto wanted = [port](int p) { return port < 0 || port == p; };
  try
  {
    if (wanted(0))
    {
      vtkInformation* info = outInfo->GetInformationObject(0);
      vtkPolyData* output = vtkPolyData::GetData(info);
      double requested = this->Iteration;
      if (info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
      {
        requested = info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
      }
      else if (this->Iteration < 0 && !d.Iterations.empty())
      {
        requested = d.Iterations.back();
      }
      const int iteration = d.Log->FindNearestSnapshot(
        static_cast<int>(std::lround(std::max(-1e9, std::min(1e9, requested)))));
      output->Initialize();
      this->LoadedIteration = iteration;
      if (iteration >= 0)
      {
        vis4gs::SnapshotReadOptions options;
        options.Arrays = vis4gs::SnapshotIds | vis4gs::SnapshotPositions;
        options.Arrays |= this->LoadScales ? vis4gs::SnapshotLogScales : 0u;
        options.Arrays |= this->LoadRotations ? vis4gs::SnapshotRotations : 0u;
        options.Arrays |= this->LoadOpacities ? vis4gs::SnapshotOpacityLogits : 0u;
        options.Arrays |= this->LoadSH ? vis4gs::SnapshotSH : 0u;
        options.Arrays |=
          this->LoadStatistics ? vis4gs::SnapshotGradAccum | vis4gs::SnapshotDenom : 0u;
        options.ShDegree = this->LoadSHRest ? -1 : 0;
        vis4gs::GaussianCloud cloud = d.Log->ReadSnapshot(iteration, options);
        ++this->SnapshotReads;
        vis4gs::GaussianCloudToPolyData(std::move(cloud), output); // no copy
        output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), iteration);
      }
    }
    if (wanted(1))
    {
      vtkTable* output = vtkTable::GetData(outInfo->GetInformationObject(1));
      output->Initialize();
      // Image paths as a consumer needs them wherever it runs: a path relative to the log
      // becomes absolute; "/images/<name>" (an image inside the log) stays, and the table
      // names the log in its field data (TrainingLogFile) so that
      // vtkGaussianArtifactScoreFilter reads those images from it, with no temporary files.
      std::vector<vis4gs::Camera> cameras = d.Log->ReadCameras();
      const std::filesystem::path logFile = std::filesystem::absolute(this->FileName);
      for (vis4gs::Camera& camera : cameras)
      {
        if (!camera.ImagePath.empty() && camera.ImagePath.rfind("/images/", 0) != 0 &&
          std::filesystem::path(camera.ImagePath).is_relative())
        {
          camera.ImagePath = (logFile.parent_path() / camera.ImagePath).lexically_normal();
        }
      }
      vis4gs::CamerasToTable(cameras, output);
      vtkNew<vtkStringArray> source;
      source->SetName(vis4gs::arrays::CameraTrainingLogFile);
      source->InsertNextValue(logFile.string());
      output->GetFieldData()->AddArray(source);
    }
    if (wanted(2))
    {
      vtkTable* output = vtkTable::GetData(outInfo->GetInformationObject(2));
      output->Initialize();
      const vis4gs::MetricsTable train = d.Log->ReadMetrics(false);
      const vis4gs::MetricsTable test = d.Log->ReadMetrics(true);
      if (this->MetricsAsLogged)
      {
        LoggedMetrics(train, test, output);
      }
      else
      {
        MergedMetrics(train, test, output);
      }
    }
    if (wanted(3))
    {
      vtkTable* output = vtkTable::GetData(outInfo->GetInformationObject(3));
      output->Initialize();
      // The columns take over the event vectors (a large log has tens of millions of events).
      vis4gs::EventTable e = d.Log->ReadEvents();
      using vis4gs::AdoptVector;
      namespace names = vis4gs::arrays;
      output->AddColumn(AdoptVector<vtkIntArray>(names::EventIteration, std::move(e.Iteration)));
      output->AddColumn(AdoptVector<vtkUnsignedCharArray>(names::EventKind, std::move(e.Kind)));
      output->AddColumn(AdoptVector<vtkIdTypeArray>(names::EventParent, std::move(e.Parent)));
      output->AddColumn(AdoptVector<vtkIdTypeArray>(names::EventChild, std::move(e.Child)));
      // What vtkGaussianGenealogyTreeFilter needs besides the rows, so that connecting this
      // port to it needs no glue: the initial Gaussians (the ids of the first snapshot, as the
      // application takes them) and the last iteration (the planned one, or the last snapshot
      // when training went on longer).
      const std::vector<int>& snapshots = d.Log->GetSnapshotIterations();
      vtkNew<vtkIdTypeArray> initial;
      initial->SetName(vis4gs::arrays::EventInitialIds);
      if (!snapshots.empty())
      {
        vis4gs::SnapshotReadOptions idsOnly;
        idsOnly.Arrays = vis4gs::SnapshotIds;
        const auto first = d.Log->ReadSnapshot(snapshots.front(), idsOnly);
        initial->SetNumberOfTuples(static_cast<vtkIdType>(first.Count));
        for (std::size_t i = 0; i < first.Count; ++i)
        {
          initial->SetValue(static_cast<vtkIdType>(i), first.GetId(i));
        }
      }
      output->GetFieldData()->AddArray(initial);
      vtkNew<vtkIntArray> last;
      last->SetName(vis4gs::arrays::EventLastIteration);
      last->InsertNextValue(
        std::max(d.Log->GetHeader().Iterations, snapshots.empty() ? 0 : snapshots.back()));
      output->GetFieldData()->AddArray(last);
      // Where the logger lost the lineage, for the genealogy filter (only when it did).
      const vis4gs::LineageBreakTable breaks = d.Log->ReadLineageBreaks();
      if (breaks.Size() > 0)
      {
        output->GetFieldData()->AddArray(
          MakeColumn<vtkIntArray>(names::EventBreakIteration, breaks.Iteration));
        for (const auto& c : names::LineageBreakIdColumns(breaks))
        {
          output->GetFieldData()->AddArray(MakeColumn<vtkIdTypeArray>(c.first, *c.second));
        }
      }
    }
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  d.Repairs = d.Log->GetRepairs();
  return 1;
}

//------------------------------------------------------------------------------
int vtkGaussianTrainingLogReader::GetPropertyHistory(vtkIdTypeArray* ids, vtkTable* output)
{
  vtkInternals& d = *this->Internals;
  if (!ids || !output)
  {
    vtkErrorMacro(<< "GetPropertyHistory needs an id array and an output table.");
    return 0;
  }
  if (!d.Log && !this->OpenLog())
  {
    return 0;
  }
  std::vector<std::int64_t> wanted(static_cast<std::size_t>(ids->GetNumberOfValues()));
  for (vtkIdType i = 0; i < ids->GetNumberOfValues(); ++i)
  {
    wanted[static_cast<std::size_t>(i)] = ids->GetValue(i);
  }
  vis4gs::PropertyHistory h;
  try
  {
    h = d.Log->ReadPropertyHistory(wanted,
      vis4gs::SnapshotPositions | vis4gs::SnapshotLogScales | vis4gs::SnapshotRotations |
        vis4gs::SnapshotOpacityLogits | vis4gs::SnapshotSH);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  d.Repairs = d.Log->GetRepairs();
  output->Initialize();
  output->AddColumn(MakeColumn<vtkIdTypeArray>(vis4gs::arrays::GaussianId, h.Id));
  output->AddColumn(MakeColumn<vtkIntArray>(vis4gs::arrays::HistoryIteration, h.Iteration));
  output->AddColumn(MakeColumn<vtkFloatArray>(vis4gs::arrays::HistoryPosition, h.Positions, 3));
  output->AddColumn(MakeColumn<vtkFloatArray>(vis4gs::arrays::LogScale, h.LogScales, 3));
  output->AddColumn(MakeColumn<vtkFloatArray>(vis4gs::arrays::Rotation, h.Rotations, 4));
  output->AddColumn(MakeColumn<vtkFloatArray>(vis4gs::arrays::OpacityLogit, h.OpacityLogits));
  output->AddColumn(MakeColumn<vtkFloatArray>(vis4gs::arrays::HistorySHDC, h.SHDC, 3));
  std::vector<float> opacity(h.Size()), scale(3 * h.Size());
  for (std::size_t i = 0; i < h.Size(); ++i)
  {
    opacity[i] = vis4gs::Sigmoid(h.OpacityLogits[i]);
    for (int c = 0; c < 3; ++c)
    {
      scale[3 * i + c] = std::exp(h.LogScales[3 * i + c]);
    }
  }
  output->AddColumn(MakeColumn<vtkFloatArray>(vis4gs::arrays::Opacity, opacity));
  output->AddColumn(MakeColumn<vtkFloatArray>(vis4gs::arrays::Scale, scale, 3));
  return 1;
}

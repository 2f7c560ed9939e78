// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSDocument.h"

#include "GaussianIO.h"
#include "GaussianMath.h"
#include "ImageIO.h"
#include "TrainingLogReader.h"
#include "Vis4GSDataModel.h"
#include "Vis4GSSceneCameras.h"

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkDoubleArray.h"
#include "vtkGaussianArtifactScoreFilter.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkTree.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"
#include "vtkTypeUInt8Array.h"
#include "vtkUnsignedCharArray.h"

#ifdef VIS4GS_HAVE_GENEALOGY_FILTER
#include "vtkGaussianGenealogyTreeFilter.h"
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <exception>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <thread>

namespace
{
// Updates @p algorithm; false when it reported an error (VTK filters report, not throw).
bool UpdateReportingErrors(vtkAlgorithm* algorithm)
{
  vtkNew<vtkCallbackCommand> errors;
  bool failed = false;
  errors->SetClientData(&failed);
  errors->SetCallback(
    [](vtkObject*, unsigned long, void* client, void*) { *static_cast<bool*>(client) = true; });
  const unsigned long tag = algorithm->AddObserver(vtkCommand::ErrorEvent, errors);
  algorithm->Update();
  algorithm->RemoveObserver(tag);
  return !failed;
}

vtkSmartPointer<vtkTable> MetricsToTable(const vis4gs::MetricsTable& m)
{
  auto table = vtkSmartPointer<vtkTable>::New();
  vtkNew<vtkIntArray> it;
  it->SetName(vis4gs::arrays::MetricIteration);
  for (auto v : m.Iteration)
  {
    it->InsertNextValue(v);
  }
  table->AddColumn(it);
  auto add = [&](const char* name, const std::vector<double>& values)
  {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    for (double v : values)
    {
      a->InsertNextValue(v);
    }
    table->AddColumn(a);
  };
  std::vector<double> count(m.NumGaussians.begin(), m.NumGaussians.end());
  add(vis4gs::arrays::MetricGaussians, count);
  add(vis4gs::arrays::MetricLoss, m.Loss);
  add(vis4gs::arrays::MetricPSNR, m.Psnr);
  add(vis4gs::arrays::MetricSSIM, m.Ssim);
  add(vis4gs::arrays::MetricLPIPS, m.Lpips);
  return table;
}

double WallNow()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double CpuClock(clockid_t clock)
{
  timespec t{};
  clock_gettime(clock, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
double ProcessCpuNow()
{
  return CpuClock(CLOCK_PROCESS_CPUTIME_ID);
}
double ThreadCpuNow()
{
  return CpuClock(CLOCK_THREAD_CPUTIME_ID);
}

#ifdef VIS4GS_HAVE_GENEALOGY_FILTER
/// Wraps a std::vector's memory in a VTK array without copying (the vector must outlive it).
template <typename ArrayT, typename T>
vtkSmartPointer<ArrayT> WrapColumn(const char* name, const std::vector<T>& values)
{
  static_assert(sizeof(typename ArrayT::ValueType) == sizeof(T), "same value size");
  auto a = vtkSmartPointer<ArrayT>::New();
  a->SetName(name);
  // save = 1: VTK never frees (nor writes) this memory.
  a->SetArray(reinterpret_cast<typename ArrayT::ValueType*>(const_cast<T*>(values.data())),
    static_cast<vtkIdType>(values.size()),
    1);
  return a;
}

/// The genealogy filter on Core events (no copy into VTK arrays: the table wraps them).
void BuildGenealogy(const vis4gs::EventTable& events,
  const std::vector<std::int64_t>& initialIds,
  int lastIteration,
  vtkSmartPointer<vtkTree>& tree,
  vtkSmartPointer<vtkTable>& bands)
{
  vtkNew<vtkTable> table;
  table->AddColumn(WrapColumn<vtkTypeInt32Array>("Iteration", events.Iteration));
  table->AddColumn(WrapColumn<vtkTypeUInt8Array>("Kind", events.Kind));
  table->AddColumn(WrapColumn<vtkTypeInt64Array>("Parent", events.Parent));
  table->AddColumn(WrapColumn<vtkTypeInt64Array>("Child", events.Child));
  vtkNew<vtkGaussianGenealogyTreeFilter> filter;
  filter->SetInputData(table);
  if (!initialIds.empty())
  {
    vtkNew<vtkIdTypeArray> initial;
    initial->SetNumberOfTuples(static_cast<vtkIdType>(initialIds.size()));
    std::copy(initialIds.begin(), initialIds.end(), initial->GetPointer(0));
    filter->SetInitialIds(initial);
  }
  else
  {
    filter->SetNumberOfInitialGaussians(0);
  }
  filter->SetLastIteration(lastIteration);
  filter->SetRepairUnknownParents(true);
  const bool failed = !UpdateReportingErrors(filter);
  if (failed)
  {
    throw std::runtime_error("vtkGaussianGenealogyTreeFilter failed (see the error output)");
  }
  tree = vtkTree::SafeDownCast(filter->GetOutputDataObject(0));
  bands = filter->GetFamilyBands();
}
#endif
}

//------------------------------------------------------------------------------
std::shared_ptr<Vis4GSDocument> Vis4GSDocument::Load(const std::string& path,
  const Progress& progress,
  const std::string& cameraPath)
{
  const auto start = std::chrono::steady_clock::now();
  auto doc = std::make_shared<Vis4GSDocument>();
  doc->Path = path;
  auto report = [&](double f, const std::string& m)
  {
    if (progress)
    {
      progress(f, m);
    }
  };
  std::string lower = path;
  std::transform(lower.begin(), lower.end(), lower.begin(), ::tolower);
  const bool isLog = lower.size() > 3 &&
    (lower.compare(lower.size() - 3, 3, ".h5") == 0 ||
      (lower.size() > 5 && lower.compare(lower.size() - 5, 5, ".hdf5") == 0));
  std::ostringstream text;
  auto lap = start;
  double lapCpu = ProcessCpuNow();
  std::ostringstream timings;
  timings.precision(3);
  auto stage = [&](const char* what)
  {
    const auto now = std::chrono::steady_clock::now();
    const double cpu = ProcessCpuNow();
    timings << " " << what << " " << std::chrono::duration<double>(now - lap).count() << " s ("
            << cpu - lapCpu << " s CPU);";
    lap = now;
    lapCpu = cpu;
  };
  if (!isLog)
  {
    std::error_code size;
    const auto bytes = std::filesystem::file_size(path, size);
    std::ostringstream what;
    what.precision(3);
    what << "reading the scene";
    if (!size)
    {
      what << " (" << static_cast<double>(bytes) / 1e6 << " MB)";
    }
    report(-1.0, what.str()); // the Core readers report no fraction
    vis4gs::GaussianCloud cloud = vis4gs::ReadGaussianScene(path);
    doc->Scene = vtkSmartPointer<vtkPolyData>::New();
    vis4gs::GaussianCloudToPolyData(cloud, doc->Scene);
    text << path << ": " << cloud.Count << " Gaussians (a scene file: no training history)\n";
    stage("scene file");
    report(0.8, "reading the cameras");
    const std::vector<vis4gs::Camera> cameras = Vis4GSFindSceneCameras(path, cameraPath);
    if (!cameras.empty())
    {
      doc->Cameras = vtkSmartPointer<vtkTable>::New();
      vis4gs::CamerasToTable(cameras, doc->Cameras);
      text << "cameras: " << cameras.size() << "\n";
      stage("cameras");
    }
  }
  else
  {
    doc->IsLog = true;
    report(0.05, "opening the training log");
    doc->Log = std::make_shared<vis4gs::TrainingLogReader>(path);
    const auto& log = *doc->Log;
    const auto& header = log.GetHeader();
    doc->Snapshots = log.GetSnapshotIterations();
    text << path << "\nproducer: " << header.Producer << "\nscene: " << header.Scene
         << "\nplanned iterations: " << header.Iterations << "\nSH degree: " << header.ShDegree
         << "\nsnapshots: " << doc->Snapshots.size() << "\n";
    for (const auto& lack : log.GetLacks())
    {
      text << "lacks: " << lack << "\n";
    }
    if (log.HasMetrics())
    {
      report(0.1, "reading the metrics");
      doc->Metrics = MetricsToTable(log.ReadMetrics());
      text << "metrics rows: " << doc->Metrics->GetNumberOfRows() << "\n";
      if (log.HasTestMetrics())
      {
        doc->TestMetrics = MetricsToTable(log.ReadMetrics(true));
      }
    }
    if (log.HasCameras())
    {
      doc->Cameras = vtkSmartPointer<vtkTable>::New();
      vis4gs::CamerasToTable(log.ReadCameras(), doc->Cameras);
      text << "cameras: " << doc->Cameras->GetNumberOfRows() << "\n";
    }
    stage("header, metrics, cameras");
    // The genealogy (events, initial ids, then vtkGaussianGenealogyTreeFilter) is built in a
    // second thread while this one reads the last snapshot, so the two largest steps overlap
    // on two cores. Both threads read the log: the reader's const methods keep no shared
    // state, and the HDF5 library is built thread-safe (it serialises its own calls; the
    // chunk decoding of the reader runs outside it).
    std::thread genealogyThread;
    std::string genealogyError, genealogyTimes;
    std::exception_ptr readError;
    std::size_t eventCount = 0;
    if (log.HasEvents())
    {
#ifdef VIS4GS_HAVE_GENEALOGY_FILTER
      const int last =
        std::max(header.Iterations, doc->Snapshots.empty() ? 0 : doc->Snapshots.back());
      Vis4GSDocument* target = doc.get();
      genealogyThread = std::thread(
        [target, last, &genealogyError, &genealogyTimes, &readError, &eventCount]
        {
          const vis4gs::TrainingLogReader& reader = *target->Log;
          vis4gs::EventTable events;
          std::vector<std::int64_t> initial;
          const double w0 = WallNow(), c0 = ThreadCpuNow();
          try
          {
            events = reader.ReadEvents();
            eventCount = events.Size();
            if (!target->Snapshots.empty())
            {
              vis4gs::SnapshotReadOptions ids;
              ids.Arrays = vis4gs::SnapshotIds;
              const auto first = reader.ReadSnapshot(target->Snapshots.front(), ids);
              initial.resize(first.Count);
              for (std::size_t i = 0; i < first.Count; ++i)
              {
                initial[i] = first.GetId(i);
              }
            }
          }
          catch (...)
          {
            readError = std::current_exception();
            return;
          }
          const double w1 = WallNow(), c1 = ThreadCpuNow();
          std::ostringstream t;
          t.precision(3);
          t << " second thread: events and initial ids " << w1 - w0 << " s (" << c1 - c0
            << " s CPU of that thread), " << events.Size() << " events;";
          try
          {
            BuildGenealogy(events, initial, last, target->Tree, target->Bands);
            t << " genealogy filter " << WallNow() - w1 << " s (" << ThreadCpuNow() - c1
              << " s CPU of that thread);";
          }
          catch (const std::exception& e)
          {
            genealogyError = e.what();
          }
          genealogyTimes = t.str();
        });
#else
      text << "genealogy: not available (built without Filters/Genealogy)\n";
#endif
    }
    if (!doc->Snapshots.empty())
    {
      report(0.2, "reading the last snapshot and the events");
      try
      {
        doc->LoadIteration(doc->Snapshots.back());
      }
      catch (...)
      {
        if (genealogyThread.joinable())
        {
          genealogyThread.join();
        }
        throw;
      }
      stage("last snapshot");
    }
    if (genealogyThread.joinable())
    {
      report(0.6, "building the genealogy");
      genealogyThread.join();
      stage("waiting for the genealogy");
      timings << genealogyTimes;
      if (readError)
      {
        std::rethrow_exception(readError);
      }
      text << "events: " << eventCount << "\n";
      if (!genealogyError.empty())
      {
        // The views that need no genealogy stay usable.
        doc->Tree = nullptr;
        doc->Bands = nullptr;
        text << "genealogy: could not be built: " << genealogyError << "\n";
      }
      else if (doc->Tree)
      {
        text << "genealogy: " << doc->Tree->GetNumberOfVertices() - 1 << " Gaussians ever born, "
             << (doc->Bands ? doc->Bands->GetNumberOfRows() : 0) << " families\n";
      }
    }
  }
  report(1.0, "done");
  doc->Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  text << "loaded in " << doc->Seconds << " s";
  const std::string stages = timings.str();
  if (!stages.empty()) // (every branch above times its stages; never print "( )")
  {
    text << " (" << stages.substr(1, stages.size() - 2) << ")";
  }
  text << "\n";
  doc->Summary = text.str();
  return doc;
}

//------------------------------------------------------------------------------
int Vis4GSDocument::LoadIteration(int iteration)
{
  if (!this->Log || this->Snapshots.empty())
  {
    return this->Iteration;
  }
  vis4gs::SnapshotReadOptions options;
  options.Arrays = vis4gs::SnapshotParameters;
  const int nearest = this->Log->FindNearestSnapshot(iteration);
  options.ShDegree = this->Log->GetSnapshotSize(nearest) <= FullShLimit ? -1 : 0;
  int logged = -1;
  const vis4gs::GaussianCloud cloud = this->Log->ReadNearestSnapshot(iteration, options, &logged);
  auto scene = vtkSmartPointer<vtkPolyData>::New();
  vis4gs::GaussianCloudToPolyData(cloud, scene);
  this->Scene = scene;
  this->Iteration = logged;
  return logged;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkTable> Vis4GSDocument::History(const std::vector<std::int64_t>& ids) const
{
  auto table = vtkSmartPointer<vtkTable>::New();
  vtkNew<vtkIntArray> it;
  it->SetName("Iteration");
  vtkNew<vtkIdTypeArray> id;
  id->SetName("GaussianId");
  vtkNew<vtkDoubleArray> opacity, scale, px, py, pz;
  opacity->SetName("Opacity");
  scale->SetName("Scale");
  px->SetName("PositionX");
  py->SetName("PositionY");
  pz->SetName("PositionZ");
  if (this->Log && !ids.empty())
  {
    const vis4gs::PropertyHistory h = this->Log->ReadPropertyHistory(
      ids, vis4gs::SnapshotPositions | vis4gs::SnapshotLogScales | vis4gs::SnapshotOpacityLogits);
    for (std::size_t r = 0; r < h.Size(); ++r)
    {
      it->InsertNextValue(h.Iteration[r]);
      id->InsertNextValue(h.Id[r]);
      opacity->InsertNextValue(vis4gs::Sigmoid(static_cast<double>(h.OpacityLogits[r])));
      const float m =
        std::max({ h.LogScales[3 * r], h.LogScales[3 * r + 1], h.LogScales[3 * r + 2] });
      scale->InsertNextValue(vis4gs::ActivatedScale(static_cast<double>(m)));
      px->InsertNextValue(h.Positions[3 * r]);
      py->InsertNextValue(h.Positions[3 * r + 1]);
      pz->InsertNextValue(h.Positions[3 * r + 2]);
    }
  }
  for (vtkAbstractArray* a : { static_cast<vtkAbstractArray*>(it),
         static_cast<vtkAbstractArray*>(id),
         static_cast<vtkAbstractArray*>(opacity),
         static_cast<vtkAbstractArray*>(scale),
         static_cast<vtkAbstractArray*>(px),
         static_cast<vtkAbstractArray*>(py),
         static_cast<vtkAbstractArray*>(pz) })
  {
    table->AddColumn(a);
  }
  return table;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkTable> Vis4GSDocument::ScoreCameras(const std::string& folder)
{
  this->CamerasWithImages = 0;
  if (!this->Cameras || !this->Log)
  {
    return this->Cameras;
  }
  std::vector<vis4gs::Camera> cameras = this->Log->ReadCameras();
  namespace fs = std::filesystem;
  const fs::path logDir = fs::path(this->Path).parent_path();
  const std::string prefix = "/images/";
  for (vis4gs::Camera& c : cameras)
  {
    if (c.ImagePath.rfind(prefix, 0) == 0)
    {
      int width = 0, height = 0;
      const std::string name = c.ImagePath.substr(prefix.size());
      const std::vector<unsigned char> pixels = this->Log->ReadImage(name, width, height);
      const fs::path file = fs::path(folder) / (name + ".png");
      fs::create_directories(file.parent_path());
      if (!fs::exists(file))
      {
        vis4gs::WritePng8(file.string(), width, height, 3, pixels.data());
      }
      c.ImagePath = file.string();
    }
    else if (!c.ImagePath.empty() && fs::path(c.ImagePath).is_relative())
    {
      c.ImagePath = (logDir / c.ImagePath).string();
    }
    if (!c.ImagePath.empty() && fs::exists(c.ImagePath))
    {
      ++this->CamerasWithImages;
    }
  }
  auto table = vtkSmartPointer<vtkTable>::New();
  vis4gs::CamerasToTable(cameras, table);
  return table;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> Vis4GSDocument::ComputeScores(vtkPolyData* scene,
  vtkTable* cameras,
  bool withImages,
  const Progress& progress)
{
  if (!scene)
  {
    throw std::runtime_error("no scene to compute scores for");
  }
  vtkNew<vtkPolyData> input;
  input->ShallowCopy(scene);
  vtkNew<vtkGaussianArtifactScoreFilter> filter;
  filter->SetInputData(input);
  const bool haveCameras = cameras && cameras->GetNumberOfRows() > 0;
  if (haveCameras)
  {
    filter->SetCamerasData(cameras);
  }
  filter->SetComputeViewCoverage(haveCameras);
  filter->SetComputeBlurScore(haveCameras && withImages);
  filter->SetComputeNeedleScore(haveCameras && withImages);
  filter->SetComputeNeedleShape(true);
  vtkNew<vtkCallbackCommand> observer;
  observer->SetClientData(const_cast<Progress*>(&progress));
  observer->SetCallback(
    [](vtkObject* caller, unsigned long, void* client, void*)
    {
      const auto* p = static_cast<const Progress*>(client);
      if (*p)
      {
        (*p)(static_cast<vtkAlgorithm*>(caller)->GetProgress(), "computing the scores");
      }
    });
  filter->AddObserver(vtkCommand::ProgressEvent, observer);
  const bool failed = !UpdateReportingErrors(filter);
  if (failed || !filter->GetOutput())
  {
    throw std::runtime_error("the score filter failed (see the error output)");
  }
  auto result = vtkSmartPointer<vtkPolyData>::New();
  for (const char* name : { vis4gs::arrays::ViewCoverage,
         vis4gs::arrays::BlurScore,
         vis4gs::arrays::NeedleScore,
         vis4gs::arrays::NeedleShape,
         "NoVisibleView" })
  {
    if (vtkAbstractArray* a = filter->GetOutput()->GetPointData()->GetAbstractArray(name))
    {
      result->GetPointData()->AddArray(a);
    }
  }
  return result;
}

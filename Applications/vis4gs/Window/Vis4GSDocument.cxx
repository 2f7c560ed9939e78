// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSDocument.h"
#include "Vis4GSStateFiles.h"

#include "RemovalEffect.h"
#include "ScoreRegistry.h"
#include "Vis4GSDataModel.h"
#include "Vis4GSPipeline.h"
#include "Vis4GSSceneCameras.h"

#include "vtkAlgorithm.h"
#include "vtkAnnotationLink.h"
#include "vtkCallbackCommand.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkFieldData.h"
#include "vtkGaussianArtifactScoreFilter.h"
#include "vtkGaussianSceneReader.h"
#include "vtkGaussianSelectionHub.h"
#include "vtkGaussianSession.h"
#include "vtkGaussianTrainingLogReader.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkTable.h"
#include "vtkTree.h"
#include "vtkXMLPolyDataWriter.h"
#include "vtkXMLTableWriter.h"

#ifdef VIS4GS_HAVE_GENEALOGY_FILTER
#include "vtkGaussianGenealogyTreeFilter.h"
#endif

#include <algorithm>
#include <cctype>
#include <chrono>
#include <ctime>
#include <exception>
#include <filesystem>
#include <iostream>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <thread>

namespace
{
/// Forwards the ProgressEvents of @p algorithm to @p progress, mapped into [from, to].
class ProgressForwarder
{
public:
  ProgressForwarder(vtkAlgorithm* algorithm,
    const Vis4GSDocument::Progress& progress,
    double from,
    double to,
    const std::string& message)
    : Algorithm(algorithm)
    , Report(progress)
    , From(from)
    , To(to)
    , Message(message)
  {
    this->Callback->SetClientData(this);
    this->Callback->SetCallback(
      [](vtkObject* caller, unsigned long, void* client, void*)
      {
        const auto* self = static_cast<const ProgressForwarder*>(client);
        if (self->Report)
        {
          const double f = static_cast<vtkAlgorithm*>(caller)->GetProgress();
          self->Report(self->From + f * (self->To - self->From), self->Message);
        }
      });
    this->Tag = algorithm->AddObserver(vtkCommand::ProgressEvent, this->Callback);
  }
  ~ProgressForwarder() { this->Algorithm->RemoveObserver(this->Tag); }
  ProgressForwarder(const ProgressForwarder&) = delete;
  ProgressForwarder& operator=(const ProgressForwarder&) = delete;

private:
  vtkAlgorithm* Algorithm;
  const Vis4GSDocument::Progress& Report;
  double From, To;
  std::string Message;
  vtkNew<vtkCallbackCommand> Callback;
  unsigned long Tag = 0;
};

/// A new data object sharing the arrays of @p output: the document keeps it while the
/// algorithm re-executes into @p output (a new snapshot) in another thread.
template <typename T>
vtkSmartPointer<T> Detach(T* output)
{
  auto copy = vtkSmartPointer<T>::New();
  if (output)
  {
    copy->ShallowCopy(output);
  }
  return copy;
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

// A reader's error as collected, "ERROR: In <source>, line <n>\n<class> (<address>): <text>\n\n",
// reduced to <text> for the tree view and the warnings a user reads.
std::string PlainError(const std::string& collected)
{
  static const std::regex vtkPrefix(
    "ERROR: In [^\n]*, line [0-9]+\n[A-Za-z0-9_]+ \\(0x[0-9a-fA-F]+\\): ");
  std::string text = std::regex_replace(collected, vtkPrefix, "");
  text = std::regex_replace(text, std::regex("\\s*\n\\s*"), " ");
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back())))
  {
    text.pop_back();
  }
  return text;
}

#ifdef VIS4GS_HAVE_GENEALOGY_FILTER
/**
 * Builds the session's genealogy (@p filter: its events reader into the genealogy filter, as
 * a script connects them) by updating that filter itself, so that it runs in a second thread
 * beside the session's snapshot read (the session reports only what runs in its own thread).
 * The session's tree and bands ports then pass the filter's output on without building it
 * again. Returns the error messages (empty: success); the events reader's go to @p readError.
 */
std::string BuildGenealogy(vtkGaussianGenealogyTreeFilter* filter,
  const Vis4GSDocument::Progress& progress,
  std::size_t& eventCount,
  std::string& readError)
{
  auto* events = vtkGaussianTrainingLogReader::SafeDownCast(filter->GetInputAlgorithm(0, 0));
  if (!events)
  {
    return "the session's genealogy filter has no events reader";
  }
  readError = Vis4GSUpdate(events, 3);
  if (!readError.empty())
  {
    return readError;
  }
  eventCount = static_cast<std::size_t>(events->GetEventsOutput()->GetNumberOfRows());
  // The window keeps the tree only: the events table (hundreds of MB at millions of Gaussians)
  // is released once the filter has built it, as the reader of its own did before.
  if (auto* exec = vtkDemandDrivenPipeline::SafeDownCast(events->GetExecutive()))
  {
    exec->SetReleaseDataFlag(3, 1);
  }
  ProgressForwarder forward(filter, progress, 0.6, 0.95, "building the genealogy");
  return Vis4GSUpdate(filter, 0);
}
#endif
}

//------------------------------------------------------------------------------
std::shared_ptr<Vis4GSDocument> Vis4GSDocument::Load(const std::string& path,
  const Progress& progress,
  const std::string& cameraPath,
  const std::string& imageFolder)
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
  // A log by its name (so that a damaged .h5 gets the log reader's message) or its content.
  const bool isLog = Vis4GSIsLogPath(path) || vtkGaussianSession::IsTrainingLogFile(path.c_str());
  // The pipeline (DESIGN §8): the views' inputs are its ports. The scores run on a filter of
  // their own in the background (ComputeScores), on the Gaussians shown.
  doc->Session = vtkSmartPointer<vtkGaussianSession>::New();
  vtkGaussianSession* session = doc->Session;
  session->SetFileName(path.c_str());
  session->ComputeScoresOff();
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
    report(-1.0, what.str()); // the scene parsers report no fraction
    // The session's scene reader and camera reader (cameras.json beside the file or two
    // folders up, else @p cameraPath), as a script or ParaView reads them.
    session->SetCamerasFileName(cameraPath.c_str());
    const std::string errors = Vis4GSUpdate(session, vtkGaussianSession::GaussiansPort);
    if (!errors.empty())
    {
      throw std::runtime_error(errors);
    }
    doc->Scene = Detach(session->GetGaussiansOutput());
    text << path << ": " << doc->Scene->GetNumberOfPoints()
         << " Gaussians (a scene file: no training history)\n";
    stage("scene file");
    report(0.8, "reading the cameras");
    const std::string cameraErrors = Vis4GSUpdate(session, vtkGaussianSession::CamerasPort);
    if (!cameraErrors.empty())
    {
      throw std::runtime_error(cameraErrors);
    }
    vtkSmartPointer<vtkTable> cameras = Detach(session->GetCamerasOutput());
    const vtkIdType count = cameras->GetNumberOfRows();
    if (!imageFolder.empty())
    {
      if (count == 0)
      {
        throw std::runtime_error(path + ": --images needs cameras (none found; give --cameras)");
      }
      // In the camera table's Image column, where every filter finds them.
      std::vector<vis4gs::Camera> views;
      std::string error;
      if (!vis4gs::TableToCameras(cameras, views, &error))
      {
        throw std::runtime_error(path + ": the cameras: " + error);
      }
      Vis4GSAttachImagesByName(views, imageFolder);
      cameras = vtkSmartPointer<vtkTable>::New();
      vis4gs::CamerasToTable(views, cameras);
    }
    if (count > 0)
    {
      doc->Cameras = cameras;
      text << "cameras: " << count << "\n";
      stage("cameras");
    }
  }
  else
  {
    doc->IsLog = true;
    report(0.05, "opening the training log");
    // The session's log reader: the header, the snapshot list and the queries of panel C.
    doc->Reader = session->GetLogReader();
    vtkGaussianTrainingLogReader* log = doc->Reader;
    log->SetFileName(path.c_str());
    session->SetFullSHLimit(static_cast<vtkIdType>(FullShLimit));
    {
      Vis4GSErrorCollector errors(log);
      log->UpdateInformation(); // opens the log: header, snapshot list, what it holds
      if (!errors.GetMessages().empty())
      {
        throw std::runtime_error(errors.GetMessages());
      }
    }
    for (int i = 0; i < log->GetNumberOfSnapshots(); ++i)
    {
      doc->Snapshots.push_back(log->GetSnapshotIteration(i));
    }
    text << path << "\nproducer: " << log->GetProducer() << "\nscene: " << log->GetSceneName()
         << "\nplanned iterations: " << log->GetPlannedIterations()
         << "\nSH degree: " << log->GetTrainerSHDegree() << "\nsnapshots: " << doc->Snapshots.size()
         << "\n";
    for (int i = 0; i < log->GetNumberOfLacks(); ++i)
    {
      text << "lacks: " << log->GetLack(i) << "\n";
    }
    if (log->HasMetrics())
    {
      report(0.1, "reading the metrics");
      const std::string errors = Vis4GSUpdate(session, vtkGaussianSession::MetricsPort);
      if (!errors.empty())
      {
        throw std::runtime_error(errors);
      }
      doc->Metrics = Detach(session->GetMetricsOutput());
      text << "metrics rows: " << doc->Metrics->GetNumberOfRows() << "\n";
    }
    if (log->HasCameras())
    {
      const std::string errors = Vis4GSUpdate(session, vtkGaussianSession::CamerasPort);
      if (!errors.empty())
      {
        throw std::runtime_error(errors);
      }
      doc->Cameras = Detach(session->GetCamerasOutput());
      text << "cameras: " << doc->Cameras->GetNumberOfRows() << "\n";
    }
    stage("header, metrics, cameras");
    // The genealogy (the session's events reader into its genealogy filter) is built in a
    // second thread while this one reads the last snapshot through the session, so the two
    // largest steps overlap on two cores. The HDF5 library is built thread-safe (it serialises
    // its own calls; the chunk decoding of the Core reader runs outside it).
    std::thread genealogyThread;
    std::string genealogyError, readError, genealogyTimes;
    std::size_t eventCount = 0;
    if (log->HasEvents())
    {
#ifdef VIS4GS_HAVE_GENEALOGY_FILTER
      // Set up in this thread (GetGenealogyFilter connects the session): the second one only
      // updates the filter and its events reader.
      vtkGaussianGenealogyTreeFilter* genealogy = session->GetGenealogyFilter();
      genealogy->SetRepairUnknownParents(true);
      // The same vertices, edges and arrays as a script's default vtkTree, in flat arrays: 40
      // bytes per vertex instead of ~100 (630 MiB less at 4.89M Gaussians, see
      // vtkGaussianCompactTree). The views read it through vtkTree's accessors.
      genealogy->CompactTreeOn();
      genealogyThread = std::thread(
        [genealogy, &progress, &genealogyError, &readError, &genealogyTimes, &eventCount]
        {
          const double w0 = WallNow(), c0 = ThreadCpuNow();
          genealogyError = BuildGenealogy(genealogy, progress, eventCount, readError);
          std::ostringstream t;
          t.precision(3);
          t << " second thread: events and genealogy filter " << WallNow() - w0 << " s ("
            << ThreadCpuNow() - c0 << " s CPU of that thread);";
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
        doc->LoadLatestReadableSnapshot();
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
      if (readError.empty())
      {
        text << "events: " << eventCount << "\n";
      }
      if (genealogyError.empty())
      {
        // The session's ports pass the tree built above on (nothing is built again).
        genealogyError = Vis4GSUpdate(session, vtkGaussianSession::TreePort);
        doc->Tree =
          vtkTree::SafeDownCast(session->GetOutputDataObject(vtkGaussianSession::TreePort));
        if (genealogyError.empty())
        {
          genealogyError = Vis4GSUpdate(session, vtkGaussianSession::BandsPort);
          doc->Bands =
            vtkTable::SafeDownCast(session->GetOutputDataObject(vtkGaussianSession::BandsPort));
        }
      }
      if (!genealogyError.empty())
      {
        // Damaged events (the reader's error) or a genealogy that cannot be built: the views
        // that need no genealogy stay usable, and the tree view says why it is empty.
        doc->Tree = nullptr;
        doc->Bands = nullptr;
        doc->TreeUnavailable =
          "The densification tree cannot be shown: " + PlainError(genealogyError);
        doc->Warnings.push_back(doc->TreeUnavailable + " (the other views are open)");
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
void Vis4GSDocument::LoadLatestReadableSnapshot()
{
  std::string errors;
  while (!this->Snapshots.empty())
  {
    try
    {
      this->LoadIteration(this->Snapshots.back());
      break;
    }
    catch (const std::exception& e)
    {
      // Left out of the iteration slider: the snapshots before it stay usable.
      errors += (errors.empty() ? "" : "; ") + PlainError(e.what());
      this->Snapshots.pop_back();
    }
  }
  if (this->Snapshots.empty())
  {
    throw std::runtime_error(this->Path + ": no snapshot can be read: " + errors);
  }
  if (!errors.empty())
  {
    this->Warnings.push_back("snapshots that cannot be read are left out (" + errors +
      "); showing iteration " + std::to_string(this->Iteration));
  }
}

//------------------------------------------------------------------------------
int Vis4GSDocument::LoadIteration(int iteration)
{
  if (!this->Session || !this->Reader || this->Snapshots.empty())
  {
    return this->Iteration;
  }
  this->Reader->UpdateInformation(); // the snapshot list
  // The session reads the snapshot nearest this (every SH degree up to FullShLimit Gaussians).
  this->Session->SetIteration(this->Reader->FindNearestSnapshot(iteration));
  const std::string errors = Vis4GSUpdate(this->Session, vtkGaussianSession::GaussiansPort);
  if (!errors.empty())
  {
    throw std::runtime_error(errors);
  }
  this->Scene = Detach(this->Session->GetGaussiansOutput());
  this->Scored = nullptr; // (the scores of the previous snapshot)
  this->Iteration = this->Session->GetLoadedIteration();
  return this->Iteration;
}

//------------------------------------------------------------------------------
std::vector<std::int64_t> Vis4GSDocument::HistoryDumpSelection() const
{
  std::vector<std::int64_t> ids;
  vtkDataArray* column =
    this->Scene ? this->Scene->GetPointData()->GetArray(vis4gs::arrays::GaussianId) : nullptr;
  const vtkIdType n = column ? column->GetNumberOfTuples() : 0;
  const vtkIdType count = std::min<vtkIdType>(n, HistoryLines);
  for (vtkIdType k = 0; k < count; ++k)
  {
    ids.push_back(static_cast<std::int64_t>(column->GetTuple1(k * n / count)));
  }
  return ids;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkTable> Vis4GSDocument::ScoreCameras(const std::string&)
{
  this->CamerasWithImages = 0;
  if (!this->Cameras)
  {
    return this->Cameras;
  }
  std::vector<vis4gs::Camera> cameras;
  std::string error;
  if (!vis4gs::TableToCameras(this->Cameras, cameras, &error))
  {
    throw std::runtime_error(this->Path + ": " + error);
  }
  std::set<std::string> embedded;
  for (int i = 0; this->Reader && i < this->Reader->GetNumberOfEmbeddedImages(); ++i)
  {
    embedded.insert(this->Reader->GetEmbeddedImageName(i));
  }
  const std::string prefix = "/images/";
  for (const vis4gs::Camera& c : cameras)
  {
    // As vis4gs::LoadCameraImage finds them: a file of that path, else the log's image.
    if (!c.ImagePath.empty() &&
      (std::filesystem::exists(c.ImagePath) ||
        (c.ImagePath.rfind(prefix, 0) == 0 && embedded.count(c.ImagePath.substr(prefix.size())))))
    {
      ++this->CamerasWithImages;
    }
  }
  return this->Cameras;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkGaussianSession> Vis4GSDocument::ComputeScores(vtkPolyData* scene,
  vtkTable* cameras,
  bool withImages,
  const Progress& progress,
  vis4gs::RemovalBaseline* baseline,
  int stage,
  const std::atomic<bool>* stop,
  const std::string& name)
{
  if (!scene)
  {
    throw std::runtime_error("no scene to compute scores for");
  }
  // A session of its own, given the Gaussians and cameras (no file read again): what it
  // computes is the application's Gaussians port once it lands.
  auto session = vtkSmartPointer<vtkGaussianSession>::New();
  session->SetFileName(name.c_str());
  session->SetGaussiansData(scene);
  const bool haveCameras = cameras && cameras->GetNumberOfRows() > 0;
  vtkNew<vtkTable> none;
  session->SetCamerasData(haveCameras ? cameras : none.GetPointer());
  vtkGaussianArtifactScoreFilter* filter = session->GetScoreFilter();
  // Every registered score the inputs allow.
  std::string scores;
  for (const vis4gs::ScoreDefinition& d : vis4gs::ScoreDefinitions())
  {
    if ((haveCameras || !(d.Needs & vis4gs::NeedsCameras)) &&
      (withImages || !(d.Needs & vis4gs::NeedsImages)))
    {
      scores += (scores.empty() ? "" : ",") + std::string(d.Name);
    }
  }
  filter->SetScores(scores.c_str());
  filter->SetProgressiveStage(stage);
  // The Stop button sets @p stop in the GUI thread; the filter looks at its own flag between
  // views, and this observer passes the button's on at each view.
  vtkNew<vtkCallbackCommand> stopper;
  stopper->SetClientData(const_cast<std::atomic<bool>*>(stop));
  stopper->SetCallback(
    [](vtkObject* caller, unsigned long, void* client, void*)
    {
      if (static_cast<const std::atomic<bool>*>(client)->load())
      {
        static_cast<vtkGaussianArtifactScoreFilter*>(caller)->StopExecution();
      }
    });
  if (stop)
  {
    filter->AddObserver(vtkCommand::ProgressEvent, stopper);
  }
  if (baseline && haveCameras && withImages && filter->GetLossResolution() == 1 && stage == 0)
  {
    std::vector<vis4gs::Camera> views;
    std::string error;
    if (!vis4gs::TableToCameras(cameras, views, &error))
    {
      throw std::runtime_error("the score cameras: " + error);
    }
    // The recorder sizes the baseline from the cloud's count and the cameras' sizes only: the
    // filter converts the scene itself, a second copy of its Gaussians is not needed here.
    vis4gs::GaussianCloud counted;
    counted.Count = static_cast<std::size_t>(scene->GetNumberOfPoints());
    filter->SetViewRendered(
      vis4gs::RemovalBaselineRecorder(counted, views, vis4gs::RasterSettings{}, 0, *baseline));
  }
  ProgressForwarder forward(filter, progress, 0.0, 1.0, "computing the scores");
  const std::string errors = Vis4GSUpdate(session, vtkGaussianSession::GaussiansPort);
  filter->RemoveObserver(stopper);
  if (!errors.empty() || !session->GetGaussiansOutput())
  {
    throw std::runtime_error("the score filter failed: " + errors);
  }
  if (filter->GetStopped())
  {
    return nullptr;
  }
  return session;
}

//------------------------------------------------------------------------------
vtkAlgorithmOutput* Vis4GSDocument::GaussiansConnection() const
{
  vtkGaussianSession* source = this->Scored ? this->Scored : this->Session;
  return source ? source->GetOutputPort(vtkGaussianSession::GaussiansPort) : nullptr;
}

//------------------------------------------------------------------------------
vtkPolyData* Vis4GSDocument::Shown() const
{
  return this->Scored ? this->Scored->GetGaussiansOutput() : this->Scene.GetPointer();
}

//------------------------------------------------------------------------------
void Vis4GSDocument::DumpInputs(const std::string& folder) const
{
  namespace fs = std::filesystem;
  fs::create_directories(folder);
  auto write = [&](vtkXMLWriter* writer, vtkDataObject* data, const std::string& name)
  {
    const fs::path file = fs::path(folder) / name;
    const fs::path partial = fs::path(folder) / (name + ".partial");
    // Cached ranges in the arrays' information would be written as keys that VTK 9.1's XML
    // readers fail to read back (L2_NORM_RANGE); they are only caches.
    vtkDataObject* copy = data->NewInstance();
    copy->ShallowCopy(data);
    for (int kind = 0; kind < vtkDataObject::NUMBER_OF_ATTRIBUTE_TYPES; ++kind)
    {
      vtkFieldData* fields = copy->GetAttributesAsFieldData(kind);
      for (int a = 0; fields && a < fields->GetNumberOfArrays(); ++a)
      {
        if (vtkAbstractArray* array = fields->GetAbstractArray(a))
        {
          if (array->HasInformation())
          {
            array->GetInformation()->Clear();
          }
        }
      }
    }
    writer->SetInputDataObject(copy);
    copy->Delete();
    writer->SetFileName(partial.string().c_str());
    writer->SetDataModeToBinary();
    if (writer->Write() != 1)
    {
      throw std::runtime_error(file.string() + ": could not be written");
    }
    fs::rename(partial, file);
  };
  if (vtkPolyData* shown = this->Shown())
  {
    vtkNew<vtkXMLPolyDataWriter> writer;
    write(writer, shown, "scene.vtp");
  }
  vtkNew<vtkXMLTableWriter> tables;
  // (No cameras: the NaN padding of their Distortion column gives a range key that VTK 9.1's
  // XML reader cannot read back; the scores compare what they fed.)
  const std::pair<vtkTable*, const char*> named[] = { { this->Metrics, "metrics.vtt" },
    { this->TestMetrics, "test-metrics.vtt" },
    { this->Bands, "bands.vtt" } };
  for (const auto& [table, name] : named)
  {
    if (table)
    {
      write(tables, table, name);
    }
  }
  if (this->Reader && this->Scene)
  {
    // The timeline's path: a hub's selection on the session's selection input (the annotation
    // link's current selection), at most HistoryLines ids, the history port's table.
    const std::vector<std::int64_t> selection = this->HistoryDumpSelection();
    const std::vector<vtkIdType> ids(selection.begin(), selection.end());
    vtkNew<vtkGaussianSelectionHub> hub;
    hub->RenderOnChangeOff();
    hub->SelectIds(ids.data(), static_cast<vtkIdType>(ids.size()));
    this->Session->SetSelectionConnection(hub->GetAnnotationLink()->GetOutputPort(2));
    this->Session->SetMaximumHistoryIds(HistoryLines);
    const std::string errors = Vis4GSUpdate(this->Session, vtkGaussianSession::HistoryPort);
    if (errors.empty())
    {
      write(tables, this->Session->GetHistoryOutput(), "history.vtt");
    }
    else
    {
      // The history reads every snapshot: one that cannot be read leaves it out (the window's
      // timeline says so in the status bar); the other inputs are written.
      std::cerr << "vis4gs view: warning: no property history: " << errors << "\n";
    }
    this->Session->SetSelectionConnection(nullptr);
  }
  if (this->Tree)
  {
    vtkNew<vtkTable> vertices;
    vertices->GetRowData()->ShallowCopy(this->Tree->GetVertexData());
    vtkNew<vtkIdTypeArray> parent;
    parent->SetName("ParentVertex");
    parent->SetNumberOfTuples(this->Tree->GetNumberOfVertices());
    for (vtkIdType v = 0; v < this->Tree->GetNumberOfVertices(); ++v)
    {
      parent->SetValue(v, this->Tree->GetParent(v));
    }
    vertices->AddColumn(parent);
    write(tables, vertices, "tree-vertices.vtt");
    vtkNew<vtkTable> edges;
    edges->GetRowData()->ShallowCopy(this->Tree->GetEdgeData());
    write(tables, edges, "tree-edges.vtt");
  }
}

//------------------------------------------------------------------------------
void Vis4GSDocument::LoadAndDumpInputs(const std::string& path,
  const std::string& cameras,
  const std::string& folder)
{
  const std::shared_ptr<Vis4GSDocument> doc = Load(path, Progress(), cameras);
  for (const std::string& warning : doc->Warnings)
  {
    std::cerr << "vis4gs view: warning: " << warning << "\n";
  }
  vtkSmartPointer<vtkTable> scoreCameras = doc->ScoreCameras();
  if (doc->Scene)
  {
    doc->Scored = ComputeScores(
      doc->Scene, scoreCameras, doc->CamerasWithImages > 0, Progress(), nullptr, 0, nullptr, path);
  }
  doc->DumpInputs(folder);
}

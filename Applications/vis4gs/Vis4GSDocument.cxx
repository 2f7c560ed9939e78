// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSDocument.h"

#include "GaussianIO.h"
#include "GaussianMath.h"
#include "ImageIO.h"
#include "TrainingLogReader.h"
#include "Vis4GSDataModel.h"

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
#include "vtkUnsignedCharArray.h"

#ifdef VIS4GS_HAVE_GENEALOGY_FILTER
#include "vtkGaussianGenealogyTreeFilter.h"
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace
{
vtkSmartPointer<vtkTable> MetricsToTable(const vis4gs::MetricsTable& m)
{
  auto table = vtkSmartPointer<vtkTable>::New();
  vtkNew<vtkIntArray> it;
  it->SetName("iteration");
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
  add("num_gaussians", count);
  add("loss", m.Loss);
  add("psnr", m.Psnr);
  add("ssim", m.Ssim);
  add("lpips", m.Lpips);
  return table;
}
}

//------------------------------------------------------------------------------
std::shared_ptr<Vis4GSDocument> Vis4GSDocument::Load(const std::string& path,
  const Progress& progress)
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
  std::ostringstream timings;
  auto stage = [&](const char* what)
  {
    const auto now = std::chrono::steady_clock::now();
    timings << " " << what << " " << std::chrono::duration<double>(now - lap).count() << " s;";
    lap = now;
  };
  if (!isLog)
  {
    report(0.1, "reading the scene");
    vis4gs::GaussianCloud cloud = vis4gs::ReadGaussianScene(path);
    doc->Scene = vtkSmartPointer<vtkPolyData>::New();
    vis4gs::GaussianCloudToPolyData(cloud, doc->Scene);
    text << path << ": " << cloud.Count << " Gaussians (a scene file: no training history)\n";
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
    if (!doc->Snapshots.empty())
    {
      stage("header, metrics, cameras");
      report(0.2, "reading the last snapshot");
      doc->LoadIteration(doc->Snapshots.back());
      stage("last snapshot");
    }
    if (log.HasEvents())
    {
      report(0.5, "reading the events");
      const vis4gs::EventTable events = log.ReadEvents();
      text << "events: " << events.Size() << "\n";
      stage("events");
#ifdef VIS4GS_HAVE_GENEALOGY_FILTER
      report(0.6, "building the genealogy");
      vtkNew<vtkTable> table;
      vtkNew<vtkIntArray> it;
      it->SetName("Iteration");
      vtkNew<vtkUnsignedCharArray> kind;
      kind->SetName("Kind");
      vtkNew<vtkIdTypeArray> parent, child;
      parent->SetName("Parent");
      child->SetName("Child");
      const std::size_t ne = events.Size();
      it->SetNumberOfTuples(static_cast<vtkIdType>(ne));
      kind->SetNumberOfTuples(static_cast<vtkIdType>(ne));
      parent->SetNumberOfTuples(static_cast<vtkIdType>(ne));
      child->SetNumberOfTuples(static_cast<vtkIdType>(ne));
      for (std::size_t e = 0; e < ne; ++e)
      {
        it->SetValue(e, events.Iteration[e]);
        kind->SetValue(e, static_cast<unsigned char>(events.Kind[e]));
        parent->SetValue(e, events.Parent[e]);
        child->SetValue(e, events.Child[e]);
      }
      table->AddColumn(it);
      table->AddColumn(kind);
      table->AddColumn(parent);
      table->AddColumn(child);
      vtkNew<vtkGaussianGenealogyTreeFilter> filter;
      filter->SetInputData(table);
      if (!doc->Snapshots.empty())
      {
        vis4gs::SnapshotReadOptions ids;
        ids.Arrays = vis4gs::SnapshotIds;
        const auto first = log.ReadSnapshot(doc->Snapshots.front(), ids);
        vtkNew<vtkIdTypeArray> initial;
        for (std::size_t i = 0; i < first.Count; ++i)
        {
          initial->InsertNextValue(first.GetId(i));
        }
        filter->SetInitialIds(initial);
      }
      filter->SetLastIteration(
        std::max(header.Iterations, doc->Snapshots.empty() ? 0 : doc->Snapshots.back()));
      filter->SetRepairUnknownParents(true);
      stage("event table, initial ids");
      filter->Update();
      stage("genealogy filter");
      doc->Tree = vtkTree::SafeDownCast(filter->GetOutputDataObject(0));
      doc->Bands = filter->GetFamilyBands();
      if (doc->Tree)
      {
        text << "genealogy: " << doc->Tree->GetNumberOfVertices() - 1 << " Gaussians ever born, "
             << (doc->Bands ? doc->Bands->GetNumberOfRows() : 0) << " families\n";
      }
#else
      text << "genealogy: not available (built without Filters/Genealogy)\n";
#endif
    }
  }
  report(1.0, "done");
  doc->Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  text << "loaded in " << doc->Seconds << " s (" << timings.str() << " )\n";
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
  vtkNew<vtkCallbackCommand> errors;
  bool failed = false;
  errors->SetClientData(&failed);
  errors->SetCallback(
    [](vtkObject*, unsigned long, void* client, void*) { *static_cast<bool*>(client) = true; });
  filter->AddObserver(vtkCommand::ErrorEvent, errors);
  filter->Update();
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

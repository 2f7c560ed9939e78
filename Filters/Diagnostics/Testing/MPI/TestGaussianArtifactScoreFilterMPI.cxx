/*=========================================================================

  Program:   Vis4GS
  Module:    TestGaussianArtifactScoreFilterMPI.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
// vtkGaussianArtifactScoreFilter distributed over MPI processes (run under mpiexec -n K)
// against the single-process Core computation on every process: View Coverage, the visible
// view counts and the flags identical, Blur and Needle identical with the fixed split and within
// 1e-12 relative with the machine's view queue (whose assignment varies), for the demo log
// and a random scene with stiff Gaussians, for every approximation of the scores, with fewer
// views than processes, and a failing view on one process (every process fails, the error
// names the process and the view).
#include "vtkGaussianArtifactScoreFilter.h"
#include "vtkGaussianSceneReader.h"

#include "ArtifactScores.h"
#include "GaussianIO.h"
#include "ImageIO.h"
#include "LossMap.h"
#include "ScoreRegistry.h"
#include "TrainingLogReader.h"
#include "Vis4GSDataModel.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkMPIController.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkTable.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <string>
#include <vector>

namespace
{
int Failures = 0;
int Rank = 0;
void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "FAILED (process " << Rank << "): " << what << "\n";
    ++Failures;
  }
}

struct Scene
{
  std::string Name;
  vis4gs::GaussianCloud Cloud;
  std::vector<vis4gs::Camera> Cameras;
};

vis4gs::Camera LookAtOrigin(const std::string& name, double angle, double distance)
{
  vis4gs::Camera c;
  c.Name = name;
  c.Width = 64;
  c.Height = 48;
  c.Fx = c.Fy = 56;
  c.Cx = 32;
  c.Cy = 24;
  // Camera on a circle in the xz-plane looking at the origin (rows: right, down, forward).
  const double s = std::sin(angle), co = std::cos(angle);
  const double eye[3] = { distance * s, 0.3, -distance * co };
  const double f[3] = { -s, 0, co }, r[3] = { co, 0, s }, d[3] = { 0, 1, 0 };
  const double* rows[3] = { r, d, f };
  for (int i = 0; i < 3; ++i)
  {
    c.WorldToCamera[4 * i + 0] = rows[i][0];
    c.WorldToCamera[4 * i + 1] = rows[i][1];
    c.WorldToCamera[4 * i + 2] = rows[i][2];
    c.WorldToCamera[4 * i + 3] = -(rows[i][0] * eye[0] + rows[i][1] * eye[1] + rows[i][2] * eye[2]);
  }
  return c;
}

// Random Gaussians, a third of them stiff (needles and disks, scale ratios up to e^9), with
// opacities from almost 0 to almost 1, a few NaN and one huge; random training images.
Scene RandomStiffScene(const std::filesystem::path& folder)
{
  Scene s;
  s.Name = "random stiff scene";
  std::mt19937 rng(18);
  std::uniform_real_distribution<float> u(-1, 1);
  const std::size_t n = 3000;
  s.Cloud.Resize(n, 0);
  for (std::size_t i = 0; i < n; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      s.Cloud.Positions[3 * i + k] = 1.5f * u(rng);
      s.Cloud.LogScales[3 * i + k] = -3.5f + 1.5f * u(rng);
      s.Cloud.SH[3 * i + k] = u(rng);
    }
    if (i % 3 == 0)
    {
      s.Cloud.LogScales[3 * i + i % 2] += 4.5f; // needle or disk
      s.Cloud.LogScales[3 * i + 2] -= 4.5f;
    }
    for (int k = 0; k < 4; ++k)
    {
      s.Cloud.Rotations[4 * i + k] = u(rng);
    }
    s.Cloud.OpacityLogits[i] = 6 * u(rng);
  }
  s.Cloud.Positions[3 * 7] = std::nanf("");
  s.Cloud.LogScales[3 * 11] = 3;
  for (int v = 0; v < 7; ++v)
  {
    s.Cameras.push_back(LookAtOrigin("rand" + std::to_string(v), 0.8 * v, 4.0 + 0.3 * v));
    // Different sizes make the views' costs differ.
    s.Cameras.back().Width = 64 + 16 * (v % 3);
    s.Cameras.back().Cx = s.Cameras.back().Width / 2.0;
    vis4gs::Image image;
    image.Width = s.Cameras.back().Width;
    image.Height = 48;
    image.Pixels.resize(3 * static_cast<std::size_t>(image.Width) * 48);
    for (float& p : image.Pixels)
    {
      p = 0.5f + 0.5f * u(rng);
    }
    const auto file = folder / ("rand" + std::to_string(v) + ".png");
    if (Rank == 0)
    {
      vis4gs::WritePng(file.string(), image);
    }
    s.Cameras.back().ImagePath = file.string();
  }
  s.Cameras[3].Split = vis4gs::CameraSplit::Test;
  return s;
}

// The demo log's last snapshot with its views at a quarter of their size (512x512 -> 128x128,
// Camera::Resized keeps the field of view; the images box-filtered): what is compared here is
// the distribution over processes, not the resolution, and the full-size scores of every
// configuration on 2 and 3 processes would take minutes.
Scene DemoLog(const std::string& path, const std::filesystem::path& folder)
{
  Scene s;
  s.Name = "demo log";
  const vis4gs::TrainingLogReader log(path);
  vis4gs::SnapshotReadOptions options;
  options.ShDegree = -1;
  int logged = 0;
  s.Cloud = log.ReadNearestSnapshot(log.GetSnapshotIterations().back(), options, &logged);
  s.Cameras = log.ReadCameras();
  const int factor = 4;
  for (vis4gs::Camera& c : s.Cameras)
  {
    const int width = std::max(1, c.Width / factor), height = std::max(1, c.Height / factor);
    const std::string prefix = "/images/", image = c.ImagePath;
    c = c.Resized(width, height);
    if (image.rfind(prefix, 0) == 0)
    {
      const std::string name = image.substr(prefix.size());
      const auto file = folder / ("demo-" + name + ".png");
      if (Rank == 0)
      {
        int w = 0, h = 0;
        const std::vector<unsigned char> pixels = log.ReadImage(name, w, h);
        vis4gs::WritePng(file.string(),
          vis4gs::BoxDownsample(vis4gs::ImageFromBytes(pixels.data(), w, h, 3), width, height));
      }
      c.ImagePath = file.string();
    }
  }
  return s;
}

struct Config
{
  std::string Name;
  vis4gs::ScoreSettings Settings;
};

std::vector<Config> Configs(std::size_t trainViews)
{
  std::vector<Config> configs;
  auto add = [&](const std::string& name, auto change)
  {
    Config c;
    c.Name = name;
    change(c.Settings);
    configs.push_back(c);
  };
  add("exact", [](vis4gs::ScoreSettings&) {});
  add("loss resolution 2", [](vis4gs::ScoreSettings& s) { s.LossResolution = 2; });
  add("loss resolution 8", [](vis4gs::ScoreSettings& s) { s.LossResolution = 8; });
  add("coverage resolution 4", [](vis4gs::ScoreSettings& s) { s.CoverageResolution = 4; });
  add("coverage only, resolution 2",
    [](vis4gs::ScoreSettings& s)
    {
      s.Request.Blur = s.Request.Needle = false;
      s.CoverageResolution = 2;
    });
  add("view stride 2", [](vis4gs::ScoreSettings& s) { s.ViewStride = 2; });
  // The render-cost pass beside the others: its sums reduce with no code of its own.
  add("render cost too",
    [](vis4gs::ScoreSettings& s) { s.Request.RenderCost = s.Request.CostPerContribution = true; });
  add("ellipse footprint",
    [](vis4gs::ScoreSettings& s) { s.Footprint = vis4gs::FootprintMode::Ellipse3Sigma; });
  add("float accumulation",
    [](vis4gs::ScoreSettings& s) { s.Accumulation = vis4gs::FootprintAccumulation::Float; });
  add("occlusion threshold 0.05", [](vis4gs::ScoreSettings& s) { s.OcclusionThreshold = 0.05; });
  add("lambda 0.7, blur only",
    [](vis4gs::ScoreSettings& s)
    {
      s.Lambda = 0.7;
      s.Request.Needle = s.Request.ViewCoverage = false;
    });
  // One view for all processes: every process but one renders none.
  add("one view",
    [trainViews](vis4gs::ScoreSettings& s) { s.ViewStride = static_cast<int>(trainViews); });
  return configs;
}

void Configure(vtkGaussianArtifactScoreFilter* filter, const vis4gs::ScoreSettings& s)
{
  for (const vis4gs::ScoreDefinition& d : vis4gs::ScoreDefinitions())
  {
    filter->EnableScore(d.Name, s.Request.*(d.Request));
  }
  filter->SetLossResolution(s.LossResolution);
  filter->SetCoverageResolution(s.CoverageResolution);
  filter->SetViewStride(s.ViewStride);
  filter->SetFootprintMode(s.Footprint == vis4gs::FootprintMode::Ellipse3Sigma ? 1 : 0);
  filter->SetFloatAccumulation(s.Accumulation == vis4gs::FootprintAccumulation::Float);
  filter->SetOcclusionThreshold(s.OcclusionThreshold);
  filter->SetLambda(s.Lambda);
}

void CompareExact(vtkDataArray* a, const std::vector<double>& v, const std::string& what)
{
  bool same = a && a->GetNumberOfTuples() == static_cast<vtkIdType>(v.size());
  for (std::size_t i = 0; same && i < v.size(); ++i)
  {
    same = a->GetTuple1(static_cast<vtkIdType>(i)) == v[i];
  }
  Check(same, what + ": not identical to one process");
}

void CompareRelative(vtkDataArray* a, const std::vector<double>& v, const std::string& what)
{
  if (!a || a->GetNumberOfTuples() != static_cast<vtkIdType>(v.size()))
  {
    Check(false, what + ": missing or wrong size");
    return;
  }
  double worst = 0;
  for (std::size_t i = 0; i < v.size(); ++i)
  {
    const double x = a->GetTuple1(static_cast<vtkIdType>(i));
    if (x == v[i] || (std::isnan(x) && std::isnan(v[i])))
    {
      continue; // equal, infinities included
    }
    const double scale = std::max(std::abs(x), std::abs(v[i]));
    if (scale > 0)
    {
      worst = std::max(worst, std::abs(x - v[i]) / scale);
    }
  }
  Check(worst <= 1e-12, what + ": relative difference " + std::to_string(worst) + " > 1e-12");
}

void OnError(vtkObject*, unsigned long, void* clientData, void* callData)
{
  auto* messages = static_cast<std::string*>(clientData);
  *messages += callData ? static_cast<const char*>(callData) : "";
  *messages += "\n";
}

void TestScene(vtkMPIController* controller, const Scene& scene)
{
  auto provider = [](std::size_t, const vis4gs::Camera& c, vis4gs::Image& image)
  {
    if (c.ImagePath.empty() || !std::filesystem::exists(c.ImagePath))
    {
      return false;
    }
    image = vis4gs::LoadTrainingImage(c);
    return true;
  };
  vtkNew<vtkPolyData> poly;
  vis4gs::GaussianCloudToPolyData(scene.Cloud, poly);
  vtkNew<vtkTable> table;
  vis4gs::CamerasToTable(scene.Cameras, table);
  std::size_t train = 0;
  for (const vis4gs::Camera& c : scene.Cameras)
  {
    train += c.Split == vis4gs::CameraSplit::Train ? 1 : 0;
  }
  for (const Config& config : Configs(train))
  {
    const vis4gs::GaussianScores one =
      vis4gs::ComputeGaussianScores(scene.Cloud, scene.Cameras, config.Settings, provider);
    // The views from the machine's shared queue (the default), then the fixed split.
    for (const bool queue : { true, false })
    {
      const std::string what =
        scene.Name + ", " + config.Name + (queue ? ", view queue" : ", fixed split");
      vtkNew<vtkGaussianArtifactScoreFilter> filter;
      filter->SetController(controller);
      filter->SetInputData(poly);
      filter->SetCamerasData(table);
      Configure(filter, config.Settings);
      filter->SetDynamicViewBalancing(queue);
      filter->Update();
      vtkPointData* pd = filter->GetOutput()->GetPointData();
      const auto& r = config.Settings.Request;
      if (r.ViewCoverage)
      {
        CompareExact(pd->GetArray(vis4gs::arrays::ViewCoverage), one.ViewCoverage, what);
      }
      // Compensated sums (ScorePartials::BlurCompensation): the fixed split, whose views and
      // order are the same on every run, gives one process's doubles bit for bit; with the
      // queue the assignment varies with timing, and a sum within ~2^-77 of a rounding boundary
      // could in principle round the other way, so that case is compared to 1e-12.
      auto compare = queue ? CompareRelative : CompareExact;
      if (r.Blur)
      {
        compare(pd->GetArray(vis4gs::arrays::BlurScore), one.BlurScore, what + " blur");
      }
      if (r.Needle)
      {
        compare(pd->GetArray(vis4gs::arrays::NeedleScore), one.NeedleScore, what + " needle");
      }
      if (r.RenderCost)
      {
        // Integer sums: exact in any order.
        CompareExact(pd->GetArray("RenderCost"), one.RenderCost, what + " render cost");
      }
      if (r.CostPerContribution)
      {
        CompareRelative(
          pd->GetArray("CostPerContribution"), one.CostPerContribution, what + " per contribution");
      }
      std::vector<double> flags(one.Flags.begin(), one.Flags.end());
      CompareExact(pd->GetArray("NoVisibleView"), flags, what + " flags");
      Check(filter->GetNumberOfViewsUsed() == static_cast<vtkIdType>(one.ViewsUsed),
        what + ": views used");
      Check(filter->GetNumberOfViewsWithoutImage() == static_cast<vtkIdType>(one.ViewsWithoutImage),
        what + ": views without image");
      // Every view rendered exactly once over the processes (the scores above would differ if a
      // view were rendered twice and another not at all), and by its owner in the fixed split
      // (also with the queue when there is no blur/needle pass to take views from it).
      long long mine = filter->GetNumberOfViewsRendered(), all = 0;
      controller->AllReduce(&mine, &all, 1, vtkCommunicator::SUM_OP);
      Check(all == static_cast<long long>(one.ViewsUsed), what + ": views rendered in all");
      if (!queue || !(r.Blur || r.Needle))
      {
        const std::vector<int> owner = vis4gs::SplitViewsByCost(
          vis4gs::EstimateViewCosts(scene.Cloud, scene.Cameras, one.ViewIndices, config.Settings),
          controller->GetNumberOfProcesses());
        long long expected = 0;
        for (int o : owner)
        {
          expected += o == Rank ? 1 : 0;
        }
        Check(mine == expected, what + ": views rendered here");
      }
    }
  }

  // A view whose image cannot be read is left out of the image scores by the process that owns
  // it, as a view without image, with a warning naming the file (issue 32): the scores equal
  // one process's with that view's image missing.
  std::vector<vis4gs::Camera> broken = scene.Cameras;
  vis4gs::ScoreSettings exact;
  const std::vector<std::size_t> views = vis4gs::SelectViews(broken, exact);
  const std::vector<int> owner =
    vis4gs::SplitViewsByCost(vis4gs::EstimateViewCosts(scene.Cloud, broken, views, exact),
      controller->GetNumberOfProcesses());
  const int victim = controller->GetNumberOfProcesses() - 1;
  std::size_t badView = views.size();
  for (std::size_t k = 0; k < views.size(); ++k)
  {
    if (owner[k] == victim)
    {
      badView = views[k];
      break;
    }
  }
  if (badView == views.size())
  {
    return; // the last process has no view (more processes than views)
  }
  const auto badFile = std::filesystem::path(broken[badView].ImagePath).parent_path() /
    ("broken-" + std::to_string(badView) + ".png");
  if (Rank == 0)
  {
    std::ofstream(badFile) << "not a PNG";
  }
  controller->Barrier();
  broken[badView].ImagePath = badFile.string();
  vtkNew<vtkTable> brokenTable;
  vis4gs::CamerasToTable(broken, brokenTable);
  // With the queue (the default) whichever process takes the view warns; the fixed split's
  // owner is the victim.
  for (const bool queue : { false, true })
  {
    vtkNew<vtkGaussianArtifactScoreFilter> filter;
    filter->SetDynamicViewBalancing(queue);
    filter->SetController(controller);
    filter->SetInputData(poly);
    filter->SetCamerasData(brokenTable);
    std::string errors;
    vtkNew<vtkCallbackCommand> onError;
    onError->SetCallback(OnError);
    onError->SetClientData(&errors);
    filter->AddObserver(vtkCommand::WarningEvent, onError);
    exact.Request.ViewCoverage = exact.Request.Blur = exact.Request.Needle = true;
    Configure(filter, exact);
    filter->Update();
    std::vector<vis4gs::Camera> without = scene.Cameras;
    without[badView].ImagePath.clear();
    const vis4gs::GaussianScores one =
      vis4gs::ComputeGaussianScores(scene.Cloud, without, exact, provider);
    vtkPointData* pd = filter->GetOutput()->GetPointData();
    CompareExact(pd->GetArray(vis4gs::arrays::ViewCoverage), one.ViewCoverage, scene.Name + " bad");
    CompareRelative(pd->GetArray(vis4gs::arrays::BlurScore), one.BlurScore, scene.Name + " bad");
    CompareRelative(
      pd->GetArray(vis4gs::arrays::NeedleScore), one.NeedleScore, scene.Name + " bad");
    Check(filter->GetNumberOfViewsWithoutImage() == static_cast<vtkIdType>(one.ViewsWithoutImage),
      scene.Name + ": the unreadable view does not count as one without image");
    const bool named = errors.find(badFile.filename().string()) != std::string::npos;
    int warned = named ? 1 : 0, warnedAll = 0;
    controller->AllReduce(&warned, &warnedAll, 1, vtkCommunicator::SUM_OP);
    Check(warnedAll == 1,
      scene.Name + ": " + std::to_string(warnedAll) + " processes warn of " + badFile.string());
    if (!queue && Rank == victim)
    {
      Check(named, scene.Name + ": no warning names " + badFile.string() + ": " + errors);
    }
  }
}
}

// The preparation shared by the processes of this machine (Vis4GSNodeSharedMemory) gives the
// scores of every process preparing alone bit for bit (the same views on the same processes),
// and so does the fallback when one process cannot map the shared memory
// (VIS4GS_TEST_NO_SHARED_MEMORY), which that process reports in a warning.
void TestSharedPreparation(vtkMPIController* controller, const Scene& scene)
{
  vtkNew<vtkPolyData> poly;
  vis4gs::GaussianCloudToPolyData(scene.Cloud, poly);
  vtkNew<vtkTable> table;
  vis4gs::CamerasToTable(scene.Cameras, table);
  const int ranks = controller->GetNumberOfProcesses();
  auto run = [&](bool share, bool refuse, int& processes, std::string& warnings)
  {
    if (refuse)
    {
      setenv("VIS4GS_TEST_NO_SHARED_MEMORY", std::to_string(ranks - 1).c_str(), 1);
    }
    vtkNew<vtkGaussianArtifactScoreFilter> filter;
    filter->SetController(controller);
    filter->SetInputData(poly);
    filter->SetCamerasData(table);
    Check(filter->SetScores("coverage,blur,needle,render-cost"), "SetScores");
    filter->SetSharePreparation(share);
    filter->SetDynamicViewBalancing(false); // (bit for bit needs the same views on each process)
    vtkNew<vtkCallbackCommand> onWarning;
    onWarning->SetCallback(OnError);
    onWarning->SetClientData(&warnings);
    filter->AddObserver(vtkCommand::WarningEvent, onWarning);
    filter->Update();
    unsetenv("VIS4GS_TEST_NO_SHARED_MEMORY");
    processes = filter->GetPreparationProcesses();
    vtkSmartPointer<vtkPolyData> out = filter->GetOutput();
    return out;
  };
  int alone = 0, shared = 0, refused = 0;
  std::string w0, w1, w2;
  const auto a = run(false, false, alone, w0);
  const auto b = run(true, false, shared, w1);
  const auto c = run(true, true, refused, w2);
  const std::string what = scene.Name + ", shared preparation";
  // (every process of this test runs on one machine)
  Check(alone == 1 && shared == ranks && refused == 1,
    what + ": processes sharing " + std::to_string(alone) + " / " + std::to_string(shared) + " / " +
      std::to_string(refused));
  for (const char* name : { vis4gs::arrays::ViewCoverage,
         vis4gs::arrays::BlurScore,
         vis4gs::arrays::NeedleScore,
         "RenderCost",
         "NoVisibleView" })
  {
    vtkDataArray* x = a->GetPointData()->GetArray(name);
    for (vtkPolyData* other : { b.GetPointer(), c.GetPointer() })
    {
      vtkDataArray* y = other->GetPointData()->GetArray(name);
      bool same = x && y && x->GetNumberOfTuples() == y->GetNumberOfTuples() &&
        x->GetNumberOfTuples() == static_cast<vtkIdType>(scene.Cloud.Count);
      for (vtkIdType i = 0; same && i < x->GetNumberOfTuples(); ++i)
      {
        const double u = x->GetTuple1(i), v = y->GetTuple1(i);
        same = std::memcmp(&u, &v, sizeof(u)) == 0;
      }
      Check(same, what + ": " + name + " not bit-identical to the unshared preparation's");
    }
  }
  const bool warned = w2.find("VIS4GS_TEST_NO_SHARED_MEMORY") != std::string::npos &&
    w2.find("each prepared it alone") != std::string::npos;
  Check(warned == (Rank == ranks - 1), what + ": the fallback's warning: '" + w2 + "'");
  Check((w0 + w1).find("could not share") == std::string::npos,
    what + ": a fallback's warning without a fallback: " + w0 + w1);
}

// The pipeline pvbatch under mpiexec runs: every process asks for its own piece of the output,
// and a reader that cannot split its file gives Gaussians to piece 0 only. The filter asks for
// the whole scene on every process (else piece 1 had no Gaussians and process 0 waited forever
// in the reduction), and piece 0 holds every Gaussian with one process's scores.
void TestPieces(vtkMPIController* controller,
  const Scene& scene,
  const std::filesystem::path& folder)
{
  const std::string ply = (folder / "pieces.ply").string();
  if (Rank == 0)
  {
    vis4gs::WriteGaussianPly(ply, scene.Cloud);
  }
  controller->Barrier();
  vis4gs::ScoreSettings coverage;
  coverage.Request.Blur = coverage.Request.Needle = coverage.Request.NeedleShape = false;
  const vis4gs::GaussianScores one =
    vis4gs::ComputeGaussianScores(scene.Cloud, scene.Cameras, coverage);
  vtkNew<vtkGaussianSceneReader> reader;
  reader->SetFileName(ply.c_str());
  vtkNew<vtkTable> table;
  vis4gs::CamerasToTable(scene.Cameras, table);
  vtkNew<vtkGaussianArtifactScoreFilter> filter;
  filter->SetController(controller);
  filter->SetInputConnection(reader->GetOutputPort());
  filter->SetCamerasData(table);
  filter->SetScores("coverage");
  filter->UpdatePiece(Rank, controller->GetNumberOfProcesses(), 0);
  vtkPolyData* out = filter->GetOutput();
  const std::string what = scene.Name + ", piece " + std::to_string(Rank) + " of " +
    std::to_string(controller->GetNumberOfProcesses());
  if (Rank == 0)
  {
    CompareExact(out->GetPointData()->GetArray(vis4gs::arrays::ViewCoverage),
      one.ViewCoverage,
      what + ": coverage of a reader's scene");
  }
  else
  {
    Check(out->GetNumberOfPoints() == 0, what + ": no Gaussian outside piece 0");
  }
  long long mine = filter->GetNumberOfViewsRendered(), all = 0;
  controller->AllReduce(&mine, &all, 1, vtkCommunicator::SUM_OP);
  Check(all == static_cast<long long>(one.ViewsUsed), what + ": views shared by the processes");
}

int main(int argc, char* argv[])
{
  vtkNew<vtkMPIController> controller;
  controller->Initialize(&argc, &argv);
  Rank = controller->GetLocalProcessId();
  if (argc < 3)
  {
    std::cerr << "usage: TestGaussianArtifactScoreFilterMPI DEMO.h5 SCRATCH_FOLDER\n";
    controller->Finalize();
    return 2;
  }
  const std::filesystem::path folder = argv[2];
  if (Rank == 0)
  {
    std::filesystem::create_directories(folder);
  }
  controller->Barrier();
  try
  {
    const Scene random = RandomStiffScene(folder);
    const Scene demo = DemoLog(argv[1], folder);
    controller->Barrier(); // process 0's images are written
    TestScene(controller, random);
    TestScene(controller, demo);
    TestPieces(controller, random, folder);
    TestSharedPreparation(controller, random);
  }
  catch (const std::exception& e)
  {
    Check(false, std::string("exception: ") + e.what());
  }
  int mine = Failures, all = 0;
  controller->AllReduce(&mine, &all, 1, vtkCommunicator::SUM_OP);
  if (Rank == 0)
  {
    std::cout << (all == 0 ? "PASSED" : "FAILED") << " on " << controller->GetNumberOfProcesses()
              << " processes\n";
  }
  controller->Finalize();
  return all == 0 ? 0 : 1;
}

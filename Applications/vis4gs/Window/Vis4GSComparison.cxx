// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSComparison.h"

#include "Vis4GSDataModel.h"
#include "Vis4GSPipeline.h"
#include "Vis4GSSceneCameras.h"
#include "Vis4GSStateFiles.h"
#include "vtkGaussianSceneReader.h"
#include "vtkGaussianSession.h"
#include "vtkGaussianStateComparisonFilter.h"

#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkTable.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <stdexcept>

namespace
{
namespace fs = std::filesystem;

// Measures wall and process CPU seconds from construction to Stop().
struct Stopwatch
{
  std::chrono::steady_clock::time_point Wall = std::chrono::steady_clock::now();
  std::clock_t Cpu = std::clock();
  void Stop(double& wall, double& cpu) const
  {
    wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - this->Wall).count();
    cpu = static_cast<double>(std::clock() - this->Cpu) / CLOCKS_PER_SEC;
  }
};

// "FILE@N" -> FILE and N; anything else is a plain path (iteration -1: the last).
void SplitIteration(const std::string& spec, std::string& path, int& iteration)
{
  path = spec;
  iteration = -1;
  const std::size_t at = spec.rfind('@');
  if (at == std::string::npos || at + 1 == spec.size() ||
    !std::all_of(spec.begin() + static_cast<std::ptrdiff_t>(at) + 1,
      spec.end(),
      [](unsigned char c) { return std::isdigit(c) != 0; }))
  {
    return;
  }
  path = spec.substr(0, at);
  iteration = std::stoi(spec.substr(at + 1));
}

// The rows of the reader's merged metrics table where one of @p prefix's quality columns (or,
// for training rows, the count) is finite, with the columns named as the timeline view reads
// them: the merged table holds NaN for the iterations measured only on the other split.
vtkSmartPointer<vtkTable> MetricRows(vtkTable* merged, const std::string& prefix)
{
  namespace a = vis4gs::arrays;
  auto* iteration = vtkDataArray::SafeDownCast(merged->GetColumnByName(a::MetricIteration));
  if (!iteration)
  {
    return nullptr;
  }
  std::vector<std::pair<std::string, vtkDataArray*>> columns;
  for (const char* name : { a::MetricPSNR, a::MetricSSIM, a::MetricLPIPS, a::MetricGaussians })
  {
    const bool count = std::string(name) == a::MetricGaussians;
    vtkDataArray* column = vtkDataArray::SafeDownCast(
      merged->GetColumnByName((count ? std::string(name) : prefix + name).c_str()));
    if (column && (!count || prefix.empty()))
    {
      columns.emplace_back(name, column);
    }
  }
  auto table = vtkSmartPointer<vtkTable>::New();
  vtkNew<vtkFloatArray> x;
  x->SetName(a::MetricIteration);
  table->AddColumn(x);
  std::vector<vtkSmartPointer<vtkFloatArray>> y;
  for (const auto& column : columns)
  {
    y.push_back(vtkSmartPointer<vtkFloatArray>::New());
    y.back()->SetName(column.first.c_str());
    table->AddColumn(y.back());
  }
  for (vtkIdType r = 0; r < iteration->GetNumberOfTuples(); ++r)
  {
    const bool measured = std::any_of(columns.begin(),
      columns.end(),
      [r](const std::pair<std::string, vtkDataArray*>& c)
      { return std::isfinite(c.second->GetComponent(r, 0)); });
    if (measured)
    {
      x->InsertNextValue(static_cast<float>(iteration->GetComponent(r, 0)));
      for (std::size_t k = 0; k < columns.size(); ++k)
      {
        y[k]->InsertNextValue(static_cast<float>(columns[k].second->GetComponent(r, 0)));
      }
    }
  }
  return table->GetNumberOfRows() > 0 ? table : nullptr;
}

Vis4GSComparison::State ReadState(const std::string& path,
  int iteration,
  const std::string& cameras)
{
  if (!fs::exists(path))
  {
    throw std::runtime_error(path + ": no such file");
  }
  Vis4GSComparison::State s;
  s.Path = path;
  s.Name = fs::path(path).filename().string();
  const bool log = Vis4GSIsLogPath(path);
  if (!log && iteration >= 0)
  {
    throw std::runtime_error(path + ": @ITERATION needs a training log, not a scene file");
  }
  // A session per state, as `vis4gs compare` reads them: a log's snapshot, cameras and metrics,
  // or a scene file with its ids when it has them and the cameras found for it.
  auto session = vtkSmartPointer<vtkGaussianSession>::New();
  session->SetFileName(path.c_str());
  session->SetIteration(iteration);
  session->ComputeScoresOff();
  session->SetIdProperty("id");
  session->GetSceneReader()->IdPropertyOptionalOn();
  session->SetCamerasFileName(cameras.c_str());
  Vis4GSSceneCameraRules(session->GetCameraReader());
  for (const int port : { vtkGaussianSession::GaussiansPort,
         vtkGaussianSession::CamerasPort,
         vtkGaussianSession::MetricsPort })
  {
    const std::string errors = Vis4GSUpdate(session, port);
    if (!errors.empty())
    {
      throw std::runtime_error(errors);
    }
  }
  s.Scene = vtkSmartPointer<vtkPolyData>::New();
  s.Scene->ShallowCopy(session->GetGaussiansOutput());
  if (vtkTable* table = session->GetCamerasOutput())
  {
    if (table->GetNumberOfRows() > 0)
    {
      s.Cameras = vtkSmartPointer<vtkTable>::New();
      s.Cameras->ShallowCopy(table);
    }
  }
  if (session->GetIsTrainingLog())
  {
    s.Iteration = session->GetLoadedIteration();
    s.Name += " @" + std::to_string(s.Iteration);
    s.Session = session;
    if (vtkTable* merged = session->GetMetricsOutput())
    {
      s.Metrics = MetricRows(merged, "");
      s.TestMetrics = MetricRows(merged, vis4gs::arrays::MetricTestPrefix);
    }
  }
  return s;
}

// The set whose colour a Gaussian with the StateChange @p flags takes in the overlay.
int OverlaySet(unsigned flags)
{
  return (flags & vis4gs::StateDied)        ? Vis4GSComparison::DIED
    : (flags & vis4gs::StateBorn)           ? Vis4GSComparison::BORN
    : (flags & vis4gs::StateMoved)          ? Vis4GSComparison::MOVED
    : (flags & vis4gs::StateScaleChanged)   ? Vis4GSComparison::SCALE
    : (flags & vis4gs::StateOpacityChanged) ? Vis4GSComparison::OPACITY
                                            : Vis4GSComparison::UNCHANGED;
}
}

//------------------------------------------------------------------------------
const char* Vis4GSComparison::SetName(int set)
{
  static const char* names[NUMBER_OF_SETS] = {
    "born", "died", "moved", "opacity changed", "scale changed", "unchanged"
  };
  return set >= 0 && set < NUMBER_OF_SETS ? names[set] : "";
}

//------------------------------------------------------------------------------
std::array<unsigned char, 3> Vis4GSComparison::SetColor(int set)
{
  // Distinct hues (the tab10 palette) and a neutral grey for the unchanged Gaussians; none is
  // near the selection highlight (yellow) of the comparison window.
  static const std::array<unsigned char, 3> colors[NUMBER_OF_SETS] = { { { 44, 160, 44 } },
    { { 214, 39, 40 } },
    { { 31, 119, 180 } },
    { { 255, 127, 14 } },
    { { 148, 103, 189 } },
    { { 120, 120, 120 } } };
  return colors[std::clamp(set, 0, NUMBER_OF_SETS - 1)];
}

//------------------------------------------------------------------------------
std::shared_ptr<Vis4GSComparison> Vis4GSComparison::Load(const std::string& a,
  int iterationA,
  const std::string& b,
  const std::string& cameras)
{
  const Stopwatch watch;
  auto c = std::make_shared<Vis4GSComparison>();
  c->A = ReadState(a, iterationA, cameras);
  std::string pathB;
  int iterationB = -1;
  SplitIteration(b, pathB, iterationB);
  if (pathB.empty()) // "@N": another iteration of A's log
  {
    if (!Vis4GSIsLogPath(a))
    {
      throw std::runtime_error(b + ": @ITERATION compares two iterations of a training log, but " +
        a + " is a scene file");
    }
    pathB = a;
  }
  c->B = ReadState(pathB, iterationB, cameras);
  std::error_code ec;
  c->SameLog = Vis4GSIsLogPath(a) && fs::equivalent(a, pathB, ec);
  if (!c->B.Cameras) // two scenes of the same cameras: A's serve both
  {
    c->B.Cameras = c->A.Cameras;
  }
  watch.Stop(c->LoadSeconds, c->LoadCpuSeconds);
  return c;
}

//------------------------------------------------------------------------------
void Vis4GSComparison::Compare(const vis4gs::StateThresholds& thresholds)
{
  const Stopwatch watch;
  this->Thresholds = thresholds;
  vtkNew<vtkGaussianStateComparisonFilter> filter;
  filter->SetInputData(0, this->A.Scene);
  filter->SetInputData(1, this->B.Scene);
  filter->SetMoveThreshold(thresholds.Move);
  filter->SetOpacityThreshold(thresholds.Opacity);
  filter->SetScaleThreshold(thresholds.Scale);
  filter->Update();
  this->Differences = filter->GetOutput();
  auto* ids = vtkDataArray::SafeDownCast(this->Differences->GetColumnByName("GaussianId"));
  auto* change = vtkDataArray::SafeDownCast(this->Differences->GetColumnByName("Change"));
  if (!ids || !change)
  {
    throw std::runtime_error("the state comparison gave no GaussianId and Change columns");
  }
  for (auto& set : this->Ids)
  {
    set.clear();
  }
  for (vtkIdType r = 0; r < ids->GetNumberOfTuples(); ++r)
  {
    const auto id = static_cast<vtkIdType>(ids->GetComponent(r, 0));
    const auto flags = static_cast<unsigned>(change->GetComponent(r, 0));
    const std::pair<unsigned, int> sets[] = { { vis4gs::StateBorn, BORN },
      { vis4gs::StateDied, DIED },
      { vis4gs::StateMoved, MOVED },
      { vis4gs::StateOpacityChanged, OPACITY },
      { vis4gs::StateScaleChanged, SCALE } };
    for (const auto& s : sets)
    {
      if (flags & s.first)
      {
        this->Ids[s.second].push_back(id);
      }
    }
    if (flags == vis4gs::StateUnchanged)
    {
      this->Ids[UNCHANGED].push_back(id);
    }
  }
  watch.Stop(this->CompareSeconds, this->CompareCpuSeconds);
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> Vis4GSComparison::Overlay(int side) const
{
  vtkPolyData* scene = side == 0 ? this->A.Scene : this->B.Scene;
  auto overlay = vtkSmartPointer<vtkPolyData>::New();
  overlay->ShallowCopy(scene); // the point data is the copy's own: the SH array can be swapped
  vtkDataArray* sh = scene->GetPointData()->GetArray(vis4gs::arrays::SH);
  auto* ids = vtkDataArray::SafeDownCast(scene->GetPointData()->GetArray("GaussianId"));
  auto* rowIds = this->Differences
    ? vtkDataArray::SafeDownCast(this->Differences->GetColumnByName("GaussianId"))
    : nullptr;
  auto* change = this->Differences
    ? vtkDataArray::SafeDownCast(this->Differences->GetColumnByName("Change"))
    : nullptr;
  if (!rowIds || !change)
  {
    return overlay;
  }
  // The rows are sorted by id (StateComparison), so each Gaussian's row is a binary search.
  std::vector<vtkIdType> sorted(static_cast<std::size_t>(rowIds->GetNumberOfTuples()));
  for (vtkIdType r = 0; r < rowIds->GetNumberOfTuples(); ++r)
  {
    sorted[static_cast<std::size_t>(r)] = static_cast<vtkIdType>(rowIds->GetComponent(r, 0));
  }
  const int components = sh ? sh->GetNumberOfComponents() : 3;
  vtkNew<vtkFloatArray> colors;
  colors->SetName(vis4gs::arrays::SH);
  colors->SetNumberOfComponents(components);
  colors->SetNumberOfTuples(scene->GetNumberOfPoints());
  colors->FillValue(0.f);
  const double c0 = 0.28209479177387814; // SH band 0: colour = 0.5 + C0 * DC
  for (vtkIdType i = 0; i < scene->GetNumberOfPoints(); ++i)
  {
    const vtkIdType id = ids ? static_cast<vtkIdType>(ids->GetComponent(i, 0)) : i;
    const auto row = std::lower_bound(sorted.begin(), sorted.end(), id);
    const unsigned flags = row != sorted.end() && *row == id
      ? static_cast<unsigned>(change->GetComponent(row - sorted.begin(), 0))
      : 0u;
    const std::array<unsigned char, 3> rgb = SetColor(OverlaySet(flags));
    for (int k = 0; k < 3; ++k)
    {
      colors->SetTypedComponent(i, k, static_cast<float>((rgb[k] / 255.0 - 0.5) / c0));
    }
  }
  overlay->GetPointData()->RemoveArray(vis4gs::arrays::SH);
  overlay->GetPointData()->AddArray(colors);
  return overlay;
}

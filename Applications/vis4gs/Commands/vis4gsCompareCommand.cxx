// SPDX-License-Identifier: BSD-3-Clause
// `vis4gs compare A B --output=DIR` (issue 20): two states of a reconstruction side by side,
// two iterations of one training log, or two logs or scenes of the same cameras. Writes
// differences.csv (per Gaussian id: born, died, moved, opacity or scale changed beyond a
// threshold; Core/Selection/StateComparison.h), metrics.csv (PSNR, SSIM, L1 of both states in
// every camera with an image, measured as RemovalEffect.h measures a clean-up, and the /metrics
// tables of the logs, as the sessions' metrics ports give them with the log reader's
// MetricsAsLogged) and report.html.
#include "Vis4GSCommand.h"

#include "GaussianIO.h"
#include "RemovalEffect.h"
#include "StateComparison.h"
#include "Vis4GSDataModel.h"
#include "Vis4GSPipeline.h"
#include "Vis4GSSceneCameras.h"
#include "Vis4GSStagingFolder.h"
#include "Vis4GSStateFiles.h"
#include "vtkGaussianSceneReader.h"
#include "vtkGaussianSession.h"
#include "vtkGaussianStateComparisonFilter.h"
#include "vtkGaussianTrainingLogReader.h"

#include "vtkDataArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTable.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace
{
namespace fs = std::filesystem;

void Define(Vis4GSArguments& args)
{
  args.AddPositional(
    "A", "First state: a 3DGS scene (.ply, .spz, .splat, .glb, ...), or a training log .h5.");
  args.AddPositional("B", "Second state, as A (the same log for two of its iterations).");
  args.AddOption("iteration-a", "N", "-1", "Log A: the snapshot nearest to N; -1: the last.");
  args.AddOption("iteration-b", "N", "-1", "Log B: the snapshot nearest to N; -1: the last.");
  args.AddOption("cameras",
    "FILE|DIR",
    "",
    "cameras.json, a COLMAP dataset folder or a transforms*.json. Default: the cameras of log "
    "A, else of log B, else cameras.json beside A or two folders up.");
  args.AddOption(
    "images", "DIR", "", "Folder of training images, matched to cameras by name (file stem).");
  args.AddOption("move", "T", "0", "A Gaussian moved when its centre travelled more than T.");
  args.AddOption(
    "opacity", "T", "0", "Its opacity changed when sigmoid(logit) changed by more than T.");
  args.AddOption("scale",
    "T",
    "0",
    "Its scale changed when |log s_b - log s_a| > T on some axis (0.1: about 10 %).");
  args.AddFlag("metrics", true, "Measure both states in every camera with an image.");
  args.AddOption("output", "DIR", "vis4gs-compare", "Folder the results are written to.");
}

// One side of the comparison, as its session read it (also its log's /metrics rows).
struct State
{
  std::string Path;
  vtkGaussianSession* Session = nullptr;
  bool Log = false;   ///< whether it is a training log
  int Iteration = -1; ///< logged iteration; -1 for a scene file
  vtkIdType Count = 0;
};

// The training PSNR curve of a log (x: iteration, y: PSNR), named.
struct Curve
{
  std::string Name;
  std::vector<double> Iteration;
  std::vector<double> Psnr;
};

// Reads @p session's Gaussians port (a scene "with its ids when it has them": the id property).
State ReadState(vtkGaussianSession* session, const char* which)
{
  State s;
  s.Path = session->GetFileName();
  s.Session = session;
  session->SetIdProperty("id");
  session->GetSceneReader()->IdPropertyOptionalOn();
  // metrics.csv writes the log's rows as it holds them, not the timeline's merged table.
  session->GetLogReader()->MetricsAsLoggedOn();
  const std::string errors = Vis4GSUpdate(session, vtkGaussianSession::GaussiansPort);
  if (!errors.empty())
  {
    throw std::runtime_error(errors);
  }
  s.Count = session->GetGaussiansOutput()->GetNumberOfPoints();
  if (session->GetIsTrainingLog())
  {
    s.Iteration = session->GetLoadedIteration();
    s.Log = true;
  }
  std::cout << "vis4gs compare: " << which << " = " << s.Path;
  if (s.Log)
  {
    std::cout << ", snapshot of iteration " << s.Iteration;
  }
  std::cout << ": " << s.Count << " Gaussians\n";
  return s;
}

// A column of the comparison's per-camera table.
double Figure(vtkTable* views, const char* column, vtkIdType row)
{
  vtkDataArray* values = vtkDataArray::SafeDownCast(views->GetColumnByName(column));
  return values ? values->GetTuple1(row) : std::numeric_limits<double>::quiet_NaN();
}

std::string Number(double v, int precision = 4)
{
  std::ostringstream out;
  out << std::fixed << std::setprecision(precision) << v;
  return out.str();
}

const char* SplitName(vis4gs::CameraSplit split)
{
  return split == vis4gs::CameraSplit::Train ? "train" : "test";
}

// The training PSNR curves of the logs as one inline SVG.
std::string Curves(const std::vector<Curve>& runs)
{
  double x0 = std::numeric_limits<double>::max(), x1 = -x0, y0 = x0, y1 = -x0;
  for (const Curve& run : runs)
  {
    for (std::size_t i = 0; i < run.Iteration.size(); ++i)
    {
      if (std::isfinite(run.Psnr[i]))
      {
        x0 = std::min(x0, run.Iteration[i]);
        x1 = std::max(x1, run.Iteration[i]);
        y0 = std::min(y0, run.Psnr[i]);
        y1 = std::max(y1, run.Psnr[i]);
      }
    }
  }
  if (!(x1 > x0) || !(y1 > y0))
  {
    return "";
  }
  const char* colours[] = { "#1f77b4", "#d62728" };
  std::ostringstream s;
  s << "<figure><svg width=\"520\" height=\"220\" xmlns=\"http://www.w3.org/2000/svg\">"
    << "<rect width=\"520\" height=\"220\" fill=\"#fff\"/>";
  for (std::size_t r = 0; r < runs.size(); ++r)
  {
    s << "<polyline fill=\"none\" stroke=\"" << colours[r % 2]
      << "\" stroke-width=\"1.5\" points=\"";
    for (std::size_t i = 0; i < runs[r].Iteration.size(); ++i)
    {
      if (std::isfinite(runs[r].Psnr[i]))
      {
        s << 40 + 470 * (runs[r].Iteration[i] - x0) / (x1 - x0) << ","
          << 190 - 170 * (runs[r].Psnr[i] - y0) / (y1 - y0) << " ";
      }
    }
    s << "\"/><text x=\"" << 50 + 160 * r << "\" y=\"14\" font-size=\"11\" fill=\""
      << colours[r % 2] << "\">" << Vis4GSHtml(runs[r].Name) << "</text>";
  }
  s << "<text x=\"40\" y=\"210\" font-size=\"11\">" << x0 << "</text><text x=\"510\" y=\"210\" "
    << "font-size=\"11\" text-anchor=\"end\">" << x1 << "</text><text x=\"2\" y=\"190\" "
    << "font-size=\"11\">" << Number(y0, 1) << "</text><text x=\"2\" y=\"24\" font-size=\"11\">"
    << Number(y1, 1) << "</text></svg><figcaption>Training PSNR (dB) per iteration, from the "
    << "logs' /metrics</figcaption></figure>\n";
  return s.str();
}

int Run(const Vis4GSArguments& args)
{
  vis4gs::StateThresholds thresholds;
  thresholds.Move = args.GetDouble("move");
  thresholds.Opacity = args.GetDouble("opacity");
  thresholds.Scale = args.GetDouble("scale");
  for (const double t : { thresholds.Move, thresholds.Opacity, thresholds.Scale })
  {
    if (!(t >= 0))
    {
      throw std::runtime_error("--move, --opacity and --scale must be >= 0");
    }
  }
  // One session: A, B as its compared state, the cameras by compare's rule (--cameras, log A's,
  // log B's, cameras.json beside A), the comparison filter's tables on its ports 8 and 9.
  vtkNew<vtkGaussianSession> session;
  session->SetFileName(args.GetPositional("A").c_str());
  session->SetIteration(args.GetInt("iteration-a"));
  session->ComputeScoresOff();
  session->SetCamerasFileName(args.Get("cameras").c_str());
  Vis4GSSceneCameraRules(session->GetCameraReader());
  session->SetCompareFileName(args.GetPositional("B").c_str());
  session->SetCompareIteration(args.GetInt("iteration-b"));
  const State a = ReadState(session, "A");
  const State b = ReadState(session->GetComparedSession(), "B");
  vtkGaussianStateComparisonFilter* comparison = session->GetComparisonFilter();
  comparison->SetMoveThreshold(thresholds.Move);
  comparison->SetOpacityThreshold(thresholds.Opacity);
  comparison->SetScaleThreshold(thresholds.Scale);
  comparison->SetNumberOfThreads(args.GetInt("threads"));
  comparison->SetMeasureViews(args.GetFlag("metrics"));
  // As analyze and repair: a camera without a file is measured without image (skipped in the
  // means), which is no reason to refuse the others.
  if (!args.Get("images").empty() && !fs::is_directory(args.Get("images")))
  {
    throw std::runtime_error(args.Get("images") + ": --images is not a folder");
  }
  session->SetImageDirectory(args.Get("images").c_str());
  std::string errors = Vis4GSUpdate(session, vtkGaussianSession::ComparisonPort);
  if (!errors.empty())
  {
    throw std::runtime_error(errors);
  }
  vtkTable* differences = session->GetComparisonOutput();
  std::cout << "vis4gs compare: " << comparison->GetNumberMatched() << " Gaussians in both, "
            << comparison->GetNumberBorn() << " born, " << comparison->GetNumberDied()
            << " died; of those in both " << comparison->GetNumberMoved() << " moved, "
            << comparison->GetNumberOpacityChanged() << " changed opacity, "
            << comparison->GetNumberScaleChanged() << " changed scale, "
            << comparison->GetNumberUnchanged() << " unchanged\n";

  // Per-camera figures of both states.
  std::vector<vis4gs::Camera> cameras;
  std::vector<vis4gs::ViewMetrics> ma, mb;
  if (args.GetFlag("metrics"))
  {
    // The figures the comparison measured with its table (no second run).
    errors = Vis4GSUpdate(session, vtkGaussianSession::ComparisonViewsPort);
    if (!errors.empty())
    {
      throw std::runtime_error(errors);
    }
    vtkTable* views = session->GetComparisonViewsOutput();
    if (views->GetNumberOfRows() == 0)
    {
      std::cerr << "vis4gs compare: note: no cameras found (give --cameras): the states are "
                   "not measured against images\n";
    }
    else
    {
      // The cameras measured, for their names and splits.
      vtkTable* table = vtkTable::SafeDownCast(comparison->GetInputDataObject(2, 0));
      std::string error;
      if (!table || !vis4gs::TableToCameras(table, cameras, &error))
      {
        throw std::runtime_error(a.Path + ": the cameras: " + error);
      }
      for (vtkIdType r = 0; r < views->GetNumberOfRows(); ++r)
      {
        ma.push_back(
          { Figure(views, "PSNR_A", r), Figure(views, "SSIM_A", r), Figure(views, "L1_A", r) });
        mb.push_back(
          { Figure(views, "PSNR_B", r), Figure(views, "SSIM_B", r), Figure(views, "L1_B", r) });
      }
    }
  }

  const fs::path output = args.Get("output");
  Vis4GSStagingFolder staging(output, "compare");
  {
    std::ostringstream csv;
    csv << "id,status,dmove,dopacity,dscale\n" << std::setprecision(9);
    auto* ids = vtkIdTypeArray::SafeDownCast(differences->GetColumnByName("GaussianId"));
    auto* status = vtkStringArray::SafeDownCast(differences->GetColumnByName("Status"));
    for (vtkIdType r = 0; r < differences->GetNumberOfRows(); ++r)
    {
      csv << static_cast<std::int64_t>(ids->GetValue(r)) << "," << status->GetValue(r) << ","
          << Figure(differences, "Move", r) << "," << Figure(differences, "OpacityChange", r) << ","
          << Figure(differences, "ScaleChange", r) << "\n";
    }
    vis4gs::WriteTextFile((staging.Get() / "differences.csv").string(), csv.str());
  }

  // metrics.csv: source a / b (the states, per view and "mean" per split), log-a / log-b (the
  // logs' /metrics and /metrics/test rows).
  std::vector<Curve> curves;
  std::ostringstream csv;
  csv << "source,split,iteration,view,gaussians,psnr,ssim,l1\n" << std::setprecision(9);
  const State* states[] = { &a, &b };
  const std::vector<vis4gs::ViewMetrics>* measured[] = { &ma, &mb };
  std::ostringstream means;
  for (int s = 0; s < 2; ++s)
  {
    const char* source = s == 0 ? "a" : "b";
    for (const vis4gs::CameraSplit split :
      { vis4gs::CameraSplit::Train, vis4gs::CameraSplit::Test })
    {
      std::size_t views = 0;
      const vis4gs::ViewMetrics mean =
        vis4gs::MeanViewMetrics(*measured[s], cameras, split, &views);
      if (views > 0)
      {
        csv << source << "," << SplitName(split) << "," << states[s]->Iteration << ",mean,"
            << states[s]->Count << "," << mean.Psnr << "," << mean.Ssim << "," << mean.L1 << "\n";
        means << "<tr><td>" << source << "</td><td>" << SplitName(split) << "</td><td>" << views
              << "</td><td>" << Number(mean.Psnr) << "</td><td>" << Number(mean.Ssim) << "</td><td>"
              << Number(mean.L1) << "</td></tr>";
      }
    }
    for (std::size_t i = 0; i < measured[s]->size(); ++i)
    {
      const vis4gs::ViewMetrics& m = (*measured[s])[i];
      if (std::isfinite(m.L1))
      {
        csv << source << "," << SplitName(cameras[i].Split) << "," << states[s]->Iteration << ","
            << cameras[i].Name << "," << states[s]->Count << "," << m.Psnr << "," << m.Ssim << ","
            << m.L1 << "\n";
      }
    }
  }
  for (int s = 0; s < 2; ++s)
  {
    const State& state = *states[s];
    std::error_code ec;
    const bool sameLog = s == 1 && a.Log && fs::equivalent(a.Path, b.Path, ec);
    if (!state.Log || !state.Session->GetLogReader()->HasMetrics() || sameLog)
    {
      continue;
    }
    // The session's metrics port: /metrics's rows, then /metrics/test's (empty without them).
    errors = Vis4GSUpdate(state.Session, vtkGaussianSession::MetricsPort);
    if (!errors.empty())
    {
      throw std::runtime_error(errors);
    }
    vtkTable* table = state.Session->GetMetricsOutput();
    namespace names = vis4gs::arrays;
    // (Split: 0 a /metrics row, 1 a /metrics/test row, as the cameras' Split.)
    vtkDataArray* split = vtkDataArray::SafeDownCast(table->GetColumnByName(names::CameraSplit));
    vtkDataArray* iteration =
      vtkDataArray::SafeDownCast(table->GetColumnByName(names::MetricIteration));
    vtkDataArray* gaussians =
      vtkDataArray::SafeDownCast(table->GetColumnByName(names::MetricGaussians));
    if (!split || !iteration || !gaussians)
    {
      throw std::runtime_error(
        state.Path + ": the metrics table lacks its Split, Iteration or " + "NumGaussians column");
    }
    const std::string source = s == 0 ? "log-a" : "log-b";
    Curve curve{ source + ": " + fs::path(state.Path).filename().string(), {}, {} };
    for (vtkIdType r = 0; r < table->GetNumberOfRows(); ++r)
    {
      const bool test = split->GetTuple1(r) != 0;
      const double psnr = Figure(table, names::MetricPSNR, r);
      csv << source << "," << (test ? "test" : "train") << ","
          << static_cast<int>(iteration->GetTuple1(r)) << ",,"
          << static_cast<long long>(gaussians->GetTuple1(r)) << "," << psnr << ","
          << Figure(table, names::MetricSSIM, r) << "," << Figure(table, names::MetricL1, r)
          << "\n";
      if (!test)
      {
        curve.Iteration.push_back(iteration->GetTuple1(r));
        curve.Psnr.push_back(psnr);
      }
    }
    curves.push_back(std::move(curve));
  }
  vis4gs::WriteTextFile((staging.Get() / "metrics.csv").string(), csv.str());

  std::ostringstream html;
  html << "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>vis4gs compare</title>"
       << "<style>body{font-family:sans-serif;margin:2em}table{border-collapse:collapse}"
       << "td,th{border:1px solid #ccc;padding:2px 8px;text-align:right}</style></head><body>"
       << "<h1>Two states compared</h1><p>A: <code>" << Vis4GSHtml(a.Path) << "</code>"
       << (a.Log ? ", iteration " + std::to_string(a.Iteration) : std::string()) << " (" << a.Count
       << " Gaussians)<br>B: <code>" << Vis4GSHtml(b.Path) << "</code>"
       << (b.Log ? ", iteration " + std::to_string(b.Iteration) : std::string()) << " (" << b.Count
       << " Gaussians)</p><p>Thresholds (strict): move &gt; " << thresholds.Move
       << ", |opacity change| &gt; " << thresholds.Opacity << ", |log scale change| &gt; "
       << thresholds.Scale << ".</p>\n<h2>Gaussians by id</h2><table><tr><th>in both</th>"
       << "<th>born</th><th>died</th><th>moved</th><th>opacity changed</th><th>scale changed</th>"
       << "<th>unchanged</th></tr><tr><td>" << comparison->GetNumberMatched() << "</td><td>"
       << comparison->GetNumberBorn() << "</td><td>" << comparison->GetNumberDied() << "</td><td>"
       << comparison->GetNumberMoved() << "</td><td>" << comparison->GetNumberOpacityChanged()
       << "</td><td>" << comparison->GetNumberScaleChanged() << "</td><td>"
       << comparison->GetNumberUnchanged() << "</td></tr></table>\n";
  if (!means.str().empty())
  {
    html << "<h2>Against the images</h2><p>Both states rendered in every camera with an image "
            "(exact rasteriser, renders clamped to [0, 1]); means per split.</p><table><tr>"
            "<th>state</th><th>split</th><th>views</th><th>PSNR</th><th>SSIM</th><th>L1</th></tr>"
         << means.str() << "</table>\n<h3>Views, the largest PSNR loss from A to B first</h3>"
         << "<table><tr><th>view</th><th>split</th><th>PSNR A</th><th>PSNR B</th><th>change</th>"
            "<th>SSIM A</th><th>SSIM B</th><th>L1 A</th><th>L1 B</th></tr>";
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < ma.size(); ++i)
    {
      if (std::isfinite(ma[i].L1))
      {
        order.push_back(i);
      }
    }
    std::stable_sort(order.begin(),
      order.end(),
      [&](std::size_t i, std::size_t j)
      { return mb[i].Psnr - ma[i].Psnr < mb[j].Psnr - ma[j].Psnr; });
    for (const std::size_t i : order)
    {
      html << "<tr><td>" << Vis4GSHtml(cameras[i].Name) << "</td><td>"
           << SplitName(cameras[i].Split) << "</td><td>" << Number(ma[i].Psnr) << "</td><td>"
           << Number(mb[i].Psnr) << "</td><td>" << Number(mb[i].Psnr - ma[i].Psnr) << "</td><td>"
           << Number(ma[i].Ssim) << "</td><td>" << Number(mb[i].Ssim) << "</td><td>"
           << Number(ma[i].L1) << "</td><td>" << Number(mb[i].L1) << "</td></tr>";
    }
    html << "</table>\n";
  }
  if (!curves.empty())
  {
    html << "<h2>Metric curves</h2>" << Curves(curves);
  }
  html << "<p>Files: differences.csv (one row per id), metrics.csv.</p></body></html>\n";
  vis4gs::WriteTextFile((staging.Get() / "report.html").string(), html.str());
  staging.Commit();
  std::cout << "vis4gs compare: wrote " << (output / "differences.csv").string() << ", "
            << (output / "metrics.csv").string() << ", " << (output / "report.html").string()
            << "\n";
  return 0;
}
} // namespace

VIS4GS_REGISTER_COMMAND("compare",
  "Compare two states (iterations, logs or scenes): Gaussians by id, figures per camera.",
  Define,
  Run)

// SPDX-License-Identifier: BSD-3-Clause
// `vis4gs demo`: the embedded default scene end to end (DESIGN §5). The embedded scene is a
// training log of the built-in trainer (Data/Demo/vis4gs-demo.h5, see its README). With a
// display, the demo opens it in the application; without one (or with --no-gui) it runs the
// whole diagnosis in batch: every score through `vis4gs analyze` (report, tables, overlays),
// then the paper's case study — the most suspicious floater traced back through the
// densification tree to its root, with the View Coverage of each ancestor at the snapshot
// nearest its birth.
#include "Vis4GSCommand.h"
#include "Vis4GSPipeline.h"
#include "Vis4GSStagingFolder.h"

#include "GaussianIO.h"
#include "Genealogy.h"
#include "TrainingLogReader.h"
#include "Vis4GSDataModel.h"

#include "vtkDataArray.h"
#include "vtkGaussianArtifactScoreFilter.h"
#include "vtkGaussianSession.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

namespace
{
namespace fs = std::filesystem;

const char* KindName(vis4gs::BirthKind kind)
{
  switch (kind)
  {
    case vis4gs::BirthKind::Root:
      return "root";
    case vis4gs::BirthKind::Clone:
      return "clone";
    case vis4gs::BirthKind::Split:
      return "split";
    case vis4gs::BirthKind::CloneSplit:
      return "clone-split";
  }
  return "?";
}

void Define(Vis4GSArguments& args)
{
  args.AddOption("log",
    "FILE",
    VIS4GS_DATA_DIR "/Demo/vis4gs-demo.h5",
    "Training log to run the demo on (the embedded demo log).");
  args.AddOption("output", "DIR", "vis4gs-demo", "Folder the batch diagnosis writes to.");
  args.AddOption("top", "K", "10", "Number of most suspicious Gaussians listed per score.");
  args.AddFlag("gui",
    true,
    "Open the application when a display is present ($DISPLAY set); --no-gui always runs the "
    "batch diagnosis.");
  args.AddOption("min-opacity",
    "O",
    "0.1",
    "Case study: only Gaussians at least this opaque count as visible floaters.");
}

// Runs another registered subcommand with @p words as its command line.
int RunCommand(const std::string& name, const std::vector<std::string>& words)
{
  const Vis4GSCommand* command = Vis4GSFindCommand(name);
  if (!command)
  {
    throw std::runtime_error("this vis4gs was built without the '" + name + "' command");
  }
  Vis4GSArguments args(command->Name, command->Summary);
  Vis4GSDefineArguments(*command, args);
  if (args.Parse(words, std::cerr) != Vis4GSArguments::Result::Ok)
  {
    throw std::logic_error("vis4gs demo built a bad command line for " + name);
  }
  return command->Run(args);
}

// View Coverage of every Gaussian of every snapshot through the session (the pipeline the
// application, Python and ParaView use; its score filter asked for the coverage only): coverage
// needs only the Gaussians and the cameras (no rendering), so the whole history costs a few
// seconds on the demo.
std::map<std::int32_t, std::map<std::int64_t, double>> CoverageHistory(const std::string& logPath,
  const std::vector<int>& iterations)
{
  vtkNew<vtkGaussianSession> session;
  session->SetFileName(logPath.c_str());
  session->SetFullSHLimit(0); // the coverage needs no colour: the DC coefficients only
  session->GetScoreFilter()->SetScores("coverage");
  std::map<std::int32_t, std::map<std::int64_t, double>> history;
  for (int iteration : iterations)
  {
    std::cout << "vis4gs demo: View Coverage of the snapshot of iteration " << iteration << " ("
              << history.size() + 1 << " of " << iterations.size() << ")" << std::endl;
    session->SetIteration(iteration);
    const std::string errors = Vis4GSUpdate(session, vtkGaussianSession::GaussiansPort);
    vtkPointData* pd = session->GetGaussiansOutput()->GetPointData();
    vtkDataArray* ids = pd->GetArray(vis4gs::arrays::GaussianId);
    vtkDataArray* coverage = pd->GetArray(vis4gs::arrays::ViewCoverage);
    if (!errors.empty() || !ids || !coverage)
    {
      throw std::runtime_error(
        logPath + ": no View Coverage of iteration " + std::to_string(iteration) + ": " + errors);
    }
    auto& values = history[iteration];
    for (vtkIdType i = 0; i < ids->GetNumberOfTuples(); ++i)
    {
      values[static_cast<std::int64_t>(ids->GetTuple1(i))] = coverage->GetTuple1(i);
    }
  }
  return history;
}

int CaseStudy(const std::string& logPath, const fs::path& output, double minOpacity)
{
  const vis4gs::TrainingLogReader log(logPath);
  const std::vector<int>& snapshots = log.GetSnapshotIterations();
  if (snapshots.empty() || !log.HasCameras() || !log.HasEvents())
  {
    std::cout << "vis4gs demo: " << logPath
              << " lacks snapshots, cameras or events; no root-cause trace\n";
    return 0;
  }
  const std::vector<vis4gs::Camera> cameras = log.ReadCameras();
  // View Coverage is a fraction of the training views (DESIGN §4), not of every camera.
  const auto trainViews = std::count_if(cameras.begin(),
    cameras.end(),
    [](const vis4gs::Camera& c) { return c.Split == vis4gs::CameraSplit::Train; });
  const auto coverage = CoverageHistory(logPath, snapshots);

  // The floater: the visible Gaussian of the last snapshot that the fewest training views see.
  vis4gs::SnapshotReadOptions options;
  options.Arrays = vis4gs::SnapshotParameters;
  const vis4gs::GaussianCloud last = log.ReadSnapshot(snapshots.back(), options);
  const auto& lastCoverage = coverage.at(snapshots.back());
  std::int64_t floater = -1;
  double best = 2;
  for (std::size_t i = 0; i < last.Count; ++i)
  {
    const double opacity = 1 / (1 + std::exp(-static_cast<double>(last.OpacityLogits[i])));
    const double c = lastCoverage.at(last.GetId(i));
    if (opacity >= minOpacity && c > 0 && c < best)
    {
      best = c;
      floater = last.GetId(i);
    }
  }
  if (floater < 0)
  {
    std::cout << "vis4gs demo: no visible Gaussian with partial coverage; no root-cause trace\n";
    return 0;
  }

  // DESIGN §3: the initial Gaussians are 0..N0-1 and every new one gets the next unused id,
  // so N0 is the first child id of the events (or one past the largest id without births).
  const vis4gs::EventTable events = log.ReadEvents();
  std::int64_t roots = std::numeric_limits<std::int64_t>::max();
  for (std::size_t e = 0; e < events.Size(); ++e)
  {
    if (events.Child[e] >= 0)
    {
      roots = std::min(roots, events.Child[e]);
    }
  }
  if (roots == std::numeric_limits<std::int64_t>::max())
  {
    roots = last.Count ? *std::max_element(last.Ids.begin(), last.Ids.end()) + 1 : 0;
  }
  // Core's Genealogy, not vtkGaussianGenealogyTreeFilter: the demo draws no tree, it writes
  // one lineage as text (root-cause.txt) beside the log its trainer wrote, and the trace needs
  // per-snapshot coverage values that the VTK trace filter leaves to its caller
  // (vtkGaussianGenealogyLineage); building a vtkTree of every Gaussian to read one chain back
  // would add a copy and no check. `vis4gs view` and scripts show the same tree through the
  // VTK filter.
  const vis4gs::Genealogy tree = vis4gs::Genealogy::Build(roots, events, snapshots.back());
  const std::int64_t node = tree.FindNode(floater);
  const std::vector<std::int32_t> snapshotIterations(snapshots.begin(), snapshots.end());
  const auto trace = tree.TraceToRoot(node,
    snapshotIterations,
    [&](std::int32_t s, std::int64_t id)
    {
      const auto it = coverage.find(s);
      if (it == coverage.end())
      {
        return std::nan("");
      }
      const auto v = it->second.find(id);
      return v == it->second.end() ? std::nan("") : v->second;
    });

  std::ostringstream text;
  text << "Root-cause trace of Gaussian " << floater << ", a visible floater (View Coverage "
       << best << " = " << static_cast<int>(std::lround(best * trainViews)) << " of " << trainViews
       << " training views; lowest among Gaussians with opacity >= " << minOpacity
       << " at iteration " << snapshots.back() << "):\n"
       << "  GaussianId  born   kind         died   coverage at snapshot\n";
  for (const vis4gs::TraceStep& step : trace)
  {
    text << "  " << std::setw(10) << step.GaussianId << "  " << std::setw(5) << step.BirthIteration
         << "  " << std::left << std::setw(11) << KindName(step.Kind) << std::right << "  "
         << std::setw(5)
         << (step.DeathIteration < 0 ? std::string("alive") : std::to_string(step.DeathIteration))
         << "  ";
    if (step.SnapshotIteration < 0)
    {
      text << "(in no snapshot)\n";
    }
    else
    {
      text << std::fixed << std::setprecision(3) << step.Value << std::defaultfloat << " at "
           << step.SnapshotIteration << "\n";
    }
  }
  std::cout << text.str();
  vis4gs::WriteTextFile((output / "root-cause.txt").string(), text.str());
  // The report names the traced floater too, so that it reads as one diagnosis.
  const fs::path report = output / "report.html";
  std::ifstream in(report);
  std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t end = html.rfind("</body>");
  if (!in || end == std::string::npos)
  {
    throw std::runtime_error(report.string() + ": analyze's report is missing or incomplete");
  }
  html.insert(end, "<h2>Root-cause trace</h2><pre>" + Vis4GSHtml(text.str()) + "</pre>\n");
  vis4gs::WriteTextFile(report.string(), html);
  std::cout << "vis4gs demo: wrote root-cause.txt and added the trace to report.html\n";
  return 0;
}

int Run(const Vis4GSArguments& args)
{
  const std::string log = args.Get("log");
  if (!fs::is_regular_file(log))
  {
    throw std::runtime_error(log + ": the demo training log does not exist");
  }
  const char* display = std::getenv("DISPLAY");
  if (args.GetFlag("gui") && display && *display)
  {
    std::cout << "vis4gs demo: opening " << log << " (use --no-gui for the batch report)\n";
    return RunCommand("view", { log, "--welcome" });
  }
  // analyze's outputs and the trace are moved into the output folder together, so that a
  // failure (a full disk) leaves an earlier run's report and trace as they were.
  const fs::path output = args.Get("output");
  Vis4GSStagingFolder staging(output, "demo");
  const int analyzed = RunCommand("analyze",
    { log, "--output=" + staging.Get().string(), "--top=" + args.Get("top"), "--overlay-views=3" });
  if (analyzed != 0)
  {
    return analyzed;
  }
  const int traced = CaseStudy(log, staging.Get(), args.GetDouble("min-opacity"));
  staging.Commit();
  std::cout << "vis4gs demo: wrote " << output.string() << "\n";
  return traced;
}
}

VIS4GS_REGISTER_COMMAND("demo",
  "Run the diagnosis end to end on the embedded demo training log.",
  Define,
  Run)

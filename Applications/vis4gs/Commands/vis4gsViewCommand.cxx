// SPDX-License-Identifier: BSD-3-Clause
// `vis4gs view [FILE]`: the Qt5 application with the four linked views (DESIGN §5).
#include "Vis4GSBenchmark.h"
#include "Vis4GSCommand.h"
#include "Vis4GSCompareWindow.h"
#include "Vis4GSDocument.h"
#include "Vis4GSFollow.h"
#include "Vis4GSMainWindow.h"
#include "Vis4GSSelfTest.h"
#include "Vis4GSSoak.h"

#include "QVTKOpenGLNativeWidget.h"

#include <QApplication>
#include <QSurfaceFormat>
#include <QTimer>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <iostream>
#include <string>

namespace
{
void Define(Vis4GSArguments& args)
{
  args.AddPositional("FILE",
    "Training log (.h5) or Gaussian scene (.ply, .compressed.ply, .sog, meta.json, .spz, .ksplat, "
    ".splat, .glb, .gltf) to open.",
    false);
  args.AddOption("self-test",
    "DIR",
    "",
    "Run the scripted end-to-end check after loading (select in the scene, check the tree "
    "lineage and the timeline history, select in the tree, check the scene highlight), save "
    "screenshots of every view into DIR and exit with 0 on success.");
  args.AddOption("baseline",
    "DIR",
    "",
    "With --self-test: compare the scene and tree screenshots with the PNG baselines of the "
    "same names in DIR (per-pixel tolerance, see --baseline-tolerance).");
  args.AddOption("baseline-tolerance",
    "T,F",
    "48,0.02",
    "Baseline comparison: a pixel differs when a channel differs by more than T (0-255); the "
    "image matches when at most the fraction F of its pixels differ.");
  args.AddFlag("benchmark",
    false,
    "Load FILE, print the time from start to all views ready (wall and CPU), the scene "
    "view's orbit (moving frames per second, the longest event-loop gap, the still frame "
    "after the stop) and the tree view's pan/zoom frames per second, then exit (no scores "
    "are computed).");
  args.AddFlag("follow",
    false,
    "Follow a training log while its trainer writes it (the Python logger and `vis4gs train` "
    "write it in SWMR mode; LOG.tmp while it is written when LOG does not exist yet): new "
    "metrics, events and snapshots show within about 2 s, the scene at the latest snapshot.");
  args.AddOption("soak",
    "N,DIR",
    "",
    "A soak of the application (issue 35): N cycles in this process, each opening FILE and "
    "--soak-also in turn, switching iterations, selecting with every mode and measuring a "
    "clean-up; resident memory, descriptors, threads and temporary files per cycle go to "
    "DIR/soak.csv; exits 1 when they grow beyond the bounds (--soak-bound).");
  args.AddOption("soak-also", "FILE", "", "With --soak: the file opened every other cycle.");
  args.AddOption("soak-bound",
    "MB",
    "16",
    "With --soak: resident memory growth allowed after the warm-up (the mean of the last 5 "
    "cycles against that of the 5 after the warm-up); descriptors, threads and temporary "
    "entries may not grow.");
  args.AddOption("soak-fine-tune",
    "N",
    "1",
    "With --soak: on a document with training images, also fine-tune the measured removal for "
    "N iterations in the clean-up panel (its log written to DIR and deleted); 0: no fine-tune.");
  args.AddOption("splat-budget",
    "N",
    "200000",
    "Level of detail of the scene view on a hardware OpenGL: draw at most N splats (every "
    "k-th in depth order; selection and scores use every Gaussian). 0 draws all. Software "
    "OpenGL draws every Gaussian with the exact CPU rasteriser instead.");
  args.AddOption("resolution", "W,H", "1400,900", "Initial window size.");
  args.AddOption("cameras",
    "FILE_OR_DIR",
    "",
    "Cameras of a scene file (a training log has its own): the trainer's cameras.json, a "
    "COLMAP dataset folder or a transforms*.json (file or folder). Default: cameras.json next to "
    "the scene or two folders up (the "
    "INRIA model layout); none found, no cameras.");
  args.AddOption("images",
    "DIR",
    "",
    "Training images of a scene file, matched to its cameras by name (up to the first '.'): "
    "the blur and needle scores and the clean-up panel's before/after measurement and "
    "fine-tune use them.");
  args.AddOption("compare",
    "B",
    "",
    "Open the comparison window instead (issue 20): FILE side by side with B, another snapshot "
    "of FILE's log (@ITERATION), a training log (its last snapshot, or LOG@ITERATION) or a "
    "scene of the same cameras; with --self-test, its scripted check.");
  args.AddOption("iteration",
    "N",
    "-1",
    "With --compare: FILE's snapshot nearest N; -1: the last. A scene file: the iteration it "
    "was trained to, which the clean-up's fine-tune continues from (as vis4gs repair "
    "--iteration); -1: 0.");
  args.AddOption("compare-thresholds",
    "M,O,S",
    "0,0,0",
    "With --compare: the move, opacity and log-scale thresholds of `vis4gs compare`.");
  args.AddOption("dump-inputs",
    "DIR",
    "",
    "Load FILE and compute its scores as the window does, write the views' inputs into DIR "
    "(scene.vtp with the scores; metrics, tree-vertices, tree-edges and bands as "
    ".vtt) and exit without a window, for comparing with a VTK script "
    "(Documentation/dev/ARCHITECTURE.md).");
  args.AddFlag("welcome",
    false,
    "Show the welcome panel (what to try first: the user guide's case study) at the top of "
    "the control panel; `vis4gs demo` turns it on.");
}

int Run(const Vis4GSArguments& args)
{
  const double start =
    std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  const double startCpu = static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
  if (!args.Get("dump-inputs").empty())
  {
    if (args.GetPositional("FILE").empty())
    {
      std::cerr << "vis4gs view: error: --dump-inputs needs a FILE\n";
      return 1;
    }
    Vis4GSDocument::LoadAndDumpInputs(
      args.GetPositional("FILE"), args.Get("cameras"), args.Get("dump-inputs"));
    return 0;
  }
  if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY"))
  {
    std::cerr << "vis4gs view: error: no display (set DISPLAY, or run under xvfb-run)\n";
    return 1;
  }
  // Must come before the QApplication (guide: "More traps").
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  static int argc = 1;
  static char name[] = "vis4gs";
  static char* argv[] = { name, nullptr };
  QApplication app(argc, argv);
  if (!args.Get("compare").empty())
  {
    const std::vector<double> t = args.GetNumbers("compare-thresholds");
    if (args.GetPositional("FILE").empty() || t.size() != 3 ||
      !std::all_of(t.begin(), t.end(), [](double v) { return v >= 0; }))
    {
      std::cerr
        << "vis4gs view: error: --compare needs a FILE and --compare-thresholds M,O,S >= 0\n";
      return 1;
    }
    Vis4GSCompareWindow compare;
    const std::vector<double> size = args.GetNumbers("resolution");
    if (size.size() == 2)
    {
      compare.resize(static_cast<int>(size[0]), static_cast<int>(size[1]));
    }
    compare.SetThresholds(t[0], t[1], t[2]);
    if (!args.Get("self-test").empty())
    {
      compare.SetSelfTest(QString::fromStdString(args.Get("self-test")));
    }
    compare.show();
    compare.Open(QString::fromStdString(args.GetPositional("FILE")),
      args.GetInt("iteration"),
      QString::fromStdString(args.Get("compare")),
      QString::fromStdString(args.Get("cameras")));
    return app.exec();
  }
  Vis4GSMainWindow window;
  const std::vector<double> size = args.GetNumbers("resolution");
  if (size.size() == 2)
  {
    window.resize(static_cast<int>(size[0]), static_cast<int>(size[1]));
  }
  window.SetSplatBudget(static_cast<long long>(args.GetDouble("splat-budget")));
  window.SetSceneCameras(QString::fromStdString(args.Get("cameras")));
  window.SetSceneImages(QString::fromStdString(args.Get("images")), args.GetInt("iteration"));
  if (args.GetFlag("welcome"))
  {
    window.ShowWelcome();
  }
  if (args.GetFlag("benchmark"))
  {
    if (args.GetPositional("FILE").empty())
    {
      std::cerr << "vis4gs view: error: --benchmark needs a FILE\n";
      return 1;
    }
    Vis4GSInstallBenchmark(&window, start, startCpu);
  }
  const std::string selfTest = args.Get("self-test");
  Vis4GSSelfTestOptions selfTestOptions;
  selfTestOptions.Directory = QString::fromStdString(selfTest);
  if (!args.Get("baseline").empty())
  {
    const std::vector<double> tolerance = args.GetNumbers("baseline-tolerance");
    if (tolerance.size() != 2)
    {
      std::cerr << "vis4gs view: error: --baseline-tolerance expects T,F\n";
      return 1;
    }
    selfTestOptions.BaselineDirectory = QString::fromStdString(args.Get("baseline"));
    selfTestOptions.Tolerance = static_cast<int>(tolerance[0]);
    selfTestOptions.Fraction = tolerance[1];
  }
  if (!args.Get("soak").empty())
  {
    const std::string soak = args.Get("soak");
    const auto comma = soak.find(',');
    Vis4GSSoakOptions o;
    o.Cycles = std::atoi(soak.substr(0, comma).c_str());
    o.Directory = QString::fromStdString(comma == std::string::npos ? "." : soak.substr(comma + 1));
    o.BoundMB = args.GetDouble("soak-bound");
    o.FineTuneIterations = std::atoi(args.Get("soak-fine-tune").c_str());
    o.Files << QString::fromStdString(args.GetPositional("FILE"));
    if (!args.Get("soak-also").empty())
    {
      o.Files << QString::fromStdString(args.Get("soak-also"));
    }
    if (args.GetPositional("FILE").empty() || o.Cycles < 10)
    {
      std::cerr << "vis4gs view: error: --soak needs a FILE and N >= 10 cycles\n";
      return 1;
    }
    window.show();
    Vis4GSInstallSoak(&window, o);
    return app.exec();
  }
  if (!selfTest.empty())
  {
    Vis4GSInstallSelfTest(&window, selfTestOptions);
    if (args.GetPositional("FILE").empty())
    {
      std::cerr << "vis4gs view: error: --self-test needs a FILE\n";
      return 1;
    }
  }
  if (args.GetFlag("follow"))
  {
    if (args.GetPositional("FILE").empty())
    {
      std::cerr << "vis4gs view: --follow needs a FILE (a training log)\n";
      return 1;
    }
    Vis4GSInstallFollow(&window, QString::fromStdString(args.GetPositional("FILE")), 1000);
  }
  window.show();
  const std::string file = args.GetPositional("FILE");
  if (!file.empty())
  {
    QTimer::singleShot(0, &window, [&window, file] { window.Open(QString::fromStdString(file)); });
  }
  return app.exec();
}
}

VIS4GS_REGISTER_COMMAND("view",
  "Open a training log or a scene in the linked views (Qt application).",
  Define,
  Run)

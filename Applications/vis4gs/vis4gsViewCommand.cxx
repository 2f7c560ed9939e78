// SPDX-License-Identifier: BSD-3-Clause
// `vis4gs view [FILE]`: the Qt5 application with the four linked views (DESIGN §5).
#include "Vis4GSCommand.h"
#include "Vis4GSMainWindow.h"

#include "QVTKOpenGLNativeWidget.h"

#include <QApplication>
#include <QSurfaceFormat>
#include <QTimer>

#include <cstdlib>
#include <iostream>
#include <string>

namespace
{
void Define(Vis4GSArguments& args)
{
  args.AddPositional("FILE", "Training log (.h5) or Gaussian scene (.ply, .splat) to open.", false);
  args.AddOption("self-test",
    "DIR",
    "",
    "Run the scripted end-to-end check after loading (select in the scene, check the tree "
    "lineage and the timeline history, select in the tree, check the scene highlight), save "
    "screenshots of every view into DIR and exit with 0 on success.");
  args.AddOption("resolution", "W,H", "1400,900", "Initial window size.");
}

int Run(const Vis4GSArguments& args)
{
  if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY"))
  {
    std::cerr << "vis4gs view: no display (set DISPLAY, or run under xvfb-run)\n";
    return 1;
  }
  // Must come before the QApplication (guide: "More traps").
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  static int argc = 1;
  static char name[] = "vis4gs";
  static char* argv[] = { name, nullptr };
  QApplication app(argc, argv);
  Vis4GSMainWindow window;
  const std::vector<double> size = args.GetNumbers("resolution");
  if (size.size() == 2)
  {
    window.resize(static_cast<int>(size[0]), static_cast<int>(size[1]));
  }
  const std::string selfTest = args.Get("self-test");
  if (!selfTest.empty())
  {
    window.SetSelfTest(QString::fromStdString(selfTest));
    if (args.GetPositional("FILE").empty())
    {
      std::cerr << "vis4gs view: --self-test needs a FILE\n";
      return 1;
    }
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

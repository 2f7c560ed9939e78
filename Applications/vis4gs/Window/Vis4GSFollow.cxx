// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSFollow.h"

#include "Vis4GSDocument.h"
#include "Vis4GSMainWindow.h"

#include "vtkGaussianTrainingLogReader.h"
#include "vtkTable.h"

#include <QFileInfo>
#include <QStatusBar>
#include <QTimer>

#include <iostream>
#include <memory>

namespace
{
struct FollowState
{
  Vis4GSDocument* Shown = nullptr;     ///< the document the counts below describe
  Vis4GSDocument* Reloading = nullptr; ///< the document replaced by a reload under way
  bool Pending = false;
  int Snapshots = 0;
  vtkIdType MetricsRows = 0;
};

vtkIdType MetricsRows(const Vis4GSDocument& doc)
{
  return doc.Metrics ? doc.Metrics->GetNumberOfRows() : 0;
}
} // namespace

//------------------------------------------------------------------------------
void Vis4GSInstallFollow(Vis4GSMainWindow* window, const QString& path, int intervalMs)
{
  auto state = std::make_shared<FollowState>();
  QObject::connect(window,
    &Vis4GSMainWindow::loadFailed,
    window,
    [state](const QString&)
    {
      // The writer was between states: the next tick tries again.
      state->Pending = false;
    });
  auto* timer = new QTimer(window);
  QObject::connect(timer,
    &QTimer::timeout,
    window,
    [window, state, path]
    {
      const std::shared_ptr<Vis4GSDocument> doc = window->GetDocument();
      // The Python logger and `vis4gs train` write LOG.tmp and rename it onto LOG when the run
      // ends: a .tmp is the live run (LOG may be an earlier run's log).
      const QString live = QFileInfo::exists(path + ".tmp") ? path + ".tmp" : path;
      if (!doc && !state->Pending)
      {
        // Not open yet (the trainer has not created it, or not written its first snapshot):
        // try again.
        state->Pending = true;
        window->Open(live);
        return;
      }
      if (doc && !state->Pending && QString::fromStdString(doc->Path) != live &&
        !QFileInfo::exists(QString::fromStdString(doc->Path)))
      {
        state->Pending = true; // the temporary became LOG: follow that
        state->Reloading = doc.get();
        window->Open(live);
        return;
      }
      if (!doc || !doc->IsLog || !doc->Reader)
      {
        return;
      }
      if (state->Pending && doc.get() == state->Reloading)
      {
        return; // the reload is still loading
      }
      if (doc.get() != state->Shown)
      {
        // A new document (the first, or a reload): what it shows is the new baseline.
        state->Pending = false;
        state->Shown = doc.get();
        state->Snapshots = static_cast<int>(doc->Snapshots.size());
        state->MetricsRows = MetricsRows(*doc);
        std::cout << "vis4gs view: following " << doc->Path << ": " << state->Snapshots
                  << " snapshots (last " << (doc->Snapshots.empty() ? -1 : doc->Snapshots.back())
                  << "), " << state->MetricsRows << " metrics rows" << std::endl;
        return;
      }
      // Reopen the log (RequestInformation opens it afresh) and count what it holds now.
      vtkGaussianTrainingLogReader* reader = doc->Reader;
      reader->Modified();
      reader->UpdateInformation();
      const int snapshots = reader->GetNumberOfSnapshots();
      vtkIdType rows = state->MetricsRows;
      if (reader->HasMetrics())
      {
        reader->Update(2);
        rows = reader->GetMetricsOutput() ? reader->GetMetricsOutput()->GetNumberOfRows() : rows;
      }
      if (snapshots <= state->Snapshots && rows <= state->MetricsRows)
      {
        return;
      }
      state->Pending = true;
      state->Reloading = doc.get();
      window->statusBar()->showMessage(QString("following: %1 snapshots, %2 metrics rows")
                                         .arg(snapshots)
                                         .arg(static_cast<qlonglong>(rows)),
        3000);
      window->Open(QString::fromStdString(doc->Path));
    });
  timer->start(intervalMs);
}

// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSCleanupPanelInternals.h"
#include "Vis4GSPostResult.h"

#include "GaussianIO.h"
#include "Vis4GSDataModel.h"
#include "Vis4GSPipeline.h"
#include "vtkGaussianFineTuneFilter.h"
#include "vtkGaussianSelectionHub.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkStringArray.h"

#include <QApplication>
#include <QFile>
#include <QFileInfo>
#include <QLabel>
#include <QPushButton>
#include <QScrollArea>
#include <QTableWidget>
#include <QThread>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

using namespace Vis4GSCleanupTable;

namespace
{
// The fine-tune filter's figures @p table (repair.csv's rows) into @p rows, and the repaired
// figures per camera of @p cameras (NaN for the views without a row: without an image).
std::string ReadFineTuneFigures(vtkTable* table,
  const std::vector<vis4gs::Camera>& cameras,
  std::vector<vis4gs::FineTuneFigureRow>& rows,
  std::vector<vis4gs::ViewMetrics>& repaired)
{
  const std::vector<std::string>& columns = vis4gs::FineTuneFigureColumns();
  auto* view = vtkStringArray::SafeDownCast(table->GetColumnByName(columns[0].c_str()));
  auto* split = vtkStringArray::SafeDownCast(table->GetColumnByName(columns[1].c_str()));
  std::vector<vtkDataArray*> values;
  for (std::size_t c = 2; c < columns.size(); ++c)
  {
    values.push_back(vtkDataArray::SafeDownCast(table->GetColumnByName(columns[c].c_str())));
  }
  if (!view || !split || std::find(values.begin(), values.end(), nullptr) != values.end())
  {
    return "the fine-tune filter gave no figures table";
  }
  // The repaired figures per camera: the rows of the views with an image, in camera order.
  repaired.assign(cameras.size(), vis4gs::ViewMetrics());
  std::size_t camera = 0;
  bool means = true; // (the "mean" rows come first)
  for (vtkIdType r = 0; r < table->GetNumberOfRows(); ++r)
  {
    vis4gs::FineTuneFigureRow row{ view->GetValue(r), split->GetValue(r), {} };
    for (std::size_t k = 0; k < values.size(); ++k)
    {
      row.Values[k] = values[k]->GetTuple1(r);
    }
    means = means && row.View == "mean";
    if (!means)
    {
      while (camera < cameras.size() && cameras[camera].Name != row.View)
      {
        ++camera;
      }
      if (camera < cameras.size())
      {
        repaired[camera] = { row.Values[2], row.Values[5], row.Values[8] };
        ++camera;
      }
    }
    rows.push_back(std::move(row));
  }
  return std::string();
}
} // namespace

//------------------------------------------------------------------------------
bool Vis4GSCleanupPanel::StartFineTune(const QString& logPath,
  int iterations,
  bool freePositions,
  bool densify)
{
  auto refuse = [this](const QString& why)
  {
    d->RepairLabel->setText(why);
    return false;
  };
  if (d->Worker || d->RepairWorker)
  {
    return refuse("A measurement or a fine-tune is running.");
  }
  if (!d->Shown || d->Shown->Scene != d->Scene ||
    d->MeasuredChanges != d->Hub->GetNumberOfChanges())
  {
    return refuse("Measure the removal of the selection first: the fine-tune starts from its "
                  "preview (the table is of another selection or snapshot).");
  }
  auto job = std::make_shared<Internals::Repair>();
  job->Preview = d->Shown;
  job->LogPath = logPath;
  job->Iterations = iterations;
  job->FreePositions = freePositions;
  job->Densify = densify;
  job->SourceIteration = this->GetSourceIteration();
  // A session of its own, given the scene measured (a shallow copy again: the preview's
  // session stays the GUI thread's, for the difference images) and the cameras.
  vtkNew<vtkPolyData> copy;
  copy->ShallowCopy(d->Shown->Session->GetGaussiansData());
  job->Session = this->GivenDataSession(copy);
  vtkGaussianFineTuneFilter* tune = job->Session->GetFineTuneFilter();
  tune->SetRemovedIds(d->Shown->Removed);
  tune->SetSourceIteration(job->SourceIteration);
  tune->SetIterations(iterations);
  tune->SetFreePositions(freePositions);
  tune->SetDensify(densify);
  tune->SetOutputLogFileName(logPath.toStdString().c_str());
  tune->SetProducer((std::string("vis4gs view ") + VIS4GS_VERSION).c_str());
  // The source and deleted figures are the preview's (the same per-tile sums as vis4gs
  // repair's): only the repaired scene is measured.
  vtkNew<vtkTable> figures;
  figures->ShallowCopy(d->Shown->Session->GetRemovalViewsOutput());
  tune->SetRemovalFiguresData(figures);
  if (auto* logFile = vtkStringArray::SafeDownCast(
        d->Cameras->GetFieldData()->GetAbstractArray(vis4gs::arrays::CameraTrainingLogFile)))
  {
    if (logFile->GetNumberOfValues() == 1)
    {
      // The filter names the repaired log after it and embeds the images when it does.
      job->SourceLog = QString::fromStdString(logFile->GetValue(0));
    }
  }
  if (job->SourceLog.isEmpty())
  {
    // Its images embedded, so that the repaired log stands on its own; a scene file names it,
    // as vis4gs repair does.
    tune->SetEmbedImages(1);
    if (!d->SceneFile.isEmpty())
    {
      job->SourceScene = d->SceneFile;
      job->SourceCameras = d->SceneCameras;
      tune->SetSceneName(QFileInfo(d->SceneFile).completeBaseName().toStdString().c_str());
    }
  }
  d->Repairing = job;
  d->RepairLabel->setText(QString("fine-tuning the deletion of %1 Gaussians for %2 iterations...")
                            .arg(d->Shown->Effect.Removed)
                            .arg(iterations));
  if (d->Progress)
  {
    d->Progress(0, d->RepairLabel->text(), false);
  }
  d->RepairWorker = QThread::create(
    [this, job, tune]
    {
      // Each iteration's progress to the bar; Cancel aborts the filter after the iteration.
      struct Context
      {
        Vis4GSCleanupPanel* Panel;
        Internals::Repair* Job;
      } context{ this, job.get() };
      vtkNew<vtkCallbackCommand> progress;
      progress->SetClientData(&context);
      progress->SetCallback(
        [](vtkObject* caller, unsigned long, void* client, void*)
        {
          auto* c = static_cast<Context*>(client);
          auto* filter = static_cast<vtkGaussianFineTuneFilter*>(caller);
          const int total = c->Job->Iterations;
          const int done = static_cast<int>(std::lround(filter->GetProgress() * total));
          Vis4GSCleanupPanel* panel = c->Panel;
          Vis4GSPostResult(panel,
            [panel, done, total]
            {
              if (panel->d->Progress && panel->d->RepairWorker)
              {
                panel->d->Progress(done < total ? static_cast<double>(done) / total : -1.0,
                  done < total ? QString("fine-tuning the cleaned scene: iteration %1 of %2")
                                   .arg(done)
                                   .arg(total)
                               : QString("measuring the repaired scene in every view"),
                  false);
              }
            });
          if (c->Job->Cancel)
          {
            filter->AbortExecuteOn();
          }
        });
      const unsigned long tag = tune->AddObserver(vtkCommand::ProgressEvent, progress);
      const std::string errors = Vis4GSUpdate(tune, 0);
      tune->RemoveObserver(tag);
      job->LastIteration = tune->GetLastIteration();
      job->TrainSeconds = tune->GetTrainSeconds();
      job->MeasureSeconds = tune->GetMeasureSeconds();
      if (!errors.empty())
      {
        job->Error = errors;
      }
      else if (job->Cancel && tune->GetOutput()->GetNumberOfPoints() == 0)
      {
        job->Cancelled = true;
      }
      else
      {
        job->Error = ReadFineTuneFigures(
          tune->GetFiguresOutput(), job->Preview->Cameras, job->Rows, job->RepairedFigures);
      }
      Vis4GSPostResult(this, [this] { this->OnFineTuned(); });
    });
  this->UpdateButtons();
  d->RepairWorker->start();
  this->UpdateButtons();
  return true;
}

//------------------------------------------------------------------------------
void Vis4GSCleanupPanel::CancelFineTune()
{
  if (d->Repairing)
  {
    d->Repairing->Cancel = true;
  }
}

//------------------------------------------------------------------------------
void Vis4GSCleanupPanel::OnFineTuned()
{
  d->RepairWorker->wait();
  d->RepairWorker->deleteLater();
  d->RepairWorker = nullptr;
  const std::shared_ptr<Internals::Repair> job = std::move(d->Repairing);
  d->Measure->setEnabled(d->Scene && d->Cameras);
  this->UpdateButtons();
  if (!job->Error.empty() || job->Cancelled)
  {
    d->RepairLabel->setText(!job->Error.empty()
        ? "fine-tune failed: " + QString::fromStdString(job->Error)
        : QString("Fine-tune cancelled after iteration %1 of %2: no log written.")
            .arg(std::max(0, job->LastIteration - job->SourceIteration))
            .arg(job->Iterations));
    if (d->Progress)
    {
      d->Progress(1, d->RepairLabel->text(), true);
    }
    return;
  }
  d->Repaired = job;
  // The third state in the table, if it still shows the preview fine-tuned.
  const bool shown = d->Shown == job->Preview;
  double means[2][9];
  bool have[2] = { false, false };
  for (const vis4gs::FineTuneFigureRow& row : job->Rows)
  {
    if (row.View == "mean")
    {
      const int split = row.Split == "train" ? 0 : 1;
      std::copy(row.Values, row.Values + 9, means[split]);
      have[split] = true;
    }
  }
  if (shown)
  {
    for (int split = 0; split < 2; ++split)
    {
      for (int m = 0; m < 3; ++m)
      {
        SetNumber(d->Totals,
          split,
          RepairedColumn + m,
          have[split] ? means[split][3 * m + 2] : std::numeric_limits<double>::quiet_NaN());
      }
    }
    for (int row = 0; row < d->Views->rowCount(); ++row)
    {
      const std::size_t v = d->Views->item(row, 0)->data(Qt::UserRole).toULongLong();
      const vis4gs::ViewMetrics m =
        v < job->RepairedFigures.size() ? job->RepairedFigures[v] : vis4gs::ViewMetrics{};
      SetNumber(d->Views, row, RepairedColumn, m.Psnr);
      SetNumber(d->Views, row, RepairedColumn + 1, m.Ssim);
      SetNumber(d->Views, row, RepairedColumn + 2, m.L1);
    }
    for (QTableWidget* table : { d->Totals, d->Views })
    {
      for (int c = RepairedColumn; c < NumberOfColumns; ++c)
      {
        table->setColumnHidden(c, false);
      }
    }
  }
  auto psnr = [&](int split, int state)
  { return have[split] ? QString::number(means[split][state], 'f', 3) : QString("-"); };
  d->RepairLabel->setToolTip("The repaired run's log: " + job->LogPath);
  d->RepairLabel->setText(
    QString("Repaired (%1 iterations, positions %2, densification %3, %4 s): PSNR source -> "
            "deleted -> repaired: train %5 -> %6 -> %7 dB, test %8 -> %9 -> %10 dB. Log: %11")
      .arg(job->Iterations)
      .arg(job->FreePositions ? "free" : "fixed")
      .arg(job->Densify ? "on" : "off")
      .arg(job->TrainSeconds + job->MeasureSeconds, 0, 'f', 1)
      .arg(psnr(0, 0))
      .arg(psnr(0, 1))
      .arg(psnr(0, 2))
      .arg(psnr(1, 0))
      .arg(psnr(1, 1))
      .arg(psnr(1, 2))
      .arg(QFileInfo(job->LogPath).fileName()));
  d->OpenRepaired->setVisible(static_cast<bool>(d->Open));
  d->CompareRepaired->setVisible(!job->SourceLog.isEmpty() || !job->SourceScene.isEmpty());
  // The new columns and the summary in sight.
  d->LeftScroll->ensureWidgetVisible(d->RepairLabel);
  for (QTableWidget* table : { d->Totals, d->Views })
  {
    if (shown && table->rowCount() > 0 && table->item(0, RepairedColumn))
    {
      table->scrollToItem(table->item(0, RepairedColumn));
    }
  }
  if (d->Progress)
  {
    d->Progress(1, d->RepairLabel->text() + " (" + job->LogPath + ")", true);
  }
}

//------------------------------------------------------------------------------
bool Vis4GSCleanupPanel::WaitForFineTune()
{
  const std::shared_ptr<Internals::Repair> job = d->Repairing;
  while (d->RepairWorker)
  {
    QApplication::processEvents(QEventLoop::AllEvents, 50);
    QThread::msleep(5);
  }
  return job && d->Repaired == job;
}

//------------------------------------------------------------------------------
bool Vis4GSCleanupPanel::WriteRepairTable(const QString& path) const
{
  if (!d->Repaired)
  {
    return false;
  }
  std::ostringstream csv;
  {
    const std::vector<std::string>& columns = vis4gs::FineTuneFigureColumns();
    for (std::size_t c = 0; c < columns.size(); ++c)
    {
      csv << (c ? "," : "") << columns[c];
    }
    csv << "\n" << std::setprecision(17);
    for (const vis4gs::FineTuneFigureRow& row : d->Repaired->Rows)
    {
      csv << row.View << "," << row.Split;
      for (double v : row.Values)
      {
        csv << "," << v;
      }
      csv << "\n";
    }
  }
  try
  {
    vis4gs::WriteTextFile(path.toStdString(), csv.str());
    return true;
  }
  catch (const std::exception&)
  {
    return false;
  }
}

// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSCleanupPanelInternals.h"
#include "Vis4GSPostResult.h"

#include "GaussianIO.h"
#include "Vis4GSDataModel.h"
#include "Vis4GSPipeline.h"
#include "vtkGaussianSelectionHub.h"
#include "vtkGaussianTrainingLogReader.h"

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
#include <chrono>
#include <iomanip>
#include <limits>
#include <sstream>

using namespace Vis4GSCleanupTable;

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
  vis4gs::FineTuneOptions& options = job->Options;
  options.Iterations = iterations;
  options.FreePositions = freePositions;
  options.Densify = densify;
  options.LogPath = logPath.toStdString();
  options.Producer = std::string("vis4gs view ") + VIS4GS_VERSION;
  // The source and deleted figures are the preview's (the same per-tile sums as vis4gs
  // repair's): only the repaired scene is measured.
  options.Measure = false;
  if (auto* logFile = vtkStringArray::SafeDownCast(
        d->Cameras->GetFieldData()->GetAbstractArray(vis4gs::arrays::CameraTrainingLogFile)))
  {
    if (logFile->GetNumberOfValues() == 1)
    {
      job->SourceLog = QString::fromStdString(logFile->GetValue(0));
      // The header as a script reads it: the repaired log keeps the scene name, and embeds
      // the images when the source log does (as vis4gs repair).
      vtkNew<vtkGaussianTrainingLogReader> log;
      log->SetFileName(logFile->GetValue(0).c_str());
      Vis4GSErrorCollector errors(log);
      log->UpdateInformation();
      if (!errors.GetMessages().empty())
      {
        return refuse(QString::fromStdString(errors.GetMessages()));
      }
      options.Scene = log->GetSceneName();
      options.EmbedImages = log->HasImages();
    }
  }
  if (job->SourceLog.isEmpty() && !d->SceneFile.isEmpty())
  {
    // A scene file, as vis4gs repair names it; its images are embedded (the default) so that
    // the repaired log stands on its own.
    job->SourceScene = d->SceneFile;
    job->SourceCameras = d->SceneCameras;
    options.Scene = QFileInfo(d->SceneFile).completeBaseName().toStdString();
  }
  Internals::Repair* raw = job.get(); // (the job owns its options: no cycle)
  options.Progress = [this, raw](int done, int total)
  {
    QMetaObject::invokeMethod(
      this,
      [this, done, total]
      {
        if (d->Progress && d->RepairWorker)
        {
          d->Progress(static_cast<double>(done) / total,
            QString("fine-tuning the cleaned scene: iteration %1 of %2").arg(done).arg(total),
            false);
        }
      },
      Qt::QueuedConnection);
    return !raw->Cancel;
  };
  const int source = this->GetSourceIteration();
  d->Repairing = job;
  d->RepairLabel->setText(QString("fine-tuning the deletion of %1 Gaussians for %2 iterations...")
                            .arg(d->Shown->Effect.Removed)
                            .arg(iterations));
  if (d->Progress)
  {
    d->Progress(0, d->RepairLabel->text(), false);
  }
  d->RepairWorker = QThread::create(
    [this, job, source]
    {
      try
      {
        const Internals::Result& preview = *job->Preview;
        job->Figures = vis4gs::FineTune(
          *preview.Cloud, source, preview.Removed, preview.Cameras, preview.Images, job->Options);
        if (!job->Figures.Cancelled)
        {
          QMetaObject::invokeMethod(
            this,
            [this]
            {
              if (d->Progress)
              {
                d->Progress(-1, "measuring the repaired scene in every view", false);
              }
            },
            Qt::QueuedConnection);
          const std::size_t n = preview.Cameras.size();
          job->Figures.Source.assign(n, vis4gs::ViewMetrics{});
          job->Figures.Deleted.assign(n, vis4gs::ViewMetrics{});
          for (std::size_t v = 0; v < preview.Baseline.Views.size() && v < n; ++v)
          {
            if (!preview.Baseline.Views[v].Empty())
            {
              job->Figures.Source[v] = preview.Baseline.Views[v].Metrics();
            }
          }
          for (const vis4gs::RemovalViewEffect& view : preview.Effect.Views)
          {
            if (view.HasImage && view.CameraIndex < n)
            {
              job->Figures.Deleted[view.CameraIndex] = view.After;
            }
          }
          const auto t0 = std::chrono::steady_clock::now();
          job->Figures.RepairedFigures = vis4gs::MeasureViewMetrics(
            job->Figures.Repaired, preview.Cameras, vis4gs::RemovalEffectOptions{}, preview.Images);
          job->Figures.MeasureSeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          job->Rows = vis4gs::FineTuneFigureRows(job->Figures, preview.Cameras);
        }
      }
      catch (const std::exception& e)
      {
        job->Error = e.what();
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
  const vis4gs::FineTuneResult& r = job->Figures;
  if (!job->Error.empty() || r.Cancelled)
  {
    d->RepairLabel->setText(!job->Error.empty()
        ? "fine-tune failed: " + QString::fromStdString(job->Error)
        : QString("Fine-tune cancelled after iteration %1 of %2: no log written.")
            .arg(r.LastIteration - r.SourceIteration)
            .arg(job->Options.Iterations));
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
        v < r.RepairedFigures.size() ? r.RepairedFigures[v] : vis4gs::ViewMetrics{};
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
      .arg(job->Options.Iterations)
      .arg(job->Options.FreePositions ? "free" : "fixed")
      .arg(job->Options.Densify ? "on" : "off")
      .arg(r.TrainSeconds + r.MeasureSeconds, 0, 'f', 1)
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

// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSCleanupPanelInternals.h"
#include "Vis4GSPostResult.h"

#include "GaussianIO.h"
#include "Vis4GSDataModel.h"
#include "Vis4GSTrainingImages.h"
#include "vtkGaussianSelectionHub.h"

#include <QApplication>
#include <QImage>
#include <QLabel>
#include <QPixmap>
#include <QPushButton>
#include <QTableWidget>
#include <QThread>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>

using namespace Vis4GSCleanupTable;

namespace
{
// A heat map of t in [0, 1]: black, red, yellow, white.
void Heat(double t, unsigned char* rgb)
{
  t = std::min(1.0, std::max(0.0, t)) * 3.0;
  const double r = std::min(1.0, t), g = std::min(1.0, std::max(0.0, t - 1.0)),
               b = std::max(0.0, t - 2.0);
  rgb[0] = static_cast<unsigned char>(255 * r + 0.5);
  rgb[1] = static_cast<unsigned char>(255 * g + 0.5);
  rgb[2] = static_cast<unsigned char>(255 * b + 0.5);
}

QImage ToQImage(const vis4gs::Image& image)
{
  QImage out(image.Width, image.Height, QImage::Format_RGB888);
  for (int y = 0; y < image.Height; ++y)
  {
    unsigned char* line = out.scanLine(y);
    for (int x = 0; x < image.Width; ++x)
    {
      for (int c = 0; c < 3; ++c)
      {
        const float v =
          image.Pixels[(static_cast<std::size_t>(y) * image.Width + x) * image.Channels +
            static_cast<std::size_t>(std::min(c, image.Channels - 1))];
        line[3 * x + c] = static_cast<unsigned char>(255.0f * v + 0.5f);
      }
    }
  }
  return out;
}

void SetText(QTableWidget* table, int row, int column, const QString& text)
{
  table->setItem(row, column, new QTableWidgetItem(text));
}

// Renders the "before" of the wanted views with an image that @p baseline lacks (every view
// for an empty baseline: the score pass keeps only the training views it renders). Returns
// the number of views rendered.
std::size_t CompleteBaseline(vis4gs::RemovalBaseline& baseline,
  const vis4gs::GaussianCloud& cloud,
  const std::vector<vis4gs::Camera>& cameras,
  const vis4gs::RemovalEffectOptions& options,
  const vis4gs::TrainingImageProvider& images)
{
  if (baseline.Views.empty())
  {
    baseline = vis4gs::MeasureRemovalBaseline(cloud, cameras, options, images);
    return baseline.MeasuredViews();
  }
  std::vector<std::size_t> missing;
  std::vector<vis4gs::Camera> subset;
  for (std::size_t v = 0; v < cameras.size(); ++v)
  {
    if (baseline.Views[v].Empty())
    {
      missing.push_back(v);
      subset.push_back(cameras[v]);
    }
  }
  if (missing.empty())
  {
    return 0;
  }
  vis4gs::RemovalBaseline part = vis4gs::MeasureRemovalBaseline(cloud,
    subset,
    options,
    [&images, &missing](std::size_t i, const vis4gs::Camera& camera, vis4gs::Image& image)
    { return images(missing[i], camera, image); });
  std::size_t rendered = 0;
  for (std::size_t i = 0; i < missing.size(); ++i)
  {
    if (!part.Views[i].Empty())
    {
      baseline.Views[missing[i]] = std::move(part.Views[i]);
      ++rendered;
    }
  }
  return rendered;
}
} // namespace

//------------------------------------------------------------------------------
void Vis4GSCleanupTable::SetNumber(QTableWidget* table, int row, int column, double value)
{
  auto* item =
    new QTableWidgetItem(std::isnan(value) ? QString("-") : QString::number(value, 'f', 4));
  item->setData(Qt::UserRole, value);
  item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
  table->setItem(row, column, item);
}

//------------------------------------------------------------------------------
void Vis4GSCleanupTable::FillRow(QTableWidget* table,
  int row,
  const QString& name,
  const QString& split,
  const QString& changed,
  const vis4gs::ViewMetrics& before,
  const vis4gs::ViewMetrics& after)
{
  SetText(table, row, 0, name);
  SetText(table, row, 1, split);
  SetText(table, row, 2, changed);
  const double b[3] = { before.Psnr, before.Ssim, before.L1 };
  const double a[3] = { after.Psnr, after.Ssim, after.L1 };
  for (int m = 0; m < 3; ++m)
  {
    SetNumber(table, row, 3 + 3 * m, b[m]);
    SetNumber(table, row, 4 + 3 * m, a[m]);
    SetNumber(table, row, 5 + 3 * m, a[m] - b[m]);
  }
}

//------------------------------------------------------------------------------
void Vis4GSCleanupPanel::MeasureRemoval()
{
  if (d->Worker || d->RepairWorker || !d->Scene || !d->Cameras)
  {
    return;
  }
  auto job = std::make_shared<Internals::Result>();
  job->Scene = d->Scene;
  job->CameraTable = d->Cameras;
  // A shallow copy: the GUI thread may add score arrays to the scene while the worker reads.
  vtkNew<vtkPolyData> copy;
  copy->ShallowCopy(d->Scene);
  job->Cloud = std::make_shared<vis4gs::GaussianCloud>();
  std::string error;
  if (!vis4gs::PolyDataToGaussianCloud(copy, *job->Cloud, &error) ||
    !vis4gs::TableToCameras(d->Cameras, job->Cameras, &error))
  {
    d->MeasureLabel->setText(QString::fromStdString(error));
    return;
  }
  // The training images as the score and removal filters find them (Vis4GSTrainingImages):
  // "/images/<name>" from the log that the camera table names, others from files.
  if (!Vis4GSTrainingImages(
        d->Cameras, std::string(), { 0.f, 0.f, 0.f }, job->Cameras, job->Images, error))
  {
    d->MeasureLabel->setText(QString::fromStdString(error));
    return;
  }
  job->Removed.assign(job->Cloud->Count, 0);
  std::size_t removed = 0;
  for (std::size_t i = 0; i < job->Cloud->Count; ++i)
  {
    if (d->Hub->IsSelected(static_cast<vtkIdType>(job->Cloud->GetId(i))))
    {
      job->Removed[i] = 1;
      ++removed;
    }
  }
  if (removed == 0)
  {
    d->MeasureLabel->setText("Select Gaussians first (a rule, a brush, the histogram).");
    return;
  }
  if (d->BaselineScene == d->Scene && d->BaselineCameras == d->Cameras &&
    d->Baseline.Views.size() == job->Cameras.size())
  {
    job->Baseline = d->Baseline;
    job->BeforeReused = d->Baseline.MeasuredViews();
  }
  d->Running = job;
  d->MeasuredChanges = d->Hub->GetNumberOfChanges();
  d->LastFailed = false;
  d->Measure->setEnabled(false);
  d->FineTune->setEnabled(false);
  const QString what = QString("measuring the removal of %1 Gaussians").arg(removed);
  d->MeasureLabel->setText(what + "...");
  if (d->Progress)
  {
    d->Progress(-1,
      what +
        (job->BeforeReused == 0 ? ": rendering every view before"
                                : ": rendering the views before that the score pass did not"),
      false);
  }
  // RemovalEffect has no progress callback: the bar is a busy indicator with the step named.
  d->Worker = QThread::create(
    [this, job, what]
    {
      try
      {
        vis4gs::RemovalEffectOptions options;
        const auto t0 = std::chrono::steady_clock::now();
        job->BeforeRendered =
          CompleteBaseline(job->Baseline, *job->Cloud, job->Cameras, options, job->Images);
        if (job->BeforeRendered > 0)
        {
          job->BaselineSeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          QMetaObject::invokeMethod(
            this,
            [this, what]
            {
              if (d->Progress)
              {
                d->Progress(-1, what + ": rendering the views it touches after", false);
              }
            },
            Qt::QueuedConnection);
        }
        options.TileBaseline = job->Baseline;
        job->Effect = vis4gs::MeasureRemovalEffect(
          *job->Cloud, job->Removed, job->Cameras, options, job->Images);
      }
      catch (const std::exception& e)
      {
        job->Error = e.what();
      }
      Vis4GSPostResult(this, [this] { this->OnMeasured(); });
    });
  d->Worker->start();
}

//------------------------------------------------------------------------------
void Vis4GSCleanupPanel::OnMeasured()
{
  d->Worker->wait();
  d->Worker->deleteLater();
  d->Worker = nullptr;
  std::shared_ptr<Internals::Result> job = std::move(d->Running);
  d->Measure->setEnabled(d->Scene && d->Cameras);
  this->UpdateButtons();
  if (!job->Error.empty())
  {
    d->LastFailed = true;
    d->MeasureLabel->setText("measurement failed: " + QString::fromStdString(job->Error));
    if (d->Progress)
    {
      d->Progress(1, d->MeasureLabel->text(), true);
    }
    return;
  }
  d->BaselineScene = job->Scene;
  d->BaselineCameras = job->CameraTable;
  d->Baseline = job->Baseline;
  d->Shown = job;
  const vis4gs::RemovalEffect& e = job->Effect;
  const QString summary = QString(
    "Deleting %1 Gaussians (%2 kept): training PSNR %3 -> %4 dB (%5 of %6 views "
    "changed), test PSNR %7 -> %8 dB (%9 of %10). Before: %11 views reused (the score pass, "
    "earlier previews), %12; after: %13 views rendered in %14 s.")
                            .arg(e.Removed)
                            .arg(e.Kept)
                            .arg(e.Train.Before.Psnr, 0, 'f', 3)
                            .arg(e.Train.After.Psnr, 0, 'f', 3)
                            .arg(e.Train.AffectedViews)
                            .arg(e.Train.Views)
                            .arg(e.Test.Before.Psnr, 0, 'f', 3)
                            .arg(e.Test.After.Psnr, 0, 'f', 3)
                            .arg(e.Test.AffectedViews)
                            .arg(e.Test.Views)
                            .arg(job->BeforeReused)
                            .arg(QString("%1 rendered in %2 s")
                                   .arg(job->BeforeRendered)
                                   .arg(std::max(0.0, job->BaselineSeconds), 0, 'f', 2))
                            .arg(e.ViewsRendered)
                            .arg(e.SecondsAfter, 0, 'f', 2);
  d->MeasureLabel->setText(summary);
  FillRow(d->Totals,
    0,
    "mean",
    "train",
    QString("%1 of %2").arg(e.Train.AffectedViews).arg(e.Train.Views),
    e.Train.Before,
    e.Train.After);
  FillRow(d->Totals,
    1,
    "mean",
    "test",
    QString("%1 of %2").arg(e.Test.AffectedViews).arg(e.Test.Views),
    e.Test.Before,
    e.Test.After);
  d->Views->blockSignals(true);
  d->Views->clearContents();
  for (QTableWidget* table : { d->Totals, d->Views })
  {
    for (int c = RepairedColumn; c < NumberOfColumns; ++c)
    {
      table->setColumnHidden(c, true); // a fine-tune of this preview shows them
    }
  }
  d->Views->setRowCount(static_cast<int>(e.Views.size()));
  for (std::size_t r = 0; r < e.Views.size(); ++r)
  {
    const vis4gs::RemovalViewEffect& v = e.Views[r];
    FillRow(d->Views,
      static_cast<int>(r),
      QString::fromStdString(v.Name),
      v.Split == vis4gs::CameraSplit::Train ? "train" : "test",
      v.Affected ? "yes" : "no",
      v.Before,
      v.After);
    d->Views->item(static_cast<int>(r), 0)
      ->setData(Qt::UserRole, static_cast<qulonglong>(v.CameraIndex));
    if (v.HasImage && v.PsnrChange() < 0)
    {
      d->Views->item(static_cast<int>(r), 5)->setForeground(QColor(192, 0, 0));
    }
  }
  d->Views->blockSignals(false);
  this->OnSelectionChanged();
  if (d->Progress)
  {
    d->Progress(1, summary, true);
  }
}

//------------------------------------------------------------------------------
bool Vis4GSCleanupPanel::WaitForMeasurement()
{
  while (d->Worker)
  {
    QApplication::processEvents(QEventLoop::AllEvents, 50);
    QThread::msleep(5);
  }
  return !d->LastFailed && d->Shown;
}

//------------------------------------------------------------------------------
bool Vis4GSCleanupPanel::WriteTable(const QString& path) const
{
  std::ostringstream csv;
  csv << "view,split,affected,psnr_before,psnr_after,ssim_before,ssim_after,l1_before,l1_after\n"
      << std::setprecision(17);
  for (QTableWidget* table : { d->Totals, d->Views })
  {
    for (int r = 0; r < table->rowCount(); ++r)
    {
      if (!table->item(r, 0))
      {
        continue;
      }
      const QString changed = table->item(r, 2)->text();
      csv << table->item(r, 0)->text().toStdString() << ","
          << table->item(r, 1)->text().toStdString() << ","
          << (table == d->Totals ? changed.section(' ', 0, 0).toStdString()
                                 : std::string(changed == "yes" ? "1" : "0"));
      for (int c : { 3, 4, 6, 7, 9, 10 })
      {
        csv << "," << table->item(r, c)->data(Qt::UserRole).toDouble();
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

//------------------------------------------------------------------------------
void Vis4GSCleanupPanel::ShowDifference(int row)
{
  const std::shared_ptr<Internals::Result> shown = d->Shown;
  QTableWidgetItem* item = row >= 0 ? d->Views->item(row, 0) : nullptr;
  if (!shown || !item)
  {
    return;
  }
  const std::size_t index = item->data(Qt::UserRole).toULongLong();
  if (index >= shown->Cameras.size())
  {
    return;
  }
  QApplication::setOverrideCursor(Qt::WaitCursor);
  const vis4gs::Camera& camera = shown->Cameras[index];
  vis4gs::RemovalEffectOptions options; // the measurement's rasteriser settings
  const vis4gs::Image before =
    vis4gs::ClampedImage(vis4gs::Rasterize<float>(*shown->Cloud, camera, options.Raster));
  const vis4gs::Image after = vis4gs::ClampedImage(vis4gs::Rasterize<float>(
    vis4gs::RemoveGaussians(*shown->Cloud, shown->Removed), camera, options.Raster));
  vis4gs::Image diff = after;
  const std::size_t pixels = static_cast<std::size_t>(after.Width) * after.Height;
  std::vector<double> change(pixels, 0.0);
  double largest = 0;
  for (std::size_t p = 0; p < pixels; ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      const std::size_t i = 3 * p + static_cast<std::size_t>(c);
      change[p] += std::abs(static_cast<double>(after.Pixels[i]) - before.Pixels[i]) / 3.0;
    }
    largest = std::max(largest, change[p]);
  }
  for (std::size_t p = 0; p < pixels; ++p)
  {
    unsigned char rgb[3];
    // A square-root scale: small changes around a large one stay visible.
    Heat(largest > 0 ? std::sqrt(change[p] / largest) : 0.0, rgb);
    for (int c = 0; c < 3; ++c)
    {
      diff.Pixels[3 * p + static_cast<std::size_t>(c)] = rgb[c] / 255.0f;
    }
  }
  const vis4gs::Image* shownImages[3] = { &before, &after, &diff };
  for (int k = 0; k < 3; ++k)
  {
    const QImage image = ToQImage(*shownImages[k]);
    d->Images[k]->setPixmap(QPixmap::fromImage(image).scaled(d->Images[k]->width(),
      d->Images[k]->height(),
      Qt::KeepAspectRatio,
      Qt::SmoothTransformation));
    d->Images[k]->setProperty("largestChange", largest);
  }
  d->ImageCaption->setText(QString("%1: before, after, |after - before| (mean over RGB, "
                                   "square-root scale; white = %2, the largest change)")
                             .arg(QString::fromStdString(camera.Name))
                             .arg(largest, 0, 'g', 3));
  QApplication::restoreOverrideCursor();
}

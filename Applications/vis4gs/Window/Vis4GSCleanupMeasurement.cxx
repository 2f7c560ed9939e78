// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSCleanupPanelInternals.h"
#include "Vis4GSPostResult.h"

#include "GaussianIO.h"
#include "Vis4GSDataModel.h"
#include "Vis4GSPipeline.h"
#include "vtkGaussianRemovalEffectFilter.h"
#include "vtkGaussianSelectionHub.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkStringArray.h"

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
QString Vis4GSCleanupPanel::SourceName() const
{
  if (d->Cameras)
  {
    if (auto* logFile = vtkStringArray::SafeDownCast(
          d->Cameras->GetFieldData()->GetAbstractArray(vis4gs::arrays::CameraTrainingLogFile)))
    {
      if (logFile->GetNumberOfValues() == 1)
      {
        return QString::fromStdString(logFile->GetValue(0));
      }
    }
  }
  return d->SceneFile.isEmpty() ? QString("the scene shown") : d->SceneFile;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkGaussianSession> Vis4GSCleanupPanel::GivenDataSession(
  vtkPolyData* gaussians) const
{
  auto session = vtkSmartPointer<vtkGaussianSession>::New();
  session->SetFileName(this->SourceName().toStdString().c_str()); // (names its errors)
  session->SetGaussiansData(gaussians);
  // A table of its own (a shallow copy): updating a session marks its given data generated,
  // and two sessions may run in two threads (a preview's in the GUI thread, a fine-tune's).
  vtkNew<vtkTable> cameras;
  cameras->ShallowCopy(d->Cameras);
  session->SetCamerasData(cameras);
  session->ComputeScoresOff();
  return session;
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
  std::string error;
  if (!vis4gs::TableToCameras(d->Cameras, job->Cameras, &error))
  {
    d->MeasureLabel->setText(QString::fromStdString(error));
    return;
  }
  // A shallow copy: the GUI thread may add score arrays to the scene while the worker reads.
  vtkNew<vtkPolyData> copy;
  copy->ShallowCopy(d->Scene);
  // The selected Gaussians of this scene (the hub may hold ids of another snapshot too).
  job->Removed = vtkSmartPointer<vtkIdTypeArray>::New();
  vtkDataArray* ids = copy->GetPointData()->GetArray(vis4gs::arrays::GaussianId);
  for (vtkIdType i = 0; i < copy->GetNumberOfPoints(); ++i)
  {
    const vtkIdType id = ids ? static_cast<vtkIdType>(ids->GetTuple1(i)) : i;
    if (d->Hub->IsSelected(id))
    {
      job->Removed->InsertNextValue(id);
    }
  }
  const vtkIdType removed = job->Removed->GetNumberOfValues();
  if (removed == 0)
  {
    d->MeasureLabel->setText("Select Gaussians first (a rule, a brush, the histogram).");
    return;
  }
  job->Session = this->GivenDataSession(copy);
  job->Session->SetSelectedIds(job->Removed);
  if (d->BaselineScene == d->Scene && d->BaselineCameras == d->Cameras && d->Baseline &&
    d->Baseline->Views.size() == job->Cameras.size())
  {
    job->Session->GetRemovalEffectFilter()->SetBaseline(d->Baseline);
    job->BeforeReused = d->Baseline->MeasuredViews();
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
        (job->BeforeReused == 0 ? ": rendering every view before, then those it touches after"
                                : ": rendering the views before that the score pass did not, "
                                  "then those it touches after"),
      false);
  }
  // The removal filter has no progress events: the bar is a busy indicator with the step named.
  d->Worker = QThread::create(
    [this, job]
    {
      // Nothing else touches this session until the result is posted.
      const std::string errors = Vis4GSUpdate(job->Session, vtkGaussianSession::RemovalViewsPort);
      vtkGaussianRemovalEffectFilter* removal = job->Session->GetRemovalEffectFilter();
      if (!errors.empty())
      {
        job->Error = errors;
      }
      else if (removal->GetEffect(job->Effect, &job->Error))
      {
        job->Baseline = removal->GetMeasuredBaseline();
        job->BeforeRendered = static_cast<std::size_t>(removal->GetNumberOfBaselineViewsRendered());
        job->BeforeReused = static_cast<std::size_t>(removal->GetNumberOfBaselineViewsReused());
        job->BaselineSeconds = job->BeforeRendered > 0 ? removal->GetSecondsBefore() : -1;
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
  // The session's preview port: the renders the figures were measured on (the measurement's
  // worker has ended: the session is the GUI thread's now).
  shown->Session->SetRemovalPreviewView(static_cast<vtkIdType>(index));
  const std::string errors = Vis4GSUpdate(shown->Session, vtkGaussianSession::RemovalPreviewPort);
  vtkImageData* preview = shown->Session->GetRemovalPreviewOutput();
  vis4gs::Image before, after;
  if (!errors.empty() || !vtkGaussianRemovalEffectFilter::PreviewImage(preview, true, before) ||
    !vtkGaussianRemovalEffectFilter::PreviewImage(preview, false, after) ||
    after.Pixels.size() != before.Pixels.size())
  {
    d->ImageCaption->setText(QString("%1: no preview (%2)")
                               .arg(QString::fromStdString(camera.Name))
                               .arg(QString::fromStdString(errors)));
    QApplication::restoreOverrideCursor();
    return;
  }
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

// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSCleanupPanelInternals.h"

#include "TrainingLogTypes.h"
#include "Vis4GSCompareWindow.h"
#include "Vis4GSDataModel.h"
#include "Vis4GSPipeline.h"
#include "Vis4GSSelectionExport.h"
#include "Vis4GSTrainingImages.h"
#include "vtkGaussianFineTuneFilter.h"
#include "vtkGaussianRemovalEffectFilter.h"
#include "vtkGaussianSceneView.h"
#include "vtkGaussianSelectionHub.h"
#include "vtkGaussianTrainingLogReader.h"

#include "vtkDataArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkPointData.h"

#include <QApplication>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QLabel>
#include <QLineEdit>
#include <QTableWidget>
#include <QThread>
#include <QVariant>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <set>
#include <vector>

using namespace Vis4GSCleanupTable;

//------------------------------------------------------------------------------
bool Vis4GSCleanupPanel::RunSelfTest(const QString& directory,
  const std::function<bool(bool, const std::string&)>& check)
{
  bool ok = true;
  // A scene file (vis4gs-ViewCleanupScene): the checks of the panel's own mechanics that the
  // demo log's run makes (a 'before' rendered anew, a second preview, a cancelled fine-tune)
  // are left out, for time; its deletion is the rule's whole selection (step 7).
  const bool sceneFile = !d->SceneFile.isEmpty();
  vtkDataArray* ids = d->Scene ? d->Scene->GetPointData()->GetArray("GaussianId") : nullptr;
  if (!check(ids && ids->GetNumberOfTuples() > 10, "clean-up: a scene with ids"))
  {
    return false;
  }
  std::vector<vis4gs::Camera> cameras;
  vis4gs::TableToCameras(d->Cameras, cameras, nullptr);
  const double trainViews = static_cast<double>(std::count_if(cameras.begin(),
    cameras.end(),
    [](const vis4gs::Camera& c) { return c.Split == vis4gs::CameraSplit::Train; }));
  vtkDataArray* coverage = d->Scene->GetPointData()->GetArray(vis4gs::arrays::ViewCoverage);
  std::set<vtkIdType> expected;
  for (vtkIdType i = 0; coverage && i < coverage->GetNumberOfTuples(); ++i)
  {
    if (coverage->GetComponent(i, 0) * trainViews <= 3)
    {
      expected.insert(static_cast<vtkIdType>(ids->GetComponent(i, 0)));
    }
  }
  // A brushed selection (what the scene's modes or the histogram publish): two Gaussians and
  // one the rule selects.
  const vtkIdType brushed[3] = { static_cast<vtkIdType>(ids->GetComponent(0, 0)),
    static_cast<vtkIdType>(ids->GetComponent(1, 0)),
    expected.empty() ? static_cast<vtkIdType>(ids->GetComponent(2, 0)) : *expected.rbegin() };
  d->Hub->SelectIds(brushed, 3, vtkGaussianSelectionHub::REPLACE);
  const vtkIdType changes = d->Hub->GetNumberOfChanges();
  const vtkIdType brushedCount =
    static_cast<vtkIdType>(std::set<vtkIdType>(brushed, brushed + 3).size());
  // 1. A bad rule: an error naming the token, the selection unchanged.
  const bool applied = this->ApplyRule("covrage<=0.1 and opacity>=0.5", ADD);
  ok = check(!applied && d->Error && this->GetFeedback().contains("covrage") &&
           d->Rule->selectedText() == "covrage",
         "clean-up: a misspelt attribute is an error naming it (" +
           this->GetFeedback().toStdString() + ")") &&
    ok;
  ok = check(d->Hub->GetNumberOfSelectedIds() == brushedCount &&
           d->Hub->GetNumberOfChanges() == changes,
         "clean-up: the bad rule left the selection alone") &&
    ok;
  // 2. The rule typed with spaces is shown in canonical form; Replace selects what the rule
  //    selects, computed here from the score array directly.
  d->Rule->setText("VIEWS <= 3");
  ok =
    check(!d->Error && this->GetFeedback().contains("views&lt;=3"),
      "clean-up: the canonical form is shown back (" + this->GetFeedback().toStdString() + ")") &&
    ok;
  auto selected = [this]
  {
    vtkNew<vtkIdTypeArray> a;
    d->Hub->GetSelectedIds(a);
    return std::set<vtkIdType>(a->GetPointer(0), a->GetPointer(0) + a->GetNumberOfTuples());
  };
  std::set<vtkIdType> withBrush(expected);
  withBrush.insert(brushed, brushed + 3);
  ok = check(this->ApplyRule(d->Rule->text(), ADD) && selected() == withBrush,
         "clean-up: 'views<=3' added to a brushed selection selects " +
           std::to_string(withBrush.size()) + " Gaussians") &&
    ok;
  std::set<vtkIdType> inBrush;
  for (vtkIdType id : brushed)
  {
    if (expected.count(id))
    {
      inBrush.insert(id);
    }
  }
  d->Hub->SelectIds(brushed, 3, vtkGaussianSelectionHub::REPLACE);
  ok = check(this->ApplyRule(d->Rule->text(), INTERSECT) && selected() == inBrush,
         "clean-up: intersected with the brushed selection leaves " +
           std::to_string(inBrush.size())) &&
    ok;
  ok =
    check(this->ApplyRule(d->Rule->text(), REPLACE) && selected() == expected && !expected.empty(),
      "clean-up: replace selects the " + std::to_string(expected.size()) +
        " Gaussians with E_VC |V| <= 3") &&
    ok;
  {
    std::ofstream csv((directory + "/cleanup-selection.csv").toStdString());
    csv << "GaussianId\n";
    for (vtkIdType id : selected())
    {
      csv << id << "\n";
    }
  }
  // 3. Save and load (the file analyze --select=@FILE reads).
  const QString rulePath = directory + "/cleanup-rule.txt";
  ok = check(this->SaveRule(rulePath), "clean-up: the rule is saved") && ok;
  d->Rule->setText("opacity>0");
  ok = check(this->LoadRule(rulePath) && d->Rule->text() == "views<=3",
         "clean-up: the saved rule loads back in canonical form") &&
    ok;
  // 4. Another iteration (a new scene): the rule is re-applied once its scores are there.
  {
    const vtkSmartPointer<vtkPolyData> scene = d->Scene;
    const vtkSmartPointer<vtkTable> table = d->Cameras;
    vtkNew<vtkPolyData> withoutScores, withScores;
    withoutScores->ShallowCopy(scene);
    withoutScores->GetPointData()->RemoveArray(vis4gs::arrays::ViewCoverage);
    withScores->ShallowCopy(scene);
    const std::shared_ptr<const vis4gs::RemovalBaseline> fromScores = d->Baseline;
    d->Hub->SelectIds(brushed, 3, vtkGaussianSelectionHub::REPLACE);
    this->SetScene(withoutScores, table);
    ok = check(d->Hub->GetNumberOfSelectedIds() == brushedCount,
           "clean-up: a new iteration without its scores yet keeps the selection") &&
      ok;
    this->SetScoreBaseline(scene, table, fromScores);
    ok = check(!d->Baseline && !d->BaselineScene,
           "clean-up: another snapshot drops the score pass's 'before', and a 'before' of "
           "a scene not shown is refused") &&
      ok;
    this->SetScene(withScores, table);
    ok =
      check(selected() == expected, "clean-up: the rule is re-applied once the scores are there") &&
      ok;
    this->SetScene(scene, table);
    // What the main window hands over when the score pass of this scene ends.
    this->SetScoreBaseline(scene, table, fromScores);
  }
  // The inputs of a measurement as Core takes them, read here from what the panel's session
  // was given (its Gaussians, the camera table, the ids removed): the panel measured through
  // Core itself before it ran the session (issue 33), and its figures, preview images and
  // fine-tuned scene must be what Core gives.
  struct CoreInputs
  {
    vis4gs::GaussianCloud Cloud;
    std::vector<std::uint8_t> Removed;
    std::vector<vis4gs::Camera> Cameras;
    vis4gs::TrainingImageProvider Images;
  };
  auto coreInputs = [](const Internals::Result& shown, CoreInputs& in)
  {
    std::string error;
    if (!vis4gs::PolyDataToGaussianCloud(shown.Session->GetGaussiansData(), in.Cloud, &error) ||
      !vis4gs::TableToCameras(shown.CameraTable, in.Cameras, &error) ||
      !Vis4GSTrainingImages(
        shown.CameraTable, std::string(), { 0.f, 0.f, 0.f }, in.Cameras, in.Images, error))
    {
      return false;
    }
    const vtkIdType* removed = shown.Removed->GetPointer(0);
    const std::set<vtkIdType> ids(removed, removed + shown.Removed->GetNumberOfValues());
    in.Removed.assign(in.Cloud.Count, 0);
    for (std::size_t i = 0; i < in.Cloud.Count; ++i)
    {
      in.Removed[i] = ids.count(static_cast<vtkIdType>(in.Cloud.GetId(i))) ? 1 : 0;
    }
    return true;
  };
  // The "before" renders of a preview (the score pass renders no test view), its "after"
  // renders (the affected views only), and its figures against those of a "before" rendered
  // anew through Core (what the panel did before it reused the score pass's): bit for bit.
  auto checkReuse = [&check, &coreInputs](
                      const Internals::Result& shown, std::size_t reused, bool figures)
  {
    const vis4gs::RemovalEffect& effect = shown.Effect;
    std::size_t affected = 0;
    for (const vis4gs::RemovalViewEffect& v : effect.Views)
    {
      affected += v.Affected && v.HasImage ? 1 : 0;
    }
    bool ok = check(reused > 0 && shown.BeforeReused == reused &&
        shown.BeforeRendered + reused == effect.Train.Views + effect.Test.Views &&
        reused >= effect.Train.Views && effect.ViewsRendered == affected,
      "clean-up: the preview reused " + std::to_string(reused) + " views 'before' (" +
        std::to_string(effect.Train.Views) + " training views), rendered " +
        std::to_string(shown.BeforeRendered) + " 'before' and " +
        std::to_string(effect.ViewsRendered) + " 'after' (" + std::to_string(effect.TilesRendered) +
        " of " + std::to_string(effect.TilesOfTiledViews) + " tiles) for " +
        std::to_string(affected) + " affected views");
    if (!figures)
    {
      return ok;
    }
    CoreInputs in;
    if (!check(coreInputs(shown, in), "clean-up: the measurement's inputs read back for Core"))
    {
      return false;
    }
    vis4gs::RemovalEffectOptions options;
    const auto t0 = std::chrono::steady_clock::now();
    options.TileBaseline = vis4gs::MeasureRemovalBaseline(in.Cloud, in.Cameras, options, in.Images);
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const vis4gs::RemovalEffect fresh =
      vis4gs::MeasureRemovalEffect(in.Cloud, in.Removed, in.Cameras, options, in.Images);
    auto same = [](const vis4gs::ViewMetrics& a, const vis4gs::ViewMetrics& b)
    {
      auto equal = [](double x, double y) { return std::isnan(x) ? std::isnan(y) : x == y; };
      return equal(a.Psnr, b.Psnr) && equal(a.Ssim, b.Ssim) && equal(a.L1, b.L1);
    };
    bool identical = fresh.Views.size() == effect.Views.size() && fresh.Removed == effect.Removed &&
      fresh.Kept == effect.Kept && fresh.Train.Views == effect.Train.Views &&
      fresh.Test.AffectedViews == effect.Test.AffectedViews &&
      same(fresh.Train.Before, effect.Train.Before) &&
      same(fresh.Train.After, effect.Train.After) && same(fresh.Test.Before, effect.Test.Before) &&
      same(fresh.Test.After, effect.Test.After);
    for (std::size_t r = 0; identical && r < effect.Views.size(); ++r)
    {
      identical = fresh.Views[r].CameraIndex == effect.Views[r].CameraIndex &&
        fresh.Views[r].Affected == effect.Views[r].Affected &&
        fresh.Views[r].HasImage == effect.Views[r].HasImage &&
        same(fresh.Views[r].Before, effect.Views[r].Before) &&
        same(fresh.Views[r].After, effect.Views[r].After);
    }
    ok =
      check(identical,
        "clean-up: the figures with the score pass's 'before' equal those of a 'before' "
        "rendered anew, bit for bit (train PSNR " +
          std::to_string(effect.Train.Before.Psnr) + " -> " +
          std::to_string(effect.Train.After.Psnr) + "); 'before' of the preview " +
          std::to_string(std::max(0.0, shown.BaselineSeconds)) + " s, rendered anew " +
          std::to_string(seconds) + " s; 'after' " + std::to_string(effect.SecondsAfter) + " s") &&
      ok;
    return ok;
  };
  // 5. The measurement in the worker thread; the table and the images. The score pass (full
  //    resolution) rendered every training view: the preview renders none of them "before".
  const std::size_t fromScores =
    d->BaselineScene == d->Scene && d->Baseline ? d->Baseline->MeasuredViews() : std::size_t(0);
  this->MeasureRemoval();
  ok = check(this->WaitForMeasurement(), "clean-up: the removal was measured") && ok;
  if (!d->Shown)
  {
    return false;
  }
  const vis4gs::RemovalEffect& e = d->Shown->Effect;
  ok =
    check(d->Views->rowCount() == static_cast<int>(cameras.size()) && e.Removed == expected.size(),
      "clean-up: the table lists every view (" + std::to_string(d->Views->rowCount()) +
        ") for the " + std::to_string(e.Removed) + " Gaussians removed") &&
    ok;
  ok = checkReuse(*d->Shown, fromScores, !sceneFile) && ok;
  bool worstFirst = true;
  for (int r = 1; r < d->Views->rowCount(); ++r)
  {
    const double a = d->Views->item(r - 1, 5)->data(Qt::UserRole).toDouble(),
                 b = d->Views->item(r, 5)->data(Qt::UserRole).toDouble();
    worstFirst = worstFirst && (std::isnan(b) || a <= b);
  }
  ok = check(worstFirst, "clean-up: the views are listed with the largest PSNR loss first") && ok;
  ok = check(this->WriteTable(directory + "/cleanup-before-after.csv"),
         "clean-up: the table is written to cleanup-before-after.csv") &&
    ok;
  d->Views->setCurrentCell(0, 0);
  const double largest = d->Images[2]->property("largestChange").toDouble();
  {
    // The images shown are the session's preview port's: Core's renders of the worst view.
    CoreInputs in;
    const std::size_t view = d->Views->item(0, 0)->data(Qt::UserRole).toULongLong();
    vtkImageData* preview = d->Shown->Session->GetRemovalPreviewOutput();
    bool same = coreInputs(*d->Shown, in) && view < in.Cameras.size() && preview;
    if (same)
    {
      const vis4gs::Image before = vis4gs::ClampedImage(
        vis4gs::Rasterize<float>(in.Cloud, in.Cameras[view], vis4gs::RasterSettings{}));
      const vis4gs::Image after = vis4gs::ClampedImage(vis4gs::Rasterize<float>(
        vis4gs::RemoveGaussians(in.Cloud, in.Removed), in.Cameras[view], vis4gs::RasterSettings{}));
      vis4gs::Image shownBefore, shownAfter;
      same = vtkGaussianRemovalEffectFilter::PreviewImage(preview, true, shownBefore) &&
        vtkGaussianRemovalEffectFilter::PreviewImage(preview, false, shownAfter) &&
        shownBefore.Pixels == before.Pixels && shownAfter.Pixels == after.Pixels &&
        !before.Pixels.empty();
    }
    ok = check(same,
           "clean-up: the preview images of the worst view are Core's renders before and "
           "after, bit for bit") &&
      ok;
  }
  ok = check(!d->Images[0]->pixmap(Qt::ReturnByValue).isNull() &&
           (largest > 0) == (d->Views->item(0, 2)->text() == "yes"),
         "clean-up: picking the worst view shows its before/after images (largest change " +
           std::to_string(largest) + ")") &&
    ok;
  QApplication::processEvents();
  ok = check(this->grab().save(directory + "/cleanup-panel.png"),
         "clean-up: screenshot cleanup-panel.png") &&
    ok;
  // 6. A second preview of the same scene (one Gaussian fewer) renders no view "before".
  if (expected.size() > 1 && !sceneFile)
  {
    const vtkIdType first = *expected.begin();
    d->Hub->SelectIds(&first, 1, vtkGaussianSelectionHub::SUBTRACT);
    this->MeasureRemoval();
    const bool measured = this->WaitForMeasurement();
    ok = check(measured && d->Shown->BeforeRendered == 0 &&
             d->Shown->BeforeReused == d->Shown->Effect.Train.Views + d->Shown->Effect.Test.Views,
           "clean-up: a second preview renders no view 'before' (" +
             std::to_string(d->Shown->BeforeRendered) + "), it reuses " +
             std::to_string(d->Shown->BeforeReused)) &&
      ok;
    ok = checkReuse(*d->Shown, d->Shown->BeforeReused, false) && ok;
  }
  // 7. Fine-tune the previewed deletion (as `vis4gs repair`): a cancelled one writes nothing;
  //    a short one writes the repaired log, whose events are the deletion's prunes only
  //    (densification off). The deletion and its cleaned scene (the main window's export) are
  //    written for CTest, which runs `vis4gs repair` on them and compares.
  {
    if (!sceneFile)
    {
      const QString cancelled = directory + "/cleanup-cancelled.h5";
      QFile::remove(cancelled);
      ok = check(this->StartFineTune(cancelled, 100000, false, false),
             "clean-up: the fine-tune starts from the current preview") &&
        ok;
      this->CancelFineTune();
      const bool finished = this->WaitForFineTune();
      ok = check(!finished && !QFileInfo::exists(cancelled) &&
               QDir(directory)
                 .entryList({ ".cleanup-cancelled*" }, QDir::Files | QDir::Hidden)
                 .isEmpty() &&
               d->RepairLabel->text().contains("cancelled"),
             "clean-up: a cancelled fine-tune writes no log, nor its temporary (" +
               d->RepairLabel->text().toStdString() + ")") &&
        ok;
    }
    const QString repaired = directory + "/cleanup-repaired.h5";
    // A log: one iteration (the trainer logs /metrics, every view rendered, after each of so
    // few). A scene file: 2 iterations of the rule's whole selection (the preview of step 5),
    // the deletion and the fine-tune that vis4gs-RepairScene's `vis4gs repair` ran on it,
    // whose figures the test compares with these.
    const int iterations = sceneFile ? 2 : 1;
    if (sceneFile)
    {
      ok = check(selected() == expected && d->Shown->Effect.Removed == expected.size(),
             "clean-up: the fine-tune starts from the preview of the rule's " +
               std::to_string(expected.size()) + " Gaussians") &&
        ok;
    }
    QFile::remove(repaired);
    const bool tuned =
      this->StartFineTune(repaired, iterations, false, false) && this->WaitForFineTune();
    ok = check(tuned,
           "clean-up: fine-tuned " + std::to_string(iterations) + " iteration(s) from iteration " +
             std::to_string(this->GetSourceIteration()) + " (" +
             d->RepairLabel->text().toStdString() + ")") &&
      ok;
    if (tuned)
    {
      // The session's fine-tune against Core's, run here as the panel ran it before (the
      // preview's figures as the source and deleted states, the repaired state measured after):
      // the same repaired Gaussians and figures, bit for bit.
      CoreInputs in;
      vis4gs::GaussianCloud tunedCloud;
      bool same = coreInputs(*d->Repaired->Preview, in) &&
        vis4gs::PolyDataToGaussianCloud(
          d->Repaired->Session->GetFineTuneFilter()->GetOutput(), tunedCloud, nullptr);
      if (same)
      {
        vis4gs::FineTuneOptions options;
        options.Iterations = iterations;
        options.Measure = false;
        const vis4gs::FineTuneResult reference = vis4gs::FineTune(
          in.Cloud, this->GetSourceIteration(), in.Removed, in.Cameras, in.Images, options);
        const std::vector<vis4gs::ViewMetrics> figures = vis4gs::MeasureViewMetrics(
          reference.Repaired, in.Cameras, vis4gs::RemovalEffectOptions{}, in.Images);
        const vis4gs::GaussianCloud& r = reference.Repaired;
        same = tunedCloud.Ids == r.Ids && tunedCloud.Positions == r.Positions &&
          tunedCloud.LogScales == r.LogScales && tunedCloud.Rotations == r.Rotations &&
          tunedCloud.OpacityLogits == r.OpacityLogits && tunedCloud.SH == r.SH &&
          d->Repaired->RepairedFigures.size() == figures.size();
        auto equal = [](double x, double y) { return std::isnan(x) ? std::isnan(y) : x == y; };
        for (std::size_t v = 0; same && v < figures.size(); ++v)
        {
          const vis4gs::ViewMetrics& m = d->Repaired->RepairedFigures[v];
          same = equal(m.Psnr, figures[v].Psnr) && equal(m.Ssim, figures[v].Ssim) &&
            equal(m.L1, figures[v].L1);
        }
      }
      ok = check(same,
             "clean-up: the session's fine-tune gives Core's repaired Gaussians and figures, "
             "bit for bit") &&
        ok;
    }
    std::vector<std::int64_t> deleted, pruned;
    for (vtkIdType id : selected())
    {
      deleted.push_back(static_cast<std::int64_t>(id));
    }
    int last = -1;
    std::size_t events = 0;
    // Read back as a script reads it (the log reader's events port).
    vtkNew<vtkGaussianTrainingLogReader> log;
    log->SetFileName(repaired.toStdString().c_str());
    const std::string errors = Vis4GSUpdate(log, 3);
    check(errors.empty(), "clean-up: the repaired log reads back " + errors);
    if (vtkTable* table = errors.empty() ? log->GetEventsOutput() : nullptr)
    {
      events = static_cast<std::size_t>(table->GetNumberOfRows());
      vtkDataArray* kind =
        vtkDataArray::SafeDownCast(table->GetColumnByName(vis4gs::arrays::EventKind));
      vtkDataArray* at =
        vtkDataArray::SafeDownCast(table->GetColumnByName(vis4gs::arrays::EventIteration));
      vtkDataArray* parent =
        vtkDataArray::SafeDownCast(table->GetColumnByName(vis4gs::arrays::EventParent));
      for (vtkIdType i = 0; kind && at && parent && i < table->GetNumberOfRows(); ++i)
      {
        if (static_cast<int>(kind->GetTuple1(i)) == static_cast<int>(vis4gs::EventKind::Prune) &&
          static_cast<int>(at->GetTuple1(i)) == this->GetSourceIteration())
        {
          pruned.push_back(static_cast<std::int64_t>(parent->GetTuple1(i)));
        }
      }
      last = log->GetNumberOfSnapshots() > 0
        ? log->GetSnapshotIteration(log->GetNumberOfSnapshots() - 1)
        : -1;
    }
    std::sort(pruned.begin(), pruned.end());
    ok = check(!deleted.empty() && pruned == deleted && events == deleted.size() &&
             last == this->GetSourceIteration() + iterations,
           "clean-up: the repaired log's " + std::to_string(events) +
             " events are the prunes "
             "of the " +
             std::to_string(deleted.size()) + " deleted Gaussians at iteration " +
             std::to_string(this->GetSourceIteration()) + "; its last snapshot is iteration " +
             std::to_string(last)) &&
      ok;
    bool filled = !d->Views->isColumnHidden(RepairedColumn) && d->Views->rowCount() > 0;
    for (int r = 0; filled && r < d->Views->rowCount(); ++r)
    {
      const double before = d->Views->item(r, 3)->data(Qt::UserRole).toDouble();
      const double after = d->Views->item(r, RepairedColumn)->data(Qt::UserRole).toDouble();
      filled = std::isnan(before) == std::isnan(after);
    }
    ok = check(filled, "clean-up: the table shows the repaired figures of every view") && ok;
    Vis4GSWriteSelectedIds(directory + "/cleanup-repair-deleted.csv", d->Hub);
    Vis4GSWriteSelectedScene(directory + "/cleanup-repair-cleaned.ply", d->Scene, d->Hub, true);
    ok = check(this->WriteRepairTable(directory + "/cleanup-repair.csv") &&
             QFileInfo::exists(directory + "/cleanup-repair-cleaned.ply"),
           "clean-up: cleanup-repair.csv, the deletion and its cleaned scene are written") &&
      ok;
    // 8. "Compare with source": the source and the repaired log's last snapshot side by side,
    //    B holding the Gaussians kept (densification off).
    Vis4GSCompareWindow* compare = tuned ? this->OpenComparison() : nullptr;
    vtkIdType shownB = -1;
    for (int waited = 0; compare && waited < 60000; waited += 50)
    {
      QApplication::processEvents(QEventLoop::AllEvents, 50);
      vtkPolyData* b = compare->GetSceneView(1)->GetScene();
      shownB = b ? b->GetNumberOfPoints() : -1;
      if (shownB > 0)
      {
        break;
      }
      QThread::msleep(50);
    }
    const vtkIdType kept = d->Scene->GetNumberOfPoints() - static_cast<vtkIdType>(deleted.size());
    ok =
      check(compare && shownB == kept && compare->grab().save(directory + "/cleanup-compare.png"),
        "clean-up: the comparison window shows the repaired state with the " +
          std::to_string(kept) + " Gaussians kept (" + std::to_string(shownB) +
          "), screenshot cleanup-compare.png") &&
      ok;
    if (compare)
    {
      compare->close(); // deletes itself
      QApplication::processEvents();
    }
  }
  return ok;
}

// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSSelfTest.h"

#include "Vis4GSCleanupPanel.h"
#include "Vis4GSDocument.h"
#include "Vis4GSMainWindow.h"
#include "Vis4GSSelectionTable.h"

#include "Vis4GSDataModel.h"
#include "vtkGaussianCameraFrustums.h"
#include "vtkGaussianCameraUtilities.h"
#include "vtkGaussianSceneView.h"
#include "vtkGaussianSelectionHub.h"
#include "vtkGaussianSelector.h"
#include "vtkGaussianSplatMapper.h"
#include "vtkGaussianTimelineView.h"
#include "vtkGaussianTrainingLogReader.h"
#include "vtkGaussianTreeItem.h"
#include "vtkGaussianTreeView.h"

#include "vtkCamera.h"
#include "vtkContextMouseEvent.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"
#include "vtkLookupTable.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkScalarBarActor.h"
#include "vtkTable.h"
#include "vtkTree.h"
#include "vtkVariant.h"

#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QImage>
#include <QLabel>
#include <QListWidget>
#include <QMenuBar>
#include <QSlider>
#include <QStackedWidget>
#include <QStatusBar>
#include <QTableView>
#include <QTimer>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numeric>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace
{
const char* DockNames[5] = { "scene", "tree", "panel", "timeline", "histogram" };

// The scene and tree screenshots of the self-test against the PNG baselines (same names):
// per-pixel differences up to Tolerance on at most Fraction of the pixels.
bool CompareBaselines(const Vis4GSSelfTestOptions& options)
{
  bool ok = true;
  for (const QString name : { "selected-in-scene-scene", "selected-in-scene-tree" })
  {
    const QString baselinePath = options.BaselineDirectory + "/" + name + ".png";
    const QString testPath = options.Directory + "/" + name + ".png";
    QImage baseline(baselinePath), test(testPath);
    if (baseline.isNull())
    {
      std::cout << "FAILED: baseline " << baselinePath.toStdString()
                << " is missing or unreadable (copy " << testPath.toStdString()
                << " there after checking it)" << std::endl;
      ok = false;
      continue;
    }
    if (test.isNull() || test.size() != baseline.size())
    {
      std::cout << "FAILED: " << testPath.toStdString() << " is missing or its size differs from "
                << baselinePath.toStdString() << std::endl;
      ok = false;
      continue;
    }
    baseline = baseline.convertToFormat(QImage::Format_RGB32);
    test = test.convertToFormat(QImage::Format_RGB32);
    QImage diff(test.size(), QImage::Format_RGB32);
    long long bad = 0;
    double sum = 0;
    for (int r = 0; r < test.height(); ++r)
    {
      const auto* a = reinterpret_cast<const QRgb*>(baseline.constScanLine(r));
      const auto* b = reinterpret_cast<const QRgb*>(test.constScanLine(r));
      auto* o = reinterpret_cast<QRgb*>(diff.scanLine(r));
      for (int c = 0; c < test.width(); ++c)
      {
        const int e = std::max({ std::abs(qRed(a[c]) - qRed(b[c])),
          std::abs(qGreen(a[c]) - qGreen(b[c])),
          std::abs(qBlue(a[c]) - qBlue(b[c])) });
        sum += e;
        bad += e > options.Tolerance ? 1 : 0;
        o[c] = qRgb(e, e, e);
      }
    }
    const double pixels = static_cast<double>(test.width()) * test.height();
    const bool same = bad <= options.Fraction * pixels;
    std::cout << (same ? "ok: " : "FAILED: ") << name.toStdString() << " matches its baseline ("
              << bad << " of " << static_cast<long long>(pixels) << " pixels differ by more than "
              << options.Tolerance << ", mean difference " << sum / pixels << ")" << std::endl;
    if (!same)
    {
      diff.save(options.Directory + "/" + name + "-diff.png");
    }
    ok = ok && same;
  }
  return ok;
}

bool RunSelfTest(Vis4GSMainWindow& w, const Vis4GSSelfTestOptions& options)
{
  bool ok = true;
  auto check = [&ok](bool condition, const std::string& what)
  {
    std::cout << (condition ? "ok: " : "FAILED: ") << what << std::endl;
    ok = ok && condition;
  };
  QDir().mkpath(options.Directory);
  const std::shared_ptr<Vis4GSDocument> doc = w.GetDocument();
  vtkGaussianSelectionHub* hub = w.GetHub();
  vtkGaussianSceneView* sceneView = w.GetSceneView();
  vtkRenderer* renderer = sceneView->GetRenderer();
  vtkGaussianSplatMapper* mapper = sceneView->GetSplatMapper();
  vtkGaussianSelector* selector = sceneView->GetSelector();
  vtkGaussianTreeView* tree = w.GetTreeView();
  vtkGaussianTimelineView* timeline = w.GetTimelineView();
  auto* selectionMode = w.findChild<QComboBox*>("selection-mode");
  auto* cameraList = w.findChild<QListWidget*>("cameras");
  auto* slider = w.findChild<QSlider*>("iteration");
  auto* overlay = w.findChild<QComboBox*>("overlay");
  auto* overlayMax = w.findChild<QDoubleSpinBox*>("overlay-max");
  auto* hideOutside = w.findChild<QCheckBox*>("hide-outside");
  if (!selectionMode || !cameraList || !slider || !overlay || !overlayMax || !hideOutside)
  {
    check(false, "panel C has its controls");
    return false;
  }
  QDockWidget* docks[5];
  for (int k = 0; k < 5; ++k)
  {
    docks[k] = w.GetDock(DockNames[k]);
  }
  // What the views show: the scoring session's Gaussians (the snapshot with the scores).
  vtkPolyData* scene = doc ? doc->Shown() : nullptr;
  check(scene && scene->GetNumberOfPoints() > 0, "the scene has Gaussians");
  if (!scene)
  {
    return false;
  }
  // The dock layout of the document (LayoutForDocument) settles over several posted layout
  // requests; the picks below need the scene view at its final size.
  for (int k = 0; k < 5; ++k)
  {
    QApplication::sendPostedEvents();
    QApplication::processEvents();
  }
  hub->RenderAll();
  {
    // The layout shows exactly the views with data, and they fill the window between the
    // menu and the status bar (no large empty area).
    // (A log with damaged events shows the tree view with the reason it is empty.)
    const bool has[5] = { true,
      doc->Tree != nullptr || !doc->TreeUnavailable.empty(),
      true,
      doc->Metrics != nullptr,
      true };
    if (!doc->TreeUnavailable.empty())
    {
      auto* stack = qobject_cast<QStackedWidget*>(docks[1]->widget());
      auto* label = stack ? qobject_cast<QLabel*>(stack->currentWidget()) : nullptr;
      check(label && label->isVisible() && label->text().toStdString() == doc->TreeUnavailable &&
          !doc->Tree,
        "the tree view says why it is empty: " + doc->TreeUnavailable);
    }
    long long covered = 0;
    for (int k = 0; k < 5; ++k)
    {
      const bool shown = docks[k]->isVisible();
      check(shown == has[k],
        std::string("the ") + DockNames[k] + " view is " + (shown ? "shown" : "hidden") +
          " (it has " + (has[k] ? "data" : "no data") + ")");
      if (shown)
      {
        covered += static_cast<long long>(docks[k]->width()) * docks[k]->height();
        check(docks[k]->width() >= 200 && docks[k]->height() >= 150,
          std::string("the ") + DockNames[k] + " view is usable (" +
            std::to_string(docks[k]->width()) + "x" + std::to_string(docks[k]->height()) +
            " pixels)");
      }
    }
    const long long area = static_cast<long long>(w.width()) *
      (w.height() - w.menuBar()->height() - w.statusBar()->height());
    check(covered >= 0.9 * area,
      "the views cover " + std::to_string(100 * covered / std::max(1LL, area)) +
        " % of the window (at least 90 %)");
    if (doc->Metrics)
    {
      check(docks[3]->height() >= 280,
        "the timeline's three charts have " + std::to_string(docks[3]->height()) +
          " pixels of height (at least 280)");
    }
    if (auto* text = w.findChild<QLabel*>("welcome"))
    {
      // The welcome panel is shown and names controls that exist (it tells what to click).
      auto* form = qobject_cast<QFormLayout*>(overlay->parentWidget()->layout());
      auto* label = form ? qobject_cast<QLabel*>(form->labelForField(overlay)) : nullptr;
      const QString welcome = text->text();
      check(text->parentWidget()->isVisible() && label && welcome.contains(label->text()) &&
          welcome.contains(hideOutside->text()) &&
          (!doc->Cameras || overlay->findText(vis4gs::arrays::ViewCoverage) >= 0) &&
          welcome.contains(vis4gs::arrays::ViewCoverage),
        "the welcome panel is shown and its steps name the panel's controls");
    }
    const std::string& summary = doc->Summary;
    check(summary.find("loaded in") != std::string::npos &&
        summary.find("( )") == std::string::npos && summary.find("()") == std::string::npos,
      "the load summary names the time of every stage (no empty parentheses)");
  }
  vtkTable* cameras = doc->Cameras;
  vtkPointData* pd = scene->GetPointData();
  vtkDataArray* ids = pd->GetArray("GaussianId");
  vtkDataArray* coverage = pd->GetArray(vis4gs::arrays::ViewCoverage);
  vtkDataArray* opacity = pd->GetArray("Opacity");
  check(pd->GetArray(vis4gs::arrays::NeedleShape) != nullptr, "the needle shape was computed");
  if (cameras)
  {
    check(coverage != nullptr, "View Coverage was computed (the log has cameras)");
  }
  if (doc->CamerasWithImages > 0)
  {
    check(pd->GetArray(vis4gs::arrays::BlurScore) && pd->GetArray(vis4gs::arrays::NeedleScore),
      "Blur and Needle scores were computed (the log has training images)");
  }

  // 1. Select a floater in the scene with the Single mode, at the pixel where its centre
  //    projects: the visible Gaussians (opacity >= 0.1) of lowest View Coverage first (the
  //    demo's root-cause criterion), seen from the training cameras in turn; without scores,
  //    the newest Gaussians (longest lineages).
  std::vector<vtkIdType> candidates(scene->GetNumberOfPoints());
  for (vtkIdType i = 0; i < scene->GetNumberOfPoints(); ++i)
  {
    candidates[i] = i;
  }
  if (coverage && opacity)
  {
    candidates.erase(std::remove_if(candidates.begin(),
                       candidates.end(),
                       [&](vtkIdType i) {
                         return !(opacity->GetComponent(i, 0) >= 0.1) ||
                           !std::isfinite(coverage->GetComponent(i, 0));
                       }),
      candidates.end());
    std::stable_sort(candidates.begin(),
      candidates.end(),
      [&](vtkIdType a, vtkIdType b)
      { return coverage->GetComponent(a, 0) < coverage->GetComponent(b, 0); });
  }
  else
  {
    std::stable_sort(candidates.begin(),
      candidates.end(),
      [&](vtkIdType a, vtkIdType b) { return ids->GetComponent(a, 0) > ids->GetComponent(b, 0); });
  }
  candidates.resize(std::min<std::size_t>(candidates.size(), 40));
  const vtkIdType views = cameras ? cameras->GetNumberOfRows() : 0;
  // Training cameras (Split 0) first, then the others.
  std::vector<vtkIdType> order;
  vtkAbstractArray* split =
    cameras ? cameras->GetColumnByName(vis4gs::arrays::CameraSplit) : nullptr;
  int trainingViews = 0;
  for (int pass = 0; pass < 2; ++pass)
  {
    for (vtkIdType v = 0; v < views; ++v)
    {
      const bool training = !split || split->GetVariantValue(v).ToInt() == 0;
      trainingViews += pass == 0 && training ? 1 : 0;
      if (training == (pass == 0))
      {
        order.push_back(v);
      }
    }
  }
  // Without cameras: five orbit views around the scene's bounds (v = -1 ... -5).
  const int orbitViews = 5;
  for (int k = 0; order.empty() && k < orbitViews; ++k)
  {
    order.push_back(-1 - k);
  }
  auto setView = [&](vtkIdType v)
  {
    if (v >= 0)
    {
      vtkGaussianCameraUtilities::JumpToCamera(renderer, cameras, v);
      return;
    }
    const int k = static_cast<int>(-1 - v);
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetFocalPoint(0, 0, 0);
    camera->SetPosition(0, 0, 1);
    camera->SetViewUp(0, 1, 0);
    renderer->ResetCamera(scene->GetBounds());
    camera->Azimuth(360.0 / orbitViews * k);
    camera->Elevation(k % 2 == 0 ? 25.0 : -25.0);
    camera->OrthogonalizeViewUp();
    renderer->ResetCameraClippingRange();
  };
  int width = sceneView->GetRenderWindow()->GetSize()[0],
      height = sceneView->GetRenderWindow()->GetSize()[1];
  selector->SetScene(scene);
  {
    // One definition per mode, on every scene: at a grid of pixels of several views, the
    // Gaussian Single picks is among those Ray returns (the footprints covering the pixel in
    // the drawn frame), and Ray lists them in depth order with alpha in [1/255, 0.99].
    // The file's first three cameras and three orbit views.
    std::vector<vtkIdType> gridViews;
    for (std::size_t n = 0; n < order.size() && order[n] >= 0 && n < 3; ++n)
    {
      gridViews.push_back(order[n]);
    }
    for (vtkIdType v = -1; v >= -3; --v)
    {
      gridViews.push_back(v);
    }
    int tested = 0, members = 0, ordered = 0, nonEmpty = 0;
    std::string firstFailure;
    for (vtkIdType view : gridViews)
    {
      setView(view);
      sceneView->Render();
      for (int gy = 1; gy <= 7; ++gy)
      {
        for (int gx = 1; gx <= 7; ++gx)
        {
          const double sx = std::floor(width * gx / 8.0), sy = std::floor(height * gy / 8.0);
          selector->SetModifier(vtkGaussianSelector::REPLACE);
          if (selector->SelectSingle(sx, sy) < 0)
          {
            continue;
          }
          vtkIdTypeArray* single = selector->GetSelectedIds();
          const vtkIdType pick = single->GetNumberOfTuples() == 1 ? single->GetValue(0) : -1;
          if (selector->SelectRay(sx, sy) < 0)
          {
            continue;
          }
          ++tested;
          vtkIdTypeArray* ray = selector->GetRayHitIds();
          vtkDoubleArray* depth = selector->GetRayHitDistances();
          vtkDoubleArray* alpha = selector->GetRayHitAlphas();
          bool found = pick < 0, sorted = true;
          for (vtkIdType k = 0; k < ray->GetNumberOfTuples(); ++k)
          {
            found = found || ray->GetValue(k) == pick;
            sorted = sorted && (k == 0 || depth->GetValue(k - 1) <= depth->GetValue(k)) &&
              alpha->GetValue(k) >= 1.0 / 255.0 - 1e-7 && alpha->GetValue(k) <= 0.99 + 1e-7;
          }
          nonEmpty += pick >= 0 ? 1 : 0;
          members += found ? 1 : 0;
          ordered += sorted ? 1 : 0;
          if ((!found || !sorted) && firstFailure.empty())
          {
            firstFailure = " (first failure: view " + std::to_string(view) + ", pixel " +
              std::to_string(static_cast<int>(sx)) + "," + std::to_string(static_cast<int>(sy)) +
              ", Single " + std::to_string(pick) + ", " + std::to_string(ray->GetNumberOfTuples()) +
              " on the ray)";
          }
        }
      }
    }
    check(tested > 0 && members == tested && ordered == tested,
      "Single's pick is on the Ray at " + std::to_string(members) + " of " +
        std::to_string(tested) + " pixels of " + std::to_string(gridViews.size()) + " views (" +
        std::to_string(nonEmpty) + " with a pick), Ray in depth order with alpha in " +
        "[1/255, 0.99] at " + std::to_string(ordered) + firstFailure);
  }
  vtkIdType target = -1, targetId = -1, view = -1;
  double display[3] = { 0, 0, 0 };
  // Whether candidate c is the front-most Gaussian at the pixel where its centre projects in
  // the current view (then it becomes the target).
  auto tryCandidate = [&](vtkIdType c, vtkIdType v)
  {
    const vtkIdType id = static_cast<vtkIdType>(ids->GetComponent(c, 0));
    double p[3];
    scene->GetPoint(c, p);
    renderer->SetWorldPoint(p[0], p[1], p[2], 1.0);
    renderer->WorldToDisplay();
    renderer->GetDisplayPoint(display);
    display[0] = std::round(display[0]);
    display[1] = std::round(display[1]);
    if (display[0] < 1 || display[1] < 1 || display[0] > width - 2 || display[1] > height - 2 ||
      display[2] <= 0 || display[2] >= 1)
    {
      return false;
    }
    selector->SetModifier(vtkGaussianSelector::REPLACE);
    vtkIdTypeArray* picked = selector->GetSelectedIds();
    if (selector->SelectSingle(display[0], display[1]) == 1 && picked->GetNumberOfTuples() == 1 &&
      picked->GetValue(0) == id)
    {
      target = c;
      targetId = id;
      view = v;
      return true;
    }
    return false;
  };
  for (std::size_t n = 0; n < candidates.size() && target < 0; ++n)
  {
    for (std::size_t m = 0; m < order.size() && target < 0; ++m)
    {
      setView(order[m]);
      tryCandidate(candidates[n], order[m]);
    }
  }
  // None of the preferred candidates is front-most anywhere (e.g. a file without scores or
  // lineage, where the newest are arbitrary): the most opaque Gaussians, view by view (one
  // projection per view).
  if (target < 0 && opacity)
  {
    std::vector<vtkIdType> opaque(static_cast<std::size_t>(scene->GetNumberOfPoints()));
    std::iota(opaque.begin(), opaque.end(), vtkIdType(0));
    std::stable_sort(opaque.begin(),
      opaque.end(),
      [&](vtkIdType a, vtkIdType b)
      { return opacity->GetComponent(a, 0) > opacity->GetComponent(b, 0); });
    opaque.resize(std::min<std::size_t>(opaque.size(), 2000));
    for (std::size_t m = 0; m < order.size() && target < 0; ++m)
    {
      setView(order[m]);
      for (std::size_t n = 0; n < opaque.size() && target < 0; ++n)
      {
        tryCandidate(opaque[n], order[m]);
      }
    }
  }
  check(target >= 0, "a floater candidate is the front-most Gaussian at its projected pixel");
  if (target < 0)
  {
    return false;
  }
  if (view >= 0)
  {
    cameraList->blockSignals(true);
    cameraList->setCurrentRow(static_cast<int>(view));
    cameraList->blockSignals(false);
  }
  const int x = static_cast<int>(display[0]), y = static_cast<int>(display[1]);
  const long long picked = sceneView->PickAt(x, y);
  std::ostringstream what;
  what << "Single mode picked Gaussian " << picked << " at pixel (" << x << ", " << y << ")";
  if (view >= 0)
  {
    what << " of training camera "
         << cameras->GetColumnByName(vis4gs::arrays::CameraName)->GetVariantValue(view).ToString();
  }
  if (coverage)
  {
    what << ", View Coverage " << coverage->GetComponent(target, 0);
  }
  check(picked == targetId, what.str());
  check(hub->GetNumberOfSelectedIds() == 1, "the hub holds one selected Gaussian");
  check(sceneView->GetHighlightCount() == 1, "the scene highlights it");
  vtkGaussianTreeItem* item = tree->GetTreeItem();
  vtkNew<vtkIdTypeArray> lineage, history;
  if (doc->Tree)
  {
    item->UpdateLevelOfDetail();
    item->GetLineageVertices(lineage);
    vtkDataArray* treeIds = doc->Tree->GetVertexData()->GetArray("GaussianId");
    vtkDataArray* born = doc->Tree->GetVertexData()->GetArray("LayoutX");
    std::ostringstream chain;
    bool containsTarget = false;
    for (vtkIdType k = 0; k < lineage->GetNumberOfTuples(); ++k)
    {
      const vtkIdType v = lineage->GetValue(k);
      const vtkIdType gid = static_cast<vtkIdType>(treeIds->GetComponent(v, 0));
      containsTarget = containsTarget || gid == targetId;
      chain << (k ? ", " : "") << gid;
      if (born)
      {
        chain << " (born " << born->GetComponent(v, 0) << ")";
      }
    }
    check(containsTarget && lineage->GetNumberOfTuples() >= 1,
      "the tree shows its lineage (" + std::to_string(lineage->GetNumberOfTuples()) +
        " nodes: " + chain.str() + ")");
    item->GetVisibleVertices(history);
    std::set<vtkIdType> visible(
      history->GetPointer(0), history->GetPointer(0) + history->GetNumberOfTuples());
    bool allShown = true;
    for (vtkIdType k = 0; k < lineage->GetNumberOfTuples(); ++k)
    {
      allShown = allShown && visible.count(lineage->GetValue(k));
    }
    check(allShown, "the whole lineage is drawn at the overview zoom");
    item->ZoomToSelection();
  }
  // A snapshot left out as unreadable (Vis4GSDocument::LoadLatestReadableSnapshot) makes the
  // history fail, which reads every snapshot: the status bar must say why (the session's error,
  // posted to the window when the timeline pulled its port).
  const bool unreadable =
    doc->Reader && static_cast<int>(doc->Snapshots.size()) < doc->Reader->GetNumberOfSnapshots();
  if (unreadable)
  {
    QApplication::processEvents();
    const std::string message = w.statusBar()->currentMessage().toStdString();
    check(timeline->GetNumberOfHistoryLines() == 0 &&
        message.find(doc->Path + ": the property history: ") == 0 &&
        message.find("0x") == std::string::npos,
      "the status bar says why the timeline has no history: " + message);
  }
  else if (doc->Reader)
  {
    check(timeline->GetNumberOfHistoryLines() == 1, "the timeline shows its history");
    // The table the timeline took from the session's history port for this selection.
    vtkTable* h = timeline->GetHistory();
    vtkDataArray* hid =
      h ? vtkArrayDownCast<vtkDataArray>(h->GetColumnByName("GaussianId")) : nullptr;
    bool onlyTarget = hid && h->GetNumberOfRows() > 0;
    for (vtkIdType r = 0; onlyTarget && r < h->GetNumberOfRows(); ++r)
    {
      onlyTarget = static_cast<vtkIdType>(hid->GetComponent(r, 0)) == targetId;
    }
    check(onlyTarget, "the timeline's history table is the picked Gaussian's");
    std::cout << "info: Gaussian " << targetId << " over the snapshots (iteration: opacity, "
              << "largest scale):";
    // Scale has 3 components: a vtkVariant of its row is an array, whose ToDouble() read it
    // as one component (VTK warned "3 != 1" for each row); its largest is what is meant.
    vtkDataArray* iteration =
      h ? vtkArrayDownCast<vtkDataArray>(h->GetColumnByName("Iteration")) : nullptr;
    vtkDataArray* opacity =
      h ? vtkArrayDownCast<vtkDataArray>(h->GetColumnByName("Opacity")) : nullptr;
    vtkDataArray* scale = h ? vtkArrayDownCast<vtkDataArray>(h->GetColumnByName("Scale")) : nullptr;
    for (vtkIdType r = 0; h && iteration && opacity && scale && r < h->GetNumberOfRows(); ++r)
    {
      double largest = scale->GetComponent(r, 0);
      for (int c = 1; c < scale->GetNumberOfComponents(); ++c)
      {
        largest = std::max(largest, scale->GetComponent(r, c));
      }
      std::cout << " " << static_cast<long long>(iteration->GetComponent(r, 0)) << ": "
                << opacity->GetComponent(r, 0) << ", " << largest << ";";
    }
    std::cout << std::endl;
  }
  if (cameras)
  {
    vtkDataArray* counts =
      sceneView->GetFrustums()->GetOutput()->GetPointData()->GetArray("VisibleSelectedCount");
    vtkDataArray* index =
      sceneView->GetFrustums()->GetOutput()->GetPointData()->GetArray("CameraIndex");
    int seeing = 0, trainingSeeing = 0;
    for (vtkIdType k = 0; counts && index && k < counts->GetNumberOfTuples(); k += 5)
    {
      const vtkIdType row = static_cast<vtkIdType>(index->GetComponent(k, 0));
      const bool seen = counts->GetComponent(k, 0) > 0;
      seeing += seen ? 1 : 0;
      trainingSeeing += seen && (!split || split->GetVariantValue(row).ToInt() == 0) ? 1 : 0;
    }
    check(seeing >= 1,
      "the frustums of " + std::to_string(seeing) + " of " + std::to_string(views) +
        " cameras are coloured as seeing the selected Gaussian");
    if (coverage)
    {
      // Independent paths: the frustum counts (CountVisibleInViews on the selection) and
      // View Coverage (the score filter) use the same footprint definition (DESIGN §4).
      const double expected = coverage->GetComponent(target, 0) * trainingViews;
      check(std::abs(trainingSeeing - expected) < 1e-6,
        "training frustums seeing it (" + std::to_string(trainingSeeing) +
          ") = View Coverage x training views (" + std::to_string(expected) + ")");
    }
  }
  hub->RenderAll();
  QApplication::processEvents();
  for (const char* name : DockNames)
  {
    w.SaveScreenshot(name, options.Directory + "/selected-in-scene-" + name + ".png");
  }
  w.SaveScreenshot("window", options.Directory + "/selected-in-scene-window.png");
  // The same views with nothing selected: the baseline comparison must fail on these, or it
  // would not notice a missing highlight (Documentation/dev/TESTING.md, masked baselines).
  hub->ClearSelection();
  hub->RenderAll();
  QApplication::processEvents();
  for (const char* name : { "scene", "tree" })
  {
    w.SaveScreenshot(name, options.Directory + "/unselected-in-scene-" + name + ".png");
  }
  hub->SelectIds(&targetId, 1);
  check(hub->GetNumberOfSelectedIds() == 1 && hub->IsSelected(targetId),
    "the selection is back after the screenshots without it");
  if (coverage)
  {
    // The same view coloured by View Coverage (viridis, legend), the floater highlighted.
    overlay->setCurrentText(vis4gs::arrays::ViewCoverage);
    check(mapper->GetSplatColoring() == vtkGaussianSplatMapper::SCORE,
      "the View Coverage overlay is shown");
    {
      // The legend names the suspicious end (low coverage), drawn bright on the black scene.
      auto* table = vtkLookupTable::SafeDownCast(sceneView->GetLegend()->GetLookupTable());
      const double* range = table ? table->GetRange() : nullptr;
      double bright[3] = { 0, 0, 0 }, dark[3] = { 0, 0, 0 };
      if (range)
      {
        table->GetColor(range[0], bright);
        table->GetColor(range[1], dark);
      }
      const vtkIdType at = range ? table->GetAnnotatedValueIndex(vtkVariant(range[0])) : -1;
      auto luminance = [](const double* c)
      { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; };
      check(sceneView->GetLegend()->GetVisibility() && at >= 0 &&
          table->GetAnnotation(at) == "suspicious" && luminance(bright) > 5 * luminance(dark),
        "the legend labels the low end of View Coverage 'suspicious' and draws it bright "
        "(luminance " +
          std::to_string(luminance(bright)) + " against " + std::to_string(luminance(dark)) + ")");
    }
    sceneView->Render();
    QApplication::processEvents();
    w.SaveScreenshot("scene", options.Directory + "/overlay-coverage-scene.png");
    hideOutside->setChecked(true);
    overlayMax->setValue(0.3);
    check(mapper->GetHideOutsideRange(), "hide-outside-range is on");
    sceneView->Render();
    QApplication::processEvents();
    w.SaveScreenshot("scene", options.Directory + "/overlay-coverage-low-scene.png");
    hideOutside->setChecked(false);
    overlay->setCurrentText("True colour");
  }

  // 2. The other scene modes at the same pixel, with the hub's modifiers.
  const double px = x, py = y;
  sceneView->SelectRay(px, py, vtkGaussianSelectionHub::REPLACE);
  vtkIdTypeArray* rayHits = sceneView->GetLastRayHitIds();
  const std::vector<vtkIdType> hits(
    rayHits->GetPointer(0), rayHits->GetPointer(0) + rayHits->GetNumberOfTuples());
  check(std::find(hits.begin(), hits.end(), targetId) != hits.end() && hub->IsSelected(targetId),
    "Ray through the pixel hits it (" + std::to_string(hits.size()) + " Gaussians on the ray)");
  sceneView->SelectFrame(px - 12, py - 12, px + 12, py + 12, vtkGaussianSelectionHub::REPLACE);
  const vtkIdType framed = hub->GetNumberOfSelectedIds();
  check(framed >= 1 && hub->IsSelected(targetId),
    "Frame around it selects it (" + std::to_string(framed) + " Gaussians)");
  {
    // Panel C's table: a row per selected Gaussian (at most 1000), each the scene's values.
    Vis4GSSelectionTable* table = nullptr;
    for (QTableView* view : w.findChildren<QTableView*>())
    {
      table = table ? table : dynamic_cast<Vis4GSSelectionTable*>(view);
    }
    vtkPolyData* shown = doc->Shown();
    vtkDataArray* ids = shown->GetPointData()->GetArray(vis4gs::arrays::GaussianId);
    vtkDataArray* opacity = shown->GetPointData()->GetArray("Opacity");
    bool rowsRight =
      table && ids && opacity && table->GetNumberOfRows() == std::min<vtkIdType>(framed, 1000);
    for (int r = 0; rowsRight && r < table->GetNumberOfRows(); ++r)
    {
      const auto id = static_cast<vtkIdType>(table->GetValue(r, 0));
      vtkIdType row = -1;
      for (vtkIdType i = 0; i < ids->GetNumberOfTuples() && row < 0; ++i)
      {
        row = static_cast<vtkIdType>(ids->GetComponent(i, 0)) == id ? i : -1;
      }
      double p[3] = { NAN, NAN, NAN };
      if (row >= 0)
      {
        shown->GetPoint(row, p);
      }
      rowsRight = row >= 0 && hub->IsSelected(id) && table->GetValue(r, 1) == p[0] &&
        table->GetValue(r, 2) == p[1] && table->GetValue(r, 3) == p[2] &&
        table->GetValue(r, 4) == opacity->GetComponent(row, 0);
    }
    check(rowsRight, "the selection table shows a row per framed Gaussian with its values");
  }
  {
    vtkNew<vtkPoints> stroke;
    for (double dx : { -3.0, 0.0, 3.0 })
    {
      stroke->InsertNextPoint(px + dx, py, 0.0);
    }
    sceneView->SelectBrush(stroke, vtkGaussianSelectionHub::SUBTRACT);
  }
  check(!hub->IsSelected(targetId) && hub->GetNumberOfSelectedIds() < framed,
    "Brush over it with Ctrl (subtract) removes it");
  sceneView->SelectSingle(px, py, vtkGaussianSelectionHub::ADD);
  check(hub->IsSelected(targetId), "Single with Shift (add) adds it back");

  // The same through the scene's interactor, as the mouse does it: a Frame drag selects and
  // does not rotate the camera; a Ctrl+click in Single mode subtracts; a Brush drag with Shift
  // adds.
  {
    vtkRenderWindowInteractor* iren = sceneView->GetInteractor();
    auto send = [iren](unsigned long event, double ex, double ey, bool shift, bool control)
    {
      iren->SetEventInformation(static_cast<int>(ex), static_cast<int>(ey), control, shift);
      iren->InvokeEvent(event);
    };
    double before[3], after[3];
    renderer->GetActiveCamera()->GetPosition(before);
    hub->ClearSelection();
    selectionMode->setCurrentIndex(vtkGaussianSceneView::FRAME);
    send(vtkCommand::LeftButtonPressEvent, px - 12, py - 12, false, false);
    send(vtkCommand::MouseMoveEvent, px, py, false, false);
    send(vtkCommand::MouseMoveEvent, px + 12, py + 12, false, false);
    send(vtkCommand::LeftButtonReleaseEvent, px + 12, py + 12, false, false);
    renderer->GetActiveCamera()->GetPosition(after);
    check(hub->GetNumberOfSelectedIds() == framed && hub->IsSelected(targetId) &&
        std::equal(before, before + 3, after),
      "a Frame drag with the mouse selects the same " + std::to_string(framed) +
        " Gaussians and leaves the camera alone");
    selectionMode->setCurrentIndex(vtkGaussianSceneView::SINGLE);
    send(vtkCommand::LeftButtonPressEvent, px, py, false, true);
    send(vtkCommand::LeftButtonReleaseEvent, px, py, false, true);
    check(!hub->IsSelected(targetId) && hub->GetNumberOfSelectedIds() == framed - 1,
      "a Ctrl+click in Single mode subtracts it");
    selectionMode->setCurrentIndex(vtkGaussianSceneView::BRUSH);
    send(vtkCommand::LeftButtonPressEvent, px - 3, py, true, false);
    send(vtkCommand::MouseMoveEvent, px, py, true, false);
    send(vtkCommand::LeftButtonReleaseEvent, px + 3, py, true, false);
    check(hub->IsSelected(targetId), "a Brush drag with Shift adds it back");
    selectionMode->setCurrentIndex(vtkGaussianSceneView::SINGLE);
  }

  // 3. Select a node in the tree (click on a visible node alive in the scene).
  if (doc->Tree)
  {
    item->ResetViewport();
    item->SetZoom(2.0);
    item->UpdateLevelOfDetail();
    vtkNew<vtkIdTypeArray> visible;
    item->GetVisibleVertices(visible);
    vtkDataArray* treeIds = doc->Tree->GetVertexData()->GetArray("GaussianId");
    vtkIdType chosen = -1;
    for (vtkIdType k = 0; k < visible->GetNumberOfTuples() && chosen < 0; ++k)
    {
      const vtkIdType v = visible->GetValue(k);
      const vtkIdType id = static_cast<vtkIdType>(treeIds->GetComponent(v, 0));
      vtkNew<vtkIdTypeArray> rows;
      vtkGaussianSelectionHub::IdsToIndices(&id, 1, ids, rows);
      if (rows->GetNumberOfTuples() == 1 && id != static_cast<vtkIdType>(picked))
      {
        chosen = v;
      }
    }
    check(chosen >= 0, "a tree node alive in the scene is visible");
    if (chosen >= 0)
    {
      float pos[2];
      item->GetVertexPosition(chosen, pos);
      vtkContextMouseEvent event;
      event.SetInteractor(tree->GetRenderWindow()->GetInteractor());
      event.SetButton(vtkContextMouseEvent::LEFT_BUTTON);
      event.SetScenePos(vtkVector2f(pos[0], pos[1]));
      event.SetPos(vtkVector2f(pos[0], pos[1]));
      event.SetLastScenePos(vtkVector2f(pos[0], pos[1]));
      item->MouseButtonPressEvent(event);
      item->MouseButtonReleaseEvent(event);
      const vtkIdType expected = static_cast<vtkIdType>(treeIds->GetComponent(chosen, 0));
      check(hub->GetNumberOfSelectedIds() == 1 && hub->IsSelected(expected),
        "the tree click selected Gaussian " + std::to_string(expected));
      check(sceneView->GetHighlightCount() == 1, "the scene highlights the tree's selection");
      vtkIdTypeArray* mapperIds = mapper->GetSelectedIds();
      check(mapperIds && mapperIds->GetNumberOfTuples() == 1 && mapperIds->GetValue(0) == expected,
        "the splat mapper highlights Gaussian " + std::to_string(expected));
    }
  }
  hub->RenderAll();
  QApplication::processEvents();
  for (const char* name : DockNames)
  {
    w.SaveScreenshot(name, options.Directory + "/selected-in-tree-" + name + ".png");
  }
  w.SaveScreenshot("window", options.Directory + "/window.png");
  if (!options.BaselineDirectory.isEmpty())
  {
    ok = CompareBaselines(options) && ok;
  }
  // The clean-up panel on a log with training images (Vis4GSCleanupPanel::RunSelfTest).
  if (doc->CamerasWithImages > 0 && w.GetScoreCameras())
  {
    const QSize size = w.size();
    w.resize(1280, 800); // the user guide's screenshot
    w.ShowCleanup();
    QApplication::processEvents();
    ok = w.GetCleanupPanel()->RunSelfTest(options.Directory,
           [&check](bool condition, const std::string& what)
           {
             check(condition, what);
             return condition;
           }) &&
      ok;
    hub->RenderAll();
    QApplication::processEvents();
    w.SaveScreenshot("window", options.Directory + "/cleanup-window.png");
    w.GetDock("cleanup")->hide();
    w.resize(size);
  }
  // 4. The iteration slider loads another snapshot into the scene (and back). The pointers
  //    into the old scene above are not used after this.
  if (doc->Reader && doc->Snapshots.size() > 1)
  {
    const int last = doc->Iteration;
    const int previous = doc->Snapshots[doc->Snapshots.size() - 2];
    slider->setValue(slider->maximum() - 1);
    // The view's copy of the session's Gaussians port (pulled when it changed).
    vtkPolyData* shown = sceneView->GetScene();
    check(hub->GetIteration() == previous && doc->Iteration == previous && shown &&
        mapper->GetInput() == shown &&
        shown->GetNumberOfPoints() == doc->Reader->GetSnapshotSize(previous),
      "the iteration slider loads the snapshot of iteration " + std::to_string(previous) +
        " into the scene (" + std::to_string(shown ? shown->GetNumberOfPoints() : 0) +
        " Gaussians)");
    slider->setValue(slider->maximum());
    shown = sceneView->GetScene();
    check(doc->Iteration == last && shown && mapper->GetInput() == shown &&
        shown->GetNumberOfPoints() == doc->Scene->GetNumberOfPoints(),
      "and back to iteration " + std::to_string(last));
  }
  std::cout << (ok ? "self-test passed" : "self-test FAILED") << std::endl;
  return ok;
}
}

//------------------------------------------------------------------------------
void Vis4GSInstallSelfTest(Vis4GSMainWindow* window, const Vis4GSSelfTestOptions& options)
{
  // Once, after the first scores (the checks need them); a load error fails at once.
  auto started = std::make_shared<bool>(false);
  QObject::connect(window,
    &Vis4GSMainWindow::scoresComputed,
    window,
    [window, options, started]
    {
      if (*started)
      {
        return;
      }
      *started = true;
      QTimer::singleShot(200,
        window,
        [window, options] { QApplication::exit(RunSelfTest(*window, options) ? 0 : 1); });
    });
  QObject::connect(
    window, &Vis4GSMainWindow::loadFailed, window, [](const QString&) { QApplication::exit(1); });
}

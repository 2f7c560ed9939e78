// SPDX-License-Identifier: BSD-3-Clause
// vtkGaussianSceneView without Qt on the embedded demo log (Data/Demo/vis4gs-demo.h5, read
// through vtkGaussianTrainingLogReader): every selection mode publishes to the hub and comes
// back as the mapper's highlight, the markers and the frustum colours; a Frame drag through
// the interactor selects what SelectFrame selects and leaves the camera alone; the overlay's
// legend shows the asked range (or the array's own range); a regression image of the view
// with one Gaussian selected (masked baseline comparison, see the CMakeLists).
#include "LinkedViewsTestData.h"
#include "Vis4GSTestData.h"

#include "Vis4GSDataModel.h"
#include "vtkGaussianCameraFrustums.h"
#include "vtkGaussianSceneView.h"
#include "vtkGaussianSelectionHub.h"
#include "vtkGaussianSelector.h"
#include "vtkGaussianSplatMapper.h"
#include "vtkGaussianTrainingLogReader.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkIdTypeArray.h"
#include "vtkLookupTable.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkScalarBarActor.h"
#include "vtkTable.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
int failures = 0;
void Check(bool ok, const std::string& what)
{
  std::cout << (ok ? "ok: " : "ERROR: check failed: ") << what << "\n";
  failures += ok ? 0 : 1;
}

std::vector<vtkIdType> Values(vtkIdTypeArray* a)
{
  return a ? std::vector<vtkIdType>(a->GetPointer(0), a->GetPointer(0) + a->GetNumberOfTuples())
           : std::vector<vtkIdType>();
}

std::vector<vtkIdType> Selected(vtkGaussianSelectionHub* hub)
{
  vtkNew<vtkIdTypeArray> ids;
  hub->GetSelectedIds(ids);
  return Values(ids);
}

// Display position of point @p i of @p scene in @p renderer (x, y; z in [0, 1] when in front).
void Project(vtkRenderer* renderer, vtkPolyData* scene, vtkIdType i, double display[3])
{
  double p[3];
  scene->GetPoint(i, p);
  renderer->SetWorldPoint(p[0], p[1], p[2], 1.0);
  renderer->WorldToDisplay();
  renderer->GetDisplayPoint(display);
}

void Send(vtkRenderWindowInteractor* iren, unsigned long event, double x, double y, bool shift)
{
  iren->SetEventInformation(static_cast<int>(x), static_cast<int>(y), 0, shift ? 1 : 0);
  iren->InvokeEvent(event);
}
}

int TestGaussianSceneView(int argc, char* argv[])
{
  vtkNew<vtkGaussianTrainingLogReader> reader;
  reader->SetFileName(vis4gs::testing::SourcePath("Data/Demo/vis4gs-demo.h5").c_str());
  reader->Update(0);
  reader->Update(1);
  vtkPolyData* scene = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  vtkTable* cameras = vtkTable::SafeDownCast(reader->GetOutputDataObject(1));
  if (!scene || scene->GetNumberOfPoints() == 0 || !cameras || cameras->GetNumberOfRows() == 0)
  {
    std::cerr << "ERROR: the demo log gave no scene or no cameras\n";
    return 1;
  }
  vtkDataArray* ids = scene->GetPointData()->GetArray(vis4gs::arrays::GaussianId);

  vtkNew<vtkGaussianSelectionHub> hub;
  hub->RenderOnChangeOff();
  vtkNew<vtkGaussianSceneView> view;
  vtkRenderWindow* window = view->GetRenderWindow();
  window->SetSize(320, 240);
  window->SetMultiSamples(0);
  view->SetSelectionHub(hub);
  view->SetScene(scene);
  view->SetCameras(cameras);
  view->SetMaximumNumberOfSplats(0);
  Check(
    view->GetInteractiveSplatBudget() == 400000, "the CPU path's moving budget defaults to 400000");
  view->SetInteractiveSplatBudget(1234);
  Check(view->GetInteractiveSplatBudget() == 1234, "SetInteractiveSplatBudget reaches the mapper");
  Check(view->JumpToCamera(0), "JumpToCamera(0) on the log's first camera");
  Check(!view->JumpToCamera(cameras->GetNumberOfRows()), "JumpToCamera past the last camera fails");
  view->Render();
  vtkRenderer* renderer = view->GetRenderer();
  {
    std::ostringstream print;
    view->PrintSelf(print, vtkIndent());
    Check(print.str().find("SharedGaussians: " + std::to_string(scene->GetNumberOfPoints())) !=
        std::string::npos,
      "the view holds one shared copy of the scene's Gaussians (PrintSelf)");
  }

  // 1. Single: the opaque Gaussian nearest the image centre whose centre projects to a pixel
  //    where it is front-most (Single picks it there; Ray lists it).
  vtkIdType target = -1;
  double at[3] = { 0, 0, 0 };
  {
    std::vector<std::pair<double, vtkIdType>> order;
    vtkDataArray* logit = scene->GetPointData()->GetArray(vis4gs::arrays::OpacityLogit);
    for (vtkIdType i = 0; i < scene->GetNumberOfPoints(); ++i)
    {
      double d[3];
      Project(renderer, scene, i, d);
      if (logit->GetComponent(i, 0) > 2.0 && d[2] > 0 && d[2] < 1)
      {
        order.emplace_back(std::hypot(d[0] - 160, d[1] - 120), i);
      }
    }
    std::sort(order.begin(), order.end());
    for (std::size_t k = 0; k < order.size() && k < 200 && target < 0; ++k)
    {
      Project(renderer, scene, order[k].second, at);
      at[0] = std::round(at[0]);
      at[1] = std::round(at[1]);
      const vtkIdType id = static_cast<vtkIdType>(ids->GetComponent(order[k].second, 0));
      if (view->PickAt(at[0], at[1]) == id)
      {
        target = order[k].second;
      }
    }
  }
  Check(target >= 0, "a Gaussian is picked at the pixel of its centre");
  if (target < 0)
  {
    return 1;
  }
  const vtkIdType targetId = static_cast<vtkIdType>(ids->GetComponent(target, 0));
  Check(Selected(hub) == std::vector<vtkIdType>({ targetId }), "Single publishes it to the hub");
  Check(view->GetLastSelectionMode() == vtkGaussianSceneView::SINGLE &&
      view->GetLastSelectionCount() == 1,
    "the last selection: Single, one Gaussian");
  Check(view->GetHighlightCount() == 1, "the view highlights one Gaussian");
  Check(Values(view->GetSplatMapper()->GetSelectedIds()) == std::vector<vtkIdType>({ targetId }),
    "the mapper highlights it");
  {
    vtkPolyData* markers = view->GetMarkers();
    double m[3] = { 0, 0, 0 }, p[3];
    scene->GetPoint(target, p);
    if (markers->GetNumberOfPoints() == 1)
    {
      markers->GetPoint(0, m);
    }
    Check(markers->GetNumberOfPoints() == 1 && markers->GetNumberOfVerts() == 1 && m[0] == p[0] &&
        m[1] == p[1] && m[2] == p[2],
      "one marker at its centre");
  }
  {
    // The frustum of camera 0, from which it was picked, sees it (its footprint covers a pixel
    // of that view).
    vtkPolyData* frustums = view->GetFrustums()->GetOutput();
    vtkDataArray* counts = frustums->GetPointData()->GetArray("VisibleSelectedCount");
    vtkDataArray* index = frustums->GetPointData()->GetArray("CameraIndex");
    double seen = -1;
    for (vtkIdType k = 0; counts && index && k < counts->GetNumberOfTuples(); ++k)
    {
      if (index->GetComponent(k, 0) == 0)
      {
        seen = counts->GetComponent(k, 0);
      }
    }
    Check(view->GetFrustumActor()->GetVisibility() && seen == 1,
      "camera 0's frustum counts the selected Gaussian (" + std::to_string(seen) + ")");
    view->ShowFrustumsOff();
    Check(!view->GetFrustumActor()->GetVisibility(), "ShowFrustumsOff hides the frustums");
    view->ShowFrustumsOn();
  }

  // 2. Ray at the same pixel: it is on the ray, depths ascending; the hub holds the ray.
  const vtkIdType onRay = view->SelectRay(at[0], at[1]);
  const std::vector<vtkIdType> ray = Values(view->GetLastRayHitIds());
  Check(onRay >= 1 && std::find(ray.begin(), ray.end(), targetId) != ray.end(),
    "Ray through the pixel lists it (" + std::to_string(onRay) + " on the ray)");
  std::vector<vtkIdType> sortedRay = ray;
  std::sort(sortedRay.begin(), sortedRay.end());
  sortedRay.erase(std::unique(sortedRay.begin(), sortedRay.end()), sortedRay.end());
  Check(Selected(hub) == sortedRay && view->GetHighlightCount() == onRay,
    "the hub holds the ray's Gaussians and the view highlights as many");

  // 3. Frame around it: it is selected; every selected centre projects into the rectangle.
  const double half = 20;
  const vtkIdType framed =
    view->SelectFrame(at[0] - half, at[1] - half, at[0] + half, at[1] + half);
  bool inside = true;
  {
    vtkNew<vtkIdTypeArray> rows;
    vtkNew<vtkIdTypeArray> selected;
    hub->GetSelectedIds(selected);
    vtkGaussianSelectionHub::IdsToIndices(selected, ids, rows);
    for (vtkIdType k = 0; k < rows->GetNumberOfTuples(); ++k)
    {
      double d[3];
      Project(renderer, scene, rows->GetValue(k), d);
      inside = inside && d[0] >= at[0] - half - 1 && d[0] <= at[0] + half + 1 &&
        d[1] >= at[1] - half - 1 && d[1] <= at[1] + half + 1;
    }
  }
  Check(
    framed >= 1 && hub->GetNumberOfSelectedIds() == framed && hub->IsSelected(targetId) && inside,
    "Frame selects it and " + std::to_string(framed) + " Gaussians, all centred inside");
  Check(view->GetHighlightCount() == framed &&
      view->GetMarkers()->GetNumberOfPoints() == (framed <= 200 ? framed : 0),
    "the view highlights the framed Gaussians (markers up to 200)");

  // 4. Brush with SUBTRACT removes it, Single with ADD adds it back.
  vtkNew<vtkPoints> stroke;
  for (double dx : { -3.0, 0.0, 3.0 })
  {
    stroke->InsertNextPoint(at[0] + dx, at[1], 0.0);
  }
  view->SelectBrush(stroke, vtkGaussianSelectionHub::SUBTRACT);
  Check(!hub->IsSelected(targetId) && hub->GetNumberOfSelectedIds() < framed,
    "Brush with SUBTRACT removes it");
  view->SelectSingle(at[0], at[1], vtkGaussianSelectionHub::ADD);
  Check(hub->IsSelected(targetId), "Single with ADD adds it back");

  // 5. The mouse through the interactor: a Frame drag selects the same Gaussians, draws the
  //    band while dragging and does not rotate the camera; a Brush drag with Shift adds.
  {
    vtkRenderWindowInteractor* iren = view->GetInteractor();
    Check(iren != nullptr, "the view has an interactor");
    double before[3], after[3];
    renderer->GetActiveCamera()->GetPosition(before);
    hub->ClearSelection();
    view->SetSelectionMode(vtkGaussianSceneView::FRAME);
    Send(iren, vtkCommand::LeftButtonPressEvent, at[0] - half, at[1] - half, false);
    Send(iren, vtkCommand::MouseMoveEvent, at[0], at[1], false);
    Send(iren, vtkCommand::MouseMoveEvent, at[0] + half, at[1] + half, false);
    Check(view->GetBand()->GetNumberOfPoints() == 5, "the frame's band is drawn while dragging");
    Send(iren, vtkCommand::LeftButtonReleaseEvent, at[0] + half, at[1] + half, false);
    renderer->GetActiveCamera()->GetPosition(after);
    Check(hub->GetNumberOfSelectedIds() == framed && hub->IsSelected(targetId) &&
        std::equal(before, before + 3, after) && view->GetBand()->GetNumberOfPoints() == 0,
      "a Frame drag selects the same " + std::to_string(framed) +
        " Gaussians, clears its band and leaves the camera alone");
    view->SelectSingle(at[0], at[1], vtkGaussianSelectionHub::SUBTRACT);
    view->SetSelectionMode(vtkGaussianSceneView::BRUSH);
    Send(iren, vtkCommand::LeftButtonPressEvent, at[0] - 3, at[1], true);
    Send(iren, vtkCommand::MouseMoveEvent, at[0], at[1], true);
    Send(iren, vtkCommand::LeftButtonReleaseEvent, at[0] + 3, at[1], true);
    Check(hub->IsSelected(targetId), "a Brush drag with Shift adds it back");
    view->SetSelectionMode(vtkGaussianSceneView::SINGLE);
  }

  // 6. A selection made elsewhere (the hub) comes back to the view.
  hub->SelectIds(&targetId, 1);
  Check(view->GetHighlightCount() == 1 && view->GetMarkers()->GetNumberOfPoints() == 1,
    "a selection from the hub is highlighted");

  // 7. Overlay and legend: the asked range, then the array's own range (hi <= lo).
  vtkDataArray* overlay = scene->GetPointData()->GetArray(vis4gs::arrays::OpacityLogit);
  double own[2];
  overlay->GetRange(own);
  view->SetOverlayArrayName(vis4gs::arrays::OpacityLogit);
  view->SetOverlayRange(-1.0, 3.0);
  view->Render();
  vtkScalarBarActor* legend = view->GetLegend();
  auto* table = vtkLookupTable::SafeDownCast(legend->GetLookupTable());
  const double* range = table ? table->GetRange() : nullptr;
  Check(legend->GetVisibility() && range && range[0] == -1.0 && range[1] == 3.0 &&
      std::string(legend->GetTitle()) == vis4gs::arrays::OpacityLogit &&
      view->GetSplatMapper()->GetSplatColoring() == vtkGaussianSplatMapper::SCORE,
    "the overlay's legend spans the asked range [-1, 3]");
  view->SetOverlayRange(0.0, 0.0);
  view->Render();
  range = table ? table->GetRange() : nullptr;
  Check(range && std::abs(range[0] - own[0]) < 1e-6 && std::abs(range[1] - own[1]) < 1e-6,
    "with hi <= lo the legend spans the array's range [" + std::to_string(own[0]) + ", " +
      std::to_string(own[1]) + "]");
  view->SetOverlayRange(-1.0, 3.0);
  view->HideOutsideRangeOn();
  Check(view->GetSplatMapper()->GetHideOutsideRange(), "HideOutsideRange reaches the mapper");
  view->HideOutsideRangeOff();
  view->SetOverlayArrayName("NoSuchArray");
  Check(!legend->GetVisibility() &&
      view->GetSplatMapper()->GetSplatColoring() == vtkGaussianSplatMapper::TRUE_COLOR,
    "an array the scene lacks draws true colour without a legend");
  view->SetOverlayArrayName(nullptr);

  // 8. The picture: the floater selected (marker and frustum highlight), true colour.
  hub->SelectIds(&targetId, 1);
  view->Render();
  int retVal = vtkRegressionTestImage(window);
  if (retVal == vtkRegressionTester::DO_INTERACTOR)
  {
    retVal = vtkRegressionTester::PASSED;
  }
  Check(linkedtest::WriteSelectionImages(window, hub, "TestGaussianSceneView"),
    "the pictures with and without the selection are written");
  view->SetSelectionHub(nullptr);
  Check(hub->GetNumberOfViews() == 0, "SetSelectionHub(nullptr) unlinks the view");
  return (failures == 0 && retVal == vtkRegressionTester::PASSED) ? 0 : 1;
}

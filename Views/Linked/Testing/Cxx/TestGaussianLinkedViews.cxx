// SPDX-License-Identifier: BSD-3-Clause
// Scripted interactions across the linked views (tree B, timeline D, histogram) and the hub:
// a selection made as the scene view would (pedigree ids on the hub) reaches every view; a
// click in the tree, a click in the timeline and a brush in the histogram reach the hub and
// hence every other view. Ends with a regression image of the three views in one window, and
// writes that picture and the same one with nothing selected to the working directory for the
// masked comparison (vis4gs_image_compare.py: the second must fail it).
#include "LinkedViewsTestData.h"

#include "vtkGaussianHistogramView.h"
#include "vtkGaussianSelectionHub.h"
#include "vtkGaussianTimelineChart.h"
#include "vtkGaussianTimelineView.h"
#include "vtkGaussianTreeItem.h"
#include "vtkGaussianTreeView.h"

#include "vtkAxis.h"
#include "vtkCallbackCommand.h"
#include "vtkContextMouseEvent.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkTable.h"
#include "vtkTree.h"

#include "Vis4GSTestCheck.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace
{
vis4gs::testing::CheckCounter Check;

// The histogram's orange bars of a large selection against a scan of every row: ids in a column
// with gaps (searched) and a contiguous one (offsets), a float array read by component, by its
// largest component, and a double one (read through the generic path); repeated ids and ids the
// scene lacks in the selection.
void CheckSelectedCountsAgainstAScan()
{
  std::mt19937 random(7);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (const int gap : { 1, 3 })
  {
    const vtkIdType n = 5000;
    vtkNew<vtkPolyData> scene;
    vtkNew<vtkPoints> points;
    points->SetNumberOfPoints(n);
    vtkNew<vtkIdTypeArray> ids;
    ids->SetName("GaussianId");
    vtkNew<vtkFloatArray> opacity, scale;
    vtkNew<vtkDoubleArray> blur;
    opacity->SetName("Opacity");
    scale->SetName("Scale");
    scale->SetNumberOfComponents(3);
    blur->SetName("BlurScore");
    for (vtkIdType i = 0; i < n; ++i)
    {
      points->SetPoint(i, 0, 0, 0);
      ids->InsertNextValue(10 + gap * i);
      opacity->InsertNextValue(uniform(random));
      scale->InsertNextTuple3(uniform(random), 2 * uniform(random), uniform(random));
      blur->InsertNextValue(i % 97 == 0 ? NAN : uniform(random));
    }
    scene->SetPoints(points);
    scene->GetPointData()->AddArray(ids);
    scene->GetPointData()->AddArray(opacity);
    scene->GetPointData()->AddArray(scale);
    scene->GetPointData()->AddArray(blur);
    std::vector<vtkIdType> chosen;
    for (vtkIdType i = 0; i < n; ++i)
    {
      if (uniform(random) < 0.3f)
      {
        chosen.push_back(10 + gap * i);
        if (i % 50 == 0)
        {
          chosen.push_back(10 + gap * i); // repeated
        }
      }
    }
    chosen.push_back(2); // not in the scene
    const std::set<vtkIdType> wanted(chosen.begin(), chosen.end());
    vtkNew<vtkGaussianSelectionHub> hub;
    vtkNew<vtkGaussianHistogramView> histogram;
    histogram->SetNumberOfBins(16);
    histogram->SetInputData(scene);
    histogram->SetSelectionHub(hub);
    hub->RenderOnChangeOff();
    for (const auto& c : std::vector<std::pair<const char*, int>>{
           { "Opacity", -1 }, { "Scale", 1 }, { "Scale", -1 }, { "BlurScore", -1 } })
    {
      histogram->SetArrayName(c.first);
      histogram->SetComponent(c.second);
      histogram->Update();
      hub->ClearSelection();
      hub->SelectIds(chosen.data(), static_cast<vtkIdType>(chosen.size()));
      double edges[17];
      histogram->GetBinEdges(edges);
      vtkDataArray* values = scene->GetPointData()->GetArray(c.first);
      std::vector<vtkIdType> expected(16, 0);
      for (vtkIdType i = 0; i < n; ++i)
      {
        if (!wanted.count(ids->GetValue(i)))
        {
          continue;
        }
        double v = values->GetComponent(i, c.second < 0 ? 0 : c.second);
        for (int k = 1; c.second < 0 && k < values->GetNumberOfComponents(); ++k)
        {
          v = std::max(v, values->GetComponent(i, k));
        }
        if (std::isfinite(v))
        {
          const double t = (v - edges[0]) / (edges[16] - edges[0]) * 16;
          ++expected[std::min(15, std::max(0, static_cast<int>(t)))];
        }
      }
      bool same = true;
      for (int b = 0; b < 16; ++b)
      {
        same = same && histogram->GetSelectedBinCount(b) == expected[b];
      }
      const std::string what = std::string("histogram: orange bars of ") + c.first +
        " (component " + std::to_string(c.second) + ", id gap " + std::to_string(gap) +
        ") equal a scan";
      Check(same, what.c_str());
    }
  }
}

std::vector<vtkIdType> Values(vtkIdTypeArray* a)
{
  return std::vector<vtkIdType>(a->GetPointer(0), a->GetPointer(0) + a->GetNumberOfTuples());
}

std::vector<vtkIdType> Selected(vtkGaussianSelectionHub* hub)
{
  vtkNew<vtkIdTypeArray> ids;
  hub->GetSelectedIds(ids);
  return Values(ids);
}

vtkIdType SelectedTotal(vtkGaussianHistogramView* h, int bins)
{
  vtkIdType total = 0;
  for (int b = 0; b < bins; ++b)
  {
    total += h->GetSelectedBinCount(b);
  }
  return total;
}

vtkRenderWindowInteractor* Interactor = nullptr;

void Click(vtkAbstractContextItem* item, float x, float y)
{
  vtkContextMouseEvent event;
  event.SetInteractor(Interactor);
  event.SetButton(vtkContextMouseEvent::LEFT_BUTTON);
  event.SetPos(vtkVector2f(x, y));
  event.SetScenePos(vtkVector2f(x, y));
  event.SetLastPos(vtkVector2f(x, y));
  event.SetLastScenePos(vtkVector2f(x, y));
  item->MouseButtonPressEvent(event);
  item->MouseButtonReleaseEvent(event);
}
}

int TestGaussianLinkedViews(int argc, char* argv[])
{
  vtkSmartPointer<vtkTree> tree = linkedtest::MakeTree();
  if (!tree)
  {
    std::cerr << "ERROR: the hand-built genealogy is not a tree\n";
    return 1;
  }
  vtkSmartPointer<vtkPolyData> scene = linkedtest::MakeScene();

  vtkNew<vtkGaussianSelectionHub> hub;
  vtkNew<vtkGaussianTreeView> treeView;
  treeView->SetTree(tree);
  treeView->SetFamilyBands(linkedtest::MakeBands());
  treeView->GetTreeItem()->SetZoomedInRows(1.0); // 8 rows: fit-all is z = 0.1, tau = 1
  treeView->SetSelectionHub(hub);
  vtkNew<vtkGaussianTimelineView> timeline;
  timeline->SetMetrics(linkedtest::MakeMetrics());
  timeline->SetHistory(linkedtest::MakeHistory());
  timeline->SetSelectionHub(hub);
  vtkNew<vtkGaussianHistogramView> histogram;
  histogram->SetNumberOfBins(8);
  histogram->SetArrayName("Opacity");
  histogram->SetInputData(scene);
  histogram->SetSelectionHub(hub);
  Check(hub->GetNumberOfViews() == 3, "three views registered with the hub");

  // One window, three viewports.
  vtkNew<vtkRenderWindow> window;
  window->SetSize(900, 520);
  window->SetMultiSamples(0);
  treeView->SetRenderWindow(window);
  timeline->SetRenderWindow(window);
  histogram->SetRenderWindow(window);
  treeView->GetRenderer()->SetViewport(0.0, 0.0, 0.5, 1.0);
  timeline->GetRenderer()->SetViewport(0.5, 0.35, 1.0, 1.0);
  histogram->GetRenderer()->SetViewport(0.5, 0.0, 1.0, 0.35);
  int renders = 0;
  vtkNew<vtkCallbackCommand> counter;
  counter->SetClientData(&renders);
  counter->SetCallback([](vtkObject*, unsigned long, void* c, void*) { ++*static_cast<int*>(c); });
  window->AddObserver(vtkCommand::EndEvent, counter);
  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(window);
  Interactor = interactor;
  window->Render();

  vtkGaussianTreeItem* item = treeView->GetTreeItem();
  vtkNew<vtkIdTypeArray> vertices;

  // 1. The scene view selects the floater, Gaussian 5 (pedigree ids on the hub).
  renders = 0;
  const vtkIdType floater = 5;
  hub->SelectIds(&floater, 1);
  Check(renders >= 3, "every view re-rendered after the selection");
  item->UpdateLevelOfDetail();
  item->GetSelectedVertices(vertices);
  Check(Values(vertices) == std::vector<vtkIdType>({ linkedtest::VertexOf(5) }),
    "tree: selected vertex of Gaussian 5");
  item->GetLineageVertices(vertices);
  Check(Values(vertices) == std::vector<vtkIdType>({ 1, 2, 4 }), // Gaussians 0, 3, 5
    "tree: lineage of Gaussian 5 is 0 -> 3 -> 5");
  item->GetVisibleVertices(vertices);
  // tau = 1 at fit-all: the two P = 1 roots (Gaussians 0 and 2) plus the lineage.
  // Gaussians 0, 3, 5, 2 are vertices 1, 2, 4, 7.
  Check(Values(vertices) == std::vector<vtkIdType>({ 1, 2, 4, 7 }),
    "tree: visible = P >= 1 nodes + the selected lineage");
  Check(timeline->GetNumberOfHistoryLines() == 1, "timeline: history of the one selected");
  Check(SelectedTotal(histogram, 8) == 1, "histogram: one selected Gaussian");
  // Opacity 0.55 over [0.05, 0.75] in 8 bins: bin 5.
  Check(histogram->GetSelectedBinCount(5) == 1, "histogram: in the bin of opacity 0.55");

  // 2. A click on Gaussian 6 in the tree selects it everywhere.
  item->SetZoomedInRows(100.0); // fewer rows than that: always z = 2, tau = 0
  item->ResetViewport();
  Check(item->GetZoom() == 2.0, "tree: z = zmax");
  item->UpdateLevelOfDetail();
  Check(item->GetNumberOfVisibleVertices() == 8, "tree: all 8 nodes at z = 2 (tau = 0)");
  float pos[2];
  item->GetVertexPosition(linkedtest::VertexOf(6), pos);
  Check(item->PickVertex(pos[0], pos[1]) == linkedtest::VertexOf(6), "tree: pick");
  Click(item, pos[0], pos[1]);
  Check(Selected(hub) == std::vector<vtkIdType>({ 6 }), "tree click selects Gaussian 6");
  Check(timeline->GetNumberOfHistoryLines() == 1, "timeline follows the tree click");
  Check(SelectedTotal(histogram, 8) == 1 && histogram->GetSelectedBinCount(6) == 1,
    "histogram follows the tree click (opacity 0.65: bin 6)");
  item->GetLineageVertices(vertices);
  Check(Values(vertices) == std::vector<vtkIdType>({ 5, 6 }), // Gaussians 1, 6
    "tree: lineage of Gaussian 6 is 1 -> 6");

  // 3. A click in the timeline moves every view to the (snapped) iteration.
  int picked = -1;
  vtkNew<vtkCallbackCommand> itObserver;
  itObserver->SetClientData(&picked);
  itObserver->SetCallback([](vtkObject*, unsigned long, void* c, void* d)
    { *static_cast<int*>(c) = *static_cast<int*>(d); });
  timeline->AddObserver(vtkGaussianTimelineView::IterationSelectedEvent, itObserver);
  window->Render();
  vtkGaussianTimelineChart* quality = timeline->GetChart(vtkGaussianTimelineView::QUALITY);
  const float cx = quality->IterationToScene(1400.0);
  const float cy = 0.5f *
    (quality->GetAxis(vtkAxis::LEFT)->GetPoint1()[1] +
      quality->GetAxis(vtkAxis::LEFT)->GetPoint2()[1]);
  Click(quality, cx, cy);
  Check(picked == 1500, "timeline click picks iteration 1400 -> logged 1500");
  Check(hub->GetIteration() == 1500, "the hub's iteration moved");
  Check(timeline->GetChart(vtkGaussianTimelineView::COUNT)->GetCursorIteration() == 1500,
    "every timeline chart shows the cursor");

  // 4. Brushing the histogram selects the Gaussians in the value range.
  const vtkIdType matched = histogram->SelectRange(0.3, 0.6);
  Check(matched == 3, "brush [0.3, 0.6] matches opacities 0.35, 0.45, 0.55");
  Check(Selected(hub) == std::vector<vtkIdType>({ 3, 4, 5 }), "brush publishes ids 3, 4, 5");
  item->GetSelectedVertices(vertices);
  Check(vertices->GetNumberOfTuples() == 3, "tree shows the brushed Gaussians");
  Check(timeline->GetNumberOfHistoryLines() == 3, "timeline shows their histories");

  CheckSelectedCountsAgainstAScan();

  // Final picture: the floater selected, the tree fitted, iteration 1500.
  hub->SelectIds(&floater, 1);
  item->SetZoomedInRows(1.0);
  item->ResetViewport();
  window->Render();
  int retVal = vtkRegressionTestImage(window);
  if (retVal == vtkRegressionTester::DO_INTERACTOR)
  {
    retVal = vtkRegressionTester::PASSED;
  }
  Check(linkedtest::WriteSelectionImages(window, hub, "TestGaussianLinkedViews"),
    "the pictures with and without the selection are written");
  hub->RemoveAllViews();
  return (Check.GetFailures() == 0 && retVal == vtkRegressionTester::PASSED) ? 0 : 1;
}

// SPDX-License-Identifier: BSD-3-Clause
// The views connected to vtkGaussianSession's ports (issue 33), as the application connects
// them, on the embedded demo log: after an Update() every view holds what the port holds (the
// scene view and the histogram the Gaussians with their scores, the tree view the tree and
// bands, the timeline the metrics and the history of the hub's selection, which reaches the
// session through its selection input); a change made to the session alone (another snapshot,
// other scores) reaches the views at their next Update() without anything handed over; and a
// new selection, which makes the session pass its cached Gaussians and tree on again, does not
// make the scene view or the tree view take them again. The history follows the selection when
// the hub renders the views, with no Update() called. The history is checked against a
// second reader's own history query of the selected ids.
#include "vtkGaussianHistogramView.h"
#include "vtkGaussianSceneView.h"
#include "vtkGaussianSelectionHub.h"
#include "vtkGaussianSession.h"
#include "vtkGaussianTimelineView.h"
#include "vtkGaussianTrainingLogReader.h"
#include "vtkGaussianTreeView.h"

#include "Vis4GSTestCheck.h"
#include "Vis4GSTestData.h"

#include "vtkAnnotationLink.h"
// (Its module header makes the 2D views' OpenGL device available here: autoinit.)
#include "vtkContextScene.h"
#include "vtkDataArray.h"
#include "vtkGaussianArtifactScoreFilter.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkTable.h"
#include "vtkTree.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace
{
vis4gs::testing::CheckCounter Counter;

void Check(bool ok, const std::string& what)
{
  Counter(ok, what.c_str());
}

vtkIdType BinTotal(vtkGaussianHistogramView* view)
{
  vtkIdType total = 0;
  for (int b = 0; b < view->GetNumberOfBins(); ++b)
  {
    total += view->GetBinCount(b);
  }
  return total;
}

/// Whether @p a and @p b hold the same values (NaN equal to NaN).
bool SameValues(vtkDataArray* a, vtkDataArray* b)
{
  if (!a || !b || a->GetNumberOfTuples() != b->GetNumberOfTuples() ||
    a->GetNumberOfComponents() != b->GetNumberOfComponents())
  {
    return false;
  }
  for (vtkIdType t = 0; t < a->GetNumberOfTuples(); ++t)
  {
    for (int c = 0; c < a->GetNumberOfComponents(); ++c)
    {
      const double x = a->GetComponent(t, c), y = b->GetComponent(t, c);
      if (!(x == y || (std::isnan(x) && std::isnan(y))))
      {
        return false;
      }
    }
  }
  return true;
}
}

int TestGaussianViewConnections(int, char*[])
{
  const std::string log = vis4gs::testing::SourcePath("Data/Demo/vis4gs-demo.h5");
  vtkNew<vtkGaussianSelectionHub> hub;
  vtkNew<vtkGaussianSession> session;
  session->SetFileName(log.c_str());
  // (The coverage and the needle shape suffice here; blur and needle cost most of the time.)
  Check(session->GetScoreFilter()->SetScores("coverage,shape"), "the scores are set");
  session->SetSelectionConnection(hub->GetAnnotationLink()->GetOutputPort(2));
  session->SetMaximumHistoryIds(16);

  vtkNew<vtkGaussianSceneView> scene;
  scene->SetSelectionHub(hub);
  scene->SetInputConnection(session->GetOutputPort(vtkGaussianSession::GaussiansPort));
  scene->SetCamerasConnection(session->GetOutputPort(vtkGaussianSession::CamerasPort));
  vtkNew<vtkGaussianHistogramView> histogram;
  histogram->SetSelectionHub(hub);
  histogram->SetArrayName("ViewCoverage");
  histogram->SetInputConnection(session->GetOutputPort(vtkGaussianSession::GaussiansPort));
  vtkNew<vtkGaussianTreeView> tree;
  tree->SetSelectionHub(hub);
  tree->SetInputConnection(session->GetOutputPort(vtkGaussianSession::TreePort));
  tree->SetFamilyBandsConnection(session->GetOutputPort(vtkGaussianSession::BandsPort));
  vtkNew<vtkGaussianTimelineView> timeline;
  timeline->SetSelectionHub(hub);
  timeline->SetMetricsConnection(session->GetOutputPort(vtkGaussianSession::MetricsPort));
  timeline->SetHistoryConnection(session->GetOutputPort(vtkGaussianSession::HistoryPort));
  Check(scene->GetScene() == nullptr && tree->GetTree() == nullptr,
    "a connected view pulls nothing before its update");

  scene->Update();
  histogram->Update();
  tree->Update();
  timeline->Update();
  vtkPolyData* gaussians = session->GetGaussiansOutput();
  vtkPolyData* shown = scene->GetScene();
  const vtkIdType n = gaussians->GetNumberOfPoints();
  Check(n > 0 && shown && shown != gaussians && shown->GetNumberOfPoints() == n,
    "the scene view draws its own copy of the Gaussians port (" + std::to_string(n) + ")");
  Check(shown &&
      shown->GetPointData()->GetArray("ViewCoverage") ==
        gaussians->GetPointData()->GetArray("ViewCoverage") &&
      shown->GetPointData()->GetArray("ViewCoverage") != nullptr,
    "which shares the port's score arrays (a shallow copy)");
  Check(scene->GetCameras() &&
      scene->GetCameras()->GetNumberOfRows() == session->GetCamerasOutput()->GetNumberOfRows() &&
      scene->GetCameras()->GetNumberOfRows() > 0,
    "the scene view's cameras are the cameras port's");
  Check(BinTotal(histogram) == n, "the histogram bins every Gaussian of the port's ViewCoverage");
  vtkTree* portTree =
    vtkTree::SafeDownCast(session->GetOutputDataObject(vtkGaussianSession::TreePort));
  Check(tree->GetTree() && portTree && portTree->GetNumberOfVertices() > 1 &&
      tree->GetTree()->GetNumberOfVertices() == portTree->GetNumberOfVertices(),
    "the tree view has the tree port's tree");
  Check(tree->GetFamilyBands() &&
      tree->GetFamilyBands()->GetNumberOfRows() ==
        vtkTable::SafeDownCast(session->GetOutputDataObject(vtkGaussianSession::BandsPort))
          ->GetNumberOfRows(),
    "and the bands port's bands");
  Check(timeline->GetMetrics() &&
      timeline->GetMetrics()->GetNumberOfRows() == session->GetMetricsOutput()->GetNumberOfRows() &&
      timeline->GetMetrics()->GetNumberOfRows() > 0,
    "the timeline has the metrics port's metrics");
  Check(!timeline->GetHistory() || timeline->GetHistory()->GetNumberOfRows() == 0,
    "and no history without a selection");

  // A selection in the hub reaches the history through the session's selection input.
  vtkDataArray* ids = gaussians->GetPointData()->GetArray("GaussianId");
  const vtkIdType picked[2] = { static_cast<vtkIdType>(ids->GetTuple1(0)),
    static_cast<vtkIdType>(ids->GetTuple1(n / 2)) };
  vtkTree* treeBefore = tree->GetTree();
  // The hub renders its views after the change, and a view's Render() pulls its ports: no
  // Update() is called here, as the window calls none.
  const vtkIdType changes = hub->GetNumberOfChanges();
  hub->SelectIds(picked, 2);
  Check(hub->GetNumberOfChanges() == changes + 1 && hub->GetRenderOnChange(),
    "the selection is published and the views rendered");
  vtkNew<vtkGaussianTrainingLogReader> second;
  second->SetFileName(log.c_str());
  vtkNew<vtkIdTypeArray> wanted;
  wanted->SetNumberOfValues(2);
  wanted->SetValue(0, std::min(picked[0], picked[1]));
  wanted->SetValue(1, std::max(picked[0], picked[1]));
  vtkNew<vtkTable> expected;
  second->GetPropertyHistory(wanted, expected);
  vtkTable* history = timeline->GetHistory();
  Check(history && expected->GetNumberOfRows() > 0 &&
      history->GetNumberOfRows() == expected->GetNumberOfRows(),
    "the timeline's history is the selection's (" +
      std::to_string(history ? history->GetNumberOfRows() : 0) + " rows, " +
      std::to_string(expected->GetNumberOfRows()) + " by a second reader)");
  Check(history &&
      SameValues(vtkDataArray::SafeDownCast(history->GetColumnByName("Opacity")),
        vtkDataArray::SafeDownCast(expected->GetColumnByName("Opacity"))) &&
      SameValues(vtkDataArray::SafeDownCast(history->GetColumnByName("GaussianId")),
        vtkDataArray::SafeDownCast(expected->GetColumnByName("GaussianId"))),
    "with the second reader's ids and opacities");
  Check(scene->GetScene() == shown,
    "the new selection did not make the scene view take again "
    "the Gaussians the session passed on unchanged");
  Check(tree->GetTree() == treeBefore, "nor the tree view its tree");

  // A change made to the session alone: the first snapshot, fewer scores.
  vtkNew<vtkGaussianTrainingLogReader> header;
  header->SetFileName(log.c_str());
  header->UpdateInformation();
  const int first = header->GetSnapshotIteration(0);
  const vtkIdType firstSize = header->GetSnapshotSize(first);
  Check(firstSize != n, "the demo log's first snapshot has another size than its last");
  session->SetIteration(first);
  Check(session->GetScoreFilter()->SetScores("coverage"), "fewer scores are set");
  scene->Update();
  histogram->Update();
  shown = scene->GetScene();
  Check(shown && shown->GetNumberOfPoints() == firstSize,
    "another snapshot set on the session reaches the scene view at its update (" +
      std::to_string(shown ? shown->GetNumberOfPoints() : 0) + " of " + std::to_string(firstSize) +
      ")");
  Check(shown && shown->GetPointData()->GetArray("ViewCoverage") &&
      !shown->GetPointData()->GetArray("NeedleShape"),
    "with the scores the session's score filter now computes");
  Check(BinTotal(histogram) == firstSize, "and the histogram's");
  return Counter.ExitCode();
}

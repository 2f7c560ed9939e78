// SPDX-License-Identifier: BSD-3-Clause
// vtkGaussianSession on the embedded demo log and on a scene file written from it: every port
// equals what the readers and filters connected by hand give (the Gaussians with their
// scores, cameras, metrics, tree, bands, the history of a selection given as a vtkSelection,
// the removal effect of that selection), only the requested port is computed (showing the
// snapshot builds no tree, a new selection re-reads no snapshot), the file kind comes from
// the content (a log renamed .ply is still a log), and a missing file or a bad rule is an error
// naming the file; the genealogy filter updated by a client in a second thread while the
// session reads a snapshot (the application's load) gives the tree port its tree; a session
// given Gaussians and cameras as data (the application's scores) reads no file and computes
// the same scores; MaximumHistoryIds keeps the smallest selected ids' history.
#include "vtkGaussianSession.h"

#include "SessionTestUtils.h"
#include "Vis4GSTestCheck.h"
#include "Vis4GSTestData.h"

#include "vtkAbstractArray.h"
#include "vtkCallbackCommand.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkExecutive.h"
#include "vtkGaussianArtifactScoreFilter.h"
#include "vtkGaussianGenealogyTreeFilter.h"
#include "vtkGaussianPLYWriter.h"
#include "vtkGaussianRemovalEffectFilter.h"
#include "vtkGaussianRuleSelectionFilter.h"
#include "vtkGaussianTrainingLogReader.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkTable.h"
#include "vtkTree.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

namespace
{
using sessiontest::ErrorText;
vis4gs::testing::CheckCounter Check;

/// Whether @p a and @p b hold the same values, NaN equal to NaN.
bool SameArray(vtkAbstractArray* a, vtkAbstractArray* b)
{
  if (!a || !b || a->GetNumberOfTuples() != b->GetNumberOfTuples() ||
    a->GetNumberOfComponents() != b->GetNumberOfComponents())
  {
    return false;
  }
  vtkDataArray* da = vtkDataArray::SafeDownCast(a);
  vtkDataArray* db = vtkDataArray::SafeDownCast(b);
  if (!da || !db)
  {
    for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
    {
      if (a->GetVariantValue(i) != b->GetVariantValue(i))
      {
        return false;
      }
    }
    return true;
  }
  for (vtkIdType t = 0; t < da->GetNumberOfTuples(); ++t)
  {
    for (int c = 0; c < da->GetNumberOfComponents(); ++c)
    {
      const double x = da->GetComponent(t, c), y = db->GetComponent(t, c);
      if (!(x == y || (std::isnan(x) && std::isnan(y))))
      {
        return false;
      }
    }
  }
  return true;
}

/// Every column (array) of @p expected is in @p actual with the same values.
bool SameFields(vtkDataSetAttributes* expected, vtkDataSetAttributes* actual, const char* what)
{
  bool same = expected->GetNumberOfArrays() > 0 &&
    expected->GetNumberOfArrays() == actual->GetNumberOfArrays();
  for (int a = 0; same && a < expected->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* e = expected->GetAbstractArray(a);
    if (!SameArray(e, actual->GetAbstractArray(e->GetName())))
    {
      std::cerr << what << ": array " << e->GetName() << " differs\n";
      same = false;
    }
  }
  return same;
}
}

int TestGaussianSession(int, char*[])
{
  const std::string log = vis4gs::testing::SourcePath("Data/Demo/vis4gs-demo.h5");
  Check(vtkGaussianSession::IsTrainingLogFile(log.c_str()), "the demo log has the HDF5 signature");
  Check(!vtkGaussianSession::IsTrainingLogFile(
          vis4gs::testing::SourcePath("Data/Scenes/demo.json").c_str()),
    "a JSON file is no training log");

  // By hand, as a script connects them.
  vtkNew<vtkGaussianTrainingLogReader> reader;
  reader->SetFileName(log.c_str());
  vtkNew<vtkGaussianArtifactScoreFilter> scores;
  scores->SetInputConnection(reader->GetOutputPort(0));
  scores->SetCamerasConnection(reader->GetOutputPort(1));
  // (Blur and needle scores cost most of the time; the session passes the settings on, which
  // the coverage and the shape show as well.)
  scores->ComputeBlurScoreOff();
  scores->ComputeNeedleScoreOff();
  scores->Update();
  vtkNew<vtkGaussianTrainingLogReader> events;
  events->SetFileName(log.c_str());
  vtkNew<vtkGaussianGenealogyTreeFilter> genealogy;
  genealogy->SetInputConnection(events->GetOutputPort(3));
  genealogy->Update();
  reader->Update(2);

  vtkNew<vtkGaussianSession> session;
  session->SetFileName(log.c_str());
  session->GetScoreFilter()->ComputeBlurScoreOff();
  session->GetScoreFilter()->ComputeNeedleScoreOff();
  session->Update(vtkGaussianSession::GaussiansPort, nullptr);
  Check(session->GetIsTrainingLog(), "the session reads the log as a log");
  Check(session->GetLoadedIteration() == reader->GetLoadedIteration(), "the last snapshot");
  vtkPolyData* gaussians = session->GetGaussiansOutput();
  Check(gaussians->GetNumberOfPoints() == scores->GetOutput()->GetNumberOfPoints() &&
      gaussians->GetNumberOfPoints() > 0,
    "the Gaussians port has the snapshot's Gaussians");
  Check(SameFields(scores->GetOutput()->GetPointData(), gaussians->GetPointData(), "Gaussians"),
    "the Gaussians port has the score filter's arrays, equal");
  Check(gaussians->GetPointData()->GetArray("ViewCoverage") != nullptr &&
      gaussians->GetPointData()->GetArray("BlurScore") == nullptr,
    "the score filter's settings choose the scores");
  Check(session->GetGenealogyFilter()->GetOutput()->GetNumberOfVertices() == 0,
    "showing the snapshot builds no tree");

  session->Update(vtkGaussianSession::CamerasPort, nullptr);
  Check(SameFields(reader->GetCamerasOutput()->GetRowData(),
          session->GetCamerasOutput()->GetRowData(),
          "cameras"),
    "the cameras port is the reader's camera table");
  session->Update(vtkGaussianSession::MetricsPort, nullptr);
  Check(SameFields(reader->GetMetricsOutput()->GetRowData(),
          session->GetMetricsOutput()->GetRowData(),
          "metrics"),
    "the metrics port is the reader's metrics");
  session->Update(vtkGaussianSession::TreePort, nullptr);
  vtkTree* tree = vtkTree::SafeDownCast(session->GetOutputDataObject(vtkGaussianSession::TreePort));
  Check(tree && tree->GetNumberOfVertices() == genealogy->GetOutput()->GetNumberOfVertices() &&
      tree->GetNumberOfVertices() > 1,
    "the tree port has the genealogy filter's vertices");
  Check(tree && SameFields(genealogy->GetOutput()->GetVertexData(), tree->GetVertexData(), "tree"),
    "the tree's vertex arrays are the genealogy filter's");
  session->Update(vtkGaussianSession::BandsPort, nullptr);
  Check(SameFields(genealogy->GetFamilyBands()->GetRowData(),
          vtkTable::SafeDownCast(session->GetOutputDataObject(vtkGaussianSession::BandsPort))
            ->GetRowData(),
          "bands"),
    "the bands port is the genealogy filter's family bands");

  // The application's pattern: a client updates the genealogy filter in a second thread while
  // the session reads the snapshot in this one (its sub-filters' events count only in its own
  // thread); the tree port then passes that tree on without building it again.
  {
    vtkNew<vtkGaussianSession> overlapped;
    overlapped->SetFileName(log.c_str());
    overlapped->ComputeScoresOff();
    vtkGaussianGenealogyTreeFilter* filter = overlapped->GetGenealogyFilter();
    vtkTypeBool built = 0;
    std::thread second([filter, &built] { built = filter->Update(0, nullptr); });
    const vtkTypeBool read = overlapped->Update(vtkGaussianSession::GaussiansPort, nullptr);
    second.join();
    Check(read && built && overlapped->GetGaussiansOutput()->GetNumberOfPoints() > 0,
      "the snapshot and the tree are read in two threads at once");
    const vtkMTimeType builtAt = filter->GetOutput()->GetMTime();
    Check(overlapped->Update(vtkGaussianSession::TreePort, nullptr) != 0, "the tree port");
    vtkTree* passed =
      vtkTree::SafeDownCast(overlapped->GetOutputDataObject(vtkGaussianSession::TreePort));
    Check(passed && filter->GetOutput()->GetMTime() == builtAt &&
        passed->GetNumberOfVertices() == genealogy->GetOutput()->GetNumberOfVertices(),
      "the tree port passes the tree built in the second thread on, not built again");
  }

  // Given data (the application's scores): a second session given the snapshot without scores
  // and the cameras reads no file (its FileName does not exist) and computes the scores a script
  // computes, on the given arrays themselves.
  {
    vtkNew<vtkGaussianSession> plain;
    plain->SetFileName(log.c_str());
    plain->ComputeScoresOff();
    plain->Update(vtkGaussianSession::GaussiansPort, nullptr);
    plain->Update(vtkGaussianSession::CamerasPort, nullptr);
    vtkNew<vtkPolyData> snapshot;
    snapshot->ShallowCopy(plain->GetGaussiansOutput());
    vtkNew<vtkTable> cameras;
    cameras->ShallowCopy(plain->GetCamerasOutput());
    vtkNew<vtkGaussianSession> given;
    given->SetFileName("/nonexistent/vis4gs-given.h5");
    given->SetGaussiansData(snapshot);
    given->SetCamerasData(cameras);
    given->GetScoreFilter()->ComputeBlurScoreOff();
    given->GetScoreFilter()->ComputeNeedleScoreOff();
    Check(given->Update(vtkGaussianSession::GaussiansPort, nullptr) != 0 &&
        !given->GetIsTrainingLog() && given->GetLoadedIteration() == -1,
      "a session given Gaussians and cameras reads no file");
    vtkPolyData* scored = given->GetGaussiansOutput();
    Check(SameFields(scores->GetOutput()->GetPointData(), scored->GetPointData(), "given"),
      "and its Gaussians port has the scores of the log's snapshot, equal");
    Check(
      scored->GetPointData()->GetArray("Opacity") == snapshot->GetPointData()->GetArray("Opacity"),
      "on the given arrays (no copy)");
    Check(given->Update(vtkGaussianSession::CamerasPort, nullptr) != 0 &&
        given->GetCamerasOutput()->GetNumberOfRows() == cameras->GetNumberOfRows(),
      "its cameras port is the given table");
  }

  // The selection as the hub publishes it: pedigree ids named GaussianId.
  vtkDataArray* idColumn = gaussians->GetPointData()->GetArray("GaussianId");
  vtkNew<vtkIdTypeArray> picked;
  picked->SetName("GaussianId");
  for (vtkIdType k = 0; k < 5; ++k)
  {
    picked->InsertNextValue(
      static_cast<vtkIdType>(idColumn->GetTuple1(k * (idColumn->GetNumberOfTuples() - 1) / 4)));
  }
  vtkNew<vtkSelection> selection;
  vtkNew<vtkSelectionNode> node;
  node->SetContentType(vtkSelectionNode::PEDIGREEIDS);
  node->SetFieldType(vtkSelectionNode::POINT);
  node->SetSelectionList(picked);
  selection->AddNode(node);
  session->SetSelectionData(selection);
  const int readsBefore = session->GetLogReader()->GetSnapshotReads();
  session->Update(vtkGaussianSession::GaussiansPort, nullptr);
  Check(session->GetLogReader()->GetSnapshotReads() == readsBefore,
    "a new selection re-reads no snapshot for the Gaussians port");
  session->Update(vtkGaussianSession::HistoryPort, nullptr);
  vtkNew<vtkTable> history;
  Check(reader->GetPropertyHistory(picked, history) != 0, "the reader gives the history");
  vtkTable* sessionHistory = session->GetHistoryOutput();
  Check(history->GetNumberOfRows() > 0 &&
      sessionHistory->GetNumberOfRows() == history->GetNumberOfRows() &&
      SameFields(history->GetRowData(), sessionHistory->GetRowData(), "history"),
    "the history port is the reader's history of the selected Gaussians");
  // At most MaximumHistoryIds of them, the smallest (the application's 16 of a large brush).
  session->SetMaximumHistoryIds(2);
  session->Update(vtkGaussianSession::HistoryPort, nullptr);
  std::vector<vtkIdType> sorted(picked->GetPointer(0), picked->GetPointer(0) + 5);
  std::sort(sorted.begin(), sorted.end());
  vtkNew<vtkIdTypeArray> smallest;
  smallest->InsertNextValue(sorted[0]);
  smallest->InsertNextValue(sorted[1]);
  vtkNew<vtkTable> limited;
  reader->GetPropertyHistory(smallest, limited);
  Check(limited->GetNumberOfRows() > 0 && limited->GetNumberOfRows() < history->GetNumberOfRows() &&
      session->GetHistoryOutput()->GetNumberOfRows() == limited->GetNumberOfRows() &&
      SameFields(limited->GetRowData(), session->GetHistoryOutput()->GetRowData(), "limited"),
    "MaximumHistoryIds keeps the history of the smallest selected ids");
  session->SetMaximumHistoryIds(0);

  session->GetRemovalEffectFilter()->TestViewsOff();
  session->Update(vtkGaussianSession::RemovalTotalsPort, nullptr);
  vtkNew<vtkGaussianRemovalEffectFilter> removal;
  removal->TestViewsOff();
  removal->SetInputConnection(0, scores->GetOutputPort());
  removal->SetInputConnection(1, reader->GetOutputPort(1));
  removal->SetRemovedIds(picked);
  removal->Update();
  vtkTable* totals =
    vtkTable::SafeDownCast(session->GetOutputDataObject(vtkGaussianSession::RemovalTotalsPort));
  Check(totals->GetNumberOfRows() == 2 &&
      SameFields(removal->GetOutput(1)->GetRowData(), totals->GetRowData(), "removal"),
    "the removal port is the removal-effect filter's totals for the selection");
  // The preview port: the filter's renders of the camera asked for, the tables kept.
  Check(session->GetRemovalPreviewView() == -1 &&
      session->Update(vtkGaussianSession::RemovalPreviewPort, nullptr) &&
      session->GetRemovalPreviewOutput()->GetNumberOfPoints() == 0,
    "no preview view by default: an empty preview port");
  vtkAbstractArray* measured = session->GetRemovalEffectFilter()->GetOutput(1)->GetColumn(3);
  session->SetRemovalPreviewView(1);
  removal->SetPreviewView(1);
  removal->Update();
  Check(session->Update(vtkGaussianSession::RemovalPreviewPort, nullptr) != 0,
    "the preview port updates");
  Check(session->GetRemovalEffectFilter()->GetOutput(1)->GetColumn(3) == measured,
    "a new preview view does not measure the removal again (the same totals arrays)");
  Check(session->GetRemovalPreviewOutput()->GetNumberOfPoints() > 0 &&
      SameFields(removal->GetPreviewOutput()->GetPointData(),
        session->GetRemovalPreviewOutput()->GetPointData(),
        "preview"),
    "the preview port is the filter's renders of camera 1");
  session->SetRemovalPreviewView(-1);

  // The rule's marks, with the views the scores used.
  session->SetRule("views<=3");
  session->Update(vtkGaussianSession::GaussiansPort, nullptr);
  vtkNew<vtkGaussianRuleSelectionFilter> rule;
  rule->SetInputConnection(scores->GetOutputPort());
  rule->SetNumberOfViews(static_cast<int>(scores->GetNumberOfViewsUsed()));
  rule->SetRule("views<=3");
  rule->Update();
  Check(SameArray(rule->GetOutput()->GetPointData()->GetArray("RuleSelected"),
          session->GetGaussiansOutput()->GetPointData()->GetArray("RuleSelected")),
    "the rule's marks are the rule filter's");
  session->SetRule("views<=");
  {
    ErrorText error(session);
    Check(!session->Update(vtkGaussianSession::GaussiansPort, nullptr) &&
        error.Text.find(log + ": ") != std::string::npos,
      "a bad rule fails the update with an error naming the file");
  }
  session->SetRule(nullptr);

  // A scene file holding the same snapshot: the kind by content, the ids by IdProperty.
  namespace fs = std::filesystem;
  const fs::path folder =
    fs::temp_directory_path() / ("vis4gs-session-" + std::to_string(::getpid()));
  fs::create_directories(folder);
  const std::string ply = (folder / "snapshot.ply").string();
  vtkNew<vtkGaussianPLYWriter> writer;
  writer->SetInputConnection(reader->GetOutputPort(0));
  writer->SetFileName(ply.c_str());
  writer->WriteIdsOn();
  Check(writer->Write() == 1, "the snapshot is written as a PLY");
  vtkNew<vtkGaussianSession> scene;
  scene->SetFileName(ply.c_str());
  scene->SetIdProperty("id");
  scene->GetScoreFilter()->ComputeViewCoverageOff();
  scene->GetScoreFilter()->ComputeBlurScoreOff();
  scene->GetScoreFilter()->ComputeNeedleScoreOff();
  scene->Update(vtkGaussianSession::GaussiansPort, nullptr);
  Check(!scene->GetIsTrainingLog(), "a PLY is read as a scene file");
  vtkPolyData* sceneGaussians = scene->GetGaussiansOutput();
  Check(SameArray(sceneGaussians->GetPointData()->GetArray("GaussianId"),
          scores->GetOutput()->GetPointData()->GetArray("GaussianId")),
    "the scene file's Gaussians keep their ids");
  Check(SameArray(sceneGaussians->GetPointData()->GetArray("NeedleShape"),
          scores->GetOutput()->GetPointData()->GetArray("NeedleShape")),
    "the scene file's needle shape is the log's");
  scene->Update(vtkGaussianSession::MetricsPort, nullptr);
  scene->Update(vtkGaussianSession::TreePort, nullptr);
  Check(scene->GetMetricsOutput()->GetNumberOfRows() == 0, "a scene file has no metrics");
  Check(vtkTree::SafeDownCast(scene->GetOutputDataObject(vtkGaussianSession::TreePort))
          ->GetNumberOfVertices() == 0,
    "a scene file has no tree");

  // The content decides, not the name.
  const std::string renamed = (folder / "log.ply").string();
  fs::copy_file(log, renamed, fs::copy_options::overwrite_existing);
  vtkNew<vtkGaussianSession> disguised;
  disguised->SetFileName(renamed.c_str());
  disguised->ComputeScoresOff();
  disguised->Update(vtkGaussianSession::GaussiansPort, nullptr);
  Check(disguised->GetIsTrainingLog() &&
      disguised->GetGaussiansOutput()->GetNumberOfPoints() ==
        scores->GetOutput()->GetNumberOfPoints(),
    "a log named .ply is read as a log");

  const std::string missing = (folder / "missing.h5").string();
  vtkNew<vtkGaussianSession> nothing;
  nothing->SetFileName(missing.c_str());
  {
    ErrorText error(nothing);
    Check(!nothing->Update(vtkGaussianSession::GaussiansPort, nullptr), "a missing file fails");
    const std::size_t at = error.Text.find(missing + ": no such file");
    Check(at != std::string::npos, "the error names the file and the problem");
  }
  fs::remove_all(folder);
  return Check.ExitCode();
}

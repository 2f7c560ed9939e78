// SPDX-License-Identifier: BSD-3-Clause
// vtkGaussianSession's comparison (issue 33: `vis4gs compare` as a client of the session): two
// iterations of the demo log through CompareFileName / CompareIteration give on port 8 the rows
// Core's CompareStates gives for the two snapshots read by Core's log reader, and on port 9 the
// figures Core's MeasureViewMetrics gives for both in the log's cameras with its own images; a
// scene file compared with the log takes the log's cameras (compare's rule); a scene file is
// read with its ids when it has them (the scene reader's IdPropertyOptional) and with its row
// numbers when it has none; a missing second file is an error naming it, and a damaged .h5 is
// read as a log (the log reader's error).
#include "vtkGaussianSession.h"

#include "CameraJson.h"
#include "RemovalEffect.h"
#include "SessionTestUtils.h"
#include "StateComparison.h"
#include "TrainingLogReader.h"
#include "Vis4GSTestCheck.h"
#include "Vis4GSTestData.h"

#include "vtkCallbackCommand.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkGaussianCameraReader.h"
#include "vtkGaussianPLYWriter.h"
#include "vtkGaussianSceneReader.h"
#include "vtkGaussianStateComparisonFilter.h"
#include "vtkGaussianTrainingLogReader.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkVariant.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <unistd.h>
#include <vector>

namespace
{
using sessiontest::ErrorText;
vis4gs::testing::CheckCounter Check;

bool Same(double x, double y)
{
  return x == y || (std::isnan(x) && std::isnan(y));
}

double Value(vtkTable* table, const char* column, vtkIdType row)
{
  vtkDataArray* values = vtkDataArray::SafeDownCast(table->GetColumnByName(column));
  return values ? values->GetTuple1(row) : std::nan("");
}

/// Port 8 against Core's comparison, row by row.
bool SameDifferences(vtkTable* table, const vis4gs::StateComparison& c)
{
  if (table->GetNumberOfRows() != static_cast<vtkIdType>(c.Gaussians.size()) || c.Gaussians.empty())
  {
    std::cerr << "rows: " << table->GetNumberOfRows() << " against " << c.Gaussians.size() << "\n";
    return false;
  }
  auto* status = vtkStringArray::SafeDownCast(table->GetColumnByName("Status"));
  for (vtkIdType r = 0; r < table->GetNumberOfRows(); ++r)
  {
    const vis4gs::GaussianStateDifference& d = c.Gaussians[static_cast<std::size_t>(r)];
    if (Value(table, "GaussianId", r) != static_cast<double>(d.Id) ||
      Value(table, "Change", r) != d.Change || !status ||
      status->GetValue(r) != vis4gs::StateChangeName(d.Change) ||
      !Same(Value(table, "Move", r), d.Move) ||
      !Same(Value(table, "OpacityChange", r), d.Opacity) ||
      !Same(Value(table, "ScaleChange", r), d.Scale))
    {
      std::cerr << "row " << r << " (id " << d.Id << ") differs\n";
      return false;
    }
  }
  return true;
}
}

int TestGaussianSessionComparison(int, char*[])
{
  namespace fs = std::filesystem;
  const std::string log = vis4gs::testing::SourcePath("Data/Demo/vis4gs-demo.h5");

  // Independently: Core's reader, comparison and measurement.
  const vis4gs::TrainingLogReader core(log);
  const std::vector<int>& iterations = core.GetSnapshotIterations();
  vis4gs::SnapshotReadOptions every;
  every.ShDegree = -1;
  const vis4gs::GaussianCloud first = core.ReadSnapshot(iterations.front(), every);
  const vis4gs::GaussianCloud last = core.ReadSnapshot(iterations.back(), every);
  vis4gs::StateThresholds thresholds;
  thresholds.Move = 0.01;
  thresholds.Opacity = 0.05;
  const vis4gs::StateComparison expected = vis4gs::CompareStates(first, last, thresholds);
  const std::vector<vis4gs::Camera> cameras = core.ReadCameras();
  const vis4gs::TrainingImageProvider images =
    [&core](std::size_t, const vis4gs::Camera& camera, vis4gs::Image& image)
  { return vis4gs::LoadCameraImage(&core, camera, image); };
  vis4gs::RemovalEffectOptions options;
  const std::vector<vis4gs::ViewMetrics> figuresA =
    vis4gs::MeasureViewMetrics(first, cameras, options, images);
  const std::vector<vis4gs::ViewMetrics> figuresB =
    vis4gs::MeasureViewMetrics(last, cameras, options, images);

  vtkNew<vtkGaussianSession> session;
  session->SetFileName(log.c_str());
  session->SetIteration(iterations.front());
  session->ComputeScoresOff();
  session->SetCompareFileName(log.c_str());
  Check(session->GetCompareIteration() == -1, "CompareIteration defaults to the last");
  vtkGaussianStateComparisonFilter* comparison = session->GetComparisonFilter();
  comparison->SetMoveThreshold(thresholds.Move);
  comparison->SetOpacityThreshold(thresholds.Opacity);
  Check(session->Update(vtkGaussianSession::ComparisonPort, nullptr) != 0, "the comparison port");
  Check(session->GetComparedSession()->GetLoadedIteration() == iterations.back(),
    "the compared session reads the last snapshot");
  Check(SameDifferences(session->GetComparisonOutput(), expected),
    "port 8 is Core's CompareStates of the two snapshots, row by row");
  Check(comparison->GetNumberBorn() == static_cast<vtkIdType>(expected.Born) &&
      comparison->GetNumberMoved() == static_cast<vtkIdType>(expected.Moved) &&
      comparison->GetNumberUnchanged() == static_cast<vtkIdType>(expected.Unchanged),
    "the counts are Core's");

  Check(session->Update(vtkGaussianSession::ComparisonViewsPort, nullptr) != 0, "the views port");
  vtkTable* views = session->GetComparisonViewsOutput();
  bool same = views->GetNumberOfRows() == static_cast<vtkIdType>(cameras.size());
  std::size_t measured = 0;
  for (vtkIdType r = 0; same && r < views->GetNumberOfRows(); ++r)
  {
    const std::size_t i = static_cast<std::size_t>(r);
    same = Same(Value(views, "PSNR_A", r), figuresA[i].Psnr) &&
      Same(Value(views, "SSIM_A", r), figuresA[i].Ssim) &&
      Same(Value(views, "L1_A", r), figuresA[i].L1) &&
      Same(Value(views, "PSNR_B", r), figuresB[i].Psnr) &&
      Same(Value(views, "SSIM_B", r), figuresB[i].Ssim) &&
      Same(Value(views, "L1_B", r), figuresB[i].L1) &&
      views->GetValueByName(r, "Name").ToString() == cameras[i].Name;
    measured += std::isfinite(figuresA[i].L1) ? 1 : 0;
  }
  Check(same && measured > 0,
    "port 9 is Core's MeasureViewMetrics of both states in the log's cameras and images");
  Check(comparison->GetNumberOfViewsMeasured() == static_cast<vtkIdType>(measured),
    "the views measured are counted");

  // A scene file as A and the log as B: the compared log's cameras (compare's rule); the
  // scene's ids from its id property.
  const fs::path folder =
    fs::temp_directory_path() / ("vis4gs-session-compare-" + std::to_string(::getpid()));
  fs::create_directories(folder);
  vtkNew<vtkGaussianTrainingLogReader> reader;
  reader->SetFileName(log.c_str());
  reader->SetIteration(iterations.front());
  const std::string withIds = (folder / "first.ply").string();
  const std::string withoutIds = (folder / "first-no-ids.ply").string();
  vtkNew<vtkGaussianPLYWriter> writer;
  writer->SetInputConnection(reader->GetOutputPort(0));
  writer->SetFileName(withIds.c_str());
  writer->WriteIdsOn();
  Check(writer->Write() == 1, "the first snapshot is written with ids");
  writer->SetFileName(withoutIds.c_str());
  writer->WriteIdsOff();
  Check(writer->Write() == 1, "and without");

  vtkNew<vtkGaussianSession> scene;
  scene->SetFileName(withIds.c_str());
  scene->ComputeScoresOff();
  scene->SetIdProperty("id");
  scene->GetSceneReader()->IdPropertyOptionalOn();
  scene->SetCompareFileName(log.c_str());
  scene->GetComparisonFilter()->SetMoveThreshold(thresholds.Move);
  scene->GetComparisonFilter()->SetOpacityThreshold(thresholds.Opacity);
  scene->GetComparisonFilter()->MeasureViewsOff();
  Check(scene->Update(vtkGaussianSession::ComparisonPort, nullptr) != 0 &&
      SameDifferences(scene->GetComparisonOutput(), expected),
    "a scene file with ids compared with the log gives the same rows");
  // (Measured above: here only which cameras the comparison takes.)
  vtkTable* taken = vtkTable::SafeDownCast(scene->GetComparisonFilter()->GetInputDataObject(2, 0));
  Check(taken && taken->GetNumberOfRows() == static_cast<vtkIdType>(cameras.size()) &&
      taken->GetValueByName(0, "Name").ToString() == cameras[0].Name,
    "a scene file without cameras is compared in the compared log's cameras");

  scene->SetFileName(withoutIds.c_str());
  Check(scene->Update(vtkGaussianSession::GaussiansPort, nullptr) != 0,
    "a scene without the optional id property is read");
  vtkDataArray* rows = scene->GetGaussiansOutput()->GetPointData()->GetArray("GaussianId");
  bool numbered = rows && rows->GetNumberOfTuples() == static_cast<vtkIdType>(first.Count);
  for (vtkIdType i = 0; numbered && i < rows->GetNumberOfTuples(); ++i)
  {
    numbered = rows->GetTuple1(i) == static_cast<double>(i);
  }
  Check(numbered, "its ids are its row numbers");
  scene->GetSceneReader()->IdPropertyOptionalOff();
  {
    ErrorText error(scene);
    Check(!scene->Update(vtkGaussianSession::GaussiansPort, nullptr) &&
        error.Text.find(withoutIds) != std::string::npos,
      "without IdPropertyOptional the missing id property is an error naming the file");
  }

  // The cameras of a scene given without them: cameras.json two folders up (the trainer's
  // <model>/point_cloud/iteration_N/), the one beside the scene first.
  const fs::path model = folder / "model";
  const fs::path iteration = model / "point_cloud" / "iteration_7";
  fs::create_directories(iteration);
  const std::string inModel = (iteration / "point_cloud.ply").string();
  fs::copy_file(withIds, inModel);
  Check(vtkGaussianCameraReader::FindSceneCamerasFile(inModel).empty(), "no cameras.json: none");
  const std::vector<vis4gs::Camera> some(cameras.begin(), cameras.begin() + 2);
  vis4gs::WriteCamerasJson((model / "cameras.json").string(), cameras);
  Check(
    fs::equivalent(vtkGaussianCameraReader::FindSceneCamerasFile(inModel), model / "cameras.json"),
    "cameras.json two folders up is found");
  vtkNew<vtkGaussianSession> trained;
  trained->SetFileName(inModel.c_str());
  trained->ComputeScoresOff();
  trained->GetCameraReader()->SetImageFolder("");
  Check(trained->Update(vtkGaussianSession::CamerasPort, nullptr) != 0 &&
      trained->GetCamerasOutput()->GetNumberOfRows() == static_cast<vtkIdType>(cameras.size()),
    "the session reads the cameras two folders up");
  vis4gs::WriteCamerasJson((iteration / "cameras.json").string(), some);
  Check(
    vtkGaussianCameraReader::FindSceneCamerasFile(inModel) == (iteration / "cameras.json").string(),
    "cameras.json beside the scene comes first");
  trained->Modified();
  Check(trained->Update(vtkGaussianSession::CamerasPort, nullptr) != 0 &&
      trained->GetCamerasOutput()->GetNumberOfRows() == 2,
    "the session reads the cameras beside the scene then");

  const std::string missing = (folder / "missing.ply").string();
  session->SetCompareFileName(missing.c_str());
  {
    ErrorText error(session);
    Check(!session->Update(vtkGaussianSession::ComparisonPort, nullptr) &&
        error.Text.find(missing + ": no such file") != std::string::npos &&
        error.Text.find(log + ": " + missing) == std::string::npos,
      "a missing second state is an error naming it, once");
  }

  // A damaged log keeps its name's kind: the log reader's error, not a scene reader's.
  const std::string damaged = (folder / "damaged.h5").string();
  {
    std::ofstream out(damaged, std::ios::binary);
    out << "not a training log at all\n";
  }
  Check(vtkGaussianSession::IsTrainingLogPath(damaged.c_str()) &&
      !vtkGaussianSession::IsTrainingLogFile(damaged.c_str()),
    "a .h5 without the HDF5 signature is read as a (damaged) log");
  vtkNew<vtkGaussianSession> broken;
  broken->SetFileName(damaged.c_str());
  {
    ErrorText error(broken);
    Check(!broken->Update(vtkGaussianSession::GaussiansPort, nullptr) &&
        broken->GetIsTrainingLog() && error.Text.find(damaged) != std::string::npos,
      "its update fails with an error naming it");
  }
  fs::remove_all(folder);
  return Check.ExitCode();
}

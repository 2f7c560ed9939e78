/*=========================================================================

  Program:   Vis4GS
  Module:    TestGaussianFineTuneFilter.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
// vtkGaussianFineTuneFilter (issue 20) on a planted case written as a training log (a wall
// whose colours are off from the images and a floater in front of one training view; Core's
// PlantedWallScene.h), read back with vtkGaussianTrainingLogReader: deleting the floater by id
// (source iteration from the reader's DATA_TIME_STEP) and by a mask array give the same
// result; the figures table equals Core's FineTune() on the same inputs, and has the expected
// direction (deleted > source, repaired > deleted in training PSNR); positions stay fixed;
// the log written holds the deletion as a prune event; progress events follow the
// iterations; AbortExecute from a progress observer leaves empty outputs and no log; a
// missing mask array is an error.
#include "vtkGaussianFineTuneFilter.h"

#include "FineTune.h"
#include "TrainingLogReader.h"
#include "TrainingLogWriter.h"
#include "Vis4GSDataModel.h"

#include "../../../../Core/Selection/Testing/PlantedWallScene.h"

#include "vtkCallbackCommand.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkGaussianTrainingLogReader.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkUnsignedCharArray.h"

#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace
{
namespace fs = std::filesystem;
int failures = 0;
void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++failures;
  }
}

struct Counter
{
  int Progress = 0;
  int Errors = 0;
  double AbortAt = 2; // progress at which to abort (> 1: never)
};
void OnEvent(vtkObject* caller, unsigned long event, void* clientData, void* callData)
{
  auto* c = static_cast<Counter*>(clientData);
  if (event == vtkCommand::ProgressEvent)
  {
    ++c->Progress;
    if (*static_cast<double*>(callData) >= c->AbortAt)
    {
      static_cast<vtkAlgorithm*>(caller)->AbortExecuteOn();
    }
  }
  c->Errors += event == vtkCommand::ErrorEvent ? 1 : 0;
}

// The planted scene as a training log: cameras, embedded 8-bit images, the snapshot of
// iteration 100.
void WriteLog(const vis4gs::plantedwall::PlantedScene& s, const std::string& path)
{
  vis4gs::TrainingLogWriterOptions options;
  options.Scene = "planted";
  options.ShDegree = 0;
  options.Iterations = 100;
  vis4gs::TrainingLogWriter writer(path, options);
  std::vector<vis4gs::Camera> cameras = s.Cameras;
  for (std::size_t v = 0; v < cameras.size(); ++v)
  {
    cameras[v].ImagePath = "/images/" + cameras[v].Name;
    std::vector<unsigned char> rgb(s.Targets[v].Pixels.size());
    for (std::size_t k = 0; k < rgb.size(); ++k)
    {
      rgb[k] = static_cast<unsigned char>(std::lround(s.Targets[v].Pixels[k] * 255.0f));
    }
    writer.WriteImage(cameras[v].Name, cameras[v].Width, cameras[v].Height, rgb.data());
  }
  writer.WriteCameras(cameras);
  writer.WriteSnapshot(100, s.Cloud);
  writer.Close();
}

bool SameTable(vtkTable* a, vtkTable* b)
{
  if (a->GetNumberOfRows() != b->GetNumberOfRows() ||
    a->GetNumberOfColumns() != b->GetNumberOfColumns())
  {
    return false;
  }
  for (vtkIdType c = 2; c < a->GetNumberOfColumns(); ++c)
  {
    for (vtkIdType r = 0; r < a->GetNumberOfRows(); ++r)
    {
      if (a->GetValue(r, c).ToDouble() != b->GetValue(r, c).ToDouble())
      {
        return false;
      }
    }
  }
  return true;
}
}

int TestGaussianFineTuneFilter(int, char*[])
{
  const vis4gs::plantedwall::PlantedScene s = vis4gs::plantedwall::MakePlantedScene();
  const fs::path folder = fs::temp_directory_path() /
    ("vis4gs-finetune-filter-" + std::to_string(static_cast<long>(::getpid())));
  fs::remove_all(folder);
  fs::create_directories(folder);
  const std::string logPath = (folder / "planted.h5").string();
  WriteLog(s, logPath);
  const std::int64_t floaterId = s.Cloud.GetId(s.Floater);

  vtkNew<vtkGaussianTrainingLogReader> reader;
  reader->SetFileName(logPath.c_str());
  Counter counter;
  vtkNew<vtkCallbackCommand> callback;
  callback->SetCallback(OnEvent);
  callback->SetClientData(&counter);

  // By id, the source iteration from the reader.
  vtkNew<vtkIdTypeArray> ids;
  ids->InsertNextValue(floaterId);
  vtkNew<vtkGaussianFineTuneFilter> byId;
  byId->SetInputConnection(0, reader->GetOutputPort(0));
  byId->SetCamerasConnection(reader->GetOutputPort(1));
  byId->SetRemovedIds(ids);
  byId->SetIterations(10);
  byId->SetNumberOfThreads(2);
  const std::string repairedLog = (folder / "repaired.h5").string();
  byId->SetOutputLogFileName(repairedLog.c_str());
  byId->AddObserver(vtkCommand::ProgressEvent, callback);
  byId->Update();
  Check(byId->GetNumberOfRemoved() == 1, "one Gaussian deleted");
  Check(byId->GetLastIteration() == 110, "iterations 101..110");
  Check(counter.Progress >= 10, "a progress event per iteration");
  vtkPolyData* repaired = byId->GetOutput();
  vtkTable* figures = byId->GetFiguresOutput();
  Check(repaired->GetNumberOfPoints() == static_cast<vtkIdType>(s.Cloud.Count - 1),
    "the repaired scene lacks the floater");
  auto* repairedIds =
    vtkIdTypeArray::SafeDownCast(repaired->GetPointData()->GetArray(vis4gs::arrays::GaussianId));
  Check(repairedIds && repairedIds->LookupValue(floaterId) < 0, "the floater's id is gone");
  bool fixed = repaired->GetNumberOfPoints() > 0;
  for (vtkIdType i = 0; fixed && i < repaired->GetNumberOfPoints(); ++i)
  {
    double p[3];
    repaired->GetPoint(i, p);
    for (int k = 0; k < 3; ++k)
    {
      fixed = fixed && p[k] == static_cast<double>(s.Cloud.Positions[3 * i + k]);
    }
  }
  Check(fixed, "positions fixed bit for bit");

  // The table: repair.csv's columns, means then views, and the direction.
  const std::vector<std::string>& columns = vis4gs::FineTuneFigureColumns();
  Check(figures->GetNumberOfColumns() == static_cast<vtkIdType>(columns.size()), "11 columns");
  for (std::size_t c = 0; c < columns.size() && c < 11; ++c)
  {
    Check(figures->GetColumnName(static_cast<vtkIdType>(c)) == columns[c], "column " + columns[c]);
  }
  Check(figures->GetNumberOfRows() == 5, "two means and three views");
  if (figures->GetNumberOfRows() == 5)
  {
    Check(figures->GetValueByName(0, "view").ToString() == "mean" &&
        figures->GetValueByName(0, "split").ToString() == "train",
      "first row: training mean");
    Check(figures->GetValueByName(4, "view").ToString() == "B", "last row: test view B");
    const double source = figures->GetValueByName(0, "psnr_source").ToDouble();
    const double deleted = figures->GetValueByName(0, "psnr_deleted").ToDouble();
    const double after = figures->GetValueByName(0, "psnr_repaired").ToDouble();
    Check(deleted > source, "deleting the floater raises the training PSNR");
    Check(after > deleted, "the fine-tune raises it further");
  }

  // The same as Core's FineTune() on the log's snapshot and images.
  {
    vis4gs::TrainingLogReader log(logPath);
    const vis4gs::GaussianCloud snapshot = log.ReadSnapshot(100);
    const std::vector<std::uint8_t> removed = s.FloaterMask();
    vis4gs::FineTuneOptions options;
    options.Iterations = 10;
    options.Threads = 2;
    const std::vector<vis4gs::Camera> cameras = log.ReadCameras();
    const vis4gs::FineTuneResult core = vis4gs::FineTune(
      snapshot,
      100,
      removed,
      cameras,
      [&log](std::size_t, const vis4gs::Camera& camera, vis4gs::Image& image)
      { return vis4gs::LoadCameraImage(&log, camera, image); },
      options);
    const auto rows = vis4gs::FineTuneFigureRows(core, cameras);
    bool same = static_cast<vtkIdType>(rows.size()) == figures->GetNumberOfRows();
    for (std::size_t r = 0; same && r < rows.size(); ++r)
    {
      for (std::size_t k = 0; k < 9; ++k)
      {
        same = same &&
          figures->GetValue(static_cast<vtkIdType>(r), static_cast<vtkIdType>(k + 2)).ToDouble() ==
            rows[r].Values[k];
      }
    }
    Check(same, "figures == Core FineTune()");
  }

  // The log: the deletion as one prune event at the source iteration.
  {
    vis4gs::TrainingLogReader log(repairedLog);
    const vis4gs::EventTable events = log.ReadEvents();
    Check(events.Size() == 1 && events.Iteration[0] == 100 && events.Parent[0] == floaterId &&
        events.Kind[0] == static_cast<std::uint8_t>(vis4gs::EventKind::Prune),
      "the log's only event is the floater's prune at iteration 100");
    Check(log.GetSnapshotIterations() == std::vector<int>({ 100, 110 }), "snapshots 100, 110");
  }

  // By a mask array on a copy (no DATA_TIME_STEP: SourceIteration set): the same figures.
  reader->Update(0);
  vtkNew<vtkPolyData> marked;
  marked->ShallowCopy(reader->GetOutputDataObject(0));
  vtkNew<vtkUnsignedCharArray> mask;
  mask->SetName("Floater");
  mask->SetNumberOfTuples(marked->GetNumberOfPoints());
  mask->Fill(0);
  mask->SetValue(static_cast<vtkIdType>(s.Floater), 1);
  marked->GetPointData()->AddArray(mask);
  vtkNew<vtkGaussianFineTuneFilter> byMask;
  byMask->SetInputData(0, marked);
  byMask->SetCamerasConnection(reader->GetOutputPort(1));
  byMask->SetRemovalArrayName("Floater");
  byMask->SetSourceIteration(100);
  byMask->SetIterations(10);
  byMask->SetNumberOfThreads(2);
  byMask->AddObserver(vtkCommand::ErrorEvent, callback);
  byMask->Update(1);
  Check(SameTable(byMask->GetFiguresOutput(), figures), "mask and ids give the same figures");
  Check(counter.Errors == 0, "no error with a mask");

  // A missing mask array is an error.
  byMask->SetRemovalArrayName("NoSuchArray");
  byMask->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, callback);
  byMask->Update();
  Check(counter.Errors > 0, "a missing mask array is an error");

  // Aborted from a progress observer: empty outputs, no log.
  Counter aborter;
  aborter.AbortAt = 0.3;
  vtkNew<vtkCallbackCommand> abortCallback;
  abortCallback->SetCallback(OnEvent);
  abortCallback->SetClientData(&aborter);
  vtkNew<vtkGaussianFineTuneFilter> aborted;
  aborted->SetInputConnection(0, reader->GetOutputPort(0));
  aborted->SetCamerasConnection(reader->GetOutputPort(1));
  aborted->SetRemovedIds(ids);
  aborted->SetIterations(10);
  aborted->SetNumberOfThreads(2);
  const std::string abortedLog = (folder / "aborted.h5").string();
  aborted->SetOutputLogFileName(abortedLog.c_str());
  aborted->AddObserver(vtkCommand::ProgressEvent, abortCallback);
  aborted->Update();
  Check(aborted->GetLastIteration() == 103, "aborted after the third iteration");
  Check(aborted->GetOutput()->GetNumberOfPoints() == 0, "aborted: no Gaussians");
  Check(aborted->GetFiguresOutput()->GetNumberOfRows() == 0, "aborted: no figures");
  Check(!fs::exists(abortedLog) && !fs::exists(folder / ".aborted.h5.partial"), "aborted: no log");

  std::ostringstream print;
  byId->Print(print);
  Check(print.str().find("OutputLogFileName: " + repairedLog) != std::string::npos &&
      print.str().find("RemovedIds: 1 ids") != std::string::npos &&
      print.str().find("WarmupIterations: 10") != std::string::npos,
    "PrintSelf");
  fs::remove_all(folder);
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

/*=========================================================================

  Program:   Vis4GS
  Module:    TestGaussianTrainingLogReader.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
// Writes a log with the Core writer and reads it through the VTK reader: time steps,
// nearest snapshot, lazily produced outputs, SH rest on demand, tables, property history
// and a clear error for a missing file.
#include "vtkGaussianTrainingLogReader.h"

#include "TrainingLogWriter.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTable.h"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <unistd.h>

#define CHECK(cond)                                                                                \
  do                                                                                               \
  {                                                                                                \
    if (!(cond))                                                                                   \
    {                                                                                              \
      std::cerr << "Check failed at line " << __LINE__ << ": " #cond << std::endl;                 \
      return EXIT_FAILURE;                                                                         \
    }                                                                                              \
  } while (0)

namespace
{
vis4gs::GaussianCloud Cloud(std::size_t n, int degree, float base)
{
  vis4gs::GaussianCloud c;
  c.Resize(n, degree);
  c.Ids.resize(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    c.Ids[i] = static_cast<std::int64_t>(2 * i);
    for (int k = 0; k < 3; ++k)
    {
      c.Positions[3 * i + k] = base + static_cast<float>(i) + 0.25f * k;
      c.LogScales[3 * i + k] = -3.0f - 0.01f * static_cast<float>(i);
    }
    for (int k = 0; k < 4; ++k)
    {
      c.Rotations[4 * i + k] = k == 0 ? 1.0f : 0.0f;
    }
    c.OpacityLogits[i] = base * 0.001f + static_cast<float>(i);
    for (std::size_t k = 0; k < 3 * static_cast<std::size_t>(c.ShCoefficientCount()); ++k)
    {
      c.SH[i * 3 * c.ShCoefficientCount() + k] = base + static_cast<float>(k);
    }
  }
  return c;
}
} // namespace

int TestGaussianTrainingLogReader(int, char*[])
{
  const std::string path = "/tmp/vis4gs_vtk_log_" + std::to_string(::getpid()) + ".h5";
  {
    vis4gs::TrainingLogWriter writer(path);
    vis4gs::Camera cam;
    cam.Name = "c0";
    cam.Width = 20;
    cam.Height = 10;
    cam.Fx = cam.Fy = 15;
    cam.Cx = 10;
    cam.Cy = 5;
    writer.WriteCameras({ cam });
    for (int it = 1; it <= 30; ++it)
    {
      vis4gs::MetricsRow row;
      row.Iteration = it * 100;
      row.Loss = 1.0 / it;
      row.NumGaussians = 10;
      writer.AppendMetrics(row);
    }
    vis4gs::MetricsRow test;
    test.Iteration = 1500;
    test.Psnr = 25.5;
    writer.AppendMetrics(test, true);
    test.Psnr = 26.0; // the same iteration measured twice: the merged table keeps the first
    writer.AppendMetrics(test, true);
    test.Iteration = 3050; // a test-only iteration
    test.Psnr = 27.0;
    writer.AppendMetrics(test, true);
    writer.AppendEvent({ 600, vis4gs::EventKind::Clone, 2, 20 });
    writer.AppendEvent({ 700, vis4gs::EventKind::Prune, 4, -1 });
    writer.WriteSnapshot(1000, Cloud(10, 3, 0.f));
    writer.WriteSnapshot(2000, Cloud(12, 3, 100.f));
    writer.WriteSnapshot(3000, Cloud(8, 3, 200.f));
  }

  vtkNew<vtkGaussianTrainingLogReader> reader;
  reader->SetFileName(path.c_str());
  reader->UpdateInformation();
  vtkInformation* info = reader->GetOutputInformation(0);
  CHECK(info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS()) == 3);
  CHECK(info->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS())[1] == 2000.0);
  CHECK(reader->GetNumberOfSnapshots() == 3 && reader->GetSnapshotIteration(2) == 3000);
  CHECK(reader->GetNumberOfLacks() == 0);
  CHECK(!reader->HasImages() && reader->GetNumberOfEmbeddedImages() == 0);
  CHECK(reader->HasCameras() && reader->HasMetrics() && reader->HasEvents());

  // Default: the last snapshot with the SH rest (as vis4gs analyze reads it); here DC only,
  // asked for; the tables are not read.
  CHECK(reader->GetLoadSHRest());
  reader->LoadSHRestOff();
  reader->Update(0);
  vtkPolyData* g = reader->GetGaussiansOutput();
  CHECK(reader->GetLoadedIteration() == 3000);
  CHECK(g->GetNumberOfPoints() == 8);
  CHECK(g->GetPointData()->GetArray("SH")->GetNumberOfComponents() == 3);
  CHECK(g->GetPointData()->GetArray("SH")->GetComponent(1, 2) == 202.f);
  CHECK(g->GetPointData()->GetPedigreeIds()->GetVariantValue(3).ToInt() == 6);
  CHECK(reader->GetSnapshotReads() == 1);
  CHECK(reader->GetEventsOutput()->GetNumberOfRows() == 0);

  // A requested time: the nearest snapshot (1600 -> 2000), with the SH rest on demand.
  reader->LoadSHRestOn();
  reader->UpdateTimeStep(1600);
  CHECK(reader->GetLoadedIteration() == 2000);
  CHECK(g->GetNumberOfPoints() == 12);
  CHECK(g->GetPointData()->GetArray("SH")->GetNumberOfComponents() == 48);
  CHECK(g->GetPointData()->GetArray("SH")->GetComponent(0, 47) == 147.f);
  CHECK(std::fabs(g->GetPoint(5)[0] - 105.0) < 1e-6);
  const int reads = reader->GetSnapshotReads();

  // Tables: updating them does not read the snapshot again.
  reader->Update(3);
  vtkTable* events = reader->GetEventsOutput();
  CHECK(events->GetNumberOfRows() == 2);
  CHECK(events->GetValueByName(0, "Child").ToInt() == 20);
  CHECK(events->GetValueByName(1, "Kind").ToInt() == 3);
  reader->Update(2);
  vtkTable* metrics = reader->GetMetricsOutput();
  CHECK(metrics->GetNumberOfRows() == 31);
  CHECK(metrics->GetValueByName(14, "Iteration").ToInt() == 1500);
  CHECK(metrics->GetValueByName(14, "TestPSNR").ToDouble() == 25.5);
  CHECK(std::isnan(metrics->GetValueByName(13, "TestPSNR").ToDouble()));
  CHECK(metrics->GetValueByName(30, "Iteration").ToInt() == 3050);
  CHECK(std::isnan(metrics->GetValueByName(30, "Loss").ToDouble()));
  // As logged (what `vis4gs compare` writes): every row, /metrics's then /metrics/test's, with
  // their Split; the second test row of 1500 too.
  reader->MetricsAsLoggedOn();
  reader->Update(2);
  metrics = reader->GetMetricsOutput();
  CHECK(metrics->GetNumberOfRows() == 33 && !metrics->GetColumnByName("TestPSNR"));
  CHECK(metrics->GetValueByName(29, "Iteration").ToInt() == 3000 &&
    metrics->GetValueByName(29, "Split").ToInt() == 0 &&
    std::fabs(metrics->GetValueByName(29, "Loss").ToDouble() - 1.0 / 30) < 1e-6);
  const int testRows[3][2] = { { 1500, 255 }, { 1500, 260 }, { 3050, 270 } };
  for (int r = 0; r < 3; ++r)
  {
    CHECK(metrics->GetValueByName(30 + r, "Split").ToInt() == 1 &&
      metrics->GetValueByName(30 + r, "Iteration").ToInt() == testRows[r][0] &&
      metrics->GetValueByName(30 + r, "PSNR").ToDouble() == testRows[r][1] / 10.0);
  }
  reader->MetricsAsLoggedOff();
  reader->Update(1);
  CHECK(reader->GetCamerasOutput()->GetNumberOfRows() == 1);
  CHECK(reader->GetSnapshotReads() == reads);
  CHECK(g->GetNumberOfPoints() == 12); // port 0 kept its data

  // Property history of ids 0, 4 (in all), 20 (only in the 2000 snapshot), 15 (never).
  vtkNew<vtkIdTypeArray> ids;
  for (vtkIdType id : { 0, 4, 20, 15 })
  {
    ids->InsertNextValue(id);
  }
  vtkNew<vtkTable> history;
  CHECK(reader->GetPropertyHistory(ids, history) == 1);
  CHECK(history->GetNumberOfRows() == 7);
  CHECK(history->GetValueByName(3, "GaussianId").ToInt() == 4);
  CHECK(history->GetValueByName(4, "Iteration").ToInt() == 2000);
  CHECK(history->GetValueByName(6, "GaussianId").ToInt() == 20);
  CHECK(history->GetValueByName(6, "Iteration").ToInt() == 2000);
  // Id 4 is row 2: opacity logit base*0.001 + 2 at iteration 2000.
  const float logit = 0.1f + 2.f;
  CHECK(history->GetValueByName(4, "OpacityLogit").ToFloat() == logit);
  CHECK(std::fabs(history->GetValueByName(4, "Opacity").ToDouble() -
          1.0 / (1.0 + std::exp(-logit))) < 1e-6);
  vtkDataArray* pos = vtkDataArray::SafeDownCast(history->GetColumnByName("Position"));
  CHECK(pos && pos->GetComponent(4, 1) == 102.25f);

  // A log with an embedded image: HasImages and its name (what a fine-tune of it embeds).
  const std::string withImage = path + ".image.h5";
  {
    vis4gs::TrainingLogWriter writer(withImage);
    const unsigned char rgb[2 * 3 * 3] = {};
    writer.WriteImage("c0", 3, 2, rgb);
    writer.WriteSnapshot(100, Cloud(4, 0, 0.f));
  }
  vtkNew<vtkGaussianTrainingLogReader> imaged;
  imaged->SetFileName(withImage.c_str());
  imaged->UpdateInformation();
  CHECK(imaged->HasImages());
  CHECK(imaged->GetNumberOfEmbeddedImages() == 1 &&
    std::string(imaged->GetEmbeddedImageName(0)) == "c0");
  std::ostringstream printed;
  imaged->Print(printed);
  CHECK(printed.str().find("HasImages: 1") != std::string::npos);
  std::remove(withImage.c_str());

  // A missing file: a clear error, no crash.
  vtkNew<vtkGaussianTrainingLogReader> missing;
  missing->SetFileName("/tmp/vis4gs-missing-log.h5");
  std::cout << "(an error about /tmp/vis4gs-missing-log.h5 is expected)" << std::endl;
  missing->GlobalWarningDisplayOff();
  missing->Update();
  CHECK(missing->GetNumberOfSnapshots() == 0);
  std::remove(path.c_str());
  return EXIT_SUCCESS;
}

/*=========================================================================

  Program:   Vis4GS
  Module:    TestGaussianPLYWriter.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
// vtkGaussianPLYWriter: reader -> writer reproduces the trainer's file byte for byte; added
// score arrays become extra PLY properties; ids, big-endian/ASCII; errors.
#include "vtkGaussianPLYWriter.h"
#include "vtkGaussianSceneReader.h"

#include "IOSceneTestUtils.h"
#include "Vis4GSDataModel.h"
#include "Vis4GSTestData.h"

#include "GaussianIO.h"

#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <cstring>
#include <fstream>
#include <iterator>

using iotest::Check;

namespace
{
std::vector<char> Bytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}
}

int TestGaussianPLYWriter(int, char*[])
{
  VIS4GS_SHARED_DATA_OR_SKIP();
  const std::string ply = vis4gs::testing::SharedDataPath(
    "inria_ply_tiny_kacytran/point_cloud/iteration_7000/point_cloud.ply");
  iotest::TempDir dir;
  vtkNew<vtkGaussianSceneReader> reader;
  reader->SetFileName(ply.c_str());
  reader->Update();

  vtkNew<vtkGaussianPLYWriter> writer;
  writer->SetInputConnection(reader->GetOutputPort());
  writer->SetFileName((dir / "same.ply").c_str());
  writer->Write();
  Check(Bytes(dir / "same.ply") == Bytes(ply), "read -> write gives the original bytes");

  // Scores added by a filter become extra properties of their type.
  vtkNew<vtkPolyData> scored;
  scored->ShallowCopy(reader->GetOutput());
  const vtkIdType n = scored->GetNumberOfPoints();
  vtkNew<vtkFloatArray> coverage;
  coverage->SetName(vis4gs::arrays::ViewCoverage);
  coverage->SetNumberOfValues(n);
  vtkNew<vtkIntArray> flag;
  flag->SetName("flag");
  flag->SetNumberOfValues(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    coverage->SetValue(i, static_cast<float>(i) / n);
    flag->SetValue(i, static_cast<int>(i % 3) - 1);
  }
  scored->GetPointData()->AddArray(coverage);
  scored->GetPointData()->AddArray(flag);
  for (int format : { vtkGaussianPLYWriter::BINARY_LITTLE_ENDIAN,
         vtkGaussianPLYWriter::BINARY_BIG_ENDIAN,
         vtkGaussianPLYWriter::ASCII })
  {
    writer->SetInputData(scored);
    writer->SetFileFormat(format);
    writer->WriteIdsOn();
    writer->SetFileName((dir / "scored.ply").c_str());
    writer->Write();
    vis4gs::GaussianReadOptions o;
    o.IdProperty = "id";
    const vis4gs::GaussianCloud back = vis4gs::ReadGaussianPly(dir / "scored.ply", o);
    const vis4gs::GaussianCloud orig = vis4gs::ReadGaussianPly(ply);
    const std::string tag = " (format " + std::to_string(format) + ")";
    Check(back.Count == 9080, "count" + tag);
    Check(
      back.SH == orig.SH && back.LogScales == orig.LogScales && back.Positions == orig.Positions,
      "parameters" + tag);
    Check(back.Ids.size() == 9080 && back.Ids[9079] == 9079, "ids written" + tag);
    const vis4gs::ExtraProperty* vc = back.FindExtra(vis4gs::arrays::ViewCoverage);
    const vis4gs::ExtraProperty* fl = back.FindExtra("flag");
    Check(vc && vc->Type == vis4gs::ScalarType::Float32 && vc->GetAsDouble(4540) == 0.5,
      "ViewCoverage extra" + tag);
    Check(
      fl && fl->Type == vis4gs::ScalarType::Int32 && fl->GetAsDouble(3) == -1, "int extra" + tag);
    Check(back.FindExtra(vis4gs::arrays::Opacity) == nullptr, "activated arrays not written" + tag);
  }

  // By the file name, glTF (issue 34): the scores kept as attributes, SH and positions exact,
  // the ids as float32 (exact below 2^24), the measured error in the report.
  writer->SetFileFormat(vtkGaussianPLYWriter::BINARY_LITTLE_ENDIAN);
  writer->SetFileName((dir / "scored.glb").c_str());
  writer->Write();
  {
    const vis4gs::GaussianCloud back = vis4gs::ReadGaussianScene(dir / "scored.glb");
    const vis4gs::GaussianCloud orig = vis4gs::ReadGaussianPly(ply);
    const vis4gs::ExtraProperty* vc = back.FindExtra(vis4gs::arrays::ViewCoverage);
    const vis4gs::ExtraProperty* id = back.FindExtra("id");
    Check(back.Count == 9080 && back.SH == orig.SH && back.Positions == orig.Positions,
      "glTF: SH and positions exact");
    Check(vc && vc->GetAsDouble(4540) == 0.5 && id && id->GetAsDouble(9079) == 9079,
      "glTF: scores and ids kept");
    Check(
      std::string(writer->GetWriteReport()).find("9080 Gaussians written; quantisation error") !=
        std::string::npos,
      std::string("glTF: the write report: ") + writer->GetWriteReport());
  }

  // Errors: unwritable folder, input without points.
  vtkNew<iotest::MessageObserver> errors;
  writer->AddObserver(vtkCommand::ErrorEvent, errors);
  writer->SetFileName("/nonexistent-folder/x.ply");
  writer->Write();
  Check(errors->ErrorContains("/nonexistent-folder/x.ply"), "error names the file");
  errors->Errors.clear();
  vtkNew<vtkPolyData> empty;
  writer->SetInputData(empty);
  writer->SetFileName((dir / "empty.ply").c_str());
  writer->Write();
  Check(errors->ErrorContains("no points"), "input without points");
  return iotest::Failures() ? EXIT_FAILURE : EXIT_SUCCESS;
}

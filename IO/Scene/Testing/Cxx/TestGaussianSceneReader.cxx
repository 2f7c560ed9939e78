/*=========================================================================

  Program:   Vis4GS
  Module:    TestGaussianSceneReader.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
// vtkGaussianSceneReader on the real INRIA PLY and .splat files: array layout of DESIGN §2,
// bit-exact values against the Core reader, options, and errors/warnings.
#include "vtkGaussianSceneReader.h"

#include "IOSceneTestUtils.h"
#include "Vis4GSDataModel.h"
#include "Vis4GSTestData.h"

#include "GaussianIO.h"

#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <cmath>
#include <cstring>
#include <limits>

using iotest::Check;

namespace
{
bool SameFloats(vtkDataArray* a, const std::vector<float>& v)
{
  auto* f = vtkFloatArray::SafeDownCast(a);
  return f && static_cast<std::size_t>(f->GetNumberOfValues()) == v.size() &&
    (v.empty() || std::memcmp(f->GetPointer(0), v.data(), 4 * v.size()) == 0);
}
}

int TestGaussianSceneReader(int, char*[])
{
  VIS4GS_SHARED_DATA_OR_SKIP();
  const std::string ply = vis4gs::testing::SharedDataPath(
    "inria_ply_tiny_kacytran/point_cloud/iteration_7000/point_cloud.ply");
  const vis4gs::GaussianCloud core = vis4gs::ReadGaussianPly(ply);

  vtkNew<vtkGaussianSceneReader> reader;
  reader->SetFileName(ply.c_str());
  reader->Update();
  vtkPolyData* pd = reader->GetOutput();
  Check(pd->GetNumberOfPoints() == 9080, "9080 Gaussians");
  Check(reader->GetFileSHDegree() == 3, "file SH degree 3");
  Check(std::string(reader->GetFileFormat()) == "binary_little_endian", "format");
  Check(reader->GetNumberOfNonFiniteGaussians() == 0, "no NaN");
  Check(SameFloats(pd->GetPoints()->GetData(), core.Positions), "points bit-exact");
  vtkPointData* d = pd->GetPointData();
  Check(SameFloats(d->GetArray(vis4gs::arrays::LogScale), core.LogScales), "LogScale");
  Check(SameFloats(d->GetArray(vis4gs::arrays::Rotation), core.Rotations), "Rotation");
  Check(SameFloats(d->GetArray(vis4gs::arrays::OpacityLogit), core.OpacityLogits), "OpacityLogit");
  Check(SameFloats(d->GetArray(vis4gs::arrays::SH), core.SH), "SH");
  Check(d->GetArray(vis4gs::arrays::SH)->GetNumberOfComponents() == 48, "SH has 48 components");
  Check(d->GetArray(vis4gs::arrays::Rotation)->GetNumberOfComponents() == 4, "Rotation 4");
  Check(d->GetArray("nx") != nullptr && d->GetArray("nz") != nullptr, "normals kept as arrays");
  vtkDataArray* ids = vtkDataArray::SafeDownCast(d->GetPedigreeIds());
  Check(ids && std::string(ids->GetName()) == vis4gs::arrays::GaussianId, "GaussianId pedigree");
  Check(ids && ids->GetTuple1(9079) == 9079, "ids are row indices");
  // Activated arrays from the raw values (independent: textbook sigmoid / exp in double).
  vtkDataArray* opacity = d->GetArray(vis4gs::arrays::Opacity);
  vtkDataArray* scale = d->GetArray(vis4gs::arrays::Scale);
  Check(opacity && scale, "activated arrays present");
  if (opacity && scale)
  {
    double maxErr = 0;
    for (vtkIdType i = 0; i < 9080; i += 13)
    {
      const double o = 1.0 / (1.0 + std::exp(-static_cast<double>(core.OpacityLogits[i])));
      maxErr = std::max(maxErr, std::fabs(opacity->GetTuple1(i) - o));
      const double s = std::exp(static_cast<double>(core.LogScales[3 * i + 1]));
      maxErr = std::max(maxErr, std::fabs(scale->GetComponent(i, 1) - s) / s);
    }
    Check(maxErr < 1e-6, "activated values");
  }

  // Options: SH degree 1, no extras, no activated arrays.
  reader->SetMaxSHDegree(1);
  reader->LoadExtrasOff();
  reader->ActivatedArraysOff();
  reader->Update();
  d = reader->GetOutput()->GetPointData();
  Check(d->GetArray(vis4gs::arrays::SH)->GetNumberOfComponents() == 12, "SH degree 1: 12");
  Check(d->GetArray(vis4gs::arrays::SH)->GetComponent(5, 11) == core.SH[48 * 5 + 11],
    "SH degree 1 values");
  Check(d->GetArray("nx") == nullptr, "extras left out");
  Check(d->GetArray(vis4gs::arrays::Opacity) == nullptr, "activated arrays left out");
  reader->LoadSHOff();
  reader->LoadScalesOff();
  reader->Update();
  d = reader->GetOutput()->GetPointData();
  Check(d->GetArray(vis4gs::arrays::SH) == nullptr, "SH left out");
  Check(d->GetArray(vis4gs::arrays::LogScale) == nullptr, "scales left out");
  Check(d->GetArray(vis4gs::arrays::Rotation) != nullptr, "rotations still read");

  // .splat by extension.
  vtkNew<vtkGaussianSceneReader> splat;
  splat->SetFileName(
    vis4gs::testing::SharedDataPath("inria_ply_tiny_kacytran/model_1.splat").c_str());
  splat->Update();
  Check(splat->GetOutput()->GetNumberOfPoints() == 22764, "22764 splats");
  Check(std::string(splat->GetFileFormat()) == "splat", "splat format");
  Check(
    splat->GetOutput()->GetPointData()->GetArray(vis4gs::arrays::SH)->GetNumberOfComponents() == 3,
    "splat SH degree 0");

  // SPZ by content (issue 19): the real PLY written as SPZ v4 by the Core writer and read
  // back through the VTK reader, equal to the Core SPZ reader's values.
  iotest::TempDir dir;
  vis4gs::WriteSpz(dir / "inria.spz", core);
  const vis4gs::GaussianCloud spzCore = vis4gs::ReadSpz(dir / "inria.spz");
  vtkNew<vtkGaussianSceneReader> spz;
  spz->SetFileName((dir / "inria.spz").c_str());
  spz->Update();
  Check(std::string(spz->GetFileFormat()) == "spz v4", "spz format");
  Check(spz->GetFileSHDegree() == 3, "spz SH degree 3");
  vtkPointData* sd = spz->GetOutput()->GetPointData();
  Check(spz->GetOutput()->GetNumberOfPoints() == static_cast<vtkIdType>(core.Count) &&
      SameFloats(sd->GetArray(vis4gs::arrays::LogScale), spzCore.LogScales) &&
      SameFloats(sd->GetArray(vis4gs::arrays::SH), spzCore.SH) &&
      SameFloats(sd->GetArray(vis4gs::arrays::Rotation), spzCore.Rotations),
    "spz arrays equal to the Core reader's");

  // glTF KHR_gaussian_splatting by content (issue 34): the real PLY as a GLB, extras (the
  // normals) kept as application-specific attributes, read as the Core reader reads it.
  vis4gs::WriteGltf(dir / "inria.glb", core);
  const vis4gs::GaussianCloud gltfCore = vis4gs::ReadGltf(dir / "inria.glb");
  vtkNew<vtkGaussianSceneReader> gltf;
  gltf->SetFileName((dir / "inria.glb").c_str());
  gltf->Update();
  Check(std::string(gltf->GetFileFormat()) == "gltf", "glTF format");
  vtkPointData* gd = gltf->GetOutput()->GetPointData();
  Check(gltf->GetOutput()->GetNumberOfPoints() == static_cast<vtkIdType>(core.Count) &&
      SameFloats(gd->GetArray(vis4gs::arrays::SH), core.SH) &&
      SameFloats(gd->GetArray(vis4gs::arrays::Rotation), gltfCore.Rotations) &&
      SameFloats(gd->GetArray(vis4gs::arrays::LogScale), gltfCore.LogScales) &&
      gd->GetArray("nx") != nullptr,
    "glTF arrays equal to the Core reader's, SH as the PLY's");

  // A compressed PLY, whatever its name: recognised by content, decoded as the Core reader.
  vis4gs::WriteCompressedPly(dir / "scene.bin", core);
  const vis4gs::GaussianCloud compressed = vis4gs::ReadCompressedPly(dir / "scene.bin");
  vtkNew<vtkGaussianSceneReader> comp;
  comp->SetFileName((dir / "scene.bin").c_str());
  comp->Update();
  Check(std::string(comp->GetFileFormat()) == "compressed_ply", "compressed PLY format");
  Check(comp->GetOutput()->GetNumberOfPoints() == static_cast<vtkIdType>(core.Count),
    "every Gaussian of the compressed PLY");
  Check(SameFloats(comp->GetOutput()->GetPointData()->GetArray(vis4gs::arrays::Rotation),
          compressed.Rotations) &&
      SameFloats(comp->GetOutput()->GetPointData()->GetArray(vis4gs::arrays::SH), compressed.SH),
    "compressed PLY values as the Core reader");

  // .ksplat by content (issue 19), whatever the name: one level-0 record built from the
  // layout (4096-byte header, one 1024-byte section header, 44 bytes of float32 / RGBA).
  std::vector<unsigned char> ksplat(4096 + 1024 + 44, 0);
  const auto putU32 = [&ksplat](std::size_t at, std::uint32_t v)
  { std::memcpy(ksplat.data() + at, &v, 4); }; // little-endian hosts only, as VTK's tests
  ksplat[1] = 1;                               // version 0.1
  for (std::size_t at : { 4, 8, 12, 16, 4096, 4100 })
  {
    putU32(at, 1); // one section, one splat
  }
  const float record[10] = { 1.f, 2.f, 3.f, 0.5f, 0.5f, 0.5f, 1.f, 0.f, 0.f, 0.f };
  std::memcpy(ksplat.data() + 5120, record, sizeof(record));
  ksplat[5160 + 3] = 255; // black, opaque
  FILE* kf = std::fopen((dir / "scene.dat").c_str(), "wb");
  std::fwrite(ksplat.data(), 1, ksplat.size(), kf);
  std::fclose(kf);
  vtkNew<vtkGaussianSceneReader> ks;
  ks->SetFileName((dir / "scene.dat").c_str());
  ks->Update();
  vtkPolyData* kout = ks->GetOutput();
  Check(std::string(ks->GetFileFormat()) == "ksplat" && kout->GetNumberOfPoints() == 1 &&
      kout->GetPoint(0)[2] == 3.0 &&
      std::abs(kout->GetPointData()->GetArray(vis4gs::arrays::LogScale)->GetComponent(0, 1) -
        std::log(0.5)) < 1e-6,
    "ksplat read by content");

  // NaN values: kept, counted, one warning.
  vis4gs::GaussianCloud bad = core;
  bad.OpacityLogits[3] = std::numeric_limits<float>::quiet_NaN();
  bad.Positions[3 * 7] = std::numeric_limits<float>::infinity();
  vis4gs::WriteGaussianPly(dir / "nan.ply", bad);
  vtkNew<iotest::MessageObserver> messages;
  vtkNew<vtkGaussianSceneReader> nanReader;
  messages->Watch(nanReader);
  nanReader->SetFileName((dir / "nan.ply").c_str());
  nanReader->Update();
  Check(nanReader->GetNumberOfNonFiniteGaussians() == 2, "2 non-finite Gaussians");
  Check(messages->Warnings.size() == 1 &&
      messages->Warnings[0].find("2 Gaussians hold NaN") != std::string::npos,
    "one NaN warning");
  Check(
    std::isnan(
      nanReader->GetOutput()->GetPointData()->GetArray(vis4gs::arrays::OpacityLogit)->GetTuple1(3)),
    "NaN kept");
  Check(messages->Errors.empty(), "no error for NaN");

  // Errors: missing file, truncated file; the request fails with a message naming the file.
  vtkNew<vtkGaussianSceneReader> missing;
  vtkNew<iotest::MessageObserver> errors;
  errors->Watch(missing);
  missing->SetFileName((dir / "missing.ply").c_str());
  missing->Update();
  Check(errors->ErrorContains(dir / "missing.ply"), "error names the missing file");
  const auto bytes = vis4gs::WriteGaussianPlyToMemory(core);
  FILE* f = std::fopen((dir / "cut.ply").c_str(), "wb");
  std::fwrite(bytes.data(), 1, bytes.size() / 2, f);
  std::fclose(f);
  errors->Errors.clear();
  missing->SetFileName((dir / "cut.ply").c_str());
  missing->Update();
  Check(errors->ErrorContains("cut.ply: header declares 9080 vertices"), "truncated file error");
  Check(missing->GetOutput()->GetNumberOfPoints() == 0, "empty output after an error");
  return iotest::Failures() ? EXIT_FAILURE : EXIT_SUCCESS;
}

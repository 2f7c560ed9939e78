/*=========================================================================

  Program:   Vis4GS
  Module:    TestVis4GSDataModel.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
// Round trips of the Gaussian and camera data model through VTK (DESIGN §2).
#include "Vis4GSDataModel.h"

#include "vtkDataArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTable.h"

#include "Vis4GSTestCheck.h"

#include <cmath>
#include <cstring>
#include <iostream>
#include <limits>
#include <utility>

namespace
{
vis4gs::testing::CheckCounter Check;

bool SameBits(const std::vector<float>& a, const std::vector<float>& b)
{
  return a.size() == b.size() && (a.empty() || !std::memcmp(a.data(), b.data(), 4 * a.size()));
}
}

int TestVis4GSDataModel(int, char*[])
{
  vis4gs::GaussianCloud cloud;
  cloud.Resize(4, 1);
  for (std::size_t i = 0; i < cloud.Positions.size(); ++i)
  {
    cloud.Positions[i] = 0.1f * static_cast<float>(i) - 0.3f;
  }
  for (std::size_t i = 0; i < cloud.SH.size(); ++i)
  {
    cloud.SH[i] = std::sin(static_cast<float>(i));
  }
  cloud.LogScales = { -1000.f, 0.f, 1000.f, -2.f, -2.f, -2.f, 1.f, 2.f, 3.f, 0.f, 0.f, 0.f };
  cloud.Rotations = { 1, 0, 0, 0, 0, 0, 0, 0, 0.5f, 0.5f, 0.5f, 0.5f, 2, 0, 0, 0 };
  cloud.OpacityLogits = { -1000.f, 1000.f, std::numeric_limits<float>::quiet_NaN(), 0.f };
  cloud.Ids = { 7, 9, 12, 40 };
  vis4gs::ExtraProperty nx;
  nx.Name = "nx";
  nx.Type = vis4gs::ScalarType::UInt8;
  nx.Bytes = { 1, 2, 3, 255 };
  cloud.Extra.push_back(nx);

  vtkNew<vtkPolyData> pd;
  vis4gs::GaussianCloudToPolyData(cloud, pd);
  Check(pd->GetNumberOfPoints() == 4, "point count");
  Check(pd->GetPointData()->GetPedigreeIds() != nullptr, "pedigree ids set");
  Check(pd->GetPointData()->GetArray("SH")->GetNumberOfComponents() == 12, "SH components");
  vtkDataArray* opacity = pd->GetPointData()->GetArray("Opacity");
  Check(opacity && opacity->GetTuple1(0) == 0.0 && opacity->GetTuple1(1) == 1.0,
    "opacity saturates at logits of +-1000");
  vtkDataArray* scale = pd->GetPointData()->GetArray("Scale");
  Check(scale && std::isfinite(scale->GetComponent(0, 2)) && scale->GetComponent(0, 0) == 0.0,
    "scale of log-scale +-1000 is finite");

  vis4gs::GaussianCloud back;
  std::string error;
  Check(vis4gs::PolyDataToGaussianCloud(pd, back, &error, true), error.c_str());
  Check(back.Count == 4 && back.ShDegree == 1, "count and degree");
  Check(SameBits(back.Positions, cloud.Positions), "positions bit-exact");
  Check(SameBits(back.SH, cloud.SH), "SH bit-exact");
  Check(SameBits(back.OpacityLogits, cloud.OpacityLogits), "opacity logits bit-exact (NaN)");
  Check(back.Ids == cloud.Ids, "ids");
  Check(back.Extra.size() == 1 && back.Extra[0].Bytes == nx.Bytes &&
      back.Extra[0].Type == vis4gs::ScalarType::UInt8,
    "extra property kept with its type");

  // Adopting (the readers' way): the same arrays, bit for bit and in the same order, in the
  // very memory of the cloud's vectors (no copy), freed with the arrays.
  {
    vis4gs::GaussianCloud moved = cloud;
    const float* positions = moved.Positions.data();
    const float* sh = moved.SH.data();
    const std::int64_t* ids = moved.Ids.data();
    vtkNew<vtkPolyData> adopted;
    vis4gs::GaussianCloudToPolyData(std::move(moved), adopted);
    Check(adopted->GetPoints()->GetData()->GetVoidPointer(0) == positions &&
        adopted->GetPointData()->GetArray("SH")->GetVoidPointer(0) == sh &&
        adopted->GetPointData()->GetArray("GaussianId")->GetVoidPointer(0) == ids,
      "the positions, SH and ids are adopted, not copied");
    Check(moved.Count == 0 && moved.Positions.empty(), "the moved-from cloud is empty");
    Check(adopted->GetPointData()->GetNumberOfArrays() == pd->GetPointData()->GetNumberOfArrays(),
      "adopting gives as many arrays");
    for (int a = 0; a < pd->GetPointData()->GetNumberOfArrays(); ++a)
    {
      vtkDataArray* copied = pd->GetPointData()->GetArray(a);
      vtkDataArray* taken = adopted->GetPointData()->GetArray(a);
      const bool same = taken && !std::strcmp(copied->GetName(), taken->GetName()) &&
        copied->GetDataType() == taken->GetDataType() &&
        copied->GetNumberOfComponents() == taken->GetNumberOfComponents() &&
        copied->GetNumberOfTuples() == taken->GetNumberOfTuples() &&
        !std::memcmp(copied->GetVoidPointer(0),
          taken->GetVoidPointer(0),
          static_cast<std::size_t>(copied->GetDataSize()) *
            static_cast<std::size_t>(copied->GetDataTypeSize()));
      Check(same, copied->GetName());
    }
    // The memory lives as long as the array, not the cloud; shallow copies share it.
    vtkNew<vtkPolyData> copy;
    copy->ShallowCopy(adopted);
    adopted->Initialize();
    vis4gs::GaussianCloud again;
    Check(vis4gs::PolyDataToGaussianCloud(copy, again, &error, true) &&
        SameBits(again.Positions, cloud.Positions) && SameBits(again.SH, cloud.SH) &&
        again.Ids == cloud.Ids,
      "adopted values survive their first owner");
    std::vector<std::int64_t> big(1000, 5);
    auto ints = vis4gs::AdoptVector<vtkIdTypeArray>("Parent", std::move(big), 2);
    Check(ints->GetNumberOfTuples() == 500 && ints->GetNumberOfComponents() == 2 &&
        ints->GetValue(999) == 5 && big.empty(),
      "AdoptVector: tuples of the given components");
  }

  // One copy (issue 22): the Core form of an adopting polydata is its arrays' own memory, the
  // same as a conversion would give; shallow copies keep it; any array that stops being the
  // cloud's vector (replaced, deep-copied, removed, reallocated) makes it a conversion again.
  {
    vtkNew<vtkPolyData> one;
    vis4gs::GaussianCloud moved = cloud;
    vis4gs::GaussianCloudToPolyData(std::move(moved), one);
    vis4gs::GaussianCloud converted;
    Check(vis4gs::PolyDataToGaussianCloud(one, converted, &error), error.c_str());
    auto shared = vis4gs::SharedGaussianCloud(one);
    Check(shared != nullptr, "an adopting polydata has a shared cloud");
    if (shared)
    {
      Check(shared->Positions.data() == one->GetPoints()->GetData()->GetVoidPointer(0) &&
          shared->Rotations.data() == one->GetPointData()->GetArray("Rotation")->GetVoidPointer(0),
        "the shared cloud is the arrays' memory");
      Check(shared->Count == converted.Count && shared->ShDegree == converted.ShDegree &&
          SameBits(shared->Positions, converted.Positions) &&
          SameBits(shared->LogScales, converted.LogScales) &&
          SameBits(shared->Rotations, converted.Rotations) &&
          SameBits(shared->OpacityLogits, converted.OpacityLogits) &&
          SameBits(shared->SH, converted.SH) && shared->Ids == converted.Ids &&
          shared->Extra.empty() && shared->Ids == cloud.Ids,
        "the shared cloud equals the conversion (without extras)");
      Check(vis4gs::GaussianCloudOf(one, &error) == shared, "GaussianCloudOf gives it");
      // Written through the array: the cloud is the same memory.
      one->GetPointData()->GetArray("OpacityLogit")->SetComponent(3, 0, 2.5);
      Check(shared->OpacityLogits[3] == 2.5f, "a value written into an array is the cloud's");
    }
    vtkNew<vtkPolyData> shallow;
    shallow->ShallowCopy(one);
    Check(vis4gs::SharedGaussianCloud(shallow) == shared, "a shallow copy shares it");
    vtkNew<vtkPolyData> deep;
    deep->DeepCopy(one);
    Check(!vis4gs::SharedGaussianCloud(deep), "a deep copy is not the shared cloud");
    auto copied = vis4gs::GaussianCloudOf(deep, &error);
    Check(copied && copied != shared && SameBits(copied->SH, cloud.SH) &&
        copied->Positions.data() != deep->GetPoints()->GetData()->GetVoidPointer(0),
      "GaussianCloudOf converts a deep copy");
    shallow->GetPointData()->RemoveArray("Rotation");
    Check(!vis4gs::SharedGaussianCloud(shallow), "a removed array is not the shared cloud's");
    // The storage outlives the polydata while the cloud is held, and the reverse.
    one->Initialize();
    Check(shared && SameBits(shared->SH, cloud.SH), "the held cloud survives its polydata");
    shared.reset();
    vis4gs::GaussianCloud fromShallow;
    Check(vis4gs::PolyDataToGaussianCloud(deep, fromShallow, &error) &&
        SameBits(fromShallow.Positions, cloud.Positions),
      "the deep copy is intact");
    const auto* kept =
      static_cast<const float*>(shallow->GetPointData()->GetArray("SH")->GetVoidPointer(0));
    Check(SameBits(std::vector<float>(kept, kept + cloud.SH.size()), cloud.SH),
      "the arrays survive the released cloud");
    // Reallocated by VTK (a resize): no longer the cloud's memory.
    vtkNew<vtkPolyData> grown;
    grown->ShallowCopy(deep);
    vis4gs::GaussianCloud noIds = cloud;
    noIds.Ids.clear();
    noIds.Extra.clear();
    vis4gs::GaussianCloudToPolyData(std::move(noIds), grown);
    auto identity = vis4gs::SharedGaussianCloud(grown);
    Check(identity && identity->Ids == std::vector<std::int64_t>({ 0, 1, 2, 3 }) &&
        grown->GetPointData()->GetArray("GaussianId")->GetTuple1(3) == 3.0,
      "a cloud without ids shares the ids 0..n-1");
    grown->GetPointData()->GetArray("LogScale")->Resize(100);
    Check(!vis4gs::SharedGaussianCloud(grown), "a reallocated array is not the cloud's");
  }

  // A wrong component count is refused with a message naming the array.
  pd->GetPointData()->GetArray("Rotation")->SetNumberOfComponents(3);
  Check(!vis4gs::PolyDataToGaussianCloud(pd, back, &error) &&
      error.find("Rotation") != std::string::npos,
    "bad Rotation array refused");

  std::vector<vis4gs::Camera> cameras(2);
  cameras[0].Name = "a";
  cameras[0].Width = 640;
  cameras[0].Height = 480;
  cameras[0].Fx = 500;
  cameras[0].Fy = 501;
  cameras[0].Cx = 320;
  cameras[0].Cy = 240;
  cameras[0].Model = "SIMPLE_RADIAL";
  cameras[0].Distortion = { 0.01 };
  cameras[1] = cameras[0];
  cameras[1].Name = "b";
  cameras[1].Split = vis4gs::CameraSplit::Test;
  cameras[1].WorldToCamera[3] = 2.5;
  cameras[1].Distortion.clear();
  vtkNew<vtkTable> table;
  vis4gs::CamerasToTable(cameras, table);
  std::vector<vis4gs::Camera> cameras2;
  Check(vis4gs::TableToCameras(table, cameras2, &error), error.c_str());
  Check(cameras2.size() == 2 && cameras2[1].Name == "b" &&
      cameras2[1].Split == vis4gs::CameraSplit::Test && cameras2[1].WorldToCamera[3] == 2.5 &&
      cameras2[0].Distortion.size() == 1 && cameras2[1].Distortion.empty() && cameras2[0].Fy == 501,
    "camera round trip");
  // The first training camera: row 0 here; row 1 once the test camera comes first; row 0 when
  // every camera is a test camera; -1 for an empty table.
  Check(vis4gs::FirstTrainingCamera(table) == 0, "first training camera, train first");
  std::swap(cameras[0], cameras[1]);
  vtkNew<vtkTable> testFirst;
  vis4gs::CamerasToTable(cameras, testFirst);
  Check(vis4gs::FirstTrainingCamera(testFirst) == 1, "first training camera after a test camera");
  cameras[1].Split = vis4gs::CameraSplit::Test;
  vtkNew<vtkTable> allTest;
  vis4gs::CamerasToTable(cameras, allTest);
  Check(vis4gs::FirstTrainingCamera(allTest) == 0, "no training camera: the first row");
  vtkNew<vtkTable> empty;
  Check(vis4gs::FirstTrainingCamera(empty) == -1 && vis4gs::FirstTrainingCamera(nullptr) == -1,
    "no camera: -1");
  table->RemoveColumnByName("Fx");
  Check(!vis4gs::TableToCameras(table, cameras2, &error) && error.find("Fx") != std::string::npos,
    "missing column named");
  return Check.ExitCode();
}

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
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkTable.h"

#include <cmath>
#include <cstring>
#include <iostream>
#include <limits>

namespace
{
int failures = 0;
void Check(bool ok, const char* what)
{
  if (!ok)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++failures;
  }
}

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
  table->RemoveColumnByName("Fx");
  Check(!vis4gs::TableToCameras(table, cameras2, &error) && error.find("Fx") != std::string::npos,
    "missing column named");
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

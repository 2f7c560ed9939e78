/*=========================================================================

  Program:   Vis4GS
  Module:    TestGaussianRasterizer.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
// vtkGaussianRasterizer against Core's Rasterize(): same values, rows flipped, size override,
// camera by name, double precision, and errors for a bad camera.
#include "vtkGaussianRasterizer.h"

#include "GaussianIO.h"
#include "Rasterizer.h"
#include "Vis4GSDataModel.h"
#include "Vis4GSTestData.h"

#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkTable.h"
#include "vtkTestErrorObserver.h"

#include "Vis4GSTestCheck.h"

#include <cmath>
#include <iostream>

namespace
{

vis4gs::testing::CheckCounter Check;

vis4gs::Camera MakeCamera(const std::string& name, int w, int h, double f, double tz)
{
  vis4gs::Camera c;
  c.Name = name;
  c.Width = w;
  c.Height = h;
  c.Fx = c.Fy = f;
  c.Cx = w / 2.0;
  c.Cy = h / 2.0;
  c.WorldToCamera[11] = tz; // camera looks down +z; the scene is moved tz in front
  return c;
}

template <typename T>
bool SameAsCore(vtkImageData* out, const vis4gs::RasterImage<T>& ref)
{
  int dims[3];
  out->GetDimensions(dims);
  if (dims[0] != ref.Width || dims[1] != ref.Height || dims[2] != 1)
  {
    return false;
  }
  vtkDataArray* rgb = out->GetPointData()->GetArray("RGB");
  vtkDataArray* alpha = out->GetPointData()->GetArray("Alpha");
  vtkDataArray* depth = out->GetPointData()->GetArray("Depth");
  vtkDataArray* contrib = out->GetPointData()->GetArray("Contributors");
  if (!rgb || !alpha || !depth || !contrib || rgb->GetNumberOfComponents() != 3)
  {
    return false;
  }
  for (int j = 0; j < ref.Height; ++j)
  {
    for (int x = 0; x < ref.Width; ++x)
    {
      const std::size_t src = static_cast<std::size_t>(ref.Height - 1 - j) * ref.Width + x;
      const vtkIdType dst = static_cast<vtkIdType>(j) * ref.Width + x;
      for (int c = 0; c < 3; ++c)
      {
        if (rgb->GetComponent(dst, c) != static_cast<double>(ref.Color[3 * src + c]))
        {
          return false;
        }
      }
      if (alpha->GetComponent(dst, 0) != static_cast<double>(ref.Alpha[src]) ||
        depth->GetComponent(dst, 0) != static_cast<double>(ref.Depth[src]) ||
        contrib->GetComponent(dst, 0) != ref.Contributors[src])
      {
        return false;
      }
    }
  }
  return true;
}

} // namespace

int TestGaussianRasterizer(int, char*[])
{
  VIS4GS_SHARED_DATA_OR_SKIP();
  const vis4gs::GaussianCloud cloud = vis4gs::ReadGaussianPly(
    vis4gs::testing::SharedDataPath("gs_ply_sh0_variant_donut_v3dg/fused.ply"));
  vtkNew<vtkPolyData> scene;
  vis4gs::GaussianCloudToPolyData(cloud, scene);
  // The donut is about 0.2 units across around the origin: look at it from 0.5 away.
  std::vector<vis4gs::Camera> cameras = { MakeCamera("near", 96, 64, 120, 0.5),
    MakeCamera("far", 80, 60, 150, 0.8) };
  vtkNew<vtkTable> table;
  vis4gs::CamerasToTable(cameras, table);

  vtkNew<vtkGaussianRasterizer> raster;
  raster->SetInputData(0, scene);
  raster->SetCamerasData(table);
  raster->SetBackground(0.1, 0.2, 0.3);
  raster->Update();
  vis4gs::RasterSettings s;
  s.Background = { 0.1, 0.2, 0.3 };
  const auto ref = vis4gs::Rasterize<float>(cloud, cameras[0], s);
  Check(SameAsCore(raster->GetOutput(), ref), "float output equals Core, rows flipped");
  Check(raster->GetOutput()->GetPointData()->GetArray("RGB")->GetDataType() == VTK_FLOAT,
    "float arrays");
  Check(raster->GetNumberOfVisibleGaussians() > 1000, "visible Gaussians reported");
  Check(raster->GetNumberOfInvalidGaussians() == 0, "no invalid Gaussians");
  double covered = 0;
  vtkDataArray* alpha = raster->GetOutput()->GetPointData()->GetArray("Alpha");
  for (vtkIdType i = 0; i < alpha->GetNumberOfTuples(); ++i)
  {
    covered += alpha->GetComponent(i, 0) > 0.5;
  }
  Check(covered > 200, "the donut is in view");

  // Camera by name, double precision, size override (keeps the field of view).
  raster->SetCameraName("far");
  raster->SetPrecisionToDouble();
  raster->SetWidth(40);
  raster->SetHeight(30);
  raster->SetSHDegree(0);
  raster->Update();
  const auto refD = vis4gs::Rasterize<double>(cloud, cameras[1].Resized(40, 30), s);
  Check(SameAsCore(raster->GetOutput(), refD), "double output, named camera, resized");
  Check(raster->GetOutput()->GetPointData()->GetArray("RGB")->GetDataType() == VTK_DOUBLE,
    "double arrays");

  // A camera that does not exist: an error, no crash.
  vtkNew<vtkTest::ErrorObserver> observer;
  raster->AddObserver(vtkCommand::ErrorEvent, observer);
  raster->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
  raster->SetCameraName("missing");
  raster->Update();
  Check(observer->GetError(), "unknown camera name is an error");
  observer->Clear();
  raster->SetCameraName(nullptr);
  raster->SetCameraIndex(5);
  raster->Update();
  Check(observer->GetError(), "camera index out of range is an error");

  vtkNew<vtkGaussianRasterizer> printer;
  printer->Print(std::cout);
  return Check.ExitCode();
}

/*=========================================================================

  Program:   Vis4GS
  Module:    TestGaussianCameraReader.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
// vtkGaussianCameraReader on the real COLMAP statue dataset and on a cameras.json written
// from it: table layout of DESIGN §2, split, resolution, and errors.
#include "vtkGaussianCameraReader.h"

#include "IOSceneTestUtils.h"
#include "Vis4GSDataModel.h"
#include "Vis4GSTestData.h"

#include "CameraJson.h"
#include "ColmapDataset.h"

#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkStringArray.h"
#include "vtkTable.h"

#include <cmath>
#include <fstream>

using iotest::Check;

int TestGaussianCameraReader(int, char*[])
{
  VIS4GS_SHARED_DATA_OR_SKIP();
  const std::string statue = vis4gs::testing::SharedDataPath("colmap_statue_bartoszek");
  vtkNew<vtkGaussianCameraReader> reader;
  reader->SetFileName(statue.c_str());
  reader->Update();
  vtkTable* t = reader->GetOutput();
  Check(t->GetNumberOfRows() == 23, "23 cameras");
  Check(!reader->GetDistorted(), "undistorted");
  auto* names = vtkStringArray::SafeDownCast(t->GetColumnByName(vis4gs::arrays::CameraName));
  Check(names && names->GetValue(0) == "DSC_5283", "sorted by name");
  vtkDataArray* w2c =
    vtkDataArray::SafeDownCast(t->GetColumnByName(vis4gs::arrays::CameraWorldToCamera));
  Check(w2c && w2c->GetNumberOfComponents() == 16, "4x4 world-to-camera");
  const vis4gs::Dataset ds = vis4gs::LoadColmapDataset(statue);
  if (w2c)
  {
    double err = 0;
    for (int k = 0; k < 16; ++k)
    {
      err = std::max(err, std::fabs(w2c->GetComponent(22, k) - ds.Cameras[22].WorldToCamera[k]));
    }
    Check(err == 0, "matrix equals the Core dataset's");
  }
  auto* images = vtkStringArray::SafeDownCast(t->GetColumnByName(vis4gs::arrays::CameraImage));
  Check(images && images->GetValue(0) == statue + "/images/DSC_5283.jpg", "image path");

  reader->EvalOn();
  reader->SetResolution(2);
  reader->Update();
  t = reader->GetOutput();
  vtkDataArray* split = vtkDataArray::SafeDownCast(t->GetColumnByName(vis4gs::arrays::CameraSplit));
  vtkDataArray* width = vtkDataArray::SafeDownCast(t->GetColumnByName(vis4gs::arrays::CameraWidth));
  int tests = 0;
  for (vtkIdType i = 0; split && i < 23; ++i)
  {
    tests += split->GetTuple1(i) == 1;
  }
  Check(tests == 3, "llffhold 8: 3 test views");
  Check(split && split->GetTuple1(8) == 1 && split->GetTuple1(9) == 0, "test views 0, 8, 16");
  Check(width && width->GetTuple1(0) == 500, "resolution 2");

  // cameras.json written from the dataset; images matched by name from an explicit folder.
  iotest::TempDir dir;
  vis4gs::WriteCamerasJson(dir / "cameras.json", ds.Cameras);
  vtkNew<vtkGaussianCameraReader> json;
  json->SetFileName((dir / "cameras.json").c_str());
  json->SetImageFolder((statue + "/images").c_str());
  json->Update();
  vtkTable* jt = json->GetOutput();
  Check(jt->GetNumberOfRows() == 23, "json: 23 cameras");
  vtkDataArray* fx = vtkDataArray::SafeDownCast(jt->GetColumnByName(vis4gs::arrays::CameraFx));
  Check(fx && fx->GetTuple1(4) == ds.Cameras[4].Fx, "json: fx");
  auto* jimages = vtkStringArray::SafeDownCast(jt->GetColumnByName(vis4gs::arrays::CameraImage));
  Check(jimages && jimages->GetValue(0) == statue + "/images/DSC_5283.jpg", "json: image matched");

  // An empty images/ beside a cameras.json: rendering needs no image, so RequireImages off
  // reads every camera (issue 31: `vis4gs render` refused them); on, the missing image is named.
  iotest::TempDir beside;
  vis4gs::WriteCamerasJson(beside / "cameras.json", ds.Cameras);
  Check(std::system(("mkdir '" + (beside / "images") + "'").c_str()) == 0, "images/ made");
  vtkNew<vtkGaussianCameraReader> noImages;
  noImages->SetFileName((beside / "cameras.json").c_str());
  noImages->RequireImagesOff();
  noImages->Update();
  Check(noImages->GetOutput()->GetNumberOfRows() == 23, "empty images/: 23 cameras");
  auto* noPaths = vtkStringArray::SafeDownCast(
    noImages->GetOutput()->GetColumnByName(vis4gs::arrays::CameraImage));
  Check(noPaths && noPaths->GetValue(0).empty(), "empty images/: no image path");
  vtkNew<vtkGaussianCameraReader> needImages;
  vtkNew<iotest::MessageObserver> needErrors;
  needErrors->Watch(needImages);
  needImages->SetFileName((beside / "cameras.json").c_str());
  needImages->Update();
  Check(needErrors->ErrorContains("no image for camera 'DSC_5283'"), "required: camera named");

  // A NeRF-synthetic folder (TransformsJson.h): splits, the OpenGL -> OpenCV pose, frames kept
  // without images when w/h are given and RequireImages is off.
  const std::string frame = R"({"fl_x": 100, "w": 8, "h": 6, "frames": [{"file_path": "r_0",
    "transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,4],[0,0,0,1]]}]})";
  std::ofstream(dir / "transforms_train.json") << frame;
  std::ofstream(dir / "transforms_test.json") << frame;
  vtkNew<vtkGaussianCameraReader> nerf;
  nerf->SetFileName(dir.Path.c_str());
  nerf->RequireImagesOff();
  nerf->Update();
  vtkTable* nt = nerf->GetOutput();
  Check(nt->GetNumberOfRows() == 2, "transforms: 2 cameras");
  vtkDataArray* nsplit =
    vtkDataArray::SafeDownCast(nt->GetColumnByName(vis4gs::arrays::CameraSplit));
  Check(nsplit && nsplit->GetTuple1(0) == 0 && nsplit->GetTuple1(1) == 1, "transforms: splits");
  vtkDataArray* nw2c =
    vtkDataArray::SafeDownCast(nt->GetColumnByName(vis4gs::arrays::CameraWorldToCamera));
  Check(nw2c && nw2c->GetComponent(0, 5) == -1 && nw2c->GetComponent(0, 10) == -1 &&
      nw2c->GetComponent(0, 11) == 4,
    "transforms: y and z flipped, camera 4 in front of the origin");

  // Errors: a missing dataset, a dataset whose images are missing.
  vtkNew<vtkGaussianCameraReader> bad;
  vtkNew<iotest::MessageObserver> errors;
  errors->Watch(bad);
  bad->SetFileName((dir / "nothing.json").c_str());
  bad->Update();
  Check(errors->ErrorContains(dir / "nothing.json"), "missing file named");
  errors->Errors.clear();
  bad->SetFileName(statue.c_str());
  bad->SetImageFolder("no_such_images");
  bad->Update();
  Check(errors->ErrorContains("has no image file"), "camera without image");
  return iotest::Failures() ? EXIT_FAILURE : EXIT_SUCCESS;
}

/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianCameraUtilities.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianCameraUtilities.h"

#include "SplatCamera.h"
#include "Vis4GSDataModel.h"

#include "vtkCamera.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkRenderer.h"
#include "vtkTable.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkGaussianCameraUtilities);

//------------------------------------------------------------------------------
void vtkGaussianCameraUtilities::ApplyCamera(const vis4gs::Camera& view, vtkCamera* camera)
{
  if (!camera)
  {
    throw std::invalid_argument("ApplyCamera: no vtkCamera");
  }
  const vis4gs::CameraLookAt l = vis4gs::CameraToLookAt(view, 1.0);
  camera->SetParallelProjection(false);
  camera->SetUseHorizontalViewAngle(false);
  camera->SetWindowCenter(0.0, 0.0);
  camera->SetPosition(l.Position.data());
  camera->SetFocalPoint(l.FocalPoint.data());
  camera->SetViewUp(l.ViewUp.data());
  camera->SetViewAngle(l.ViewAngle);
  camera->SetClippingRange(0.01, 1000.0);
  if (std::abs(l.PixelAspect - 1.0) > 1e-9)
  {
    const auto p =
      vis4gs::GLProjectionMatrix(view.Width, view.Height, view.Fx, view.Fy, 0.01, 1000.0);
    vtkNew<vtkMatrix4x4> m;
    m->DeepCopy(p.data());
    camera->SetExplicitProjectionTransformMatrix(m);
    camera->SetUseExplicitProjectionTransformMatrix(true);
  }
  else
  {
    camera->SetUseExplicitProjectionTransformMatrix(false);
  }
}

//------------------------------------------------------------------------------
vis4gs::Camera vtkGaussianCameraUtilities::FromVTKCamera(vtkCamera* camera, int width, int height)
{
  if (!camera || width <= 0 || height <= 0)
  {
    throw std::invalid_argument("FromVTKCamera: no camera or an empty viewport");
  }
  if (camera->GetParallelProjection())
  {
    throw std::invalid_argument("FromVTKCamera: a parallel projection has no pinhole camera");
  }
  vtkMatrix4x4* v = camera->GetModelViewTransformMatrix();
  std::array<double, 16> view{};
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      view[4 * r + c] = v->GetElement(r, c);
    }
  }
  vtkMatrix4x4* p =
    camera->GetProjectionTransformMatrix(static_cast<double>(width) / height, -1.0, 1.0);
  vis4gs::Camera c = PinholeCamera(width,
    height,
    p->GetElement(0, 0) * width / 2.0,
    p->GetElement(1, 1) * height / 2.0,
    vis4gs::GLViewToWorldToCamera(view));
  c.Name = "view";
  if (!(c.Fx > 0) || !(c.Fy > 0) || !std::isfinite(c.Fx) || !std::isfinite(c.Fy))
  {
    throw std::invalid_argument("FromVTKCamera: degenerate projection");
  }
  return c;
}

//------------------------------------------------------------------------------
vis4gs::Camera vtkGaussianCameraUtilities::PinholeCamera(int width,
  int height,
  double fx,
  double fy,
  const std::array<double, 16>& worldToCamera)
{
  vis4gs::Camera c;
  c.Width = width;
  c.Height = height;
  c.Fx = fx;
  c.Fy = fy;
  c.Cx = width / 2.0;
  c.Cy = height / 2.0;
  c.WorldToCamera = worldToCamera;
  return c;
}

//------------------------------------------------------------------------------
bool vtkGaussianCameraUtilities::SetCamera(vtkCamera* camera,
  int width,
  int height,
  double fx,
  double fy,
  vtkMatrix4x4* worldToCamera)
{
  if (!camera || !worldToCamera)
  {
    vtkGenericWarningMacro("SetCamera: no camera or no world-to-camera matrix");
    return false;
  }
  std::array<double, 16> w2c{};
  for (int r = 0; r < 4; ++r)
  {
    for (int k = 0; k < 4; ++k)
    {
      w2c[4 * r + k] = worldToCamera->GetElement(r, k);
    }
  }
  const vis4gs::Camera c = PinholeCamera(width, height, fx, fy, w2c);
  try
  {
    ApplyCamera(c, camera);
  }
  catch (const std::exception& e)
  {
    vtkGenericWarningMacro("SetCamera: " << e.what());
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkGaussianCameraUtilities::JumpToCamera(vtkRenderer* renderer,
  vtkTable* cameras,
  vtkIdType row)
{
  if (!renderer || !cameras)
  {
    vtkGenericWarningMacro("JumpToCamera: no renderer or no camera table");
    return false;
  }
  std::vector<vis4gs::Camera> list;
  std::string error;
  if (!vis4gs::TableToCameras(cameras, list, &error))
  {
    vtkGenericWarningMacro("JumpToCamera: " << error);
    return false;
  }
  if (row < 0 || row >= static_cast<vtkIdType>(list.size()))
  {
    vtkGenericWarningMacro(
      "JumpToCamera: row " << row << " is not in the table of " << list.size() << " cameras");
    return false;
  }
  try
  {
    ApplyCamera(list[static_cast<std::size_t>(row)], renderer->GetActiveCamera());
  }
  catch (const std::exception& e)
  {
    vtkGenericWarningMacro("JumpToCamera: " << e.what());
    return false;
  }
  renderer->ResetCameraClippingRange();
  return true;
}

//------------------------------------------------------------------------------
void vtkGaussianCameraUtilities::WorldToRasterPixel(vtkRenderer* renderer,
  const double p[3],
  double pixel[2])
{
  renderer->SetWorldPoint(p[0], p[1], p[2], 1.0);
  renderer->WorldToDisplay();
  double d[3];
  renderer->GetDisplayPoint(d);
  const int* size = renderer->GetSize();
  const int* origin = renderer->GetOrigin();
  // Display coordinates put pixel centres at integer + 0.5.
  pixel[0] = d[0] - origin[0] - 0.5;
  pixel[1] = size[1] - 1 - (d[1] - origin[1] - 0.5);
}

//------------------------------------------------------------------------------
void vtkGaussianCameraUtilities::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}

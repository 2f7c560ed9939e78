// SPDX-License-Identifier: BSD-3-Clause
// A VTK camera set from a vis4gs::Camera projects world points to the same pixels as the Core
// projection (square and non-square pixels); the inverse conversion and the jump to a row of a
// camera table round-trip.
#include "SplatCamera.h"
#include "Vis4GSDataModel.h"
#include "vtkGaussianCameraUtilities.h"

#include "vtkCamera.h"
#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTable.h"

#include <cmath>
#include <cstdio>
#include <vector>

namespace
{
vis4gs::Camera Tilted(int w, int h, double fx, double fy, double yaw)
{
  vis4gs::CameraLookAt l;
  l.Position = { 1.0 + yaw, -0.5, 4.0 };
  l.FocalPoint = { 0.1, 0.2, -0.3 };
  l.ViewUp = { 0.1, 1, 0 };
  l.ViewAngle = 50;
  vis4gs::Camera c = vis4gs::LookAtToCamera(l, w, h);
  c.Fx = fx;
  c.Fy = fy;
  c.Name = "tilted";
  return c;
}

int Compare(vtkRenderer* ren, const vis4gs::Camera& cam, const char* what)
{
  int fail = 0;
  double worst = 0;
  const double pts[4][3] = {
    { 0, 0, 0 }, { 0.5, -0.3, 0.2 }, { -0.7, 0.4, -0.5 }, { 0.2, 0.9, 0.1 }
  };
  for (const auto& p : pts)
  {
    const auto expected = vis4gs::ProjectToPixel(cam, { p[0], p[1], p[2] });
    double got[2];
    vtkGaussianCameraUtilities::WorldToRasterPixel(ren, p, got);
    worst =
      std::max(worst, std::max(std::abs(got[0] - expected[0]), std::abs(got[1] - expected[1])));
  }
  std::printf("%s: worst pixel difference %.3g\n", what, worst);
  if (!(worst < 1e-6))
  {
    std::printf("FAILED: %s projects differently in VTK and Core\n", what);
    fail = 1;
  }
  return fail;
}
}

int TestGaussianCameraUtilities(int, char*[])
{
  int fail = 0;
  vtkNew<vtkRenderer> ren;
  vtkNew<vtkRenderWindow> win;
  win->SetOffScreenRendering(1);
  win->SetMultiSamples(0);
  win->AddRenderer(ren);

  // Square pixels, non-square image.
  const vis4gs::Camera a = Tilted(160, 100, 120, 120, 0.0);
  win->SetSize(a.Width, a.Height);
  vtkGaussianCameraUtilities::ApplyCamera(a, ren->GetActiveCamera());
  win->Render();
  fail |= Compare(ren, a, "square pixels");
  const vis4gs::Camera back =
    vtkGaussianCameraUtilities::FromVTKCamera(ren->GetActiveCamera(), a.Width, a.Height);
  for (int k = 0; k < 16; ++k)
  {
    if (std::abs(back.WorldToCamera[k] - a.WorldToCamera[k]) > 1e-9)
    {
      std::printf("FAILED: W2C[%d] %.12g vs %.12g\n", k, back.WorldToCamera[k], a.WorldToCamera[k]);
      fail = 1;
    }
  }
  if (std::abs(back.Fx - a.Fx) > 1e-9 || std::abs(back.Fy - a.Fy) > 1e-9)
  {
    std::printf("FAILED: focal lengths %.12g %.12g\n", back.Fx, back.Fy);
    fail = 1;
  }

  // Non-square pixels: explicit projection.
  const vis4gs::Camera b = Tilted(120, 90, 150, 100, 0.5);
  win->SetSize(b.Width, b.Height);
  vtkGaussianCameraUtilities::ApplyCamera(b, ren->GetActiveCamera());
  win->Render();
  fail |= Compare(ren, b, "non-square pixels");
  const vis4gs::Camera back2 =
    vtkGaussianCameraUtilities::FromVTKCamera(ren->GetActiveCamera(), b.Width, b.Height);
  if (std::abs(back2.Fx - 150) > 1e-9 || std::abs(back2.Fy - 100) > 1e-9)
  {
    std::printf("FAILED: explicit projection focal lengths %.12g %.12g\n", back2.Fx, back2.Fy);
    fail = 1;
  }

  // Jump to a training camera from a camera table.
  std::vector<vis4gs::Camera> cams = { a, Tilted(160, 100, 120, 120, 1.5) };
  vtkNew<vtkTable> table;
  vis4gs::CamerasToTable(cams, table);
  win->SetSize(160, 100);
  if (!vtkGaussianCameraUtilities::JumpToCamera(ren, table, 1))
  {
    std::printf("FAILED: JumpToCamera returned false\n");
    fail = 1;
  }
  win->Render();
  const auto center = cams[1].Center();
  const double* pos = ren->GetActiveCamera()->GetPosition();
  for (int k = 0; k < 3; ++k)
  {
    if (std::abs(pos[k] - center[k]) > 1e-9)
    {
      std::printf("FAILED: camera position %d: %.12g vs %.12g\n", k, pos[k], center[k]);
      fail = 1;
    }
  }
  fail |= Compare(ren, cams[1], "jump to camera 1");
  if (vtkGaussianCameraUtilities::JumpToCamera(ren, table, 7))
  {
    std::printf("FAILED: JumpToCamera accepted a missing row\n");
    fail = 1;
  }
  vtkNew<vtkTable> empty;
  if (vtkGaussianCameraUtilities::JumpToCamera(ren, empty, 0))
  {
    std::printf("FAILED: JumpToCamera accepted a table without camera columns\n");
    fail = 1;
  }
  return fail;
}

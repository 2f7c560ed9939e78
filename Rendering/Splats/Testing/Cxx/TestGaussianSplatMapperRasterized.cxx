// SPDX-License-Identifier: BSD-3-Clause
// The CPU-rasteriser drawing path of vtkGaussianSplatMapper (forced):
//  1. at full resolution the window holds the exact CPU rasteriser's image (Core/Render,
//     Rasterize<float> for the same camera), rounded to 8 bits: no channel off by more than
//     one level, almost all equal, on two real scenes (SH 0 and SH 3);
//  2. interactive frames (the window's DesiredUpdateRate >= InteractiveUpdateRate) are rendered
//     at 1/InteractiveImageSampleDistance of the resolution and still frames at full
//     resolution again; the reduced image stays close (PSNR printed, bound 20 dB);
//  3. depth compositing with opaque props: a plane in front of the splats hides them, a plane
//     behind drawn before them shows through by (1 - alpha), and a plane behind drawn after
//     them is hidden where the splats' accumulated alpha is >= 0.5 (the depth they write);
//  4. a display mode (hiding by score) changes the picture (the cached image is not reused).
#include "SplatTestHelpers.h"
#include "Vis4GSTestData.h" // VIS4GS_SHARED_DATA_OR_SKIP

#include "Rasterizer.h"
#include "Vis4GSDataModel.h"
#include "vtkGaussianCameraUtilities.h"
#include "vtkGaussianSplatMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <cmath>
#include <cstdio>

namespace
{
int Level(float v)
{
  return static_cast<int>(std::lround(std::min(1.0f, std::max(0.0f, v)) * 255.0f));
}

// A red, unlit square facing the camera at view depth @p depth, covering the columns
// [x0, x1) of the image (fractions of the width) and every row.
vtkSmartPointer<vtkActor> MakePlane(const vis4gs::Camera& cam, double depth, double x0, double x1)
{
  const auto& m = cam.WorldToCamera;
  auto toWorld = [&](double u, double v)
  {
    // Camera-space point at pixel (u, v) and the given depth, back to world: R^T (c - t).
    const double c[3] = {
      (u - cam.Width / 2.0) / cam.Fx * depth, (v - cam.Height / 2.0) / cam.Fy * depth, depth
    };
    const double d[3] = { c[0] - m[3], c[1] - m[7], c[2] - m[11] };
    std::array<double, 3> p{};
    for (int r = 0; r < 3; ++r)
    {
      p[r] = m[r] * d[0] + m[4 + r] * d[1] + m[8 + r] * d[2];
    }
    return p;
  };
  const double W = cam.Width, H = cam.Height;
  auto o = toWorld(x0 * W - 2, -2), p1 = toWorld(x1 * W, -2), p2 = toWorld(x0 * W - 2, H + 2);
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(o.data());
  plane->SetPoint1(p1.data());
  plane->SetPoint2(p2.data());
  vtkNew<vtkPolyDataMapper> pm;
  pm->SetInputConnection(plane->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(pm);
  actor->GetProperty()->SetColor(1, 0, 0);
  actor->GetProperty()->SetAmbient(1.0);
  actor->GetProperty()->SetDiffuse(0.0);
  actor->GetProperty()->SetSpecular(0.0);
  actor->GetProperty()->LightingOff();
  return actor;
}

int CheckScene(bool inria, int width, int height, double azimuth)
{
  int fail = 0;
  const vis4gs::GaussianCloud cloud = splattest::LoadScene(inria);
  const vis4gs::Camera frame = splattest::FrameScene(cloud, width, height, azimuth);

  vtkNew<vtkPolyData> scene;
  vis4gs::GaussianCloudToPolyData(cloud, scene);
  vtkNew<vtkGaussianSplatMapper> mapper;
  mapper->SetInputData(scene);
  mapper->SetDrawMethodToCPURasterizer();
  mapper->SetNumberOfThreads(2);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> ren;
  ren->SetBackground(0, 0, 0);
  ren->AddActor(actor);
  vtkNew<vtkRenderWindow> win;
  win->SetOffScreenRendering(1);
  win->SetMultiSamples(0);
  win->SetSize(width, height);
  win->AddRenderer(ren);
  vtkGaussianCameraUtilities::ApplyCamera(frame, ren->GetActiveCamera());
  win->Render();
  // The camera as the mapper sees it (after the round trip through vtkCamera).
  const vis4gs::Camera cam =
    vtkGaussianCameraUtilities::FromVTKCamera(ren->GetActiveCamera(), width, height);
  const auto reference = vis4gs::Rasterize<float>(cloud, cam);
  const auto image = splattest::ReadWindow(win);
  const char* name = inria ? "inria" : "donut";

  // 1. Exact agreement, up to the framebuffer's 8-bit rounding.
  std::size_t equal = 0, offByOne = 0, worse = 0;
  double coverage = 0;
  for (std::size_t i = 0; i < image.size(); ++i)
  {
    const int d = std::abs(Level(reference.Color[i]) - Level(image[i]));
    (d == 0 ? equal : d == 1 ? offByOne : worse)++;
  }
  for (float a : reference.Alpha)
  {
    coverage += a;
  }
  coverage /= static_cast<double>(reference.Alpha.size());
  const double psnr = splattest::Psnr(reference.Color, image);
  std::printf("%s %dx%d: path %d, %lld drawn, %zu channels equal, %zu off by one level, %zu "
              "worse; PSNR %.2f dB, coverage %.3f\n",
    name,
    width,
    height,
    mapper->GetLastDrawMethod(),
    static_cast<long long>(mapper->GetLastDrawnCount()),
    equal,
    offByOne,
    worse,
    psnr,
    coverage);
  if (mapper->GetLastDrawMethod() != vtkGaussianSplatMapper::CPU_RASTERIZER ||
    mapper->GetLastImageSampleDistance() != 1.0)
  {
    std::printf("FAILED: the CPU rasteriser path at full resolution was not taken\n");
    fail = 1;
  }
  if (worse != 0 || offByOne > image.size() / 1000 || !(coverage > 0.05))
  {
    std::printf("FAILED: the CPU path does not reproduce the rasteriser's image\n");
    fail = 1;
  }
  if (mapper->GetLastDrawnCount() !=
    static_cast<vtkIdType>(vis4gs::ProjectGaussians<float>(cloud, cam).Counts.Visible))
  {
    std::printf("FAILED: drawn count differs from the rasteriser's visible count\n");
    fail = 1;
  }
  // A still frame with nothing changed reuses the image (no rasterisation).
  win->Render();
  const double again = splattest::Psnr(reference.Color, splattest::ReadWindow(win));
  if (mapper->GetLastRasterTime() != 0.0 || again != psnr)
  {
    std::printf("FAILED: an unchanged still frame was re-rasterised (%.1f ms) or differs (%.2f "
                "dB)\n",
      mapper->GetLastRasterTime(),
      again);
    fail = 1;
  }

  // 2. Interactive frames at reduced resolution, still frames at full resolution.
  mapper->AutoAdjustImageSampleDistancesOff();
  mapper->SetInteractiveImageSampleDistance(2.0);
  win->SetDesiredUpdateRate(15.0);
  win->Render();
  const auto interactive = splattest::ReadWindow(win);
  const double psnrInteractive = splattest::Psnr(reference.Color, interactive);
  std::printf("  interactive (sample distance %.1f): PSNR %.2f dB against full resolution\n",
    mapper->GetLastImageSampleDistance(),
    psnrInteractive);
  if (mapper->GetLastImageSampleDistance() != 2.0 || !(psnrInteractive >= 20.0) ||
    !(psnrInteractive < psnr))
  {
    std::printf("FAILED: interactive frame not at half resolution or too far off\n");
    fail = 1;
  }
  win->SetDesiredUpdateRate(0.0001);
  win->Render();
  if (mapper->GetLastImageSampleDistance() != 1.0 ||
    splattest::Psnr(reference.Color, splattest::ReadWindow(win)) != psnr)
  {
    std::printf("FAILED: the still frame after interaction is not the full-resolution image\n");
    fail = 1;
  }

  // 3. Depth compositing with opaque props.
  double depthMin = 1e30, depthMax = 0;
  {
    const auto proj = vis4gs::ProjectGaussians<float>(cloud, cam);
    for (const auto& g : proj.Gaussians)
    {
      if (g.IsVisible())
      {
        depthMin = std::min(depthMin, static_cast<double>(g.Depth));
        depthMax = std::max(depthMax, static_cast<double>(g.Depth));
      }
    }
  }
  ren->RemoveActor(actor);
  auto front = MakePlane(cam, 0.5 * depthMin, 0.0, 0.5);  // left half, in front
  auto behind = MakePlane(cam, 1.5 * depthMax, 0.5, 1.0); // right half, behind, drawn first
  ren->AddActor(front);
  ren->AddActor(behind);
  ren->AddActor(actor);
  auto after = MakePlane(cam, 1.5 * depthMax, 0.0, 0.5); // left half, behind, drawn after
  ren->ResetCameraClippingRange();
  win->Render();
  auto composed = splattest::ReadWindow(win);
  int badFront = 0, badBehind = 0, checkedBehind = 0;
  for (int y = 2; y < height - 2; ++y)
  {
    for (int x = 2; x < width - 2; ++x)
    {
      const std::size_t p = static_cast<std::size_t>(y) * width + x;
      const float a = reference.Alpha[p];
      for (int c = 0; c < 3; ++c)
      {
        const float got = composed[3 * p + c];
        if (x < width / 2 - 2)
        {
          badFront += std::abs(Level(got) - (c == 0 ? 255 : 0)) > 0;
        }
        else if (x > width / 2 + 2)
        {
          const float expect = reference.Color[3 * p + c] + (c == 0 ? 1.0f - a : 0.0f);
          badBehind += std::abs(Level(got) - Level(expect)) > 2;
          ++checkedBehind;
        }
      }
    }
  }
  // The plane behind, drawn after the splats, on the left half instead of the front plane.
  ren->RemoveActor(front);
  ren->AddActor(after);
  win->Render();
  composed = splattest::ReadWindow(win);
  int badAfter = 0, opaqueAfter = 0, thinAfter = 0;
  for (int y = 2; y < height - 2; ++y)
  {
    for (int x = 2; x < width / 2 - 2; ++x)
    {
      const std::size_t p = static_cast<std::size_t>(y) * width + x;
      const float a = reference.Alpha[p];
      if (a >= 0.55f)
      {
        ++opaqueAfter; // the splats' depth hides the plane: the splat colour over black
        for (int c = 0; c < 3; ++c)
        {
          badAfter += std::abs(Level(composed[3 * p + c]) - Level(reference.Color[3 * p + c])) > 1;
        }
      }
      else if (a < 0.45f)
      {
        ++thinAfter; // no depth written: the plane overwrites the pixel
        badAfter += Level(composed[3 * p]) != 255 || Level(composed[3 * p + 1]) != 0;
      }
    }
  }
  std::printf("  depth: %d bad channels in front (plane covers), %d of %d behind (drawn first), "
              "%d bad of %d opaque + %d thin pixels behind (drawn after)\n",
    badFront,
    badBehind,
    checkedBehind,
    badAfter,
    opaqueAfter,
    thinAfter);
  if (badFront != 0 || badBehind > checkedBehind / 1000 || badAfter > opaqueAfter / 1000 ||
    opaqueAfter < 100 || thinAfter < 100)
  {
    std::printf("FAILED: depth compositing with other props\n");
    fail = 1;
  }
  ren->RemoveActor(after);
  ren->RemoveActor(behind);

  // 4. Hiding by score re-renders (the cached image must not be reused).
  vtkNew<vtkFloatArray> score;
  score->SetName("TestScore");
  score->SetNumberOfTuples(static_cast<vtkIdType>(cloud.Count));
  for (vtkIdType i = 0; i < score->GetNumberOfTuples(); ++i)
  {
    score->SetValue(i, static_cast<float>(i % 2));
  }
  scene->GetPointData()->AddArray(score);
  mapper->SetScoreArrayName("TestScore");
  mapper->HideOutsideRangeOn();
  mapper->SetVisibleRange(0.5, 1.5);
  win->Render();
  const vtkIdType halfDrawn = mapper->GetLastDrawnCount();
  const double psnrHidden = splattest::Psnr(reference.Color, splattest::ReadWindow(win));
  std::printf("  half hidden: %lld drawn, PSNR %.2f dB against all\n",
    static_cast<long long>(halfDrawn),
    psnrHidden);
  if (!(psnrHidden < 40.0) || halfDrawn <= 0 || halfDrawn >= static_cast<vtkIdType>(cloud.Count))
  {
    std::printf("FAILED: hiding half of the Gaussians did not change the picture\n");
    fail = 1;
  }
  return fail;
}
}

int TestGaussianSplatMapperRasterized(int, char*[])
{
  VIS4GS_SHARED_DATA_OR_SKIP();
  int fail = 0;
  fail |= CheckScene(false, 240, 180, 0.3);
  fail |= CheckScene(true, 256, 160, 0.8);
  return fail;
}

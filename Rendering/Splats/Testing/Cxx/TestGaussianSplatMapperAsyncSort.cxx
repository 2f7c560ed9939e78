// SPDX-License-Identifier: BSD-3-Clause
// The OpenGL splat path's worker-thread sort and shader SH colours (forced OpenGL splats,
// synthetic scenes, no shared data):
//  1. while the camera moves a frame draws with the last finished order (the second moving
//     frame lags exactly one camera change, none lags more than the frames drawn); the still
//     frame after the orbit waits for its own order: its window bytes equal those of the same
//     mapper sorting synchronously (AsynchronousSort off) for that camera;
//  2. moving the camera uploads nothing but orders (the scene upload counter stays, the order
//     counter grows by at most one per frame); a display change uploads the display colours
//     only;
//  3. the colours the shader evaluates from the SH coefficients equal the CPU's
//     (EvaluateSplatColors) at the centres of a few large, nearly opaque splats, also with
//     the highlight of a selection and the dimming of the others applied in the shader.
#include "SplatTestHelpers.h"

#include "BenchmarkScene.h"
#include "SplatAttributes.h"
#include "Vis4GSDataModel.h"
#include "vtkGaussianCameraUtilities.h"
#include "vtkGaussianSplatMapper.h"

#include "vtkActor.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

namespace
{
constexpr int Width = 320, Height = 240;

struct View
{
  vtkNew<vtkGaussianSplatMapper> Mapper;
  vtkNew<vtkActor> Actor;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;

  explicit View(vtkPolyData* scene)
  {
    this->Mapper->SetInputData(scene);
    this->Mapper->SetDrawMethodToOpenGLSplats();
    this->Mapper->SetNumberOfThreads(2);
    this->Actor->SetMapper(this->Mapper);
    this->Renderer->SetBackground(0, 0, 0);
    this->Renderer->AddActor(this->Actor);
    this->Window->SetOffScreenRendering(1);
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(Width, Height);
    this->Window->AddRenderer(this->Renderer);
  }

  std::vector<float> Draw(const vis4gs::Camera& camera, bool moving)
  {
    vtkGaussianCameraUtilities::ApplyCamera(camera, this->Renderer->GetActiveCamera());
    this->Window->SetDesiredUpdateRate(moving ? 15.0 : 0.0001);
    this->Window->Render();
    // (reading the window renders again: only still frames are read, which that cannot change)
    return moving ? std::vector<float>() : splattest::ReadWindow(this->Window);
  }
};

int CheckOrbit()
{
  int fail = 0;
  const vis4gs::GaussianCloud cloud = vis4gs::MakeBenchmarkScene(150000, 3, 5);
  vtkNew<vtkPolyData> scene;
  vis4gs::GaussianCloudToPolyData(cloud, scene);
  View view(scene);
  view.Draw(vis4gs::MakeBenchmarkCamera(Width, Height, 0.0), true); // no order yet: waits
  const vtkIdType sceneUploads = view.Mapper->GetSceneUploadCount();
  const vtkIdType orderUploads = view.Mapper->GetOrderUploadCount();
  if (view.Mapper->GetLastOrderLag() != 0 || sceneUploads != 3 || orderUploads != 1)
  {
    std::printf("FAILED: the first frame lags %lld or uploaded %lld scene arrays and %lld orders "
                "(expected 0, 3, 1)\n",
      static_cast<long long>(view.Mapper->GetLastOrderLag()),
      static_cast<long long>(sceneUploads),
      static_cast<long long>(orderUploads));
    fail = 1;
  }
  const int frames = 6;
  for (int f = 1; f <= frames; ++f)
  {
    view.Draw(vis4gs::MakeBenchmarkCamera(Width, Height, 0.05 * f), true);
    const vtkIdType lag = view.Mapper->GetLastOrderLag();
    std::printf("moving frame %d: order lags %lld camera changes, sort %.1f ms, render thread "
                "%.2f ms + draw call %.2f ms\n",
      f,
      static_cast<long long>(lag),
      view.Mapper->GetLastSortTime(),
      view.Mapper->GetLastRenderThreadTime(),
      view.Mapper->GetLastDrawCallTime());
    // The first moving frame's order cannot have finished before the frame took it.
    if ((f == 1 && lag != 1) || lag < 1 || lag > f)
    {
      std::printf(
        "FAILED: moving frame %d lags %lld camera changes\n", f, static_cast<long long>(lag));
      fail = 1;
    }
  }
  if (view.Mapper->GetSceneUploadCount() != sceneUploads ||
    view.Mapper->GetOrderUploadCount() <= orderUploads ||
    view.Mapper->GetOrderUploadCount() > orderUploads + frames)
  {
    std::printf("FAILED: moving the camera uploaded %lld scene arrays and %lld orders in %d "
                "frames (expected none, 1 to %d)\n",
      static_cast<long long>(view.Mapper->GetSceneUploadCount() - sceneUploads),
      static_cast<long long>(view.Mapper->GetOrderUploadCount() - orderUploads),
      frames,
      frames);
    fail = 1;
  }
  // The camera stops.
  const vis4gs::Camera last = vis4gs::MakeBenchmarkCamera(Width, Height, 0.05 * frames);
  const auto stopped = view.Draw(last, false);
  if (view.Mapper->GetLastOrderLag() != 0)
  {
    std::printf("FAILED: the still frame lags %lld camera changes\n",
      static_cast<long long>(view.Mapper->GetLastOrderLag()));
    fail = 1;
  }
  view.Mapper->AsynchronousSortOff();
  const vis4gs::Camera other = vis4gs::MakeBenchmarkCamera(Width, Height, 1.0);
  view.Draw(other, true); // (a synchronous sort never lags, moving or not)
  if (view.Mapper->GetLastOrderLag() != 0)
  {
    std::printf("FAILED: a synchronously sorted frame lags\n");
    fail = 1;
  }
  const auto synchronous = view.Draw(last, false);
  double coverage = 0;
  for (float v : stopped)
  {
    coverage += v > 0.1f ? 1 : 0;
  }
  if (stopped != synchronous || coverage < 0.05 * stopped.size())
  {
    std::printf("FAILED: the still frame after moving differs from the synchronously sorted one "
                "(PSNR %.2f dB) or is nearly empty (%.0f values above 0.1)\n",
      splattest::Psnr(synchronous, stopped),
      coverage);
    fail = 1;
  }
  // A display change uploads the display colours, nothing else.
  const vtkIdType before = view.Mapper->GetSceneUploadCount();
  view.Mapper->SetHighlightMix(0.5);
  view.Draw(last, false);
  if (view.Mapper->GetSceneUploadCount() != before + 1)
  {
    std::printf("FAILED: a display change uploaded %lld scene arrays (expected 1)\n",
      static_cast<long long>(view.Mapper->GetSceneUploadCount() - before));
    fail = 1;
  }
  return fail;
}

// A few large splats in front of a camera at the origin looking down +z, each one where no
// other reaches; SH degree 3 with random coefficients.
int CheckShaderColors()
{
  int fail = 0;
  const double fx = 300.0;
  vis4gs::GaussianCloud cloud;
  const int count = 6;
  cloud.Resize(count, 3);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> dc(-0.8f, 0.8f), rest(-0.3f, 0.3f);
  std::vector<std::array<int, 2>> pixels;
  for (int i = 0; i < count; ++i)
  {
    const int column = 50 + 110 * (i % 3), row = 60 + 120 * (i / 3);
    const float z = 4.0f + static_cast<float>(i);
    // Pixel (column, row) is at u = fx x / z + W / 2 - 0.5 (the reference's pixel centres).
    cloud.Positions[3 * i] = static_cast<float>((column - Width / 2 + 0.5) * z / fx);
    cloud.Positions[3 * i + 1] = static_cast<float>((row - Height / 2 + 0.5) * z / fx);
    cloud.Positions[3 * i + 2] = z;
    pixels.push_back({ { column, row } });
    for (int k = 0; k < 3; ++k)
    {
      cloud.LogScales[3 * i + k] = std::log(6.0f * z / static_cast<float>(fx)); // ~6 px sigma
    }
    cloud.Rotations[4 * i] = 1.0f;
    cloud.OpacityLogits[i] = 12.0f;
    for (int k = 0; k < 16; ++k)
    {
      for (int ch = 0; ch < 3; ++ch)
      {
        cloud.SH[48 * i + 3 * k + ch] = k == 0 ? dc(rng) : rest(rng);
      }
    }
  }
  std::vector<float> cpu;
  vis4gs::EvaluateSplatColors(cloud, { { 0.0, 0.0, 0.0 } }, -1, cpu, 1);
  vtkNew<vtkPolyData> scene;
  vis4gs::GaussianCloudToPolyData(cloud, scene);
  View view(scene);
  const std::array<double, 16> identity{ { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 } };
  const vis4gs::Camera camera =
    vtkGaussianCameraUtilities::PinholeCamera(Width, Height, fx, fx, identity);
  for (int pass = 0; pass < 2; ++pass)
  {
    // Pass 1: Gaussian 0 selected (highlighted), the others dimmed (colour towards grey,
    // opacity times 0.15), all in the shader from the deferred display codes.
    if (pass == 1)
    {
      vtkNew<vtkIdTypeArray> ids;
      ids->InsertNextValue(0);
      view.Mapper->SetSelectedIds(ids);
      view.Mapper->DimUnselectedOn();
    }
    const auto image = view.Draw(camera, false);
    for (int i = 0; i < count; ++i)
    {
      float c[3] = { cpu[3 * i], cpu[3 * i + 1], cpu[3 * i + 2] };
      float alpha = 0.99f;
      if (pass == 1 && i == 0)
      {
        const float highlight[3] = { 1.0f, 0.35f, 0.0f }; // the default HighlightColor
        for (int ch = 0; ch < 3; ++ch)
        {
          c[ch] = c[ch] + 0.7f * (highlight[ch] - c[ch]);
        }
      }
      else if (pass == 1)
      {
        const float grey = 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
        for (float& v : c)
        {
          v = v + 0.8f * (grey - v);
        }
        alpha = 0.15f; // (the opacity at the centre, 1 - 6e-6, times 0.15)
      }
      const std::size_t p = 3 * (static_cast<std::size_t>(pixels[i][1]) * Width + pixels[i][0]);
      for (int ch = 0; ch < 3; ++ch)
      {
        const float expected = std::min(1.0f, alpha * c[ch]);
        if (!(std::abs(image[p + ch] - expected) <= 1.5f / 255.0f))
        {
          std::printf("FAILED: pass %d, splat %d channel %d: shader colour %.4f, CPU SH colour "
                      "%.4f\n",
            pass,
            i,
            ch,
            image[p + ch],
            expected);
          fail = 1;
        }
      }
    }
  }
  return fail;
}
} // namespace

int TestGaussianSplatMapperAsyncSort(int, char*[])
{
  int fail = CheckOrbit();
  fail |= CheckShaderColors();
  return fail;
}

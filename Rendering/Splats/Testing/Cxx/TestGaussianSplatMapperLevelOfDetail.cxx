// SPDX-License-Identifier: BSD-3-Clause
// The CPU path's level of detail while the camera moves (InteractiveSplatBudget), on the
// synthetic benchmark scene (no shared data):
//  1. an interactive frame of a scene larger than the budget draws the budget's Gaussians
//     (LastFrameReduced), a picture close to the exact one but not equal to it: at most the
//     budget with InteractiveReuseAngle 0, and at most 5 % more with the default angle, whose
//     selection adds a margin's ring around the view (Core/Splats/SplatMovingSet.h) of which a
//     few reach the image's edge tiles;
//  2. the still frame after an orbit of moving frames is the exact one bit for bit: the same
//     window bytes as a mapper that never moved drew for that camera, and the CPU
//     rasteriser's image (Core, Rasterize<float>) up to the framebuffer's 8-bit rounding; the
//     same with the next choice of Gaussians made ahead on a builder thread
//     (InteractiveRebuildAhead), whose moving frames stay reduced and close to the exact ones;
//  3. a budget of 0, or one at least the scene's size, draws every Gaussian while moving;
//  4. hiding by score applies to the reduced frame's Gaussians (fewer drawn, none hidden
//     drawn: a range that hides everything draws nothing).
#include "SplatTestHelpers.h"

#include "BenchmarkScene.h"
#include "Rasterizer.h"
#include "Vis4GSDataModel.h"
#include "vtkGaussianCameraUtilities.h"
#include "vtkGaussianSplatMapper.h"

#include "vtkActor.h"
#include "vtkDoubleArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

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
    this->Mapper->SetDrawMethodToCPURasterizer();
    this->Mapper->SetNumberOfThreads(2);
    this->Mapper->AutoAdjustImageSampleDistancesOff();
    this->Actor->SetMapper(this->Mapper);
    this->Renderer->SetBackground(0, 0, 0);
    this->Renderer->AddActor(this->Actor);
    this->Window->SetOffScreenRendering(1);
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(Width, Height);
    this->Window->AddRenderer(this->Renderer);
  }

  std::vector<float> Draw(double azimuth, bool moving)
  {
    vtkGaussianCameraUtilities::ApplyCamera(
      vis4gs::MakeBenchmarkCamera(Width, Height, azimuth), this->Renderer->GetActiveCamera());
    this->Window->SetDesiredUpdateRate(moving ? 15.0 : 0.0001);
    this->Window->Render();
    return splattest::ReadWindow(this->Window);
  }
};

int Level(float v)
{
  return static_cast<int>(std::lround(std::min(1.0f, std::max(0.0f, v)) * 255.0f));
}
} // namespace

int TestGaussianSplatMapperLevelOfDetail(int, char*[])
{
  int fail = 0;
  const vis4gs::GaussianCloud cloud = vis4gs::MakeBenchmarkScene(60000, 1, 4);
  vtkNew<vtkPolyData> scene;
  vis4gs::GaussianCloudToPolyData(cloud, scene);
  const vtkIdType budget = 6000;
  View view(scene);
  view.Mapper->SetInteractiveSplatBudget(budget);
  view.Mapper->SetInteractiveImageSampleDistance(1.0);

  // 1. A moving frame draws the budget; the still frame at the same camera draws everything.
  const auto still0 = view.Draw(0.3, false);
  const vtkIdType visible = view.Mapper->GetLastDrawnCount();
  view.Mapper->SetInteractiveReuseAngle(0.0);
  view.Draw(0.3, true);
  const vtkIdType drawnNoReuse = view.Mapper->GetLastDrawnCount();
  view.Draw(0.3, false);
  view.Mapper->SetInteractiveReuseAngle(6.0);
  const auto moving0 = view.Draw(0.3, true);
  const double psnr = splattest::Psnr(still0, moving0);
  std::printf("moving frame: %lld of %lld visible drawn (%lld with reuse angle 0), PSNR %.2f dB "
              "against the still frame\n",
    static_cast<long long>(view.Mapper->GetLastDrawnCount()),
    static_cast<long long>(visible),
    static_cast<long long>(drawnNoReuse),
    psnr);
  if (!view.Mapper->GetLastFrameReduced() ||
    view.Mapper->GetLastDrawnCount() > budget + budget / 20 ||
    view.Mapper->GetLastDrawnCount() < budget / 2 || visible <= budget || drawnNoReuse > budget ||
    drawnNoReuse < budget / 2)
  {
    std::printf("FAILED: the moving frame did not draw the budget's Gaussians\n");
    fail = 1;
  }
  if (!(psnr > 18.0) || !(psnr < 100.0))
  {
    std::printf("FAILED: the moving frame is not a close approximation of the exact frame\n");
    fail = 1;
  }

  // 2. An orbit of moving frames (sample distance 2 too), then the camera stops.
  view.Mapper->SetInteractiveImageSampleDistance(2.0);
  for (int f = 1; f <= 4; ++f)
  {
    view.Draw(0.3 + 0.05 * f, true);
  }
  const auto stopped = view.Draw(0.5, false);
  View fresh(scene); // never moved
  const auto exact = fresh.Draw(0.5, false);
  if (view.Mapper->GetLastFrameReduced() || stopped != exact ||
    view.Mapper->GetLastDrawnCount() != fresh.Mapper->GetLastDrawnCount())
  {
    std::printf("FAILED: the still frame after moving is not the exact frame bit for bit\n");
    fail = 1;
  }
  const vis4gs::Camera cam =
    vtkGaussianCameraUtilities::FromVTKCamera(view.Renderer->GetActiveCamera(), Width, Height);
  const auto reference = vis4gs::Rasterize<float>(cloud, cam);
  std::size_t offByOne = 0, worse = 0;
  for (std::size_t i = 0; i < stopped.size(); ++i)
  {
    const int d = std::abs(Level(reference.Color[i]) - Level(stopped[i]));
    offByOne += d == 1 ? 1 : 0;
    worse += d > 1 ? 1 : 0;
  }
  std::printf("still frame after moving: %zu channels off by one level, %zu worse than the "
              "rasteriser's image\n",
    offByOne,
    worse);
  if (worse != 0 || offByOne > stopped.size() / 1000)
  {
    std::printf("FAILED: the still frame is not the CPU rasteriser's image\n");
    fail = 1;
  }

  // 2b. The same orbit with the next choice made ahead on a builder thread
  // (InteractiveRebuildAhead): every moving frame draws a reduced picture close to the exact
  // one, and the still frame after it is again the exact frame bit for bit.
  {
    View ahead(scene);
    ahead.Mapper->SetInteractiveSplatBudget(budget);
    ahead.Mapper->SetInteractiveImageSampleDistance(2.0);
    ahead.Mapper->SetInteractiveRebuildAhead(0.25);
    ahead.Draw(0.3, false);
    for (int f = 1; f <= 6; ++f)
    {
      const auto moving = ahead.Draw(0.3 + 0.03 * f, true);
      const double p = splattest::Psnr(fresh.Draw(0.3 + 0.03 * f, false), moving);
      if (!ahead.Mapper->GetLastFrameReduced() || ahead.Mapper->GetLastDrawnCount() == 0 ||
        p < 20.0)
      {
        std::printf("FAILED: moving frame %d with rebuilds ahead: reduced %d, %lld drawn, "
                    "%.2f dB against the exact frame\n",
          f,
          static_cast<int>(ahead.Mapper->GetLastFrameReduced()),
          static_cast<long long>(ahead.Mapper->GetLastDrawnCount()),
          p);
        fail = 1;
      }
    }
    const auto aheadStopped = ahead.Draw(0.5, false);
    if (aheadStopped != exact || ahead.Mapper->GetLastFrameReduced())
    {
      std::printf("FAILED: the still frame after moving with rebuilds ahead is not the exact "
                  "frame bit for bit\n");
      fail = 1;
    }
  }

  // 3. Budget 0 and a budget of at least the scene's size: every Gaussian while moving.
  for (vtkIdType all : { vtkIdType(0), static_cast<vtkIdType>(cloud.Count) })
  {
    view.Mapper->SetInteractiveSplatBudget(all);
    view.Mapper->SetInteractiveImageSampleDistance(1.0);
    view.Draw(0.3, true);
    if (view.Mapper->GetLastFrameReduced() || view.Mapper->GetLastDrawnCount() != visible)
    {
      std::printf("FAILED: budget %lld drew %lld of %lld while moving\n",
        static_cast<long long>(all),
        static_cast<long long>(view.Mapper->GetLastDrawnCount()),
        static_cast<long long>(visible));
      fail = 1;
    }
  }

  // 4. Hiding by score in a reduced frame.
  view.Mapper->SetInteractiveSplatBudget(budget);
  vtkNew<vtkDoubleArray> score;
  score->SetName("Parity");
  score->SetNumberOfTuples(static_cast<vtkIdType>(cloud.Count));
  for (vtkIdType i = 0; i < score->GetNumberOfTuples(); ++i)
  {
    score->SetValue(i, static_cast<double>(i % 2));
  }
  scene->GetPointData()->AddArray(score);
  view.Mapper->SetScoreArrayName("Parity");
  view.Mapper->HideOutsideRangeOn();
  view.Mapper->SetVisibleRange(0.5, 1.5);
  view.Draw(0.31, true);
  const vtkIdType odd = view.Mapper->GetLastDrawnCount();
  view.Mapper->SetVisibleRange(2.0, 3.0);
  const auto none = view.Draw(0.32, true);
  std::printf("hiding in a reduced frame: %lld of the odd Gaussians drawn, then %lld\n",
    static_cast<long long>(odd),
    static_cast<long long>(view.Mapper->GetLastDrawnCount()));
  if (!view.Mapper->GetLastFrameReduced() || odd <= 0 || odd >= budget ||
    view.Mapper->GetLastDrawnCount() != 0 || *std::max_element(none.begin(), none.end()) != 0.0f)
  {
    std::printf("FAILED: hiding by score does not apply to the reduced frame\n");
    fail = 1;
  }
  return fail ? EXIT_FAILURE : EXIT_SUCCESS;
}

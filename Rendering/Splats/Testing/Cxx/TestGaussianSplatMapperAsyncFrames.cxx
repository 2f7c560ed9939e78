// SPDX-License-Identifier: BSD-3-Clause
// The CPU path's frames made on the mapper's worker thread (AsynchronousFrames), on the
// synthetic benchmark scene (no shared data):
//  1. after an orbit of moving frames, the still frame drawn once the worker finished it is
//     the exact frame bit for bit: the same window bytes as a synchronous mapper that never
//     moved drew for that camera;
//  2. the newest request wins: while the worker is held (in its frame-ready callback),
//     renders at several cameras replace each other's request; the worker then makes one
//     frame, the last camera's, and it is that camera's exact frame;
//  3. no frame of a replaced scene is drawn: a frame of scene A finished after the input
//     became scene B is dropped (nothing drawn), then B's exact frame is drawn;
//  4. the synchronous and asynchronous modes switch back and forth without losing a frame;
//  5. with the next choice of the moving frames' Gaussians made ahead on a builder thread
//     (InteractiveRebuildAhead) beside the worker, the moving frames of an orbit are reduced
//     and the still frame after it is the exact frame bit for bit (Scripts/run-sanitizers.sh
//     thread runs this test: the worker, the builder and the render thread together).
#include "SplatTestHelpers.h"

#include "BenchmarkScene.h"
#include "Vis4GSDataModel.h"
#include "vtkGaussianCameraUtilities.h"
#include "vtkGaussianSplatMapper.h"

#include "vtkActor.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <thread>

namespace
{
constexpr int Width = 320, Height = 240;

struct View
{
  vtkNew<vtkGaussianSplatMapper> Mapper;
  vtkNew<vtkActor> Actor;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;

  View(vtkPolyData* scene, bool asynchronous)
  {
    this->Mapper->SetInputData(scene);
    this->Mapper->SetDrawMethodToCPURasterizer();
    this->Mapper->SetNumberOfThreads(2);
    this->Mapper->AutoAdjustImageSampleDistancesOff();
    this->Mapper->SetInteractiveSplatBudget(5000);
    this->Mapper->SetAsynchronousFrames(asynchronous);
    this->Actor->SetMapper(this->Mapper);
    this->Renderer->SetBackground(0, 0, 0);
    this->Renderer->AddActor(this->Actor);
    this->Window->SetOffScreenRendering(1);
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(Width, Height);
    this->Window->AddRenderer(this->Renderer);
  }

  // Renders at @p azimuth (moving or still) without waiting for the worker.
  void Request(double azimuth, bool moving)
  {
    vtkGaussianCameraUtilities::ApplyCamera(
      vis4gs::MakeBenchmarkCamera(Width, Height, azimuth), this->Renderer->GetActiveCamera());
    this->Window->SetDesiredUpdateRate(moving ? 15.0 : 0.0001);
    this->Window->Render();
  }

  // Waits for the worker, renders again and reads the window.
  std::vector<float> Finish()
  {
    this->Mapper->WaitForFrame();
    this->Window->Render();
    return splattest::ReadWindow(this->Window);
  }
};

// Holds the worker in its frame-ready callback until released; counts the frames finished.
struct Gate
{
  std::mutex Mutex;
  std::condition_variable Changed;
  bool Closed = true;
  int Finished = 0;

  void Pass()
  {
    std::unique_lock<std::mutex> lock(this->Mutex);
    ++this->Finished;
    this->Changed.notify_all();
    this->Changed.wait(lock, [this] { return !this->Closed; });
  }
  bool WaitFinished(int count)
  {
    std::unique_lock<std::mutex> lock(this->Mutex);
    return this->Changed.wait_for(
      lock, std::chrono::seconds(60), [&] { return this->Finished >= count; });
  }
  void Open()
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    this->Closed = false;
    this->Changed.notify_all();
  }
};

bool AllZero(const std::vector<float>& pixels)
{
  return std::all_of(pixels.begin(), pixels.end(), [](float v) { return v == 0.0f; });
}
} // namespace

int TestGaussianSplatMapperAsyncFrames(int, char*[])
{
  int fail = 0;
  const vis4gs::GaussianCloud cloudA = vis4gs::MakeBenchmarkScene(40000, 1, 4);
  const vis4gs::GaussianCloud cloudB = vis4gs::MakeBenchmarkScene(30000, 1, 7);
  vtkNew<vtkPolyData> sceneA, sceneB;
  vis4gs::GaussianCloudToPolyData(cloudA, sceneA);
  vis4gs::GaussianCloudToPolyData(cloudB, sceneB);
  View exactA(sceneA, false), exactB(sceneB, false);
  auto exact = [](View& v, double azimuth)
  {
    v.Request(azimuth, false);
    return splattest::ReadWindow(v.Window);
  };

  // 1. An orbit, then the camera stops.
  {
    View view(sceneA, true);
    for (int f = 0; f < 6; ++f)
    {
      view.Request(0.3 + 0.05 * f, true);
    }
    view.Request(0.6, false);
    const auto stopped = view.Finish();
    const auto reference = exact(exactA, 0.6);
    std::printf("1. still frame after an orbit: %lld drawn (exact %lld), %lld new images\n",
      static_cast<long long>(view.Mapper->GetLastDrawnCount()),
      static_cast<long long>(exactA.Mapper->GetLastDrawnCount()),
      static_cast<long long>(view.Mapper->GetFramesShown()));
    if (view.Mapper->GetFramePending() || view.Mapper->GetLastFrameReduced() ||
      stopped != reference ||
      view.Mapper->GetLastDrawnCount() != exactA.Mapper->GetLastDrawnCount() || AllZero(reference))
    {
      std::printf("FAILED: the still frame after motion is not the exact frame bit for bit\n");
      fail = 1;
    }
  }

  // 2. The newest request wins.
  {
    View view(sceneA, true);
    Gate gate;
    view.Mapper->SetFrameReadyCallback([&gate] { gate.Pass(); });
    view.Request(0.2, false);
    const bool first = gate.WaitFinished(1); // the worker is held after its first frame
    const bool pendingWhileHeld = view.Mapper->GetFramePending();
    for (int f = 1; f <= 5; ++f)
    {
      view.Request(0.2 + 0.07 * f, f % 2 == 1);
    }
    view.Request(0.95, false);
    gate.Open();
    const auto shown = view.Finish();
    view.Mapper->SetFrameReadyCallback(nullptr);
    const auto reference = exact(exactA, 0.95);
    std::printf(
      "2. 7 requests while the worker was held after the first: %d frames made\n", gate.Finished);
    if (!first || !pendingWhileHeld || gate.Finished != 2 || shown != reference ||
      view.Mapper->GetFramePending())
    {
      std::printf("FAILED: the newest request did not replace the waiting ones\n");
      fail = 1;
    }
  }

  // 3. A frame of the replaced scene is never drawn.
  {
    View view(sceneA, true);
    Gate gate;
    view.Mapper->SetFrameReadyCallback([&gate] { gate.Pass(); });
    view.Request(0.4, false);
    const bool first = gate.WaitFinished(1); // A's frame is finished, not drawn yet
    view.Mapper->SetInputData(sceneB);
    view.Request(0.4, false);
    const auto during = splattest::ReadWindow(view.Window);
    gate.Open();
    const auto after = view.Finish();
    view.Mapper->SetFrameReadyCallback(nullptr);
    const auto reference = exact(exactB, 0.4);
    std::printf("3. scene replaced while its frame was made: %s drawn meanwhile\n",
      AllZero(during) ? "nothing" : "something");
    if (!first || !AllZero(during) || after != reference)
    {
      std::printf("FAILED: a frame of the replaced scene was drawn, or the new one is wrong\n");
      fail = 1;
    }
  }

  // 4. Switching modes.
  {
    View view(sceneB, true);
    view.Request(0.7, true);
    view.Mapper->SetAsynchronousFrames(false);
    view.Request(0.8, false);
    const auto sync = splattest::ReadWindow(view.Window);
    view.Mapper->SetAsynchronousFrames(true);
    view.Request(0.4, true);
    view.Request(0.4, false);
    const auto async = view.Finish();
    if (sync != exact(exactB, 0.8) || async != exact(exactB, 0.4))
    {
      std::printf("FAILED: switching between the modes lost or changed a frame\n");
      fail = 1;
    }
  }

  // 5. An orbit with rebuilds ahead: steps of 0.01 rad, so that the builder starts every
  // 1.5 degrees (a quarter of the default reuse angle of 6) and its set is published while the
  // frames keep drawing the current one; every other step waits for its frame (a frame made
  // while the builder runs), the others are replaced by the next request.
  {
    View view(sceneA, true);
    view.Mapper->SetInteractiveRebuildAhead(0.25);
    int notReduced = 0;
    for (int f = 0; f < 16; ++f)
    {
      view.Request(0.3 + 0.01 * f, true);
      if (f % 2 == 1)
      {
        view.Finish();
        notReduced += view.Mapper->GetLastFrameReduced() ? 0 : 1;
      }
    }
    view.Request(0.46, false);
    const auto stopped = view.Finish();
    std::printf(
      "5. orbit with rebuilds ahead: %d of 8 awaited moving frames not reduced\n", notReduced);
    if (notReduced != 0 || view.Mapper->GetLastFrameReduced() || stopped != exact(exactA, 0.46))
    {
      std::printf("FAILED: with rebuilds ahead, a moving frame was not reduced or the still "
                  "frame is not the exact frame bit for bit\n");
      fail = 1;
    }
  }
  return fail ? EXIT_FAILURE : EXIT_SUCCESS;
}

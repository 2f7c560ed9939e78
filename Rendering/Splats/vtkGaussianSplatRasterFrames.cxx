/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianSplatRasterFrames.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianSplatRasterFrames.h"

#include "ElapsedTime.h"
#include "ThreadCount.h"

#include "vtkGaussianSplatRasterImageFS.h"

#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <time.h>
#include <utility>

using vis4gs::MsSince;

namespace
{
// CPU milliseconds of the whole process (every thread: OpenMP's work of a step included).
double ProcessCpuMs()
{
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}
}

//------------------------------------------------------------------------------
vtkGaussianSplatRasterFrames::vtkGaussianSplatRasterFrames()
  : ImageTexture(vtkTextureObject::New())
  , DepthTexture(vtkTextureObject::New())
{
}

//------------------------------------------------------------------------------
vtkGaussianSplatRasterFrames::~vtkGaussianSplatRasterFrames()
{
  this->Cancel(); // (the frame in production is finished: the rasteriser cannot be stopped)
  this->SetAsynchronous(false);
  this->FinishLodBuild(0);
  this->ImageTexture->Delete();
  this->DepthTexture->Delete();
}

//------------------------------------------------------------------------------
bool vtkGaussianSplatRasterFrames::SameKey(const std::array<double, 25>& a,
  const std::array<double, 25>& b)
{
  for (int q = 0; q < 25; ++q)
  {
    const bool same =
      (q == 16 || q == 17) ? std::abs(a[q] - b[q]) <= 1e-7 * std::abs(b[q]) : a[q] == b[q];
    if (!same)
    {
      return false;
    }
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkGaussianSplatRasterFrames::SetAsynchronous(bool on)
{
  std::thread worker;
  {
    std::unique_lock<std::mutex> lock(this->Mutex);
    if (on == this->Asynchronous)
    {
      return;
    }
    this->Asynchronous = on;
    if (!on && this->Worker.joinable())
    {
      // The request not started yet is produced by the worker before it stops.
      this->Idle.wait(lock, [this] { return !this->Working && !this->Pending; });
      this->Stop = true;
      worker = std::move(this->Worker);
    }
  }
  this->Wake.notify_all();
  if (worker.joinable())
  {
    worker.join();
  }
  std::lock_guard<std::mutex> lock(this->Mutex);
  this->Stop = false;
}

//------------------------------------------------------------------------------
void vtkGaussianSplatRasterFrames::SetFrameReadyCallback(std::function<void()> callback)
{
  std::lock_guard<std::mutex> lock(this->CallbackMutex);
  this->Callback = std::move(callback);
}

//------------------------------------------------------------------------------
void vtkGaussianSplatRasterFrames::Submit(Request request)
{
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    if (this->Asynchronous)
    {
      this->Pending.reset(new Request(std::move(request)));
      if (!this->Worker.joinable())
      {
        this->Worker = std::thread([this] { this->Run(); });
      }
    }
  }
  if (this->Asynchronous)
  {
    this->Wake.notify_one();
    return;
  }
  // Synchronous: this thread is the producing one and nothing else touches Back or Ready.
  this->Produce(request, this->Back);
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    std::swap(this->Back, this->Ready);
    this->HasReady = true;
  }
  this->PrepareWantedLevelOfDetail();
}

//------------------------------------------------------------------------------
void vtkGaussianSplatRasterFrames::FinishLodBuild(std::uint64_t cloudVersion)
{
  if (!this->LodBuilder.joinable())
  {
    return;
  }
  this->LodBuilder.join();
  this->LodBuilt = false;
  if (!this->LodBuildFailed && this->LodBuildVersion == cloudVersion && cloudVersion != 0)
  {
    vis4gs::PublishSplatMovingSet(this->LodSet);
  }
  this->LodSet.Next.Ready = false;
  this->LodBuildCloud.reset();
}

//------------------------------------------------------------------------------
void vtkGaussianSplatRasterFrames::PrepareWantedLevelOfDetail()
{
  if (this->LodWanted && this->LodSource != this->LodWantedVersion)
  {
    this->FinishLodBuild(0); // (it reads the level of detail about to change)
    vis4gs::PrepareSplatLevelOfDetail(*this->LodWanted, this->Lod, this->LodWantedThreads);
    this->LodSource = this->LodWantedVersion;
    // The moving set's buffers too (the margin's ring adds a fifth at the default reuse angle,
    // more at wider ones): its rebuilds then neither allocate nor touch fresh pages.
    vis4gs::ReserveSplatMovingSet(
      this->LodSet, this->LodWantedBudget + this->LodWantedBudget / 2, this->LodWantedThreads);
  }
  this->LodWanted.reset();
}

//------------------------------------------------------------------------------
void vtkGaussianSplatRasterFrames::SetWorkerNice(int nice)
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  this->WorkerNice = nice;
}

//------------------------------------------------------------------------------
void vtkGaussianSplatRasterFrames::Run()
{
  std::unique_lock<std::mutex> lock(this->Mutex);
  // Before any parallel region: the OpenMP team this thread starts inherits it.
  vis4gs::LowerThreadPriority(this->WorkerNice);
  for (;;)
  {
    this->Wake.wait(lock, [this] { return this->Stop || this->Pending; });
    if (this->Stop)
    {
      return;
    }
    const std::unique_ptr<Request> request = std::move(this->Pending);
    this->Working = true;
    lock.unlock();
    this->Produce(*request, this->Back);
    lock.lock();
    std::swap(this->Back, this->Ready);
    this->HasReady = true;
    lock.unlock();
    {
      std::lock_guard<std::mutex> callbackLock(this->CallbackMutex);
      if (this->Callback)
      {
        this->Callback();
      }
    }
    lock.lock();
    // Idle only once the callback has returned: whoever waited (Wait()) may then drop the
    // callback knowing that none is still to come for these frames (a worker at a lower
    // priority than the waiting thread may be preempted between the two).
    this->Working = false;
    this->Idle.notify_all();
    if (!this->Pending && this->LodWanted)
    {
      // (Working stays false: this is no frame; a request arriving meanwhile waits for it.)
      lock.unlock();
      this->PrepareWantedLevelOfDetail();
      lock.lock();
    }
  }
}

//------------------------------------------------------------------------------
bool vtkGaussianSplatRasterFrames::TakeFinished(std::uint64_t cloudVersion, Frame& frame)
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  if (!this->HasReady)
  {
    return false;
  }
  this->HasReady = false;
  if (this->Ready.CloudVersion != cloudVersion)
  {
    return false;
  }
  std::swap(this->Ready, frame);
  return true;
}

//------------------------------------------------------------------------------
bool vtkGaussianSplatRasterFrames::Busy() const
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  return this->Working || this->Pending;
}

//------------------------------------------------------------------------------
void vtkGaussianSplatRasterFrames::Wait()
{
  std::unique_lock<std::mutex> lock(this->Mutex);
  this->Idle.wait(lock, [this] { return !this->Working && !this->Pending; });
}

//------------------------------------------------------------------------------
void vtkGaussianSplatRasterFrames::Cancel()
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  this->Pending.reset();
  this->Idle.notify_all();
}

//------------------------------------------------------------------------------
const vis4gs::RasterWorkspace<float>* vtkGaussianSplatRasterFrames::LastFullFrame(
  const vis4gs::Camera*& camera,
  vtkPolyData*& input,
  vtkMTimeType& inputTime,
  const vis4gs::PixelWeightRecord** weights) const
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  // Only a render (this thread) starts a new frame, so the buffers stay as they are until
  // the caller renders again.
  const bool reusable = this->FrameReusable && !this->Working && !this->Pending;
  camera = reusable ? &this->FrameCamera : nullptr;
  input = reusable ? this->FrameInput : nullptr;
  inputTime = reusable ? this->FrameInputTime : 0;
  if (weights)
  {
    *weights = reusable && this->Weights.Complete ? &this->Weights : nullptr;
  }
  return reusable ? &this->Work : nullptr;
}

//------------------------------------------------------------------------------
void vtkGaussianSplatRasterFrames::Produce(const Request& r, Frame& f)
{
  const auto t0 = std::chrono::steady_clock::now();
  // Each step's wall and CPU time, for the benchmarks (where a frame's time goes).
  auto stepStart = t0;
  double stepCpu = ProcessCpuMs();
  f.PhaseMs.fill(0.0);
  f.PhaseCpuMs.fill(0.0);
  auto endStep = [&](int step)
  {
    const auto now = std::chrono::steady_clock::now();
    const double cpu = ProcessCpuMs();
    f.PhaseMs[step] += std::chrono::duration<double, std::milli>(now - stepStart).count();
    f.PhaseCpuMs[step] += cpu - stepCpu;
    stepStart = now;
    stepCpu = cpu;
  };
  this->LodWanted.reset();
  f.Key = r.Key;
  f.CloudVersion = r.CloudVersion;
  f.Reduced = r.Reduced;
  f.SampleDistance = r.SampleDistance;
  f.Interactive = r.Interactive;
  f.Failed = false;
  f.Error.clear();
  f.Drawn = 0;
  const int threads = r.Settings.Threads;
  const vis4gs::GaussianCloud& cloud = *r.Cloud;
  const std::size_t n = cloud.Count;
  const vis4gs::Camera& camera = r.Camera;
  {
    // (LastFullFrame reads these under the lock while no frame is in production.)
    std::lock_guard<std::mutex> lock(this->Mutex);
    this->FrameReusable = false;
  }
  if (this->LodSource != 0 && this->LodSource != r.CloudVersion)
  {
    // A new scene: the old one's level of detail is not needed any more.
    this->FinishLodBuild(0);
    this->Lod = vis4gs::SplatLevelOfDetail();
    this->LodSet = vis4gs::SplatMovingSet();
    this->LodWork = vis4gs::RasterWorkspace<float>();
    this->LodSource = 0;
  }
  bool unmodified = !r.Reduced && r.FullResolution && r.Settings.ScaleModifier == 1.0;
  try
  {
    // Gaussian i of a reduced frame is Gaussian LodSet.Subset[i] of the cloud.
    vis4gs::RasterWorkspace<float>& work = r.Reduced ? this->LodWork : this->Work;
    if (r.Reduced)
    {
      if (this->LodSource != r.CloudVersion)
      {
        vis4gs::PrepareSplatLevelOfDetail(cloud, this->Lod, threads);
        this->LodSource = r.CloudVersion;
      }
      // Whether the published set serves this view, or serves it with this fraction of the
      // reuse angle to spare.
      auto serves = [&](double fraction)
      {
        return vis4gs::SplatMovingSetReusable(cloud,
          r.CloudVersion,
          camera,
          r.Budget,
          r.Settings,
          r.ReuseAngle,
          this->LodSet,
          fraction);
      };
      // A rebuild started ahead of need becomes the set once it has finished, or when the
      // current set does not serve this view any more (then this frame waits for it).
      if (this->LodBuilder.joinable() && (this->LodBuilt.load() || !serves(1.0)))
      {
        this->FinishLodBuild(r.CloudVersion);
      }
      // The compact copy of the selected Gaussians, kept while the view moves less than the
      // reuse angle, is projected with its own kept preparation.
      vis4gs::UpdateSplatMovingSet(cloud,
        r.CloudVersion,
        this->Lod,
        camera,
        r.Budget,
        r.Settings,
        r.ReuseAngle,
        r.ColorAngle,
        this->LodSet);
      if (r.RebuildAhead > 0.0 && r.ReuseAngle > 0.0 && !this->LodBuilder.joinable() &&
        !serves(r.RebuildAhead))
      {
        // The next set, for this view, on the builder thread: it reads the cloud, the level of
        // detail and the published set, and writes only the set's spare buffers, while the
        // frames keep projecting the published set.
        this->LodBuildCloud = r.Cloud;
        this->LodBuildVersion = r.CloudVersion;
        this->LodBuildFailed = false;
        this->LodBuilt = false;
        this->LodBuilder = std::thread(
          [this, camera, r]
          {
            try
            {
              vis4gs::BuildSplatMovingSet(*this->LodBuildCloud,
                r.CloudVersion,
                this->Lod,
                camera,
                r.Budget,
                r.Settings,
                r.ReuseAngle,
                r.ColorAngle,
                this->LodSet);
            }
            catch (const std::exception&)
            {
              // (dropped: the frame that needs a new set rebuilds it and reports the error)
              this->LodBuildFailed = true;
            }
            this->LodBuilt = true;
          });
      }
      endStep(0);
      vis4gs::ProjectSplatMovingSet(
        this->LodSet, camera, r.Settings, work.Projection, work.Prepared);
    }
    else
    {
      vis4gs::ProjectGaussians(
        cloud, camera, r.Settings, work.Projection, work.Prepared, r.CloudVersion);
    }
    endStep(1);
    vis4gs::ViewProjection<float>& projection = work.Projection;
    const std::size_t m = projection.Gaussians.size();
    f.Drawn = projection.Counts.Visible;
    if (r.Display)
    {
      vis4gs::SplatDisplayOptions opt = r.Display->Options;
      if (r.Reduced)
      {
        // The scores and selection of the Gaussians drawn.
        if (opt.Scores)
        {
          this->LodScores.resize(m);
          for (std::size_t i = 0; i < m; ++i)
          {
            this->LodScores[i] = opt.Scores[this->LodSet.Subset[i]];
          }
          opt.Scores = this->LodScores.data();
        }
        if (opt.Selected)
        {
          this->LodSelected.resize(m);
          for (std::size_t i = 0; i < m; ++i)
          {
            this->LodSelected[i] = opt.Selected[this->LodSet.Subset[i]];
          }
          opt.Selected = this->LodSelected.data();
        }
      }
      // Overlay colours, hiding, highlight and dimming replace the projected colours and
      // scale the opacities; hidden Gaussians are left out of the tile lists.
      this->TrueColors.resize(3 * m);
      for (std::size_t i = 0; i < m; ++i)
      {
        std::copy_n(projection.Gaussians[i].Color, 3, &this->TrueColors[3 * i]);
      }
      vis4gs::ComputeSplatDisplay(
        this->TrueColors.data(), m, opt, this->Display, this->Keep, threads);
      for (std::size_t i = 0; i < m; ++i)
      {
        auto& g = projection.Gaussians[i];
        if (!g.IsVisible())
        {
          continue;
        }
        if (!this->Keep[i])
        {
          g.Status = vis4gs::ProjectionStatus::OffScreen;
          --f.Drawn;
          unmodified = false;
          continue;
        }
        std::copy_n(&this->Display[4 * i], 3, g.Color);
        unmodified = unmodified && this->Display[4 * i + 3] == 1.0f;
        g.Opacity *= this->Display[4 * i + 3];
      }
    }
    endStep(2);
    vis4gs::BinGaussians<float>(projection, threads, work.Bins, work.Scratch);
    endStep(3);
    // Nothing replays the blending: the compositing reads the kernels from the projection.
    work.Composite.KeepKernels = false;
    // An exact frame keeps the blends the selections read (Brush and Frame then look them
    // up instead of replaying the compositing); not a reduced or modified frame.
    const bool record = unmodified && r.RecordThreshold > 0.0f;
    this->Weights.Complete = false;
    this->Weights.Threshold = record ? r.RecordThreshold : this->Weights.Threshold;
    vis4gs::CompositeTiles<float>(projection,
      work.Bins,
      r.Settings,
      this->Image,
      nullptr,
      nullptr,
      &work.Composite,
      true,
      record ? &this->Weights : nullptr);
    endStep(4);
    if (!r.Reduced)
    {
      std::lock_guard<std::mutex> lock(this->Mutex);
      this->FrameReusable = unmodified;
      this->FrameCamera = camera;
      this->FrameInput = r.Input;
      this->FrameInputTime = r.InputTime;
    }
    // The level of detail for the first moving frame is made once per scene after its first
    // picture is handed over (PrepareWantedLevelOfDetail).
    const bool wanted =
      !r.Reduced && r.Budget > 0 && r.Budget < n && this->LodSource != r.CloudVersion;
    this->LodWanted = wanted ? r.Cloud : nullptr;
    this->LodWantedVersion = wanted ? r.CloudVersion : 0;
    this->LodWantedThreads = threads;
    this->LodWantedBudget = r.Budget;
  }
  catch (const std::exception& e)
  {
    f.Failed = true;
    f.Error = e.what();
    return;
  }
  // Premultiplied RGBA and expected depth, flipped to OpenGL's bottom-up rows.
  const int w = this->Image.Width, h = this->Image.Height;
  const std::size_t pixels = static_cast<std::size_t>(w) * h;
  f.Width = w;
  f.Height = h;
  f.Texels.resize(4 * pixels);
  f.DepthTexels.resize(pixels);
  for (int y = 0; y < h; ++y)
  {
    const std::size_t src = static_cast<std::size_t>(y) * w;
    const std::size_t dst = static_cast<std::size_t>(h - 1 - y) * w;
    for (int x = 0; x < w; ++x)
    {
      const std::size_t s = src + x, d = dst + x;
      const float a = this->Image.Alpha[s];
      f.Texels[4 * d] = this->Image.Color[3 * s];
      f.Texels[4 * d + 1] = this->Image.Color[3 * s + 1];
      f.Texels[4 * d + 2] = this->Image.Color[3 * s + 2];
      f.Texels[4 * d + 3] = a;
      f.DepthTexels[d] = a > 0.0f ? this->Image.Depth[s] / a : 1.0e30f;
    }
  }
  endStep(5);
  f.Milliseconds = MsSince(t0);
}

//------------------------------------------------------------------------------
bool vtkGaussianSplatRasterFrames::Upload(vtkOpenGLRenderWindow* window,
  const Frame& frame,
  bool magnified)
{
  this->ImageTexture->SetContext(window);
  this->ImageTexture->SetMinificationFilter(
    magnified ? vtkTextureObject::Linear : vtkTextureObject::Nearest);
  this->ImageTexture->SetMagnificationFilter(
    magnified ? vtkTextureObject::Linear : vtkTextureObject::Nearest);
  this->ImageTexture->SetWrapS(vtkTextureObject::ClampToEdge);
  this->ImageTexture->SetWrapT(vtkTextureObject::ClampToEdge);
  this->DepthTexture->SetContext(window);
  this->DepthTexture->SetMinificationFilter(vtkTextureObject::Nearest);
  this->DepthTexture->SetMagnificationFilter(vtkTextureObject::Nearest);
  this->DepthTexture->SetWrapS(vtkTextureObject::ClampToEdge);
  this->DepthTexture->SetWrapT(vtkTextureObject::ClampToEdge);
  const auto w = static_cast<unsigned int>(frame.Width);
  const auto h = static_cast<unsigned int>(frame.Height);
  // (const_cast: Create2DFromRaw takes void* but only reads.)
  return this->ImageTexture->Create2DFromRaw(
           w, h, 4, VTK_FLOAT, const_cast<float*>(frame.Texels.data())) &&
    this->DepthTexture->Create2DFromRaw(
      w, h, 1, VTK_FLOAT, const_cast<float*>(frame.DepthTexels.data()));
}

//------------------------------------------------------------------------------
bool vtkGaussianSplatRasterFrames::Draw(vtkOpenGLRenderWindow* window, const double depthCoeffs[2])
{
  if (!this->Quad)
  {
    this->Quad.reset(new vtkOpenGLQuadHelper(window, nullptr, vtkGaussianSplatRasterImageFS, ""));
    if (!this->Quad->Program)
    {
      this->Quad.reset();
      return false;
    }
  }
  else
  {
    window->GetShaderCache()->ReadyShaderProgram(this->Quad->Program);
  }
  vtkShaderProgram* prog = this->Quad->Program;
  this->ImageTexture->Activate();
  this->DepthTexture->Activate();
  prog->SetUniformi("splatImage", this->ImageTexture->GetTextureUnit());
  prog->SetUniformi("splatDepth", this->DepthTexture->GetTextureUnit());
  const float coeffs[2] = { static_cast<float>(depthCoeffs[0]),
    static_cast<float>(depthCoeffs[1]) };
  prog->SetUniform2f("depthCoeffs", coeffs);
  vtkOpenGLState* state = window->GetState();
  vtkOpenGLState::ScopedglEnableDisable blendSaver(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthSaver(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable cullSaver(state, GL_CULL_FACE);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFuncSaver(state);
  vtkOpenGLState::ScopedglDepthMask depthMaskSaver(state);
  vtkOpenGLState::ScopedglColorMask colorMaskSaver(state);
  vtkOpenGLState::ScopedglDepthFunc depthFuncSaver(state);
  state->vtkglEnable(GL_DEPTH_TEST);
  state->vtkglDepthFunc(GL_LEQUAL);
  state->vtkglDisable(GL_CULL_FACE);
  state->vtkglEnable(GL_BLEND);
  state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  state->vtkglDepthMask(GL_FALSE);
  prog->SetUniformi("depthPass", 0);
  this->Quad->Render();
  state->vtkglColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  state->vtkglDepthMask(GL_TRUE);
  prog->SetUniformi("depthPass", 1);
  this->Quad->Render();
  this->DepthTexture->Deactivate();
  this->ImageTexture->Deactivate();
  return true;
}

//------------------------------------------------------------------------------
void vtkGaussianSplatRasterFrames::ReleaseGraphicsResources(vtkWindow* window)
{
  if (window)
  {
    this->ImageTexture->ReleaseGraphicsResources(window);
    this->DepthTexture->ReleaseGraphicsResources(window);
  }
  this->Quad.reset();
}

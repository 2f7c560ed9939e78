/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianSplatRasterFrames.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianSplatRasterFrames
 * @brief   vtkGaussianSplatMapper's CPU-rasteriser path: produces frames, on the calling
 *          thread or on a worker thread, and draws the last finished one.
 *
 * Not a VTK object (a private part of the mapper, not wrapped). A frame is produced for a
 * Request (the cloud, its camera at the image's resolution, the level of detail and the
 * display overlay) with Core's rasteriser: the projection (all Gaussians, or the budget's
 * Gaussians of highest expected contribution for a moving frame), the overlay colours and
 * hiding, binning and compositing, then the image is turned into OpenGL's bottom-up texels
 * (premultiplied RGBA and the expected depth).
 *
 * Synchronous (default): Submit() produces the frame before it returns. Asynchronous: one
 * std::thread (joined by the destructor) produces the frames; Submit() replaces the request
 * not started yet (the newest request wins) and returns at once; the frame-ready callback is
 * called on the worker thread when a frame is finished, so that the owner can ask its GUI
 * thread for a render; TakeFinished() hands the newest finished frame to the render thread,
 * which uploads and draws it. Frames of a cloud version older than the one given to
 * TakeFinished() are dropped, so a frame of a replaced scene is never shown.
 *
 * The rasteriser's buffers (projection, tile lists, compositing data) and the level of
 * detail's per-scene data are owned by the producing thread and kept between frames.
 */
#ifndef vtkGaussianSplatRasterFrames_h
#define vtkGaussianSplatRasterFrames_h

#include "Camera.h"
#include "Rasterizer.h"
#include "SplatAttributes.h"
#include "SplatLevelOfDetail.h"
#include "SplatMovingSet.h"

#include "vtkType.h"

#include <array>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

class vtkOpenGLQuadHelper;
class vtkOpenGLRenderWindow;
class vtkPolyData;
class vtkTextureObject;
class vtkWindow;

class vtkGaussianSplatRasterFrames
{
public:
  /// The overlay of a frame: scores and selection (one per Gaussian of the cloud) and the
  /// options that point into them.
  struct Overlay
  {
    std::vector<double> Scores;
    std::vector<std::uint8_t> Selected;
    vis4gs::SplatDisplayOptions Options;
  };

  /// What a frame is rendered for. Key identifies it (camera, sizes, display time, input
  /// time, budget); SameKey() compares two.
  struct Request
  {
    std::shared_ptr<const vis4gs::GaussianCloud> Cloud;
    std::uint64_t CloudVersion = 0;
    vis4gs::Camera Camera; ///< at the image's resolution
    vis4gs::RasterSettings Settings;
    std::size_t Budget = 0; ///< level of detail (0: none)
    bool Reduced = false;   ///< draw the Budget's Gaussians only (a moving frame)
    /// Radians the view may move before a reduced frame's Gaussians and colours are chosen
    /// again (vis4gs::SplatMovingSet; 0: for every frame).
    double ReuseAngle = 0.0;
    /// Radians the view may move before the colours of the Gaussians a reduced frame keeps
    /// drawing are evaluated again (0: at every choice).
    double ColorAngle = 0.0;
    /// Fraction of ReuseAngle the view may move before the next choice of a reduced frame's
    /// Gaussians starts on a builder thread, while the frames keep drawing the current one
    /// (0: chosen again only when a frame needs it, on the producing thread).
    double RebuildAhead = 0.0;
    bool FullResolution = false;
    double SampleDistance = 1.0;            ///< image pixels per screen pixel, for the record
    bool Interactive = false;               ///< a moving frame (the sample distance adapts to it)
    std::shared_ptr<const Overlay> Display; ///< nullptr: true colours, every Gaussian
    vtkPolyData* Input = nullptr;           ///< identity only (GetLastFullFrame)
    vtkMTimeType InputTime = 0;
    /// An exact frame (full resolution, unmodified Gaussians) keeps the blends of weight >=
    /// this for the selections (vis4gs::PixelWeightRecord); 0: none kept.
    float RecordThreshold = 0.0f;
    std::array<double, 25> Key{};
  };

  /// A finished frame: bottom-up premultiplied RGBA and expected view depth per pixel.
  struct Frame
  {
    std::vector<float> Texels;
    std::vector<float> DepthTexels;
    int Width = 0, Height = 0;
    std::size_t Drawn = 0;
    double Milliseconds = 0.0; ///< wall time of the production
    /// Wall and process CPU milliseconds (all threads) of the production's steps, in the order
    /// of vtkGaussianSplatMapper::GetLastRasterPhaseTimes(): the level of detail (selection or
    /// reuse), projection, overlay, binning, compositing, texels.
    std::array<double, 6> PhaseMs{};
    std::array<double, 6> PhaseCpuMs{};
    bool Reduced = false;
    double SampleDistance = 1.0;
    bool Interactive = false;
    bool Failed = false;
    std::string Error;
    std::array<double, 25> Key{};
    std::uint64_t CloudVersion = 0;
  };

  vtkGaussianSplatRasterFrames();
  ~vtkGaussianSplatRasterFrames();
  vtkGaussianSplatRasterFrames(const vtkGaussianSplatRasterFrames&) = delete;
  vtkGaussianSplatRasterFrames& operator=(const vtkGaussianSplatRasterFrames&) = delete;

  /// Two keys are equal; the focal lengths (16, 17) come out of vtkCamera's projection matrix
  /// with a few ulps of noise between renders of the same view: compared to 1e-7.
  static bool SameKey(const std::array<double, 25>& a, const std::array<double, 25>& b);

  /// Produce frames on a worker thread (started on the first asynchronous Submit()).
  /// Switching off waits for the frame in production.
  void SetAsynchronous(bool on);
  bool GetAsynchronous() const { return this->Asynchronous; }

  /// The worker's nice value (vis4gs::LowerThreadPriority), taken when the worker starts.
  void SetWorkerNice(int nice);

  /// Called on the worker thread after each finished frame (asynchronous mode); clearing it
  /// waits for a call in progress.
  void SetFrameReadyCallback(std::function<void()> callback);

  /// Produces @p request now (synchronous) or hands it to the worker, replacing a request it
  /// has not started.
  void Submit(Request request);

  /// Moves the newest finished frame into @p frame; false when none is waiting. Frames of a
  /// cloud version other than @p cloudVersion are dropped (false).
  bool TakeFinished(std::uint64_t cloudVersion, Frame& frame);

  /// Whether a request is waiting or in production (its frame-ready callback included).
  bool Busy() const;

  /// Blocks until no request is waiting or in production: every frame-ready callback of the
  /// frames made so far has returned.
  void Wait();

  /// Drops the request not started yet (the scene changed).
  void Cancel();

  /// The workspace of the last full-resolution, unmodified, exact frame, the camera and input
  /// it was made for; nullptr while a frame is in production (the buffers are the worker's)
  /// or when the last frame was not such a frame. With @p weights, also the blends that frame's
  /// compositing kept (nullptr when it kept none: Request::RecordThreshold 0, or over the
  /// record's budget).
  const vis4gs::RasterWorkspace<float>* LastFullFrame(const vis4gs::Camera*& camera,
    vtkPolyData*& input,
    vtkMTimeType& inputTime,
    const vis4gs::PixelWeightRecord** weights = nullptr) const;

  /// Uploads @p frame (magnified linearly when smaller than the viewport) to @p window.
  bool Upload(vtkOpenGLRenderWindow* window, const Frame& frame, bool magnified);

  /// Draws the uploaded image depth-tested at its expected depth, then writes that depth
  /// where alpha >= 0.5 (@p depthCoeffs: the projection's z row). False: shaders failed.
  bool Draw(vtkOpenGLRenderWindow* window, const double depthCoeffs[2]);

  void ReleaseGraphicsResources(vtkWindow* window);

private:
  void Produce(const Request& request, Frame& frame);
  // Waits for the builder thread; its rebuild becomes LodSet's when it was made for
  // @p cloudVersion and did not fail (otherwise it is dropped).
  void FinishLodBuild(std::uint64_t cloudVersion);
  void Run();
  void PrepareWantedLevelOfDetail();

  // Producing thread's state: the rasteriser's buffers and the level of detail.
  vis4gs::RasterWorkspace<float> Work;
  vis4gs::RasterWorkspace<float> LodWork;
  vis4gs::RasterImage<float> Image;
  vis4gs::SplatLevelOfDetail Lod;
  std::uint64_t LodSource = 0;
  std::shared_ptr<const vis4gs::GaussianCloud> LodWanted; // after the frame is handed over
  std::uint64_t LodWantedVersion = 0;
  int LodWantedThreads = 0;
  std::size_t LodWantedBudget = 0;
  vis4gs::SplatMovingSet LodSet; // the reduced frames' Gaussians, kept while the view moves
  // A rebuild of LodSet ahead of need (Request::RebuildAhead): the thread, whether it has
  // finished, the cloud it holds and that cloud's version.
  std::thread LodBuilder;
  std::atomic<bool> LodBuilt{ false };
  bool LodBuildFailed = false;
  std::shared_ptr<const vis4gs::GaussianCloud> LodBuildCloud;
  std::uint64_t LodBuildVersion = 0;
  std::vector<double> LodScores;
  std::vector<std::uint8_t> LodSelected;
  std::vector<float> TrueColors;
  std::vector<float> Display;
  std::vector<std::uint8_t> Keep;
  bool FrameReusable = false;
  vis4gs::PixelWeightRecord Weights; // the last exact frame's blends (Request::RecordThreshold)
  vis4gs::Camera FrameCamera;
  vtkPolyData* FrameInput = nullptr;
  vtkMTimeType FrameInputTime = 0;

  // Hand-over between the render thread and the worker (Mutex guards everything below).
  mutable std::mutex Mutex;
  std::condition_variable Wake;
  std::condition_variable Idle;
  std::unique_ptr<Request> Pending;
  bool Working = false;
  bool Stop = false;
  Frame Back;  // the producing thread's
  Frame Ready; // finished, not taken yet
  bool HasReady = false;
  bool Asynchronous = false;
  int WorkerNice = 0;
  std::thread Worker;
  std::mutex CallbackMutex; // held while the callback runs
  std::function<void()> Callback;

  // Render thread's OpenGL side.
  std::unique_ptr<vtkOpenGLQuadHelper> Quad;
  vtkTextureObject* ImageTexture;
  vtkTextureObject* DepthTexture;
};

#endif
// VTK-HeaderTest-Exclude: vtkGaussianSplatRasterFrames.h

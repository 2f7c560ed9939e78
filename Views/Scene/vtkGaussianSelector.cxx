/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianSelector.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianSelector.h"

#include "ElapsedTime.h"
#include "GaussianOctree.h"
#include "ScreenSelection.h"
#include "SelectionSet.h"
#include "Vis4GSDataModel.h"
#include "vtkGaussianCameraUtilities.h"
#include "vtkGaussianSplatMapper.h"

#include "vtkAnnotationLink.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkGaussianSelectionHub.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderer.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkWeakPointer.h"

#include <array>
#include <chrono>
#include <cmath>
#include <exception>
#include <memory>
#include <vector>

using vis4gs::MsSince;

namespace
{
// The projection and tile lists @p mapper last drew, when they are provably those of
// @p scene's @p count Gaussians seen by @p view (same scene object and MTime, equal camera
// and size; the mapper vouches for full resolution, ScaleModifier 1 and unmodified
// Gaussians); nullptr otherwise.
const vis4gs::RasterWorkspace<float>* DrawnFrame(vtkGaussianSplatMapper* mapper,
  vtkPolyData* scene,
  const vis4gs::Camera& view,
  std::size_t count,
  const vis4gs::PixelWeightRecord** weights = nullptr)
{
  if (weights)
  {
    *weights = nullptr;
  }
  if (!mapper || !scene)
  {
    return nullptr;
  }
  const vis4gs::Camera* cam = nullptr;
  vtkPolyData* input = nullptr;
  vtkMTimeType inputTime = 0;
  const vis4gs::PixelWeightRecord* kept = nullptr;
  const vis4gs::RasterWorkspace<float>* frame =
    mapper->GetLastFullFrame(cam, input, inputTime, &kept);
  if (!frame || !cam || input != scene || inputTime != scene->GetMTime() ||
    cam->WorldToCamera != view.WorldToCamera || cam->Fx != view.Fx || cam->Fy != view.Fy ||
    cam->Width != view.Width || cam->Height != view.Height ||
    frame->Projection.Width != view.Width || frame->Projection.Height != view.Height ||
    frame->Projection.Gaussians.size() != count)
  {
    return nullptr;
  }
  if (weights && kept && kept->Width == view.Width && kept->Height == view.Height)
  {
    *weights = kept;
  }
  return frame;
}
}

//------------------------------------------------------------------------------
struct vtkGaussianSelector::vtkInternals
{
  // The Core form of the scene (its GaussianIds included): converted here, or shared
  // (SetSharedGaussians). Null until a scene is prepared.
  std::shared_ptr<const vis4gs::GaussianCloud> Cloud;
  std::shared_ptr<const vis4gs::GaussianCloud> Shared;
  vtkPolyData* SharedScene = nullptr; // identity only
  vtkMTimeType SharedSceneTime = 0;
  vtkMTimeType SceneTime = 0;
  vtkPolyData* SceneSeen = nullptr;
  bool SceneValid = false;
  vis4gs::Camera ViewCamera;
  bool ViewValid = false;
  vis4gs::SelectionView View;
  vis4gs::GaussianOctree Octree;
  bool OctreeValid = false;
  std::vector<std::int64_t> Current;
  vtkWeakPointer<vtkGaussianSelectionHub> Hub;
  vtkNew<vtkSelection> Selection;
  vtkNew<vtkIdTypeArray> SelectedIds;
  vtkNew<vtkIdTypeArray> RayIds;
  vtkNew<vtkDoubleArray> RayDistances;
  vtkNew<vtkDoubleArray> RayAlphas;
  vtkNew<vtkDoubleArray> RayWeights;
  int Width = 0, Height = 0, OriginX = 0, OriginY = 0;
};

// The hub combines a pick by the selector's Modifier as by its own mode.
static_assert(int(vtkGaussianSelector::REPLACE) == int(vtkGaussianSelectionHub::REPLACE) &&
    int(vtkGaussianSelector::ADD) == int(vtkGaussianSelectionHub::ADD) &&
    int(vtkGaussianSelector::SUBTRACT) == int(vtkGaussianSelectionHub::SUBTRACT) &&
    int(vtkGaussianSelector::TOGGLE) == int(vtkGaussianSelectionHub::TOGGLE),
  "the selector's modifiers are the hub's modes");

vtkStandardNewMacro(vtkGaussianSelector);
vtkCxxSetObjectMacro(vtkGaussianSelector, Scene, vtkPolyData);
vtkCxxSetObjectMacro(vtkGaussianSelector, Renderer, vtkRenderer);
vtkCxxSetObjectMacro(vtkGaussianSelector, AnnotationLink, vtkAnnotationLink);
vtkCxxSetObjectMacro(vtkGaussianSelector, SplatMapper, vtkGaussianSplatMapper);

//------------------------------------------------------------------------------
vtkGaussianSelector::vtkGaussianSelector()
  : Internals(new vtkInternals)
{
  this->Internals->SelectedIds->SetName(vis4gs::arrays::GaussianId);
  this->Internals->RayIds->SetName(vis4gs::arrays::GaussianId);
  this->Internals->RayDistances->SetName("Depth");
  this->Internals->RayAlphas->SetName("Alpha");
  this->Internals->RayWeights->SetName("Weight");
}

//------------------------------------------------------------------------------
vtkGaussianSelector::~vtkGaussianSelector()
{
  this->SetScene(nullptr);
  this->SetRenderer(nullptr);
  this->SetAnnotationLink(nullptr);
  this->SetSplatMapper(nullptr);
}

//------------------------------------------------------------------------------
// Scene and view preparation shared by every mode; false (with an error) when impossible.
bool vtkGaussianSelector::PrepareView(bool needView)
{
  vtkGaussianSelector* self = this;
  vtkInternals& in = *this->Internals;
  vtkPolyData* scene = this->Scene;
  vtkRenderer* renderer = this->Renderer;
  const int threads = this->NumberOfThreads;
  double& prepareMs = this->LastPrepareTime;
  prepareMs = 0;
  if (!scene || !renderer)
  {
    vtkErrorWithObjectMacro(self, "vtkGaussianSelector: set a scene and a renderer first");
    return false;
  }
  const auto t0 = std::chrono::steady_clock::now();
  if (scene != in.SceneSeen || scene->GetMTime() != in.SceneTime)
  {
    in.SceneSeen = scene;
    in.SceneTime = scene->GetMTime();
    in.ViewValid = false;
    in.OctreeValid = false;
    in.View = vis4gs::SelectionView();
    in.Cloud.reset(); // (the old copy is released before a new one is made)
    std::string error;
    const bool shared =
      in.Shared && in.SharedScene == scene && in.SharedSceneTime == scene->GetMTime();
    in.Cloud = shared ? in.Shared : vtkGaussianSplatMapper::ConvertScene(scene, &error);
    if (!shared)
    {
      in.Shared.reset();
    }
    in.SceneValid = in.Cloud != nullptr;
    if (!in.SceneValid)
    {
      vtkErrorWithObjectMacro(self, "vtkGaussianSelector: " << error);
      return false;
    }
  }
  if (!in.SceneValid)
  {
    vtkErrorWithObjectMacro(self, "vtkGaussianSelector: the scene is not a Gaussian scene");
    return false;
  }
  const int* size = renderer->GetSize();
  const int* origin = renderer->GetOrigin();
  in.Width = size[0];
  in.Height = size[1];
  in.OriginX = origin[0];
  in.OriginY = origin[1];
  try
  {
    const vis4gs::Camera cam =
      vtkGaussianCameraUtilities::FromVTKCamera(renderer->GetActiveCamera(), size[0], size[1]);
    const bool same = in.ViewValid && cam.WorldToCamera == in.ViewCamera.WorldToCamera &&
      cam.Fx == in.ViewCamera.Fx && cam.Fy == in.ViewCamera.Fy &&
      cam.Width == in.ViewCamera.Width && cam.Height == in.ViewCamera.Height;
    in.ViewCamera = cam;
    if (needView && !same)
    {
      in.View = vis4gs::PrepareSelectionView(*in.Cloud, cam, threads);
      in.ViewValid = true;
    }
    else if (!same)
    {
      in.ViewValid = false;
    }
  }
  catch (const std::exception& e)
  {
    vtkErrorWithObjectMacro(self, "vtkGaussianSelector: " << e.what());
    in.ViewValid = false;
    return false;
  }
  prepareMs = MsSince(t0);
  return true;
}

//------------------------------------------------------------------------------
void vtkGaussianSelector::SetSharedGaussians(vtkPolyData* scene,
  std::shared_ptr<const vis4gs::GaussianCloud> cloud)
{
  vtkInternals& in = *this->Internals;
  in.Shared = std::move(cloud);
  in.SharedScene = in.Shared ? scene : nullptr;
  in.SharedSceneTime = in.Shared && scene ? scene->GetMTime() : 0;
  if (in.Shared && scene && scene == in.SceneSeen && in.SceneTime == in.SharedSceneTime &&
    in.SceneValid && in.Cloud != in.Shared)
  {
    // The same Gaussians: hold the shared copy so that the selector's own is released (the
    // cached projection was computed from equal values; the octree points into the copy).
    in.Cloud = in.Shared;
    in.OctreeValid = false;
    in.Octree = vis4gs::GaussianOctree();
  }
}

//------------------------------------------------------------------------------
void vtkGaussianSelector::SetSelectionHub(vtkGaussianSelectionHub* hub)
{
  if (this->Internals->Hub != hub)
  {
    this->Internals->Hub = hub;
    this->Modified();
  }
}

vtkGaussianSelectionHub* vtkGaussianSelector::GetSelectionHub()
{
  return this->Internals->Hub;
}

//------------------------------------------------------------------------------
void vtkGaussianSelector::ClearSelection()
{
  this->Internals->Current.clear();
  if (vtkGaussianSelectionHub* hub = this->Internals->Hub)
  {
    hub->ClearSelection();
  }
  this->GetSelection();
  if (this->AnnotationLink)
  {
    this->AnnotationLink->SetCurrentSelection(this->Internals->Selection);
    this->AnnotationLink->InvokeEvent(
      vtkCommand::AnnotationChangedEvent, this->Internals->Selection);
  }
  this->Modified();
}

//------------------------------------------------------------------------------
vtkSelection* vtkGaussianSelector::GetSelection()
{
  vtkInternals& in = *this->Internals;
  in.SelectedIds->SetNumberOfTuples(static_cast<vtkIdType>(in.Current.size()));
  for (std::size_t k = 0; k < in.Current.size(); ++k)
  {
    in.SelectedIds->SetValue(static_cast<vtkIdType>(k), static_cast<vtkIdType>(in.Current[k]));
  }
  in.SelectedIds->Modified();
  in.Selection->RemoveAllNodes();
  vtkNew<vtkSelectionNode> node;
  node->SetContentType(vtkSelectionNode::PEDIGREEIDS);
  node->SetFieldType(vtkSelectionNode::POINT);
  // (The node holds the selector's array itself, refreshed at every pick as it is.)
  node->SetSelectionList(in.SelectedIds);
  in.Selection->AddNode(node);
  return in.Selection;
}

//------------------------------------------------------------------------------
vtkIdTypeArray* vtkGaussianSelector::GetSelectedIds()
{
  this->GetSelection();
  return this->Internals->SelectedIds;
}

//------------------------------------------------------------------------------
vtkIdTypeArray* vtkGaussianSelector::GetRayHitIds()
{
  return this->Internals->RayIds;
}

//------------------------------------------------------------------------------
vtkDoubleArray* vtkGaussianSelector::GetRayHitDistances()
{
  return this->Internals->RayDistances;
}

//------------------------------------------------------------------------------
vtkDoubleArray* vtkGaussianSelector::GetRayHitAlphas()
{
  return this->Internals->RayAlphas;
}

//------------------------------------------------------------------------------
vtkDoubleArray* vtkGaussianSelector::GetRayHitWeights()
{
  return this->Internals->RayWeights;
}

//------------------------------------------------------------------------------
void vtkGaussianSelector::PublishIndices(const std::vector<unsigned int>& indices)
{
  const auto t0 = std::chrono::steady_clock::now();
  vtkInternals& in = *this->Internals;
  const int modifier = this->Modifier;
  vtkAnnotationLink* link = this->AnnotationLink;
  vtkGaussianSelector* self = this;
  std::vector<std::int64_t> ids;
  ids.reserve(indices.size());
  for (std::uint32_t i : indices)
  {
    ids.push_back(in.Cloud->GetId(i));
  }
  vtkGaussianSelectionHub* hub = in.Hub;
  // With a hub the hub combines (its selection holds the other views' picks too); the selector
  // keeps the pick alone, sorted and unique.
  in.Current = vis4gs::CombineSelection(hub ? std::vector<std::int64_t>() : in.Current,
    std::move(ids),
    static_cast<vis4gs::SelectionModifier>(hub ? REPLACE : modifier));
  if (hub)
  {
    // The selector's modifiers are the hub's modes (both REPLACE, ADD, SUBTRACT, TOGGLE).
    static_assert(sizeof(vtkIdType) == sizeof(std::int64_t), "GaussianIds are 64-bit");
    hub->SelectIds(reinterpret_cast<const vtkIdType*>(in.Current.data()),
      static_cast<vtkIdType>(in.Current.size()),
      modifier);
  }
  // (Callers hold GetSelection() and GetSelectedIds() across picks: both are refreshed.)
  vtkSelection* sel = self->GetSelection();
  if (link)
  {
    link->SetCurrentSelection(sel);
    link->InvokeEvent(vtkCommand::AnnotationChangedEvent, sel);
  }
  self->Modified();
  this->LastPublishTime = MsSince(t0);
}

//------------------------------------------------------------------------------
// Single and Brush: the scene view's drawn frame when it is this camera's (no projection
// needed), else the prepared selection view.
bool vtkGaussianSelector::PrepareViewOrFrame(const vis4gs::RasterWorkspace<float>*& frame,
  const vis4gs::PixelWeightRecord** weights)
{
  vtkInternals& in = *this->Internals;
  frame = nullptr;
  if (weights)
  {
    *weights = nullptr;
  }
  if (!this->PrepareView(false))
  {
    return false;
  }
  if (!in.ViewValid)
  {
    frame = DrawnFrame(this->SplatMapper, this->Scene, in.ViewCamera, in.Cloud->Count, weights);
  }
  if (!frame && !this->PrepareView(true))
  {
    return false;
  }
  this->LastSelectionReusedFrame = frame != nullptr;
  return true;
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianSelector::SelectSingle(double x, double y)
{
  const auto t0 = std::chrono::steady_clock::now();
  vtkInternals& in = *this->Internals;
  this->LastSelectionReusedFrame = false;
  this->LastSelectionReadWeights = false;
  const vis4gs::RasterWorkspace<float>* frame = nullptr;
  if (!this->PrepareViewOrFrame(frame))
  {
    return -1;
  }
  const int px = static_cast<int>(std::floor(x)) - in.OriginX;
  const int py = in.Height - 1 - (static_cast<int>(std::floor(y)) - in.OriginY);
  std::int64_t g = -1;
  try
  {
    g = frame ? vis4gs::SelectSingle(frame->Projection, frame->Bins, px, py)
              : vis4gs::SelectSingle(in.View, px, py);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("vtkGaussianSelector: " << e.what());
    return -1;
  }
  std::vector<std::uint32_t> picked;
  if (g >= 0)
  {
    picked.push_back(static_cast<std::uint32_t>(g));
  }
  this->PublishIndices(picked);
  this->LastSelectionTime = MsSince(t0);
  return static_cast<vtkIdType>(picked.size());
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianSelector::SelectBrush(vtkPoints* stroke)
{
  const auto t0 = std::chrono::steady_clock::now();
  vtkInternals& in = *this->Internals;
  this->LastSelectionReusedFrame = false;
  this->LastSelectionReadWeights = false;
  const vis4gs::RasterWorkspace<float>* frame = nullptr;
  const vis4gs::PixelWeightRecord* weights = nullptr;
  if (!this->PrepareViewOrFrame(frame, &weights))
  {
    return -1;
  }
  std::vector<std::array<double, 2>> pts;
  for (vtkIdType k = 0; stroke && k < stroke->GetNumberOfPoints(); ++k)
  {
    double p[3];
    stroke->GetPoint(k, p);
    pts.push_back(
      { std::floor(p[0]) - in.OriginX, in.Height - 1 - (std::floor(p[1]) - in.OriginY) });
  }
  std::vector<std::uint32_t> picked;
  try
  {
    const auto pixels = vis4gs::BrushPixels(pts, this->BrushRadius, in.Width, in.Height);
    this->LastSelectionReadWeights =
      frame && weights && vis4gs::RecordAnswers(*weights, this->WeightThreshold);
    picked = this->LastSelectionReadWeights
      ? vis4gs::SelectBrush(
          *weights, frame->Projection.Gaussians.size(), pixels, this->WeightThreshold)
      : frame
      ? vis4gs::SelectBrush(
          frame->Projection, frame->Bins, pixels, this->WeightThreshold, this->NumberOfThreads)
      : vis4gs::SelectBrush(in.View, pixels, this->WeightThreshold, this->NumberOfThreads);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("vtkGaussianSelector: " << e.what());
    return -1;
  }
  this->PublishIndices(picked);
  this->LastSelectionTime = MsSince(t0);
  return static_cast<vtkIdType>(picked.size());
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianSelector::SelectFrame(double x0, double y0, double x1, double y1)
{
  const auto t0 = std::chrono::steady_clock::now();
  vtkInternals& in = *this->Internals;
  this->LastSelectionReusedFrame = false;
  this->LastSelectionReadWeights = false;
  // Scene and camera first, without projecting: the scene view's frame may serve.
  if (!this->PrepareView(false))
  {
    return -1;
  }
  vis4gs::FrameOptions fo;
  fo.WeightThreshold = this->WeightThreshold;
  fo.IncludeOccluded = this->IncludeOccluded;
  fo.Threads = this->NumberOfThreads;
  const int ax = static_cast<int>(std::floor(x0)) - in.OriginX;
  const int bx = static_cast<int>(std::floor(x1)) - in.OriginX;
  const int ay = in.Height - 1 - (static_cast<int>(std::floor(y0)) - in.OriginY);
  const int by = in.Height - 1 - (static_cast<int>(std::floor(y1)) - in.OriginY);
  // Every Gaussian's largest weight over the view (one compositing pass, cached with the
  // projection) lets visible-only frames replay only pixels near the rectangle's border. It
  // costs about what replaying the whole view costs (1M Gaussians, 1280x720: ~0.7 s of CPU
  // against ~0.1 s for replaying a dense 200x200 rectangle), so it is computed only for a
  // rectangle covering half of the view or more.
  const double area = (std::abs(x1 - x0) + 1.0) * (std::abs(y1 - y0) + 1.0);
  const bool wantMaxima =
    !this->IncludeOccluded && 2.0 * area >= static_cast<double>(in.Width) * in.Height;
  std::vector<std::uint32_t> picked;
  try
  {
    const vis4gs::PixelWeightRecord* weights = nullptr;
    const vis4gs::RasterWorkspace<float>* frame = in.ViewValid
      ? nullptr
      : DrawnFrame(this->SplatMapper, this->Scene, in.ViewCamera, in.Cloud->Count, &weights);
    this->LastSelectionReusedFrame = frame != nullptr;
    this->LastSelectionReadWeights = frame && !this->IncludeOccluded && weights &&
      vis4gs::RecordAnswers(*weights, this->WeightThreshold);
    if (this->LastSelectionReadWeights)
    {
      // The drawn frame's blends over the rectangle: no replay, no view maxima.
      picked = vis4gs::SelectFrame(frame->Projection, *weights, ax, ay, bx, by, fo);
    }
    else if (frame && !wantMaxima)
    {
      picked = vis4gs::SelectFrame(frame->Projection, frame->Bins, ax, ay, bx, by, fo);
    }
    else
    {
      if (frame)
      {
        // The view maxima are cached with the projection, which the mapper overwrites at its
        // next frame: the drawn frame is copied into the selector's view (~40 ms of CPU at
        // 1M Gaussians, against ~100-400 ms for projecting and binning again).
        in.View.Projection = frame->Projection;
        in.View.Bins = frame->Bins;
        in.View.Settings = vis4gs::RasterSettings();
        in.View.Settings.ComputeColors = false;
        in.View.Settings.Threads = this->NumberOfThreads;
        in.View.ViewMaxWeights.clear();
        in.ViewValid = true;
      }
      else if (!this->PrepareView(true))
      {
        return -1;
      }
      if (wantMaxima && in.View.ViewMaxWeights.empty())
      {
        vis4gs::ComputeViewMaxWeights(in.View);
      }
      picked = vis4gs::SelectFrame(in.View, ax, ay, bx, by, fo);
    }
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("vtkGaussianSelector: " << e.what());
    return -1;
  }
  this->PublishIndices(picked);
  this->LastSelectionTime = MsSince(t0);
  return static_cast<vtkIdType>(picked.size());
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianSelector::SelectRay(double x, double y)
{
  const auto t0 = std::chrono::steady_clock::now();
  vtkInternals& in = *this->Internals;
  this->LastSelectionReusedFrame = false;
  this->LastSelectionReadWeights = false;
  std::vector<vis4gs::RayContribution> hits;
  std::vector<vis4gs::RayHit> ellipsoidHits;
  try
  {
    if (this->RayEllipsoid)
    {
      if (!this->PrepareView(false))
      {
        return -1;
      }
      if (!in.OctreeValid || in.Octree.GetBoundSigmas() < this->RaySigmas)
      {
        const auto tb = std::chrono::steady_clock::now();
        vis4gs::GaussianOctree::Options o;
        o.BoundSigmas = std::max(3.0, this->RaySigmas);
        in.Octree.Build(*in.Cloud, o);
        in.OctreeValid = true;
        this->LastPrepareTime += MsSince(tb);
      }
      const double px = std::floor(x) - in.OriginX;
      const double py = in.Height - 1 - (std::floor(y) - in.OriginY);
      ellipsoidHits =
        in.Octree.IntersectRay(vis4gs::PixelRay(in.ViewCamera, px, py, this->RaySigmas));
    }
    else
    {
      const vis4gs::RasterWorkspace<float>* frame = nullptr;
      if (!this->PrepareViewOrFrame(frame))
      {
        return -1;
      }
      const int px = static_cast<int>(std::floor(x)) - in.OriginX;
      const int py = in.Height - 1 - (static_cast<int>(std::floor(y)) - in.OriginY);
      hits = frame ? vis4gs::SelectRay(frame->Projection, frame->Bins, px, py)
                   : vis4gs::SelectRay(in.View, px, py);
    }
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("vtkGaussianSelector: " << e.what());
    return -1;
  }
  const std::size_t n = this->RayEllipsoid ? ellipsoidHits.size() : hits.size();
  in.RayIds->SetNumberOfTuples(static_cast<vtkIdType>(n));
  in.RayDistances->SetNumberOfTuples(static_cast<vtkIdType>(n));
  in.RayDistances->SetName(this->RayEllipsoid ? "Sigmas" : "Depth");
  in.RayAlphas->SetNumberOfTuples(static_cast<vtkIdType>(this->RayEllipsoid ? 0 : n));
  in.RayWeights->SetNumberOfTuples(static_cast<vtkIdType>(this->RayEllipsoid ? 0 : n));
  std::vector<std::uint32_t> picked;
  for (std::size_t k = 0; k < n; ++k)
  {
    const vtkIdType t = static_cast<vtkIdType>(k);
    const std::uint32_t g = this->RayEllipsoid ? ellipsoidHits[k].Gaussian : hits[k].Gaussian;
    in.RayIds->SetValue(t, static_cast<vtkIdType>(in.Cloud->GetId(g)));
    if (this->RayEllipsoid)
    {
      in.RayDistances->SetValue(t, ellipsoidHits[k].Distance);
    }
    else
    {
      in.RayDistances->SetValue(t, hits[k].Depth);
      in.RayAlphas->SetValue(t, hits[k].Alpha);
      in.RayWeights->SetValue(t, hits[k].Weight);
    }
    picked.push_back(g);
  }
  in.RayIds->Modified();
  in.RayDistances->Modified();
  in.RayAlphas->Modified();
  in.RayWeights->Modified();
  this->PublishIndices(picked);
  this->LastSelectionTime = MsSince(t0);
  return static_cast<vtkIdType>(picked.size());
}

//------------------------------------------------------------------------------
void vtkGaussianSelector::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Scene: " << this->Scene << "\n";
  os << indent << "Renderer: " << this->Renderer << "\n";
  os << indent << "AnnotationLink: " << this->AnnotationLink << "\n";
  os << indent << "SelectionHub: " << this->Internals->Hub.GetPointer() << "\n";
  os << indent << "SplatMapper: " << this->SplatMapper << "\n";
  os << indent << "Modifier: " << this->Modifier << "\n";
  os << indent << "WeightThreshold: " << this->WeightThreshold << "\n";
  os << indent << "BrushRadius: " << this->BrushRadius << "\n";
  os << indent << "IncludeOccluded: " << this->IncludeOccluded << "\n";
  os << indent << "RaySigmas: " << this->RaySigmas << "\n";
  os << indent << "RayEllipsoid: " << this->RayEllipsoid << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "LastSelectionTime: " << this->LastSelectionTime << "\n";
  os << indent << "LastPrepareTime: " << this->LastPrepareTime << "\n";
  os << indent << "LastSelectionReusedFrame: " << this->LastSelectionReusedFrame << "\n";
  os << indent << "LastSelectionReadWeights: " << this->LastSelectionReadWeights << "\n";
  os << indent << "LastPublishTime: " << this->LastPublishTime << "\n";
  os << indent << "Selected: " << this->Internals->Current.size() << "\n";
}

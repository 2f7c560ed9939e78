/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianSplatMapper.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
// Over 1,200 lines on purpose: one mapper with two drawing paths (OpenGL splats, the CPU
// rasteriser) that share the input's conversion, the display options (scores, hiding,
// selection), the camera and the render window's interactive/still state; what each path
// computes lives in Core (SplatSortWorker, SplatAttributes, the rasteriser, the level of detail)
// and the CPU path's frame production and drawing in vtkGaussianSplatRasterFrames; this file
// holds the OpenGL splats and what both paths share.
#include "vtkGaussianSplatMapper.h"

#include "ElapsedTime.h"

#include "vtkGaussianCameraUtilities.h"
#include "vtkGaussianSplatFS.h"
#include "vtkGaussianSplatGS.h"
#include "vtkGaussianSplatInstancedVS.h"
#include "vtkGaussianSplatPointVS.h"
#include "vtkGaussianSplatProjection.h"
#include "vtkGaussianSplatRasterFrames.h"

#include "GaussianMath.h"
#include "Rasterizer.h"
#include "SortedIdLookup.h"
#include "SplatAttributes.h"
#include "SplatCamera.h"
#include "SplatLevelOfDetail.h"
#include "SplatSort.h"
#include "SplatSortWorker.h"
#include "Vis4GSDataModel.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkLookupTable.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRenderer.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkVariant.h"
#include "vtk_glew.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

using vis4gs::MsSince;

namespace
{
// The shaders are the files in glsl/, embedded at build time (vtk_encode_string, as VTK's
// own OpenGL2 module does). Both vertex paths share the per-Gaussian projection.
std::string SplatVertexShader(bool instanced)
{
  return std::string("//VTK::System::Dec\n") + vtkGaussianSplatProjection +
    (instanced ? vtkGaussianSplatInstancedVS : vtkGaussianSplatPointVS);
}

// CPU time of the calling thread (not the process: the sort worker and the OpenGL driver's
// threads are not counted), in milliseconds.
double ThreadCpuMs()
{
#if defined(CLOCK_THREAD_CPUTIME_ID)
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
#else
  return 0.0;
#endif
}

std::shared_ptr<const vis4gs::GaussianCloud> EmptyCloud()
{
  static const auto empty = std::make_shared<const vis4gs::GaussianCloud>();
  return empty;
}
} // namespace

//------------------------------------------------------------------------------
struct vtkGaussianSplatMapper::vtkInternals
{
  // CPU side.
  // The Core form of the input: converted here, or shared (SetSharedGaussians). Never null.
  std::shared_ptr<const vis4gs::GaussianCloud> Cloud = EmptyCloud();
  std::shared_ptr<const vis4gs::GaussianCloud> Shared;
  vtkPolyData* SharedInput = nullptr; // identity only
  vtkMTimeType SharedInputTime = 0;
  bool HasSH = false;
  std::vector<float> Geometry;    // packed, 12 per Gaussian
  std::vector<float> TrueColors;  // 3 per Gaussian (CPU path's overlays; grey without SH)
  std::vector<float> Display;     // 4 per Gaussian
  std::vector<std::uint8_t> Keep; // 1 per Gaussian
  std::vector<std::uint8_t> Selected;
  std::vector<double> Scores;
  // Selected GaussianIds to indices: the id is the index when the cloud has no ids; a binary
  // search in the cloud's ids when they ascend (a reader's output: no table); else IdOrder,
  // the indices sorted by id (4 bytes per Gaussian).
  std::vector<std::uint32_t> IdOrder;
  vis4gs::IdColumnOrder IdsOrder; // of the cloud's Ids (kept with the cloud: SetSharedGaussians
                                  // swaps in equal values)
  std::vector<float> Depths;      // scratch of the synchronous sort
  vtkMTimeType InputTime = 0;
  std::uint64_t CloudVersion = 0; // changes whenever Cloud is rebuilt (Work.Prepared's key)
  vtkMTimeType DisplayTime = 0;
  bool PackDirty = true;
  bool ColorsDirty = true;
  bool GeometryDirty = true;
  double AutoRange[2] = { 0.0, 1.0 };
  bool ReportedParallel = false;
  double PackedScale = std::nan("");
  int SoftwareGL = -1; // -1 not yet known

  // CPU rasteriser path (vtkGaussianSplatRasterFrames): the frames' producer, the key of
  // the image shown and of the last request, the overlay the requests share.
  vtkGaussianSplatRasterFrames Frames;
  vtkGaussianSplatRasterFrames::Frame Shown; // the last image uploaded (its buffers reused)
  std::array<double, 25> RasterKey{};
  bool RasterValid = false;
  std::array<double, 25> SubmittedKey{};
  bool SubmittedValid = false;
  double AdaptiveDistance = 0.0; // interactive sample distance (auto-adjusted); 0 = not set
  std::size_t RasterDrawn = 0;
  bool RasterReduced = false;
  vtkIdType FramesShown = 0;
  std::shared_ptr<const vtkGaussianSplatRasterFrames::Overlay> Overlay;
  std::array<double, 2> OverlayKey{ -1.0, -1.0 }; // display time, input time
  std::uint64_t OverlayVersion = 0;

  // OpenGL path's order: the worker, the order drawn (Front) and the keys of what it was
  // sorted for. SceneKey counts changes of what an order depends on besides the camera
  // (cloud, kept set, budget); CameraKey counts camera changes.
  vis4gs::SplatSortWorker Sorter;
  vis4gs::SplatSortResult Front;
  bool FrontValid = false;
  std::shared_ptr<const std::vector<std::uint8_t>> KeepShared; // nullptr: every one kept
  std::uint64_t KeepVersion = 0;
  std::array<std::uint64_t, 3> OrderScene{};
  std::uint64_t SceneKey = 0;
  std::array<double, 16> CameraW2C{};
  std::uint64_t CameraKey = 0;
  std::uint64_t SubmittedScene = 0;
  std::uint64_t SubmittedCamera = 0;
  vtkIdType SceneUploads = 0;
  vtkIdType OrderUploads = 0;

  // GPU side.
  vtkOpenGLRenderWindow* Window = nullptr;
  vtkShaderProgram* Program = nullptr;
  vtkShaderProgram* InstancedProgram = nullptr;
  vtkNew<vtkOpenGLVertexArrayObject> VAO;
  vtkNew<vtkOpenGLBufferObject> GeometryBuffer;
  vtkNew<vtkOpenGLBufferObject> ColorBuffer;
  vtkNew<vtkOpenGLBufferObject> OrderBuffer;
  vtkNew<vtkOpenGLBufferObject> ShBuffer;
  vtkNew<vtkTextureObject> GeometryTexture;
  vtkNew<vtkTextureObject> ShTexture;
  vtkNew<vtkTextureObject> ColorTexture;
  vtkNew<vtkTextureObject> OrderTexture;
  bool GeometryOnGPU = false;
  bool ColorsOnGPU = false;
  bool OrderOnGPU = false;
  bool ShOnGPU = false;
  std::size_t OrderBytes = 0; // size of OrderBuffer's store

  void Release(vtkWindow* w)
  {
    if (w)
    {
      this->VAO->ReleaseGraphicsResources();
      this->GeometryTexture->ReleaseGraphicsResources(w);
      this->ColorTexture->ReleaseGraphicsResources(w);
      this->OrderTexture->ReleaseGraphicsResources(w);
      this->ShTexture->ReleaseGraphicsResources(w);
      this->GeometryBuffer->ReleaseGraphicsResources();
      this->ColorBuffer->ReleaseGraphicsResources();
      this->OrderBuffer->ReleaseGraphicsResources();
      this->ShBuffer->ReleaseGraphicsResources();
    }
    this->Frames.ReleaseGraphicsResources(w);
    this->Program = nullptr;
    this->InstancedProgram = nullptr;
    this->Window = nullptr;
    this->SoftwareGL = -1;
    this->RasterValid = this->SubmittedValid = false; // (the image is gone with its texture)
    this->GeometryOnGPU = this->ColorsOnGPU = this->OrderOnGPU = this->ShOnGPU = false;
    this->GeometryDirty = this->ColorsDirty = true;
    this->OrderBytes = 0;
    // The packed geometry and display colours are freed once uploaded: made again.
    this->PackDirty = true;
    this->DisplayTime = 0;
  }

  // The overlay, hiding, highlight and dimming options of @p self for the current input
  // (fills Scores, AutoRange and Selected); false (error reported) when the score array is
  // missing.
  bool FillDisplayOptions(vtkGaussianSplatMapper* self,
    vtkPolyData* input,
    vis4gs::SplatDisplayOptions& opt)
  {
    const std::size_t n = this->Cloud->Count;
    this->Scores.clear();
    const bool needScores = self->SplatColoring == SCORE || self->HideOutsideRange;
    if (needScores)
    {
      vtkDataArray* arr =
        self->ScoreArrayName ? input->GetPointData()->GetArray(self->ScoreArrayName) : nullptr;
      if (!arr || arr->GetNumberOfTuples() != static_cast<vtkIdType>(n))
      {
        vtkErrorWithObjectMacro(self,
          "vtkGaussianSplatMapper: score array '"
            << (self->ScoreArrayName ? self->ScoreArrayName : "(none)")
            << "' is missing from the input point data");
        return false;
      }
      this->Scores.resize(n);
      double lo = VTK_DOUBLE_MAX, hi = VTK_DOUBLE_MIN;
      for (std::size_t i = 0; i < n; ++i)
      {
        const double s = arr->GetComponent(static_cast<vtkIdType>(i), 0);
        this->Scores[i] = s;
        if (std::isfinite(s))
        {
          lo = std::min(lo, s);
          hi = std::max(hi, s);
        }
      }
      this->AutoRange[0] = lo <= hi ? lo : 0.0;
      this->AutoRange[1] = lo <= hi ? hi : 1.0;
      opt.Scores = this->Scores.data();
    }
    opt.ScoreColoring = self->SplatColoring == SCORE;
    opt.Suspicious = vis4gs::SuspiciousEndOf(self->ScoreArrayName ? self->ScoreArrayName : "");
    opt.ColorRange = self->AutoScoreRange
      ? std::array<double, 2>{ this->AutoRange[0], this->AutoRange[1] }
      : std::array<double, 2>{ self->ScoreRange[0], self->ScoreRange[1] };
    opt.HideOutsideRange = self->HideOutsideRange;
    opt.VisibleRange = { self->VisibleRange[0], self->VisibleRange[1] };
    this->Selected.clear();
    vtkIdTypeArray* ids = self->SelectedIds;
    if (ids && ids->GetNumberOfTuples() > 0)
    {
      const std::vector<std::int64_t>& cloudIds = this->Cloud->Ids;
      this->Selected.assign(n, 0);
      const vtkIdType* idp = ids->GetPointer(0);
      const vtkIdType count = ids->GetNumberOfTuples();
      const bool ascending = std::is_sorted(idp, idp + count);
      if (cloudIds.size() == n && ascending && this->IdsOrder.Sorted)
      {
        // The hub's ids (sorted) in a snapshot's (sorted) ids: O(selection), on the render
        // thread once per selection.
        static_assert(sizeof(vtkIdType) == sizeof(std::int64_t), "64-bit vtkIdType");
        vis4gs::ForEachRowOfSortedIds(cloudIds.data(),
          n,
          this->IdsOrder,
          reinterpret_cast<const std::int64_t*>(idp),
          static_cast<std::size_t>(count),
          [&](std::size_t r) { this->Selected[r] = 1; });
      }
      else
      {
        // Any order: a binary search per id (in IdOrder when the cloud's ids do not ascend);
        // without ids the id is the index.
        for (vtkIdType k = 0; k < count; ++k)
        {
          const vtkIdType id = idp[k];
          if (cloudIds.size() != n)
          {
            if (id >= 0 && id < static_cast<vtkIdType>(n))
            {
              this->Selected[id] = 1;
            }
          }
          else if (this->IdOrder.empty())
          {
            const auto range = std::equal_range(cloudIds.begin(), cloudIds.end(), id);
            for (auto it = range.first; it != range.second; ++it)
            {
              this->Selected[static_cast<std::size_t>(it - cloudIds.begin())] = 1;
            }
          }
          else
          {
            auto it = std::lower_bound(this->IdOrder.begin(),
              this->IdOrder.end(),
              id,
              [&](std::uint32_t i, vtkIdType v) { return cloudIds[i] < v; });
            for (; it != this->IdOrder.end() && cloudIds[*it] == id; ++it)
            {
              this->Selected[*it] = 1;
            }
          }
        }
      }
      opt.Selected = this->Selected.data();
    }
    opt.Highlight = self->HighlightSelected;
    opt.HighlightColor = { static_cast<float>(self->HighlightColor[0]),
      static_cast<float>(self->HighlightColor[1]),
      static_cast<float>(self->HighlightColor[2]) };
    opt.HighlightMix = static_cast<float>(self->HighlightMix);
    opt.DimUnselected = self->DimUnselected && opt.Selected != nullptr;
    opt.DimOpacity = static_cast<float>(self->DimOpacity);
    return true;
  }
};

vtkStandardNewMacro(vtkGaussianSplatMapper);
vtkCxxSetObjectMacro(vtkGaussianSplatMapper, SelectedIds, vtkIdTypeArray);

//------------------------------------------------------------------------------
vtkGaussianSplatMapper::vtkGaussianSplatMapper()
  : Internals(new vtkInternals)
{
  this->ScalarVisibilityOff();
}

//------------------------------------------------------------------------------
vtkGaussianSplatMapper::~vtkGaussianSplatMapper()
{
  this->SetScoreArrayName(nullptr);
  this->SetSelectedIds(nullptr);
  if (this->ScoreLookupTable)
  {
    this->ScoreLookupTable->Delete();
  }
}

//------------------------------------------------------------------------------
void vtkGaussianSplatMapper::SetScoreRange(double lo, double hi)
{
  if (this->ScoreRange[0] != lo || this->ScoreRange[1] != hi || this->AutoScoreRange)
  {
    this->ScoreRange[0] = lo;
    this->ScoreRange[1] = hi;
    this->AutoScoreRange = false;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkGaussianSplatMapper::SetSelection(vtkSelection* selection)
{
  vtkIdTypeArray* found = nullptr;
  for (unsigned int n = 0; selection && n < selection->GetNumberOfNodes() && !found; ++n)
  {
    vtkSelectionNode* node = selection->GetNode(n);
    if (node->GetContentType() == vtkSelectionNode::PEDIGREEIDS ||
      node->GetContentType() == vtkSelectionNode::INDICES)
    {
      found = vtkIdTypeArray::SafeDownCast(node->GetSelectionList());
    }
  }
  if (found)
  {
    vtkNew<vtkIdTypeArray> copy;
    copy->DeepCopy(found);
    this->SetSelectedIds(copy);
  }
  else
  {
    this->SetSelectedIds(nullptr);
  }
}

//------------------------------------------------------------------------------
vtkLookupTable* vtkGaussianSplatMapper::GetScoreLookupTable()
{
  if (!this->ScoreLookupTable)
  {
    this->ScoreLookupTable = vtkLookupTable::New();
    this->ScoreLookupTable->SetNumberOfTableValues(256);
    this->ScoreLookupTable->SetNanColor(0.5, 0.5, 0.5, 1.0);
  }
  // The splats' colour map (OverlayColor), its suspicious end bright and labelled.
  const vis4gs::SuspiciousEnd end =
    vis4gs::SuspiciousEndOf(this->ScoreArrayName ? this->ScoreArrayName : "");
  for (int i = 0; i < 256; ++i)
  {
    const auto c = vis4gs::OverlayColor(i, 0, 255, end);
    this->ScoreLookupTable->SetTableValue(i, c[0], c[1], c[2], 1.0);
  }
  double range[2] = { this->ScoreRange[0], this->ScoreRange[1] };
  if (this->AutoScoreRange)
  {
    vtkPolyData* input = this->GetInput();
    vtkDataArray* arr = (input && this->ScoreArrayName)
      ? input->GetPointData()->GetArray(this->ScoreArrayName)
      : nullptr;
    if (arr)
    {
      arr->GetRange(range, 0);
    }
  }
  if (!(range[1] > range[0]))
  {
    range[1] = range[0] + 1.0;
  }
  this->ScoreLookupTable->SetTableRange(range);
  this->ScoreLookupTable->ResetAnnotations();
  if (end != vis4gs::SuspiciousEnd::None)
  {
    this->ScoreLookupTable->SetAnnotation(
      vtkVariant(end == vis4gs::SuspiciousEnd::Low ? range[0] : range[1]), "suspicious");
  }
  return this->ScoreLookupTable;
}

//------------------------------------------------------------------------------
void vtkGaussianSplatMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Internals->Release(window);
  this->Superclass::ReleaseGraphicsResources(window);
}

//------------------------------------------------------------------------------
void vtkGaussianSplatMapper::RenderPiece(vtkRenderer* ren, vtkActor* actor)
{
  vtkInternals& in = *this->Internals;
  const double cpu0 = ThreadCpuMs();
  this->LastDrawnCount = 0;
  this->LastSortTime = this->LastColorTime = this->LastUploadTime = this->LastRasterTime = 0.0;
  this->LastDrawCallTime = this->LastRenderThreadTime = 0.0;
  vtkPolyData* input = this->GetInput();
  if (!input || input->GetNumberOfPoints() == 0 || ren->GetSelector())
  {
    return;
  }
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  if (!renWin)
  {
    vtkErrorMacro("vtkGaussianSplatMapper needs an OpenGL render window");
    return;
  }
  if (in.Window != renWin)
  {
    in.Release(in.Window);
    in.Window = renWin;
  }
  vtkCamera* cam = ren->GetActiveCamera();
  if (cam->GetParallelProjection())
  {
    if (!in.ReportedParallel)
    {
      vtkErrorMacro("vtkGaussianSplatMapper: parallel projection is not supported");
      in.ReportedParallel = true;
    }
    return;
  }

  // 0. Drawing path: the CPU rasteriser on a software OpenGL.
  if (in.SoftwareGL < 0)
  {
    const char* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const std::string renderer = name ? name : "";
    in.SoftwareGL = (renderer.find("llvmpipe") != std::string::npos ||
                      renderer.find("softpipe") != std::string::npos ||
                      renderer.find("SWR") != std::string::npos ||
                      renderer.find("Software Rasterizer") != std::string::npos)
      ? 1
      : 0;
  }
  const int method = this->DrawMethod != AUTOMATIC ? this->DrawMethod
    : in.SoftwareGL == 1                           ? CPU_RASTERIZER
                                                   : OPENGL_SPLATS;
  this->LastDrawMethod = method;

  // 1. Input -> Core cloud (only when the input changed).
  if (input->GetMTime() != in.InputTime)
  {
    std::string error;
    in.Cloud = EmptyCloud(); // (the old copy is released before a new one is made)
    in.InputTime = input->GetMTime();
    ++in.CloudVersion;
    in.RasterValid = false;
    const bool shared = in.Shared && in.SharedInput == input && in.SharedInputTime == in.InputTime;
    in.Cloud = shared ? in.Shared : ConvertScene(input, &error);
    if (!shared)
    {
      in.Shared.reset();
    }
    if (!in.Cloud)
    {
      vtkErrorMacro("vtkGaussianSplatMapper: " << error);
      in.Cloud = EmptyCloud();
      return;
    }
    const vis4gs::GaussianCloud& cloud = *in.Cloud;
    const std::size_t n = cloud.Count;
    in.HasSH = cloud.SH.size() == 3 * n * static_cast<std::size_t>(cloud.ShCoefficientCount());
    // (the cloud's Ids are the input's GaussianId array: ConvertScene)
    std::vector<std::uint32_t>().swap(in.IdOrder);
    const std::vector<std::int64_t>& ids = cloud.Ids;
    in.IdsOrder = vis4gs::InspectIdColumn(ids.data(), ids.size());
    if (ids.size() == n && n <= std::numeric_limits<std::uint32_t>::max() && !in.IdsOrder.Sorted)
    {
      in.IdOrder.resize(n);
      std::iota(in.IdOrder.begin(), in.IdOrder.end(), 0u);
      std::stable_sort(in.IdOrder.begin(),
        in.IdOrder.end(),
        [&](std::uint32_t a, std::uint32_t b) { return ids[a] < ids[b]; });
    }
    in.DisplayTime = 0; // new display colours
    in.ShOnGPU = false;
    in.PackDirty = true;
    // A frame of the old scene is never shown (TakeFinished drops it by its version).
    in.Frames.Cancel();
    in.SubmittedValid = false;
  }
  const std::size_t n = in.Cloud->Count;
  if (n == 0)
  {
    return;
  }
  if (n > static_cast<std::size_t>(std::numeric_limits<int>::max() / 3))
  {
    vtkErrorMacro("vtkGaussianSplatMapper: too many Gaussians (" << n << ")");
    return;
  }

  // 2. Camera: world (actor's model frame) to OpenCV camera, focal lengths from the projection.
  int width = 0, height = 0, ox = 0, oy = 0;
  ren->GetTiledSizeAndOrigin(&width, &height, &ox, &oy);
  if (width <= 0 || height <= 0)
  {
    return;
  }
  vtkNew<vtkMatrix4x4> modelView;
  vtkMatrix4x4::Multiply4x4(cam->GetModelViewTransformMatrix(), actor->GetMatrix(), modelView);
  std::array<double, 16> view{};
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      view[4 * r + c] = modelView->GetElement(r, c);
    }
  }
  const std::array<double, 16> w2c = vis4gs::GLViewToWorldToCamera(view);
  vtkMatrix4x4* proj =
    cam->GetProjectionTransformMatrix(static_cast<double>(width) / height, -1.0, 1.0);
  const double fx = proj->GetElement(0, 0) * width / 2.0;
  const double fy = proj->GetElement(1, 1) * height / 2.0;
  const double depthCoeffs[2] = { proj->GetElement(2, 2), proj->GetElement(2, 3) };
  vtkNew<vtkMatrix4x4> inverse;
  vtkMatrix4x4::Invert(modelView, inverse);
  // Camera centre in the model frame: the inverse maps the eye origin back.
  const double center[3] = {
    inverse->GetElement(0, 3), inverse->GetElement(1, 3), inverse->GetElement(2, 3)
  };

  if (method == CPU_RASTERIZER)
  {
    this->RenderRasterized(ren, input, width, height, w2c.data(), fx, fy, depthCoeffs);
  }
  else
  {
    const double rate = renWin->GetDesiredUpdateRate();
    const bool interactive = this->InteractiveUpdateRate > 0 && rate >= this->InteractiveUpdateRate;
    this->RenderOpenGLSplats(
      ren, input, width, height, ox, oy, w2c.data(), fx, fy, center, depthCoeffs, interactive);
  }
  this->LastRenderThreadTime = ThreadCpuMs() - cpu0 - this->LastDrawCallTime;
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianSplatMapper::GetSceneUploadCount()
{
  return this->Internals->SceneUploads;
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianSplatMapper::GetOrderUploadCount()
{
  return this->Internals->OrderUploads;
}

//------------------------------------------------------------------------------
void vtkGaussianSplatMapper::RenderRasterized(vtkRenderer* ren,
  vtkPolyData* input,
  int width,
  int height,
  const double worldToCamera[16],
  double fx,
  double fy,
  const double depthCoeffs[2])
{
  vtkInternals& in = *this->Internals;
  vtkOpenGLRenderWindow* renWin = in.Window;
  const std::size_t n = in.Cloud->Count;
  in.Frames.SetWorkerNice(this->FrameWorkerNice);
  in.Frames.SetAsynchronous(this->AsynchronousFrames);

  // Resolution: reduced while interacting (VTK's desired update rate), full for still frames.
  const double rate = ren->GetRenderWindow()->GetDesiredUpdateRate();
  const bool interactive = this->InteractiveUpdateRate > 0 && rate >= this->InteractiveUpdateRate;
  double distance = this->ImageSampleDistance;
  if (interactive)
  {
    if (!this->AutoAdjustImageSampleDistances)
    {
      distance = this->InteractiveImageSampleDistance;
    }
    else
    {
      if (!(in.AdaptiveDistance >= 1.0))
      {
        in.AdaptiveDistance = this->InteractiveImageSampleDistance;
      }
      in.AdaptiveDistance = std::min(in.AdaptiveDistance, this->MaximumImageSampleDistance);
      distance = in.AdaptiveDistance;
    }
  }
  const int w = std::max(1, static_cast<int>(std::lround(width / distance)));
  const int h = std::max(1, static_cast<int>(std::lround(height / distance)));

  // A new frame only when something that changes the picture changed.
  const vtkMTimeType displayTime =
    std::max(this->GetMTime(), this->SelectedIds ? this->SelectedIds->GetMTime() : vtkMTimeType(0));
  // A moving frame of a scene larger than the budget draws the level of detail.
  const std::size_t budget = static_cast<std::size_t>(this->InteractiveSplatBudget);
  const bool reduced = interactive && budget > 0 && budget < n;
  std::array<double, 25> key{};
  std::copy(worldToCamera, worldToCamera + 16, key.begin());
  key[16] = fx;
  key[17] = fy;
  key[18] = width;
  key[19] = height;
  key[20] = w;
  key[21] = h;
  key[22] = static_cast<double>(displayTime);
  key[23] = static_cast<double>(in.InputTime);
  key[24] = reduced ? static_cast<double>(budget) : 0.0;
  const bool shown = in.RasterValid && vtkGaussianSplatRasterFrames::SameKey(key, in.RasterKey);
  const bool requested =
    in.SubmittedValid && vtkGaussianSplatRasterFrames::SameKey(key, in.SubmittedKey);
  if (!shown && !requested)
  {
    // The overlay (scores, selection) is read from the input here, on the render thread, and
    // shared by the requests until the display options or the input change.
    if (in.OverlayKey[0] != key[22] || in.OverlayKey[1] != key[23] ||
      in.OverlayVersion != in.CloudVersion)
    {
      vis4gs::SplatDisplayOptions opt;
      if (!in.FillDisplayOptions(this, input, opt))
      {
        return;
      }
      in.Overlay.reset();
      if (opt.ScoreColoring || opt.HideOutsideRange || opt.Selected)
      {
        auto overlay = std::make_shared<vtkGaussianSplatRasterFrames::Overlay>();
        overlay->Scores = std::move(in.Scores);
        overlay->Selected = std::move(in.Selected);
        overlay->Options = opt;
        overlay->Options.Scores = opt.Scores ? overlay->Scores.data() : nullptr;
        overlay->Options.Selected = opt.Selected ? overlay->Selected.data() : nullptr;
        in.Overlay = std::move(overlay);
      }
      in.OverlayKey = { key[22], key[23] };
      in.OverlayVersion = in.CloudVersion;
    }
    vtkGaussianSplatRasterFrames::Request request;
    std::array<double, 16> w2c{};
    std::copy(worldToCamera, worldToCamera + 16, w2c.begin());
    request.Camera = vtkGaussianCameraUtilities::PinholeCamera(width, height, fx, fy, w2c);
    if (w != width || h != height)
    {
      request.Camera = request.Camera.Resized(w, h);
    }
    request.Cloud = in.Cloud;
    request.CloudVersion = in.CloudVersion;
    request.Settings.ShDegree = this->ShDegree;
    request.Settings.ScaleModifier = this->ScaleModifier;
    request.Settings.Threads = this->NumberOfThreads;
    request.Budget = budget;
    request.Reduced = reduced;
    request.ReuseAngle = this->InteractiveReuseAngle * vtkMath::Pi() / 180.0;
    request.ColorAngle = this->InteractiveColorAngle * vtkMath::Pi() / 180.0;
    request.RebuildAhead = this->InteractiveRebuildAhead;
    if (reduced)
    {
      request.Settings.TransmittanceStop = this->InteractiveTransmittanceStop;
    }
    request.FullResolution = w == width && h == height;
    request.SampleDistance = distance;
    request.Interactive = interactive;
    request.Display = in.Overlay;
    request.Input = input;
    request.InputTime = in.InputTime;
    request.RecordThreshold = static_cast<float>(this->SelectionWeightThreshold);
    request.Key = key;
    in.SubmittedKey = key;
    in.SubmittedValid = true;
    in.Frames.Submit(std::move(request));
  }

  // Show the newest finished frame (synchronous: the one just made).
  this->LastRasterTime = this->LastRasterDrawTime = 0.0;
  std::fill_n(this->LastRasterPhaseTimes, 6, 0.0);
  std::fill_n(this->LastRasterPhaseCpuTimes, 6, 0.0);
  const auto drawStart = std::chrono::steady_clock::now();
  bool uploaded = false;
  if (in.Frames.TakeFinished(in.CloudVersion, in.Shown))
  {
    const vtkGaussianSplatRasterFrames::Frame& frame = in.Shown;
    if (frame.Failed)
    {
      vtkErrorMacro("vtkGaussianSplatMapper: " << frame.Error);
      in.RasterValid = in.SubmittedValid = false;
      return;
    }
    const bool magnified = frame.Width != width || frame.Height != height;
    if (!in.Frames.Upload(renWin, frame, magnified))
    {
      vtkErrorMacro("vtkGaussianSplatMapper: could not upload the rasterised image");
      in.RasterValid = in.SubmittedValid = false;
      return;
    }
    in.RasterKey = frame.Key;
    in.RasterValid = true;
    in.RasterDrawn = frame.Drawn;
    in.RasterReduced = frame.Reduced;
    ++in.FramesShown;
    uploaded = true;
    this->LastRasterTime = frame.Milliseconds;
    std::copy(frame.PhaseMs.begin(), frame.PhaseMs.end(), this->LastRasterPhaseTimes);
    std::copy(frame.PhaseCpuMs.begin(), frame.PhaseCpuMs.end(), this->LastRasterPhaseCpuTimes);
    this->LastImageSampleDistance = frame.SampleDistance;
    if (frame.Interactive && this->AutoAdjustImageSampleDistances && rate > 0)
    {
      // Aim at 1 / DesiredUpdateRate: the work shrinks roughly with the pixel count.
      const double used = this->LastImageSampleDistance;
      const double ratio = this->LastRasterTime / (1000.0 / rate);
      if (ratio > 1.2 || ratio < 0.6)
      {
        in.AdaptiveDistance = std::min(this->MaximumImageSampleDistance,
          std::max(1.0, used * std::sqrt(std::min(4.0, std::max(0.25, ratio)))));
      }
    }
  }
  if (!in.RasterValid)
  {
    return; // (asynchronous: nothing finished for this scene yet)
  }
  this->LastDrawnCount = static_cast<vtkIdType>(in.RasterDrawn);
  this->LastFrameReduced = in.RasterReduced;

  // Draw: blend the image depth-tested at the expected depth, then write that depth.
  if (!in.Frames.Draw(renWin, depthCoeffs))
  {
    vtkErrorMacro("vtkGaussianSplatMapper: the image shaders failed to compile");
  }
  if (uploaded)
  {
    this->LastRasterDrawTime = vis4gs::MsSince(drawStart);
  }
}

//------------------------------------------------------------------------------
bool vtkGaussianSplatMapper::GetFramePending()
{
  vtkInternals& in = *this->Internals;
  return in.Frames.Busy() ||
    (in.SubmittedValid &&
      !(in.RasterValid && vtkGaussianSplatRasterFrames::SameKey(in.SubmittedKey, in.RasterKey)));
}

//------------------------------------------------------------------------------
void vtkGaussianSplatMapper::WaitForFrame()
{
  this->Internals->Frames.Wait();
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianSplatMapper::GetFramesShown()
{
  return this->Internals->FramesShown;
}

//------------------------------------------------------------------------------
void vtkGaussianSplatMapper::SetFrameReadyCallback(std::function<void()> callback)
{
  this->Internals->Frames.SetFrameReadyCallback(std::move(callback));
}

//------------------------------------------------------------------------------
std::shared_ptr<const vis4gs::GaussianCloud> vtkGaussianSplatMapper::ConvertScene(
  vtkPolyData* scene,
  std::string* error)
{
  // No copy when the scene's arrays are a shared cloud (GaussianCloudToPolyData of a reader).
  auto cloud = vis4gs::GaussianCloudOf(scene, error);
  if (!cloud)
  {
    return nullptr;
  }
  const std::size_t n = cloud->Count;
  if (cloud->LogScales.size() != 3 * n || cloud->Rotations.size() != 4 * n ||
    cloud->OpacityLogits.size() != n)
  {
    if (error)
    {
      *error = "the scene lacks LogScale, Rotation or OpacityLogit point arrays";
    }
    return nullptr;
  }
  return cloud;
}

//------------------------------------------------------------------------------
void vtkGaussianSplatMapper::SetSharedGaussians(vtkPolyData* input,
  std::shared_ptr<const vis4gs::GaussianCloud> cloud)
{
  vtkInternals& in = *this->Internals;
  in.Shared = std::move(cloud);
  in.SharedInput = in.Shared ? input : nullptr;
  in.SharedInputTime = in.Shared && input ? input->GetMTime() : 0;
  if (in.Shared && input && input == this->GetInput() && in.InputTime == in.SharedInputTime &&
    in.Cloud != in.Shared)
  {
    // The same Gaussians as drawn already: hold the shared copy so that the mapper's own is
    // released (a new version: nothing derived keeps pointing into the old one).
    in.Cloud = in.Shared;
    ++in.CloudVersion;
  }
}

//------------------------------------------------------------------------------
const vis4gs::RasterWorkspace<float>* vtkGaussianSplatMapper::GetLastFullFrame(
  const vis4gs::Camera*& camera,
  vtkPolyData*& input,
  vtkMTimeType& inputTime,
  const vis4gs::PixelWeightRecord** weights) const
{
  const vtkInternals& in = *this->Internals;
  return in.Frames.LastFullFrame(camera, input, inputTime, weights);
}

//------------------------------------------------------------------------------
void vtkGaussianSplatMapper::RenderOpenGLSplats(vtkRenderer* ren,
  vtkPolyData* input,
  int width,
  int height,
  int ox,
  int oy,
  const double worldToCamera[16],
  double fx,
  double fy,
  const double cameraCenter[3],
  const double depthCoeffsIn[2],
  bool interactive)
{
  vtkInternals& in = *this->Internals;
  vtkOpenGLRenderWindow* renWin = in.Window;
  (void)ren;
  const std::size_t n = in.Cloud->Count;
  const int threads = this->NumberOfThreads;
  std::array<double, 16> w2c{};
  std::copy(worldToCamera, worldToCamera + 16, w2c.begin());

  // 1. Packed geometry (when the input or the scale modifier changed).
  if (in.PackDirty || in.PackedScale != this->ScaleModifier)
  {
    try
    {
      vis4gs::PackSplatGeometry(*in.Cloud, this->ScaleModifier, in.Geometry, threads);
      in.PackedScale = this->ScaleModifier;
    }
    catch (const std::exception& e)
    {
      vtkErrorMacro("vtkGaussianSplatMapper: " << e.what());
      return;
    }
    in.PackDirty = false;
    in.GeometryDirty = true;
  }

  // 2. Display colours (view-independent: the SH colours are evaluated in the shader), only
  // when a display property or the input changed.
  const auto tc = std::chrono::steady_clock::now();
  const bool trueColor = in.HasSH && this->SplatColoring != SCORE;
  const vtkMTimeType displayTime =
    std::max(this->GetMTime(), this->SelectedIds ? this->SelectedIds->GetMTime() : vtkMTimeType(0));
  if (displayTime != in.DisplayTime)
  {
    vis4gs::SplatDisplayOptions opt;
    if (!in.FillDisplayOptions(this, input, opt))
    {
      return;
    }
    opt.DeferTrueColor = trueColor;
    if (!in.HasSH)
    {
      in.TrueColors.assign(3 * n, 0.7f); // no SH: light grey
    }
    const std::vector<std::uint8_t> oldKeep = in.Keep;
    try
    {
      vis4gs::ComputeSplatDisplay(
        in.HasSH ? nullptr : in.TrueColors.data(), n, opt, in.Display, in.Keep, threads);
    }
    catch (const std::exception& e)
    {
      vtkErrorMacro("vtkGaussianSplatMapper: " << e.what());
      return;
    }
    if (in.Keep != oldKeep || in.KeepVersion == 0)
    {
      const bool all =
        std::all_of(in.Keep.begin(), in.Keep.end(), [](std::uint8_t k) { return k; });
      in.KeepShared = all ? nullptr : std::make_shared<const std::vector<std::uint8_t>>(in.Keep);
      ++in.KeepVersion;
    }
    in.ColorsDirty = true;
    in.DisplayTime = displayTime;
  }
  this->LastColorTime = MsSince(tc);

  // 3. Back-to-front order. Asynchronous: take the order that finished before this frame,
  // ask for this frame's camera, and draw with the taken one while the camera moves (only the
  // camera may lag: a changed scene, kept set or budget waits, as does a still frame).
  if (w2c != in.CameraW2C)
  {
    in.CameraW2C = w2c;
    ++in.CameraKey;
  }
  const std::array<std::uint64_t, 3> scene{
    { in.CloudVersion, in.KeepVersion, static_cast<std::uint64_t>(this->MaximumNumberOfSplats) }
  };
  if (scene != in.OrderScene)
  {
    in.OrderScene = scene;
    ++in.SceneKey;
  }
  vis4gs::SplatSortResult& front = in.Front;
  if (!in.FrontValid || front.SceneKey != in.SceneKey || front.CameraKey != in.CameraKey)
  {
    vis4gs::SplatSortRequest request;
    request.Cloud = in.Cloud;
    request.Keep = in.KeepShared;
    request.WorldToCamera = w2c;
    request.Budget = static_cast<std::size_t>(this->MaximumNumberOfSplats);
    request.Threads = threads;
    request.SceneKey = in.SceneKey;
    request.CameraKey = in.CameraKey;
    bool arrived = false;
    try
    {
      if (this->AsynchronousSort)
      {
        arrived = in.Sorter.TakeResult(front);
        if (in.SubmittedScene != in.SceneKey || in.SubmittedCamera != in.CameraKey)
        {
          in.Sorter.Submit(std::move(request));
          in.SubmittedScene = in.SceneKey;
          in.SubmittedCamera = in.CameraKey;
        }
        const bool sameScene = (in.FrontValid || arrived) && front.SceneKey == in.SceneKey;
        if (!sameScene || (!interactive && front.CameraKey != in.CameraKey))
        {
          in.Sorter.WaitForLatest();
          arrived = in.Sorter.TakeResult(front) || arrived;
          const std::string error = in.Sorter.GetLastError();
          if (!error.empty())
          {
            throw std::runtime_error(error);
          }
        }
      }
      else
      {
        vis4gs::SplatSortWorker::Sort(request, in.Depths, front);
        arrived = true;
      }
    }
    catch (const std::exception& e)
    {
      vtkErrorMacro("vtkGaussianSplatMapper: " << e.what());
      in.FrontValid = false;
      return;
    }
    if (arrived)
    {
      in.FrontValid = true;
      in.OrderOnGPU = false;
      this->LastSortTime = front.Milliseconds;
    }
  }
  if (!in.FrontValid || front.SceneKey != in.SceneKey)
  {
    return; // (an error was reported)
  }
  this->LastOrderLag = static_cast<vtkIdType>(in.CameraKey - front.CameraKey);
  const std::vector<std::uint32_t>& order = front.Order;

  // 4. Uploads: the scene's data once (until the input or a display property changes), each
  // new order once.
  const auto tu = std::chrono::steady_clock::now();
  GLint maxTexels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
  if (in.GeometryDirty || !in.GeometryOnGPU)
  {
    if (static_cast<double>(3 * n) > static_cast<double>(maxTexels))
    {
      vtkErrorMacro("vtkGaussianSplatMapper: " << n << " Gaussians need " << 3 * n
                                               << " texels; the GL texture buffer limit is "
                                               << maxTexels);
      return;
    }
    in.GeometryBuffer->Upload(
      in.Geometry.data(), in.Geometry.size(), vtkOpenGLBufferObject::TextureBuffer);
    in.GeometryTexture->SetContext(renWin);
    in.GeometryTexture->CreateTextureBuffer(
      static_cast<unsigned int>(3 * n), 4, VTK_FLOAT, in.GeometryBuffer);
    in.GeometryOnGPU = true;
    in.GeometryDirty = false;
    std::vector<float>().swap(in.Geometry); // (the GL's copy is the one drawn: 48 B a Gaussian)
    ++in.SceneUploads;
  }
  const int shStride = 3 * in.Cloud->ShCoefficientCount();
  if (!in.ShOnGPU)
  {
    // The input's SH array as it is, read as RGBA texels (a padded copy when its length is not
    // a multiple of 4; a dummy texel without SH).
    const std::vector<float>& sh = in.Cloud->SH;
    const float* data = sh.data();
    std::size_t floats = in.HasSH ? sh.size() : 0;
    std::vector<float> padded;
    if (floats % 4 != 0 || floats == 0)
    {
      padded.assign(data, data + floats);
      padded.resize(std::max<std::size_t>(4, (floats + 3) / 4 * 4), 0.0f);
      data = padded.data();
      floats = padded.size();
    }
    if (static_cast<double>(floats / 4) > static_cast<double>(maxTexels) ||
      static_cast<double>(n) * shStride > std::numeric_limits<int>::max())
    {
      vtkErrorMacro("vtkGaussianSplatMapper: the SH coefficients of "
        << n << " Gaussians need " << floats / 4 << " texels; the GL texture buffer limit is "
        << maxTexels);
      return;
    }
    in.ShBuffer->Upload(data, floats, vtkOpenGLBufferObject::TextureBuffer);
    in.ShTexture->SetContext(renWin);
    in.ShTexture->CreateTextureBuffer(
      static_cast<unsigned int>(floats / 4), 4, VTK_FLOAT, in.ShBuffer);
    in.ShOnGPU = true;
    ++in.SceneUploads;
  }
  if (in.ColorsDirty || !in.ColorsOnGPU)
  {
    in.ColorBuffer->Upload(
      in.Display.data(), in.Display.size(), vtkOpenGLBufferObject::TextureBuffer);
    in.ColorTexture->SetContext(renWin);
    in.ColorTexture->CreateTextureBuffer(
      static_cast<unsigned int>(n), 4, VTK_FLOAT, in.ColorBuffer);
    in.ColorsOnGPU = true;
    in.ColorsDirty = false;
    std::vector<float>().swap(in.Display);
    ++in.SceneUploads;
  }
  if (!in.OrderOnGPU && !order.empty())
  {
    const std::size_t bytes = order.size() * sizeof(std::uint32_t);
    if (bytes == in.OrderBytes)
    {
      // Same size: into the existing store, without reallocating it.
      in.OrderBuffer->Bind();
      glBufferSubData(GL_TEXTURE_BUFFER, 0, static_cast<GLsizeiptr>(bytes), order.data());
      in.OrderBuffer->Release();
    }
    else
    {
      in.OrderBuffer->Upload(order.data(), order.size(), vtkOpenGLBufferObject::TextureBuffer);
      in.OrderTexture->SetContext(renWin);
      in.OrderTexture->SetInternalFormat(GL_R32UI);
      in.OrderTexture->CreateTextureBuffer(
        static_cast<unsigned int>(order.size()), 1, VTK_UNSIGNED_INT, in.OrderBuffer);
      in.OrderBytes = bytes;
    }
    in.OrderOnGPU = true;
    ++in.OrderUploads;
  }
  this->LastUploadTime = MsSince(tu);
  if (order.empty())
  {
    return;
  }

  // 5. Draw.
  const bool instanced = this->GeometryPath == INSTANCED_QUADS;
  vtkShaderProgram*& cached = instanced ? in.InstancedProgram : in.Program;
  if (!cached)
  {
    const std::string vs = SplatVertexShader(instanced);
    cached = renWin->GetShaderCache()->ReadyShaderProgram(
      vs.c_str(), vtkGaussianSplatFS, instanced ? "" : vtkGaussianSplatGS);
    if (!cached)
    {
      vtkErrorMacro("vtkGaussianSplatMapper: the splat shaders failed to compile");
      return;
    }
  }
  else
  {
    renWin->GetShaderCache()->ReadyShaderProgram(cached);
  }
  vtkShaderProgram* prog = cached;
  in.VAO->Bind();
  in.GeometryTexture->Activate();
  in.ColorTexture->Activate();
  in.OrderTexture->Activate();
  in.ShTexture->Activate();
  prog->SetUniformi("splatGeometry", in.GeometryTexture->GetTextureUnit());
  prog->SetUniformi("splatSH", in.ShTexture->GetTextureUnit());
  // SH in the shader: the degree drawn, the input's stride, the reference's constants.
  const int degree = !in.HasSH ? 0
    : this->ShDegree < 0       ? in.Cloud->ShDegree
                               : std::min(this->ShDegree, in.Cloud->ShDegree);
  prog->SetUniformi("trueColor", trueColor ? 1 : 0);
  prog->SetUniformi("shDegree", degree);
  prog->SetUniformi("shStride", shStride);
  float shC[14] = { static_cast<float>(vis4gs::sh::C0), static_cast<float>(vis4gs::sh::C1) };
  for (int k = 0; k < 5; ++k)
  {
    shC[2 + k] = static_cast<float>(vis4gs::sh::C2[k]);
  }
  for (int k = 0; k < 7; ++k)
  {
    shC[7 + k] = static_cast<float>(vis4gs::sh::C3[k]);
  }
  prog->SetUniform1fv("shC", 14, shC);
  const float eye[3] = { static_cast<float>(cameraCenter[0]),
    static_cast<float>(cameraCenter[1]),
    static_cast<float>(cameraCenter[2]) };
  prog->SetUniform3f("cameraCenter", eye);
  const float highlight[3] = { static_cast<float>(this->HighlightColor[0]),
    static_cast<float>(this->HighlightColor[1]),
    static_cast<float>(this->HighlightColor[2]) };
  prog->SetUniform3f("highlightColor", highlight);
  prog->SetUniformf("highlightMix", static_cast<float>(this->HighlightMix));
  prog->SetUniformf("dimDesaturation", vis4gs::SplatDisplayOptions().DimDesaturation);
  prog->SetUniformi("splatColor", in.ColorTexture->GetTextureUnit());
  prog->SetUniformi("splatOrder", in.OrderTexture->GetTextureUnit());
  for (int r = 0; r < 3; ++r)
  {
    const float row[4] = { static_cast<float>(w2c[4 * r]),
      static_cast<float>(w2c[4 * r + 1]),
      static_cast<float>(w2c[4 * r + 2]),
      static_cast<float>(w2c[4 * r + 3]) };
    const std::string name = "viewRow" + std::to_string(r);
    prog->SetUniform4f(name.c_str(), row);
  }
  // The reference passes tan(fov/2) in float and recomputes the focal lengths from it.
  const float tanFov[2] = { static_cast<float>(width / (2.0 * fx)),
    static_cast<float>(height / (2.0 * fy)) };
  const float focal[2] = { static_cast<float>(width) / (2.0f * tanFov[0]),
    static_cast<float>(height) / (2.0f * tanFov[1]) };
  const float imageSize[2] = { static_cast<float>(width), static_cast<float>(height) };
  const float depthCoeffs[2] = { static_cast<float>(depthCoeffsIn[0]),
    static_cast<float>(depthCoeffsIn[1]) };
  const float viewportRect[4] = { static_cast<float>(ox),
    static_cast<float>(oy),
    static_cast<float>(width),
    static_cast<float>(height) };
  prog->SetUniform2f("focal", focal);
  prog->SetUniform2f("tanFov", tanFov);
  prog->SetUniform2f("imageSize", imageSize);
  prog->SetUniform2f("depthCoeffs", depthCoeffs);
  prog->SetUniform4f("viewportRect", viewportRect);

  vtkOpenGLState* state = renWin->GetState();
  vtkOpenGLState::ScopedglEnableDisable blendSaver(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable cullSaver(state, GL_CULL_FACE);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFuncSaver(state);
  vtkOpenGLState::ScopedglDepthMask depthMaskSaver(state);
  state->vtkglEnable(GL_BLEND);
  state->vtkglDisable(GL_CULL_FACE);
  state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  state->vtkglDepthMask(GL_FALSE);
  const double draw0 = ThreadCpuMs();
  if (instanced)
  {
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(order.size()));
  }
  else
  {
    glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(order.size()));
  }
  this->LastDrawCallTime = ThreadCpuMs() - draw0;
  in.ShTexture->Deactivate();
  in.OrderTexture->Deactivate();
  in.ColorTexture->Deactivate();
  in.GeometryTexture->Deactivate();
  in.VAO->Release();
  this->LastDrawnCount = static_cast<vtkIdType>(order.size());
}

//------------------------------------------------------------------------------
void vtkGaussianSplatMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SplatColoring: " << (this->SplatColoring == SCORE ? "Score" : "TrueColor")
     << "\n";
  os << indent << "ScoreArrayName: " << (this->ScoreArrayName ? this->ScoreArrayName : "(none)")
     << "\n";
  os << indent << "ScoreRange: " << this->ScoreRange[0] << ", " << this->ScoreRange[1] << "\n";
  os << indent << "AutoScoreRange: " << this->AutoScoreRange << "\n";
  os << indent << "HideOutsideRange: " << this->HideOutsideRange << "\n";
  os << indent << "VisibleRange: " << this->VisibleRange[0] << ", " << this->VisibleRange[1]
     << "\n";
  os << indent << "SelectedIds: " << this->SelectedIds << "\n";
  os << indent << "HighlightSelected: " << this->HighlightSelected << "\n";
  os << indent << "HighlightColor: " << this->HighlightColor[0] << ", " << this->HighlightColor[1]
     << ", " << this->HighlightColor[2] << "\n";
  os << indent << "HighlightMix: " << this->HighlightMix << "\n";
  os << indent << "DimUnselected: " << this->DimUnselected << "\n";
  os << indent << "DimOpacity: " << this->DimOpacity << "\n";
  os << indent << "ShDegree: " << this->ShDegree << "\n";
  os << indent << "ScaleModifier: " << this->ScaleModifier << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "MaximumNumberOfSplats: " << this->MaximumNumberOfSplats << "\n";
  os << indent << "GeometryPath: "
     << (this->GeometryPath == INSTANCED_QUADS ? "InstancedQuads" : "GeometryShader") << "\n";
  os << indent << "DrawMethod: "
     << (this->DrawMethod == AUTOMATIC           ? "Automatic"
            : this->DrawMethod == CPU_RASTERIZER ? "CPURasterizer"
                                                 : "OpenGLSplats")
     << "\n";
  os << indent << "LastDrawMethod: " << this->LastDrawMethod << "\n";
  os << indent << "ImageSampleDistance: " << this->ImageSampleDistance << "\n";
  os << indent << "InteractiveImageSampleDistance: " << this->InteractiveImageSampleDistance
     << "\n";
  os << indent << "AutoAdjustImageSampleDistances: " << this->AutoAdjustImageSampleDistances
     << "\n";
  os << indent << "MaximumImageSampleDistance: " << this->MaximumImageSampleDistance << "\n";
  os << indent << "InteractiveUpdateRate: " << this->InteractiveUpdateRate << "\n";
  os << indent << "LastImageSampleDistance: " << this->LastImageSampleDistance << "\n";
  os << indent << "LastRasterTime: " << this->LastRasterTime << "\n";
  os << indent << "LastRasterPhaseTimes:";
  for (double t : this->LastRasterPhaseTimes)
  {
    os << " " << t;
  }
  os << "\n" << indent << "LastRasterPhaseCpuTimes:";
  for (double t : this->LastRasterPhaseCpuTimes)
  {
    os << " " << t;
  }
  os << "\n" << indent << "LastRasterDrawTime: " << this->LastRasterDrawTime << "\n";
  os << indent << "InteractiveSplatBudget: " << this->InteractiveSplatBudget << "\n";
  os << indent << "SelectionWeightThreshold: " << this->SelectionWeightThreshold << "\n";
  os << indent << "InteractiveReuseAngle: " << this->InteractiveReuseAngle << "\n";
  os << indent << "InteractiveColorAngle: " << this->InteractiveColorAngle << "\n";
  os << indent << "InteractiveRebuildAhead: " << this->InteractiveRebuildAhead << "\n";
  os << indent << "InteractiveTransmittanceStop: " << this->InteractiveTransmittanceStop << "\n";
  os << indent << "LastFrameReduced: " << this->LastFrameReduced << "\n";
  os << indent << "AsynchronousFrames: " << this->AsynchronousFrames << "\n";
  os << indent << "FrameWorkerNice: " << this->FrameWorkerNice << "\n";
  os << indent << "ScoreLookupTable: " << this->ScoreLookupTable << "\n";
  os << indent << "LastDrawnCount: " << this->LastDrawnCount << "\n";
  os << indent << "LastSortTime: " << this->LastSortTime << "\n";
  os << indent << "LastColorTime: " << this->LastColorTime << "\n";
  os << indent << "LastUploadTime: " << this->LastUploadTime << "\n";
  os << indent << "AsynchronousSort: " << this->AsynchronousSort << "\n";
  os << indent << "LastOrderLag: " << this->LastOrderLag << "\n";
  os << indent << "LastRenderThreadTime: " << this->LastRenderThreadTime << "\n";
  os << indent << "LastDrawCallTime: " << this->LastDrawCallTime << "\n";
  os << indent << "SceneUploadCount: " << this->Internals->SceneUploads << "\n";
  os << indent << "OrderUploadCount: " << this->Internals->OrderUploads << "\n";
}

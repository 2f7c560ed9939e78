/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianSplatMapper.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianSplatMapper
 * @brief   Draws a 3D Gaussian Splatting scene as anisotropic, depth-sorted splats (OpenGL2).
 *
 * The input is a Gaussian scene vtkPolyData (DESIGN §2: points = means, LogScale, Rotation,
 * OpacityLogit, SH, GaussianId point arrays). Each Gaussian is drawn the way the reference
 * rasteriser blends it (reference §2.3-§2.6):
 *
 *  - each Gaussian becomes a screen-space rectangle (an instanced 4-vertex strip, or a point
 *    expanded by a geometry shader, see GeometryPath); the vertex shader does the EWA projection of
 * the 3D covariance (Jacobian clamped at 1.3 tan(fov/2), +0.3 pixel^2 dilation, det == 0 cull, near
 * cull at view z <= 0.2) and the reference's 3-sigma radius and 16x16 tile rectangle; the rectangle
 * drawn is the tile rectangle intersected with the box of the ellipse where alpha can reach 1/255,
 * so the same pixels are evaluated as in the reference;
 *  - the fragment shader evaluates the conic, alpha = min(0.99, o e^power), discards
 *    alpha < 1/255 and writes premultiplied colour;
 *  - splats are blended back to front (dst = src + (1 - alpha_src) dst) in the order of the
 *    view-space depth of their centres, ties by index reversed: the exact reverse of the
 *    reference's per-tile order. The sort is a parallel radix sort on the CPU
 *    (Core/Splats/SplatSort.h), redone when the camera moves, on a worker thread of the
 *    mapper (AsynchronousSort, Core/Splats/SplatSortWorker.h): while the camera moves
 *    (InteractiveUpdateRate) a frame is drawn with the last order that finished, which lags
 *    the camera by the sort's duration (LastOrderLag); a still frame waits for the order of
 *    its own camera, so still frames are exact;
 *  - colours come from the SH coefficients for the direction camera -> mean (all degrees the
 *    input holds, or ShDegree), evaluated in the vertex shader from the coefficients uploaded
 *    once (a texture buffer): the positions, covariances, coefficients and display colours
 *    are uploaded when the input or a display property changes, never because the camera
 *    moved; a moving camera uploads only each new order (GetSceneUploadCount,
 *    GetOrderUploadCount).
 *
 * Known difference from the CPU rasteriser: the reference stops a pixel once the
 * transmittance would fall below 1e-4 (the Gaussian that would cross it is not blended).
 * Back-to-front blending cannot know the transmittance in front of a splat, so every
 * splat is blended; in pixels that saturate, the result differs by at most about 1e-4 of the
 * colour range (plus 8-bit rounding of each blend in the window's framebuffer).
 *
 * Modes (each a property, combinable):
 *  - SplatColoring TRUE_COLOR (default) or SCORE: a point-data score array
 *    (ScoreArrayName, e.g. ViewCoverage, BlurScore, NeedleScore, NeedleShape) through the
 *    viridis colour map over ScoreRange (automatic from the data unless set), turned so that
 *    the score's suspicious end (low View Coverage, high Blur, Needle and needle shape;
 *    vis4gs::OverlayColor) is its bright end and stands out against a dark background; the
 *    same map is available as a vtkLookupTable for a vtkScalarBarActor legend
 *    (GetScoreLookupTable()).
 *  - HideOutsideRange: only Gaussians whose score lies in VisibleRange are drawn.
 *  - SelectedIds (GaussianId values, e.g. from a PEDIGREEIDS vtkSelection via SetSelection()):
 *    highlighted (mixed towards HighlightColor); DimUnselected dims every other Gaussian.
 *
 * The mapper draws in the opaque pass (HasOpaqueGeometry) with its own blending (VTK 9.1's
 * translucent pass would apply order-independent transparency): add the splat actor after the
 * opaque actors it should be composited over (e.g. camera frustums). Splats are depth-tested
 * against what is already drawn; the OpenGL splats do not write depth (the CPU-rasteriser path
 * below does). A parallel projection is not supported (error).
 *
 * Drawing methods (DrawMethod): the OpenGL splat path above, or the exact CPU rasteriser
 * (Core/Render, the same code as the training render) drawn as a full-viewport textured quad.
 * AUTOMATIC (default) takes the CPU rasteriser on a software OpenGL (GL_RENDERER naming
 * llvmpipe, softpipe, SWR or a software rasteriser), where it is several times faster, and
 * the OpenGL splats elsewhere. The CPU path:
 *  - renders colour, accumulated alpha and the expected depth (sum w z / alpha) with
 *    Core's ProjectGaussians/BinGaussians/CompositeTiles, front to back with the reference's
 *    early stop: at full resolution the picture is the CPU rasteriser's, bit for bit before
 *    the framebuffer's 8-bit rounding;
 *  - composites the image over what is drawn (premultiplied), depth-tested per pixel at the
 *    expected depth, and writes that depth where the accumulated alpha is >= 0.5, so other
 *    props (camera frustums, axes) composite correctly in front of and behind the splats;
 *  - follows VTK's interactive/still mechanism: while the render window's DesiredUpdateRate is
 *    at least InteractiveUpdateRate (a vtkRenderWindowInteractor sets it during interaction),
 *    the image is rendered at 1/InteractiveImageSampleDistance of the resolution (adapted to the
 *    desired rate when AutoAdjustImageSampleDistances is on) and magnified linearly; still
 *    frames are rendered at 1/ImageSampleDistance (default full resolution);
 *  - re-renders only when the camera, the viewport, the input or a display property changed;
 *  - keeps the rasteriser's per-frame buffers (vis4gs::RasterWorkspace: projection, tile
 *    lists, compositing data; about 300 MB at 1M Gaussians) between frames, so a frame does
 *    not allocate and page-fault them again, and the input's view-independent preparation
 *    (3D covariances, opacities: 44 B per Gaussian) until the input changes;
 *  - while the camera moves, draws only the InteractiveSplatBudget Gaussians of highest
 *    expected contribution to the view (a level of detail), so that a moving frame costs in
 *    proportion to the budget; the still frame after it is the exact one again.
 * MaximumNumberOfSplats and GeometryPath apply to the OpenGL path only.
 *
 * Set the renderer's camera from a vis4gs::Camera with vtkGaussianCameraUtilities.
 */
#ifndef vtkGaussianSplatMapper_h
#define vtkGaussianSplatMapper_h

#include "vis4gsRenderingSplatsModule.h" // For export macro
#include "vtkPolyDataMapper.h"

#include <functional> // For std::function
#include <memory>     // For std::unique_ptr
#include <string>     // For std::string

class vtkIdTypeArray;
class vtkLookupTable;
class vtkSelection;
#ifndef __VTK_WRAP__
namespace vis4gs
{
struct Camera;
struct GaussianCloud;
struct PixelWeightRecord;
template <typename T>
struct RasterWorkspace;
}
#endif

class VIS4GSRENDERINGSPLATS_EXPORT vtkGaussianSplatMapper : public vtkPolyDataMapper
{
public:
  static vtkGaussianSplatMapper* New();
  vtkTypeMacro(vtkGaussianSplatMapper, vtkPolyDataMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum SplatColoringModes
  {
    TRUE_COLOR = 0,
    SCORE = 1
  };

  ///@{
  /**
   * TRUE_COLOR (SH colours, default) or SCORE (ScoreArrayName through viridis).
   */
  vtkSetClampMacro(SplatColoring, int, TRUE_COLOR, SCORE);
  vtkGetMacro(SplatColoring, int);
  void SetSplatColoringToTrueColor() { this->SetSplatColoring(TRUE_COLOR); }
  void SetSplatColoringToScore() { this->SetSplatColoring(SCORE); }
  ///@}

  ///@{
  /**
   * Name of the point-data array (1 component) used by SCORE colouring and by
   * HideOutsideRange. Default none.
   */
  vtkSetStringMacro(ScoreArrayName);
  vtkGetStringMacro(ScoreArrayName);
  ///@}

  ///@{
  /**
   * Score mapped to the ends of the colour map. Used when AutoScoreRange is off; setting it
   * turns AutoScoreRange off. Default [0, 1].
   */
  void SetScoreRange(double lo, double hi);
  vtkGetVector2Macro(ScoreRange, double);
  ///@}

  ///@{
  /**
   * Take the colour-map range from the finite values of the score array. Default on.
   */
  vtkSetMacro(AutoScoreRange, bool);
  vtkGetMacro(AutoScoreRange, bool);
  vtkBooleanMacro(AutoScoreRange, bool);
  ///@}

  ///@{
  /**
   * Draw only the Gaussians whose score is inside VisibleRange (inclusive; NaN is outside).
   * Works in both colourings. Default off, range [-inf, +inf].
   */
  vtkSetMacro(HideOutsideRange, bool);
  vtkGetMacro(HideOutsideRange, bool);
  vtkBooleanMacro(HideOutsideRange, bool);
  vtkSetVector2Macro(VisibleRange, double);
  vtkGetVector2Macro(VisibleRange, double);
  ///@}

  ///@{
  /**
   * GaussianId values of the selected Gaussians (ids not in the input are ignored). When the
   * input has no GaussianId array, the values are point indices. Default none.
   */
  void SetSelectedIds(vtkIdTypeArray* ids);
  vtkGetObjectMacro(SelectedIds, vtkIdTypeArray);
  ///@}

  /**
   * Takes the selected ids from the first node of @p selection that holds PEDIGREEIDS (or
   * INDICES, treated as point indices); nullptr or an empty selection clears it.
   */
  void SetSelection(vtkSelection* selection);

  ///@{
  /**
   * Mix selected Gaussians' colour towards HighlightColor by HighlightMix. Default on,
   * orange (1, 0.35, 0), 0.7.
   */
  vtkSetMacro(HighlightSelected, bool);
  vtkGetMacro(HighlightSelected, bool);
  vtkBooleanMacro(HighlightSelected, bool);
  vtkSetVector3Macro(HighlightColor, double);
  vtkGetVector3Macro(HighlightColor, double);
  vtkSetClampMacro(HighlightMix, double, 0.0, 1.0);
  vtkGetMacro(HighlightMix, double);
  ///@}

  ///@{
  /**
   * Dim every unselected Gaussian (opacity times DimOpacity, colour desaturated) when a
   * selection is set. Default off, 0.15.
   */
  vtkSetMacro(DimUnselected, bool);
  vtkGetMacro(DimUnselected, bool);
  vtkBooleanMacro(DimUnselected, bool);
  vtkSetClampMacro(DimOpacity, double, 0.0, 1.0);
  vtkGetMacro(DimOpacity, double);
  ///@}

  ///@{
  /**
   * SH degree used for the colours; -1 (default) uses every degree the input holds.
   */
  vtkSetClampMacro(ShDegree, int, -1, 3);
  vtkGetMacro(ShDegree, int);
  ///@}

  ///@{
  /**
   * Multiplies every scale (the reference's scale_modifier). Default 1.
   */
  vtkSetClampMacro(ScaleModifier, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(ScaleModifier, double);
  ///@}

  enum GeometryPaths
  {
    INSTANCED_QUADS = 0,
    GEOMETRY_SHADER = 1
  };

  ///@{
  /**
   * How splats become screen-space quads: GEOMETRY_SHADER (default; one point per Gaussian
   * expanded by a geometry shader, the projection done once) or INSTANCED_QUADS (one instance
   * of a 4-vertex strip per Gaussian, the projection repeated per vertex). Same pixels either
   * way; which is faster depends on the OpenGL implementation (on Mesa llvmpipe the geometry
   * shader path is about 1.7x faster, see Documentation/performance.md).
   */
  vtkSetClampMacro(GeometryPath, int, INSTANCED_QUADS, GEOMETRY_SHADER);
  vtkGetMacro(GeometryPath, int);
  ///@}

  ///@{
  /**
   * Level-of-detail budget: when more Gaussians would be drawn, only every k-th of the
   * back-to-front order is drawn (k = ceil(drawn / budget)), keeping the order. An
   * approximation for interaction on software OpenGL (selection stays exact). 0 (default)
   * draws every Gaussian.
   */
  vtkSetClampMacro(MaximumNumberOfSplats, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(MaximumNumberOfSplats, vtkIdType);
  ///@}

  enum DrawMethods
  {
    AUTOMATIC = 0,
    OPENGL_SPLATS = 1,
    CPU_RASTERIZER = 2
  };

  ///@{
  /**
   * AUTOMATIC (default): CPU_RASTERIZER on a software OpenGL implementation, OPENGL_SPLATS
   * otherwise. OPENGL_SPLATS / CPU_RASTERIZER force a path.
   */
  vtkSetClampMacro(DrawMethod, int, AUTOMATIC, CPU_RASTERIZER);
  vtkGetMacro(DrawMethod, int);
  void SetDrawMethodToAutomatic() { this->SetDrawMethod(AUTOMATIC); }
  void SetDrawMethodToOpenGLSplats() { this->SetDrawMethod(OPENGL_SPLATS); }
  void SetDrawMethodToCPURasterizer() { this->SetDrawMethod(CPU_RASTERIZER); }
  ///@}

  /**
   * The path the last render took (OPENGL_SPLATS or CPU_RASTERIZER; AUTOMATIC before the
   * first render).
   */
  vtkGetMacro(LastDrawMethod, int);

  ///@{
  /**
   * CPU path: image sample distance of still frames (1 = one rasteriser pixel per screen
   * pixel). Default 1.
   */
  vtkSetClampMacro(ImageSampleDistance, double, 1.0, 32.0);
  vtkGetMacro(ImageSampleDistance, double);
  ///@}

  ///@{
  /**
   * CPU path: image sample distance of interactive frames (see InteractiveUpdateRate), the
   * starting value when AutoAdjustImageSampleDistances is on. Default 2 (a quarter of the
   * pixels).
   */
  vtkSetClampMacro(InteractiveImageSampleDistance, double, 1.0, 32.0);
  vtkGetMacro(InteractiveImageSampleDistance, double);
  ///@}

  ///@{
  /**
   * CPU path: adapt the interactive sample distance after each interactive frame so that a
   * frame takes about 1 / DesiredUpdateRate, within [1, MaximumImageSampleDistance].
   * Default on, maximum 4.
   */
  vtkSetMacro(AutoAdjustImageSampleDistances, bool);
  vtkGetMacro(AutoAdjustImageSampleDistances, bool);
  vtkBooleanMacro(AutoAdjustImageSampleDistances, bool);
  vtkSetClampMacro(MaximumImageSampleDistance, double, 1.0, 32.0);
  vtkGetMacro(MaximumImageSampleDistance, double);
  ///@}

  ///@{
  /**
   * Both paths: a frame is interactive when the render window's DesiredUpdateRate is >= this
   * (a vtkRenderWindowInteractor sets 15 while interacting and 0.0001 for still frames).
   * 0 makes every frame a still one. Default 1.
   */
  vtkSetClampMacro(InteractiveUpdateRate, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(InteractiveUpdateRate, double);
  ///@}

  ///@{
  /**
   * CPU path: the level of detail of interactive frames. While the camera moves (see
   * InteractiveUpdateRate), at most this many Gaussians are drawn: those in the view's frustum
   * of highest expected contribution to it (opacity times projected area,
   * Core/Splats/SplatLevelOfDetail.h), selected per frame without a sort; the projection,
   * colours, binning and blending of a moving frame then cost in proportion to the budget
   * instead of the scene's size. Still frames draw every Gaussian (exact). 0 draws every
   * Gaussian while moving too. Default 400000 (Documentation/accuracy-vs-runtime.md).
   */
  vtkSetClampMacro(InteractiveSplatBudget, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(InteractiveSplatBudget, vtkIdType);
  ///@}

  ///@{
  /**
   * CPU path: an exact frame (full resolution, ScaleModifier 1, no Gaussian hidden or dimmed)
   * keeps, while it is composited, every blend of weight alpha*T >= this value
   * (vis4gs::PixelWeightRecord, GetLastFullFrame()): vtkGaussianSelector's Brush and Frame with
   * a WeightThreshold at least this large then read the frame's blends over the brushed pixels
   * or the rectangle instead of replaying the compositing there (the same selection). It costs
   * 9 bytes a kept blend (at most 1 / value blends a pixel; measured 13 MiB for the 4.89M
   * scene at 1280x800, 61 MiB for the 6.1M one, Documentation/performance-history.md) and no
   * measurable compositing time. 0 keeps none. Default 0.01, the selector's default
   * WeightThreshold.
   */
  vtkSetClampMacro(SelectionWeightThreshold, double, 0.0, 1.0);
  vtkGetMacro(SelectionWeightThreshold, double);
  ///@}

  ///@{
  /**
   * CPU path: degrees the view may turn (or travel, seen from the drawn Gaussians' median
   * depth) while moving before the level of detail's Gaussians and their view-dependent
   * colours are chosen again (vis4gs::SplatMovingSet, Core/Splats/SplatMovingSet.h). In
   * between, moving frames project a compact copy of the chosen Gaussians with the colours of
   * the camera that chose them, selected with a margin of this angle around the view. 0
   * chooses them for every moving frame. Still frames are exact whatever the angle. Default
   * 7 degrees: the same error as 6 over an orbit for a third fewer choices at the benchmark's
   * orbit speed (Documentation/accuracy-vs-runtime.md).
   */
  vtkSetClampMacro(InteractiveReuseAngle, double, 0.0, 45.0);
  vtkGetMacro(InteractiveReuseAngle, double);
  ///@}

  ///@{
  /**
   * CPU path: degrees the view may move from the camera that last evaluated every colour of
   * the level of detail's Gaussians before all are evaluated again; until then a new choice of
   * Gaussians (InteractiveReuseAngle) evaluates only the colours of those newly chosen and
   * keeps the others'. 0 evaluates every colour at every choice. Default 18 degrees
   * (Documentation/accuracy-vs-runtime.md).
   */
  vtkSetClampMacro(InteractiveColorAngle, double, 0.0, 90.0);
  vtkGetMacro(InteractiveColorAngle, double);
  ///@}

  ///@{
  /**
   * CPU path: once the view has moved this fraction of InteractiveReuseAngle away from the
   * camera the level of detail's Gaussians were chosen for, the next choice starts on a
   * builder thread for the current view (vis4gs::BuildSplatMovingSet), and the moving frames
   * keep drawing the current choice until it is ready (a frame whose view the current choice
   * no longer serves waits for it). The choice's work is the same; it leaves the frame's
   * level-of-detail step and runs beside the frame, which on two cores then shares them with
   * it (measured: no less CPU per moving frame, Documentation/accuracy-vs-runtime.md; in fast
   * motion the choice made ahead may be stale and made again). 0 (default) chooses again only
   * when a frame needs it, on the thread that makes the frame (the frames then depend on
   * nothing but their cameras).
   */
  vtkSetClampMacro(InteractiveRebuildAhead, double, 0.0, 1.0);
  vtkGetMacro(InteractiveRebuildAhead, double);
  ///@}

  ///@{
  /**
   * CPU path: the transmittance at which a moving frame's pixel stops blending
   * (vis4gs::RasterSettings::TransmittanceStop): what remains behind it, at most this fraction
   * of the pixel, is left out. Still frames use the reference's 1e-4 whatever this is. Default
   * 0.004, about one 8-bit level (Documentation/accuracy-vs-runtime.md).
   */
  vtkSetClampMacro(InteractiveTransmittanceStop, double, 1e-4, 0.5);
  vtkGetMacro(InteractiveTransmittanceStop, double);
  ///@}

  ///@{
  /**
   * CPU path: the image sample distance of the last frame and the milliseconds its CPU
   * rasterisation took (0 when the cached image was reused).
   */
  vtkGetMacro(LastImageSampleDistance, double);
  vtkGetMacro(LastRasterTime, double);
  ///@}

  ///@{
  /**
   * CPU path: wall and CPU milliseconds (the whole process's, every thread) of the steps of
   * the last frame made: 0 the level of detail (a moving frame's choice of Gaussians, or its
   * reuse), 1 projection, 2 overlay, 3 binning, 4 compositing, 5 the image turned into
   * texels; and of its texture upload and draw on the render thread (LastRasterDrawTime).
   * Zeros when the cached image was reused. For the benchmarks: where a frame's time goes.
   */
  vtkGetVector6Macro(LastRasterPhaseTimes, double);
  vtkGetVector6Macro(LastRasterPhaseCpuTimes, double);
  vtkGetMacro(LastRasterDrawTime, double);
  ///@}

  /**
   * CPU path: whether the last frame drew the InteractiveSplatBudget's Gaussians only (a
   * moving frame of a scene larger than the budget) instead of every Gaussian.
   */
  vtkGetMacro(LastFrameReduced, bool);

#ifndef __VTK_WRAP__
  /**
   * CPU path: the rasteriser buffers of the last image drawn (projection and tile lists in
   * vis4gs::RasterWorkspace), with the camera and the input (pointer, for identity only, and
   * its MTime when converted) it was drawn for, when that image was drawn at full resolution
   * with ScaleModifier 1 and every Gaussian unmodified (no hiding, no opacity dimming:
   * overlay colours do not matter); nullptr otherwise (nothing drawn on the CPU path yet, a
   * reduced interactive frame, ...). Valid until the next render. vtkGaussianSelector reuses
   * them, when the camera and scene are its own, instead of projecting the scene again. With
   * @p weights, also the blends that image's compositing kept (SelectionWeightThreshold), or
   * nullptr when it kept none.
   */
  const vis4gs::RasterWorkspace<float>* GetLastFullFrame(const vis4gs::Camera*& camera,
    vtkPolyData*& input,
    vtkMTimeType& inputTime,
    const vis4gs::PixelWeightRecord** weights = nullptr) const;

  /**
   * The Core form of @p scene that the mapper draws and vtkGaussianSelector selects in;
   * nullptr, with a message in @p error, when the scene has no points or lacks the LogScale,
   * Rotation or OpacityLogit arrays. No copy when the scene's arrays are a reader's shared
   * cloud (vis4gs::GaussianCloudOf): then the scene's arrays are the only copy.
   */
  static std::shared_ptr<const vis4gs::GaussianCloud> ConvertScene(vtkPolyData* scene,
    std::string* error);

  /**
   * Draws @p cloud, the Core form of @p input at its current MTime (ConvertScene), instead of
   * converting the input itself: vtkGaussianSceneView converts its scene once and shares the
   * copy with its selector. Used while the mapper's input is @p input with that MTime; after
   * a change the mapper converts on its own again. nullptr forgets it.
   */
  void SetSharedGaussians(vtkPolyData* input, std::shared_ptr<const vis4gs::GaussianCloud> cloud);
#endif

  ///@{
  /**
   * CPU path: produce the frames on a worker thread of the mapper (one std::thread, joined
   * when the mapper is destroyed or this is switched off) instead of the render thread, so
   * that a render never waits for the rasteriser. A render hands the worker a request for
   * its camera and display options (the newest request replaces one not started yet) and
   * draws the newest finished frame of the current scene (nothing before the first one; never
   * a frame of a replaced input); the still frame after motion is the exact frame, bit for
   * bit as in the synchronous mode, drawn by the first render after it is finished. The
   * frame-ready callback (SetFrameReadyCallback) tells the application when to render again;
   * WaitForFrame() waits for it. Default off (every render makes its frame).
   */
  vtkSetMacro(AsynchronousFrames, bool);
  vtkGetMacro(AsynchronousFrames, bool);
  vtkBooleanMacro(AsynchronousFrames, bool);
  ///@}

  ///@{
  /**
   * CPU path, AsynchronousFrames: the nice value of the frame worker and of the OpenMP threads
   * it starts (vis4gs::LowerThreadPriority), taken when the worker starts (the first
   * asynchronous frame). The render thread and the OpenGL driver's threads then run first when
   * they have work, so that a pick's answer and the linked views' renders do not wait for the
   * highlighted frame the same pick asked for (on two cores the worker's team takes both); the
   * worker has the CPU whenever they wait. Frames are the same, only their timing changes.
   * 0-19; default 10 (0: the render thread's priority).
   */
  vtkSetClampMacro(FrameWorkerNice, int, 0, 19);
  vtkGetMacro(FrameWorkerNice, int);
  ///@}

  /**
   * CPU path: whether the frame drawn by the last render is not yet the one for its camera
   * and display options (being produced, or finished and waiting for a render).
   */
  bool GetFramePending();

  /**
   * CPU path: blocks until the worker has finished the frames requested (AsynchronousFrames);
   * the next render draws the newest. Returns at once in the synchronous mode.
   */
  void WaitForFrame();

  /**
   * CPU path: how many new images renders have drawn since the mapper was made (a render
   * that draws the image already drawn does not count).
   */
  vtkIdType GetFramesShown();

#ifndef __VTK_WRAP__
  /**
   * CPU path, AsynchronousFrames: called on the mapper's worker thread whenever a frame is
   * finished (e.g. to post a render to the GUI thread's event loop). Setting another, or
   * nullptr, waits for a call in progress. Default none.
   */
  void SetFrameReadyCallback(std::function<void()> callback);
#endif

  ///@{
  /**
   * CPU threads for sorting and colours; 0 (default) uses OpenMP's default.
   */
  vtkSetClampMacro(NumberOfThreads, int, 0, 1024);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  /**
   * The splats' colour-map lookup table over the current colour-map range (for a
   * vtkScalarBarActor). The range is the automatic one of the current input when
   * AutoScoreRange is on. For a score with a suspicious end (vis4gs::SuspiciousEndOf) the
   * table carries the annotation "suspicious" at that end of the range.
   */
  vtkLookupTable* GetScoreLookupTable();

  ///@{
  /**
   * OpenGL path: sort on the mapper's worker thread (one std::thread, joined when the mapper
   * is destroyed) instead of the render thread. While the camera moves (the render window's
   * DesiredUpdateRate >= InteractiveUpdateRate) a frame draws with the last order that
   * finished; a still frame waits for the order of its camera. Off: every frame sorts for
   * its camera on the render thread. Default on.
   */
  vtkSetMacro(AsynchronousSort, bool);
  vtkGetMacro(AsynchronousSort, bool);
  vtkBooleanMacro(AsynchronousSort, bool);
  ///@}

  ///@{
  /**
   * Figures of the last render: splats drawn (after culls and hiding); milliseconds the
   * order that arrived for this frame took to sort (on the worker thread when
   * AsynchronousSort is on; 0 when no new order arrived); milliseconds on display colours
   * (SCORE colours, hiding, highlight: only when they changed) and uploading.
   */
  vtkGetMacro(LastDrawnCount, vtkIdType);
  vtkGetMacro(LastSortTime, double);
  vtkGetMacro(LastColorTime, double);
  vtkGetMacro(LastUploadTime, double);
  ///@}

  ///@{
  /**
   * OpenGL path, figures of the last render: LastOrderLag, the number of camera changes
   * between the camera the drawn order was sorted for and the frame's camera (0: exact);
   * LastRenderThreadTime, the CPU milliseconds of the render thread in RenderPiece
   * (thread CPU clock) except the draw call; LastDrawCallTime, the render thread's CPU
   * milliseconds inside the draw call (on a software OpenGL such as llvmpipe this is the
   * driver running the vertex and geometry shaders on this thread; on a GPU, queueing).
   */
  vtkGetMacro(LastOrderLag, vtkIdType);
  vtkGetMacro(LastRenderThreadTime, double);
  vtkGetMacro(LastDrawCallTime, double);
  ///@}

  /**
   * OpenGL path: how many times the scene's data (geometry, SH coefficients, display colours)
   * were uploaded, and how many orders, since the mapper was made. For tests: moving the
   * camera uploads orders only.
   */
  vtkIdType GetSceneUploadCount();
  vtkIdType GetOrderUploadCount();

  void RenderPiece(vtkRenderer* ren, vtkActor* act) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;
  bool HasOpaqueGeometry() override
  {
    return true;
  }
  bool HasTranslucentPolygonalGeometry() override
  {
    return false;
  }

protected:
  vtkGaussianSplatMapper();
  ~vtkGaussianSplatMapper() override;

  int SplatColoring = TRUE_COLOR;
  char* ScoreArrayName = nullptr;
  double ScoreRange[2] = { 0.0, 1.0 };
  bool AutoScoreRange = true;
  bool HideOutsideRange = false;
  double VisibleRange[2] = { VTK_DOUBLE_MIN, VTK_DOUBLE_MAX };
  vtkIdTypeArray* SelectedIds = nullptr;
  bool HighlightSelected = true;
  double HighlightColor[3] = { 1.0, 0.35, 0.0 };
  double HighlightMix = 0.7;
  bool DimUnselected = false;
  double DimOpacity = 0.15;
  int ShDegree = -1;
  double ScaleModifier = 1.0;
  int NumberOfThreads = 0;
  int GeometryPath = GEOMETRY_SHADER;
  vtkIdType MaximumNumberOfSplats = 0;
  int DrawMethod = AUTOMATIC;
  int LastDrawMethod = AUTOMATIC;
  double ImageSampleDistance = 1.0;
  double InteractiveImageSampleDistance = 2.0;
  bool AutoAdjustImageSampleDistances = true;
  double MaximumImageSampleDistance = 4.0;
  double InteractiveUpdateRate = 1.0;
  double LastImageSampleDistance = 1.0;
  double LastRasterTime = 0.0;
  double LastRasterPhaseTimes[6] = { 0, 0, 0, 0, 0, 0 };
  double LastRasterPhaseCpuTimes[6] = { 0, 0, 0, 0, 0, 0 };
  double LastRasterDrawTime = 0.0;
  vtkIdType InteractiveSplatBudget = 400000;
  double SelectionWeightThreshold = 0.01;
  double InteractiveReuseAngle = 7.0;
  double InteractiveColorAngle = 18.0;
  double InteractiveRebuildAhead = 0.0;
  double InteractiveTransmittanceStop = 0.004;
  bool LastFrameReduced = false;
  bool AsynchronousFrames = false;
  int FrameWorkerNice = 10; // (vis4gs::BackgroundThreadNice)
  vtkLookupTable* ScoreLookupTable = nullptr;
  vtkIdType LastDrawnCount = 0;
  double LastSortTime = 0.0;
  double LastColorTime = 0.0;
  double LastUploadTime = 0.0;
  bool AsynchronousSort = true;
  vtkIdType LastOrderLag = 0;
  double LastRenderThreadTime = 0.0;
  double LastDrawCallTime = 0.0;

private:
  vtkGaussianSplatMapper(const vtkGaussianSplatMapper&) = delete;
  void operator=(const vtkGaussianSplatMapper&) = delete;

  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;

  void RenderOpenGLSplats(vtkRenderer* ren,
    vtkPolyData* input,
    int width,
    int height,
    int ox,
    int oy,
    const double worldToCamera[16],
    double fx,
    double fy,
    const double center[3],
    const double depthCoeffs[2],
    bool interactive);
  void RenderRasterized(vtkRenderer* ren,
    vtkPolyData* input,
    int width,
    int height,
    const double worldToCamera[16],
    double fx,
    double fy,
    const double depthCoeffs[2]);
};

#endif

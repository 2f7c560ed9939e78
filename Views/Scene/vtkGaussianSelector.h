/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianSelector.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianSelector
 * @brief   Selects Gaussians of a scene in the view of a renderer: Single, Brush, Frame, Ray.
 *
 * The four selection modes of the Gaussian analysis view (DESIGN, view A), computed by Core
 * (Core/Selection) on the exact CPU rasteriser for the renderer's current camera and size:
 *
 *  - Single: the Gaussian with the largest blending weight alpha*T at the clicked pixel.
 *  - Brush: every Gaussian whose largest weight over the brushed pixels (within BrushRadius
 *    of the stroke) is >= WeightThreshold.
 *  - Frame: every Gaussian whose centre projects into the rectangle and whose largest weight
 *    over the rectangle is >= WeightThreshold (visible inside the rectangle); with
 *    IncludeOccluded, every projected one whose centre is inside. A visible-only frame
 *    replays the compositing of the rectangle's pixels (each Gaussian only on the pixel rows
 *    its blend box meets); one that covers half of the view or more first computes every
 *    Gaussian's largest weight over the view (one compositing pass, about the cost of
 *    replaying the whole view, cached with the projection), after which frames with that
 *    camera replay only pixels near the rectangle's border (the same result).
 *  - Ray: every Gaussian whose rasteriser footprint covers the pixel in the drawn frame
 *    (alpha = min(0.99, o e^power) >= 1/255 there, inside its tile rectangle, after the
 *    near-plane cull), occluded or not, in depth order (GetRayHitIds()) with its view depth,
 *    alpha and weight alpha*T along the full composite (GetRayHitDistances(),
 *    GetRayHitAlphas(), GetRayHitWeights()). Single's pick at a pixel is always one of them.
 *    With RayEllipsoid on instead: every Gaussian that the viewing ray passes within
 *    RaySigmas standard deviations of (the 3D ellipsoid test, distances in sigmas, no alpha
 *    or weight), found through an octree over the Gaussians' bounding boxes.
 *
 * Coordinates are VTK display coordinates of the renderer's window (x right, y up, as the
 * interactor reports them). Each selection combines with the current one by Modifier
 * (REPLACE, ADD, SUBTRACT, TOGGLE). With a SelectionHub (what vtkGaussianSceneView sets) the hub
 * is the one selection state: each pick is combined there, by Modifier, with whatever the
 * other views selected, and the selector keeps only its last pick (GetSelection()). Without
 * one, the selector combines the picks itself: the result is a vtkSelection with one node of
 * PEDIGREEIDS on POINT data whose list is the GaussianId values (point indices when the scene
 * has no GaussianId array); when an AnnotationLink is set it is published there (the
 * selection hub's link) and the link's AnnotationChangedEvent is fired.
 *
 * The projection and binning of the scene are cached per camera (the first selection after
 * the camera moved pays for them: GetLastPrepareTime()); the octree per scene. With a
 * SplatMapper set, a Single, Brush, Frame or (footprint) Ray selection after the camera moved
 * reuses instead the projection and tile lists of the image the mapper last drew on its
 * CPU-rasteriser path, when that image is provably of this view: the mapper's input is the Scene
 * (same object, same MTime), the camera and viewport size are equal to the renderer's, at full
 * resolution, with ScaleModifier 1 and no hidden or dimmed Gaussians
 * (vtkGaussianSplatMapper::GetLastFullFrame()); a Frame that computes the view maxima copies
 * that frame into its cached view instead of projecting. Otherwise it projects the scene as
 * above; the selection is the same. When that frame's compositing also kept its blends of
 * weight >= the mapper's SelectionWeightThreshold (<= WeightThreshold), Brush and visible-only
 * Frame read them over the stroke's pixels or the rectangle instead of replaying the
 * compositing there (GetLastSelectionReadWeights()): the same selection, as a lookup.
 */
#ifndef vtkGaussianSelector_h
#define vtkGaussianSelector_h

#include "vis4gsViewsSceneModule.h" // For export macro
#include "vtkObject.h"

#include <memory> // For std::unique_ptr
#include <vector> // For std::vector

#ifndef __VTK_WRAP__
namespace vis4gs
{
struct GaussianCloud;
struct PixelWeightRecord;
template <typename T>
struct RasterWorkspace;
}
#endif

class vtkAnnotationLink;
class vtkGaussianSelectionHub;
class vtkDoubleArray;
class vtkGaussianSplatMapper;
class vtkIdTypeArray;
class vtkPoints;
class vtkPolyData;
class vtkRenderer;
class vtkSelection;

class VIS4GSVIEWSSCENE_EXPORT vtkGaussianSelector : public vtkObject
{
public:
  static vtkGaussianSelector* New();
  vtkTypeMacro(vtkGaussianSelector, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Modifiers
  {
    REPLACE = 0,
    ADD = 1,
    SUBTRACT = 2,
    TOGGLE = 3
  };

  ///@{
  /**
   * The Gaussian scene (DESIGN §2 polydata). Default none.
   */
  void SetScene(vtkPolyData* scene);
  vtkGetObjectMacro(Scene, vtkPolyData);
  ///@}

  ///@{
  /**
   * The renderer whose active camera and size define the view. Default none.
   */
  void SetRenderer(vtkRenderer* renderer);
  vtkGetObjectMacro(Renderer, vtkRenderer);
  ///@}

  ///@{
  /**
   * The mapper drawing the Scene in the Renderer, whose last full-resolution CPU-rasteriser
   * frame a Single, Brush, Frame or Ray selection may reuse (see above). Default none (always
   * project).
   */
  void SetSplatMapper(vtkGaussianSplatMapper* mapper);
  vtkGetObjectMacro(SplatMapper, vtkGaussianSplatMapper);
  ///@}

#ifndef __VTK_WRAP__
  /**
   * Selects in @p cloud, the Core form of @p scene at its current MTime
   * (vtkGaussianSplatMapper::ConvertScene), instead of converting the scene itself:
   * vtkGaussianSceneView shares one copy between its mapper and this selector. Used while the
   * Scene is @p scene with that MTime; after a change the selector converts on its own again.
   * nullptr forgets it.
   */
  void SetSharedGaussians(vtkPolyData* scene, std::shared_ptr<const vis4gs::GaussianCloud> cloud);
#endif

  ///@{
  /**
   * How a new selection combines with the current one. Default REPLACE.
   */
  vtkSetClampMacro(Modifier, int, REPLACE, TOGGLE);
  vtkGetMacro(Modifier, int);
  ///@}

  ///@{
  /**
   * Minimum blending weight for Brush and Frame. Default 0.01.
   */
  vtkSetClampMacro(WeightThreshold, double, 1e-12, 1.0);
  vtkGetMacro(WeightThreshold, double);
  ///@}

  ///@{
  /**
   * Brush radius in pixels. Default 8.
   */
  vtkSetClampMacro(BrushRadius, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(BrushRadius, double);
  ///@}

  ///@{
  /**
   * Frame: also take Gaussians whose centre is inside but that are not visible. Default off.
   */
  vtkSetMacro(IncludeOccluded, bool);
  vtkGetMacro(IncludeOccluded, bool);
  vtkBooleanMacro(IncludeOccluded, bool);
  ///@}

  ///@{
  /**
   * Ray with RayEllipsoid: k of the k-sigma test. Default 3 (the octree is rebuilt when a
   * larger k is asked).
   */
  vtkSetClampMacro(RaySigmas, double, 0.0, 100.0);
  vtkGetMacro(RaySigmas, double);
  ///@}

  ///@{
  /**
   * Ray by the 3D k-sigma ellipsoid through the octree instead of the drawn footprints.
   * Default off (the footprints: the set consistent with the image and with Single).
   */
  vtkSetMacro(RayEllipsoid, bool);
  vtkGetMacro(RayEllipsoid, bool);
  vtkBooleanMacro(RayEllipsoid, bool);
  ///@}

  ///@{
  /**
   * Threads of the selection passes; 0 (default) uses OpenMP's default.
   */
  vtkSetClampMacro(NumberOfThreads, int, 0, 1024);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  ///@{
  /**
   * When set, every selection is published as the link's current selection. Default none.
   */
  void SetAnnotationLink(vtkAnnotationLink* link);
  vtkGetObjectMacro(AnnotationLink, vtkAnnotationLink);
  ///@}

  ///@{
  /**
   * The selection hub each pick is combined into (by Modifier), held weakly; it then holds the
   * selection and the selector only its last pick. Default none (the selector combines).
   */
  void SetSelectionHub(vtkGaussianSelectionHub* hub);
  vtkGaussianSelectionHub* GetSelectionHub();
  ///@}

  ///@{
  /**
   * The selection modes. Return the number of Gaussians the mode picked (before the
   * modifier), or -1 on error (no scene, no renderer, invalid scene).
   */
  vtkIdType SelectSingle(double x, double y);
  vtkIdType SelectBrush(vtkPoints* stroke);
  vtkIdType SelectFrame(double x0, double y0, double x1, double y1);
  vtkIdType SelectRay(double x, double y);
  ///@}

  /// Clears the current selection (and publishes the empty selection).
  void ClearSelection();

  /// The current selection (PEDIGREEIDS of GaussianId on POINT data); with a SelectionHub, the
  /// last pick.
  vtkSelection* GetSelection();

  /// GetSelection()'s GaussianId values, ascending.
  vtkIdTypeArray* GetSelectedIds();

  ///@{
  /**
   * The last Ray selection: GaussianIds in depth order; their view depths ("Depth"), or
   * distances in sigmas ("Sigmas") with RayEllipsoid; their alpha and alpha*T at the pixel
   * (empty with RayEllipsoid).
   */
  vtkIdTypeArray* GetRayHitIds();
  vtkDoubleArray* GetRayHitDistances();
  vtkDoubleArray* GetRayHitAlphas();
  vtkDoubleArray* GetRayHitWeights();
  ///@}

  ///@{
  /**
   * Milliseconds of the last selection call, and of the projection/binning (or octree build)
   * it had to do first (0 when cached).
   */
  vtkGetMacro(LastSelectionTime, double);
  vtkGetMacro(LastPrepareTime, double);
  ///@}

  /**
   * Whether the last selection read (or copied) the SplatMapper's drawn frame instead of
   * projecting the scene.
   */
  vtkGetMacro(LastSelectionReusedFrame, bool);

  /**
   * Whether the last Brush or (visible-only) Frame read the blends the SplatMapper's drawn
   * frame kept (vtkGaussianSplatMapper::SelectionWeightThreshold, at most this WeightThreshold)
   * instead of replaying the compositing over the stroke or the rectangle: the same
   * selection, as a lookup.
   */
  vtkGetMacro(LastSelectionReadWeights, bool);

  /**
   * Milliseconds of the last selection's publishing (the hub, the linked views' updates and
   * renders): part of LastSelectionTime.
   */
  vtkGetMacro(LastPublishTime, double);

protected:
  vtkGaussianSelector();
  ~vtkGaussianSelector() override;

  vtkPolyData* Scene = nullptr;
  vtkRenderer* Renderer = nullptr;
  vtkAnnotationLink* AnnotationLink = nullptr;
  vtkGaussianSplatMapper* SplatMapper = nullptr;
  int Modifier = REPLACE;
  double WeightThreshold = 0.01;
  double BrushRadius = 8.0;
  bool IncludeOccluded = false;
  double RaySigmas = 3.0;
  bool RayEllipsoid = false;
  int NumberOfThreads = 0;
  double LastSelectionTime = 0.0;
  double LastPrepareTime = 0.0;
  bool LastSelectionReusedFrame = false;
  bool LastSelectionReadWeights = false;
  double LastPublishTime = 0.0;

private:
  vtkGaussianSelector(const vtkGaussianSelector&) = delete;
  void operator=(const vtkGaussianSelector&) = delete;

  bool PrepareView(bool needView);
#ifndef __VTK_WRAP__
  bool PrepareViewOrFrame(const vis4gs::RasterWorkspace<float>*& frame,
    const vis4gs::PixelWeightRecord** weights = nullptr);
#endif
  void PublishIndices(const std::vector<unsigned int>& indices);

  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif

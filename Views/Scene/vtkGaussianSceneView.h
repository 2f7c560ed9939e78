/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianSceneView.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianSceneView
 * @brief   the Gaussian analysis view (DESIGN, view A), linked through the selection hub
 *
 * A vtkRenderViewBase drawing a Gaussian scene (DESIGN §2 polydata) with
 * vtkGaussianSplatMapper: true colour or a score overlay (OverlayArrayName) with its legend,
 * the training cameras' frustums coloured by how many selected Gaussians each one sees
 * (vtkGaussianCameraFrustums), markers at the centres of a small selection (at most
 * MaximumNumberOfMarkers, drawn on a second layer above the splats) and the selection modes of
 * DESIGN (Single, Brush, Frame, Ray) computed by vtkGaussianSelector on the exact CPU
 * rasteriser.
 *
 * Selections go to the hub (SetSelectionHub) and come back from it: a selection made here or
 * in any other view highlights the Gaussians in the mapper, places the markers and recolours
 * the frustums. The hub renders the view after every change (it is one of its views).
 *
 * Mouse: the view observes its interactor (SetInteractor, or the render window's). In Brush
 * and Frame mode a left-button drag selects (the band is drawn while dragging) instead of
 * rotating the camera; in Single and Ray mode a left click (a press and release within two
 * pixels) selects. Shift adds to the selection, Ctrl subtracts. Scripts call SelectSingle,
 * SelectBrush, SelectFrame and SelectRay with display coordinates (x right, y up). After each
 * selection the view fires vtkCommand::EndPickEvent (GetLastSelectionCount/Mode say what was
 * picked, the selector's GetLastSelectionTime how long it took).
 *
 * The mapper and the selector share one Core form of the Gaussians, taken once per scene and
 * MTime: for a reader's scene it is the scene's own arrays (vis4gs::SharedGaussianCloud), so
 * the polydata is the only copy; any other scene is converted once.
 */
#ifndef vtkGaussianSceneView_h
#define vtkGaussianSceneView_h

#include "vis4gsViewsSceneModule.h" // For export macro
#include "vtkRenderViewBase.h"

#include <array>  // For std::array
#include <memory> // For std::unique_ptr
#include <vector> // For std::vector

class vtkActor;
class vtkAlgorithmOutput;
class vtkGaussianCameraFrustums;
class vtkGaussianSelectionHub;
class vtkGaussianSelector;
class vtkGaussianSplatMapper;
class vtkIdTypeArray;
class vtkPoints;
class vtkPolyData;
class vtkRenderWindow;
class vtkRenderWindowInteractor;
class vtkRenderer;
class vtkScalarBarActor;
class vtkTable;

class VIS4GSVIEWSSCENE_EXPORT vtkGaussianSceneView : public vtkRenderViewBase
{
public:
  static vtkGaussianSceneView* New();
  vtkTypeMacro(vtkGaussianSceneView, vtkRenderViewBase);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The selection modes of DESIGN's view A.
  enum SelectionModes
  {
    SINGLE = 0,
    BRUSH = 1,
    FRAME = 2,
    RAY = 3
  };

  ///@{
  /**
   * The Gaussians (DESIGN §2 polydata, with GaussianId). Default none. SetScene() hands the
   * data over and disconnects SetInputConnection(); GetScene() is what the view draws.
   */
  void SetScene(vtkPolyData* scene);
  vtkPolyData* GetScene();
  ///@}

  ///@{
  /**
   * The Gaussians as a connection, e.g. vtkGaussianSession's GaussiansPort: the view updates
   * it in Update() and Render() and takes a shallow copy of its output when its arrays
   * changed (Vis4GSViewInput), so that a new snapshot or new score arrays reach the view
   * without a client handing them over, and the producer may execute again while the splat
   * mapper's asynchronous frame still draws the previous copy. Null (the default): none.
   */
  void SetInputConnection(vtkAlgorithmOutput* output);
  vtkAlgorithmOutput* GetInputConnection();
  ///@}

  ///@{
  /**
   * The cameras (the table of vis4gs::arrays columns) whose frustums are drawn; none draws
   * none. Default none. SetCameras() disconnects SetCamerasConnection(), which takes them
   * from a port (vtkGaussianSession's CamerasPort) as SetInputConnection() does.
   */
  void SetCameras(vtkTable* cameras);
  vtkTable* GetCameras();
  void SetCamerasConnection(vtkAlgorithmOutput* output);
  vtkAlgorithmOutput* GetCamerasConnection();
  ///@}

  /// Pulls the connections (nothing is taken again when their arrays are unchanged).
  void Update() override;
  /// Update(), then draws.
  void Render() override;

  /// Moves the camera to camera @p row of Cameras; false when there is no such row.
  bool JumpToCamera(vtkIdType row);

  ///@{
  /**
   * Links the view to @p hub (registered as one of its views); nullptr unlinks.
   */
  void SetSelectionHub(vtkGaussianSelectionHub* hub);
  vtkGaussianSelectionHub* GetSelectionHub();
  ///@}

  ///@{
  /**
   * The mode of the mouse (SelectionModes). Default SINGLE.
   */
  vtkSetClampMacro(SelectionMode, int, SINGLE, RAY);
  vtkGetMacro(SelectionMode, int);
  ///@}

  ///@{
  /**
   * The score overlay: the point array coloured through the score colour map, nullptr or ""
   * for the true colour (SH). A name the scene lacks draws true colour. Default true colour.
   */
  void SetOverlayArrayName(const char* name);
  vtkGetStringMacro(OverlayArrayName);
  ///@}

  ///@{
  /**
   * The colour range of the overlay; hi <= lo takes the array's range. Default (0, 0).
   */
  void SetOverlayRange(double lo, double hi);
  vtkGetVector2Macro(OverlayRange, double);
  ///@}

  ///@{
  /**
   * Hide the Gaussians whose overlay value is outside OverlayRange. Default off.
   */
  void SetHideOutsideRange(bool hide);
  vtkGetMacro(HideOutsideRange, bool);
  vtkBooleanMacro(HideOutsideRange, bool);
  ///@}

  ///@{
  /**
   * Hide the Gaussians whose overlay value is below Threshold (with UseThreshold).
   * Defaults off, 0.
   */
  void SetUseThreshold(bool use);
  vtkGetMacro(UseThreshold, bool);
  vtkBooleanMacro(UseThreshold, bool);
  void SetThreshold(double threshold);
  vtkGetMacro(Threshold, double);
  ///@}

  ///@{
  /**
   * Dim the Gaussians that are not selected. Default off.
   */
  void SetDimUnselected(bool dim);
  vtkGetMacro(DimUnselected, bool);
  vtkBooleanMacro(DimUnselected, bool);
  ///@}

  ///@{
  /**
   * Draw the cameras' frustums (when Cameras is set). Default on.
   */
  void SetShowFrustums(bool show);
  vtkGetMacro(ShowFrustums, bool);
  vtkBooleanMacro(ShowFrustums, bool);
  ///@}

  ///@{
  /**
   * Level of detail: at most this many splats drawn
   * (vtkGaussianSplatMapper::MaximumNumberOfSplats); 0 draws all. Selection always uses every
   * Gaussian. Default 200000.
   */
  void SetMaximumNumberOfSplats(vtkIdType splats);
  vtkIdType GetMaximumNumberOfSplats();
  ///@}

  ///@{
  /**
   * Level of detail of the CPU rasteriser while the camera moves: at most this many
   * Gaussians, those of highest contribution to the view, drawn per moving frame
   * (vtkGaussianSplatMapper::InteractiveSplatBudget); still frames draw every Gaussian. 0
   * draws all. Default the mapper's (400000).
   */
  void SetInteractiveSplatBudget(vtkIdType splats);
  vtkIdType GetInteractiveSplatBudget();
  ///@}

  ///@{
  /**
   * Selections with more Gaussians than this get no centre markers. Default 200.
   */
  vtkSetClampMacro(MaximumNumberOfMarkers, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(MaximumNumberOfMarkers, vtkIdType);
  ///@}

  ///@{
  /**
   * The selection modes in display coordinates, published to the hub combined by @p combine
   * (vtkGaussianSelectionHub::REPLACE, ADD, SUBTRACT). Return the number of Gaussians the mode
   * picked (before combining), -1 on error (no scene, no hub, an invalid scene). A REPLACE
   * that picks nothing clears the selection.
   */
  vtkIdType SelectSingle(double x, double y, int combine = 0);
  vtkIdType SelectRay(double x, double y, int combine = 0);
  vtkIdType SelectFrame(double x0, double y0, double x1, double y1, int combine = 0);
  vtkIdType SelectBrush(vtkPoints* stroke, int combine = 0);
  ///@}

  /**
   * Replaces the selection with the Gaussian drawn at display pixel (x, y); returns its
   * GaussianId, -1 when there is none.
   */
  vtkIdType PickAt(double x, double y);

  /// GaussianIds of the last Ray selection, front to back.
  vtkIdTypeArray* GetLastRayHitIds();

  /// Number of the scene's Gaussians that are selected in the hub (highlighted).
  vtkGetMacro(HighlightCount, vtkIdType);

  ///@{
  /**
   * The last selection: its mode and the number of Gaussians it picked.
   */
  vtkGetMacro(LastSelectionMode, int);
  vtkGetMacro(LastSelectionCount, vtkIdType);
  ///@}

  ///@{
  /**
   * The parts, for styling, scripted checks and the application's status messages.
   */
  vtkGaussianSplatMapper* GetSplatMapper();
  vtkGaussianSelector* GetSelector();
  vtkScalarBarActor* GetLegend();
  vtkGaussianCameraFrustums* GetFrustums();
  vtkActor* GetFrustumActor();
  /// Centre markers of the selection (vertices; empty above MaximumNumberOfMarkers).
  vtkPolyData* GetMarkers();
  /// The brush stroke or frame being dragged, in display coordinates (empty otherwise).
  vtkPolyData* GetBand();
  /// The renderer of the markers (layer 1, sharing the camera of GetRenderer()).
  vtkRenderer* GetMarkerRenderer();
  ///@}

  ///@{
  /**
   * The render window (its renderers are moved over) and the interactor whose mouse events
   * select.
   */
  void SetRenderWindow(vtkRenderWindow* window) override;
  void SetInteractor(vtkRenderWindowInteractor* interactor) override;
  ///@}

protected:
  vtkGaussianSceneView();
  ~vtkGaussianSceneView() override;

  char* OverlayArrayName = nullptr;
  double OverlayRange[2] = { 0.0, 0.0 };
  bool HideOutsideRange = false;
  bool UseThreshold = false;
  double Threshold = 0.0;
  bool DimUnselected = false;
  bool ShowFrustums = true;
  int SelectionMode = SINGLE;
  vtkIdType MaximumNumberOfMarkers = 200;
  vtkIdType HighlightCount = 0;
  int LastSelectionMode = SINGLE;
  vtkIdType LastSelectionCount = 0;

private:
  vtkGaussianSceneView(const vtkGaussianSceneView&) = delete;
  void operator=(const vtkGaussianSceneView&) = delete;

#ifndef __VTK_WRAP__
  vtkIdType Select(int mode, const std::vector<std::array<double, 2>>& points, int combine);
#endif
  void UpdateOverlay();
  // The frustums' selected ids: @p selected (the hub's ids), or a copy of the hub's.
  void UpdateFrustums(vtkIdTypeArray* selected = nullptr);
  void UpdateFrustumColors();
  void ApplyScene(vtkPolyData* scene);
  void ApplyCameras(vtkTable* cameras);
  void OnSelectionChanged();
  void OnMouse(unsigned long event, bool& abort);
  void OnClick();
  void DrawBand();
  void ObserveInteractor(vtkRenderWindowInteractor* interactor);

  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif

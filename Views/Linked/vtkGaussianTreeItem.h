/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianTreeItem.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianTreeItem
 * @brief   context item drawing the densification tree (view B) with level of detail
 *
 * Draws the genealogy vtkTree of Filters/Genealogy in layout coordinates (x = birth
 * iteration, y = layout row, row 0 at the top): family bands (alternating shades), lifespan
 * lines from birth to death (or the last iteration while alive), parent-child edges (a
 * vertical segment at the child's birth from the parent's row to the child's row), node
 * markers coloured by birth kind (DESIGN §6: root brown, clone aquamarine, split tan,
 * clone-split teal; a purple marker at the death of pruned Gaussians; a white ring around a
 * root that a lineage break of the log started, when the tree has the optional vertex array
 * LineageBreakRoot, and then a legend entry "lineage break"), the selected lineage
 * highlighted, the iteration cursor, an iteration axis and a legend.
 *
 * Level of detail (DESIGN §4): a node is drawn when P(i) >= tau(z) (tau from Core's
 * vis4gs::ZoomThreshold) or when it is in the selected lineage (the selected nodes, their
 * ancestors and their descendants), and its row and life intersect the viewport. Only that
 * subset is visited: the nodes are indexed once by P (descending) and by row, and each frame
 * scans whichever is shorter (the P >= tau prefix or the rows in the viewport).
 *
 * Zoom z: 1 at "fit all rows" would make tau depend on the tree size, so z is defined from
 * the vertical magnification s = (all rows) / (rows in the viewport) on a log scale:
 * z = ZMin + (ZMax - ZMin) * log(s) / log(sMax), sMax = (all rows) / ZoomedInRows, clamped
 * to [ZMin, ZMax] = [0.1, 2.0]; so the whole tree shows at z = 0.1 (tau = 1: only the most
 * perceptible node of each family) and every node shows once ZoomedInRows rows fill the view.
 *
 * Interaction: mouse wheel zooms the rows around the cursor (with Control: the iterations),
 * left drag pans, a left click selects the node under the cursor (Shift adds, Control
 * toggles; a click on nothing clears), through the selection hub.
 *
 * Input arrays (vertex data of the tree; names settable): GaussianId, LayoutX (birth
 * iteration), LayoutY (row), DeathIteration (-1 alive), PerceptionValue, BirthKind (0 root,
 * 1 clone, 2 split, 4 clone-split), optional Pruned. Vertices with a negative GaussianId
 * (the virtual root) are not drawn. Optional family bands table with columns MinIteration,
 * MaxIteration, MinRow, MaxRow. The last iteration is the field-data value `LastIteration`
 * when present, else the largest birth/death.
 */
#ifndef vtkGaussianTreeItem_h
#define vtkGaussianTreeItem_h

#include "vis4gsViewsLinkedModule.h" // For export macro
#include "vtkContextItem.h"
#include "vtkSmartPointer.h" // For vtkSmartPointer

#include <memory> // For std::unique_ptr

class vtkGaussianSelectionHub;
class vtkIdTypeArray;
class vtkTable;
class vtkTree;

class VIS4GSVIEWSLINKED_EXPORT vtkGaussianTreeItem : public vtkContextItem
{
public:
  static vtkGaussianTreeItem* New();
  vtkTypeMacro(vtkGaussianTreeItem, vtkContextItem);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The genealogy tree (Filters/Genealogy output) and its family bands table. Default none.
   */
  void SetTree(vtkTree* tree);
  vtkTree* GetTree();
  void SetFamilyBands(vtkTable* bands);
  vtkTable* GetFamilyBands();
  ///@}

  ///@{
  /**
   * The selection hub: clicks publish to it, its changes update the highlighted lineage,
   * its iteration moves the cursor. Held by a weak reference. Default none.
   */
  void SetSelectionHub(vtkGaussianSelectionHub* hub);
  vtkGaussianSelectionHub* GetSelectionHub();
  ///@}

  ///@{
  /**
   * Vertex array names. Defaults: GaussianId, LayoutX, LayoutY, DeathIteration,
   * PerceptionValue, BirthKind, Pruned.
   */
  vtkSetStringMacro(IdArrayName);
  vtkGetStringMacro(IdArrayName);
  vtkSetStringMacro(XArrayName);
  vtkGetStringMacro(XArrayName);
  vtkSetStringMacro(YArrayName);
  vtkGetStringMacro(YArrayName);
  vtkSetStringMacro(DeathArrayName);
  vtkGetStringMacro(DeathArrayName);
  vtkSetStringMacro(PerceptionArrayName);
  vtkGetStringMacro(PerceptionArrayName);
  vtkSetStringMacro(KindArrayName);
  vtkGetStringMacro(KindArrayName);
  vtkSetStringMacro(PrunedArrayName);
  vtkGetStringMacro(PrunedArrayName);
  ///@}

  ///@{
  /**
   * Rows filling the view at z = ZMax (see the class comment). Default 100.
   */
  vtkSetClampMacro(ZoomedInRows, double, 1.0, 1e12);
  vtkGetMacro(ZoomedInRows, double);
  ///@}

  ///@{
  /**
   * Drawing level of detail: when more than 256 lifespan lines are drawn, lines of one colour
   * on the same pixel row that overlap are drawn as one (opaque where several merged). Rows
   * at least a pixel apart are never merged, so it only changes views with more rows than
   * pixels, where it removes the overdraw that bounds the frame rate on software OpenGL.
   * Default on.
   */
  vtkSetMacro(MergeLinesPerPixelRow, bool);
  vtkGetMacro(MergeLinesPerPixelRow, bool);
  vtkBooleanMacro(MergeLinesPerPixelRow, bool);
  ///@}

  ///@{
  /**
   * The viewport in layout coordinates: iterations [MinX, MaxX], rows [MinY, MaxY].
   * ResetViewport() fits the whole tree.
   */
  void SetViewport(double minX, double maxX, double minY, double maxY);
  void GetViewport(double viewport[4]);
  void ResetViewport();
  ///@}

  ///@{
  /**
   * The zoom z of DESIGN §4 (derived from the viewport, see the class comment). SetZoom keeps
   * the viewport centred on the same row. Zoom/Pan act like the mouse: factor > 1 zooms in.
   */
  double GetZoom();
  void SetZoom(double z);
  double GetZoomThreshold();
  void ZoomRows(double factor, double aboutRow);
  void ZoomIterations(double factor, double aboutIteration);
  void Pan(double dIterations, double dRows);
  ///@}

  /// Pans/zooms so that the selected lineage fills the view (no-op without a selection).
  void ZoomToSelection();

  ///@{
  /**
   * Screen size used to convert the viewport when no scene is attached (tests, benchmarks).
   * The scene size is used when there is one. Default 400 x 300.
   */
  vtkSetVector2Macro(Size, int);
  vtkGetVector2Macro(Size, int);
  ///@}

  /**
   * Recomputes the level-of-detail subset for the current viewport and zoom (Paint does it).
   * Returns the number of visible vertices.
   */
  vtkIdType UpdateLevelOfDetail();

  ///@{
  /**
   * Results of the last UpdateLevelOfDetail: visible vertex ids of the tree, the selected
   * vertices, the selected lineage (selected + ancestors + descendants), all sorted.
   */
  void GetVisibleVertices(vtkIdTypeArray* vertices);
  vtkIdType GetNumberOfVisibleVertices();
  void GetSelectedVertices(vtkIdTypeArray* vertices);
  void GetLineageVertices(vtkIdTypeArray* vertices);
  /// Number of node records examined by the last level-of-detail update (for benchmarks).
  vtkIdType GetLastLevelOfDetailWork();
  ///@}

  /**
   * The vertex drawn nearest to the scene point (x, y) within @p tolerance pixels (marker or
   * lifespan line), or -1. Uses the last level-of-detail subset.
   */
  vtkIdType PickVertex(float x, float y, float tolerance = 5.0f);

  /// Scene position of a vertex's birth marker under the current viewport.
  void GetVertexPosition(vtkIdType vertex, float position[2]);

  /// Number of tree vertices (including a virtual root).
  vtkIdType GetNumberOfVertices();

  bool Paint(vtkContext2D* painter) override;
  bool Hit(const vtkContextMouseEvent& mouse) override;
  bool MouseButtonPressEvent(const vtkContextMouseEvent& mouse) override;
  bool MouseMoveEvent(const vtkContextMouseEvent& mouse) override;
  bool MouseButtonReleaseEvent(const vtkContextMouseEvent& mouse) override;
  bool MouseWheelEvent(const vtkContextMouseEvent& mouse, int delta) override;

  /// Called by the hub observer: re-reads the hub's selection and iteration.
  void UpdateFromHub();

protected:
  vtkGaussianTreeItem();
  ~vtkGaussianTreeItem() override;

  void BuildIndex();
  void UpdateSelection();

  char* IdArrayName = nullptr;
  char* XArrayName = nullptr;
  char* YArrayName = nullptr;
  char* DeathArrayName = nullptr;
  char* PerceptionArrayName = nullptr;
  char* KindArrayName = nullptr;
  char* PrunedArrayName = nullptr;
  double ZoomedInRows = 100.0;
  bool MergeLinesPerPixelRow = true;
  int Size[2] = { 400, 300 };

private:
  vtkGaussianTreeItem(const vtkGaussianTreeItem&) = delete;
  void operator=(const vtkGaussianTreeItem&) = delete;

  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif

/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianSelectionHub.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianSelectionHub
 * @brief   the one place where the selected Gaussians live; links every view (DESIGN §2)
 *
 * The hub owns one vtkAnnotationLink whose current selection is always a vtkSelection with
 * one PEDIGREEIDS node whose selection list is a vtkIdTypeArray named `GaussianId` (sorted,
 * without duplicates). Every representation that understands pedigree ids can share the link
 * directly (GetAnnotationLink()); anything that sets the link's current selection, directly or
 * through SetSelection()/SelectIds(), reaches every view:
 *
 * - the hub normalises the selection to sorted unique GaussianIds (pedigree-id nodes, and
 *   INDICES nodes whose field type has an id column registered with AddChart, are accepted),
 * - pushes the matching row INDICES/POINT selection into every chart added with AddChart()
 *   (vtkChartXY reads its annotation link's selection as row indices, guide §5.14),
 * - invokes vtkCommand::SelectionChangedEvent on itself (the tree, timeline and histogram
 *   views observe it and update their highlight),
 * - renders every view added with AddView() (vtkRenderView and vtkContextView alike:
 *   vtkViewUpdater renders only vtkRenderViews) and every render window of AddRenderWindow().
 *
 * The other direction: a chart added with AddChart() writes INDICES/POINT selections of its
 * table rows into its own annotation link when the user selects; the hub converts them to
 * GaussianIds through the chart's id column and publishes them.
 *
 * The hub also carries the current training iteration (SetIteration); a change invokes
 * IterationChangedEvent with a pointer to the int iteration as call data.
 *
 * The conversions are public static functions so that other modules and tests can use them:
 * IdsToIndices (GaussianIds -> row/point/vertex indices of a table, data set or tree whose
 * id column is given) and IndicesToIds.
 */
#ifndef vtkGaussianSelectionHub_h
#define vtkGaussianSelectionHub_h

#include "vis4gsViewsLinkedModule.h" // For export macro
#include "vtkCommand.h"              // For vtkCommand::UserEvent
#include "vtkObject.h"
#include "vtkSmartPointer.h" // For vtkSmartPointer

#include <memory> // For std::unique_ptr
#include <vector> // For std::vector

class vtkAbstractArray;
class vtkAnnotationLink;
class vtkChartXY;
class vtkIdTypeArray;
class vtkRenderWindow;
class vtkSelection;
class vtkTable;
class vtkView;

class VIS4GSVIEWSLINKED_EXPORT vtkGaussianSelectionHub : public vtkObject
{
public:
  static vtkGaussianSelectionHub* New();
  vtkTypeMacro(vtkGaussianSelectionHub, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Events of the hub (besides vtkCommand::SelectionChangedEvent).
  enum Events
  {
    /// The current iteration changed; call data: int* iteration.
    IterationChangedEvent = vtkCommand::UserEvent + 4101
  };

  /// How SelectIds combines the given ids with the current selection.
  enum Modes
  {
    REPLACE = 0,
    ADD = 1,
    SUBTRACT = 2,
    TOGGLE = 3
  };

  /**
   * The shared annotation link. Its current selection holds the selected GaussianIds as
   * pedigree ids (never null; empty when nothing is selected).
   */
  vtkAnnotationLink* GetAnnotationLink();

  ///@{
  /**
   * Change the selection. SetSelection accepts pedigree-id nodes (any array name), and
   * INDICES nodes when a chart/id column is registered for the node's field type through
   * AddChart/SetIndexColumn. SelectIds combines ids with the current selection by @p mode.
   * Each call publishes one change (one SelectionChangedEvent, one render per view) unless
   * the selection is unchanged.
   */
  void SetSelection(vtkSelection* selection);
  void SelectIds(vtkIdTypeArray* ids, int mode = REPLACE);
  void SelectIds(const vtkIdType* ids, vtkIdType count, int mode = REPLACE);
  void ClearSelection();
  ///@}

  ///@{
  /**
   * The current selection: sorted unique GaussianIds.
   */
  void GetSelectedIds(vtkIdTypeArray* ids);
  vtkIdType GetNumberOfSelectedIds();
  bool IsSelected(vtkIdType gaussianId);
#ifndef __VTK_WRAP__
  const std::vector<vtkIdType>& GetSelectedIdVector() const
  {
    return this->Selected;
  }
#endif
  ///@}

  /**
   * The current selection as the array the hub's annotation link holds: a new array after
   * every change, never modified afterwards, so that views may keep it instead of copying it
   * (the scene view's splat mapper and frustums: 200,000 ids for a Frame at 4.89M). Read it
   * only.
   */
  vtkIdTypeArray* GetSelectedIdArray();

  /**
   * The current selection as a new vtkSelection of pedigree ids (`GaussianId`).
   */
  vtkSmartPointer<vtkSelection> GetCurrentSelection();

  ///@{
  /**
   * Views re-rendered after every change. vtkContextViews are rendered too (vtkViewUpdater
   * does not). The hub keeps references.
   */
  void AddView(vtkView* view);
  void RemoveView(vtkView* view);
  void AddRenderWindow(vtkRenderWindow* window);
  void RemoveAllViews();
  int GetNumberOfViews();
  ///@}

  /**
   * Links @p chart, whose plots draw the rows of @p table, both ways: the hub pushes the rows
   * whose @p idColumn value is selected as an INDICES/POINT selection into a private
   * annotation link of the chart, and converts the chart's own selections back. The hub
   * keeps references to the chart and the table.
   */
  void AddChart(vtkChartXY* chart, vtkTable* table, const char* idColumn = "GaussianId");
  /// Stops linking @p chart.
  void RemoveChart(vtkChartXY* chart);

  ///@{
  /**
   * When false, the hub renders nothing after a change (useful while loading). Default true.
   */
  vtkSetMacro(RenderOnChange, bool);
  vtkGetMacro(RenderOnChange, bool);
  vtkBooleanMacro(RenderOnChange, bool);
  ///@}

  /// Renders every registered view and render window now.
  void RenderAll();

  ///@{
  /**
   * The current training iteration shared by the views. Default -1 (none).
   */
  void SetIteration(int iteration);
  vtkGetMacro(Iteration, int);
  ///@}

  /// Number of changes published so far (for tests).
  vtkGetMacro(NumberOfChanges, vtkIdType);

  /**
   * Rows (points, vertices) of @p idColumn whose value is one of the sorted unique @p ids,
   * ascending. O(n) for a sorted column (merge) or O(n) expected with a hash otherwise.
   */
  static void IdsToIndices(const vtkIdType* ids,
    vtkIdType count,
    vtkAbstractArray* idColumn,
    vtkIdTypeArray* indices);
  /// Convenience overload taking an array of sorted unique ids.
  static void IdsToIndices(vtkIdTypeArray* ids,
    vtkAbstractArray* idColumn,
    vtkIdTypeArray* indices);

  /**
   * GaussianIds of the rows @p indices of @p idColumn, sorted unique; out-of-range indices
   * are skipped.
   */
  static void IndicesToIds(vtkIdTypeArray* indices,
    vtkAbstractArray* idColumn,
    vtkIdTypeArray* ids);

  /**
   * A new selection of one INDICES node with @p fieldType (vtkSelectionNode::POINT, VERTEX,
   * ROW...) listing @p indices.
   */
  static vtkSmartPointer<vtkSelection> MakeIndexSelection(vtkIdTypeArray* indices, int fieldType);
  /// A new selection of one PEDIGREEIDS node named `GaussianId` listing @p ids.
  static vtkSmartPointer<vtkSelection> MakePedigreeSelection(vtkIdTypeArray* ids);

protected:
  vtkGaussianSelectionHub();
  ~vtkGaussianSelectionHub() override;

  void Publish(std::vector<vtkIdType>&& ids);
  void OnLinkChanged();
  void OnChartChanged(vtkObject* caller);

  bool RenderOnChange = true;
  int Iteration = -1;
  vtkIdType NumberOfChanges = 0;
  std::vector<vtkIdType> Selected;

private:
  vtkGaussianSelectionHub(const vtkGaussianSelectionHub&) = delete;
  void operator=(const vtkGaussianSelectionHub&) = delete;

  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif

/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianTreeView.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianTreeView
 * @brief   view B of DESIGN: the densification tree, linked through the selection hub
 *
 * A vtkContextView holding one vtkGaussianTreeItem (see it for what is drawn, the level of
 * detail and the interaction). Give it the genealogy vtkTree and family bands table of
 * Filters/Genealogy and a vtkGaussianSelectionHub: a click in the tree selects the node's
 * GaussianId in every view; a selection made elsewhere highlights the selected nodes and
 * their lineage here (always shown whatever the zoom), and the view re-renders.
 *
 * To embed it in a Qt widget, call SetRenderWindow(widget->renderWindow()) (and
 * SetInteractor(widget->interactor())) before the first render.
 */
#ifndef vtkGaussianTreeView_h
#define vtkGaussianTreeView_h

#include "vis4gsViewsLinkedModule.h" // For export macro
#include "vtkContextView.h"
#include "vtkNew.h" // For vtkNew

#include <memory> // For std::unique_ptr

class vtkAlgorithmOutput;
class vtkGaussianSelectionHub;
class vtkGaussianTreeItem;
class vtkTable;
class vtkTree;

class VIS4GSVIEWSLINKED_EXPORT vtkGaussianTreeView : public vtkContextView
{
public:
  static vtkGaussianTreeView* New();
  vtkTypeMacro(vtkGaussianTreeView, vtkContextView);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The genealogy (vertex arrays documented in vtkGaussianTreeItem) and its family bands.
   * Default none.
   */
  void SetTree(vtkTree* tree);
  vtkTree* GetTree();
  void SetFamilyBands(vtkTable* bands);
  vtkTable* GetFamilyBands();
  ///@}

  ///@{
  /**
   * The tree and the bands as connections (vtkGaussianSession's TreePort and BandsPort),
   * pulled in Update() and Render(); the layout is rebuilt only when the port's arrays
   * changed (Vis4GSViewInput). SetTree() / SetFamilyBands() disconnect them. Default none.
   */
  void SetInputConnection(vtkAlgorithmOutput* tree);
  vtkAlgorithmOutput* GetInputConnection();
  void SetFamilyBandsConnection(vtkAlgorithmOutput* bands);
  vtkAlgorithmOutput* GetFamilyBandsConnection();
  ///@}

  /// Pulls the connections.
  void Update() override;
  /// Update(), then draws.
  void Render() override;

  /**
   * Links the view: registers it with @p hub (rendered after every change) and lets the
   * item observe the hub. nullptr unlinks.
   */
  void SetSelectionHub(vtkGaussianSelectionHub* hub);
  vtkGaussianSelectionHub* GetSelectionHub();

  /// The drawing item (zoom, pan, viewport, level-of-detail results).
  vtkGaussianTreeItem* GetTreeItem();

protected:
  vtkGaussianTreeView();
  ~vtkGaussianTreeView() override;

  vtkNew<vtkGaussianTreeItem> Item;

private:
  struct vtkInputs;
  std::unique_ptr<vtkInputs> Inputs;

  vtkGaussianTreeView(const vtkGaussianTreeView&) = delete;
  void operator=(const vtkGaussianTreeView&) = delete;
};

#endif

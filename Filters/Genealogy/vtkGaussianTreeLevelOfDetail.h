/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianTreeLevelOfDetail.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianTreeLevelOfDetail
 * @brief   multiscale level of detail of the densification tree (DESIGN §4)
 *
 * Input port 0: the vtkTree of vtkGaussianGenealogyTreeFilter. Input port 1 (optional): a
 * vtkSelection of PEDIGREEIDS (GaussianIds) or INDICES (tree vertices); SelectedGaussianIds
 * adds more. A genealogy node is visible when
 *   (PerceptionValue >= tau(Zoom), or it is in the selected lineage: the selected nodes,
 *   their ancestors and descendants)
 *   and LayoutY lies in RowRange and its life [BirthIteration, End] meets IterationRange,
 * with tau(z) = (1 - (z - ZoomMin)/(ZoomMax - ZoomMin))^ZoomExponent, z clamped.
 *
 * Output port 0: the visible subtree as a vtkTree: vertex 0 is a virtual root; the visible
 * nodes follow in genealogy order, each attached to its nearest visible ancestor (or the
 * virtual root); all input vertex arrays are carried over, plus `InputVertexId` (vertex of
 * the input tree); edges carry the input `EventKind` of the edge entering the child.
 * Output port 1: a vtkSelection with one VERTEX / INDICES node listing the visible vertices
 * of the *input* tree, sorted. This is what the tree view needs (issue 10): it draws the
 * full tree's layout arrays for those vertices without copying anything; port 0 is for
 * pipelines that want a small self-contained tree (turn it off with BuildVisibleTree).
 *
 * The Core genealogy and its grid index (Core/Genealogy/GenealogyLevelOfDetail.h) are built
 * once per input tree (cached on its modification time); changing the zoom, selection or
 * viewport only runs the query, whose cost is proportional to the visible cells and nodes.
 */
#ifndef vtkGaussianTreeLevelOfDetail_h
#define vtkGaussianTreeLevelOfDetail_h

#include "vis4gsFiltersGenealogyModule.h" // For export macro
#include "vtkSmartPointer.h"              // For vtkSmartPointer
#include "vtkTreeAlgorithm.h"

#include <memory> // For std::unique_ptr

class vtkIdTypeArray;
class vtkSelection;

class VIS4GSFILTERSGENEALOGY_EXPORT vtkGaussianTreeLevelOfDetail : public vtkTreeAlgorithm
{
public:
  static vtkGaussianTreeLevelOfDetail* New();
  vtkTypeMacro(vtkGaussianTreeLevelOfDetail, vtkTreeAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Zoom level z. Default 0.1 (the coarsest level: tau = 1).
   */
  vtkSetMacro(Zoom, double);
  vtkGetMacro(Zoom, double);
  ///@}

  ///@{
  /**
   * Zoom threshold parameters z_min, z_max, k. Defaults 0.1, 2.0, 1.2 (DESIGN §4).
   */
  vtkSetMacro(ZoomMin, double);
  vtkGetMacro(ZoomMin, double);
  vtkSetMacro(ZoomMax, double);
  vtkGetMacro(ZoomMax, double);
  vtkSetMacro(ZoomExponent, double);
  vtkGetMacro(ZoomExponent, double);
  ///@}

  ///@{
  /**
   * Viewport: inclusive iteration range. Default [VTK_INT_MIN, VTK_INT_MAX] (everything).
   */
  vtkSetVector2Macro(IterationRange, int);
  vtkGetVector2Macro(IterationRange, int);
  ///@}

  ///@{
  /**
   * Viewport: inclusive range of LayoutY rows. Default [VTK_ID_MIN, VTK_ID_MAX].
   */
  vtkSetVector2Macro(RowRange, vtkIdType);
  vtkGetVector2Macro(RowRange, vtkIdType);
  ///@}

  ///@{
  /**
   * Selected GaussianIds (added to the selection of input port 1). Default nullptr.
   */
  void SetSelectedGaussianIds(vtkIdTypeArray* ids);
  vtkIdTypeArray* GetSelectedGaussianIds();
  ///@}

  ///@{
  /**
   * Build the visible subtree on output port 0. Default on.
   */
  vtkSetMacro(BuildVisibleTree, bool);
  vtkGetMacro(BuildVisibleTree, bool);
  vtkBooleanMacro(BuildVisibleTree, bool);
  ///@}

  ///@{
  /**
   * Results of the last execution: tau, visible vertices, selected ids not in the tree,
   * seconds spent building the index (0 when cached) and answering the query.
   */
  vtkGetMacro(Threshold, double);
  vtkGetMacro(NumberOfVisibleVertices, vtkIdType);
  vtkGetMacro(NumberOfUnknownSelectedIds, vtkIdType);
  vtkGetMacro(IndexSeconds, double);
  vtkGetMacro(QuerySeconds, double);
  vtkGetMacro(QueryCPUSeconds, double);
  ///@}

  /**
   * Input port 1 (optional selection).
   */
  void SetSelectionConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }

  /**
   * The selection of visible input vertices (output port 1).
   */
  vtkSelection* GetVisibleSelection();

protected:
  vtkGaussianTreeLevelOfDetail();
  ~vtkGaussianTreeLevelOfDetail() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  double Zoom = 0.1;
  double ZoomMin = 0.1;
  double ZoomMax = 2.0;
  double ZoomExponent = 1.2;
  int IterationRange[2] = { VTK_INT_MIN, VTK_INT_MAX };
  vtkIdType RowRange[2] = { VTK_ID_MIN, VTK_ID_MAX };
  vtkSmartPointer<vtkIdTypeArray> SelectedGaussianIds;
  bool BuildVisibleTree = true;
  double Threshold = 1.0;
  vtkIdType NumberOfVisibleVertices = 0;
  vtkIdType NumberOfUnknownSelectedIds = 0;
  double IndexSeconds = 0.0;
  double QuerySeconds = 0.0;
  double QueryCPUSeconds = 0.0;

private:
  vtkGaussianTreeLevelOfDetail(const vtkGaussianTreeLevelOfDetail&) = delete;
  void operator=(const vtkGaussianTreeLevelOfDetail&) = delete;

  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif

/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianGenealogyLineage.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianGenealogyLineage
 * @brief   lineage queries and the root-cause trace on a densification tree
 *
 * Works on the vtkTree of vtkGaussianGenealogyTreeFilter (the Core genealogy is rebuilt
 * once per tree modification). Selections are GaussianIds (the pedigree ids); results are
 * GaussianIds in genealogy (creation) order, each once; unknown ids are skipped and counted.
 * - Ancestors / Descendants: proper ancestors / descendants of any selected Gaussian;
 * - Lineage: the selection, its ancestors and its descendants (what the views highlight);
 * - Family: every Gaussian of the families (roots and all their descendants) of the selection.
 * TraceToRoot: the chain from a Gaussian back to its root with, for each ancestor, the value
 * (e.g. View Coverage) at the snapshot nearest its birth among the snapshots in which it
 * exists; the values per snapshot are supplied with AddSnapshotValues.
 */
#ifndef vtkGaussianGenealogyLineage_h
#define vtkGaussianGenealogyLineage_h

#include "vis4gsFiltersGenealogyModule.h" // For export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // For vtkSmartPointer

#include <memory> // For std::unique_ptr

class vtkDataArray;
class vtkIdTypeArray;
class vtkTable;
class vtkTree;

class VIS4GSFILTERSGENEALOGY_EXPORT vtkGaussianGenealogyLineage : public vtkObject
{
public:
  static vtkGaussianGenealogyLineage* New();
  vtkTypeMacro(vtkGaussianGenealogyLineage, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The tree (output of vtkGaussianGenealogyTreeFilter). Default nullptr.
   */
  void SetTree(vtkTree* tree);
  vtkTree* GetTree();
  ///@}

  ///@{
  /**
   * Lineage queries: GaussianIds in, GaussianIds out (@p result is reset). Return false (with
   * an error) when there is no valid tree.
   */
  bool GetAncestors(vtkIdTypeArray* gaussianIds, vtkIdTypeArray* result);
  bool GetDescendants(vtkIdTypeArray* gaussianIds, vtkIdTypeArray* result);
  bool GetLineage(vtkIdTypeArray* gaussianIds, vtkIdTypeArray* result);
  bool GetFamily(vtkIdTypeArray* gaussianIds, vtkIdTypeArray* result);
  ///@}

  /**
   * Selected ids of the last query that are not in the tree.
   */
  vtkGetMacro(NumberOfUnknownIds, vtkIdType);

  ///@{
  /**
   * Per-snapshot values for TraceToRoot: @p values[i] belongs to Gaussian @p ids[i] in the
   * snapshot logged at @p iteration (replaces an earlier snapshot of that iteration).
   */
  void AddSnapshotValues(int iteration, vtkIdTypeArray* ids, vtkDataArray* values);
  void RemoveAllSnapshotValues();
  ///@}

  /**
   * Root-cause trace of @p gaussianId into @p result (reset), one row per Gaussian from the
   * given one up to its root: GaussianId, Vertex, BirthIteration, DeathIteration, BirthKind,
   * SnapshotIteration (-1: in no snapshot) and Value (NaN when there is no snapshot or the
   * snapshot lacks the id). Returns false (with an error) for an unknown id or no tree.
   */
  bool TraceToRoot(vtkIdType gaussianId, vtkTable* result);

protected:
  vtkGaussianGenealogyLineage();
  ~vtkGaussianGenealogyLineage() override;

  vtkSmartPointer<vtkTree> Tree;
  vtkIdType NumberOfUnknownIds = 0;

private:
  vtkGaussianGenealogyLineage(const vtkGaussianGenealogyLineage&) = delete;
  void operator=(const vtkGaussianGenealogyLineage&) = delete;

  bool Query(int which, vtkIdTypeArray* gaussianIds, vtkIdTypeArray* result);
  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif

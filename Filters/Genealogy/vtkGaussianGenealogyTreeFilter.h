/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianGenealogyTreeFilter.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianGenealogyTreeFilter
 * @brief   densification tree (genealogy) of a training run as a vtkTree
 *
 * Input: a vtkTable of densification events with the numeric columns `Iteration`, `Kind`
 * (1 clone, 2 split, 3 prune), `Parent` and `Child` (GaussianIds, -1 for prune) — the
 * /events group of the training log (DESIGN §3); lower-case names are accepted too.
 * The initial Gaussians are 0..NumberOfInitialGaussians-1, or the ids of InitialIds when
 * set; when neither is set, the table's field data may provide an `InitialIds` id array or a
 * one-value `NumberOfInitialGaussians` array. The last logged iteration is LastIteration,
 * else a field-data `LastIteration` value, else the largest event iteration.
 *
 * Output port 0, a vtkTree (a vtkGaussianCompactTree when CompactTree is on): vertex 0 is a virtual
 * root over the root Gaussians, vertex i + 1 is genealogy node i (creation order: the initial
 * Gaussians, then one node per birth in event order), edge i enters vertex i + 1, children are in
 * creation order. Vertex arrays (virtual-root value in brackets):
 * - `GaussianId` (vtkIdType, also the pedigree ids) [-1]
 * - `BirthIteration`, `DeathIteration` (int; death -1 while alive) [first birth, -1]
 * - `BirthKind` (unsigned char: 0 root, 1 clone, 2 split, 4 clone-split) [255]
 * - `Pruned` (unsigned char 0/1) [0]
 * - `FamilyId` (row of the family bands table) [-1]
 * - `DescendantCount` D, `Lifespan` T (int), `PerceptionValue` P (double) (DESIGN §4) [N, 0, 1]
 * - `LayoutX` (int, = BirthIteration) and `LayoutY` (unique row; pre-order within a family
 *   with children in creation order, families stacked in FamilyId order) [first birth, -1]
 * FamilyId, DescendantCount and LayoutY are 32-bit ints (vtkTypeInt32Array) below 2^31 - 1
 * vertices, vtkIdType beyond: read them as vtkDataArray. (Narrower than the vtkIdType and
 * double arrays they were: 160 MB less at 10M vertices.)
 * Edge array `EventKind` (unsigned char: the child's birth kind; 255 for virtual-root edges).
 * Field data: `LastIteration`, `PerceptionAlpha`.
 * Output port 1, a vtkTable with one row per family: FamilyId, RootVertex, RootGaussianId,
 * MinIteration, MaxIteration, MinRow, MaxRow (inclusive), NodeCount, MaxDescendantCount,
 * MaxLifespan.
 *
 * All the numerics are in Core/Genealogy/Genealogy.h (definitions, bad-input behaviour).
 * Bad input (unknown parents, Gaussians born twice, ...) is an error (vtkErrorMacro, empty
 * output) unless the matching Repair option is on; repairs and reordering are reported as
 * warnings. The tree is built directly in the graph's internal edge lists (exact sizes, filled
 * in parallel from Core's child lists) and handed over as a tree that is valid by
 * construction, which is much faster than AddChild per vertex and vtkTree's validation walk
 * (see ValidateStructure and Documentation/performance.md).
 */
#ifndef vtkGaussianGenealogyTreeFilter_h
#define vtkGaussianGenealogyTreeFilter_h

#include "vis4gsFiltersGenealogyModule.h" // For export macro
#include "vtkSmartPointer.h"              // For vtkSmartPointer
#include "vtkTreeAlgorithm.h"

#include <string> // For std::string

class vtkIdTypeArray;
class vtkTable;

class VIS4GSFILTERSGENEALOGY_EXPORT vtkGaussianGenealogyTreeFilter : public vtkTreeAlgorithm
{
public:
  static vtkGaussianGenealogyTreeFilter* New();
  vtkTypeMacro(vtkGaussianGenealogyTreeFilter, vtkTreeAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Number of initial Gaussians (ids 0..N0-1). Default -1: use InitialIds or field data.
   */
  vtkSetMacro(NumberOfInitialGaussians, vtkIdType);
  vtkGetMacro(NumberOfInitialGaussians, vtkIdType);
  ///@}

  ///@{
  /**
   * Ids of the initial Gaussians (e.g. the first snapshot's ids). Default nullptr.
   * Takes precedence over NumberOfInitialGaussians.
   */
  void SetInitialIds(vtkIdTypeArray* ids);
  vtkIdTypeArray* GetInitialIds();
  ///@}

  ///@{
  /**
   * Last logged iteration (alive Gaussians end there). Default -1: field data
   * `LastIteration` of the input, else the largest event iteration.
   */
  vtkSetMacro(LastIteration, int);
  vtkGetMacro(LastIteration, int);
  ///@}

  ///@{
  /**
   * Coarsen events to this logging interval (clone-split nodes). Default 0 (off).
   */
  vtkSetClampMacro(CoarsenInterval, int, 0, VTK_INT_MAX);
  vtkGetMacro(CoarsenInterval, int);
  ///@}

  ///@{
  /**
   * Events out of iteration order are an error instead of being sorted. Default off.
   */
  vtkSetMacro(StrictEventOrder, bool);
  vtkGetMacro(StrictEventOrder, bool);
  vtkBooleanMacro(StrictEventOrder, bool);
  ///@}

  ///@{
  /**
   * Create orphan roots for unknown parents instead of failing. Default off.
   */
  vtkSetMacro(RepairUnknownParents, bool);
  vtkGetMacro(RepairUnknownParents, bool);
  vtkBooleanMacro(RepairUnknownParents, bool);
  ///@}

  ///@{
  /**
   * Drop later birth rows of Gaussians born twice instead of failing. Default off.
   */
  vtkSetMacro(RepairDuplicateBirths, bool);
  vtkGetMacro(RepairDuplicateBirths, bool);
  vtkBooleanMacro(RepairDuplicateBirths, bool);
  ///@}

  ///@{
  /**
   * Weight alpha of the descendant term of the perception value. Default 0.4 (DESIGN §4).
   */
  vtkSetClampMacro(Alpha, double, 0.0, 1.0);
  vtkGetMacro(Alpha, double);
  ///@}

  ///@{
  /**
   * Output a vtkGaussianCompactTree (a read-only vtkTree whose structure is three flat arrays,
   * 40 bytes per vertex) instead of a plain vtkTree (vtkTree's adjacency lists: 48 bytes of
   * headers per vertex plus a heap block per vertex and per child list, about 100 bytes per
   * vertex in all). Same vertices, edges, ids, arrays and accessors; for very large logs
   * (630 MiB less at the 9.8M vertices of a 4.89M-Gaussian log). VTK filters that copy their
   * input's structure need the plain vtkTree (see vtkGaussianCompactTree). Default off; the
   * application turns it on. NaiveConstruction and ValidateStructure apply to the plain tree.
   */
  vtkSetMacro(CompactTree, bool);
  vtkGetMacro(CompactTree, bool);
  vtkBooleanMacro(CompactTree, bool);
  ///@}

  ///@{
  /**
   * Build the tree through vtkMutableDirectedGraph::AddChild one vertex at a time (slow,
   * for comparisons only). Default off.
   */
  vtkSetMacro(NaiveConstruction, bool);
  vtkGetMacro(NaiveConstruction, bool);
  vtkBooleanMacro(NaiveConstruction, bool);
  ///@}

  ///@{
  /**
   * Pass the fast path's tree through vtkTree::CheckedShallowCopy (VTK's O(n) connectivity
   * walk) instead of handing it over as valid by construction (every parent precedes its
   * child, checked in O(n); see vtkGaussianGenealogyAdapter). Same output, slower; for tests
   * and comparisons. Default off.
   */
  vtkSetMacro(ValidateStructure, bool);
  vtkGetMacro(ValidateStructure, bool);
  vtkBooleanMacro(ValidateStructure, bool);
  ///@}

  ///@{
  /**
   * Seconds spent in the last execution building the genealogy (Core) and the vtkTree:
   * wall-clock, and CPU time of the process during each step (all threads; not inflated by
   * other processes, but including any other thread of the process running meanwhile).
   */
  vtkGetMacro(GenealogySeconds, double);
  vtkGetMacro(TreeSeconds, double);
  vtkGetMacro(GenealogyCPUSeconds, double);
  vtkGetMacro(TreeCPUSeconds, double);
  ///@}

  /**
   * Warnings of the last execution (reordering, repairs), one per line; empty if none.
   */
  const char* GetWarnings() { return this->Warnings.c_str(); }

  /**
   * The family bands table (output port 1).
   */
  vtkTable* GetFamilyBands();

protected:
  vtkGaussianGenealogyTreeFilter();
  ~vtkGaussianGenealogyTreeFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  vtkTypeBool ProcessRequest(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  // Output port 0 is a vtkGaussianCompactTree when CompactTree is on, else a vtkTree.
  int RequestDataObject(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector);
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  vtkIdType NumberOfInitialGaussians = -1;
  vtkSmartPointer<vtkIdTypeArray> InitialIds;
  int LastIteration = -1;
  int CoarsenInterval = 0;
  bool StrictEventOrder = false;
  bool RepairUnknownParents = false;
  bool RepairDuplicateBirths = false;
  double Alpha = 0.4;
  bool CompactTree = false;
  bool NaiveConstruction = false;
  bool ValidateStructure = false;
  double GenealogySeconds = 0.0;
  double TreeSeconds = 0.0;
  double GenealogyCPUSeconds = 0.0;
  double TreeCPUSeconds = 0.0;
  std::string Warnings;

private:
  vtkGaussianGenealogyTreeFilter(const vtkGaussianGenealogyTreeFilter&) = delete;
  void operator=(const vtkGaussianGenealogyTreeFilter&) = delete;
};

#endif

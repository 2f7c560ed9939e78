/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianCompactTree.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianCompactTree
 * @brief   a read-only vtkTree whose structure is three flat arrays (40 bytes per vertex)
 *
 * vtkTree keeps one vtkVertexAdjacencyList per vertex: two std::vector headers (48 bytes) and,
 * for every vertex, a heap block for its one in-edge (16 bytes in a 32-byte malloc chunk) and
 * one for each non-empty child list. No reservation or construction order avoids those blocks:
 * they are the std::vectors' own. At the 9.8M vertices of a 4.89M-Gaussian training log that
 * is about 1 GiB in 15M blocks (Documentation/performance-history.md). This subclass keeps
 * the same edges in one in-edge array (vtkInEdgeType per vertex), one out-edge array in vertex
 * order (vtkOutEdgeType per edge) and its offsets: 40 bytes per vertex, three allocations.
 *
 * It answers every structure query of vtkGraph and vtkTree through their virtual accessors
 * (GetParent, GetChild, GetNumberOfChildren, GetIn/OutDegree, GetIn/OutEdge(s), the edge,
 * adjacency and vertex iterators, GetSourceVertex/GetTargetVertex, vtkTreeDFSIterator, ...),
 * with the same vertex and edge ids a vtkTree built from the same edges has. It is read-only:
 * it has no mutable form, so ReorderChildren is refused. ShallowCopy and DeepCopy into another
 * vtkGaussianCompactTree keep the structure; a plain vtkTree copies vtkGraph's internal
 * adjacency lists, which this class leaves empty, so hand a plain vtkTree (the genealogy
 * filter's default output) to VTK filters that copy their input's structure.
 *
 * vtkGaussianGenealogyTreeFilter produces it when CompactTree is on (the application does).
 */
#ifndef vtkGaussianCompactTree_h
#define vtkGaussianCompactTree_h

#include "vis4gsFiltersGenealogyModule.h" // For export macro
#include "vtkTree.h"

#include <memory> // For std::shared_ptr
#include <vector> // For std::vector

class VIS4GSFILTERSGENEALOGY_EXPORT vtkGaussianCompactTree : public vtkTree
{
public:
  static vtkGaussianCompactTree* New();
  vtkTypeMacro(vtkGaussianCompactTree, vtkTree);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * The structure: vertex v's in-edge is InEdges[v] (ignored for the root vertex 0, which has
   * none), its out-edges are OutEdges[OutOffsets[v] .. OutOffsets[v + 1]). Edge ids must be
   * 0..E-1 with E = OutEdges.size() and each edge listed once in each direction.
   */
  struct Structure
  {
    std::vector<vtkInEdgeType> InEdges;
    std::vector<vtkOutEdgeType> OutEdges;
    std::vector<vtkIdType> OutOffsets;
  };

  /**
   * Adopts @p structure (moved from) as a tree rooted at vertex 0. The caller guarantees a
   * tree (every vertex but 0 has one in-edge, from a vertex that reaches 0; the out-edges are
   * the in-edges reversed); this is not checked here (the genealogy filter checks it while
   * building, see vtkGaussianGenealogyAdapter). Returns false, leaving the tree empty, when the
   * array sizes disagree.
   */
  bool SetStructure(Structure&& structure);

  ///@{
  /**
   * vtkGraph / vtkTree structure queries answered from the flat arrays.
   */
  vtkIdType GetNumberOfVertices() override;
  vtkIdType GetNumberOfEdges() override;
  vtkIdType GetDegree(vtkIdType v) override;
  vtkIdType GetOutDegree(vtkIdType v) override;
  vtkIdType GetInDegree(vtkIdType v) override;
  vtkOutEdgeType GetOutEdge(vtkIdType v, vtkIdType index) override;
  void GetOutEdge(vtkIdType v, vtkIdType index, vtkGraphEdge* e) override;
  vtkInEdgeType GetInEdge(vtkIdType v, vtkIdType index) override;
  void GetInEdge(vtkIdType v, vtkIdType index, vtkGraphEdge* e) override;
  using Superclass::GetInEdges;
  using Superclass::GetOutEdges;
  ///@}

  /**
   * Refused (the structure is read-only): reports an error and changes nothing.
   */
  void ReorderChildren(vtkIdType parent, vtkIdTypeArray* children) override;

  ///@{
  /**
   * Copies keep the compact structure when the source is a vtkGaussianCompactTree with one
   * (shared by shallow copies, as it is never modified in place; duplicated by deep copies);
   * from any other graph they take vtkTree's own adjacency lists, which the accessors then
   * use.
   */
  void ShallowCopy(vtkDataObject* src) override;
  void DeepCopy(vtkDataObject* src) override;
  bool CheckedShallowCopy(vtkGraph* g) override;
  bool CheckedDeepCopy(vtkGraph* g) override;
  void CopyStructure(vtkGraph* g) override;
  void Initialize() override;
  ///@}

  /**
   * Memory of the structure and the attributes, in kibibytes.
   */
  unsigned long GetActualMemorySize() override;

protected:
  vtkGaussianCompactTree();
  ~vtkGaussianCompactTree() override;

  void GetOutEdges(vtkIdType v, const vtkOutEdgeType*& edges, vtkIdType& nedges) override;
  void GetInEdges(vtkIdType v, const vtkInEdgeType*& edges, vtkIdType& nedges) override;

  // Shared by shallow copies; replaced, never modified, once set.
  std::shared_ptr<const Structure> Edges;

private:
  vtkGaussianCompactTree(const vtkGaussianCompactTree&) = delete;
  void operator=(const vtkGaussianCompactTree&) = delete;

  bool CheckVertex(vtkIdType v);
  // The compact structure of @p src when it is a vtkGaussianCompactTree, else null.
  static std::shared_ptr<const Structure> EdgesOf(vtkDataObject* src);
};

#endif

/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianGenealogyAdapter.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianGenealogyAdapter
 * @brief   private helper: Core genealogy <-> vtkTree arrays (not installed, not wrapped)
 *
 * Tree layout contract (documented in vtkGaussianGenealogyTreeFilter.h): vertex 0 is the
 * virtual root, vertex i + 1 is genealogy node i, edge i enters vertex i + 1.
 */
#ifndef vtkGaussianGenealogyAdapter_h
#define vtkGaussianGenealogyAdapter_h

#include "Genealogy.h" // Core genealogy

#include "vtkType.h"

#include <memory>
#include <string>
#include <vector>

class vtkFieldData;
class vtkTable;
class vtkTree;
class vtkSelection;
class vtkDataSetAttributes;

class vtkGaussianGenealogyAdapter
{
public:
  /// Value of BirthKind / EventKind for the virtual root and its edges.
  static constexpr unsigned char VirtualRootKind = 255;

  /// CPU time of the calling thread in seconds (benchmark figures on shared cores).
  static double ThreadCpuSeconds();
  /// CPU time of the whole process (all threads) in seconds.
  static double ProcessCpuSeconds();

  /**
   * Events from a table (columns Iteration, Kind, Parent, Child; lower-case accepted) as
   * columns: the table's own arrays when they hold the log's types (32-bit int, unsigned
   * char, 64-bit int, 64-bit int, one component, contiguous), without a copy; otherwise
   * converted copies kept in @p storage. @p events is valid while both live.
   */
  static bool EventsFromTable(vtkTable* table,
    vis4gs::EventTable& storage,
    vis4gs::EventColumns& events,
    std::string& error);

  /**
   * The lineage breaks that vtkGaussianTrainingLogReader puts into its events port's field
   * data (LineageBreakIteration, ... LineageBreakNewRoots, one tuple per break): false with
   * @p error naming the array when one is missing or of another length.
   */
  static bool BreaksFromFieldData(vtkFieldData* fd,
    vis4gs::LineageBreakTable& breaks,
    std::string& error);

  /**
   * Fills @p tree (vertex and edge arrays, pedigree ids, field data LastIteration and
   * PerceptionAlpha) and @p bands from @p g. With @p naive the structure is built through
   * vtkMutableDirectedGraph::AddChild one vertex at a time (for benchmarks). Otherwise the
   * adjacency lists are filled directly from Core's child lists (exact sizes, in parallel);
   * with @p validate the result goes through vtkTree::CheckedShallowCopy's O(n) walk,
   * without it the tree is valid by construction (parents precede children, checked in
   * O(n)) and shallow-copied as a tree. Both give the same vtkTree.
   */
  static bool FillTree(const vis4gs::Genealogy& g,
    vtkTree* tree,
    vtkTable* bands,
    bool naive,
    std::string& error,
    bool validate = false);

  /**
   * Builds the structure of a tree from parent indices (-1 = virtual root), fast path.
   * Requires -1 <= parents[k] < k for every k (else false with @p error); vertex 0 is the
   * virtual root, vertex k + 1 is node k, edge k enters vertex k + 1, children in node order.
   * @p validate as in FillTree.
   */
  static bool BuildStructure(const std::vector<vtkIdType>& parents,
    vtkTree* tree,
    vtkDataSetAttributes* vertexData,
    vtkDataSetAttributes* edgeData,
    std::string& error,
    bool validate = false);

  /// Core genealogy of a tree produced by vtkGaussianGenealogyTreeFilter.
  static std::shared_ptr<vis4gs::Genealogy> FromTree(vtkTree* tree, std::string& error);

  /**
   * Node indices of a selection: PEDIGREEIDS (GaussianIds) or INDICES (vertex indices of
   * the tree, the virtual root ignored). Unknown ids are counted in @p unknown.
   */
  static std::vector<std::int64_t> NodesFromSelection(const vis4gs::Genealogy& g,
    vtkSelection* selection,
    vtkIdType& unknown,
    std::string& error);
};

#endif

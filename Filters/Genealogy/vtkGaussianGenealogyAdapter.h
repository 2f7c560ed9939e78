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

  /// Events from a table (columns Iteration, Kind, Parent, Child; lower-case accepted).
  static bool EventsFromTable(vtkTable* table, vis4gs::EventTable& events, std::string& error);

  /**
   * Fills @p tree (vertex and edge arrays, pedigree ids, field data LastIteration and
   * PerceptionAlpha) and @p bands from @p g. With @p naive the structure is built through
   * vtkMutableDirectedGraph::AddChild one vertex at a time (for benchmarks).
   */
  static bool FillTree(const vis4gs::Genealogy& g,
    vtkTree* tree,
    vtkTable* bands,
    bool naive,
    std::string& error);

  /// Builds the structure of a tree from parent indices (-1 = virtual root), fast path.
  /// parents[k] < k for every k; vertex 0 is the virtual root, vertex k + 1 is node k.
  static bool BuildStructure(const std::vector<vtkIdType>& parents,
    vtkTree* tree,
    vtkDataSetAttributes* vertexData,
    vtkDataSetAttributes* edgeData,
    std::string& error);

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

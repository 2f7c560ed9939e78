// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file GenealogyLevelOfDetail.h
 * @brief Multiscale level of detail of the densification tree (DESIGN §4): which nodes the
 * tree view shows at zoom z for a selection and a viewport.
 *
 * A node i is **visible** when
 *   (P(i) >= tau(z)  or  i is in the selected lineage (the selected nodes, their ancestors
 *   and their descendants))
 *   and its layout row lies in [MinRow, MaxRow]
 *   and its life [BirthIteration, End] intersects [MinIteration, MaxIteration]
 * (End = death iteration, or the last iteration when alive; all ranges inclusive). The
 * viewport applies to lineage nodes as well.
 *
 * Index: a 2D grid over (row block, birth-iteration block). Each cell keeps its nodes
 * sorted by P descending (by a 16-bit quantised P, with an exact test of P >= tau on the
 * boundary quantum only, so results equal the exact definition) and the largest End of its
 * nodes (IterationsPerCell is doubled until there are at most about 4 cells per node). A
 * query visits only the cells that intersect the viewport (skipping cells whose
 * largest End is before MinIteration) and, in each, only the prefix of nodes with
 * P >= tau plus one boundary quantum; lineage nodes come from contiguous row intervals
 * (a subtree occupies consecutive rows). Build is O(N) (two counting-sort passes).
 *
 * The index keeps a pointer to the Genealogy, which must outlive it and not move.
 */
#ifndef vis4gs_GenealogyLevelOfDetail_h
#define vis4gs_GenealogyLevelOfDetail_h

#include "Genealogy.h"

#include <cstdint>
#include <limits>
#include <vector>

namespace vis4gs
{

/// Viewport of the tree view in layout coordinates (all bounds inclusive).
struct GenealogyViewport
{
  std::int32_t MinIteration = std::numeric_limits<std::int32_t>::min();
  std::int32_t MaxIteration = std::numeric_limits<std::int32_t>::max();
  std::int64_t MinRow = std::numeric_limits<std::int64_t>::min();
  std::int64_t MaxRow = std::numeric_limits<std::int64_t>::max();
};

/// Grid resolution of the level-of-detail index.
struct LevelOfDetailGrid
{
  std::int64_t RowsPerCell = 4096;
  std::int32_t IterationsPerCell = 1000;
};

class GenealogyLevelOfDetail
{
public:
  explicit GenealogyLevelOfDetail(const Genealogy& genealogy,
    const LevelOfDetailGrid& grid = LevelOfDetailGrid());

  /**
   * Visible nodes (node indices) for the threshold @p tau (use ZoomThreshold(z)), the
   * selected nodes @p selection (node indices; out-of-range throws) and the viewport.
   * Result order: nodes passing the P test cell by cell, then lineage nodes by row; each
   * node once. @p out is cleared first (its capacity is reused).
   */
  void Query(double tau,
    const std::vector<std::int64_t>& selection,
    const GenealogyViewport& viewport,
    std::vector<std::int64_t>& out) const;
  std::vector<std::int64_t> Query(double tau,
    const std::vector<std::int64_t>& selection,
    const GenealogyViewport& viewport = GenealogyViewport()) const;

  /// Straightforward reference: tests every node (O(N)); same result set as Query.
  std::vector<std::int64_t> QueryBruteForce(double tau,
    const std::vector<std::int64_t>& selection,
    const GenealogyViewport& viewport = GenealogyViewport()) const;

  /// Grid actually used (see the class comment).
  const LevelOfDetailGrid& GetGrid() const { return this->Grid; }
  std::int64_t GetNumberOfCells() const
  {
    return static_cast<std::int64_t>(this->CellMaxEnd.size());
  }
  /// Entries examined by the last Query (for benchmarks; not thread-safe bookkeeping).
  std::int64_t GetLastQueryWork() const { return this->LastWork; }
  std::size_t GetMemorySize() const;

private:
  const Genealogy* G = nullptr;
  LevelOfDetailGrid Grid;
  std::int32_t IterationOrigin = 0;
  std::int64_t RowBlocks = 0;
  std::int64_t IterationBlocks = 0;
  std::vector<std::int64_t> CellOffsets; // size cells + 1
  std::vector<std::int32_t> CellMaxEnd;  // largest End in the cell
  std::vector<std::int32_t> CellMinEnd;  // smallest End in the cell
  // Entries sorted by (cell, quantised P descending); copies keep the scan cache-friendly.
  std::vector<std::int64_t> EntryNode;
  std::vector<std::int64_t> EntryRow;
  std::vector<std::int32_t> EntryBirth;
  std::vector<std::int32_t> EntryEnd;
  std::vector<std::uint16_t> EntryLevel;
  mutable std::int64_t LastWork = 0;
};

} // namespace vis4gs

#endif

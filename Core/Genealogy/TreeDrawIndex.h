// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TreeDrawIndex.h
 * @brief The numerics behind the densification-tree view (DESIGN §6): per-vertex columns,
 * the orders that answer "which nodes does this window show at this zoom" in time
 * proportional to the answer, and GaussianId -> vertex lookup. The view (vtkGaussianTreeItem)
 * fills the columns from its vtkTree and draws what QueryVisible() returns.
 */
#ifndef vis4gs_TreeDrawIndex_h
#define vis4gs_TreeDrawIndex_h

#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace vis4gs
{

class TreeDrawIndex
{
public:
  /// Per vertex (index = tree vertex), filled by the caller before Build(): birth and end
  /// iteration (an end < 0 means alive: Build() sets it to the last iteration), the layout
  /// row and the perception value P (DESIGN §4; NaN sorts last).
  std::vector<std::int32_t> Birth, End;
  std::vector<double> Row, P;
  /// Optional, instead of filling Birth / P: n values that the caller keeps alive and
  /// unchanged while the index is in use (e.g. the tree's own LayoutX and PerceptionValue
  /// arrays, which then need no copy: 120 MB at 10M vertices).
  const std::int32_t* BirthView = nullptr;
  const double* PView = nullptr;
  ///@{ The birth and P columns in use: the views when set, else the vectors.
  const std::int32_t* BirthData() const
  {
    return this->BirthView ? this->BirthView : this->Birth.data();
  }
  const double* PData() const { return this->PView ? this->PView : this->P.data(); }
  ///@}

  /**
   * Builds the index for vertices with GaussianIds @p ids (a negative id marks a vertex that
   * is not drawn, such as the virtual root; ids >= 0 must be unique). @p lastIteration
   * replaces the last iteration found in Birth/End when it is not INT32_MIN. Throws
   * std::invalid_argument when the columns' lengths differ, std::length_error beyond
   * INT32_MAX vertices (the orders hold 32-bit vertex indices: at 10M vertices they are half
   * the memory, and a tree that size would need hundreds of GB anyway).
   */
  void Build(const std::vector<std::int64_t>& ids,
    std::int32_t lastIteration = std::numeric_limits<std::int32_t>::min());
  /// Empties every column and order.
  void Clear();

  /// Built: 1 for drawn vertices (id >= 0).
  std::vector<std::uint8_t> Valid;
  /// Built: the drawn vertices by P descending (NaN last), and by row ascending (stable).
  std::vector<std::int32_t> ByP, ByRow;
  /// Built: bounds of the drawn vertices (birth .. end, rows); 0..1 when none is drawn.
  double DataMinX = 0, DataMaxX = 1, DataMinY = 0, DataMaxY = 1;
  /// Built: number of drawn vertices, and the last iteration used for alive ones.
  std::int64_t NumberOfRows = 0;
  std::int32_t LastIteration = 0;

  /// The vertex of GaussianId @p id, or -1.
  std::int64_t VertexOfId(std::int64_t id) const;

  /**
   * Appends to @p out the drawn vertices with P >= @p tau whose row lies in
   * [rowLo, rowHi] and whose life [birth, end] meets [xLo, xHi], leaving out those with
   * @p excluded[v] != 0 (may be null). Walks the shorter of the two candidate lists (the
   * vertices with P >= tau, or those in the row range) and returns its length (the work
   * done, for benchmarks and the level-of-detail tests). The order of @p out is that walk's.
   */
  std::int64_t QueryVisible(double tau,
    double xLo,
    double xHi,
    double rowLo,
    double rowHi,
    const std::uint8_t* excluded,
    std::vector<std::int64_t>& out) const;

private:
  // GaussianId -> vertex: id - IdShift when every drawn vertex has id = vertex + IdShift (the
  // genealogy filter's output for a log whose ids follow creation order, which the trainer
  // writes: no table), else a dense table from IdMin, else a sorted list.
  bool IdentityIds = false;
  std::int64_t IdShift = 0;
  std::int64_t IdMin = 0;
  std::vector<std::int32_t> DenseIdToVertex;
  std::vector<std::pair<std::int64_t, std::int64_t>> SortedIdToVertex;
};

} // namespace vis4gs

#endif

// SPDX-License-Identifier: BSD-3-Clause
#include "GenealogyLevelOfDetail.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace vis4gs
{

namespace
{
constexpr double LevelScale = 65535.0;

/// Quantised perception value; monotone in p, so q(p) < q(tau) => p < tau and
/// q(p) > q(tau) => p > tau: only entries with q(p) == q(tau) need the exact test.
std::uint16_t Level(double p)
{
  if (!(p > 0.0))
  {
    return 0;
  }
  if (p >= 1.0)
  {
    return 65535;
  }
  return static_cast<std::uint16_t>(std::floor(p * LevelScale));
}

bool InViewport(std::int64_t row, std::int32_t birth, std::int32_t end, const GenealogyViewport& v)
{
  return row >= v.MinRow && row <= v.MaxRow && birth <= v.MaxIteration && end >= v.MinIteration;
}

bool InIntervals(const std::vector<std::pair<std::int64_t, std::int64_t>>& iv, std::int64_t row)
{
  auto it = std::upper_bound(iv.begin(),
    iv.end(),
    row,
    [](std::int64_t r, const std::pair<std::int64_t, std::int64_t>& p) { return r < p.first; });
  return it != iv.begin() && (it - 1)->second >= row;
}
/// Whether [a, b] meets one of the sorted disjoint intervals.
bool IntersectsIntervals(const std::vector<std::pair<std::int64_t, std::int64_t>>& iv,
  std::int64_t a,
  std::int64_t b)
{
  auto it = std::upper_bound(iv.begin(),
    iv.end(),
    b,
    [](std::int64_t r, const std::pair<std::int64_t, std::int64_t>& p) { return r < p.first; });
  return it != iv.begin() && (it - 1)->second >= a;
}
} // namespace

//------------------------------------------------------------------------------
GenealogyLevelOfDetail::GenealogyLevelOfDetail(const Genealogy& genealogy,
  const LevelOfDetailGrid& grid)
  : G(&genealogy)
  , Grid(grid)
{
  if (grid.RowsPerCell <= 0 || grid.IterationsPerCell <= 0)
  {
    throw std::runtime_error("genealogy level of detail: grid cells must be at least 1x1");
  }
  const Genealogy& g = genealogy;
  const std::int64_t n = g.GetNumberOfNodes();
  const std::vector<std::int32_t>& birth = g.GetBirthIterations();
  std::int32_t minBirth = 0;
  std::int32_t maxBirth = 0;
  if (n > 0)
  {
    const auto mm = std::minmax_element(birth.begin(), birth.end());
    minBirth = *mm.first;
    maxBirth = *mm.second;
  }
  this->IterationOrigin = minBirth;
  this->RowBlocks = n > 0 ? (n - 1) / this->Grid.RowsPerCell + 1 : 0;
  // Never more cells than about 4 per node: widen the iteration blocks if needed.
  for (;;)
  {
    this->IterationBlocks = n > 0
      ? (static_cast<std::int64_t>(maxBirth) - minBirth) / this->Grid.IterationsPerCell + 1
      : 0;
    if (this->RowBlocks * this->IterationBlocks <= 4 * n + 1024 || this->IterationBlocks <= 1)
    {
      break;
    }
    this->Grid.IterationsPerCell = static_cast<std::int32_t>(std::min<std::int64_t>(
      2LL * this->Grid.IterationsPerCell, std::numeric_limits<std::int32_t>::max()));
  }
  const std::int64_t cells = this->RowBlocks * this->IterationBlocks;
  const std::vector<double>& p = g.GetPerceptionValues();
  const std::vector<std::int64_t>& byRow = g.GetNodesByRow();
  const std::int64_t rowsPerCell = this->Grid.RowsPerCell;
  const std::int64_t iterationsPerCell = this->Grid.IterationsPerCell;
  if (n >= (std::int64_t(1) << 40))
  {
    throw std::runtime_error("genealogy level of detail: more than 2^40 nodes");
  }

  // Row block by row block (rows are contiguous in a block, so every write is sequential):
  // bucket the block's nodes by birth-iteration block, then sort each cell by level
  // descending (ties by node index) through packed 64-bit keys.
  this->CellOffsets.assign(static_cast<std::size_t>(cells + 1), 0);
  this->CellMaxEnd.assign(
    static_cast<std::size_t>(cells), std::numeric_limits<std::int32_t>::min());
  this->CellMinEnd.assign(
    static_cast<std::size_t>(cells), std::numeric_limits<std::int32_t>::max());
  this->EntryNode.resize(static_cast<std::size_t>(n));
  this->EntryRow.resize(static_cast<std::size_t>(n));
  this->EntryBirth.resize(static_cast<std::size_t>(n));
  this->EntryEnd.resize(static_cast<std::size_t>(n));
  this->EntryLevel.resize(static_cast<std::size_t>(n));
  const std::int64_t blocks = this->IterationBlocks;
  std::vector<std::int64_t> counts(static_cast<std::size_t>(blocks + 1));
  std::vector<std::uint64_t> keys;
  std::vector<std::int32_t> blockOf, localBirth, localEnd;
  std::vector<std::uint16_t> localLevel;
  for (std::int64_t rb = 0; rb < this->RowBlocks; ++rb)
  {
    const std::int64_t r0 = rb * rowsPerCell;
    const std::int64_t r1 = std::min(n, r0 + rowsPerCell);
    const std::int64_t m = r1 - r0;
    blockOf.resize(static_cast<std::size_t>(m));
    localBirth.resize(static_cast<std::size_t>(m));
    localEnd.resize(static_cast<std::size_t>(m));
    localLevel.resize(static_cast<std::size_t>(m));
    keys.resize(static_cast<std::size_t>(m));
    std::fill(counts.begin(), counts.end(), 0);
    // Gather the block's node data once (the only random reads), then work locally.
    for (std::int64_t k = 0; k < m; ++k)
    {
      const std::int64_t node = byRow[r0 + k];
      localBirth[k] = birth[node];
      localEnd[k] = g.GetEndIteration(node);
      localLevel[k] = Level(p[node]);
      const std::int32_t ib = static_cast<std::int32_t>(
        (static_cast<std::int64_t>(localBirth[k]) - minBirth) / iterationsPerCell);
      blockOf[k] = ib;
      ++counts[ib + 1];
    }
    for (std::int64_t b = 0; b < blocks; ++b)
    {
      counts[b + 1] += counts[b];
      this->CellOffsets[rb * blocks + b + 1] = r0 + counts[b + 1];
    }
    // Key: level descending, then row (pre-order) ascending.
    for (std::int64_t k = 0; k < m; ++k)
    {
      keys[counts[blockOf[k]]++] =
        (static_cast<std::uint64_t>(65535 - localLevel[k]) << 40) | static_cast<std::uint64_t>(k);
    }
    for (std::int64_t b = 0; b < blocks; ++b)
    {
      const std::int64_t c = rb * blocks + b;
      const std::int64_t e0 = this->CellOffsets[c];
      const std::int64_t e1 = this->CellOffsets[c + 1];
      std::sort(keys.begin() + (e0 - r0), keys.begin() + (e1 - r0));
      for (std::int64_t e = e0; e < e1; ++e)
      {
        const std::int64_t k =
          static_cast<std::int64_t>(keys[e - r0] & ((std::uint64_t(1) << 40) - 1));
        const std::int32_t end = localEnd[k];
        this->EntryNode[e] = byRow[r0 + k];
        this->EntryRow[e] = r0 + k;
        this->EntryBirth[e] = localBirth[k];
        this->EntryEnd[e] = end;
        this->EntryLevel[e] = localLevel[k];
        this->CellMaxEnd[c] = std::max(this->CellMaxEnd[c], end);
        this->CellMinEnd[c] = std::min(this->CellMinEnd[c], end);
      }
    }
  }
}

//------------------------------------------------------------------------------
void GenealogyLevelOfDetail::Query(double tau,
  const std::vector<std::int64_t>& selection,
  const GenealogyViewport& v,
  std::vector<std::int64_t>& out) const
{
  out.clear();
  const Genealogy& g = *this->G;
  const std::vector<std::pair<std::int64_t, std::int64_t>> lineage = selection.empty()
    ? std::vector<std::pair<std::int64_t, std::int64_t>>()
    : g.LineageRowIntervals(selection);
  std::int64_t work = 0;
  const std::int64_t n = g.GetNumberOfNodes();
  if (n == 0 || v.MinRow > v.MaxRow || v.MinIteration > v.MaxIteration)
  {
    this->LastWork = 0;
    return;
  }
  const std::int64_t rowLo = std::max<std::int64_t>(v.MinRow, 0);
  const std::int64_t rowHi = std::min<std::int64_t>(v.MaxRow, n - 1);
  const bool noThreshold = std::isnan(tau);
  const std::uint16_t tauLevel = noThreshold ? 65535 : Level(tau);
  const bool anyP = !noThreshold;
  if (rowLo <= rowHi && anyP)
  {
    const std::vector<double>& p = g.GetPerceptionValues();
    const std::int64_t rb0 = rowLo / this->Grid.RowsPerCell;
    const std::int64_t rb1 = rowHi / this->Grid.RowsPerCell;
    // Birth <= MaxIteration limits the iteration blocks from above.
    std::int64_t ib1 = this->IterationBlocks - 1;
    if (static_cast<std::int64_t>(v.MaxIteration) < this->IterationOrigin)
    {
      ib1 = -1;
    }
    else
    {
      ib1 = std::min(ib1,
        (static_cast<std::int64_t>(v.MaxIteration) - this->IterationOrigin) /
          this->Grid.IterationsPerCell);
    }
    const bool hasLineage = !lineage.empty();
    for (std::int64_t rb = rb0; rb <= rb1; ++rb)
    {
      const bool interior =
        rb * this->Grid.RowsPerCell >= rowLo && (rb + 1) * this->Grid.RowsPerCell - 1 <= rowHi;
      const std::int64_t cellRow0 = rb * this->Grid.RowsPerCell;
      const std::int64_t cellRow1 = std::min(n, cellRow0 + this->Grid.RowsPerCell) - 1;
      const bool touchesLineage = hasLineage && IntersectsIntervals(lineage, cellRow0, cellRow1);
      for (std::int64_t ib = 0; ib <= ib1; ++ib)
      {
        const std::int64_t c = rb * this->IterationBlocks + ib;
        if (this->CellMaxEnd[c] < v.MinIteration)
        {
          continue;
        }
        const std::int64_t begin = this->CellOffsets[c];
        const std::int64_t end = this->CellOffsets[c + 1];
        const std::int64_t lastBirth = static_cast<std::int64_t>(this->IterationOrigin) +
          (ib + 1) * this->Grid.IterationsPerCell - 1;
        if (interior && !touchesLineage && lastBirth <= v.MaxIteration &&
          this->CellMinEnd[c] >= v.MinIteration)
        {
          // Every node of the cell is inside the viewport: copy the prefix with level > tau's
          // and test the boundary quantum exactly.
          std::int64_t above = begin;
          while (above<end&& this->EntryLevel[above]> tauLevel)
          {
            ++above;
          }
          std::int64_t atOrAbove = above;
          while (atOrAbove < end && this->EntryLevel[atOrAbove] == tauLevel)
          {
            ++atOrAbove;
          }
          out.insert(out.end(), this->EntryNode.begin() + begin, this->EntryNode.begin() + above);
          for (std::int64_t e = above; e < atOrAbove; ++e)
          {
            if (p[this->EntryNode[e]] >= tau)
            {
              out.push_back(this->EntryNode[e]);
            }
          }
          work += atOrAbove - begin;
          continue;
        }
        for (std::int64_t e = begin; e < end; ++e)
        {
          const std::uint16_t lv = this->EntryLevel[e];
          if (lv < tauLevel)
          {
            break;
          }
          ++work;
          const std::int64_t node = this->EntryNode[e];
          if (lv == tauLevel && !(p[node] >= tau))
          {
            continue;
          }
          const std::int64_t row = this->EntryRow[e];
          if (!interior && (row < rowLo || row > rowHi))
          {
            continue;
          }
          if (this->EntryBirth[e] > v.MaxIteration || this->EntryEnd[e] < v.MinIteration)
          {
            continue;
          }
          if (touchesLineage && InIntervals(lineage, row))
          {
            continue; // listed with the lineage below
          }
          out.push_back(node);
        }
      }
    }
  }
  // Lineage nodes (each once), clipped to the viewport.
  const std::vector<std::int64_t>& byRow = g.GetNodesByRow();
  const std::vector<std::int32_t>& birth = g.GetBirthIterations();
  for (const auto& iv : lineage)
  {
    const std::int64_t a = std::max(iv.first, rowLo);
    const std::int64_t b = std::min(iv.second, rowHi);
    for (std::int64_t row = a; row <= b; ++row)
    {
      ++work;
      const std::int64_t node = byRow[row];
      if (birth[node] <= v.MaxIteration && g.GetEndIteration(node) >= v.MinIteration)
      {
        out.push_back(node);
      }
    }
  }
  this->LastWork = work;
}

//------------------------------------------------------------------------------
std::vector<std::int64_t> GenealogyLevelOfDetail::Query(double tau,
  const std::vector<std::int64_t>& selection,
  const GenealogyViewport& viewport) const
{
  std::vector<std::int64_t> out;
  this->Query(tau, selection, viewport, out);
  return out;
}

//------------------------------------------------------------------------------
std::vector<std::int64_t> GenealogyLevelOfDetail::QueryBruteForce(double tau,
  const std::vector<std::int64_t>& selection,
  const GenealogyViewport& v) const
{
  const Genealogy& g = *this->G;
  const std::int64_t n = g.GetNumberOfNodes();
  // Lineage by explicit marking: walk every selected node up to its root and mark whole
  // subtrees by an explicit stack (independent of the row-interval trick used by Query).
  std::vector<std::uint8_t> mark(static_cast<std::size_t>(n), 0);
  std::vector<std::int64_t> stack;
  for (std::int64_t s : selection)
  {
    if (s < 0 || s >= n)
    {
      throw std::runtime_error("genealogy level of detail: selected node out of range");
    }
    for (std::int64_t u = g.GetParents()[s]; u >= 0; u = g.GetParents()[u])
    {
      mark[u] = 1;
    }
    stack.push_back(s);
    while (!stack.empty())
    {
      const std::int64_t u = stack.back();
      stack.pop_back();
      mark[u] = 1;
      for (std::int64_t k = g.GetChildOffsets()[u]; k < g.GetChildOffsets()[u + 1]; ++k)
      {
        stack.push_back(g.GetChildren()[k]);
      }
    }
  }
  std::vector<std::int64_t> out;
  for (std::int64_t i = 0; i < n; ++i)
  {
    const bool shown = g.GetPerceptionValues()[i] >= tau || mark[i];
    if (shown && InViewport(g.GetRows()[i], g.GetBirthIterations()[i], g.GetEndIteration(i), v))
    {
      out.push_back(i);
    }
  }
  return out;
}

//------------------------------------------------------------------------------
std::size_t GenealogyLevelOfDetail::GetMemorySize() const
{
  auto bytes = [](const auto& x) { return x.capacity() * sizeof(x[0]); };
  return bytes(this->CellOffsets) + bytes(this->CellMaxEnd) + bytes(this->EntryNode) +
    bytes(this->EntryRow) + bytes(this->EntryBirth) + bytes(this->EntryEnd) +
    bytes(this->EntryLevel);
}

} // namespace vis4gs

// SPDX-License-Identifier: BSD-3-Clause
#include "TreeDrawIndex.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vis4gs
{

//------------------------------------------------------------------------------
void TreeDrawIndex::Clear()
{
  *this = TreeDrawIndex();
}

//------------------------------------------------------------------------------
void TreeDrawIndex::Build(const std::vector<std::int64_t>& ids, std::int32_t lastIteration)
{
  const std::int64_t n = static_cast<std::int64_t>(ids.size());
  const std::size_t un = ids.size();
  if ((!this->BirthView && this->Birth.size() != un) || this->End.size() != un ||
    this->Row.size() != un || (!this->PView && this->P.size() != un))
  {
    throw std::invalid_argument("TreeDrawIndex: the birth, end, row and P columns need one value "
                                "per vertex");
  }
  if (n > std::numeric_limits<std::int32_t>::max())
  {
    throw std::length_error("TreeDrawIndex: more than INT32_MAX vertices");
  }
  this->Valid.resize(un);
  std::int32_t last = std::numeric_limits<std::int32_t>::min();
  std::int64_t idMin = std::numeric_limits<std::int64_t>::max(), idMax = -1, valid = 0;
  // id - vertex over the drawn vertices: one value when the ids follow the vertex order.
  std::int64_t shiftMin = std::numeric_limits<std::int64_t>::max();
  std::int64_t shiftMax = std::numeric_limits<std::int64_t>::min();
  {
    const std::int64_t* idp = ids.data();
    std::uint8_t* validp = this->Valid.data();
    const std::int32_t* birthp = this->BirthData();
    const std::int32_t* endp = this->End.data();
#pragma omp parallel for schedule(static) reduction(max : last, idMax, shiftMax)                 \
  reduction(min : idMin, shiftMin) reduction(+ : valid) if (n > 65536)
    for (std::int64_t v = 0; v < n; ++v)
    {
      const std::int64_t id = idp[v];
      validp[v] = id >= 0;
      if (id >= 0)
      {
        ++valid;
        last = std::max({ last, birthp[v], endp[v] });
        idMin = std::min(idMin, id);
        idMax = std::max(idMax, id);
        shiftMin = std::min(shiftMin, id - v);
        shiftMax = std::max(shiftMax, id - v);
      }
    }
  }
  if (lastIteration != std::numeric_limits<std::int32_t>::min())
  {
    last = lastIteration;
  }
  this->LastIteration = valid > 0 ? last : 0;
  double minX = std::numeric_limits<double>::max(), minY = minX;
  double maxX = std::numeric_limits<double>::lowest(), maxY = maxX;
  {
    const std::uint8_t* validp = this->Valid.data();
    const std::int32_t* birthp = this->BirthData();
    std::int32_t* endp = this->End.data();
    const double* rowp = this->Row.data();
#pragma omp parallel for schedule(static) reduction(min                                            \
                                                    : minX, minY)                                  \
  reduction(max                                                                                    \
            : maxX, maxY) if (n > 65536)
    for (std::int64_t v = 0; v < n; ++v)
    {
      if (!validp[v])
      {
        continue;
      }
      if (endp[v] < 0)
      {
        endp[v] = last;
      }
      minX = std::min(minX, double(birthp[v]));
      maxX = std::max(maxX, double(endp[v]));
      minY = std::min(minY, rowp[v]);
      maxY = std::max(maxY, rowp[v]);
    }
  }
  if (valid == 0)
  {
    minX = minY = 0;
    maxX = maxY = 1;
  }
  this->DataMinX = minX;
  this->DataMaxX = std::max(maxX, minX + 1);
  this->DataMinY = minY;
  this->DataMaxY = maxY;
  this->NumberOfRows = valid;

  // P descending: counting sort on an 18-bit key (buckets of ~40 nodes at 10M), then exact
  // order inside each bucket.
  const int levels = 1 << 18;
  const int buckets = levels + 1;
  const double* pv = this->PData();
  auto key = [pv](std::int64_t v) -> int
  {
    const double p = pv[v];
    if (!(p == p))
    {
      return buckets - 1; // NaN last
    }
    const double c = std::min(1.0, std::max(0.0, p));
    return (levels - 1) - static_cast<int>(c * (levels - 1));
  };
  std::vector<std::int32_t> keys(un);
  {
    std::int32_t* k = keys.data();
    const std::uint8_t* validp = this->Valid.data();
#pragma omp parallel for schedule(static) if (n > 65536)
    for (std::int64_t v = 0; v < n; ++v)
    {
      k[v] = validp[v] ? key(v) : -1;
    }
  }
  std::vector<std::int64_t> count(buckets + 1, 0);
  for (std::int64_t v = 0; v < n; ++v)
  {
    if (keys[v] >= 0)
    {
      ++count[keys[v] + 1];
    }
  }
  for (int b = 0; b < buckets; ++b)
  {
    count[b + 1] += count[b];
  }
  this->ByP.assign(static_cast<std::size_t>(valid), 0);
  {
    std::vector<std::int64_t> pos(count.begin(), count.end() - 1);
    for (std::int64_t v = 0; v < n; ++v)
    {
      if (keys[v] >= 0)
      {
        this->ByP[pos[keys[v]]++] = static_cast<std::int32_t>(v);
      }
    }
  }
  keys = std::vector<std::int32_t>();
  {
    // Buckets are sorted independently (same result as one after the other).
    std::int32_t* byP = this->ByP.data();
    const std::int64_t* c = count.data();
#pragma omp parallel for schedule(dynamic, 256) if (valid > 65536)
    for (int b = 0; b < buckets; ++b)
    {
      if (c[b + 1] - c[b] > 1)
      {
        std::sort(byP + c[b],
          byP + c[b + 1],
          [pv](std::int32_t a, std::int32_t d) { return pv[a] > pv[d]; });
      }
    }
  }
  // Rows ascending. The genealogy filter's rows are a permutation of minY .. minY + valid - 1:
  // then ByRow is its inverse (one scatter); otherwise (other inputs) a counting sort when
  // the rows are dense integers, else a stable sort.
  this->ByRow.assign(static_cast<std::size_t>(valid), -1);
  bool permutation = valid > 0 && maxY - minY + 1 == static_cast<double>(valid);
  for (std::int64_t v = 0; permutation && v < n; ++v)
  {
    if (this->Valid[v])
    {
      const double r = this->Row[v] - minY;
      if (!(r >= 0 && r < static_cast<double>(valid))) // (also NaN)
      {
        permutation = false;
        break;
      }
      const std::int64_t k = static_cast<std::int64_t>(r);
      if (static_cast<double>(k) != r || this->ByRow[k] >= 0)
      {
        permutation = false; // not an integer, or a repeated row
      }
      else
      {
        this->ByRow[k] = static_cast<std::int32_t>(v);
      }
    }
  }
  if (!permutation)
  {
    this->ByRow.clear();
    for (std::int64_t v = 0; v < n; ++v)
    {
      if (this->Valid[v])
      {
        this->ByRow.push_back(static_cast<std::int32_t>(v));
      }
    }
    // Counting sort only for integer rows: a fractional row would be ordered by its bucket
    // only (the tree item did that before this index was tested against a stable sort).
    const double rowSpan = maxY - minY + 1;
    bool integers = true;
    for (const std::int32_t v : this->ByRow)
    {
      if (this->Row[v] != std::floor(this->Row[v]))
      {
        integers = false;
        break;
      }
    }
    if (valid > 0 && integers && rowSpan <= 2.0 * valid + 16)
    {
      std::vector<std::int64_t> rc(static_cast<std::size_t>(rowSpan) + 1, 0);
      for (const std::int32_t v : this->ByRow)
      {
        ++rc[static_cast<std::size_t>(this->Row[v] - minY) + 1];
      }
      for (std::size_t b = 0; b + 1 < rc.size(); ++b)
      {
        rc[b + 1] += rc[b];
      }
      std::vector<std::int32_t> sorted(this->ByRow.size());
      for (const std::int32_t v : this->ByRow)
      {
        sorted[rc[static_cast<std::size_t>(this->Row[v] - minY)]++] = v;
      }
      this->ByRow.swap(sorted);
    }
    else
    {
      const double* rowp = this->Row.data();
      std::stable_sort(this->ByRow.begin(),
        this->ByRow.end(),
        [rowp](std::int32_t a, std::int32_t b) { return rowp[a] < rowp[b]; });
    }
  }
  // GaussianId -> vertex.
  this->DenseIdToVertex.clear();
  this->SortedIdToVertex.clear();
  this->IdentityIds = valid > 0 && shiftMin == shiftMax;
  this->IdShift = this->IdentityIds ? shiftMin : 0;
  if (this->IdentityIds)
  {
    // No table: VertexOfId(id) = id - IdShift.
  }
  else if (valid > 0 && idMax - idMin < 4 * valid + 1024)
  {
    this->IdMin = idMin;
    this->DenseIdToVertex.assign(static_cast<std::size_t>(idMax - idMin + 1), -1);
    std::int32_t* dense = this->DenseIdToVertex.data();
    const std::int64_t* idp = ids.data();
    const std::uint8_t* validp = this->Valid.data();
    // Ids are unique (pedigree ids), so the threads write distinct entries.
#pragma omp parallel for schedule(static) if (n > 65536)
    for (std::int64_t v = 0; v < n; ++v)
    {
      if (validp[v])
      {
        dense[idp[v] - idMin] = static_cast<std::int32_t>(v);
      }
    }
  }
  else
  {
    for (std::int64_t v = 0; v < n; ++v)
    {
      if (this->Valid[v])
      {
        this->SortedIdToVertex.emplace_back(ids[v], v);
      }
    }
    std::sort(this->SortedIdToVertex.begin(), this->SortedIdToVertex.end());
  }
}

//------------------------------------------------------------------------------
std::int64_t TreeDrawIndex::VertexOfId(std::int64_t id) const
{
  if (this->IdentityIds)
  {
    if (id < this->IdShift)
    {
      return -1;
    }
    // Unsigned: id - IdShift may exceed INT64_MAX (a negative shift).
    const std::uint64_t v =
      static_cast<std::uint64_t>(id) - static_cast<std::uint64_t>(this->IdShift);
    return v < this->Valid.size() && this->Valid[v] ? static_cast<std::int64_t>(v) : -1;
  }
  if (!this->DenseIdToVertex.empty())
  {
    if (id < this->IdMin)
    {
      return -1;
    }
    // Unsigned, as above: id - IdMin overflows int64 for ids far apart (UBSan, issue 35).
    const std::uint64_t k =
      static_cast<std::uint64_t>(id) - static_cast<std::uint64_t>(this->IdMin);
    return k < this->DenseIdToVertex.size() ? this->DenseIdToVertex[k] : -1;
  }
  auto it = std::lower_bound(this->SortedIdToVertex.begin(),
    this->SortedIdToVertex.end(),
    std::make_pair(id, std::numeric_limits<std::int64_t>::min()));
  return (it != this->SortedIdToVertex.end() && it->first == id) ? it->second : -1;
}

//------------------------------------------------------------------------------
std::int64_t TreeDrawIndex::QueryVisible(double tau,
  double xLo,
  double xHi,
  double rowLo,
  double rowHi,
  const std::uint8_t* excluded,
  std::vector<std::int64_t>& out) const
{
  if (this->ByP.empty())
  {
    return 0;
  }
  const double* row = this->Row.data();
  const double* p = this->PData();
  const std::int32_t* birth = this->BirthData();
  const std::int32_t* end = this->End.data();
  auto rowLess = [row](std::int64_t v, double r) { return row[v] < r; };
  auto k0 = std::lower_bound(this->ByRow.begin(), this->ByRow.end(), rowLo, rowLess);
  auto k1 = std::lower_bound(k0, this->ByRow.end(), std::nextafter(rowHi, HUGE_VAL), rowLess);
  auto p1 = std::partition_point(
    this->ByP.begin(), this->ByP.end(), [p, tau](std::int64_t v) { return p[v] >= tau; });
  const std::int64_t nRows = k1 - k0;
  const std::int64_t nP = p1 - this->ByP.begin();
  auto keep = [&](std::int64_t v)
  { return !(excluded && excluded[v]) && birth[v] <= xHi && end[v] >= xLo; };
  if (nP <= nRows)
  {
    for (auto it = this->ByP.begin(); it != p1; ++it)
    {
      const std::int64_t v = *it;
      if (row[v] >= rowLo && row[v] <= rowHi && keep(v))
      {
        out.push_back(v);
      }
    }
    return nP;
  }
  for (auto it = k0; it != k1; ++it)
  {
    const std::int64_t v = *it;
    if (p[v] >= tau && keep(v))
    {
      out.push_back(v);
    }
  }
  return nRows;
}

} // namespace vis4gs

// SPDX-License-Identifier: BSD-3-Clause
#include "SplatLevelOfDetail.h"

#include "ElapsedTime.h"
#include "GaussianMath.h"
#include "RadixSort.h"
#include "ThreadCount.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace vis4gs
{
namespace
{
constexpr std::size_t Bins = 32768;
constexpr std::uint32_t RingBit = 0x8000;

// The view's frustum as SelectSplatsForView tests it, and the margin's wider one.
struct ViewFrustum
{
  float R0[4], R1[4], R2[4];
  // The field of view's half-angle tangents, as the rasteriser's tile rectangle sees them,
  // and sqrt(1 + t^2) of each.
  float Tx, Ty, Cx, Cy;
  // The margin's (the same test with the widened half-angles).
  bool Ring;
  float Mx, My, Mcx, Mcy;

  ViewFrustum(const Camera& camera, double margin)
  {
    const auto& m = camera.WorldToCamera;
    for (int k = 0; k < 4; ++k)
    {
      this->R0[k] = static_cast<float>(m[k]);
      this->R1[k] = static_cast<float>(m[4 + k]);
      this->R2[k] = static_cast<float>(m[8 + k]);
    }
    this->Tx = static_cast<float>(camera.Width / (2.0 * camera.Fx));
    this->Ty = static_cast<float>(camera.Height / (2.0 * camera.Fy));
    this->Cx = std::sqrt(1.0f + this->Tx * this->Tx);
    this->Cy = std::sqrt(1.0f + this->Ty * this->Ty);
    this->Ring = margin > 0.0;
    const double half = 1.5; // (below pi/2 so that the tangents stay finite)
    this->Mx = static_cast<float>(std::tan(std::min(half, std::atan(double(this->Tx)) + margin)));
    this->My = static_cast<float>(std::tan(std::min(half, std::atan(double(this->Ty)) + margin)));
    this->Mcx = std::sqrt(1.0f + this->Mx * this->Mx);
    this->Mcy = std::sqrt(1.0f + this->My * this->My);
  }

  // The key of a Gaussian at @p p (SplatContributionKey, 0 outside the frustum, at most
  // RingBit - 1) with RingBit set when it lies in the margin's ring only. The one computation
  // of both selections, so that they agree bit for bit.
  std::uint32_t Key(const float* p, float mass, float reach) const
  {
    const float z = R2[0] * p[0] + R2[1] * p[1] + R2[2] * p[2] + R2[3];
    const float x = R0[0] * p[0] + R0[1] * p[1] + R0[2] * p[2] + R0[3];
    const float y = R1[0] * p[0] + R1[1] * p[1] + R1[2] * p[2] + R1[3];
    // The sphere of radius reach misses the frustum when it lies wholly beyond a side
    // plane (distance of the centre to the plane x = tx z is (x - tx z) / sqrt(1 + tx^2)).
    const bool in =
      z > 0.2f && std::abs(x) - Tx * z <= reach * Cx && std::abs(y) - Ty * z <= reach * Cy;
    const bool near = Ring && !in && z > 0.2f && std::abs(x) - Mx * z <= reach * Mcx &&
      std::abs(y) - My * z <= reach * Mcy;
    std::uint32_t key = in || near ? SplatContributionKey(mass, z) : 0;
    key = std::min<std::uint32_t>(key, RingBit - 1);
    return key | (near ? RingBit : 0);
  }

  // Whether every Gaussian of @p cell fails Key()'s frustum test (so has key 0), with slack
  // for the float rounding of Key(); and otherwise the largest key any of them can have.
  bool Culled(const SplatCell& cell, std::uint32_t& bound) const
  {
    bound = RingBit - 1;
    const double c[3] = { cell.Center[0], cell.Center[1], cell.Center[2] };
    const double x = double(R0[0]) * c[0] + double(R0[1]) * c[1] + double(R0[2]) * c[2] + R0[3];
    const double y = double(R1[0]) * c[0] + double(R1[1]) * c[1] + double(R1[2]) * c[2] + R1[3];
    const double z = double(R2[0]) * c[0] + double(R2[1]) * c[1] + double(R2[2]) * c[2] + R2[3];
    const double radius = cell.Radius, extent = cell.Extent;
    if (!std::isfinite(x + y + z + radius + extent))
    {
      return false;
    }
    const double slack = 1e-4 * (std::abs(x) + std::abs(y) + std::abs(z) + extent) + 1e-6;
    // Every centre behind the near plane (z_i <= z + radius).
    if (z + radius + slack < 0.2)
    {
      return true;
    }
    // Beyond a side plane: |x_i| - t z_i >= |x| - t z - d_i (1 + t), and 1 + t <= sqrt(2)
    // sqrt(1 + t^2), so the test fails for every Gaussian when |x| - t z exceeds
    // sqrt(2) sqrt(1 + t^2) (d_i + reach_i), at most sqrt(2) sqrt(1 + t^2) extent.
    const double tx = Ring ? Mx : Tx, ty = Ring ? My : Ty;
    const double cx = Ring ? Mcx : Cx, cy = Ring ? Mcy : Cy;
    if (std::abs(x) - tx * z > std::sqrt(2.0) * cx * extent + slack ||
      std::abs(y) - ty * z > std::sqrt(2.0) * cy * extent + slack)
    {
      return true;
    }
    // The nearest a centre can be (a selected one is beyond the near plane), rounded down.
    const float zmin = std::nextafter(static_cast<float>(std::max(0.2, z - radius - slack)), 0.0f);
    bound = std::min<std::uint32_t>(SplatContributionKey(cell.MaxMass, zmin), RingBit - 1);
    return false;
  }
};

// The boundary key of a selection of @p budget from the histogram @p total of the view's own
// frustum: every key above it is kept, and @p take of those equal to it in index order. Returns
// false when the budget is not reached above @p floor (the histogram below it is incomplete).
bool FindBoundary(const std::vector<std::uint64_t>& total,
  std::size_t budget,
  std::uint32_t floor,
  std::uint32_t& boundary,
  std::size_t& take)
{
  boundary = 1;
  take = total[1];
  std::size_t above = 0;
  if (budget == 0)
  {
    return floor <= 1;
  }
  for (std::size_t b = Bins - 1; b >= 1; --b)
  {
    if (above + total[b] >= budget)
    {
      boundary = static_cast<std::uint32_t>(b);
      take = budget - above;
      return b >= floor;
    }
    above += total[b];
  }
  return floor <= 1; // fewer than the budget in the frustum: every one (complete only from 1)
}

// The selected Gaussians, ascending, from the keys (ring bit included): the ring's at or above
// the boundary, the view's own above it, and the first @p take equal to it in index order.
// Parallel: each chunk of the index range counts, then writes at its offset.
void ExtractSubset(const std::vector<std::uint16_t>& keys,
  std::uint32_t boundary,
  std::size_t take,
  int nt,
  std::vector<std::uint32_t>& subset)
{
  const std::size_t n = keys.size();
  std::vector<std::size_t> kept(static_cast<std::size_t>(nt) + 1, 0),
    ties(static_cast<std::size_t>(nt), 0);
#pragma omp parallel for schedule(static, 1) num_threads(nt)
  for (int c = 0; c < nt; ++c)
  {
    const std::size_t b = n * c / nt, e = n * (c + 1) / nt;
    std::size_t k = 0, t = 0;
    for (std::size_t i = b; i < e; ++i)
    {
      const std::uint32_t key = keys[i] & (RingBit - 1);
      const bool ring = keys[i] & RingBit;
      k += (ring && key >= boundary && key > 0) || (!ring && key > boundary) ? 1 : 0;
      t += !ring && key == boundary ? 1 : 0;
    }
    kept[static_cast<std::size_t>(c) + 1] = k;
    ties[static_cast<std::size_t>(c)] = t;
  }
  // Chunk c takes the ties left after the earlier chunks', in index order.
  std::vector<std::size_t> taken(static_cast<std::size_t>(nt), 0);
  std::size_t left = take;
  for (int c = 0; c < nt; ++c)
  {
    const std::size_t cc = static_cast<std::size_t>(c);
    taken[cc] = std::min(ties[cc], left);
    left -= taken[cc];
    kept[cc + 1] += kept[cc] + taken[cc];
  }
  subset.resize(kept[static_cast<std::size_t>(nt)]);
#pragma omp parallel for schedule(static, 1) num_threads(nt)
  for (int c = 0; c < nt; ++c)
  {
    const std::size_t b = n * c / nt, e = n * (c + 1) / nt;
    std::size_t at = kept[static_cast<std::size_t>(c)];
    std::size_t tiesLeft = taken[static_cast<std::size_t>(c)];
    for (std::size_t i = b; i < e; ++i)
    {
      const std::uint32_t key = keys[i] & (RingBit - 1);
      const bool ring = keys[i] & RingBit;
      bool keep = (ring && key >= boundary && key > 0) || (!ring && key > boundary);
      if (!ring && key == boundary && tiesLeft > 0)
      {
        keep = true;
        --tiesLeft;
      }
      if (keep)
      {
        subset[at++] = static_cast<std::uint32_t>(i);
      }
    }
  }
}

void SumHistograms(const std::vector<std::vector<std::uint32_t>>& hist,
  std::vector<std::uint64_t>& total)
{
  total.assign(Bins, 0);
  for (const auto& h : hist)
  {
    for (std::size_t b = 0; b < Bins; ++b)
    {
      total[b] += h[b];
    }
  }
}

void CheckLevelOfDetail(const GaussianCloud& cloud, const SplatLevelOfDetail& lod)
{
  const std::size_t n = cloud.Count;
  if (lod.Mass.size() != n || lod.Reach.size() != n || cloud.Positions.size() != 3 * n)
  {
    throw std::invalid_argument("SelectSplatsForView: the level of detail holds " +
      std::to_string(lod.Mass.size()) + " Gaussians, the cloud " + std::to_string(n));
  }
}

// The cells of SelectSplatsInCells: the Gaussians of positive mass sorted by (mass class of a
// factor sqrt 2, Morton code of their position in a 256^3 grid over the central 98 % of the
// cloud), cut into runs of at most @p cellSize sharing the class and a 32^3 block.
void BuildCells(const GaussianCloud& cloud, SplatLevelOfDetail& lod, int nt, std::size_t cellSize)
{
  const std::size_t n = cloud.Count;
  lod.Entries.clear();
  lod.Cells.clear();
  if (n == 0 || n > std::numeric_limits<std::uint32_t>::max() || cellSize == 0)
  {
    return;
  }
  // The box: 1st and 99th percentiles of a sample per axis (far floaters land on its border).
  std::vector<std::uint32_t> members;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (lod.Mass[i] > 0.0f)
    {
      members.push_back(static_cast<std::uint32_t>(i));
    }
  }
  const std::size_t m = members.size();
  if (m == 0)
  {
    return;
  }
  float lo[3], scale[3];
  {
    const std::size_t stride = std::max<std::size_t>(1, m / 65536);
    std::vector<float> sample;
    for (int k = 0; k < 3; ++k)
    {
      sample.clear();
      for (std::size_t j = 0; j < m; j += stride)
      {
        sample.push_back(cloud.Positions[3 * static_cast<std::size_t>(members[j]) + k]);
      }
      const std::size_t a = sample.size() / 100, b = sample.size() - 1 - sample.size() / 100;
      std::nth_element(sample.begin(), sample.begin() + a, sample.end());
      const float low = sample[a];
      std::nth_element(sample.begin(), sample.begin() + b, sample.end());
      const float high = sample[b];
      lo[k] = low;
      scale[k] = high > low ? 255.999f / (high - low) : 1.0f;
    }
  }
  std::uint32_t lowest = std::numeric_limits<std::uint32_t>::max();
  for (std::size_t j = 0; j < m; ++j)
  {
    std::uint32_t bits;
    std::memcpy(&bits, &lod.Mass[members[j]], sizeof(bits));
    lowest = std::min(lowest, bits >> 22);
  }
  std::vector<std::uint64_t> keys(2 * m);
  const std::int64_t count = static_cast<std::int64_t>(m);
#pragma omp parallel for schedule(static) num_threads(nt)
  for (std::int64_t jj = 0; jj < count; ++jj)
  {
    const std::size_t j = static_cast<std::size_t>(jj);
    const std::uint32_t i = members[j];
    std::uint32_t bits;
    std::memcpy(&bits, &lod.Mass[i], sizeof(bits));
    const std::uint64_t cls = std::min<std::uint32_t>(255, (bits >> 22) - lowest);
    std::uint64_t morton = 0;
    for (int k = 0; k < 3; ++k)
    {
      const float q = (cloud.Positions[3 * static_cast<std::size_t>(i) + k] - lo[k]) * scale[k];
      const std::uint64_t cell = q >= 0.0f ? static_cast<std::uint64_t>(std::min(q, 255.0f)) : 0;
      for (int b = 0; b < 8; ++b)
      {
        morton |= ((cell >> b) & 1u) << (3 * b + k);
      }
    }
    keys[j] = (((cls << 24) | morton) << 32) | i;
  }
  std::vector<std::uint32_t>().swap(members);
  const std::uint64_t* sorted = RadixSortKeys(keys.data(), keys.data() + m, count, 32, 64, nt);
  // Runs of one class and one 32^3 block (the top 15 bits of the Morton code).
  lod.Entries.resize(m);
  std::uint64_t group = ~std::uint64_t(0);
  for (std::size_t j = 0; j < m; ++j)
  {
    const std::uint64_t g = sorted[j] >> (32 + 9);
    if (g != group || j - lod.Cells.back().Begin >= cellSize)
    {
      SplatCell cell{};
      cell.Begin = static_cast<std::uint32_t>(j);
      lod.Cells.push_back(cell);
      group = g;
    }
  }
  for (std::size_t c = 0; c + 1 < lod.Cells.size(); ++c)
  {
    lod.Cells[c].End = lod.Cells[c + 1].Begin;
  }
  lod.Cells.back().End = static_cast<std::uint32_t>(m);
#pragma omp parallel for schedule(static) num_threads(nt)
  for (std::int64_t jj = 0; jj < count; ++jj)
  {
    const std::size_t j = static_cast<std::size_t>(jj);
    const std::uint32_t i = static_cast<std::uint32_t>(sorted[j]);
    const float* p = &cloud.Positions[3 * static_cast<std::size_t>(i)];
    lod.Entries[j] = { p[0], p[1], p[2], lod.Mass[i], lod.Reach[i], i };
  }
  const std::int64_t cells = static_cast<std::int64_t>(lod.Cells.size());
#pragma omp parallel for schedule(static) num_threads(nt)
  for (std::int64_t cc = 0; cc < cells; ++cc)
  {
    SplatCell& cell = lod.Cells[static_cast<std::size_t>(cc)];
    double box[6] = { std::numeric_limits<double>::infinity(),
      std::numeric_limits<double>::infinity(),
      std::numeric_limits<double>::infinity(),
      -std::numeric_limits<double>::infinity(),
      -std::numeric_limits<double>::infinity(),
      -std::numeric_limits<double>::infinity() };
    float maxMass = 0.0f;
    for (std::uint32_t j = cell.Begin; j < cell.End; ++j)
    {
      const SplatCellEntry& e = lod.Entries[j];
      const double p[3] = { e.X, e.Y, e.Z };
      for (int k = 0; k < 3; ++k)
      {
        box[k] = std::min(box[k], p[k]);
        box[3 + k] = std::max(box[3 + k], p[k]);
      }
      maxMass = std::max(maxMass, e.Mass);
    }
    for (int k = 0; k < 3; ++k)
    {
      cell.Center[k] = static_cast<float>(0.5 * (box[k] + box[3 + k]));
    }
    double radius = 0.0, extent = 0.0;
    for (std::uint32_t j = cell.Begin; j < cell.End; ++j)
    {
      const SplatCellEntry& e = lod.Entries[j];
      const double d = std::sqrt((e.X - double(cell.Center[0])) * (e.X - double(cell.Center[0])) +
        (e.Y - double(cell.Center[1])) * (e.Y - double(cell.Center[1])) +
        (e.Z - double(cell.Center[2])) * (e.Z - double(cell.Center[2])));
      radius = std::max(radius, d);
      extent = std::max(extent, d + e.Reach);
    }
    // Rounded up, so that the bounds stay bounds in float.
    cell.Radius =
      std::nextafter(static_cast<float>(radius), std::numeric_limits<float>::infinity());
    cell.Extent =
      std::nextafter(static_cast<float>(extent), std::numeric_limits<float>::infinity());
    cell.MaxMass = maxMass;
  }
}
}

//------------------------------------------------------------------------------
void PrepareSplatLevelOfDetail(const GaussianCloud& cloud,
  SplatLevelOfDetail& lod,
  int threads,
  bool cells,
  std::size_t cellSize)
{
  const std::size_t n = cloud.Count;
  lod.Mass.assign(n, 0.0f);
  lod.Reach.assign(n, 0.0f);
  lod.Entries.clear();
  lod.Cells.clear();
  if (cloud.Positions.size() != 3 * n || cloud.LogScales.size() != 3 * n ||
    cloud.Rotations.size() != 4 * n || cloud.OpacityLogits.size() != n)
  {
    return;
  }
  const int nt = ThreadCount(threads);
  const std::int64_t count = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static) num_threads(nt)
  for (std::int64_t ii = 0; ii < count; ++ii)
  {
    const std::size_t i = static_cast<std::size_t>(ii);
    const float* p = &cloud.Positions[3 * i];
    const float* s = &cloud.LogScales[3 * i];
    const float* q = &cloud.Rotations[4 * i];
    bool finite = std::isfinite(cloud.OpacityLogits[i]);
    for (int k = 0; k < 3; ++k)
    {
      finite = finite && std::isfinite(p[k]) && std::isfinite(s[k]);
    }
    for (int k = 0; k < 4; ++k)
    {
      finite = finite && std::isfinite(q[k]);
    }
    if (!finite)
    {
      continue;
    }
    const double smallest = std::min({ s[0], s[1], s[2] });
    const double largest = std::max({ s[0], s[1], s[2] });
    const double area = std::exp(static_cast<double>(s[0]) + s[1] + s[2] - smallest);
    lod.Mass[i] = static_cast<float>(Sigmoid(static_cast<double>(cloud.OpacityLogits[i])) * area);
    lod.Reach[i] = static_cast<float>(3.0 * std::exp(largest));
  }
  if (cells)
  {
    BuildCells(cloud, lod, nt, cellSize);
  }
}

//------------------------------------------------------------------------------
std::uint32_t SplatContributionKey(float mass, float z)
{
  const float c = mass / (z * z);
  if (!(c > 0.0f)) // also NaN
  {
    return 0;
  }
  std::uint32_t bits;
  std::memcpy(&bits, &c, sizeof(bits));
  return std::max<std::uint32_t>(1, bits >> 16); // positive floats order like their bits
}

//------------------------------------------------------------------------------
std::size_t SelectSplatsForView(const GaussianCloud& cloud,
  const SplatLevelOfDetail& lod,
  const Camera& camera,
  std::size_t budget,
  std::vector<std::uint32_t>& subset,
  int threads,
  double margin,
  std::vector<std::uint16_t>* scratch)
{
  CheckLevelOfDetail(cloud, lod);
  const std::size_t n = cloud.Count;
  const ViewFrustum view(camera, margin);
  const int nt = ThreadCount(threads);
  const std::int64_t count = static_cast<std::int64_t>(n);
  // The key of every Gaussian (0 outside the frustum) and a histogram per thread of those in
  // the view's own frustum. A key is at most 0x7f80 (the top 16 bits of a positive float), so
  // its bit 15 marks a Gaussian of the margin's ring only.
  std::vector<std::uint16_t> own;
  std::vector<std::uint16_t>& keys = scratch ? *scratch : own;
  keys.resize(n);
  // (zeroed here, not by each thread: a team smaller than nt, under OMP_THREAD_LIMIT, OMP_DYNAMIC
  // or nested in a parallel region, leaves the histograms of the threads that did not start)
  std::vector<std::vector<std::uint32_t>> hist(
    static_cast<std::size_t>(nt), std::vector<std::uint32_t>(Bins, 0));
  std::size_t inside = 0;
#pragma omp parallel num_threads(nt) reduction(+ : inside)
  {
    std::vector<std::uint32_t>& h = hist[static_cast<std::size_t>(omp_get_thread_num())];
#pragma omp for schedule(static)
    for (std::int64_t ii = 0; ii < count; ++ii)
    {
      const std::size_t i = static_cast<std::size_t>(ii);
      const std::uint32_t key = view.Key(&cloud.Positions[3 * i], lod.Mass[i], lod.Reach[i]);
      keys[i] = static_cast<std::uint16_t>(key);
      if (!(key & RingBit))
      {
        ++h[key];
        inside += key > 0 ? 1 : 0;
      }
    }
  }
  std::uint32_t boundary = 1;
  std::size_t take = 0;
  std::vector<std::uint64_t> total;
  SumHistograms(hist, total);
  FindBoundary(total, budget, 1, boundary, take);
  ExtractSubset(keys, boundary, take, nt, subset);
  return inside;
}

//------------------------------------------------------------------------------
std::size_t SelectSplatsInCells(const GaussianCloud& cloud,
  const SplatLevelOfDetail& lod,
  const Camera& camera,
  std::size_t budget,
  std::vector<std::uint32_t>& subset,
  SplatSelectionState& state,
  int threads,
  double margin)
{
  CheckLevelOfDetail(cloud, lod);
  const std::size_t n = cloud.Count;
  const int nt = ThreadCount(threads);
  state.Fallback = false;
  if (lod.Cells.empty())
  {
    SelectSplatsForView(cloud, lod, camera, budget, subset, nt, margin, &state.Keys);
    state.Examined = n;
    state.Boundary = 0;
    return n;
  }
  const ViewFrustum view(camera, margin);
  // The floor: a little below the last boundary (a factor 2^(48/128) = 1.3 in contribution),
  // as the view moved little since; every key the selection can keep is at or above it.
  std::uint32_t floor = budget > 0 && state.Boundary > 48 ? state.Boundary - 48 : 1;
  // Per thread, the histogram of the view's own frustum and the Gaussians whose key reaches
  // the floor: (key with the ring bit) << 32 | index. Nothing of the size of the cloud is read
  // or written, and every buffer is the state's, kept between selections (no allocation or
  // first touch of fresh pages once they have grown to the selection's size).
  const std::size_t threadCount = static_cast<std::size_t>(nt);
  std::vector<std::vector<std::uint32_t>>& hist = state.Histograms;
  std::vector<std::vector<std::uint64_t>>& found = state.Candidates;
  std::vector<std::vector<std::uint64_t>>& keptBy = state.KeptBy;
  std::vector<std::vector<std::uint64_t>>& tiesBy = state.TiesBy;
  for (auto* v : { &found, &keptBy, &tiesBy })
  {
    v->resize(threadCount);
  }
  hist.resize(threadCount);
  std::vector<std::uint64_t>& total = state.Total;
  const std::int64_t cells = static_cast<std::int64_t>(lod.Cells.size());
  auto stepStart = std::chrono::steady_clock::now();
  for (;;)
  {
    std::size_t examined = 0;
    // (here, not by each thread: a smaller team leaves the lists of the threads that did not
    // start, which would hold another view's candidates from an earlier selection)
    for (std::size_t t = 0; t < found.size(); ++t)
    {
      hist[t].assign(Bins, 0);
      found[t].clear();
    }
#pragma omp parallel num_threads(nt) reduction(+ : examined)
    {
      const std::size_t t = static_cast<std::size_t>(omp_get_thread_num());
      std::vector<std::uint32_t>& h = hist[t];
      std::vector<std::uint64_t>& mine = found[t];
#pragma omp for schedule(dynamic, 16)
      for (std::int64_t cc = 0; cc < cells; ++cc)
      {
        const SplatCell& cell = lod.Cells[static_cast<std::size_t>(cc)];
        std::uint32_t bound;
        if (view.Culled(cell, bound) || bound < floor)
        {
          continue;
        }
        examined += cell.End - cell.Begin;
        for (std::uint32_t j = cell.Begin; j < cell.End; ++j)
        {
          const SplatCellEntry& e = lod.Entries[j];
          const float p[3] = { e.X, e.Y, e.Z };
          const std::uint32_t key = view.Key(p, e.Mass, e.Reach);
          const std::uint32_t k = key & (RingBit - 1);
          if (k >= floor && k > 0)
          {
            mine.push_back((static_cast<std::uint64_t>(key) << 32) | e.Index);
            h[k] += key & RingBit ? 0 : 1;
          }
        }
      }
    }
    SumHistograms(hist, total);
    std::uint32_t boundary = 1;
    std::size_t take = 0;
    if (!FindBoundary(total, budget, floor, boundary, take))
    {
      // The floor was above the boundary: every cell in the frustum again.
      floor = 1;
      state.Fallback = true;
      continue;
    }
    state.StepMs[0] = MsSince(stepStart);
    stepStart = std::chrono::steady_clock::now();
    // The ring's at or above the boundary, the view's own above it, and of those equal to it
    // the first take in index order; then every kept index in ascending order.
    // (each thread filters the Gaussians it found; the lists are then joined)
#pragma omp parallel for schedule(static, 1) num_threads(nt)
    for (int t = 0; t < nt; ++t)
    {
      std::vector<std::uint64_t>& kept = keptBy[static_cast<std::size_t>(t)];
      std::vector<std::uint64_t>& ties = tiesBy[static_cast<std::size_t>(t)];
      kept.clear();
      ties.clear();
      for (std::uint64_t c : found[static_cast<std::size_t>(t)])
      {
        const std::uint32_t key = static_cast<std::uint32_t>(c >> 32);
        const std::uint32_t k = key & (RingBit - 1);
        const std::uint64_t index = c & 0xFFFFFFFFu;
        if ((key & RingBit) ? k >= boundary : k > boundary)
        {
          kept.push_back(index);
        }
        else if (!(key & RingBit) && k == boundary)
        {
          ties.push_back(index);
        }
      }
    }
    std::vector<std::uint64_t>& kept = state.Kept;
    std::vector<std::uint64_t>& ties = state.Ties;
    kept.clear();
    ties.clear();
    for (std::size_t t = 0; t < threadCount; ++t)
    {
      kept.insert(kept.end(), keptBy[t].begin(), keptBy[t].end());
      ties.insert(ties.end(), tiesBy[t].begin(), tiesBy[t].end());
    }
    take = std::min(take, ties.size());
    std::nth_element(ties.begin(), ties.begin() + static_cast<std::ptrdiff_t>(take), ties.end());
    kept.insert(kept.end(), ties.begin(), ties.begin() + static_cast<std::ptrdiff_t>(take));
    state.StepMs[1] = MsSince(stepStart);
    stepStart = std::chrono::steady_clock::now();
    const std::int64_t m = static_cast<std::int64_t>(kept.size());
    state.Spare.resize(kept.size());
    int bits = 0;
    while (bits < 32 && (std::uint64_t(n - 1) >> bits) != 0)
    {
      ++bits;
    }
    const std::uint64_t* sorted = RadixSortKeys(kept.data(), state.Spare.data(), m, 0, bits, nt);
    subset.resize(kept.size());
#pragma omp parallel for schedule(static) num_threads(nt)
    for (std::int64_t j = 0; j < m; ++j)
    {
      subset[static_cast<std::size_t>(j)] = static_cast<std::uint32_t>(sorted[j]);
    }
    state.Boundary = boundary;
    state.Examined = examined;
    state.StepMs[2] = MsSince(stepStart);
    return examined;
  }
}

} // namespace vis4gs

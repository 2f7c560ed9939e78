// SPDX-License-Identifier: BSD-3-Clause
// BinGaussians(): the per-tile lists in depth order (reference §2.5): the stable parallel
// radix sort of (depth, index) keys and the tile lists of the sorted tile rectangles.
#include "Rasterizer.h"

#include "RadixSort.h"
#include "RasterInternal.h"
#include "ThreadCount.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <memory>
#include <new>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

namespace vis4gs
{

using raster::internal::ResizeKeep;

//------------------------------------------------------------------------------
// BinScratch: BinGaussians' intermediate buffers, uninitialised on growth (RawVector: every
// element is written before it is read) and kept between calls.
namespace
{
using raster::internal::RawVector;

/// ResizeKeep() that returns the data pointer.
template <typename U>
U* GrowRaw(RawVector<U>& v, std::size_t n)
{
  ResizeKeep(v, n);
  return v.data();
}
} // namespace

struct BinScratch::Buffers
{
  /// 2 per visible Gaussian: the sort keys and the radix sort's other buffer; after the sort,
  /// the half not holding the sorted keys holds the sorted tile rectangles (16-bit).
  RawVector<std::uint64_t> Keys;
  /// The sorted tile rectangles when the tile grid exceeds 16 bits (images wider or taller
  /// than 2^20 pixels); empty otherwise.
  RawVector<std::array<int, 4>> WideRects;
  std::vector<std::int64_t> Diff;
};

BinScratch::BinScratch() = default;
BinScratch::~BinScratch() = default;
BinScratch::BinScratch(BinScratch&&) noexcept = default;
BinScratch& BinScratch::operator=(BinScratch&&) noexcept = default;

//------------------------------------------------------------------------------
// Binning: (1) compact the visible Gaussians in index order; (2) sort them once, globally,
// by (depth, index); (3) a stable counting scatter of that sequence into the tiles (per
// chunk of the sorted sequence: tile counts from a 2D difference array of the tile
// rectangles, tile-major chunk-minor offsets, scatter in order). Every tile's run is then a
// subsequence of the global order: sorted by (depth, index) with no per-tile sort, exactly
// the order of the reference's stable radix sort on (tile, depth) keys.
template <typename T>
void BinGaussians(const ViewProjection<T>& projection,
  int threads,
  TileBins& bins,
  BinScratch& scratch)
{
  if (!scratch.Impl)
  {
    scratch.Impl.reset(new BinScratch::Buffers);
  }
  BinScratch::Buffers& buf = *scratch.Impl;
  bins.TilesX = projection.TilesX;
  bins.TilesY = projection.TilesY;
  const auto& gs = projection.Gaussians;
  const std::int64_t n = static_cast<std::int64_t>(gs.size());
  const int chunks = ThreadCount(threads);
  const std::size_t gx = static_cast<std::size_t>(projection.TilesX);
  const std::size_t gy = static_cast<std::size_t>(projection.TilesY);

  // (1) Visible Gaussians in index order: one 64-bit key each, the Gaussian's index in the
  // low 32 bits (below 2^32: ProjectGaussians refuses larger clouds) and, for float, the
  // depth bits above it. The index breaks depth ties, as the reference's stable sort does.
  std::vector<std::uint64_t> before(static_cast<std::size_t>(chunks) + 1, 0);
#pragma omp parallel for schedule(static, 1) num_threads(chunks)
  for (int c = 0; c < chunks; ++c)
  {
    const std::int64_t b = n * c / chunks, e = n * (c + 1) / chunks;
    std::uint64_t k = 0;
    for (std::int64_t i = b; i < e; ++i)
    {
      k += gs[static_cast<std::size_t>(i)].IsVisible() ? 1 : 0;
    }
    before[static_cast<std::size_t>(c) + 1] = k;
  }
  for (int c = 0; c < chunks; ++c)
  {
    before[static_cast<std::size_t>(c) + 1] += before[static_cast<std::size_t>(c)];
  }
  const std::size_t visible = static_cast<std::size_t>(before[static_cast<std::size_t>(chunks)]);
  const std::int64_t nv = static_cast<std::int64_t>(visible);
  // The keys and a second buffer of the same size: the radix sort's (float), then the sorted
  // rectangles'. 16 bytes per visible Gaussian in all, reused from frame to frame.
  std::uint64_t* keys = GrowRaw(buf.Keys, 2 * visible);
  std::vector<std::pair<T, std::uint32_t>> pairs(
    std::is_same<T, float>::value ? 0 : visible); // double
  std::uint32_t depthOr = 0, depthAnd = ~0u;
#pragma omp parallel for schedule(static, 1) num_threads(chunks) reduction(| : depthOr) reduction(& : depthAnd)
  for (int c = 0; c < chunks; ++c)
  {
    const std::int64_t b = n * c / chunks, e = n * (c + 1) / chunks;
    std::size_t k = static_cast<std::size_t>(before[static_cast<std::size_t>(c)]);
    for (std::int64_t i = b; i < e; ++i)
    {
      const auto& g = gs[static_cast<std::size_t>(i)];
      if (!g.IsVisible())
      {
        continue;
      }
      if constexpr (std::is_same<T, float>::value)
      {
        // depth > 0.2, so the bits order like the values.
        std::uint32_t bits;
        std::memcpy(&bits, &g.Depth, sizeof(bits));
        depthOr |= bits;
        depthAnd &= bits;
        keys[k] = (static_cast<std::uint64_t>(bits) << 32) | static_cast<std::uint64_t>(i);
      }
      else
      {
        pairs[k] = { g.Depth, static_cast<std::uint32_t>(i) };
      }
      ++k;
    }
  }

  // (2) Global order by (depth, index). Float: stable radix sort on the depth bits that
  // differ between Gaussians (the keys arrive in index order, so ties stay in index order).
  // Double: std::sort of (depth, index) pairs, whose indices then become the keys.
  const std::uint64_t* sorted = keys;
  if constexpr (std::is_same<T, float>::value)
  {
    sorted =
      RadixSortKeys(keys, keys + visible, nv, 32, 32 + DifferingBits(depthOr, depthAnd), chunks);
  }
  else
  {
    std::sort(pairs.begin(), pairs.end());
#pragma omp parallel for schedule(static) num_threads(chunks)
    for (std::int64_t k = 0; k < nv; ++k)
    {
      keys[k] = pairs[static_cast<std::size_t>(k)].second;
    }
    std::vector<std::pair<T, std::uint32_t>>().swap(pairs);
  }
  // The tile rectangles in sorted order, in the buffer the sorted keys do not occupy.
  std::uint64_t* spare = sorted == keys ? keys + visible : keys;
  const bool narrow = gx <= 0xFFFF && gy <= 0xFFFF;
  raster::internal::NarrowRect* narrowRects =
    reinterpret_cast<raster::internal::NarrowRect*>(spare);
  std::array<int, 4>* wideRects = GrowRaw(buf.WideRects, narrow ? 0 : visible);
#pragma omp parallel for schedule(static) num_threads(chunks)
  for (std::int64_t k = 0; k < nv; ++k)
  {
    const int* r = gs[static_cast<std::uint32_t>(sorted[k])].TileRect;
    if (narrow)
    {
      narrowRects[k] = { { static_cast<std::uint16_t>(r[0]),
        static_cast<std::uint16_t>(r[1]),
        static_cast<std::uint16_t>(r[2]),
        static_cast<std::uint16_t>(r[3]) } };
    }
    else
    {
      wideRects[k] = { r[0], r[1], r[2], r[3] };
    }
  }

  // (3) The per-tile lists of the Gaussian indices (the keys' low 32 bits).
  if (narrow)
  {
    raster::internal::BinSortedKeys(
      narrowRects, sorted, nv, static_cast<int>(gx), static_cast<int>(gy), chunks, buf.Diff, bins);
  }
  else
  {
    raster::internal::BinSortedKeys(
      wideRects, sorted, nv, static_cast<int>(gx), static_cast<int>(gy), chunks, buf.Diff, bins);
  }
}

//------------------------------------------------------------------------------
template <typename T>
TileBins BinGaussians(const ViewProjection<T>& projection, int threads)
{
  TileBins bins;
  BinScratch scratch;
  BinGaussians(projection, threads, bins, scratch);
  return bins;
}

//------------------------------------------------------------------------------
// Internals shared with MultiViewRenderer.cxx (RasterInternal.h).
namespace raster
{
namespace internal
{
namespace
{
// BinSortedRects() for any rectangle type (4 tile coordinates) and any source of the entries
// (IdAt(k): the entry of sorted position k).
template <typename Rect, typename IdAt>
void BinSortedRectsOf(const Rect* rects,
  IdAt idAt,
  std::int64_t count,
  int gxi,
  int gyi,
  int chunks,
  std::vector<std::int64_t>& diff,
  TileBins& bins)
{
  const std::size_t gx = static_cast<std::size_t>(gxi), gy = static_cast<std::size_t>(gyi);
  const std::size_t tiles = gx * gy;
  const std::int64_t nv = count;
  // Per chunk of the sorted sequence, per tile counts: a 2D difference array of the
  // rectangles ((gx+1) x (gy+1)), integrated by rows then columns.
  const std::size_t dx = gx + 1;
  const std::size_t diffSize = dx * (gy + 1);
  diff.assign(static_cast<std::size_t>(chunks) * diffSize, 0);
#pragma omp parallel for schedule(static, 1) num_threads(chunks)
  for (int c = 0; c < chunks; ++c)
  {
    std::int64_t* d = &diff[static_cast<std::size_t>(c) * diffSize];
    const std::int64_t b = nv * c / chunks, e = nv * (c + 1) / chunks;
    for (std::int64_t k = b; k < e; ++k)
    {
      const Rect& r = rects[static_cast<std::size_t>(k)];
      const std::size_t x0 = static_cast<std::size_t>(r[0]), y0 = static_cast<std::size_t>(r[1]);
      const std::size_t x1 = static_cast<std::size_t>(r[2]), y1 = static_cast<std::size_t>(r[3]);
      ++d[y0 * dx + x0];
      --d[y0 * dx + x1];
      --d[y1 * dx + x0];
      ++d[y1 * dx + x1];
    }
    for (std::size_t y = 0; y < gy; ++y)
    {
      std::int64_t* row = d + y * dx;
      for (std::size_t x = 1; x < gx; ++x)
      {
        row[x] += row[x - 1];
      }
      if (y > 0)
      {
        const std::int64_t* up = row - dx;
        for (std::size_t x = 0; x < gx; ++x)
        {
          row[x] += up[x];
        }
      }
    }
  }
  // Offsets: tile-major, chunk-minor; the counts become each chunk's write cursors.
  bins.Offsets.assign(tiles + 1, 0);
  std::uint64_t running = 0;
  for (std::size_t ty = 0; ty < gy; ++ty)
  {
    for (std::size_t tx = 0; tx < gx; ++tx)
    {
      bins.Offsets[ty * gx + tx] = running;
      for (int c = 0; c < chunks; ++c)
      {
        std::int64_t& h = diff[static_cast<std::size_t>(c) * diffSize + ty * dx + tx];
        const std::uint64_t k = static_cast<std::uint64_t>(h);
        h = static_cast<std::int64_t>(running);
        running += k;
      }
    }
  }
  bins.Offsets[tiles] = running;
  ResizeKeep(bins.Ids, static_cast<std::size_t>(running));
  std::uint32_t* out = bins.Ids.data();
#pragma omp parallel for schedule(static, 1) num_threads(chunks)
  for (int c = 0; c < chunks; ++c)
  {
    std::int64_t* cursor = &diff[static_cast<std::size_t>(c) * diffSize];
    const std::int64_t b = nv * c / chunks, e = nv * (c + 1) / chunks;
    for (std::int64_t k = b; k < e; ++k)
    {
      const Rect& r = rects[static_cast<std::size_t>(k)];
      const std::uint32_t id = idAt(k);
      for (int ty = r[1]; ty < r[3]; ++ty)
      {
        std::int64_t* row = cursor + static_cast<std::size_t>(ty) * dx;
        for (int tx = r[0]; tx < r[2]; ++tx)
        {
          out[row[tx]++] = id;
        }
      }
    }
  }
}

} // namespace

template <typename Rect>
void BinSortedRects(const Rect* rects,
  const std::uint32_t* ids,
  std::int64_t count,
  int gx,
  int gy,
  int chunks,
  std::vector<std::int64_t>& diff,
  TileBins& bins)
{
  if (ids)
  {
    BinSortedRectsOf(
      rects, [ids](std::int64_t k) { return ids[k]; }, count, gx, gy, chunks, diff, bins);
  }
  else
  {
    BinSortedRectsOf(
      rects,
      [](std::int64_t k) { return static_cast<std::uint32_t>(k); },
      count,
      gx,
      gy,
      chunks,
      diff,
      bins);
  }
}

template void BinSortedRects<NarrowRect>(const NarrowRect*,
  const std::uint32_t*,
  std::int64_t,
  int,
  int,
  int,
  std::vector<std::int64_t>&,
  TileBins&);

template <typename Rect>
void BinSortedKeys(const Rect* rects,
  const std::uint64_t* keys,
  std::int64_t count,
  int gx,
  int gy,
  int chunks,
  std::vector<std::int64_t>& diff,
  TileBins& bins)
{
  BinSortedRectsOf(
    rects,
    [keys](std::int64_t k) { return static_cast<std::uint32_t>(keys[k]); },
    count,
    gx,
    gy,
    chunks,
    diff,
    bins);
}

} // namespace internal
} // namespace raster

template void BinGaussians<float>(const ViewProjection<float>&, int, TileBins&, BinScratch&);
template void BinGaussians<double>(const ViewProjection<double>&, int, TileBins&, BinScratch&);
template TileBins BinGaussians<float>(const ViewProjection<float>&, int);
template TileBins BinGaussians<double>(const ViewProjection<double>&, int);

} // namespace vis4gs

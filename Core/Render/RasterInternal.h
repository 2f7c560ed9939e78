// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file RasterInternal.h
 * @brief Internal to Core/Render: the parts of the Raster*.cxx files that MultiViewRenderer.cxx
 * runs too (one projection code, one compositing code), exported under
 * vis4gs::raster::internal. Not installed; no other module includes it.
 */
#ifndef vis4gs_RasterInternal_h
#define vis4gs_RasterInternal_h

#include "MultiViewData.h"
#include "RasterBounds.h"
#include "Rasterizer.h"
#include "RawVector.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vis4gs
{
namespace raster
{
namespace internal
{

/// ProjectGaussians()'s checks of the cloud's arrays (throws std::invalid_argument).
void ValidateCloud(const GaussianCloud& cloud, bool colors);

/// View-independent part of ProjectGaussians<float> step 3 for Gaussian @p i into slot @p k
/// of @p p (Valid -1, or 0 and zeros when a parameter it would use is not finite, or for
/// padding: @p i at or past the cloud's Count).
void PrepareGaussianForLanes(const GaussianCloud& cloud,
  std::size_t i,
  float mod,
  int shStride,
  int shUsed,
  bool colors,
  MultiViewPrepared& p,
  std::size_t k);

/// Projects the 16 prepared Gaussians [first, first + 16) into [at, at + 16) of the output
/// (ProjectionLanes.inc).
using ProjectBlockFunction = void (*)(const MultiViewPrepared&,
  std::size_t first,
  const PreparedView&,
  MultiViewProjected&,
  std::size_t at);
/// 0 best, 1 generic vectors, 2 AVX2, 3 AVX-512 (each falls back to what the machine has).
ProjectBlockFunction SelectProjection(int isa);

/// A tile rectangle in 16 bits per coordinate (tile grids of at most 65535 x 65535 tiles):
/// half the bytes of BinGaussians()' sorted rectangles.
using NarrowRect = std::array<std::uint16_t, 4>;

/// BinGaussians()'s step 3: the per-tile lists of @p count tile rectangles given in depth
/// order (tile-major; depth order inside a tile). Each of @p chunks consecutive parts of the
/// sequence counts its rectangles per tile with a 2D difference array ((gx+1) x (gy+1),
/// kept in @p diff between calls) and scatters into its own range of every tile, so the
/// lists do not depend on the number of chunks. The entries are @p ids[k], or the sorted
/// positions k when @p ids is null. Rectangles narrow (NarrowRect) or not (std::array<int, 4>).
template <typename Rect>
void BinSortedRects(const Rect* rects,
  const std::uint32_t* ids,
  std::int64_t count,
  int gx,
  int gy,
  int chunks,
  std::vector<std::int64_t>& diff,
  TileBins& bins);

/// BinSortedRects() with the entries in the low 32 bits of @p keys (BinGaussians()' sorted
/// keys: a Gaussian's index below its depth bits), rectangles narrow (NarrowRect) or not
/// (std::array<int, 4>). Defined in RasterBinning.cxx, its only user.
template <typename Rect>
void BinSortedKeys(const Rect* rects,
  const std::uint64_t* keys,
  std::int64_t count,
  int gx,
  int gy,
  int chunks,
  std::vector<std::int64_t>& diff,
  TileBins& bins);

/// The AVX-512 tile loop's candidate columns of pixel rows py0 .. py0 + 7 (CompositeLanes.inc
/// RowColumns8: SpanBounds::Columns() in 8 double lanes, clipped to the tile [X0, X0 + 15]):
/// bit l set when row py0 + l has candidate columns in the tile, then [lo[l], hi[l]] relative
/// to X0. -1 when the machine has no AVX-512 (for the tests).
int RowColumnsAvx512(const detail::SpanBounds& sb, int py0, int X0, int* lo, int* hi);

/// CompositeTiles()'s tile loop (CompositeLanes.inc, with depth) on per-Gaussian data indexed
/// by the ids of @p Bins.
struct CompositeInput
{
  int Width = 0, Height = 0;
  const TileBins* Bins = nullptr;
  const detail::KernelGaussian<float>* Kernels = nullptr;
  const detail::SpanRecord* Bounds = nullptr;
  std::array<double, 3> Background{ 0.0, 0.0, 0.0 };
  int KernelIsa = 0;
  int Threads = 1;
  /// Optional per-Gaussian statistics of the KernelCount kernels, indexed like Kernels (sized
  /// and filled here).
  GaussianWeightStats* Weights = nullptr;
  std::size_t KernelCount = 0;
};
void CompositeSorted(const CompositeInput& in, RasterImage<float>& image);

} // namespace internal
} // namespace raster
} // namespace vis4gs

#endif

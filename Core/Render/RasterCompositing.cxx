// SPDX-License-Identifier: BSD-3-Clause
// CompositeTiles(): front-to-back blending of every tile (reference §2.6), with optional
// per-Gaussian weight statistics and kept per-Gaussian data (CompositeData): the tile loop
// of CompositeLanes.inc compiled once per instruction set, and the per-Gaussian kernel and
// span records it reads (RasterBounds.h).
#include "Rasterizer.h"

#include "KernelIsa.h"
#include "RasterBounds.h"
#include "RasterInternal.h"
#include "ThreadCount.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <immintrin.h>
#include <limits>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

namespace vis4gs
{

namespace
{
//------------------------------------------------------------------------------
// Uninitialised buffer of a trivial type (first touched by the parallel loops that fill it).
template <typename U>
std::unique_ptr<U[]> RawBuffer(std::size_t n)
{
  static_assert(std::is_trivial<U>::value, "RawBuffer holds trivial types only");
  std::unique_ptr<U[]> buffer(new U[n > 0 ? n : 1]);
  raster::internal::HugePages(buffer.get(), n * sizeof(U));
  return buffer;
}

using raster::internal::ResizeKeep;
} // namespace

namespace
{

//------------------------------------------------------------------------------
// Compositing: 16 lanes = one tile row, with GCC vector extensions (CompositeLanes.inc,
// compiled once per instruction set with every helper carrying the target attribute).
template <typename T>
struct Lanes;
template <>
struct Lanes<float>
{
  typedef float V __attribute__((vector_size(64)));
  typedef std::int32_t I __attribute__((vector_size(64)));
};
template <>
struct Lanes<double>
{
  typedef double V __attribute__((vector_size(128)));
  typedef std::int64_t I __attribute__((vector_size(128)));
};

using raster::detail::KernelGaussian;

template <typename T>
struct CompositeContext
{
  int Width, Height, TilesX;
  const TileBins* Bins;
  /// Gaussian id's kernel record at Kernels + id * KernelStride bytes: a KernelGaussian array,
  /// or the projection's ProjectedGaussians, which start with the same values (KernelAt()).
  const unsigned char* Kernels;
  std::size_t KernelStride;
  const raster::detail::SpanRecord* Bounds;
  RasterImage<T>* Image;
  GaussianWeightStats* Weights;
  T Background[3];
  std::atomic<std::uint64_t>* KernelEvaluations;
  std::atomic<std::uint64_t>* ReferenceEvaluations;
  /// With GaussianWeightStats::CountEvaluations: per tile-list entry (index into Bins->Ids), the
  /// entry's alpha*T sum and evaluated pixels, summed per Gaussian in list order afterwards
  /// (EntrySums), so that WeightSum does not depend on the order threads finish tiles in.
  double* EntryWeight = nullptr;
  std::uint16_t* EntryEvaluations = nullptr;
  /// The blends to keep (CompositeTiles' record), its running count of blends and its limit.
  PixelWeightRecord* Record = nullptr;
  std::atomic<std::uint64_t>* RecordEntries = nullptr;
  /// RasterSettings::TransmittanceStop (the reference's value for every caller but
  /// CompositeTiles() with another setting).
  double Stop = raster::TransmittanceStop;
};

/// One tile's part of a PixelWeightRecord while the tile is blended (nullptr: not recording).
struct TileRecorder
{
  float Threshold;
  std::vector<PixelWeight>* Weights;
  std::vector<std::uint8_t>* Pixels;
  std::uint32_t Gaussian; // the list entry being blended

  /// Keeps lane l of tile row r when its weight reaches the threshold.
  void Add(int r, int l, float w)
  {
    if (w >= this->Threshold)
    {
      this->Weights->push_back({ this->Gaussian, w });
      this->Pixels->push_back(static_cast<std::uint8_t>(r * 16 + l));
    }
  }
};

/// Per-entry buffers of the counted statistics (see CompositeContext), zeroed.
struct EntrySums
{
  std::vector<double> Weight;
  std::vector<std::uint16_t> Evaluations;

  template <typename T>
  void Attach(CompositeContext<T>& ctx, const TileBins& bins, const GaussianWeightStats* weights)
  {
    if (weights && weights->CountEvaluations)
    {
      this->Weight.assign(bins.Ids.size(), 0.0);
      this->Evaluations.assign(bins.Ids.size(), 0);
      ctx.EntryWeight = this->Weight.data();
      ctx.EntryEvaluations = this->Evaluations.data();
    }
  }

  /// WeightSum and Evaluations of every Gaussian: its entries in tile order, one thread.
  void Reduce(const TileBins& bins, GaussianWeightStats* weights) const
  {
    if (!weights || !weights->CountEvaluations)
    {
      return;
    }
    for (std::size_t k = 0; k < bins.Ids.size(); ++k)
    {
      weights->WeightSum[bins.Ids[k]] += this->Weight[k];
      weights->Evaluations[bins.Ids[k]] += this->Evaluations[k];
    }
  }
};

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
namespace composite_baseline
{
#define VIS4GS_LANES_ISA 1
#include "CompositeLanes.inc"
#undef VIS4GS_LANES_ISA
} // namespace composite_baseline
namespace composite_avx2
{
#define VIS4GS_LANES_ISA 2
#include "CompositeLanes.inc"
#undef VIS4GS_LANES_ISA
} // namespace composite_avx2
namespace composite_avx512
{
#define VIS4GS_LANES_ISA 3
#include "CompositeLanes.inc"
#undef VIS4GS_LANES_ISA
} // namespace composite_avx512
#pragma GCC diagnostic pop

template <typename T>
using TileFunction = void (*)(const CompositeContext<T>&, std::int64_t);

// A ProjectedGaussian begins with a KernelGaussian's values in its order: the compositing reads
// the kernels of a projection in place.
template <typename T>
constexpr bool ProjectionStartsWithKernel()
{
  using P = ProjectedGaussian<T>;
  using K = KernelGaussian<T>;
  return std::is_standard_layout<P>::value && std::is_standard_layout<K>::value &&
    offsetof(P, U) == offsetof(K, U) && offsetof(P, V) == offsetof(K, V) &&
    offsetof(P, ConicA) == offsetof(K, A) && offsetof(P, ConicB) == offsetof(K, B) &&
    offsetof(P, ConicC) == offsetof(K, C) && offsetof(P, Opacity) == offsetof(K, O) &&
    offsetof(P, Color) == offsetof(K, R) && offsetof(P, Color) + sizeof(T) == offsetof(K, G) &&
    offsetof(P, Color) + 2 * sizeof(T) == offsetof(K, Bl) && offsetof(P, Depth) == offsetof(K, Z);
}
static_assert(ProjectionStartsWithKernel<float>(), "ProjectedGaussian<float> layout");
static_assert(ProjectionStartsWithKernel<double>(), "ProjectedGaussian<double> layout");

VIS4GS_TARGET_AVX512 int RowColumnsOn512(const raster::detail::SpanBounds& sb,
  int py0,
  int X0,
  int* lo,
  int* hi)
{
  return static_cast<int>(composite_avx512::RowColumns8(sb, py0, X0, lo, hi));
}

template <typename T, bool Stats, bool Work, bool Depth>
TileFunction<T> SelectTileFunction(int isa)
{
  switch (ResolveKernelIsa(isa))
  {
    case KernelIsa::Avx512:
      return &composite_avx512::CompositeTile<T, Stats, Work, Depth>;
    case KernelIsa::Avx2:
      return &composite_avx2::CompositeTile<T, Stats, Work, Depth>;
    default:
      return &composite_baseline::CompositeTile<T, Stats, Work, Depth>;
  }
}

} // namespace

//------------------------------------------------------------------------------
namespace
{
// The per-Gaussian data of the compositing loop (CompositeData) for Gaussians [begin, end),
// every element written.
template <typename T>
inline __attribute__((always_inline)) void FillCompositeRange(const ViewProjection<T>& projection,
  std::size_t begin,
  std::size_t end,
  raster::detail::KernelGaussian<T>* kernels,
  raster::detail::SpanRecord* bounds)
{
  using raster::detail::KernelGaussian;
  for (std::size_t i = begin; i < end; ++i)
  {
    const auto& g = projection.Gaussians[i];
    // Constructed in place (placement new of a prvalue: no temporary on the stack, whose
    // copy into the large array cost store-forwarding stalls).
    if (!g.IsVisible())
    {
      if (kernels)
      {
        new (&kernels[i]) KernelGaussian<T>{};
      }
      new (&bounds[i]) raster::detail::SpanRecord();
      continue;
    }
    if (kernels)
    {
      new (&kernels[i]) KernelGaussian<T>{ g.U,
        g.V,
        g.ConicA,
        g.ConicB,
        g.ConicC,
        g.Opacity,
        g.Color[0],
        g.Color[1],
        g.Color[2],
        g.Depth };
    }
    if (g.Opacity >= raster::MinAlpha<T>())
    {
      const double level = std::log(raster::MinAlpha<double>() / static_cast<double>(g.Opacity));
      new (&bounds[i]) raster::detail::SpanRecord(raster::detail::MakeSpanBounds<T>(
        g.U, g.V, g.ConicA, g.ConicB, g.ConicC, std::min(0.0, level)));
    }
    else
    {
      new (&bounds[i]) raster::detail::SpanRecord();
    }
  }
}

template <typename T>
void FillCompositeRangeBaseline(const ViewProjection<T>& projection,
  std::size_t begin,
  std::size_t end,
  raster::detail::KernelGaussian<T>* kernels,
  raster::detail::SpanRecord* bounds)
{
  FillCompositeRange(projection, begin, end, kernels, bounds);
}

/// The same IEEE operations (no contraction: -ffp-contract=off) with AVX2 encodings (rounding
/// instructions for floor/ceil instead of the baseline's emulation): the same bits, faster.
template <typename T>
VIS4GS_TARGET_AVX2 void FillCompositeRangeAvx2(const ViewProjection<T>& projection,
  std::size_t begin,
  std::size_t end,
  raster::detail::KernelGaussian<T>* kernels,
  raster::detail::SpanRecord* bounds)
{
  FillCompositeRange(projection, begin, end, kernels, bounds);
}

template <typename T>
void FillCompositeData(const ViewProjection<T>& projection,
  int threads,
  raster::detail::KernelGaussian<T>* kernels,
  raster::detail::SpanRecord* bounds)
{
  const std::size_t n = projection.Gaussians.size();
  const auto fill = CpuHasAvx2() ? &FillCompositeRangeAvx2<T> : &FillCompositeRangeBaseline<T>;
  constexpr std::size_t block = 4096;
  const std::int64_t blocks = static_cast<std::int64_t>((n + block - 1) / block);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::int64_t b = 0; b < blocks; ++b)
  {
    const std::size_t begin = static_cast<std::size_t>(b) * block;
    fill(projection, begin, std::min(n, begin + block), kernels, bounds);
  }
}
} // namespace

//------------------------------------------------------------------------------
template <typename T>
void PrepareCompositeData(const ViewProjection<T>& projection, int threads, CompositeData<T>& data)
{
  const std::size_t n = projection.Gaussians.size();
  ResizeKeep(data.Kernels, n);
  ResizeKeep(data.Bounds, n);
  FillCompositeData(projection, ThreadCount(threads), data.Kernels.data(), data.Bounds.data());
}

//------------------------------------------------------------------------------
std::size_t PixelWeightRecord::Entries() const
{
  std::size_t n = 0;
  for (const auto& tile : this->Weights)
  {
    n += tile.size();
  }
  return n;
}

//------------------------------------------------------------------------------
template <typename T>
void CompositeTiles(const ViewProjection<T>& projection,
  const TileBins& bins,
  const RasterSettings& settings,
  RasterImage<T>& image,
  GaussianWeightStats* weights,
  RasterWorkCounts* work,
  CompositeData<T>* keep,
  bool depth,
  PixelWeightRecord* record)
{
  if (bins.TilesX != projection.TilesX || bins.TilesY != projection.TilesY ||
    bins.Offsets.size() != bins.TileCount() + 1)
  {
    throw std::invalid_argument("CompositeTiles: the tile bins do not belong to this projection");
  }
  if (!depth && (weights || work))
  {
    throw std::invalid_argument("CompositeTiles: weights and work counts need depth on");
  }
  const int threads = ThreadCount(settings.Threads);
  const std::size_t n = projection.Gaussians.size();
  const std::size_t pixels = static_cast<std::size_t>(projection.Width) * projection.Height;
  image.Width = projection.Width;
  image.Height = projection.Height;
  image.Color.resize(3 * pixels);
  image.Alpha.resize(pixels);
  image.Transmittance.resize(pixels);
  if (depth)
  {
    image.Depth.resize(pixels);
  }
  else
  {
    image.Depth.clear();
  }
  image.Contributors.resize(pixels);

  // Conservative spans per Gaussian (input order; culled Gaussians get no bound), and the
  // compact kernel records when *keep asks for them; otherwise the kernels are read from the
  // projection in place. Kept in *keep when given (its buffers are reused).
  std::unique_ptr<unsigned char[]> ownBounds; // raw storage of trivially copyable SpanRecord
  KernelGaussian<T>* kernels = nullptr;
  raster::detail::SpanRecord* bounds;
  if (keep)
  {
    if (keep->KeepKernels)
    {
      ResizeKeep(keep->Kernels, n);
      kernels = keep->Kernels.data();
    }
    else
    {
      std::vector<KernelGaussian<T>>().swap(keep->Kernels);
    }
    ResizeKeep(keep->Bounds, n);
    bounds = keep->Bounds.data();
  }
  else
  {
    // Uninitialised: the loop below writes every element (first touch in parallel).
    static_assert(std::is_trivially_copyable<raster::detail::SpanRecord>::value, "");
    ownBounds = RawBuffer<unsigned char>((n > 0 ? n : 1) * sizeof(raster::detail::SpanRecord));
    bounds = reinterpret_cast<raster::detail::SpanRecord*>(ownBounds.get());
  }
  FillCompositeData(projection, threads, kernels, bounds);
  if (weights)
  {
    weights->MaxWeight.assign(n, 0.0f);
    weights->WeightSum.assign(n, 0.0);
    weights->BlendedPixels.assign(n, 0);
    if (weights->CountEvaluations)
    {
      weights->Evaluations.assign(n, 0);
    }
    else
    {
      weights->Evaluations.clear();
    }
  }
  std::atomic<std::uint64_t> kernelEvals{ 0 }, referenceEvals{ 0 };
  CompositeContext<T> ctx{ projection.Width,
    projection.Height,
    projection.TilesX,
    &bins,
    kernels ? reinterpret_cast<const unsigned char*>(kernels)
            : reinterpret_cast<const unsigned char*>(projection.Gaussians.data()),
    kernels ? sizeof(KernelGaussian<T>) : sizeof(ProjectedGaussian<T>),
    bounds,
    &image,
    weights,
    { static_cast<T>(settings.Background[0]),
      static_cast<T>(settings.Background[1]),
      static_cast<T>(settings.Background[2]) },
    &kernelEvals,
    &referenceEvals };
  if (!(settings.TransmittanceStop > 0.0) || !(settings.TransmittanceStop < 1.0))
  {
    throw std::invalid_argument("CompositeTiles: transmittance stop " +
      std::to_string(settings.TransmittanceStop) + " is not in (0, 1)");
  }
  ctx.Stop = settings.TransmittanceStop;
  EntrySums entries;
  entries.Attach(ctx, bins, weights);
  std::atomic<std::uint64_t> recordEntries{ 0 };
  if (record)
  {
    if (!(record->Threshold > 0.0f))
    {
      throw std::invalid_argument("CompositeTiles: the record's weight threshold must be positive");
    }
    record->Width = projection.Width;
    record->Height = projection.Height;
    record->TilesX = projection.TilesX;
    record->Complete = false;
    // Each tile's vectors keep their capacity from the previous frame (filled by one thread).
    record->Weights.resize(bins.TileCount());
    record->Pixels.resize(bins.TileCount());
    ctx.Record = record;
    ctx.RecordEntries = &recordEntries;
  }
  TileFunction<T> fn;
  const int isa = settings.KernelIsa;
  if (!depth)
  {
    fn = SelectTileFunction<T, false, false, false>(isa);
  }
  else if (weights)
  {
    // The evaluations need the per-pixel stop positions that the work counters keep.
    fn = work || weights->CountEvaluations ? SelectTileFunction<T, true, true, true>(isa)
                                           : SelectTileFunction<T, true, false, true>(isa);
  }
  else
  {
    fn = work ? SelectTileFunction<T, false, true, true>(isa)
              : SelectTileFunction<T, false, false, true>(isa);
  }
  const std::int64_t tiles = static_cast<std::int64_t>(bins.TileCount());
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (std::int64_t t = 0; t < tiles; ++t)
  {
    fn(ctx, t);
  }
  entries.Reduce(bins, weights);
  if (record)
  {
    record->Complete = recordEntries.load() <= record->MaximumEntries;
    if (!record->Complete)
    {
      // Over its budget: freed, not kept partial.
      std::vector<std::vector<PixelWeight>>().swap(record->Weights);
      std::vector<std::vector<std::uint8_t>>().swap(record->Pixels);
    }
  }
  if (work)
  {
    work->TilePairs = bins.Ids.size();
    work->KernelEvaluations = kernelEvals.load();
    work->ReferenceEvaluations = referenceEvals.load();
  }
}

//------------------------------------------------------------------------------
// Internals shared with MultiViewRenderer.cxx (RasterInternal.h).
namespace raster
{
namespace internal
{
int RowColumnsAvx512(const detail::SpanBounds& sb, int py0, int X0, int* lo, int* hi)
{
  if (!CpuHasAvx512())
  {
    return -1;
  }
  return RowColumnsOn512(sb, py0, X0, lo, hi);
}

void CompositeSorted(const CompositeInput& in, RasterImage<float>& image)
{
  const std::size_t pixels = static_cast<std::size_t>(in.Width) * in.Height;
  image.Width = in.Width;
  image.Height = in.Height;
  image.Color.resize(3 * pixels);
  image.Alpha.resize(pixels);
  image.Transmittance.resize(pixels);
  image.Depth.resize(pixels);
  image.Contributors.resize(pixels);
  if (in.Weights)
  {
    const std::size_t n = in.KernelCount;
    in.Weights->MaxWeight.assign(n, 0.0f);
    in.Weights->WeightSum.assign(n, 0.0);
    in.Weights->BlendedPixels.assign(n, 0);
    in.Weights->Evaluations.assign(in.Weights->CountEvaluations ? n : 0, 0);
  }
  std::atomic<std::uint64_t> kernelEvals{ 0 }, referenceEvals{ 0 };
  CompositeContext<float> ctx{ in.Width,
    in.Height,
    in.Bins->TilesX,
    in.Bins,
    reinterpret_cast<const unsigned char*>(in.Kernels),
    sizeof(KernelGaussian<float>),
    in.Bounds,
    &image,
    in.Weights,
    { static_cast<float>(in.Background[0]),
      static_cast<float>(in.Background[1]),
      static_cast<float>(in.Background[2]) },
    &kernelEvals,
    &referenceEvals };
  EntrySums entries;
  entries.Attach(ctx, *in.Bins, in.Weights);
  const TileFunction<float> fn = !in.Weights
    ? SelectTileFunction<float, false, false, true>(in.KernelIsa)
    : in.Weights->CountEvaluations ? SelectTileFunction<float, true, true, true>(in.KernelIsa)
                                   : SelectTileFunction<float, true, false, true>(in.KernelIsa);
  const std::int64_t tiles = static_cast<std::int64_t>(in.Bins->TileCount());
#pragma omp parallel for schedule(dynamic, 1) num_threads(in.Threads)
  for (std::int64_t t = 0; t < tiles; ++t)
  {
    fn(ctx, t);
  }
  entries.Reduce(*in.Bins, in.Weights);
}
} // namespace internal
} // namespace raster

template void PrepareCompositeData<float>(const ViewProjection<float>&, int, CompositeData<float>&);
template void PrepareCompositeData<double>(const ViewProjection<double>&,
  int,
  CompositeData<double>&);
template void CompositeTiles<float>(const ViewProjection<float>&,
  const TileBins&,
  const RasterSettings&,
  RasterImage<float>&,
  GaussianWeightStats*,
  RasterWorkCounts*,
  CompositeData<float>*,
  bool,
  PixelWeightRecord*);
template void CompositeTiles<double>(const ViewProjection<double>&,
  const TileBins&,
  const RasterSettings&,
  RasterImage<double>&,
  GaussianWeightStats*,
  RasterWorkCounts*,
  CompositeData<double>*,
  bool,
  PixelWeightRecord*);

} // namespace vis4gs

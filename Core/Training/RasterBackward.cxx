// SPDX-License-Identifier: BSD-3-Clause
#include "RasterBackward.h"

#include "GaussianMath.h"
#include "KernelIsa.h"
#include "RasterBounds.h"
#include "RasterKernel.h"
#include "ThreadCount.h"

#include <algorithm>
#include <cmath>
#include <immintrin.h>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace vis4gs
{
namespace
{

//------------------------------------------------------------------------------
// SH basis values Y_k(d) for k < 16 (reference §2.4).
template <typename T>
void ShBasis(const T d[3], int degree, T Y[16])
{
  const T x = d[0], y = d[1], z = d[2];
  Y[0] = T(sh::C0);
  if (degree < 1)
  {
    return;
  }
  Y[1] = -T(sh::C1) * y;
  Y[2] = T(sh::C1) * z;
  Y[3] = -T(sh::C1) * x;
  if (degree < 2)
  {
    return;
  }
  const T xx = x * x, yy = y * y, zz = z * z;
  Y[4] = T(sh::C2[0]) * x * y;
  Y[5] = T(sh::C2[1]) * y * z;
  Y[6] = T(sh::C2[2]) * (T(2) * zz - xx - yy);
  Y[7] = T(sh::C2[3]) * x * z;
  Y[8] = T(sh::C2[4]) * (xx - yy);
  if (degree < 3)
  {
    return;
  }
  Y[9] = T(sh::C3[0]) * y * (T(3) * xx - yy);
  Y[10] = T(sh::C3[1]) * x * y * z;
  Y[11] = T(sh::C3[2]) * y * (T(4) * zz - xx - yy);
  Y[12] = T(sh::C3[3]) * z * (T(2) * zz - T(3) * xx - T(3) * yy);
  Y[13] = T(sh::C3[4]) * x * (T(4) * zz - xx - yy);
  Y[14] = T(sh::C3[5]) * z * (xx - yy);
  Y[15] = T(sh::C3[6]) * x * (xx - T(3) * yy);
}

// Gradients of the basis, x, y, z treated as independent (reference §5.7 table).
template <typename T>
void ShBasisGradient(const T d[3], int degree, T dY[16][3])
{
  const T x = d[0], y = d[1], z = d[2];
  for (int k = 0; k < 16; ++k)
  {
    dY[k][0] = dY[k][1] = dY[k][2] = T(0);
  }
  if (degree < 1)
  {
    return;
  }
  const T C1 = T(sh::C1);
  dY[1][1] = -C1;
  dY[2][2] = C1;
  dY[3][0] = -C1;
  if (degree < 2)
  {
    return;
  }
  const T xx = x * x, yy = y * y, zz = z * z;
  auto set = [&](int k, T c, T gx, T gy, T gz)
  {
    dY[k][0] = c * gx;
    dY[k][1] = c * gy;
    dY[k][2] = c * gz;
  };
  set(4, T(sh::C2[0]), y, x, T(0));
  set(5, T(sh::C2[1]), T(0), z, y);
  set(6, T(sh::C2[2]), T(-2) * x, T(-2) * y, T(4) * z);
  set(7, T(sh::C2[3]), z, T(0), x);
  set(8, T(sh::C2[4]), T(2) * x, T(-2) * y, T(0));
  if (degree < 3)
  {
    return;
  }
  set(9, T(sh::C3[0]), T(6) * x * y, T(3) * xx - T(3) * yy, T(0));
  set(10, T(sh::C3[1]), y * z, x * z, x * y);
  set(11, T(sh::C3[2]), T(-2) * x * y, T(4) * zz - xx - T(3) * yy, T(8) * y * z);
  set(12, T(sh::C3[3]), T(-6) * x * z, T(-6) * y * z, T(6) * zz - T(3) * xx - T(3) * yy);
  set(13, T(sh::C3[4]), T(4) * zz - T(3) * xx - yy, T(-2) * x * y, T(8) * x * z);
  set(14, T(sh::C3[5]), T(2) * x * z, T(-2) * y * z, xx - yy);
  set(15, T(sh::C3[6]), T(3) * xx - T(3) * yy, T(-6) * x * y, T(0));
}

//------------------------------------------------------------------------------
// Compositing backward, per tile. Two implementations of the same per-pixel arithmetic:
//
//  - TileBackwardScalar(): the reference, pixel by pixel (each Gaussian's gradients summed
//    over its pixels in row-major order);
//  - TileBackwardLanes(): 16 lanes = one tile row, with GCC vector extensions, compiled for
//    baseline x86-64, AVX2 and AVX-512 and selected at run time like the forward's
//    compositing (Core/Render/RasterCompositing.cxx). Every lane performs exactly the scalar
//    operations (the library is built with -ffp-contract=off; KernelExpLanes equals
//    KernelExp bit for bit), so each pixel's contribution is bit-identical to the scalar
//    path's; only the order of the per-Gaussian sums differs: per lane over the rows, then a
//    fixed tree over the 16 lanes. That order is the same on every instruction set and for
//    every thread count.

/// Per Gaussian: compact 2D data and the conservative spans of the pixels where
/// o e^power >= 1/255 is possible (Render's CompositeData, as the forward makes them);
/// pixels outside are provably skipped by the exact kernel, so the spans never change a
/// result.
template <typename T>
using BackwardKernel = raster::detail::KernelGaussian<T>;

template <typename T>
struct BackwardContext
{
  const TileBins* Bins;
  const BackwardKernel<T>* Kernels;
  const raster::detail::SpanRecord* Spans;
  const RasterImage<T>* Image;
  const T* dLdImage;
  T Background[3];
  int Width, Height;
};

/// A partition's per-Gaussian accumulators: a Gaussian's row is zeroed and recorded on
/// first use; each tile then adds its one sum per Gaussian, tiles in order.
template <typename T>
struct PartitionSink
{
  T* Accumulators;
  std::uint8_t* Marks;
  std::vector<std::uint32_t>* Touched;
  std::vector<T>* Local; ///< scratch of the scalar path

  T* Row(std::uint32_t g)
  {
    constexpr int S = ProjectedGradients<T>::Stride;
    T* o = this->Accumulators + static_cast<std::size_t>(g) * S;
    if (!this->Marks[g])
    {
      this->Marks[g] = 1;
      this->Touched->push_back(g);
      for (int k = 0; k < S; ++k)
      {
        o[k] = T(0);
      }
    }
    return o;
  }
};

template <typename T>
void TileBackwardScalar(const BackwardContext<T>& ctx, std::size_t t, PartitionSink<T>& sink)
{
  constexpr int S = ProjectedGradients<T>::Stride;
  constexpr int TS = raster::TileSize;
  const TileBins& bins = *ctx.Bins;
  const RasterImage<T>& image = *ctx.Image;
  const int W = ctx.Width, H = ctx.Height;
  const T minAlpha = raster::MinAlpha<T>();
  const T maxAlpha = T(raster::MaxAlpha);
  const std::size_t begin = bins.Offsets[t], end = bins.Offsets[t + 1];
  const std::size_t m = end - begin;
  const int tx = static_cast<int>(t % static_cast<std::size_t>(bins.TilesX));
  const int ty = static_cast<int>(t / static_cast<std::size_t>(bins.TilesX));
  // Per-pixel state of the back-to-front walk (TS x TS pixels of the tile).
  T pT[TS * TS], pFinal[TS * TS], pBg[TS * TS], pAcc[TS * TS][3], pLastA[TS * TS],
    pLastC[TS * TS][3], pG[TS * TS][3];
  std::uint32_t pLast[TS * TS];
  sink.Local->assign(m * S, T(0));
  T* local = sink.Local->data(); // the tile's Gaussians' gradients, in list order
  const int x0 = tx * TS, y0 = ty * TS;
  const int x1 = std::min(W, x0 + TS), y1 = std::min(H, y0 + TS);
  std::uint32_t maxLast = 0;
  for (int py = y0; py < y1; ++py)
  {
    for (int px = x0; px < x1; ++px)
    {
      const std::size_t pix = static_cast<std::size_t>(py) * W + px;
      const int q = (py - y0) * TS + (px - x0);
      pLast[q] = static_cast<std::uint32_t>(std::min<std::size_t>(image.Contributors[pix], m));
      maxLast = std::max(maxLast, pLast[q]);
      pFinal[q] = image.Transmittance[pix];
      pT[q] = pFinal[q];
      for (int ch = 0; ch < 3; ++ch)
      {
        pG[q][ch] = ctx.dLdImage[3 * pix + ch];
        pAcc[q][ch] = 0;
        pLastC[q][ch] = 0;
      }
      pBg[q] =
        ctx.Background[0] * pG[q][0] + ctx.Background[1] * pG[q][1] + ctx.Background[2] * pG[q][2];
      pLastA[q] = 0;
    }
  }
  // Gaussian-major walk, back to front: every pixel still sees its Gaussians in decreasing
  // list order (the exact sequence of renderCUDA's backward), and each Gaussian's gradients
  // are summed over its pixels in row-major order.
  for (std::size_t jj = maxLast; jj-- > 0;)
  {
    const std::uint32_t id = bins.Ids[begin + jj];
    const BackwardKernel<T>& g = ctx.Kernels[id];
    const raster::detail::SpanBounds sb = ctx.Spans[id].Expand(g.U, g.V);
    int r0 = y0, r1 = y1 - 1;
    if (sb.Bounded)
    {
      r0 = std::max(r0, sb.RowMin);
      r1 = std::min(r1, sb.RowMax);
    }
    T* r = local + jj * S;
    const T u = g.U, v = g.V, ca = g.A, cb = g.B, cc = g.C, op = g.O;
    const T col[3] = { g.R, g.G, g.Bl };
    // Below pmin, o e^power < 1/255 for certain (a margin of 1e-3 covers the rounding of
    // KernelExp and of this logarithm): the scalar path skips the pair without exp().
    const T pmin = static_cast<T>(std::log(1.0 / (255.0 * static_cast<double>(g.O))) - 1e-3);
    for (int py = r0; py <= r1; ++py)
    {
      int c0 = x0, c1 = x1 - 1;
      if (sb.Bounded)
      {
        int xa, xb;
        if (!sb.Columns(py, xa, xb))
        {
          continue;
        }
        c0 = std::max(c0, xa);
        c1 = std::min(c1, xb);
      }
      const T fy = static_cast<T>(py);
      for (int px = c0; px <= c1; ++px)
      {
        const int q = (py - y0) * TS + (px - x0);
        if (jj >= pLast[q])
        {
          continue;
        }
        const T fx = static_cast<T>(px);
        const T power = raster::KernelPower(u, v, ca, cb, cc, fx, fy);
        if (power < pmin || !(power <= T(0)))
        {
          continue;
        }
        const T G = raster::KernelExp(power);
        const T a = op * G;
        const T alpha = a < maxAlpha ? a : maxAlpha;
        if (!(alpha >= minAlpha))
        {
          continue;
        }
        const T inv = T(1) / (T(1) - alpha);
        const T Tc = pT[q] * inv;
        pT[q] = Tc;
        const T w = alpha * Tc;
        const T lastAlpha = pLastA[q];
        T dLdAlpha = 0;
        for (int ch = 0; ch < 3; ++ch)
        {
          pAcc[q][ch] = lastAlpha * pLastC[q][ch] + (T(1) - lastAlpha) * pAcc[q][ch];
          pLastC[q][ch] = col[ch];
          dLdAlpha += (col[ch] - pAcc[q][ch]) * pG[q][ch];
          r[6 + ch] += w * pG[q][ch];
        }
        dLdAlpha *= Tc;
        pLastA[q] = alpha;
        dLdAlpha += ((-pFinal[q]) * inv) * pBg[q];
        const T dLdG = op * dLdAlpha;
        const T dx = u - fx, dy = v - fy;
        const T gdx = G * dx, gdy = G * dy;
        r[0] += dLdG * (-gdx * ca - gdy * cb);
        r[1] += dLdG * (-gdy * cc - gdx * cb);
        r[2] += T(-0.5) * gdx * dx * dLdG;
        r[3] += -gdx * dy * dLdG;
        r[4] += T(-0.5) * gdy * dy * dLdG;
        r[5] += G * dLdAlpha;
      }
    }
  }
  // Into the partition's accumulators, in list order.
  for (std::size_t j = 0; j < m; ++j)
  {
    T* o = sink.Row(bins.Ids[begin + j]);
    for (int k = 0; k < S; ++k)
    {
      o[k] += local[j * S + k];
    }
  }
}

template <typename T>
struct BackwardLanes;
template <>
struct BackwardLanes<float>
{
  typedef float V __attribute__((vector_size(64)));
  typedef std::int32_t I __attribute__((vector_size(64)));
};
template <>
struct BackwardLanes<double>
{
  typedef double V __attribute__((vector_size(128)));
  typedef std::int64_t I __attribute__((vector_size(128)));
};

// The baseline and AVX2 instantiations run the tile loop on vectors of the width of their
// registers (VIS4GS_LANES_NATIVE_BYTES).
namespace lanes_baseline
{
#define VIS4GS_LANES_ISA 1
#include "RasterBackwardLanes.inc"
#undef VIS4GS_LANES_ISA
} // namespace lanes_baseline
namespace lanes_avx2
{
#define VIS4GS_LANES_ISA 2
#include "RasterBackwardLanes.inc"
#undef VIS4GS_LANES_ISA
} // namespace lanes_avx2
namespace lanes_avx512
{
#define VIS4GS_LANES_ISA 3
#include "RasterBackwardLanes.inc"
#undef VIS4GS_LANES_ISA
} // namespace lanes_avx512

template <typename T>
using BackwardTileFunction = void (*)(const BackwardContext<T>&, std::size_t, PartitionSink<T>&);

template <typename T>
void TileLanesBaseline(const BackwardContext<T>& ctx, std::size_t t, PartitionSink<T>& sink)
{
  lanes_baseline::TileBackwardLanes<T>(ctx, t, sink);
}
template <typename T>
VIS4GS_TARGET_AVX2 void TileLanesAvx2(const BackwardContext<T>& ctx,
  std::size_t t,
  PartitionSink<T>& sink)
{
  lanes_avx2::TileBackwardLanes<T>(ctx, t, sink);
}
template <typename T>
VIS4GS_TARGET_AVX512 void TileLanesAvx512(const BackwardContext<T>& ctx,
  std::size_t t,
  PartitionSink<T>& sink)
{
  lanes_avx512::TileBackwardLanes<T>(ctx, t, sink);
}

template <typename T>
BackwardTileFunction<T> SelectBackwardTile(int isa)
{
  if (isa < 0)
  {
    return &TileBackwardScalar<T>;
  }
  switch (ResolveKernelIsa(isa))
  {
    case KernelIsa::Avx512:
      return &TileLanesAvx512<T>;
    case KernelIsa::Avx2:
      return &TileLanesAvx2<T>;
    default:
      return &TileLanesBaseline<T>;
  }
}

std::uint32_t SpanRowMaskBaseline(const raster::detail::SpanBounds& sb, int x0, int y0)
{
  return lanes_baseline::SpanRowMask(sb, x0, y0);
}
VIS4GS_TARGET_AVX2 std::uint32_t SpanRowMaskAvx2(const raster::detail::SpanBounds& sb,
  int x0,
  int y0)
{
  return lanes_avx2::SpanRowMask(sb, x0, y0);
}
VIS4GS_TARGET_AVX512 std::uint32_t SpanRowMaskAvx512(const raster::detail::SpanBounds& sb,
  int x0,
  int y0)
{
  return lanes_avx512::SpanRowMask(sb, x0, y0);
}

} // namespace

//------------------------------------------------------------------------------
std::uint32_t detail::BackwardSpanRowMask(const raster::detail::SpanBounds& span,
  int x0,
  int y0,
  int isa)
{
  if (isa < 0)
  {
    std::uint32_t mask = 0;
    for (int r = 0; r < 16; ++r)
    {
      int xa, xb;
      if (span.Columns(y0 + r, xa, xb) && xb >= x0 && xa <= x0 + 15)
      {
        mask |= 1u << r;
      }
    }
    return mask;
  }
  const BackwardTileFunction<float> f = SelectBackwardTile<float>(isa);
  if (f == &TileLanesAvx512<float>)
  {
    return SpanRowMaskAvx512(span, x0, y0);
  }
  if (f == &TileLanesAvx2<float>)
  {
    return SpanRowMaskAvx2(span, x0, y0);
  }
  return SpanRowMaskBaseline(span, x0, y0);
}

//------------------------------------------------------------------------------
template <typename T>
void GaussianGradients<T>::Reset(std::size_t count, int shCoefficients)
{
  this->Count = count;
  this->ShCoefficients = shCoefficients;
  this->Positions.assign(3 * count, T(0));
  this->LogScales.assign(3 * count, T(0));
  this->Rotations.assign(4 * count, T(0));
  this->OpacityLogits.assign(count, T(0));
  this->SH.assign(3 * static_cast<std::size_t>(shCoefficients) * count, T(0));
  this->ViewspaceGradients.assign(2 * count, T(0));
  this->Visible.assign(count, 0);
}

//------------------------------------------------------------------------------
template <typename T>
T GaussianGradients<T>::ViewspaceNorm(std::size_t i) const
{
  const T x = this->ViewspaceGradients[2 * i], y = this->ViewspaceGradients[2 * i + 1];
  return std::sqrt(x * x + y * y);
}

//------------------------------------------------------------------------------
template <typename T>
void CompositeBackward(const ViewProjection<T>& projection,
  const TileBins& bins,
  const RasterSettings& settings,
  const RasterImage<T>& image,
  const T* dLdImage,
  ProjectedGradients<T>& gradients,
  const BackwardSettings& options)
{
  constexpr int S = ProjectedGradients<T>::Stride;
  const std::size_t n = projection.Gaussians.size();
  const int W = projection.Width, H = projection.Height;
  if (image.Width != W || image.Height != H ||
    image.Transmittance.size() != static_cast<std::size_t>(W) * H ||
    image.Contributors.size() != static_cast<std::size_t>(W) * H)
  {
    throw std::invalid_argument("CompositeBackward: the image does not match the projection (" +
      std::to_string(image.Width) + "x" + std::to_string(image.Height) + " vs " +
      std::to_string(W) + "x" + std::to_string(H) + ")");
  }
  if (bins.TilesX != projection.TilesX || bins.TilesY != projection.TilesY ||
    bins.Offsets.size() != bins.TileCount() + 1)
  {
    throw std::invalid_argument("CompositeBackward: the tile bins do not match the projection");
  }
  gradients.Values.assign(n * S, T(0));
  const int threads = ThreadCount(options.Threads);
  // Fixed partitions of the image (bands of tile rows), independent of the thread count:
  // each partition accumulates into its own per-Gaussian array, its tiles in order, and the
  // partitions are summed in order. Memory is bounded to ~256 MB of partition arrays.
  const std::size_t perPartition = std::max<std::size_t>(1, n * S * sizeof(T));
  const int P = static_cast<int>(std::max<std::size_t>(1,
    std::min<std::size_t>({ 16,
      static_cast<std::size_t>(std::max(1, bins.TilesY)),
      (std::size_t(1) << 28) / perPartition })));
  BackwardWorkspace<T>& ws = gradients.Workspace;
  if (ws.Accumulators.size() < static_cast<std::size_t>(P) * n * S)
  {
    ws.Accumulators.resize(static_cast<std::size_t>(P) * n * S);
  }
  ws.Marks.assign(static_cast<std::size_t>(P) * n, 0);
  ws.Touched.resize(static_cast<std::size_t>(P));

  CompositeData<T>& data = ws.Composite;
  if (!(ws.PreparedFor == static_cast<const void*>(projection.Gaussians.data()) &&
        ws.PreparedCount == n && data.Bounds.size() == n && data.Kernels.size() == n))
  {
    PrepareCompositeData(projection, threads, data);
  }
  ws.PreparedFor = nullptr;
  ws.PreparedCount = 0;
  const BackwardContext<T> ctx{ &bins,
    data.Kernels.data(),
    data.Bounds.data(),
    &image,
    dLdImage,
    { static_cast<T>(settings.Background[0]),
      static_cast<T>(settings.Background[1]),
      static_cast<T>(settings.Background[2]) },
    W,
    H };
  const BackwardTileFunction<T> tileFunction = SelectBackwardTile<T>(options.KernelIsa);

  // Partitions handed out largest first (by their tiles' list lengths), so that the last
  // one to finish is a small one: with 16 bands on 2 threads, the band order left one
  // thread idle for up to a band's time. Which thread runs a partition never changes what
  // it computes.
  int order[16];
  {
    std::size_t cost[16];
    for (int part = 0; part < P; ++part)
    {
      const int ty0 = static_cast<int>(static_cast<long long>(bins.TilesY) * part / P);
      const int ty1 = static_cast<int>(static_cast<long long>(bins.TilesY) * (part + 1) / P);
      cost[part] = bins.Offsets[static_cast<std::size_t>(ty1) * bins.TilesX] -
        bins.Offsets[static_cast<std::size_t>(ty0) * bins.TilesX];
      order[part] = part;
    }
    std::stable_sort(order, order + P, [&cost](int a, int b) { return cost[a] > cost[b]; });
  }
#pragma omp parallel num_threads(threads)
  {
    std::vector<T> local;
#pragma omp for schedule(dynamic, 1)
    for (int k = 0; k < P; ++k)
    {
      const int part = order[k];
      std::vector<std::uint32_t>& touched = ws.Touched[part];
      touched.clear();
      PartitionSink<T> sink{ ws.Accumulators.data() + static_cast<std::size_t>(part) * n * S,
        ws.Marks.data() + static_cast<std::size_t>(part) * n,
        &touched,
        &local };
      const int ty0 = static_cast<int>(static_cast<long long>(bins.TilesY) * part / P);
      const int ty1 = static_cast<int>(static_cast<long long>(bins.TilesY) * (part + 1) / P);
      for (int ty = ty0; ty < ty1; ++ty)
      {
        for (int tx = 0; tx < bins.TilesX; ++tx)
        {
          const std::size_t t = static_cast<std::size_t>(ty) * bins.TilesX + tx;
          if (bins.Offsets[t + 1] > bins.Offsets[t])
          {
            tileFunction(ctx, t, sink);
          }
        }
      }
    }
  }
  // Fixed-order reduction: each Gaussian adds the partitions that touched it in partition
  // order, so the sums do not depend on how the Gaussians are split between threads. The
  // Gaussians go in chunks, and within a chunk partition after partition, so that each
  // partition's rows are read as one sequential stream while the chunk's outputs stay in
  // cache (reading the 16 partitions of one Gaussian after another missed the cache on
  // nearly every row).
  T* out = gradients.Values.data();
  constexpr std::int64_t Chunk = 1024;
  const std::int64_t chunks = (static_cast<std::int64_t>(n) + Chunk - 1) / Chunk;
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t c = 0; c < chunks; ++c)
  {
    const std::size_t g0 = static_cast<std::size_t>(c * Chunk);
    const std::size_t g1 = std::min(n, g0 + static_cast<std::size_t>(Chunk));
    for (int part = 0; part < P; ++part)
    {
      const std::uint8_t* marks = ws.Marks.data() + static_cast<std::size_t>(part) * n;
      const T* rows = ws.Accumulators.data() + static_cast<std::size_t>(part) * n * S;
      for (std::size_t g = g0; g < g1; ++g)
      {
        if (marks[g])
        {
          T* o = out + g * S;
          const T* r = rows + g * S;
          for (int k = 0; k < S; ++k)
          {
            o[k] += r[k];
          }
        }
      }
    }
  }
}

//------------------------------------------------------------------------------
template <typename T>
void CompositeForward(const ViewProjection<T>& projection,
  const TileBins& bins,
  const RasterSettings& settings,
  RasterImage<T>& image,
  const BackwardSettings& options,
  BackwardWorkspace<T>* workspace)
{
  if (bins.TilesX != projection.TilesX || bins.TilesY != projection.TilesY ||
    bins.Offsets.size() != bins.TileCount() + 1)
  {
    throw std::invalid_argument("CompositeForward: the tile bins do not match the projection");
  }
  RasterSettings forward = settings;
  forward.Threads = options.Threads;
  forward.KernelIsa = std::max(0, options.KernelIsa);
  CompositeTiles(projection,
    bins,
    forward,
    image,
    nullptr,
    nullptr,
    workspace ? &workspace->Composite : nullptr,
    false);
  if (workspace)
  {
    workspace->PreparedFor = projection.Gaussians.data();
    workspace->PreparedCount = projection.Gaussians.size();
  }
}

//------------------------------------------------------------------------------
template <typename T>
void ProjectBackward(const GaussianCloud& cloud,
  const ViewProjection<T>& projection,
  const RasterSettings& settings,
  const ProjectedGradients<T>& projected,
  GaussianGradients<T>& gradients,
  const BackwardSettings& options)
{
  constexpr int S = ProjectedGradients<T>::Stride;
  const std::size_t n = cloud.Count;
  if (projection.Gaussians.size() != n || projected.Values.size() != n * S)
  {
    throw std::invalid_argument("ProjectBackward: the projection (" +
      std::to_string(projection.Gaussians.size()) + " Gaussians) or its gradients do not match " +
      "the cloud (" + std::to_string(n) + " Gaussians)");
  }
  const int K = cloud.ShCoefficientCount();
  // Sized without zeroing: every Gaussian writes all of its entries below (zeros where it
  // is culled or a coefficient is unused), which saves a pass over ~250 B per Gaussian.
  gradients.Count = n;
  gradients.ShCoefficients = K;
  gradients.Positions.resize(3 * n);
  gradients.LogScales.resize(3 * n);
  gradients.Rotations.resize(4 * n);
  gradients.OpacityLogits.resize(n);
  gradients.SH.resize(3 * static_cast<std::size_t>(K) * n);
  gradients.ViewspaceGradients.resize(2 * n);
  gradients.Visible.resize(n);
  const int degree = projection.ShDegree;
  const int used = (degree + 1) * (degree + 1);
  const T W = static_cast<T>(projection.Width), H = static_cast<T>(projection.Height);
  const T fx = projection.Fx, fy = projection.Fy;
  const T limx = T(raster::JacobianClamp) * projection.TanFovX;
  const T limy = T(raster::JacobianClamp) * projection.TanFovY;
  const auto& Vm = projection.ViewMatrix;
  const auto& F = projection.FullProjection;
  const T Rv[3][3] = { { Vm[0], Vm[1], Vm[2] }, { Vm[4], Vm[5], Vm[6] }, { Vm[8], Vm[9], Vm[10] } };
  const auto campos = projection.CameraCenter;
  const T mod = static_cast<T>(settings.ScaleModifier);
  const bool exactClamp = options.ExactJacobianClamp;
  const bool colors = settings.ComputeColors;
  const std::int64_t count = static_cast<std::int64_t>(n);
  const int threads = ThreadCount(options.Threads);

#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t ii = 0; ii < count; ++ii)
  {
    const std::size_t i = static_cast<std::size_t>(ii);
    const ProjectedGaussian<T>& pg = projection.Gaussians[i];
    T* gsh = gradients.SH.data() + i * 3 * static_cast<std::size_t>(K);
    if (!pg.IsVisible())
    {
      gradients.Visible[i] = 0;
      std::fill_n(gradients.Positions.data() + 3 * i, 3, T(0));
      std::fill_n(gradients.LogScales.data() + 3 * i, 3, T(0));
      std::fill_n(gradients.Rotations.data() + 4 * i, 4, T(0));
      gradients.OpacityLogits[i] = T(0);
      std::fill_n(gsh, 3 * K, T(0));
      gradients.ViewspaceGradients[2 * i] = T(0);
      gradients.ViewspaceGradients[2 * i + 1] = T(0);
      continue;
    }
    gradients.Visible[i] = 1;
    // Coefficients above the active degree (all of them without colours) get no gradient.
    const int firstZero = colors ? std::min(used, K) : 0;
    std::fill(gsh + 3 * firstZero, gsh + 3 * K, T(0));
    const T* pgrad = projected.Values.data() + i * S;
    const T gu = pgrad[0], gv = pgrad[1], gA = pgrad[2], gB = pgrad[3], gC = pgrad[4];
    const T gO = pgrad[5];
    // View-space (NDC) gradient: d ndc2pix / d ndc = size/2.
    const T gndcx = gu * W * T(0.5), gndcy = gv * H * T(0.5);
    gradients.ViewspaceGradients[2 * i] = gndcx;
    gradients.ViewspaceGradients[2 * i + 1] = gndcy;
    // Opacity through the sigmoid.
    gradients.OpacityLogits[i] = gO * pg.Opacity * (T(1) - pg.Opacity);

    // §5.3 conic -> dilated 2D covariance (a, b, c).
    const T a = pg.Cov2D[0], b = pg.Cov2D[1], c = pg.Cov2D[2];
    const T D = a * c - b * b;
    const T inv = T(1) / (D * D);
    const T ga = (-c * c * gA + b * c * gB - b * b * gC) * inv;
    const T gc = (-b * b * gA + a * b * gB - a * a * gC) * inv;
    const T gb = (T(2) * b * c * gA - (D + T(2) * b * b) * gB + T(2) * a * b * gC) * inv;
    const T Gp[2][2] = { { ga, gb * T(0.5) }, { gb * T(0.5), gc } };

    // Recompute the 3D covariance and the Jacobian as the forward does.
    const float* pos = &cloud.Positions[3 * i];
    const float* ls = &cloud.LogScales[3 * i];
    const float* rot = &cloud.Rotations[4 * i];
    const T s[3] = { mod * std::exp(static_cast<T>(ls[0])),
      mod * std::exp(static_cast<T>(ls[1])),
      mod * std::exp(static_cast<T>(ls[2])) };
    const T qraw[4] = { rot[0], rot[1], rot[2], rot[3] };
    const T qn =
      std::sqrt(qraw[0] * qraw[0] + qraw[1] * qraw[1] + qraw[2] * qraw[2] + qraw[3] * qraw[3]);
    const std::array<T, 4> q = NormalizeQuaternion<T>(qraw);
    const std::array<T, 9> R = QuaternionToMatrix<T>(q);
    T Sig[3][3];
    for (int r = 0; r < 3; ++r)
    {
      for (int cc = 0; cc < 3; ++cc)
      {
        Sig[r][cc] = R[3 * r] * s[0] * s[0] * R[3 * cc] +
          R[3 * r + 1] * s[1] * s[1] * R[3 * cc + 1] + R[3 * r + 2] * s[2] * s[2] * R[3 * cc + 2];
      }
    }
    const T t0 = pg.ViewPosition[0], t1 = pg.ViewPosition[1], t2 = pg.ViewPosition[2];
    const T txtz = t0 / t2, tytz = t1 / t2;
    const bool clampX = txtz < -limx || txtz > limx;
    const bool clampY = tytz < -limy || tytz > limy;
    const T tx = std::min(limx, std::max(-limx, txtz)) * t2;
    const T ty = std::min(limy, std::max(-limy, tytz)) * t2;
    const T tz2 = t2 * t2, tz3 = tz2 * t2;
    const T J[2][3] = { { fx / t2, T(0), -(fx * tx) / tz2 }, { T(0), fy / t2, -(fy * ty) / tz2 } };
    // Tm = J Rv (2x3).
    T Tm[2][3];
    for (int r = 0; r < 2; ++r)
    {
      for (int cc = 0; cc < 3; ++cc)
      {
        Tm[r][cc] = J[r][0] * Rv[0][cc] + J[r][1] * Rv[1][cc] + J[r][2] * Rv[2][cc];
      }
    }
    // §5.4: dL/dSigma = Tm^T G' Tm.
    T GpT[2][3];
    for (int r = 0; r < 2; ++r)
    {
      for (int cc = 0; cc < 3; ++cc)
      {
        GpT[r][cc] = Gp[r][0] * Tm[0][cc] + Gp[r][1] * Tm[1][cc];
      }
    }
    T GS[3][3];
    for (int r = 0; r < 3; ++r)
    {
      for (int cc = 0; cc < 3; ++cc)
      {
        GS[r][cc] = Tm[0][r] * GpT[0][cc] + Tm[1][r] * GpT[1][cc];
      }
    }
    // V = Rv Sigma Rv^T; dL/dJ = 2 G' J V.
    T RS[3][3], Vv[3][3];
    for (int r = 0; r < 3; ++r)
    {
      for (int cc = 0; cc < 3; ++cc)
      {
        RS[r][cc] = Rv[r][0] * Sig[0][cc] + Rv[r][1] * Sig[1][cc] + Rv[r][2] * Sig[2][cc];
      }
    }
    for (int r = 0; r < 3; ++r)
    {
      for (int cc = 0; cc < 3; ++cc)
      {
        Vv[r][cc] = RS[r][0] * Rv[cc][0] + RS[r][1] * Rv[cc][1] + RS[r][2] * Rv[cc][2];
      }
    }
    T GJ[2][3];
    for (int r = 0; r < 2; ++r)
    {
      T JV[3];
      for (int cc = 0; cc < 3; ++cc)
      {
        JV[cc] = T(0);
      }
      for (int k = 0; k < 2; ++k)
      {
        for (int cc = 0; cc < 3; ++cc)
        {
          JV[cc] += Gp[r][k] * (J[k][0] * Vv[0][cc] + J[k][1] * Vv[1][cc] + J[k][2] * Vv[2][cc]);
        }
      }
      for (int cc = 0; cc < 3; ++cc)
      {
        GJ[r][cc] = T(2) * JV[cc];
      }
    }
    const T kx = (exactClamp && clampX) ? T(1) : T(2);
    const T ky = (exactClamp && clampY) ? T(1) : T(2);
    T gt[3];
    gt[0] = clampX ? T(0) : (-fx / tz2) * GJ[0][2];
    gt[1] = clampY ? T(0) : (-fy / tz2) * GJ[1][2];
    gt[2] = -(fx / tz2) * GJ[0][0] - (fy / tz2) * GJ[1][1] + (kx * fx * tx / tz3) * GJ[0][2] +
      (ky * fy * ty / tz3) * GJ[1][2];
    T gmu[3];
    for (int k = 0; k < 3; ++k)
    {
      gmu[k] = Rv[0][k] * gt[0] + Rv[1][k] * gt[1] + Rv[2][k] * gt[2];
    }
    // §5.5 mean projection.
    const T x = pos[0], y = pos[1], z = pos[2];
    const T hx = F[0] * x + F[1] * y + F[2] * z + F[3];
    const T hy = F[4] * x + F[5] * y + F[6] * z + F[7];
    const T hw = F[12] * x + F[13] * y + F[14] * z + F[15];
    const T wp = hw + T(0.0000001);
    const T wp2 = wp * wp;
    for (int k = 0; k < 3; ++k)
    {
      gmu[k] +=
        (F[k] / wp - F[12 + k] * hx / wp2) * gndcx + (F[4 + k] / wp - F[12 + k] * hy / wp2) * gndcy;
    }
    // §5.6 scales and rotation.
    for (int k = 0; k < 3; ++k)
    {
      T rGr = T(0);
      for (int r = 0; r < 3; ++r)
      {
        rGr += R[3 * r + k] * (GS[r][0] * R[k] + GS[r][1] * R[3 + k] + GS[r][2] * R[6 + k]);
      }
      gradients.LogScales[3 * i + k] = T(2) * s[k] * s[k] * rGr;
    }
    T gR[3][3];
    for (int r = 0; r < 3; ++r)
    {
      for (int cc = 0; cc < 3; ++cc)
      {
        gR[r][cc] =
          T(2) * (GS[r][0] * R[cc] + GS[r][1] * R[3 + cc] + GS[r][2] * R[6 + cc]) * s[cc] * s[cc];
      }
    }
    const T w = q[0], qx = q[1], qy = q[2], qz = q[3];
    const T gw = T(2) *
      (gR[0][1] * -qz + gR[0][2] * qy + gR[1][0] * qz + gR[1][2] * -qx + gR[2][0] * -qy +
        gR[2][1] * qx);
    const T gx = T(2) *
      (gR[0][1] * qy + gR[0][2] * qz + gR[1][0] * qy + gR[1][1] * (T(-2) * qx) + gR[1][2] * -w +
        gR[2][0] * qz + gR[2][1] * w + gR[2][2] * (T(-2) * qx));
    const T gy = T(2) *
      (gR[0][0] * (T(-2) * qy) + gR[0][1] * qx + gR[0][2] * w + gR[1][0] * qx + gR[1][2] * qz +
        gR[2][0] * -w + gR[2][1] * qz + gR[2][2] * (T(-2) * qy));
    const T gz = T(2) *
      (gR[0][0] * (T(-2) * qz) + gR[0][1] * -w + gR[0][2] * qx + gR[1][0] * w +
        gR[1][1] * (T(-2) * qz) + gR[1][2] * qy + gR[2][0] * qx + gR[2][1] * qy);
    const T gqh[4] = { gw, gx, gy, gz };
    const T norm = qn > T(1e-12) ? qn : T(1e-12);
    if (qn > T(1e-12))
    {
      const T dot = q[0] * gqh[0] + q[1] * gqh[1] + q[2] * gqh[2] + q[3] * gqh[3];
      for (int k = 0; k < 4; ++k)
      {
        gradients.Rotations[4 * i + k] = (gqh[k] - q[k] * dot) / norm;
      }
    }
    else
    {
      for (int k = 0; k < 4; ++k)
      {
        gradients.Rotations[4 * i + k] = gqh[k] / norm;
      }
    }
    // §5.7 SH colour and its view-direction path.
    if (colors)
    {
      T gcol[3];
      for (int ch = 0; ch < 3; ++ch)
      {
        gcol[ch] = (pg.ClampedChannels & (1u << ch)) ? T(0) : pgrad[6 + ch];
      }
      const T v3[3] = { x - campos[0], y - campos[1], z - campos[2] };
      const T len = std::sqrt(v3[0] * v3[0] + v3[1] * v3[1] + v3[2] * v3[2]);
      const T d[3] = { v3[0] / len, v3[1] / len, v3[2] / len };
      T Y[16];
      ShBasis<T>(d, degree, Y);
      for (int k = 0; k < used; ++k)
      {
        for (int ch = 0; ch < 3; ++ch)
        {
          gsh[3 * k + ch] = Y[k] * gcol[ch];
        }
      }
      if (degree > 0)
      {
        T dY[16][3];
        ShBasisGradient<T>(d, degree, dY);
        const float* f = &cloud.SH[i * 3 * static_cast<std::size_t>(K)];
        T gd[3] = { 0, 0, 0 };
        for (int k = 1; k < used; ++k)
        {
          const T fg = static_cast<T>(f[3 * k]) * gcol[0] + static_cast<T>(f[3 * k + 1]) * gcol[1] +
            static_cast<T>(f[3 * k + 2]) * gcol[2];
          gd[0] += dY[k][0] * fg;
          gd[1] += dY[k][1] * fg;
          gd[2] += dY[k][2] * fg;
        }
        const T dd = d[0] * gd[0] + d[1] * gd[1] + d[2] * gd[2];
        for (int k = 0; k < 3; ++k)
        {
          gmu[k] += (gd[k] - d[k] * dd) / len;
        }
      }
    }
    for (int k = 0; k < 3; ++k)
    {
      gradients.Positions[3 * i + k] = gmu[k];
    }
  }
}

//------------------------------------------------------------------------------
template <typename T>
void RasterBackward(const GaussianCloud& cloud,
  const ViewProjection<T>& projection,
  const TileBins& bins,
  const RasterSettings& settings,
  const RasterImage<T>& image,
  const T* dLdImage,
  GaussianGradients<T>& gradients,
  const BackwardSettings& options)
{
  CompositeBackward(projection, bins, settings, image, dLdImage, gradients.Projected, options);
  ProjectBackward(cloud, projection, settings, gradients.Projected, gradients, options);
}

template struct GaussianGradients<float>;
template struct GaussianGradients<double>;
template void CompositeBackward<float>(const ViewProjection<float>&,
  const TileBins&,
  const RasterSettings&,
  const RasterImage<float>&,
  const float*,
  ProjectedGradients<float>&,
  const BackwardSettings&);
template void CompositeBackward<double>(const ViewProjection<double>&,
  const TileBins&,
  const RasterSettings&,
  const RasterImage<double>&,
  const double*,
  ProjectedGradients<double>&,
  const BackwardSettings&);
template void CompositeForward<float>(const ViewProjection<float>&,
  const TileBins&,
  const RasterSettings&,
  RasterImage<float>&,
  const BackwardSettings&,
  BackwardWorkspace<float>*);
template void CompositeForward<double>(const ViewProjection<double>&,
  const TileBins&,
  const RasterSettings&,
  RasterImage<double>&,
  const BackwardSettings&,
  BackwardWorkspace<double>*);
template void ProjectBackward<float>(const GaussianCloud&,
  const ViewProjection<float>&,
  const RasterSettings&,
  const ProjectedGradients<float>&,
  GaussianGradients<float>&,
  const BackwardSettings&);
template void ProjectBackward<double>(const GaussianCloud&,
  const ViewProjection<double>&,
  const RasterSettings&,
  const ProjectedGradients<double>&,
  GaussianGradients<double>&,
  const BackwardSettings&);
template void RasterBackward<float>(const GaussianCloud&,
  const ViewProjection<float>&,
  const TileBins&,
  const RasterSettings&,
  const RasterImage<float>&,
  const float*,
  GaussianGradients<float>&,
  const BackwardSettings&);
template void RasterBackward<double>(const GaussianCloud&,
  const ViewProjection<double>&,
  const TileBins&,
  const RasterSettings&,
  const RasterImage<double>&,
  const double*,
  GaussianGradients<double>&,
  const BackwardSettings&);

} // namespace vis4gs

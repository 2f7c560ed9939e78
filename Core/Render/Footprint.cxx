// SPDX-License-Identifier: BSD-3-Clause
#include "Footprint.h"

#include "KernelIsa.h"
#include "MultiViewData.h"
#include "RasterBounds.h"
#include "ThreadCount.h"

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>

namespace vis4gs
{

namespace
{

//------------------------------------------------------------------------------
// Vectorised footprint of one float Gaussian (AVX2, 8 pixels of a row at a time). Each lane
// computes KernelPower / KernelAlpha (RasterKernel.h) with the same float operations in the
// same order as the scalar loop (the library is built with -ffp-contract=off), so every pixel
// decision is bit-identical; the pixels found are then visited in ascending x, so the map sum
// is accumulated in the same order (row by row, left to right) as the scalar and brute-force
// paths and is bit-identical too.
typedef float F8 __attribute__((vector_size(32)));
typedef std::int32_t I8 __attribute__((vector_size(32)));

VIS4GS_INLINE_AVX2 F8 FootprintExp8(F8 x)
{
  raster::KernelExpLanes<F8, I8>(x);
  return x;
}

// The alpha test of KernelAlpha for 8 pixels given their powers. Most lanes are decided
// without the exponential: alpha = min(0.99, o e^power) >= 1/255 holds exactly when
// power >= ln(1/(255 o)) = level, and the computed alpha (KernelExp within 2 ulp, one
// rounded product) can only disagree with that within about 1e-6 of the level. Lanes with
// power <= 0 and power >= level + 1e-4 are therefore in Omega, lanes with power > 0 or
// power <= level - 1e-4 are not; when a lane falls in the band between (or is NaN) the
// whole group is evaluated with the exact kernel arithmetic.
VIS4GS_INLINE_AVX2 I8 AlphaTest8(F8 power, float opacity, float inside, float outside)
{
  const I8 nonPositive = power <= 0.0f;
  const I8 surelyIn = nonPositive & (power >= inside);
  const I8 surelyOut = (power > 0.0f) | (power <= outside);
  if (_mm256_movemask_ps(reinterpret_cast<__m256>(~(surelyIn | surelyOut))) == 0)
  {
    return surelyIn;
  }
  const F8 e = FootprintExp8(nonPositive ? power : F8{});
  const F8 a = opacity * e;
  const F8 alpha = a < float(raster::MaxAlpha) ? a : F8{} + float(raster::MaxAlpha);
  return nonPositive & (alpha >= raster::MinAlpha<float>());
}

// Pixels [xa, xb] of row y: counts those in Omega and adds their map values, left to right.
template <typename Acc>
VIS4GS_TARGET_AVX2 void FootprintRowAvx2(const ProjectedGaussian<float>& g,
  bool rasterMode,
  float inside,
  float outside,
  int y,
  int xa,
  int xb,
  int W,
  const float* map,
  std::uint32_t& count,
  Acc& sum)
{
  const F8 lane = { 0, 1, 2, 3, 4, 5, 6, 7 };
  const float dy = g.V - static_cast<float>(y);
  const float cdd = g.ConicC * dy * dy;
  const float* row = map ? map + static_cast<std::size_t>(y) * W : nullptr;
  for (int x0 = xa; x0 <= xb; x0 += 8)
  {
    const F8 px = static_cast<float>(x0) + lane;
    const F8 dx = g.U - px;
    const F8 power = -0.5f * (g.ConicA * dx * dx + cdd) - g.ConicB * dx * dy;
    I8 in;
    if (rasterMode)
    {
      in = AlphaTest8(power, g.Opacity, inside, outside);
    }
    else
    {
      in = power >= -4.5f;
    }
    unsigned bits = static_cast<unsigned>(_mm256_movemask_ps(reinterpret_cast<__m256>(in)));
    const int valid = xb - x0 + 1;
    if (valid < 8)
    {
      bits &= (1u << valid) - 1u;
    }
    count += static_cast<std::uint32_t>(__builtin_popcount(bits));
    if (row)
    {
      while (bits != 0)
      {
        const int l = __builtin_ctz(bits);
        bits &= bits - 1;
        sum += static_cast<Acc>(row[x0 + l]);
      }
    }
  }
}

// Lane j of a packed box of width w (1..8) is pixel (j % w, j / w): rows are packed
// back to back, so a small box costs ceil(w h / 8) evaluations and lane order is row-major.
struct BoxLanes
{
  std::int32_t Col[8][80]; // 64 lanes at most, read 8 (AVX2) or 16 (AVX-512) at a time
  std::int32_t Row[8][80];
  BoxLanes()
  {
    for (int w = 1; w <= 8; ++w)
    {
      for (int j = 0; j < 80; ++j)
      {
        this->Col[w - 1][j] = j % w;
        this->Row[w - 1][j] = j / w;
      }
    }
  }
};
const BoxLanes PackedLanes;

// Pixels [xa, xa + w) x [ya, ya + h) (w <= 8, w h <= 64, inside the image), packed 8 at a
// time. Counts the pixels in Omega and adds their map values in row-major order, visiting
// only the footprint's pixels, as the scalar path does.
template <typename Acc>
VIS4GS_TARGET_AVX2 void FootprintBoxAvx2(const ProjectedGaussian<float>& g,
  bool rasterMode,
  float inside,
  float outside,
  int xa,
  int ya,
  int w,
  int h,
  int W,
  const float* map,
  std::uint32_t& count,
  Acc& sum)
{
  const int lanes = w * h;
  const std::int32_t* colLut = PackedLanes.Col[w - 1];
  const std::int32_t* rowLut = PackedLanes.Row[w - 1];
  const I8 laneIndex = { 0, 1, 2, 3, 4, 5, 6, 7 };
  for (int j0 = 0; j0 < lanes; j0 += 8)
  {
    I8 col, row;
    std::memcpy(&col, colLut + j0, sizeof(col));
    std::memcpy(&row, rowLut + j0, sizeof(row));
    const F8 px = __builtin_convertvector(col + xa, F8);
    const F8 py = __builtin_convertvector(row + ya, F8);
    const F8 dx = g.U - px;
    const F8 dy = g.V - py;
    const F8 power = -0.5f * (g.ConicA * dx * dx + g.ConicC * dy * dy) - g.ConicB * dx * dy;
    I8 in;
    if (rasterMode)
    {
      in = AlphaTest8(power, g.Opacity, inside, outside);
    }
    else
    {
      in = power >= -4.5f;
    }
    in &= (laneIndex + j0) < lanes;
    const unsigned bits = static_cast<unsigned>(_mm256_movemask_ps(reinterpret_cast<__m256>(in)));
    count += static_cast<std::uint32_t>(__builtin_popcount(bits));
    if (map && bits != 0)
    {
      const I8 index = (row + ya) * W + col + xa;
      const F8 values = reinterpret_cast<F8>(_mm256_mask_i32gather_ps(_mm256_setzero_ps(),
        map,
        reinterpret_cast<__m256i>(index),
        reinterpret_cast<__m256>(in),
        4));
      // Only the lanes in Omega: the skipped lanes would add +0.0, which leaves the sum
      // unchanged (it starts at +0.0 and can never become -0.0 in round-to-nearest).
      unsigned set = bits;
      while (set != 0)
      {
        const int l = __builtin_ctz(set);
        set &= set - 1;
        sum += static_cast<Acc>(values[l]);
      }
    }
  }
}

//------------------------------------------------------------------------------
// The packed box with AVX-512, 16 pixels per vector: the same lanes (pixel j of the box is
// (j % w, j / w)), the same float operations per lane and the same alpha test as the AVX2
// path, and the pixels found are summed in the same row-major order, so counts and sums are
// bit-identical to it (and to the scalar and brute-force paths).
typedef float F16 __attribute__((vector_size(64)));
typedef std::int32_t I16 __attribute__((vector_size(64)));

VIS4GS_INLINE_AVX512 unsigned LaneBits16(I16 m)
{
  return static_cast<unsigned>(_mm512_movepi32_mask(reinterpret_cast<__m512i>(m)));
}

VIS4GS_INLINE_AVX512 F16 SelectF16(I16 m, F16 a, F16 b)
{
  return reinterpret_cast<F16>((reinterpret_cast<I16>(a) & m) | (reinterpret_cast<I16>(b) & ~m));
}

VIS4GS_INLINE_AVX512 F16 FootprintExp16(F16 x)
{
  // Called from here, the always-inlined comparisons take this function's instruction set.
  raster::KernelExpLanes<F16, I16>(x);
  return x;
}

// AlphaTest8 on 16 lanes (same decisions lane by lane), as a bit mask.
VIS4GS_INLINE_AVX512 unsigned AlphaTest16(F16 power, float opacity, float inside, float outside)
{
  const I16 nonPositive = power <= 0.0f;
  const I16 surelyIn = nonPositive & (power >= inside);
  const I16 surelyOut = (power > 0.0f) | (power <= outside);
  if (LaneBits16(~(surelyIn | surelyOut)) == 0)
  {
    return LaneBits16(surelyIn);
  }
  const F16 e = FootprintExp16(SelectF16(nonPositive, power, F16{}));
  const F16 a = opacity * e;
  const F16 alpha = SelectF16(a < float(raster::MaxAlpha), a, F16{} + float(raster::MaxAlpha));
  return LaneBits16(nonPositive & (alpha >= raster::MinAlpha<float>()));
}

template <typename Acc>
VIS4GS_TARGET_AVX512 void FootprintBoxAvx512(const ProjectedGaussian<float>& g,
  bool rasterMode,
  float inside,
  float outside,
  int xa,
  int ya,
  int w,
  int h,
  int W,
  const float* map,
  std::uint32_t& count,
  Acc& sum)
{
  const int lanes = w * h;
  const std::int32_t* colLut = PackedLanes.Col[w - 1];
  const std::int32_t* rowLut = PackedLanes.Row[w - 1];
  const I16 laneIndex = { 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15 };
  for (int j0 = 0; j0 < lanes; j0 += 16)
  {
    I16 col, row;
    std::memcpy(&col, colLut + j0, sizeof(col));
    std::memcpy(&row, rowLut + j0, sizeof(row));
    const F16 px = __builtin_convertvector(col + xa, F16);
    const F16 py = __builtin_convertvector(row + ya, F16);
    const F16 dx = g.U - px;
    const F16 dy = g.V - py;
    const F16 power = -0.5f * (g.ConicA * dx * dx + g.ConicC * dy * dy) - g.ConicB * dx * dy;
    unsigned bits =
      rasterMode ? AlphaTest16(power, g.Opacity, inside, outside) : LaneBits16(power >= -4.5f);
    bits &= LaneBits16((laneIndex + j0) < lanes);
    count += static_cast<std::uint32_t>(__builtin_popcount(bits));
    if (map && bits != 0)
    {
      const I16 index = (row + ya) * W + col + xa;
      const F16 values = reinterpret_cast<F16>(_mm512_mask_i32gather_ps(_mm512_setzero_ps(),
        static_cast<__mmask16>(bits),
        reinterpret_cast<__m512i>(index),
        map,
        4));
      // Only the lanes in Omega, in ascending order (row-major), as the AVX2 path.
      unsigned set = bits;
      while (set != 0)
      {
        const int l = __builtin_ctz(set);
        set &= set - 1;
        sum += static_cast<Acc>(values[l]);
      }
    }
  }
}

template <typename T>
constexpr bool IsFloat()
{
  return std::is_same<T, float>::value;
}

// The float Gaussian of the vector path (which runs only for float projections).
inline const ProjectedGaussian<float>& FloatGaussian(const ProjectedGaussian<float>& g)
{
  return g;
}
inline const ProjectedGaussian<float>& FloatGaussian(const ProjectedGaussian<double>&)
{
  throw std::logic_error("the footprint vector path is float only");
}

// Bounding box of the conservative ellipse of RasterBounds.h MakeSpanBounds (the same
// shrunken conic and lowered level, hence the same proof: outside it the computed power
// stays below the level), computed directly: x within U +- xE, y within V +- yE, widened by
// 0.01 pixel for the rounding of this double computation (errors of order 1e-12 pixel).
// False wherever MakeSpanBounds reports no bound, or when the box is large (the caller then
// takes the per-row spans).
template <typename T>
bool EllipseBox(T u, T v, T a, T b, T c, double level, int& xMin, int& xMax, int& yMin, int& yMax)
{
  const double U = u, V = v, ad = a, bd = b, cd = c;
  if (!(std::abs(U) < 1e8 && std::abs(V) < 1e8) || !(level <= 0) || !std::isfinite(ad) ||
    !std::isfinite(bd) || !std::isfinite(cd))
  {
    return false;
  }
  const double eta = 4.0 * std::numeric_limits<T>::epsilon();
  const double k = ad + cd + 2.0 * std::abs(bd);
  const double A = ad - 2.0 * eta * k;
  const double C = cd - 2.0 * eta * k;
  if (!(A > 1e-14 && C > 1e-14))
  {
    return false;
  }
  const double det = A * C - bd * bd;
  if (!(det > 1e-9 * A * C))
  {
    return false;
  }
  const double q = -2.0 * (level - 1e-5) / det;
  const double xE = std::sqrt(q * C);
  const double yE = std::sqrt(q * A);
  if (!(xE < 8.0 && yE < 64.0))
  {
    return false;
  }
  constexpr double margin = 0.01;
  xMin = static_cast<int>(std::floor(U - xE - margin));
  xMax = static_cast<int>(std::ceil(U + xE + margin));
  yMin = static_cast<int>(std::floor(V - yE - margin));
  yMax = static_cast<int>(std::ceil(V + yE + margin));
  return true;
}

//------------------------------------------------------------------------------
// Footprint of one visible Gaussian: |Omega| into @p cnt, the map sum into @p sum (row by
// row, left to right), kernels evaluated into @p evals. @p givenLevel, when not null, is the
// Gaussian's alpha level min(0, ln(1/(255 o))) already computed (rasteriser mode, o >= 1/255).
// EllipseBox() computed ahead for a batch of Gaussians (the same call, so the same box).
struct BoxHint
{
  bool Ok = false;
  int X0 = 0, X1 = 0, Y0 = 0, Y1 = 0;
};

template <typename T, typename Acc>
inline void FootprintOne(const ProjectedGaussian<T>& g,
  const FootprintOptions& opt,
  int vector,
  int W,
  int H,
  const float* map,
  const double* givenLevel,
  std::uint32_t& cnt,
  Acc& sum,
  std::uint64_t& evals,
  const BoxHint* hint = nullptr)
{
  const bool rasterMode = opt.Mode == FootprintMode::Rasterizer;
  cnt = 0;
  sum = 0;
  evals = 0;
  int xLo, xHi, yLo, yHi;
  double level;
  if (rasterMode)
  {
    if (!(g.Opacity >= raster::MinAlpha<T>()))
    {
      return; // alpha <= o < 1/255 everywhere
    }
    xLo = g.TileRect[0] * raster::TileSize;
    yLo = g.TileRect[1] * raster::TileSize;
    xHi = std::min(g.TileRect[2] * raster::TileSize, W) - 1;
    yHi = std::min(g.TileRect[3] * raster::TileSize, H) - 1;
    level = givenLevel
      ? *givenLevel
      : std::min(0.0, std::log(raster::MinAlpha<double>() / static_cast<double>(g.Opacity)));
  }
  else
  {
    const double A = g.ConicA, B = g.ConicB, C = g.ConicC;
    if (!(A > 0 && C > 0 && A * C - B * B > 0))
    {
      return; // no ellipse
    }
    xLo = 0;
    yLo = 0;
    xHi = W - 1;
    yHi = H - 1;
    level = -4.5;
  }
  const T minEllipse = T(-4.5);
  // Power band of the exact alpha test (AlphaTest8); unused in the ellipse mode.
  const float inside = static_cast<float>(level + 1e-4);
  const float outside = static_cast<float>(level - 1e-4);
  bool done = false;
  int bx0, bx1, by0, by1;
  bool boxed = false;
  if (vector && hint)
  {
    boxed = hint->Ok;
    bx0 = hint->X0;
    bx1 = hint->X1;
    by0 = hint->Y0;
    by1 = hint->Y1;
  }
  else if (vector)
  {
    boxed = EllipseBox<T>(g.U, g.V, g.ConicA, g.ConicB, g.ConicC, level, bx0, bx1, by0, by1);
  }
  if (boxed)
  {
    // Small ellipse (the common case at low resolution): its bounding box, clipped to the
    // tile rectangle and the image, is evaluated in packed lanes without per-row work.
    const int xa = std::max(xLo, bx0), xb = std::min(xHi, bx1);
    const int ya = std::max(yLo, by0), yb = std::min(yHi, by1);
    const int bw = xb - xa + 1, bh = yb - ya + 1;
    if (bw <= 0 || bh <= 0)
    {
      done = true; // empty
    }
    else if (bw <= 8 && bw * bh <= 64)
    {
      if (vector >= 3)
      {
        FootprintBoxAvx512<Acc>(
          FloatGaussian(g), rasterMode, inside, outside, xa, ya, bw, bh, W, map, cnt, sum);
        evals += static_cast<std::uint64_t>((bw * bh + 15) / 16 * 16);
      }
      else
      {
        FootprintBoxAvx2<Acc>(
          FloatGaussian(g), rasterMode, inside, outside, xa, ya, bw, bh, W, map, cnt, sum);
        evals += static_cast<std::uint64_t>((bw * bh + 7) / 8 * 8);
      }
      done = true;
    }
  }
  if (done)
  {
    return;
  }
  raster::detail::SpanBounds sb;
  if (!opt.BruteForce)
  {
    sb = raster::detail::MakeSpanBounds<T>(g.U, g.V, g.ConicA, g.ConicB, g.ConicC, level);
  }
  if (!sb.Bounded && !rasterMode && !opt.BruteForce)
  {
    // Unbounded ellipse mode: restrict to the 3-sigma radius box (the ellipse lies inside).
    const double r = g.Radius + 1.0;
    xLo = std::max(xLo, static_cast<int>(std::floor(std::max(-1e9, g.U - r))));
    xHi = std::min(xHi, static_cast<int>(std::ceil(std::min(1e9, g.U + r))));
    yLo = std::max(yLo, static_cast<int>(std::floor(std::max(-1e9, g.V - r))));
    yHi = std::min(yHi, static_cast<int>(std::ceil(std::min(1e9, g.V + r))));
  }
  if (sb.Bounded)
  {
    yLo = std::max(yLo, sb.RowMin);
    yHi = std::min(yHi, sb.RowMax);
  }
  for (int y = yLo; y <= yHi; ++y)
  {
    int xa = xLo, xb = xHi;
    if (sb.Bounded)
    {
      int ca, cb;
      if (!sb.Columns(y, ca, cb))
      {
        continue;
      }
      xa = std::max(xa, ca);
      xb = std::min(xb, cb);
    }
    if (vector)
    {
      if (xa <= xb)
      {
        FootprintRowAvx2<Acc>(
          FloatGaussian(g), rasterMode, inside, outside, y, xa, xb, W, map, cnt, sum);
      }
      evals += static_cast<std::uint64_t>(std::max(0, xb - xa + 1));
      continue;
    }
    const T py = static_cast<T>(y);
    for (int x = xa; x <= xb; ++x)
    {
      const T power =
        raster::KernelPower<T>(g.U, g.V, g.ConicA, g.ConicB, g.ConicC, static_cast<T>(x), py);
      const bool in =
        rasterMode ? raster::KernelAlpha<T>(g.Opacity, power) >= T(0) : power >= minEllipse;
      if (in)
      {
        ++cnt;
        if (map)
        {
          sum += static_cast<Acc>(map[static_cast<std::size_t>(y) * W + x]);
        }
      }
    }
    evals += static_cast<std::uint64_t>(std::max(0, xb - xa + 1));
  }
}

// 0: scalar, 2: AVX2 (rows and boxes of 8), 3: AVX2 rows and AVX-512 boxes of 16.
template <typename T>
int VectorLevel(const FootprintOptions& opt)
{
  if (!IsFloat<T>() || opt.BruteForce)
  {
    return 0;
  }
  switch (ResolveKernelIsa(opt.KernelIsa))
  {
    case KernelIsa::Avx512:
      return 3;
    case KernelIsa::Avx2:
      return 2;
    default:
      return 0;
  }
}

//------------------------------------------------------------------------------
template <typename T, typename Acc>
void FootprintPass(const ViewProjection<T>& proj,
  const FootprintOptions& opt,
  const float* map,
  FootprintStats& stats)
{
  const int W = proj.Width, H = proj.Height;
  const std::int64_t n = static_cast<std::int64_t>(proj.Gaussians.size());
  std::uint64_t total = 0, evaluated = 0;
  const int threads = ThreadCount(opt.Threads);
  const int vector = VectorLevel<T>(opt);
#pragma omp parallel for schedule(dynamic, 1024) num_threads(threads) reduction(+ : total, evaluated)
  for (std::int64_t ii = 0; ii < n; ++ii)
  {
    const std::size_t i = static_cast<std::size_t>(ii);
    const ProjectedGaussian<T>& g = proj.Gaussians[i];
    if (!g.IsVisible())
    {
      continue;
    }
    std::uint32_t cnt;
    Acc sum;
    std::uint64_t evals;
    FootprintOne<T, Acc>(g, opt, vector, W, H, map, nullptr, cnt, sum, evals);
    stats.PixelCount[i] = cnt;
    if (map)
    {
      stats.MapSum[i] = static_cast<double>(sum);
    }
    total += cnt;
    evaluated += evals;
  }
  stats.TotalPixels = total;
  stats.EvaluatedPixels = evaluated;
}

//------------------------------------------------------------------------------
// The same pass over a MultiViewRenderer's visible Gaussians (the per-Gaussian result does
// not depend on the order in which Gaussians are visited): @p store(slot, count, sum) takes
// each one's statistics. Returns the largest count.
template <typename Acc, typename Store>
std::uint32_t MultiViewFootprintPass(const MultiViewRenderer::Data& d,
  const FootprintOptions& opt,
  const float* map,
  const Store& store,
  std::uint64_t& total,
  std::uint64_t& evaluated)
{
  const int W = d.Camera.W, H = d.Camera.H;
  // Every slot (Gaussian index, padded to 16); the view's invisible ones are skipped.
  const std::int64_t nv = static_cast<std::int64_t>(d.Records.size());
  std::uint32_t largest = 0;
  const int threads = ThreadCount(opt.Threads);
  const int vector = VectorLevel<float>(opt);
  const bool rasterMode = opt.Mode == FootprintMode::Rasterizer;
  // Batches of 16: the boxes (EllipseBox, a chain of a division and two square roots per
  // Gaussian) are computed first in a tight loop, so that the chains of the batch overlap
  // instead of each waiting behind the previous Gaussian's pixel work.
  constexpr std::int64_t batch = 16;
  const std::int64_t batches = (nv + batch - 1) / batch;
#pragma omp parallel for schedule(dynamic, 64) num_threads(threads) reduction(+ : total, evaluated) reduction(max : largest)
  for (std::int64_t bb = 0; bb < batches; ++bb)
  {
    const std::int64_t first = bb * batch;
    const std::int64_t last = std::min(nv, first + batch);
    BoxHint hints[batch];
    if (vector)
    {
      for (std::int64_t ss = first; ss < last; ++ss)
      {
        const std::size_t s = static_cast<std::size_t>(ss);
        if (d.Records[s].Id == MultiViewRenderer::Data::Invisible)
        {
          continue;
        }
        const auto& k = d.Records[s].Kernel;
        BoxHint& h = hints[ss - first];
        h.Ok = EllipseBox<float>(
          k.U, k.V, k.A, k.B, k.C, rasterMode ? d.Records[s].Level : -4.5, h.X0, h.X1, h.Y0, h.Y1);
      }
    }
    // Every field FootprintOne reads is set below for each Gaussian (the others keep their
    // defaults): built once per batch instead of once per Gaussian.
    ProjectedGaussian<float> g;
    for (std::int64_t ss = first; ss < last; ++ss)
    {
      // Index order: records, levels and the outputs are all walked forwards.
      const std::size_t s = static_cast<std::size_t>(ss);
      const auto& rec = d.Records[s];
      if (rec.Id == MultiViewRenderer::Data::Invisible)
      {
        continue;
      }
      const auto& k = rec.Kernel;
      g.U = k.U;
      g.V = k.V;
      g.ConicA = k.A;
      g.ConicB = k.B;
      g.ConicC = k.C;
      g.Opacity = k.O;
      g.Radius = rec.Radius;
      for (int c = 0; c < 4; ++c)
      {
        g.TileRect[c] = rec.Rect[c];
      }
      g.Status = ProjectionStatus::Visible;
      std::uint32_t cnt;
      Acc sum;
      std::uint64_t evals;
      FootprintOne<float, Acc>(g,
        opt,
        vector,
        W,
        H,
        map,
        rasterMode ? &rec.Level : nullptr,
        cnt,
        sum,
        evals,
        vector ? &hints[ss - first] : nullptr);
      store(s, cnt, static_cast<double>(sum));
      largest = std::max(largest, cnt);
      total += cnt;
      evaluated += evals;
    }
  }
  return largest;
}

template <typename Store>
std::uint32_t MultiViewFootprints(const MultiViewRenderer::Data& d,
  const FootprintOptions& opt,
  const float* map,
  const Store& store,
  std::uint64_t& total,
  std::uint64_t& evaluated)
{
  total = evaluated = 0;
  return opt.Accumulation == FootprintAccumulation::Float
    ? MultiViewFootprintPass<float>(d, opt, map, store, total, evaluated)
    : MultiViewFootprintPass<double>(d, opt, map, store, total, evaluated);
}

} // namespace

//------------------------------------------------------------------------------
template <typename T>
FootprintStats ComputeFootprints(const ViewProjection<T>& projection,
  const FootprintOptions& options,
  const float* map)
{
  FootprintStats stats;
  const std::size_t n = projection.Gaussians.size();
  stats.PixelCount.assign(n, 0);
  if (map)
  {
    stats.MapSum.assign(n, 0.0);
  }
  if (options.Accumulation == FootprintAccumulation::Float)
  {
    FootprintPass<T, float>(projection, options, map, stats);
  }
  else
  {
    FootprintPass<T, double>(projection, options, map, stats);
  }
  return stats;
}

//------------------------------------------------------------------------------
void MultiViewRenderer::Footprints(const FootprintOptions& options,
  const float* map,
  FootprintStats& stats)
{
  const Data& d = *this->Impl;
  if (!d.HasView)
  {
    throw std::logic_error("MultiViewRenderer::Footprints: no view was projected");
  }
  stats.PixelCount.assign(d.Count, 0);
  if (map)
  {
    stats.MapSum.assign(d.Count, 0.0);
  }
  else
  {
    stats.MapSum.clear();
  }
  const Data::VisibleRecord* records = d.Records.data();
  MultiViewFootprints(
    d,
    options,
    map,
    [&stats, records, map](std::size_t s, std::uint32_t count, double sum)
    {
      stats.PixelCount[records[s].Id] = count;
      if (map)
      {
        stats.MapSum[records[s].Id] = sum;
      }
    },
    stats.TotalPixels,
    stats.EvaluatedPixels);
}

//------------------------------------------------------------------------------
void MultiViewRenderer::AddFootprints(const FootprintOptions& options,
  const float* map,
  const FootprintAdder& add)
{
  Data& d = *this->Impl;
  if (!d.HasView)
  {
    throw std::logic_error("MultiViewRenderer::AddFootprints: no view was projected");
  }
  // A record's kernel and radius are read before its statistics are known; its first 8 bytes
  // then keep the map sum and its radius the count.
  Data::VisibleRecord* records = d.Records.data();
  static_assert(sizeof(records->Kernel) >= sizeof(double) && alignof(Data::VisibleRecord) >= 8,
    "a map sum fits at the start of a record");
  std::uint64_t total = 0, evaluated = 0;
  const std::uint32_t largest = MultiViewFootprints(
    d,
    options,
    map,
    [records](std::size_t s, std::uint32_t count, double sum)
    {
      std::memcpy(&records[s].Kernel, &sum, sizeof(sum));
      std::memcpy(&records[s].Radius, &count, sizeof(count));
    },
    total,
    evaluated);
  d.HasView = false;
  const std::int64_t slots = static_cast<std::int64_t>(d.Records.size());
#pragma omp parallel for schedule(static) num_threads(ThreadCount(options.Threads))
  for (std::int64_t ss = 0; ss < slots; ++ss)
  {
    const Data::VisibleRecord& rec = records[ss];
    if (rec.Id == Data::Invisible)
    {
      continue;
    }
    double sum;
    std::uint32_t count;
    std::memcpy(&sum, &rec.Kernel, sizeof(sum));
    std::memcpy(&count, &rec.Radius, sizeof(count));
    add(rec.Id, count, map ? sum : 0.0, largest);
  }
}

template FootprintStats ComputeFootprints<float>(const ViewProjection<float>&,
  const FootprintOptions&,
  const float*);
template FootprintStats ComputeFootprints<double>(const ViewProjection<double>&,
  const FootprintOptions&,
  const float*);

} // namespace vis4gs

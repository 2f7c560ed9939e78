// SPDX-License-Identifier: BSD-3-Clause
#include "Loss.h"

#include "KernelIsa.h"
#include "ThreadCount.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace vis4gs
{
namespace
{

constexpr int Radius = 5; // 11x11 window, zero padding of 5
constexpr double C1 = 0.01 * 0.01;
constexpr double C2 = 0.03 * 0.03;

std::vector<double> MakeWindow()
{
  std::vector<double> w(2 * Radius + 1);
  double sum = 0;
  for (int i = 0; i <= 2 * Radius; ++i)
  {
    const double d = i - Radius;
    w[i] = std::exp(-(d * d) / (2.0 * 1.5 * 1.5));
    sum += w[i];
  }
  for (double& v : w)
  {
    v /= sum;
  }
  return w;
}

/**
 * Zero-padded "same" 2D convolution of a W x H plane with the separable window (rows then
 * columns). The window is symmetric, so this is also its own adjoint. @p tmp holds W*H.
 */
template <typename T>
inline __attribute__((always_inline)) void BlurBody(const T* in, T* out, T* tmp, int W, int H)
{
  const std::vector<double>& wd = SsimWindow1D();
  T w[2 * Radius + 1];
  for (int k = 0; k <= 2 * Radius; ++k)
  {
    w[k] = static_cast<T>(wd[k]);
  }
  // Horizontal. Interior columns (the whole window inside the row) tap by tap across the
  // row, which vectorises; each output still sums its taps from k = 0 up, starting at 0,
  // exactly as the per-pixel loop used for the border columns.
  const int xi0 = std::min(Radius, W), xi1 = std::max(xi0, W - Radius);
  for (int y = 0; y < H; ++y)
  {
    const T* row = in + static_cast<std::size_t>(y) * W;
    T* o = tmp + static_cast<std::size_t>(y) * W;
    auto border = [&](int x)
    {
      T s = 0;
      const int k0 = std::max(0, Radius - x), k1 = std::min(2 * Radius, W - 1 - x + Radius);
      for (int k = k0; k <= k1; ++k)
      {
        s += w[k] * row[x + k - Radius];
      }
      o[x] = s;
    };
    for (int x = 0; x < xi0; ++x)
    {
      border(x);
    }
    for (int x = xi1; x < W; ++x)
    {
      border(x);
    }
    for (int x = xi0; x < xi1; ++x)
    {
      o[x] = 0;
    }
    for (int k = 0; k <= 2 * Radius; ++k)
    {
      const T wk = w[k];
      const T* r = row + k - Radius;
      for (int x = xi0; x < xi1; ++x)
      {
        o[x] += wk * r[x];
      }
    }
  }
  // Vertical.
  for (int y = 0; y < H; ++y)
  {
    T* o = out + static_cast<std::size_t>(y) * W;
    for (int x = 0; x < W; ++x)
    {
      o[x] = 0;
    }
    const int k0 = std::max(0, Radius - y), k1 = std::min(2 * Radius, H - 1 - y + Radius);
    for (int k = k0; k <= k1; ++k)
    {
      const T* r = tmp + static_cast<std::size_t>(y + k - Radius) * W;
      const T wk = w[k];
      for (int x = 0; x < W; ++x)
      {
        o[x] += wk * r[x];
      }
    }
  }
}

// BlurBody compiled for baseline x86-64, AVX2 and AVX-512, chosen at run time. Its loops
// are element-wise (each output sums its taps in a fixed order; no contraction: the library
// is built with -ffp-contract=off), so the vector width changes no result bit.
template <typename T>
void BlurBaseline(const T* in, T* out, T* tmp, int W, int H)
{
  BlurBody(in, out, tmp, W, H);
}
template <typename T>
VIS4GS_TARGET_AVX2 void BlurAvx2(const T* in, T* out, T* tmp, int W, int H)
{
  BlurBody(in, out, tmp, W, H);
}
template <typename T>
VIS4GS_TARGET_AVX512 void BlurAvx512(const T* in, T* out, T* tmp, int W, int H)
{
  BlurBody(in, out, tmp, W, H);
}

template <typename T>
using BlurFunction = void (*)(const T*, T*, T*, int, int);

/// The instruction sets of KernelIsa.h (every variant gives the same bits).
template <typename T>
BlurFunction<T> SelectBlur(int isa)
{
  switch (ResolveKernelIsa(isa))
  {
    case KernelIsa::Avx512:
      return &BlurAvx512<T>;
    case KernelIsa::Avx2:
      return &BlurAvx2<T>;
    default:
      return &BlurBaseline<T>;
  }
}

// The per-pixel passes of SSIM over pixels [p0, p1) of one channel, element-wise like the
// blur and dispatched the same way (same bits on every instruction set).
template <typename T>
inline __attribute__((always_inline)) void SplitBody(const T* x,
  const T* y,
  int ch,
  std::size_t p0,
  std::size_t p1,
  T* px,
  T* py,
  T* pxx,
  T* pyy,
  T* pxy)
{
  for (std::size_t p = p0; p < p1; ++p)
  {
    const T a = x[3 * p + ch], c = y[3 * p + ch];
    px[p] = a;
    py[p] = c;
    pxx[p] = a * a;
    pyy[p] = c * c;
    pxy[p] = a * c;
  }
}

template <typename T>
inline __attribute__((always_inline)) void MapBody(std::size_t p0,
  std::size_t p1,
  const T* mx,
  const T* my,
  const T* sxx,
  const T* syy,
  const T* sxy,
  T* smap,
  T* gmu,
  T* gxx,
  T* gxy,
  bool gradient)
{
  for (std::size_t p = p0; p < p1; ++p)
  {
    const T mux = mx[p], muy = my[p];
    const T vx = sxx[p] - mux * mux, vy = syy[p] - muy * muy, cxy = sxy[p] - mux * muy;
    const T A1 = T(2) * mux * muy + T(C1), A2 = T(2) * cxy + T(C2);
    const T B1 = mux * mux + muy * muy + T(C1), B2 = vx + vy + T(C2);
    const T S = (A1 * A2) / (B1 * B2);
    smap[p] = S;
    if (gradient)
    {
      // The three gradient maps g_mu, g_xx, g_xy replace xx, yy, xy.
      gmu[p] = S * (T(2) * muy / A1 - T(2) * mux / B1 - T(2) * muy / A2 + T(2) * mux / B2);
      gxx[p] = -S / B2;
      gxy[p] = T(2) * S / A2;
    }
  }
}

template <typename T>
inline __attribute__((always_inline)) void GradBody(int ch,
  std::size_t p0,
  std::size_t p1,
  const T* bmu,
  const T* bxx,
  const T* bxy,
  const T* px,
  const T* py,
  T invN,
  T* gradSsim)
{
  for (std::size_t p = p0; p < p1; ++p)
  {
    gradSsim[3 * p + ch] = (bmu[p] + T(2) * px[p] * bxx[p] + py[p] * bxy[p]) * invN;
  }
}

#define VIS4GS_SSIM_PASSES(SUFFIX, TARGET)                                                         \
  template <typename T>                                                                            \
  TARGET void Split##SUFFIX(const T* x,                                                            \
    const T* y,                                                                                    \
    int ch,                                                                                        \
    std::size_t p0,                                                                                \
    std::size_t p1,                                                                                \
    T* px,                                                                                         \
    T* py,                                                                                         \
    T* pxx,                                                                                        \
    T* pyy,                                                                                        \
    T* pxy)                                                                                        \
  {                                                                                                \
    SplitBody(x, y, ch, p0, p1, px, py, pxx, pyy, pxy);                                            \
  }                                                                                                \
  template <typename T>                                                                            \
  TARGET void Map##SUFFIX(std::size_t p0,                                                          \
    std::size_t p1,                                                                                \
    const T* mx,                                                                                   \
    const T* my,                                                                                   \
    const T* sxx,                                                                                  \
    const T* syy,                                                                                  \
    const T* sxy,                                                                                  \
    T* smap,                                                                                       \
    T* gmu,                                                                                        \
    T* gxx,                                                                                        \
    T* gxy,                                                                                        \
    bool gradient)                                                                                 \
  {                                                                                                \
    MapBody(p0, p1, mx, my, sxx, syy, sxy, smap, gmu, gxx, gxy, gradient);                         \
  }                                                                                                \
  template <typename T>                                                                            \
  TARGET void Grad##SUFFIX(int ch,                                                                 \
    std::size_t p0,                                                                                \
    std::size_t p1,                                                                                \
    const T* bmu,                                                                                  \
    const T* bxx,                                                                                  \
    const T* bxy,                                                                                  \
    const T* px,                                                                                   \
    const T* py,                                                                                   \
    T invN,                                                                                        \
    T* gradSsim)                                                                                   \
  {                                                                                                \
    GradBody(ch, p0, p1, bmu, bxx, bxy, px, py, invN, gradSsim);                                   \
  }
VIS4GS_SSIM_PASSES(Baseline, )
VIS4GS_SSIM_PASSES(Avx2, VIS4GS_TARGET_AVX2)
VIS4GS_SSIM_PASSES(Avx512, VIS4GS_TARGET_AVX512)
#undef VIS4GS_SSIM_PASSES

/// The SSIM kernels of one instruction set (0 best, 1 baseline, 2 AVX2, 3 AVX-512).
template <typename T>
struct SsimKernels
{
  void (*Blur)(const T*, T*, T*, int, int);
  void (*Split)(const T*, const T*, int, std::size_t, std::size_t, T*, T*, T*, T*, T*);
  void (*Map)(std::size_t,
    std::size_t,
    const T*,
    const T*,
    const T*,
    const T*,
    const T*,
    T*,
    T*,
    T*,
    T*,
    bool);
  void (
    *Grad)(int, std::size_t, std::size_t, const T*, const T*, const T*, const T*, const T*, T, T*);

  static SsimKernels Select(int isa)
  {
    const BlurFunction<T> blur = SelectBlur<T>(isa);
    if (blur == &BlurAvx512<T>)
    {
      return { blur, &SplitAvx512<T>, &MapAvx512<T>, &GradAvx512<T> };
    }
    if (blur == &BlurAvx2<T>)
    {
      return { blur, &SplitAvx2<T>, &MapAvx2<T>, &GradAvx2<T> };
    }
    return { blur, &SplitBaseline<T>, &MapBaseline<T>, &GradBaseline<T> };
  }
  static const SsimKernels& Best()
  {
    static const SsimKernels best = Select(0);
    return best;
  }
};

/**
 * SSIM map sum per channel, and optionally the gradient of the mean SSIM with respect to x
 * (reference §3) written to @p gradSsim (3 per pixel, interleaved).
 */
template <typename T>
double SsimImpl(const T* x,
  const T* y,
  int W,
  int H,
  int threads,
  T* gradSsim,
  const SsimKernels<T>& kernels = SsimKernels<T>::Best(),
  const T* targetPlanes = nullptr,
  T* targetOut = nullptr,
  T* mapOut = nullptr)
{
  if (W <= 0 || H <= 0)
  {
    throw std::invalid_argument(
      "SSIM: image size " + std::to_string(W) + "x" + std::to_string(H) + " is not positive");
  }
  const std::size_t P = static_cast<std::size_t>(W) * H;
  const double N = 3.0 * static_cast<double>(P);
  const int nthreads = ThreadCount(threads);
  // Planes per channel: inputs x, y, xx, yy, xy (later reused as the three gradient maps),
  // their blurs mu_x, mu_y, s_xx, s_yy, s_xy, and the SSIM map. Kept between calls (the
  // trainer calls this every iteration; fresh pages cost more than the arithmetic), one set
  // per calling thread. The 15 (and 9) blurs are independent: they are the parallel work,
  // so every pixel sees the operations of the serial code and each channel's sum keeps its
  // pixel order (results do not depend on the thread count).
  enum
  {
    X,
    Y,
    XX,
    YY,
    XY,
    MX,
    MY,
    SXX,
    SYY,
    SXY,
    SMAP,
    PlanesPerChannel
  };
  thread_local std::vector<T> planes;
  planes.resize(static_cast<std::size_t>(3 * PlanesPerChannel + nthreads) * P);
  // OpenMP workers must use the caller's buffer: a thread_local named inside the parallel
  // regions would be each worker's own (empty) vector.
  T* const base = planes.data();
  auto plane = [base, P](int ch, int k) { return base + (ch * PlanesPerChannel + k) * P; };
  auto scratch = [base, P](int t) { return base + (3 * PlanesPerChannel + t) * P; };
  auto blurAll = [&](const int(*pairs)[2], int count)
  {
#pragma omp parallel for num_threads(nthreads) schedule(dynamic, 1)
    for (int task = 0; task < 3 * count; ++task)
    {
#ifdef _OPENMP
      const int t = omp_get_thread_num();
#else
      const int t = 0;
#endif
      const int ch = task / count, k = task % count;
      kernels.Blur(plane(ch, pairs[k][0]), plane(ch, pairs[k][1]), scratch(t), W, H);
    }
  };
  // Per-pixel passes in blocks of pixels, channel by channel inside a block, so that the
  // inner loops run over contiguous planes and vectorise.
  constexpr std::size_t Block = 4096;
  const std::int64_t blocks = static_cast<std::int64_t>((P + Block - 1) / Block);
#pragma omp parallel for num_threads(nthreads) schedule(static)
  for (std::int64_t b = 0; b < blocks; ++b)
  {
    const std::size_t p0 = static_cast<std::size_t>(b) * Block, p1 = std::min(P, p0 + Block);
    for (int ch = 0; ch < 3; ++ch)
    {
      kernels.Split(
        x, y, ch, p0, p1, plane(ch, X), plane(ch, Y), plane(ch, XX), plane(ch, YY), plane(ch, XY));
    }
  }
  static const int forward[5][2] = { { X, MX }, { XX, SXX }, { XY, SXY }, { Y, MY }, { YY, SYY } };
  // With the target's maps given, its two blurs per channel are not redone.
  blurAll(forward, targetPlanes ? 3 : 5);
  if (targetOut)
  {
    // PrepareSsimTarget(): keep the target's maps (blurred mean, blurred square).
    for (int ch = 0; ch < 3; ++ch)
    {
      std::copy(plane(ch, MY), plane(ch, MY) + P, targetOut + (2 * ch) * P);
      std::copy(plane(ch, SYY), plane(ch, SYY) + P, targetOut + (2 * ch + 1) * P);
    }
    return 0;
  }
#pragma omp parallel for num_threads(nthreads) schedule(static)
  for (std::int64_t b = 0; b < blocks; ++b)
  {
    const std::size_t p0 = static_cast<std::size_t>(b) * Block, p1 = std::min(P, p0 + Block);
    for (int ch = 0; ch < 3; ++ch)
    {
      kernels.Map(p0,
        p1,
        plane(ch, MX),
        targetPlanes ? targetPlanes + (2 * ch) * P : plane(ch, MY),
        plane(ch, SXX),
        targetPlanes ? targetPlanes + (2 * ch + 1) * P : plane(ch, SYY),
        plane(ch, SXY),
        plane(ch, SMAP),
        plane(ch, XX),
        plane(ch, YY),
        plane(ch, XY),
        gradSsim != nullptr);
    }
  }
  if (mapOut)
  {
    for (int ch = 0; ch < 3; ++ch)
    {
      std::copy(plane(ch, SMAP), plane(ch, SMAP) + P, mapOut + ch * P);
    }
  }
  // The three channel sums, each in pixel order, advanced together: three independent
  // addition chains instead of one at a time (same additions, same bits).
  double channelSum[3] = { 0, 0, 0 };
  {
    const T *s0 = plane(0, SMAP), *s1 = plane(1, SMAP), *s2 = plane(2, SMAP);
    double sum0 = 0, sum1 = 0, sum2 = 0;
    for (std::size_t p = 0; p < P; ++p)
    {
      sum0 += static_cast<double>(s0[p]);
      sum1 += static_cast<double>(s1[p]);
      sum2 += static_cast<double>(s2[p]);
    }
    channelSum[0] = sum0;
    channelSum[1] = sum1;
    channelSum[2] = sum2;
  }
  if (gradSsim)
  {
    static const int backward[3][2] = { { XX, MX }, { YY, MY }, { XY, SXX } };
    blurAll(backward, 3);
    const T invN = static_cast<T>(1.0 / N);
#pragma omp parallel for num_threads(nthreads) schedule(static)
    for (std::int64_t b = 0; b < blocks; ++b)
    {
      const std::size_t p0 = static_cast<std::size_t>(b) * Block, p1 = std::min(P, p0 + Block);
      for (int ch = 0; ch < 3; ++ch)
      {
        kernels.Grad(ch,
          p0,
          p1,
          plane(ch, MX),
          plane(ch, MY),
          plane(ch, SXX),
          plane(ch, X),
          plane(ch, Y),
          invN,
          gradSsim);
      }
    }
  }
  return (channelSum[0] + channelSum[1] + channelSum[2]) / N;
}

} // namespace

//------------------------------------------------------------------------------
const std::vector<double>& SsimWindow1D()
{
  static const std::vector<double> window = MakeWindow();
  return window;
}

//------------------------------------------------------------------------------
template <typename T>
void detail::SsimBlur(const T* in, T* out, int width, int height, int isa)
{
  std::vector<T> tmp(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  SelectBlur<T>(isa)(in, out, tmp.data(), width, height);
}

//------------------------------------------------------------------------------
template <typename T>
double detail::SsimOnIsa(const T* x, const T* y, int width, int height, int isa, T* gradient)
{
  return SsimImpl<T>(x, y, width, height, 1, gradient, SsimKernels<T>::Select(isa));
}

//------------------------------------------------------------------------------
template <typename T>
double L1Loss(const T* x, const T* y, std::size_t count)
{
  double s = 0;
  for (std::size_t i = 0; i < count; ++i)
  {
    s += std::abs(static_cast<double>(x[i]) - static_cast<double>(y[i]));
  }
  return count ? s / static_cast<double>(count) : 0.0;
}

//------------------------------------------------------------------------------
template <typename T>
double Ssim(const T* x, const T* y, int width, int height, int threads)
{
  return SsimImpl<T>(x, y, width, height, threads, nullptr);
}

//------------------------------------------------------------------------------
template <typename T>
void SsimMap(const T* x, const T* y, int width, int height, std::vector<T>& map, int threads)
{
  map.resize(3 * static_cast<std::size_t>(std::max(0, width)) *
    static_cast<std::size_t>(std::max(0, height)));
  SsimImpl<T>(
    x, y, width, height, threads, nullptr, SsimKernels<T>::Best(), nullptr, nullptr, map.data());
}

//------------------------------------------------------------------------------
template <typename T>
void PrepareSsimTarget(const T* y, int width, int height, SsimTarget<T>& target, int threads)
{
  const std::size_t P =
    static_cast<std::size_t>(std::max(0, width)) * static_cast<std::size_t>(std::max(0, height));
  target.Planes.resize(6 * P);
  SsimImpl<T>(
    y, y, width, height, threads, nullptr, SsimKernels<T>::Best(), nullptr, target.Planes.data());
  target.Image = y;
  target.Width = width;
  target.Height = height;
}

//------------------------------------------------------------------------------
template <typename T>
LossValues TrainingLoss(const T* x,
  const T* y,
  int width,
  int height,
  double lambda,
  std::vector<T>* gradient,
  int threads,
  const SsimTarget<T>* target)
{
  const std::size_t count = 3 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (target &&
    (target->Image != y || target->Width != width || target->Height != height ||
      target->Planes.size() != 2 * count))
  {
    throw std::invalid_argument("TrainingLoss: the SSIM target maps were made for another image");
  }
  const T* targetPlanes = target ? target->Planes.data() : nullptr;
  LossValues v;
  if (!gradient)
  {
    v.Ssim =
      SsimImpl<T>(x, y, width, height, threads, nullptr, SsimKernels<T>::Best(), targetPlanes);
    v.L1 = L1Loss(x, y, count);
    v.Loss = (1.0 - lambda) * v.L1 + lambda * (1.0 - v.Ssim);
    return v;
  }
  // SsimImpl writes every entry of the gradient: sized, not zeroed.
  gradient->resize(count);
  v.Ssim = SsimImpl<T>(
    x, y, width, height, threads, gradient->data(), SsimKernels<T>::Best(), targetPlanes);
  // The L1 term and its gradient in one pass (the L1 sum in the order of L1Loss()).
  const T l1w = static_cast<T>((1.0 - lambda) / static_cast<double>(count));
  const T sw = static_cast<T>(-lambda);
  T* g = gradient->data();
  // The L1 sum (one ordered chain) and the element-wise gradient update are independent:
  // with two threads or more they run side by side, the update vectorised (the same
  // operations per element; the sum in the order of L1Loss()).
  double l1 = 0;
  const auto sumL1 = [x, y, count]()
  {
    double sum = 0;
    for (std::size_t i = 0; i < count; ++i)
    {
      sum += std::abs(static_cast<double>(x[i]) - static_cast<double>(y[i]));
    }
    return sum;
  };
  const auto updateGradient = [x, y, g, l1w, sw](std::size_t i0, std::size_t i1)
  {
    for (std::size_t i = i0; i < i1; ++i)
    {
      const T d = x[i] - y[i];
      const T sign = d > T(0) ? T(1) : (d < T(0) ? T(-1) : T(0));
      g[i] = l1w * sign + sw * g[i];
    }
  };
  if (ThreadCount(threads) >= 2)
  {
#pragma omp parallel num_threads(2)
    {
#ifdef _OPENMP
      const int t = omp_get_thread_num();
      const int team = omp_get_num_threads();
#else
      const int t = 0;
      const int team = 1;
#endif
      if (t == 0)
      {
        l1 = sumL1();
        if (team < 2)
        {
          updateGradient(0, count); // the runtime gave a team of one
        }
      }
      else if (t == 1)
      {
        updateGradient(0, count);
      }
    }
  }
  else
  {
    l1 = sumL1();
    updateGradient(0, count);
  }
  v.L1 = count ? l1 / static_cast<double>(count) : 0.0;
  v.Loss = (1.0 - lambda) * v.L1 + lambda * (1.0 - v.Ssim);
  return v;
}

//------------------------------------------------------------------------------
template <typename T>
double Psnr(const T* x, const T* y, std::size_t count)
{
  double s = 0;
  for (std::size_t i = 0; i < count; ++i)
  {
    const double d = static_cast<double>(x[i]) - static_cast<double>(y[i]);
    s += d * d;
  }
  const double mse = count ? s / static_cast<double>(count) : 0.0;
  if (mse <= 0)
  {
    return std::numeric_limits<double>::infinity();
  }
  return 20.0 * std::log10(1.0 / std::sqrt(mse));
}

template void detail::SsimBlur<float>(const float*, float*, int, int, int);
template void detail::SsimBlur<double>(const double*, double*, int, int, int);
template double detail::SsimOnIsa<float>(const float*, const float*, int, int, int, float*);
template double detail::SsimOnIsa<double>(const double*, const double*, int, int, int, double*);
template double L1Loss<float>(const float*, const float*, std::size_t);
template double L1Loss<double>(const double*, const double*, std::size_t);
template double Ssim<float>(const float*, const float*, int, int, int);
template double Ssim<double>(const double*, const double*, int, int, int);
template void SsimMap<float>(const float*, const float*, int, int, std::vector<float>&, int);
template void SsimMap<double>(const double*, const double*, int, int, std::vector<double>&, int);
template void PrepareSsimTarget<float>(const float*, int, int, SsimTarget<float>&, int);
template void PrepareSsimTarget<double>(const double*, int, int, SsimTarget<double>&, int);
template LossValues TrainingLoss<float>(const float*,
  const float*,
  int,
  int,
  double,
  std::vector<float>*,
  int,
  const SsimTarget<float>*);
template LossValues TrainingLoss<double>(const double*,
  const double*,
  int,
  int,
  double,
  std::vector<double>*,
  int,
  const SsimTarget<double>*);
template double Psnr<float>(const float*, const float*, std::size_t);
template double Psnr<double>(const double*, const double*, std::size_t);

} // namespace vis4gs

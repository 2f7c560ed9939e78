// SPDX-License-Identifier: BSD-3-Clause
#include "Loss.h"

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

int ThreadCount(int requested)
{
#ifdef _OPENMP
  return requested > 0 ? requested : omp_get_max_threads();
#else
  (void)requested;
  return 1;
#endif
}

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
void Blur(const T* in, T* out, T* tmp, int W, int H)
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

/**
 * SSIM map sum per channel, and optionally the gradient of the mean SSIM with respect to x
 * (reference §3) written to @p gradSsim (3 per pixel, interleaved).
 */
template <typename T>
double SsimImpl(const T* x, const T* y, int W, int H, int threads, T* gradSsim)
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
      Blur(plane(ch, pairs[k][0]), plane(ch, pairs[k][1]), scratch(t), W, H);
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
      T *px = plane(ch, X), *py = plane(ch, Y), *pxx = plane(ch, XX), *pyy = plane(ch, YY),
        *pxy = plane(ch, XY);
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
  }
  static const int forward[5][2] = { { X, MX }, { Y, MY }, { XX, SXX }, { YY, SYY }, { XY, SXY } };
  blurAll(forward, 5);
#pragma omp parallel for num_threads(nthreads) schedule(static)
  for (std::int64_t b = 0; b < blocks; ++b)
  {
    const std::size_t p0 = static_cast<std::size_t>(b) * Block, p1 = std::min(P, p0 + Block);
    for (int ch = 0; ch < 3; ++ch)
    {
      const T *mx = plane(ch, MX), *my = plane(ch, MY), *sxx = plane(ch, SXX),
              *syy = plane(ch, SYY), *sxy = plane(ch, SXY);
      T *smap = plane(ch, SMAP), *gmu = plane(ch, XX), *gxx = plane(ch, YY), *gxy = plane(ch, XY);
      for (std::size_t p = p0; p < p1; ++p)
      {
        const T mux = mx[p], muy = my[p];
        const T vx = sxx[p] - mux * mux, vy = syy[p] - muy * muy, cxy = sxy[p] - mux * muy;
        const T A1 = T(2) * mux * muy + T(C1), A2 = T(2) * cxy + T(C2);
        const T B1 = mux * mux + muy * muy + T(C1), B2 = vx + vy + T(C2);
        const T S = (A1 * A2) / (B1 * B2);
        smap[p] = S;
        if (gradSsim)
        {
          // The three gradient maps g_mu, g_xx, g_xy replace xx, yy, xy.
          gmu[p] = S * (T(2) * muy / A1 - T(2) * mux / B1 - T(2) * muy / A2 + T(2) * mux / B2);
          gxx[p] = -S / B2;
          gxy[p] = T(2) * S / A2;
        }
      }
    }
  }
  double channelSum[3] = { 0, 0, 0 };
  for (int ch = 0; ch < 3; ++ch)
  {
    const T* smap = plane(ch, SMAP);
    double sum = 0;
    for (std::size_t p = 0; p < P; ++p)
    {
      sum += static_cast<double>(smap[p]);
    }
    channelSum[ch] = sum;
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
        const T *bmu = plane(ch, MX), *bxx = plane(ch, MY), *bxy = plane(ch, SXX),
                *px = plane(ch, X), *py = plane(ch, Y);
        for (std::size_t p = p0; p < p1; ++p)
        {
          gradSsim[3 * p + ch] = (bmu[p] + T(2) * px[p] * bxx[p] + py[p] * bxy[p]) * invN;
        }
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
LossValues TrainingLoss(const T* x,
  const T* y,
  int width,
  int height,
  double lambda,
  std::vector<T>* gradient,
  int threads)
{
  const std::size_t count = 3 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  LossValues v;
  if (gradient)
  {
    gradient->assign(count, T(0));
  }
  v.Ssim = SsimImpl<T>(x, y, width, height, threads, gradient ? gradient->data() : nullptr);
  v.L1 = L1Loss(x, y, count);
  v.Loss = (1.0 - lambda) * v.L1 + lambda * (1.0 - v.Ssim);
  if (gradient)
  {
    const T l1w = static_cast<T>((1.0 - lambda) / static_cast<double>(count));
    const T sw = static_cast<T>(-lambda);
    T* g = gradient->data();
    for (std::size_t i = 0; i < count; ++i)
    {
      const T d = x[i] - y[i];
      const T sign = d > T(0) ? T(1) : (d < T(0) ? T(-1) : T(0));
      g[i] = l1w * sign + sw * g[i];
    }
  }
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

template double L1Loss<float>(const float*, const float*, std::size_t);
template double L1Loss<double>(const double*, const double*, std::size_t);
template double Ssim<float>(const float*, const float*, int, int, int);
template double Ssim<double>(const double*, const double*, int, int, int);
template LossValues
TrainingLoss<float>(const float*, const float*, int, int, double, std::vector<float>*, int);
template LossValues
TrainingLoss<double>(const double*, const double*, int, int, double, std::vector<double>*, int);
template double Psnr<float>(const float*, const float*, std::size_t);
template double Psnr<double>(const double*, const double*, std::size_t);

} // namespace vis4gs

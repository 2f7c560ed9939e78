// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file RasterKernel.h
 * @brief Constants of the reference 3DGS rasteriser and the exact per-pixel arithmetic it
 * applies (reference §2.3, §2.6), shared by the tiled rasteriser, attribution, footprints,
 * the trainer's backward pass and the tests' naive re-implementations.
 *
 * Everything that decides whether a Gaussian touches a pixel goes through these inline
 * functions, so every module of Vis4GS makes bit-identical decisions for the same scalar
 * type. The library is compiled with -ffp-contract=off (no fused multiply-adds): the
 * vectorised paths and these scalar functions then round identically.
 */
#ifndef vis4gs_RasterKernel_h
#define vis4gs_RasterKernel_h

#include <cmath>
#include <cstdint>
#include <cstring>

namespace vis4gs
{
namespace raster
{

constexpr int TileSize = 16;          ///< BLOCK_X = BLOCK_Y
constexpr double NearPlane = 0.2;     ///< cull when view z <= 0.2
constexpr double Dilation = 0.3;      ///< low-pass filter added to the 2D covariance diagonal
constexpr double JacobianClamp = 1.3; ///< x/z, y/z clamped to +-1.3 tan(fov/2) in the Jacobian
constexpr double ProjectionZNear = 0.01;
constexpr double ProjectionZFar = 100.0;
constexpr double MaxAlpha = 0.99;
constexpr double TransmittanceStop = 1e-4;

/// alpha < 1/255 is skipped; the threshold is the float (or double) value of 1/255.
template <typename T>
constexpr T MinAlpha()
{
  return T(1) / T(255);
}

/**
 * exp() used for the Gaussian kernel. float: a Cephes-style polynomial with at most 2 ulp
 * error on [-87, 0] (CUDA's expf, used by the reference, also has up to 2 ulp), chosen
 * because it vectorises with bit-identical results; inputs below -87.3 give 0 (the true
 * value is below 1.2e-38, far below any alpha threshold). double: std::exp.
 * Defined for x <= 0; callers never pass positive or NaN arguments.
 */
inline float KernelExp(float x)
{
  if (!(x >= -87.33654f))
  {
    return 0.0f;
  }
  const float t = x * 1.44269504088896341f;
  const float n = (t + 12582912.0f) - 12582912.0f; // round to nearest integer
  float r = x - n * 0.693359375f;
  r = r - n * -2.12194440e-4f;
  const float r2 = r * r;
  float p = 1.9875691500E-4f;
  p = p * r + 1.3981999507E-3f;
  p = p * r + 8.3334519073E-3f;
  p = p * r + 4.1665795894E-2f;
  p = p * r + 1.6666665459E-1f;
  p = p * r + 5.0000001201E-1f;
  p = p * r2 + r + 1.0f;
  const std::int32_t bits = (static_cast<std::int32_t>(n) + 127) << 23;
  float scale;
  std::memcpy(&scale, &bits, sizeof(scale));
  return p * scale;
}

inline double KernelExp(double x)
{
  return std::exp(x);
}

/**
 * KernelExp(float) on a GCC vector of floats @p V (with @p I the int vector of the same lane
 * count), lane by lane with the same operations, so every lane equals the scalar result bit
 * for bit. The one copy every SIMD path (compositing, footprints, coverage, selection) uses;
 * always inlined, so it compiles with the caller's instruction set. In place through a
 * reference: clang refuses a vector of 32 or 64 bytes passed or returned by value by a
 * function without AVX / AVX-512 enabled, even an always-inlined one (the sanitizer build).
 */
template <typename V, typename I>
__attribute__((always_inline)) inline void KernelExpLanes(V& x)
{
  const I inRange = x >= -87.33654f;
  x = inRange ? x : V{};
  const V t = x * 1.44269504088896341f;
  const V n = (t + 12582912.0f) - 12582912.0f;
  V r = x - n * 0.693359375f;
  r = r - n * -2.12194440e-4f;
  const V r2 = r * r;
  V p = V{} + 1.9875691500E-4f;
  p = p * r + 1.3981999507E-3f;
  p = p * r + 8.3334519073E-3f;
  p = p * r + 4.1665795894E-2f;
  p = p * r + 1.6666665459E-1f;
  p = p * r + 5.0000001201E-1f;
  p = p * r2 + r + 1.0f;
  const I bits = (__builtin_convertvector(n, I) + 127) << 23;
  const V res = p * reinterpret_cast<V>(bits);
  x = inRange ? res : V{};
}

/// Float to int conversion without undefined behaviour: values are clamped to +-2^30 first
/// (pixel means and tile rectangles of Gaussians far outside the view).
template <typename T>
inline int ClampToInt(T x)
{
  const T big = T(1073741824.0);
  return static_cast<int>(x < -big ? -big : (x > big ? big : x));
}

/// The reference's ndc2Pix: computed in double (its literals are double), stored as T.
template <typename T>
inline T Ndc2Pix(T ndc, int size)
{
  return static_cast<T>(((static_cast<double>(ndc) + 1.0) * size - 1.0) * 0.5);
}

/// The Gaussian's exponent at pixel (px, py), in the reference's operation order.
template <typename T>
inline T KernelPower(T u, T v, T conicA, T conicB, T conicC, T px, T py)
{
  const T dx = u - px;
  const T dy = v - py;
  return T(-0.5) * (conicA * dx * dx + conicC * dy * dy) - conicB * dx * dy;
}

/**
 * alpha of a Gaussian at a pixel given its power, or a negative value when the reference
 * skips the pair (power > 0, or alpha < 1/255). A NaN power is skipped too (the reference's
 * fminf would turn it into 0.99; it cannot arise from finite, culled-checked projections
 * except through overflow, which Vis4GS treats as "no contribution").
 */
template <typename T>
inline T KernelAlpha(T opacity, T power)
{
  if (!(power <= T(0)))
  {
    return T(-1);
  }
  const T a = opacity * KernelExp(power);
  const T alpha = a < T(MaxAlpha) ? a : T(MaxAlpha);
  return alpha >= MinAlpha<T>() ? alpha : T(-1);
}

} // namespace raster
} // namespace vis4gs

#endif

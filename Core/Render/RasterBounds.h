// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file RasterBounds.h
 * @brief Internal: conservative analytic spans of the pixels where a Gaussian's kernel can
 * reach a level, used to skip pixels whose result is known without changing any result.
 *
 * For a positive-definite conic Q = [[A, B], [B, C]], the pixels where the *computed* power
 * can be >= L lie inside an ellipse with a slightly shrunken conic (see MakeSpanBounds for
 * the error model). Pixels outside the span are provably skipped by the exact kernel; pixels
 * inside are evaluated exactly, so using the spans never changes a result. Where no bound can
 * be guaranteed (indefinite conics, needles so thin that the float quadratic form loses all
 * precision, widths beyond 1e7 pixels) the bounds report "unbounded" and the caller evaluates
 * every pixel, as the reference does.
 */
#ifndef vis4gs_RasterBounds_h
#define vis4gs_RasterBounds_h

#include <algorithm>
#include <cmath>
#include <limits>

namespace vis4gs
{
namespace raster
{
namespace detail
{

/// Compact per-Gaussian data of the compositing loops (forward and the trainer's backward):
/// pixel-space mean (U, V), conic (A, B, C), opacity O, colour (R, G, Bl), view depth Z.
template <typename T>
struct KernelGaussian
{
  T U, V, A, B, C, O, R, G, Bl, Z;
};

struct SpanBounds
{
  bool Bounded = false;
  double U = 0, V = 0;
  double A = 0, B = 0, Det = 0;
  double InvA = 0, BOverA = 0;
  double NegTwoL = 0;          ///< -2 L' (> 0)
  int RowMin = 0, RowMax = -1; ///< inclusive candidate rows (not clipped)

  /// Candidate columns of row @p py (inclusive); false when the row has none.
  bool Columns(int py, int& xMin, int& xMax) const
  {
    const double dy = this->V - py;
    const double disc = this->NegTwoL * this->A - this->Det * dy * dy;
    if (disc < 0)
    {
      return false;
    }
    const double s = std::sqrt(disc) * this->InvA;
    // dx = u - px in [(-B dy - s)/A, (-B dy + s)/A]  =>  px in [u - dxMax, u - dxMin].
    const double centre = this->U + this->BOverA * dy;
    const double lo = centre - s - 1.0;
    const double hi = centre + s + 1.0;
    constexpr double big = 1073741824.0;
    xMin = static_cast<int>(std::floor(std::max(-big, std::min(big, lo))));
    xMax = static_cast<int>(std::ceil(std::max(-big, std::min(big, hi))));
    return xMin <= xMax;
  }
};

/**
 * A SpanBounds as the per-Gaussian arrays keep it (40 bytes instead of 88): without the mean
 * (U, V), which the compositing loops read from the Gaussian's kernel record (the same
 * values: MakeSpanBounds takes them from there), without InvA and BOverA, recomputed as
 * MakeSpanBounds computes them (1 / A and B / A in double: the same bits), and with Bounded
 * as NegTwoL > 0 (an unbounded SpanBounds holds NegTwoL 0, a bounded one -2 L' >= 2e-5).
 * Expand() gives back the SpanBounds field for field, so every decision made with it is
 * unchanged.
 */
struct SpanRecord
{
  double A = 0, B = 0, Det = 0;
  double NegTwoL = 0;
  int RowMin = 0, RowMax = -1;
  SpanRecord() = default;
  explicit SpanRecord(const SpanBounds& s)
    : A(s.A)
    , B(s.B)
    , Det(s.Det)
    , NegTwoL(s.Bounded ? s.NegTwoL : 0.0)
    , RowMin(s.RowMin)
    , RowMax(s.RowMax)
  {
  }
  /// The SpanBounds of a Gaussian with mean (@p u, @p v) (its kernel's U and V).
  SpanBounds Expand(double u, double v) const
  {
    SpanBounds s;
    s.RowMin = this->RowMin;
    s.RowMax = this->RowMax;
    if (this->NegTwoL > 0)
    {
      s.Bounded = true;
      s.U = u;
      s.V = v;
      s.A = this->A;
      s.B = this->B;
      s.Det = this->Det;
      s.InvA = 1.0 / this->A;
      s.BOverA = this->B / this->A;
      s.NegTwoL = this->NegTwoL;
    }
    return s;
  }
};

/**
 * Bounds for the level set power >= @p level (level <= 0) of a Gaussian with mean (u, v)
 * and conic (a, b, c) held in scalar type T.
 *
 * Error model: the kernel computes power = -0.5 ((A dx) dx + (C dy) dy) - (B dx) dy in T with
 * correctly rounded operations, dx = u - px and dy = v - py being themselves correctly
 * rounded, so the computed power differs from the exact one by at most eta * S(d) with
 * eta = 4 eps (twice the worst case) and S(d) = A dx^2 + C dy^2 + 2 |B dx dy| <= k |d|^2,
 * k = A + C + 2|B|. Hence the computed power can reach L only where
 * d^T (Q - 2 eta k I) d <= -2 L: an ellipse with a shrunken conic, when that conic is still
 * positive definite. L is lowered by 1e-5 for the rounding of exp and of o * e^power.
 */
template <typename T>
inline SpanBounds MakeSpanBounds(T u, T v, T a, T b, T c, double level)
{
  SpanBounds s;
  const double U = u, V = v;
  if (!std::isfinite(U) || !std::isfinite(V) || !(level <= 0) ||
    !std::isfinite(static_cast<double>(a)) || !std::isfinite(static_cast<double>(b)) ||
    !std::isfinite(static_cast<double>(c)))
  {
    return s;
  }
  const double eta = 4.0 * std::numeric_limits<T>::epsilon();
  const double k =
    static_cast<double>(a) + static_cast<double>(c) + 2.0 * std::abs(static_cast<double>(b));
  const double A = static_cast<double>(a) - 2.0 * eta * k;
  const double C = static_cast<double>(c) - 2.0 * eta * k;
  const double B = b;
  if (!(A > 1e-14 && C > 1e-14))
  {
    return s;
  }
  const double det = A * C - B * B;
  if (!(det > 1e-9 * A * C))
  {
    return s; // (nearly) singular shrunken conic: no useful bound, evaluate everything
  }
  const double L = level - 1e-5;
  s.NegTwoL = -2.0 * L;
  const double yE = std::sqrt(s.NegTwoL * A / det);
  constexpr double big = 1073741824.0;
  s.RowMin = static_cast<int>(std::floor(std::max(-big, std::min(big, V - yE - 1.0))));
  s.RowMax = static_cast<int>(std::ceil(std::max(-big, std::min(big, V + yE + 1.0))));
  s.U = U;
  s.V = V;
  s.A = A;
  s.B = B;
  s.Det = det;
  s.InvA = 1.0 / A;
  s.BOverA = B / A;
  s.Bounded = true;
  return s;
}

} // namespace detail
} // namespace raster
} // namespace vis4gs

#endif

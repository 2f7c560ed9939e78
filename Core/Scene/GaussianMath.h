// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file GaussianMath.h
 * @brief Activations and small per-Gaussian math shared by the readers, the rasteriser and
 * the diagnostics. Every function is defined for extreme inputs (logits and log-scales of
 * +-1000, zero quaternions) without overflow or NaN, as documented per function.
 */
#ifndef vis4gs_GaussianMath_h
#define vis4gs_GaussianMath_h

#include <array>
#include <cmath>
#include <limits>

namespace vis4gs
{

/// SH basis constants of the reference rasteriser (reference §2.4).
namespace sh
{
constexpr double C0 = 0.28209479177387814;
constexpr double C1 = 0.4886025119029199;
constexpr double C2[5] = { 1.0925484305920792,
  -1.0925484305920792,
  0.31539156525252005,
  -1.0925484305920792,
  0.5462742152960396 };
constexpr double C3[7] = { -0.5900435899266435,
  2.890611442640554,
  -0.4570457994644658,
  0.3731763325901154,
  -0.4570457994644658,
  1.445305721320277,
  -0.5900435899266435 };
}

/// Logistic sigmoid that never overflows: exact 0 < s < 1 for finite x, 0 and 1 at -inf/+inf.
template <typename T>
inline T Sigmoid(T x)
{
  if (x >= T(0))
  {
    return T(1) / (T(1) + std::exp(-x));
  }
  const T e = std::exp(x);
  return e / (T(1) + e);
}

/// Inverse sigmoid; logit(0) = -inf and logit(1) = +inf.
template <typename T>
inline T Logit(T p)
{
  return std::log(p) - std::log1p(-p);
}

/// exp of a log-scale, saturated at the largest finite value of T instead of overflowing to
/// infinity (log-scales of +1000 occur in broken scenes); NaN stays NaN.
template <typename T>
inline T ActivatedScale(T logScale)
{
  const T maxLog = std::log(std::numeric_limits<T>::max());
  return logScale > maxLog ? std::numeric_limits<T>::max() : std::exp(logScale);
}

/// Normalises a (w,x,y,z) quaternion the way PyTorch's F.normalize does (norm floored at
/// 1e-12). A zero quaternion stays zero; QuaternionToMatrix then gives the identity (every
/// product term vanishes), so the Gaussian is axis-aligned, exactly as in the reference.
template <typename T>
inline std::array<T, 4> NormalizeQuaternion(const T q[4])
{
  const T n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  const T d = n > T(1e-12) ? n : T(1e-12);
  return { q[0] / d, q[1] / d, q[2] / d, q[3] / d };
}

/// Row-major rotation matrix of a unit quaternion (w,x,y,z), reference §2.1.
template <typename T>
inline std::array<T, 9> QuaternionToMatrix(const std::array<T, 4>& q)
{
  const T w = q[0], x = q[1], y = q[2], z = q[3];
  return { T(1) - T(2) * (y * y + z * z),
    T(2) * (x * y - w * z),
    T(2) * (x * z + w * y),
    T(2) * (x * y + w * z),
    T(1) - T(2) * (x * x + z * z),
    T(2) * (y * z - w * x),
    T(2) * (x * z - w * y),
    T(2) * (y * z + w * x),
    T(1) - T(2) * (x * x + y * y) };
}

/**
 * 3D covariance R diag((m s)^2) R^T of a Gaussian from its stored log-scales and (w,x,y,z)
 * quaternion, with scale modifier @p m, as the upper triangle (xx, xy, xz, yy, yz, zz).
 * Reference §2.1 in the reference's operation order: M = diag(m s) R^T, Sigma = M^T M. The one
 * copy of the preparation that the rasteriser (scalar and lane projection), the fast coverage
 * and the splat mapper's attributes run, so they start from the same bits for the same T.
 */
template <typename T>
inline std::array<T, 6> GaussianCovariance(const float logScale[3], const float rotation[4], T m)
{
  const T s[3] = { m * std::exp(static_cast<T>(logScale[0])),
    m * std::exp(static_cast<T>(logScale[1])),
    m * std::exp(static_cast<T>(logScale[2])) };
  const T q[4] = { rotation[0], rotation[1], rotation[2], rotation[3] };
  const std::array<T, 9> R = QuaternionToMatrix<T>(NormalizeQuaternion<T>(q));
  T M[3][3]; // M[k][r] = s_k R_rk
  for (int k = 0; k < 3; ++k)
  {
    for (int r = 0; r < 3; ++r)
    {
      M[k][r] = s[k] * R[3 * r + k];
    }
  }
  auto sig = [&](int r, int c)
  { return M[0][r] * M[0][c] + M[1][r] * M[1][c] + M[2][r] * M[2][c]; };
  return { sig(0, 0), sig(0, 1), sig(0, 2), sig(1, 1), sig(1, 2), sig(2, 2) };
}

/**
 * SH colour (reference §2.4) of the coefficients @p sh (coefficient-major, 3 per
 * coefficient) of degree 0-3 in the unit direction @p dir, plus 0.5, in the reference's
 * operation order; not clamped (ViewColor clamps).
 */
template <typename T>
inline void ShColor(const float* sh, int degree, const T dir[3], T out[3])
{
  const T C0 = T(sh::C0), C1 = T(sh::C1);
  T f[16][3];
  const int k = (degree + 1) * (degree + 1);
  for (int i = 0; i < k; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      f[i][c] = static_cast<T>(sh[3 * i + c]);
    }
  }
  T r[3];
  for (int c = 0; c < 3; ++c)
  {
    r[c] = C0 * f[0][c];
  }
  if (degree > 0)
  {
    const T x = dir[0], y = dir[1], z = dir[2];
    for (int c = 0; c < 3; ++c)
    {
      r[c] = r[c] - C1 * y * f[1][c] + C1 * z * f[2][c] - C1 * x * f[3][c];
    }
    if (degree > 1)
    {
      const T xx = x * x, yy = y * y, zz = z * z;
      const T xy = x * y, yz = y * z, xz = x * z;
      for (int c = 0; c < 3; ++c)
      {
        r[c] = r[c] + T(sh::C2[0]) * xy * f[4][c] + T(sh::C2[1]) * yz * f[5][c] +
          T(sh::C2[2]) * (T(2) * zz - xx - yy) * f[6][c] + T(sh::C2[3]) * xz * f[7][c] +
          T(sh::C2[4]) * (xx - yy) * f[8][c];
      }
      if (degree > 2)
      {
        for (int c = 0; c < 3; ++c)
        {
          r[c] = r[c] + T(sh::C3[0]) * y * (T(3) * xx - yy) * f[9][c] +
            T(sh::C3[1]) * xy * z * f[10][c] + T(sh::C3[2]) * y * (T(4) * zz - xx - yy) * f[11][c] +
            T(sh::C3[3]) * z * (T(2) * zz - T(3) * xx - T(3) * yy) * f[12][c] +
            T(sh::C3[4]) * x * (T(4) * zz - xx - yy) * f[13][c] +
            T(sh::C3[5]) * z * (xx - yy) * f[14][c] +
            T(sh::C3[6]) * x * (xx - T(3) * yy) * f[15][c];
        }
      }
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    out[c] = r[c] + T(0.5);
  }
}

/**
 * Colour of the Gaussian at @p position seen from @p center: ShColor in the direction
 * (position - center) / |position - center| (the zero vector when the two coincide), clamped
 * at 0 as the reference does. Returns the channels the clamp changed (bit c for channel c).
 */
template <typename T>
inline unsigned ViewColor(const float* sh,
  int degree,
  const float position[3],
  const T center[3],
  T rgb[3])
{
  T dir[3] = { static_cast<T>(position[0]) - center[0],
    static_cast<T>(position[1]) - center[1],
    static_cast<T>(position[2]) - center[2] };
  const T len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
  for (T& d : dir)
  {
    d = len > T(0) ? d / len : T(0);
  }
  ShColor<T>(sh, degree, dir, rgb);
  unsigned clamped = 0;
  for (int c = 0; c < 3; ++c)
  {
    if (rgb[c] < T(0))
    {
      clamped |= 1u << c;
      rgb[c] = T(0);
    }
  }
  return clamped;
}

/// How the reference draws one Gaussian with special values (Documentation/special-values.md).
/// Drawn covers every case where the reference's arithmetic has an answer: opacity logit
/// +inf (opacity 1) and -inf (opacity 0, never reaches 1/255), log-scale -inf (scale 0: a
/// point dilated by +0.3 px^2), a zero quaternion (identity rotation), +-0 and denormals.
/// Every other reason names a parameter for which the reference has no answer (NaN or an
/// infinity that turns into NaN in the covariance or the projection); such a Gaussian is
/// skipped and counted per reason.
enum class GaussianClass : int
{
  Drawn = 0,
  NaNParameter,     ///< NaN in position, log-scale, rotation or opacity logit
  InfinitePosition, ///< +-inf position component
  InfiniteLogScale, ///< +inf log-scale: inf * 0 in the covariance
  InfiniteRotation, ///< +-inf quaternion component: inf / inf on normalisation
  Count
};

/// Classifies one Gaussian from its stored parameters (position xyz, log-scales, quaternion
/// wxyz, opacity logit). SH coefficients do not take part: the reference draws a Gaussian
/// with non-finite SH with whatever colour its arithmetic gives (NaN included).
template <typename T>
inline GaussianClass ClassifyGaussian(const T pos[3], const T logScale[3], const T rot[4], T logit)
{
  bool nan = std::isnan(logit);
  bool infPos = false, infScale = false, infRot = false;
  for (int k = 0; k < 3; ++k)
  {
    nan = nan || std::isnan(pos[k]) || std::isnan(logScale[k]);
    infPos = infPos || std::isinf(pos[k]);
    infScale = infScale || (std::isinf(logScale[k]) && logScale[k] > T(0));
  }
  for (int k = 0; k < 4; ++k)
  {
    nan = nan || std::isnan(rot[k]);
    infRot = infRot || std::isinf(rot[k]);
  }
  if (nan)
  {
    return GaussianClass::NaNParameter;
  }
  if (infPos)
  {
    return GaussianClass::InfinitePosition;
  }
  if (infScale)
  {
    return GaussianClass::InfiniteLogScale;
  }
  if (infRot)
  {
    return GaussianClass::InfiniteRotation;
  }
  return GaussianClass::Drawn;
}

} // namespace vis4gs

#endif

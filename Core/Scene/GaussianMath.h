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

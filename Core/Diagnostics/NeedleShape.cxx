// SPDX-License-Identifier: BSD-3-Clause
#include "NeedleShape.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vis4gs
{

//------------------------------------------------------------------------------
double ScaleEntropy(const double logScale[3])
{
  const double x[3] = { 2 * logScale[0], 2 * logScale[1], 2 * logScale[2] };
  if (std::isnan(x[0]) || std::isnan(x[1]) || std::isnan(x[2]))
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  const double m = std::max({ x[0], x[1], x[2] });
  // Equal variances (including all -inf): the uniform distribution, H = log 3. Returned
  // exactly so that a sphere has s = 0 exactly rather than a rounding residue.
  if (x[0] == x[1] && x[1] == x[2])
  {
    return std::log(3.0);
  }
  if (std::isinf(m))
  {
    // m = +inf: the infinite axes share the variance equally, the others get none.
    const int infinite = (x[0] == m) + (x[1] == m) + (x[2] == m);
    return std::log(static_cast<double>(infinite));
  }
  // Finite maximum: log q_k = x_k - logsumexp(x). -inf axes give q = 0 and contribute 0.
  double sum = 0;
  for (double v : x)
  {
    sum += std::exp(v - m);
  }
  const double lse = m + std::log(sum);
  double h = 0;
  for (double v : x)
  {
    const double logQ = v - lse;
    const double q = std::exp(logQ);
    if (q > 0)
    {
      h -= q * logQ;
    }
  }
  return std::max(0.0, std::min(h, std::log(3.0)));
}

//------------------------------------------------------------------------------
double EffectiveRank(const double logScale[3])
{
  const double h = ScaleEntropy(logScale);
  if (h == std::log(3.0))
  {
    return 3.0;
  }
  return std::exp(h);
}

//------------------------------------------------------------------------------
double NeedleShape(const double logScale[3])
{
  const double r = EffectiveRank(logScale);
  return std::isnan(r) ? r : std::max(0.0, std::min(1.0, (3.0 - r) / 2.0));
}

//------------------------------------------------------------------------------
void ComputeNeedleShapes(const float* logScales,
  std::size_t count,
  double* needleShape,
  double* effectiveRank)
{
  const long long n = static_cast<long long>(count);
#pragma omp parallel for schedule(static)
  for (long long i = 0; i < n; ++i)
  {
    const double s[3] = { logScales[3 * i], logScales[3 * i + 1], logScales[3 * i + 2] };
    needleShape[i] = NeedleShape(s);
    if (effectiveRank)
    {
      effectiveRank[i] = EffectiveRank(s);
    }
  }
}

} // namespace vis4gs

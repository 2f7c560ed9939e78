// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file NeedleShape.h
 * @brief Shape statistics of a Gaussian from its log-scales alone (no cameras needed).
 *
 * With q_k = sigma_k^2 / sum sigma^2 and H = -sum q_k log q_k (0 log 0 = 0):
 *   effective rank  r(g) = exp(H)            in [1, 3]  (reference §6.1)
 *   needle shape    s(g) = (3 - exp(H)) / 2  in [0, 1]  (DESIGN §4)
 * q and H are computed in the log domain (q = softmax(2 * LogScale), log q = 2 s - logsumexp),
 * in double precision, so log-scales of +-700 and beyond give finite, correct values.
 *
 * Defined cases:
 * - all three log-scales equal (any finite value): s = 0 and r = 3 exactly;
 * - one dominant axis: s -> 1; two equal dominant axes: s -> 1/2;
 * - +inf log-scales: the m infinite axes share the variance equally, s = (3 - m) / 2;
 * - -inf log-scales: that axis has zero variance (q = 0); all three -inf count as equal, s = 0;
 * - any NaN log-scale: NaN (callers flag it).
 */
#ifndef vis4gs_NeedleShape_h
#define vis4gs_NeedleShape_h

#include <cstddef>

namespace vis4gs
{

/// Shannon entropy H of q = softmax(2 * logScale) for one Gaussian (NaN if any input is NaN).
double ScaleEntropy(const double logScale[3]);

/// Effective rank exp(H) in [1, 3].
double EffectiveRank(const double logScale[3]);

/// Needle shape s = (3 - exp(H)) / 2 in [0, 1].
double NeedleShape(const double logScale[3]);

/// Needle shape of @p count Gaussians from float log-scales (3 per Gaussian), in parallel.
/// @p effectiveRank may be null; otherwise it receives exp(H) per Gaussian.
void ComputeNeedleShapes(const float* logScales,
  std::size_t count,
  double* needleShape,
  double* effectiveRank = nullptr);

} // namespace vis4gs

#endif

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SpecialValues.h
 * @brief Counts of a scene's special parameter values, per the table of
 * Documentation/special-values.md: what every layer skips (no answer in the reference's
 * arithmetic) and what it draws although it is special (opacity logit +-inf, log-scale -inf,
 * a zero quaternion). One pass over the cloud, so commands and filters can say exactly why
 * Gaussians are missing from a render, a score or a selection.
 */
#ifndef vis4gs_SpecialValues_h
#define vis4gs_SpecialValues_h

#include "GaussianCloud.h"
#include "GaussianMath.h"

#include <array>
#include <cstddef>
#include <string>

namespace vis4gs
{

struct SpecialValueCounts
{
  /// Gaussians per ClassifyGaussian class; index GaussianClass::Drawn counts the drawn ones.
  std::array<std::size_t, static_cast<int>(GaussianClass::Count)> ByClass{};
  /// Drawn Gaussians whose SH coefficients used at the counted degree hold +-inf or NaN: the
  /// reference would blend an inf/NaN colour into every pixel they reach, so renders skip them.
  std::size_t NonFiniteSH = 0;
  // Special values the reference draws (all among the drawn).
  std::size_t OpacityPlusInf = 0;   ///< sigmoid(+inf) = 1
  std::size_t OpacityMinusInf = 0;  ///< sigmoid(-inf) = 0: never reaches alpha 1/255
  std::size_t LogScaleMinusInf = 0; ///< exp(-inf) = 0 on some axis: flat or a dilated point
  std::size_t ZeroQuaternion = 0;   ///< normalises to 0, rotation matrix I

  /// Gaussians no layer draws or scores: every class but Drawn.
  std::size_t Skipped() const;
  /// Skipped() plus, for renders, NonFiniteSH.
  std::size_t SkippedByRender() const { return this->Skipped() + this->NonFiniteSH; }
};

/// A short name of a class ("NaN parameter", "infinite position", ...).
const char* GaussianClassName(GaussianClass c);

/**
 * Counts the special values of @p cloud. @p shDegree is the SH degree a render uses (clamped
 * to the cloud's); -1 leaves SH out (geometry-only users: scores, selection).
 */
SpecialValueCounts CountSpecialValues(const GaussianCloud& cloud, int shDegree = -1);

/// "3 skipped: 2 with a NaN parameter, 1 with an infinite position" or "" when none is
/// skipped; @p render adds the non-finite SH reason.
std::string DescribeSkipped(const SpecialValueCounts& counts, bool render);

/// "drawn as the reference does: 12 with opacity logit +inf (opacity 1), ..." or "" when none.
std::string DescribeDrawnSpecials(const SpecialValueCounts& counts);

} // namespace vis4gs

#endif

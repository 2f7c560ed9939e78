// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file StateComparison.h
 * @brief Two states of a reconstruction compared Gaussian by Gaussian (issue 20): two
 * iterations of one training log, or two logs or scenes of the same cameras, matched by their
 * stable ids (DESIGN §3; a scene without ids numbers its Gaussians 0..N-1, and RemoveGaussians()
 * keeps those numbers, so a scene and its cleaned copy match).
 *
 * A Gaussian only in the second state was born, one only in the first died; one in both moved
 * when its centre travelled more than Thresholds::Move (Euclidean, scene units), changed its
 * opacity when the activated opacity sigmoid(logit) changed by more than Thresholds::Opacity,
 * changed its scale when one axis' scale changed by a factor beyond exp(Thresholds::Scale),
 * i.e. |log s_b - log s_a| > Scale on some axis. Thresholds compare strictly, so the default 0
 * reports any change and bit-identical Gaussians are unchanged.
 *
 * The image figures of both states come from MeasureViewMetrics() (RemovalEffect.h), the
 * trainer's metric code.
 */
#ifndef vis4gs_StateComparison_h
#define vis4gs_StateComparison_h

#include "GaussianCloud.h"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace vis4gs
{

struct StateThresholds
{
  double Move = 0;    ///< centre distance, scene units
  double Opacity = 0; ///< change of the activated opacity
  double Scale = 0;   ///< largest |change of the natural log of a scale axis|
};

/// What happened to one Gaussian between the states; Moved, Opacity and Scale combine.
enum StateChange : std::uint8_t
{
  StateUnchanged = 0,
  StateMoved = 1,
  StateOpacityChanged = 2,
  StateScaleChanged = 4,
  StateBorn = 8,
  StateDied = 16
};

struct GaussianStateDifference
{
  std::int64_t Id = 0;
  std::uint8_t Change = StateUnchanged; ///< StateChange flags
  /// Index in the first / second state, or -1 where the Gaussian is not there.
  std::int64_t IndexA = -1, IndexB = -1;
  /// |centre b - centre a|; NaN for born and died Gaussians (also Opacity, Scale).
  double Move = std::numeric_limits<double>::quiet_NaN();
  /// sigmoid(logit b) - sigmoid(logit a), signed.
  double Opacity = std::numeric_limits<double>::quiet_NaN();
  /// The axis' log b - log a of largest magnitude, signed (log of the scale ratio).
  double Scale = std::numeric_limits<double>::quiet_NaN();
};

struct StateComparison
{
  std::size_t CountA = 0, CountB = 0;
  std::size_t Matched = 0; ///< ids in both states
  std::size_t Born = 0, Died = 0;
  std::size_t Moved = 0, OpacityChanged = 0, ScaleChanged = 0;
  std::size_t Unchanged = 0; ///< matched and under every threshold
  /// One row per id of either state, by increasing id.
  std::vector<GaussianStateDifference> Gaussians;
};

/// "unchanged", "born", "died", or the changes joined by '+' ("moved+opacity+scale").
std::string StateChangeName(std::uint8_t change);

/**
 * Compares @p a and @p b (positions, log scales and opacity logits must be loaded). Throws
 * std::invalid_argument naming the state and the id when a state holds an id twice, or when
 * an array is missing.
 */
StateComparison CompareStates(const GaussianCloud& a,
  const GaussianCloud& b,
  const StateThresholds& thresholds = StateThresholds());

} // namespace vis4gs

#endif

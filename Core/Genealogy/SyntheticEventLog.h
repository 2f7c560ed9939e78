// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SyntheticEventLog.h
 * @brief SYNTHETIC densification event logs for benchmarks and scale tests. The output is
 * NOT a real training log: it only mimics the schedule of the original 3DGS trainer's
 * adaptive density control (ADC); use it to measure speed and memory, never to draw
 * conclusions about real reconstructions.
 *
 * What follows the original trainer exactly (shared/reference/3dgs-reference.md §4.1, §4.3,
 * §4.4, §4.5):
 * - densification every 100 iterations from 600 to 14900 (`iteration > 500`,
 *   `iteration % 100 == 0`, `iteration < 15000`): 144 densification steps, nothing after;
 * - within a step: clones first (parents stay), then splits (2 children each, parents
 *   removed, clone and split parents disjoint, new clones never split), then prunes;
 *   rows in that order; children get consecutive new ids; split children are numbered
 *   "all first children, then all second children" as in densify_and_split;
 * - opacity resets at 3000, 6000, 9000, 12000 run *after* that iteration's densification,
 *   so the prune burst they cause appears at the next densification: 3100, 6100, 9100, 12100;
 * - a prune can remove any alive Gaussian, including one born in the same step.
 *
 * What is ASSUMED (figures we could not measure here; change them through the parameters):
 * - 54,275 initial Gaussians (the size of Mip-NeRF 360 Bicycle's COLMAP point cloud as
 *   commonly reported; not verified against the data set);
 * - 4,890,000 final Gaussians (the Bicycle figure of the Vis4GS issue / paper) and about
 *   10,000,000 Gaussians ever born (initial + clone/split children), also from the issue;
 * - 40 % of densified parents split, 60 % clone (SplitShare); the reference trainer decides
 *   per Gaussian by its size, so the real share varies with the scene;
 * - 35 % of all prunes fall in the four post-reset bursts (BurstPruneShare), the rest are
 *   spread over the steps in proportion to the current count;
 * - the count grows along the smoothstep 3u^2 - 2u^3 over the densification window (slow
 *   start, fastest mid-window, slowing before 15000), at most doubling per step;
 * - densified parents are drawn from the previous step's newborns with probability
 *   RecentParentBias (0.5) and uniformly otherwise, which produces the deep lineages of
 *   regions that keep densifying.
 * With these, prunes total (Total - N0)/(1 + SplitShare) - (Final - N0) and deaths
 * (splits + prunes) equal Total - Final: about 2.27M prunes, 2.84M splits and 4.26M clones.
 */
#ifndef vis4gs_SyntheticEventLog_h
#define vis4gs_SyntheticEventLog_h

#include "TrainingLogTypes.h"

#include <cstdint>

namespace vis4gs
{

/// Parameters of GenerateSyntheticEventLog (defaults: a Bicycle-sized run, see the file comment).
struct SyntheticLogParameters
{
  std::int64_t InitialGaussians = 54275;
  std::int64_t FinalGaussians = 4890000;
  /// Initial Gaussians + every clone/split child.
  std::int64_t TotalGaussians = 10000000;
  double SplitShare = 0.4;
  double BurstPruneShare = 0.35;
  double RecentParentBias = 0.5;
  std::int32_t DensifyFrom = 600;
  std::int32_t DensifyUntil = 14900;
  std::int32_t DensifyInterval = 100;
  std::int32_t OpacityResetInterval = 3000;
  std::int32_t Iterations = 30000;
  std::uint64_t Seed = 1;
};

/// A synthetic log: events as /events holds them, initial ids 0..InitialGaussians-1.
struct SyntheticEventLog
{
  EventTable Events;
  std::int64_t InitialGaussians = 0;
  std::int32_t LastIteration = 0;
  std::int64_t FinalGaussians = 0; ///< alive after the last event
  std::int64_t Clones = 0;
  std::int64_t Splits = 0; ///< split parents (each has 2 children)
  std::int64_t Prunes = 0;
};

/// Generates a synthetic log (deterministic for a seed). Throws std::runtime_error when the
/// parameters are inconsistent (e.g. fewer total than final Gaussians).
SyntheticEventLog GenerateSyntheticEventLog(const SyntheticLogParameters& parameters);

} // namespace vis4gs

#endif

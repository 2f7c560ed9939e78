// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSProgressiveStages.h
 * @brief The error of the first stage of progressive scores against the exact scores, for
 * `vis4gs analyze --stop-after-stage=2` (issue 31); the stages themselves are the score
 * filter's (vtkGaussianArtifactScoreFilter::SetProgressiveStage).
 */
#ifndef Vis4GSProgressiveStages_h
#define Vis4GSProgressiveStages_h

#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

class vtkPointData;

using ScoreColumns = std::vector<std::pair<std::string, std::vector<double>>>;

/// The scores @p want names (the registry's short names) from the score filter's output
/// @p pd, in the order of scores.csv; throws std::runtime_error when one is missing.
ScoreColumns ScoresOf(vtkPointData* pd, std::map<std::string, bool>& want);

/// A stage's error against the exact scores: the largest absolute difference, and how many of
/// the exact top 1 % most suspicious Gaussians (lowest coverage, highest other scores; ties
/// by row) the stage ranks in its own top 1 %. Non-finite values are left out of both.
struct StageError
{
  double LargestDifference = 0;
  double LargestExact = 0;
  std::size_t TopCount = 0;
  std::size_t TopShared = 0;
};

StageError CompareStage(const std::vector<double>& stage,
  const std::vector<double>& exact,
  bool lowestFirst);

#endif

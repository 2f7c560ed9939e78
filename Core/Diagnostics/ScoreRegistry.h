// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ScoreRegistry.h
 * @brief The one list of per-Gaussian scores (DESIGN §8, issue 33): what every interface
 * (the score filter, `vis4gs analyze`, the application's panel, histogram and selection
 * table, the rule language, the Python layer, the ParaView plugin) reads instead of naming
 * scores itself.
 *
 * A score is: its short name (`vis4gs analyze --scores=`, rules, `Scene.scores()`), its
 * point-data array (the data model's name), a title, which end is suspicious, what it needs
 * (cameras, training images), its parameters (documentation of the ScoreSettings fields it
 * reads) and its computation: the ScoreRequest switch that asks ComputeGaussianScores() for
 * it and the GaussianScores member that holds its values. The computation stays in the
 * shared per-view passes of ArtifactScores.cxx (coverage, blur and needle share one
 * projection per view; the two render-cost scores share one compositing pass), so asking
 * for a score never adds a pass per score.
 *
 * Adding a score: its definition in DESIGN §4 and in ArtifactScores.h, its switch, values and
 * pass in ArtifactScores, one entry in ScoreRegistry.cxx (the order there is the order of
 * columns in scores.csv, of the application's menus and of the Python layer). Nothing else.
 */
#ifndef vis4gs_ScoreRegistry_h
#define vis4gs_ScoreRegistry_h

#include "ArtifactScores.h"

#include <string>
#include <vector>

namespace vis4gs
{

/**
 * Which end of a score marks a Gaussian as suspicious: View Coverage when low (few training
 * views constrain the Gaussian), the other scores when high. An array that is no score has
 * none.
 */
enum class SuspiciousEnd
{
  None,
  Low,
  High
};

/// Bits of ScoreDefinition::Needs.
enum ScoreNeed : unsigned
{
  NeedsNothing = 0,
  NeedsCameras = 1, ///< the camera table (training views)
  NeedsImages = 2   ///< training images too
};

/// One parameter a score reads (a ScoreSettings field, a property of the score filter and an
/// option of `vis4gs analyze`): documentation, the same text everywhere.
struct ScoreParameter
{
  const char* Name;    ///< the analyze option / Python keyword, e.g. "loss-resolution"
  const char* Type;    ///< "int", "double", "bool" or "choice"
  const char* Default; ///< the exact mode's value, as text
  double Minimum;
  double Maximum;
  const char* Doc;
};

/// One score.
struct ScoreDefinition
{
  const char* Name;      ///< short name: "coverage", "render-cost"
  const char* ArrayName; ///< point-data array: "ViewCoverage", "RenderCost"
  /// Its name in the rule language (SelectionRule.h): identifiers there have no '-', and
  /// "needle" was the needle shape (a property of the log-scales) before the registry.
  const char* RuleName;
  const char* Title; ///< for reports and menus: "View Coverage"
  SuspiciousEnd Suspicious;
  unsigned Needs; ///< ScoreNeed bits
  /// Computed when no list is given (the score filter's and `vis4gs analyze`'s default).
  bool DefaultOn;
  /// Values lie in [0, 1]: overlays and legends map that range (others: 0 to the 99th
  /// percentile).
  bool UnitRange;
  const char* Doc; ///< one sentence: the definition in words, the range
  std::vector<ScoreParameter> Parameters;
  /// The computation: the switch of ComputeGaussianScores() and where its values come back.
  bool ScoreRequest::*Request;
  std::vector<double> GaussianScores::*Values;
};

/// Every score, in the order of scores.csv's columns.
const std::vector<ScoreDefinition>& ScoreDefinitions();

/// The score whose short name or array name is @p name (case-sensitive), or nullptr.
const ScoreDefinition* FindScore(const std::string& name);

/// The short names, joined by @p separator ("coverage, blur, ...").
std::string ScoreNames(const std::string& separator = ", ");

/// The short names of the scores on by default, joined by ",".
std::string DefaultScoreList();

/**
 * The scores of a comma-separated list of short names (spaces around names ignored, empty
 * items skipped, each score once, in registry order). Throws std::invalid_argument naming the
 * unknown name and the known ones.
 */
std::vector<const ScoreDefinition*> ParseScoreList(const std::string& list);

/// The ScoreNeed bits of the scores @p request asks for.
unsigned NeedsOf(const ScoreRequest& request);

/// The suspicious end of the per-Gaussian array named @p arrayName (None when no score).
SuspiciousEnd SuspiciousEndOf(const std::string& arrayName);

} // namespace vis4gs

#endif

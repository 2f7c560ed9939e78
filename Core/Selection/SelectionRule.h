// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SelectionRule.h
 * @brief Guided selection by evidence (issue 20): a small rule language over the diagnostic
 * scores and the attributes of the Gaussians, parsed from text, printed back canonically (so
 * that a rule is shown, saved and re-applied to another iteration or run) and evaluated over
 * a cloud.
 *
 * Grammar (keywords and attribute names are case-insensitive):
 *
 *     rule       := or
 *     or         := and ( "or" and )*
 *     and        := not ( "and" not )*
 *     not        := "not" not | "(" rule ")" | condition
 *     condition  := ATTRIBUTE OP NUMBER            coverage<=0.1, opacity>=0.5
 *                 | ATTRIBUTE ("top"|"bottom") NUMBER "%"   blur top 5%
 *                 | "isolated" "r" "=" NUMBER      isolated r=0.1
 *     OP         := "<" | "<=" | ">" | ">=" | "==" | "!="
 *
 * Attributes (one value per Gaussian, double):
 *   every score of Core/Diagnostics/ScoreRegistry.h by its rule name (ScoreDefinition::
 *   RuleName: coverage, blur, needle_score, shape, render_cost, ...; needs the score's values
 *   in SelectionRuleInputs::Scores)
 *   views         visible training views |V~_g| = E_VC |V| (needs the coverage)
 *   needle        needle shape s(g) in [0, 1] (NeedleShape.h; from the log-scales)
 *   opacity       sigmoid of the opacity logit
 *   scale         the largest activated scale exp(max log-scale)
 *   volume        volume of the 1-sigma ellipsoid, 4/3 pi exp(sum of log-scales)
 *
 * Semantics, chosen so that an independent evaluation (numpy) gives the same set:
 * - a comparison is IEEE: false for a NaN value, so "not (x<t)" holds for NaN values;
 * - "A top p%" holds for the Gaussians whose value (not NaN) is >= the k-th largest value,
 *   k = ceil(p n / 100), n the number of values that are not NaN over the whole cloud (not only
 *   those other conditions keep); +inf ranks first (CostPerContribution of a Gaussian that is
 *   drawn and never shows); ties at the threshold are included; k = 0 selects none. "bottom"
 *   is the same from below;
 * - "isolated r=R" holds when the Gaussian's centre is finite and no other finite centre lies
 *   within distance R (|d| <= R is a neighbour); R must be finite and > 0.
 *
 * The canonical form has lower-case names, no spaces around an operator, numbers in their
 * shortest round-trip form, n-ary "and"/"or" flattened and parentheses only where precedence
 * needs them: Parse(ToString()) gives the same tree, and ToString() of it the same text.
 */
#ifndef vis4gs_SelectionRule_h
#define vis4gs_SelectionRule_h

#include "GaussianCloud.h"
#include "SelectionSet.h"

#include <cstddef>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace vis4gs
{

/// What a condition reads.
enum class RuleAttribute : std::uint8_t
{
  Score, ///< a registered score (RuleNode::Score), read from SelectionRuleInputs::Scores
  Views,
  Needle,
  Opacity,
  Scale,
  Volume
};

/// Canonical name of @p attribute in the rule language ("score" for RuleAttribute::Score,
/// whose name is its score's: RuleNodeAttributeName()).
const char* RuleAttributeName(RuleAttribute attribute);

enum class RuleComparison : std::uint8_t
{
  Less,
  LessEqual,
  Greater,
  GreaterEqual,
  Equal,
  NotEqual
};

/// One node of a parsed rule.
struct RuleNode
{
  enum class Kind : std::uint8_t
  {
    Compare,  ///< Attribute Comparison Value
    Top,      ///< Attribute in the top Value percent
    Bottom,   ///< Attribute in the bottom Value percent
    Isolated, ///< no other centre within Value
    And,
    Or,
    Not
  };
  Kind Type = Kind::Compare;
  RuleAttribute Attribute = RuleAttribute::Score;
  /// With RuleAttribute::Score: the score's index in vis4gs::ScoreDefinitions().
  std::size_t Score = 0;
  RuleComparison Comparison = RuleComparison::LessEqual;
  double Value = 0;
  std::vector<RuleNode> Children; ///< And/Or: two or more; Not: one
};

/// A rule that cannot be parsed or evaluated: the message names the rule and the offending
/// token; Column is the token's 1-based column in the rule text (0 when not about a token).
class SelectionRuleError : public std::invalid_argument
{
public:
  SelectionRuleError(const std::string& message, std::size_t column, std::string token)
    : std::invalid_argument(message)
    , Column(column)
    , Token(std::move(token))
  {
  }
  std::size_t Column;
  std::string Token;
};

/// The per-Gaussian scores a rule may read (Core/Diagnostics/ArtifactScores.h's results, or
/// arrays read back from a scene file). A missing or null entry means "not computed".
struct SelectionRuleInputs
{
  const GaussianCloud* Cloud = nullptr;
  /// By the registry's short name ("coverage", "blur", "needle", "render-cost", ...).
  std::map<std::string, const std::vector<double>*> Scores;
  /// |V| of the scores, for "views"; 0: unknown ("views" then throws).
  std::size_t ViewsUsed = 0;
  /// OpenMP threads; 0 uses OpenMP's default.
  int Threads = 0;
};

/// A parsed rule.
class SelectionRule
{
public:
  /// Parses @p text; throws SelectionRuleError naming the rule and the offending token.
  static SelectionRule Parse(const std::string& text);

  /// The canonical text of the rule.
  std::string ToString() const;
  /// The root of the parse tree.
  const RuleNode& GetRoot() const { return this->Root; }

  /// Whether the rule reads @p attribute anywhere.
  bool Reads(RuleAttribute attribute) const;

  /// The short names of the registered scores the rule reads, in registry order ("views"
  /// reads "coverage"), to compute only the scores it needs.
  std::vector<std::string> ScoresRead() const;

  /**
   * One byte per Gaussian of @p inputs.Cloud: 1 where the rule holds. Throws
   * SelectionRuleError when the rule reads a score @p inputs lacks (naming the rule and the
   * attribute) and std::invalid_argument when an array's size differs from the cloud's.
   */
  std::vector<std::uint8_t> Evaluate(const SelectionRuleInputs& inputs) const;

  /// The indices where the rule holds, ascending.
  std::vector<std::int64_t> Select(const SelectionRuleInputs& inputs) const;

  /// The indices where the rule holds combined with @p current (sorted, unique) by
  /// @p modifier (Add, Subtract, Intersect, ...), as SelectionSet.h's CombineSelection().
  std::vector<std::int64_t> Apply(const std::vector<std::int64_t>& current,
    SelectionModifier modifier,
    const SelectionRuleInputs& inputs) const;

private:
  RuleNode Root;
};

/**
 * Whether each Gaussian of @p cloud has no other centre within @p radius (see the file
 * comment); a uniform grid of cell @p radius, O(N) for evenly spread centres.
 */
std::vector<std::uint8_t> IsolatedGaussians(const GaussianCloud& cloud,
  double radius,
  int threads = 0);

} // namespace vis4gs

#endif

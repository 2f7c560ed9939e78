// SPDX-License-Identifier: BSD-3-Clause
// The selection rule language (issue 20): parsing, canonical text, errors, evaluation on
// hand-built scenes with hand-derived answers, and agreement with an independent numpy
// evaluation of the same rules over the same arrays (selection_rule_numpy.py).
#include "ScoreRegistry.h"
#include "SelectionRule.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <unistd.h>

namespace vis4gs
{
namespace
{
typedef std::vector<std::int64_t> V;

// A cloud of @p n Gaussians with the given opacities; scales 0.1 unless set later.
GaussianCloud MakeCloud(const std::vector<double>& opacities)
{
  GaussianCloud cloud;
  cloud.Resize(opacities.size(), 0);
  for (std::size_t i = 0; i < opacities.size(); ++i)
  {
    cloud.OpacityLogits[i] = static_cast<float>(std::log(opacities[i] / (1 - opacities[i])));
    for (int k = 0; k < 3; ++k)
    {
      cloud.Positions[3 * i + k] = static_cast<float>(10.0 * i);
      cloud.LogScales[3 * i + k] = static_cast<float>(std::log(0.1));
    }
    cloud.Rotations[4 * i] = 1;
  }
  return cloud;
}

std::string ErrorOf(const std::string& text,
  std::size_t* column = nullptr,
  std::string* token = nullptr)
{
  try
  {
    SelectionRule::Parse(text);
  }
  catch (const SelectionRuleError& e)
  {
    if (column)
    {
      *column = e.Column;
    }
    if (token)
    {
      *token = e.Token;
    }
    return e.what();
  }
  return "";
}
} // namespace

TEST(SelectionRule, CanonicalText)
{
  const std::vector<std::pair<std::string, std::string>> cases{
    { "coverage<=2 and opacity>=0.5", "coverage<=2 and opacity>=0.5" },
    { "  Coverage <= 2  AND Opacity >= .50 ", "coverage<=2 and opacity>=0.5" },
    { "blur top 5%", "blur top 5%" },
    { "BLUR TOP 5.0 %", "blur top 5%" },
    { "needle>=0.8", "needle>=0.8" },
    { "needle-score bottom 1e-1%", "needle_score bottom 0.1%" },
    { "isolated r=0.1", "isolated r=0.1" },
    { "isolated r = 1e-2", "isolated r=0.01" },
    { "(a_b)", "" }, // not a rule: see the errors test
    { "opacity>+0.25 or scale<-1", "opacity>0.25 or scale<-1" },
    { "(coverage<0.1 or views<=1) and not (volume>1 and blur>2)",
      "(coverage<0.1 or views<=1) and not (volume>1 and blur>2)" },
    { "((coverage<0.1)) and ((opacity>0.5) and (needle>0.5))",
      "coverage<0.1 and opacity>0.5 and needle>0.5" },
    { "not not opacity==1", "opacity==1" },
    { "not opacity!=1 or not isolated r=2", "not opacity!=1 or not isolated r=2" },
    { "a_top", "" },
  };
  for (const auto& [input, canonical] : cases)
  {
    if (canonical.empty())
    {
      EXPECT_THROW(SelectionRule::Parse(input), SelectionRuleError) << input;
      continue;
    }
    const std::string text = SelectionRule::Parse(input).ToString();
    EXPECT_EQ(text, canonical) << input;
    // Canonical text is a fixed point and re-parses to the same meaning.
    EXPECT_EQ(SelectionRule::Parse(text).ToString(), text);
  }
  // Shortest round-trip numbers: the value printed is the value parsed.
  const SelectionRule r = SelectionRule::Parse("opacity>=0.30000000000000004");
  EXPECT_EQ(r.ToString(), "opacity>=0.30000000000000004");
  EXPECT_EQ(r.GetRoot().Value, 0.1 + 0.2);
}

TEST(SelectionRule, ErrorsNameTheRuleAndToken)
{
  std::size_t column = 0;
  std::string token;
  std::string message = ErrorOf("coverage<=x and opacity>0.5", &column, &token);
  EXPECT_NE(message.find("'coverage<=x and opacity>0.5'"), std::string::npos) << message;
  EXPECT_NE(message.find("'x'"), std::string::npos) << message;
  EXPECT_NE(message.find("after 'coverage<='"), std::string::npos) << message;
  EXPECT_EQ(column, 11u);
  EXPECT_EQ(token, "x");

  message = ErrorOf("covrage<=2", &column, &token);
  EXPECT_NE(message.find("unknown attribute"), std::string::npos) << message;
  EXPECT_EQ(token, "covrage");
  EXPECT_EQ(column, 1u);

  message = ErrorOf("blur top 5", &column, &token);
  EXPECT_NE(message.find("'%'"), std::string::npos) << message;
  EXPECT_NE(message.find("the end"), std::string::npos) << message;
  EXPECT_EQ(column, 11u);

  ErrorOf("blur top 150%", &column, &token);
  EXPECT_EQ(token, "150");
  ErrorOf("isolated r=0", &column, &token);
  EXPECT_EQ(token, "0");
  EXPECT_EQ(column, 12u);
  ErrorOf("isolated 0.1", &column, &token);
  EXPECT_EQ(token, "0.1");
  ErrorOf("opacity>0.5 and", &column, &token);
  EXPECT_EQ(column, 16u);
  ErrorOf("opacity>0.5 opacity<1", &column, &token);
  EXPECT_EQ(token, "opacity");
  EXPECT_EQ(column, 13u);
  ErrorOf("(opacity>0.5", &column, &token);
  EXPECT_EQ(column, 13u);
  ErrorOf("opacity>0.5)", &column, &token);
  EXPECT_EQ(token, ")");
  ErrorOf("opacity=>0.5", &column, &token);
  EXPECT_EQ(token, "=");
  ErrorOf("opacity>1e999", &column, &token);
  EXPECT_EQ(token, "1e999");
  ErrorOf("opacity>nan", &column, &token);
  EXPECT_EQ(token, "nan");
  ErrorOf("opacity>0.5 & blur>1", &column, &token);
  EXPECT_EQ(token, "&");
  EXPECT_EQ(column, 13u);
  EXPECT_NE(ErrorOf("   ").find("empty"), std::string::npos);
}

TEST(SelectionRule, HandBuiltScene)
{
  // Six Gaussians; values chosen so that each condition's answer is derived by hand.
  GaussianCloud cloud = MakeCloud({ 0.9, 0.2, 0.6, 0.99, 0.5, 0.7 });
  // Gaussian 2: a needle (scales 1, 0.01, 0.01) -> needle shape near 1; largest scale 1.
  cloud.LogScales[6] = 0;
  cloud.LogScales[7] = cloud.LogScales[8] = static_cast<float>(std::log(0.01));
  // Gaussian 4: large and round (scales 2) -> volume 4/3 pi 8, needle shape 0.
  for (int k = 0; k < 3; ++k)
  {
    cloud.LogScales[12 + k] = static_cast<float>(std::log(2.0));
  }
  const std::vector<double> coverage{ 1.0, 0.1, 0.05, 0.05, 0.5, 0.0 };
  const std::vector<double> blur{
    0.5, 3.0, 1.0, std::numeric_limits<double>::quiet_NaN(), 2.0, 0.0
  };
  const std::vector<double> needle{ 0, 0, 5, 0, 0, 0 };
  SelectionRuleInputs in;
  in.Cloud = &cloud;
  in.Scores = { { "coverage", &coverage }, { "blur", &blur }, { "needle", &needle } };
  in.ViewsUsed = 20;
  auto sel = [&in](const std::string& text) { return SelectionRule::Parse(text).Select(in); };
  EXPECT_EQ(sel("coverage<=0.1 and opacity>=0.5"), (V{ 2, 3, 5 }));
  EXPECT_EQ(sel("coverage<=0.1 or opacity>=0.95"), (V{ 1, 2, 3, 5 }));
  EXPECT_EQ(sel("views<=1"), (V{ 2, 3, 5 })); // 0.05 * 20 = 1 view
  EXPECT_EQ(sel("views==2"), (V{ 1 }));
  EXPECT_EQ(sel("needle>=0.8"), (V{ 2 }));
  EXPECT_EQ(sel("needle<0.01"), (V{ 0, 1, 3, 4, 5 })); // equal scales: s = 0
  EXPECT_EQ(sel("needle_score>1"), (V{ 2 }));
  EXPECT_EQ(sel("scale>=0.5"), (V{ 2, 4 }));
  EXPECT_EQ(sel("volume>30"), (V{ 4 })); // 4/3 pi 8 = 33.5; 4/3 pi 0.001 for the others
  // blur: finite values 0.5, 3, 1, 2, 0 (n = 5); NaN is never in a percentile.
  EXPECT_EQ(sel("blur top 20%"), (V{ 1 }));       // k = 1
  EXPECT_EQ(sel("blur top 21%"), (V{ 1, 4 }));    // k = ceil(1.05) = 2
  EXPECT_EQ(sel("blur bottom 40%"), (V{ 0, 5 })); // k = 2
  EXPECT_EQ(sel("blur top 0%"), V{});
  EXPECT_EQ(sel("blur top 100%"), (V{ 0, 1, 2, 4, 5 }));
  // Comparisons with NaN are false, so their negation holds.
  EXPECT_EQ(sel("blur>=0"), (V{ 0, 1, 2, 4, 5 }));
  EXPECT_EQ(sel("not blur>=0"), (V{ 3 }));
  EXPECT_EQ(sel("blur!=1"), (V{ 0, 1, 3, 4, 5 }));
  // Precedence: and binds tighter than or.
  EXPECT_EQ(sel("opacity>0.95 or opacity<0.3 and coverage<0.5"), (V{ 1, 3 }));
  EXPECT_EQ(sel("(opacity>0.95 or opacity<0.3) and coverage<0.07"), (V{ 3 }));

  // Combining with an existing selection.
  const SelectionRule rule = SelectionRule::Parse("coverage<=0.1");
  EXPECT_EQ(rule.Apply({ 0, 2 }, SelectionModifier::Add, in), (V{ 0, 1, 2, 3, 5 }));
  EXPECT_EQ(rule.Apply({ 0, 2 }, SelectionModifier::Subtract, in), (V{ 0 }));
  EXPECT_EQ(rule.Apply({ 0, 2, 4 }, SelectionModifier::Intersect, in), (V{ 2 }));
  EXPECT_EQ(rule.Apply({ 0 }, SelectionModifier::Replace, in), (V{ 1, 2, 3, 5 }));

  // The same rule re-applied to another state (fewer Gaussians) is evaluated on that state.
  GaussianCloud later = MakeCloud({ 0.9, 0.2 });
  SelectionRuleInputs laterIn;
  laterIn.Cloud = &later;
  EXPECT_EQ(SelectionRule::Parse(SelectionRule::Parse("opacity >= 0.5").ToString()).Select(laterIn),
    (V{ 0 }));

  // Scores a rule needs and the scene lacks: an error naming the rule and the attribute.
  try
  {
    SelectionRule::Parse("opacity>0.5 and blur top 5%").Select(laterIn);
    ADD_FAILURE() << "no error for a missing score";
  }
  catch (const SelectionRuleError& e)
  {
    EXPECT_NE(std::string(e.what()).find("'opacity>0.5 and blur top 5%'"), std::string::npos);
    EXPECT_EQ(e.Token, "blur");
  }
  // The scores a rule reads, by the registry's short names ("views" reads the coverage).
  EXPECT_EQ(rule.ScoresRead(), std::vector<std::string>{ "coverage" });
  EXPECT_EQ(SelectionRule::Parse("views<2").ScoresRead(), std::vector<std::string>{ "coverage" });
  EXPECT_EQ(SelectionRule::Parse("needle_score>1 or blur top 1% or needle>0.5").ScoresRead(),
    (std::vector<std::string>{ "blur", "needle" }));
  EXPECT_TRUE(SelectionRule::Parse("opacity<0.1").ScoresRead().empty());
  // Every registered score is an attribute under its rule name, read from Scores.
  for (const vis4gs::ScoreDefinition& d : vis4gs::ScoreDefinitions())
  {
    const SelectionRule byName = SelectionRule::Parse(std::string(d.RuleName) + " top 50%");
    EXPECT_EQ(byName.ToString(), std::string(d.RuleName) + " top 50%");
    EXPECT_EQ(byName.ScoresRead(), std::vector<std::string>{ d.Name });
    const std::vector<double> values{ 0.1, 0.5, std::nan(""), 0.3, 0.2, 0.9 };
    SelectionRuleInputs scored;
    scored.Cloud = in.Cloud;
    scored.Scores[d.Name] = &values;
    // 5 finite values: k = ceil(2.5) = 3, the three largest.
    EXPECT_EQ(byName.Select(scored), (V{ 1, 3, 5 })) << d.Name;
  }
  // An array of the wrong size is refused before it is read.
  const std::vector<double> shortCoverage{ 1.0 };
  in.Scores["coverage"] = &shortCoverage;
  EXPECT_THROW(rule.Select(in), std::invalid_argument);
}

TEST(SelectionRule, Isolation)
{
  GaussianCloud cloud = MakeCloud({ 0.5, 0.5, 0.5, 0.5, 0.5, 0.5 });
  const float p[6][3] = { { 0, 0, 0 },
    { 0.1f, 0, 0 },
    { 5, 5, 5 },
    { 5, 5, 5.3f },
    { -3, 2, 1 },
    { std::numeric_limits<float>::quiet_NaN(), 0, 0 } };
  for (int i = 0; i < 6; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      cloud.Positions[3 * i + k] = p[i][k];
    }
  }
  SelectionRuleInputs in;
  in.Cloud = &cloud;
  auto sel = [&in](const std::string& text) { return SelectionRule::Parse(text).Select(in); };
  EXPECT_EQ(sel("isolated r=0.05"), (V{ 0, 1, 2, 3, 4 }));
  EXPECT_EQ(sel("isolated r=0.2"), (V{ 2, 3, 4 }));
  EXPECT_EQ(sel("isolated r=0.30001"), (V{ 4 }));
  EXPECT_EQ(sel("isolated r=100"), V{});
  // The NaN centre is neither a neighbour nor isolated.
  EXPECT_EQ(sel("not isolated r=0.05"), (V{ 5 }));
  EXPECT_THROW(IsolatedGaussians(cloud, 0), std::invalid_argument);
}

// The same rules over the same random arrays, evaluated by selection_rule_numpy.py with its
// own numpy expressions (no parser): the sets must be identical.
TEST(SelectionRule, MatchesNumpy)
{
  const std::size_t n = 3000;
  std::mt19937 rng(20);
  std::normal_distribution<float> gauss(0, 1);
  std::uniform_real_distribution<double> uni(0, 1);
  GaussianCloud cloud;
  cloud.Resize(n, 0);
  std::vector<double> coverage(n), blur(n), needleScore(n);
  const std::size_t views = 29;
  for (std::size_t i = 0; i < n; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      cloud.Positions[3 * i + k] = 2.0f * gauss(rng);
      cloud.LogScales[3 * i + k] = -3.0f + 1.5f * gauss(rng);
    }
    cloud.OpacityLogits[i] = 3.0f * gauss(rng);
    coverage[i] = static_cast<double>(rng() % (views + 1)) / static_cast<double>(views);
    blur[i] = uni(rng) < 0.02 ? std::numeric_limits<double>::quiet_NaN() : std::exp(2 * uni(rng));
    // Plenty of ties for the percentiles.
    needleScore[i] = std::floor(10 * uni(rng));
  }
  cloud.Positions[3 * 17] = std::numeric_limits<float>::infinity();
  cloud.LogScales[3 * 18] = -std::numeric_limits<float>::infinity();
  const std::vector<std::string> rules{
    "coverage<=0.1 and opacity>=0.5",
    "blur top 5%",
    "needle>=0.8",
    "isolated r=0.3",
    "views<=2 or not (scale<0.1 and volume>1e-5)",
    "needle_score top 12.5% and blur bottom 30%",
    "not isolated r=0.5 and opacity<0.2 or needle<0.1",
  };
  char folder[] = "/tmp/vis4gs-rule-numpy-XXXXXX";
  ASSERT_NE(::mkdtemp(folder), nullptr);
  const std::string dir = folder;
  auto write = [&dir](const std::string& name, const void* data, std::size_t bytes)
  {
    std::ofstream f(dir + "/" + name, std::ios::binary);
    f.write(static_cast<const char*>(data), static_cast<std::streamsize>(bytes));
  };
  write("positions.f32", cloud.Positions.data(), 4 * cloud.Positions.size());
  write("log_scales.f32", cloud.LogScales.data(), 4 * cloud.LogScales.size());
  write("opacity_logits.f32", cloud.OpacityLogits.data(), 4 * n);
  write("coverage.f64", coverage.data(), 8 * n);
  write("blur.f64", blur.data(), 8 * n);
  write("needle_score.f64", needleScore.data(), 8 * n);
  {
    std::ofstream f(dir + "/rules.txt");
    for (const std::string& r : rules)
    {
      f << SelectionRule::Parse(r).ToString() << "\n";
    }
    f << "views " << views << "\n";
  }
  const std::string command =
    std::string(VIS4GS_SYSTEM_PYTHON) + " " + VIS4GS_RULE_NUMPY_SCRIPT + " " + dir;
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  SelectionRuleInputs in;
  in.Cloud = &cloud;
  in.Scores = { { "coverage", &coverage }, { "blur", &blur }, { "needle", &needleScore } };
  in.ViewsUsed = views;
  for (std::size_t r = 0; r < rules.size(); ++r)
  {
    std::ifstream f(dir + "/mask" + std::to_string(r) + ".u8", std::ios::binary);
    std::vector<char> expected(n);
    f.read(expected.data(), static_cast<std::streamsize>(n));
    ASSERT_EQ(static_cast<std::size_t>(f.gcount()), n) << rules[r];
    const std::vector<std::uint8_t> mask = SelectionRule::Parse(rules[r]).Evaluate(in);
    std::size_t differ = 0, selected = 0;
    for (std::size_t i = 0; i < n; ++i)
    {
      differ += (mask[i] != 0) != (expected[i] != 0);
      selected += mask[i] != 0;
    }
    EXPECT_EQ(differ, 0u) << rules[r];
    // Every rule selects some but not all, or the comparison would say little.
    EXPECT_GT(selected, 0u) << rules[r];
    EXPECT_LT(selected, n) << rules[r];
  }
  std::system(("rm -rf " + dir).c_str());
}

} // namespace vis4gs

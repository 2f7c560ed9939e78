// SPDX-License-Identifier: BSD-3-Clause
#include "SelectionRule.h"

#include "GaussianMath.h"
#include "NeedleShape.h"
#include "ScoreRegistry.h"
#include "ThreadCount.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <utility>

namespace vis4gs
{
namespace
{
// The attributes that are no registered score (the registry's rule names are the others).
constexpr std::array<std::pair<const char*, RuleAttribute>, 5> AttributeNames{ {
  { "views", RuleAttribute::Views },
  { "needle", RuleAttribute::Needle },
  { "opacity", RuleAttribute::Opacity },
  { "scale", RuleAttribute::Scale },
  { "volume", RuleAttribute::Volume },
} };

std::string AttributeNameOf(const RuleNode& node)
{
  return node.Attribute == RuleAttribute::Score ? ScoreDefinitions().at(node.Score).RuleName
                                                : RuleAttributeName(node.Attribute);
}

const char* ComparisonText(RuleComparison c)
{
  switch (c)
  {
    case RuleComparison::Less:
      return "<";
    case RuleComparison::LessEqual:
      return "<=";
    case RuleComparison::Greater:
      return ">";
    case RuleComparison::GreaterEqual:
      return ">=";
    case RuleComparison::Equal:
      return "==";
    case RuleComparison::NotEqual:
      return "!=";
  }
  return "?";
}

std::string NumberText(double v)
{
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), v);
  return std::string(buffer, result.ptr);
}

struct Token
{
  enum class Kind
  {
    Word,
    Number,
    Operator,
    Open,
    Close,
    Percent,
    End
  };
  Kind Type = Kind::End;
  std::string Text;
  double Number = 0;
  std::size_t Column = 0; // 1-based
};

class Parser
{
public:
  explicit Parser(const std::string& text)
    : Text(text)
  {
    this->Tokenize();
  }

  RuleNode ParseRule()
  {
    if (this->Tokens.front().Type == Token::Kind::End)
    {
      this->Fail("the rule is empty", this->Tokens.front());
    }
    RuleNode root = this->ParseOr();
    if (this->Peek().Type != Token::Kind::End)
    {
      this->Fail("expected 'and', 'or' or the end of the rule", this->Peek());
    }
    return root;
  }

private:
  [[noreturn]] void Fail(const std::string& what, const Token& token) const
  {
    const std::string shown = token.Type == Token::Kind::End ? "the end" : "'" + token.Text + "'";
    throw SelectionRuleError("selection rule '" + this->Text + "': " + what + ", found " + shown +
        " (column " + std::to_string(token.Column) + ")",
      token.Column,
      token.Text);
  }

  void Tokenize()
  {
    const std::string& s = this->Text;
    std::size_t i = 0;
    while (i < s.size())
    {
      const unsigned char c = static_cast<unsigned char>(s[i]);
      if (std::isspace(c))
      {
        ++i;
        continue;
      }
      Token t;
      t.Column = i + 1;
      if (std::isalpha(c) || c == '_')
      {
        std::size_t j = i;
        while (j < s.size() &&
          (std::isalnum(static_cast<unsigned char>(s[j])) || s[j] == '_' || s[j] == '-'))
        {
          ++j;
        }
        t.Type = Token::Kind::Word;
        t.Text = s.substr(i, j - i);
        std::transform(t.Text.begin(),
          t.Text.end(),
          t.Text.begin(),
          [](unsigned char x) { return static_cast<char>(std::tolower(x)); });
        std::replace(t.Text.begin(), t.Text.end(), '-', '_');
        i = j;
      }
      else if (std::isdigit(c) || c == '.' ||
        ((c == '-' || c == '+') && i + 1 < s.size() &&
          (std::isdigit(static_cast<unsigned char>(s[i + 1])) || s[i + 1] == '.')))
      {
        // from_chars takes no leading '+' and is locale-independent, unlike strtod.
        const std::size_t start = c == '+' ? i + 1 : i;
        double value = 0;
        const auto result = std::from_chars(s.data() + start, s.data() + s.size(), value);
        std::size_t j = static_cast<std::size_t>(result.ptr - s.data());
        if (result.ec != std::errc() || j == start)
        {
          // Take the whole malformed run for the message.
          j = i + 1;
          while (j < s.size() && (std::isalnum(static_cast<unsigned char>(s[j])) || s[j] == '.'))
          {
            ++j;
          }
          t.Text = s.substr(i, j - i);
          this->Fail(result.ec == std::errc::result_out_of_range ? "a number out of range"
                                                                 : "a malformed number",
            t);
        }
        t.Type = Token::Kind::Number;
        t.Text = s.substr(i, j - i);
        t.Number = value;
        i = j;
      }
      else if (c == '<' || c == '>' || c == '=' || c == '!')
      {
        std::size_t j = i + 1;
        if (j < s.size() && s[j] == '=')
        {
          ++j;
        }
        t.Type = Token::Kind::Operator;
        t.Text = s.substr(i, j - i);
        i = j;
      }
      else if (c == '(' || c == ')' || c == '%')
      {
        t.Type = c == '(' ? Token::Kind::Open
          : c == ')'      ? Token::Kind::Close
                          : Token::Kind::Percent;
        t.Text = std::string(1, static_cast<char>(c));
        ++i;
      }
      else
      {
        t.Text = std::string(1, static_cast<char>(c));
        this->Fail("a character the rule language does not use", t);
      }
      this->Tokens.push_back(std::move(t));
    }
    Token end;
    end.Column = s.size() + 1;
    this->Tokens.push_back(end);
  }

  const Token& Peek() const { return this->Tokens[this->Position]; }
  const Token& Next() { return this->Tokens[this->Position++]; }
  bool IsWord(const char* word) const
  {
    return this->Peek().Type == Token::Kind::Word && this->Peek().Text == word;
  }

  RuleNode Combine(RuleNode::Kind kind, RuleNode first, const char* word)
  {
    if (!this->IsWord(word))
    {
      return first;
    }
    RuleNode node;
    node.Type = kind;
    auto append = [&node](RuleNode child)
    {
      // Flatten nested nodes of the same kind so that the canonical text re-parses to the
      // same tree.
      if (child.Type == node.Type)
      {
        for (RuleNode& grandchild : child.Children)
        {
          node.Children.push_back(std::move(grandchild));
        }
      }
      else
      {
        node.Children.push_back(std::move(child));
      }
    };
    append(std::move(first));
    while (this->IsWord(word))
    {
      this->Next();
      append(kind == RuleNode::Kind::Or ? this->ParseAnd() : this->ParseNot());
    }
    return node;
  }

  RuleNode ParseOr() { return this->Combine(RuleNode::Kind::Or, this->ParseAnd(), "or"); }
  RuleNode ParseAnd() { return this->Combine(RuleNode::Kind::And, this->ParseNot(), "and"); }

  RuleNode ParseNot()
  {
    if (this->IsWord("not"))
    {
      this->Next();
      RuleNode node;
      node.Type = RuleNode::Kind::Not;
      RuleNode child = this->ParseNot();
      if (child.Type == RuleNode::Kind::Not) // "not not x" is x
      {
        return std::move(child.Children.front());
      }
      node.Children.push_back(std::move(child));
      return node;
    }
    if (this->Peek().Type == Token::Kind::Open)
    {
      this->Next();
      RuleNode inner = this->ParseOr();
      if (this->Peek().Type != Token::Kind::Close)
      {
        this->Fail("expected ')'", this->Peek());
      }
      this->Next();
      return inner;
    }
    return this->ParseCondition();
  }

  double ExpectNumber(const char* after)
  {
    const Token& t = this->Peek();
    if (t.Type != Token::Kind::Number)
    {
      this->Fail(std::string("expected a number after '") + after + "'", t);
    }
    if (!std::isfinite(t.Number))
    {
      this->Fail("expected a finite number", t);
    }
    return this->Next().Number;
  }

  RuleNode ParseCondition()
  {
    const Token& name = this->Peek();
    if (name.Type != Token::Kind::Word)
    {
      this->Fail("expected a condition (an attribute, 'isolated', 'not' or '(')", name);
    }
    RuleNode node;
    if (name.Text == "isolated")
    {
      this->Next();
      if (!this->IsWord("r"))
      {
        this->Fail("expected 'r=RADIUS' after 'isolated'", this->Peek());
      }
      this->Next();
      if (this->Peek().Type != Token::Kind::Operator || this->Peek().Text != "=")
      {
        this->Fail("expected '=' after 'isolated r'", this->Peek());
      }
      this->Next();
      const Token& radius = this->Peek();
      node.Type = RuleNode::Kind::Isolated;
      node.Value = this->ExpectNumber("isolated r=");
      if (!(node.Value > 0))
      {
        this->Fail("the radius must be greater than 0", radius);
      }
      return node;
    }
    auto it = std::find_if(AttributeNames.begin(),
      AttributeNames.end(),
      [&name](const auto& entry) { return name.Text == entry.first; });
    const auto& scores = ScoreDefinitions();
    auto score = std::find_if(scores.begin(),
      scores.end(),
      [&name](const ScoreDefinition& d) { return name.Text == d.RuleName; });
    if (it == AttributeNames.end() && score == scores.end())
    {
      std::string known;
      for (const ScoreDefinition& d : scores)
      {
        known += std::string(d.RuleName) + ", ";
      }
      for (const auto& entry : AttributeNames)
      {
        known += std::string(entry.first) + ", ";
      }
      this->Fail("unknown attribute (expected " + known + "or isolated)", name);
    }
    if (it != AttributeNames.end())
    {
      node.Attribute = it->second;
    }
    else
    {
      node.Attribute = RuleAttribute::Score;
      node.Score = static_cast<std::size_t>(score - scores.begin());
    }
    this->Next();
    const Token& op = this->Peek();
    if (this->IsWord("top") || this->IsWord("bottom"))
    {
      node.Type = op.Text == "top" ? RuleNode::Kind::Top : RuleNode::Kind::Bottom;
      const std::string after = AttributeNameOf(node) + " " + op.Text;
      this->Next();
      const Token& percent = this->Peek();
      node.Value = this->ExpectNumber(after.c_str());
      if (node.Value < 0 || node.Value > 100)
      {
        this->Fail("a percentage must be between 0 and 100", percent);
      }
      if (this->Peek().Type != Token::Kind::Percent)
      {
        this->Fail("expected '%' after the percentage", this->Peek());
      }
      this->Next();
      return node;
    }
    static const std::array<std::pair<const char*, RuleComparison>, 6> comparisons{ {
      { "<", RuleComparison::Less },
      { "<=", RuleComparison::LessEqual },
      { ">", RuleComparison::Greater },
      { ">=", RuleComparison::GreaterEqual },
      { "==", RuleComparison::Equal },
      { "!=", RuleComparison::NotEqual },
    } };
    auto cmp = std::find_if(comparisons.begin(),
      comparisons.end(),
      [&op](const auto& entry)
      { return op.Type == Token::Kind::Operator && op.Text == entry.first; });
    if (cmp == comparisons.end())
    {
      this->Fail(
        "expected <, <=, >, >=, ==, != or top/bottom after '" + AttributeNameOf(node) + "'", op);
    }
    node.Type = RuleNode::Kind::Compare;
    node.Comparison = cmp->second;
    const std::string after = AttributeNameOf(node) + cmp->first;
    this->Next();
    node.Value = this->ExpectNumber(after.c_str());
    return node;
  }

  std::string Text;
  std::vector<Token> Tokens;
  std::size_t Position = 0;
};

int Precedence(const RuleNode& node)
{
  switch (node.Type)
  {
    case RuleNode::Kind::Or:
      return 1;
    case RuleNode::Kind::And:
      return 2;
    default:
      return 3;
  }
}

void Print(const RuleNode& node, std::string& out)
{
  auto child = [&out](const RuleNode& c, int minimum)
  {
    const bool parens = Precedence(c) < minimum;
    out += parens ? "(" : "";
    Print(c, out);
    out += parens ? ")" : "";
  };
  switch (node.Type)
  {
    case RuleNode::Kind::Compare:
      out += AttributeNameOf(node);
      out += ComparisonText(node.Comparison);
      out += NumberText(node.Value);
      return;
    case RuleNode::Kind::Top:
    case RuleNode::Kind::Bottom:
      out += AttributeNameOf(node);
      out += node.Type == RuleNode::Kind::Top ? " top " : " bottom ";
      out += NumberText(node.Value) + "%";
      return;
    case RuleNode::Kind::Isolated:
      out += "isolated r=" + NumberText(node.Value);
      return;
    case RuleNode::Kind::Not:
      out += "not ";
      child(node.Children.front(), 3);
      return;
    case RuleNode::Kind::And:
    case RuleNode::Kind::Or:
      for (std::size_t i = 0; i < node.Children.size(); ++i)
      {
        out += i ? (node.Type == RuleNode::Kind::And ? " and " : " or ") : "";
        child(node.Children[i], Precedence(node) + 1);
      }
      return;
  }
}

bool ReadsAttribute(const RuleNode& node, RuleAttribute attribute, std::size_t score = 0)
{
  if (node.Type == RuleNode::Kind::Compare || node.Type == RuleNode::Kind::Top ||
    node.Type == RuleNode::Kind::Bottom)
  {
    return node.Attribute == attribute &&
      (attribute != RuleAttribute::Score || node.Score == score);
  }
  return std::any_of(node.Children.begin(),
    node.Children.end(),
    [attribute, score](const RuleNode& c) { return ReadsAttribute(c, attribute, score); });
}

class Evaluator
{
public:
  Evaluator(const SelectionRuleInputs& inputs, std::string ruleText)
    : Inputs(inputs)
    , RuleText(std::move(ruleText))
  {
    if (!inputs.Cloud)
    {
      throw std::invalid_argument("selection rule '" + this->RuleText + "': no cloud to evaluate");
    }
  }

  std::vector<std::uint8_t> Evaluate(const RuleNode& node)
  {
    const std::size_t n = this->Inputs.Cloud->Count;
    std::vector<std::uint8_t> mask(n, 0);
    const long long count = static_cast<long long>(n);
    switch (node.Type)
    {
      case RuleNode::Kind::Compare:
      {
        const std::vector<double>& v = this->Values(node);
        const double t = node.Value;
        const RuleComparison c = node.Comparison;
#pragma omp parallel for schedule(static) num_threads(this->Threads())
        for (long long i = 0; i < count; ++i)
        {
          const double x = v[static_cast<std::size_t>(i)];
          bool holds = false;
          switch (c)
          {
            case RuleComparison::Less:
              holds = x < t;
              break;
            case RuleComparison::LessEqual:
              holds = x <= t;
              break;
            case RuleComparison::Greater:
              holds = x > t;
              break;
            case RuleComparison::GreaterEqual:
              holds = x >= t;
              break;
            case RuleComparison::Equal:
              holds = x == t;
              break;
            case RuleComparison::NotEqual:
              holds = x != t; // true for NaN, as IEEE and numpy say
              break;
          }
          mask[static_cast<std::size_t>(i)] = holds ? 1 : 0;
        }
        return mask;
      }
      case RuleNode::Kind::Top:
      case RuleNode::Kind::Bottom:
      {
        const std::vector<double>& v = this->Values(node);
        const bool top = node.Type == RuleNode::Kind::Top;
        std::vector<double> finite;
        finite.reserve(n);
        for (double x : v)
        {
          if (!std::isnan(x)) // +-inf rank (R/A of a Gaussian that never shows is +inf)
          {
            finite.push_back(top ? -x : x);
          }
        }
        const double k = std::ceil(node.Value * static_cast<double>(finite.size()) / 100.0);
        if (k < 1)
        {
          return mask;
        }
        const std::size_t kth = std::min(finite.size(), static_cast<std::size_t>(k)) - 1;
        std::nth_element(
          finite.begin(), finite.begin() + static_cast<std::ptrdiff_t>(kth), finite.end());
        const double threshold = top ? -finite[kth] : finite[kth];
        for (std::size_t i = 0; i < n; ++i)
        {
          const double x = v[i];
          mask[i] = !std::isnan(x) && (top ? x >= threshold : x <= threshold) ? 1 : 0;
        }
        return mask;
      }
      case RuleNode::Kind::Isolated:
        return IsolatedGaussians(*this->Inputs.Cloud, node.Value, this->Inputs.Threads);
      case RuleNode::Kind::Not:
        mask = this->Evaluate(node.Children.front());
        for (std::uint8_t& m : mask)
        {
          m = m ? 0 : 1;
        }
        return mask;
      case RuleNode::Kind::And:
      case RuleNode::Kind::Or:
      {
        const bool isAnd = node.Type == RuleNode::Kind::And;
        mask = this->Evaluate(node.Children.front());
        for (std::size_t c = 1; c < node.Children.size(); ++c)
        {
          const std::vector<std::uint8_t> other = this->Evaluate(node.Children[c]);
          for (std::size_t i = 0; i < n; ++i)
          {
            mask[i] = isAnd ? (mask[i] & other[i]) : (mask[i] | other[i]);
          }
        }
        return mask;
      }
    }
    return mask;
  }

private:
  int Threads() const
  {
    return ThreadCount(this->Inputs.Threads);
  }

  const std::vector<double>& Score(const std::string& shortName, const std::string& what)
  {
    const auto found = this->Inputs.Scores.find(shortName);
    const std::vector<double>* values =
      found == this->Inputs.Scores.end() ? nullptr : found->second;
    if (!values)
    {
      throw SelectionRuleError("selection rule '" + this->RuleText + "': '" + what +
          "' needs the diagnostic scores, which were not computed for this scene",
        0,
        what);
    }
    if (values->size() != this->Inputs.Cloud->Count)
    {
      throw std::invalid_argument("selection rule '" + this->RuleText +
        "': " + std::to_string(values->size()) + " values of '" + what + "' for " +
        std::to_string(this->Inputs.Cloud->Count) + " Gaussians");
    }
    return *values;
  }

  const std::vector<double>& Values(const RuleNode& node)
  {
    const RuleAttribute attribute = node.Attribute;
    if (attribute == RuleAttribute::Score)
    {
      const ScoreDefinition& d = ScoreDefinitions().at(node.Score);
      return this->Score(d.Name, d.RuleName);
    }
    std::vector<double>& cached = this->Cache[static_cast<std::size_t>(attribute)];
    const char* name = RuleAttributeName(attribute);
    if (!cached.empty() || this->Inputs.Cloud->Count == 0)
    {
      return cached;
    }
    const GaussianCloud& cloud = *this->Inputs.Cloud;
    const std::size_t n = cloud.Count;
    auto require = [&](const std::vector<float>& array, std::size_t per, const char* field)
    {
      if (array.size() != per * n)
      {
        throw std::invalid_argument("selection rule '" + this->RuleText + "': '" + name +
          "' needs the " + field + " of every Gaussian, which the scene does not hold");
      }
    };
    cached.resize(n);
    const long long count = static_cast<long long>(n);
    switch (attribute)
    {
      case RuleAttribute::Views:
      {
        const std::vector<double>& coverage = this->Score("coverage", name);
        if (this->Inputs.ViewsUsed == 0)
        {
          throw SelectionRuleError("selection rule '" + this->RuleText +
              "': 'views' needs the number of training views the scores used",
            0,
            name);
        }
        const double views = static_cast<double>(this->Inputs.ViewsUsed);
        for (std::size_t i = 0; i < n; ++i)
        {
          cached[i] = std::round(coverage[i] * views); // E_VC = |V~_g| / |V| exactly
        }
        break;
      }
      case RuleAttribute::Needle:
        require(cloud.LogScales, 3, "log-scales");
#pragma omp parallel for schedule(static) num_threads(this->Threads())
        for (long long i = 0; i < count; ++i)
        {
          const float* s = &cloud.LogScales[3 * static_cast<std::size_t>(i)];
          const double ls[3] = { s[0], s[1], s[2] };
          cached[static_cast<std::size_t>(i)] = NeedleShape(ls);
        }
        break;
      case RuleAttribute::Opacity:
        require(cloud.OpacityLogits, 1, "opacity logits");
        for (std::size_t i = 0; i < n; ++i)
        {
          cached[i] = Sigmoid<double>(cloud.OpacityLogits[i]);
        }
        break;
      case RuleAttribute::Scale:
        require(cloud.LogScales, 3, "log-scales");
        for (std::size_t i = 0; i < n; ++i)
        {
          const float* s = &cloud.LogScales[3 * i];
          // max of NaN is NaN on purpose: a NaN scale compares false.
          const double m = std::isnan(s[0]) || std::isnan(s[1]) || std::isnan(s[2])
            ? std::numeric_limits<double>::quiet_NaN()
            : std::max({ s[0], s[1], s[2] });
          cached[i] = std::exp(m);
        }
        break;
      case RuleAttribute::Volume:
        require(cloud.LogScales, 3, "log-scales");
        for (std::size_t i = 0; i < n; ++i)
        {
          const float* s = &cloud.LogScales[3 * i];
          // In the log domain: exp of each scale may under- or overflow where the product
          // does not.
          cached[i] = 4.0 / 3.0 * 3.14159265358979323846 *
            std::exp(
              static_cast<double>(s[0]) + static_cast<double>(s[1]) + static_cast<double>(s[2]));
        }
        break;
      default:
        break;
    }
    return cached;
  }

  const SelectionRuleInputs& Inputs;
  std::string RuleText;
  std::array<std::vector<double>, 8> Cache;
};

struct CellKey
{
  std::int64_t X, Y, Z;
  bool operator==(const CellKey& o) const { return X == o.X && Y == o.Y && Z == o.Z; }
};

struct CellHash
{
  std::size_t operator()(const CellKey& k) const
  {
    std::uint64_t h = static_cast<std::uint64_t>(k.X) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<std::uint64_t>(k.Y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= static_cast<std::uint64_t>(k.Z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h);
  }
};

std::int64_t CellOf(double x, double radius)
{
  // Clamped so that far-away centres share a cell instead of overflowing; the distance test
  // decides, so clamping costs time, never correctness.
  const double c = std::floor(x / radius);
  constexpr double limit = 4.0e18;
  return static_cast<std::int64_t>(std::max(-limit, std::min(limit, c)));
}
} // namespace

//------------------------------------------------------------------------------
const char* RuleAttributeName(RuleAttribute attribute)
{
  if (attribute == RuleAttribute::Score)
  {
    return "score";
  }
  for (const auto& entry : AttributeNames)
  {
    if (entry.second == attribute)
    {
      return entry.first;
    }
  }
  return "?";
}

//------------------------------------------------------------------------------
SelectionRule SelectionRule::Parse(const std::string& text)
{
  SelectionRule rule;
  rule.Root = Parser(text).ParseRule();
  return rule;
}

//------------------------------------------------------------------------------
std::string SelectionRule::ToString() const
{
  std::string out;
  Print(this->Root, out);
  return out;
}

//------------------------------------------------------------------------------
bool SelectionRule::Reads(RuleAttribute attribute) const
{
  if (attribute == RuleAttribute::Score)
  {
    return !this->ScoresRead().empty();
  }
  return ReadsAttribute(this->Root, attribute);
}

//------------------------------------------------------------------------------
std::vector<std::string> SelectionRule::ScoresRead() const
{
  std::vector<std::string> out;
  const auto& scores = ScoreDefinitions();
  for (std::size_t k = 0; k < scores.size(); ++k)
  {
    // "views" is the coverage times |V|.
    if (ReadsAttribute(this->Root, RuleAttribute::Score, k) ||
      (std::string(scores[k].Name) == "coverage" &&
        ReadsAttribute(this->Root, RuleAttribute::Views)))
    {
      out.push_back(scores[k].Name);
    }
  }
  return out;
}

//------------------------------------------------------------------------------
std::vector<std::uint8_t> SelectionRule::Evaluate(const SelectionRuleInputs& inputs) const
{
  return Evaluator(inputs, this->ToString()).Evaluate(this->Root);
}

//------------------------------------------------------------------------------
std::vector<std::int64_t> SelectionRule::Select(const SelectionRuleInputs& inputs) const
{
  const std::vector<std::uint8_t> mask = this->Evaluate(inputs);
  std::vector<std::int64_t> out;
  for (std::size_t i = 0; i < mask.size(); ++i)
  {
    if (mask[i])
    {
      out.push_back(static_cast<std::int64_t>(i));
    }
  }
  return out;
}

//------------------------------------------------------------------------------
std::vector<std::int64_t> SelectionRule::Apply(const std::vector<std::int64_t>& current,
  SelectionModifier modifier,
  const SelectionRuleInputs& inputs) const
{
  return CombineSelection(current, this->Select(inputs), modifier);
}

//------------------------------------------------------------------------------
std::vector<std::uint8_t> IsolatedGaussians(const GaussianCloud& cloud, double radius, int threads)
{
  if (!(radius > 0) || !std::isfinite(radius))
  {
    throw std::invalid_argument("isolated: the radius must be finite and greater than 0");
  }
  const std::size_t n = cloud.Count;
  if (cloud.Positions.size() != 3 * n)
  {
    throw std::invalid_argument("isolated: the scene holds no positions for its Gaussians");
  }
  std::vector<std::uint8_t> isolated(n, 0);
  std::vector<CellKey> keys(n);
  std::vector<std::uint8_t> finite(n, 0);
  std::unordered_map<CellKey, std::vector<std::uint32_t>, CellHash> cells;
  for (std::size_t i = 0; i < n; ++i)
  {
    const float* p = &cloud.Positions[3 * i];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    {
      continue;
    }
    finite[i] = 1;
    keys[i] = { CellOf(p[0], radius), CellOf(p[1], radius), CellOf(p[2], radius) };
    cells[keys[i]].push_back(static_cast<std::uint32_t>(i));
  }
  const double r2 = radius * radius;
  const long long count = static_cast<long long>(n);
#pragma omp parallel for schedule(dynamic, 4096) num_threads(ThreadCount(threads))
  for (long long ii = 0; ii < count; ++ii)
  {
    const std::size_t i = static_cast<std::size_t>(ii);
    if (!finite[i])
    {
      continue;
    }
    const float* p = &cloud.Positions[3 * i];
    bool alone = true;
    for (int dz = -1; dz <= 1 && alone; ++dz)
    {
      for (int dy = -1; dy <= 1 && alone; ++dy)
      {
        for (int dx = -1; dx <= 1 && alone; ++dx)
        {
          const auto it = cells.find({ keys[i].X + dx, keys[i].Y + dy, keys[i].Z + dz });
          if (it == cells.end())
          {
            continue;
          }
          for (std::uint32_t j : it->second)
          {
            if (j == i)
            {
              continue;
            }
            const float* q = &cloud.Positions[3 * static_cast<std::size_t>(j)];
            const double ex = static_cast<double>(p[0]) - q[0];
            const double ey = static_cast<double>(p[1]) - q[1];
            const double ez = static_cast<double>(p[2]) - q[2];
            if (ex * ex + ey * ey + ez * ez <= r2)
            {
              alone = false;
              break;
            }
          }
        }
      }
    }
    isolated[i] = alone ? 1 : 0;
  }
  return isolated;
}

} // namespace vis4gs

// SPDX-License-Identifier: BSD-3-Clause
#include "ScoreRegistry.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace vis4gs
{
namespace
{

// The parameters of ScoreSettings that the scores read (`vis4gs analyze`'s options).
const ScoreParameter ViewStride{ "view-stride",
  "int",
  "1",
  1,
  2147483647,
  "Use every k-th training view (|V| is the size of the subset)." };
const ScoreParameter CoverageResolution{ "coverage-resolution",
  "int",
  "1",
  1,
  8,
  "Resolution factor of the coverage pass: 1 (exact), 2, 4 or 8." };
const ScoreParameter LossResolution{ "loss-resolution",
  "int",
  "1",
  1,
  8,
  "Loss-map resolution factor: 1 (exact), 2, 4 or 8." };
const ScoreParameter Footprint{ "footprint",
  "choice",
  "alpha",
  0,
  1,
  "Footprint: alpha (the rasteriser's, exact) or ellipse (3 sigma)." };
const ScoreParameter FloatAccumulation{ "float-accumulation",
  "bool",
  "off",
  0,
  1,
  "Accumulate the footprint sums of the loss map in float instead of double." };
const ScoreParameter OcclusionThreshold{ "occlusion-threshold",
  "double",
  "0",
  0,
  1,
  "Occlusion-aware coverage: count a view only when max alpha*T >= T (0: off)." };
const ScoreParameter Lambda{ "lambda", "double", "0.2", 0, 1, "lambda of the loss map." };

std::vector<ScoreDefinition> MakeDefinitions()
{
  return {
    { "coverage",
      "ViewCoverage",
      "coverage",
      "View Coverage",
      SuspiciousEnd::Low,
      NeedsCameras,
      true,
      true,
      "E_VC: the fraction of the training views whose footprint of the Gaussian is not empty, "
      "in [0, 1].",
      { ViewStride, CoverageResolution, Footprint, OcclusionThreshold },
      &ScoreRequest::ViewCoverage,
      &GaussianScores::ViewCoverage },
    { "blur",
      "BlurScore",
      "blur",
      "Blur",
      SuspiciousEnd::High,
      NeedsCameras | NeedsImages,
      true,
      false,
      "E_B: the mean over the visible training views of the pixel coverage times the loss "
      "summed over the footprint, >= 0.",
      { ViewStride, LossResolution, Footprint, FloatAccumulation, Lambda },
      &ScoreRequest::Blur,
      &GaussianScores::BlurScore },
    { "needle",
      "NeedleScore",
      "needle_score",
      "Needle",
      SuspiciousEnd::High,
      NeedsCameras | NeedsImages,
      true,
      false,
      "E_N: the needle shape times the mean over the visible training views of the loss summed "
      "over the footprint, >= 0.",
      { ViewStride, LossResolution, Footprint, FloatAccumulation, Lambda },
      &ScoreRequest::Needle,
      &GaussianScores::NeedleScore },
    { "shape",
      "NeedleShape",
      "shape",
      "Needle shape",
      SuspiciousEnd::High,
      NeedsNothing,
      true,
      true,
      "s(g) = (3 - exp(H))/2 from the log-scales alone, in [0, 1] (1: one dominant axis).",
      {},
      &ScoreRequest::NeedleShape,
      &GaussianScores::NeedleShape },
    { "render-cost",
      "RenderCost",
      "render_cost",
      "Render cost",
      SuspiciousEnd::High,
      NeedsCameras,
      false,
      false,
      "R: the pixel evaluations the rasteriser spends on the Gaussian summed over the training "
      "views (pixels of its tiles that have not stopped before it), >= 0.",
      { ViewStride },
      &ScoreRequest::RenderCost,
      &GaussianScores::RenderCost },
    { "cost-per-contribution",
      "CostPerContribution",
      "cost_per_contribution",
      "Cost per contribution",
      SuspiciousEnd::High,
      NeedsCameras,
      false,
      false,
      "R/A: the render cost divided by the Gaussian's blending weight alpha*T summed over the "
      "training views' pixels; +inf when it costs and never blends, NaN when never evaluated.",
      { ViewStride },
      &ScoreRequest::CostPerContribution,
      &GaussianScores::CostPerContribution },
  };
}

} // namespace

//------------------------------------------------------------------------------
const std::vector<ScoreDefinition>& ScoreDefinitions()
{
  static const std::vector<ScoreDefinition> definitions = MakeDefinitions();
  return definitions;
}

//------------------------------------------------------------------------------
const ScoreDefinition* FindScore(const std::string& name)
{
  for (const ScoreDefinition& d : ScoreDefinitions())
  {
    if (name == d.Name || name == d.ArrayName)
    {
      return &d;
    }
  }
  return nullptr;
}

//------------------------------------------------------------------------------
std::string ScoreNames(const std::string& separator)
{
  std::string out;
  for (const ScoreDefinition& d : ScoreDefinitions())
  {
    out += (out.empty() ? "" : separator) + d.Name;
  }
  return out;
}

//------------------------------------------------------------------------------
std::string DefaultScoreList()
{
  std::string out;
  for (const ScoreDefinition& d : ScoreDefinitions())
  {
    if (d.DefaultOn)
    {
      out += (out.empty() ? "" : ",") + std::string(d.Name);
    }
  }
  return out;
}

//------------------------------------------------------------------------------
std::vector<const ScoreDefinition*> ParseScoreList(const std::string& list)
{
  std::vector<bool> wanted(ScoreDefinitions().size(), false);
  std::stringstream items(list);
  std::string item;
  while (std::getline(items, item, ','))
  {
    const auto first = item.find_first_not_of(" \t");
    if (first == std::string::npos)
    {
      continue;
    }
    item = item.substr(first, item.find_last_not_of(" \t") - first + 1);
    const ScoreDefinition* d = FindScore(item);
    if (!d || item != d->Name)
    {
      throw std::invalid_argument(
        "unknown score '" + item + "' (expected one of " + ScoreNames() + ")");
    }
    wanted[static_cast<std::size_t>(d - ScoreDefinitions().data())] = true;
  }
  std::vector<const ScoreDefinition*> out;
  for (std::size_t k = 0; k < wanted.size(); ++k)
  {
    if (wanted[k])
    {
      out.push_back(&ScoreDefinitions()[k]);
    }
  }
  return out;
}

//------------------------------------------------------------------------------
unsigned NeedsOf(const ScoreRequest& request)
{
  unsigned needs = NeedsNothing;
  for (const ScoreDefinition& d : ScoreDefinitions())
  {
    if (request.*(d.Request))
    {
      needs |= d.Needs;
    }
  }
  return needs;
}

//------------------------------------------------------------------------------
SuspiciousEnd SuspiciousEndOf(const std::string& arrayName)
{
  for (const ScoreDefinition& d : ScoreDefinitions())
  {
    if (arrayName == d.ArrayName)
    {
      return d.Suspicious;
    }
  }
  return SuspiciousEnd::None;
}

} // namespace vis4gs

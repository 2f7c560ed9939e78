// SPDX-License-Identifier: BSD-3-Clause
// The pieces a distributed score run is made of (issues 18 and 31): partials of view subsets
// that add up to one process's scores, views taken from a queue, slices finished in place, and
// the split of views by estimated cost. The scores themselves: TestArtifactScores.cxx.
#include "ArtifactScores.h"
#include "ArtifactScoresTestScenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{
using vis4gs::Camera;
using vis4gs::GaussianCloud;
using vis4gs_test::MakeCamera;
using vis4gs_test::OffsetImages;
using vis4gs_test::SetGaussian;
} // namespace

// The pieces a distributed run is made of (issue 18): partials over disjoint view subsets,
// added element by element (the compensated sums with AddCompensated()), finished, equal
// ComputeGaussianScores bit for bit; a view outside the selection is refused.
TEST(ArtifactScores, PartialsOfViewSubsetsAddUpToTheScores)
{
  GaussianCloud cloud;
  cloud.Resize(4, 0);
  SetGaussian(cloud, 0, 0, 0, 5, std::log(0.5f), std::log(0.3f), std::log(0.3f), 2);
  SetGaussian(cloud, 1, 0.3f, 0.1f, 4, std::log(0.02f), std::log(0.4f), std::log(0.01f), 1);
  SetGaussian(cloud, 2, 60, 0, -3, -2, -2, -2, 1); // seen by no view
  SetGaussian(cloud, 3, -0.2f, 0.2f, 6, -1.5f, -2.5f, -2, 0);
  const std::vector<Camera> cameras{
    MakeCamera(0), MakeCamera(10, true), MakeCamera(-1), MakeCamera(11, true), MakeCamera(0.5)
  };
  OffsetImages images{ &cloud, { 0.2f, 0.1f, 0.3f, 0.05f, 0.15f }, { false, false, false, true } };
  vis4gs::ScoreSettings settings;
  const auto whole = vis4gs::ComputeGaussianScores(cloud, cameras, settings, images);
  const std::vector<std::size_t> first{ 0, 3 }, second{ 1, 2, 4 };
  auto a = vis4gs::ComputeScorePartials(cloud, cameras, settings, first, images);
  const auto b = vis4gs::ComputeScorePartials(cloud, cameras, settings, second, images);
  for (std::size_t g = 0; g < cloud.Count; ++g)
  {
    a.CoverageViews[g] += b.CoverageViews[g];
    a.ScoredViews[g] += b.ScoredViews[g];
    vis4gs::AddCompensated(
      a.BlurSum[g], a.BlurCompensation[g], b.BlurSum[g], b.BlurCompensation[g]);
    vis4gs::AddCompensated(
      a.NeedleSum[g], a.NeedleCompensation[g], b.NeedleSum[g], b.NeedleCompensation[g]);
  }
  a.ViewsScored += b.ViewsScored;
  a.ViewsWithoutImage += b.ViewsWithoutImage;
  const auto summed = vis4gs::FinishGaussianScores(cloud, settings, a);
  EXPECT_EQ(summed.ViewCoverage, whole.ViewCoverage);
  EXPECT_EQ(summed.CoverageViews, whole.CoverageViews);
  EXPECT_EQ(summed.ScoredViews, whole.ScoredViews);
  EXPECT_EQ(summed.Flags, whole.Flags);
  EXPECT_EQ(summed.NeedleShape, whole.NeedleShape);
  EXPECT_EQ(summed.ViewsWithoutImage, 1u);
  EXPECT_EQ(summed.ViewsScored, whole.ViewsScored);
  EXPECT_EQ(summed.Warnings, whole.Warnings);
  EXPECT_GT(whole.BlurScore[0], 0);
  EXPECT_EQ(summed.BlurScore, whole.BlurScore);
  EXPECT_EQ(summed.NeedleScore, whole.NeedleScore);
  // No view at all: buffers sized for the cloud, all zero.
  const auto none =
    vis4gs::ComputeScorePartials(cloud, cameras, settings, std::vector<std::size_t>{}, images);
  EXPECT_EQ(none.CoverageViews, std::vector<std::uint32_t>(cloud.Count, 0));
  EXPECT_EQ(none.BlurSum, std::vector<double>(cloud.Count, 0.0));
  EXPECT_EQ(none.ViewIndices.size(), cameras.size());
  // A view the settings do not select.
  vis4gs::ScoreSettings stride;
  stride.ViewStride = 2;
  EXPECT_THROW(
    vis4gs::ComputeScorePartials(cloud, cameras, stride, { 1 }, images), std::invalid_argument);
  // Partials that do not match the cloud.
  auto wrong = a;
  wrong.BlurSum.pop_back();
  EXPECT_THROW(vis4gs::FinishGaussianScores(cloud, settings, wrong), std::invalid_argument);
}

// Views taken from a queue (dynamic balancing between processes, issue 31): a queue that hands
// out a list in order gives that list's partials bit for bit; another order gives the same
// counts and the same sums up to their order; RenderedViews says which views were taken; a view
// given twice or not selected is an error; without blur/needle every view is taken first.
TEST(ArtifactScores, ViewsFromAQueue)
{
  GaussianCloud cloud;
  cloud.Resize(4, 0);
  SetGaussian(cloud, 0, 0, 0, 5, std::log(0.5f), std::log(0.3f), std::log(0.3f), 2);
  SetGaussian(cloud, 1, 0.3f, 0.1f, 4, std::log(0.02f), std::log(0.4f), std::log(0.01f), 1);
  SetGaussian(cloud, 2, -0.2f, 0.2f, 6, -1.5f, -2.5f, -2, 0);
  SetGaussian(cloud, 3, 0.1f, -0.3f, 5, -2, -1, -2.5f, 1);
  const std::vector<Camera> cameras{
    MakeCamera(0), MakeCamera(-1), MakeCamera(0.5), MakeCamera(0.25)
  };
  OffsetImages images{ &cloud, { 0.2f, 0.1f, 0.3f, 0.05f }, { false, false, false, false } };
  vis4gs::ScoreSettings settings;
  settings.Request.RenderCost = settings.Request.CostPerContribution = true;
  auto queueOf = [](std::vector<std::size_t> order, std::size_t* calls = nullptr)
  {
    return [order, calls, k = std::size_t(0)](std::size_t& view) mutable
    {
      if (calls)
      {
        ++*calls;
      }
      if (k == order.size())
      {
        return false;
      }
      view = order[k++];
      return true;
    };
  };
  const std::vector<std::size_t> list{ 2, 0, 3 };
  const auto fromList = vis4gs::ComputeScorePartials(cloud, cameras, settings, list, images);
  const auto fromQueue =
    vis4gs::ComputeScorePartials(cloud, cameras, settings, queueOf(list), images);
  EXPECT_EQ(fromList.RenderedViews, list);
  EXPECT_EQ(fromQueue.RenderedViews, list);
  EXPECT_EQ(fromQueue.CoverageViews, fromList.CoverageViews);
  EXPECT_EQ(fromQueue.ScoredViews, fromList.ScoredViews);
  EXPECT_EQ(fromQueue.BlurSum, fromList.BlurSum);
  EXPECT_EQ(fromQueue.NeedleSum, fromList.NeedleSum);
  EXPECT_EQ(fromQueue.RenderCostSum, fromList.RenderCostSum);
  EXPECT_EQ(fromQueue.ContributionSum, fromList.ContributionSum);
  EXPECT_EQ(fromQueue.ViewsScored, 3u);
  const auto reversed =
    vis4gs::ComputeScorePartials(cloud, cameras, settings, queueOf({ 3, 0, 2 }), images);
  EXPECT_EQ(reversed.CoverageViews, fromList.CoverageViews);
  EXPECT_EQ(reversed.ScoredViews, fromList.ScoredViews);
  EXPECT_EQ(reversed.RenderCostSum, fromList.RenderCostSum); // integers: exact in any order
  ASSERT_GT(fromList.BlurSum[0], 0);
  for (std::size_t g = 0; g < cloud.Count; ++g)
  {
    EXPECT_NEAR(reversed.BlurSum[g], fromList.BlurSum[g], 1e-13 * std::abs(fromList.BlurSum[g]));
    EXPECT_NEAR(
      reversed.NeedleSum[g], fromList.NeedleSum[g], 1e-13 * std::abs(fromList.NeedleSum[g]));
  }
  // The compensated sums make the finished scores independent of the order bit for bit.
  const auto finishedList = vis4gs::FinishGaussianScores(cloud, settings, fromList);
  const auto finishedReversed = vis4gs::FinishGaussianScores(cloud, settings, reversed);
  EXPECT_EQ(finishedReversed.BlurScore, finishedList.BlurScore);
  EXPECT_EQ(finishedReversed.NeedleScore, finishedList.NeedleScore);
  EXPECT_EQ(finishedReversed.CostPerContribution, finishedList.CostPerContribution);
  EXPECT_THROW(vis4gs::ComputeScorePartials(cloud, cameras, settings, queueOf({ 1, 1 }), images),
    std::invalid_argument);
  vis4gs::ScoreSettings stride;
  stride.ViewStride = 2;
  EXPECT_THROW(vis4gs::ComputeScorePartials(cloud, cameras, stride, queueOf({ 0, 1 }), images),
    std::invalid_argument);
  // Coverage alone (no image pass): the queue is emptied before the first view is rendered.
  vis4gs::ScoreSettings coverage;
  coverage.Request.Blur = coverage.Request.Needle = false;
  std::size_t calls = 0, callsAtFirstView = 0;
  const auto covered = vis4gs::ComputeScorePartials(cloud,
    cameras,
    coverage,
    queueOf({ 1, 3 }, &calls),
    {},
    {},
    [&](std::size_t) { callsAtFirstView = callsAtFirstView ? callsAtFirstView : calls; });
  EXPECT_EQ(covered.RenderedViews, (std::vector<std::size_t>{ 1, 3 }));
  EXPECT_EQ(callsAtFirstView, 3u);
  const auto coveredList =
    vis4gs::ComputeScorePartials(cloud, cameras, coverage, std::vector<std::size_t>{ 1, 3 });
  EXPECT_EQ(covered.CoverageViews, coveredList.CoverageViews);
}

// A distributed run finishes each process's slice of the Gaussians in place (issue 31): the
// slices' scores, put end to end, are the whole finish's bit for bit (the same operations on the
// same sums, no entry outside the slice read), their counts add up to its counts and
// ScoreWarnings() of the sums gives its warnings.
TEST(ArtifactScores, FinishedSlicesAreTheWholeFinish)
{
  GaussianCloud cloud;
  cloud.Resize(5, 0);
  SetGaussian(cloud, 0, 0, 0, 5, std::log(0.5f), std::log(0.3f), std::log(0.3f), 2);
  SetGaussian(cloud, 1, 0.3f, 0.1f, 4, std::log(0.02f), std::log(0.4f), std::log(0.01f), 1);
  SetGaussian(cloud, 2, 60, 0, -3, -2, -2, -2, 1); // seen by no view
  SetGaussian(cloud, 3, -0.2f, 0.2f, 6, -1.5f, -2.5f, -2, 0);
  SetGaussian(cloud, 4, std::nanf(""), 0, 5, -2, -2, -2, 1); // invalid: flagged
  const std::vector<Camera> cameras{ MakeCamera(0), MakeCamera(-1), MakeCamera(0.5) };
  OffsetImages images{ &cloud, { 0.2f, 0.1f, 0.3f }, { false, true, false } };
  vis4gs::ScoreSettings settings;
  settings.Request.RenderCost = settings.Request.CostPerContribution = true;
  const auto partials = vis4gs::ComputeScorePartials(
    cloud, cameras, settings, vis4gs::SelectViews(cameras, settings), images);
  const auto whole = vis4gs::FinishGaussianScores(cloud, settings, partials);
  ASSERT_EQ(whole.NoCoverageViewCount, 2u);
  ASSERT_EQ(whole.InvalidCount, 1u);
  ASSERT_EQ(whole.Warnings.size(), 4u); // without image, not evaluated, no view, invalid
  for (const std::vector<std::size_t>& cuts :
    { std::vector<std::size_t>{ 0, 5 }, { 0, 2, 5 }, { 0, 0, 3, 3, 5 }, { 0, 1, 2, 3, 4, 5 } })
  {
    vis4gs::GaussianScores joined;
    joined.ViewCoverage.assign(cloud.Count, -1.0);
    for (auto member : { &vis4gs::GaussianScores::BlurScore,
           &vis4gs::GaussianScores::NeedleScore,
           &vis4gs::GaussianScores::NeedleShape,
           &vis4gs::GaussianScores::RenderCost,
           &vis4gs::GaussianScores::CostPerContribution })
    {
      (joined.*member).assign(cloud.Count, -1.0);
    }
    joined.Flags.assign(cloud.Count, 0xff);
    std::size_t noCoverage = 0, noScored = 0, invalid = 0, notEvaluated = 0;
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k)
    {
      const std::size_t first = cuts[k], count = cuts[k + 1] - cuts[k];
      // The slice's sums are in place in vectors of the cloud's size; the others' entries are
      // poisoned, so that reading one would show.
      vis4gs::ScorePartials slice = partials;
      for (std::vector<std::uint32_t>* v : slice.PerGaussianCounts())
      {
        for (std::size_t g = 0; g < v->size(); ++g)
        {
          (*v)[g] = g >= first && g < first + count ? (*v)[g] : 0xdeadbeefu;
        }
      }
      for (std::vector<double>* v : slice.PerGaussianSums())
      {
        for (std::size_t g = 0; g < v->size(); ++g)
        {
          (*v)[g] = g >= first && g < first + count ? (*v)[g] : std::nan("");
        }
      }
      const auto part = vis4gs::FinishGaussianScores(cloud, settings, slice, first, count);
      ASSERT_EQ(part.Flags.size(), cloud.Count);
      for (auto member : { &vis4gs::GaussianScores::ViewCoverage,
             &vis4gs::GaussianScores::BlurScore,
             &vis4gs::GaussianScores::NeedleScore,
             &vis4gs::GaussianScores::NeedleShape,
             &vis4gs::GaussianScores::RenderCost,
             &vis4gs::GaussianScores::CostPerContribution })
      {
        ASSERT_EQ((part.*member).size(), cloud.Count);
        std::copy((part.*member).begin() + first,
          (part.*member).begin() + first + count,
          (joined.*member).begin() + first);
      }
      std::copy(part.Flags.begin() + first,
        part.Flags.begin() + first + count,
        joined.Flags.begin() + first);
      noCoverage += part.NoCoverageViewCount;
      noScored += part.NoScoredViewCount;
      invalid += part.InvalidCount;
      notEvaluated += part.NotEvaluatedCount;
      joined.ViewsUsed = part.ViewsUsed;
      joined.ViewsWithoutImage = part.ViewsWithoutImage;
    }
    const std::string what = "cut into " + std::to_string(cuts.size() - 1);
    auto same = [&what](const std::vector<double>& a, const std::vector<double>& b)
    {
      ASSERT_EQ(a.size(), b.size()) << what;
      for (std::size_t g = 0; g < a.size(); ++g)
      {
        // Bit for bit, NaN (R/A never evaluated) included.
        EXPECT_EQ(std::memcmp(&a[g], &b[g], sizeof(double)), 0) << what << ", Gaussian " << g;
      }
    };
    same(joined.ViewCoverage, whole.ViewCoverage);
    same(joined.BlurScore, whole.BlurScore);
    same(joined.NeedleScore, whole.NeedleScore);
    same(joined.NeedleShape, whole.NeedleShape);
    same(joined.RenderCost, whole.RenderCost);
    same(joined.CostPerContribution, whole.CostPerContribution);
    EXPECT_EQ(joined.Flags, whole.Flags) << what;
    EXPECT_EQ(noCoverage, whole.NoCoverageViewCount) << what;
    EXPECT_EQ(noScored, whole.NoScoredViewCount) << what;
    EXPECT_EQ(invalid, whole.InvalidCount) << what;
    EXPECT_EQ(notEvaluated, whole.NotEvaluatedCount) << what;
    joined.NoCoverageViewCount = noCoverage;
    joined.InvalidCount = invalid;
    joined.NotEvaluatedCount = notEvaluated;
    EXPECT_EQ(vis4gs::ScoreWarnings(joined, settings.Request, cloud.Count), whole.Warnings) << what;
  }
  // A range outside the cloud.
  EXPECT_THROW(
    vis4gs::FinishGaussianScores(cloud, settings, partials, 3, 3), std::invalid_argument);
}

// The split: every view to exactly one process, largest cost first onto the least-loaded one
// (an LPT schedule: within 4/3 of the optimum), deterministic, idle processes when views are
// fewer, costs from pixels x Gaussians in view.
TEST(ArtifactScores, SplitViewsByCost)
{
  const std::vector<double> costs{ 5, 1, 1, 1, 1, 1, 4, 2 };
  const std::vector<int> owner = vis4gs::SplitViewsByCost(costs, 2);
  double load[2] = { 0, 0 };
  for (std::size_t v = 0; v < costs.size(); ++v)
  {
    ASSERT_TRUE(owner[v] == 0 || owner[v] == 1);
    load[owner[v]] += costs[v];
  }
  EXPECT_EQ(load[0], 8); // 5+1+1+1 and 4+2+1+1: the optimum here
  EXPECT_EQ(load[1], 8);
  EXPECT_EQ(owner, vis4gs::SplitViewsByCost(costs, 2));
  // One costly view and ten cheap ones: a split by count would give 6 + 5 views.
  const std::vector<int> skewed = vis4gs::SplitViewsByCost({ 10, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1 }, 2);
  EXPECT_EQ(std::count(skewed.begin(), skewed.end(), skewed[0]), 1); // the big view alone
  const std::vector<int> few = vis4gs::SplitViewsByCost({ 3, 2 }, 5);
  EXPECT_EQ(few, (std::vector<int>{ 0, 1 })); // processes 2..4 get nothing
  EXPECT_TRUE(vis4gs::SplitViewsByCost({}, 3).empty());
  EXPECT_THROW(vis4gs::SplitViewsByCost({ 1 }, 0), std::invalid_argument);

  // Costs: a view that sees the Gaussians costs more than one looking away, and pixels count.
  GaussianCloud cloud;
  cloud.Resize(2, 0);
  SetGaussian(cloud, 0, 0, 0, 5, -2, -2, -2, 1);
  SetGaussian(cloud, 1, 0.2f, 0, 6, -2, -2, -2, 1);
  const std::vector<Camera> cameras{
    MakeCamera(0), MakeCamera(0, true), MakeCamera(0, false, 128, 96)
  };
  const auto cost = vis4gs::EstimateViewCosts(cloud, cameras, { 0, 1, 2 }, {});
  ASSERT_EQ(cost.size(), 3u);
  EXPECT_GT(cost[0], cost[1]);
  EXPECT_DOUBLE_EQ(cost[2], 4 * cost[0]);
  EXPECT_GT(cost[1], 0);
}

// Compensated sums (ScorePartials::BlurCompensation): terms of very different magnitudes added
// in any order, or split into two partial sums combined afterwards, give the same value bit for
// bit, where the plain double sums of the same orders differ; infinities and NaN pass through.
TEST(ArtifactScores, CompensatedSumsDoNotDependOnTheOrder)
{
  std::mt19937 random(31);
  std::lognormal_distribution<double> magnitude(0.0, 6.0);
  std::vector<double> terms(194);
  for (double& t : terms)
  {
    t = magnitude(random);
  }
  auto compensated = [](const std::vector<double>& order, std::size_t split)
  {
    double a = 0, b = 0;
    float ca = 0, cb = 0;
    for (std::size_t k = 0; k < order.size(); ++k)
    {
      vis4gs::AddCompensated(k < split ? a : b, k < split ? ca : cb, order[k]);
    }
    vis4gs::AddCompensated(a, ca, b, cb);
    return a + static_cast<double>(ca);
  };
  auto plain = [](const std::vector<double>& order)
  {
    double s = 0;
    for (double t : order)
    {
      s += t;
    }
    return s;
  };
  const double reference = compensated(terms, terms.size());
  bool plainDiffered = false;
  for (int trial = 0; trial < 200; ++trial)
  {
    std::vector<double> order = terms;
    std::shuffle(order.begin(), order.end(), random);
    const std::size_t split = static_cast<std::size_t>(trial) % (order.size() + 1);
    EXPECT_EQ(compensated(order, split), reference) << "trial " << trial;
    plainDiffered = plainDiffered || plain(order) != plain(terms);
  }
  EXPECT_TRUE(plainDiffered); // (else the terms would not test anything)
  // Special values: the sum is what a plain sum gives.
  const double inf = std::numeric_limits<double>::infinity();
  double s = 1.0;
  float c = 0;
  vis4gs::AddCompensated(s, c, inf);
  vis4gs::AddCompensated(s, c, 1e-30);
  EXPECT_EQ(s + static_cast<double>(c), inf);
  vis4gs::AddCompensated(s, c, -inf);
  EXPECT_TRUE(std::isnan(s + static_cast<double>(c)));
}

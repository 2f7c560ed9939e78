// SPDX-License-Identifier: BSD-3-Clause
// Render cost R(g) and cost per contribution R/A(g) (ArtifactScores.h) against a brute-force
// double-precision loop over every pixel of every view: the pixel's tile list (the Gaussians
// whose tile rectangle holds the pixel's tile, in depth order) walked front to back as the
// reference forward pass does (reference §2.6), counting each list entry the pixel evaluates
// and summing alpha*T where it blends. The projection (mean, conic, tile rectangle, depth) is
// the rasteriser's float projection; the tile kernels, binning and per-Gaussian counting of
// the compositing are what is checked. Then the stiff cases: a Gaussian behind every camera
// and one outside every view (R = 0, R/A NaN), opacity 0 (R > 0, A = 0: +inf), opacity 1,
// tiny and huge scales.
#include "ArtifactScores.h"
#include "RasterKernel.h"
#include "Rasterizer.h"
#include "ScoreRegistry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

namespace
{

using vis4gs::Camera;
using vis4gs::GaussianCloud;

// Looking down +z from (ox, 0, cz), w x h pixels.
Camera MakeView(double ox, double cz, int w, int h)
{
  Camera c;
  c.Name = "view";
  c.Width = w;
  c.Height = h;
  c.Fx = c.Fy = 60;
  c.Cx = w / 2.0;
  c.Cy = h / 2.0;
  c.WorldToCamera = { 1, 0, 0, -ox, 0, 1, 0, 0, 0, 0, 1, -cz, 0, 0, 0, 1 };
  return c;
}

void Set(GaussianCloud& cloud, std::size_t i, const float p[3], const float ls[3], float logit)
{
  for (int k = 0; k < 3; ++k)
  {
    cloud.Positions[3 * i + k] = p[k];
    cloud.LogScales[3 * i + k] = ls[k];
    cloud.SH[3 * i + k] = 0.1f * static_cast<float>(k);
  }
  const float q[4] = { 0.9f, 0.1f * static_cast<float>(i % 3), 0.2f, -0.1f };
  for (int k = 0; k < 4; ++k)
  {
    cloud.Rotations[4 * i + k] = q[k];
  }
  cloud.OpacityLogits[i] = logit;
}

struct BruteForce
{
  std::vector<double> Cost, Contribution;
  /// Gaussians evaluated at a pixel where a float/double decision could flip (alpha within
  /// 1e-5 relative of 1/255, or T(1 - alpha) within 1e-5 relative of 1e-4): left out of the
  /// exact comparison (DESIGN §4: such pixels are counted, not compared).
  std::vector<bool> Borderline;
};

BruteForce Reference(const GaussianCloud& cloud, const std::vector<Camera>& views)
{
  const std::size_t n = cloud.Count;
  BruteForce out{
    std::vector<double>(n, 0.0), std::vector<double>(n, 0.0), std::vector<bool>(n, false)
  };
  vis4gs::RasterSettings settings;
  settings.ComputeColors = false;
  const double minAlpha = 1.0 / 255.0, stop = 0.0001;
  auto near = [](double a, double b) { return std::abs(a - b) <= 1e-5 * b; };
  for (const Camera& view : views)
  {
    const auto proj = vis4gs::ProjectGaussians<float>(cloud, view, settings);
    for (int y = 0; y < view.Height; ++y)
    {
      for (int x = 0; x < view.Width; ++x)
      {
        const int tx = x / 16, ty = y / 16;
        std::vector<std::size_t> list;
        for (std::size_t i = 0; i < n; ++i)
        {
          const auto& g = proj.Gaussians[i];
          if (g.IsVisible() && tx >= g.TileRect[0] && tx < g.TileRect[2] && ty >= g.TileRect[1] &&
            ty < g.TileRect[3])
          {
            list.push_back(i);
          }
        }
        std::stable_sort(list.begin(),
          list.end(),
          [&](std::size_t a, std::size_t b)
          { return proj.Gaussians[a].Depth < proj.Gaussians[b].Depth; });
        double T = 1;
        std::vector<std::size_t> evaluated;
        bool borderline = false;
        for (std::size_t i : list)
        {
          const auto& g = proj.Gaussians[i];
          out.Cost[i] += 1;
          evaluated.push_back(i);
          const double dx = static_cast<double>(g.U) - x, dy = static_cast<double>(g.V) - y;
          const double power = -0.5 * (double(g.ConicA) * dx * dx + double(g.ConicC) * dy * dy) -
            double(g.ConicB) * dx * dy;
          if (power > 0)
          {
            continue;
          }
          const double alpha = std::min(0.99, double(g.Opacity) * std::exp(power));
          borderline = borderline || near(alpha, minAlpha);
          if (alpha < minAlpha)
          {
            continue;
          }
          const double next = T * (1 - alpha);
          borderline = borderline || near(next, stop);
          if (next < stop)
          {
            break;
          }
          out.Contribution[i] += alpha * T;
          T = next;
        }
        if (borderline)
        {
          for (std::size_t i : evaluated)
          {
            out.Borderline[i] = true;
          }
        }
      }
    }
  }
  return out;
}

vis4gs::GaussianScores RenderCostOf(const GaussianCloud& cloud, const std::vector<Camera>& views)
{
  vis4gs::ScoreSettings settings;
  settings.Request = vis4gs::ScoreRequest{ false, false, false, false, true, true };
  return vis4gs::ComputeGaussianScores(cloud, views, settings);
}

} // namespace

TEST(RenderCost, EqualsBruteForcePerPixelLoop)
{
  // 300 Gaussians in a slab in front of three cameras, overlapping so that many pixels stop
  // (T < 1e-4) before the end of their lists; scales from sub-pixel to several tiles.
  const std::size_t n = 300;
  GaussianCloud cloud;
  cloud.Resize(n, 0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1, 1);
  for (std::size_t i = 0; i < n; ++i)
  {
    const float p[3] = { 0.8f * u(rng), 0.6f * u(rng), 4.0f + 0.8f * u(rng) };
    const float ls[3] = { -3.2f + 1.4f * u(rng), -3.2f + 1.4f * u(rng), -3.2f + 1.4f * u(rng) };
    Set(cloud, i, p, ls, 3.0f * u(rng) + 1.0f);
  }
  const std::vector<Camera> views = {
    MakeView(0, 0, 64, 48), MakeView(0.3, -0.5, 80, 40), MakeView(-0.2, 0.4, 37, 53)
  };
  const vis4gs::GaussianScores scores = RenderCostOf(cloud, views);
  const BruteForce ref = Reference(cloud, views);
  ASSERT_EQ(scores.RenderCost.size(), n);
  ASSERT_EQ(scores.CostPerContribution.size(), n);
  std::size_t compared = 0, borderline = 0, stopped = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (ref.Borderline[i])
    {
      ++borderline;
      continue;
    }
    ++compared;
    EXPECT_EQ(scores.RenderCost[i], ref.Cost[i]) << "Gaussian " << i;
    if (ref.Contribution[i] > 0)
    {
      const double expected = ref.Cost[i] / ref.Contribution[i];
      EXPECT_NEAR(scores.CostPerContribution[i], expected, 1e-4 * expected) << "Gaussian " << i;
    }
    else if (ref.Cost[i] > 0)
    {
      EXPECT_EQ(scores.CostPerContribution[i], std::numeric_limits<double>::infinity());
    }
    else
    {
      EXPECT_TRUE(std::isnan(scores.CostPerContribution[i])) << "Gaussian " << i;
    }
  }
  // The comparison means something: most Gaussians compared, and the lists are cut short.
  EXPECT_LE(borderline, n / 20);
  EXPECT_GE(compared, n - n / 20);
  // Early termination happened: the costs are below the "every pixel of every tile" bound.
  vis4gs::RasterSettings plain;
  for (const Camera& view : views)
  {
    const auto proj = vis4gs::ProjectGaussians<float>(cloud, view, plain);
    const auto bins = vis4gs::BinGaussians(proj, 0);
    vis4gs::RasterImage<float> image;
    vis4gs::RasterWorkCounts work;
    vis4gs::CompositeTiles(proj, bins, plain, image, nullptr, &work);
    double tilePixels = 0;
    for (const auto& g : proj.Gaussians)
    {
      if (g.IsVisible())
      {
        for (int ty = g.TileRect[1]; ty < g.TileRect[3]; ++ty)
        {
          for (int tx = g.TileRect[0]; tx < g.TileRect[2]; ++tx)
          {
            tilePixels += std::min(16, view.Width - 16 * tx) * std::min(16, view.Height - 16 * ty);
          }
        }
      }
    }
    stopped += work.ReferenceEvaluations < tilePixels ? 1 : 0;
  }
  EXPECT_EQ(stopped, views.size()) << "no pixel stopped early: the test would not test it";
  // The per-view work counter is the sum of the per-Gaussian costs (one view alone).
  const auto one = RenderCostOf(cloud, { views[0] });
  {
    const auto proj = vis4gs::ProjectGaussians<float>(cloud, views[0], plain);
    const auto bins = vis4gs::BinGaussians(proj, 0);
    vis4gs::RasterImage<float> image;
    vis4gs::RasterWorkCounts work;
    vis4gs::CompositeTiles(proj, bins, plain, image, nullptr, &work);
    EXPECT_EQ(std::accumulate(one.RenderCost.begin(), one.RenderCost.end(), 0.0),
      static_cast<double>(work.ReferenceEvaluations));
  }
}

TEST(RenderCost, StiffCases)
{
  GaussianCloud cloud;
  cloud.Resize(7, 0);
  const float inf = std::numeric_limits<float>::infinity();
  const float mid[3] = { -2.0f, -2.0f, -2.0f };
  const float front[3] = { 0.0f, 0.0f, 5.0f };
  const float behind[3] = { 0.0f, 0.0f, -5.0f };
  const float aside[3] = { 500.0f, 0.0f, 5.0f };
  const float tiny[3] = { -30.0f, -30.0f, -30.0f };
  const float huge[3] = { 3.0f, 3.0f, 3.0f };
  const float left[3] = { -0.3f, 0.0f, 5.0f };
  const float leftBehind[3] = { -0.3f, 0.0f, 5.2f };
  const float near[3] = { 0.0f, 0.0f, 4.5f };
  const float far[3] = { 0.0f, 0.0f, 6.0f };
  Set(cloud, 0, behind, mid, 2.0f); // behind the camera: never evaluated
  Set(cloud, 1, aside, mid, 2.0f);  // outside the view: never evaluated
  Set(cloud, 2, front, mid, -inf);  // opacity 0: evaluated, never blended
  Set(cloud, 3, left, mid, inf);    // opacity 1 (alpha capped at 0.99)
  Set(cloud, 4, near, tiny, 2.0f);  // sub-pixel: the 0.3 dilation still gives a footprint
  Set(cloud, 5, far, huge, 0.0f);   // covers the whole view
  Set(cloud, 6, leftBehind, mid, 0.0f);
  const Camera view = MakeView(0, 0, 64, 48);
  const vis4gs::GaussianScores scores = RenderCostOf(cloud, { view });
  const BruteForce ref = Reference(cloud, { view });
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    EXPECT_FALSE(ref.Borderline[i]) << "Gaussian " << i;
    EXPECT_EQ(scores.RenderCost[i], ref.Cost[i]) << "Gaussian " << i;
  }
  // Never evaluated: R = 0, R/A NaN, and a warning counts them.
  for (std::size_t i : { 0, 1 })
  {
    EXPECT_EQ(scores.RenderCost[i], 0.0);
    EXPECT_TRUE(std::isnan(scores.CostPerContribution[i]));
  }
  EXPECT_EQ(scores.NotEvaluatedCount, 2u);
  EXPECT_FALSE(scores.Warnings.empty());
  // Opacity 0: it costs every pixel of its tiles and never shows.
  EXPECT_GT(scores.RenderCost[2], 0.0);
  EXPECT_EQ(scores.CostPerContribution[2], std::numeric_limits<double>::infinity());
  // Opacity 1 in front of another Gaussian at the same place: that one's pixels where the
  // first has alpha 0.99 still cost, but contribute at most 1 % of their alpha.
  EXPECT_GT(ref.Contribution[3], 0.0);
  EXPECT_NEAR(scores.CostPerContribution[3],
    ref.Cost[3] / ref.Contribution[3],
    1e-4 * ref.Cost[3] / ref.Contribution[3]);
  // Tiny: evaluated over its one tile, blended at about one pixel.
  EXPECT_GE(scores.RenderCost[4], 1.0);
  EXPECT_LE(scores.RenderCost[4], 4 * 256.0);
  // Huge: binned into every tile of the view.
  EXPECT_EQ(scores.RenderCost[5], ref.Cost[5]);
  EXPECT_GT(scores.RenderCost[5], 0.0);
  for (std::size_t i : { 3, 4, 5, 6 })
  {
    EXPECT_TRUE(std::isfinite(scores.CostPerContribution[i]) && scores.CostPerContribution[i] > 0)
      << "Gaussian " << i;
  }
}

TEST(RenderCost, PartialsOfViewSubsetsAddUp)
{
  GaussianCloud cloud;
  cloud.Resize(40, 0);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1, 1);
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    const float p[3] = { 0.5f * u(rng), 0.4f * u(rng), 4.0f + u(rng) };
    const float ls[3] = { -3 + u(rng), -3 + u(rng), -3 + u(rng) };
    Set(cloud, i, p, ls, 2 * u(rng));
  }
  const std::vector<Camera> views = {
    MakeView(0, 0, 48, 32), MakeView(0.2, 0, 48, 32), MakeView(-0.2, 0.3, 32, 32)
  };
  vis4gs::ScoreSettings settings;
  settings.Request = vis4gs::ScoreRequest{ false, false, false, false, true, true };
  const auto whole = vis4gs::ComputeGaussianScores(cloud, views, settings);
  auto a = vis4gs::ComputeScorePartials(cloud, views, settings, { 0, 2 });
  auto b = vis4gs::ComputeScorePartials(cloud, views, settings, { 1 });
  // The reduction a process does: every per-Gaussian sum, without knowing the scores (the
  // compensated ones with AddCompensated()).
  const auto sa = a.PerGaussianSums(), sb = b.PerGaussianSums();
  for (std::size_t k = 0; k < sa.size(); ++k)
  {
    for (std::size_t i = 0; i < sa[k]->size(); ++i)
    {
      (*sa[k])[i] += (*sb[k])[i];
    }
  }
  const auto ca = a.CompensatedSums(), cb = b.CompensatedSums();
  for (std::size_t k = 0; k < ca.size(); ++k)
  {
    for (std::size_t i = 0; i < ca[k].first->size(); ++i)
    {
      vis4gs::AddCompensated(
        (*ca[k].first)[i], (*ca[k].second)[i], (*cb[k].first)[i], (*cb[k].second)[i]);
    }
  }
  const auto finished = vis4gs::FinishGaussianScores(cloud, settings, std::move(a));
  EXPECT_EQ(finished.RenderCost, whole.RenderCost);
  // (compensated sums: bit for bit, whatever the split)
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    const double x = finished.CostPerContribution[i], y = whole.CostPerContribution[i];
    EXPECT_TRUE((std::isnan(x) && std::isnan(y)) || x == y) << i << ": " << x << " " << y;
  }
}

TEST(RenderCost, SharedWithTheScorePassIsTheSame)
{
  // Asked with blur and needle at full resolution, the render cost comes from the score pass's
  // compositing (one projection per view); alone, or beside a lower-resolution score pass, it
  // has its own. The numbers must not depend on which, nor on the thread count: the per-tile
  // sums are added per Gaussian in list order, not in the order threads finish tiles.
  GaussianCloud cloud;
  cloud.Resize(120, 0);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1, 1);
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    const float p[3] = { 0.6f * u(rng), 0.4f * u(rng), 4.0f + u(rng) };
    const float ls[3] = { -3 + u(rng), -3 + u(rng), -3 + u(rng) };
    Set(cloud, i, p, ls, 2 * u(rng) + 1);
  }
  std::vector<Camera> views = {
    MakeView(0, 0, 64, 48), MakeView(0.2, 0, 64, 48), MakeView(-0.2, 0.3, 48, 48)
  };
  auto grey = [](std::size_t index, const Camera& c, vis4gs::Image& image)
  {
    if (index == 1)
    {
      return false; // a view without image: the score pass skips it, the cost pass does not
    }
    image.Width = c.Width;
    image.Height = c.Height;
    image.Channels = 3;
    image.Pixels.assign(3 * static_cast<std::size_t>(c.Width) * c.Height, 0.4f);
    return true;
  };
  const vis4gs::GaussianScores alone = RenderCostOf(cloud, views);
  for (int variant = 0; variant < 5; ++variant)
  {
    vis4gs::ScoreSettings settings;
    settings.Request.RenderCost = settings.Request.CostPerContribution = true;
    settings.SharedProjection = variant != 1;       // 1: the per-view compositing path
    settings.LossResolution = variant == 2 ? 2 : 1; // 2: not shared, a pass of its own
    settings.Threads = variant == 3 ? 1 : variant == 4 ? 3 : 0;
    const auto with = vis4gs::ComputeGaussianScores(cloud, views, settings, grey);
    EXPECT_EQ(with.RenderCost, alone.RenderCost) << "variant " << variant;
    for (std::size_t i = 0; i < cloud.Count; ++i)
    {
      const double x = with.CostPerContribution[i], y = alone.CostPerContribution[i];
      EXPECT_TRUE(x == y || (std::isnan(x) && std::isnan(y)))
        << "variant " << variant << ", Gaussian " << i << ": " << x << " vs " << y;
    }
    EXPECT_FALSE(with.BlurScore.empty());
  }
}

// SPDX-License-Identifier: BSD-3-Clause
#include "ArtifactScores.h"

#include "FastCoverage.h"
#include "GaussianMath.h"
#include "NeedleShape.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

namespace vis4gs
{
namespace
{

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point since)
{
  return std::chrono::duration<double>(Clock::now() - since).count();
}

bool ValidFactor(int f)
{
  return f == 1 || f == 2 || f == 4 || f == 8;
}

Camera ViewAt(const Camera& camera, int factor)
{
  if (factor == 1)
  {
    return camera;
  }
  return camera.Resized(LossMapSize(camera.Width, factor), LossMapSize(camera.Height, factor));
}

/// Parameter @p k of Gaussian @p i, or @p fallback when the request left the array out.
float Param(const std::vector<float>& values, std::size_t i, int width, int k, float fallback)
{
  return values.empty() ? fallback : values[static_cast<std::size_t>(width) * i + k];
}

/// The class the renderer gives Gaussian @p i (Documentation/special-values.md), so a
/// Gaussian it draws is never flagged and one it skips always is.
GaussianClass ClassOf(const GaussianCloud& cloud, std::size_t i)
{
  float pos[3], ls[3], rot[4];
  for (int k = 0; k < 3; ++k)
  {
    pos[k] = Param(cloud.Positions, i, 3, k, 0.0f);
    ls[k] = Param(cloud.LogScales, i, 3, k, 0.0f);
  }
  for (int k = 0; k < 4; ++k)
  {
    rot[k] = Param(cloud.Rotations, i, 4, k, k == 0 ? 1.0f : 0.0f);
  }
  return ClassifyGaussian(pos, ls, rot, Param(cloud.OpacityLogits, i, 1, 0, 0.0f));
}

// Per-view visibility (and optionally occlusion-aware visibility) into the coverage counts.
void AddCoverage(const std::vector<std::uint32_t>& pixelCount,
  const GaussianWeightStats* weights,
  double threshold,
  std::vector<std::uint32_t>& views)
{
  const std::int64_t n = static_cast<std::int64_t>(views.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t g = 0; g < n; ++g)
  {
    bool visible = pixelCount[g] >= 1;
    if (visible && weights)
    {
      visible = static_cast<double>(weights->MaxWeight[g]) >= threshold;
    }
    views[g] += visible ? 1u : 0u;
  }
}

} // namespace

//------------------------------------------------------------------------------
std::vector<std::size_t> SelectViews(const std::vector<Camera>& cameras,
  const ScoreSettings& settings)
{
  std::vector<std::size_t> views;
  if (!settings.ViewList.empty())
  {
    for (std::size_t i : settings.ViewList)
    {
      if (i >= cameras.size())
      {
        throw std::invalid_argument("view list: camera index " + std::to_string(i) +
          " is out of range (" + std::to_string(cameras.size()) + " cameras)");
      }
      if (cameras[i].Split != CameraSplit::Train)
      {
        throw std::invalid_argument("view list: camera " + std::to_string(i) + " ('" +
          cameras[i].Name + "') is a test view; scores use training views only");
      }
      if (std::find(views.begin(), views.end(), i) != views.end())
      {
        throw std::invalid_argument(
          "view list: camera index " + std::to_string(i) + " is listed twice");
      }
      views.push_back(i);
    }
    return views;
  }
  if (settings.ViewStride < 1)
  {
    throw std::invalid_argument(
      "view stride must be at least 1 (got " + std::to_string(settings.ViewStride) + ")");
  }
  std::size_t k = 0;
  for (std::size_t i = 0; i < cameras.size(); ++i)
  {
    if (cameras[i].Split != CameraSplit::Train)
    {
      continue;
    }
    if (k++ % static_cast<std::size_t>(settings.ViewStride) == 0)
    {
      views.push_back(i);
    }
  }
  return views;
}

//------------------------------------------------------------------------------
namespace
{
// Both overloads: @p expected views (0: unknown, progress against the views taken so far).
ScorePartials PartialsOfQueue(const GaussianCloud& cloud,
  const std::vector<Camera>& cameras,
  const ScoreSettings& settings,
  const ScoreNextView& next,
  const TrainingImageProvider& images,
  const ScoreProgress& progress,
  const ScoreViewStarted& viewStarted,
  std::size_t expected)
{
  const auto start = Clock::now();
  const ScoreRequest& request = settings.Request;
  const bool scores = request.Blur || request.Needle;
  const bool needCameras = request.NeedsCameras();
  const bool renderCost = request.NeedsCompositing();
  if (!ValidFactor(settings.LossResolution) || !ValidFactor(settings.CoverageResolution))
  {
    throw std::invalid_argument("resolution factors must be 1, 2, 4 or 8 (got loss " +
      std::to_string(settings.LossResolution) + ", coverage " +
      std::to_string(settings.CoverageResolution) + ")");
  }
  if (!(settings.OcclusionThreshold >= 0 && settings.OcclusionThreshold <= 1))
  {
    throw std::invalid_argument("the occlusion threshold must be in [0, 1]");
  }
  if (!(settings.Lambda >= 0 && settings.Lambda <= 1))
  {
    throw std::invalid_argument("lambda must be in [0, 1]");
  }
  const std::size_t n = cloud.Count;
  if ((request.Needle || request.NeedleShape) && cloud.LogScales.size() != 3 * n)
  {
    throw std::invalid_argument("the needle shape needs the log-scales of every Gaussian");
  }
  if (needCameras &&
    (cloud.Positions.size() != 3 * n || cloud.LogScales.size() != 3 * n ||
      cloud.Rotations.size() != 4 * n || cloud.OpacityLogits.size() != n))
  {
    throw std::invalid_argument("coverage, blur, needle and render cost need positions, "
                                "log-scales, rotations and opacities");
  }
  if (scores && !images)
  {
    throw std::invalid_argument("blur and needle scores need training images");
  }
  if (n > 0xffffffffull)
  {
    throw std::invalid_argument("more than 2^32-1 Gaussians");
  }

  ScorePartials out;
  if (!needCameras)
  {
    out.Timings.Total = Seconds(start);
    return out;
  }

  out.ViewIndices = SelectViews(cameras, settings);
  // The views taken from the queue, in order: the blur/needle pass takes them as it goes, the
  // other passes go over them afterwards.
  std::vector<std::size_t>& ownViews = out.RenderedViews;
  std::vector<bool> taken(cameras.size(), false);
  auto take = [&](std::size_t& i)
  {
    if (!next || !next(i))
    {
      return false;
    }
    if (std::find(out.ViewIndices.begin(), out.ViewIndices.end(), i) == out.ViewIndices.end())
    {
      throw std::invalid_argument(
        "camera " + std::to_string(i) + " is not one of the views the settings select");
    }
    if (taken[i])
    {
      throw std::invalid_argument("camera " + std::to_string(i) + " is given twice");
    }
    taken[i] = true;
    ownViews.push_back(i);
    return true;
  };
  if (!scores)
  {
    for (std::size_t i = 0; take(i);)
    {
    }
  }
  for (std::size_t i : out.ViewIndices)
  {
    const Camera& c = cameras[i];
    if (c.Width <= 0 || c.Height <= 0 || !(c.Fx > 0) || !(c.Fy > 0))
    {
      throw std::invalid_argument(
        "camera " + std::to_string(i) + " ('" + c.Name + "') has no usable size or focal length");
    }
  }

  RasterSettings raster = settings.Raster;
  raster.Threads = settings.Threads;
  RasterSettings projectionOnly = raster;
  projectionOnly.ComputeColors = false;
  FootprintOptions footprint;
  footprint.Mode = settings.Footprint;
  footprint.Accumulation = settings.Accumulation;
  footprint.BruteForce = settings.BruteForceFootprints;
  footprint.Threads = settings.Threads;
  footprint.KernelIsa = settings.KernelIsa;

  const bool occlusion = settings.OcclusionThreshold > 0;
  // The score pass provides the coverage of the views it scores when both passes run at the
  // same resolution (identical projections and footprints).
  const bool shareCoverage =
    request.ViewCoverage && scores && settings.LossResolution == settings.CoverageResolution;
  if (request.ViewCoverage)
  {
    out.CoverageViews.assign(n, 0);
  }
  std::vector<double>& blurSum = out.BlurSum;
  std::vector<double>& needleSum = out.NeedleSum;
  if (scores)
  {
    out.ScoredViews.assign(n, 0);
    blurSum.assign(n, 0.0);
    needleSum.assign(n, 0.0);
    out.BlurCompensation.assign(n, 0.0f);
    out.NeedleCompensation.assign(n, 0.0f);
  }
  if (renderCost)
  {
    out.RenderCostSum.assign(n, 0.0);
    out.ContributionSum.assign(n, 0.0);
    out.ContributionCompensation.assign(n, 0.0f);
  }
  std::vector<bool> coveredByScorePass(cameras.size(), false);
  // The score pass's compositing also gives the render cost of the views it renders at full
  // resolution (the same projection and blending), so no view is drawn twice for it.
  const bool shareRenderCost = renderCost && scores && settings.LossResolution == 1;
  std::vector<bool> costedByScorePass(cameras.size(), false);
  auto addRenderCost = [&out, n](const GaussianWeightStats& weights)
  {
    const std::int64_t count = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static)
    for (std::int64_t g = 0; g < count; ++g)
    {
      out.RenderCostSum[g] += static_cast<double>(weights.Evaluations[g]);
      AddCompensated(out.ContributionSum[g], out.ContributionCompensation[g], weights.WeightSum[g]);
    }
  };
  // (with a queue, against the views taken so far: the blur/needle pass takes them as it goes)
  const std::size_t passes =
    (request.ViewCoverage ? 1 : 0) + (scores ? 1 : 0) + (renderCost ? 1 : 0);
  std::size_t done = 0;
  auto step = [&]()
  {
    ++done;
    if (progress)
    {
      progress(done, passes * std::max(expected, ownViews.size()));
    }
  };

  // Blur / needle pass.
  if (scores)
  {
    const std::int64_t sn = static_cast<std::int64_t>(n);
    const bool wantWeights = occlusion && shareCoverage;
    std::unique_ptr<MultiViewRenderer> multi;
    if (settings.SharedProjection && !wantWeights && !settings.BruteForceFootprints)
    {
      const auto t0 = Clock::now();
      multi.reset(new MultiViewRenderer(cloud, raster, settings.SharePreparation));
      out.Timings.Projection += Seconds(t0);
    }
    FootprintStats stats;
    RasterImage<float> render;
    // The shared pass's render-cost statistics, in the renderer's sorted order, kept between
    // views (each view's in input order would be 24 more bytes a Gaussian, allocated anew).
    GaussianWeightStats sortedWeights;
    sortedWeights.CountEvaluations = true;
    for (std::size_t vi = 0; take(vi);)
    {
      if (viewStarted)
      {
        viewStarted(vi);
      }
      const Camera& full = cameras[vi];
      auto t0 = Clock::now();
      Image image;
      const bool hasImage = images(vi, full, image);
      if (hasImage &&
        (image.Width != full.Width || image.Height != full.Height || image.Channels != 3 ||
          image.Pixels.size() != 3 * static_cast<std::size_t>(image.Width) * image.Height))
      {
        throw std::runtime_error("view '" + full.Name + "': the image is " +
          std::to_string(image.Width) + "x" + std::to_string(image.Height) + " but the camera is " +
          std::to_string(full.Width) + "x" + std::to_string(full.Height));
      }
      if (!hasImage)
      {
        ++out.ViewsWithoutImage;
        out.Timings.Images += Seconds(t0);
        step();
        continue;
      }
      const Camera view = ViewAt(full, settings.LossResolution);
      if (settings.LossResolution != 1)
      {
        image = BoxDownsample(image, view.Width, view.Height);
      }
      out.Timings.Images += Seconds(t0);

      ViewProjection<float> projection;
      GaussianWeightStats weights;
      weights.CountEvaluations = shareRenderCost;
      if (multi)
      {
        t0 = Clock::now();
        multi->Project(view);
        out.Timings.Projection += Seconds(t0);
        t0 = Clock::now();
        if (shareRenderCost)
        {
          multi->CompositeInSortedOrder(render, sortedWeights);
        }
        else
        {
          multi->Composite(render);
        }
        out.Timings.Rendering += Seconds(t0);
      }
      else
      {
        t0 = Clock::now();
        projection = ProjectGaussians<float>(cloud, view, raster);
        out.Timings.Projection += Seconds(t0);
        t0 = Clock::now();
        const TileBins bins = BinGaussians(projection, settings.Threads);
        CompositeTiles(
          projection, bins, raster, render, wantWeights || shareRenderCost ? &weights : nullptr);
        out.Timings.Rendering += Seconds(t0);
      }

      if (settings.ViewRendered)
      {
        t0 = Clock::now();
        settings.ViewRendered(vi, view, render, image);
        out.Timings.ViewHook += Seconds(t0);
      }

      t0 = Clock::now();
      const double area = (static_cast<double>(full.Width) * full.Height) /
        (static_cast<double>(view.Width) * view.Height);
      const std::vector<float> loss = ComputeLossMap(render.Color.data(),
        image.Pixels.data(),
        view.Width,
        view.Height,
        settings.Lambda,
        1.0 / area);
      out.Timings.LossMaps += Seconds(t0);

      if (multi)
      {
        // The footprints' statistics go straight into the sums (the same operations on the
        // same values as below), without two vectors of the cloud's size.
        t0 = Clock::now();
        multi->AddFootprints(footprint,
          loss.data(),
          [&](std::uint32_t g, std::uint32_t count, double mapSum, std::uint32_t maxCount)
          {
            if (count == 0)
            {
              return;
            }
            const double lp = area * mapSum;
            const double omega = count * (1.0 / maxCount);
            out.ScoredViews[g] += 1;
            AddCompensated(blurSum[g], out.BlurCompensation[g], omega * lp);
            AddCompensated(needleSum[g], out.NeedleCompensation[g], lp);
            if (shareCoverage)
            {
              out.CoverageViews[g] += 1;
            }
          });
        out.Timings.Footprints += Seconds(t0);
        t0 = Clock::now();
        if (shareRenderCost)
        {
          const std::vector<std::uint32_t>& ids = multi->SortedIds();
          const std::int64_t visible = static_cast<std::int64_t>(ids.size());
#pragma omp parallel for schedule(static)
          for (std::int64_t k = 0; k < visible; ++k)
          {
            const std::uint32_t g = ids[static_cast<std::size_t>(k)];
            out.RenderCostSum[g] += static_cast<double>(sortedWeights.Evaluations[k]);
            AddCompensated(
              out.ContributionSum[g], out.ContributionCompensation[g], sortedWeights.WeightSum[k]);
          }
          costedByScorePass[vi] = true;
        }
        coveredByScorePass[vi] = shareCoverage;
        out.Timings.Accumulation += Seconds(t0);
        ++out.ViewsScored;
        step();
        continue;
      }
      t0 = Clock::now();
      stats = ComputeFootprints(projection, footprint, loss.data());
      out.Timings.Footprints += Seconds(t0);

      t0 = Clock::now();
      std::uint32_t maxCount = 0;
      for (std::uint32_t c : stats.PixelCount)
      {
        maxCount = std::max(maxCount, c);
      }
      const double invMax = maxCount > 0 ? 1.0 / maxCount : 0.0;
#pragma omp parallel for schedule(static)
      for (std::int64_t g = 0; g < sn; ++g)
      {
        const std::uint32_t count = stats.PixelCount[g];
        if (count == 0)
        {
          continue;
        }
        const double lp = area * stats.MapSum[g];
        const double omega = count * invMax;
        out.ScoredViews[g] += 1;
        AddCompensated(blurSum[g], out.BlurCompensation[g], omega * lp);
        AddCompensated(needleSum[g], out.NeedleCompensation[g], lp);
      }
      if (shareRenderCost)
      {
        addRenderCost(weights);
        costedByScorePass[vi] = true;
      }
      if (shareCoverage)
      {
        AddCoverage(stats.PixelCount,
          wantWeights ? &weights : nullptr,
          settings.OcclusionThreshold,
          out.CoverageViews);
        coveredByScorePass[vi] = true;
      }
      out.Timings.Accumulation += Seconds(t0);
      ++out.ViewsScored;
      step();
    }
  }

  // Coverage pass (views the score pass did not cover).
  if (request.ViewCoverage && !occlusion && !settings.BruteForceFootprints)
  {
    // Fused, early-exit visibility (FastCoverage.h): identical counts, no footprint sizes.
    std::vector<Camera> pending;
    for (std::size_t vi : ownViews)
    {
      if (!coveredByScorePass[vi])
      {
        pending.push_back(ViewAt(cameras[vi], settings.CoverageResolution));
      }
    }
    // Batches of views: the cloud is read (and its view-independent part prepared) once per
    // batch, progress is reported per batch.
    constexpr std::size_t batch = 64;
    for (std::size_t first = 0; first < pending.size(); first += batch)
    {
      if (viewStarted)
      {
        for (std::size_t vi : ownViews)
        {
          if (!coveredByScorePass[vi])
          {
            viewStarted(vi); // the batch's views are counted together; name the first
            break;
          }
        }
      }
      const std::size_t last = std::min(pending.size(), first + batch);
      const std::vector<Camera> views(pending.begin() + first, pending.begin() + last);
      const auto t0 = Clock::now();
      CountVisibleViews(cloud,
        views,
        settings.Footprint,
        out.CoverageViews,
        settings.Threads,
        settings.Raster.ScaleModifier,
        settings.KernelIsa);
      out.Timings.Footprints += Seconds(t0);
      for (std::size_t k = first; k < last; ++k)
      {
        step();
      }
    }
    for (std::size_t k = pending.size(); k < ownViews.size(); ++k)
    {
      step(); // views the score pass covered
    }
  }
  else if (request.ViewCoverage)
  {
    for (std::size_t vi : ownViews)
    {
      if (coveredByScorePass[vi])
      {
        step();
        continue;
      }
      if (viewStarted)
      {
        viewStarted(vi);
      }
      const Camera view = ViewAt(cameras[vi], settings.CoverageResolution);
      auto t0 = Clock::now();
      const ViewProjection<float> projection =
        ProjectGaussians<float>(cloud, view, occlusion ? raster : projectionOnly);
      out.Timings.Projection += Seconds(t0);
      GaussianWeightStats weights;
      if (occlusion)
      {
        t0 = Clock::now();
        const TileBins bins = BinGaussians(projection, settings.Threads);
        RasterImage<float> render;
        CompositeTiles(projection, bins, raster, render, &weights);
        out.Timings.Rendering += Seconds(t0);
      }
      t0 = Clock::now();
      FootprintOptions countOnly = footprint;
      const FootprintStats stats = ComputeFootprints(projection, countOnly, nullptr);
      out.Timings.Footprints += Seconds(t0);
      t0 = Clock::now();
      AddCoverage(stats.PixelCount,
        occlusion ? &weights : nullptr,
        settings.OcclusionThreshold,
        out.CoverageViews);
      out.Timings.Accumulation += Seconds(t0);
      step();
    }
  }

  // Render-cost pass: every view at full resolution, whatever the loss and coverage
  // resolutions (the cost is the one of drawing the training views), no image needed; the
  // views the score pass rendered at full resolution are done.
  if (renderCost)
  {
    RasterImage<float> render;
    GaussianWeightStats weights;
    weights.CountEvaluations = true;
    for (std::size_t vi : ownViews)
    {
      if (costedByScorePass[vi])
      {
        step();
        continue;
      }
      if (viewStarted)
      {
        viewStarted(vi);
      }
      const auto t0 = Clock::now();
      const ViewProjection<float> projection =
        ProjectGaussians<float>(cloud, cameras[vi], projectionOnly);
      const TileBins bins = BinGaussians(projection, settings.Threads);
      CompositeTiles(projection, bins, projectionOnly, render, &weights);
      addRenderCost(weights);
      out.Timings.RenderCost += Seconds(t0);
      step();
    }
  }

  out.Timings.Total = Seconds(start);
  return out;
}
} // namespace

//------------------------------------------------------------------------------
GaussianScores FinishGaussianScores(const GaussianCloud& cloud,
  const ScoreSettings& settings,
  ScorePartials partials)
{
  return FinishGaussianScores(cloud, settings, std::move(partials), 0, cloud.Count);
}

//------------------------------------------------------------------------------
std::vector<std::string> ScoreWarnings(const GaussianScores& scores,
  const ScoreRequest& request,
  std::size_t gaussians)
{
  std::vector<std::string> warnings;
  if (!request.NeedsCameras())
  {
    return warnings;
  }
  if ((request.Blur || request.Needle) && scores.ViewsWithoutImage > 0)
  {
    warnings.push_back(std::to_string(scores.ViewsWithoutImage) + " of " +
      std::to_string(scores.ViewsUsed) +
      " training views have no image and were skipped for the blur and needle scores");
  }
  if (!scores.ScoresUnavailable.empty())
  {
    warnings.push_back(scores.ScoresUnavailable);
  }
  if (request.NeedsCompositing() && scores.NotEvaluatedCount > 0)
  {
    warnings.push_back(std::to_string(scores.NotEvaluatedCount) + " of " +
      std::to_string(gaussians) +
      " Gaussians are evaluated at no pixel of any training view (RenderCost 0" +
      (request.CostPerContribution ? ", CostPerContribution NaN: no cost to divide)" : ")"));
  }
  if (scores.NoCoverageViewCount > 0)
  {
    warnings.push_back(std::to_string(scores.NoCoverageViewCount) + " of " +
      std::to_string(gaussians) +
      " Gaussians are visible in no training view (ViewCoverage 0, flagged)");
  }
  if (scores.InvalidCount > 0)
  {
    warnings.push_back(std::to_string(scores.InvalidCount) +
      " Gaussians have NaN or infinite parameters; they are never visible and are flagged");
  }
  return warnings;
}

//------------------------------------------------------------------------------
GaussianScores FinishGaussianScores(const GaussianCloud& cloud,
  const ScoreSettings& settings,
  ScorePartials partials,
  std::size_t first,
  std::size_t count)
{
  const auto start = Clock::now();
  const ScoreRequest& request = settings.Request;
  const bool scores = request.Blur || request.Needle;
  const bool needCameras = request.NeedsCameras();
  const bool renderCost = request.NeedsCompositing();
  const std::size_t n = cloud.Count;
  if (first > cloud.Count || count > cloud.Count - first)
  {
    throw std::invalid_argument("Gaussians " + std::to_string(first) + " to " +
      std::to_string(first + count) + " are not all in the cloud of " +
      std::to_string(cloud.Count));
  }
  if ((request.Needle || request.NeedleShape) && cloud.LogScales.size() != 3 * cloud.Count)
  {
    throw std::invalid_argument("the needle shape needs the log-scales of every Gaussian");
  }
  if ((request.ViewCoverage && partials.CoverageViews.size() != n) ||
    (scores &&
      (partials.ScoredViews.size() != n || partials.BlurSum.size() != n ||
        partials.NeedleSum.size() != n || partials.BlurCompensation.size() != n ||
        partials.NeedleCompensation.size() != n)) ||
    (renderCost &&
      (partials.RenderCostSum.size() != n || partials.ContributionSum.size() != n ||
        partials.ContributionCompensation.size() != n)))
  {
    throw std::invalid_argument("the partial scores do not match the cloud or the request");
  }
  // The range's loops run over g in [begin, end); the vectors keep the cloud's size.
  const std::int64_t begin = static_cast<std::int64_t>(first);
  const std::int64_t end = static_cast<std::int64_t>(first + count);
  GaussianScores out;
  out.Flags.assign(n, 0);
  // Invalid parameters (flag only; the rasteriser skips these Gaussians by itself).
  {
    std::size_t invalid = 0;
#pragma omp parallel for reduction(+ : invalid) schedule(static)
    for (std::int64_t g = begin; g < end; ++g)
    {
      if (ClassOf(cloud, static_cast<std::size_t>(g)) != GaussianClass::Drawn)
      {
        out.Flags[g] |= InvalidParameters;
        ++invalid;
      }
    }
    out.InvalidCount = invalid;
  }

  // Needle shape: no cameras needed.
  std::vector<double> shape;
  if (request.Needle || request.NeedleShape)
  {
    const auto t0 = Clock::now();
    shape.resize(n);
    ComputeNeedleShapes(cloud.LogScales.data() + 3 * first, count, shape.data() + first);
    out.Timings.NeedleShape = Seconds(t0);
  }
  if (!needCameras)
  {
    if (request.NeedleShape)
    {
      out.NeedleShape = std::move(shape);
    }
    out.Timings.Total = Seconds(start);
    return out;
  }

  out.ViewIndices = std::move(partials.ViewIndices);
  out.ViewsUsed = out.ViewIndices.size();
  out.ViewsScored = partials.ViewsScored;
  out.ViewsWithoutImage = partials.ViewsWithoutImage;
  out.CoverageViews = std::move(partials.CoverageViews);
  out.ScoredViews = std::move(partials.ScoredViews);
  const ScoreTimings& pt = partials.Timings;
  out.Timings.Projection = pt.Projection;
  out.Timings.Rendering = pt.Rendering;
  out.Timings.Images = pt.Images;
  out.Timings.LossMaps = pt.LossMaps;
  out.Timings.Footprints = pt.Footprints;
  out.Timings.Accumulation = pt.Accumulation;
  out.Timings.ViewHook = pt.ViewHook;
  out.Timings.RenderCost = pt.RenderCost;

  // Final scores.
  const auto t0 = Clock::now();
  if (request.ViewCoverage)
  {
    out.ViewCoverage.assign(n, 0.0);
  }
  // The means are taken in the sums' memory (no second 8 bytes a Gaussian to allocate and
  // touch): the sum of Gaussian g is read once, then replaced by its mean.
  if (request.Blur)
  {
    out.BlurScore = std::move(partials.BlurSum);
  }
  if (request.Needle)
  {
    out.NeedleScore = std::move(partials.NeedleSum);
  }
  const double invViews = out.ViewsUsed > 0 ? 1.0 / out.ViewsUsed : 0.0;
  std::size_t noCoverage = 0, noScored = 0;
#pragma omp parallel for reduction(+ : noCoverage, noScored) schedule(static)
  for (std::int64_t g = begin; g < end; ++g)
  {
    if (request.ViewCoverage)
    {
      const std::uint32_t k = out.CoverageViews[g];
      out.ViewCoverage[g] = k * invViews;
      if (k == 0)
      {
        out.Flags[g] |= NoVisibleCoverageView;
        ++noCoverage;
      }
    }
    if (scores)
    {
      const std::uint32_t k = out.ScoredViews[g];
      if (k == 0)
      {
        out.Flags[g] |= NoVisibleScoredView;
        ++noScored;
        if (request.Blur)
        {
          out.BlurScore[g] = 0.0;
        }
        if (request.Needle)
        {
          out.NeedleScore[g] = 0.0;
        }
        continue;
      }
      if (request.Blur)
      {
        out.BlurScore[g] = (out.BlurScore[g] + partials.BlurCompensation[g]) / k;
      }
      if (request.Needle)
      {
        out.NeedleScore[g] = shape[g] * ((out.NeedleScore[g] + partials.NeedleCompensation[g]) / k);
      }
    }
  }
  if (scores && out.ViewsScored == 0 && out.ViewsUsed > 0)
  {
    out.ScoresUnavailable = "no training image for any of the " + std::to_string(out.ViewsUsed) +
      " views used: BlurScore and NeedleScore cannot be computed and are NaN";
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (request.Blur)
    {
      std::fill(out.BlurScore.begin() + begin, out.BlurScore.begin() + end, nan);
    }
    if (request.Needle)
    {
      std::fill(out.NeedleScore.begin() + begin, out.NeedleScore.begin() + end, nan);
    }
  }
  if (renderCost)
  {
    if (request.CostPerContribution)
    {
      out.CostPerContribution.assign(n, 0.0);
    }
    std::size_t notEvaluated = 0;
#pragma omp parallel for reduction(+ : notEvaluated) schedule(static)
    for (std::int64_t g = begin; g < end; ++g)
    {
      const double cost = partials.RenderCostSum[g],
                   contribution =
                     partials.ContributionSum[g] + partials.ContributionCompensation[g];
      notEvaluated += cost > 0 ? 0 : 1;
      if (request.CostPerContribution)
      {
        out.CostPerContribution[g] = contribution > 0 ? cost / contribution
          : cost > 0                                  ? std::numeric_limits<double>::infinity()
                                                      : std::numeric_limits<double>::quiet_NaN();
      }
    }
    if (request.RenderCost)
    {
      out.RenderCost = std::move(partials.RenderCostSum);
    }
    out.NotEvaluatedCount = notEvaluated;
  }
  if (request.NeedleShape)
  {
    out.NeedleShape = std::move(shape); // the needle score above has read it
  }
  out.NoCoverageViewCount = noCoverage;
  out.NoScoredViewCount = noScored;
  out.Timings.Accumulation += Seconds(t0);
  out.Warnings = ScoreWarnings(out, request, cloud.Count);
  out.Timings.Total = pt.Total + Seconds(start);
  return out;
}

//------------------------------------------------------------------------------
ScorePartials ComputeScorePartials(const GaussianCloud& cloud,
  const std::vector<Camera>& cameras,
  const ScoreSettings& settings,
  const std::vector<std::size_t>& views,
  const TrainingImageProvider& images,
  const ScoreProgress& progress,
  const ScoreViewStarted& viewStarted)
{
  std::size_t k = 0;
  return PartialsOfQueue(
    cloud,
    cameras,
    settings,
    [&](std::size_t& view)
    {
      if (k == views.size())
      {
        return false;
      }
      view = views[k++];
      return true;
    },
    images,
    progress,
    viewStarted,
    views.size());
}

//------------------------------------------------------------------------------
ScorePartials ComputeScorePartials(const GaussianCloud& cloud,
  const std::vector<Camera>& cameras,
  const ScoreSettings& settings,
  const ScoreNextView& next,
  const TrainingImageProvider& images,
  const ScoreProgress& progress,
  const ScoreViewStarted& viewStarted)
{
  return PartialsOfQueue(cloud, cameras, settings, next, images, progress, viewStarted, 0);
}

//------------------------------------------------------------------------------
GaussianScores ComputeGaussianScores(const GaussianCloud& cloud,
  const std::vector<Camera>& cameras,
  const ScoreSettings& settings,
  const TrainingImageProvider& images,
  const ScoreProgress& progress)
{
  const bool needCameras = settings.Request.NeedsCameras();
  const std::vector<std::size_t> views =
    needCameras ? SelectViews(cameras, settings) : std::vector<std::size_t>();
  return FinishGaussianScores(
    cloud, settings, ComputeScorePartials(cloud, cameras, settings, views, images, progress));
}

//------------------------------------------------------------------------------
std::vector<double> EstimateViewCosts(const GaussianCloud& cloud,
  const std::vector<Camera>& cameras,
  const std::vector<std::size_t>& views,
  const ScoreSettings& settings)
{
  const bool scores = settings.Request.Blur || settings.Request.Needle;
  const int factor = scores ? settings.LossResolution : settings.CoverageResolution;
  const std::size_t n = cloud.Count;
  const std::size_t stride = std::max<std::size_t>(1, n / 4096);
  std::vector<double> costs;
  costs.reserve(views.size());
  for (std::size_t vi : views)
  {
    const Camera& c = cameras.at(vi);
    const double w = c.Width, h = c.Height;
    const auto& m = c.WorldToCamera;
    std::size_t seen = 0, sampled = 0;
    for (std::size_t g = 0; g < n && cloud.Positions.size() >= 3 * n; g += stride)
    {
      ++sampled;
      const double x = cloud.Positions[3 * g], y = cloud.Positions[3 * g + 1],
                   z = cloud.Positions[3 * g + 2];
      const double cz = m[8] * x + m[9] * y + m[10] * z + m[11];
      if (!(cz > 0.2))
      {
        continue; // the rasteriser's near plane
      }
      const double u = c.Fx * (m[0] * x + m[1] * y + m[2] * z + m[3]) / cz + c.Cx;
      const double v = c.Fy * (m[4] * x + m[5] * y + m[6] * z + m[7]) / cz + c.Cy;
      seen += (u >= 0 && u < w && v >= 0 && v < h) ? 1 : 0;
    }
    const double fraction = sampled > 0 ? (seen + 1.0) / (sampled + 1.0) : 1.0;
    const double pixels =
      static_cast<double>(LossMapSize(c.Width, factor)) * LossMapSize(c.Height, factor);
    // The +1 keeps an empty view's cost positive: it still costs a projection.
    costs.push_back(pixels * fraction * static_cast<double>(n + 1));
  }
  return costs;
}

//------------------------------------------------------------------------------
std::vector<int> SplitViewsByCost(const std::vector<double>& costs, int parts)
{
  if (parts < 1)
  {
    throw std::invalid_argument("views must be split over at least one process");
  }
  std::vector<std::size_t> order(costs.size());
  for (std::size_t i = 0; i < order.size(); ++i)
  {
    order[i] = i;
  }
  std::stable_sort(
    order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return costs[a] > costs[b]; });
  std::vector<double> load(static_cast<std::size_t>(parts), 0.0);
  std::vector<int> owner(costs.size(), 0);
  for (std::size_t i : order)
  {
    const auto least = std::min_element(load.begin(), load.end());
    *least += std::isfinite(costs[i]) ? costs[i] : 0.0;
    owner[i] = static_cast<int>(least - load.begin());
  }
  return owner;
}

} // namespace vis4gs

// SPDX-License-Identifier: BSD-3-Clause
#include "RemovalEffect.h"

#include "ThreadCount.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <memory>
#include <numeric>
#include <stdexcept>

namespace vis4gs
{
namespace
{
using Clock = std::chrono::steady_clock;

double Since(Clock::time_point t)
{
  return std::chrono::duration<double>(Clock::now() - t).count();
}

bool Wanted(const Camera& camera, const RemovalEffectOptions& options)
{
  return camera.Split == CameraSplit::Train ? options.TrainViews : options.TestViews;
}

RasterSettings Settings(const RemovalEffectOptions& options)
{
  RasterSettings s = options.Raster;
  s.Threads = options.Threads;
  return s;
}

// Every figure is measured per tile, so that a view re-measured in part (RemeasureViewTiles)
// and one measured whole give the same bits.
ViewMetrics Measure(const RasterImage<float>& render, const Image& target, int threads)
{
  return MeasureViewTiles(
    render.Color.data(), target.Pixels.data(), render.Width, render.Height, threads)
    .Metrics();
}

// The image of view @p index, or false; throws when its size is not the camera's.
bool LoadTarget(const TrainingImageProvider& images,
  std::size_t index,
  const Camera& camera,
  Image& target)
{
  if (!images || !images(index, camera, target))
  {
    return false;
  }
  if (target.Width != camera.Width || target.Height != camera.Height || target.Channels != 3 ||
    target.Pixels.size() != 3 * static_cast<std::size_t>(camera.Width) * camera.Height)
  {
    throw std::runtime_error("camera " + camera.Name + ": its image is " +
      std::to_string(target.Width) + "x" + std::to_string(target.Height) + ", the camera " +
      std::to_string(camera.Width) + "x" + std::to_string(camera.Height));
  }
  return true;
}

void AddToTotals(RemovalTotals& totals, const RemovalViewEffect& v)
{
  if (!v.HasImage)
  {
    return;
  }
  for (auto [sum, m] :
    { std::make_pair(&totals.Before, &v.Before), std::make_pair(&totals.After, &v.After) })
  {
    if (totals.Views == 0)
    {
      *sum = ViewMetrics{ 0, 0, 0 };
    }
    sum->Psnr += m->Psnr;
    sum->Ssim += m->Ssim;
    sum->L1 += m->L1;
  }
  ++totals.Views;
  totals.AffectedViews += v.Affected ? 1 : 0;
}

void FinishTotals(RemovalTotals& totals)
{
  const double n = static_cast<double>(totals.Views);
  for (ViewMetrics* m : { &totals.Before, &totals.After })
  {
    if (totals.Views > 0)
    {
      m->Psnr /= n;
      m->Ssim /= n;
      m->L1 /= n;
    }
  }
}

// The tiles whose lists hold a Gaussian visible in @p projection (the removed ones).
std::vector<std::uint8_t> ListedTiles(const ViewProjection<float>& projection)
{
  std::vector<std::uint8_t> tiles(
    static_cast<std::size_t>(projection.TilesX) * projection.TilesY, 0);
  for (const ProjectedGaussian<float>& g : projection.Gaussians)
  {
    if (g.IsVisible())
    {
      for (int y = g.TileRect[1]; y < g.TileRect[3]; ++y)
      {
        std::fill_n(&tiles[static_cast<std::size_t>(y) * projection.TilesX + g.TileRect[0]],
          g.TileRect[2] - g.TileRect[0],
          std::uint8_t(1));
      }
    }
  }
  return tiles;
}

void CheckTileBaseline(const RemovalBaseline& baseline,
  const GaussianCloud& cloud,
  const std::vector<Camera>& cameras,
  const RasterSettings& raster)
{
  if (baseline.Views.empty())
  {
    return;
  }
  auto fail = [](const std::string& what)
  { throw std::invalid_argument("MeasureRemovalEffect: the tile baseline " + what); };
  if (baseline.Views.size() != cameras.size())
  {
    fail("has " + std::to_string(baseline.Views.size()) + " views for " +
      std::to_string(cameras.size()) + " cameras");
  }
  if (baseline.Gaussians != cloud.Count)
  {
    fail("was measured on " + std::to_string(baseline.Gaussians) + " Gaussians, not " +
      std::to_string(cloud.Count));
  }
  if (baseline.Background != raster.Background || baseline.ShDegree != raster.ShDegree ||
    baseline.ScaleModifier != raster.ScaleModifier)
  {
    fail("was rendered with another background, SH degree or scale modifier");
  }
  for (std::size_t v = 0; v < cameras.size(); ++v)
  {
    const ViewTileSums& t = baseline.Views[v];
    if (!t.Empty() && (t.Width != cameras[v].Width || t.Height != cameras[v].Height))
    {
      fail("of camera " + cameras[v].Name + " is " + std::to_string(t.Width) + "x" +
        std::to_string(t.Height) + ", the camera " + std::to_string(cameras[v].Width) + "x" +
        std::to_string(cameras[v].Height));
    }
  }
}

std::size_t CountTiles(const std::vector<std::uint8_t>& tiles)
{
  return static_cast<std::size_t>(
    std::count_if(tiles.begin(), tiles.end(), [](std::uint8_t t) { return t != 0; }));
}

// The sort key: identical renders of a perfect view (PSNR +inf before and after) did not change.
double Change(const RemovalViewEffect& v)
{
  const double c = v.PsnrChange();
  return std::isnan(c) ? 0.0 : c;
}
} // namespace

//------------------------------------------------------------------------------
Image ClampedImage(const RasterImage<float>& render)
{
  Image image;
  image.Width = render.Width;
  image.Height = render.Height;
  image.Pixels.resize(render.Color.size());
  std::transform(render.Color.begin(),
    render.Color.end(),
    image.Pixels.begin(),
    [](float x) { return std::min(1.0f, std::max(0.0f, x)); });
  return image;
}

//------------------------------------------------------------------------------
GaussianCloud RemoveGaussians(const GaussianCloud& cloud, const std::vector<std::uint8_t>& removed)
{
  if (removed.size() != cloud.Count)
  {
    throw std::invalid_argument("RemoveGaussians: " + std::to_string(removed.size()) +
      " flags for " + std::to_string(cloud.Count) + " Gaussians");
  }
  const std::size_t kept = cloud.Count -
    static_cast<std::size_t>(
      std::count_if(removed.begin(), removed.end(), [](std::uint8_t r) { return r != 0; }));
  GaussianCloud out;
  out.Count = kept;
  out.ShDegree = cloud.ShDegree;
  // Every per-Gaussian array, whatever it holds per Gaussian (arrays not loaded stay empty).
  auto subset = [&](const auto& in, auto& result, std::size_t per)
  {
    if (in.size() != per * cloud.Count)
    {
      return;
    }
    result.resize(per * kept);
    std::size_t j = 0;
    for (std::size_t i = 0; i < cloud.Count; ++i)
    {
      if (!removed[i])
      {
        std::copy_n(&in[per * i], per, &result[per * j++]);
      }
    }
  };
  if (!cloud.Ids.empty())
  {
    subset(cloud.Ids, out.Ids, 1);
  }
  else
  {
    // Ids default to the indices: keep them, or the survivors would be renumbered.
    std::vector<std::int64_t> ids(cloud.Count);
    std::iota(ids.begin(), ids.end(), std::int64_t(0));
    subset(ids, out.Ids, 1);
  }
  subset(cloud.Positions, out.Positions, 3);
  subset(cloud.LogScales, out.LogScales, 3);
  subset(cloud.Rotations, out.Rotations, 4);
  subset(cloud.OpacityLogits, out.OpacityLogits, 1);
  if (cloud.Count > 0)
  {
    subset(cloud.SH, out.SH, cloud.SH.size() / cloud.Count);
  }
  for (const ExtraProperty& extra : cloud.Extra)
  {
    ExtraProperty e;
    e.Name = extra.Name;
    e.Type = extra.Type;
    subset(extra.Bytes, e.Bytes, ScalarTypeSize(extra.Type));
    out.Extra.push_back(std::move(e));
  }
  return out;
}

//------------------------------------------------------------------------------
std::vector<ViewMetrics> MeasureViewMetrics(const GaussianCloud& cloud,
  const std::vector<Camera>& cameras,
  const RemovalEffectOptions& options,
  const TrainingImageProvider& images)
{
  // The figures of the per-tile sums, so that they equal a baseline's bit for bit.
  const RemovalBaseline baseline = MeasureRemovalBaseline(cloud, cameras, options, images);
  std::vector<ViewMetrics> metrics(cameras.size());
  for (std::size_t v = 0; v < cameras.size(); ++v)
  {
    if (!baseline.Views[v].Empty())
    {
      metrics[v] = baseline.Views[v].Metrics();
    }
  }
  return metrics;
}

//------------------------------------------------------------------------------
std::size_t RemovalBaseline::MeasuredViews() const
{
  return static_cast<std::size_t>(std::count_if(
    this->Views.begin(), this->Views.end(), [](const ViewTileSums& v) { return !v.Empty(); }));
}

namespace
{
RemovalBaseline EmptyBaseline(const GaussianCloud& cloud,
  const std::vector<Camera>& cameras,
  const RasterSettings& raster)
{
  RemovalBaseline baseline;
  baseline.Views.assign(cameras.size(), ViewTileSums{});
  baseline.Gaussians = cloud.Count;
  baseline.Background = raster.Background;
  baseline.ShDegree = raster.ShDegree;
  baseline.ScaleModifier = raster.ScaleModifier;
  return baseline;
}
} // namespace

//------------------------------------------------------------------------------
ScoreViewRendered RemovalBaselineRecorder(const GaussianCloud& cloud,
  const std::vector<Camera>& cameras,
  const RasterSettings& raster,
  int threads,
  RemovalBaseline& baseline)
{
  baseline = EmptyBaseline(cloud, cameras, raster);
  RemovalBaseline* out = &baseline;
  std::vector<std::array<int, 2>> sizes;
  for (const Camera& c : cameras)
  {
    sizes.push_back({ c.Width, c.Height });
  }
  return
    [out, threads, sizes](
      std::size_t index, const Camera& view, const RasterImage<float>& render, const Image& image)
  {
    // Only a render at the camera's own size is the "before" of that view (a score pass at a
    // reduced resolution renders smaller views).
    const std::array<int, 2> size{ view.Width, view.Height };
    if (index < out->Views.size() && size == sizes[index] && render.Width == view.Width &&
      render.Height == view.Height && image.Width == view.Width && image.Height == view.Height)
    {
      out->Views[index] = MeasureViewTiles(
        render.Color.data(), image.Pixels.data(), view.Width, view.Height, threads);
    }
  };
}

//------------------------------------------------------------------------------
bool RecordRemovalBaseline(ScoreSettings& settings,
  const GaussianCloud& cloud,
  const std::vector<Camera>& cameras,
  RemovalBaseline& baseline)
{
  if (settings.LossResolution != 1)
  {
    return false;
  }
  ScoreViewRendered record =
    RemovalBaselineRecorder(cloud, cameras, settings.Raster, settings.Threads, baseline);
  ScoreViewRendered earlier = std::move(settings.ViewRendered);
  settings.ViewRendered =
    [record, earlier](
      std::size_t index, const Camera& view, const RasterImage<float>& render, const Image& image)
  {
    if (earlier)
    {
      earlier(index, view, render, image);
    }
    record(index, view, render, image);
  };
  return true;
}

//------------------------------------------------------------------------------
RemovalBaseline MeasureRemovalBaseline(const GaussianCloud& cloud,
  const std::vector<Camera>& cameras,
  const RemovalEffectOptions& options,
  const TrainingImageProvider& images)
{
  RemovalBaseline baseline = EmptyBaseline(cloud, cameras, options.Raster);
  const RasterSettings settings = Settings(options);
  RasterWorkspace<float> workspace;
  Image target;
  for (std::size_t v = 0; v < cameras.size(); ++v)
  {
    if (!Wanted(cameras[v], options) || !LoadTarget(images, v, cameras[v], target))
    {
      continue;
    }
    Rasterize(cloud, cameras[v], settings, workspace);
    baseline.Views[v] = MeasureViewTiles(workspace.Image.Color.data(),
      target.Pixels.data(),
      cameras[v].Width,
      cameras[v].Height,
      options.Threads);
  }
  return baseline;
}

//------------------------------------------------------------------------------
RemovalEffect MeasureRemovalEffect(const GaussianCloud& cloud,
  const std::vector<std::uint8_t>& removed,
  const std::vector<Camera>& cameras,
  const RemovalEffectOptions& options,
  const TrainingImageProvider& images)
{
  if (!options.Baseline.empty() && options.Baseline.size() != cameras.size())
  {
    throw std::invalid_argument("MeasureRemovalEffect: a baseline of " +
      std::to_string(options.Baseline.size()) + " views for " + std::to_string(cameras.size()) +
      " cameras");
  }
  RemovalEffect effect;
  const RasterSettings settings = Settings(options);
  const int threads = ThreadCount(options.Threads);

  // Which views a removed Gaussian takes part in: project only those.
  std::vector<std::uint8_t> kept(removed.size());
  std::transform(
    removed.begin(), removed.end(), kept.begin(), [](std::uint8_t r) { return r ? 0 : 1; });
  const GaussianCloud gone = RemoveGaussians(cloud, kept);
  effect.Removed = gone.Count;
  effect.Kept = cloud.Count - gone.Count;
  RasterSettings cull = settings;
  cull.ComputeColors = false;
  // The cleaned cloud (a copy of every kept Gaussian), made when a view needs it whole.
  std::unique_ptr<GaussianCloud> afterCloud;
  auto after = [&]() -> const GaussianCloud&
  {
    if (!afterCloud)
    {
      afterCloud.reset(new GaussianCloud(RemoveGaussians(cloud, removed)));
    }
    return *afterCloud;
  };
  ViewProjection<float> reach;
  PreparedCloudCache prepared;
  std::vector<std::uint8_t> outside;

  CheckTileBaseline(options.TileBaseline, cloud, cameras, options.Raster);

  RasterWorkspace<float> workspace;
  ViewProjection<float> projection;
  Image target;
  for (std::size_t v = 0; v < cameras.size(); ++v)
  {
    const Camera& camera = cameras[v];
    if (!Wanted(camera, options))
    {
      continue;
    }
    RemovalViewEffect view;
    view.CameraIndex = v;
    view.Name = camera.Name;
    view.Split = camera.Split;
    const ViewTileSums* tiled =
      options.TileBaseline.Views.empty() || options.TileBaseline.Views[v].Empty()
      ? nullptr
      : &options.TileBaseline.Views[v];
    const bool known = tiled || !options.Baseline.empty();
    auto t0 = Clock::now();
    if (gone.Count > 0)
    {
      ProjectGaussians(gone, camera, cull, projection);
      view.Affected = projection.Counts.Visible > 0;
    }
    effect.SecondsAfter += Since(t0);
    if (known && !view.Affected)
    {
      // Nothing to render or read: the baseline is this view's figures, before and after.
      const ViewMetrics m = tiled ? tiled->Metrics() : options.Baseline[v];
      view.HasImage = !std::isnan(m.Psnr);
      view.Before = view.After = m;
      effect.ViewsWithoutImage += view.HasImage ? 0 : 1;
      effect.Views.push_back(std::move(view));
      continue;
    }
    view.HasImage = LoadTarget(images, v, camera, target);
    if (!view.HasImage)
    {
      ++effect.ViewsWithoutImage;
      effect.Views.push_back(std::move(view));
      continue;
    }
    t0 = Clock::now();
    // The "before" per tile: given, or measured on this render.
    ViewTileSums sums;
    if (tiled)
    {
      sums = *tiled;
      view.Before = sums.Metrics();
    }
    else if (!options.Baseline.empty())
    {
      view.Before = options.Baseline[v];
    }
    else
    {
      Rasterize(cloud, camera, settings, workspace);
      ++effect.ViewsRendered;
      sums = MeasureViewTiles(
        workspace.Image.Color.data(), target.Pixels.data(), camera.Width, camera.Height, threads);
      view.Before = sums.Metrics();
    }
    effect.SecondsBefore += Since(t0);
    t0 = Clock::now();
    if (!view.Affected)
    {
      view.After = view.Before;
    }
    else if (!sums.Empty() && options.ReuseTiles)
    {
      const std::vector<std::uint8_t> changed = ListedTiles(projection);
      const std::vector<std::uint8_t> rendered =
        DilateTiles(changed, projection.TilesX, projection.TilesY, 2);
      // Only the kept Gaussians that reach those tiles are rendered, as a cloud of their own in
      // their order (the same tile lists, so the same pixels). They are found by a projection
      // without colours, the view-independent part kept between views; a Gaussian it keeps
      // and the render culls (its SH not finite) only costs its copy. When most of the view is
      // rendered again, most Gaussians reach it: the cleaned cloud is rendered directly.
      bool whole = 2 * CountTiles(rendered) > rendered.size();
      if (!whole)
      {
        ProjectGaussians(cloud, camera, cull, reach, prepared, 1);
        for (std::size_t i = 0; i < cloud.Count; ++i)
        {
          if (removed[i])
          {
            reach.Gaussians[i].Status = ProjectionStatus::OffScreen;
          }
        }
        KeepTiles(reach, rendered);
        outside.resize(cloud.Count);
        std::size_t inside = 0;
        for (std::size_t i = 0; i < cloud.Count; ++i)
        {
          outside[i] = reach.Gaussians[i].IsVisible() ? 0 : 1;
          inside += 1 - outside[i];
        }
        whole = 2 * inside > cloud.Count;
      }
      if (whole)
      {
        RasterizeTiles(after(), camera, settings, rendered, workspace);
      }
      else
      {
        RasterizeTiles(RemoveGaussians(cloud, outside), camera, settings, rendered, workspace);
      }
      ++effect.ViewsRendered;
      effect.TilesRendered += CountTiles(rendered);
      effect.TilesOfTiledViews += sums.TileCount();
      RemeasureViewTiles(sums,
        workspace.Image.Color.data(),
        target.Pixels.data(),
        DilateTiles(changed, projection.TilesX, projection.TilesY, 1),
        threads);
      view.After = sums.Metrics();
    }
    else
    {
      Rasterize(after(), camera, settings, workspace);
      ++effect.ViewsRendered;
      view.After = Measure(workspace.Image, target, threads);
    }
    effect.SecondsAfter += Since(t0);
    effect.Views.push_back(std::move(view));
  }
  for (const RemovalViewEffect& v : effect.Views)
  {
    AddToTotals(v.Split == CameraSplit::Train ? effect.Train : effect.Test, v);
  }
  FinishTotals(effect.Train);
  FinishTotals(effect.Test);
  std::stable_sort(effect.Views.begin(),
    effect.Views.end(),
    [](const RemovalViewEffect& a, const RemovalViewEffect& b)
    {
      if (a.HasImage != b.HasImage)
      {
        return a.HasImage;
      }
      return a.HasImage && Change(a) < Change(b);
    });
  return effect;
}

//------------------------------------------------------------------------------
ViewMetrics MeanViewMetrics(const std::vector<ViewMetrics>& figures,
  const std::vector<Camera>& cameras,
  CameraSplit split,
  std::size_t* views)
{
  ViewMetrics mean;
  double psnr = 0, ssim = 0, l1 = 0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < figures.size() && i < cameras.size(); ++i)
  {
    if (cameras[i].Split == split && std::isfinite(figures[i].L1))
    {
      psnr += figures[i].Psnr;
      ssim += figures[i].Ssim;
      l1 += figures[i].L1;
      ++count;
    }
  }
  if (count > 0)
  {
    mean.Psnr = psnr / static_cast<double>(count);
    mean.Ssim = ssim / static_cast<double>(count);
    mean.L1 = l1 / static_cast<double>(count);
  }
  if (views)
  {
    *views = count;
  }
  return mean;
}

} // namespace vis4gs

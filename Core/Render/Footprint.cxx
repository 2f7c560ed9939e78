// SPDX-License-Identifier: BSD-3-Clause
#include "Footprint.h"

#include "RasterBounds.h"

#include <omp.h>

#include <algorithm>
#include <cmath>

namespace vis4gs
{

namespace
{

//------------------------------------------------------------------------------
template <typename T, typename Acc>
void FootprintPass(const ViewProjection<T>& proj,
  const FootprintOptions& opt,
  const float* map,
  FootprintStats& stats)
{
  const int W = proj.Width, H = proj.Height;
  const bool rasterMode = opt.Mode == FootprintMode::Rasterizer;
  const std::int64_t n = static_cast<std::int64_t>(proj.Gaussians.size());
  std::uint64_t total = 0, evaluated = 0;
  const int threads = opt.Threads > 0 ? opt.Threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 1024) num_threads(threads) reduction(+ : total, evaluated)
  for (std::int64_t ii = 0; ii < n; ++ii)
  {
    const std::size_t i = static_cast<std::size_t>(ii);
    const ProjectedGaussian<T>& g = proj.Gaussians[i];
    if (!g.IsVisible())
    {
      continue;
    }
    int xLo, xHi, yLo, yHi;
    double level;
    if (rasterMode)
    {
      if (!(g.Opacity >= raster::MinAlpha<T>()))
      {
        continue; // alpha <= o < 1/255 everywhere
      }
      xLo = g.TileRect[0] * raster::TileSize;
      yLo = g.TileRect[1] * raster::TileSize;
      xHi = std::min(g.TileRect[2] * raster::TileSize, W) - 1;
      yHi = std::min(g.TileRect[3] * raster::TileSize, H) - 1;
      level = std::min(0.0, std::log(raster::MinAlpha<double>() / static_cast<double>(g.Opacity)));
    }
    else
    {
      const double A = g.ConicA, B = g.ConicB, C = g.ConicC;
      if (!(A > 0 && C > 0 && A * C - B * B > 0))
      {
        continue; // no ellipse
      }
      xLo = 0;
      yLo = 0;
      xHi = W - 1;
      yHi = H - 1;
      level = -4.5;
    }
    raster::detail::SpanBounds sb;
    if (!opt.BruteForce)
    {
      sb = raster::detail::MakeSpanBounds<T>(g.U, g.V, g.ConicA, g.ConicB, g.ConicC, level);
    }
    if (!sb.Bounded && !rasterMode && !opt.BruteForce)
    {
      // Unbounded ellipse mode: restrict to the 3-sigma radius box (the ellipse lies inside).
      const double r = g.Radius + 1.0;
      xLo = std::max(xLo, static_cast<int>(std::floor(std::max(-1e9, g.U - r))));
      xHi = std::min(xHi, static_cast<int>(std::ceil(std::min(1e9, g.U + r))));
      yLo = std::max(yLo, static_cast<int>(std::floor(std::max(-1e9, g.V - r))));
      yHi = std::min(yHi, static_cast<int>(std::ceil(std::min(1e9, g.V + r))));
    }
    if (sb.Bounded)
    {
      yLo = std::max(yLo, sb.RowMin);
      yHi = std::min(yHi, sb.RowMax);
    }
    std::uint32_t cnt = 0;
    Acc sum = 0;
    std::uint64_t evals = 0;
    const T minEllipse = T(-4.5);
    for (int y = yLo; y <= yHi; ++y)
    {
      int xa = xLo, xb = xHi;
      if (sb.Bounded)
      {
        int ca, cb;
        if (!sb.Columns(y, ca, cb))
        {
          continue;
        }
        xa = std::max(xa, ca);
        xb = std::min(xb, cb);
      }
      const T py = static_cast<T>(y);
      for (int x = xa; x <= xb; ++x)
      {
        const T power =
          raster::KernelPower<T>(g.U, g.V, g.ConicA, g.ConicB, g.ConicC, static_cast<T>(x), py);
        const bool in =
          rasterMode ? raster::KernelAlpha<T>(g.Opacity, power) >= T(0) : power >= minEllipse;
        if (in)
        {
          ++cnt;
          if (map)
          {
            sum += static_cast<Acc>(map[static_cast<std::size_t>(y) * W + x]);
          }
        }
      }
      evals += static_cast<std::uint64_t>(std::max(0, xb - xa + 1));
    }
    stats.PixelCount[i] = cnt;
    if (map)
    {
      stats.MapSum[i] = static_cast<double>(sum);
    }
    total += cnt;
    evaluated += evals;
  }
  stats.TotalPixels = total;
  stats.EvaluatedPixels = evaluated;
}

} // namespace

//------------------------------------------------------------------------------
template <typename T>
FootprintStats ComputeFootprints(const ViewProjection<T>& projection,
  const FootprintOptions& options,
  const float* map)
{
  FootprintStats stats;
  const std::size_t n = projection.Gaussians.size();
  stats.PixelCount.assign(n, 0);
  if (map)
  {
    stats.MapSum.assign(n, 0.0);
  }
  if (options.Accumulation == FootprintAccumulation::Float)
  {
    FootprintPass<T, float>(projection, options, map, stats);
  }
  else
  {
    FootprintPass<T, double>(projection, options, map, stats);
  }
  return stats;
}

template FootprintStats ComputeFootprints<float>(const ViewProjection<float>&,
  const FootprintOptions&,
  const float*);
template FootprintStats ComputeFootprints<double>(const ViewProjection<double>&,
  const FootprintOptions&,
  const float*);

} // namespace vis4gs

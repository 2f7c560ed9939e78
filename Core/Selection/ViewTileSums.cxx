// SPDX-License-Identifier: BSD-3-Clause
#include "ViewTileSums.h"

#include "Loss.h"
#include "RasterKernel.h"
#include "ThreadCount.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vis4gs
{
namespace
{
constexpr int Tile = raster::TileSize;
constexpr int Reach = 5; // the SSIM window's radius (11x11)

// A group of 8-connected flagged tiles: its tiles and its bounding box (inclusive).
struct TileGroup
{
  std::vector<std::size_t> Tiles;
  int X0 = 0, Y0 = 0, X1 = 0, Y1 = 0;
};

// The flagged tiles grouped by 8-connectivity: each group is measured on one crop, so that the
// SSIM window's margin is paid once per group rather than once per tile.
std::vector<TileGroup> GroupTiles(const std::vector<std::uint8_t>& tiles, int tx, int ty)
{
  std::vector<TileGroup> groups;
  std::vector<std::uint8_t> seen(tiles.size(), 0);
  std::vector<std::size_t> stack;
  for (std::size_t first = 0; first < tiles.size(); ++first)
  {
    if (!tiles[first] || seen[first])
    {
      continue;
    }
    TileGroup g;
    g.X0 = g.X1 = static_cast<int>(first % tx);
    g.Y0 = g.Y1 = static_cast<int>(first / tx);
    seen[first] = 1;
    stack.assign(1, first);
    while (!stack.empty())
    {
      const std::size_t t = stack.back();
      stack.pop_back();
      g.Tiles.push_back(t);
      const int x = static_cast<int>(t % tx), y = static_cast<int>(t / tx);
      g.X0 = std::min(g.X0, x);
      g.X1 = std::max(g.X1, x);
      g.Y0 = std::min(g.Y0, y);
      g.Y1 = std::max(g.Y1, y);
      for (int ny = std::max(0, y - 1); ny <= std::min(ty - 1, y + 1); ++ny)
      {
        for (int nx = std::max(0, x - 1); nx <= std::min(tx - 1, x + 1); ++nx)
        {
          const std::size_t n = static_cast<std::size_t>(ny) * tx + nx;
          if (tiles[n] && !seen[n])
          {
            seen[n] = 1;
            stack.push_back(n);
          }
        }
      }
    }
    groups.push_back(std::move(g));
  }
  return groups;
}
} // namespace

//------------------------------------------------------------------------------
ViewMetrics ViewTileSums::Metrics() const
{
  ViewMetrics m;
  if (this->Sums.empty())
  {
    return m;
  }
  double se = 0, ae = 0, ss = 0;
  for (std::size_t t = 0; t < this->TileCount(); ++t)
  {
    se += this->Sums[3 * t];
    ae += this->Sums[3 * t + 1];
    ss += this->Sums[3 * t + 2];
  }
  const double n = 3.0 * static_cast<double>(this->Width) * this->Height;
  const double mse = se / n;
  // As Psnr() of Loss.h: +inf for identical images.
  m.Psnr =
    mse <= 0 ? std::numeric_limits<double>::infinity() : 20.0 * std::log10(1.0 / std::sqrt(mse));
  m.Ssim = ss / n;
  m.L1 = ae / n;
  return m;
}

//------------------------------------------------------------------------------
ViewTileSums MeasureViewTiles(const float* render,
  const float* image,
  int width,
  int height,
  int threads)
{
  if (width <= 0 || height <= 0)
  {
    throw std::invalid_argument("MeasureViewTiles: image size " + std::to_string(width) + "x" +
      std::to_string(height) + " is not positive");
  }
  ViewTileSums sums;
  sums.Width = width;
  sums.Height = height;
  sums.TilesX = (width + Tile - 1) / Tile;
  sums.TilesY = (height + Tile - 1) / Tile;
  sums.Sums.assign(3 * sums.TileCount(), 0.0);
  RemeasureViewTiles(sums, render, image, std::vector<std::uint8_t>(sums.TileCount(), 1), threads);
  return sums;
}

//------------------------------------------------------------------------------
void RemeasureViewTiles(ViewTileSums& sums,
  const float* render,
  const float* image,
  const std::vector<std::uint8_t>& tiles,
  int threads)
{
  if (tiles.size() != sums.TileCount() || sums.Sums.size() != 3 * sums.TileCount() ||
    sums.TilesX != (sums.Width + Tile - 1) / Tile || sums.TilesY != (sums.Height + Tile - 1) / Tile)
  {
    throw std::invalid_argument("RemeasureViewTiles: " + std::to_string(tiles.size()) +
      " tile flags for sums of " + std::to_string(sums.TilesX) + "x" + std::to_string(sums.TilesY) +
      " tiles (" + std::to_string(sums.Sums.size()) + " values)");
  }
  const int W = sums.Width, H = sums.Height;
  const int nthreads = ThreadCount(threads);
  std::vector<float> cropRender, cropImage, map;
  for (const TileGroup& g : GroupTiles(tiles, sums.TilesX, sums.TilesY))
  {
    // The group's pixels and the SSIM window's reach around them, inside the image.
    const int x0 = std::max(0, g.X0 * Tile - Reach), y0 = std::max(0, g.Y0 * Tile - Reach);
    const int x1 = std::min(W, (g.X1 + 1) * Tile + Reach);
    const int y1 = std::min(H, (g.Y1 + 1) * Tile + Reach);
    const int cw = x1 - x0, ch = y1 - y0;
    const std::size_t cp = static_cast<std::size_t>(cw) * ch;
    cropRender.resize(3 * cp);
    cropImage.resize(3 * cp);
    for (int y = y0; y < y1; ++y)
    {
      const std::size_t from = 3 * (static_cast<std::size_t>(y) * W + x0);
      const std::size_t to = 3 * static_cast<std::size_t>(y - y0) * cw;
      // Clamped as ClampedImage() of RemovalEffect.h (NaN becomes 0).
      std::transform(render + from,
        render + from + 3 * cw,
        cropRender.begin() + to,
        [](float v) { return std::min(1.0f, std::max(0.0f, v)); });
      std::copy(image + from, image + from + 3 * cw, cropImage.begin() + to);
    }
    // A small crop is not worth a parallel region (their start dominates on a loaded machine).
    const bool parallel = cp >= 65536;
    SsimMap(cropRender.data(), cropImage.data(), cw, ch, map, parallel ? nthreads : 1);

    const std::int64_t count = static_cast<std::int64_t>(g.Tiles.size());
#pragma omp parallel for schedule(dynamic, 4) num_threads(nthreads) if (parallel)
    for (std::int64_t k = 0; k < count; ++k)
    {
      const std::size_t t = g.Tiles[static_cast<std::size_t>(k)];
      const int tx = static_cast<int>(t % sums.TilesX), ty = static_cast<int>(t / sums.TilesX);
      double se = 0, ae = 0, ss = 0;
      for (int y = ty * Tile; y < std::min(H, (ty + 1) * Tile); ++y)
      {
        for (int x = tx * Tile; x < std::min(W, (tx + 1) * Tile); ++x)
        {
          const std::size_t p = static_cast<std::size_t>(y - y0) * cw + (x - x0);
          for (int c = 0; c < 3; ++c)
          {
            const double d = static_cast<double>(cropRender[3 * p + c]) -
              static_cast<double>(cropImage[3 * p + c]);
            se += d * d;
            ae += std::abs(d);
            ss += static_cast<double>(map[c * cp + p]);
          }
        }
      }
      sums.Sums[3 * t] = se;
      sums.Sums[3 * t + 1] = ae;
      sums.Sums[3 * t + 2] = ss;
    }
  }
}

//------------------------------------------------------------------------------
std::vector<std::uint8_t> DilateTiles(const std::vector<std::uint8_t>& tiles,
  int tilesX,
  int tilesY,
  int radius)
{
  if (tiles.size() != static_cast<std::size_t>(tilesX) * static_cast<std::size_t>(tilesY))
  {
    throw std::invalid_argument("DilateTiles: " + std::to_string(tiles.size()) +
      " flags for a grid of " + std::to_string(tilesX) + "x" + std::to_string(tilesY));
  }
  // Separable: along rows, then along columns.
  std::vector<std::uint8_t> rows(tiles.size(), 0), out(tiles.size(), 0);
  for (int y = 0; y < tilesY; ++y)
  {
    for (int x = 0; x < tilesX; ++x)
    {
      if (tiles[static_cast<std::size_t>(y) * tilesX + x])
      {
        for (int nx = std::max(0, x - radius); nx <= std::min(tilesX - 1, x + radius); ++nx)
        {
          rows[static_cast<std::size_t>(y) * tilesX + nx] = 1;
        }
      }
    }
  }
  for (int y = 0; y < tilesY; ++y)
  {
    for (int x = 0; x < tilesX; ++x)
    {
      if (rows[static_cast<std::size_t>(y) * tilesX + x])
      {
        for (int ny = std::max(0, y - radius); ny <= std::min(tilesY - 1, y + radius); ++ny)
        {
          out[static_cast<std::size_t>(ny) * tilesX + x] = 1;
        }
      }
    }
  }
  return out;
}

} // namespace vis4gs

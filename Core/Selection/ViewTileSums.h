// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ViewTileSums.h
 * @brief A render measured against its image per 16x16 tile (the rasteriser's tiles), so that
 * a clean-up's "after" re-measures only the tiles it changed (issue 20).
 *
 * The figures are those the trainer logs (Core/Training/Loss.h), on the render clamped to
 * [0, 1]: PSNR over every channel and pixel, SSIM (11x11 Gaussian window, zero padding), L1.
 * Each tile keeps, in double, the sums over its pixels and channels of the squared error, of
 * the absolute error and of the SSIM map; the figures are the sums of the tiles in tile order.
 * They equal Psnr()/Ssim()/L1Loss() of the whole image up to the order of the double
 * additions (relative differences of about 1e-15).
 *
 * Re-measuring tiles is exact: a pixel's SSIM value depends only on the render and image
 * within 5 pixels of it, and SsimMap() of a crop reproduces the full image's value bit for bit
 * wherever that window lies inside the crop, so RemeasureViewTiles() of the tiles that changed
 * gives the very sums MeasureViewTiles() of the whole new render gives.
 */
#ifndef vis4gs_ViewTileSums_h
#define vis4gs_ViewTileSums_h

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace vis4gs
{

/// Image figures of one render against its image; NaN when the view has no image.
struct ViewMetrics
{
  double Psnr = std::numeric_limits<double>::quiet_NaN();
  double Ssim = std::numeric_limits<double>::quiet_NaN();
  double L1 = std::numeric_limits<double>::quiet_NaN();
};

/// Per-tile sums of one view (16x16 tiles, row-major, the last row and column clipped).
struct ViewTileSums
{
  int Width = 0, Height = 0;
  int TilesX = 0, TilesY = 0;
  /// Three per tile (ty * TilesX + tx): squared error, absolute error, SSIM map, each summed
  /// over the tile's pixels and the three channels.
  std::vector<double> Sums;

  bool Empty() const { return this->Sums.empty(); }
  std::size_t TileCount() const { return static_cast<std::size_t>(this->TilesX) * this->TilesY; }
  /// PSNR, SSIM and L1 of the whole view (NaN for empty sums).
  ViewMetrics Metrics() const;
};

/**
 * Measures the RGB render @p render (3 floats per pixel, not clamped: the values are clamped to
 * [0, 1] here) against the RGB image @p image of @p width x @p height, every tile. Throws
 * std::invalid_argument for a non-positive size.
 */
ViewTileSums MeasureViewTiles(const float* render,
  const float* image,
  int width,
  int height,
  int threads = 0);

/**
 * Re-measures the tiles where @p tiles is non-zero (one byte per tile of @p sums) against a
 * new render; every other tile keeps its sums. @p render must hold the new render on those
 * tiles and within 5 pixels around them (the SSIM window's reach); other pixels are not read
 * for the result. Throws std::invalid_argument when @p tiles or the size does not match.
 */
void RemeasureViewTiles(ViewTileSums& sums,
  const float* render,
  const float* image,
  const std::vector<std::uint8_t>& tiles,
  int threads = 0);

/// The tiles within @p radius tiles (8-neighbourhood) of a flagged tile of a @p tilesX x
/// @p tilesY grid.
std::vector<std::uint8_t> DilateTiles(const std::vector<std::uint8_t>& tiles,
  int tilesX,
  int tilesY,
  int radius);

} // namespace vis4gs

#endif

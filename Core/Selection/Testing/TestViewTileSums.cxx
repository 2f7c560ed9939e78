// SPDX-License-Identifier: BSD-3-Clause
// Per-tile figures of a render (issue 20): the whole-image figures of Loss.h up to the order of
// the sums, per-tile sums against a plain double loop, and re-measuring some tiles of a changed
// render (with garbage outside what it may read) equal to measuring the new render whole, bit
// for bit.
#include "ViewTileSums.h"

#include "Loss.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

namespace vis4gs
{
namespace
{
// Values around [0, 1], some outside it (the render is clamped before it is measured).
std::vector<float> RandomRgb(int w, int h, unsigned seed, float lo, float hi)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(lo, hi);
  std::vector<float> v(3 * static_cast<std::size_t>(w) * h);
  for (float& x : v)
  {
    x = u(rng);
  }
  return v;
}

std::vector<float> Clamped(std::vector<float> v)
{
  for (float& x : v)
  {
    x = std::min(1.0f, std::max(0.0f, x));
  }
  return v;
}

void ExpectClose(double a, double b, const char* what)
{
  EXPECT_NEAR(a, b, 1e-12 * std::max(1.0, std::abs(b))) << what;
}
} // namespace

TEST(ViewTileSums, FiguresAreTheLossMetricsAndTilesArePlainSums)
{
  const int W = 83, H = 45; // 6 x 3 tiles, the last column and row clipped
  const std::vector<float> render = RandomRgb(W, H, 1, -0.2f, 1.2f);
  const std::vector<float> image = RandomRgb(W, H, 2, 0.0f, 1.0f);
  const ViewTileSums sums = MeasureViewTiles(render.data(), image.data(), W, H, 2);
  ASSERT_EQ(sums.TilesX, 6);
  ASSERT_EQ(sums.TilesY, 3);
  ASSERT_EQ(sums.Sums.size(), 3u * 18);
  const std::vector<float> clamped = Clamped(render);
  const std::size_t n = clamped.size();
  const ViewMetrics m = sums.Metrics();
  ExpectClose(m.Psnr, Psnr(clamped.data(), image.data(), n), "PSNR");
  ExpectClose(m.Ssim, Ssim(clamped.data(), image.data(), W, H), "SSIM");
  ExpectClose(m.L1, L1Loss(clamped.data(), image.data(), n), "L1");

  // Tile (5, 2), the clipped corner: 3 x 13 pixels.
  double se = 0, ae = 0;
  for (int y = 32; y < H; ++y)
  {
    for (int x = 80; x < W; ++x)
    {
      for (int c = 0; c < 3; ++c)
      {
        const std::size_t i = 3 * (static_cast<std::size_t>(y) * W + x) + c;
        const double d = static_cast<double>(clamped[i]) - image[i];
        se += d * d;
        ae += std::abs(d);
      }
    }
  }
  const std::size_t corner = 2 * 6 + 5;
  ExpectClose(sums.Sums[3 * corner], se, "squared error of the corner tile");
  ExpectClose(sums.Sums[3 * corner + 1], ae, "absolute error of the corner tile");

  // Identical images: PSNR +inf, SSIM 1, L1 0, exactly.
  const ViewMetrics same = MeasureViewTiles(image.data(), image.data(), W, H).Metrics();
  EXPECT_TRUE(std::isinf(same.Psnr) && same.Psnr > 0);
  EXPECT_EQ(same.Ssim, 1.0);
  EXPECT_EQ(same.L1, 0.0);
  EXPECT_TRUE(std::isnan(ViewTileSums{}.Metrics().Psnr));
  EXPECT_THROW(MeasureViewTiles(image.data(), image.data(), 0, H), std::invalid_argument);
}

// A render changed on some tiles: re-measuring the changed tiles and one tile around them, with a
// buffer that holds the new render only there and 5 pixels further (NaN beyond), gives the sums
// of the new render measured whole, bit for bit.
TEST(ViewTileSums, RemeasuredTilesEqualAWholeMeasure)
{
  const int W = 150, H = 97; // 10 x 7 tiles
  const int TX = 10, TY = 7;
  const std::vector<float> image = RandomRgb(W, H, 3, 0.0f, 1.0f);
  const std::vector<float> before = RandomRgb(W, H, 4, -0.1f, 1.1f);
  const ViewTileSums base = MeasureViewTiles(before.data(), image.data(), W, H);

  struct Case
  {
    const char* Name;
    std::vector<int> Changed; // tiles whose pixels change
  };
  std::vector<int> all(TX * TY);
  for (int t = 0; t < TX * TY; ++t)
  {
    all[t] = t;
  }
  const std::vector<Case> cases = { { "no tile", {} },
    { "one interior tile", { 3 * TX + 4 } },
    { "the corner tile", { TX * TY - 1 } },
    { "two groups", { 0, 1, TX + 1, 5 * TX + 8 } },
    { "every tile", all } };
  for (const Case& c : cases)
  {
    std::vector<std::uint8_t> changed(TX * TY, 0);
    for (int t : c.Changed)
    {
      changed[t] = 1;
    }
    // The new render: other values in the changed tiles.
    std::vector<float> after = before;
    const std::vector<float> noise = RandomRgb(W, H, 5, -0.1f, 1.1f);
    for (int y = 0; y < H; ++y)
    {
      for (int x = 0; x < W; ++x)
      {
        if (changed[(y / 16) * TX + x / 16])
        {
          for (int k = 0; k < 3; ++k)
          {
            after[3 * (y * W + x) + k] = noise[3 * (y * W + x) + k];
          }
        }
      }
    }
    const std::vector<std::uint8_t> remeasured = DilateTiles(changed, TX, TY, 1);
    // What the caller must provide: the new render on the re-measured tiles and 5 px around.
    std::vector<float> partial(after.size(), std::numeric_limits<float>::quiet_NaN());
    for (int y = 0; y < H; ++y)
    {
      for (int x = 0; x < W; ++x)
      {
        bool near = false;
        for (int t = 0; t < TX * TY && !near; ++t)
        {
          const int x0 = (t % TX) * 16, y0 = (t / TX) * 16;
          near = remeasured[t] && x >= x0 - 5 && x < x0 + 21 && y >= y0 - 5 && y < y0 + 21;
        }
        if (near)
        {
          for (int k = 0; k < 3; ++k)
          {
            partial[3 * (y * W + x) + k] = after[3 * (y * W + x) + k];
          }
        }
      }
    }
    ViewTileSums sums = base;
    RemeasureViewTiles(sums, partial.data(), image.data(), remeasured, 2);
    const ViewTileSums whole = MeasureViewTiles(after.data(), image.data(), W, H);
    EXPECT_EQ(sums.Sums, whole.Sums) << c.Name;
    if (c.Changed.empty())
    {
      EXPECT_EQ(sums.Sums, base.Sums);
    }
    else
    {
      EXPECT_NE(sums.Metrics().Psnr, base.Metrics().Psnr) << c.Name;
    }
  }
  ViewTileSums sums = base;
  EXPECT_THROW(
    RemeasureViewTiles(sums, before.data(), image.data(), { 1, 0 }), std::invalid_argument);
}

TEST(ViewTileSums, DilateTiles)
{
  // 5 x 4 grid, one tile at (1, 1) and one at (4, 3).
  std::vector<std::uint8_t> tiles(20, 0);
  tiles[1 * 5 + 1] = 1;
  tiles[3 * 5 + 4] = 1;
  const std::vector<std::uint8_t> expected = {
    1,
    1,
    1,
    0,
    0, //
    1,
    1,
    1,
    0,
    0, //
    1,
    1,
    1,
    1,
    1, //
    0,
    0,
    0,
    1,
    1, //
  };
  EXPECT_EQ(DilateTiles(tiles, 5, 4, 1), expected);
  EXPECT_EQ(DilateTiles(tiles, 5, 4, 0), tiles);
  EXPECT_EQ(DilateTiles(tiles, 5, 4, 9), std::vector<std::uint8_t>(20, 1));
  EXPECT_THROW(DilateTiles(tiles, 4, 4, 1), std::invalid_argument);
}

} // namespace vis4gs

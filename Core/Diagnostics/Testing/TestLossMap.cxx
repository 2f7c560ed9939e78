// SPDX-License-Identifier: BSD-3-Clause
// Loss maps (DESIGN §4): hand-computed cases, replicated edges, a naive double reference that
// applies the Laplacian to render and image separately, NaN locality, and the box reduction.
#include "LossMap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace
{

vis4gs::Image Constant(int w, int h, float r, float g, float b)
{
  vis4gs::Image image;
  image.Width = w;
  image.Height = h;
  image.Pixels.resize(static_cast<std::size_t>(w) * h * 3);
  for (std::size_t p = 0; p < static_cast<std::size_t>(w) * h; ++p)
  {
    image.Pixels[3 * p] = r;
    image.Pixels[3 * p + 1] = g;
    image.Pixels[3 * p + 2] = b;
  }
  return image;
}

vis4gs::Image Random(int w, int h, unsigned seed)
{
  vis4gs::Image image = Constant(w, h, 0, 0, 0);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (float& v : image.Pixels)
  {
    v = u(rng);
  }
  return image;
}

// Naive reference: Laplacians of render and image computed separately, in double.
std::vector<double> NaiveLoss(const vis4gs::Image& r, const vis4gs::Image& i, double lambda)
{
  const int w = r.Width, h = r.Height;
  auto at = [&](const vis4gs::Image& im, int x, int y, int c) -> double
  {
    x = std::min(std::max(x, 0), w - 1);
    y = std::min(std::max(y, 0), h - 1);
    return im.Pixels[(static_cast<std::size_t>(y) * w + x) * 3 + c];
  };
  auto lap = [&](const vis4gs::Image& im, int x, int y, int c)
  {
    return at(im, x - 1, y, c) + at(im, x + 1, y, c) + at(im, x, y - 1, c) + at(im, x, y + 1, c) -
      4 * at(im, x, y, c);
  };
  std::vector<double> out(static_cast<std::size_t>(w) * h);
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      double l1 = 0, edge = 0;
      for (int c = 0; c < 3; ++c)
      {
        l1 += std::abs(at(r, x, y, c) - at(i, x, y, c));
        edge += std::abs(lap(r, x, y, c) - lap(i, x, y, c));
      }
      out[static_cast<std::size_t>(y) * w + x] = (1 - lambda) * l1 / 3 + lambda * edge / 3;
    }
  }
  return out;
}

} // namespace

TEST(LossMap, SinglePixelDifferenceByHand)
{
  // 3x3, the centre differs by d in red only.
  const float d = 0.5f;
  vis4gs::Image image = Constant(3, 3, 0.25f, 0.5f, 0.75f);
  vis4gs::Image render = image;
  render.Pixels[3 * 4] += d;
  const auto loss = vis4gs::ComputeLossMap(render, image);
  // centre: L1 = d/3, Laplacian of the difference = -4d -> edge = 4d/3.
  EXPECT_NEAR(loss[4], 0.8 * d / 3 + 0.2 * 4 * d / 3, 1e-7);
  // four neighbours: L1 = 0, Laplacian = d -> edge d/3.
  for (int p : { 1, 3, 5, 7 })
  {
    EXPECT_NEAR(loss[p], 0.2 * d / 3, 1e-7) << p;
  }
  // corners see no difference.
  for (int p : { 0, 2, 6, 8 })
  {
    EXPECT_EQ(loss[p], 0.0f) << p;
  } // edgeScale multiplies the Laplacian term only (the lower-resolution correction).
  const auto scaled =
    vis4gs::ComputeLossMap(render.Pixels.data(), image.Pixels.data(), 3, 3, 0.2, 0.25);
  EXPECT_NEAR(scaled[4], 0.8 * d / 3 + 0.25 * 0.2 * 4 * d / 3, 1e-7);
  EXPECT_NEAR(scaled[1], 0.25 * 0.2 * d / 3, 1e-7);
}

TEST(LossMap, ReplicatedEdges)
{
  // Difference d at the corner (0,0) of 3x3: its Laplacian there is d + d + 0 + 0 - 4d = -2d
  // (the missing up and left neighbours are the corner itself).
  const float d = 0.25f;
  vis4gs::Image image = Constant(3, 3, 0, 0, 0);
  vis4gs::Image render = image;
  render.Pixels[1] = d; // green of (0,0)
  const auto loss = vis4gs::ComputeLossMap(render, image);
  EXPECT_NEAR(loss[0], 0.8 * d / 3 + 0.2 * 2 * d / 3, 1e-7);
  EXPECT_NEAR(loss[1], 0.2 * d / 3, 1e-7);
  EXPECT_NEAR(loss[3], 0.2 * d / 3, 1e-7);
  EXPECT_EQ(loss[4], 0.0f);
}

TEST(LossMap, ConstantDifferenceHasNoEdgeTerm)
{
  // With replicated edges the Laplacian of a constant is 0 everywhere, borders included.
  const vis4gs::Image image = Constant(7, 5, 0.1f, 0.2f, 0.3f);
  const vis4gs::Image render = Constant(7, 5, 0.4f, 0.0f, 0.3f);
  const auto loss = vis4gs::ComputeLossMap(render, image);
  const double expected = 0.8 * (0.3 + 0.2 + 0.0) / 3;
  for (float v : loss)
  {
    EXPECT_NEAR(v, expected, 1e-7);
  }
  // lambda = 1: only the edge term, which is 0.
  for (float v : vis4gs::ComputeLossMap(render, image, 1.0))
  {
    EXPECT_NEAR(v, 0.0, 1e-7);
  }
}

TEST(LossMap, MatchesNaiveReference)
{
  for (int size : { 1, 2, 17 })
  {
    const vis4gs::Image render = Random(size, size + 3, 1);
    const vis4gs::Image image = Random(size, size + 3, 2);
    const auto loss = vis4gs::ComputeLossMap(render, image);
    const auto naive = NaiveLoss(render, image, 0.2);
    ASSERT_EQ(loss.size(), naive.size());
    for (std::size_t p = 0; p < loss.size(); ++p)
    {
      EXPECT_NEAR(loss[p], naive[p], 1e-6 * (1 + naive[p])) << p;
    }
    // Swapping render and image changes nothing.
    const auto swapped = vis4gs::ComputeLossMap(image, render);
    for (std::size_t p = 0; p < loss.size(); ++p)
    {
      EXPECT_EQ(loss[p], swapped[p]);
    }
  }
}

TEST(LossMap, NaNStaysLocal)
{
  vis4gs::Image image = Constant(5, 5, 0.5f, 0.5f, 0.5f);
  vis4gs::Image render = image;
  render.Pixels[3 * 12] = std::nanf(""); // centre (2,2)
  const auto loss = vis4gs::ComputeLossMap(render, image);
  for (int p = 0; p < 25; ++p)
  {
    const bool touched = p == 12 || p == 7 || p == 11 || p == 13 || p == 17;
    EXPECT_EQ(std::isnan(loss[p]), touched) << p;
    if (!touched)
    {
      EXPECT_EQ(loss[p], 0.0f);
    }
  }
}

TEST(LossMap, RejectsMismatchedSizes)
{
  EXPECT_THROW(vis4gs::ComputeLossMap(Constant(3, 3, 0, 0, 0), Constant(3, 4, 0, 0, 0)),
    std::invalid_argument);
  vis4gs::Image rgba = Constant(3, 3, 0, 0, 0);
  rgba.Channels = 4;
  EXPECT_THROW(vis4gs::ComputeLossMap(rgba, rgba), std::invalid_argument);
  EXPECT_THROW(vis4gs::ComputeLossMap(nullptr, nullptr, 0, 0), std::invalid_argument);
}

TEST(LossMap, LowResolutionSize)
{
  EXPECT_EQ(vis4gs::LossMapSize(1000, 4), 250);
  EXPECT_EQ(vis4gs::LossMapSize(657, 4), 164); // 164.25
  EXPECT_EQ(vis4gs::LossMapSize(658, 4), 165); // 164.5 rounds up
  EXPECT_EQ(vis4gs::LossMapSize(3, 8), 1);     // never 0
  EXPECT_EQ(vis4gs::LossMapSize(5, 1), 5);
  EXPECT_THROW(vis4gs::LossMapSize(0, 2), std::invalid_argument);
}

TEST(LossMap, BoxDownsampleBlocks)
{
  // Divisible: each output pixel is the plain mean of its f x f block.
  const vis4gs::Image image = Random(8, 4, 3);
  const vis4gs::Image low = vis4gs::BoxDownsample(image, 2, 1);
  ASSERT_EQ(low.Width, 2);
  ASSERT_EQ(low.Height, 1);
  for (int k = 0; k < 2; ++k)
  {
    for (int c = 0; c < 3; ++c)
    {
      double s = 0;
      for (int y = 0; y < 4; ++y)
      {
        for (int x = 4 * k; x < 4 * k + 4; ++x)
        {
          s += image.At(x, y, c);
        }
      }
      EXPECT_NEAR(low.At(k, 0, c), s / 16, 1e-6);
    }
  }
}

TEST(LossMap, BoxDownsampleFractionalWeights)
{
  // 5 -> 2 columns: s = 2.5; output 0 = (p0 + p1 + 0.5 p2)/2.5, output 1 = (0.5 p2 + p3 + p4)/2.5.
  vis4gs::Image image = Constant(5, 1, 0, 0, 0);
  const float p[5] = { 1, 2, 4, 8, 16 };
  for (int x = 0; x < 5; ++x)
  {
    image.At(x, 0, 0) = p[x];
  }
  const vis4gs::Image low = vis4gs::BoxDownsample(image, 2, 1);
  EXPECT_NEAR(low.At(0, 0, 0), (1 + 2 + 0.5 * 4) / 2.5, 1e-6);
  EXPECT_NEAR(low.At(1, 0, 0), (0.5 * 4 + 8 + 16) / 2.5, 1e-6);
  // Area weights preserve the integral: sum(out) * (W/w') * (H/h') = sum(in).
  const vis4gs::Image big = Random(13, 7, 4);
  const vis4gs::Image small = vis4gs::BoxDownsample(big, 4, 3);
  double in = 0, out = 0;
  for (float v : big.Pixels)
  {
    in += v;
  }
  for (float v : small.Pixels)
  {
    out += v;
  }
  EXPECT_NEAR(out * (13.0 / 4) * (7.0 / 3), in, 1e-4);
  // A constant stays constant; same size is the identity; bad sizes throw.
  for (float v : vis4gs::BoxDownsample(Constant(9, 9, 0.3f, 0.3f, 0.3f), 2, 4).Pixels)
  {
    EXPECT_NEAR(v, 0.3f, 1e-6);
  }
  EXPECT_EQ(vis4gs::BoxDownsample(big, 13, 7).Pixels, big.Pixels);
  EXPECT_THROW(vis4gs::BoxDownsample(big, 14, 7), std::invalid_argument);
  EXPECT_THROW(vis4gs::BoxDownsample(big, 0, 7), std::invalid_argument);
}

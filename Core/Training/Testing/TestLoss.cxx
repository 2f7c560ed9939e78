// SPDX-License-Identifier: BSD-3-Clause
// Losses and metrics (reference §3) against naive re-implementations and finite differences.
#include "Loss.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

using namespace vis4gs;

namespace
{

std::vector<double> RandomImage(int w, int h, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> img(3 * static_cast<std::size_t>(w) * h);
  for (double& v : img)
  {
    v = u(rng);
  }
  return img;
}

// Naive SSIM: direct 11x11 2D window with zero padding, per channel, straight from §3.
double NaiveSsim(const std::vector<double>& x, const std::vector<double>& y, int W, int H)
{
  double g[11], sum = 0;
  for (int i = 0; i < 11; ++i)
  {
    g[i] = std::exp(-((i - 5) * (i - 5)) / (2 * 1.5 * 1.5));
    sum += g[i];
  }
  for (double& v : g)
  {
    v /= sum;
  }
  double total = 0;
  for (int c = 0; c < 3; ++c)
  {
    for (int py = 0; py < H; ++py)
    {
      for (int px = 0; px < W; ++px)
      {
        double mx = 0, my = 0, xx = 0, yy = 0, xy = 0;
        for (int j = 0; j < 11; ++j)
        {
          for (int i = 0; i < 11; ++i)
          {
            const int qx = px + i - 5, qy = py + j - 5;
            if (qx < 0 || qy < 0 || qx >= W || qy >= H)
            {
              continue; // zero padding
            }
            const double w = g[i] * g[j];
            const double a = x[3 * (qy * W + qx) + c], b = y[3 * (qy * W + qx) + c];
            mx += w * a;
            my += w * b;
            xx += w * a * a;
            yy += w * b * b;
            xy += w * a * b;
          }
        }
        const double C1 = 1e-4, C2 = 9e-4;
        const double sx = xx - mx * mx, sy = yy - my * my, sxy = xy - mx * my;
        total +=
          ((2 * mx * my + C1) * (2 * sxy + C2)) / ((mx * mx + my * my + C1) * (sx + sy + C2));
      }
    }
  }
  return total / (3.0 * W * H);
}

} // namespace

TEST(Loss, WindowIsNormalisedGaussian)
{
  const auto& w = SsimWindow1D();
  ASSERT_EQ(w.size(), 11u);
  double s = 0;
  for (double v : w)
  {
    s += v;
  }
  EXPECT_NEAR(s, 1.0, 1e-15);
  EXPECT_NEAR(w[5] / w[4], std::exp(1.0 / 4.5), 1e-12);
  EXPECT_DOUBLE_EQ(w[0], w[10]);
}

TEST(Loss, SsimMatchesNaiveWindow)
{
  for (auto [W, H] : { std::pair<int, int>{ 23, 17 }, { 7, 5 }, { 1, 1 } })
  {
    const auto x = RandomImage(W, H, 1), y = RandomImage(W, H, 2);
    EXPECT_NEAR(Ssim(x.data(), y.data(), W, H), NaiveSsim(x, y, W, H), 1e-13) << W << "x" << H;
    // Identical images: every map value is exactly 1 (the border included).
    EXPECT_NEAR(Ssim(x.data(), x.data(), W, H), 1.0, 1e-12);
    std::vector<float> xf(x.begin(), x.end()), yf(y.begin(), y.end());
    EXPECT_NEAR(Ssim(xf.data(), yf.data(), W, H), NaiveSsim(x, y, W, H), 2e-5);
  }
}

TEST(Loss, TrainingLossGradientMatchesFiniteDifferences)
{
  const int W = 19, H = 14;
  auto x = RandomImage(W, H, 3);
  const auto y = RandomImage(W, H, 4);
  std::vector<double> grad;
  const LossValues v = TrainingLoss(x.data(), y.data(), W, H, 0.2, &grad);
  EXPECT_NEAR(v.Loss, 0.8 * v.L1 + 0.2 * (1 - v.Ssim), 1e-15);
  // Away from x == y (the L1 kink), central differences.
  const double h = 1e-6;
  double maxErr = 0, maxG = 0;
  for (std::size_t i = 0; i < x.size(); i += 7)
  {
    if (std::abs(x[i] - y[i]) < 1e-4)
    {
      continue;
    }
    const double o = x[i];
    x[i] = o + h;
    const double lp =
      TrainingLoss(x.data(), y.data(), W, H, 0.2, static_cast<std::vector<double>*>(nullptr)).Loss;
    x[i] = o - h;
    const double lm =
      TrainingLoss(x.data(), y.data(), W, H, 0.2, static_cast<std::vector<double>*>(nullptr)).Loss;
    x[i] = o;
    const double fd = (lp - lm) / (2 * h);
    maxErr = std::max(maxErr, std::abs(fd - grad[i]));
    maxG = std::max(maxG, std::abs(grad[i]));
  }
  EXPECT_GT(maxG, 0.0);
  EXPECT_LT(maxErr, 1e-8 * std::max(1.0, maxG) + 1e-10);
  // Pure SSIM gradient (lambda = 1) on the border pixels as well.
  std::vector<double> gs;
  TrainingLoss(x.data(), y.data(), W, H, 1.0, &gs);
  for (std::size_t i :
    { std::size_t(0), std::size_t(3 * W - 1), x.size() - 1, std::size_t(3 * W * 7 + 5) })
  {
    const double o = x[i];
    x[i] = o + h;
    const double lp =
      TrainingLoss(x.data(), y.data(), W, H, 1.0, static_cast<std::vector<double>*>(nullptr)).Loss;
    x[i] = o - h;
    const double lm =
      TrainingLoss(x.data(), y.data(), W, H, 1.0, static_cast<std::vector<double>*>(nullptr)).Loss;
    x[i] = o;
    EXPECT_NEAR(gs[i], (lp - lm) / (2 * h), 1e-9) << i;
  }
}

TEST(Loss, L1GradientUsesSignZeroAtTies)
{
  std::vector<double> x = { 0.5, 0.2, 0.9 }, y = { 0.5, 0.4, 0.1 };
  std::vector<double> g;
  TrainingLoss(x.data(), y.data(), 1, 1, 0.0, &g);
  EXPECT_EQ(g[0], 0.0);
  EXPECT_DOUBLE_EQ(g[1], -1.0 / 3);
  EXPECT_DOUBLE_EQ(g[2], 1.0 / 3);
}

TEST(Loss, PsnrHandValues)
{
  std::vector<double> x(300, 0.5), y(300, 0.5);
  EXPECT_TRUE(std::isinf(Psnr(x.data(), y.data(), x.size())));
  for (double& v : y)
  {
    v = 0.6; // MSE 0.01 -> 20 dB
  }
  EXPECT_NEAR(Psnr(x.data(), y.data(), x.size()), 20.0, 1e-12);
  y[0] = 0.5 + std::sqrt(0.01 * 300 - 0.01 * 299); // unchanged MSE
  EXPECT_NEAR(Psnr(x.data(), y.data(), x.size()), 20.0, 1e-9);
  EXPECT_NEAR(L1Loss(x.data(), y.data(), x.size()), 0.1, 1e-12);
}

TEST(Loss, ThreadCountDoesNotChangeResults)
{
  const int W = 64, H = 48;
  const auto xd = RandomImage(W, H, 5), yd = RandomImage(W, H, 6);
  std::vector<float> x(xd.begin(), xd.end()), y(yd.begin(), yd.end());
  std::vector<float> g1, g2;
  const auto a = TrainingLoss(x.data(), y.data(), W, H, 0.2, &g1, 1);
  const auto b = TrainingLoss(x.data(), y.data(), W, H, 0.2, &g2, 2);
  EXPECT_EQ(a.Loss, b.Loss);
  EXPECT_EQ(g1, g2);
}

// The SSIM blur runs on the best instruction set: every instruction set must give the same
// bits (element-wise loops, no contraction), and the blur must equal a direct 11x11
// zero-padded window in double to float rounding, on planes narrower and wider than the
// window, with border columns only, and with large and tiny values.
TEST(Loss, SsimBlurIsBitIdenticalOnEveryInstructionSetAndMatchesDirectWindow)
{
  const std::vector<double>& g = SsimWindow1D();
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (const auto& size : { std::pair<int, int>{ 1, 1 },
         { 7, 3 },
         { 10, 11 },
         { 11, 12 },
         { 37, 29 },
         { 64, 5 },
         { 130, 67 } })
  {
    const int W = size.first, H = size.second;
    std::vector<float> in(static_cast<std::size_t>(W) * H);
    for (std::size_t i = 0; i < in.size(); ++i)
    {
      in[i] = u(rng) * (i % 13 == 0 ? 1e20f : (i % 7 == 0 ? 1e-20f : 1.0f));
    }
    std::vector<float> ref(in.size()), out(in.size());
    detail::SsimBlur(in.data(), ref.data(), W, H, 1);
    for (int isa : { 0, 2, 3 })
    {
      detail::SsimBlur(in.data(), out.data(), W, H, isa);
      EXPECT_EQ(out, ref) << W << "x" << H << " isa " << isa;
    }
    for (int py = 0; py < H; ++py)
    {
      for (int px = 0; px < W; ++px)
      {
        double s = 0, mag = 0;
        for (int j = 0; j < 11; ++j)
        {
          for (int i = 0; i < 11; ++i)
          {
            const int qx = px + i - 5, qy = py + j - 5;
            if (qx >= 0 && qy >= 0 && qx < W && qy < H)
            {
              const double v = in[static_cast<std::size_t>(qy) * W + qx];
              s += g[i] * g[j] * v;
              mag += g[i] * g[j] * std::abs(v);
            }
          }
        }
        const float b = ref[static_cast<std::size_t>(py) * W + px];
        ASSERT_NEAR(b, s, 1e-6 * mag + 1e-30) << W << "x" << H << " pixel " << px << ", " << py;
      }
    }
  }
}

// The whole SSIM (map, mean and gradient) gives the same bits on every instruction set.
TEST(Loss, SsimIsBitIdenticalOnEveryInstructionSet)
{
  for (const auto& size : { std::pair<int, int>{ 9, 4 }, { 45, 38 }, { 130, 70 } })
  {
    const int W = size.first, H = size.second;
    std::vector<double> xd = RandomImage(W, H, 11);
    const std::vector<double> yd = RandomImage(W, H, 12);
    for (std::size_t i = 0; i < xd.size(); i += 17)
    {
      xd[i] = yd[i]; // equal pixels
    }
    const std::vector<float> x(xd.begin(), xd.end()), y(yd.begin(), yd.end());
    std::vector<float> ref(x.size()), grad(x.size());
    const double s1 = detail::SsimOnIsa(x.data(), y.data(), W, H, 1, ref.data());
    EXPECT_NEAR(s1, NaiveSsim(xd, yd, W, H), 1e-5);
    for (int isa : { 0, 2, 3 })
    {
      const double s = detail::SsimOnIsa(x.data(), y.data(), W, H, isa, grad.data());
      EXPECT_EQ(s, s1) << W << "x" << H << " isa " << isa;
      EXPECT_EQ(grad, ref) << W << "x" << H << " isa " << isa;
    }
    EXPECT_EQ(Ssim(x.data(), y.data(), W, H, 2), s1);
  }
}

// The trainer keeps each view's target-only SSIM maps: the loss and its gradient must be
// the same bits as without them, with and without a gradient, on any thread count, and maps
// made for another image or size are refused.
TEST(Loss, KeptTargetMapsGiveTheSameBits)
{
  const int W = 53, H = 41;
  const std::vector<double> xd = RandomImage(W, H, 21), yd = RandomImage(W, H, 22);
  const std::vector<float> x(xd.begin(), xd.end()), y(yd.begin(), yd.end());
  SsimTarget<float> target;
  PrepareSsimTarget(y.data(), W, H, target, 2);
  EXPECT_EQ(target.Planes.size(), 6u * W * H);
  for (int threads : { 1, 2 })
  {
    std::vector<float> g0, g1;
    const LossValues a = TrainingLoss(x.data(), y.data(), W, H, 0.2, &g0, threads);
    const LossValues b = TrainingLoss(x.data(), y.data(), W, H, 0.2, &g1, threads, &target);
    EXPECT_EQ(a.Loss, b.Loss);
    EXPECT_EQ(a.L1, b.L1);
    EXPECT_EQ(a.Ssim, b.Ssim);
    EXPECT_EQ(g0, g1);
    const LossValues c = TrainingLoss(
      x.data(), y.data(), W, H, 0.2, static_cast<std::vector<float>*>(nullptr), threads, &target);
    EXPECT_EQ(c.Loss, a.Loss);
  }
  // Identical images: SSIM 1 through the kept maps as well.
  EXPECT_NEAR(
    TrainingLoss(
      y.data(), y.data(), W, H, 0.2, static_cast<std::vector<float>*>(nullptr), 1, &target)
      .Ssim,
    1.0,
    1e-6);
  const std::vector<float> other = y;
  EXPECT_THROW(
    TrainingLoss(
      x.data(), other.data(), W, H, 0.2, static_cast<std::vector<float>*>(nullptr), 1, &target),
    std::invalid_argument);
  EXPECT_THROW(
    TrainingLoss(
      x.data(), y.data(), W, H - 1, 0.2, static_cast<std::vector<float>*>(nullptr), 1, &target),
    std::invalid_argument);
}

TEST(Loss, SsimMapAveragesToSsimAndCropsKeepTheBits)
{
  const int W = 61, H = 37;
  const auto xd = RandomImage(W, H, 5), yd = RandomImage(W, H, 6);
  const std::vector<float> x(xd.begin(), xd.end()), y(yd.begin(), yd.end());
  std::vector<float> map;
  SsimMap(x.data(), y.data(), W, H, map);
  ASSERT_EQ(map.size(), 3u * W * H);
  // The map's mean, summed per channel in pixel order as Ssim() does, is Ssim() bit for bit.
  const std::size_t P = static_cast<std::size_t>(W) * H;
  double channel[3] = { 0, 0, 0 };
  for (int c = 0; c < 3; ++c)
  {
    for (std::size_t p = 0; p < P; ++p)
    {
      channel[c] += map[c * P + p];
    }
  }
  EXPECT_EQ((channel[0] + channel[1] + channel[2]) / (3.0 * P), Ssim(x.data(), y.data(), W, H));
  // Against the direct 11x11 window of one pixel (a 1x1 crop of the naive SSIM would not do).
  std::vector<double> mapd;
  SsimMap(xd.data(), yd.data(), W, H, mapd);
  double naiveTotal = 0;
  for (std::size_t i = 0; i < mapd.size(); ++i)
  {
    naiveTotal += mapd[i];
  }
  EXPECT_NEAR(naiveTotal / (3.0 * P), NaiveSsim(xd, yd, W, H), 1e-13);

  // Crops: one inside the image (valid pixels 5 px away from its edges) and one sharing the
  // image's top-left corner (valid up to its own border there).
  struct Crop
  {
    int X0, Y0, W, H;
  };
  for (const Crop& c : { Crop{ 13, 9, 30, 21 }, Crop{ 0, 0, 27, 20 }, Crop{ 40, 20, 21, 17 } })
  {
    std::vector<float> cx(3 * static_cast<std::size_t>(c.W) * c.H), cy(cx.size());
    for (int j = 0; j < c.H; ++j)
    {
      for (int i = 0; i < 3 * c.W; ++i)
      {
        cx[3 * j * c.W + i] = x[3 * ((c.Y0 + j) * W + c.X0) + i];
        cy[3 * j * c.W + i] = y[3 * ((c.Y0 + j) * W + c.X0) + i];
      }
    }
    std::vector<float> cropMap;
    SsimMap(cx.data(), cy.data(), c.W, c.H, cropMap, 2);
    const std::size_t cp = static_cast<std::size_t>(c.W) * c.H;
    int compared = 0;
    for (int j = 0; j < c.H; ++j)
    {
      for (int i = 0; i < c.W; ++i)
      {
        const int gx = c.X0 + i, gy = c.Y0 + j;
        const bool validX = (i >= 5 || c.X0 == 0) && (i < c.W - 5 || c.X0 + c.W == W);
        const bool validY = (j >= 5 || c.Y0 == 0) && (j < c.H - 5 || c.Y0 + c.H == H);
        if (!validX || !validY)
        {
          continue;
        }
        for (int ch = 0; ch < 3; ++ch)
        {
          ASSERT_EQ(cropMap[ch * cp + j * c.W + i], map[ch * P + gy * W + gx])
            << "crop at " << c.X0 << "," << c.Y0 << " pixel " << gx << "," << gy;
        }
        ++compared;
      }
    }
    EXPECT_GT(compared, 100);
  }
}

// SPDX-License-Identifier: BSD-3-Clause
#include "ScreenSelection.h"

#include "Footprint.h"
#include "RasterKernel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

namespace vis4gs
{
namespace
{
Camera TestCamera()
{
  Camera c;
  c.Name = "test";
  c.Width = 96;
  c.Height = 64;
  c.Fx = c.Fy = 80;
  const double a = 0.2;
  c.WorldToCamera = {
    std::cos(a), 0, std::sin(a), 0.1, 0, 1, 0, -0.1, -std::sin(a), 0, std::cos(a), 6.0, 0, 0, 0, 1
  };
  return c;
}

GaussianCloud TestCloud(std::size_t n, unsigned seed)
{
  GaussianCloud c;
  c.Resize(n, 0);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (std::size_t i = 0; i < n; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      c.Positions[3 * i + k] = 2.5f * u(rng);
      c.LogScales[3 * i + k] = -3.0f + 0.8f * u(rng);
    }
    for (int k = 0; k < 4; ++k)
    {
      c.Rotations[4 * i + k] = u(rng);
    }
    c.OpacityLogits[i] = 1.0f + 3.0f * u(rng);
  }
  return c;
}

// Independent replay without tile bins: every visible Gaussian whose tile rectangle holds the
// pixel's tile, sorted by (depth, index), blended with the reference rule.
std::vector<float> NaiveMaxWeights(const SelectionView& v,
  const std::vector<std::array<int, 2>>& px)
{
  const auto& p = v.Projection;
  std::vector<float> best(p.Gaussians.size(), 0.0f);
  for (const auto& q : px)
  {
    if (q[0] < 0 || q[1] < 0 || q[0] >= p.Width || q[1] >= p.Height)
    {
      continue;
    }
    const int tx = q[0] / 16, ty = q[1] / 16;
    std::vector<std::uint32_t> list;
    for (std::uint32_t i = 0; i < p.Gaussians.size(); ++i)
    {
      const auto& g = p.Gaussians[i];
      if (g.IsVisible() && tx >= g.TileRect[0] && tx < g.TileRect[2] && ty >= g.TileRect[1] &&
        ty < g.TileRect[3])
      {
        list.push_back(i);
      }
    }
    std::stable_sort(list.begin(),
      list.end(),
      [&p](std::uint32_t a, std::uint32_t b)
      { return p.Gaussians[a].Depth < p.Gaussians[b].Depth; });
    float T = 1.0f;
    for (std::uint32_t i : list)
    {
      const auto& g = p.Gaussians[i];
      const float dx = g.U - static_cast<float>(q[0]), dy = g.V - static_cast<float>(q[1]);
      const float power = -0.5f * (g.ConicA * dx * dx + g.ConicC * dy * dy) - g.ConicB * dx * dy;
      if (power > 0.0f)
      {
        continue;
      }
      const float alpha = std::min(0.99f, g.Opacity * raster::KernelExp(power));
      if (alpha < 1.0f / 255.0f)
      {
        continue;
      }
      const float Tn = T * (1.0f - alpha);
      if (Tn < 0.0001f)
      {
        break;
      }
      best[i] = std::max(best[i], alpha * T);
      T = Tn;
    }
  }
  return best;
}

/// Frame selection by definition: centre in the (clamped) rectangle and largest weight over
/// its pixels >= threshold, from NaiveMaxWeights().
std::vector<std::uint32_t> BruteForceFrame(const SelectionView& v,
  int x0,
  int y0,
  int x1,
  int y1,
  double threshold)
{
  std::vector<std::array<int, 2>> rect;
  const int w1 = v.Projection.Width - 1, h1 = v.Projection.Height - 1;
  const int ax = std::max(0, std::min(x0, x1)), bx = std::min(w1, std::max(x0, x1));
  const int ay = std::max(0, std::min(y0, y1)), by = std::min(h1, std::max(y0, y1));
  for (int y = ay; y <= by; ++y)
  {
    for (int x = ax; x <= bx; ++x)
    {
      rect.push_back({ x, y });
    }
  }
  const auto w = NaiveMaxWeights(v, rect);
  std::vector<std::uint32_t> selected;
  for (std::uint32_t i = 0; i < v.Projection.Gaussians.size(); ++i)
  {
    const auto& g = v.Projection.Gaussians[i];
    if (g.IsVisible() && g.U >= ax - 0.5f && g.U < bx + 0.5f && g.V >= ay - 0.5f &&
      g.V < by + 0.5f && static_cast<double>(w[i]) >= threshold)
    {
      selected.push_back(i);
    }
  }
  return selected;
}
// Needles, disks, huge and tiny scales, means at and behind the near plane, opacity 0 and 1
// (logits -inf and +inf) among ordinary Gaussians.
GaussianCloud ExtremeCloud()
{
  GaussianCloud c = TestCloud(400, 11);
  const float inf = std::numeric_limits<float>::infinity();
  for (std::size_t i = 0; i < c.Count; ++i)
  {
    float* s = &c.LogScales[3 * i];
    switch (i % 8)
    {
      case 0: // needle
        s[0] = 0.5f;
        s[1] = s[2] = -9.0f;
        break;
      case 1: // disk
        s[0] = s[1] = 0.0f;
        s[2] = -12.0f;
        break;
      case 2: // huge
        s[0] = s[1] = s[2] = 2.0f;
        break;
      case 3: // tiny
        s[0] = s[1] = s[2] = -14.0f;
        break;
      case 4: // near the camera plane (camera at world z ~ -6 in front of the scene)
        c.Positions[3 * i + 2] = -5.8f + 0.002f * static_cast<float>(i % 50);
        break;
      case 5:
        c.OpacityLogits[i] = inf;
        break;
      case 6:
        c.OpacityLogits[i] = -inf;
        break;
      default:
        break;
    }
  }
  return c;
}
}

// Ray = the footprints covering the pixel in depth order, from an independent walk without
// tile bins; Single is its largest blended weight, hence a member, and agrees with the
// attribution replay; the blended prefix carries the compositor's weights bit for bit.
TEST(ScreenSelection, RayIsTheFootprintsAndContainsSingle)
{
  std::size_t withOccluded = 0;
  for (int scene = 0; scene < 2; ++scene)
  {
    const GaussianCloud cloud = scene == 0 ? TestCloud(600, 5) : ExtremeCloud();
    const SelectionView v = PrepareSelectionView(cloud, TestCamera(), 1);
    const auto& p = v.Projection;
    RasterSettings rs;
    rs.ComputeColors = false;
    std::size_t nonEmpty = 0;
    for (int y = 0; y < p.Height; y += 3)
    {
      for (int x = 0; x < p.Width; x += 3)
      {
        const auto ray = SelectRay(v, x, y);
        // Independent list: tile rectangle holds the pixel's tile, visible, depth order.
        std::vector<std::uint32_t> list;
        for (std::uint32_t i = 0; i < p.Gaussians.size(); ++i)
        {
          const auto& g = p.Gaussians[i];
          if (g.IsVisible() && x / 16 >= g.TileRect[0] && x / 16 < g.TileRect[2] &&
            y / 16 >= g.TileRect[1] && y / 16 < g.TileRect[3])
          {
            list.push_back(i);
          }
        }
        std::stable_sort(list.begin(),
          list.end(),
          [&p](std::uint32_t a, std::uint32_t b)
          { return p.Gaussians[a].Depth < p.Gaussians[b].Depth; });
        std::vector<std::uint32_t> expected;
        for (std::uint32_t i : list)
        {
          const auto& g = p.Gaussians[i];
          const float dx = g.U - static_cast<float>(x), dy = g.V - static_cast<float>(y);
          const float power =
            -0.5f * (g.ConicA * dx * dx + g.ConicC * dy * dy) - g.ConicB * dx * dy;
          if (power <= 0.0f &&
            std::min(0.99f, g.Opacity * raster::KernelExp(power)) >= 1.0f / 255.0f)
          {
            expected.push_back(i);
          }
        }
        std::vector<std::uint32_t> got;
        for (const auto& c : ray)
        {
          got.push_back(c.Gaussian);
          EXPECT_GE(c.Alpha, 1.0 / 255.0 - 1e-9);
          EXPECT_LE(c.Alpha, 0.99 + 1e-9);
          EXPECT_GE(c.Weight, 0.0);
          EXPECT_TRUE(std::isfinite(c.Weight));
          EXPECT_GT(cloud.OpacityLogits[c.Gaussian], -std::numeric_limits<float>::infinity());
        }
        // Ties in depth may be ordered differently by the two sorts: compare as sets, and
        // the depths must not decrease.
        for (std::size_t k = 1; k < ray.size(); ++k)
        {
          EXPECT_LE(ray[k - 1].Depth, ray[k].Depth);
        }
        auto sg = got, se = expected;
        std::sort(sg.begin(), sg.end());
        std::sort(se.begin(), se.end());
        ASSERT_EQ(sg, se) << "pixel " << x << "," << y << " scene " << scene;

        const auto att = AttributePixels<float>(p, v.Bins, rs, { { x, y } });
        const std::int64_t single = SelectSingle(v, x, y);
        if (att[0].Contributions.empty())
        {
          EXPECT_EQ(single, -1);
          EXPECT_TRUE(std::none_of(
            ray.begin(), ray.end(), [](const RayContribution& c) { return c.Blended; }));
          continue;
        }
        ++nonEmpty;
        EXPECT_EQ(single, att[0].Contributions.front().Gaussian);
        EXPECT_TRUE(std::any_of(ray.begin(),
          ray.end(),
          [single](const RayContribution& c)
          { return static_cast<std::int64_t>(c.Gaussian) == single; }));
        std::size_t blended = 0;
        for (const auto& c : ray)
        {
          if (!c.Blended)
          {
            // Past the stop: T (1 - alpha) fell below 1e-4 at the first of them, alpha <= 0.99.
            EXPECT_LE(c.Weight, c.Transmittance);
            EXPECT_LT(c.Transmittance, 1e-4 / (1.0 - 0.99) * (1.0 + 1e-6));
            withOccluded += 1;
            continue;
          }
          ++blended;
          const auto it = std::find_if(att[0].Contributions.begin(),
            att[0].Contributions.end(),
            [&c](const PixelContribution& a) { return a.Gaussian == c.Gaussian; });
          ASSERT_NE(it, att[0].Contributions.end());
          EXPECT_EQ(it->Weight, c.Weight);
          EXPECT_EQ(it->Transmittance, c.Transmittance);
        }
        EXPECT_EQ(blended, att[0].Contributions.size());
      }
    }
    EXPECT_GT(nonEmpty, 50u) << "scene " << scene;
  }
  EXPECT_GT(withOccluded, 0u) << "no pixel reached the early stop: the test is too easy";
  EXPECT_TRUE(SelectRay(PrepareSelectionView(TestCloud(10, 1), TestCamera(), 1), -1, 0).empty());
}

TEST(ScreenSelection, MaxWeightsAgreeWithAttributionAndNaiveReplay)
{
  const auto cloud = TestCloud(1500, 5);
  const auto view = PrepareSelectionView(cloud, TestCamera(), 2);
  std::vector<std::array<int, 2>> pixels;
  for (int y = 10; y < 50; y += 3)
  {
    for (int x = 5; x < 90; x += 4)
    {
      pixels.push_back({ x, y });
    }
  }
  pixels.push_back({ -1, 3 }); // outside: ignored
  const auto w = MaxWeightsOverPixels(view, pixels, 2);
  const auto naive = NaiveMaxWeights(view, pixels);
  const auto ranked =
    RankContributors(AttributePixels<float>(view.Projection, view.Bins, view.Settings, pixels));
  std::vector<double> fromAttribution(cloud.Count, 0.0);
  for (const auto& c : ranked)
  {
    fromAttribution[c.Gaussian] = c.MaxWeight;
  }
  std::size_t nonzero = 0;
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    ASSERT_EQ(static_cast<double>(w[i]), fromAttribution[i]) << i;
    ASSERT_EQ(w[i], naive[i]) << i;
    nonzero += w[i] > 0 ? 1 : 0;
  }
  EXPECT_GT(nonzero, 100u);
}

TEST(ScreenSelection, SingleBrushFrameAgainstBruteForce)
{
  const auto cloud = TestCloud(1500, 9);
  const Camera cam = TestCamera();
  const auto view = PrepareSelectionView(cloud, cam, 2);
  // Single: the largest naive weight at the pixel.
  int singles = 0;
  for (int y = 4; y < 64; y += 9)
  {
    for (int x = 3; x < 96; x += 11)
    {
      const auto w = NaiveMaxWeights(view, { { x, y } });
      const auto it = std::max_element(w.begin(), w.end());
      const std::int64_t expected = *it > 0 ? it - w.begin() : -1;
      ASSERT_EQ(SelectSingle(view, x, y), expected) << x << "," << y;
      singles += expected >= 0 ? 1 : 0;
    }
  }
  EXPECT_GT(singles, 20);
  EXPECT_EQ(SelectSingle(view, -5, 3), -1);
  EXPECT_EQ(SelectSingle(view, 96, 3), -1);

  // Brush: a stroke across the image.
  const auto pixels = BrushPixels({ { 10.0, 20.0 }, { 60.0, 40.0 } }, 3.0, cam.Width, cam.Height);
  for (double threshold : { 0.01, 0.2 })
  {
    const auto got = SelectBrush(view, pixels, threshold, 2);
    const auto w = NaiveMaxWeights(view, pixels);
    std::vector<std::uint32_t> expected;
    for (std::uint32_t i = 0; i < w.size(); ++i)
    {
      if (w[i] >= threshold)
      {
        expected.push_back(i);
      }
    }
    EXPECT_EQ(got, expected);
    EXPECT_FALSE(got.empty());
  }
  EXPECT_THROW(SelectBrush(view, pixels, 0.0), std::invalid_argument);

  // Frame: corners in any order, clipped to the image.
  FrameOptions fo;
  fo.Threads = 2;
  const auto frame = SelectFrame(view, 70, 50, 20, 8, fo);
  std::vector<std::array<int, 2>> rect;
  for (int y = 8; y <= 50; ++y)
  {
    for (int x = 20; x <= 70; ++x)
    {
      rect.push_back({ x, y });
    }
  }
  const auto w = NaiveMaxWeights(view, rect);
  std::vector<std::uint32_t> expected, occluded;
  for (std::uint32_t i = 0; i < cloud.Count; ++i)
  {
    const auto& g = view.Projection.Gaussians[i];
    const bool inside = g.IsVisible() && g.U >= 19.5f && g.U < 70.5f && g.V >= 7.5f && g.V < 50.5f;
    if (inside)
    {
      occluded.push_back(i);
      if (w[i] >= 0.01f)
      {
        expected.push_back(i);
      }
    }
  }
  EXPECT_EQ(frame, expected);
  fo.IncludeOccluded = true;
  EXPECT_EQ(SelectFrame(view, 20, 8, 70, 50, fo), occluded);
  EXPECT_GT(occluded.size(), expected.size()); // some centres are hidden
  EXPECT_GT(expected.size(), 10u);
  EXPECT_TRUE(SelectFrame(view, 200, 200, 300, 300, fo).empty());
  const auto whole = SelectFrame(view, -100, -100, 1000, 1000, fo);
  EXPECT_GE(whole.size(), occluded.size());
}

TEST(ScreenSelection, FrameFromViewMaxWeightsEqualsReplay)
{
  // Small and large Gaussians, plus needles and disks whose blend boxes are long and thin.
  auto cloud = TestCloud(2500, 11);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (std::size_t i = 0; i < cloud.Count; i += 10)
  {
    cloud.LogScales[3 * i] = -1.2f + 0.3f * u(rng);
    if (i % 20 == 0)
    {
      cloud.LogScales[3 * i + 1] = -7.0f;
      cloud.OpacityLogits[i] = 6.0f; // opacity ~1
    }
  }
  const Camera cam = TestCamera();
  const SelectionView replay = PrepareSelectionView(cloud, cam, 2);
  SelectionView cached = replay;
  ComputeViewMaxWeights(cached);
  ASSERT_EQ(cached.ViewMaxWeights.size(), cloud.Count);

  // 1. The view-wide maxima equal an independent replay of every pixel.
  std::vector<std::array<int, 2>> all;
  for (int y = 0; y < cam.Height; ++y)
  {
    for (int x = 0; x < cam.Width; ++x)
    {
      all.push_back({ x, y });
    }
  }
  const auto naive = NaiveMaxWeights(replay, all);
  std::size_t blended = 0;
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    ASSERT_EQ(cached.ViewMaxWeights[i], naive[i]) << i;
    blended += naive[i] > 0 ? 1 : 0;
  }
  EXPECT_GT(blended, 500u);

  // 2. No Gaussian passes the kernel test (power <= 0, alpha >= 1/255) at a pixel of its tile
  // rectangle outside its BlendBox.
  std::size_t outsideChecks = 0, partial = 0;
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    const auto& g = replay.Projection.Gaussians[i];
    const auto box = BlendBox(replay.Projection, i);
    if (!g.IsVisible())
    {
      EXPECT_GT(box[0], box[2]);
      continue;
    }
    partial += (box[2] - box[0] + 1) * (box[3] - box[1] + 1) < 16 * 16 ? 0 : 1;
    for (const auto& q : all)
    {
      if (q[0] >= box[0] && q[0] <= box[2] && q[1] >= box[1] && q[1] <= box[3])
      {
        continue;
      }
      if (q[0] / 16 < g.TileRect[0] || q[0] / 16 >= g.TileRect[2] || q[1] / 16 < g.TileRect[1] ||
        q[1] / 16 >= g.TileRect[3])
      {
        continue; // outside the tile rectangle: never in the pixel's list
      }
      const float dx = g.U - static_cast<float>(q[0]), dy = g.V - static_cast<float>(q[1]);
      const float power = -0.5f * (g.ConicA * dx * dx + g.ConicC * dy * dy) - g.ConicB * dx * dy;
      const float alpha = std::min(0.99f, g.Opacity * raster::KernelExp(power));
      ASSERT_FALSE(power <= 0.0f && alpha >= 1.0f / 255.0f)
        << "Gaussian " << i << " blends at " << q[0] << "," << q[1] << " outside its box " << box[0]
        << "," << box[1] << "-" << box[2] << "," << box[3] << " tiles " << g.TileRect[0] << ","
        << g.TileRect[1] << "-" << g.TileRect[2] << "," << g.TileRect[3] << " centre " << g.U << ","
        << g.V << " cov " << g.Cov2D[0] << " " << g.Cov2D[1] << " " << g.Cov2D[2] << " opacity "
        << g.Opacity;
      ++outsideChecks;
    }
  }
  EXPECT_GT(outsideChecks, 100000u);
  EXPECT_GT(partial, 10u);

  // 3. Visible-only Frame selections: identical with and without the cached maxima, and equal
  // to the brute-force definition (largest naive weight over the rectangle).
  std::uniform_int_distribution<int> px(-20, 110), py(-20, 80);
  int nonEmpty = 0;
  for (int r = 0; r < 40; ++r)
  {
    const int x0 = px(rng), x1 = px(rng), y0 = py(rng), y1 = py(rng);
    for (double threshold : { 0.01, 0.3 })
    {
      FrameOptions fo;
      fo.Threads = 2;
      fo.WeightThreshold = threshold;
      const auto fast = SelectFrame(cached, x0, y0, x1, y1, fo);
      FrameOptions full = fo;
      full.CullReplay = false;
      ASSERT_EQ(fast, SelectFrame(replay, x0, y0, x1, y1, full))
        << x0 << "," << y0 << " " << x1 << "," << y1 << " threshold " << threshold;
      nonEmpty += fast.empty() ? 0 : 1;
      if (r % 8 == 0)
      {
        ASSERT_EQ(fast, BruteForceFrame(replay, x0, y0, x1, y1, threshold));
      }
    }
  }
  EXPECT_GT(nonEmpty, 30);
}

TEST(ScreenSelection, FrameOnReusedDrawnProjectionEqualsReplay)
{
  // The scene view's frame: projected with colours (SH degree 1) and binned by the renderer's
  // own calls, reused as is; the selection must equal the full replay on the selection's own
  // projection, and the brute-force definition.
  auto cloud = TestCloud(2500, 23);
  cloud.ShDegree = 1;
  cloud.SH.assign(3 * cloud.Count * static_cast<std::size_t>(cloud.ShCoefficientCount()), 0.0f);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (auto& v : cloud.SH)
  {
    v = 0.5f * u(rng);
  }
  for (auto& p : cloud.Positions)
  {
    p *= 0.6f; // denser: several layers per pixel
  }
  for (std::size_t i = 0; i < cloud.Count; i += 10)
  {
    cloud.LogScales[3 * i] = -1.2f + 0.3f * u(rng); // large: crosses many tiles
    if (i % 20 == 0)
    {
      cloud.LogScales[3 * i + 1] = -7.0f; // needles and disks
      cloud.OpacityLogits[i] = 6.0f;
    }
    if (i % 30 == 0)
    {
      cloud.OpacityLogits[i] = -5.6f; // opacity just above 1/255
    }
    if (i % 500 == 0)
    {
      cloud.LogScales[3 * i] = cloud.LogScales[3 * i + 2] = 0.5f; // covers most of the image
      cloud.OpacityLogits[i] = -3.0f;
    }
  }
  const Camera cam = TestCamera();
  const SelectionView replay = PrepareSelectionView(cloud, cam, 2);
  RasterWorkspace<float> frame;
  RasterSettings drawn;
  drawn.Threads = 3;
  drawn.Background = { 0.2, 0.3, 0.4 };
  Rasterize<float>(cloud, cam, drawn, frame);
  ASSERT_EQ(frame.Projection.Gaussians.size(), cloud.Count);
  // What the selection reads is the same with and without colours, bit for bit.
  std::size_t visible = 0;
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    const auto& a = frame.Projection.Gaussians[i];
    const auto& b = replay.Projection.Gaussians[i];
    ASSERT_EQ(a.Status, b.Status) << i;
    ASSERT_TRUE(std::memcmp(&a.U, &b.U, 6 * sizeof(float)) == 0) << i; // U..Opacity
    ASSERT_TRUE(std::memcmp(&a.Depth, &b.Depth, sizeof(float)) == 0) << i;
    ASSERT_TRUE(std::memcmp(a.Cov2D, b.Cov2D, sizeof(a.Cov2D)) == 0) << i;
    ASSERT_TRUE(std::memcmp(a.TileRect, b.TileRect, sizeof(a.TileRect)) == 0) << i;
    visible += a.IsVisible() ? 1 : 0;
  }
  EXPECT_GT(visible, 2000u);
  ASSERT_EQ(frame.Bins.Offsets, replay.Bins.Offsets);
  ASSERT_EQ(frame.Bins.Ids, replay.Bins.Ids);

  // 1. The culled replay's weights over every pixel equal an independent replay.
  {
    std::vector<std::array<int, 2>> all;
    for (int y = 0; y < cam.Height; ++y)
    {
      for (int x = 0; x < cam.Width; ++x)
      {
        all.push_back({ x, y });
      }
    }
    const auto culled = MaxWeightsOverPixels(replay, all, 2);
    const auto naive = NaiveMaxWeights(replay, all);
    ASSERT_EQ(culled.size(), cloud.Count);
    std::size_t blended = 0;
    for (std::size_t i = 0; i < cloud.Count; ++i)
    {
      ASSERT_EQ(culled[i], naive[i]) << i;
      blended += naive[i] > 0 ? 1 : 0;
    }
    EXPECT_GT(blended, 1000u);
  }

  // 2. Frames on the reused projection (culled replay): identical to the straightforward
  // replay on the selection's own projection (every Gaussian of a tile's list on every pixel),
  // to the culled replay there, and to the brute-force definition.
  std::uniform_int_distribution<int> px(-20, 110), py(-20, 80);
  int nonEmpty = 0;
  std::size_t selected = 0;
  for (int r = 0; r < 24; ++r)
  {
    int x0 = px(rng), x1 = px(rng), y0 = py(rng), y1 = py(rng);
    if (r < 4)
    {
      // Single pixels, a single row, and the whole image.
      x1 = x0 + (r == 2 ? 30 : 0);
      y1 = y0;
      if (r == 3)
      {
        x0 = y0 = -3;
        x1 = y1 = 500;
      }
    }
    for (double threshold : { 0.01, r < 4 ? 0.98 : 0.3 })
    {
      FrameOptions fo;
      fo.Threads = 2;
      fo.WeightThreshold = threshold;
      const auto reused = SelectFrame(frame.Projection, frame.Bins, x0, y0, x1, y1, fo);
      FrameOptions full = fo;
      full.CullReplay = false;
      const auto expected = SelectFrame(replay, x0, y0, x1, y1, full);
      ASSERT_EQ(reused, expected) << x0 << "," << y0 << " " << x1 << "," << y1 << " threshold "
                                  << threshold;
      ASSERT_EQ(SelectFrame(replay, x0, y0, x1, y1, fo), expected);
      ASSERT_EQ(SelectFrame(frame.Projection, frame.Bins, x0, y0, x1, y1, full), expected);
      nonEmpty += reused.empty() ? 0 : 1;
      selected += reused.size();
      if (r % 8 == 0)
      {
        ASSERT_EQ(reused, BruteForceFrame(replay, x0, y0, x1, y1, threshold));
      }
    }
    FrameOptions occ;
    occ.IncludeOccluded = true;
    ASSERT_EQ(SelectFrame(frame.Projection, frame.Bins, x0, y0, x1, y1, occ),
      SelectFrame(replay, x0, y0, x1, y1, occ));
  }
  EXPECT_GT(nonEmpty, 15);
  EXPECT_GT(selected, 3000u);

  // 3. Bins of another projection are refused.
  TileBins wrong = frame.Bins;
  wrong.TilesX += 1;
  EXPECT_THROW(SelectFrame(frame.Projection, wrong, 0, 0, 10, 10), std::invalid_argument);
}

TEST(ScreenSelection, BrushAndFrameFromTheFramesRecordEqualReplay)
{
  // The drawn frame's compositing keeps the blends of weight >= the record's threshold; Brush
  // and Frame read them instead of replaying: the same selections, on every instruction set.
  auto cloud = TestCloud(3000, 31);
  for (auto& p : cloud.Positions)
  {
    p *= 0.6f; // several layers per pixel: occlusion decides
  }
  for (std::size_t i = 0; i < cloud.Count; i += 10)
  {
    cloud.LogScales[3 * i] = -1.2f; // large: crosses many tiles
    if (i % 20 == 0)
    {
      cloud.LogScales[3 * i + 1] = -7.0f; // needles and disks
      cloud.OpacityLogits[i] = 6.0f;
    }
  }
  const Camera cam = TestCamera();
  const SelectionView view = PrepareSelectionView(cloud, cam, 2);
  const std::vector<std::vector<std::array<double, 2>>> strokes = {
    { { 40, 30 } }, { { 5, 5 }, { 90, 60 } }, { { 0, 63 }, { 50, 20 }, { 95, 40 } }
  };
  const std::vector<std::array<int, 4>> rects = { { 0, 0, 95, 63 },
    { 30, 20, 60, 45 },
    { 70, 50, 10, 5 },
    { 47, 31, 47, 31 },
    { -10, -10, 200, 15 } };
  for (int isa = 1; isa <= 3; ++isa)
  {
    RasterSettings settings = view.Settings;
    settings.KernelIsa = isa;
    RasterImage<float> plain, recorded;
    CompositeTiles<float>(view.Projection, view.Bins, settings, plain);
    PixelWeightRecord record;
    record.Threshold = 0.01f;
    CompositeTiles<float>(
      view.Projection, view.Bins, settings, recorded, nullptr, nullptr, nullptr, true, &record);
    ASSERT_TRUE(record.Complete);
    ASSERT_GT(record.Entries(), 1000u);
    // Recording changes no output.
    EXPECT_EQ(0,
      std::memcmp(plain.Color.data(), recorded.Color.data(), plain.Color.size() * sizeof(float)));
    EXPECT_EQ(plain.Contributors, recorded.Contributors);
    // Each kept blend is the independent replay's weight at its pixel, and every weight of
    // the replay >= the threshold is kept (a sample of pixels).
    for (int y = 0; y < cam.Height; y += 7)
    {
      for (int x = 0; x < cam.Width; x += 5)
      {
        const auto naive = NaiveMaxWeights(view, { { x, y } });
        const std::size_t tile = static_cast<std::size_t>(y / 16) * record.TilesX + x / 16;
        const std::uint8_t at = static_cast<std::uint8_t>((y % 16) * 16 + x % 16);
        std::vector<std::pair<std::uint32_t, float>> kept, expected;
        for (std::size_t k = 0; k < record.Weights[tile].size(); ++k)
        {
          if (record.Pixels[tile][k] == at)
          {
            kept.emplace_back(record.Weights[tile][k].Gaussian, record.Weights[tile][k].Weight);
          }
        }
        for (std::uint32_t i = 0; i < naive.size(); ++i)
        {
          if (naive[i] >= 0.01f)
          {
            expected.emplace_back(i, naive[i]);
          }
        }
        std::sort(kept.begin(), kept.end());
        ASSERT_EQ(kept, expected) << "isa " << isa << " pixel " << x << "," << y;
      }
    }
    std::size_t selected = 0;
    for (const double threshold : { 0.01, 0.05, 0.3 })
    {
      ASSERT_TRUE(RecordAnswers(record, threshold));
      for (const auto& stroke : strokes)
      {
        const auto pixels = BrushPixels(stroke, 6.0, cam.Width, cam.Height);
        const auto fast = SelectBrush(record, cloud.Count, pixels, threshold);
        EXPECT_EQ(fast, SelectBrush(view, pixels, threshold, 2)) << isa << " " << threshold;
        selected += fast.size();
      }
      FrameOptions fo;
      fo.WeightThreshold = threshold;
      for (const auto& r : rects)
      {
        const auto fast = SelectFrame(view.Projection, record, r[0], r[1], r[2], r[3], fo);
        EXPECT_EQ(fast, SelectFrame(view.Projection, view.Bins, r[0], r[1], r[2], r[3], fo))
          << isa << " " << threshold << " " << r[0] << "," << r[1];
        selected += fast.size();
      }
    }
    EXPECT_GT(selected, 1000u);
    // A selection below the record's threshold is not answered from it.
    EXPECT_FALSE(RecordAnswers(record, 0.005));
    EXPECT_THROW(SelectBrush(record, cloud.Count, { { 1, 1 } }, 0.005), std::invalid_argument);
    // Over its budget the record is dropped, not kept partial.
    PixelWeightRecord small;
    small.MaximumEntries = 100;
    CompositeTiles<float>(
      view.Projection, view.Bins, settings, recorded, nullptr, nullptr, nullptr, true, &small);
    EXPECT_FALSE(small.Complete);
    EXPECT_EQ(small.Entries(), 0u);
    EXPECT_FALSE(RecordAnswers(small, 0.5));
  }
}

TEST(ScreenSelection, BrushPixels)
{
  auto disk = BrushPixels({ { 10.0, 10.0 } }, 2.0, 100, 100);
  EXPECT_EQ(disk.size(), 13u); // |dx|^2 + |dy|^2 <= 4
  auto clipped = BrushPixels({ { 0.0, 0.0 } }, 2.0, 100, 100);
  EXPECT_EQ(clipped.size(), 6u);
  auto line = BrushPixels({ { 10.0, 10.0 }, { 20.0, 10.0 } }, 0.0, 100, 100);
  EXPECT_EQ(line.size(), 11u);
  EXPECT_TRUE(BrushPixels({}, 3.0, 100, 100).empty());
  EXPECT_THROW(BrushPixels({ { std::nan(""), 1.0 } }, 3.0, 100, 100), std::invalid_argument);
}

TEST(ScreenSelection, PixelRayAndFrustum)
{
  const Camera cam = TestCamera();
  const auto& m = cam.WorldToCamera;
  auto project = [&m, &cam](const std::array<double, 3>& p)
  {
    double t[3];
    for (int r = 0; r < 3; ++r)
    {
      t[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
    }
    return std::array<double, 3>{ cam.Fx * t[0] / t[2] + (cam.Width - 1) / 2.0,
      cam.Fy * t[1] / t[2] + (cam.Height - 1) / 2.0,
      t[2] };
  };
  const auto ray = PixelRay(cam, 17.25, 40.5, 2.0);
  EXPECT_EQ(ray.Sigmas, 2.0);
  for (double t : { 1.0, 7.0 })
  {
    const std::array<double, 3> p{ ray.Origin[0] + t * ray.Direction[0],
      ray.Origin[1] + t * ray.Direction[1],
      ray.Origin[2] + t * ray.Direction[2] };
    const auto uv = project(p);
    EXPECT_NEAR(uv[0], 17.25, 1e-9);
    EXPECT_NEAR(uv[1], 40.5, 1e-9);
    EXPECT_GT(uv[2], 0);
  }
  const auto f = CameraFrustum(cam, 2.0);
  const auto c = cam.Center();
  for (int k = 0; k < 3; ++k)
  {
    EXPECT_NEAR(f[0][k], c[k], 1e-12);
  }
  const double corners[4][2] = { { -0.5, -0.5 }, { 95.5, -0.5 }, { 95.5, 63.5 }, { -0.5, 63.5 } };
  for (int k = 0; k < 4; ++k)
  {
    const auto uv = project(f[k + 1]);
    EXPECT_NEAR(uv[0], corners[k][0], 1e-9);
    EXPECT_NEAR(uv[1], corners[k][1], 1e-9);
    EXPECT_NEAR(uv[2], 2.0, 1e-12);
  }
}

TEST(ScreenSelection, VisibleCountsPerView)
{
  const auto cloud = TestCloud(800, 17);
  std::vector<Camera> cams;
  for (int v = 0; v < 4; ++v)
  {
    Camera c = TestCamera();
    const double a = -0.6 + 0.4 * v;
    c.WorldToCamera = { std::cos(a),
      0,
      std::sin(a),
      1.5 * v - 2.0,
      0,
      1,
      0,
      0,
      -std::sin(a),
      0,
      std::cos(a),
      5.0,
      0,
      0,
      0,
      1 };
    cams.push_back(c);
  }
  std::vector<std::uint32_t> selected;
  for (std::uint32_t i = 0; i < cloud.Count; i += 3)
  {
    selected.push_back(i);
  }
  const auto counts = CountVisibleInViews(cloud, selected, cams, 2);
  ASSERT_EQ(counts.size(), cams.size());
  bool differ = false;
  for (std::size_t v = 0; v < cams.size(); ++v)
  {
    // Brute force on the full cloud.
    RasterSettings s;
    s.ComputeColors = false;
    FootprintOptions fo;
    fo.BruteForce = true;
    const auto fp = ComputeFootprints<float>(ProjectGaussians<float>(cloud, cams[v], s), fo);
    std::uint32_t expected = 0;
    for (std::uint32_t i : selected)
    {
      expected += fp.PixelCount[i] > 0 ? 1 : 0;
    }
    EXPECT_EQ(counts[v], expected) << v;
    differ = differ || counts[v] != counts[0];
  }
  EXPECT_TRUE(differ);
  EXPECT_EQ(CountVisibleInViews(cloud, {}, cams), std::vector<std::uint32_t>(4, 0));
  EXPECT_THROW(CountVisibleInViews(cloud, { 5000 }, cams), std::invalid_argument);
}

// The automatic frustum depth: 8 cameras on a ring of radius 10 around a cluster at (5, 0, 0)
// give a tenth of the ring's bounding-box diagonal (20 sqrt(2)), with or without the scene;
// the same capture in millimetres gives 1000 times that. Cameras close together (a forward
// line 0.2 long, 10 from the cluster) get a tenth of the way to the scene (1), not of their
// spread, and 1 % of the means thrown 1e6 away move nothing; a single camera without means
// gets 1.
TEST(ScreenSelection, AutoFrustumDepthFollowsTheScene)
{
  const auto ring = [](double unit)
  {
    std::vector<Camera> cams;
    for (int k = 0; k < 8; ++k)
    {
      Camera c = TestCamera();
      const double a = 2 * M_PI * k / 8;
      // Centre (5 + 10 cos a, 0, 10 sin a) in the given unit: t = -R C with R = identity.
      c.WorldToCamera = { 1,
        0,
        0,
        -(5 + 10 * std::cos(a)) * unit,
        0,
        1,
        0,
        0,
        0,
        0,
        1,
        -10 * std::sin(a) * unit,
        0,
        0,
        0,
        1 };
      cams.push_back(c);
    }
    return cams;
  };
  std::vector<float> means;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-0.5f, 0.5f);
  for (int i = 0; i < 10000; ++i)
  {
    const bool floater = i % 100 == 0;
    means.insert(means.end(), { floater ? 1e6f : 5 + u(rng), u(rng), u(rng) });
  }
  const double ringDepth = 0.1 * 20 * std::sqrt(2.0);
  EXPECT_NEAR(AutoFrustumDepth(ring(1), means.data(), means.size() / 3), ringDepth, 1e-9);
  EXPECT_NEAR(AutoFrustumDepth(ring(1), nullptr, 0), ringDepth, 1e-9);
  std::vector<float> mm(means);
  for (float& x : mm)
  {
    x *= 1000;
  }
  EXPECT_NEAR(AutoFrustumDepth(ring(1000), mm.data(), mm.size() / 3), 1000 * ringDepth, 1e-6);
  std::vector<Camera> line;
  for (int k = 0; k < 3; ++k)
  {
    Camera c = TestCamera();
    c.WorldToCamera = { 1, 0, 0, -(4.9 + 0.1 * k), 0, 1, 0, 0, 0, 0, 1, 10, 0, 0, 0, 1 };
    line.push_back(c);
  }
  EXPECT_NEAR(AutoFrustumDepth(line, means.data(), means.size() / 3), 1.0, 0.01);
  EXPECT_NEAR(AutoFrustumDepth(line, nullptr, 0), 0.1 * 0.2, 1e-9);
  EXPECT_EQ(AutoFrustumDepth({ TestCamera() }, nullptr, 0), 1.0);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> bad = { nan, 0, 0 };
  EXPECT_NEAR(AutoFrustumDepth(line, bad.data(), 1), 0.1 * 0.2, 1e-9);
}

} // namespace vis4gs

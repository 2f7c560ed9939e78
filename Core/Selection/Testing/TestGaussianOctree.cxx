// SPDX-License-Identifier: BSD-3-Clause
#include "GaussianOctree.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace vis4gs
{
namespace
{
GaussianCloud Cloud(const std::vector<std::array<float, 3>>& pos,
  const std::vector<std::array<float, 3>>& logScales,
  const std::vector<std::array<float, 4>>& rot = {})
{
  GaussianCloud c;
  c.Resize(pos.size(), 0);
  for (std::size_t i = 0; i < pos.size(); ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      c.Positions[3 * i + k] = pos[i][k];
      c.LogScales[3 * i + k] = logScales[i][k];
    }
    const std::array<float, 4> q = rot.empty() ? std::array<float, 4>{ 1, 0, 0, 0 } : rot[i];
    for (int k = 0; k < 4; ++k)
    {
      c.Rotations[4 * i + k] = q[k];
    }
  }
  return c;
}

RayQuery Ray(std::array<double, 3> o, std::array<double, 3> d, double k = 3)
{
  RayQuery r;
  r.Origin = o;
  r.Direction = d;
  r.Sigmas = k;
  return r;
}
}

TEST(GaussianOctree, HandDerivedDistances)
{
  const float l2 = std::log(2.0f), lh = std::log(0.5f);
  auto cloud = Cloud(
    { { 0, 0, 10 }, { 20, 0, 10 }, { 0, 0, -10 } }, { { 0, 0, 0 }, { l2, lh, 0 }, { 0, 0, 0 } });
  // Straight through the isotropic unit Gaussian.
  EXPECT_NEAR(RayMahalanobisDistance(cloud, 0, Ray({ 0, 0, 0 }, { 0, 0, 1 })), 0.0, 1e-12);
  EXPECT_NEAR(RayMahalanobisDistance(cloud, 0, Ray({ 2, 0, 0 }, { 0, 0, 3 })), 2.0, 1e-12);
  // Anisotropic: sigma_x = 2, sigma_y = 0.5.
  EXPECT_NEAR(RayMahalanobisDistance(cloud, 1, Ray({ 25, 0, 0 }, { 0, 0, 1 })), 2.5, 1e-6);
  EXPECT_NEAR(RayMahalanobisDistance(cloud, 1, Ray({ 20, 1.6, 0 }, { 0, 0, 1 })), 3.2, 1e-6);
  // Half-line: the Gaussian behind the origin is 10 sigma from the start point.
  EXPECT_NEAR(RayMahalanobisDistance(cloud, 2, Ray({ 0, 0, 0 }, { 0, 0, 1 })), 10.0, 1e-12);
  RayQuery far = Ray({ 0, 0, 0 }, { 0, 0, 1 });
  far.TMin = 12; // starts beyond Gaussian 0: distance 2
  EXPECT_NEAR(RayMahalanobisDistance(cloud, 0, far), 2.0, 1e-12);

  GaussianOctree tree;
  tree.Build(cloud);
  auto hits = tree.IntersectRay(Ray({ 0, 0, 0 }, { 0, 0, 1 }));
  ASSERT_EQ(hits.size(), 1u);
  EXPECT_EQ(hits[0].Gaussian, 0u);
  EXPECT_NEAR(hits[0].Depth, 10.0, 1e-12);
  hits = tree.IntersectRay(Ray({ 25, 0, 0 }, { 0, 0, 1 }));
  ASSERT_EQ(hits.size(), 1u);
  EXPECT_EQ(hits[0].Gaussian, 1u);
  EXPECT_TRUE(tree.IntersectRay(Ray({ 20, 1.6, 0 }, { 0, 0, 1 })).empty());
  EXPECT_EQ(tree.IntersectRay(Ray({ 20, 1.6, 0 }, { 0, 0, 1 }, 2.0)).size(), 0u);
  // Backwards along -z from the origin meets only Gaussian 2.
  hits = tree.IntersectRay(Ray({ 0, 0, 0 }, { 0, 0, -1 }));
  ASSERT_EQ(hits.size(), 1u);
  EXPECT_EQ(hits[0].Gaussian, 2u);
  EXPECT_THROW(tree.IntersectRay(Ray({ 0, 0, 0 }, { 0, 0, 1 }, 4.0)), std::invalid_argument);
  EXPECT_THROW(tree.IntersectRay(Ray({ 0, 0, 0 }, { 0, 0, 0 })), std::invalid_argument);
  GaussianOctree empty;
  EXPECT_THROW(empty.IntersectRay(Ray({ 0, 0, 0 }, { 0, 0, 1 })), std::invalid_argument);
}

TEST(GaussianOctree, MatchesBruteForceOnRandomScenes)
{
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<std::array<float, 3>> pos, ls;
  std::vector<std::array<float, 4>> rot;
  for (int i = 0; i < 20000; ++i)
  {
    pos.push_back({ 10 * u(rng), 10 * u(rng), 10 * u(rng) });
    ls.push_back({ -2.5f + 1.5f * u(rng), -2.5f + 1.5f * u(rng), -2.5f + 1.5f * u(rng) });
    rot.push_back({ u(rng), u(rng), u(rng), u(rng) });
  }
  // A few big ones that stay near the root.
  for (int i = 0; i < 20; ++i)
  {
    ls[i] = { 1.5f, 0.5f, -1.0f };
  }
  auto cloud = Cloud(pos, ls, rot);
  GaussianOctree tree;
  GaussianOctree::Options o;
  o.BoundSigmas = 3.5;
  tree.Build(cloud, o);
  EXPECT_GT(tree.GetNodeCount(), 100u);
  std::size_t total = 0, boxTests = 0;
  for (int r = 0; r < 30; ++r)
  {
    RayQuery ray = Ray(
      { 15 * u(rng), 15 * u(rng), -20.0 }, { 0.3 * u(rng), 0.3 * u(rng), 1.0 }, r % 2 ? 3.0 : 3.5);
    ray.TMin = r % 3 == 0 ? 12.0 : 0.0;
    const auto a = tree.IntersectRay(ray);
    boxTests += tree.GetLastBoxTests();
    const auto b = IntersectRayBruteForce(cloud, ray);
    ASSERT_EQ(a.size(), b.size()) << "ray " << r;
    for (std::size_t k = 0; k < a.size(); ++k)
    {
      ASSERT_EQ(a[k].Gaussian, b[k].Gaussian) << "ray " << r << " hit " << k;
      ASSERT_NEAR(a[k].Distance, b[k].Distance, 1e-9 * (1 + b[k].Distance));
      ASSERT_NEAR(a[k].Depth, b[k].Depth, 1e-9 * (1 + std::abs(b[k].Depth)));
      if (k > 0)
      {
        ASSERT_LE(a[k - 1].Depth, a[k].Depth);
      }
    }
    total += a.size();
  }
  EXPECT_GT(total, 30u); // the rays do hit things
  // The tree prunes: far fewer box tests than a full scan.
  EXPECT_LT(boxTests, 30u * 20000u / 4u);
}

TEST(GaussianOctree, StiffGaussians)
{
  const float nan = std::numeric_limits<float>::quiet_NaN();
  auto cloud =
    Cloud({ { 0, 0, 0 }, { 0, 0, 6 }, { 6, 0, 5 }, { 0, 4, 5 }, { 0, -4, 5 }, { 8, 8, 8 } },
      { { 0, -200, -200 },
        { 500, 500, 500 },
        { 0, 0, 0 },
        { 0, 0, 0 },
        { -1000, -1000, -1000 },
        { 0, 0, 0 } },
      { { 1, 0, 0, 0 },
        { 1, 0, 0, 0 },
        { 0, 0, 0, 0 },
        { nan, 0, 0, 0 },
        { 1, 0, 0, 0 },
        { 1, 0, 0, 0 } });
  GaussianOctree tree;
  tree.Build(cloud);
  // 0: a needle along x (sigma_y = sigma_z = e^-200); a ray along y at z offset 1e-90 from it
  // is 1e-90 e^200 = 7.2e-4 sigma away. 1: enormous, hit by every ray. 2: zero quaternion,
  // the identity rotation as the renderer draws it (Documentation/special-values.md): a unit
  // sphere. 3: NaN: never hit. 4: scales e^-1000 (below the clamp): a point, missed at 0.001
  // offset.
  RayQuery ray = Ray({ 0, -10, 1e-90 }, { 0, 1, 0 });
  auto hits = tree.IntersectRay(ray);
  ASSERT_EQ(hits.size(), 2u);
  // Both centres are at depth 10 along +y: the tie goes to the lower index.
  EXPECT_EQ(hits[0].Gaussian, 0u);
  EXPECT_EQ(hits[1].Gaussian, 1u);
  EXPECT_NEAR(hits[0].Distance, 1e-90 * std::exp(200.0), 1e-9);
  EXPECT_EQ(hits[0].Depth, 10.0);
  // The naive form c + 2tb + t^2 a cancels catastrophically here (terms of 1e176), so only
  // the set and order are compared with it.
  const auto bf = IntersectRayBruteForce(cloud, ray);
  ASSERT_EQ(bf.size(), 2u);
  EXPECT_EQ(bf[0].Gaussian, 0u);
  EXPECT_EQ(bf[1].Gaussian, 1u);
  // Through the zero-rotation Gaussian's centre: it (depth 5), then the huge one (depth 6),
  // as the brute force finds them.
  hits = tree.IntersectRay(Ray({ 6, 0, 0 }, { 0, 0, 1 }));
  ASSERT_EQ(hits.size(), 2u);
  EXPECT_EQ(hits[0].Gaussian, 2u);
  EXPECT_EQ(hits[0].Distance, 0.0);
  EXPECT_EQ(hits[1].Gaussian, 1u);
  const auto bfZero = IntersectRayBruteForce(cloud, Ray({ 6, 0, 0 }, { 0, 0, 1 }));
  ASSERT_EQ(bfZero.size(), 2u);
  EXPECT_EQ(bfZero[0].Gaussian, 2u);
  // Through the NaN Gaussian's centre: only the huge one.
  hits = tree.IntersectRay(Ray({ 0, 4, 0 }, { 0, 0, 1 }));
  ASSERT_EQ(hits.size(), 1u);
  // Exactly through the point-like Gaussian 4's centre: distance 0 (hit); 1e-3 beside: miss.
  hits = tree.IntersectRay(Ray({ 0, -4, 0 }, { 0, 0, 1 }));
  EXPECT_EQ(hits.size(), 2u);
  hits = tree.IntersectRay(Ray({ 0.001, -4, 0 }, { 0, 0, 1 }));
  EXPECT_EQ(hits.size(), 1u);
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    EXPECT_FALSE(std::isnan(RayMahalanobisDistance(cloud, i, ray))) << i;
  }
}

} // namespace vis4gs

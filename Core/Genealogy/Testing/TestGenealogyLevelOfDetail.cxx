// SPDX-License-Identifier: BSD-3-Clause
// Level of detail: the indexed query against the brute-force filter of the definition, over
// thresholds (including exact P values on quantisation boundaries), selections and viewports.
#include "GenealogyLevelOfDetail.h"
#include "SyntheticEventLog.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace
{
using vis4gs::Genealogy;
using vis4gs::GenealogyLevelOfDetail;
using vis4gs::GenealogyViewport;

std::vector<std::int64_t> Sorted(std::vector<std::int64_t> v)
{
  std::sort(v.begin(), v.end());
  return v;
}

Genealogy RandomGenealogy(std::uint64_t seed)
{
  vis4gs::SyntheticLogParameters prm;
  prm.InitialGaussians = 60;
  prm.FinalGaussians = 4000;
  prm.TotalGaussians = 9000;
  prm.Seed = seed;
  const auto log = vis4gs::GenerateSyntheticEventLog(prm);
  return Genealogy::Build(log.InitialGaussians, log.Events, log.LastIteration);
}
} // namespace

TEST(GenealogyLevelOfDetail, HandChecked)
{
  // One root (0) with children 1, 2, 3 cloned at 100, 200, 300; last iteration 1000.
  vis4gs::EventTable t;
  for (int k = 1; k <= 3; ++k)
  {
    t.Iteration.push_back(100 * k);
    t.Kind.push_back(1);
    t.Parent.push_back(0);
    t.Child.push_back(k);
  }
  const Genealogy g = Genealogy::Build(1, t, 1000);
  // P: root 1; child k: 0.6 * (1000 - 100k) / 1000 = 0.54, 0.48, 0.42.
  const GenealogyLevelOfDetail lod(g);
  EXPECT_EQ(Sorted(lod.Query(1.0, {})), (std::vector<std::int64_t>{ 0 }));
  EXPECT_EQ(Sorted(lod.Query(0.48, {})), (std::vector<std::int64_t>{ 0, 1, 2 }));
  EXPECT_EQ(Sorted(lod.Query(0.0, {})), (std::vector<std::int64_t>{ 0, 1, 2, 3 }));
  EXPECT_EQ(Sorted(lod.Query(1.0, { 3 })), (std::vector<std::int64_t>{ 0, 3 }));
  EXPECT_TRUE(lod.Query(std::nan(""), {}).empty());
  // Viewport: rows 2..3 (nodes 2, 3); iterations 250..260 (node 2 born 200 alive: shown;
  // node 3 born 300: culled).
  GenealogyViewport v;
  v.MinRow = 2;
  v.MaxRow = 3;
  v.MinIteration = 250;
  v.MaxIteration = 260;
  EXPECT_EQ(Sorted(lod.Query(0.0, {}, v)), (std::vector<std::int64_t>{ 2 }));
  // tau from the zoom: z = 2 shows everything.
  EXPECT_EQ(lod.Query(vis4gs::ZoomThreshold(2.0), {}).size(), 4u);
}

TEST(GenealogyLevelOfDetail, AgainstBruteForce)
{
  const Genealogy g = RandomGenealogy(11);
  const std::int64_t n = g.GetNumberOfNodes();
  std::mt19937_64 rng(5);
  // Thresholds: zoom levels, exact P values (boundary quanta), extremes.
  std::vector<double> taus = { -1.0, 0.0, 1.0, 1.5, std::nan("") };
  for (double z = 0.1; z <= 2.0; z += 0.13)
  {
    taus.push_back(vis4gs::ZoomThreshold(z));
  }
  for (int k = 0; k < 12; ++k)
  {
    const double p = g.GetPerceptionValues()[rng() % n];
    taus.push_back(p);
    taus.push_back(std::nextafter(p, 2.0));
    taus.push_back(std::nextafter(p, -1.0));
  }
  const vis4gs::LevelOfDetailGrid grids[3] = {
    { 4096, 1000 }, { 7, 300 }, { 1, 1 }
  } /* 1x1 is widened */;
  std::vector<std::int64_t> out;
  for (const auto& grid : grids)
  {
    const GenealogyLevelOfDetail lod(g, grid);
    EXPECT_GT(lod.GetNumberOfCells(), 0);
    EXPECT_LE(lod.GetNumberOfCells(), 4 * n + 1024);
    for (std::size_t ti = 0; ti < taus.size(); ++ti)
    {
      const double tau = taus[ti];
      std::vector<std::int64_t> sel;
      for (std::size_t k = 0; k < ti % 4; ++k)
      {
        sel.push_back(static_cast<std::int64_t>(rng() % n));
      }
      GenealogyViewport v;
      if (ti % 3 != 0)
      {
        v.MinRow = static_cast<std::int64_t>(rng() % n) - 100;
        v.MaxRow = v.MinRow + static_cast<std::int64_t>(rng() % (n / 2));
        v.MinIteration = static_cast<std::int32_t>(rng() % 16000);
        v.MaxIteration = v.MinIteration + static_cast<std::int32_t>(rng() % 20000);
      }
      lod.Query(tau, sel, v, out);
      const std::vector<std::int64_t> brute = lod.QueryBruteForce(tau, sel, v);
      const std::vector<std::int64_t> fast = Sorted(out);
      EXPECT_EQ(fast.size(), out.size()) << "duplicates";
      EXPECT_TRUE(std::adjacent_find(fast.begin(), fast.end()) == fast.end());
      EXPECT_EQ(fast, brute) << "tau " << tau << " grid " << grid.RowsPerCell;
    }
  }
  // Empty and inverted viewports.
  const GenealogyLevelOfDetail lod(g);
  GenealogyViewport inverted;
  inverted.MinRow = 10;
  inverted.MaxRow = 5;
  EXPECT_TRUE(lod.Query(0.0, { 1 }, inverted).empty());
  GenealogyViewport outside;
  outside.MinRow = n + 10;
  EXPECT_TRUE(lod.Query(0.0, { 1 }, outside).empty());
  EXPECT_THROW(lod.Query(0.0, { n }), std::runtime_error);
}

TEST(GenealogyLevelOfDetail, QueryTouchesOnlyVisibleWork)
{
  const Genealogy g = RandomGenealogy(3);
  const GenealogyLevelOfDetail lod(g, { 64, 500 });
  // Coarsest zoom: only nodes with P >= 1 are touched (plus at most a boundary quantum).
  const std::vector<std::int64_t> top = lod.Query(1.0, {});
  EXPECT_LE(lod.GetLastQueryWork(), static_cast<std::int64_t>(top.size()) + 64);
  // A viewport of 100 rows touches at most the cells of those rows.
  GenealogyViewport v;
  v.MinRow = 1000;
  v.MaxRow = 1099;
  lod.Query(0.0, {}, v);
  EXPECT_LE(lod.GetLastQueryWork(), 3 * 64);
}

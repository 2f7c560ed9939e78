// SPDX-License-Identifier: BSD-3-Clause
// Genealogy: hand-built logs with hand-computed D, T, P, rows and bands; coarsening to
// clone-split; lineage queries against brute-force walks; root-cause trace; deep chains and
// huge families.
#include "Genealogy.h"
#include "SyntheticEventLog.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace
{
using vis4gs::BirthKind;
using vis4gs::EventTable;
using vis4gs::Genealogy;
using vis4gs::GenealogyOptions;

void Add(EventTable& t, std::int32_t it, int kind, std::int64_t parent, std::int64_t child)
{
  t.Iteration.push_back(it);
  t.Kind.push_back(static_cast<std::uint8_t>(kind));
  t.Parent.push_back(parent);
  t.Child.push_back(child);
}

/// The hand-computed log of the file comment of TestGenealogy.HandBuiltLog.
EventTable HandLog()
{
  EventTable t;
  Add(t, 100, 1, 0, 2); // clone 0 -> 2
  Add(t, 200, 2, 0, 3); // split 0 -> 3, 4 (0 ends at 200)
  Add(t, 200, 2, 0, 4);
  Add(t, 300, 1, 3, 5);  // clone 3 -> 5
  Add(t, 400, 3, 4, -1); // prune 4
  Add(t, 500, 3, 1, -1); // prune 1
  Add(t, 600, 2, 5, 6);  // split 5 -> 6, 7
  Add(t, 600, 2, 5, 7);
  return t;
}

std::vector<std::int64_t> V(std::initializer_list<std::int64_t> l)
{
  return std::vector<std::int64_t>(l);
}

} // namespace

// Initial ids 0, 1; last iteration 1000. Hand computation:
// node = id here. Deaths: 0 split@200, 1 pruned@500, 4 pruned@400, 5 split@600; 2,3,6,7 alive.
// T: 0:200 1:500 2:900 3:800 4:200 5:300 6:400 7:400.  D: 0:6 3:3 5:2 others 0.
// Family 0 = {0,2,3,4,5,6,7}: maxD 6, maxT 900. Family 1 = {1}: maxD 0 (term 0), maxT 500.
// P = 0.4 D/maxD + 0.6 T/maxT. Rows (pre-order, children in creation order):
// 0:0 2:1 3:2 5:3 6:4 7:5 4:6 | 1:7.
TEST(Genealogy, HandBuiltLog)
{
  const Genealogy g = Genealogy::Build(2, HandLog(), 1000);
  ASSERT_EQ(g.GetNumberOfNodes(), 8);
  ASSERT_EQ(g.GetNumberOfFamilies(), 2);
  EXPECT_TRUE(g.GetWarnings().empty());
  for (std::int64_t i = 0; i < 8; ++i)
  {
    EXPECT_EQ(g.GetGaussianIds()[i], i);
    EXPECT_EQ(g.FindNode(i), i);
  }
  EXPECT_EQ(g.FindNode(8), -1);
  EXPECT_EQ(g.FindNode(-5), -1);

  const std::vector<std::int32_t> birth = { 0, 0, 100, 200, 200, 300, 600, 600 };
  const std::vector<std::int32_t> death = { 200, 500, -1, -1, 400, 600, -1, -1 };
  const std::vector<std::uint8_t> pruned = { 0, 1, 0, 0, 1, 0, 0, 0 };
  const std::vector<BirthKind> kind = { BirthKind::Root,
    BirthKind::Root,
    BirthKind::Clone,
    BirthKind::Split,
    BirthKind::Split,
    BirthKind::Clone,
    BirthKind::Split,
    BirthKind::Split };
  const std::vector<std::int64_t> parent = { -1, -1, 0, 0, 0, 3, 5, 5 };
  const std::vector<std::int64_t> family = { 0, 1, 0, 0, 0, 0, 0, 0 };
  const std::vector<std::int64_t> d = { 6, 0, 0, 3, 0, 2, 0, 0 };
  const std::vector<std::int32_t> t = { 200, 500, 900, 800, 200, 300, 400, 400 };
  const std::vector<std::int64_t> row = { 0, 7, 1, 2, 6, 3, 4, 5 };
  EXPECT_EQ(g.GetBirthIterations(), birth);
  EXPECT_EQ(g.GetDeathIterations(), death);
  EXPECT_EQ(g.GetPruned(), pruned);
  EXPECT_EQ(g.GetBirthKinds(), kind);
  EXPECT_EQ(g.GetParents(), parent);
  EXPECT_EQ(g.GetFamilyIds(), family);
  EXPECT_EQ(g.GetDescendantCounts(), d);
  EXPECT_EQ(g.GetLifespans(), t);
  EXPECT_EQ(g.GetRows(), row);
  for (std::int64_t i = 0; i < 8; ++i)
  {
    EXPECT_EQ(g.GetNodesByRow()[row[i]], i);
  }
  const double p[8] = { 0.4 + 0.6 * 200.0 / 900.0,
    0.6,
    0.6,
    0.4 * 3.0 / 6.0 + 0.6 * 800.0 / 900.0,
    0.6 * 200.0 / 900.0,
    0.4 * 2.0 / 6.0 + 0.6 * 300.0 / 900.0,
    0.6 * 400.0 / 900.0,
    0.6 * 400.0 / 900.0 };
  for (int i = 0; i < 8; ++i)
  {
    EXPECT_NEAR(g.GetPerceptionValues()[i], p[i], 1e-15) << "node " << i;
  }
  // Children in creation order.
  EXPECT_EQ(g.GetNumberOfChildren(0), 3);
  EXPECT_EQ(g.GetChildren()[g.GetChildOffsets()[0]], 2);
  EXPECT_EQ(g.GetChildren()[g.GetChildOffsets()[0] + 1], 3);
  EXPECT_EQ(g.GetChildren()[g.GetChildOffsets()[0] + 2], 4);
  EXPECT_EQ(g.GetNumberOfChildren(1), 0);
  EXPECT_EQ(g.GetEndIteration(2), 1000);
  EXPECT_EQ(g.GetEndIteration(4), 400);

  const auto& bands = g.GetFamilyBands();
  EXPECT_EQ(bands[0].RootNode, 0);
  EXPECT_EQ(bands[0].MinIteration, 0);
  EXPECT_EQ(bands[0].MaxIteration, 1000);
  EXPECT_EQ(bands[0].MinRow, 0);
  EXPECT_EQ(bands[0].MaxRow, 6);
  EXPECT_EQ(bands[0].NodeCount, 7);
  EXPECT_EQ(bands[0].MaxDescendants, 6);
  EXPECT_EQ(bands[0].MaxLifespan, 900);
  EXPECT_EQ(bands[1].RootGaussianId, 1);
  EXPECT_EQ(bands[1].MinIteration, 0);
  EXPECT_EQ(bands[1].MaxIteration, 500);
  EXPECT_EQ(bands[1].MinRow, 7);
  EXPECT_EQ(bands[1].MaxRow, 7);
  EXPECT_EQ(bands[1].MaxDescendants, 0);
  EXPECT_EQ(bands[1].MaxLifespan, 500);
}

TEST(Genealogy, AlphaAndInitialIds)
{
  GenealogyOptions o;
  o.Alpha = 1.0;
  // Same log with arbitrary initial ids: 1 -> 0 in the log, so give ids {0, 1} in another order.
  const Genealogy g = Genealogy::Build(std::vector<std::int64_t>{ 1, 0 }, HandLog(), 1000, o);
  EXPECT_EQ(g.FindNode(1), 0);
  EXPECT_EQ(g.FindNode(0), 1);
  // Family order follows the initial ids: GaussianId 1 first (rows 0), GaussianId 0 after.
  EXPECT_EQ(g.GetRows()[g.FindNode(1)], 0);
  EXPECT_EQ(g.GetRows()[g.FindNode(0)], 1);
  EXPECT_DOUBLE_EQ(g.GetPerceptionValues()[g.FindNode(0)], 1.0);
  EXPECT_DOUBLE_EQ(g.GetPerceptionValues()[g.FindNode(5)], 2.0 / 6.0);
  EXPECT_DOUBLE_EQ(g.GetPerceptionValues()[g.FindNode(1)], 0.0);
}

TEST(Genealogy, ZoomThreshold)
{
  EXPECT_DOUBLE_EQ(vis4gs::ZoomThreshold(0.1), 1.0);
  EXPECT_DOUBLE_EQ(vis4gs::ZoomThreshold(2.0), 0.0);
  EXPECT_DOUBLE_EQ(vis4gs::ZoomThreshold(-3.0), 1.0);
  EXPECT_DOUBLE_EQ(vis4gs::ZoomThreshold(50.0), 0.0);
  EXPECT_DOUBLE_EQ(vis4gs::ZoomThreshold(std::nan("")), 1.0);
  EXPECT_NEAR(vis4gs::ZoomThreshold(1.05), std::pow(0.5, 1.2), 1e-15);
  EXPECT_NEAR(vis4gs::ZoomThreshold(0.575), std::pow(0.75, 1.2), 1e-15);
  // Monotone decreasing.
  double previous = 2.0;
  for (double z = 0.0; z <= 2.1; z += 0.01)
  {
    const double tau = vis4gs::ZoomThreshold(z);
    EXPECT_LE(tau, previous);
    previous = tau;
  }
  vis4gs::ZoomParameters bad;
  bad.ZMax = bad.ZMin;
  EXPECT_THROW(vis4gs::ZoomThreshold(1.0, bad), std::runtime_error);
}

// Interval 500: events at 100 and 300 fall in (0, 500] -> iteration 500; 0 cloned and split
// there, so 1, 2, 3 are clone-split children and 0 ends at 500. 1 clones 4 at 700 -> 1000,
// 4 is pruned at 800 -> 1000: zero lifespan.
TEST(Genealogy, CoarsenCloneSplit)
{
  EventTable t;
  Add(t, 100, 1, 0, 1);
  Add(t, 300, 2, 0, 2);
  Add(t, 300, 2, 0, 3);
  Add(t, 700, 1, 1, 4);
  Add(t, 800, 3, 4, -1);
  GenealogyOptions o;
  o.CoarsenInterval = 500;
  const Genealogy g = Genealogy::Build(1, t, 1000, o);
  ASSERT_EQ(g.GetNumberOfNodes(), 5);
  const std::vector<BirthKind> kind = { BirthKind::Root,
    BirthKind::CloneSplit,
    BirthKind::CloneSplit,
    BirthKind::CloneSplit,
    BirthKind::Clone };
  EXPECT_EQ(g.GetBirthKinds(), kind);
  EXPECT_EQ(g.GetBirthIterations(), (std::vector<std::int32_t>{ 0, 500, 500, 500, 1000 }));
  EXPECT_EQ(g.GetDeathIterations(), (std::vector<std::int32_t>{ 500, -1, -1, -1, 1000 }));
  EXPECT_EQ(g.GetPruned(), (std::vector<std::uint8_t>{ 0, 0, 0, 0, 1 }));
  EXPECT_EQ(g.GetLifespans(), (std::vector<std::int32_t>{ 500, 500, 500, 500, 0 }));
  EXPECT_EQ(g.GetDescendantCounts(), (std::vector<std::int64_t>{ 4, 1, 0, 0, 0 }));
  // Rows: 0, then 1 (with 4 below it), then 2, 3.
  EXPECT_EQ(g.GetRows(), (std::vector<std::int64_t>{ 0, 1, 3, 4, 2 }));
  EXPECT_NEAR(g.GetPerceptionValues()[1], 0.4 * 0.25 + 0.6, 1e-15);
  EXPECT_NEAR(g.GetPerceptionValues()[4], 0.0, 0.0);

  // Without coarsening the same log keeps the kinds as logged.
  const Genealogy f = Genealogy::Build(1, t, 1000);
  EXPECT_EQ(f.GetBirthKinds(),
    (std::vector<BirthKind>{
      BirthKind::Root, BirthKind::Clone, BirthKind::Split, BirthKind::Split, BirthKind::Clone }));
  EXPECT_EQ(f.GetDeathIterations()[0], 300);
  EXPECT_EQ(f.GetLifespans()[4], 100);

  // Inside one interval the order does not matter: split before clone is fine coarsened,
  // an error (parent already ended) in fine mode.
  EventTable u;
  Add(u, 300, 2, 0, 2);
  Add(u, 300, 2, 0, 3);
  Add(u, 400, 1, 0, 1);
  const Genealogy h = Genealogy::Build(1, u, 1000, o);
  EXPECT_EQ(h.GetBirthKinds()[1], BirthKind::CloneSplit);
  EXPECT_EQ(h.GetBirthKinds()[3], BirthKind::CloneSplit);
  EXPECT_EQ(h.GetDeathIterations()[0], 500);
  EXPECT_THROW(Genealogy::Build(1, u, 1000), std::runtime_error);

  // A parent that only splits (or only clones) in an interval keeps plain kinds.
  EventTable w;
  Add(w, 100, 1, 0, 1);
  Add(w, 600, 2, 0, 2);
  Add(w, 600, 2, 0, 3);
  const Genealogy k = Genealogy::Build(1, w, 1000, o);
  EXPECT_EQ(k.GetBirthKinds(),
    (std::vector<BirthKind>{
      BirthKind::Root, BirthKind::Clone, BirthKind::Split, BirthKind::Split }));
  EXPECT_EQ(k.GetDeathIterations()[0], 1000);
}

TEST(Genealogy, LineageHand)
{
  const Genealogy g = Genealogy::Build(2, HandLog(), 1000);
  EXPECT_EQ(g.Ancestors(V({ 6 })), V({ 0, 3, 5 }));
  EXPECT_EQ(g.Ancestors(V({ 5, 6 })), V({ 0, 3, 5 }));
  EXPECT_EQ(g.Ancestors(V({ 6, 2, 1 })), V({ 0, 3, 5 }));
  EXPECT_EQ(g.Ancestors(V({ 0 })), V({}));
  EXPECT_EQ(g.Descendants(V({ 3 })), V({ 5, 6, 7 }));
  EXPECT_EQ(g.Descendants(V({ 3, 5 })), V({ 5, 6, 7 }));
  EXPECT_EQ(g.Descendants(V({ 1, 4 })), V({}));
  EXPECT_EQ(g.Lineage(V({ 5 })), V({ 0, 3, 5, 6, 7 }));
  EXPECT_EQ(g.Lineage(V({ 5, 1 })), V({ 0, 1, 3, 5, 6, 7 }));
  EXPECT_EQ(g.Family(V({ 4 })), V({ 0, 2, 3, 4, 5, 6, 7 }));
  EXPECT_EQ(g.Family(V({ 1, 1 })), V({ 1 }));
  EXPECT_EQ(g.Family(V({})), V({}));
  EXPECT_THROW(g.Ancestors(V({ 8 })), std::runtime_error);
  EXPECT_THROW(g.Family(V({ -1 })), std::runtime_error);
  EXPECT_EQ(g.FindNodes(V({ 7, 99, 3 })), V({ 7, 3 }));
}

TEST(Genealogy, TraceToRoot)
{
  const Genealogy g = Genealogy::Build(2, HandLog(), 1000);
  int calls = 0;
  auto value = [&calls](std::int32_t s, std::int64_t id)
  {
    ++calls;
    return static_cast<double>(id * 10000 + s);
  };
  const auto trace = g.TraceToRoot(6, { 700, 0, 250 }, value);
  ASSERT_EQ(trace.size(), 4u);
  EXPECT_EQ(trace[0].GaussianId, 6);
  EXPECT_EQ(trace[0].SnapshotIteration, 700); // born 600, alive
  EXPECT_DOUBLE_EQ(trace[0].Value, 60700.0);
  EXPECT_EQ(trace[1].GaussianId, 5); // born 300, split at 600: in no snapshot
  EXPECT_EQ(trace[1].SnapshotIteration, -1);
  EXPECT_TRUE(std::isnan(trace[1].Value));
  EXPECT_EQ(trace[2].GaussianId, 3); // born 200, alive: snapshot 250
  EXPECT_EQ(trace[2].SnapshotIteration, 250);
  EXPECT_DOUBLE_EQ(trace[2].Value, 30250.0);
  EXPECT_EQ(trace[3].GaussianId, 0); // root, born 0, split at 200: snapshot 0
  EXPECT_EQ(trace[3].SnapshotIteration, 0);
  EXPECT_EQ(trace[3].Kind, BirthKind::Root);
  EXPECT_EQ(calls, 3);
  EXPECT_EQ(g.TraceToRoot(1, {}, value).size(), 1u);
  EXPECT_THROW(g.TraceToRoot(99, {}, value), std::runtime_error);
}

// Lineage queries and layout invariants on a random synthetic log against brute force.
TEST(Genealogy, RandomAgainstBruteForce)
{
  vis4gs::SyntheticLogParameters prm;
  prm.InitialGaussians = 40;
  prm.FinalGaussians = 3000;
  prm.TotalGaussians = 6000;
  prm.Seed = 7;
  const auto log = vis4gs::GenerateSyntheticEventLog(prm);
  const Genealogy g = Genealogy::Build(log.InitialGaussians, log.Events, log.LastIteration);
  const std::int64_t n = g.GetNumberOfNodes();
  ASSERT_EQ(n, prm.TotalGaussians);
  const auto& par = g.GetParents();
  // Brute-force D, depth-first rows, family maxima and P.
  std::vector<std::int64_t> d(n, 0);
  for (std::int64_t i = 0; i < n; ++i)
  {
    for (std::int64_t u = par[i]; u >= 0; u = par[u])
    {
      ++d[u];
    }
  }
  EXPECT_EQ(g.GetDescendantCounts(), d);
  std::vector<std::int64_t> row(n, -1);
  std::int64_t next = 0;
  std::vector<std::int64_t> stack;
  for (std::int64_t r = 0; r < n; ++r)
  {
    if (par[r] >= 0)
    {
      continue;
    }
    stack.push_back(r);
    while (!stack.empty())
    {
      const std::int64_t u = stack.back();
      stack.pop_back();
      row[u] = next++;
      // push children in reverse creation order so the first-born is visited first
      std::vector<std::int64_t> kids;
      for (std::int64_t c = 0; c < n; ++c)
      {
        if (c > u && par[c] == u)
        {
          kids.push_back(c);
        }
      }
      for (auto it = kids.rbegin(); it != kids.rend(); ++it)
      {
        stack.push_back(*it);
      }
    }
    if (r > 200)
    {
      break; // the quadratic child search is enough for the first families
    }
  }
  for (std::int64_t i = 0; i < n; ++i)
  {
    if (row[i] >= 0)
    {
      EXPECT_EQ(g.GetRows()[i], row[i]) << "node " << i;
    }
  }
  for (std::int64_t i = 0; i < n; ++i)
  {
    std::int64_t root = i;
    while (par[root] >= 0)
    {
      root = par[root];
    }
    std::int64_t maxD = 0;
    std::int32_t maxT = 0;
    for (std::int64_t j = 0; j < n; ++j)
    {
      if (g.GetFamilyIds()[j] == g.GetFamilyIds()[i])
      {
        maxD = std::max(maxD, d[j]);
        maxT = std::max(maxT, g.GetEndIteration(j) - g.GetBirthIterations()[j]);
      }
    }
    EXPECT_EQ(g.GetFamilyBands()[g.GetFamilyIds()[i]].RootNode, root);
    const double p = (maxD > 0 ? 0.4 * double(d[i]) / double(maxD) : 0.0) +
      (maxT > 0 ? 0.6 * double(g.GetLifespans()[i]) / double(maxT) : 0.0);
    EXPECT_NEAR(g.GetPerceptionValues()[i], p, 1e-12);
    if (i > 300)
    {
      break; // O(N^2) reference: a sample is enough
    }
  }
  std::mt19937 rng(3);
  for (int trial = 0; trial < 30; ++trial)
  {
    std::vector<std::int64_t> sel;
    const int k = 1 + trial % 7;
    for (int j = 0; j < k; ++j)
    {
      sel.push_back(static_cast<std::int64_t>(rng() % n));
    }
    std::vector<std::uint8_t> anc(n, 0), desc(n, 0), fam(n, 0);
    for (std::int64_t s : sel)
    {
      for (std::int64_t u = par[s]; u >= 0; u = par[u])
      {
        anc[u] = 1;
      }
      for (std::int64_t j = 0; j < n; ++j)
      {
        for (std::int64_t u = par[j]; u >= 0; u = par[u])
        {
          if (u == s)
          {
            desc[j] = 1;
          }
        }
        if (g.GetFamilyIds()[j] == g.GetFamilyIds()[s])
        {
          fam[j] = 1;
        }
      }
    }
    std::vector<std::int64_t> a, de, li, fa;
    for (std::int64_t j = 0; j < n; ++j)
    {
      const bool selected = std::find(sel.begin(), sel.end(), j) != sel.end();
      if (anc[j])
        a.push_back(j);
      if (desc[j])
        de.push_back(j);
      if (anc[j] || desc[j] || selected)
        li.push_back(j);
      if (fam[j])
        fa.push_back(j);
    }
    EXPECT_EQ(g.Ancestors(sel), a);
    EXPECT_EQ(g.Descendants(sel), de);
    EXPECT_EQ(g.Lineage(sel), li);
    EXPECT_EQ(g.Family(sel), fa);
  }
}

// 10,000 generations: every traversal must be iterative.
TEST(Genealogy, DeepChain)
{
  const std::int64_t depth = 10000;
  EventTable t;
  for (std::int64_t k = 0; k < depth; ++k)
  {
    Add(t, static_cast<std::int32_t>(k + 1), 2, k, k + 1); // split: one child per generation
  }
  const Genealogy g = Genealogy::Build(1, t, -1);
  ASSERT_EQ(g.GetNumberOfNodes(), depth + 1);
  EXPECT_EQ(g.GetLastIteration(), depth);
  EXPECT_EQ(g.GetDescendantCounts()[0], depth);
  EXPECT_EQ(g.GetDescendantCounts()[depth], 0);
  EXPECT_EQ(g.GetRows()[depth], depth);
  EXPECT_EQ(g.GetLifespans()[depth], 0); // born at the last iteration, alive: T = 0
  EXPECT_EQ(g.GetLifespans()[5], 1);
  EXPECT_EQ(g.Ancestors({ depth }).size(), static_cast<std::size_t>(depth));
  EXPECT_EQ(g.Descendants({ 0 }).size(), static_cast<std::size_t>(depth));
  const auto trace = g.TraceToRoot(depth, {}, nullptr);
  ASSERT_EQ(trace.size(), static_cast<std::size_t>(depth + 1));
  EXPECT_EQ(trace.back().GaussianId, 0);
  // P: D term 0.4 * (depth - k) / depth, T term 0.6 * 1/1 except the last node (T = 0).
  EXPECT_NEAR(g.GetPerceptionValues()[0], 1.0, 1e-15);
  EXPECT_NEAR(g.GetPerceptionValues()[depth / 2], 0.4 * 0.5 + 0.6, 1e-15);
  EXPECT_NEAR(g.GetPerceptionValues()[depth], 0.0, 0.0);
}

// One root with 1,000,000 clone children.
TEST(Genealogy, MillionChildren)
{
  const std::int64_t m = 1000000;
  EventTable t;
  t.Iteration.reserve(m);
  for (std::int64_t k = 0; k < m; ++k)
  {
    Add(t, static_cast<std::int32_t>(1 + k / 100), 1, 0, k + 1);
  }
  const Genealogy g = Genealogy::Build(1, t, 20000);
  ASSERT_EQ(g.GetNumberOfNodes(), m + 1);
  EXPECT_EQ(g.GetNumberOfChildren(0), m);
  EXPECT_EQ(g.GetDescendantCounts()[0], m);
  EXPECT_EQ(g.GetFamilyBands()[0].MaxRow, m);
  EXPECT_EQ(g.GetRows()[m], m); // k-th child on row k
  EXPECT_EQ(g.GetRows()[12345], 12345);
  // Root: D = max, T = 20000 = max -> P = 1; last child born at 10000: T = 10000.
  EXPECT_DOUBLE_EQ(g.GetPerceptionValues()[0], 1.0);
  EXPECT_NEAR(g.GetPerceptionValues()[m], 0.6 * 10000.0 / 20000.0, 1e-15);
  EXPECT_EQ(g.Family({ 77 }).size(), static_cast<std::size_t>(m + 1));
  EXPECT_EQ(g.Ancestors({ 77, 78, 79 }), V({ 0 }));
  EXPECT_EQ(g.Lineage({ 77 }), V({ 0, 77 }));
}

// Sparse ids use the hash index.
TEST(Genealogy, SparseIds)
{
  const std::int64_t big = 1000000000000LL;
  EventTable t;
  Add(t, 10, 1, big, big + 7);
  Add(t, 20, 2, 3, 99 * big);
  Add(t, 20, 2, 3, 5);
  const Genealogy g = Genealogy::Build(std::vector<std::int64_t>{ 3, big }, t, 100);
  ASSERT_EQ(g.GetNumberOfNodes(), 5);
  EXPECT_EQ(g.FindNode(big + 7), 2);
  EXPECT_EQ(g.FindNode(99 * big), 3);
  EXPECT_EQ(g.FindNode(5), 4);
  EXPECT_EQ(g.FindNode(4), -1);
  EXPECT_EQ(g.GetDeathIterations()[0], 20);
}

// Assemble from per-node arrays reproduces Build; inconsistent arrays are rejected.
TEST(Genealogy, AssembleMatchesBuild)
{
  vis4gs::SyntheticLogParameters prm;
  prm.InitialGaussians = 30;
  prm.FinalGaussians = 2000;
  prm.TotalGaussians = 4000;
  const auto log = vis4gs::GenerateSyntheticEventLog(prm);
  GenealogyOptions o;
  o.CoarsenInterval = 500;
  const Genealogy g = Genealogy::Build(log.InitialGaussians, log.Events, log.LastIteration, o);
  vis4gs::GenealogyNodes nodes;
  nodes.GaussianIds = g.GetGaussianIds();
  nodes.Parents = g.GetParents();
  nodes.Birth = g.GetBirthIterations();
  nodes.Death = g.GetDeathIterations();
  nodes.Kinds = g.GetBirthKinds();
  nodes.Pruned = g.GetPruned();
  const Genealogy h = Genealogy::Assemble(nodes, g.GetLastIteration());
  EXPECT_EQ(h.GetRows(), g.GetRows());
  EXPECT_EQ(h.GetPerceptionValues(), g.GetPerceptionValues());
  EXPECT_EQ(h.GetDescendantCounts(), g.GetDescendantCounts());
  EXPECT_EQ(h.GetFamilyIds(), g.GetFamilyIds());
  EXPECT_EQ(h.GetLifespans(), g.GetLifespans());
  EXPECT_EQ(h.FindNode(1234), g.FindNode(1234));

  auto bad = nodes;
  bad.Parents[50] = 60;
  EXPECT_THROW(Genealogy::Assemble(bad, g.GetLastIteration()), std::runtime_error);
  bad = nodes;
  bad.GaussianIds[70] = bad.GaussianIds[20];
  EXPECT_THROW(Genealogy::Assemble(bad, g.GetLastIteration()), std::runtime_error);
  bad = nodes;
  bad.Death[80] = bad.Birth[80] - 1;
  EXPECT_THROW(Genealogy::Assemble(bad, g.GetLastIteration()), std::runtime_error);
  bad = nodes;
  bad.Kinds.pop_back();
  EXPECT_THROW(Genealogy::Assemble(bad, g.GetLastIteration()), std::runtime_error);
}

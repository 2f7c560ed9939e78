// SPDX-License-Identifier: BSD-3-Clause
// The tree view's draw index against brute force: orders, bounds, id lookup and the
// visible-node query, on layouts like the genealogy filter's and on arbitrary ones.
#include "TreeDrawIndex.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <set>
#include <vector>

namespace
{
using vis4gs::TreeDrawIndex;

struct Case
{
  std::vector<std::int64_t> Ids;
  TreeDrawIndex Index;
};

// n vertices; vertex 0 is a virtual root (id -1). Rows: a permutation (as the genealogy
// filter lays out), integers with repeats, or non-integers. Ids (idMode): 0 in vertex order
// (vertex + 499, as the genealogy filter gives for a trainer's log), 1 sparse, 2 dense but
// shuffled.
Case MakeCase(int n, int rowMode, int idMode, unsigned seed)
{
  std::mt19937 rng(seed);
  Case c;
  TreeDrawIndex& x = c.Index;
  std::vector<double> perm(n - 1);
  for (int i = 0; i < n - 1; ++i)
  {
    perm[i] = 10 + i;
  }
  std::shuffle(perm.begin(), perm.end(), rng);
  std::vector<std::int64_t> shuffled(n - 1);
  for (int i = 0; i < n - 1; ++i)
  {
    shuffled[i] = 500 + i;
  }
  std::shuffle(shuffled.begin(), shuffled.end(), rng);
  std::uniform_int_distribution<int> it(0, 3000);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int v = 0; v < n; ++v)
  {
    const bool root = v == 0;
    c.Ids.push_back(root ? -1
        : idMode == 0    ? 499 + v
        : idMode == 1    ? 1000 * v + 7
                         : shuffled[v - 1]);
    const int b = it(rng);
    x.Birth.push_back(b);
    x.End.push_back(u(rng) < 0.3 ? -1 : b + it(rng) / 4);
    const double row = rowMode == 0 ? (root ? 0 : perm[v - 1])
      : rowMode == 1                ? std::floor(u(rng) * n / 3)
                                    : u(rng) * n;
    x.Row.push_back(row);
    const double r = u(rng);
    x.P.push_back(r < 0.05 ? std::nan("") : (r < 0.15 ? 0.5 : u(rng) * 1.2 - 0.1));
  }
  return c;
}

std::set<std::int64_t> BruteVisible(const Case& c,
  const std::vector<std::int32_t>& end,
  double tau,
  double xLo,
  double xHi,
  double rowLo,
  double rowHi,
  const std::vector<std::uint8_t>& excluded)
{
  std::set<std::int64_t> out;
  const TreeDrawIndex& x = c.Index;
  for (std::size_t v = 0; v < c.Ids.size(); ++v)
  {
    if (c.Ids[v] >= 0 && x.P[v] >= tau && x.Row[v] >= rowLo && x.Row[v] <= rowHi &&
      x.Birth[v] <= xHi && end[v] >= xLo && !excluded[v])
    {
      out.insert(static_cast<std::int64_t>(v));
    }
  }
  return out;
}
} // namespace

TEST(TreeDrawIndex, OrdersBoundsAndLookupEqualBruteForce)
{
  for (int rowMode = 0; rowMode < 3; ++rowMode)
  {
    for (int idMode : { 0, 1, 2 })
    {
      const bool sparse = idMode == 1;
      const int n = 3001;
      Case c = MakeCase(n, rowMode, idMode, 11u + rowMode * 3 + idMode);
      const std::vector<std::int32_t> endIn = c.Index.End;
      const std::vector<double> rows = c.Index.Row;
      c.Index.Build(c.Ids);
      const TreeDrawIndex& x = c.Index;
      SCOPED_TRACE(testing::Message() << "rows " << rowMode << " ids " << idMode);

      // Last iteration and alive ends, bounds, drawn count.
      std::int32_t last = std::numeric_limits<std::int32_t>::min();
      double minX = 1e300, maxX = -1e300, minY = 1e300, maxY = -1e300;
      for (int v = 1; v < n; ++v)
      {
        last = std::max({ last, x.Birth[v], endIn[v] });
      }
      EXPECT_EQ(x.LastIteration, last);
      EXPECT_EQ(x.NumberOfRows, n - 1);
      EXPECT_EQ(x.Valid[0], 0);
      for (int v = 1; v < n; ++v)
      {
        EXPECT_EQ(x.End[v], endIn[v] < 0 ? last : endIn[v]);
        minX = std::min(minX, double(x.Birth[v]));
        maxX = std::max(maxX, double(x.End[v]));
        minY = std::min(minY, rows[v]);
        maxY = std::max(maxY, rows[v]);
      }
      EXPECT_EQ(x.End[0], endIn[0]) << "a vertex that is not drawn keeps its end";
      EXPECT_EQ(x.DataMinX, minX);
      EXPECT_EQ(x.DataMaxX, std::max(maxX, minX + 1));
      EXPECT_EQ(x.DataMinY, minY);
      EXPECT_EQ(x.DataMaxY, maxY);

      // ByP: every drawn vertex once, P descending, NaN last.
      ASSERT_EQ(x.ByP.size(), std::size_t(n - 1));
      EXPECT_EQ(std::set<std::int64_t>(x.ByP.begin(), x.ByP.end()).size(), std::size_t(n - 1));
      bool seenNaN = false;
      for (std::size_t k = 0; k < x.ByP.size(); ++k)
      {
        const double p = x.P[x.ByP[k]];
        if (std::isnan(p))
        {
          seenNaN = true;
          continue;
        }
        EXPECT_FALSE(seenNaN) << "a number after a NaN at " << k;
        if (k > 0 && !std::isnan(x.P[x.ByP[k - 1]]))
        {
          EXPECT_GE(x.P[x.ByP[k - 1]], p) << k;
        }
      }
      // ByRow: std::stable_sort of the drawn vertices by row.
      std::vector<std::int32_t> byRow;
      for (int v = 1; v < n; ++v)
      {
        byRow.push_back(v);
      }
      std::stable_sort(byRow.begin(),
        byRow.end(),
        [&](std::int32_t a, std::int32_t b) { return rows[a] < rows[b]; });
      EXPECT_EQ(x.ByRow, byRow);

      // Id lookup, including ids that are absent.
      for (int v = 0; v < n; ++v)
      {
        if (c.Ids[v] >= 0)
        {
          EXPECT_EQ(x.VertexOfId(c.Ids[v]), v);
        }
      }
      EXPECT_EQ(x.VertexOfId(-1), -1);
      EXPECT_EQ(x.VertexOfId(sparse ? 1001 : 499), -1) << "the virtual root's place";
      EXPECT_EQ(x.VertexOfId(sparse ? 1000 * n + 7 : 499 + n), -1) << "past the last vertex";
      EXPECT_EQ(x.VertexOfId(498), -1);
      EXPECT_EQ(x.VertexOfId(std::numeric_limits<std::int64_t>::max()), -1);
      EXPECT_EQ(x.VertexOfId(std::numeric_limits<std::int64_t>::min()), -1);

      // The visible-node query for windows and thresholds that favour either walk.
      std::vector<std::uint8_t> excluded(n, 0);
      for (int v = 0; v < n; v += 17)
      {
        excluded[v] = 1;
      }
      for (double tau : { -1.0, 0.0, 0.5, 0.9, 2.0 })
      {
        for (double frac : { 0.01, 0.2, 1.0 })
        {
          const double rowLo = minY + 0.3 * (maxY - minY);
          const double rowHi = rowLo + frac * (maxY - minY);
          const double xLo = 800, xHi = 2200;
          std::vector<std::int64_t> got;
          const std::int64_t work =
            x.QueryVisible(tau, xLo, xHi, rowLo, rowHi, excluded.data(), got);
          const std::set<std::int64_t> want =
            BruteVisible(c, x.End, tau, xLo, xHi, rowLo, rowHi, excluded);
          EXPECT_EQ(std::set<std::int64_t>(got.begin(), got.end()), want)
            << "tau " << tau << " rows " << rowLo << ".." << rowHi;
          EXPECT_EQ(got.size(), want.size()) << "no vertex twice";
          std::int64_t nP = 0, nRows = 0;
          for (int v = 1; v < n; ++v)
          {
            nP += x.P[v] >= tau;
            nRows += rows[v] >= rowLo && rows[v] <= rowHi;
          }
          EXPECT_EQ(work, std::min(nP, nRows)) << "walks the shorter list";
        }
      }
    }
  }
}

TEST(TreeDrawIndex, ColumnsReadInPlaceEqualCopies)
{
  for (int rowMode = 0; rowMode < 3; ++rowMode)
  {
    Case copies = MakeCase(2001, rowMode, rowMode, 40u + rowMode);
    Case views = copies;
    const std::vector<std::int32_t> birth = views.Index.Birth;
    const std::vector<double> p = views.Index.P;
    views.Index.Birth.clear();
    views.Index.P.clear();
    views.Index.BirthView = birth.data();
    views.Index.PView = p.data();
    copies.Index.Build(copies.Ids);
    views.Index.Build(views.Ids);
    EXPECT_EQ(views.Index.BirthData(), birth.data());
    EXPECT_EQ(views.Index.PData(), p.data());
    EXPECT_EQ(views.Index.ByP, copies.Index.ByP);
    EXPECT_EQ(views.Index.ByRow, copies.Index.ByRow);
    EXPECT_EQ(views.Index.End, copies.Index.End);
    EXPECT_EQ(views.Index.DataMinX, copies.Index.DataMinX);
    EXPECT_EQ(views.Index.DataMaxX, copies.Index.DataMaxX);
    for (double tau : { 0.0, 0.5, 0.95 })
    {
      std::vector<std::int64_t> a, b;
      const double lo = copies.Index.DataMinY, hi = copies.Index.DataMaxY;
      EXPECT_EQ(views.Index.QueryVisible(tau, 500, 2500, lo, lo + 0.4 * (hi - lo), nullptr, a),
        copies.Index.QueryVisible(tau, 500, 2500, lo, lo + 0.4 * (hi - lo), nullptr, b));
      EXPECT_EQ(a, b) << "tau " << tau;
      EXPECT_FALSE(a.empty());
    }
    // A view stands in for its column in the length check too.
    views.Index.BirthView = nullptr;
    EXPECT_THROW(views.Index.Build(views.Ids), std::invalid_argument);
  }
}

TEST(TreeDrawIndex, EmptyAndBadInput)
{
  TreeDrawIndex x;
  x.Build({});
  EXPECT_EQ(x.NumberOfRows, 0);
  EXPECT_EQ(x.DataMinX, 0.0);
  EXPECT_EQ(x.DataMaxX, 1.0);
  std::vector<std::int64_t> out;
  EXPECT_EQ(x.QueryVisible(0, 0, 1, 0, 1, nullptr, out), 0);
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(x.VertexOfId(0), -1);

  // Only a virtual root: nothing drawn, bounds 0..1.
  x.Birth = { 0 };
  x.End = { -1 };
  x.Row = { 0 };
  x.P = { 1 };
  x.Build({ -1 });
  EXPECT_EQ(x.NumberOfRows, 0);
  EXPECT_TRUE(x.ByP.empty());

  x.Birth = { 0, 1 };
  EXPECT_THROW(x.Build({ 1 }), std::invalid_argument);

  // A fixed last iteration replaces the one found in the data.
  x.Birth = { 5 };
  x.End = { -1 };
  x.Row = { 0 };
  x.P = { 1 };
  x.Build({ 3 }, 900);
  EXPECT_EQ(x.End[0], 900);
  EXPECT_EQ(x.LastIteration, 900);
  EXPECT_EQ(x.VertexOfId(3), 0);
}

TEST(TreeDrawIndex, IdsInVertexOrderWithGaps)
{
  // id = vertex - 1 for the drawn vertices (no table), with vertices 0 and 3 not drawn.
  TreeDrawIndex x;
  x.Birth = { 0, 0, 1, 2, 3 };
  x.End = { -1, -1, -1, -1, -1 };
  x.Row = { -1, 0, 1, 2, 3 };
  x.P = { 1, 1, 0.5, 0.5, 0.2 };
  x.Build({ -1, 0, 1, -1, 3 });
  EXPECT_EQ(x.NumberOfRows, 3);
  EXPECT_EQ(x.VertexOfId(0), 1);
  EXPECT_EQ(x.VertexOfId(1), 2);
  EXPECT_EQ(x.VertexOfId(2), -1) << "vertex 3 is not drawn";
  EXPECT_EQ(x.VertexOfId(3), 4);
  EXPECT_EQ(x.VertexOfId(4), -1);
  EXPECT_EQ(x.VertexOfId(-1), -1) << "vertex 0 is not drawn";
  EXPECT_EQ(x.VertexOfId(-2), -1);
  EXPECT_EQ(x.VertexOfId(std::numeric_limits<std::int64_t>::max()), -1);
  EXPECT_EQ(x.VertexOfId(std::numeric_limits<std::int64_t>::min()), -1);
  // One id out of order: the same lookups through the table.
  x.Build({ -1, 0, 5, -1, 3 });
  EXPECT_EQ(x.VertexOfId(5), 2);
  EXPECT_EQ(x.VertexOfId(1), -1);
  EXPECT_EQ(x.VertexOfId(3), 4);
}

// SPDX-License-Identifier: BSD-3-Clause
#include "GaussianOctree.h"

#include "GaussianMath.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace vis4gs
{
namespace
{
constexpr double LogScaleClamp = 300.0;
constexpr double Inf = std::numeric_limits<double>::infinity();

void CheckCloud(const GaussianCloud& cloud)
{
  const std::size_t n = cloud.Count;
  auto check = [n](const char* name, std::size_t size, std::size_t per)
  {
    if (size != n * per)
    {
      throw std::invalid_argument(std::string("Gaussian cloud: ") + name + " holds " +
        std::to_string(size) + " values, expected " + std::to_string(n * per));
    }
  };
  check("Positions", cloud.Positions.size(), 3);
  check("LogScales", cloud.LogScales.size(), 3);
  check("Rotations", cloud.Rotations.size(), 4);
  if (n > std::numeric_limits<std::uint32_t>::max())
  {
    throw std::invalid_argument("Gaussian cloud: too many Gaussians for the octree (> 2^32-1)");
  }
}

/// Rotation and clamped scales of Gaussian i; false for a Gaussian the renderer skips
/// (ClassifyGaussian). What the renderer draws is selectable: a zero quaternion is the
/// identity rotation and a log-scale of -inf the clamped smallest scale, as drawn.
bool GaussianFrame(const GaussianCloud& cloud, std::size_t i, std::array<double, 9>& R, double s[3])
{
  const float* p = &cloud.Positions[3 * i];
  const float* ls = &cloud.LogScales[3 * i];
  const float* q = &cloud.Rotations[4 * i];
  const float logit = cloud.OpacityLogits.empty() ? 0.0f : cloud.OpacityLogits[i];
  if (ClassifyGaussian(p, ls, q, logit) != GaussianClass::Drawn)
  {
    return false;
  }
  const double qd[4] = { q[0], q[1], q[2], q[3] };
  R = QuaternionToMatrix<double>(NormalizeQuaternion<double>(qd));
  for (int k = 0; k < 3; ++k)
  {
    s[k] = std::exp(std::min(LogScaleClamp, std::max(-LogScaleClamp, static_cast<double>(ls[k]))));
  }
  return true;
}

bool UnitDirection(const RayQuery& ray, double d[3])
{
  const double n = std::sqrt(ray.Direction[0] * ray.Direction[0] +
    ray.Direction[1] * ray.Direction[1] + ray.Direction[2] * ray.Direction[2]);
  if (!(n > 0) || !std::isfinite(n))
  {
    return false;
  }
  for (int k = 0; k < 3; ++k)
  {
    d[k] = ray.Direction[k] / n;
  }
  return true;
}

double DistanceInFrame(const GaussianCloud& cloud,
  std::size_t i,
  const std::array<double, 9>& R,
  const double s[3],
  const double start[3],
  const double d[3])
{
  const float* mu = &cloud.Positions[3 * i];
  const double delta[3] = { start[0] - mu[0], start[1] - mu[1], start[2] - mu[2] };
  double o[3], e[3];
  for (int k = 0; k < 3; ++k)
  {
    // (R^T v)_k = sum_r R_rk v_r, then divide by the scale.
    o[k] = (R[k] * delta[0] + R[3 + k] * delta[1] + R[6 + k] * delta[2]) / s[k];
    e[k] = (R[k] * d[0] + R[3 + k] * d[1] + R[6 + k] * d[2]) / s[k];
  }
  const double ee = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
  const double oe = o[0] * e[0] + o[1] * e[1] + o[2] * e[2];
  const double t = ee > 0 ? -oe / ee : 0.0;
  double d2;
  if (!(t > 0))
  {
    d2 = o[0] * o[0] + o[1] * o[1] + o[2] * o[2];
  }
  else
  {
    const double p[3] = { o[0] + t * e[0], o[1] + t * e[1], o[2] + t * e[2] };
    d2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
  }
  return std::isnan(d2) ? Inf : std::sqrt(d2);
}

// Slab test of the half-line start + t d, t >= 0, against a box.
template <typename B>
bool RayHitsBox(const double start[3], const double invD[3], const B* lo, const B* hi)
{
  double t0 = 0.0, t1 = Inf;
  for (int k = 0; k < 3; ++k)
  {
    double a = (static_cast<double>(lo[k]) - start[k]) * invD[k];
    double b = (static_cast<double>(hi[k]) - start[k]) * invD[k];
    if (std::isnan(a) || std::isnan(b))
    {
      // Direction component 0 (inf * 0): inside the slab iff start lies within it.
      if (start[k] < lo[k] || start[k] > hi[k])
      {
        return false;
      }
      continue;
    }
    if (a > b)
    {
      std::swap(a, b);
    }
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1)
    {
      return false;
    }
  }
  return true;
}

void SortHits(std::vector<RayHit>& hits)
{
  std::sort(hits.begin(),
    hits.end(),
    [](const RayHit& a, const RayHit& b)
    { return a.Depth < b.Depth || (a.Depth == b.Depth && a.Gaussian < b.Gaussian); });
}
} // namespace

//------------------------------------------------------------------------------
double RayMahalanobisDistance(const GaussianCloud& cloud, std::size_t i, const RayQuery& ray)
{
  std::array<double, 9> R;
  double s[3], d[3];
  if (!UnitDirection(ray, d) || !GaussianFrame(cloud, i, R, s))
  {
    return Inf;
  }
  const double start[3] = { ray.Origin[0] + ray.TMin * d[0],
    ray.Origin[1] + ray.TMin * d[1],
    ray.Origin[2] + ray.TMin * d[2] };
  return DistanceInFrame(cloud, i, R, s, start, d);
}

//------------------------------------------------------------------------------
void GaussianOctree::Build(const GaussianCloud& cloud, const Options& options)
{
  CheckCloud(cloud);
  if (!(options.BoundSigmas > 0) || options.LeafSize < 1 || options.MaxDepth < 0)
  {
    throw std::invalid_argument("GaussianOctree: BoundSigmas must be positive, LeafSize >= 1");
  }
  this->Cloud = &cloud;
  this->Opts = options;
  this->Nodes.clear();
  this->Items.clear();
  this->Depth = 0;
  const std::size_t n = cloud.Count;
  this->Boxes.assign(6 * n, std::numeric_limits<float>::quiet_NaN());

  // Boxes of the k-sigma ellipsoids: half extent k sqrt(Sigma_ii).
  double lo[3] = { Inf, Inf, Inf }, hi[3] = { -Inf, -Inf, -Inf };
  std::vector<std::uint32_t> valid;
  valid.reserve(n);
  const double k = options.BoundSigmas;
  for (std::size_t i = 0; i < n; ++i)
  {
    std::array<double, 9> R;
    double s[3];
    if (!GaussianFrame(cloud, i, R, s))
    {
      continue;
    }
    valid.push_back(static_cast<std::uint32_t>(i));
    const float* mu = &cloud.Positions[3 * i];
    bool finite = true;
    for (int r = 0; r < 3; ++r)
    {
      double v = 0;
      for (int c = 0; c < 3; ++c)
      {
        v += R[3 * r + c] * R[3 * r + c] * s[c] * s[c];
      }
      const double h = k * std::sqrt(v);
      // Round outwards so the float box contains the double one.
      float bmin = static_cast<float>(mu[r] - h), bmax = static_cast<float>(mu[r] + h);
      bmin = std::nextafter(bmin, -std::numeric_limits<float>::infinity());
      bmax = std::nextafter(bmax, std::numeric_limits<float>::infinity());
      this->Boxes[6 * i + r] = bmin;
      this->Boxes[6 * i + 3 + r] = bmax;
      finite = finite && std::isfinite(bmin) && std::isfinite(bmax);
    }
    if (finite)
    {
      for (int r = 0; r < 3; ++r)
      {
        lo[r] = std::min(lo[r], static_cast<double>(this->Boxes[6 * i + r]));
        hi[r] = std::max(hi[r], static_cast<double>(this->Boxes[6 * i + 3 + r]));
      }
    }
  }
  // Root cube.
  Node root;
  double side = 0;
  for (int r = 0; r < 3; ++r)
  {
    if (!(lo[r] <= hi[r]))
    {
      lo[r] = hi[r] = 0;
    }
    side = std::max(side, hi[r] - lo[r]);
  }
  side = side > 0 ? side * 1.0001 : 1.0;
  for (int r = 0; r < 3; ++r)
  {
    const double c = 0.5 * (lo[r] + hi[r]);
    root.Min[r] = c - 0.5 * side;
    root.Max[r] = c + 0.5 * side;
  }
  this->Nodes.push_back(root);

  // Recursive subdivision (explicit stack of (node, items, depth)).
  struct Task
  {
    std::int32_t Node;
    std::vector<std::uint32_t> Ids;
    int Depth;
  };
  std::vector<Task> stack;
  stack.push_back({ 0, std::move(valid), 0 });
  while (!stack.empty())
  {
    Task task = std::move(stack.back());
    stack.pop_back();
    this->Depth = std::max(this->Depth, task.Depth);
    const Node cell = this->Nodes[task.Node];
    std::vector<std::uint32_t> stay;
    std::vector<std::uint32_t> child[8];
    const bool split =
      task.Ids.size() > static_cast<std::size_t>(options.LeafSize) && task.Depth < options.MaxDepth;
    double mid[3];
    for (int r = 0; r < 3; ++r)
    {
      mid[r] = 0.5 * (cell.Min[r] + cell.Max[r]);
    }
    for (std::uint32_t id : task.Ids)
    {
      const float* b = &this->Boxes[6 * static_cast<std::size_t>(id)];
      int octant = 0;
      bool inside = split;
      for (int r = 0; r < 3 && inside; ++r)
      {
        // Inside the cell at all (oversize boxes stay at the root)?
        if (!(b[r] >= cell.Min[r] && b[3 + r] <= cell.Max[r]))
        {
          inside = false;
        }
        else if (b[3 + r] <= mid[r])
        {
          // lower half
        }
        else if (b[r] >= mid[r])
        {
          octant |= 1 << r;
        }
        else
        {
          inside = false; // straddles the split plane
        }
      }
      if (inside)
      {
        child[octant].push_back(id);
      }
      else
      {
        stay.push_back(id);
      }
    }
    this->Nodes[task.Node].First = static_cast<std::uint32_t>(this->Items.size());
    this->Nodes[task.Node].Count = static_cast<std::uint32_t>(stay.size());
    this->Items.insert(this->Items.end(), stay.begin(), stay.end());
    for (int o = 0; o < 8; ++o)
    {
      if (child[o].empty())
      {
        continue;
      }
      Node c;
      for (int r = 0; r < 3; ++r)
      {
        const bool upper = (o >> r) & 1;
        c.Min[r] = upper ? mid[r] : cell.Min[r];
        c.Max[r] = upper ? cell.Max[r] : mid[r];
      }
      const std::int32_t idx = static_cast<std::int32_t>(this->Nodes.size());
      this->Nodes.push_back(c);
      this->Nodes[task.Node].Children[o] = idx;
      stack.push_back({ idx, std::move(child[o]), task.Depth + 1 });
    }
  }
}

//------------------------------------------------------------------------------
std::vector<RayHit> GaussianOctree::IntersectRay(const RayQuery& ray) const
{
  if (this->Cloud == nullptr || this->Nodes.empty())
  {
    throw std::invalid_argument("GaussianOctree: IntersectRay before Build");
  }
  if (!(ray.Sigmas <= this->Opts.BoundSigmas) || !(ray.Sigmas >= 0))
  {
    throw std::invalid_argument("GaussianOctree: a query of " + std::to_string(ray.Sigmas) +
      " sigmas needs a tree built with BoundSigmas >= it (built with " +
      std::to_string(this->Opts.BoundSigmas) + ")");
  }
  double d[3];
  if (!UnitDirection(ray, d))
  {
    throw std::invalid_argument("GaussianOctree: the ray direction is zero or not finite");
  }
  const double start[3] = { ray.Origin[0] + ray.TMin * d[0],
    ray.Origin[1] + ray.TMin * d[1],
    ray.Origin[2] + ray.TMin * d[2] };
  const double invD[3] = { 1.0 / d[0], 1.0 / d[1], 1.0 / d[2] };
  const GaussianCloud& cloud = *this->Cloud;
  std::vector<RayHit> hits;
  std::size_t tests = 0;
  std::vector<std::int32_t> stack{ 0 };
  while (!stack.empty())
  {
    const Node& node = this->Nodes[stack.back()];
    stack.pop_back();
    for (std::uint32_t k = 0; k < node.Count; ++k)
    {
      const std::uint32_t id = this->Items[node.First + k];
      const float* b = &this->Boxes[6 * static_cast<std::size_t>(id)];
      ++tests;
      if (!RayHitsBox(start, invD, b, b + 3))
      {
        continue;
      }
      std::array<double, 9> R;
      double s[3];
      GaussianFrame(cloud, id, R, s);
      const double dist = DistanceInFrame(cloud, id, R, s, start, d);
      if (dist <= ray.Sigmas)
      {
        const float* mu = &cloud.Positions[3 * static_cast<std::size_t>(id)];
        const double depth = (mu[0] - ray.Origin[0]) * d[0] + (mu[1] - ray.Origin[1]) * d[1] +
          (mu[2] - ray.Origin[2]) * d[2];
        hits.push_back({ id, depth, dist });
      }
    }
    for (std::int32_t c : node.Children)
    {
      if (c >= 0 && RayHitsBox(start, invD, this->Nodes[c].Min, this->Nodes[c].Max))
      {
        stack.push_back(c);
      }
    }
  }
  this->LastBoxTests = tests;
  SortHits(hits);
  return hits;
}

//------------------------------------------------------------------------------
std::vector<RayHit> IntersectRayBruteForce(const GaussianCloud& cloud, const RayQuery& ray)
{
  CheckCloud(cloud);
  typedef long double L;
  const L dn = std::sqrt(static_cast<L>(ray.Direction[0]) * ray.Direction[0] +
    static_cast<L>(ray.Direction[1]) * ray.Direction[1] +
    static_cast<L>(ray.Direction[2]) * ray.Direction[2]);
  if (!(dn > 0) || !std::isfinite(static_cast<double>(dn)))
  {
    throw std::invalid_argument("IntersectRayBruteForce: zero or non-finite direction");
  }
  const L d[3] = { ray.Direction[0] / dn, ray.Direction[1] / dn, ray.Direction[2] / dn };
  std::vector<RayHit> hits;
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    const float* mu = &cloud.Positions[3 * i];
    const float* ls = &cloud.LogScales[3 * i];
    const float* q = &cloud.Rotations[4 * i];
    const float logit = cloud.OpacityLogits.empty() ? 0.0f : cloud.OpacityLogits[i];
    if (ClassifyGaussian(mu, ls, q, logit) != GaussianClass::Drawn)
    {
      continue;
    }
    // The reference's normalisation: a zero quaternion stays zero, i.e. the identity.
    const L qn = std::max(std::sqrt(static_cast<L>(q[0]) * q[0] + static_cast<L>(q[1]) * q[1] +
                            static_cast<L>(q[2]) * q[2] + static_cast<L>(q[3]) * q[3]),
      1e-12L);
    const L w = q[0] / qn, x = q[1] / qn, y = q[2] / qn, z = q[3] / qn;
    const L R[3][3] = { { 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y) },
      { 2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x) },
      { 2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y) } };
    L S[3][3];
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
      {
        S[r][c] = 0;
        for (int k = 0; k < 3; ++k)
        {
          S[r][c] += R[r][k] * R[c][k] * std::exp(2 * static_cast<L>(ls[k]));
        }
      }
    }
    // Explicit inverse by the adjugate.
    const L det = S[0][0] * (S[1][1] * S[2][2] - S[1][2] * S[2][1]) -
      S[0][1] * (S[1][0] * S[2][2] - S[1][2] * S[2][0]) +
      S[0][2] * (S[1][0] * S[2][1] - S[1][1] * S[2][0]);
    if (!(det > 0))
    {
      continue;
    }
    L I[3][3];
    I[0][0] = (S[1][1] * S[2][2] - S[1][2] * S[2][1]) / det;
    I[0][1] = (S[0][2] * S[2][1] - S[0][1] * S[2][2]) / det;
    I[0][2] = (S[0][1] * S[1][2] - S[0][2] * S[1][1]) / det;
    I[1][0] = (S[1][2] * S[2][0] - S[1][0] * S[2][2]) / det;
    I[1][1] = (S[0][0] * S[2][2] - S[0][2] * S[2][0]) / det;
    I[1][2] = (S[0][2] * S[1][0] - S[0][0] * S[1][2]) / det;
    I[2][0] = (S[1][0] * S[2][1] - S[1][1] * S[2][0]) / det;
    I[2][1] = (S[0][1] * S[2][0] - S[0][0] * S[2][1]) / det;
    I[2][2] = (S[0][0] * S[1][1] - S[0][1] * S[1][0]) / det;
    L delta[3];
    for (int k = 0; k < 3; ++k)
    {
      delta[k] = ray.Origin[k] + ray.TMin * d[k] - mu[k];
    }
    auto form = [&I](const L* u, const L* v)
    {
      L s = 0;
      for (int r = 0; r < 3; ++r)
      {
        for (int c = 0; c < 3; ++c)
        {
          s += u[r] * I[r][c] * v[c];
        }
      }
      return s;
    };
    const L a = form(d, d), b = form(d, delta), c = form(delta, delta);
    const L t = std::max(L(0), -b / a);
    const L d2 = c + 2 * t * b + t * t * a;
    const double dist = static_cast<double>(std::sqrt(std::max(L(0), d2)));
    if (dist <= ray.Sigmas)
    {
      const double depth = static_cast<double>((mu[0] - ray.Origin[0]) * d[0] +
        (mu[1] - ray.Origin[1]) * d[1] + (mu[2] - ray.Origin[2]) * d[2]);
      hits.push_back({ static_cast<std::uint32_t>(i), depth, dist });
    }
  }
  SortHits(hits);
  return hits;
}

} // namespace vis4gs

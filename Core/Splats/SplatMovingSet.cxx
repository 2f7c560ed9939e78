// SPDX-License-Identifier: BSD-3-Clause
#include "SplatMovingSet.h"

#include "ElapsedTime.h"
#include "GaussianMath.h"
#include "ThreadCount.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace vis4gs
{

//------------------------------------------------------------------------------
double SplatViewChangeAngle(const Camera& rank, const Camera& now, double depth)
{
  const auto& a = rank.WorldToCamera;
  const auto& b = now.WorldToCamera;
  // trace(R_now R_rank^T) = sum of the products of corresponding entries of the 3x3 parts.
  double trace = 0.0;
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      trace += a[4 * r + c] * b[4 * r + c];
    }
  }
  const double rotation = std::acos(std::min(1.0, std::max(-1.0, 0.5 * (trace - 1.0))));
  if (!(depth > 0.0))
  {
    return std::numeric_limits<double>::infinity();
  }
  const auto p = rank.Center(), q = now.Center();
  const double travel = std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                          (p[2] - q[2]) * (p[2] - q[2])) /
    depth;
  const double angle = std::max(rotation, travel);
  return std::isnan(angle) ? std::numeric_limits<double>::infinity() : angle;
}

//------------------------------------------------------------------------------
namespace
{
void CheckAngles(double reuseAngle, double colorAngle)
{
  if (!(reuseAngle >= 0.0) || !std::isfinite(reuseAngle) || !(colorAngle >= 0.0) ||
    !std::isfinite(colorAngle))
  {
    throw std::invalid_argument("UpdateSplatMovingSet: reuse angle " + std::to_string(reuseAngle) +
      " or colour angle " + std::to_string(colorAngle) + " is not a finite angle >= 0");
  }
}

int UsedDegree(const GaussianCloud& cloud, const RasterSettings& settings)
{
  return std::max(
    0, settings.ShDegree < 0 ? cloud.ShDegree : std::min(settings.ShDegree, cloud.ShDegree));
}

// Whether the published set was made for this cloud, version, SH degree and colour setting.
bool SameScene(const GaussianCloud& cloud,
  std::uint64_t cloudVersion,
  const RasterSettings& settings,
  const SplatMovingSet& set)
{
  const SplatMovingSetOrigin& made = set.Made;
  return set.Generation != 0 && made.Cloud == &cloud && made.CloudVersion == cloudVersion &&
    cloudVersion != 0 && made.ShDegree == UsedDegree(cloud, settings) &&
    made.Colors == settings.ComputeColors;
}
}

//------------------------------------------------------------------------------
bool SplatMovingSetReusable(const GaussianCloud& cloud,
  std::uint64_t cloudVersion,
  const Camera& camera,
  std::size_t budget,
  const RasterSettings& settings,
  double reuseAngle,
  const SplatMovingSet& set,
  double fraction)
{
  // The field of view as tangents: a resized camera (another sample distance) keeps it.
  auto sameFov = [](const Camera& a, const Camera& b)
  {
    return std::abs(a.TanHalfFovX() - b.TanHalfFovX()) <= 1e-9 * a.TanHalfFovX() &&
      std::abs(a.TanHalfFovY() - b.TanHalfFovY()) <= 1e-9 * a.TanHalfFovY();
  };
  const SplatMovingSetOrigin& made = set.Made;
  return reuseAngle > 0.0 && SameScene(cloud, cloudVersion, settings, set) &&
    made.Budget == budget && made.ReuseAngle == reuseAngle && sameFov(made.Rank, camera) &&
    SplatViewChangeAngle(made.Rank, camera, made.Depth) <= fraction * reuseAngle;
}

//------------------------------------------------------------------------------
bool UpdateSplatMovingSet(const GaussianCloud& cloud,
  std::uint64_t cloudVersion,
  const SplatLevelOfDetail& lod,
  const Camera& camera,
  std::size_t budget,
  const RasterSettings& settings,
  double reuseAngle,
  double colorAngle,
  SplatMovingSet& set)
{
  CheckAngles(reuseAngle, colorAngle);
  if (SplatMovingSetReusable(cloud, cloudVersion, camera, budget, settings, reuseAngle, set))
  {
    ++set.Reuses;
    return false;
  }
  BuildSplatMovingSet(
    cloud, cloudVersion, lod, camera, budget, settings, reuseAngle, colorAngle, set);
  PublishSplatMovingSet(set);
  return true;
}

//------------------------------------------------------------------------------
void BuildSplatMovingSet(const GaussianCloud& cloud,
  std::uint64_t cloudVersion,
  const SplatLevelOfDetail& lod,
  const Camera& camera,
  std::size_t budget,
  const RasterSettings& settings,
  double reuseAngle,
  double colorAngle,
  SplatMovingSet& set)
{
  CheckAngles(reuseAngle, colorAngle);
  const auto start = std::chrono::steady_clock::now();
  const int degree = UsedDegree(cloud, settings);
  const bool colors = settings.ComputeColors;
  const bool sameScene = SameScene(cloud, cloudVersion, settings, set);
  // The Gaussians that stay selected keep their colour while the camera of the last full
  // colour evaluation is within the colour angle; the others are gathered from the scene.
  const bool keepColors = colorAngle > 0.0 && sameScene &&
    SplatViewChangeAngle(set.Made.ColorRank, camera, set.Made.Depth) <= colorAngle;
  const int threads = ThreadCount(settings.Threads);
  if (!sameScene)
  {
    set.Selection.Boundary = 0; // (another scene's boundary says nothing about this one)
  }
  // The new set goes into the spare buffers; the published Subset and Compact are only read
  // (frames may project them meanwhile).
  std::vector<std::uint32_t>& subset = set.PreviousSubset;
  SelectSplatsInCells(cloud, lod, camera, budget, subset, set.Selection, threads, reuseAngle);
  set.LastSelectionMs = MsSince(start);
  const std::size_t m = subset.size();
  const GaussianCloud& prev = set.Compact;
  GaussianCloud& c = set.Previous;
  c.Count = m;
  c.ShDegree = 0;
  c.Ids.clear();
  c.Extra.clear();
  c.Positions.resize(3 * m);
  c.LogScales.resize(3 * m);
  c.Rotations.resize(4 * m);
  c.OpacityLogits.resize(m);
  c.SH.resize(3 * m);
  const bool haveSh = colors &&
    cloud.SH.size() == cloud.Count * 3 * static_cast<std::size_t>(cloud.ShCoefficientCount());
  const std::size_t shStride = 3 * static_cast<std::size_t>(cloud.ShCoefficientCount());
  const auto centre = camera.Center();
  const float campos[3] = {
    static_cast<float>(centre[0]), static_cast<float>(centre[1]), static_cast<float>(centre[2])
  };
  const float c0 = static_cast<float>(sh::C0);
  const auto gatherStart = std::chrono::steady_clock::now();
  std::size_t evaluated = 0;
  // Each thread takes a contiguous part of the new subset: it merges it with the published
  // subset (which Gaussians stay), copies those that stay from the published compact cloud
  // (parameters and kept colour, contiguous), then gathers the others from the scene and
  // evaluates their colour. The scene's Gaussians lie far apart (about 7 cache lines each at
  // SH degree 3): the gather runs over the list of the new ones alone, so that its prefetch
  // reaches Ahead new Gaussians ahead (among every selected one it would reach less than one).
  std::vector<std::vector<std::uint32_t>>& fresh = set.Fresh;
  fresh.resize(static_cast<std::size_t>(threads));
  const std::vector<std::uint32_t>& old = set.Subset;
#pragma omp parallel for schedule(static, 1) num_threads(threads) reduction(+ : evaluated)
  for (int t = 0; t < threads; ++t)
  {
    const std::size_t b = m * static_cast<std::size_t>(t) / static_cast<std::size_t>(threads);
    const std::size_t e = m * static_cast<std::size_t>(t + 1) / static_cast<std::size_t>(threads);
    std::vector<std::uint32_t>& mine = fresh[static_cast<std::size_t>(t)];
    mine.clear();
    std::size_t k = keepColors && b < e
      ? static_cast<std::size_t>(std::lower_bound(old.begin(), old.end(), subset[b]) - old.begin())
      : old.size();
    for (std::size_t j = b; j < e; ++j)
    {
      while (k < old.size() && old[k] < subset[j])
      {
        ++k;
      }
      if (!keepColors || k >= old.size() || old[k] != subset[j])
      {
        mine.push_back(static_cast<std::uint32_t>(j));
        continue;
      }
      std::copy_n(&prev.Positions[3 * k], 3, &c.Positions[3 * j]);
      std::copy_n(&prev.LogScales[3 * k], 3, &c.LogScales[3 * j]);
      std::copy_n(&prev.Rotations[4 * k], 4, &c.Rotations[4 * j]);
      c.OpacityLogits[j] = prev.OpacityLogits[k];
      std::copy_n(&prev.SH[3 * k], 3, &c.SH[3 * j]);
    }
    constexpr std::size_t Ahead = 8;
    const std::size_t count = mine.size();
    evaluated += count;
    for (std::size_t q = 0; q < count; ++q)
    {
      if (q + Ahead < count)
      {
        const std::size_t a = subset[mine[q + Ahead]];
        if (haveSh)
        {
          const char* line = reinterpret_cast<const char*>(&cloud.SH[a * shStride]);
          for (std::size_t o = 0; o < shStride * sizeof(float); o += 64)
          {
            __builtin_prefetch(line + o);
          }
        }
        __builtin_prefetch(&cloud.Positions[3 * a]);
        __builtin_prefetch(&cloud.LogScales[3 * a]);
        __builtin_prefetch(&cloud.Rotations[4 * a]);
        __builtin_prefetch(&cloud.OpacityLogits[a]);
      }
      const std::size_t j = mine[q];
      const std::size_t i = subset[j];
      const float* p = &cloud.Positions[3 * i];
      std::copy_n(p, 3, &c.Positions[3 * j]);
      std::copy_n(&cloud.LogScales[3 * i], 3, &c.LogScales[3 * j]);
      std::copy_n(&cloud.Rotations[4 * i], 4, &c.Rotations[4 * j]);
      c.OpacityLogits[j] = cloud.OpacityLogits[i];
      float rgb[3] = { 0.5f, 0.5f, 0.5f };
      if (haveSh)
      {
        // The projection's colour, seen from this camera (the same function and precision);
        // a non-finite coefficient gives a non-finite colour, which the compact cloud's
        // projection skips as the whole cloud's does.
        ViewColor<float>(&cloud.SH[i * shStride], degree, p, campos, rgb);
      }
      for (int o = 0; o < 3; ++o)
      {
        c.SH[3 * j + o] = haveSh ? (rgb[o] - 0.5f) / c0 : 0.0f;
      }
    }
  }
  // The travel test's scale from a sample (a median needs no more, and sorting every depth
  // would be a serial step of the rebuild).
  const auto& v = camera.WorldToCamera;
  const std::size_t stride = std::max<std::size_t>(1, m / 4096);
  std::vector<float>& depths = set.Depths;
  depths.clear();
  for (std::size_t j = 0; j < m; j += stride)
  {
    const float* p = &c.Positions[3 * j];
    depths.push_back(static_cast<float>(v[8] * p[0] + v[9] * p[1] + v[10] * p[2] + v[11]));
  }
  set.LastGatherMs = MsSince(gatherStart);
  set.LastEvaluated = evaluated;
  // The median depth of those in front (the scale of the travel test).
  auto front = std::partition(depths.begin(), depths.end(), [](float z) { return z > 0.2f; });
  double depth = 0.0;
  if (front != depths.begin())
  {
    auto mid = depths.begin() + (front - depths.begin()) / 2;
    std::nth_element(depths.begin(), mid, front);
    depth = *mid;
  }
  SplatMovingSetOrigin& made = set.Next.Made;
  made.Rank = camera;
  made.ColorRank = keepColors ? set.Made.ColorRank : camera;
  made.Cloud = &cloud;
  made.CloudVersion = cloudVersion;
  made.Budget = budget;
  made.ShDegree = degree;
  made.Colors = colors;
  made.ReuseAngle = reuseAngle;
  made.Depth = depth;
  set.Next.ColorsRefreshed = !keepColors;
  set.Next.Ready = true;
  set.LastRebuildMs = MsSince(start);
}

//------------------------------------------------------------------------------
namespace
{
// Capacity for @p count elements, each of its pages written once (resize's zeros), size kept.
template <typename T>
void Touch(std::vector<T>& v, std::size_t count)
{
  const std::size_t size = v.size();
  if (count > size)
  {
    v.resize(count);
    v.resize(size);
  }
}
}

//------------------------------------------------------------------------------
bool ReserveSplatMovingSet(SplatMovingSet& set, std::size_t count, int threads)
{
  if (set.Generation != 0 || set.Next.Ready)
  {
    return false;
  }
  const int nt = ThreadCount(threads);
  for (auto* v : { &set.Subset, &set.PreviousSubset })
  {
    Touch(*v, count);
  }
  set.Fresh.resize(static_cast<std::size_t>(nt));
  for (auto& v : set.Fresh)
  {
    Touch(v, count / static_cast<std::size_t>(nt) + 1);
  }
  for (GaussianCloud* c : { &set.Compact, &set.Previous })
  {
    Touch(c->Positions, 3 * count);
    Touch(c->LogScales, 3 * count);
    Touch(c->Rotations, 4 * count);
    Touch(c->OpacityLogits, count);
    Touch(c->SH, 3 * count);
  }
  SplatSelectionState& s = set.Selection;
  const std::size_t threadCount = static_cast<std::size_t>(nt);
  for (auto* v : { &s.Candidates, &s.KeptBy, &s.TiesBy })
  {
    v->resize(threadCount);
  }
  // (a thread's share of the candidates is not even: each gets room for most of them)
  for (std::size_t t = 0; t < threadCount; ++t)
  {
    Touch(s.Candidates[t], count + count / 2);
    Touch(s.KeptBy[t], count);
    Touch(s.TiesBy[t], count / 16);
  }
  Touch(s.Kept, count);
  Touch(s.Ties, count / 16);
  Touch(s.Spare, count);
  return true;
}

//------------------------------------------------------------------------------
bool PublishSplatMovingSet(SplatMovingSet& set)
{
  SplatMovingSet::Build& next = set.Next;
  if (!next.Ready)
  {
    return false;
  }
  std::swap(set.Subset, set.PreviousSubset);
  std::swap(set.Compact, set.Previous);
  set.ColorRefreshes += next.ColorsRefreshed ? 1 : 0;
  set.Made = next.Made;
  next.Ready = false;
  // Unique in the process, so that no cache keyed by it mistakes another set's compact cloud
  // (at the same addresses) for this one.
  static std::atomic<std::uint64_t> generations{ 0 };
  set.Generation = ++generations;
  ++set.Rebuilds;
  return true;
}

} // namespace vis4gs

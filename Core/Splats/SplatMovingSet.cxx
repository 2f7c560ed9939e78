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
  return set.Generation != 0 && set.Cloud == &cloud && set.CloudVersion == cloudVersion &&
    cloudVersion != 0 && set.ShDegree == UsedDegree(cloud, settings) &&
    set.Colors == settings.ComputeColors;
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
  return reuseAngle > 0.0 && SameScene(cloud, cloudVersion, settings, set) &&
    set.Budget == budget && set.ReuseAngle == reuseAngle && sameFov(set.Rank, camera) &&
    SplatViewChangeAngle(set.Rank, camera, set.Depth) <= fraction * reuseAngle;
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
    SplatViewChangeAngle(set.ColorRank, camera, set.Depth) <= colorAngle;
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
  // from[j]: Gaussian j's place in the published set (kept colour), or -1.
  std::vector<std::int64_t>& from = set.From;
  from.assign(m, -1);
  if (keepColors)
  {
    const std::vector<std::uint32_t>& old = set.Subset;
    std::size_t k = 0;
    for (std::size_t j = 0; j < m; ++j)
    {
      while (k < old.size() && old[k] < subset[j])
      {
        ++k;
      }
      if (k < old.size() && old[k] == subset[j])
      {
        from[j] = static_cast<std::int64_t>(k);
      }
    }
  }
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
  const auto& v = camera.WorldToCamera;
  // The travel test's scale from a sample (a median needs no more, and sorting every depth
  // would be a serial step of the rebuild).
  const std::size_t stride = std::max<std::size_t>(1, m / 4096);
  std::vector<float>& depths = set.Depths;
  depths.resize((m + stride - 1) / stride);
  constexpr std::size_t Ahead = 8;
  const std::int64_t count = static_cast<std::int64_t>(m);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::int64_t jj = 0; jj < count; ++jj)
  {
    const std::size_t j = static_cast<std::size_t>(jj);
    const std::size_t i = subset[j];
    if (j + Ahead < m && from[j + Ahead] < 0)
    {
      // The gather is bound by memory latency (the selected Gaussians lie about a dozen apart
      // in the scene's arrays, 192 B of SH each at degree 3): ask for a later one's lines now.
      const std::size_t a = subset[j + Ahead];
      if (haveSh)
      {
        const char* q = reinterpret_cast<const char*>(&cloud.SH[a * shStride]);
        for (std::size_t b = 0; b < shStride * sizeof(float); b += 64)
        {
          __builtin_prefetch(q + b);
        }
      }
      __builtin_prefetch(&cloud.Positions[3 * a]);
      __builtin_prefetch(&cloud.LogScales[3 * a]);
      __builtin_prefetch(&cloud.Rotations[4 * a]);
      __builtin_prefetch(&cloud.OpacityLogits[a]);
    }
    const std::int64_t k = from[j];
    // (the previous set's compact copy holds the same parameters, contiguous)
    const GaussianCloud& src = k >= 0 ? prev : cloud;
    const std::size_t at = k >= 0 ? static_cast<std::size_t>(k) : i;
    const float* p = &src.Positions[3 * at];
    std::copy_n(p, 3, &c.Positions[3 * j]);
    std::copy_n(&src.LogScales[3 * at], 3, &c.LogScales[3 * j]);
    std::copy_n(&src.Rotations[4 * at], 4, &c.Rotations[4 * j]);
    c.OpacityLogits[j] = src.OpacityLogits[at];
    if (k >= 0)
    {
      std::copy_n(&prev.SH[3 * at], 3, &c.SH[3 * j]);
    }
    else
    {
      float rgb[3] = { 0.5f, 0.5f, 0.5f };
      if (haveSh)
      {
        // The projection's colour, seen from this camera (the same function and precision);
        // a non-finite coefficient gives a non-finite colour, which the compact cloud's
        // projection skips as the whole cloud's does.
        ViewColor<float>(&cloud.SH[i * shStride], degree, p, campos, rgb);
      }
      for (int q = 0; q < 3; ++q)
      {
        c.SH[3 * j + q] = haveSh ? (rgb[q] - 0.5f) / c0 : 0.0f;
      }
    }
    if (j % stride == 0)
    {
      depths[j / stride] = static_cast<float>(v[8] * p[0] + v[9] * p[1] + v[10] * p[2] + v[11]);
    }
  }
  // The median depth of those in front (the scale of the travel test).
  auto front = std::partition(depths.begin(), depths.end(), [](float z) { return z > 0.2f; });
  double depth = 0.0;
  if (front != depths.begin())
  {
    auto mid = depths.begin() + (front - depths.begin()) / 2;
    std::nth_element(depths.begin(), mid, front);
    depth = *mid;
  }
  SplatMovingSet::Build& next = set.Next;
  next.Rank = camera;
  next.ColorRank = keepColors ? set.ColorRank : camera;
  next.ColorsRefreshed = !keepColors;
  next.Cloud = &cloud;
  next.CloudVersion = cloudVersion;
  next.Budget = budget;
  next.ShDegree = degree;
  next.Colors = colors;
  next.ReuseAngle = reuseAngle;
  next.Depth = depth;
  next.Ready = true;
  set.LastRebuildMs = MsSince(start);
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
  set.Rank = next.Rank;
  set.ColorRank = next.ColorRank;
  set.Cloud = next.Cloud;
  set.CloudVersion = next.CloudVersion;
  set.Budget = next.Budget;
  set.ShDegree = next.ShDegree;
  set.Colors = next.Colors;
  set.ReuseAngle = next.ReuseAngle;
  set.Depth = next.Depth;
  next.Ready = false;
  // Unique in the process, so that no cache keyed by it mistakes another set's compact cloud
  // (at the same addresses) for this one.
  static std::atomic<std::uint64_t> generations{ 0 };
  set.Generation = ++generations;
  ++set.Rebuilds;
  return true;
}

} // namespace vis4gs

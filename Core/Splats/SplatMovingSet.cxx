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
  // The Gaussians that stay selected keep their colour (and their slot) while the camera of the
  // last full colour evaluation is within the colour angle; the others are gathered from the
  // scene.
  const bool keepColors = colorAngle > 0.0 && sameScene &&
    SplatViewChangeAngle(set.Made.ColorRank, camera, set.Made.Depth) <= colorAngle;
  const int threads = ThreadCount(settings.Threads);
  const std::size_t threadCount = static_cast<std::size_t>(threads);
  if (!sameScene)
  {
    set.Selection.Boundary = 0; // (another scene's boundary says nothing about this one)
  }
  // The new selection goes into the scratch and set.Next; the published Subset, Sorted and
  // Compact are only read (frames may project them meanwhile).
  std::vector<std::uint32_t>& selected = set.Selected;
  SelectSplatsInCells(cloud, lod, camera, budget, selected, set.Selection, threads, reuseAngle);
  set.LastSelectionMs = MsSince(start);
  const std::size_t m = selected.size();
  SplatMovingSet::Build& next = set.Next;
  next.Full = !keepColors;
  next.Threads = threads;
  next.Count = m;
  // fresh[t]: the places in the selection of the Gaussians thread t gathers from the scene.
  std::vector<std::vector<std::uint32_t>>& fresh = set.Fresh;
  fresh.resize(threadCount);
  std::vector<std::uint32_t>& slotOf = set.SlotOf;
  slotOf.resize(m);
  const std::vector<std::uint64_t>& sorted = set.Sorted;
  const std::size_t published = keepColors ? set.Subset.size() : 0;
  std::vector<std::uint8_t>& stay = set.Stay;
  stay.assign(published, 0);
  const std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
  // Each thread merges a contiguous part of the selection with the published set (ascending
  // indices both): a Gaussian found there keeps its slot, the others are new.
#pragma omp parallel for schedule(static, 1) num_threads(threads)
  for (int t = 0; t < threads; ++t)
  {
    const std::size_t b = m * static_cast<std::size_t>(t) / threadCount;
    const std::size_t e = m * static_cast<std::size_t>(t + 1) / threadCount;
    std::vector<std::uint32_t>& mine = fresh[static_cast<std::size_t>(t)];
    mine.clear();
    std::size_t k = keepColors && b < e
      ? static_cast<std::size_t>(
          std::lower_bound(
            sorted.begin(), sorted.end(), static_cast<std::uint64_t>(selected[b]) << 32) -
          sorted.begin())
      : sorted.size();
    for (std::size_t j = b; j < e; ++j)
    {
      const std::uint64_t index = selected[j];
      while (k < sorted.size() && (sorted[k] >> 32) < index)
      {
        ++k;
      }
      if (keepColors && k < sorted.size() && (sorted[k] >> 32) == index)
      {
        const std::uint32_t slot = static_cast<std::uint32_t>(sorted[k]);
        slotOf[j] = slot;
        stay[slot] = 1;
      }
      else
      {
        slotOf[j] = none;
        mine.push_back(static_cast<std::uint32_t>(j));
      }
    }
  }
  std::size_t newCount = 0;
  for (const auto& f : fresh)
  {
    newCount += f.size();
  }
  // The slots to fill below the new count: those whose Gaussian leaves, and the new ones beyond
  // the published count. The new Gaussians take the first of them; the Gaussians that stay in
  // slots beyond the new count move into the rest (as many).
  std::vector<std::uint32_t>& free = set.Free;
  free.clear();
  next.MoveFrom.clear();
  next.MoveTo.clear();
  if (keepColors)
  {
    for (std::size_t slot = 0; slot < m; ++slot)
    {
      if (slot >= published || !stay[slot])
      {
        free.push_back(static_cast<std::uint32_t>(slot));
      }
    }
    for (std::size_t slot = m; slot < published; ++slot)
    {
      if (stay[slot])
      {
        next.MoveFrom.push_back(static_cast<std::uint32_t>(slot));
      }
    }
    for (std::size_t r = 0; r < next.MoveFrom.size(); ++r)
    {
      next.MoveTo.push_back(free[newCount + r]);
    }
  }
  // The Gaussians gathered from the scene: the new ones, or every one (Full) in order.
  GaussianCloud& c = next.Patch;
  c.Count = newCount;
  c.ShDegree = 0;
  c.Ids.clear();
  c.Extra.clear();
  c.Positions.resize(3 * newCount);
  c.LogScales.resize(3 * newCount);
  c.Rotations.resize(4 * newCount);
  c.OpacityLogits.resize(newCount);
  c.SH.resize(3 * newCount);
  next.PatchSlots.resize(keepColors ? newCount : 0);
  next.PatchIndices.resize(keepColors ? newCount : 0);
  const bool haveSh = colors &&
    cloud.SH.size() == cloud.Count * 3 * static_cast<std::size_t>(cloud.ShCoefficientCount());
  const std::size_t shStride = 3 * static_cast<std::size_t>(cloud.ShCoefficientCount());
  const auto centre = camera.Center();
  const float campos[3] = {
    static_cast<float>(centre[0]), static_cast<float>(centre[1]), static_cast<float>(centre[2])
  };
  const float c0 = static_cast<float>(sh::C0);
  const auto gatherStart = std::chrono::steady_clock::now();
  // The scene's Gaussians lie far apart (about 7 cache lines each at SH degree 3): each thread
  // runs over its list of new ones, asking for the lines of the one Ahead places on.
#pragma omp parallel for schedule(static, 1) num_threads(threads)
  for (int t = 0; t < threads; ++t)
  {
    const std::vector<std::uint32_t>& mine = fresh[static_cast<std::size_t>(t)];
    std::size_t q0 = 0; // (this thread's first place in the patch)
    for (int u = 0; u < t; ++u)
    {
      q0 += fresh[static_cast<std::size_t>(u)].size();
    }
    constexpr std::size_t Ahead = 8;
    const std::size_t count = mine.size();
    for (std::size_t r = 0; r < count; ++r)
    {
      if (r + Ahead < count)
      {
        const std::size_t a = selected[mine[r + Ahead]];
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
      const std::size_t q = q0 + r;
      const std::size_t i = selected[mine[r]];
      if (keepColors)
      {
        next.PatchSlots[q] = free[q];
        next.PatchIndices[q] = static_cast<std::uint32_t>(i);
      }
      const float* p = &cloud.Positions[3 * i];
      std::copy_n(p, 3, &c.Positions[3 * q]);
      std::copy_n(&cloud.LogScales[3 * i], 3, &c.LogScales[3 * q]);
      std::copy_n(&cloud.Rotations[4 * i], 4, &c.Rotations[4 * q]);
      c.OpacityLogits[q] = cloud.OpacityLogits[i];
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
        c.SH[3 * q + o] = haveSh ? (rgb[o] - 0.5f) / c0 : 0.0f;
      }
    }
  }
  set.LastGatherMs = MsSince(gatherStart);
  set.LastEvaluated = newCount;
  // The published Sorted after the publication: each selected Gaussian with its slot.
  next.Sorted.resize(m);
  {
    std::size_t q = 0, moved = 0;
    for (std::size_t j = 0; j < m; ++j)
    {
      std::uint32_t slot = static_cast<std::uint32_t>(j);
      if (keepColors)
      {
        slot = slotOf[j];
        if (slot == none)
        {
          slot = free[q++];
        }
        else if (slot >= m)
        {
          // (MoveFrom ascends)
          moved = static_cast<std::size_t>(
            std::lower_bound(next.MoveFrom.begin(), next.MoveFrom.end(), slot) -
            next.MoveFrom.begin());
          slot = next.MoveTo[moved];
        }
      }
      next.Sorted[j] = (static_cast<std::uint64_t>(selected[j]) << 32) | slot;
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
    const float* p = &cloud.Positions[3 * static_cast<std::size_t>(selected[j])];
    depths.push_back(static_cast<float>(v[8] * p[0] + v[9] * p[1] + v[10] * p[2] + v[11]));
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
  SplatMovingSetOrigin& made = next.Made;
  made.Rank = camera;
  made.ColorRank = keepColors ? set.Made.ColorRank : camera;
  made.Cloud = &cloud;
  made.CloudVersion = cloudVersion;
  made.Budget = budget;
  made.ShDegree = degree;
  made.Colors = colors;
  made.ReuseAngle = reuseAngle;
  made.Depth = depth;
  next.ColorsRefreshed = !keepColors;
  next.Ready = true;
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
  for (auto* v : { &set.Subset, &set.Selected, &set.SlotOf, &set.Free })
  {
    Touch(*v, count);
  }
  for (auto* v : { &set.Sorted, &set.Next.Sorted })
  {
    Touch(*v, count);
  }
  Touch(set.Stay, count);
  for (auto* v : { &set.Next.PatchSlots, &set.Next.PatchIndices })
  {
    Touch(*v, count);
  }
  set.Fresh.resize(static_cast<std::size_t>(nt));
  for (auto& v : set.Fresh)
  {
    Touch(v, count / static_cast<std::size_t>(nt) + 1);
  }
  for (GaussianCloud* c : { &set.Compact, &set.Next.Patch })
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
  GaussianCloud& c = set.Compact;
  const std::size_t m = next.Count;
  if (next.Full)
  {
    std::swap(c, next.Patch);
    set.Subset.resize(m);
    for (std::size_t j = 0; j < m; ++j)
    {
      set.Subset[j] = static_cast<std::uint32_t>(next.Sorted[j] >> 32);
    }
    set.Changed.clear();
    set.AllChanged = true;
  }
  else
  {
    auto copy = [&c](const GaussianCloud& from, std::size_t a, std::size_t b)
    {
      std::copy_n(&from.Positions[3 * a], 3, &c.Positions[3 * b]);
      std::copy_n(&from.LogScales[3 * a], 3, &c.LogScales[3 * b]);
      std::copy_n(&from.Rotations[4 * a], 4, &c.Rotations[4 * b]);
      c.OpacityLogits[b] = from.OpacityLogits[a];
      std::copy_n(&from.SH[3 * a], 3, &c.SH[3 * b]);
    };
    const auto resizeTo = [&](std::size_t n)
    {
      c.Positions.resize(3 * n);
      c.LogScales.resize(3 * n);
      c.Rotations.resize(4 * n);
      c.OpacityLogits.resize(n);
      c.SH.resize(3 * n);
      set.Subset.resize(n);
    };
    resizeTo(std::max(m, c.Count));
    // The Gaussians beyond the new count that stay move down first, then the new ones land.
    for (std::size_t r = 0; r < next.MoveFrom.size(); ++r)
    {
      copy(c, next.MoveFrom[r], next.MoveTo[r]);
      set.Subset[next.MoveTo[r]] = set.Subset[next.MoveFrom[r]];
    }
    const std::int64_t count = static_cast<std::int64_t>(next.PatchSlots.size());
#pragma omp parallel for schedule(static) num_threads(next.Threads)
    for (std::int64_t qq = 0; qq < count; ++qq)
    {
      const std::size_t q = static_cast<std::size_t>(qq);
      copy(next.Patch, q, next.PatchSlots[q]);
      set.Subset[next.PatchSlots[q]] = next.PatchIndices[q];
    }
    c.Count = m;
    resizeTo(m);
    set.Changed.assign(next.PatchSlots.begin(), next.PatchSlots.end());
    set.Changed.insert(set.Changed.end(), next.MoveTo.begin(), next.MoveTo.end());
    set.AllChanged = false;
  }
  std::swap(set.Sorted, next.Sorted);
  set.ColorRefreshes += next.ColorsRefreshed ? 1 : 0;
  set.Made = next.Made;
  next.Ready = false;
  // Unique in the process, so that no cache keyed by it mistakes another set's compact cloud
  // (at the same addresses) for this one.
  static std::atomic<std::uint64_t> generations{ 0 };
  set.PreviousGeneration = set.Generation;
  set.Generation = ++generations;
  ++set.Rebuilds;
  return true;
}

//------------------------------------------------------------------------------
void ProjectSplatMovingSet(const SplatMovingSet& set,
  const Camera& camera,
  const RasterSettings& settings,
  ViewProjection<float>& projection,
  PreparedCloudCache& cache)
{
  if (!set.AllChanged)
  {
    RefreshPreparedCloud(
      cache, set.Compact, set.PreviousGeneration, set.Generation, set.Changed, settings);
  }
  ProjectGaussians(set.Compact, camera, settings, projection, cache, set.Generation);
}

} // namespace vis4gs

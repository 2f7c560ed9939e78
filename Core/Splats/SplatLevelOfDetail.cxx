// SPDX-License-Identifier: BSD-3-Clause
#include "SplatLevelOfDetail.h"

#include "GaussianMath.h"
#include "ThreadCount.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

namespace vis4gs
{
namespace
{
constexpr std::size_t Bins = 32768;
constexpr std::uint32_t RingBit = 0x8000;
}

//------------------------------------------------------------------------------
void PrepareSplatLevelOfDetail(const GaussianCloud& cloud, SplatLevelOfDetail& lod, int threads)
{
  const std::size_t n = cloud.Count;
  lod.Mass.assign(n, 0.0f);
  lod.Reach.assign(n, 0.0f);
  if (cloud.Positions.size() != 3 * n || cloud.LogScales.size() != 3 * n ||
    cloud.Rotations.size() != 4 * n || cloud.OpacityLogits.size() != n)
  {
    return;
  }
  const std::int64_t count = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static) num_threads(ThreadCount(threads))
  for (std::int64_t ii = 0; ii < count; ++ii)
  {
    const std::size_t i = static_cast<std::size_t>(ii);
    const float* p = &cloud.Positions[3 * i];
    const float* s = &cloud.LogScales[3 * i];
    const float* q = &cloud.Rotations[4 * i];
    bool finite = std::isfinite(cloud.OpacityLogits[i]);
    for (int k = 0; k < 3; ++k)
    {
      finite = finite && std::isfinite(p[k]) && std::isfinite(s[k]);
    }
    for (int k = 0; k < 4; ++k)
    {
      finite = finite && std::isfinite(q[k]);
    }
    if (!finite)
    {
      continue;
    }
    const double smallest = std::min({ s[0], s[1], s[2] });
    const double largest = std::max({ s[0], s[1], s[2] });
    const double area = std::exp(static_cast<double>(s[0]) + s[1] + s[2] - smallest);
    lod.Mass[i] = static_cast<float>(Sigmoid(static_cast<double>(cloud.OpacityLogits[i])) * area);
    lod.Reach[i] = static_cast<float>(3.0 * std::exp(largest));
  }
}

//------------------------------------------------------------------------------
std::uint32_t SplatContributionKey(float mass, float z)
{
  const float c = mass / (z * z);
  if (!(c > 0.0f)) // also NaN
  {
    return 0;
  }
  std::uint32_t bits;
  std::memcpy(&bits, &c, sizeof(bits));
  return std::max<std::uint32_t>(1, bits >> 16); // positive floats order like their bits
}

//------------------------------------------------------------------------------
std::size_t SelectSplatsForView(const GaussianCloud& cloud,
  const SplatLevelOfDetail& lod,
  const Camera& camera,
  std::size_t budget,
  std::vector<std::uint32_t>& subset,
  int threads,
  double margin,
  std::vector<std::uint16_t>* scratch)
{
  const std::size_t n = cloud.Count;
  if (lod.Mass.size() != n || lod.Reach.size() != n || cloud.Positions.size() != 3 * n)
  {
    throw std::invalid_argument("SelectSplatsForView: the level of detail holds " +
      std::to_string(lod.Mass.size()) + " Gaussians, the cloud " + std::to_string(n));
  }
  const auto& m = camera.WorldToCamera;
  const float r0[4] = { float(m[0]), float(m[1]), float(m[2]), float(m[3]) };
  const float r1[4] = { float(m[4]), float(m[5]), float(m[6]), float(m[7]) };
  const float r2[4] = { float(m[8]), float(m[9]), float(m[10]), float(m[11]) };
  // The field of view's half-angle tangents, as the rasteriser's tile rectangle sees them.
  const float tx = static_cast<float>(camera.Width / (2.0 * camera.Fx));
  const float ty = static_cast<float>(camera.Height / (2.0 * camera.Fy));
  const float cx = std::sqrt(1.0f + tx * tx), cy = std::sqrt(1.0f + ty * ty);
  // The margin's wider frustum (the same test with the widened half-angles).
  const bool ring = margin > 0.0;
  const double half = 1.5; // (below pi/2 so that the tangents stay finite)
  const float mx = static_cast<float>(std::tan(std::min(half, std::atan(double(tx)) + margin)));
  const float my = static_cast<float>(std::tan(std::min(half, std::atan(double(ty)) + margin)));
  const float mcx = std::sqrt(1.0f + mx * mx), mcy = std::sqrt(1.0f + my * my);
  const int nt = ThreadCount(threads);
  const std::int64_t count = static_cast<std::int64_t>(n);
  // Pass 1: the key of every Gaussian (0 outside the frustum) and a histogram per thread of
  // those in the view's own frustum. A key is at most 0x7f80 (the top 16 bits of a positive
  // float), so its bit 15 marks a Gaussian of the margin's ring only.
  std::vector<std::uint16_t> own;
  std::vector<std::uint16_t>& keys = scratch ? *scratch : own;
  keys.resize(n);
  std::vector<std::vector<std::uint32_t>> hist(static_cast<std::size_t>(nt));
  std::size_t inside = 0;
#pragma omp parallel num_threads(nt) reduction(+ : inside)
  {
    std::vector<std::uint32_t>& h = hist[static_cast<std::size_t>(omp_get_thread_num())];
    h.assign(Bins, 0);
#pragma omp for schedule(static)
    for (std::int64_t ii = 0; ii < count; ++ii)
    {
      const std::size_t i = static_cast<std::size_t>(ii);
      const float* p = &cloud.Positions[3 * i];
      const float z = r2[0] * p[0] + r2[1] * p[1] + r2[2] * p[2] + r2[3];
      const float x = r0[0] * p[0] + r0[1] * p[1] + r0[2] * p[2] + r0[3];
      const float y = r1[0] * p[0] + r1[1] * p[1] + r1[2] * p[2] + r1[3];
      const float reach = lod.Reach[i];
      // The sphere of radius reach misses the frustum when it lies wholly beyond a side
      // plane (distance of the centre to the plane x = tx z is (x - tx z) / sqrt(1 + tx^2)).
      const bool in =
        z > 0.2f && std::abs(x) - tx * z <= reach * cx && std::abs(y) - ty * z <= reach * cy;
      const bool near = ring && !in && z > 0.2f && std::abs(x) - mx * z <= reach * mcx &&
        std::abs(y) - my * z <= reach * mcy;
      std::uint32_t key = in || near ? SplatContributionKey(lod.Mass[i], z) : 0;
      key = std::min<std::uint32_t>(key, RingBit - 1);
      keys[i] = static_cast<std::uint16_t>(key | (near ? RingBit : 0));
      if (!near)
      {
        ++h[key];
        inside += key > 0 ? 1 : 0;
      }
    }
  }
  std::vector<std::uint64_t> total(Bins, 0);
  for (const auto& h : hist)
  {
    for (std::size_t b = 0; b < Bins; ++b)
    {
      total[b] += h[b];
    }
  }
  // The boundary key: every key above it is kept, and those equal to it in index order until
  // the budget is reached.
  std::uint32_t boundary = 1;
  std::size_t above = 0, take = total[1];
  if (budget > 0)
  {
    for (std::size_t b = Bins - 1; b >= 1; --b)
    {
      if (above + total[b] >= budget)
      {
        boundary = static_cast<std::uint32_t>(b);
        take = budget - above;
        break;
      }
      above += total[b];
    }
  }
  subset.clear();
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::uint32_t key = keys[i] & (RingBit - 1);
    if (keys[i] & RingBit)
    {
      if (key >= boundary && key > 0)
      {
        subset.push_back(static_cast<std::uint32_t>(i));
      }
    }
    else if (key > boundary || (key == boundary && take > 0))
    {
      take -= key == boundary ? 1 : 0;
      subset.push_back(static_cast<std::uint32_t>(i));
    }
  }
  return inside;
}

} // namespace vis4gs

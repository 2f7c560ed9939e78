// SPDX-License-Identifier: BSD-3-Clause
#include "SplatSort.h"

#include "RadixSort.h"
#include "ThreadCount.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace vis4gs
{
namespace
{
std::uint32_t FloatBits(float f)
{
  std::uint32_t u;
  std::memcpy(&u, &f, sizeof(u));
  return u;
}

void CheckCount(std::size_t n)
{
  if (n > std::numeric_limits<std::uint32_t>::max())
  {
    throw std::invalid_argument(
      "SortBackToFront: " + std::to_string(n) + " Gaussians exceed the limit of 2^32-1");
  }
}

bool Drawable(float depth, std::size_t i, const SplatSortOptions& options)
{
  // !(depth <= near) would keep NaN; finite and strictly beyond the near plane only.
  return depth > options.NearPlane && std::isfinite(depth) &&
    (options.Keep == nullptr || options.Keep[i] != 0);
}
} // namespace

//------------------------------------------------------------------------------
void ComputeViewDepths(const float* positions,
  std::size_t count,
  const std::array<double, 16>& worldToCamera,
  std::vector<float>& depths,
  int threads)
{
  depths.resize(count);
  const float r0 = static_cast<float>(worldToCamera[8]);
  const float r1 = static_cast<float>(worldToCamera[9]);
  const float r2 = static_cast<float>(worldToCamera[10]);
  const float t = static_cast<float>(worldToCamera[11]);
  const std::int64_t n = static_cast<std::int64_t>(count);
  float* out = depths.data();
#pragma omp parallel for num_threads(ThreadCount(threads)) schedule(static)
  for (std::int64_t i = 0; i < n; ++i)
  {
    const float* p = positions + 3 * i;
    out[i] = r0 * p[0] + r1 * p[1] + r2 * p[2] + t;
  }
}

//------------------------------------------------------------------------------
void SortBackToFront(const std::vector<float>& depths,
  std::vector<std::uint32_t>& order,
  const SplatSortOptions& options)
{
  const std::size_t n = depths.size();
  CheckCount(n);
  const int threads =
    static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(ThreadCount(options.Threads)),
      std::max<std::size_t>(1, n / 4096 + 1)));

  // 1. Compaction of the drawable Gaussians into keys (depth bits << 32 | index), in index
  // order; the bits of positive depths order like the values.
  std::vector<std::size_t> kept(static_cast<std::size_t>(threads) + 1, 0);
  std::vector<std::uint64_t> keys; // keys, then the sort's scratch
  std::uint32_t any = 0, all = ~0u;
  // The team may be smaller than asked (OMP_THREAD_LIMIT, OMP_DYNAMIC, a call from inside
  // another parallel region): the ranges are those of the team OpenMP gives, or the ranges
  // of the threads that did not start would be left out of the order.
  int team = threads;
#pragma omp parallel num_threads(threads) reduction(| : any) reduction(& : all)
  {
    const int size = omp_get_num_threads();
    const int t = omp_get_thread_num();
    const std::size_t b = n * t / size, e = n * (t + 1) / size;
    std::size_t c = 0;
    for (std::size_t i = b; i < e; ++i)
    {
      c += Drawable(depths[i], i, options) ? 1 : 0;
    }
    kept[t + 1] = c;
#pragma omp barrier
#pragma omp single
    {
      team = size;
      for (int k = 0; k < size; ++k)
      {
        kept[k + 1] += kept[k];
      }
      keys.resize(2 * kept[size]);
    }
    std::size_t o = kept[t];
    for (std::size_t i = b; i < e; ++i)
    {
      if (Drawable(depths[i], i, options))
      {
        const std::uint32_t bits = FloatBits(depths[i]);
        any |= bits;
        all &= bits;
        keys[o++] = (static_cast<std::uint64_t>(bits) << 32) | i;
      }
    }
  }
  const std::size_t m = kept[team];

  // 2. Stable radix sort on the depth bits that differ: ascending depth, ties in index order.
  const std::uint64_t* sorted = RadixSortKeys(keys.data(),
    keys.data() + m,
    static_cast<std::int64_t>(m),
    32,
    32 + DifferingBits(any, all),
    threads);

  // 3. Back to front is the exact reverse.
  order.resize(m);
  const std::int64_t mm = static_cast<std::int64_t>(m);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t i = 0; i < mm; ++i)
  {
    order[i] = static_cast<std::uint32_t>(sorted[mm - 1 - i]);
  }
}

//------------------------------------------------------------------------------
void SortBackToFrontStd(const std::vector<float>& depths,
  std::vector<std::uint32_t>& order,
  const SplatSortOptions& options)
{
  const std::size_t n = depths.size();
  CheckCount(n);
  std::vector<std::pair<float, std::uint32_t>> pairs;
  pairs.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    if (Drawable(depths[i], i, options))
    {
      pairs.emplace_back(depths[i], static_cast<std::uint32_t>(i));
    }
  }
  std::sort(pairs.begin(),
    pairs.end(),
    [](const std::pair<float, std::uint32_t>& a, const std::pair<float, std::uint32_t>& b)
    { return a.first > b.first || (a.first == b.first && a.second > b.second); });
  order.resize(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i)
  {
    order[i] = pairs[i].second;
  }
}

} // namespace vis4gs

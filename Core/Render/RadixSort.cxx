// SPDX-License-Identifier: BSD-3-Clause
#include "RadixSort.h"

#include <omp.h>

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace vis4gs
{

//------------------------------------------------------------------------------
// Per chunk and pass a histogram, then bucket-major chunk-minor offsets, then each chunk
// scatters its keys in order: stable, and the result does not depend on the chunk count.
const std::uint64_t* RadixSortKeys(std::uint64_t* keys,
  std::uint64_t* tmp,
  std::int64_t n,
  int lo,
  int hi,
  int chunks)
{
  const int bits = hi - lo;
  if (bits <= 0 || n < 2)
  {
    return keys;
  }
  const int passes = (bits + 10) / 11;
  const int width = (bits + passes - 1) / passes;
  const std::size_t buckets = std::size_t(1) << width;
  const std::uint64_t mask = buckets - 1;
  std::vector<std::uint64_t> hist(static_cast<std::size_t>(chunks) * buckets);
  std::uint64_t* from = keys;
  std::uint64_t* to = tmp;
  for (int pass = 0; pass < passes; ++pass)
  {
    const int shift = lo + pass * width;
#pragma omp parallel for schedule(static, 1) num_threads(chunks)
    for (int c = 0; c < chunks; ++c)
    {
      std::uint64_t* h = &hist[static_cast<std::size_t>(c) * buckets];
      std::fill(h, h + buckets, 0);
      const std::int64_t b = n * c / chunks, e = n * (c + 1) / chunks;
      for (std::int64_t k = b; k < e; ++k)
      {
        ++h[(from[k] >> shift) & mask];
      }
    }
    std::uint64_t running = 0;
    for (std::size_t d = 0; d < buckets; ++d)
    {
      for (int c = 0; c < chunks; ++c)
      {
        std::uint64_t& h = hist[static_cast<std::size_t>(c) * buckets + d];
        const std::uint64_t k = h;
        h = running;
        running += k;
      }
    }
#pragma omp parallel for schedule(static, 1) num_threads(chunks)
    for (int c = 0; c < chunks; ++c)
    {
      std::uint64_t* h = &hist[static_cast<std::size_t>(c) * buckets];
      const std::int64_t b = n * c / chunks, e = n * (c + 1) / chunks;
      for (std::int64_t k = b; k < e; ++k)
      {
        const std::uint64_t key = from[k];
        to[h[(key >> shift) & mask]++] = key;
      }
    }
    std::swap(from, to);
  }
  return from;
}

} // namespace vis4gs

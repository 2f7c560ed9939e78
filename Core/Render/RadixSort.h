// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file RadixSort.h
 * @brief The one radix sort of Vis4GS: the rasteriser's (depth, index) order, the many-view
 * renderer's and the splat mapper's back-to-front order all sort 64-bit keys with it.
 *
 * The callers put a float depth's bit pattern (positive depths order like their bits) in the
 * upper 32 bits and a position in the lower 32 bits, in ascending position order, then sort
 * on the depth bits that differ: a stable sort leaves ties in position order, which is the
 * reference's tie rule (reference §2.5).
 */
#ifndef vis4gs_RadixSort_h
#define vis4gs_RadixSort_h

#include <cstdint>

namespace vis4gs
{

/**
 * Stable parallel LSD radix sort of the @p n 64-bit keys at @p keys on bits [@p lo, @p hi)
 * (the other bits equal in every key, or not to be sorted on), in @p chunks contiguous parts
 * sorted by OpenMP threads, with digits of at most 11 bits. @p scratch holds n keys. Returns
 * the buffer holding the sorted keys (@p keys or @p scratch).
 */
const std::uint64_t* RadixSortKeys(std::uint64_t* keys,
  std::uint64_t* scratch,
  std::int64_t n,
  int lo,
  int hi,
  int chunks);

/// Number of low bits that hold every difference between 32-bit values whose OR is @p any
/// and whose AND is @p all (the highest bit set in one value and clear in another, plus 1).
inline int DifferingBits(std::uint32_t any, std::uint32_t all)
{
  const std::uint32_t differ = any & ~all;
  int bits = 0;
  while (bits < 32 && (differ >> bits) != 0)
  {
    ++bits;
  }
  return bits;
}

} // namespace vis4gs

#endif

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatSort.h
 * @brief Per-frame depth ordering of Gaussians for the GPU splat renderer: view depths and a
 * parallel LSD radix sort, back to front.
 *
 * The reference rasteriser blends each tile's Gaussians front to back in the order of the
 * view-space z of their centres, ties broken by Gaussian index (reference §2.5). Blending
 * back to front with premultiplied colour (dst = c*alpha + (1 - alpha)*dst) gives the same
 * sum when the order is exactly the reverse, so SortBackToFront() returns depth descending,
 * ties by index descending. Gaussians at or behind the reference near plane (z <= 0.2), with
 * a non-finite depth, or masked out are left out of the order: they are never drawn.
 */
#ifndef vis4gs_SplatSort_h
#define vis4gs_SplatSort_h

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vis4gs
{

/**
 * View-space z of each of @p count positions (3 floats each): row 2 of the row-major
 * world-to-camera matrix applied in float in the reference's order
 * (R20 x + R21 y + R22 z + t_z). Parallel with OpenMP (@p threads 0 = OpenMP's default).
 */
void ComputeViewDepths(const float* positions,
  std::size_t count,
  const std::array<double, 16>& worldToCamera,
  std::vector<float>& depths,
  int threads = 0);

/// Options of SortBackToFront().
struct SplatSortOptions
{
  /// Depths at or below this are culled (the reference's near cull). Default 0.2.
  float NearPlane = 0.2f;
  /// Optional mask, one byte per Gaussian; 0 leaves the Gaussian out. Default none.
  const std::uint8_t* Keep = nullptr;
  /// OpenMP threads; 0 uses OpenMP's default.
  int Threads = 0;
};

/**
 * Fills @p order with the indices of the drawable Gaussians, back to front: depth
 * descending, ties by index descending. The rasteriser's parallel stable LSD radix sort
 * (RadixSort.h) on the float bit patterns (which order like the values for the positive
 * depths kept), on the bits that differ between the depths only. Throws std::invalid_argument for
 * more than 2^32 - 1 Gaussians.
 */
void SortBackToFront(const std::vector<float>& depths,
  std::vector<std::uint32_t>& order,
  const SplatSortOptions& options = {});

/// The straightforward implementation (std::sort on (depth, index) pairs, one thread); the
/// same result as SortBackToFront(). Used by the tests and as the benchmark's baseline.
void SortBackToFrontStd(const std::vector<float>& depths,
  std::vector<std::uint32_t>& order,
  const SplatSortOptions& options = {});

} // namespace vis4gs

#endif

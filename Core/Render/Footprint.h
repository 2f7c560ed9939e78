// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Footprint.h
 * @brief Per-Gaussian footprint statistics of one view (DESIGN §4): |Omega(g,v)| and the
 * sum of a per-pixel map over Omega(g,v), without compositing.
 *
 * Omega(g,v) (mode Rasterizer, the exact definition): the pixels inside the image and inside
 * g's tile rectangle where the rasteriser's kernel gives power <= 0 and
 * alpha = min(0.99, o e^power) >= 1/255, evaluated with exactly the arithmetic of
 * CompositeTiles() (RasterKernel.h) -- whether or not g is occluded there. Only Gaussians
 * with ProjectionStatus::Visible have a non-empty footprint.
 *
 * Mode Ellipse3Sigma (the documented alternative): the pixels inside the image where the
 * dilated 2D Gaussian's Mahalanobis distance is at most 3, i.e. power >= -4.5, whatever the
 * opacity; non-positive-definite conics give an empty footprint.
 *
 * The pass is parallel over Gaussians and costs O(rows + |Omega|) per Gaussian: each row's
 * candidate span is solved analytically from the conic (with a safety margin), and every
 * pixel of the widened span is evaluated exactly, so the result equals a brute-force scan
 * of the tile rectangle (BruteForce = true, used by the tests).
 *
 * Float fast path (AVX2, chosen at run time; KernelIsa = 1 forces the scalar loop):
 *  - a small ellipse (bounding box of the conservative ellipse of RasterBounds.h at most
 *    8 pixels wide and 64 pixels in all, the common case at 1/4 resolution) is evaluated as
 *    one packed box, 8 pixels per vector, rows back to back, with no per-row work;
 *  - wider ellipses use the per-row spans, 8 pixels per vector;
 *  - the alpha test skips the exponential for pixels whose power is more than 1e-4 away
 *    from ln(1/(255 o)) (alpha >= 1/255 is then decided by the power alone, far outside the
 *    rounding of KernelExp and of o * e^power); pixels in that band, and NaN powers, are
 *    evaluated with the kernel's exact float arithmetic (no contraction).
 * Counts are therefore identical to the scalar and brute-force paths. Map sums are
 * accumulated in one fixed order on every path -- row by row from the top, left to right
 * within a row, one Gaussian at a time in a single accumulator -- so they are bit-identical
 * too (the tests check this with NaN/Inf/-0 map values), whatever the thread count.
 */
#ifndef vis4gs_Footprint_h
#define vis4gs_Footprint_h

#include "Rasterizer.h"

#include <cstdint>
#include <vector>

namespace vis4gs
{

enum class FootprintMode : std::uint8_t
{
  Rasterizer = 0,   ///< exact: tile rectangle, power <= 0 and alpha >= 1/255
  Ellipse3Sigma = 1 ///< approximation: power >= -4.5 (3-sigma ellipse), opacity ignored
};

enum class FootprintAccumulation : std::uint8_t
{
  Double = 0, ///< map sums accumulated in double (default)
  Float = 1   ///< map sums accumulated in float (faster, less accurate)
};

struct FootprintOptions
{
  FootprintMode Mode = FootprintMode::Rasterizer;
  FootprintAccumulation Accumulation = FootprintAccumulation::Double;
  /// Evaluate every pixel of the tile rectangle instead of the analytic spans (slow; the
  /// tests use it to check the fast path).
  bool BruteForce = false;
  /// OpenMP threads; 0 uses OpenMP's default.
  int Threads = 0;
  /// Instruction set of the float fast path (KernelIsa.h): 0 = best available (default),
  /// 1 = baseline (the scalar loop), 2 = AVX2 (8 pixels at a time), 3 = AVX2 rows and
  /// AVX-512 packed boxes (16 pixels at a time). Results are bit-identical on every path (counts,
  /// and sums accumulated in the same pixel order); a knob for tests and benchmarks.
  int KernelIsa = 0;
};

struct FootprintStats
{
  std::vector<std::uint32_t> PixelCount; ///< |Omega(g,v)| per Gaussian
  /// Sum of the map over Omega(g,v) per Gaussian; empty when no map was given.
  std::vector<double> MapSum;
  std::uint64_t TotalPixels = 0;     ///< sum of PixelCount
  std::uint64_t EvaluatedPixels = 0; ///< kernels evaluated (work measure)
};

/**
 * Computes the footprint of every Gaussian of @p projection. @p map, when not null, holds
 * Width*Height values, row-major with row 0 at the top (the rasteriser's layout); NaN
 * values in the map propagate into the sums of the Gaussians that cover them only.
 */
template <typename T>
FootprintStats ComputeFootprints(const ViewProjection<T>& projection,
  const FootprintOptions& options = {},
  const float* map = nullptr);

extern template FootprintStats ComputeFootprints<float>(const ViewProjection<float>&,
  const FootprintOptions&,
  const float*);
extern template FootprintStats ComputeFootprints<double>(const ViewProjection<double>&,
  const FootprintOptions&,
  const float*);

} // namespace vis4gs

#endif

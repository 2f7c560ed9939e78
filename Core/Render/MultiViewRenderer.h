// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file MultiViewRenderer.h
 * @brief Renders one Gaussian cloud into many views (float, the reference's precision) and
 * takes the footprint statistics of each view from the same projection, with results
 * bit-identical to ProjectGaussians<float>() + BinGaussians() + CompositeTiles() +
 * ComputeFootprints() (tested on random, stiff and real scenes, every instruction set, 1 and
 * 3 threads), but cheaper when the views are many:
 *
 *  - the view-independent part of the projection (finiteness checks, activated scales,
 *    normalised quaternion, 3D covariance, sigmoid opacity, and the colour when the active SH
 *    degree is 0) is computed once for all views, with the rasteriser's float operations in
 *    the same order;
 *  - the per-view projection runs on 16 Gaussians at once (AVX-512; 2 x 8 with AVX2; a
 *    generic vector path otherwise), each lane repeating the scalar float operations in the
 *    scalar order (no contraction, correctly rounded division and square root, the
 *    reference's double ndc2Pix), so culls, conics, radii and tile rectangles are the
 *    rasteriser's bit for bit; colours of SH degree > 0 use the rasteriser's scalar code;
 *  - each block of 16 projected lanes goes straight into one 64-byte record per Gaussian (no
 *    per-Gaussian projection arrays between), the sort keys live in the kernels' memory until
 *    the kernels are written, tile rectangles take 16 bits a coordinate: about 200 bytes a
 *    Gaussian in all (the view-independent 44 included) when every Gaussian is visible;
 *  - the visible Gaussians are stored in their global (depth, index) order, so every tile's
 *    list (a subsequence of that order, as in BinGaussians()) walks the per-Gaussian data
 *    forwards instead of gathering it at random;
 *  - the per-Gaussian alpha level, span bounds and tile rectangle are computed once per view
 *    and shared by compositing and the footprint pass;
 *  - every buffer is kept from one view to the next (no per-view allocation or page faults).
 *
 * Only float is supported (the scores' exact mode renders in float, as the reference).
 */
#ifndef vis4gs_MultiViewRenderer_h
#define vis4gs_MultiViewRenderer_h

#include "Footprint.h"
#include "Rasterizer.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace vis4gs
{

/**
 * The view-independent preparation (about 48 bytes a Gaussian at SH degree 0, 44 otherwise)
 * shared by processes of one machine that render the same cloud with the same settings (MPI):
 * each prepares its part of the Gaussians into memory they all map, then all read every part.
 * The memory is fresh for one process instead of each, and the preparation's CPU is divided
 * (issue 31: on a virtual machine a first touch costs about 2.3 s of CPU a GiB). The prepared
 * values are the same bits whoever writes them.
 */
struct PreparationShare
{
  /// Called by every process of the group, in the same order, with the same @p bytes: the
  /// group's memory of that size (64-byte aligned, the same bytes in each), or null when it
  /// cannot be made, then null in every process of the group (each prepares alone). Empty:
  /// no sharing.
  std::function<void*(std::size_t bytes)> Map;
  /// Called by every process of the group once it has written its part: returns when every
  /// part is written.
  std::function<void()> Wait;
  /// This process's part of the Gaussians, of Parts equal parts.
  int Part = 0;
  int Parts = 1;
};

class MultiViewRenderer
{
public:
  /**
   * Prepares @p cloud (which must outlive this object and stay unchanged) for rendering with
   * @p settings (background, SH degree, scale modifier, colours, threads, instruction set:
   * KernelIsa 1 = generic vectors, 2 = AVX2, 3 = AVX-512, 0 = best; every path gives the
   * same bits). Throws std::invalid_argument like ProjectGaussians() for a bad cloud (before
   * @p share is used). With @p share's Map, the preparation is the group's (PreparationShare).
   */
  MultiViewRenderer(const GaussianCloud& cloud,
    const RasterSettings& settings = {},
    const PreparationShare& share = {});
  ~MultiViewRenderer();
  MultiViewRenderer(const MultiViewRenderer&) = delete;
  MultiViewRenderer& operator=(const MultiViewRenderer&) = delete;

  /**
   * Projects every Gaussian into @p camera, bins and composites: @p image receives exactly
   * what Rasterize<float>(cloud, camera, settings) gives. The projection is kept for
   * Footprints(). Throws std::invalid_argument like ProjectGaussians() for a bad camera, and
   * for an image over 65535 tiles of 16 pixels wide or high (about 1M pixels).
   */
  void Render(const Camera& camera, RasterImage<float>& image);

  /// Projects only (no binning, no compositing); Composite() and Footprints() may follow.
  void Project(const Camera& camera);

  /**
   * Bins and composites the last projected view (Render() = Project() + Composite()). With
   * @p weights, also its per-Gaussian statistics, input order, as CompositeTiles() fills them
   * (the image is the same bit for bit).
   */
  void Composite(RasterImage<float>& image, GaussianWeightStats* weights = nullptr);

  /**
   * Composite() with the per-Gaussian statistics in the order of SortedIds(): entry s is
   * Gaussian SortedIds()[s]'s, the same values Composite() puts at that Gaussian's index. For a
   * caller that sums them per Gaussian over views: no buffer in input order, and @p weights'
   * buffers are reused from one view to the next.
   */
  void CompositeInSortedOrder(RasterImage<float>& image, GaussianWeightStats& weights);

  /**
   * Footprint statistics of the last projected view: identical (bit for bit, counts and
   * sums) to ComputeFootprints(ProjectGaussians<float>(cloud, camera, settings), options,
   * map), whatever the options (mode, accumulation, brute force, instruction set), which
   * are honoured exactly as ComputeFootprints() honours them.
   */
  void Footprints(const FootprintOptions& options, const float* map, FootprintStats& stats);

  /// Called by AddFootprints() with a visible Gaussian's index, its pixel count and map sum
  /// (FootprintStats' values) and the view's largest pixel count.
  using FootprintAdder = std::function<void(std::uint32_t gaussian,
    std::uint32_t pixelCount,
    double mapSum,
    std::uint32_t largestPixelCount)>;

  /**
   * Footprints() for a caller that sums the statistics over views, without its two vectors of
   * the cloud's size (12 bytes a Gaussian): each visible Gaussian's statistics are kept in
   * place of its projection, then @p add is called once for each visible Gaussian, with the
   * values Footprints() gives it, from several threads (never twice for one Gaussian) when the
   * renderer has more than one. The projection is then spent: Composite(), Footprints() and
   * SetColors() need a new Project().
   */
  void AddFootprints(const FootprintOptions& options, const float* map, const FootprintAdder& add);

  /**
   * Replaces the colours of the last projected view: Gaussian i is drawn with
   * @p rgb[3i..3i+2] (the activated colour, as the rasteriser's after its clamp at 0), for one
   * projection composited in several colourings (score overlays). Composite() then gives
   * exactly what Rasterize<float>() gives for a cloud of SH degree 0 with those colours.
   */
  void SetColors(const float* rgb);

  /// Status counts of the last projected view.
  const ProjectionCounts& Counts() const;

  /// Visible Gaussians of the last projected view, in (depth, index) order.
  const std::vector<std::uint32_t>& SortedIds() const;

  struct Data;

private:
  /// Bins and composites the last view; @p sorted (optional) receives the statistics in
  /// sorted order.
  void CompositeWith(RasterImage<float>& image, GaussianWeightStats* sorted);
  std::unique_ptr<Data> Impl;
};

} // namespace vis4gs

#endif

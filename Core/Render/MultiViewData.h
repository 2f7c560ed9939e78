// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file MultiViewData.h
 * @brief Internal to Core/Render: the buffers of MultiViewRenderer, shared by its projection
 * and compositing (RasterCompositing.cxx) and its footprint pass (Footprint.cxx). Not installed.
 */
#ifndef vis4gs_MultiViewData_h
#define vis4gs_MultiViewData_h

#include "MultiViewRenderer.h"
#include "RasterBounds.h"
#include "RawVector.h"

#include <array>
#include <cstdint>
#include <vector>

namespace vis4gs
{
/// View-independent part of ProjectGaussians<float>, structure of arrays padded to 16 (not
/// cleared on growth: the preparation writes every element, padding included).
struct MultiViewPrepared
{
  raster::internal::RawVector<float> X, Y, Z, S00, S01, S02, S11, S12, S22, Opacity;
  /// 3 per Gaussian when the colour is view-independent (degree 0)
  raster::internal::RawVector<float> Color;
  raster::internal::RawVector<std::int32_t> Valid; ///< -1 finite parameters, 0 not (or padding)
};

/// The projection's lane outputs: 16 Gaussians of one view (MultiViewRenderer, ProjectGaussians).
struct MultiViewProjected
{
  std::vector<std::int32_t> Status;
  std::vector<float> U, V, A, B, C, Depth;
  std::vector<std::int32_t> Radius, X0, Y0, X1, Y1;
  /// Optional (written when T0 is not empty; ProjectGaussians<float>): view x and y, the
  /// dilated 2D covariance, and -1 where the lane reached step 6 (finite, not culled before
  /// the pixel-space mean), else 0.
  std::vector<float> T0, T1, CovA, CovB, CovC;
  std::vector<std::int32_t> Reached;
};

struct MultiViewRenderer::Data
{
  const GaussianCloud* Cloud = nullptr;
  RasterSettings Settings;
  std::size_t Count = 0;
  std::size_t Padded = 0;
  int ShDegree = 0;
  int Threads = 1;
  bool Colors = true;
  bool ViewIndependentColor = true;
  MultiViewPrepared Prepared;
  PreparedView Camera{};
  ViewProjection<float> Frame; ///< the view's parameters (no Gaussians)
  ProjectionCounts Counts;
  bool HasView = false;

  // Visible Gaussians in (depth, index) order: position s holds Gaussian Sorted[s].
  std::vector<std::uint32_t> Sorted;
  raster::internal::RawVector<raster::detail::KernelGaussian<float>> Kernels;
  std::vector<raster::detail::SpanRecord> Bounds; ///< alpha-level spans (compositing)
  /// Tile rectangles in 16 bits per coordinate (Project() refuses grids over 65535 tiles).
  raster::internal::RawVector<std::array<std::uint16_t, 4>> Rects;
  TileBins Bins; ///< Ids are sorted positions s (ascending within every tile)
  /// Composite()'s statistics in sorted order, kept between views.
  GaussianWeightStats SortedWeights;

  // Scratch kept between views.
  /// A Gaussian's projection in one view, one cache line, written straight from the
  /// projection's lanes at the Gaussian's index (no per-Gaussian projection buffer in between:
  /// 48 bytes a Gaussian less). Id is the index, or Invisible when the view does not draw it.
  /// Level: the alpha level min(0, log((1/255) / o)), 0 when o < 1/255.
  struct alignas(64) VisibleRecord
  {
    raster::detail::KernelGaussian<float> Kernel;
    std::array<std::uint16_t, 4> Rect;
    std::int32_t Radius;
    std::uint32_t Id;
    double Level;
  };
  static constexpr std::uint32_t Invisible = 0xffffffffu;
  raster::internal::RawVector<VisibleRecord> Records; ///< index order, padded to 16
  /// Visible Gaussians per projection chunk.
  std::vector<std::uint64_t> ChunkVisible;
  std::vector<std::int64_t> Diff;
};

} // namespace vis4gs

#endif

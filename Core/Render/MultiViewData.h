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
/// cleared: the preparation writes every element, padding included). The arrays are one block,
/// its own or the caller's (MultiViewRenderer's PreparationShare: memory shared by processes).
struct MultiViewPrepared
{
  float *X = nullptr, *Y = nullptr, *Z = nullptr, *S00 = nullptr, *S01 = nullptr, *S02 = nullptr,
        *S11 = nullptr, *S12 = nullptr, *S22 = nullptr, *Opacity = nullptr;
  /// 3 per Gaussian when the colour is view-independent (degree 0), else null
  float* Color = nullptr;
  std::int32_t* Valid = nullptr; ///< -1 finite parameters, 0 not (or padding)
  /// Bytes of the arrays of @p padded Gaussians (a multiple of 16), with or without Color.
  static std::size_t Bytes(std::size_t padded, bool color)
  {
    return (11 + (color ? 3 : 0)) * padded * sizeof(float);
  }
  /// Points the arrays at @p memory (Bytes() of it) or, when null, at a block of its own
  /// (kept when large enough).
  void Allocate(std::size_t padded, bool color, void* memory = nullptr)
  {
    static_assert(sizeof(float) == sizeof(std::int32_t), "one block of 4-byte arrays");
    float* base = static_cast<float*>(memory);
    if (!base)
    {
      raster::internal::ResizeKeep(this->Own, Bytes(padded, color) / sizeof(float));
      base = this->Own.data();
    }
    float** arrays[10] = { &this->X,
      &this->Y,
      &this->Z,
      &this->S00,
      &this->S01,
      &this->S02,
      &this->S11,
      &this->S12,
      &this->S22,
      &this->Opacity };
    for (int a = 0; a < 10; ++a)
    {
      *arrays[a] = base + a * padded;
    }
    this->Valid = reinterpret_cast<std::int32_t*>(base + 10 * padded);
    this->Color = color ? base + 11 * padded : nullptr;
  }

private:
  raster::internal::RawVector<float> Own;
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

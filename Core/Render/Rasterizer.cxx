// SPDX-License-Identifier: BSD-3-Clause
// Rasterize(): the three steps of the forward pass (RasterProjection.cxx,
// RasterBinning.cxx, RasterCompositing.cxx) in one call, and the threading and memory
// helpers they share (RasterInternal.h).
#include "Rasterizer.h"

#include "RasterInternal.h"
#include "ThreadCount.h"

#include <stdexcept>
#include <string>
#if defined(__linux__)
#include <sys/mman.h>
#endif
#include <type_traits>

namespace vis4gs
{

//------------------------------------------------------------------------------
template <typename T>
RasterImage<T> Rasterize(const GaussianCloud& cloud,
  const Camera& camera,
  const RasterSettings& settings,
  ProjectionCounts* counts)
{
  const ViewProjection<T> projection = ProjectGaussians<T>(cloud, camera, settings);
  const TileBins bins = BinGaussians(projection, settings.Threads);
  RasterImage<T> image;
  CompositeTiles(projection, bins, settings, image);
  if (counts)
  {
    *counts = projection.Counts;
  }
  return image;
}

//------------------------------------------------------------------------------
template <typename T>
void Rasterize(const GaussianCloud& cloud,
  const Camera& camera,
  const RasterSettings& settings,
  RasterWorkspace<T>& workspace)
{
  if constexpr (std::is_same<T, float>::value)
  {
    ProjectGaussians(
      cloud, camera, settings, workspace.Projection, workspace.Prepared, workspace.CloudVersion);
  }
  else
  {
    ProjectGaussians<T>(cloud, camera, settings, workspace.Projection);
  }
  BinGaussians(workspace.Projection, settings.Threads, workspace.Bins, workspace.Scratch);
  CompositeTiles(workspace.Projection,
    workspace.Bins,
    settings,
    workspace.Image,
    nullptr,
    nullptr,
    &workspace.Composite);
}

//------------------------------------------------------------------------------
template <typename T>
std::size_t KeepTiles(ViewProjection<T>& projection, const std::vector<std::uint8_t>& tiles)
{
  const std::size_t tx = static_cast<std::size_t>(projection.TilesX);
  const std::size_t ty = static_cast<std::size_t>(projection.TilesY);
  if (tiles.size() != tx * ty)
  {
    throw std::invalid_argument("KeepTiles: " + std::to_string(tiles.size()) +
      " tile flags for a view of " + std::to_string(tx) + "x" + std::to_string(ty) + " tiles");
  }
  // Summed-area table of the chosen tiles: one test per Gaussian whatever its rectangle.
  const std::size_t stride = tx + 1;
  std::vector<std::uint32_t> area(stride * (ty + 1), 0);
  for (std::size_t y = 0; y < ty; ++y)
  {
    for (std::size_t x = 0; x < tx; ++x)
    {
      area[(y + 1) * stride + x + 1] = (tiles[y * tx + x] ? 1u : 0u) + area[y * stride + x + 1] +
        area[(y + 1) * stride + x] - area[y * stride + x];
    }
  }
  auto at = [&](int x, int y)
  { return area[static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(x)]; };
  std::size_t culled = 0;
  for (ProjectedGaussian<T>& g : projection.Gaussians)
  {
    const int* r = g.TileRect;
    if (g.IsVisible() && at(r[2], r[3]) - at(r[0], r[3]) - at(r[2], r[1]) + at(r[0], r[1]) == 0)
    {
      g.Status = ProjectionStatus::OffScreen;
      g.Radius = 0;
      ++culled;
    }
  }
  projection.Counts.Visible -= culled;
  projection.Counts.OffScreen += culled;
  return culled;
}

//------------------------------------------------------------------------------
template <typename T>
void RasterizeTiles(const GaussianCloud& cloud,
  const Camera& camera,
  const RasterSettings& settings,
  const std::vector<std::uint8_t>& tiles,
  RasterWorkspace<T>& workspace)
{
  if constexpr (std::is_same<T, float>::value)
  {
    ProjectGaussians(
      cloud, camera, settings, workspace.Projection, workspace.Prepared, workspace.CloudVersion);
  }
  else
  {
    ProjectGaussians<T>(cloud, camera, settings, workspace.Projection);
  }
  KeepTiles(workspace.Projection, tiles);
  BinGaussians(workspace.Projection, settings.Threads, workspace.Bins, workspace.Scratch);
  CompositeTiles(workspace.Projection,
    workspace.Bins,
    settings,
    workspace.Image,
    nullptr,
    nullptr,
    &workspace.Composite,
    false);
}

//------------------------------------------------------------------------------
namespace raster
{
namespace internal
{
// Asks Linux for transparent huge pages on a large buffer before it is first touched: the
// multi-megabyte buffers of projection and binning otherwise cost one page fault per 4 KiB
// (serial when a std::vector value-initialises them) and a TLB miss on most scattered writes.
// Advisory only: ignored where unsupported, never changes a value.
void HugePages(const void* data, std::size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const std::uintptr_t huge = std::uintptr_t(2) << 20;
  if (data == nullptr || bytes < 2 * huge)
  {
    return;
  }
  const std::uintptr_t a = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t b = (a + huge - 1) & ~(huge - 1), e = (a + bytes) & ~(huge - 1);
  if (e > b)
  {
    madvise(reinterpret_cast<void*>(b), e - b, MADV_HUGEPAGE);
  }
#else
  (void)data;
  (void)bytes;
#endif
}
} // namespace internal
} // namespace raster

template void Rasterize<float>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&,
  RasterWorkspace<float>&);
template void Rasterize<double>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&,
  RasterWorkspace<double>&);
template std::size_t KeepTiles<float>(ViewProjection<float>&, const std::vector<std::uint8_t>&);
template std::size_t KeepTiles<double>(ViewProjection<double>&, const std::vector<std::uint8_t>&);
template void RasterizeTiles<float>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&,
  const std::vector<std::uint8_t>&,
  RasterWorkspace<float>&);
template void RasterizeTiles<double>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&,
  const std::vector<std::uint8_t>&,
  RasterWorkspace<double>&);
template RasterImage<float> Rasterize<float>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&,
  ProjectionCounts*);
template RasterImage<double> Rasterize<double>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&,
  ProjectionCounts*);

} // namespace vis4gs

// SPDX-License-Identifier: BSD-3-Clause
// Rasterize(): the three steps of the forward pass (RasterProjection.cxx,
// RasterBinning.cxx, RasterCompositing.cxx) in one call, and the threading and memory
// helpers they share (RasterInternal.h).
#include "Rasterizer.h"

#include "RasterInternal.h"

#include <omp.h>
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
namespace raster
{
namespace internal
{
int Threads(int requested)
{
  return requested > 0 ? requested : omp_get_max_threads();
}

//------------------------------------------------------------------------------
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
template RasterImage<float> Rasterize<float>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&,
  ProjectionCounts*);
template RasterImage<double> Rasterize<double>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&,
  ProjectionCounts*);

} // namespace vis4gs

// SPDX-License-Identifier: BSD-3-Clause
// AttributePixels() and RankContributors(): which Gaussians make chosen pixels, replaying
// the blending of each pixel with the compositing's exact kernel (w = alpha T).
#include "Rasterizer.h"

#include "RasterInternal.h"
#include "RasterKernel.h"
#include "ThreadCount.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace vis4gs
{

//------------------------------------------------------------------------------
template <typename T>
std::vector<PixelAttribution> AttributePixels(const ViewProjection<T>& projection,
  const TileBins& bins,
  const RasterSettings& settings,
  const std::vector<std::array<int, 2>>& pixels)
{
  if (bins.TilesX != projection.TilesX || bins.TilesY != projection.TilesY ||
    bins.Offsets.size() != bins.TileCount() + 1)
  {
    throw std::invalid_argument("AttributePixels: the tile bins do not belong to this projection");
  }
  std::vector<PixelAttribution> out(pixels.size());
  const std::int64_t count = static_cast<std::int64_t>(pixels.size());
  const T bg[3] = { static_cast<T>(settings.Background[0]),
    static_cast<T>(settings.Background[1]),
    static_cast<T>(settings.Background[2]) };
  const int threads = ThreadCount(settings.Threads);
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads)
  for (std::int64_t q = 0; q < count; ++q)
  {
    PixelAttribution& pa = out[static_cast<std::size_t>(q)];
    const int x = pixels[static_cast<std::size_t>(q)][0],
              y = pixels[static_cast<std::size_t>(q)][1];
    pa.X = x;
    pa.Y = y;
    if (x < 0 || y < 0 || x >= projection.Width || y >= projection.Height)
    {
      continue;
    }
    const std::size_t tile = static_cast<std::size_t>(y / raster::TileSize) * projection.TilesX +
      static_cast<std::size_t>(x / raster::TileSize);
    T Tr = 1, C[3] = { 0, 0, 0 };
    std::uint32_t lastPos = 0;
    const std::uint64_t b = bins.Offsets[tile], e = bins.Offsets[tile + 1];
    for (std::uint64_t k = b; k < e; ++k)
    {
      const std::uint32_t id = bins.Ids[k];
      const auto& g = projection.Gaussians[id];
      const T power = raster::KernelPower<T>(
        g.U, g.V, g.ConicA, g.ConicB, g.ConicC, static_cast<T>(x), static_cast<T>(y));
      const T alpha = raster::KernelAlpha<T>(g.Opacity, power);
      if (alpha < T(0))
      {
        continue;
      }
      const T Tn = Tr * (T(1) - alpha);
      if (Tn < T(raster::TransmittanceStop))
      {
        break;
      }
      for (int c = 0; c < 3; ++c)
      {
        C[c] = C[c] + g.Color[c] * alpha * Tr;
      }
      const std::uint32_t pos = static_cast<std::uint32_t>(k - b + 1);
      pa.Contributions.push_back({ id,
        pos,
        static_cast<double>(alpha),
        static_cast<double>(Tr),
        static_cast<double>(alpha * Tr) });
      Tr = Tn;
      lastPos = pos;
    }
    pa.FinalTransmittance = Tr;
    pa.Contributors = lastPos;
    for (int c = 0; c < 3; ++c)
    {
      pa.Color[c] = static_cast<double>(C[c] + Tr * bg[c]);
    }
    std::stable_sort(pa.Contributions.begin(),
      pa.Contributions.end(),
      [](const PixelContribution& l, const PixelContribution& r) { return l.Weight > r.Weight; });
  }
  return out;
}

//------------------------------------------------------------------------------
std::vector<GaussianContribution> RankContributors(
  const std::vector<PixelAttribution>& attributions)
{
  std::vector<GaussianContribution> all;
  for (const auto& pa : attributions)
  {
    for (const auto& c : pa.Contributions)
    {
      all.push_back({ c.Gaussian, c.Weight, c.Weight, 1 });
    }
  }
  std::sort(all.begin(),
    all.end(),
    [](const GaussianContribution& l, const GaussianContribution& r)
    { return l.Gaussian < r.Gaussian; });
  std::vector<GaussianContribution> merged;
  for (const auto& c : all)
  {
    if (!merged.empty() && merged.back().Gaussian == c.Gaussian)
    {
      merged.back().WeightSum += c.WeightSum;
      merged.back().MaxWeight = std::max(merged.back().MaxWeight, c.MaxWeight);
      ++merged.back().Pixels;
    }
    else
    {
      merged.push_back(c);
    }
  }
  std::stable_sort(merged.begin(),
    merged.end(),
    [](const GaussianContribution& l, const GaussianContribution& r)
    { return l.WeightSum > r.WeightSum; });
  return merged;
}

template std::vector<PixelAttribution> AttributePixels<float>(const ViewProjection<float>&,
  const TileBins&,
  const RasterSettings&,
  const std::vector<std::array<int, 2>>&);
template std::vector<PixelAttribution> AttributePixels<double>(const ViewProjection<double>&,
  const TileBins&,
  const RasterSettings&,
  const std::vector<std::array<int, 2>>&);

} // namespace vis4gs

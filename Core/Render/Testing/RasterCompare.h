// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file RasterCompare.h
 * @brief Bit-for-bit comparisons of rasteriser outputs for the GoogleTest suites that check
 * one path against another (vector vs scalar projection, kept vs fresh buffers).
 */
#ifndef vis4gs_RasterCompare_h
#define vis4gs_RasterCompare_h

#include "Rasterizer.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <cstring>
#include <vector>

namespace vis4gs
{
namespace rastertest
{

template <typename U>
bool SameBits(const std::vector<U>& a, const std::vector<U>& b)
{
  return a.size() == b.size() &&
    (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(U)) == 0);
}

template <typename U>
bool SameScalar(U a, U b)
{
  return std::memcmp(&a, &b, sizeof(U)) == 0;
}

inline bool SameCounts(const ProjectionCounts& a, const ProjectionCounts& b)
{
  return a.Visible == b.Visible && a.InvalidParameters == b.InvalidParameters &&
    a.NearPlane == b.NearPlane && a.Degenerate == b.Degenerate && a.NonFinite == b.NonFinite &&
    a.OffScreen == b.OffScreen;
}

/// Every field of the view and of every projected Gaussian (culled ones included) equal bit
/// for bit; reports the first five Gaussians that differ.
template <typename T>
void ExpectSameProjection(const ViewProjection<T>& ref, const ViewProjection<T>& got)
{
  EXPECT_EQ(ref.Width, got.Width);
  EXPECT_EQ(ref.Height, got.Height);
  EXPECT_EQ(ref.TilesX, got.TilesX);
  EXPECT_EQ(ref.TilesY, got.TilesY);
  EXPECT_EQ(ref.ShDegree, got.ShDegree);
  EXPECT_TRUE(SameScalar(ref.Fx, got.Fx) && SameScalar(ref.Fy, got.Fy));
  EXPECT_TRUE(ref.ViewMatrix == got.ViewMatrix && ref.FullProjection == got.FullProjection &&
    ref.CameraCenter == got.CameraCenter);
  EXPECT_TRUE(SameCounts(ref.Counts, got.Counts));
  ASSERT_EQ(ref.Gaussians.size(), got.Gaussians.size());
  std::size_t bad = 0;
  for (std::size_t i = 0; i < ref.Gaussians.size() && bad < 5; ++i)
  {
    const auto& x = ref.Gaussians[i];
    const auto& y = got.Gaussians[i];
    bool same = x.Status == y.Status && x.ClampedChannels == y.ClampedChannels &&
      x.Radius == y.Radius && SameScalar(x.U, y.U) && SameScalar(x.V, y.V) &&
      SameScalar(x.ConicA, y.ConicA) && SameScalar(x.ConicB, y.ConicB) &&
      SameScalar(x.ConicC, y.ConicC) && SameScalar(x.Opacity, y.Opacity) &&
      SameScalar(x.Depth, y.Depth);
    for (int k = 0; k < 3; ++k)
    {
      same = same && SameScalar(x.Color[k], y.Color[k]) && SameScalar(x.Cov2D[k], y.Cov2D[k]) &&
        SameScalar(x.ViewPosition[k], y.ViewPosition[k]);
    }
    for (int k = 0; k < 4; ++k)
    {
      same = same && x.TileRect[k] == y.TileRect[k];
    }
    if (!same)
    {
      ++bad;
      ADD_FAILURE() << "Gaussian " << i << " status " << int(x.Status) << " vs " << int(y.Status)
                    << " u " << x.U << " vs " << y.U;
    }
  }
}

} // namespace rastertest
} // namespace vis4gs

#endif

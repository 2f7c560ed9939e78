// SPDX-License-Identifier: BSD-3-Clause
// ProjectGaussians(): the per-Gaussian preprocessing of the reference forward pass
// (reference §2.1-2.4): the scalar code (float and double), the 16-lane float code
// (ProjectionLanes.inc, shared with MultiViewRenderer) and the kept view-independent
// preparation (PreparedCloudCache).
#include "Rasterizer.h"

#include "GaussianMath.h"
#include "KernelIsa.h"
#include "MultiViewData.h"
#include "ProjectionSteps.h"
#include "RasterBounds.h"
#include "RasterInternal.h"
#include "ThreadCount.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <immintrin.h>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

namespace vis4gs
{

namespace
{

/// The projections' per-status tallies (indexed Visible, InvalidParameters, NearPlane,
/// Degenerate, NonFinite, OffScreen) into ProjectionCounts.
void StoreCounts(const std::size_t (&counts)[6], ProjectionCounts& out)
{
  out.Visible = counts[0];
  out.InvalidParameters = counts[1];
  out.NearPlane = counts[2];
  out.Degenerate = counts[3];
  out.NonFinite = counts[4];
  out.OffScreen = counts[5];
}

//------------------------------------------------------------------------------
using raster::internal::ResizeKeep;

template <typename T>
bool AllFinite(const T* v, std::size_t n)
{
  for (std::size_t i = 0; i < n; ++i)
  {
    if (!std::isfinite(v[i]))
    {
      return false;
    }
  }
  return true;
}

//------------------------------------------------------------------------------
void CheckCamera(const Camera& camera)
{
  if (camera.Width <= 0 || camera.Height <= 0)
  {
    throw std::invalid_argument("camera '" + camera.Name + "': image size " +
      std::to_string(camera.Width) + "x" + std::to_string(camera.Height) + " is not positive");
  }
  if (!(camera.Fx > 0) || !(camera.Fy > 0) || !std::isfinite(camera.Fx) ||
    !std::isfinite(camera.Fy))
  {
    throw std::invalid_argument("camera '" + camera.Name + "': focal lengths " +
      std::to_string(camera.Fx) + ", " + std::to_string(camera.Fy) +
      " are not positive finite numbers");
  }
  if (!AllFinite(camera.WorldToCamera.data(), 16))
  {
    throw std::invalid_argument(
      "camera '" + camera.Name + "': world-to-camera matrix is not finite");
  }
  if (static_cast<long long>(camera.Width) * camera.Height > (1LL << 30))
  {
    throw std::invalid_argument("camera '" + camera.Name + "': image of " +
      std::to_string(camera.Width) + "x" + std::to_string(camera.Height) + " pixels is too large");
  }
}

//------------------------------------------------------------------------------
void CheckCloud(const GaussianCloud& cloud, bool colors)
{
  const std::size_t n = cloud.Count;
  auto check = [&](const char* name, std::size_t size, std::size_t per)
  {
    if (size != n * per)
    {
      throw std::invalid_argument(std::string("Gaussian cloud: ") + name + " holds " +
        std::to_string(size) + " values, expected " + std::to_string(n * per) + " for " +
        std::to_string(n) + " Gaussians");
    }
  };
  check("Positions", cloud.Positions.size(), 3);
  check("LogScales", cloud.LogScales.size(), 3);
  check("Rotations", cloud.Rotations.size(), 4);
  check("OpacityLogits", cloud.OpacityLogits.size(), 1);
  if (colors)
  {
    if (cloud.ShDegree < 0 || cloud.ShDegree > 3)
    {
      throw std::invalid_argument(
        "Gaussian cloud: SH degree " + std::to_string(cloud.ShDegree) + " is not in 0..3");
    }
    check("SH", cloud.SH.size(), 3 * static_cast<std::size_t>(cloud.ShCoefficientCount()));
  }
  if (n > std::numeric_limits<std::uint32_t>::max())
  {
    throw std::invalid_argument("Gaussian cloud: " + std::to_string(n) +
      " Gaussians exceed the rasteriser's limit of 2^32-1");
  }
}

} // namespace

//------------------------------------------------------------------------------
// The 16-lane per-view projection (ProjectionLanes.inc) of ProjectGaussians<float> and
// MultiViewRenderer, and the view-independent preparation it reads.
namespace
{

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
namespace mvgeneric
{
#define VIS4GS_LANES_ISA 1
#include "ProjectionLanes.inc"
#undef VIS4GS_LANES_ISA
} // namespace mvgeneric
namespace mvavx2
{
#define VIS4GS_LANES_ISA 2
#include "ProjectionLanes.inc"
#undef VIS4GS_LANES_ISA
} // namespace mvavx2
namespace mvavx512
{
#define VIS4GS_LANES_ISA 3
#include "ProjectionLanes.inc"
#undef VIS4GS_LANES_ISA
} // namespace mvavx512
#pragma GCC diagnostic pop

using ProjectBlock = raster::internal::ProjectBlockFunction;

void ProjectBlockGeneric(const MultiViewPrepared& g,
  std::size_t first,
  const PreparedView& w,
  MultiViewProjected& out,
  std::size_t at)
{
  mvgeneric::ProjectLanes(g, first, w, out, at);
}
void ProjectBlockAvx2(const MultiViewPrepared& g,
  std::size_t first,
  const PreparedView& w,
  MultiViewProjected& out,
  std::size_t at)
{
  mvavx2::ProjectLanes(g, first, w, out, at);
  mvavx2::ProjectLanes(g, first + 8, w, out, at + 8);
}
void ProjectBlockAvx512(const MultiViewPrepared& g,
  std::size_t first,
  const PreparedView& w,
  MultiViewProjected& out,
  std::size_t at)
{
  mvavx512::ProjectLanes(g, first, w, out, at);
}

// KernelIsa.h: 1 (baseline) is the generic 16-lane vectors.
ProjectBlock SelectProjectBlock(int isa)
{
  switch (ResolveKernelIsa(isa))
  {
    case KernelIsa::Avx512:
      return &ProjectBlockAvx512;
    case KernelIsa::Avx2:
      return &ProjectBlockAvx2;
    default:
      return &ProjectBlockGeneric;
  }
}

// View-independent part of ProjectGaussians<float> step 3 for Gaussian @p i (the same
// operations in the same order) into slot @p k of @p p; Valid -1, or 0 (and zeros) when a
// parameter it would use is not finite.
inline void PrepareForLanes(const GaussianCloud& cloud,
  std::size_t i,
  float mod,
  int shStride,
  int shUsed,
  bool colors,
  MultiViewPrepared& p,
  std::size_t k)
{
  const float* pos = &cloud.Positions[3 * i];
  const float* ls = &cloud.LogScales[3 * i];
  const float* rot = &cloud.Rotations[4 * i];
  const float logit = cloud.OpacityLogits[i];
  const float* shf = colors ? &cloud.SH[i * shStride] : nullptr;
  if (ClassifyGaussian(pos, ls, rot, logit) != GaussianClass::Drawn ||
    (colors && !AllFinite(shf, static_cast<std::size_t>(shUsed))))
  {
    p.X[k] = p.Y[k] = p.Z[k] = 0.0f;
    p.S00[k] = p.S01[k] = p.S02[k] = p.S11[k] = p.S12[k] = p.S22[k] = 0.0f;
    p.Opacity[k] = 0.0f;
    p.Valid[k] = 0;
    return;
  }
  const std::array<float, 6> sigma = GaussianCovariance<float>(ls, rot, mod);
  p.X[k] = pos[0];
  p.Y[k] = pos[1];
  p.Z[k] = pos[2];
  p.S00[k] = sigma[0];
  p.S01[k] = sigma[1];
  p.S02[k] = sigma[2];
  p.S11[k] = sigma[3];
  p.S12[k] = sigma[4];
  p.S22[k] = sigma[5];
  p.Opacity[k] = Sigmoid(static_cast<float>(logit));
  p.Valid[k] = -1;
}

} // namespace

//------------------------------------------------------------------------------
// PreparedCloudCache: the view-independent preparation of a whole cloud (PrepareForLanes of
// every Gaussian, padded to 16), kept with everything it was computed from.
struct PreparedCloudCache::Impl
{
  MultiViewPrepared Data;
  bool Valid = false;
  std::uint64_t Version = 0;
  const GaussianCloud* Cloud = nullptr;
  std::size_t Count = 0;
  int ShDegree = 0;
  const float* Arrays[5] = { nullptr, nullptr, nullptr, nullptr, nullptr };
  std::size_t Sizes[5] = { 0, 0, 0, 0, 0 };
  std::uint32_t ModBits = 0;
  int ShUsed = 0;
  bool Colors = false;
  std::size_t Builds = 0, Reuses = 0;
};

PreparedCloudCache::PreparedCloudCache() = default;
PreparedCloudCache::~PreparedCloudCache() = default;
PreparedCloudCache::PreparedCloudCache(const PreparedCloudCache&) {}
PreparedCloudCache& PreparedCloudCache::operator=(const PreparedCloudCache& other)
{
  if (this != &other)
  {
    this->P.reset();
  }
  return *this;
}
PreparedCloudCache::PreparedCloudCache(PreparedCloudCache&&) noexcept = default;
PreparedCloudCache& PreparedCloudCache::operator=(PreparedCloudCache&&) noexcept = default;

void PreparedCloudCache::Clear()
{
  if (this->P)
  {
    this->P->Valid = false;
  }
}

std::size_t PreparedCloudCache::Builds() const
{
  return this->P ? this->P->Builds : 0;
}

std::size_t PreparedCloudCache::Reuses() const
{
  return this->P ? this->P->Reuses : 0;
}

PreparedCloudCache::Impl& PreparedCloudCache::Internal()
{
  if (!this->P)
  {
    this->P.reset(new Impl);
  }
  return *this->P;
}

namespace
{
// The five parameter arrays of a cloud, the part of the cache's key that says which cloud.
struct CloudArrays
{
  explicit CloudArrays(const GaussianCloud& cloud)
    : Arrays{ cloud.Positions.data(),
      cloud.LogScales.data(),
      cloud.Rotations.data(),
      cloud.OpacityLogits.data(),
      cloud.SH.data() }
    , Sizes{ cloud.Positions.size(),
      cloud.LogScales.size(),
      cloud.Rotations.size(),
      cloud.OpacityLogits.size(),
      cloud.SH.size() }
  {
  }
  void RememberIn(PreparedCloudCache::Impl& c) const
  {
    std::copy(this->Arrays, this->Arrays + 5, c.Arrays);
    std::copy(this->Sizes, this->Sizes + 5, c.Sizes);
  }
  const float* Arrays[5];
  std::size_t Sizes[5];
};

// The kept preparation of @p cloud for these settings: reused when the key matches (after a
// bit-exact spot check of 64 Gaussians, std::logic_error on a difference), else recomputed.
const MultiViewPrepared& UsePreparedCloud(PreparedCloudCache& cache,
  const GaussianCloud& cloud,
  std::uint64_t version,
  float mod,
  int shStride,
  int shUsed,
  bool colors,
  int threads)
{
  PreparedCloudCache::Impl& c = cache.Internal();
  const std::size_t n = cloud.Count;
  const CloudArrays current(cloud);
  const float* const* arrays = current.Arrays;
  const std::size_t* sizes = current.Sizes;
  std::uint32_t modBits;
  std::memcpy(&modBits, &mod, sizeof(modBits));
  const bool same = c.Valid && c.Version == version && c.Cloud == &cloud && c.Count == n &&
    c.ShDegree == cloud.ShDegree && std::equal(arrays, arrays + 5, c.Arrays) &&
    std::equal(sizes, sizes + 5, c.Sizes) && c.ModBits == modBits && c.ShUsed == shUsed &&
    c.Colors == colors;
  MultiViewPrepared& d = c.Data;
  if (same)
  {
    // Spot check: a cloud changed under an unchanged version must not pass silently.
    MultiViewPrepared probe;
    probe.Allocate(16, false);
    const std::size_t samples = std::min<std::size_t>(64, n);
    for (std::size_t j = 0; j < samples; ++j)
    {
      // Spread over the cloud, shifted at every reuse so that repeated frames cover more.
      const std::size_t i = (j * n / samples + c.Reuses * 7919) % n;
      PrepareForLanes(cloud, i, mod, shStride, shUsed, colors, probe, 0);
      const float kept[10] = { d.X[i],
        d.Y[i],
        d.Z[i],
        d.S00[i],
        d.S01[i],
        d.S02[i],
        d.S11[i],
        d.S12[i],
        d.S22[i],
        d.Opacity[i] };
      const float now[10] = { probe.X[0],
        probe.Y[0],
        probe.Z[0],
        probe.S00[0],
        probe.S01[0],
        probe.S02[0],
        probe.S11[0],
        probe.S12[0],
        probe.S22[0],
        probe.Opacity[0] };
      if (std::memcmp(kept, now, sizeof(kept)) != 0 || d.Valid[i] != probe.Valid[0])
      {
        c.Valid = false;
        throw std::logic_error("ProjectGaussians: cloud version " + std::to_string(version) +
          " was kept but the parameters of Gaussian " + std::to_string(i) +
          " changed; the caller must change the version whenever the cloud changes");
      }
    }
    ++c.Reuses;
    return d;
  }
  c.Valid = false;
  const std::size_t padded = (n + 15) / 16 * 16;
  d.Allocate(padded, false);
  const std::int64_t count = static_cast<std::int64_t>(padded);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::int64_t ii = 0; ii < count; ++ii)
  {
    const std::size_t i = static_cast<std::size_t>(ii);
    raster::internal::PrepareGaussianForLanes(cloud, i, mod, shStride, shUsed, colors, d, i);
  }
  c.Version = version;
  c.Cloud = &cloud;
  c.Count = n;
  c.ShDegree = cloud.ShDegree;
  current.RememberIn(c);
  c.ModBits = modBits;
  c.ShUsed = shUsed;
  c.Colors = colors;
  c.Valid = true;
  ++c.Builds;
  return d;
}
} // namespace

//------------------------------------------------------------------------------
bool RefreshPreparedCloud(PreparedCloudCache& cache,
  const GaussianCloud& cloud,
  std::uint64_t from,
  std::uint64_t to,
  const std::vector<std::uint32_t>& changed,
  const RasterSettings& settings)
{
  const std::size_t n = cloud.Count;
  for (std::uint32_t i : changed)
  {
    if (i >= n)
    {
      throw std::invalid_argument("RefreshPreparedCloud: changed Gaussian " + std::to_string(i) +
        " is not below the cloud's count " + std::to_string(n));
    }
  }
  // (the keys of ProjectFloatLanes and UsePreparedCloud)
  const int degree = std::max(
    0, settings.ShDegree < 0 ? cloud.ShDegree : std::min(settings.ShDegree, cloud.ShDegree));
  const bool colors = settings.ComputeColors;
  const int shStride = colors ? 3 * cloud.ShCoefficientCount() : 0;
  const int shUsed = 3 * (degree + 1) * (degree + 1);
  const float mod = static_cast<float>(settings.ScaleModifier);
  std::uint32_t modBits;
  std::memcpy(&modBits, &mod, sizeof(modBits));
  PreparedCloudCache::Impl& c = cache.Internal();
  MultiViewPrepared& d = c.Data;
  const std::size_t padded = (n + 15) / 16 * 16;
  if (!c.Valid || from == 0 || to == 0 || c.Version != from || c.Cloud != &cloud ||
    c.ShDegree != cloud.ShDegree || c.ModBits != modBits || c.ShUsed != shUsed ||
    c.Colors != colors || settings.KernelIsa < 0 || d.Color)
  {
    return false;
  }
  // The arrays lie in one block, array a at a * padded: another padded count moves them (in
  // the block when it has room, the lower arrays first when they shrink, the higher ones first
  // when they grow); a new block loses them (then everything is prepared again).
  const std::size_t before = (c.Count + 15) / 16 * 16;
  if (padded != before)
  {
    float* base = d.X;
    d.Allocate(padded, false);
    if (d.X != base)
    {
      c.Valid = false;
      return false;
    }
    const std::size_t kept = std::min(before, padded);
    for (int k = 0; k < 11; ++k)
    {
      const std::size_t a = static_cast<std::size_t>(padded > before ? 10 - k : k);
      std::memmove(base + a * padded, base + a * before, kept * sizeof(float));
    }
  }
  const int threads = ThreadCount(settings.Threads);
  const std::int64_t count = static_cast<std::int64_t>(changed.size());
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::int64_t jj = 0; jj < count; ++jj)
  {
    const std::size_t i = changed[static_cast<std::size_t>(jj)];
    raster::internal::PrepareGaussianForLanes(cloud, i, mod, shStride, shUsed, colors, d, i);
  }
  // The Gaussians beyond the previous count, and the padding.
  for (std::size_t i = std::min(c.Count, n); i < padded; ++i)
  {
    raster::internal::PrepareGaussianForLanes(cloud, i, mod, shStride, shUsed, colors, d, i);
  }
  c.Version = to;
  c.Count = n;
  CloudArrays(cloud).RememberIn(c);
  return true;
}

//------------------------------------------------------------------------------
namespace
{
// ProjectGaussians<float> steps 1-7 with the 16-lane projection (ProjectionLanes.inc, the
// code MultiViewRenderer runs), blocks of 16 Gaussians: the view-independent preparation per
// Gaussian, the projection per block, then every field of ProjectedGaussian written exactly
// as the scalar code writes it for the lane's status (bit-identical, tested).
void ProjectFloatLanes(const GaussianCloud& cloud,
  const RasterSettings& settings,
  int threads,
  ViewProjection<float>& p,
  bool reset,
  PreparedCloudCache* cache,
  std::uint64_t version,
  const std::vector<std::uint32_t>* subset)
{
  // Projected Gaussian j is the cloud's Gaussian subset[j] (j itself without a subset).
  const std::size_t n = subset ? subset->size() : cloud.Count;
  const PreparedView w = PrepareView(p);
  const ProjectBlock block = SelectProjectBlock(settings.KernelIsa);
  const bool colors = settings.ComputeColors;
  const int shDegree = p.ShDegree;
  const int shStride = colors ? 3 * cloud.ShCoefficientCount() : 0;
  const int shUsed = 3 * (shDegree + 1) * (shDegree + 1);
  const float mod = static_cast<float>(settings.ScaleModifier);
  const auto campos = p.CameraCenter;
  const std::int64_t blocks = static_cast<std::int64_t>((n + 15) / 16);
  // The whole cloud's preparation, kept between frames (or null: prepared per block).
  const MultiViewPrepared* kept = cache && version != 0
    ? &UsePreparedCloud(*cache, cloud, version, mod, shStride, shUsed, colors, threads)
    : nullptr;
  std::size_t counts[6] = { 0, 0, 0, 0, 0, 0 };
#pragma omp parallel num_threads(threads)
  {
    std::size_t local[6] = { 0, 0, 0, 0, 0, 0 };
    MultiViewPrepared in;
    in.Allocate(16, false);
    // (zeros, Valid 0 included: one block of 4-byte arrays)
    std::fill(in.X, in.X + MultiViewPrepared::Bytes(16, false) / sizeof(float), 0.0f);
    MultiViewProjected out;
    for (auto* v : { &out.U,
           &out.V,
           &out.A,
           &out.B,
           &out.C,
           &out.Depth,
           &out.T0,
           &out.T1,
           &out.CovA,
           &out.CovB,
           &out.CovC })
    {
      v->assign(16, 0.0f);
    }
    for (auto* v : { &out.Status, &out.Radius, &out.X0, &out.Y0, &out.X1, &out.Y1, &out.Reached })
    {
      v->assign(16, 0);
    }
#pragma omp for schedule(static)
    for (std::int64_t bb = 0; bb < blocks; ++bb)
    {
      const std::size_t first = static_cast<std::size_t>(bb) * 16;
      const std::size_t count = std::min<std::size_t>(16, n - first);
      if (kept && !subset)
      {
        block(*kept, first, w, out, 0);
      }
      else
      {
        for (std::size_t k = 0; k < count; ++k)
        {
          const std::size_t i = subset ? (*subset)[first + k] : first + k;
          if (kept)
          {
            // The kept preparation of Gaussian i, gathered into lane k.
            for (auto member : { &MultiViewPrepared::X,
                   &MultiViewPrepared::Y,
                   &MultiViewPrepared::Z,
                   &MultiViewPrepared::S00,
                   &MultiViewPrepared::S01,
                   &MultiViewPrepared::S02,
                   &MultiViewPrepared::S11,
                   &MultiViewPrepared::S12,
                   &MultiViewPrepared::S22,
                   &MultiViewPrepared::Opacity })
            {
              (in.*member)[k] = ((*kept).*member)[i];
            }
            in.Valid[k] = kept->Valid[i];
          }
          else
          {
            PrepareForLanes(cloud, i, mod, shStride, shUsed, colors, in, k);
          }
        }
        for (std::size_t k = count; k < 16; ++k)
        {
          in.Valid[k] = 0; // padding of the last block (zeros from the assign above)
        }
        block(in, 0, w, out, 0);
      }
      for (std::size_t k = 0; k < count; ++k)
      {
        ProjectedGaussian<float>& g = p.Gaussians[first + k];
        if (reset)
        {
          g = ProjectedGaussian<float>();
        }
        const int status = out.Status[k];
        ++local[status];
        g.Status = static_cast<ProjectionStatus>(status);
        if (g.Status == ProjectionStatus::InvalidParameters)
        {
          continue;
        }
        g.ViewPosition[0] = out.T0[k];
        g.ViewPosition[1] = out.T1[k];
        g.ViewPosition[2] = out.Depth[k];
        g.Depth = out.Depth[k];
        if (g.Status == ProjectionStatus::NearPlane)
        {
          continue;
        }
        g.Cov2D[0] = out.CovA[k];
        g.Cov2D[1] = out.CovB[k];
        g.Cov2D[2] = out.CovC[k];
        if (out.Reached[k] == 0)
        {
          continue; // Degenerate, or NonFinite covariance or conic
        }
        g.U = out.U[k];
        g.V = out.V[k];
        g.ConicA = out.A[k];
        g.ConicB = out.B[k];
        g.ConicC = out.C[k];
        g.TileRect[0] = out.X0[k];
        g.TileRect[1] = out.Y0[k];
        g.TileRect[2] = out.X1[k];
        g.TileRect[3] = out.Y1[k];
        g.Opacity = kept && !subset ? kept->Opacity[first + k] : in.Opacity[k];
        if (g.Status != ProjectionStatus::Visible)
        {
          continue; // NonFinite pixel mean or OffScreen: Radius stays 0
        }
        g.Radius = out.Radius[k];
        if (colors)
        {
          const std::size_t i = subset ? (*subset)[first + k] : first + k;
          g.ClampedChannels = static_cast<std::uint8_t>(ViewColor<float>(
            &cloud.SH[i * shStride], shDegree, &cloud.Positions[3 * i], campos.data(), g.Color));
        }
      }
    }
#pragma omp critical(vis4gsProjectLaneCounts)
    for (int k = 0; k < 6; ++k)
    {
      counts[k] += local[k];
    }
  }
  StoreCounts(counts, p.Counts);
}
} // namespace

//------------------------------------------------------------------------------
namespace
{
// ProjectGaussians into @p p. With @p reuse and enough capacity in p.Gaussians, its memory is
// kept and every element is reset to ProjectedGaussian<T>() by the (parallel) projection loop
// right before it is written, so the result is the same as in a fresh projection, field by
// field; otherwise a fresh buffer is value-initialised as before.
template <typename T>
void ProjectInto(const GaussianCloud& cloud,
  const Camera& camera,
  const RasterSettings& settings,
  ViewProjection<T>& p,
  bool reuse,
  PreparedCloudCache* cache = nullptr,
  std::uint64_t version = 0,
  const std::vector<std::uint32_t>* subset = nullptr)
{
  CheckCamera(camera);
  CheckCloud(cloud, settings.ComputeColors);
  if (subset)
  {
    std::uint32_t last = 0;
    for (std::size_t j = 0; j < subset->size(); ++j)
    {
      const std::uint32_t i = (*subset)[j];
      if (i >= cloud.Count || (j > 0 && i <= last))
      {
        throw std::invalid_argument("ProjectGaussianSubset: index " + std::to_string(i) +
          " at position " + std::to_string(j) + " is out of range or not ascending (" +
          std::to_string(cloud.Count) + " Gaussians)");
      }
      last = i;
    }
  }

  p.Counts = ProjectionCounts();
  p.Width = camera.Width;
  p.Height = camera.Height;
  p.TilesX = (camera.Width + raster::TileSize - 1) / raster::TileSize;
  p.TilesY = (camera.Height + raster::TileSize - 1) / raster::TileSize;
  p.ShDegree = settings.ShDegree < 0 ? cloud.ShDegree : std::min(settings.ShDegree, cloud.ShDegree);
  p.ShDegree = std::max(0, p.ShDegree);
  // The reference passes tan(fov/2) as float and recomputes the focal lengths from it.
  p.TanFovX = static_cast<T>(camera.Width / (2.0 * camera.Fx));
  p.TanFovY = static_cast<T>(camera.Height / (2.0 * camera.Fy));
  p.Fx = static_cast<T>(camera.Width) / (T(2) * p.TanFovX);
  p.Fy = static_cast<T>(camera.Height) / (T(2) * p.TanFovY);
  const auto& w2c = camera.WorldToCamera;
  for (int i = 0; i < 16; ++i)
  {
    p.ViewMatrix[i] = static_cast<T>(w2c[i]);
  }
  {
    // P (reference §2.2) times W2C, in double.
    const double tx = camera.Width / (2.0 * camera.Fx), ty = camera.Height / (2.0 * camera.Fy);
    const double n = raster::ProjectionZNear, f = raster::ProjectionZFar;
    const double P[16] = {
      1 / tx, 0, 0, 0, 0, 1 / ty, 0, 0, 0, 0, f / (f - n), -f * n / (f - n), 0, 0, 1, 0
    };
    for (int r = 0; r < 4; ++r)
    {
      for (int c = 0; c < 4; ++c)
      {
        double s = 0;
        for (int k = 0; k < 4; ++k)
        {
          s += P[4 * r + k] * w2c[4 * k + c];
        }
        p.FullProjection[4 * r + c] = static_cast<T>(s);
      }
    }
  }
  const auto center = camera.Center();
  for (int i = 0; i < 3; ++i)
  {
    p.CameraCenter[i] = static_cast<T>(center[i]);
  }

  const std::size_t n = subset ? subset->size() : cloud.Count;
  const bool reset = reuse && p.Gaussians.capacity() >= n;
  if (reset)
  {
    p.Gaussians.resize(n); // no reallocation; every element is reset below
  }
  else
  {
    // A kept buffer gets 1/8 of slack, as ResizeKeep gives: the level of detail's subsets
    // vary by a few thousand Gaussians from view to view, and each new maximum would otherwise
    // allocate, clear and page-fault the whole buffer again on one thread.
    const std::size_t capacity = reuse ? n + n / 8 : n;
    std::vector<ProjectedGaussian<T>>().swap(p.Gaussians);
    p.Gaussians.reserve(capacity);
    raster::internal::HugePages(p.Gaussians.data(), capacity * sizeof(ProjectedGaussian<T>));
    p.Gaussians.assign(n, ProjectedGaussian<T>());
  }
  if constexpr (std::is_same<T, float>::value)
  {
    if (settings.KernelIsa >= 0)
    {
      ProjectFloatLanes(
        cloud, settings, ThreadCount(settings.Threads), p, reset, cache, version, subset);
      return;
    }
  }
  const int shDegree = p.ShDegree;
  const int shStride = 3 * cloud.ShCoefficientCount();
  const int shUsed = 3 * (shDegree + 1) * (shDegree + 1);
  const bool colors = settings.ComputeColors;
  const T mod = static_cast<T>(settings.ScaleModifier);
  const int W = p.Width, H = p.Height, gx = p.TilesX, gy = p.TilesY;
  const auto& V = p.ViewMatrix;
  const auto& F = p.FullProjection;
  const T limx = T(raster::JacobianClamp) * p.TanFovX;
  const T limy = T(raster::JacobianClamp) * p.TanFovY;
  const T focalX = p.Fx, focalY = p.Fy;
  const raster::ProjectionView<T> view{
    V.data(), F.data(), F.data() + 4, F.data() + 12, focalX, focalY, limx, limy, W, H, gx, gy
  };
  const auto campos = p.CameraCenter;

  std::size_t counts[6] = { 0, 0, 0, 0, 0, 0 };
  const int threads = ThreadCount(settings.Threads);
  const std::int64_t count = static_cast<std::int64_t>(n);
#pragma omp parallel num_threads(threads)
  {
    std::size_t local[6] = { 0, 0, 0, 0, 0, 0 };
#pragma omp for schedule(static)
    for (std::int64_t ii = 0; ii < count; ++ii)
    {
      ProjectedGaussian<T>& g = p.Gaussians[static_cast<std::size_t>(ii)];
      const std::size_t i =
        subset ? (*subset)[static_cast<std::size_t>(ii)] : static_cast<std::size_t>(ii);
      if (reset)
      {
        g = ProjectedGaussian<T>();
      }
      const float* pos = &cloud.Positions[3 * i];
      const float* ls = &cloud.LogScales[3 * i];
      const float* rot = &cloud.Rotations[4 * i];
      const float logit = cloud.OpacityLogits[i];
      const float* shf = colors ? &cloud.SH[i * shStride] : nullptr;
      g.Status = ProjectionStatus::InvalidParameters;
      if (ClassifyGaussian(pos, ls, rot, logit) != GaussianClass::Drawn ||
        (colors && !AllFinite(shf, static_cast<std::size_t>(shUsed))))
      {
        ++local[static_cast<int>(ProjectionStatus::InvalidParameters)];
        continue;
      }
      const T x = pos[0], y = pos[1], z = pos[2];
      // Steps 1, 2, 4, 5, 6 are ProjectionSteps.h (the fast coverage runs them too).
      // 1. View position and near cull.
      const raster::ProjectedViewPosition<T> t = raster::ProjectViewPosition(view, x, y, z);
      g.ViewPosition[0] = t.T0;
      g.ViewPosition[1] = t.T1;
      g.ViewPosition[2] = t.T2;
      g.Depth = t.T2;
      if (t.T2 <= T(raster::NearPlane))
      {
        g.Status = ProjectionStatus::NearPlane;
        ++local[static_cast<int>(g.Status)];
        continue;
      }
      // 3. 3D covariance R diag(s^2) R^T.
      const std::array<T, 6> sigma = GaussianCovariance<T>(ls, rot, mod);
      const T s[6] = { sigma[0], sigma[1], sigma[2], sigma[3], sigma[4], sigma[5] };
      // 2, 4, 5. Clip coordinates, EWA projection with the clamped Jacobian, det cull,
      // conic, radius; the pixel-space mean of 6.
      const raster::ProjectedConic<T> q = raster::ProjectConic(view, x, y, z, t, s);
      g.Cov2D[0] = q.A;
      g.Cov2D[1] = q.B;
      g.Cov2D[2] = q.C;
      if (!q.CovFinite || q.Degenerate || !q.ConicFinite)
      {
        g.Status =
          q.CovFinite && q.Degenerate ? ProjectionStatus::Degenerate : ProjectionStatus::NonFinite;
        ++local[static_cast<int>(g.Status)];
        continue;
      }
      // 6. Tile rectangle.
      const raster::ProjectedTileRect r = raster::ProjectTileRect(view, q.U, q.V, q.RadiusF);
      const T u = q.U, v = q.V;
      const int x0 = r.X0, y0 = r.Y0, x1 = r.X1, y1 = r.Y1;
      g.U = u;
      g.V = v;
      g.ConicA = q.ConA;
      g.ConicB = q.ConB;
      g.ConicC = q.ConC;
      g.Radius = r.Radius;
      g.TileRect[0] = x0;
      g.TileRect[1] = y0;
      g.TileRect[2] = x1;
      g.TileRect[3] = y1;
      g.Opacity = Sigmoid(static_cast<T>(logit));
      if (!std::isfinite(u) || !std::isfinite(v))
      {
        g.Status = ProjectionStatus::NonFinite;
        g.Radius = 0;
        ++local[static_cast<int>(g.Status)];
        continue;
      }
      if (static_cast<long long>(x1 - x0) * (y1 - y0) == 0)
      {
        g.Status = ProjectionStatus::OffScreen;
        g.Radius = 0;
        ++local[static_cast<int>(g.Status)];
        continue;
      }
      // 7. Colour.
      if (colors)
      {
        g.ClampedChannels =
          static_cast<std::uint8_t>(ViewColor<T>(shf, shDegree, pos, campos.data(), g.Color));
      }
      g.Status = ProjectionStatus::Visible;
      ++local[0];
    }
#pragma omp critical(vis4gsProjectCounts)
    for (int k = 0; k < 6; ++k)
    {
      counts[k] += local[k];
    }
  }
  StoreCounts(counts, p.Counts);
}
} // namespace

//------------------------------------------------------------------------------
template <typename T>
ViewProjection<T> ProjectGaussians(const GaussianCloud& cloud,
  const Camera& camera,
  const RasterSettings& settings)
{
  ViewProjection<T> p;
  ProjectInto(cloud, camera, settings, p, false);
  return p;
}

//------------------------------------------------------------------------------
template <typename T>
void ProjectGaussians(const GaussianCloud& cloud,
  const Camera& camera,
  const RasterSettings& settings,
  ViewProjection<T>& projection)
{
  ProjectInto(cloud, camera, settings, projection, true);
}

//------------------------------------------------------------------------------
void ProjectGaussians(const GaussianCloud& cloud,
  const Camera& camera,
  const RasterSettings& settings,
  ViewProjection<float>& projection,
  PreparedCloudCache& cache,
  std::uint64_t cloudVersion)
{
  ProjectInto(cloud, camera, settings, projection, true, &cache, cloudVersion);
}

//------------------------------------------------------------------------------
void ProjectGaussianSubset(const GaussianCloud& cloud,
  const std::vector<std::uint32_t>& subset,
  const Camera& camera,
  const RasterSettings& settings,
  ViewProjection<float>& projection,
  PreparedCloudCache& cache,
  std::uint64_t cloudVersion)
{
  ProjectInto(cloud, camera, settings, projection, true, &cache, cloudVersion, &subset);
}

//------------------------------------------------------------------------------
PreparedView PrepareView(const ViewProjection<float>& f)
{
  PreparedView w{};
  w.W = f.Width;
  w.H = f.Height;
  w.Gx = f.TilesX;
  w.Gy = f.TilesY;
  for (int i = 0; i < 12; ++i)
  {
    w.V[i] = f.ViewMatrix[i];
  }
  for (int i = 0; i < 4; ++i)
  {
    w.F0[i] = f.FullProjection[i];
    w.F1[i] = f.FullProjection[4 + i];
    w.F3[i] = f.FullProjection[12 + i];
  }
  w.LimX = float(raster::JacobianClamp) * f.TanFovX;
  w.LimY = float(raster::JacobianClamp) * f.TanFovY;
  w.FocalX = f.Fx;
  w.FocalY = f.Fy;
  for (int i = 0; i < 3; ++i)
  {
    w.Center[i] = f.CameraCenter[i];
  }
  return w;
}

//------------------------------------------------------------------------------
// Internals shared with MultiViewRenderer.cxx (RasterInternal.h).
namespace raster
{
namespace internal
{
void ValidateCloud(const GaussianCloud& cloud, bool colors)
{
  CheckCloud(cloud, colors);
}

void PrepareGaussianForLanes(const GaussianCloud& cloud,
  std::size_t i,
  float mod,
  int shStride,
  int shUsed,
  bool colors,
  MultiViewPrepared& p,
  std::size_t k)
{
  if (i < cloud.Count)
  {
    PrepareForLanes(cloud, i, mod, shStride, shUsed, colors, p, k);
    return;
  }
  p.X[k] = p.Y[k] = p.Z[k] = 0.0f;
  p.S00[k] = p.S01[k] = p.S02[k] = p.S11[k] = p.S12[k] = p.S22[k] = 0.0f;
  p.Opacity[k] = 0.0f;
  p.Valid[k] = 0;
}

ProjectBlockFunction SelectProjection(int isa)
{
  return SelectProjectBlock(isa);
}
} // namespace internal
} // namespace raster

template ViewProjection<float> ProjectGaussians<float>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&);
template ViewProjection<double> ProjectGaussians<double>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&);
template void ProjectGaussians<float>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&,
  ViewProjection<float>&);
template void ProjectGaussians<double>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&,
  ViewProjection<double>&);

} // namespace vis4gs

// SPDX-License-Identifier: BSD-3-Clause
#include "FastCoverage.h"

#include "GaussianMath.h"
#include "KernelIsa.h"
#include "ProjectionSteps.h"
#include "RasterBounds.h"
#include "RasterKernel.h"
#include "Rasterizer.h"
#include "ThreadCount.h"

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace vis4gs
{
namespace
{

// View-independent part of ProjectGaussians<float> (same operations, same order).
struct PreparedGaussian
{
  float X, Y, Z;
  float S00, S01, S02, S11, S12, S22;
  float Opacity;
  bool Valid;
};

PreparedGaussian Prepare(const GaussianCloud& cloud, std::size_t i, float mod)
{
  PreparedGaussian p{};
  const float* pos = &cloud.Positions[3 * i];
  const float* ls = &cloud.LogScales[3 * i];
  const float* rot = &cloud.Rotations[4 * i];
  const float logit = cloud.OpacityLogits[i];
  p.Valid = ClassifyGaussian(pos, ls, rot, logit) == GaussianClass::Drawn;
  if (!p.Valid)
  {
    return p;
  }
  p.X = pos[0];
  p.Y = pos[1];
  p.Z = pos[2];
  const std::array<float, 6> sigma = GaussianCovariance<float>(ls, rot, mod);
  p.S00 = sigma[0];
  p.S01 = sigma[1];
  p.S02 = sigma[2];
  p.S11 = sigma[3];
  p.S12 = sigma[4];
  p.S22 = sigma[5];
  p.Opacity = Sigmoid(logit);
  return p;
}

// The view as the rasteriser's float projection holds it.
PreparedView ViewOf(const Camera& camera)
{
  // An empty cloud validates the camera and yields the rasteriser's own float matrices.
  GaussianCloud empty;
  RasterSettings settings;
  settings.ComputeColors = false;
  return PrepareView(ProjectGaussians<float>(empty, camera, settings));
}

int NearestIn(float u, int lo, int hi)
{
  const double r = std::floor(static_cast<double>(u) + 0.5);
  return static_cast<int>(std::max<double>(lo, std::min<double>(hi, r)));
}

// True when Gaussian g has at least one footprint pixel in view v.
bool Visible(const PreparedGaussian& g, const PreparedView& w, bool rasterMode)
{
  if (!g.Valid)
  {
    return false;
  }
  // The rasteriser's projection steps (ProjectionSteps.h).
  const raster::ProjectionView<float> view = raster::ProjectionViewOf(w);
  const raster::ProjectedViewPosition<float> t = raster::ProjectViewPosition(view, g.X, g.Y, g.Z);
  if (t.T2 <= float(raster::NearPlane))
  {
    return false;
  }
  if (rasterMode && !(g.Opacity >= raster::MinAlpha<float>()))
  {
    return false; // alpha <= o < 1/255 everywhere
  }
  const float s[6] = { g.S00, g.S01, g.S02, g.S11, g.S12, g.S22 };
  const raster::ProjectedConic<float> q = raster::ProjectConic(view, g.X, g.Y, g.Z, t, s);
  if (!q.CovFinite || q.Degenerate || !q.ConicFinite || !q.UvFinite)
  {
    return false;
  }
  const float u = q.U, v = q.V, conA = q.ConA, conB = q.ConB, conC = q.ConC;
  const raster::ProjectedTileRect r = raster::ProjectTileRect(view, u, v, q.RadiusF);
  const int radius = r.Radius, x0 = r.X0, y0 = r.Y0, x1 = r.X1, y1 = r.Y1;
  if (static_cast<long long>(x1 - x0) * (y1 - y0) == 0)
  {
    return false;
  }

  // Footprint search, exactly as ComputeFootprints decides, stopping at the first pixel.
  int xLo, xHi, yLo, yHi;
  double level;
  if (rasterMode)
  {
    xLo = x0 * raster::TileSize;
    yLo = y0 * raster::TileSize;
    xHi = std::min(x1 * raster::TileSize, w.W) - 1;
    yHi = std::min(y1 * raster::TileSize, w.H) - 1;
    level = std::min(0.0, std::log(raster::MinAlpha<double>() / static_cast<double>(g.Opacity)));
  }
  else
  {
    const double A = conA, B = conB, C = conC;
    if (!(A > 0 && C > 0 && A * C - B * B > 0))
    {
      return false;
    }
    xLo = 0;
    yLo = 0;
    xHi = w.W - 1;
    yHi = w.H - 1;
    level = -4.5;
  }
  const float opacity = g.Opacity;
  auto inside = [&](int px, int py)
  {
    const float power = raster::KernelPower<float>(
      u, v, conA, conB, conC, static_cast<float>(px), static_cast<float>(py));
    return rasterMode ? raster::KernelAlpha<float>(opacity, power) >= 0.0f : power >= -4.5f;
  };
  if (inside(NearestIn(u, xLo, xHi), NearestIn(v, yLo, yHi)))
  {
    return true;
  }
  const raster::detail::SpanBounds sb =
    raster::detail::MakeSpanBounds<float>(u, v, conA, conB, conC, level);
  if (!sb.Bounded && !rasterMode)
  {
    const double r = radius + 1.0;
    xLo = std::max(xLo, static_cast<int>(std::floor(std::max(-1e9, u - r))));
    xHi = std::min(xHi, static_cast<int>(std::ceil(std::min(1e9, u + r))));
    yLo = std::max(yLo, static_cast<int>(std::floor(std::max(-1e9, v - r))));
    yHi = std::min(yHi, static_cast<int>(std::ceil(std::min(1e9, v + r))));
  }
  if (sb.Bounded)
  {
    yLo = std::max(yLo, sb.RowMin);
    yHi = std::min(yHi, sb.RowMax);
  }
  for (int py = yLo; py <= yHi; ++py)
  {
    int xa = xLo, xb = xHi;
    if (sb.Bounded)
    {
      int ca, cb;
      if (!sb.Columns(py, ca, cb))
      {
        continue;
      }
      xa = std::max(xa, ca);
      xb = std::min(xb, cb);
    }
    for (int px = xa; px <= xb; ++px)
    {
      if (inside(px, py))
      {
        return true;
      }
    }
  }
  return false;
}

//------------------------------------------------------------------------------
// Vectorised test of 16 Gaussians per view (FastCoverageLanes.inc): one AVX-512 call or two
// AVX2 calls of 8 lanes.
constexpr int BlockLanes = 16;

struct GaussianBlock
{
  float X[BlockLanes], Y[BlockLanes], Z[BlockLanes];
  float S00[BlockLanes], S01[BlockLanes], S02[BlockLanes];
  float S11[BlockLanes], S12[BlockLanes], S22[BlockLanes];
  float Opacity[BlockLanes];
  std::int32_t Valid[BlockLanes]; ///< -1 valid, 0 invalid or past the end
};

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
namespace avx2
{
#define VIS4GS_LANES_ISA 2
#include "FastCoverageLanes.inc"
#undef VIS4GS_LANES_ISA
} // namespace avx2
namespace avx512
{
#define VIS4GS_LANES_ISA 3
#include "FastCoverageLanes.inc"
#undef VIS4GS_LANES_ISA
} // namespace avx512
#pragma GCC diagnostic pop

using BlockFunction = unsigned (*)(const GaussianBlock&, const PreparedView&, unsigned&);

unsigned BlockAvx2(const GaussianBlock& g, const PreparedView& w, unsigned& undecided)
{
  unsigned lo = 0, hi = 0;
  const unsigned visible = avx2::VisibleLanes(g, 0, w, lo) | (avx2::VisibleLanes(g, 8, w, hi) << 8);
  undecided = lo | (hi << 8);
  return visible;
}

unsigned BlockAvx512(const GaussianBlock& g, const PreparedView& w, unsigned& undecided)
{
  return avx512::VisibleLanes(g, 0, w, undecided);
}

// KernelIsa.h; the baseline is the scalar loop (nullptr).
BlockFunction SelectBlockFunction(int isa)
{
  switch (ResolveKernelIsa(isa))
  {
    case KernelIsa::Avx512:
      return &BlockAvx512;
    case KernelIsa::Avx2:
      return &BlockAvx2;
    default:
      return nullptr;
  }
}

} // namespace

//------------------------------------------------------------------------------
void CountVisibleViews(const GaussianCloud& cloud,
  const std::vector<Camera>& cameras,
  FootprintMode mode,
  std::vector<std::uint32_t>& visibleViews,
  int threads,
  double scaleModifier,
  int kernelIsa)
{
  const std::size_t n = cloud.Count;
  if (cloud.Positions.size() != 3 * n || cloud.LogScales.size() != 3 * n ||
    cloud.Rotations.size() != 4 * n || cloud.OpacityLogits.size() != n)
  {
    // Same message as the rasteriser.
    ProjectGaussians<float>(cloud, cameras.empty() ? Camera{} : cameras[0]);
  }
  std::vector<PreparedView> views;
  views.reserve(cameras.size());
  for (const Camera& camera : cameras)
  {
    views.push_back(ViewOf(camera));
  }
  visibleViews.resize(n, 0);
  const bool rasterMode = mode == FootprintMode::Rasterizer;
  const float mod = static_cast<float>(scaleModifier);
  const int nt = ThreadCount(threads);
  // The vector path decides the alpha footprint (the exact mode); the 3-sigma mode and
  // machines without AVX2 use the scalar test. Both give identical counts.
  const BlockFunction block = rasterMode ? SelectBlockFunction(kernelIsa) : nullptr;
  const std::int64_t blocks = static_cast<std::int64_t>((n + BlockLanes - 1) / BlockLanes);
  // Each Gaussian's counter is written by the one thread that owns its block: the result
  // does not depend on the thread count or the schedule.
#pragma omp parallel for schedule(dynamic, 64) num_threads(nt)
  for (std::int64_t bb = 0; bb < blocks; ++bb)
  {
    const std::size_t first = static_cast<std::size_t>(bb) * BlockLanes;
    const int lanes = static_cast<int>(std::min<std::size_t>(BlockLanes, n - first));
    PreparedGaussian g[BlockLanes];
    GaussianBlock soa;
    for (int l = 0; l < BlockLanes; ++l)
    {
      g[l] = l < lanes ? Prepare(cloud, first + l, mod) : PreparedGaussian{};
      const PreparedGaussian& p = g[l];
      const bool valid = l < lanes && p.Valid;
      soa.X[l] = valid ? p.X : 0.0f;
      soa.Y[l] = valid ? p.Y : 0.0f;
      soa.Z[l] = valid ? p.Z : 0.0f;
      soa.S00[l] = valid ? p.S00 : 0.0f;
      soa.S01[l] = valid ? p.S01 : 0.0f;
      soa.S02[l] = valid ? p.S02 : 0.0f;
      soa.S11[l] = valid ? p.S11 : 0.0f;
      soa.S12[l] = valid ? p.S12 : 0.0f;
      soa.S22[l] = valid ? p.S22 : 0.0f;
      soa.Opacity[l] = valid ? p.Opacity : 0.0f;
      soa.Valid[l] = valid ? -1 : 0;
    }
    std::uint32_t k[BlockLanes] = {};
    for (const PreparedView& w : views)
    {
      if (block)
      {
        unsigned undecided = 0;
        unsigned visible = block(soa, w, undecided);
        while (undecided != 0)
        {
          const int l = __builtin_ctz(undecided);
          undecided &= undecided - 1;
          if (Visible(g[l], w, true))
          {
            visible |= 1u << l;
          }
        }
        for (int l = 0; l < BlockLanes; ++l)
        {
          k[l] += (visible >> l) & 1u;
        }
      }
      else
      {
        for (int l = 0; l < lanes; ++l)
        {
          k[l] += Visible(g[l], w, rasterMode) ? 1u : 0u;
        }
      }
    }
    for (int l = 0; l < lanes; ++l)
    {
      visibleViews[first + l] += k[l];
    }
  }
}

//------------------------------------------------------------------------------
std::vector<std::uint8_t> VisibleInView(const GaussianCloud& cloud,
  const Camera& camera,
  FootprintMode mode,
  int threads,
  double scaleModifier,
  int kernelIsa)
{
  std::vector<std::uint32_t> counts;
  CountVisibleViews(cloud, { camera }, mode, counts, threads, scaleModifier, kernelIsa);
  return std::vector<std::uint8_t>(counts.begin(), counts.end());
}

} // namespace vis4gs

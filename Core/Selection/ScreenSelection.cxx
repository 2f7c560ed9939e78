// SPDX-License-Identifier: BSD-3-Clause
#include "ScreenSelection.h"

#include "FastCoverage.h"
#include "Footprint.h"
#include "KernelIsa.h"
#include "RasterKernel.h"
#include "ThreadCount.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace vis4gs
{
namespace
{
typedef float V16 __attribute__((vector_size(64)));
typedef std::int32_t I16 __attribute__((vector_size(64)));

void AtomicMax(std::uint32_t* slot, float value)
{
  // Non-negative floats order like their bit patterns.
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof(bits));
  std::uint32_t cur = __atomic_load_n(slot, __ATOMIC_RELAXED);
  while (bits > cur &&
    !__atomic_compare_exchange_n(slot, &cur, bits, true, __ATOMIC_RELAXED, __ATOMIC_RELAXED))
  {
  }
}
} // namespace

//------------------------------------------------------------------------------
SelectionView PrepareSelectionView(const GaussianCloud& cloud, const Camera& camera, int threads)
{
  SelectionView view;
  view.Settings.ComputeColors = false;
  view.Settings.Threads = threads;
  view.Projection = ProjectGaussians<float>(cloud, camera, view.Settings);
  view.Bins = BinGaussians<float>(view.Projection, threads);
  return view;
}

//------------------------------------------------------------------------------
void ComputeViewMaxWeights(SelectionView& view)
{
  RasterImage<float> image;
  GaussianWeightStats stats;
  CompositeTiles<float>(view.Projection, view.Bins, view.Settings, image, &stats);
  view.ViewMaxWeights = std::move(stats.MaxWeight);
  view.ViewMaxWeights.resize(view.Projection.Gaussians.size(), 0.0f);
}

//------------------------------------------------------------------------------
std::array<int, 4> BlendBox(const ViewProjection<float>& projection, std::size_t index)
{
  const auto& g = projection.Gaussians.at(index);
  if (!g.IsVisible())
  {
    return { 0, 0, -1, -1 };
  }
  const int ts = raster::TileSize;
  int x0 = std::max(0, g.TileRect[0] * ts);
  int y0 = std::max(0, g.TileRect[1] * ts);
  int x1 = std::min(projection.Width, g.TileRect[2] * ts) - 1;
  int y1 = std::min(projection.Height, g.TileRect[3] * ts) - 1;
  const double a = g.Cov2D[0], b = g.Cov2D[1], c = g.Cov2D[2];
  const double o = std::min(1.0, static_cast<double>(g.Opacity));
  if (std::isfinite(a) && std::isfinite(b) && std::isfinite(c) && a > 0 && c > 0 &&
    a * c - b * b > 0 && std::isfinite(static_cast<double>(g.U)) &&
    std::isfinite(static_cast<double>(g.V)))
  {
    if (!(255.0 * o >= 1.0))
    {
      return { 0, 0, -1, -1 }; // alpha never reaches 1/255
    }
    // o e^power >= 1/255 <=> d^T Sigma^-1 d <= r2: |dx| <= sqrt(r2 a), |dy| <= sqrt(r2 c).
    const double r2 = 2.0 * std::log(255.0 * o) * 1.001 + 1e-3;
    const double hx = std::sqrt(r2 * a) + 1.0, hy = std::sqrt(r2 * c) + 1.0;
    // Clamped to [-1, size] before the conversion to int.
    auto clampTo = [](double v, int size)
    { return static_cast<int>(std::min(static_cast<double>(size), std::max(-1.0, v))); };
    x0 = std::max(x0, clampTo(std::floor(g.U - hx), projection.Width));
    y0 = std::max(y0, clampTo(std::floor(g.V - hy), projection.Height));
    x1 = std::min(x1, clampTo(std::ceil(g.U + hx), projection.Width));
    y1 = std::min(y1, clampTo(std::ceil(g.V + hy), projection.Height));
  }
  return { x0, y0, x1, y1 };
}

//------------------------------------------------------------------------------
std::vector<RayContribution> SelectRay(const ViewProjection<float>& projection,
  const TileBins& bins,
  int x,
  int y)
{
  if (bins.TilesX != projection.TilesX || bins.TilesY != projection.TilesY ||
    bins.Offsets.size() != bins.TileCount() + 1)
  {
    throw std::invalid_argument("SelectRay: the tile bins do not belong to this projection");
  }
  std::vector<RayContribution> out;
  if (x < 0 || y < 0 || x >= projection.Width || y >= projection.Height)
  {
    return out;
  }
  const std::size_t tile = static_cast<std::size_t>(y / raster::TileSize) * projection.TilesX +
    static_cast<std::size_t>(x / raster::TileSize);
  // The same float expressions as CompositeTiles()/AttributePixels(): the blended prefix
  // carries the compositor's T bit for bit; past its early stop T keeps multiplying.
  float Tr = 1;
  bool blending = true;
  for (std::uint64_t k = bins.Offsets[tile]; k < bins.Offsets[tile + 1]; ++k)
  {
    const std::uint32_t id = bins.Ids[k];
    const auto& g = projection.Gaussians[id];
    const float power = raster::KernelPower<float>(
      g.U, g.V, g.ConicA, g.ConicB, g.ConicC, static_cast<float>(x), static_cast<float>(y));
    const float alpha = raster::KernelAlpha<float>(g.Opacity, power);
    if (alpha < 0.0f)
    {
      continue;
    }
    const float Tn = Tr * (1.0f - alpha);
    if (blending && Tn < static_cast<float>(raster::TransmittanceStop))
    {
      blending = false;
    }
    RayContribution c;
    c.Gaussian = id;
    c.ListPosition = static_cast<std::uint32_t>(k - bins.Offsets[tile] + 1);
    c.Depth = static_cast<double>(g.Depth);
    c.Alpha = static_cast<double>(alpha);
    c.Transmittance = static_cast<double>(Tr);
    c.Weight = static_cast<double>(alpha * Tr);
    c.Blended = blending;
    out.push_back(c);
    Tr = Tn;
  }
  return out;
}

//------------------------------------------------------------------------------
std::vector<RayContribution> SelectRay(const SelectionView& view, int x, int y)
{
  return SelectRay(view.Projection, view.Bins, x, y);
}

//------------------------------------------------------------------------------
std::int64_t SingleFromRay(const std::vector<RayContribution>& ray)
{
  std::int64_t best = -1;
  double bestWeight = -1;
  for (const auto& c : ray)
  {
    if (c.Blended && c.Weight > bestWeight)
    {
      best = c.Gaussian;
      bestWeight = c.Weight;
    }
  }
  return best;
}

//------------------------------------------------------------------------------
std::int64_t SelectSingle(const ViewProjection<float>& projection,
  const TileBins& bins,
  int x,
  int y)
{
  return SingleFromRay(SelectRay(projection, bins, x, y));
}

//------------------------------------------------------------------------------
std::int64_t SelectSingle(const SelectionView& view, int x, int y)
{
  return SelectSingle(view.Projection, view.Bins, x, y);
}

namespace
{
struct GroupContext
{
  const ViewProjection<float>* Projection;
  const TileBins* Bins;
  const std::vector<std::uint64_t>* Keys;
  const std::vector<std::size_t>* Starts;
  std::uint32_t* Best;
  const std::uint8_t* Targets; // nullptr: every Gaussian
  bool Cull;                   // skip the vectors outside each Gaussian's CullBox()
};

// A pixel box that contains BlendBox(projection, id) (the same construction with the largest
// opacity, 1, in place of the Gaussian's, and without the tile-rectangle clip): outside it
// the Gaussian never passes the kernel test (power <= 0, alpha >= 1/255). False (no box)
// when the 2D covariance is not positive definite or not finite.
inline bool CullBox(const ProjectedGaussian<float>& g, int width, int height, int box[4])
{
  const double a = g.Cov2D[0], b = g.Cov2D[1], c = g.Cov2D[2];
  if (!(std::isfinite(a) && std::isfinite(b) && std::isfinite(c) && a > 0 && c > 0 &&
        a * c - b * b > 0 && std::isfinite(static_cast<double>(g.U)) &&
        std::isfinite(static_cast<double>(g.V))))
  {
    return false;
  }
  // BlendBox()'s r2 = 2 ln(255 o) 1.001 + 1e-3 with o <= 1 (ln 255 = 5.54126...).
  constexpr double r2 = 2.0 * 5.5413 * 1.001 + 1e-3;
  const double hx = std::sqrt(r2 * a) + 1.0, hy = std::sqrt(r2 * c) + 1.0;
  auto clampTo = [](double v, int size)
  { return static_cast<int>(std::min(static_cast<double>(size), std::max(-1.0, v))); };
  box[0] = clampTo(std::floor(g.U - hx), width);
  box[1] = clampTo(std::floor(g.V - hy), height);
  box[2] = clampTo(std::ceil(g.U + hx), width);
  box[3] = clampTo(std::ceil(g.V + hy), height);
  return true;
}

// One tile's pixels walk the tile's list together, 16 pixels per vector, until every pixel
// has stopped (T < 1e-4) or the list ends. Per lane the arithmetic is RasterKernel.h's. A
// Gaussian is evaluated only on the vectors whose pixels' bounding box meets its blend box:
// on the others every lane would fail the kernel test (no weight, T unchanged), so skipping
// them changes nothing.
inline __attribute__((always_inline)) void ProcessGroup(const GroupContext& ctx, std::int64_t gi)
{
  const auto& proj = *ctx.Projection;
  const auto& bins = *ctx.Bins;
  const auto& keys = *ctx.Keys;
  const auto& starts = *ctx.Starts;
  std::uint32_t* best = ctx.Best;
  const int ts = raster::TileSize;
  const std::size_t b = starts[static_cast<std::size_t>(gi)];
  const std::size_t e = starts[static_cast<std::size_t>(gi) + 1];
  const std::uint64_t tile = keys[b] / 256;
  const int tx = static_cast<int>(tile % static_cast<std::uint64_t>(proj.TilesX));
  const int ty = static_cast<int>(tile / static_cast<std::uint64_t>(proj.TilesX));
  // Lanes of 16 pixels; dead lanes are padding or pixels that stopped (T < 1e-4).
  const int m = static_cast<int>(e - b);
  const int blocks = (m + 15) / 16;
  V16 px[16], py[16], T[16];
  I16 alive[16];
  int bx0[16], by0[16], bx1[16], by1[16]; // pixel bounding box of each vector's lanes
  int ax0 = proj.Width, ay0 = proj.Height, ax1 = -1, ay1 = -1; // of all lanes
  for (int k = 0; k < blocks; ++k)
  {
    bx0[k] = by0[k] = std::numeric_limits<int>::max();
    bx1[k] = by1[k] = std::numeric_limits<int>::min();
    for (int l = 0; l < 16; ++l)
    {
      const int j = 16 * k + l;
      const int local = j < m ? static_cast<int>(keys[b + static_cast<std::size_t>(j)] % 256) : 0;
      const int x = tx * ts + local % ts, y = ty * ts + local / ts;
      px[k][l] = static_cast<float>(x);
      py[k][l] = static_cast<float>(y);
      T[k][l] = 1.0f;
      alive[k][l] = j < m ? -1 : 0;
      if (j < m)
      {
        bx0[k] = std::min(bx0[k], x);
        bx1[k] = std::max(bx1[k], x);
        by0[k] = std::min(by0[k], y);
        by1[k] = std::max(by1[k], y);
      }
    }
    ax0 = std::min(ax0, bx0[k]);
    ax1 = std::max(ax1, bx1[k]);
    ay0 = std::min(ay0, by0[k]);
    ay1 = std::max(ay1, by1[k]);
  }
  // Every pixel of the tile requested (keys sorted): vector q is row q of the tile.
  const bool fullTile = m == ts * ts && ts == 16;
  // Bit q set while vector q has a live lane.
  std::uint32_t liveBlocks = blocks >= 32 ? ~0u : ((1u << blocks) - 1u);
  const float minAlpha = raster::MinAlpha<float>();
  const float stopT = static_cast<float>(raster::TransmittanceStop);
  const float maxAlpha = static_cast<float>(raster::MaxAlpha);
  // With targets, the walk ends after the tile's last target (later entries cannot change a
  // target's weight).
  std::uint64_t end = bins.Offsets[tile + 1];
  if (ctx.Targets)
  {
    std::uint64_t last = bins.Offsets[tile];
    for (std::uint64_t k = bins.Offsets[tile]; k < end; ++k)
    {
      last = ctx.Targets[bins.Ids[k]] ? k + 1 : last;
    }
    end = last;
  }
  for (std::uint64_t k = bins.Offsets[tile]; k < end && liveBlocks != 0; ++k)
  {
    if (k + 8 < end)
    {
      // The list is in depth order: its Gaussians are scattered in memory.
      const std::uint32_t next = bins.Ids[k + 8];
      const char* ahead = reinterpret_cast<const char*>(&proj.Gaussians[next]);
      __builtin_prefetch(ahead);
      __builtin_prefetch(ahead + 52);
      __builtin_prefetch(&best[next], 1);
    }
    const std::uint32_t id = bins.Ids[k];
    const auto& g = proj.Gaussians[id];
    int box[4] = { std::numeric_limits<int>::min(),
      std::numeric_limits<int>::min(),
      std::numeric_limits<int>::max(),
      std::numeric_limits<int>::max() };
    if (ctx.Cull)
    {
      CullBox(g, proj.Width, proj.Height, box);
    }
    if (box[0] > ax1 || box[2] < ax0 || box[1] > ay1 || box[3] < ay0)
    {
      continue;
    }
    V16 wmax = V16{};
    I16 stopped = I16{};
    bool any = false;
    // A whole tile's vectors are its rows: only the box's rows are visited.
    // (box is clamped to [-1, size] when culling: no overflow.)
    const bool rows = fullTile && ctx.Cull;
    const int qlo = rows ? std::max(0, box[1] - ty * ts) : 0;
    const int qhi = rows ? std::min(blocks - 1, box[3] - ty * ts) : blocks - 1;
    for (int q = qlo; q <= qhi; ++q)
    {
      if (!((liveBlocks >> q) & 1u) ||
        (!rows && (box[0] > bx1[q] || box[2] < bx0[q] || box[1] > by1[q] || box[3] < by0[q])))
      {
        continue;
      }
      any = true;
      // Exactly KernelPower / KernelAlpha of RasterKernel.h, lane by lane.
      const V16 dx = g.U - px[q];
      const V16 dy = g.V - py[q];
      const V16 power = -0.5f * (g.ConicA * dx * dx + g.ConicC * dy * dy) - g.ConicB * dx * dy;
      const I16 valid = power <= 0.0f;
      // raster::KernelExp(float) on 16 lanes, in place (bit-identical per lane).
      V16 e = valid ? power : V16{};
      raster::KernelExpLanes<V16, I16>(e);
      const V16 a = g.Opacity * e;
      const V16 alpha = a < maxAlpha ? a : V16{} + maxAlpha;
      const I16 ok = alive[q] & valid & (alpha >= minAlpha);
      const V16 Tn = T[q] * (1.0f - alpha);
      const I16 stop = ok & (Tn < stopT);
      const I16 blend = ok & ~stop;
      const V16 w = alpha * T[q];
      const V16 wb = blend ? w : V16{};
      wmax = wb > wmax ? wb : wmax;
      T[q] = blend ? Tn : T[q];
      alive[q] = alive[q] & ~stop;
      stopped |= stop;
    }
    if (!any)
    {
      continue;
    }
    float mx = 0.0f;
    bool someStopped = false;
    for (int l = 0; l < 16; ++l)
    {
      mx = wmax[l] > mx ? wmax[l] : mx;
      someStopped = someStopped || stopped[l] != 0;
    }
    if (mx > 0.0f)
    {
      AtomicMax(&best[id], mx);
    }
    if (someStopped)
    {
      for (int q = 0; q < blocks; ++q)
      {
        bool live = false;
        for (int l = 0; l < 16; ++l)
        {
          live = live || alive[q][l] != 0;
        }
        liveBlocks = live ? liveBlocks : (liveBlocks & ~(1u << q));
      }
    }
  }
}

VIS4GS_TARGET_AVX2 void ProcessGroupAvx2(const GroupContext& ctx, std::int64_t gi)
{
  ProcessGroup(ctx, gi);
}

VIS4GS_TARGET_AVX512 void ProcessGroupAvx512(const GroupContext& ctx, std::int64_t gi)
{
  ProcessGroup(ctx, gi);
}

void ProcessGroupBaseline(const GroupContext& ctx, std::int64_t gi)
{
  ProcessGroup(ctx, gi);
}
} // namespace

namespace
{
// The largest weights as float bit patterns (non-negative floats order like their bits).
std::vector<std::uint32_t> MaxWeightBitsOverPixels(const ViewProjection<float>& proj,
  const TileBins& bins,
  const std::vector<std::array<int, 2>>& pixels,
  int threads,
  const std::vector<std::uint8_t>* targets,
  bool cull = true)
{
  if (bins.TilesX != proj.TilesX || bins.TilesY != proj.TilesY ||
    bins.Offsets.size() != bins.TileCount() + 1)
  {
    throw std::invalid_argument(
      "MaxWeightsOverPixels: the tile bins do not belong to the projection");
  }
  // Unique in-image pixels, grouped by tile (key = tile * 256 + position in the tile).
  const int ts = raster::TileSize;
  std::vector<std::uint64_t> keys;
  keys.reserve(pixels.size());
  for (const auto& p : pixels)
  {
    if (p[0] < 0 || p[1] < 0 || p[0] >= proj.Width || p[1] >= proj.Height)
    {
      continue;
    }
    const std::uint64_t tile =
      static_cast<std::uint64_t>(p[1] / ts) * proj.TilesX + static_cast<std::uint64_t>(p[0] / ts);
    keys.push_back(tile * 256 + static_cast<std::uint64_t>((p[1] % ts) * ts + p[0] % ts));
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  std::vector<std::size_t> starts;
  for (std::size_t k = 0; k < keys.size(); ++k)
  {
    if (k == 0 || keys[k] / 256 != keys[k - 1] / 256)
    {
      starts.push_back(k);
    }
  }
  starts.push_back(keys.size());

  std::vector<std::uint32_t> best(proj.Gaussians.size(), 0u);
  if (targets && targets->size() != proj.Gaussians.size())
  {
    throw std::invalid_argument("MaxWeightsOverPixels: one target flag per Gaussian expected");
  }
  const GroupContext ctx{
    &proj, &bins, &keys, &starts, best.data(), targets ? targets->data() : nullptr, cull
  };
  const KernelIsa isa = ResolveKernelIsa(0);
  void (*process)(const GroupContext&, std::int64_t) = isa == KernelIsa::Avx512 ? ProcessGroupAvx512
    : isa == KernelIsa::Avx2                                                    ? ProcessGroupAvx2
                             : ProcessGroupBaseline;
  const std::int64_t groups = static_cast<std::int64_t>(starts.size()) - 1;
#pragma omp parallel for schedule(dynamic, 1) num_threads(ThreadCount(threads))
  for (std::int64_t gi = 0; gi < groups; ++gi)
  {
    process(ctx, gi);
  }
  return best;
}

inline float BitsToFloat(std::uint32_t bits)
{
  float f;
  std::memcpy(&f, &bits, sizeof(f));
  return f;
}
} // namespace

//------------------------------------------------------------------------------
std::vector<float> MaxWeightsOverPixels(const SelectionView& view,
  const std::vector<std::array<int, 2>>& pixels,
  int threads,
  const std::vector<std::uint8_t>* targets)
{
  const auto bits = MaxWeightBitsOverPixels(view.Projection, view.Bins, pixels, threads, targets);
  std::vector<float> out(bits.size());
  if (!bits.empty())
  {
    std::memcpy(out.data(), bits.data(), bits.size() * sizeof(float));
  }
  return out;
}

//------------------------------------------------------------------------------
std::vector<std::array<int, 2>> BrushPixels(const std::vector<std::array<double, 2>>& stroke,
  double radius,
  int width,
  int height)
{
  std::vector<std::array<int, 2>> out;
  if (stroke.empty() || !(radius >= 0) || width <= 0 || height <= 0)
  {
    return out;
  }
  double lo[2] = { stroke[0][0], stroke[0][1] }, hi[2] = { lo[0], lo[1] };
  for (const auto& p : stroke)
  {
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]))
    {
      throw std::invalid_argument("BrushPixels: non-finite stroke point");
    }
    for (int k = 0; k < 2; ++k)
    {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
  const int x0 = std::max(0, static_cast<int>(std::floor(lo[0] - radius)));
  const int y0 = std::max(0, static_cast<int>(std::floor(lo[1] - radius)));
  const int x1 = std::min(width - 1, static_cast<int>(std::ceil(hi[0] + radius)));
  const int y1 = std::min(height - 1, static_cast<int>(std::ceil(hi[1] + radius)));
  const double r2 = radius * radius;
  for (int y = y0; y <= y1; ++y)
  {
    for (int x = x0; x <= x1; ++x)
    {
      bool inside = false;
      for (std::size_t s = 0; s < stroke.size() && !inside; ++s)
      {
        const auto& a = stroke[s];
        const auto& b = s + 1 < stroke.size() ? stroke[s + 1] : stroke[s];
        const double ux = b[0] - a[0], uy = b[1] - a[1];
        const double l2 = ux * ux + uy * uy;
        double t = l2 > 0 ? ((x - a[0]) * ux + (y - a[1]) * uy) / l2 : 0.0;
        t = std::min(1.0, std::max(0.0, t));
        const double dx = x - (a[0] + t * ux), dy = y - (a[1] + t * uy);
        inside = dx * dx + dy * dy <= r2;
      }
      if (inside)
      {
        out.push_back({ x, y });
      }
    }
  }
  return out;
}

//------------------------------------------------------------------------------
std::vector<std::uint32_t> SelectBrush(const ViewProjection<float>& projection,
  const TileBins& bins,
  const std::vector<std::array<int, 2>>& pixels,
  double threshold,
  int threads)
{
  if (!(threshold > 0))
  {
    throw std::invalid_argument("SelectBrush: the weight threshold must be positive");
  }
  const auto w = MaxWeightBitsOverPixels(projection, bins, pixels, threads, nullptr);
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i < w.size(); ++i)
  {
    if (static_cast<double>(BitsToFloat(w[i])) >= threshold)
    {
      out.push_back(static_cast<std::uint32_t>(i));
    }
  }
  return out;
}

//------------------------------------------------------------------------------
std::vector<std::uint32_t> SelectBrush(const SelectionView& view,
  const std::vector<std::array<int, 2>>& pixels,
  double threshold,
  int threads)
{
  return SelectBrush(view.Projection, view.Bins, pixels, threshold, threads);
}

namespace
{
// Visible-only Frame selection of the candidates (centre inside [x0, x1] x [y0, y1], already
// clipped) from maxima M with M[i] >= the largest weight of i over the rectangle, and equal to
// it when i's BlendBox lies inside the rectangle (the maxima over the view, or over the tiles
// the rectangle touches): reject M < threshold, accept boxes inside, and replay the rectangle's
// pixels for the rest (near its border): first the pixel nearest each centre (where an
// unoccluded Gaussian weighs most), then, for those still undecided, every pixel of the
// rectangle inside their boxes.
std::vector<std::uint32_t> FrameFromMaxima(const ViewProjection<float>& proj,
  const TileBins& bins,
  const std::vector<float>& maxima,
  const std::vector<std::uint32_t>& candidates,
  int x0,
  int y0,
  int x1,
  int y1,
  const FrameOptions& options)
{
  const int rw = x1 - x0 + 1;
  std::vector<std::uint32_t> out, ambiguous;
  for (std::uint32_t i : candidates)
  {
    if (!(static_cast<double>(maxima[i]) >= options.WeightThreshold))
    {
      continue;
    }
    const auto box = BlendBox(proj, i);
    if (box[0] >= x0 && box[1] >= y0 && box[2] <= x1 && box[3] <= y1)
    {
      out.push_back(i);
    }
    else
    {
      ambiguous.push_back(i);
    }
  }
  std::vector<std::uint8_t> targets(ambiguous.empty() ? 0 : proj.Gaussians.size(), 0);
  for (int round = 0; round < 2 && !ambiguous.empty(); ++round)
  {
    for (std::uint32_t i : ambiguous)
    {
      targets[i] = static_cast<std::uint8_t>(round + 1);
    }
    std::vector<std::uint8_t> mark(static_cast<std::size_t>(rw) * (y1 - y0 + 1), 0);
    for (std::uint32_t i : ambiguous)
    {
      std::array<int, 4> box = BlendBox(proj, i);
      if (round == 0)
      {
        const auto& g = proj.Gaussians[i];
        const int cx = std::min(x1, std::max(x0, static_cast<int>(std::lround(g.U))));
        const int cy = std::min(y1, std::max(y0, static_cast<int>(std::lround(g.V))));
        box = { cx, cy, cx, cy };
      }
      const int bx0 = std::max(x0, box[0]), bx1 = std::min(x1, box[2]);
      for (int y = std::max(y0, box[1]); y <= std::min(y1, box[3]) && bx0 <= bx1; ++y)
      {
        std::fill_n(&mark[static_cast<std::size_t>(y - y0) * rw + (bx0 - x0)],
          bx1 - bx0 + 1,
          std::uint8_t(1));
      }
    }
    std::vector<std::array<int, 2>> pixels;
    for (int y = y0; y <= y1; ++y)
    {
      for (int x = x0; x <= x1; ++x)
      {
        if (mark[static_cast<std::size_t>(y - y0) * rw + (x - x0)])
        {
          pixels.push_back({ x, y });
        }
      }
    }
    const auto w =
      MaxWeightBitsOverPixels(proj, bins, pixels, options.Threads, &targets, options.CullReplay);
    std::vector<std::uint32_t> undecided;
    for (std::uint32_t i : ambiguous)
    {
      if (static_cast<double>(BitsToFloat(w[i])) >= options.WeightThreshold)
      {
        out.push_back(i);
      }
      else if (round == 0)
      {
        undecided.push_back(i);
      }
      targets[i] = 0;
    }
    ambiguous.swap(undecided);
  }
  std::sort(out.begin(), out.end());
  return out;
}

namespace
{
// The index of @p b's lowest set bit (@p b non-zero).
inline unsigned CountTrailingZeros(std::uint64_t b)
{
#if defined(__GNUC__)
  return static_cast<unsigned>(__builtin_ctzll(b));
#else
  unsigned n = 0;
  for (; (b & 1u) == 0; b >>= 1)
  {
    ++n;
  }
  return n;
#endif
}

// The number of set bits of @p b.
inline int PopCount(std::uint64_t b)
{
#if defined(__GNUC__)
  return __builtin_popcountll(b);
#else
  int n = 0;
  for (; b != 0; b &= b - 1)
  {
    ++n;
  }
  return n;
#endif
}

// Asks for both cache lines of a projected Gaussian (its centre, its status).
inline void Prefetch(const ProjectedGaussian<float>* g)
{
#if defined(__GNUC__)
  __builtin_prefetch(&g->U);
  __builtin_prefetch(&g->Status);
#else
  (void)g;
#endif
}
} // namespace

// The rectangle [x0, x1] x [y0, y1] (corners in any order) clipped to @p proj's image in
// place; false when nothing of it is left.
bool ClipFrame(const ViewProjection<float>& proj, int& x0, int& y0, int& x1, int& y1)
{
  if (x0 > x1)
  {
    std::swap(x0, x1);
  }
  if (y0 > y1)
  {
    std::swap(y0, y1);
  }
  x0 = std::max(0, x0);
  y0 = std::max(0, y0);
  x1 = std::min(proj.Width - 1, x1);
  y1 = std::min(proj.Height - 1, y1);
  return x0 <= x1 && y0 <= y1;
}

// Whether @p g is one of Frame's candidates for the clipped rectangle: visible, its centre in
// the rectangle's pixels.
inline bool CentreInFrame(const ProjectedGaussian<float>& g, int x0, int y0, int x1, int y1)
{
  const float ulo = x0 - 0.5f, uhi = x1 + 0.5f, vlo = y0 - 0.5f, vhi = y1 + 0.5f;
  return g.IsVisible() && g.U >= ulo && g.U < uhi && g.V >= vlo && g.V < vhi;
}

// Frame's candidates: the projected Gaussians whose centre lies in [x0, x1] x [y0, y1] (corners
// in any order; clipped to the image in place), ascending.
std::vector<std::uint32_t> FrameCandidates(const ViewProjection<float>& proj,
  int& x0,
  int& y0,
  int& x1,
  int& y1,
  int threads)
{
  std::vector<std::uint32_t> candidates;
  if (!ClipFrame(proj, x0, y0, x1, y1))
  {
    return candidates;
  }
  {
    // Flags in parallel (the scan reads one cache line per Gaussian), compacted in order.
    const std::int64_t n = static_cast<std::int64_t>(proj.Gaussians.size());
    std::vector<std::uint8_t> inside(static_cast<std::size_t>(n));
    const ProjectedGaussian<float>* gs = proj.Gaussians.data();
    std::uint8_t* flags = inside.data();
    const int cx0 = x0, cy0 = y0, cx1 = x1, cy1 = y1;
#pragma omp parallel for schedule(static) num_threads(ThreadCount(threads))
    for (std::int64_t i = 0; i < n; ++i)
    {
      flags[i] = CentreInFrame(gs[i], cx0, cy0, cx1, cy1);
    }
    for (std::int64_t i = 0; i < n; ++i)
    {
      if (flags[i])
      {
        candidates.push_back(static_cast<std::uint32_t>(i));
      }
    }
  }
  return candidates;
}

std::vector<std::uint32_t> SelectFrameImpl(const ViewProjection<float>& proj,
  const TileBins& bins,
  const std::vector<float>* viewMaxima,
  int x0,
  int y0,
  int x1,
  int y1,
  const FrameOptions& options)
{
  const std::vector<std::uint32_t> candidates =
    FrameCandidates(proj, x0, y0, x1, y1, options.Threads);
  if (options.IncludeOccluded || candidates.empty())
  {
    return candidates;
  }
  if (!(options.WeightThreshold > 0))
  {
    throw std::invalid_argument("SelectFrame: the weight threshold must be positive");
  }
  if (viewMaxima && viewMaxima->size() == proj.Gaussians.size())
  {
    return FrameFromMaxima(proj, bins, *viewMaxima, candidates, x0, y0, x1, y1, options);
  }
  std::vector<std::array<int, 2>> pixels;
  pixels.reserve(static_cast<std::size_t>(x1 - x0 + 1) * (y1 - y0 + 1));
  // Tile by tile keeps each thread on one tile list.
  const int ts = raster::TileSize;
  for (int ty = y0 / ts; ty <= y1 / ts; ++ty)
  {
    for (int tx = x0 / ts; tx <= x1 / ts; ++tx)
    {
      for (int y = std::max(y0, ty * ts); y <= std::min(y1, ty * ts + ts - 1); ++y)
      {
        for (int x = std::max(x0, tx * ts); x <= std::min(x1, tx * ts + ts - 1); ++x)
        {
          pixels.push_back({ x, y });
        }
      }
    }
  }
  const auto w =
    MaxWeightBitsOverPixels(proj, bins, pixels, options.Threads, nullptr, options.CullReplay);
  std::vector<std::uint32_t> out;
  for (std::uint32_t i : candidates)
  {
    if (static_cast<double>(BitsToFloat(w[i])) >= options.WeightThreshold)
    {
      out.push_back(i);
    }
  }
  return out;
}
} // namespace

//------------------------------------------------------------------------------
std::vector<std::uint32_t> SelectFrame(const SelectionView& view,
  int x0,
  int y0,
  int x1,
  int y1,
  const FrameOptions& options)
{
  return SelectFrameImpl(view.Projection, view.Bins, &view.ViewMaxWeights, x0, y0, x1, y1, options);
}

//------------------------------------------------------------------------------
std::vector<std::uint32_t> SelectFrame(const ViewProjection<float>& projection,
  const TileBins& bins,
  int x0,
  int y0,
  int x1,
  int y1,
  const FrameOptions& options)
{
  if (bins.TilesX != projection.TilesX || bins.TilesY != projection.TilesY ||
    bins.Offsets.size() != bins.TileCount() + 1)
  {
    throw std::invalid_argument("SelectFrame: the tile bins do not belong to the projection");
  }
  return SelectFrameImpl(projection, bins, nullptr, x0, y0, x1, y1, options);
}
//------------------------------------------------------------------------------
bool RecordAnswers(const PixelWeightRecord& record, double threshold)
{
  // A weight w passes when double(w) >= threshold; the record kept every w >= its float
  // threshold, so it holds every passing blend exactly when threshold >= that float.
  return record.Complete && threshold >= static_cast<double>(record.Threshold);
}

namespace
{
// The Gaussians (ascending, each once) of the @p count with a kept weight >= @p threshold at a
// pixel where @p wanted (one 256-bit mask per tile, empty: none) is set. One bit per Gaussian
// (611 KB at 4.89M, which stays in cache while the blends scatter into it, where a byte per
// Gaussian did not), read back a word at a time.
std::vector<std::uint32_t> RecordedAt(const PixelWeightRecord& record,
  std::size_t count,
  const std::vector<std::array<std::uint64_t, 4>>& wanted,
  double threshold)
{
  if (!record.Complete || record.Weights.size() != wanted.size())
  {
    throw std::invalid_argument("pixel weight record: incomplete, or of another image");
  }
  if (!RecordAnswers(record, threshold))
  {
    throw std::invalid_argument("pixel weight record: the threshold is below the record's");
  }
  std::vector<std::uint64_t> bits((count + 63) / 64, 0);
  for (std::size_t t = 0; t < wanted.size(); ++t)
  {
    const auto& mask = wanted[t];
    if ((mask[0] | mask[1] | mask[2] | mask[3]) == 0)
    {
      continue;
    }
    const bool whole = (mask[0] & mask[1] & mask[2] & mask[3]) == ~std::uint64_t(0);
    const std::vector<PixelWeight>& w = record.Weights[t];
    const std::vector<std::uint8_t>& p = record.Pixels[t];
    for (std::size_t k = 0; k < w.size(); ++k)
    {
      if ((whole || ((mask[p[k] >> 6] >> (p[k] & 63)) & 1u)) &&
        static_cast<double>(w[k].Weight) >= threshold && w[k].Gaussian < count)
      {
        bits[w[k].Gaussian >> 6] |= std::uint64_t(1) << (w[k].Gaussian & 63);
      }
    }
  }
  std::size_t total = 0;
  for (const std::uint64_t b : bits)
  {
    total += static_cast<std::size_t>(PopCount(b));
  }
  std::vector<std::uint32_t> out;
  out.reserve(total);
  for (std::size_t word = 0; word < bits.size(); ++word)
  {
    for (std::uint64_t b = bits[word]; b != 0; b &= b - 1)
    {
      out.push_back(static_cast<std::uint32_t>(64 * word + CountTrailingZeros(b)));
    }
  }
  return out;
}

// One 256-bit pixel mask per tile of the record's image.
std::vector<std::array<std::uint64_t, 4>> TileMasks(const PixelWeightRecord& record)
{
  const int ts = raster::TileSize;
  const int tilesY = (record.Height + ts - 1) / ts;
  return std::vector<std::array<std::uint64_t, 4>>(
    static_cast<std::size_t>(record.TilesX) * static_cast<std::size_t>(std::max(0, tilesY)),
    std::array<std::uint64_t, 4>{ 0, 0, 0, 0 });
}

void SetPixel(const PixelWeightRecord& record,
  std::vector<std::array<std::uint64_t, 4>>& masks,
  int x,
  int y)
{
  const int ts = raster::TileSize;
  if (x < 0 || y < 0 || x >= record.Width || y >= record.Height)
  {
    return;
  }
  const std::size_t tile =
    static_cast<std::size_t>(y / ts) * record.TilesX + static_cast<std::size_t>(x / ts);
  const unsigned bit = static_cast<unsigned>((y % ts) * ts + x % ts);
  masks[tile][bit >> 6] |= std::uint64_t(1) << (bit & 63);
}
} // namespace

//------------------------------------------------------------------------------
std::vector<std::uint32_t> SelectBrush(const PixelWeightRecord& record,
  std::size_t count,
  const std::vector<std::array<int, 2>>& pixels,
  double threshold)
{
  if (!(threshold > 0))
  {
    throw std::invalid_argument("SelectBrush: the weight threshold must be positive");
  }
  auto masks = TileMasks(record);
  for (const auto& p : pixels)
  {
    SetPixel(record, masks, p[0], p[1]);
  }
  return RecordedAt(record, count, masks, threshold);
}

//------------------------------------------------------------------------------
std::vector<std::uint32_t> SelectFrame(const ViewProjection<float>& projection,
  const PixelWeightRecord& record,
  int x0,
  int y0,
  int x1,
  int y1,
  const FrameOptions& options)
{
  if (record.Width != projection.Width || record.Height != projection.Height)
  {
    throw std::invalid_argument("SelectFrame: the pixel weight record is of another image");
  }
  if (options.IncludeOccluded)
  {
    return FrameCandidates(projection, x0, y0, x1, y1, options.Threads);
  }
  if (!ClipFrame(projection, x0, y0, x1, y1))
  {
    return {};
  }
  if (!(options.WeightThreshold > 0))
  {
    throw std::invalid_argument("SelectFrame: the weight threshold must be positive");
  }
  // The Gaussians with a kept blend >= the threshold in the rectangle first, then the centre
  // test on those only: a visible-only pick reads the rectangle's blends and its flagged
  // Gaussians, not every projected Gaussian (about 100 bytes each: 0.5 GB at 4.89M).
  auto masks = TileMasks(record);
  for (int y = y0; y <= y1; ++y)
  {
    for (int x = x0; x <= x1; ++x)
    {
      SetPixel(record, masks, x, y);
    }
  }
  std::vector<std::uint32_t> out =
    RecordedAt(record, projection.Gaussians.size(), masks, options.WeightThreshold);
  // The candidates' projections lie scattered over the whole projection (about 100 bytes a
  // Gaussian, 0.5 GB at 4.89M): each is a cache miss, fetched some candidates ahead.
  const ProjectedGaussian<float>* gs = projection.Gaussians.data();
  const std::size_t n = out.size(), ahead = 16;
  std::size_t kept = 0;
  for (std::size_t k = 0; k < n; ++k)
  {
    if (k + ahead < n)
    {
      Prefetch(&gs[out[k + ahead]]);
    }
    if (CentreInFrame(gs[out[k]], x0, y0, x1, y1))
    {
      out[kept++] = out[k];
    }
  }
  out.resize(kept);
  return out;
}

//------------------------------------------------------------------------------
RayQuery PixelRay(const Camera& camera, double x, double y, double sigmas)
{
  if (camera.Width <= 0 || camera.Height <= 0 || !(camera.Fx > 0) || !(camera.Fy > 0))
  {
    throw std::invalid_argument("PixelRay: camera '" + camera.Name + "' has no valid intrinsics");
  }
  const auto& m = camera.WorldToCamera;
  const double c[3] = {
    (x - (camera.Width - 1) / 2.0) / camera.Fx, (y - (camera.Height - 1) / 2.0) / camera.Fy, 1.0
  };
  RayQuery ray;
  ray.Origin = camera.Center();
  double n = 0;
  for (int k = 0; k < 3; ++k)
  {
    ray.Direction[k] = m[k] * c[0] + m[4 + k] * c[1] + m[8 + k] * c[2];
    n += ray.Direction[k] * ray.Direction[k];
  }
  n = std::sqrt(n);
  for (auto& v : ray.Direction)
  {
    v /= n;
  }
  ray.Sigmas = sigmas;
  ray.TMin = 0;
  return ray;
}

//------------------------------------------------------------------------------
std::array<std::array<double, 3>, 5> CameraFrustum(const Camera& camera, double depth)
{
  if (camera.Width <= 0 || camera.Height <= 0 || !(camera.Fx > 0) || !(camera.Fy > 0))
  {
    throw std::invalid_argument(
      "CameraFrustum: camera '" + camera.Name + "' has no valid intrinsics");
  }
  const auto& m = camera.WorldToCamera;
  std::array<std::array<double, 3>, 5> out;
  out[0] = camera.Center();
  const double W = camera.Width, H = camera.Height;
  const double corners[4][2] = {
    { -0.5, -0.5 }, { W - 0.5, -0.5 }, { W - 0.5, H - 0.5 }, { -0.5, H - 0.5 }
  };
  for (int k = 0; k < 4; ++k)
  {
    const double c[3] = { (corners[k][0] - (W - 1) / 2.0) / camera.Fx * depth,
      (corners[k][1] - (H - 1) / 2.0) / camera.Fy * depth,
      depth };
    // X = R^T (c - t)
    const double d[3] = { c[0] - m[3], c[1] - m[7], c[2] - m[11] };
    for (int r = 0; r < 3; ++r)
    {
      out[k + 1][r] = m[r] * d[0] + m[4 + r] * d[1] + m[8 + r] * d[2];
    }
  }
  return out;
}

//------------------------------------------------------------------------------
double AutoFrustumDepth(const std::vector<Camera>& cameras,
  const float* positions,
  std::size_t count)
{
  const std::size_t stride = std::max<std::size_t>(1, count / 65536);
  std::array<std::vector<double>, 3> axes;
  for (std::size_t i = 0; i < count; i += stride)
  {
    const float* p = positions + 3 * i;
    if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))
    {
      for (int k = 0; k < 3; ++k)
      {
        axes[k].push_back(p[k]);
      }
    }
  }
  std::vector<double> distances;
  if (!axes[0].empty())
  {
    std::array<double, 3> median;
    for (int k = 0; k < 3; ++k)
    {
      auto mid = axes[k].begin() + axes[k].size() / 2;
      std::nth_element(axes[k].begin(), mid, axes[k].end());
      median[k] = *mid;
    }
    for (const Camera& c : cameras)
    {
      const auto o = c.Center();
      distances.push_back(std::hypot(o[0] - median[0], o[1] - median[1], o[2] - median[2]));
    }
  }
  // A tenth of the camera centres' spread (a ring around an object: about a fifth of the way
  // to it) ...
  double depth = 0;
  if (!cameras.empty())
  {
    std::array<double, 3> lo, hi;
    lo.fill(std::numeric_limits<double>::infinity());
    hi.fill(-std::numeric_limits<double>::infinity());
    for (const Camera& c : cameras)
    {
      const auto o = c.Center();
      for (int k = 0; k < 3; ++k)
      {
        lo[k] = std::min(lo[k], o[k]);
        hi[k] = std::max(hi[k], o[k]);
      }
    }
    depth = 0.1 * std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  }
  // ... but at least a tenth of the way to the scene, where the cameras stand close together
  // (forward-facing captures, a single camera) and the spread says nothing of the scene.
  if (!distances.empty())
  {
    auto mid = distances.begin() + distances.size() / 2;
    std::nth_element(distances.begin(), mid, distances.end());
    depth = std::max(depth, 0.1 * *mid);
  }
  return depth > 0 && std::isfinite(depth) ? depth : 1.0;
}

//------------------------------------------------------------------------------
std::vector<std::uint32_t> CountVisibleInViews(const GaussianCloud& cloud,
  const std::vector<std::uint32_t>& indices,
  const std::vector<Camera>& cameras,
  int threads)
{
  GaussianCloud subset;
  subset.Count = indices.size();
  subset.ShDegree = 0;
  subset.Positions.resize(3 * indices.size());
  subset.LogScales.resize(3 * indices.size());
  subset.Rotations.resize(4 * indices.size());
  subset.OpacityLogits.resize(indices.size());
  for (std::size_t k = 0; k < indices.size(); ++k)
  {
    const std::size_t i = indices[k];
    if (i >= cloud.Count)
    {
      throw std::invalid_argument("CountVisibleInViews: index " + std::to_string(i) +
        " is outside the cloud of " + std::to_string(cloud.Count));
    }
    std::copy_n(&cloud.Positions[3 * i], 3, &subset.Positions[3 * k]);
    std::copy_n(&cloud.LogScales[3 * i], 3, &subset.LogScales[3 * k]);
    std::copy_n(&cloud.Rotations[4 * i], 4, &subset.Rotations[4 * k]);
    subset.OpacityLogits[k] = cloud.OpacityLogits[i];
  }
  std::vector<std::uint32_t> counts(cameras.size(), 0);
  if (indices.empty())
  {
    return counts;
  }
  // Visible = a footprint of at least one pixel: the fast coverage's test, which stops at the
  // first pixel found (identical to projecting and counting every footprint pixel, as the
  // test against the brute-force footprints checks), since a Frame of 200k Gaussians is counted
  // on the GUI thread after the pick (4 views: ~150 ms counting pixels).
  for (std::size_t v = 0; v < cameras.size(); ++v)
  {
    const std::vector<std::uint8_t> visible =
      VisibleInView(subset, cameras[v], FootprintMode::Rasterizer, threads);
    counts[v] = static_cast<std::uint32_t>(
      std::count_if(visible.begin(), visible.end(), [](std::uint8_t f) { return f != 0; }));
  }
  return counts;
}

} // namespace vis4gs

// SPDX-License-Identifier: BSD-3-Clause
#include "MultiViewRenderer.h"

#include "GaussianMath.h"
#include "MultiViewData.h"
#include "RadixSort.h"
#include "RasterInternal.h"
#include "ThreadCount.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

// MultiViewRenderer: the view-independent preparation, the per-view projection (16 lanes,
// ProjectionLanes.inc through RasterProjection.cxx), the global (depth, index) sort, binning and
// compositing (CompositeLanes.inc through RasterCompositing.cxx). The footprint pass is in
// Footprint.cxx.
namespace vis4gs
{

using namespace raster::internal;

//------------------------------------------------------------------------------
MultiViewRenderer::MultiViewRenderer(const GaussianCloud& cloud,
  const RasterSettings& settings,
  const PreparationShare& share)
  : Impl(new Data)
{
  ValidateCloud(cloud, settings.ComputeColors);
  Data& d = *this->Impl;
  d.Cloud = &cloud;
  d.Settings = settings;
  d.Count = cloud.Count;
  d.Padded = (cloud.Count + 15) / 16 * 16;
  d.Colors = settings.ComputeColors;
  d.ShDegree = settings.ShDegree < 0 ? cloud.ShDegree : std::min(settings.ShDegree, cloud.ShDegree);
  d.ShDegree = std::max(0, d.ShDegree);
  d.ViewIndependentColor = d.ShDegree == 0;
  d.Threads = ThreadCount(settings.Threads);
  MultiViewPrepared& p = d.Prepared;
  const bool color = d.Colors && d.ViewIndependentColor;
  void* shared = nullptr;
  if (share.Map)
  {
    shared = share.Map(MultiViewPrepared::Bytes(d.Padded, color));
  }
  // Not cleared: the loop below writes every element of its range (padding too), on every
  // thread, so that the fresh pages are touched in parallel.
  p.Allocate(d.Padded, color, shared);
  const int shStride = d.Colors ? 3 * cloud.ShCoefficientCount() : 0;
  const int shUsed = 3 * (d.ShDegree + 1) * (d.ShDegree + 1);
  const bool colors = d.Colors;
  const bool viewIndependent = d.ViewIndependentColor;
  const float mod = static_cast<float>(settings.ScaleModifier);
  // Shared: this process's part, in blocks of 16 (the lanes' unit).
  const std::int64_t blocks = static_cast<std::int64_t>(d.Padded / 16);
  const std::int64_t first = shared ? 16 * (blocks * share.Part / share.Parts) : 0;
  const std::int64_t last =
    shared ? 16 * (blocks * (share.Part + 1) / share.Parts) : static_cast<std::int64_t>(d.Padded);
#pragma omp parallel for schedule(static) num_threads(d.Threads)
  for (std::int64_t ii = first; ii < last; ++ii)
  {
    const std::size_t i = static_cast<std::size_t>(ii);
    PrepareGaussianForLanes(cloud, i, mod, shStride, shUsed, colors, p, i);
    if (colors && viewIndependent)
    {
      float col[3] = { 0, 0, 0 };
      if (p.Valid[i] != 0)
      {
        const float dir[3] = { 0, 0, 0 }; // unused at degree 0
        ShColor<float>(&cloud.SH[i * shStride], 0, dir, col);
      }
      for (int ch = 0; ch < 3; ++ch)
      {
        p.Color[3 * i + ch] = std::max(col[ch], 0.0f);
      }
    }
  }
  if (shared && share.Wait)
  {
    share.Wait();
  }
}

MultiViewRenderer::~MultiViewRenderer() = default;

const ProjectionCounts& MultiViewRenderer::Counts() const
{
  return this->Impl->Counts;
}

const std::vector<std::uint32_t>& MultiViewRenderer::SortedIds() const
{
  return this->Impl->Sorted;
}

//------------------------------------------------------------------------------
void MultiViewRenderer::Project(const Camera& camera)
{
  Data& d = *this->Impl;
  const GaussianCloud& cloud = *d.Cloud;
  {
    // An empty cloud validates the camera and yields the rasteriser's own float matrices.
    GaussianCloud empty;
    RasterSettings rs;
    rs.ComputeColors = false;
    d.Frame = ProjectGaussians<float>(empty, camera, rs);
  }
  d.Camera = PrepareView(d.Frame);
  const PreparedView& w = d.Camera;

  const ProjectBlockFunction block = SelectProjection(d.Settings.KernelIsa);
  const int chunks = d.Threads;
  const std::int64_t blocks = static_cast<std::int64_t>(d.Padded / 16);
  const std::size_t n = d.Count;
  if (w.Gx > 0xFFFF || w.Gy > 0xFFFF)
  {
    throw std::invalid_argument("camera '" + camera.Name + "': " + std::to_string(camera.Width) +
      "x" + std::to_string(camera.Height) +
      " pixels is over the many-view renderer's 65535 x 65535 tiles of 16 pixels");
  }
  // Every slot is written below (a record, or Invisible), so no clearing is needed.
  ResizeKeep(d.Records, d.Padded);
  // The sort keys (two buffers of 8 bytes a visible Gaussian) live in the kernels' memory (40
  // bytes a Gaussian), free until step 4 writes the kernels, once the keys are read.
  static_assert(sizeof(raster::detail::KernelGaussian<float>) >= 2 * sizeof(std::uint64_t),
    "two sort keys fit in a kernel's place");
  ResizeKeep(d.Kernels, d.Padded);
  d.ChunkVisible.assign(static_cast<std::size_t>(chunks) + 1, 0);
  Data::VisibleRecord* records = d.Records.data();
  std::uint64_t* keys = reinterpret_cast<std::uint64_t*>(d.Kernels.data());
  const MultiViewPrepared& prep = d.Prepared;
  const bool colors = d.Colors;
  const bool viewIndependent = d.ViewIndependentColor;
  const int shDegree = d.ShDegree;
  const int shStride = colors ? 3 * cloud.ShCoefficientCount() : 0;
  std::size_t counts[6] = { 0, 0, 0, 0, 0, 0 };
  std::uint32_t depthOr = 0, depthAnd = ~0u;
  // (1) Projection of chunks of contiguous blocks, 16 lanes at a time into a scratch, and (2)
  // each visible Gaussian's record at its index with its (depth bits, index) key, the keys of
  // a chunk from the chunk's first index on. The colour of SH degree > 0 is evaluated here, in
  // index order, where the coefficients (192 bytes a Gaussian at degree 3) stream through the
  // cache; in depth order (step 4) each Gaussian's were three random misses.
#pragma omp parallel num_threads(chunks) reduction(| : depthOr) reduction(& : depthAnd)
  {
    std::size_t local[6] = { 0, 0, 0, 0, 0, 0 };
    MultiViewProjected out;
    for (auto* v : { &out.U, &out.V, &out.A, &out.B, &out.C, &out.Depth })
    {
      v->assign(16, 0.0f);
    }
    for (auto* v : { &out.Status, &out.Radius, &out.X0, &out.Y0, &out.X1, &out.Y1 })
    {
      v->assign(16, 0);
    }
#pragma omp for schedule(static, 1)
    for (int c = 0; c < chunks; ++c)
    {
      const std::int64_t b = blocks * c / chunks, e = blocks * (c + 1) / chunks;
      std::size_t k = static_cast<std::size_t>(b) * 16;
      for (std::int64_t bb = b; bb < e; ++bb)
      {
        const std::size_t first = static_cast<std::size_t>(bb) * 16;
        block(prep, first, w, out, 0);
        for (std::size_t l = 0; l < 16; ++l)
        {
          const std::size_t i = first + l;
          Data::VisibleRecord& rec = records[i];
          const std::int32_t status = i < n ? out.Status[l] : -1;
          if (status >= 0)
          {
            ++local[status];
          }
          if (status != 0)
          {
            rec.Id = Data::Invisible;
            continue;
          }
          float col[3] = { 0, 0, 0 };
          if (colors && viewIndependent)
          {
            col[0] = prep.Color[3 * i];
            col[1] = prep.Color[3 * i + 1];
            col[2] = prep.Color[3 * i + 2];
          }
          else if (colors)
          {
            ViewColor<float>(&cloud.SH[i * static_cast<std::size_t>(shStride)],
              shDegree,
              &cloud.Positions[3 * i],
              w.Center,
              col);
          }
          rec.Kernel = { out.U[l],
            out.V[l],
            out.A[l],
            out.B[l],
            out.C[l],
            prep.Opacity[i],
            col[0],
            col[1],
            col[2],
            out.Depth[l] };
          rec.Rect = { static_cast<std::uint16_t>(out.X0[l]),
            static_cast<std::uint16_t>(out.Y0[l]),
            static_cast<std::uint16_t>(out.X1[l]),
            static_cast<std::uint16_t>(out.Y1[l]) };
          rec.Radius = out.Radius[l];
          rec.Id = static_cast<std::uint32_t>(i);
          const float o = prep.Opacity[i];
          rec.Level = o >= raster::MinAlpha<float>()
            ? std::min(0.0, std::log(raster::MinAlpha<double>() / static_cast<double>(o)))
            : 0.0;
          std::uint32_t bits;
          std::memcpy(&bits, &out.Depth[l], sizeof(bits));
          depthOr |= bits;
          depthAnd &= bits;
          keys[k++] = (static_cast<std::uint64_t>(bits) << 32) | static_cast<std::uint64_t>(i);
        }
      }
      d.ChunkVisible[static_cast<std::size_t>(c) + 1] = k - static_cast<std::size_t>(b) * 16;
    }
#pragma omp critical(vis4gsMultiViewCounts)
    for (int k = 0; k < 6; ++k)
    {
      counts[k] += local[k];
    }
  }
  d.Counts.Visible = counts[0];
  d.Counts.InvalidParameters = counts[1];
  d.Counts.NearPlane = counts[2];
  d.Counts.Degenerate = counts[3];
  d.Counts.NonFinite = counts[4];
  d.Counts.OffScreen = counts[5];
  // The chunks' keys made contiguous, in chunk (so index) order. A chunk's keys move down
  // (its first key stays at or after where the previous chunks' keys end), and in chunk order
  // no move overwrites keys not yet moved.
  std::size_t visible = 0;
  for (int c = 0; c < chunks; ++c)
  {
    const std::size_t from = static_cast<std::size_t>(blocks * c / chunks) * 16;
    const std::size_t count =
      static_cast<std::size_t>(d.ChunkVisible[static_cast<std::size_t>(c) + 1]);
    if (from != visible && count > 0)
    {
      std::memmove(keys + visible, keys + from, count * sizeof(std::uint64_t));
    }
    visible += count;
  }
  const std::int64_t nv = static_cast<std::int64_t>(visible);
  // (3) Global (depth, index) order: stable radix sort on the depth bits that differ (as
  // BinGaussians<float>; depth > 0.2, so the bits order like the values).
  const std::uint64_t* sorted =
    RadixSortKeys(keys, keys + visible, nv, 32, 32 + DifferingBits(depthOr, depthAnd), chunks);

  // (4) The visible Gaussians in sorted order (the keys' low bits), which frees the keys'
  // memory for the kernels; then their data in that order: kernel and colour, tile rectangle,
  // spans.
  ResizeKeep(d.Sorted, visible);
#pragma omp parallel for schedule(static) num_threads(chunks)
  for (std::int64_t ss = 0; ss < nv; ++ss)
  {
    d.Sorted[static_cast<std::size_t>(ss)] =
      static_cast<std::uint32_t>(sorted[static_cast<std::size_t>(ss)]);
  }
  const std::uint32_t* order = d.Sorted.data();
  ResizeKeep(d.Kernels, visible);
  ResizeKeep(d.Bounds, visible);
  ResizeKeep(d.Rects, visible);
#pragma omp parallel for schedule(static) num_threads(chunks)
  for (std::int64_t ss = 0; ss < nv; ++ss)
  {
    const std::size_t s = static_cast<std::size_t>(ss);
    if (ss + 16 < nv)
    {
      const std::uint32_t ahead = order[s + 16];
      __builtin_prefetch(&records[ahead]);
    }
    const std::uint32_t pos = order[s];
    const Data::VisibleRecord& rec = records[pos];
    const raster::detail::KernelGaussian<float> k = rec.Kernel;
    d.Kernels[s] = k;
    d.Rects[s] = rec.Rect;
    if (k.O >= raster::MinAlpha<float>())
    {
      raster::detail::SpanBounds sb =
        raster::detail::MakeSpanBounds<float>(k.U, k.V, k.A, k.B, k.C, rec.Level);
      if (sb.Bounded)
      {
        // Tighter candidate rows from the same conservative ellipse: its exact half-height
        // widened by 0.01 pixel instead of 1 (as Footprint.cxx's packed boxes, same proof;
        // the double rounding errors here are of order 1e-12 pixel). Rows outside cannot
        // reach the alpha level, so skipping them changes nothing.
        const double yE = std::sqrt(sb.NegTwoL * sb.A / sb.Det);
        if (std::abs(sb.V) < 1e8 && yE < 1e8)
        {
          sb.RowMin = std::max(sb.RowMin, static_cast<int>(std::floor(sb.V - yE - 0.01)));
          sb.RowMax = std::min(sb.RowMax, static_cast<int>(std::ceil(sb.V + yE + 0.01)));
        }
      }
      d.Bounds[s] = raster::detail::SpanRecord(sb);
    }
    else
    {
      d.Bounds[s] = raster::detail::SpanRecord();
    }
  }
  d.HasView = true;
}

//------------------------------------------------------------------------------
void MultiViewRenderer::Render(const Camera& camera, RasterImage<float>& image)
{
  this->Project(camera);
  this->Composite(image);
}

//------------------------------------------------------------------------------
void MultiViewRenderer::SetColors(const float* rgb)
{
  Data& d = *this->Impl;
  if (!d.HasView)
  {
    throw std::logic_error("MultiViewRenderer::SetColors: no view was projected");
  }
  const std::int64_t nv = static_cast<std::int64_t>(d.Sorted.size());
#pragma omp parallel for schedule(static) num_threads(d.Threads)
  for (std::int64_t ss = 0; ss < nv; ++ss)
  {
    const std::size_t s = static_cast<std::size_t>(ss);
    const float* c = rgb + 3 * static_cast<std::size_t>(d.Sorted[s]);
    d.Kernels[s].R = c[0];
    d.Kernels[s].G = c[1];
    d.Kernels[s].Bl = c[2];
  }
}

//------------------------------------------------------------------------------
void MultiViewRenderer::CompositeInSortedOrder(RasterImage<float>& image,
  GaussianWeightStats& weights)
{
  this->CompositeWith(image, &weights);
}

//------------------------------------------------------------------------------
void MultiViewRenderer::Composite(RasterImage<float>& image, GaussianWeightStats* weights)
{
  if (!weights)
  {
    this->CompositeWith(image, nullptr);
    return;
  }
  Data& d = *this->Impl;
  GaussianWeightStats& sorted = d.SortedWeights;
  sorted.CountEvaluations = weights->CountEvaluations;
  this->CompositeWith(image, &sorted);
  // Sorted positions back to input order; a Gaussian not drawn gets zeros.
  const std::size_t n = d.Count;
  const std::int64_t nv = static_cast<std::int64_t>(d.Sorted.size());
  weights->MaxWeight.assign(n, 0.0f);
  weights->WeightSum.assign(n, 0.0);
  weights->BlendedPixels.assign(n, 0);
  weights->Evaluations.assign(weights->CountEvaluations ? n : 0, 0);
#pragma omp parallel for schedule(static) num_threads(d.Threads)
  for (std::int64_t s = 0; s < nv; ++s)
  {
    const std::uint32_t id = d.Sorted[static_cast<std::size_t>(s)];
    weights->MaxWeight[id] = sorted.MaxWeight[static_cast<std::size_t>(s)];
    weights->WeightSum[id] = sorted.WeightSum[static_cast<std::size_t>(s)];
    weights->BlendedPixels[id] = sorted.BlendedPixels[static_cast<std::size_t>(s)];
    if (weights->CountEvaluations)
    {
      weights->Evaluations[id] = sorted.Evaluations[static_cast<std::size_t>(s)];
    }
  }
}

//------------------------------------------------------------------------------
void MultiViewRenderer::CompositeWith(RasterImage<float>& image, GaussianWeightStats* sorted)
{
  Data& d = *this->Impl;
  if (!d.HasView)
  {
    throw std::logic_error("MultiViewRenderer::Composite: no view was projected");
  }
  const int chunks = d.Threads;
  const std::int64_t nv = static_cast<std::int64_t>(d.Sorted.size());
  // Binning, as BinGaussians() step 3 on the sorted sequence; the lists hold sorted positions.
  TileBins& bins = d.Bins;
  bins.TilesX = d.Camera.Gx;
  bins.TilesY = d.Camera.Gy;
  BinSortedRects(d.Rects.data(), nullptr, nv, d.Camera.Gx, d.Camera.Gy, chunks, d.Diff, bins);

  // Compositing: the tile loop of CompositeTiles() on the sorted data.
  raster::internal::CompositeInput in;
  in.Width = d.Camera.W;
  in.Height = d.Camera.H;
  in.Bins = &bins;
  in.Kernels = d.Kernels.data();
  in.Bounds = d.Bounds.data();
  in.Background = d.Settings.Background;
  in.KernelIsa = d.Settings.KernelIsa;
  in.Threads = chunks;
  if (sorted)
  {
    in.Weights = sorted;
    in.KernelCount = static_cast<std::size_t>(nv);
  }
  raster::internal::CompositeSorted(in, image);
}

} // namespace vis4gs

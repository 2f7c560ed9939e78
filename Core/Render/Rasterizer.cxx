// SPDX-License-Identifier: BSD-3-Clause
#include "Rasterizer.h"

#include "GaussianMath.h"
#include "MultiViewData.h"
#include "RasterBounds.h"

#include <immintrin.h>

#include <omp.h>
#if defined(__linux__)
#include <sys/mman.h>
#endif

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
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

//------------------------------------------------------------------------------
int ThreadCount(int requested)
{
  return requested > 0 ? requested : omp_get_max_threads();
}

//------------------------------------------------------------------------------
// Asks Linux for transparent huge pages on a large buffer before it is first touched: the
// multi-megabyte buffers of projection and binning otherwise cost one page fault per 4 KiB
// (serial when a std::vector value-initialises them) and a TLB miss on most scattered writes.
// Advisory only: ignored where unsupported, never changes a value.
void AdviseHugePages(const void* data, std::size_t bytes)
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

//------------------------------------------------------------------------------
// Uninitialised buffer of a trivial type (first touched by the parallel loops that fill it).
template <typename U>
std::unique_ptr<U[]> RawBuffer(std::size_t n)
{
  static_assert(std::is_trivial<U>::value, "RawBuffer holds trivial types only");
  std::unique_ptr<U[]> buffer(new U[n > 0 ? n : 1]);
  AdviseHugePages(buffer.get(), n * sizeof(U));
  return buffer;
}

//------------------------------------------------------------------------------
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
// Float to int conversion without undefined behaviour: values are clamped to +-2^30 first.
template <typename T>
int ClampToInt(T x)
{
  const T big = T(1073741824.0);
  return static_cast<int>(x < -big ? -big : (x > big ? big : x));
}

//------------------------------------------------------------------------------
// The reference's ndc2Pix computes in double (its literals are double) and stores a float.
template <typename T>
T Ndc2Pix(T ndc, int size)
{
  return static_cast<T>(((static_cast<double>(ndc) + 1.0) * size - 1.0) * 0.5);
}

//------------------------------------------------------------------------------
// SH colour, reference §2.4, in the reference's operation order.
template <typename T>
void ShColor(const float* shf, int degree, const T dir[3], T out[3])
{
  const T C0 = T(sh::C0), C1 = T(sh::C1);
  T sh[16][3];
  const int k = (degree + 1) * (degree + 1);
  for (int i = 0; i < k; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      sh[i][c] = static_cast<T>(shf[3 * i + c]);
    }
  }
  T r[3];
  for (int c = 0; c < 3; ++c)
  {
    r[c] = C0 * sh[0][c];
  }
  if (degree > 0)
  {
    const T x = dir[0], y = dir[1], z = dir[2];
    for (int c = 0; c < 3; ++c)
    {
      r[c] = r[c] - C1 * y * sh[1][c] + C1 * z * sh[2][c] - C1 * x * sh[3][c];
    }
    if (degree > 1)
    {
      const T xx = x * x, yy = y * y, zz = z * z;
      const T xy = x * y, yz = y * z, xz = x * z;
      for (int c = 0; c < 3; ++c)
      {
        r[c] = r[c] + T(sh::C2[0]) * xy * sh[4][c] + T(sh::C2[1]) * yz * sh[5][c] +
          T(sh::C2[2]) * (T(2) * zz - xx - yy) * sh[6][c] + T(sh::C2[3]) * xz * sh[7][c] +
          T(sh::C2[4]) * (xx - yy) * sh[8][c];
      }
      if (degree > 2)
      {
        for (int c = 0; c < 3; ++c)
        {
          r[c] = r[c] + T(sh::C3[0]) * y * (T(3) * xx - yy) * sh[9][c] +
            T(sh::C3[1]) * xy * z * sh[10][c] +
            T(sh::C3[2]) * y * (T(4) * zz - xx - yy) * sh[11][c] +
            T(sh::C3[3]) * z * (T(2) * zz - T(3) * xx - T(3) * yy) * sh[12][c] +
            T(sh::C3[4]) * x * (T(4) * zz - xx - yy) * sh[13][c] +
            T(sh::C3[5]) * z * (xx - yy) * sh[14][c] +
            T(sh::C3[6]) * x * (xx - T(3) * yy) * sh[15][c];
        }
      }
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    out[c] = r[c] + T(0.5);
  }
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
template <typename T>
ViewProjection<T> ProjectGaussians(const GaussianCloud& cloud,
  const Camera& camera,
  const RasterSettings& settings)
{
  CheckCamera(camera);
  CheckCloud(cloud, settings.ComputeColors);

  ViewProjection<T> p;
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

  const std::size_t n = cloud.Count;
  p.Gaussians.reserve(n);
  AdviseHugePages(p.Gaussians.data(), n * sizeof(ProjectedGaussian<T>));
  p.Gaussians.assign(n, ProjectedGaussian<T>());
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
      const std::size_t i = static_cast<std::size_t>(ii);
      ProjectedGaussian<T>& g = p.Gaussians[i];
      const float* pos = &cloud.Positions[3 * i];
      const float* ls = &cloud.LogScales[3 * i];
      const float* rot = &cloud.Rotations[4 * i];
      const float logit = cloud.OpacityLogits[i];
      const float* shf = colors ? &cloud.SH[i * shStride] : nullptr;
      g.Status = ProjectionStatus::InvalidParameters;
      if (!AllFinite(pos, 3) || !AllFinite(ls, 3) || !AllFinite(rot, 4) || !std::isfinite(logit) ||
        (colors && !AllFinite(shf, static_cast<std::size_t>(shUsed))))
      {
        ++local[static_cast<int>(ProjectionStatus::InvalidParameters)];
        continue;
      }
      const T x = pos[0], y = pos[1], z = pos[2];
      // 1. View position and near cull.
      const T t0 = V[0] * x + V[1] * y + V[2] * z + V[3];
      const T t1 = V[4] * x + V[5] * y + V[6] * z + V[7];
      const T t2 = V[8] * x + V[9] * y + V[10] * z + V[11];
      g.ViewPosition[0] = t0;
      g.ViewPosition[1] = t1;
      g.ViewPosition[2] = t2;
      g.Depth = t2;
      if (t2 <= T(raster::NearPlane))
      {
        g.Status = ProjectionStatus::NearPlane;
        ++local[static_cast<int>(g.Status)];
        continue;
      }
      // 2. Clip coordinates.
      const T hx = F[0] * x + F[1] * y + F[2] * z + F[3];
      const T hy = F[4] * x + F[5] * y + F[6] * z + F[7];
      const T hw = F[12] * x + F[13] * y + F[14] * z + F[15];
      const T pw = T(1) / (hw + T(0.0000001));
      const T ndcX = hx * pw, ndcY = hy * pw;
      // 3. 3D covariance R diag(s^2) R^T.
      const T s[3] = { mod * std::exp(static_cast<T>(ls[0])),
        mod * std::exp(static_cast<T>(ls[1])),
        mod * std::exp(static_cast<T>(ls[2])) };
      const T qraw[4] = { rot[0], rot[1], rot[2], rot[3] };
      const auto R = QuaternionToMatrix<T>(NormalizeQuaternion<T>(qraw));
      T M[3][3]; // M[k][i] = s_k R_ik
      for (int k = 0; k < 3; ++k)
      {
        for (int r = 0; r < 3; ++r)
        {
          M[k][r] = s[k] * R[3 * r + k];
        }
      }
      T Sig[3][3];
      for (int r = 0; r < 3; ++r)
      {
        for (int c = r; c < 3; ++c)
        {
          Sig[r][c] = M[0][r] * M[0][c] + M[1][r] * M[1][c] + M[2][r] * M[2][c];
          Sig[c][r] = Sig[r][c];
        }
      }
      // 4. EWA projection with the clamped Jacobian.
      const T txtz = t0 / t2, tytz = t1 / t2;
      const T tx = std::min(limx, std::max(-limx, txtz)) * t2;
      const T ty = std::min(limy, std::max(-limy, tytz)) * t2;
      const T J00 = focalX / t2, J02 = -(focalX * tx) / (t2 * t2);
      const T J11 = focalY / t2, J12 = -(focalY * ty) / (t2 * t2);
      T Tm[2][3]; // J * R_v
      for (int c = 0; c < 3; ++c)
      {
        Tm[0][c] = J00 * V[c] + J02 * V[8 + c];
        Tm[1][c] = J11 * V[4 + c] + J12 * V[8 + c];
      }
      T TS[2][3];
      for (int r = 0; r < 2; ++r)
      {
        for (int c = 0; c < 3; ++c)
        {
          TS[r][c] = Tm[r][0] * Sig[0][c] + Tm[r][1] * Sig[1][c] + Tm[r][2] * Sig[2][c];
        }
      }
      const T cxx = TS[0][0] * Tm[0][0] + TS[0][1] * Tm[0][1] + TS[0][2] * Tm[0][2];
      const T cxy = TS[0][0] * Tm[1][0] + TS[0][1] * Tm[1][1] + TS[0][2] * Tm[1][2];
      const T cyy = TS[1][0] * Tm[1][0] + TS[1][1] * Tm[1][1] + TS[1][2] * Tm[1][2];
      const T a = cxx + T(raster::Dilation);
      const T b = cxy;
      const T c = cyy + T(raster::Dilation);
      g.Cov2D[0] = a;
      g.Cov2D[1] = b;
      g.Cov2D[2] = c;
      if (!std::isfinite(a) || !std::isfinite(b) || !std::isfinite(c))
      {
        g.Status = ProjectionStatus::NonFinite;
        ++local[static_cast<int>(g.Status)];
        continue;
      }
      // 5. det cull, conic, radius.
      const T det = a * c - b * b;
      if (det == T(0))
      {
        g.Status = ProjectionStatus::Degenerate;
        ++local[static_cast<int>(g.Status)];
        continue;
      }
      const T detInv = T(1) / det;
      const T conA = c * detInv, conB = -b * detInv, conC = a * detInv;
      const T mid = T(0.5) * (a + c);
      const T root = std::sqrt(std::max(T(0.1), mid * mid - det));
      const T l1 = mid + root, l2 = mid - root;
      const T radiusF = std::ceil(T(3) * std::sqrt(std::max(l1, l2)));
      if (!std::isfinite(conA) || !std::isfinite(conB) || !std::isfinite(conC) ||
        !std::isfinite(radiusF) || !std::isfinite(det))
      {
        g.Status = ProjectionStatus::NonFinite;
        ++local[static_cast<int>(g.Status)];
        continue;
      }
      // 6. Pixel-space mean and tile rectangle.
      const T u = Ndc2Pix(ndcX, W), v = Ndc2Pix(ndcY, H);
      const int radius = ClampToInt(radiusF);
      const T rr = static_cast<T>(radius);
      const T bs = T(raster::TileSize);
      const int x0 = std::min(gx, std::max(0, ClampToInt((u - rr) / bs)));
      const int y0 = std::min(gy, std::max(0, ClampToInt((v - rr) / bs)));
      const int x1 = std::min(gx, std::max(0, ClampToInt((u + rr + bs - T(1)) / bs)));
      const int y1 = std::min(gy, std::max(0, ClampToInt((v + rr + bs - T(1)) / bs)));
      g.U = u;
      g.V = v;
      g.ConicA = conA;
      g.ConicB = conB;
      g.ConicC = conC;
      g.Radius = radius;
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
        T dir[3] = { x - campos[0], y - campos[1], z - campos[2] };
        const T len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
        for (auto& d : dir)
        {
          d = d / len;
        }
        T col[3];
        ShColor<T>(shf, shDegree, dir, col);
        std::uint8_t clamped = 0;
        for (int ch = 0; ch < 3; ++ch)
        {
          if (col[ch] < T(0))
          {
            clamped = static_cast<std::uint8_t>(clamped | (1u << ch));
          }
          g.Color[ch] = std::max(col[ch], T(0));
        }
        g.ClampedChannels = clamped;
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
  p.Counts.Visible = counts[0];
  p.Counts.InvalidParameters = counts[1];
  p.Counts.NearPlane = counts[2];
  p.Counts.Degenerate = counts[3];
  p.Counts.NonFinite = counts[4];
  p.Counts.OffScreen = counts[5];
  return p;
}

//------------------------------------------------------------------------------
namespace
{

// Stable parallel LSD radix sort of the n 64-bit keys at @p keys on bits [lo, hi) (the other
// bits are equal in every key or irrelevant), in chunks of contiguous keys: per chunk and pass
// a histogram, then bucket-major chunk-minor offsets, then each chunk scatters its keys in
// order. @p tmp holds n keys; returns the buffer holding the sorted keys (keys or tmp).
std::uint64_t* RadixSortKeys(std::uint64_t* keys,
  std::uint64_t* tmp,
  std::int64_t n,
  int lo,
  int hi,
  int chunks)
{
  const int bits = hi - lo;
  if (bits <= 0 || n < 2)
  {
    return keys;
  }
  const int passes = (bits + 10) / 11;
  const int width = (bits + passes - 1) / passes;
  const std::size_t buckets = std::size_t(1) << width;
  const std::uint64_t mask = buckets - 1;
  std::vector<std::uint64_t> hist(static_cast<std::size_t>(chunks) * buckets);
  std::uint64_t* from = keys;
  std::uint64_t* to = tmp;
  for (int pass = 0; pass < passes; ++pass)
  {
    const int shift = lo + pass * width;
#pragma omp parallel for schedule(static, 1) num_threads(chunks)
    for (int c = 0; c < chunks; ++c)
    {
      std::uint64_t* h = &hist[static_cast<std::size_t>(c) * buckets];
      std::fill(h, h + buckets, 0);
      const std::int64_t b = n * c / chunks, e = n * (c + 1) / chunks;
      for (std::int64_t k = b; k < e; ++k)
      {
        ++h[(from[k] >> shift) & mask];
      }
    }
    std::uint64_t running = 0;
    for (std::size_t d = 0; d < buckets; ++d)
    {
      for (int c = 0; c < chunks; ++c)
      {
        std::uint64_t& h = hist[static_cast<std::size_t>(c) * buckets + d];
        const std::uint64_t k = h;
        h = running;
        running += k;
      }
    }
#pragma omp parallel for schedule(static, 1) num_threads(chunks)
    for (int c = 0; c < chunks; ++c)
    {
      std::uint64_t* h = &hist[static_cast<std::size_t>(c) * buckets];
      const std::int64_t b = n * c / chunks, e = n * (c + 1) / chunks;
      for (std::int64_t k = b; k < e; ++k)
      {
        const std::uint64_t key = from[k];
        to[h[(key >> shift) & mask]++] = key;
      }
    }
    std::swap(from, to);
  }
  return from;
}

} // namespace

//------------------------------------------------------------------------------
// Binning: (1) compact the visible Gaussians in index order; (2) sort them once, globally,
// by (depth, index); (3) a stable counting scatter of that sequence into the tiles (per
// chunk of the sorted sequence: tile counts from a 2D difference array of the tile
// rectangles, tile-major chunk-minor offsets, scatter in order). Every tile's run is then a
// subsequence of the global order: sorted by (depth, index) with no per-tile sort, exactly
// the order of the reference's stable radix sort on (tile, depth) keys.
template <typename T>
TileBins BinGaussians(const ViewProjection<T>& projection, int threads)
{
  TileBins bins;
  bins.TilesX = projection.TilesX;
  bins.TilesY = projection.TilesY;
  const std::size_t tiles = bins.TileCount();
  const auto& gs = projection.Gaussians;
  const std::int64_t n = static_cast<std::int64_t>(gs.size());
  const int chunks = ThreadCount(threads);
  const std::size_t gx = static_cast<std::size_t>(projection.TilesX);
  const std::size_t gy = static_cast<std::size_t>(projection.TilesY);

  // (1) Visible Gaussians, compacted in index order: ids, tile rectangles, sort keys. The
  // compact position is monotonic in the index, so it breaks depth ties like the index.
  std::vector<std::uint64_t> before(static_cast<std::size_t>(chunks) + 1, 0);
#pragma omp parallel for schedule(static, 1) num_threads(chunks)
  for (int c = 0; c < chunks; ++c)
  {
    const std::int64_t b = n * c / chunks, e = n * (c + 1) / chunks;
    std::uint64_t k = 0;
    for (std::int64_t i = b; i < e; ++i)
    {
      k += gs[static_cast<std::size_t>(i)].IsVisible() ? 1 : 0;
    }
    before[static_cast<std::size_t>(c) + 1] = k;
  }
  for (int c = 0; c < chunks; ++c)
  {
    before[static_cast<std::size_t>(c) + 1] += before[static_cast<std::size_t>(c)];
  }
  const std::size_t visible = static_cast<std::size_t>(before[static_cast<std::size_t>(chunks)]);
  const std::int64_t nv = static_cast<std::int64_t>(visible);
  using Rect = std::array<int, 4>;
  auto visIds = RawBuffer<std::uint32_t>(visible);
  auto visRects = RawBuffer<Rect>(visible);
  constexpr bool isFloat = std::is_same<T, float>::value;
  // float: depth bits above the compact position (and room for the radix sort's buffer)
  auto keys = RawBuffer<std::uint64_t>(isFloat ? 2 * visible : 0);
  std::vector<std::pair<T, std::uint32_t>> pairs(isFloat ? 0 : visible); // double
  std::uint32_t depthOr = 0, depthAnd = ~0u;
#pragma omp parallel for schedule(static, 1) num_threads(chunks) reduction(| : depthOr) reduction(& : depthAnd)
  for (int c = 0; c < chunks; ++c)
  {
    const std::int64_t b = n * c / chunks, e = n * (c + 1) / chunks;
    std::size_t k = static_cast<std::size_t>(before[static_cast<std::size_t>(c)]);
    for (std::int64_t i = b; i < e; ++i)
    {
      const auto& g = gs[static_cast<std::size_t>(i)];
      if (!g.IsVisible())
      {
        continue;
      }
      visIds[k] = static_cast<std::uint32_t>(i);
      visRects[k] = { g.TileRect[0], g.TileRect[1], g.TileRect[2], g.TileRect[3] };
      if constexpr (std::is_same<T, float>::value)
      {
        // depth > 0.2, so the bits order like the values.
        std::uint32_t bits;
        std::memcpy(&bits, &g.Depth, sizeof(bits));
        depthOr |= bits;
        depthAnd &= bits;
        keys[k] = (static_cast<std::uint64_t>(bits) << 32) | static_cast<std::uint64_t>(k);
      }
      else
      {
        pairs[k] = { g.Depth, static_cast<std::uint32_t>(k) };
      }
      ++k;
    }
  }

  // (2) Global order by (depth, index). Float: stable radix sort on the depth bits that
  // differ between Gaussians (the keys arrive in index order, so ties stay in index order).
  auto order = RawBuffer<std::uint32_t>(visible);
  auto rects = RawBuffer<Rect>(visible);
  if constexpr (std::is_same<T, float>::value)
  {
    const std::uint32_t differ = depthOr & ~depthAnd;
    int hi = 0;
    while (hi < 32 && (differ >> hi) != 0)
    {
      ++hi;
    }
    const std::uint64_t* sorted =
      RadixSortKeys(keys.get(), keys.get() + visible, nv, 32, 32 + hi, chunks);
#pragma omp parallel for schedule(static) num_threads(chunks)
    for (std::int64_t k = 0; k < nv; ++k)
    {
      const std::uint32_t pos = static_cast<std::uint32_t>(sorted[k]);
      order[static_cast<std::size_t>(k)] = visIds[pos];
      rects[static_cast<std::size_t>(k)] = visRects[pos];
    }
  }
  else
  {
    std::sort(pairs.begin(), pairs.end());
#pragma omp parallel for schedule(static) num_threads(chunks)
    for (std::int64_t k = 0; k < nv; ++k)
    {
      const std::uint32_t pos = pairs[static_cast<std::size_t>(k)].second;
      order[static_cast<std::size_t>(k)] = visIds[pos];
      rects[static_cast<std::size_t>(k)] = visRects[pos];
    }
  }
  visIds.reset();
  visRects.reset();
  keys.reset();
  std::vector<std::pair<T, std::uint32_t>>().swap(pairs);

  // (3) Per chunk of the sorted sequence, per tile counts: a 2D difference array of the
  // rectangles ((gx+1) x (gy+1)), integrated by rows then columns.
  const std::size_t dx = gx + 1;
  const std::size_t diffSize = dx * (gy + 1);
  std::vector<std::int64_t> diff(static_cast<std::size_t>(chunks) * diffSize, 0);
#pragma omp parallel for schedule(static, 1) num_threads(chunks)
  for (int c = 0; c < chunks; ++c)
  {
    std::int64_t* d = &diff[static_cast<std::size_t>(c) * diffSize];
    const std::int64_t b = nv * c / chunks, e = nv * (c + 1) / chunks;
    for (std::int64_t k = b; k < e; ++k)
    {
      const Rect& r = rects[static_cast<std::size_t>(k)];
      const std::size_t x0 = static_cast<std::size_t>(r[0]), y0 = static_cast<std::size_t>(r[1]);
      const std::size_t x1 = static_cast<std::size_t>(r[2]), y1 = static_cast<std::size_t>(r[3]);
      ++d[y0 * dx + x0];
      --d[y0 * dx + x1];
      --d[y1 * dx + x0];
      ++d[y1 * dx + x1];
    }
    for (std::size_t y = 0; y < gy; ++y)
    {
      std::int64_t* row = d + y * dx;
      for (std::size_t x = 1; x < gx; ++x)
      {
        row[x] += row[x - 1];
      }
      if (y > 0)
      {
        const std::int64_t* up = row - dx;
        for (std::size_t x = 0; x < gx; ++x)
        {
          row[x] += up[x];
        }
      }
    }
  }
  // Offsets: tile-major, chunk-minor; the counts become each chunk's write cursors.
  bins.Offsets.assign(tiles + 1, 0);
  std::uint64_t running = 0;
  for (std::size_t ty = 0; ty < gy; ++ty)
  {
    for (std::size_t tx = 0; tx < gx; ++tx)
    {
      bins.Offsets[ty * gx + tx] = running;
      for (int c = 0; c < chunks; ++c)
      {
        std::int64_t& h = diff[static_cast<std::size_t>(c) * diffSize + ty * dx + tx];
        const std::uint64_t k = static_cast<std::uint64_t>(h);
        h = static_cast<std::int64_t>(running);
        running += k;
      }
    }
  }
  bins.Offsets[tiles] = running;
  bins.Ids.reserve(running);
  AdviseHugePages(bins.Ids.data(), running * sizeof(std::uint32_t));
  bins.Ids.resize(running);
  std::uint32_t* ids = bins.Ids.data();
#pragma omp parallel for schedule(static, 1) num_threads(chunks)
  for (int c = 0; c < chunks; ++c)
  {
    std::int64_t* cursor = &diff[static_cast<std::size_t>(c) * diffSize];
    const std::int64_t b = nv * c / chunks, e = nv * (c + 1) / chunks;
    for (std::int64_t k = b; k < e; ++k)
    {
      const Rect& r = rects[static_cast<std::size_t>(k)];
      const std::uint32_t id = order[static_cast<std::size_t>(k)];
      for (int ty = r[1]; ty < r[3]; ++ty)
      {
        std::int64_t* row = cursor + static_cast<std::size_t>(ty) * dx;
        for (int tx = r[0]; tx < r[2]; ++tx)
        {
          ids[row[tx]++] = id;
        }
      }
    }
  }
  return bins;
}

namespace
{

//------------------------------------------------------------------------------
// Compositing: 16 lanes = one tile row, with GCC vector extensions. Every lane performs
// exactly the scalar operations of RasterKernel.h (no contraction), so every instruction
// set gives the same bits as AttributePixels() and the tests' scalar replays.
template <typename T>
struct Lanes;
template <>
struct Lanes<float>
{
  typedef float V __attribute__((vector_size(64)));
  typedef std::int32_t I __attribute__((vector_size(64)));
};
template <>
struct Lanes<double>
{
  typedef double V __attribute__((vector_size(128)));
  typedef std::int64_t I __attribute__((vector_size(128)));
};

using raster::detail::KernelGaussian;

template <typename T>
struct CompositeContext
{
  const ViewProjection<T>* Projection;
  const TileBins* Bins;
  const KernelGaussian<T>* Kernels;
  const raster::detail::SpanBounds* Bounds;
  RasterImage<T>* Image;
  GaussianWeightStats* Weights;
  T Background[3];
  std::atomic<std::uint64_t>* KernelEvaluations;
  std::atomic<std::uint64_t>* ReferenceEvaluations;
};

#define VIS4GS_ALWAYS_INLINE inline __attribute__((always_inline))

template <typename I>
VIS4GS_ALWAYS_INLINE bool AnyLane(I m)
{
  // Tree reduction of a 16-lane mask.
  auto h8 = __builtin_shufflevector(m, m, 0, 1, 2, 3, 4, 5, 6, 7) |
    __builtin_shufflevector(m, m, 8, 9, 10, 11, 12, 13, 14, 15);
  auto h4 =
    __builtin_shufflevector(h8, h8, 0, 1, 2, 3) | __builtin_shufflevector(h8, h8, 4, 5, 6, 7);
  auto h2 = __builtin_shufflevector(h4, h4, 0, 1) | __builtin_shufflevector(h4, h4, 2, 3);
  return (h2[0] | h2[1]) != 0;
}

VIS4GS_ALWAYS_INLINE Lanes<float>::V VectorExp(Lanes<float>::V x)
{
  return raster::KernelExpLanes<Lanes<float>::V, Lanes<float>::I>(x);
}

VIS4GS_ALWAYS_INLINE Lanes<double>::V VectorExp(Lanes<double>::V x)
{
  Lanes<double>::V r;
  for (int l = 0; l < 16; ++l)
  {
    r[l] = std::exp(x[l]);
  }
  return r;
}

template <typename T, bool Stats, bool Work>
VIS4GS_ALWAYS_INLINE void CompositeTile(const CompositeContext<T>& ctx, std::int64_t tile)
{
  typedef typename Lanes<T>::V V;
  typedef typename Lanes<T>::I I;
  typedef typename std::remove_reference<decltype(I{}[0])>::type IS;
  const ViewProjection<T>& proj = *ctx.Projection;
  const int W = proj.Width, H = proj.Height;
  const int tx = static_cast<int>(tile % proj.TilesX), ty = static_cast<int>(tile / proj.TilesX);
  const int X0 = tx * raster::TileSize, Y0 = ty * raster::TileSize;
  V px;
  I pxi;
  for (int l = 0; l < 16; ++l)
  {
    px[l] = static_cast<T>(X0 + l);
    pxi[l] = X0 + l;
  }
  V Tr[16], Cr[16], Cg[16], Cb[16], Dp[16];
  I last[16], done[16], stopAt[16];
  std::uint32_t rowAlive = 0;
  for (int r = 0; r < 16; ++r)
  {
    Tr[r] = V{} + T(1);
    Cr[r] = Cg[r] = Cb[r] = Dp[r] = V{};
    last[r] = stopAt[r] = I{};
    done[r] = (pxi >= W) | (I{} + ((Y0 + r >= H) ? -1 : 0));
    if (AnyLane(~done[r]))
    {
      rowAlive |= 1u << r;
    }
  }
  const std::uint64_t begin = ctx.Bins->Offsets[tile], end = ctx.Bins->Offsets[tile + 1];
  const T minAlpha = raster::MinAlpha<T>();
  const T maxAlpha = T(raster::MaxAlpha);
  const T stop = T(raster::TransmittanceStop);
  std::uint64_t evaluated = 0;
  for (std::uint64_t k = begin; k < end && rowAlive != 0; ++k)
  {
    const std::uint32_t id = ctx.Bins->Ids[k];
    if (k + 8 < end)
    {
      const std::uint32_t ahead = ctx.Bins->Ids[k + 8];
      __builtin_prefetch(&ctx.Kernels[ahead]);
      __builtin_prefetch(&ctx.Bounds[ahead]);
    }
    const KernelGaussian<T>& g = ctx.Kernels[id];
    if (!(g.O >= minAlpha))
    {
      continue; // alpha <= o < 1/255 at every pixel: always skipped
    }
    const raster::detail::SpanBounds& sb = ctx.Bounds[id];
    int r0 = 0, r1 = 15;
    if (sb.Bounded)
    {
      r0 = std::max(r0, sb.RowMin - Y0);
      r1 = std::min(r1, sb.RowMax - Y0);
    }
    const IS pos = static_cast<IS>(k - begin + 1);
    float wMax = 0;
    double wSum = 0;
    std::uint32_t wCount = 0;
    for (int r = r0; r <= r1; ++r)
    {
      if (!((rowAlive >> r) & 1u))
      {
        continue;
      }
      const int py = Y0 + r;
      if (sb.Bounded)
      {
        int xa, xb;
        if (!sb.Columns(py, xa, xb) || xb < X0 || xa > X0 + 15)
        {
          continue;
        }
      }
      if (Work)
      {
        evaluated += 16;
      }
      const T dy = g.V - static_cast<T>(py);
      const V dx = g.U - px;
      const T cdd = g.C * dy * dy;
      const V power = T(-0.5) * (g.A * dx * dx + cdd) - g.B * dx * dy;
      I valid = power <= T(0);
      const V e = VectorExp(valid ? power : V{});
      const V a = g.O * e;
      const V alpha = a < maxAlpha ? a : V{} + maxAlpha;
      valid &= alpha >= minAlpha;
      const I act = valid & ~done[r];
      if (!AnyLane(act))
      {
        continue;
      }
      const V Tn = Tr[r] * (T(1) - alpha);
      const I stopNow = act & (Tn < stop);
      const I blend = act & ~stopNow;
      const V aT = alpha * Tr[r];
      Cr[r] = blend ? Cr[r] + g.R * alpha * Tr[r] : Cr[r];
      Cg[r] = blend ? Cg[r] + g.G * alpha * Tr[r] : Cg[r];
      Cb[r] = blend ? Cb[r] + g.Bl * alpha * Tr[r] : Cb[r];
      Dp[r] = blend ? Dp[r] + g.Z * alpha * Tr[r] : Dp[r];
      Tr[r] = blend ? Tn : Tr[r];
      last[r] = blend ? I{} + pos : last[r];
      if (Stats)
      {
        for (int l = 0; l < 16; ++l)
        {
          if (blend[l])
          {
            const float w = static_cast<float>(aT[l]);
            wMax = std::max(wMax, w);
            wSum += static_cast<double>(aT[l]);
            ++wCount;
          }
        }
      }
      if (AnyLane(stopNow))
      {
        stopAt[r] = stopNow ? I{} + pos : stopAt[r];
        done[r] |= stopNow;
        if (!AnyLane(~done[r]))
        {
          rowAlive &= ~(1u << r);
        }
      }
    }
    if (Stats && wCount > 0)
    {
      GaussianWeightStats& ws = *ctx.Weights;
#pragma omp atomic
      ws.WeightSum[id] += wSum;
#pragma omp atomic
      ws.BlendedPixels[id] += wCount;
      auto* maxBits = reinterpret_cast<std::uint32_t*>(&ws.MaxWeight[id]);
      std::uint32_t cur = __atomic_load_n(maxBits, __ATOMIC_RELAXED);
      std::uint32_t want;
      std::memcpy(&want, &wMax, sizeof(want));
      while (want > cur &&
        !__atomic_compare_exchange_n(maxBits, &cur, want, true, __ATOMIC_RELAXED, __ATOMIC_RELAXED))
      {
      }
    }
  }
  RasterImage<T>& img = *ctx.Image;
  std::uint64_t refEvals = 0;
  const std::uint64_t listLen = end - begin;
  for (int r = 0; r < 16; ++r)
  {
    const int py = Y0 + r;
    if (py >= H)
    {
      break;
    }
    for (int l = 0; l < 16; ++l)
    {
      const int x = X0 + l;
      if (x >= W)
      {
        break;
      }
      const std::size_t pix = static_cast<std::size_t>(py) * W + x;
      const T t = Tr[r][l];
      img.Color[3 * pix + 0] = Cr[r][l] + t * ctx.Background[0];
      img.Color[3 * pix + 1] = Cg[r][l] + t * ctx.Background[1];
      img.Color[3 * pix + 2] = Cb[r][l] + t * ctx.Background[2];
      img.Transmittance[pix] = t;
      img.Alpha[pix] = T(1) - t;
      img.Depth[pix] = Dp[r][l];
      img.Contributors[pix] = static_cast<std::uint32_t>(last[r][l]);
      if (Work)
      {
        refEvals += stopAt[r][l] != 0 ? static_cast<std::uint64_t>(stopAt[r][l]) : listLen;
      }
    }
  }
  if (Work)
  {
    ctx.KernelEvaluations->fetch_add(evaluated, std::memory_order_relaxed);
    ctx.ReferenceEvaluations->fetch_add(refEvals, std::memory_order_relaxed);
  }
}

template <typename T>
using TileFunction = void (*)(const CompositeContext<T>&, std::int64_t);

template <typename T, bool Stats, bool Work>
void TileBaseline(const CompositeContext<T>& ctx, std::int64_t tile)
{
  CompositeTile<T, Stats, Work>(ctx, tile);
}
template <typename T, bool Stats, bool Work>
__attribute__((target("avx2"))) void TileAvx2(const CompositeContext<T>& ctx, std::int64_t tile)
{
  CompositeTile<T, Stats, Work>(ctx, tile);
}
template <typename T, bool Stats, bool Work>
__attribute__((target("avx512f,avx512vl,avx512bw,avx512dq"))) void TileAvx512(
  const CompositeContext<T>& ctx,
  std::int64_t tile)
{
  CompositeTile<T, Stats, Work>(ctx, tile);
}

template <typename T, bool Stats, bool Work>
TileFunction<T> SelectTileFunction(int isa)
{
  __builtin_cpu_init();
  const bool has512 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
    __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq");
  const bool has2 = __builtin_cpu_supports("avx2");
  if ((isa == 0 || isa >= 3) && has512)
  {
    return &TileAvx512<T, Stats, Work>;
  }
  if ((isa == 0 || isa >= 2) && has2)
  {
    return &TileAvx2<T, Stats, Work>;
  }
  return &TileBaseline<T, Stats, Work>;
}

} // namespace

//------------------------------------------------------------------------------
template <typename T>
void CompositeTiles(const ViewProjection<T>& projection,
  const TileBins& bins,
  const RasterSettings& settings,
  RasterImage<T>& image,
  GaussianWeightStats* weights,
  RasterWorkCounts* work)
{
  if (bins.TilesX != projection.TilesX || bins.TilesY != projection.TilesY ||
    bins.Offsets.size() != bins.TileCount() + 1)
  {
    throw std::invalid_argument("CompositeTiles: the tile bins do not belong to this projection");
  }
  const int threads = ThreadCount(settings.Threads);
  const std::size_t n = projection.Gaussians.size();
  const std::size_t pixels = static_cast<std::size_t>(projection.Width) * projection.Height;
  image.Width = projection.Width;
  image.Height = projection.Height;
  image.Color.resize(3 * pixels);
  image.Alpha.resize(pixels);
  image.Transmittance.resize(pixels);
  image.Depth.resize(pixels);
  image.Contributors.resize(pixels);

  // Compact per-Gaussian kernel data and conservative spans (only for binned Gaussians).
  std::vector<KernelGaussian<T>> kernels;
  std::vector<raster::detail::SpanBounds> bounds;
  kernels.reserve(n);
  bounds.reserve(n);
  AdviseHugePages(kernels.data(), n * sizeof(KernelGaussian<T>));
  AdviseHugePages(bounds.data(), n * sizeof(raster::detail::SpanBounds));
  kernels.resize(n);
  bounds.resize(n);
  const std::int64_t count = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::int64_t ii = 0; ii < count; ++ii)
  {
    const auto& g = projection.Gaussians[static_cast<std::size_t>(ii)];
    if (!g.IsVisible())
    {
      continue;
    }
    KernelGaussian<T>& k = kernels[static_cast<std::size_t>(ii)];
    k = {
      g.U, g.V, g.ConicA, g.ConicB, g.ConicC, g.Opacity, g.Color[0], g.Color[1], g.Color[2], g.Depth
    };
    if (g.Opacity >= raster::MinAlpha<T>())
    {
      const double level = std::log(raster::MinAlpha<double>() / static_cast<double>(g.Opacity));
      bounds[static_cast<std::size_t>(ii)] = raster::detail::MakeSpanBounds<T>(
        g.U, g.V, g.ConicA, g.ConicB, g.ConicC, std::min(0.0, level));
    }
  }
  if (weights)
  {
    weights->MaxWeight.assign(n, 0.0f);
    weights->WeightSum.assign(n, 0.0);
    weights->BlendedPixels.assign(n, 0);
  }
  std::atomic<std::uint64_t> kernelEvals{ 0 }, referenceEvals{ 0 };
  CompositeContext<T> ctx{ &projection,
    &bins,
    kernels.data(),
    bounds.data(),
    &image,
    weights,
    { static_cast<T>(settings.Background[0]),
      static_cast<T>(settings.Background[1]),
      static_cast<T>(settings.Background[2]) },
    &kernelEvals,
    &referenceEvals };
  TileFunction<T> fn;
  if (weights)
  {
    fn = work ? SelectTileFunction<T, true, true>(settings.KernelIsa)
              : SelectTileFunction<T, true, false>(settings.KernelIsa);
  }
  else
  {
    fn = work ? SelectTileFunction<T, false, true>(settings.KernelIsa)
              : SelectTileFunction<T, false, false>(settings.KernelIsa);
  }
  const std::int64_t tiles = static_cast<std::int64_t>(bins.TileCount());
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (std::int64_t t = 0; t < tiles; ++t)
  {
    fn(ctx, t);
  }
  if (work)
  {
    work->TilePairs = bins.Ids.size();
    work->KernelEvaluations = kernelEvals.load();
    work->ReferenceEvaluations = referenceEvals.load();
  }
}

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
#pragma omp parallel for schedule(dynamic, 4) num_threads(ThreadCount(settings.Threads))
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

//------------------------------------------------------------------------------
// MultiViewRenderer (MultiViewRenderer.h): preparation, projection, binning, compositing.
// The footprint pass is in Footprint.cxx.
namespace
{

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
namespace mvgeneric
{
#define VIS4GS_LANES 16
#define VIS4GS_TARGET "sse2"
#define VIS4GS_GENERIC 1
#include "ProjectionLanes.inc"
#undef VIS4GS_GENERIC
#undef VIS4GS_LANES
#undef VIS4GS_TARGET
} // namespace mvgeneric
namespace mvavx2
{
#define VIS4GS_LANES 8
#define VIS4GS_TARGET "avx2"
#include "ProjectionLanes.inc"
#undef VIS4GS_LANES
#undef VIS4GS_TARGET
} // namespace mvavx2
namespace mvavx512
{
#define VIS4GS_LANES 16
#define VIS4GS_TARGET "avx512f,avx512vl,avx512bw,avx512dq"
#include "ProjectionLanes.inc"
#undef VIS4GS_LANES
#undef VIS4GS_TARGET
} // namespace mvavx512
#pragma GCC diagnostic pop

using ProjectBlock = void (*)(const MultiViewPrepared&,
  std::size_t,
  const MultiViewCamera&,
  MultiViewProjected&);

void ProjectBlockGeneric(const MultiViewPrepared& g,
  std::size_t first,
  const MultiViewCamera& w,
  MultiViewProjected& out)
{
  mvgeneric::ProjectLanes(g, first, w, out);
}
void ProjectBlockAvx2(const MultiViewPrepared& g,
  std::size_t first,
  const MultiViewCamera& w,
  MultiViewProjected& out)
{
  mvavx2::ProjectLanes(g, first, w, out);
  mvavx2::ProjectLanes(g, first + 8, w, out);
}
void ProjectBlockAvx512(const MultiViewPrepared& g,
  std::size_t first,
  const MultiViewCamera& w,
  MultiViewProjected& out)
{
  mvavx512::ProjectLanes(g, first, w, out);
}

// 0 best, 1 generic vectors, 2 AVX2, 3 AVX-512 (each falls back to what the machine has).
ProjectBlock SelectProjectBlock(int isa)
{
  __builtin_cpu_init();
  const bool has512 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
    __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq");
  const bool has2 = __builtin_cpu_supports("avx2");
  if (isa == 1)
  {
    return &ProjectBlockGeneric;
  }
  if ((isa == 0 || isa >= 3) && has512)
  {
    return &ProjectBlockAvx512;
  }
  if (has2)
  {
    return &ProjectBlockAvx2;
  }
  return &ProjectBlockGeneric;
}

template <typename U>
void ResizeKeep(std::vector<U>& v, std::size_t n)
{
  if (v.size() != n)
  {
    if (v.capacity() < n)
    {
      std::vector<U>().swap(v);
      v.reserve(n);
      AdviseHugePages(v.data(), n * sizeof(U));
    }
    v.resize(n);
  }
}

} // namespace

//------------------------------------------------------------------------------
MultiViewRenderer::MultiViewRenderer(const GaussianCloud& cloud, const RasterSettings& settings)
  : Impl(new Data)
{
  CheckCloud(cloud, settings.ComputeColors);
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
  for (auto* v : { &p.X, &p.Y, &p.Z, &p.S00, &p.S01, &p.S02, &p.S11, &p.S12, &p.S22, &p.Opacity })
  {
    v->assign(d.Padded, 0.0f);
  }
  p.Valid.assign(d.Padded, 0);
  if (d.Colors && d.ViewIndependentColor)
  {
    p.Color.assign(3 * d.Padded, 0.0f);
  }
  const int shStride = d.Colors ? 3 * cloud.ShCoefficientCount() : 0;
  const int shUsed = 3 * (d.ShDegree + 1) * (d.ShDegree + 1);
  const bool colors = d.Colors;
  const bool viewIndependent = d.ViewIndependentColor;
  const float mod = static_cast<float>(settings.ScaleModifier);
  const std::int64_t count = static_cast<std::int64_t>(d.Count);
#pragma omp parallel for schedule(static) num_threads(d.Threads)
  for (std::int64_t ii = 0; ii < count; ++ii)
  {
    const std::size_t i = static_cast<std::size_t>(ii);
    const float* pos = &cloud.Positions[3 * i];
    const float* ls = &cloud.LogScales[3 * i];
    const float* rot = &cloud.Rotations[4 * i];
    const float logit = cloud.OpacityLogits[i];
    const float* shf = colors ? &cloud.SH[i * shStride] : nullptr;
    if (!AllFinite(pos, 3) || !AllFinite(ls, 3) || !AllFinite(rot, 4) || !std::isfinite(logit) ||
      (colors && !AllFinite(shf, static_cast<std::size_t>(shUsed))))
    {
      continue;
    }
    // ProjectGaussians<float> step 3, same operations in the same order.
    const float s[3] = { mod * std::exp(static_cast<float>(ls[0])),
      mod * std::exp(static_cast<float>(ls[1])),
      mod * std::exp(static_cast<float>(ls[2])) };
    const float qraw[4] = { rot[0], rot[1], rot[2], rot[3] };
    const auto R = QuaternionToMatrix<float>(NormalizeQuaternion<float>(qraw));
    float M[3][3];
    for (int k = 0; k < 3; ++k)
    {
      for (int r = 0; r < 3; ++r)
      {
        M[k][r] = s[k] * R[3 * r + k];
      }
    }
    auto sig = [&](int r, int c)
    { return M[0][r] * M[0][c] + M[1][r] * M[1][c] + M[2][r] * M[2][c]; };
    p.X[i] = pos[0];
    p.Y[i] = pos[1];
    p.Z[i] = pos[2];
    p.S00[i] = sig(0, 0);
    p.S01[i] = sig(0, 1);
    p.S02[i] = sig(0, 2);
    p.S11[i] = sig(1, 1);
    p.S12[i] = sig(1, 2);
    p.S22[i] = sig(2, 2);
    p.Opacity[i] = Sigmoid(static_cast<float>(logit));
    if (colors && viewIndependent)
    {
      const float dir[3] = { 0, 0, 0 }; // unused at degree 0
      float col[3];
      ShColor<float>(shf, 0, dir, col);
      for (int ch = 0; ch < 3; ++ch)
      {
        p.Color[3 * i + ch] = std::max(col[ch], 0.0f);
      }
    }
    p.Valid[i] = -1;
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
  const ViewProjection<float>& f = d.Frame;
  MultiViewCamera& w = d.Camera;
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

  MultiViewProjected& out = d.Projected;
  for (auto* v : { &out.U, &out.V, &out.A, &out.B, &out.C, &out.Depth })
  {
    ResizeKeep(*v, d.Padded);
  }
  for (auto* v : { &out.Status, &out.Radius, &out.X0, &out.Y0, &out.X1, &out.Y1 })
  {
    ResizeKeep(*v, d.Padded);
  }
  const ProjectBlock block = SelectProjectBlock(d.Settings.KernelIsa);
  const int chunks = d.Threads;
  const std::int64_t blocks = static_cast<std::int64_t>(d.Padded / 16);
  const std::size_t n = d.Count;
  d.ChunkVisible.assign(static_cast<std::size_t>(chunks) + 1, 0);
  std::size_t counts[6] = { 0, 0, 0, 0, 0, 0 };
  // (1) Projection, chunks of contiguous blocks.
#pragma omp parallel num_threads(chunks)
  {
    std::size_t local[6] = { 0, 0, 0, 0, 0, 0 };
#pragma omp for schedule(static, 1)
    for (int c = 0; c < chunks; ++c)
    {
      const std::int64_t b = blocks * c / chunks, e = blocks * (c + 1) / chunks;
      for (std::int64_t k = b; k < e; ++k)
      {
        const std::size_t first = static_cast<std::size_t>(k) * 16;
        block(d.Prepared, first, w, out);
        const std::size_t last = std::min(n, first + 16);
        for (std::size_t i = first; i < last; ++i)
        {
          ++local[out.Status[i]];
        }
      }
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

  // (2) Visible Gaussians in index order, with (depth bits, compact position) keys; chunks of
  // Gaussian indices (a chunk's visible count first).
  const std::int64_t sn = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static, 1) num_threads(chunks)
  for (int c = 0; c < chunks; ++c)
  {
    const std::int64_t b = sn * c / chunks, e = sn * (c + 1) / chunks;
    std::uint64_t k = 0;
    for (std::int64_t i = b; i < e; ++i)
    {
      k += out.Status[static_cast<std::size_t>(i)] == 0 ? 1 : 0;
    }
    d.ChunkVisible[static_cast<std::size_t>(c) + 1] = k;
  }
  for (int c = 0; c < chunks; ++c)
  {
    d.ChunkVisible[static_cast<std::size_t>(c) + 1] += d.ChunkVisible[static_cast<std::size_t>(c)];
  }
  const std::size_t visible =
    static_cast<std::size_t>(d.ChunkVisible[static_cast<std::size_t>(chunks)]);
  const std::int64_t nv = static_cast<std::int64_t>(visible);
  ResizeKeep(d.Keys, 2 * visible);
  ResizeKeep(d.Records, visible);
  ResizeKeep(d.CompactLevels, visible);
  double* levels = d.CompactLevels.data();
  std::uint64_t* keys = d.Keys.data();
  Data::VisibleRecord* records = d.Records.data();
  const MultiViewPrepared& prep = d.Prepared;
  const bool colors = d.Colors;
  const bool viewIndependent = d.ViewIndependentColor;
  std::uint32_t depthOr = 0, depthAnd = ~0u;
#pragma omp parallel for schedule(static, 1) num_threads(chunks) reduction(| : depthOr) reduction(& : depthAnd)
  for (int c = 0; c < chunks; ++c)
  {
    const std::int64_t b = sn * c / chunks, e = sn * (c + 1) / chunks;
    std::size_t k = static_cast<std::size_t>(d.ChunkVisible[static_cast<std::size_t>(c)]);
    for (std::int64_t ii = b; ii < e; ++ii)
    {
      const std::size_t i = static_cast<std::size_t>(ii);
      if (out.Status[i] != 0)
      {
        continue;
      }
      Data::VisibleRecord& rec = records[k];
      float col[3] = { 0, 0, 0 };
      if (colors && viewIndependent)
      {
        col[0] = prep.Color[3 * i];
        col[1] = prep.Color[3 * i + 1];
        col[2] = prep.Color[3 * i + 2];
      }
      rec.Kernel = { out.U[i],
        out.V[i],
        out.A[i],
        out.B[i],
        out.C[i],
        prep.Opacity[i],
        col[0],
        col[1],
        col[2],
        out.Depth[i] };
      rec.Rect[0] = out.X0[i];
      rec.Rect[1] = out.Y0[i];
      rec.Rect[2] = out.X1[i];
      rec.Rect[3] = out.Y1[i];
      rec.Radius = out.Radius[i];
      rec.Id = static_cast<std::uint32_t>(i);
      const float o = prep.Opacity[i];
      levels[k] = o >= raster::MinAlpha<float>()
        ? std::min(0.0, std::log(raster::MinAlpha<double>() / static_cast<double>(o)))
        : 0.0;
      std::uint32_t bits;
      std::memcpy(&bits, &out.Depth[i], sizeof(bits));
      depthOr |= bits;
      depthAnd &= bits;
      keys[k] = (static_cast<std::uint64_t>(bits) << 32) | static_cast<std::uint64_t>(k);
      ++k;
    }
  }
  // (3) Global (depth, index) order: stable radix sort on the depth bits that differ (as
  // BinGaussians<float>; depth > 0.2, so the bits order like the values).
  const std::uint32_t differ = depthOr & ~depthAnd;
  int hi = 0;
  while (hi < 32 && (differ >> hi) != 0)
  {
    ++hi;
  }
  const std::uint64_t* sorted = RadixSortKeys(keys, keys + visible, nv, 32, 32 + hi, chunks);

  // (4) Per-Gaussian data in sorted order: kernel, colour, tile rectangle, alpha level, spans.
  ResizeKeep(d.Sorted, visible);
  ResizeKeep(d.Kernels, visible);
  ResizeKeep(d.Bounds, visible);
  ResizeKeep(d.Rects, visible);
  ResizeKeep(d.Radius, visible);
  const int shDegree = d.ShDegree;
  const int shStride = colors ? 3 * cloud.ShCoefficientCount() : 0;
#pragma omp parallel for schedule(static) num_threads(chunks)
  for (std::int64_t ss = 0; ss < nv; ++ss)
  {
    const std::size_t s = static_cast<std::size_t>(ss);
    if (ss + 16 < nv)
    {
      const std::uint32_t ahead = static_cast<std::uint32_t>(sorted[s + 16]);
      __builtin_prefetch(&records[ahead]);
      __builtin_prefetch(&levels[ahead]);
    }
    const std::uint32_t pos = static_cast<std::uint32_t>(sorted[s]);
    const Data::VisibleRecord& rec = records[pos];
    const std::uint32_t id = rec.Id;
    d.Sorted[s] = id;
    raster::detail::KernelGaussian<float> k = rec.Kernel;
    if (colors && !viewIndependent)
    {
      const float* pos = &cloud.Positions[3 * static_cast<std::size_t>(id)];
      float dir[3] = { pos[0] - w.Center[0], pos[1] - w.Center[1], pos[2] - w.Center[2] };
      const float len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
      for (auto& v : dir)
      {
        v = v / len;
      }
      float c3[3];
      ShColor<float>(&cloud.SH[id * static_cast<std::size_t>(shStride)], shDegree, dir, c3);
      k.R = std::max(c3[0], 0.0f);
      k.G = std::max(c3[1], 0.0f);
      k.Bl = std::max(c3[2], 0.0f);
    }
    d.Kernels[s] = k;
    d.Rects[s] = { rec.Rect[0], rec.Rect[1], rec.Rect[2], rec.Rect[3] };
    d.Radius[s] = rec.Radius;
    if (k.O >= raster::MinAlpha<float>())
    {
      raster::detail::SpanBounds sb =
        raster::detail::MakeSpanBounds<float>(k.U, k.V, k.A, k.B, k.C, levels[pos]);
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
      d.Bounds[s] = sb;
    }
    else
    {
      d.Bounds[s] = raster::detail::SpanBounds();
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
void MultiViewRenderer::Composite(RasterImage<float>& image)
{
  Data& d = *this->Impl;
  if (!d.HasView)
  {
    throw std::logic_error("MultiViewRenderer::Composite: no view was projected");
  }
  const int chunks = d.Threads;
  const std::size_t gx = static_cast<std::size_t>(d.Camera.Gx);
  const std::size_t gy = static_cast<std::size_t>(d.Camera.Gy);
  const std::size_t tiles = gx * gy;
  const std::int64_t nv = static_cast<std::int64_t>(d.Sorted.size());
  // Binning, as BinGaussians() step 3 on the sorted sequence; the lists hold sorted positions.
  TileBins& bins = d.Bins;
  bins.TilesX = d.Camera.Gx;
  bins.TilesY = d.Camera.Gy;
  const std::size_t dx = gx + 1;
  const std::size_t diffSize = dx * (gy + 1);
  d.Diff.assign(static_cast<std::size_t>(chunks) * diffSize, 0);
  using Rect = std::array<int, 4>;
  const Rect* rects = d.Rects.data();
#pragma omp parallel for schedule(static, 1) num_threads(chunks)
  for (int c = 0; c < chunks; ++c)
  {
    std::int64_t* df = &d.Diff[static_cast<std::size_t>(c) * diffSize];
    const std::int64_t b = nv * c / chunks, e = nv * (c + 1) / chunks;
    for (std::int64_t k = b; k < e; ++k)
    {
      const Rect& r = rects[static_cast<std::size_t>(k)];
      const std::size_t x0 = static_cast<std::size_t>(r[0]), y0 = static_cast<std::size_t>(r[1]);
      const std::size_t x1 = static_cast<std::size_t>(r[2]), y1 = static_cast<std::size_t>(r[3]);
      ++df[y0 * dx + x0];
      --df[y0 * dx + x1];
      --df[y1 * dx + x0];
      ++df[y1 * dx + x1];
    }
    for (std::size_t y = 0; y < gy; ++y)
    {
      std::int64_t* row = df + y * dx;
      for (std::size_t x = 1; x < gx; ++x)
      {
        row[x] += row[x - 1];
      }
      if (y > 0)
      {
        const std::int64_t* up = row - dx;
        for (std::size_t x = 0; x < gx; ++x)
        {
          row[x] += up[x];
        }
      }
    }
  }
  bins.Offsets.assign(tiles + 1, 0);
  std::uint64_t running = 0;
  for (std::size_t ty = 0; ty < gy; ++ty)
  {
    for (std::size_t tx = 0; tx < gx; ++tx)
    {
      bins.Offsets[ty * gx + tx] = running;
      for (int c = 0; c < chunks; ++c)
      {
        std::int64_t& h = d.Diff[static_cast<std::size_t>(c) * diffSize + ty * dx + tx];
        const std::uint64_t k = static_cast<std::uint64_t>(h);
        h = static_cast<std::int64_t>(running);
        running += k;
      }
    }
  }
  bins.Offsets[tiles] = running;
  ResizeKeep(bins.Ids, static_cast<std::size_t>(running));
  std::uint32_t* ids = bins.Ids.data();
#pragma omp parallel for schedule(static, 1) num_threads(chunks)
  for (int c = 0; c < chunks; ++c)
  {
    std::int64_t* cursor = &d.Diff[static_cast<std::size_t>(c) * diffSize];
    const std::int64_t b = nv * c / chunks, e = nv * (c + 1) / chunks;
    for (std::int64_t k = b; k < e; ++k)
    {
      const Rect& r = rects[static_cast<std::size_t>(k)];
      for (int ty = r[1]; ty < r[3]; ++ty)
      {
        std::int64_t* row = cursor + static_cast<std::size_t>(ty) * dx;
        for (int tx = r[0]; tx < r[2]; ++tx)
        {
          ids[row[tx]++] = static_cast<std::uint32_t>(k);
        }
      }
    }
  }

  // Compositing: the tile loop of CompositeTiles() on the sorted data.
  const std::size_t pixels = static_cast<std::size_t>(d.Camera.W) * d.Camera.H;
  image.Width = d.Camera.W;
  image.Height = d.Camera.H;
  image.Color.resize(3 * pixels);
  image.Alpha.resize(pixels);
  image.Transmittance.resize(pixels);
  image.Depth.resize(pixels);
  image.Contributors.resize(pixels);
  std::atomic<std::uint64_t> kernelEvals{ 0 }, referenceEvals{ 0 };
  const RasterSettings& settings = d.Settings;
  CompositeContext<float> ctx{ &d.Frame,
    &bins,
    d.Kernels.data(),
    d.Bounds.data(),
    &image,
    nullptr,
    { static_cast<float>(settings.Background[0]),
      static_cast<float>(settings.Background[1]),
      static_cast<float>(settings.Background[2]) },
    &kernelEvals,
    &referenceEvals };
  const TileFunction<float> fn = SelectTileFunction<float, false, false>(settings.KernelIsa);
  const std::int64_t tileCount = static_cast<std::int64_t>(tiles);
#pragma omp parallel for schedule(dynamic, 1) num_threads(chunks)
  for (std::int64_t t = 0; t < tileCount; ++t)
  {
    fn(ctx, t);
  }
}

template ViewProjection<float> ProjectGaussians<float>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&);
template ViewProjection<double> ProjectGaussians<double>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&);
template TileBins BinGaussians<float>(const ViewProjection<float>&, int);
template TileBins BinGaussians<double>(const ViewProjection<double>&, int);
template void CompositeTiles<float>(const ViewProjection<float>&,
  const TileBins&,
  const RasterSettings&,
  RasterImage<float>&,
  GaussianWeightStats*,
  RasterWorkCounts*);
template void CompositeTiles<double>(const ViewProjection<double>&,
  const TileBins&,
  const RasterSettings&,
  RasterImage<double>&,
  GaussianWeightStats*,
  RasterWorkCounts*);
template RasterImage<float> Rasterize<float>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&,
  ProjectionCounts*);
template RasterImage<double> Rasterize<double>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&,
  ProjectionCounts*);
template std::vector<PixelAttribution> AttributePixels<float>(const ViewProjection<float>&,
  const TileBins&,
  const RasterSettings&,
  const std::vector<std::array<int, 2>>&);
template std::vector<PixelAttribution> AttributePixels<double>(const ViewProjection<double>&,
  const TileBins&,
  const RasterSettings&,
  const std::vector<std::array<int, 2>>&);

} // namespace vis4gs

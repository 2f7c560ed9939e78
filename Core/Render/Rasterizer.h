// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Rasterizer.h
 * @brief Exact CPU port of the forward pass of the reference 3DGS rasteriser
 * (diff-gaussian-rasterization, reference §2), with per-pixel attribution.
 *
 * The pass is split into three public steps so that diagnostics and the trainer can reuse
 * the parts they need:
 *
 *  1. ProjectGaussians(): per-Gaussian preprocessing (§2.3, §2.4): world-to-view, near cull,
 *     EWA projection with the Jacobian clamp, +0.3 dilation, det == 0 cull, conic, 3-sigma
 *     radius, pixel-space mean, 16x16 tile rectangle, SH colour. Parallel over Gaussians; in
 *     float, 16 Gaussians per vector (the projection code of MultiViewRenderer).
 *  2. BinGaussians(): per-tile lists sorted front to back by view z, ties by Gaussian index
 *     (the order of the reference's stable radix sort on (tile, depth) keys).
 *  3. CompositeTiles(): front-to-back blending per pixel (§2.6), parallel over tiles.
 *
 * Rasterize() runs all three. AttributePixels() replays the blending of chosen pixels and
 * returns every contributing Gaussian with its weight w = alpha*T. Footprint statistics
 * (|Omega(g,v)|, sums of per-pixel maps over Omega) are in Footprint.h.
 *
 * Templated on the scalar type: float reproduces the reference (float32, default); double
 * is a reference mode for accuracy checks. Only float and double are instantiated.
 *
 * Conventions: images are row-major with row 0 at the TOP (the camera's +y points down),
 * pixel (x, y) is sampled at the integer position (x, y). The principal point is the image
 * centre, as in the reference: Camera::Cx/Cy are ignored; the focal lengths used are
 * Camera::Fx/Fy (tan(fov/2) = W/(2 fx)). To render at another resolution, pass
 * Camera::Resized(w, h), which keeps the field of view.
 *
 * Degenerate input never poisons other Gaussians or pixels: a Gaussian with any NaN/Inf
 * parameter it would use is skipped and counted (ProjectionStatus::InvalidParameters), and
 * one whose projection overflows the scalar type is skipped and counted
 * (ProjectionStatus::NonFinite). Core/Render/README.md documents every stiff case.
 */
#ifndef vis4gs_Rasterizer_h
#define vis4gs_Rasterizer_h

#include "Camera.h"
#include "GaussianCloud.h"
#include "RasterBounds.h"
#include "RasterKernel.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace vis4gs
{

/// Options of a rasterisation.
struct RasterSettings
{
  /// Background colour added as T*bg to every pixel. Default black.
  std::array<double, 3> Background{ 0.0, 0.0, 0.0 };
  /// Active SH degree; -1 (default) uses every degree the cloud holds. Clamped to the cloud's.
  int ShDegree = -1;
  /// Multiplies every scale (the reference's scale_modifier). Default 1.
  double ScaleModifier = 1.0;
  /// Evaluate SH colours in ProjectGaussians(). Footprint-only work can turn this off.
  bool ComputeColors = true;
  /// OpenMP threads; 0 (default) uses OpenMP's default.
  int Threads = 0;
  /// Instruction set of the projection (float) and compositing loops: 0 = best available
  /// (default), 1 = baseline x86-64 (SSE2), 2 = AVX2, 3 = AVX-512; -1 = the scalar
  /// per-Gaussian projection (the reference the 16-lane projection is tested against) and
  /// baseline compositing. Results are bit-identical on every path; this is a knob for tests
  /// and benchmarks.
  int KernelIsa = 0;
  /// Compositing: a pixel stops at the Gaussian that would bring its transmittance below this
  /// value (reference §2.6: 1e-4, the default, bit for bit the reference). A larger value stops
  /// pixels earlier, an approximation whose error is at most about this fraction of the
  /// background and of the Gaussians behind (the scene view's moving frames). In (0, 1);
  /// CompositeTiles() throws std::invalid_argument otherwise.
  double TransmittanceStop = 1e-4;
};

/// Why a Gaussian does or does not take part in a view.
enum class ProjectionStatus : std::uint8_t
{
  Visible = 0,           ///< survived every cull: radius > 0 and a non-empty tile rectangle
  InvalidParameters = 1, ///< a NaN/Inf raw parameter it would use; skipped and counted
  NearPlane = 2,         ///< view z <= 0.2 (behind the camera included), reference cull
  Degenerate = 3,        ///< det of the dilated 2D covariance == 0, reference cull
  NonFinite = 4,         ///< the projection overflowed the scalar type (Inf/NaN covariance,
                         ///< conic or radius); skipped and counted (the reference would
                         ///< produce garbage)
  OffScreen = 5          ///< empty tile rectangle, reference cull
};

/// Number of Gaussians per ProjectionStatus.
struct ProjectionCounts
{
  std::size_t Visible = 0;
  std::size_t InvalidParameters = 0;
  std::size_t NearPlane = 0;
  std::size_t Degenerate = 0;
  std::size_t NonFinite = 0;
  std::size_t OffScreen = 0;
};

/**
 * Result of preprocessing one Gaussian for one view (reference §2.3 step 12, plus what the
 * backward pass needs). Fields other than Status are meaningful only when Status == Visible,
 * except ViewPosition (set whenever the parameters are finite). The first ten values are
 * those of the compositing's kernel record, in its order (raster::detail::KernelGaussian),
 * so that the compositing reads them in place (CompositeData::KeepKernels).
 */
template <typename T>
struct ProjectedGaussian
{
  T U = 0, V = 0;                       ///< pixel-space mean (ndc2Pix)
  T ConicA = 0, ConicB = 0, ConicC = 0; ///< inverse of the dilated 2D covariance
  T Opacity = 0;                        ///< sigmoid(logit)
  T Color[3] = { 0, 0, 0 };             ///< SH colour + 0.5, clamped at 0
  T Depth = 0;                          ///< view-space z of the mean (sort key)
  T Cov2D[3] = { 0, 0, 0 };             ///< dilated 2D covariance a, b, c (pixels^2)
  T ViewPosition[3] = { 0, 0, 0 };      ///< t = R mu + t_v
  int Radius = 0;                       ///< ceil(3 sqrt(lambda_max)) pixels; 0 when culled
  int TileRect[4] = { 0, 0, 0, 0 };     ///< tiles x_min, y_min, x_max, y_max (max exclusive)
  ProjectionStatus Status = ProjectionStatus::InvalidParameters;
  std::uint8_t ClampedChannels = 0; ///< bit c set when colour channel c was clamped at 0
  bool IsVisible() const { return this->Status == ProjectionStatus::Visible; }
};

/// The camera as the rasteriser sees it, and every Gaussian projected into it.
template <typename T>
struct ViewProjection
{
  int Width = 0, Height = 0;
  int TilesX = 0, TilesY = 0;
  int ShDegree = 0; ///< active degree used for the colours
  T Fx = 0, Fy = 0; ///< focal lengths W/(2 tan), H/(2 tan)
  T TanFovX = 0, TanFovY = 0;
  std::array<T, 16> ViewMatrix{};     ///< row-major world-to-camera
  std::array<T, 16> FullProjection{}; ///< row-major P * W2C (reference §2.2)
  std::array<T, 3> CameraCenter{};
  std::vector<ProjectedGaussian<T>> Gaussians; ///< one per input Gaussian, input order
  ProjectionCounts Counts;
};

/**
 * Preprocesses every Gaussian of @p cloud for @p camera (reference §2.3, §2.4). Throws
 * std::invalid_argument for an unusable camera (non-positive size or focal length,
 * non-finite pose) or a cloud whose arrays do not match its Count, and when Count exceeds
 * 2^32 - 1.
 */
template <typename T>
ViewProjection<T> ProjectGaussians(const GaussianCloud& cloud,
  const Camera& camera,
  const RasterSettings& settings = {});

/**
 * Preprocesses every Gaussian into @p projection, reusing its memory: for a caller that
 * projects repeatedly (the scene view's frames), the ~100 B per Gaussian are not allocated
 * and page-faulted again. Every field of every Gaussian is reset before it is written, so
 * the result is the one ProjectGaussians() returns, bit for bit and field by field.
 */
template <typename T>
void ProjectGaussians(const GaussianCloud& cloud,
  const Camera& camera,
  const RasterSettings& settings,
  ViewProjection<T>& projection);

/**
 * A view's parameters in float as every lane projection reads them (ProjectGaussians<float>,
 * MultiViewRenderer, Core/Diagnostics' fast coverage): image and tile-grid size, the rows of
 * the world-to-camera matrix, rows 0, 1 and 3 of the full projection, the Jacobian clamps
 * 1.3 tan(fov/2), the focal lengths and the camera centre, all as the float projection holds
 * them (the one per-view preparation; a copy with the same numbers is bit-identical).
 */
struct PreparedView
{
  int W, H, Gx, Gy;
  float V[12];
  float F0[4], F1[4], F3[4];
  float LimX, LimY, FocalX, FocalY;
  float Center[3];
};

/// The PreparedView of the float projection @p frame (its Gaussians are not read).
PreparedView PrepareView(const ViewProjection<float>& frame);

struct MultiViewPrepared; // internal (MultiViewData.h)

/**
 * The view-independent part of ProjectGaussians<float> (finiteness of the parameters, exp of
 * the scales, quaternion, 3D covariance, sigmoid of the opacity) kept between frames of one
 * cloud, for a caller that renders the same cloud from many cameras (the scene view). It is
 * reused only while the caller's cloud version (non-zero) and everything the preparation
 * reads besides the parameters' values are unchanged: the cloud's address, Count, ShDegree,
 * the addresses and sizes of its parameter arrays, the scale modifier, the SH coefficients
 * checked for finiteness and whether colours are computed. The caller promises that the
 * values of a cloud do not change while its version does not; a sample of 64 Gaussians is
 * re-prepared and compared bit for bit with the kept data on every reuse, and a difference
 * throws std::logic_error naming the version and the Gaussian. Copies start empty.
 */
class PreparedCloudCache
{
public:
  PreparedCloudCache();
  ~PreparedCloudCache();
  PreparedCloudCache(const PreparedCloudCache&);
  PreparedCloudCache& operator=(const PreparedCloudCache&);
  PreparedCloudCache(PreparedCloudCache&&) noexcept;
  PreparedCloudCache& operator=(PreparedCloudCache&&) noexcept;

  /// Forgets the kept data (the next projection prepares again).
  void Clear();
  /// Preparations computed / reused since construction (for tests and benchmarks).
  std::size_t Builds() const;
  std::size_t Reuses() const;

  /// Internal (RasterProjection.cxx).
  struct Impl;
  Impl& Internal();

private:
  std::unique_ptr<Impl> P;
};

/**
 * ProjectGaussians<float>(cloud, camera, settings, projection) with the view-independent
 * preparation taken from @p cache when @p cloudVersion is non-zero and matches (see
 * PreparedCloudCache); the result is the same, bit for bit and field by field. With
 * @p cloudVersion 0, or with the scalar projection (KernelIsa -1), the cache is not used.
 */
void ProjectGaussians(const GaussianCloud& cloud,
  const Camera& camera,
  const RasterSettings& settings,
  ViewProjection<float>& projection,
  PreparedCloudCache& cache,
  std::uint64_t cloudVersion);

/**
 * Makes @p cache, which holds the preparation of version @p from of @p cloud for @p settings,
 * hold that of version @p to by preparing again only the Gaussians @p changed (indices below
 * cloud.Count, any order) and those beyond the Count it was prepared for: the caller's promise
 * that no other Gaussian's parameters changed (a cloud that changes a few Gaussians in place
 * between frames: the scene view's moving set, Core/Splats/SplatMovingSet.h). The next
 * projection of version @p to reuses it, bit for bit the preparation of the whole cloud, with
 * the usual spot check. Returns false, and changes nothing, when the cache does not hold
 * version @p from of this cloud (address, SH degree, scale modifier, colours), when a version is
 * 0, when the projection does not use the cache (KernelIsa -1) or when the cloud grew beyond
 * the kept buffers: the next projection then prepares every Gaussian. Throws
 * std::invalid_argument for an index of @p changed not below cloud.Count.
 */
bool RefreshPreparedCloud(PreparedCloudCache& cache,
  const GaussianCloud& cloud,
  std::uint64_t from,
  std::uint64_t to,
  const std::vector<std::uint32_t>& changed,
  const RasterSettings& settings);

/**
 * ProjectGaussians(cloud, camera, settings, projection, cache, cloudVersion) of the Gaussians
 * @p subset of @p cloud only: projection.Gaussians[j] is the cloud's Gaussian subset[j],
 * projected exactly as in the whole cloud's projection, bit for bit, and Counts count the
 * subset. The indices ascend, so that binning breaks ties in depth as for the whole cloud.
 * The cache holds the whole cloud's preparation (the same as whole projections use). Throws
 * std::invalid_argument for an index out of range or not ascending. Level-of-detail frames of
 * the scene view project a subset (Core/Splats/SplatLevelOfDetail.h).
 */
void ProjectGaussianSubset(const GaussianCloud& cloud,
  const std::vector<std::uint32_t>& subset,
  const Camera& camera,
  const RasterSettings& settings,
  ViewProjection<float>& projection,
  PreparedCloudCache& cache,
  std::uint64_t cloudVersion);

/// Per-tile Gaussian lists, front to back.
struct TileBins
{
  int TilesX = 0, TilesY = 0;
  /// TilesX*TilesY + 1 offsets: tile t (= ty*TilesX + tx) holds Ids[Offsets[t], Offsets[t+1]).
  std::vector<std::uint64_t> Offsets;
  /// Gaussian indices, each tile's run sorted by view z, ties by index.
  std::vector<std::uint32_t> Ids;
  std::size_t TileCount() const { return static_cast<std::size_t>(this->TilesX) * this->TilesY; }
};

/// Builds the per-tile lists of the visible Gaussians: one global stable sort by (depth, index),
/// then a stable counting scatter into the tiles, so every tile's list comes out sorted.
template <typename T>
TileBins BinGaussians(const ViewProjection<T>& projection, int threads = 0);

/// BinGaussians()' intermediate buffers (sort keys, compacted ids and rectangles), kept
/// between calls by a caller that bins repeatedly. Opaque; movable, not copyable.
class BinScratch
{
public:
  BinScratch();
  ~BinScratch();
  BinScratch(BinScratch&&) noexcept;
  BinScratch& operator=(BinScratch&&) noexcept;
  struct Buffers;
  std::unique_ptr<Buffers> Impl;
};

/// BinGaussians() into @p bins, reusing its memory and @p scratch's (same lists, bit for bit).
template <typename T>
void BinGaussians(const ViewProjection<T>& projection,
  int threads,
  TileBins& bins,
  BinScratch& scratch);

/// Rasteriser outputs, row-major, row 0 at the top.
template <typename T>
struct RasterImage
{
  int Width = 0, Height = 0;
  std::vector<T> Color;         ///< 3 per pixel, RGB interleaved: C + T*bg (not clamped)
  std::vector<T> Alpha;         ///< accumulated alpha 1 - T
  std::vector<T> Transmittance; ///< final T (the reference's final_T)
  /// Alpha-weighted view z, sum_i w_i z_i with w_i = alpha_i T_i (background adds 0), as
  /// the later reference renderers accumulate depth (they accumulate 1/z the same way).
  /// The expected depth of the visible surface is Depth / Alpha.
  std::vector<T> Depth;
  /// The reference's n_contrib: 1-based position, in the pixel's tile list, of the last
  /// blended Gaussian (skipped list entries before it are counted); 0 if none blended.
  std::vector<std::uint32_t> Contributors;
};

/// Optional per-Gaussian statistics gathered while compositing (occlusion-aware).
struct GaussianWeightStats
{
  std::vector<float> MaxWeight;             ///< max over pixels of alpha*T
  std::vector<double> WeightSum;            ///< sum over pixels of alpha*T
  std::vector<std::uint32_t> BlendedPixels; ///< pixels where the Gaussian was blended
  /// Input: also count Evaluations (CompositeTiles() then keeps the per-pixel stop positions
  /// of the work counters, slightly slower). Default off.
  bool CountEvaluations = false;
  /// With CountEvaluations: the pixels at which the reference evaluates the Gaussian, the
  /// pixels of the image in the tiles it is binned into that have not stopped (T < 1e-4) at an
  /// earlier Gaussian of their tile list, whether or not its alpha reaches 1/255 there
  /// (reference §2.6: a pixel evaluates every list entry up to and including the one it
  /// stops at). Summed over the Gaussian's tiles; empty without CountEvaluations.
  std::vector<std::uint64_t> Evaluations;
};

/// Work counters of a rasterisation, for benchmarks and diagnostics.
struct RasterWorkCounts
{
  std::uint64_t TilePairs = 0;         ///< (tile, Gaussian) pairs in the bins
  std::uint64_t KernelEvaluations = 0; ///< Gaussian-pixel kernels evaluated by this code
  /// Gaussian-pixel pairs the reference evaluates (every pixel of the tile until that pixel
  /// stops): a machine-independent work measure.
  std::uint64_t ReferenceEvaluations = 0;
};

/**
 * Per-Gaussian data of the compositing loop, input order: the kernel (mean, conic, opacity,
 * colour, depth) of every visible Gaussian and the conservative spans (RasterBounds.h) of the
 * pixels where its alpha can reach 1/255 (unbounded when the opacity is below 1/255).
 * Culled Gaussians hold zeros and no bound. The spans are kept as SpanRecord (40 bytes: the
 * mean is the kernel's; SpanRecord::Expand() gives back the SpanBounds). CompositeTiles() fills it
 * on request, so that a consumer replaying the blending (the trainer's backward) reads the very
 * data the forward decided with instead of recomputing it.
 */
template <typename T>
struct CompositeData
{
  std::vector<raster::detail::KernelGaussian<T>> Kernels;
  std::vector<raster::detail::SpanRecord> Bounds;
  /// false: CompositeTiles() leaves Kernels empty and reads every kernel from the projection
  /// in place (the same values), 40 bytes (float) per Gaussian less for a caller that only
  /// draws (the scene view). The default keeps them for a consumer that replays the blending.
  bool KeepKernels = true;
};

/// Fills @p data for @p projection (what CompositeTiles() keeps), reusing its buffers.
template <typename T>
void PrepareCompositeData(const ViewProjection<T>& projection, int threads, CompositeData<T>& data);

/// One blend kept by a PixelWeightRecord: the Gaussian (index in the projection) and its
/// weight w = alpha T at the pixel.
struct PixelWeight
{
  std::uint32_t Gaussian = 0;
  float Weight = 0.0f;
};

/**
 * Per-pixel blending weights kept by CompositeTiles() on request, so that a selection over
 * the drawn image's pixels (Brush, Frame) is a lookup instead of a replay of the compositing:
 * for every tile, each blend (pixel, Gaussian) whose weight w = alpha T is >= Threshold, w
 * computed by the compositing itself (the float product alpha * T of the blended lane, as its
 * GaussianWeightStats and MaxWeightsOverPixels() compute it). The weights of one pixel sum to at
 * most 1, so a pixel holds at most 1 / Threshold blends: 9 bytes each (PixelWeight and the
 * pixel's byte), at most width * height * 9 / Threshold bytes in all, typically far fewer.
 */
struct PixelWeightRecord
{
  /// Input: the smallest weight kept (> 0). Default 0.01 (the selections' default).
  float Threshold = 0.01f;
  /// Input: the most blends kept; a frame with more drops the record (Complete false) and
  /// frees it. Default 48M (432 MB).
  std::size_t MaximumEntries = std::size_t(48) << 20;
  int Width = 0, Height = 0, TilesX = 0;
  /// Per tile (row-major): the blends kept, and parallel to them the pixel of each in its
  /// tile (row * 16 + column).
  std::vector<std::vector<PixelWeight>> Weights;
  std::vector<std::vector<std::uint8_t>> Pixels;
  /// Whether the record holds every blend >= Threshold of the last compositing.
  bool Complete = false;
  /// Blends kept in all.
  std::size_t Entries() const;
};

/**
 * Blends every pixel (reference §2.6) into @p image (resized as needed). When @p weights
 * is given, it is resized to the Gaussian count and filled. When @p work is given, the
 * counters are computed (slightly slower). When @p keep is given, the per-Gaussian kernel
 * data and spans are left in it (its buffers are reused between calls). With @p depth
 * false, RasterImage::Depth is not computed and left empty (every other output is
 * unchanged, bit for bit); @p weights and @p work need @p depth (std::invalid_argument).
 * When @p record is given, the blends of weight >= its Threshold are kept in it (every other
 * output unchanged, bit for bit; std::invalid_argument for a Threshold that is not positive).
 */
template <typename T>
void CompositeTiles(const ViewProjection<T>& projection,
  const TileBins& bins,
  const RasterSettings& settings,
  RasterImage<T>& image,
  GaussianWeightStats* weights = nullptr,
  RasterWorkCounts* work = nullptr,
  CompositeData<T>* keep = nullptr,
  bool depth = true,
  PixelWeightRecord* record = nullptr);

/**
 * Everything a rasterisation allocates, kept by a caller that renders repeatedly (the scene
 * view, a selection's per-camera pass): with it, Rasterize() reuses the projection, tile
 * lists, binning scratch, per-Gaussian compositing data and image buffers of the previous
 * call instead of allocating and page-faulting them again (≈ 300 MB at 1M Gaussians).
 * Results are bit-identical to the allocating calls, whatever the sizes of earlier calls.
 */
template <typename T>
struct RasterWorkspace
{
  ViewProjection<T> Projection;
  TileBins Bins;
  BinScratch Scratch;
  CompositeData<T> Composite;
  RasterImage<T> Image; ///< the result of Rasterize(cloud, camera, settings, workspace)
  /// The caller's version of the cloud it renders (float only): non-zero = the cloud's
  /// parameters are unchanged while this number is, and Rasterize() keeps the
  /// view-independent preparation in Prepared between calls (see PreparedCloudCache).
  /// Default 0: prepared again on every call.
  std::uint64_t CloudVersion = 0;
  PreparedCloudCache Prepared;
};

/// Projection, binning and compositing into @p workspace.Image, reusing its buffers.
template <typename T>
void Rasterize(const GaussianCloud& cloud,
  const Camera& camera,
  const RasterSettings& settings,
  RasterWorkspace<T>& workspace);

/**
 * Culls (Status OffScreen, Radius 0, Counts updated) every visible Gaussian of @p projection
 * whose tile rectangle meets no tile where @p tiles is non-zero (one byte per tile, row-major,
 * TilesX * TilesY). Binned and composited, the chosen tiles then hold the full render's pixels,
 * bit for bit (their lists keep the same Gaussians in the same order), for the cost of the
 * Gaussians that reach them; other tiles hold a partial render. Returns the Gaussians culled;
 * throws std::invalid_argument when @p tiles does not match the view.
 */
template <typename T>
std::size_t KeepTiles(ViewProjection<T>& projection, const std::vector<std::uint8_t>& tiles);

/**
 * Rasterize() of the tiles where @p tiles is non-zero (see KeepTiles()) into
 * @p workspace.Image, without depth: what a clean-up's "after" re-renders where the removal
 * changed the image (Selection/RemovalEffect.h).
 */
template <typename T>
void RasterizeTiles(const GaussianCloud& cloud,
  const Camera& camera,
  const RasterSettings& settings,
  const std::vector<std::uint8_t>& tiles,
  RasterWorkspace<T>& workspace);

/// Projection, binning and compositing in one call.
template <typename T>
RasterImage<T> Rasterize(const GaussianCloud& cloud,
  const Camera& camera,
  const RasterSettings& settings = {},
  ProjectionCounts* counts = nullptr);

/// One Gaussian's contribution to one pixel.
struct PixelContribution
{
  std::uint32_t Gaussian = 0;     ///< index in the cloud
  std::uint32_t ListPosition = 0; ///< 1-based position in the pixel's tile list
  double Alpha = 0;               ///< alpha = min(0.99, o e^power)
  double Transmittance = 0;       ///< T before this Gaussian
  double Weight = 0;              ///< blending weight w = alpha * T
};

/// Every Gaussian blended into one pixel, ranked by weight (largest first, ties front first).
struct PixelAttribution
{
  int X = 0, Y = 0;
  std::vector<PixelContribution> Contributions;
  double FinalTransmittance = 1;
  std::uint32_t Contributors = 0;         ///< n_contrib
  std::array<double, 3> Color{ 0, 0, 0 }; ///< the pixel's value, as rendered
};

/**
 * Replays the blending of each requested pixel (x, y), exactly as CompositeTiles() does,
 * and returns the contributing Gaussians with their weights. Pixels outside the image give
 * an empty attribution with FinalTransmittance 1. Parallel over pixels.
 */
template <typename T>
std::vector<PixelAttribution> AttributePixels(const ViewProjection<T>& projection,
  const TileBins& bins,
  const RasterSettings& settings,
  const std::vector<std::array<int, 2>>& pixels);

/// A Gaussian's total contribution to a set of pixels.
struct GaussianContribution
{
  std::uint32_t Gaussian = 0;
  double WeightSum = 0;     ///< sum over the pixels of w
  double MaxWeight = 0;     ///< max over the pixels of w
  std::uint32_t Pixels = 0; ///< pixels of the set it was blended into
};

/// Aggregates attributions of a pixel set per Gaussian, ranked by WeightSum (largest first,
/// ties by Gaussian index).
std::vector<GaussianContribution> RankContributors(
  const std::vector<PixelAttribution>& attributions);

extern template ViewProjection<float> ProjectGaussians<float>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&);
extern template ViewProjection<double> ProjectGaussians<double>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&);
extern template void ProjectGaussians<float>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&,
  ViewProjection<float>&);
extern template void ProjectGaussians<double>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&,
  ViewProjection<double>&);
extern template void BinGaussians<float>(const ViewProjection<float>&, int, TileBins&, BinScratch&);
extern template void BinGaussians<double>(const ViewProjection<double>&,
  int,
  TileBins&,
  BinScratch&);
extern template void Rasterize<float>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&,
  RasterWorkspace<float>&);
extern template void Rasterize<double>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&,
  RasterWorkspace<double>&);
extern template TileBins BinGaussians<float>(const ViewProjection<float>&, int);
extern template TileBins BinGaussians<double>(const ViewProjection<double>&, int);
extern template void PrepareCompositeData<float>(const ViewProjection<float>&,
  int,
  CompositeData<float>&);
extern template void PrepareCompositeData<double>(const ViewProjection<double>&,
  int,
  CompositeData<double>&);
extern template void CompositeTiles<float>(const ViewProjection<float>&,
  const TileBins&,
  const RasterSettings&,
  RasterImage<float>&,
  GaussianWeightStats*,
  RasterWorkCounts*,
  CompositeData<float>*,
  bool,
  PixelWeightRecord*);
extern template void CompositeTiles<double>(const ViewProjection<double>&,
  const TileBins&,
  const RasterSettings&,
  RasterImage<double>&,
  GaussianWeightStats*,
  RasterWorkCounts*,
  CompositeData<double>*,
  bool,
  PixelWeightRecord*);
extern template std::size_t KeepTiles<float>(ViewProjection<float>&,
  const std::vector<std::uint8_t>&);
extern template std::size_t KeepTiles<double>(ViewProjection<double>&,
  const std::vector<std::uint8_t>&);
extern template void RasterizeTiles<float>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&,
  const std::vector<std::uint8_t>&,
  RasterWorkspace<float>&);
extern template void RasterizeTiles<double>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&,
  const std::vector<std::uint8_t>&,
  RasterWorkspace<double>&);
extern template RasterImage<float> Rasterize<float>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&,
  ProjectionCounts*);
extern template RasterImage<double> Rasterize<double>(const GaussianCloud&,
  const Camera&,
  const RasterSettings&,
  ProjectionCounts*);
extern template std::vector<PixelAttribution> AttributePixels<float>(const ViewProjection<float>&,
  const TileBins&,
  const RasterSettings&,
  const std::vector<std::array<int, 2>>&);
extern template std::vector<PixelAttribution> AttributePixels<double>(const ViewProjection<double>&,
  const TileBins&,
  const RasterSettings&,
  const std::vector<std::array<int, 2>>&);

} // namespace vis4gs

#endif

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file RasterBackward.h
 * @brief Backward pass of the reference 3DGS rasteriser (reference §5): gradients of a
 * scalar loss with respect to every raw Gaussian parameter, given dL/d(image), plus the
 * view-space (NDC) gradient statistic of adaptive density control (§5.8).
 *
 * The pass reuses the forward's ViewProjection, TileBins and RasterImage (Core/Render) and
 * runs in two stages:
 *
 *  1. CompositeBackward(): per tile, per pixel, back to front over the list positions before
 *     the pixel's n_contrib, recovering T_i = T_{i+1}/(1 - alpha_i) from the final
 *     transmittance and re-applying the forward's skips (power > 0, alpha < 1/255) with the
 *     same inline kernel functions (RasterKernel.h), exactly as [DGR] renderCUDA's backward.
 *     The default implementation walks the tile's Gaussians back to front and evaluates one
 *     tile row (16 pixels) at a time in 16 lanes (GCC vector extensions, AVX-512 / AVX2 /
 *     SSE2 chosen at run time as in the forward, bit-identical on all three); each
 *     Gaussian's per-tile sums run per lane over the rows, then over the lanes in a fixed
 *     tree. BackwardSettings::KernelIsa = -1 selects the scalar pixel-by-pixel reference.
 *     Produces per-Gaussian gradients of the 2D quantities: dL/du, dL/dv (pixels), the
 *     true scalar derivatives dL/dA, dL/dB, dL/dC of the conic (A, B, C), dL/d(opacity) and
 *     dL/d(colour). Each tile accumulates its Gaussians' gradients locally; tiles are
 *     grouped into fixed partitions (up to 16 bands of tile rows, chosen from the image and
 *     cloud sizes only), each partition adds its tiles in order into its own per-Gaussian
 *     array, and the partitions are summed in order: the result does not depend on the
 *     number of threads or on scheduling (deterministic training).
 *  2. ProjectBackward(): per Gaussian (parallel, independent), through the conic inverse
 *     (§5.3), the EWA projection and the 3D covariance (§5.4), the mean projection (§5.5),
 *     scale and rotation with the quaternion normalisation (§5.6), and the SH colour with its
 *     view-direction path (§5.7).
 *
 * Conventions (documented choices):
 *  - 0.99 alpha clamp: ignored in the backward, as [DGR] does (dL/dG = o dL/dalpha even
 *    where alpha was clamped). Finite differences disagree there; tests stay away from it.
 *  - Jacobian clamp (|t_x/t_z| > 1.3 tan(fovx/2)): by default the [DGR] form: the gradient
 *    to t_x (t_y) is zeroed and dL/dt_z uses the unclamped factor 2 (2 fx t~x / t_z^3)
 *    although the exact derivative of the clamped J02 = -fx lim / t_z is fx t~x / t_z^3
 *    (factor 1). BackwardSettings::ExactJacobianClamp selects the exact derivative.
 *  - Conic inverse: the exact 1/det^2 ([DGR] adds 1e-7 to det^2 as a guard; the forward's
 *    det == 0 cull makes it unnecessary here).
 *  - Colour channels clamped at 0 in the forward get no gradient (as [DGR]).
 *  - Quaternion normalisation: dL/dq = (g - q^ (q^.g)) / |q| with the norm floored at
 *    1e-12, as PyTorch's F.normalize. A zero quaternion normalises to zero, whose rotation
 *    matrix is the identity (polynomial form) and whose derivative dR/dq^ is zero: its
 *    rotation gradient is exactly 0 (it is a stationary point and Adam never moves it).
 *  - Culled Gaussians (radius 0) get zero gradients and no view-space statistic.
 *
 * Templated on the scalar: float for training, double for finite-difference checks.
 */
#ifndef vis4gs_RasterBackward_h
#define vis4gs_RasterBackward_h

#include "GaussianCloud.h"
#include "RasterBounds.h"
#include "Rasterizer.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace vis4gs
{

/// Options of the backward pass.
struct BackwardSettings
{
  /// Exact derivative in the Jacobian-clamp regime instead of [DGR]'s factor-2 form.
  bool ExactJacobianClamp = false;
  /// OpenMP threads; 0 (default) uses OpenMP's default. Results do not depend on it.
  int Threads = 0;
  /// Compositing backward: 0 = 16-lane path on the best instruction set (default), 1 =
  /// 16-lane path on baseline x86-64 (SSE2), 2 = AVX2, 3 = AVX-512 (the lane paths give
  /// bit-identical results on every instruction set), -1 = the scalar reference, pixel by
  /// pixel (the same per-pixel arithmetic; its per-Gaussian sums run in row-major pixel
  /// order instead of per lane then across lanes, so it agrees to rounding, not bit for bit).
  int KernelIsa = 0;
};

/// Scratch memory of CompositeForward() and CompositeBackward(), kept between calls to
/// avoid reallocations.
template <typename T>
struct BackwardWorkspace
{
  std::vector<T> Accumulators;                     ///< per partition, per Gaussian
  std::vector<std::uint8_t> Marks;                 ///< per partition, per Gaussian: touched
  std::vector<std::vector<std::uint32_t>> Touched; ///< per partition: Gaussians touched
  /// Per Gaussian: the compositing loop's 2D data and pixel spans (Render's CompositeData,
  /// filled by the forward's CompositeTiles()).
  CompositeData<T> Composite;
  /// Set by CompositeForward(): the projection Composite was made from (its Gaussians'
  /// address and count). CompositeBackward() on the same, unmodified projection reuses it
  /// and clears the stamp; anything else recomputes it.
  const void* PreparedFor = nullptr;
  std::size_t PreparedCount = 0;
};

/// Per-Gaussian gradients of the 2D (projected) quantities, from CompositeBackward().
template <typename T>
struct ProjectedGradients
{
  /// 9 per Gaussian: dL/du, dL/dv, dL/dA, dL/dB, dL/dC, dL/do, dL/dcolour RGB.
  /// (u, v) in pixels; A, B, C the conic entries as scalars (B appears once).
  std::vector<T> Values;
  static constexpr int Stride = 9;
  std::size_t Count() const { return this->Values.size() / Stride; }
  /// Reused scratch memory (keep the object between calls).
  BackwardWorkspace<T> Workspace;
};

/// Gradients with respect to the raw parameters of a GaussianCloud (same layouts).
template <typename T>
struct GaussianGradients
{
  std::size_t Count = 0;
  int ShCoefficients = 1;       ///< K = (degree+1)^2 of the cloud
  std::vector<T> Positions;     ///< 3 per Gaussian
  std::vector<T> LogScales;     ///< 3 per Gaussian
  std::vector<T> Rotations;     ///< 4 per Gaussian (raw, unnormalised quaternion)
  std::vector<T> OpacityLogits; ///< 1 per Gaussian
  std::vector<T> SH;            ///< 3K per Gaussian, coefficient-major
  /// 2 per Gaussian: (sum over pixels of dL/dndc_x, dL/dndc_y), i.e. (W/2 dL/du, H/2 dL/dv).
  std::vector<T> ViewspaceGradients;
  /// 1 per Gaussian: 1 when the Gaussian survived culling in the view (radius > 0).
  std::vector<std::uint8_t> Visible;
  /// Stage-1 output of RasterBackward() and its reusable scratch memory.
  ProjectedGradients<T> Projected;

  /// Resizes and zeroes every array.
  void Reset(std::size_t count, int shCoefficients);
  /// |(dL/dndc_x, dL/dndc_y)| of Gaussian i, the per-view ADC statistic (§5.8).
  T ViewspaceNorm(std::size_t i) const;
};

/**
 * Stage 1: compositing and kernel backward. @p dLdImage holds 3 values per pixel (RGB
 * interleaved, row-major, as RasterImage::Color). @p image must be the forward's output
 * for the same projection and bins (its Transmittance and Contributors are used).
 */
template <typename T>
void CompositeBackward(const ViewProjection<T>& projection,
  const TileBins& bins,
  const RasterSettings& settings,
  const RasterImage<T>& image,
  const T* dLdImage,
  ProjectedGradients<T>& gradients,
  const BackwardSettings& options = {});

/**
 * The forward compositing of training: Render's CompositeTiles() itself (one compositing
 * code), with depth off (RasterImage::Depth left empty; Color, Alpha, Transmittance and
 * Contributors are CompositeTiles()'s bit for bit), on the best instruction set or the one
 * @p options.KernelIsa names (1 baseline, 2 AVX2, 3 AVX-512), with @p options.Threads.
 * With @p workspace (the ProjectedGradients::Workspace later passed to CompositeBackward()
 * for the same projection), the per-Gaussian spans and 2D data of the forward are kept for
 * the backward instead of being recomputed; the projection must not change in between.
 */
template <typename T>
void CompositeForward(const ViewProjection<T>& projection,
  const TileBins& bins,
  const RasterSettings& settings,
  RasterImage<T>& image,
  const BackwardSettings& options = {},
  BackwardWorkspace<T>* workspace = nullptr);

/**
 * Stage 2: from the 2D gradients to the raw parameters of @p cloud (which must be the
 * cloud @p projection was made from, with the same settings). Fills every array of
 * @p gradients (resized), including the view-space statistic.
 */
template <typename T>
void ProjectBackward(const GaussianCloud& cloud,
  const ViewProjection<T>& projection,
  const RasterSettings& settings,
  const ProjectedGradients<T>& projected,
  GaussianGradients<T>& gradients,
  const BackwardSettings& options = {});

/// Both stages. The 2D gradients are left in @p gradients.Projected, whose scratch memory is
/// reused when the same @p gradients object is passed again (the trainer does).
template <typename T>
void RasterBackward(const GaussianCloud& cloud,
  const ViewProjection<T>& projection,
  const TileBins& bins,
  const RasterSettings& settings,
  const RasterImage<T>& image,
  const T* dLdImage,
  GaussianGradients<T>& gradients,
  const BackwardSettings& options = {});

namespace detail
{
/// Testing hook of the lane path's row selection: bit r (r < 16) is set when tile row
/// y0 + r has candidate columns of @p span within [x0, x0 + 15], computed as the 16-lane
/// backward does on instruction set @p isa (1 baseline, 2 AVX2, 3 AVX-512, 0 the best;
/// an unsupported one falls back as BackwardSettings::KernelIsa does), or for @p isa = -1
/// row by row with SpanBounds::Columns(), the definition it must reproduce.
std::uint32_t BackwardSpanRowMask(const raster::detail::SpanBounds& span, int x0, int y0, int isa);
} // namespace detail

extern template struct GaussianGradients<float>;
extern template struct GaussianGradients<double>;
extern template void CompositeBackward<float>(const ViewProjection<float>&,
  const TileBins&,
  const RasterSettings&,
  const RasterImage<float>&,
  const float*,
  ProjectedGradients<float>&,
  const BackwardSettings&);
extern template void CompositeBackward<double>(const ViewProjection<double>&,
  const TileBins&,
  const RasterSettings&,
  const RasterImage<double>&,
  const double*,
  ProjectedGradients<double>&,
  const BackwardSettings&);
extern template void CompositeForward<float>(const ViewProjection<float>&,
  const TileBins&,
  const RasterSettings&,
  RasterImage<float>&,
  const BackwardSettings&,
  BackwardWorkspace<float>*);
extern template void CompositeForward<double>(const ViewProjection<double>&,
  const TileBins&,
  const RasterSettings&,
  RasterImage<double>&,
  const BackwardSettings&,
  BackwardWorkspace<double>*);
extern template void ProjectBackward<float>(const GaussianCloud&,
  const ViewProjection<float>&,
  const RasterSettings&,
  const ProjectedGradients<float>&,
  GaussianGradients<float>&,
  const BackwardSettings&);
extern template void ProjectBackward<double>(const GaussianCloud&,
  const ViewProjection<double>&,
  const RasterSettings&,
  const ProjectedGradients<double>&,
  GaussianGradients<double>&,
  const BackwardSettings&);
extern template void RasterBackward<float>(const GaussianCloud&,
  const ViewProjection<float>&,
  const TileBins&,
  const RasterSettings&,
  const RasterImage<float>&,
  const float*,
  GaussianGradients<float>&,
  const BackwardSettings&);
extern template void RasterBackward<double>(const GaussianCloud&,
  const ViewProjection<double>&,
  const TileBins&,
  const RasterSettings&,
  const RasterImage<double>&,
  const double*,
  GaussianGradients<double>&,
  const BackwardSettings&);

} // namespace vis4gs

#endif

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Loss.h
 * @brief The training loss of the reference trainer and its image metrics (reference §3):
 * L1, SSIM (11x11 Gaussian window, sigma 1.5, zero padding of 5, C1 = 0.01^2, C2 = 0.03^2,
 * mean over channels and every pixel), L = (1 - lambda) L1 + lambda (1 - SSIM) with
 * lambda = 0.2, their exact gradients with respect to the rendered image, and PSNR.
 *
 * Images are RGB interleaved, row-major (3 values per pixel), as RasterImage::Color.
 * Accumulations (sums over the image) are done in double whatever the pixel type, in a fixed
 * order, so results do not depend on the thread count.
 */
#ifndef vis4gs_Loss_h
#define vis4gs_Loss_h

#include <cstddef>
#include <vector>

namespace vis4gs
{

/// Values of the loss terms for one image pair.
struct LossValues
{
  double L1 = 0;   ///< mean |x - y| over 3HW values
  double Ssim = 0; ///< mean SSIM map
  double Loss = 0; ///< (1 - lambda) L1 + lambda (1 - SSIM)
};

/// The 11 weights of the normalised 1D Gaussian window (sigma 1.5).
const std::vector<double>& SsimWindow1D();

namespace detail
{
/// Testing hook: the zero-padded separable blur of SSIM (the 11-tap window along rows,
/// then columns) of one @p width x @p height plane, on instruction set @p isa (0 the best,
/// 1 baseline, 2 AVX2, 3 AVX-512; an unsupported one falls back to the next lower).
template <typename T>
void SsimBlur(const T* in, T* out, int width, int height, int isa);
/// Testing hook: the mean SSIM (and, when @p gradient is given, its gradient with respect
/// to @p x, 3 per pixel) with every SSIM kernel on instruction set @p isa, one thread.
template <typename T>
double SsimOnIsa(const T* x, const T* y, int width, int height, int isa, T* gradient);
} // namespace detail

/// Mean |x - y| over @p count values.
template <typename T>
double L1Loss(const T* x, const T* y, std::size_t count);

/// SSIM of two RGB images of @p width x @p height (mean of the SSIM map, all channels).
template <typename T>
double Ssim(const T* x, const T* y, int width, int height, int threads = 0);

/**
 * The SSIM map itself: @p map (resized to 3 * width * height) receives, channel after
 * channel, the SSIM value of every pixel (planar: channel c, pixel p at c * W * H + p); its
 * mean is Ssim(). A pixel's value depends only on the 11x11 window around it (zero padding at
 * the image border) and is computed in the same order whatever the image's size, so the map
 * of a crop equals the full image's map, bit for bit, at every crop pixel whose window lies
 * inside the crop or is cut only by a border the crop shares with the image (Selection's
 * ViewTileSums re-measures changed tiles this way).
 */
template <typename T>
void SsimMap(const T* x, const T* y, int width, int height, std::vector<T>& map, int threads = 0);

/**
 * The maps of SSIM that depend on the target image only (per channel its blurred mean and
 * blurred square), for a caller that compares many renderings with the same target (the
 * trainer, once per view): TrainingLoss() then blurs 18 planes per call instead of 24.
 */
template <typename T>
struct SsimTarget
{
  const T* Image = nullptr; ///< the target the maps were made from (not owned)
  int Width = 0, Height = 0;
  std::vector<T> Planes; ///< per channel: blurred mean, blurred square (W*H each)
};

/// Fills @p target for the RGB image @p y of @p width x @p height.
template <typename T>
void PrepareSsimTarget(const T* y, int width, int height, SsimTarget<T>& target, int threads = 0);

/**
 * Loss (1 - lambda) L1 + lambda (1 - SSIM) of rendered image @p x against @p y, and, when
 * @p gradient is not null, dL/dx (resized to 3 * width * height). L1's gradient uses
 * sign(0) = 0 as PyTorch does. With @p target (made by PrepareSsimTarget() from this
 * @p y and size, else std::invalid_argument), its maps are used instead of being
 * recomputed: the same results, bit for bit.
 */
template <typename T>
LossValues TrainingLoss(const T* x,
  const T* y,
  int width,
  int height,
  double lambda,
  std::vector<T>* gradient,
  int threads = 0,
  const SsimTarget<T>* target = nullptr);

/// PSNR 20 log10(1 / sqrt(MSE)) over every channel and pixel; +inf for identical images.
template <typename T>
double Psnr(const T* x, const T* y, std::size_t count);

} // namespace vis4gs

#endif

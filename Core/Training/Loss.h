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

/// Mean |x - y| over @p count values.
template <typename T>
double L1Loss(const T* x, const T* y, std::size_t count);

/// SSIM of two RGB images of @p width x @p height (mean of the SSIM map, all channels).
template <typename T>
double Ssim(const T* x, const T* y, int width, int height, int threads = 0);

/**
 * Loss (1 - lambda) L1 + lambda (1 - SSIM) of rendered image @p x against @p y, and, when
 * @p gradient is not null, dL/dx (resized to 3 * width * height). L1's gradient uses
 * sign(0) = 0 as PyTorch does.
 */
template <typename T>
LossValues TrainingLoss(const T* x,
  const T* y,
  int width,
  int height,
  double lambda,
  std::vector<T>* gradient,
  int threads = 0);

/// PSNR 20 log10(1 / sqrt(MSE)) over every channel and pixel; +inf for identical images.
template <typename T>
double Psnr(const T* x, const T* y, std::size_t count);

} // namespace vis4gs

#endif

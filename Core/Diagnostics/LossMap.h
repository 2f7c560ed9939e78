// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file LossMap.h
 * @brief The per-pixel loss map of a rendered view against its training image (DESIGN §4).
 *
 *   L(v) = (1 - lambda) L1(v) + lambda L_edge(v),   lambda = 0.2 by default
 *   L1[p]     = mean over RGB of |render - image|
 *   L_edge[p] = mean over RGB of |lap(render) - lap(image)|
 *   lap(f)[x,y] = f[x-1,y] + f[x+1,y] + f[x,y-1] + f[x,y+1] - 4 f[x,y]
 *
 * with edges replicated (a neighbour outside the image is the nearest pixel inside it). The
 * Laplacian is linear, so lap(render) - lap(image) = lap(render - image); the code applies it
 * to the difference d = render - image (one rounding fewer). Accumulation is in double; the map
 * is returned in float (the footprint sums read float maps).
 *
 * Lower-resolution loss maps (factor f in {2, 4, 8}): the view is rendered at
 * w' = max(1, round(W / f)) x h' = max(1, round(H / f)) with Camera::Resized (same field of
 * view, as the trainer's -r), and the training image is reduced to w' x h' by an exact
 * area-weighted box filter: low-resolution pixel x' covers the interval [x' W/w', (x'+1) W/w')
 * of full-resolution pixel edges, and each full-resolution pixel is weighted by the length
 * of its overlap with it (separably in x and y). When f divides W and H this is the plain mean
 * of each f x f block, whose centre is exactly the sample point of the low-resolution pixel.
 * The discrete Laplacian on a grid of spacing f approximates f^2 times the one on spacing 1,
 * so the low-resolution edge term is multiplied by edgeScale = (w' h') / (W H) (1/f^2) to
 * estimate the full-resolution one; without it the edge term grows with f^2 (measured in
 * Documentation/accuracy-vs-runtime.md).
 *
 * Images are RGB float, row-major, row 0 at the top (the rasteriser's layout), 3 values per
 * pixel. NaN in either input propagates to the pixels whose loss reads it (the centre and its
 * four neighbours) and nowhere else.
 */
#ifndef vis4gs_LossMap_h
#define vis4gs_LossMap_h

#include "ImageIO.h"

#include <cstddef>
#include <vector>

namespace vis4gs
{

/// The low-resolution size used for a loss-map factor: max(1, round(size / factor)).
int LossMapSize(int fullSize, int factor);

/**
 * Loss map of @p render against @p image (both width x height RGB, layout above); returns
 * width*height values. @p edgeScale multiplies the Laplacian term (1 for the definition;
 * the lower-resolution mode passes 1/f^2, see the file comment). Throws std::invalid_argument when
 * sizes do not match or are not positive. Parallel over rows (OpenMP).
 */
std::vector<float> ComputeLossMap(const float* render,
  const float* image,
  int width,
  int height,
  double lambda = 0.2,
  double edgeScale = 1.0);

/// Same on 3-channel images (Core/Scene/ImageIO.h); throws std::invalid_argument naming both
/// sizes when they differ, or when an image does not have 3 channels.
std::vector<float> ComputeLossMap(const Image& render, const Image& image, double lambda = 0.2);

/**
 * Area-weighted box reduction of the 3-channel @p image to @p width x @p height (each at most the
 * input's size; see the file comment). Throws std::invalid_argument for an empty image or a target
 * size that is not in [1, input size].
 */
Image BoxDownsample(const Image& image, int width, int height);

} // namespace vis4gs

#endif

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ImageIO.h
 * @brief Training images: PNG/JPEG reading (libpng, libjpeg) into float [0,1] pixels, alpha
 * compositing on a background, the trainer's resize, and a PNG writer for rendered outputs.
 *
 * Resizing follows Pillow's Image.resize with BICUBIC (what the trainer's PILtoTorch calls):
 * a separable cubic convolution with a = -0.5 whose support is widened by the scale factor
 * when shrinking (antialiasing), sample centres at (i + 0.5) * scale, weights normalised per
 * output pixel, horizontal pass first. Unlike Pillow we keep float intermediates instead of
 * rounding to 8 bits between the passes, so values differ from Pillow's by at most about one
 * 8-bit step. Alpha is composited at full resolution before resizing:
 * rgb = rgb * a + background * (1 - a) (the trainer's COLMAP path multiplies by alpha,
 * which is a black background).
 */
#ifndef vis4gs_ImageIO_h
#define vis4gs_ImageIO_h

#include "Camera.h"

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace vis4gs
{

/// Row-major interleaved float image, values nominally in [0,1].
struct Image
{
  int Width = 0;
  int Height = 0;
  int Channels = 3;
  std::vector<float> Pixels; ///< Height * Width * Channels

  float& At(int x, int y, int c)
  {
    return this->Pixels[(static_cast<std::size_t>(y) * this->Width + x) * this->Channels + c];
  }
  float At(int x, int y, int c) const
  {
    return this->Pixels[(static_cast<std::size_t>(y) * this->Width + x) * this->Channels + c];
  }
};

/// Reads a PNG or JPEG (detected from the content) as RGB (3 channels) or RGBA (4, when the
/// file has alpha); 8- and 16-bit, grey, palette. Throws std::runtime_error naming the file.
Image ReadImage(const std::string& path);
/// Same from memory; @p name is used in messages.
Image ReadImageFromMemory(const void* data, std::size_t size, const std::string& name);

/// RGB image with any alpha composited over @p background.
Image CompositeOnBackground(const Image& image, const std::array<float, 3>& background);

/// Pillow-style bicubic resize (see the file comment).
Image ResizeImage(const Image& image, int width, int height);

/// Writes 1, 3 or 4 channel float pixels (clamped to [0,1], rounded to 8 bits) as PNG,
/// through a temporary file renamed into place.
void WritePng(const std::string& path, const Image& image);
/// Writes 8-bit pixels (1, 2, 3 or 4 channels, row-major interleaved) as PNG.
void WritePng8(const std::string& path,
  int width,
  int height,
  int channels,
  const unsigned char* pixels);

/**
 * The training image of @p camera: Camera::ImagePath read, composited on @p background and
 * resized to the camera's Width x Height when its size differs. Errors name the camera and
 * the file (missing or unreadable).
 */
Image LoadTrainingImage(const Camera& camera, const std::array<float, 3>& background = { 0, 0, 0 });

/**
 * Matches cameras to image files by name: for each camera, the file in @p folder whose name
 * up to the first '.' equals Camera::Name (the trainer's image_name) becomes its ImagePath.
 * A camera without an image throws std::runtime_error naming the camera and the folder when
 * @p requireEach (default); otherwise it keeps its ImagePath, so that a reader for a purpose
 * that needs no image (rendering, coverage) takes cameras beside an empty or partial folder.
 */
void AttachImages(std::vector<Camera>& cameras, const std::string& folder, bool requireEach = true);

/// What LoadTrainingImage does to an image once read: composited on @p background and
/// resized to the camera's size. For images that come from elsewhere than a file (a training
/// log's /images), so that they are prepared exactly as the same pixels read from a PNG.
Image PrepareTrainingImage(const Image& image,
  const Camera& camera,
  const std::array<float, 3>& background = { 0, 0, 0 });

/// 8-bit samples (row-major, @p channels per pixel) as an Image of values / 255, the
/// conversion every 8-bit reader uses.
Image ImageFromBytes(const unsigned char* bytes, int width, int height, int channels);

} // namespace vis4gs

#endif

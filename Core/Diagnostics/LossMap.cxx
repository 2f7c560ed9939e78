// SPDX-License-Identifier: BSD-3-Clause
#include "LossMap.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vis4gs
{
namespace
{

std::size_t PixelCount(const Image& image)
{
  return static_cast<std::size_t>(image.Width) * static_cast<std::size_t>(image.Height);
}

struct Tap
{
  int Index;
  double Weight;
};

// Overlap weights of the full-resolution pixels [i, i+1) with each low-resolution interval
// [k s, (k+1) s), s = full/low, normalised to sum 1.
std::vector<std::vector<Tap>> BoxTaps(int full, int low)
{
  std::vector<std::vector<Tap>> taps(static_cast<std::size_t>(low));
  const double s = static_cast<double>(full) / low;
  for (int k = 0; k < low; ++k)
  {
    const double a = k * s;
    const double b = k + 1 == low ? full : (k + 1) * s;
    const int first = std::max(0, static_cast<int>(std::floor(a)));
    const int last = std::min(full - 1, static_cast<int>(std::ceil(b)) - 1);
    double total = 0;
    for (int i = first; i <= last; ++i)
    {
      const double w = std::min(b, i + 1.0) - std::max(a, static_cast<double>(i));
      if (w > 0)
      {
        taps[k].push_back({ i, w });
        total += w;
      }
    }
    for (auto& t : taps[k])
    {
      t.Weight /= total;
    }
  }
  return taps;
}

} // namespace

//------------------------------------------------------------------------------
int LossMapSize(int fullSize, int factor)
{
  if (fullSize <= 0 || factor <= 0)
  {
    throw std::invalid_argument("LossMapSize: size " + std::to_string(fullSize) + " and factor " +
      std::to_string(factor) + " must be positive");
  }
  return std::max(1, (fullSize + factor / 2) / factor);
}

//------------------------------------------------------------------------------
std::vector<float> ComputeLossMap(const float* render,
  const float* image,
  int width,
  int height,
  double lambda,
  double edgeScale)
{
  if (width <= 0 || height <= 0 || !render || !image)
  {
    throw std::invalid_argument(
      "ComputeLossMap: empty image (" + std::to_string(width) + "x" + std::to_string(height) + ")");
  }
  const std::size_t w = static_cast<std::size_t>(width);
  std::vector<float> loss(w * static_cast<std::size_t>(height));
  const double l1Weight = (1.0 - lambda) / 3.0;
  const double edgeWeight = edgeScale * lambda / 3.0;
#pragma omp parallel for schedule(static)
  for (int y = 0; y < height; ++y)
  {
    const std::size_t rowUp = static_cast<std::size_t>(y > 0 ? y - 1 : 0) * w;
    const std::size_t row = static_cast<std::size_t>(y) * w;
    const std::size_t rowDown = static_cast<std::size_t>(y + 1 < height ? y + 1 : y) * w;
    auto diff = [&](std::size_t pixel, int c) -> double
    { return static_cast<double>(render[3 * pixel + c]) - image[3 * pixel + c]; };
    for (int x = 0; x < width; ++x)
    {
      const std::size_t left = static_cast<std::size_t>(x > 0 ? x - 1 : 0);
      const std::size_t right = static_cast<std::size_t>(x + 1 < width ? x + 1 : x);
      const std::size_t xs = static_cast<std::size_t>(x);
      double l1 = 0, edge = 0;
      for (int c = 0; c < 3; ++c)
      {
        const double d = diff(row + xs, c);
        l1 += std::abs(d);
        const double lap = diff(rowUp + xs, c) + diff(rowDown + xs, c) + diff(row + left, c) +
          diff(row + right, c) - 4.0 * d;
        edge += std::abs(lap);
      }
      loss[row + xs] = static_cast<float>(l1Weight * l1 + edgeWeight * edge);
    }
  }
  return loss;
}

//------------------------------------------------------------------------------
std::vector<float> ComputeLossMap(const Image& render, const Image& image, double lambda)
{
  if (render.Width != image.Width || render.Height != image.Height)
  {
    throw std::invalid_argument("ComputeLossMap: the render is " + std::to_string(render.Width) +
      "x" + std::to_string(render.Height) + " but the image is " + std::to_string(image.Width) +
      "x" + std::to_string(image.Height));
  }
  if (render.Channels != 3 || image.Channels != 3 ||
    render.Pixels.size() != 3 * PixelCount(render) || image.Pixels.size() != 3 * PixelCount(image))
  {
    throw std::invalid_argument("ComputeLossMap: pixel buffers do not match the image sizes");
  }
  return ComputeLossMap(
    render.Pixels.data(), image.Pixels.data(), render.Width, render.Height, lambda);
}

//------------------------------------------------------------------------------
Image BoxDownsample(const Image& image, int width, int height)
{
  if (image.Width <= 0 || image.Height <= 0 || image.Channels != 3 ||
    image.Pixels.size() != 3 * PixelCount(image))
  {
    throw std::invalid_argument("BoxDownsample: empty, not RGB, or inconsistent image");
  }
  if (width < 1 || height < 1 || width > image.Width || height > image.Height)
  {
    throw std::invalid_argument("BoxDownsample: cannot reduce " + std::to_string(image.Width) +
      "x" + std::to_string(image.Height) + " to " + std::to_string(width) + "x" +
      std::to_string(height));
  }
  if (width == image.Width && height == image.Height)
  {
    return image;
  }
  const auto tx = BoxTaps(image.Width, width);
  const auto ty = BoxTaps(image.Height, height);
  // Horizontal pass into double rows, then vertical.
  const std::size_t W = static_cast<std::size_t>(image.Width);
  std::vector<double> rows(static_cast<std::size_t>(image.Height) * width * 3);
#pragma omp parallel for schedule(static)
  for (int y = 0; y < image.Height; ++y)
  {
    const float* src = image.Pixels.data() + 3 * W * y;
    double* dst = rows.data() + 3 * static_cast<std::size_t>(width) * y;
    for (int k = 0; k < width; ++k)
    {
      double s[3] = { 0, 0, 0 };
      for (const Tap& t : tx[k])
      {
        for (int c = 0; c < 3; ++c)
        {
          s[c] += t.Weight * src[3 * t.Index + c];
        }
      }
      for (int c = 0; c < 3; ++c)
      {
        dst[3 * k + c] = s[c];
      }
    }
  }
  Image out;
  out.Width = width;
  out.Height = height;
  out.Channels = 3;
  out.Pixels.resize(3 * PixelCount(out));
#pragma omp parallel for schedule(static)
  for (int k = 0; k < height; ++k)
  {
    float* dst = out.Pixels.data() + 3 * static_cast<std::size_t>(width) * k;
    for (int x = 0; x < 3 * width; ++x)
    {
      double s = 0;
      for (const Tap& t : ty[k])
      {
        s += t.Weight * rows[3 * static_cast<std::size_t>(width) * t.Index + x];
      }
      dst[x] = static_cast<float>(s);
    }
  }
  return out;
}

} // namespace vis4gs

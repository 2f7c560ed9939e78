// SPDX-License-Identifier: BSD-3-Clause
#include "ImageIO.h"
#include "SceneFile.h"

#include <png.h>

#include <cstdio> // jpeglib.h needs FILE and size_t first
#include <jerror.h>
#include <jpeglib.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstring>
#include <map>
#include <stdexcept>

#include <dirent.h>

namespace vis4gs
{

namespace
{

constexpr std::uint64_t MaxPixels = std::uint64_t(1) << 28;

[[noreturn]] void Fail(const std::string& name, const std::string& what)
{
  throw std::runtime_error(name + ": " + what);
}

//------------------------------------------------------------------------------
// PNG with the classic libpng API (keeps 16-bit precision, which the simplified API would
// gamma-convert).
struct PngMemory
{
  const unsigned char* Data;
  std::size_t Size;
  std::size_t Pos;
};

struct PngError
{
  std::string Message;
};

void PngErrorFn(png_structp png, png_const_charp msg)
{
  auto* err = static_cast<PngError*>(png_get_error_ptr(png));
  err->Message = msg ? msg : "unknown libpng error";
  png_longjmp(png, 1);
}

void PngWarningFn(png_structp, png_const_charp) {}

void PngReadFn(png_structp png, png_bytep out, png_size_t n)
{
  auto* m = static_cast<PngMemory*>(png_get_io_ptr(png));
  if (n > m->Size - m->Pos)
  {
    png_error(png, "file ends early (truncated PNG)");
  }
  std::memcpy(out, m->Data + m->Pos, n);
  m->Pos += n;
}

Image ReadPng(const unsigned char* data, std::size_t size, const std::string& name)
{
  PngError err;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &err, PngErrorFn, PngWarningFn);
  if (!png)
  {
    Fail(name, "cannot initialise libpng");
  }
  png_infop info = png_create_info_struct(png);
  Image image;
  std::vector<png_bytep> rows;
  std::vector<unsigned char> raw;
  PngMemory mem{ data, size, 0 };
  // Locals modified after setjmp must not be read after a longjmp unless volatile; only
  // err.Message is, and it is a member of an object whose address was taken.
  if (setjmp(png_jmpbuf(png)))
  {
    png_destroy_read_struct(&png, &info, nullptr);
    Fail(name, "unreadable PNG: " + err.Message);
  }
  png_set_read_fn(png, &mem, PngReadFn);
  png_set_user_limits(png, 1u << 16, 1u << 16);
  png_read_info(png, info);
  const png_uint_32 w = png_get_image_width(png, info);
  const png_uint_32 h = png_get_image_height(png, info);
  const int colorType = png_get_color_type(png, info);
  const int depth = png_get_bit_depth(png, info);
  if (w == 0 || h == 0 || static_cast<std::uint64_t>(w) * h > MaxPixels)
  {
    png_error(png, "image size not supported");
  }
  png_set_expand(png); // palette -> RGB, grey < 8 bit -> 8 bit, tRNS -> alpha
  if (colorType == PNG_COLOR_TYPE_GRAY || colorType == PNG_COLOR_TYPE_GRAY_ALPHA)
  {
    png_set_gray_to_rgb(png);
  }
  if (depth == 16 && detail::HostIsLittleEndian())
  {
    png_set_swap(png);
  }
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  const int channels = png_get_channels(png, info);
  const int outDepth = png_get_bit_depth(png, info);
  if ((channels != 3 && channels != 4) || (outDepth != 8 && outDepth != 16))
  {
    png_error(png, "unsupported PNG layout");
  }
  const std::size_t rowBytes = png_get_rowbytes(png, info);
  raw.resize(rowBytes * h);
  rows.resize(h);
  for (png_uint_32 y = 0; y < h; ++y)
  {
    rows[y] = raw.data() + y * rowBytes;
  }
  png_read_image(png, rows.data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);

  image.Width = static_cast<int>(w);
  image.Height = static_cast<int>(h);
  image.Channels = channels;
  const std::size_t n = static_cast<std::size_t>(w) * h * channels;
  image.Pixels.resize(n);
  if (outDepth == 8)
  {
    image = ImageFromBytes(raw.data(), image.Width, image.Height, channels);
  }
  else
  {
    for (std::size_t i = 0; i < n; ++i)
    {
      std::uint16_t v;
      std::memcpy(&v, raw.data() + 2 * i, 2);
      image.Pixels[i] = v / 65535.0f;
    }
  }
  return image;
}

//------------------------------------------------------------------------------
struct JpegError
{
  jpeg_error_mgr Mgr;
  std::jmp_buf Jump;
  char Message[JMSG_LENGTH_MAX];
  bool Truncated;
};

void JpegErrorExit(j_common_ptr cinfo)
{
  auto* err = reinterpret_cast<JpegError*>(cinfo->err);
  (*cinfo->err->format_message)(cinfo, err->Message);
  std::longjmp(err->Jump, 1);
}

void JpegOutputMessage(j_common_ptr) {}

// Warnings are ignored except a premature end of data, which Pillow (and so the trainer)
// refuses as a truncated image.
void JpegEmitMessage(j_common_ptr cinfo, int level)
{
  auto* err = reinterpret_cast<JpegError*>(cinfo->err);
  if (level < 0 && cinfo->err->msg_code == JWRN_JPEG_EOF)
  {
    err->Truncated = true;
  }
}

Image ReadJpeg(const unsigned char* data, std::size_t size, const std::string& name)
{
  jpeg_decompress_struct cinfo;
  JpegError err;
  err.Message[0] = 0;
  err.Truncated = false;
  cinfo.err = jpeg_std_error(&err.Mgr);
  err.Mgr.error_exit = JpegErrorExit;
  err.Mgr.output_message = JpegOutputMessage;
  err.Mgr.emit_message = JpegEmitMessage;
  Image image;
  std::vector<unsigned char> raw;
  if (setjmp(err.Jump))
  {
    jpeg_destroy_decompress(&cinfo);
    Fail(name, std::string("unreadable JPEG: ") + err.Message);
  }
  jpeg_create_decompress(&cinfo);
  jpeg_mem_src(&cinfo, data, static_cast<unsigned long>(size));
  jpeg_read_header(&cinfo, TRUE);
  if (cinfo.jpeg_color_space == JCS_CMYK || cinfo.jpeg_color_space == JCS_YCCK)
  {
    jpeg_destroy_decompress(&cinfo);
    Fail(name, "CMYK JPEGs are not supported; convert the image to RGB");
  }
  cinfo.out_color_space = JCS_RGB;
  if (cinfo.image_width == 0 || cinfo.image_height == 0 ||
    static_cast<std::uint64_t>(cinfo.image_width) * cinfo.image_height > MaxPixels)
  {
    jpeg_destroy_decompress(&cinfo);
    Fail(name, "image size not supported");
  }
  jpeg_start_decompress(&cinfo);
  const std::size_t w = cinfo.output_width, h = cinfo.output_height;
  raw.resize(w * h * 3);
  while (cinfo.output_scanline < cinfo.output_height)
  {
    JSAMPROW row = raw.data() + static_cast<std::size_t>(cinfo.output_scanline) * w * 3;
    jpeg_read_scanlines(&cinfo, &row, 1);
    if (err.Truncated)
    {
      break;
    }
  }
  if (err.Truncated)
  {
    jpeg_destroy_decompress(&cinfo);
    Fail(name, "unreadable JPEG: the file is truncated (premature end of data)");
  }
  jpeg_finish_decompress(&cinfo);
  jpeg_destroy_decompress(&cinfo);
  return ImageFromBytes(raw.data(), static_cast<int>(w), static_cast<int>(h), 3);
}

//------------------------------------------------------------------------------
// Pillow's bicubic kernel (a = -0.5).
double Bicubic(double x)
{
  const double a = -0.5;
  x = std::fabs(x);
  if (x < 1.0)
  {
    return ((a + 2.0) * x - (a + 3.0)) * x * x + 1.0;
  }
  if (x < 2.0)
  {
    return (((x - 5.0) * x + 8.0) * x - 4.0) * a;
  }
  return 0.0;
}

struct Coefficients
{
  std::vector<int> First;      // first input index per output
  std::vector<int> Count;      // taps per output
  std::vector<double> Weights; // Taps per output, padded
  int Taps = 0;
};

// Mirrors Pillow's precompute_coeffs (Resample.c).
Coefficients Precompute(int inSize, int outSize)
{
  const double scale = static_cast<double>(inSize) / outSize;
  const double filterScale = std::max(scale, 1.0);
  const double support = 2.0 * filterScale;
  Coefficients c;
  c.Taps = static_cast<int>(std::ceil(support)) * 2 + 1;
  c.First.resize(outSize);
  c.Count.resize(outSize);
  c.Weights.assign(static_cast<std::size_t>(outSize) * c.Taps, 0.0);
  for (int xx = 0; xx < outSize; ++xx)
  {
    const double center = (xx + 0.5) * scale;
    const double ss = 1.0 / filterScale;
    int xmin = static_cast<int>(center - support + 0.5);
    xmin = std::max(xmin, 0);
    int xmax = static_cast<int>(center + support + 0.5);
    xmax = std::min(xmax, inSize) - xmin;
    xmax = std::min(xmax, c.Taps);
    double* k = &c.Weights[static_cast<std::size_t>(xx) * c.Taps];
    double ww = 0;
    for (int x = 0; x < xmax; ++x)
    {
      const double w = Bicubic((x + xmin - center + 0.5) * ss);
      k[x] = w;
      ww += w;
    }
    for (int x = 0; x < xmax; ++x)
    {
      if (ww != 0.0)
      {
        k[x] /= ww;
      }
    }
    c.First[xx] = xmin;
    c.Count[xx] = std::max(xmax, 0);
  }
  return c;
}

} // namespace

//------------------------------------------------------------------------------
Image ReadImageFromMemory(const void* data, std::size_t size, const std::string& name)
{
  const auto* b = static_cast<const unsigned char*>(data);
  if (size >= 8 && png_sig_cmp(b, 0, 8) == 0)
  {
    return ReadPng(b, size, name);
  }
  if (size >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF)
  {
    return ReadJpeg(b, size, name);
  }
  Fail(name, "not a PNG or JPEG image");
}

//------------------------------------------------------------------------------
Image ReadImage(const std::string& path)
{
  const auto bytes = detail::ReadWholeFile(path);
  return ReadImageFromMemory(bytes.data(), bytes.size(), path);
}

//------------------------------------------------------------------------------
Image CompositeOnBackground(const Image& image, const std::array<float, 3>& background)
{
  if (image.Channels == 3)
  {
    return image;
  }
  Image out;
  out.Width = image.Width;
  out.Height = image.Height;
  out.Channels = 3;
  const std::size_t n = static_cast<std::size_t>(image.Width) * image.Height;
  out.Pixels.resize(3 * n);
  for (std::size_t i = 0; i < n; ++i)
  {
    if (image.Channels == 4)
    {
      const float a = image.Pixels[4 * i + 3];
      for (int c = 0; c < 3; ++c)
      {
        out.Pixels[3 * i + c] = image.Pixels[4 * i + c] * a + background[c] * (1.0f - a);
      }
    }
    else if (image.Channels == 1)
    {
      for (int c = 0; c < 3; ++c)
      {
        out.Pixels[3 * i + c] = image.Pixels[i];
      }
    }
    else
    {
      throw std::invalid_argument("CompositeOnBackground: 1, 3 or 4 channels expected");
    }
  }
  return out;
}

//------------------------------------------------------------------------------
Image ResizeImage(const Image& image, int width, int height)
{
  if (width <= 0 || height <= 0 || image.Width <= 0 || image.Height <= 0)
  {
    throw std::invalid_argument("ResizeImage: sizes must be positive");
  }
  if (width == image.Width && height == image.Height)
  {
    return image;
  }
  const int ch = image.Channels;
  // Horizontal pass into a float buffer (double accumulation), then vertical.
  Image tmp;
  tmp.Width = width;
  tmp.Height = image.Height;
  tmp.Channels = ch;
  tmp.Pixels.resize(static_cast<std::size_t>(width) * image.Height * ch);
  const Coefficients cx = Precompute(image.Width, width);
#pragma omp parallel for schedule(static)
  for (int y = 0; y < image.Height; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      const double* k = &cx.Weights[static_cast<std::size_t>(x) * cx.Taps];
      for (int c = 0; c < ch; ++c)
      {
        double s = 0;
        for (int t = 0; t < cx.Count[x]; ++t)
        {
          s += k[t] * image.At(cx.First[x] + t, y, c);
        }
        tmp.At(x, y, c) = static_cast<float>(s);
      }
    }
  }
  Image out;
  out.Width = width;
  out.Height = height;
  out.Channels = ch;
  out.Pixels.resize(static_cast<std::size_t>(width) * height * ch);
  const Coefficients cy = Precompute(image.Height, height);
#pragma omp parallel for schedule(static)
  for (int y = 0; y < height; ++y)
  {
    const double* k = &cy.Weights[static_cast<std::size_t>(y) * cy.Taps];
    for (int x = 0; x < width; ++x)
    {
      for (int c = 0; c < ch; ++c)
      {
        double s = 0;
        for (int t = 0; t < cy.Count[y]; ++t)
        {
          s += k[t] * tmp.At(x, cy.First[y] + t, c);
        }
        // Pillow clips to the 8-bit range; clamp to [0,1] likewise.
        out.At(x, y, c) = static_cast<float>(std::min(1.0, std::max(0.0, s)));
      }
    }
  }
  return out;
}

//------------------------------------------------------------------------------
void WritePng8(const std::string& path,
  int width,
  int height,
  int channels,
  const unsigned char* pixels)
{
  if (width <= 0 || height <= 0 || channels < 1 || channels > 4)
  {
    throw std::invalid_argument("WritePng8: bad image size or channel count");
  }
  png_image img;
  std::memset(&img, 0, sizeof(img));
  img.version = PNG_IMAGE_VERSION;
  img.width = static_cast<png_uint_32>(width);
  img.height = static_cast<png_uint_32>(height);
  img.format = channels == 1 ? PNG_FORMAT_GRAY
    : channels == 2          ? PNG_FORMAT_GA
    : channels == 3          ? PNG_FORMAT_RGB
                             : PNG_FORMAT_RGBA;
  detail::WriteFileAtomically(path,
    [&](std::FILE* f)
    {
      if (!png_image_write_to_stdio(&img, f, 0, pixels, 0, nullptr))
      {
        // libpng says only "Write Error"; the stream's errno says why (a full disk).
        const int error = errno;
        const std::string why = std::ferror(f) && error != 0 ? std::strerror(error) : img.message;
        png_image_free(&img);
        throw std::runtime_error(path + ": cannot write PNG: " + why);
      }
    });
}

//------------------------------------------------------------------------------
void WritePng(const std::string& path, const Image& image)
{
  if (image.Channels != 1 && image.Channels != 3 && image.Channels != 4)
  {
    throw std::invalid_argument("WritePng: 1, 3 or 4 channels expected");
  }
  std::vector<unsigned char> bytes(image.Pixels.size());
  for (std::size_t i = 0; i < bytes.size(); ++i)
  {
    const float v = image.Pixels[i];
    const float c = std::isnan(v) ? 0.0f : std::min(1.0f, std::max(0.0f, v));
    bytes[i] = static_cast<unsigned char>(std::lround(c * 255.0f));
  }
  WritePng8(path, image.Width, image.Height, image.Channels, bytes.data());
}

//------------------------------------------------------------------------------
Image LoadTrainingImage(const Camera& camera, const std::array<float, 3>& background)
{
  if (camera.ImagePath.empty())
  {
    throw std::runtime_error("camera '" + camera.Name + "' has no image");
  }
  if (!detail::IsRegularFile(camera.ImagePath))
  {
    throw std::runtime_error(camera.ImagePath + ": the image of camera '" + camera.Name +
      "' does not exist or is not a file");
  }
  Image image;
  try
  {
    image = ReadImage(camera.ImagePath);
  }
  catch (const std::runtime_error& e)
  {
    throw std::runtime_error(std::string(e.what()) + " (image of camera '" + camera.Name + "')");
  }
  return PrepareTrainingImage(image, camera, background);
}

//------------------------------------------------------------------------------
Image PrepareTrainingImage(const Image& image,
  const Camera& camera,
  const std::array<float, 3>& background)
{
  Image out = CompositeOnBackground(image, background);
  if (camera.Width > 0 && camera.Height > 0 &&
    (out.Width != camera.Width || out.Height != camera.Height))
  {
    out = ResizeImage(out, camera.Width, camera.Height);
  }
  return out;
}

//------------------------------------------------------------------------------
Image ImageFromBytes(const unsigned char* bytes, int width, int height, int channels)
{
  Image image;
  image.Width = width;
  image.Height = height;
  image.Channels = channels;
  const std::size_t n = static_cast<std::size_t>(width) * height * channels;
  image.Pixels.resize(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    image.Pixels[i] = bytes[i] / 255.0f;
  }
  return image;
}

//------------------------------------------------------------------------------
void AttachImages(std::vector<Camera>& cameras, const std::string& folder, bool requireEach)
{
  DIR* dir = ::opendir(folder.c_str());
  if (!dir)
  {
    throw std::runtime_error(folder + ": cannot open the image folder");
  }
  std::map<std::string, std::string> byStem;
  while (dirent* e = ::readdir(dir))
  {
    const std::string file = e->d_name;
    if (file.empty() || file[0] == '.')
    {
      continue;
    }
    const std::string ext = detail::LowerExtension(file);
    if (ext != ".png" && ext != ".jpg" && ext != ".jpeg")
    {
      continue;
    }
    byStem.emplace(file.substr(0, file.find('.')), file);
  }
  ::closedir(dir);
  for (Camera& cam : cameras)
  {
    const auto it = byStem.find(cam.Name);
    if (it == byStem.end() && !requireEach)
    {
      continue;
    }
    if (it == byStem.end())
    {
      throw std::runtime_error(folder + ": no image for camera '" + cam.Name + "' (looked for " +
        cam.Name + ".png/.jpg/.jpeg)");
    }
    cam.ImagePath = folder + "/" + it->second;
  }
}

} // namespace vis4gs

// SPDX-License-Identifier: BSD-3-Clause
// PNG/JPEG reading, alpha compositing, the Pillow-style bicubic resize (against an independent
// direct evaluation of Pillow's formula), the PNG writer and image/camera matching.
#include "ColmapDataset.h"
#include "ImageIO.h"
#include "SceneTestUtils.h"
#include "Vis4GSTestData.h"

#include <gtest/gtest.h>

#include <png.h>

#include <cmath>
#include <cstring>
#include <string>

#include <sys/stat.h>

namespace vis4gs
{
namespace
{

using testing::FileBytes;
using testing::TempDir;
using testing::WriteFile;

const std::string Statue = testing::SharedDataPath("colmap_statue_bartoszek");

Image Gradient(int w, int h, int ch)
{
  Image im;
  im.Width = w;
  im.Height = h;
  im.Channels = ch;
  im.Pixels.resize(static_cast<std::size_t>(w) * h * ch);
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      for (int c = 0; c < ch; ++c)
      {
        // Multiples of 1/255 so that 8-bit files hold them exactly.
        im.At(x, y, c) = static_cast<float>((x * 7 + y * 13 + c * 50) % 256) / 255.0f;
      }
    }
  }
  return im;
}

// Pillow's bicubic resample written out directly (one output sample, one axis).
double PillowWeight(double x)
{
  x = std::fabs(x);
  const double a = -0.5;
  return x < 1 ? (a + 2) * x * x * x - (a + 3) * x * x + 1
    : x < 2    ? a * x * x * x - 5 * a * x * x + 8 * a * x - 4 * a
               : 0;
}

std::vector<double> PillowRow(const std::vector<double>& in, int outSize)
{
  const int n = static_cast<int>(in.size());
  const double scale = static_cast<double>(n) / outSize;
  const double fs = scale > 1 ? scale : 1;
  std::vector<double> out(outSize);
  for (int i = 0; i < outSize; ++i)
  {
    const double center = (i + 0.5) * scale;
    double sum = 0, wsum = 0;
    for (int j = 0; j < n; ++j)
    {
      // Pixel j covers [j, j+1); its centre is j + 0.5. Taps outside the support weigh 0.
      const double w = PillowWeight((j + 0.5 - center) / fs);
      if (j >= static_cast<int>(center - 2 * fs + 0.5) &&
        j < static_cast<int>(center + 2 * fs + 0.5))
      {
        sum += w * in[j];
        wsum += w;
      }
    }
    out[i] = sum / wsum;
  }
  return out;
}

TEST(ImageIO, ReadsStatueJpegAtTheCameraSize)
{
  VIS4GS_REQUIRE_SHARED_DATA();
  const Dataset ds = LoadColmapDataset(Statue);
  const Image im = ReadImage(ds.Cameras[0].ImagePath);
  EXPECT_EQ(im.Channels, 3);
  EXPECT_EQ(im.Width, ds.Cameras[0].Width);
  EXPECT_EQ(im.Height, ds.Cameras[0].Height);
  float lo = 1, hi = 0;
  double mean = 0;
  for (float v : im.Pixels)
  {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    mean += v;
  }
  mean /= im.Pixels.size();
  EXPECT_GE(lo, 0.0f);
  EXPECT_LE(hi, 1.0f);
  EXPECT_GT(hi - lo, 0.5f); // a real photo, not a flat image
  EXPECT_GT(mean, 0.05);
  EXPECT_LT(mean, 0.95);
  // Training image at --resolution 2: resized to the camera's size.
  DatasetOptions o;
  o.Resolution = 2;
  const Dataset half = LoadColmapDataset(Statue, o);
  const Image small = LoadTrainingImage(half.Cameras[0]);
  EXPECT_EQ(small.Width, half.Cameras[0].Width);
  EXPECT_EQ(small.Height, half.Cameras[0].Height);
  // The mean brightness is kept by a normalised filter.
  double smallMean = 0;
  for (float v : small.Pixels)
  {
    smallMean += v;
  }
  smallMean /= small.Pixels.size();
  EXPECT_NEAR(smallMean, mean, 0.01);
}

TEST(ImageIO, PngRoundTripIsExactAt8Bits)
{
  TempDir dir;
  for (int ch : { 1, 3, 4 })
  {
    const Image im = Gradient(37, 21, ch);
    WritePng(dir / "a.png", im);
    const Image back = ReadImage(dir / "a.png");
    EXPECT_EQ(back.Width, 37);
    EXPECT_EQ(back.Height, 21);
    // Grey comes back as RGB; alpha is kept.
    EXPECT_EQ(back.Channels, ch == 4 ? 4 : 3);
    for (int y = 0; y < 21; ++y)
    {
      for (int x = 0; x < 37; ++x)
      {
        for (int c = 0; c < back.Channels; ++c)
        {
          ASSERT_EQ(back.At(x, y, c), im.At(x, y, ch == 1 ? 0 : c)) << x << "," << y << "," << c;
        }
      }
    }
  }
  // Values are clamped and rounded; NaN becomes 0.
  Image odd;
  odd.Width = 4;
  odd.Height = 1;
  odd.Channels = 1;
  odd.Pixels = { -1.0f, 2.0f, 0.5f, std::nanf("") };
  WritePng(dir / "b.png", odd);
  const Image b = ReadImage(dir / "b.png");
  EXPECT_EQ(b.At(0, 0, 0), 0.0f);
  EXPECT_EQ(b.At(1, 0, 0), 1.0f);
  EXPECT_EQ(b.At(2, 0, 0), 128 / 255.0f); // 127.5 rounds up
  EXPECT_EQ(b.At(3, 0, 0), 0.0f);
}

TEST(ImageIO, SixteenBitPngKeepsPrecision)
{
  TempDir dir;
  // 16-bit grey written with libpng directly (big-endian samples).
  const int w = 3;
  std::vector<unsigned char> row = { 0x00, 0x01, 0x80, 0x00, 0xff, 0xff };
  png_image img;
  std::memset(&img, 0, sizeof(img));
  img.version = PNG_IMAGE_VERSION;
  img.width = w;
  img.height = 1;
  img.format = PNG_FORMAT_LINEAR_Y; // 16-bit grey, native-endian uint16
  std::vector<std::uint16_t> samples = { 1, 32768, 65535 };
  ASSERT_TRUE(
    png_image_write_to_file(&img, (dir / "g16.png").c_str(), 0, samples.data(), 0, nullptr));
  const Image im = ReadImage(dir / "g16.png");
  ASSERT_EQ(im.Channels, 3);
  EXPECT_FLOAT_EQ(im.At(0, 0, 0), 1 / 65535.0f);
  EXPECT_FLOAT_EQ(im.At(1, 0, 1), 32768 / 65535.0f);
  EXPECT_FLOAT_EQ(im.At(2, 0, 2), 1.0f);
}

TEST(ImageIO, AlphaIsCompositedOnTheBackground)
{
  Image rgba;
  rgba.Width = 3;
  rgba.Height = 1;
  rgba.Channels = 4;
  rgba.Pixels = { 1, 0, 0, 0, /**/ 1, 0, 0, 1, /**/ 0.2f, 0.4f, 0.6f, 0.5f };
  const Image white = CompositeOnBackground(rgba, { 1, 1, 1 });
  ASSERT_EQ(white.Channels, 3);
  EXPECT_EQ(white.At(0, 0, 0), 1.0f); // transparent: background
  EXPECT_EQ(white.At(0, 0, 1), 1.0f);
  EXPECT_EQ(white.At(1, 0, 0), 1.0f); // opaque: colour
  EXPECT_EQ(white.At(1, 0, 1), 0.0f);
  EXPECT_FLOAT_EQ(white.At(2, 0, 0), 0.2f * 0.5f + 0.5f);
  EXPECT_FLOAT_EQ(white.At(2, 0, 2), 0.6f * 0.5f + 0.5f);
  const Image black = CompositeOnBackground(rgba, { 0, 0, 0 });
  EXPECT_EQ(black.At(0, 0, 0), 0.0f);
  EXPECT_FLOAT_EQ(black.At(2, 0, 1), 0.2f);
  // Through a file and a camera: the same result.
  TempDir dir;
  WritePng(dir / "cam.png", rgba);
  Camera cam;
  cam.Name = "cam";
  cam.ImagePath = dir / "cam.png";
  cam.Width = 3;
  cam.Height = 1;
  const Image loaded = LoadTrainingImage(cam, { 1, 1, 1 });
  EXPECT_NEAR(loaded.At(2, 0, 0), 0.2f * 0.5f + 0.5f, 1.0f / 255);
  EXPECT_EQ(loaded.At(0, 0, 2), 1.0f);
}

TEST(ImageIO, ResizeMatchesPillowsFormula)
{
  // Separable: a rank-one image (row profile r times column profile c) resizes to the outer
  // product of the 1D resizes, evaluated independently here.
  const int w = 23, h = 17;
  std::vector<double> r(w), c(h);
  for (int x = 0; x < w; ++x)
  {
    r[x] = 0.5 + 0.4 * std::sin(0.9 * x);
  }
  for (int y = 0; y < h; ++y)
  {
    c[y] = 0.6 + 0.3 * std::cos(1.3 * y);
  }
  Image im;
  im.Width = w;
  im.Height = h;
  im.Channels = 1;
  im.Pixels.resize(w * h);
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      im.At(x, y, 0) = static_cast<float>(r[x] * c[y]);
    }
  }
  for (auto [ow, oh] : { std::pair<int, int>(11, 8), { 5, 4 }, { 46, 34 }, { 23, 9 }, { 7, 17 } })
  {
    const Image out = ResizeImage(im, ow, oh);
    ASSERT_EQ(out.Width, ow);
    ASSERT_EQ(out.Height, oh);
    const auto rr = PillowRow(r, ow);
    const auto cc = PillowRow(c, oh);
    double maxErr = 0;
    for (int y = 0; y < oh; ++y)
    {
      for (int x = 0; x < ow; ++x)
      {
        const double expected = std::min(1.0, std::max(0.0, rr[x] * cc[y]));
        maxErr = std::max(maxErr, std::fabs(out.At(x, y, 0) - expected));
      }
    }
    EXPECT_LT(maxErr, 1e-6) << ow << "x" << oh;
  }
  // A constant image stays constant; halving averages pairs of a 2-periodic pattern.
  Image flat = im;
  std::fill(flat.Pixels.begin(), flat.Pixels.end(), 0.25f);
  for (float v : ResizeImage(flat, 9, 30).Pixels)
  {
    EXPECT_NEAR(v, 0.25f, 1e-6);
  }
  Image stripes;
  stripes.Width = 64;
  stripes.Height = 1;
  stripes.Channels = 1;
  for (int x = 0; x < 64; ++x)
  {
    stripes.Pixels.push_back(x % 2 ? 1.0f : 0.0f);
  }
  const Image halfStripes = ResizeImage(stripes, 32, 1);
  for (int x = 4; x < 28; ++x) // away from the borders
  {
    EXPECT_NEAR(halfStripes.At(x, 0, 0), 0.5f, 1e-6);
  }
}

TEST(ImageIO, UnreadableImagesAndCamerasWithoutImages)
{
  VIS4GS_REQUIRE_SHARED_DATA();
  TempDir dir;
  WriteFile(dir / "garbage.png", std::string("this is not an image"));
  EXPECT_THROW_WITH(ReadImage(dir / "garbage.png"), "garbage.png", "not a PNG or JPEG");
  // A truncated JPEG and PNG.
  const auto jpg = FileBytes(Statue + "/images/DSC_5283.jpg");
  WriteFile(dir / "cut.jpg", jpg.data(), jpg.size() / 2);
  EXPECT_THROW_WITH(ReadImage(dir / "cut.jpg"), "cut.jpg", "truncated");
  WritePng(dir / "ok.png", Gradient(40, 30, 3));
  const auto png = FileBytes(dir / "ok.png");
  WriteFile(dir / "cut.png", png.data(), png.size() / 2);
  EXPECT_THROW_WITH(ReadImage(dir / "cut.png"), "cut.png", "unreadable PNG");
  EXPECT_THROW_WITH(ReadImage(dir / "none.png"), "none.png", "cannot open");
  // Every prefix of a small PNG fails cleanly.
  for (std::size_t len = 0; len < png.size(); len += 7)
  {
    EXPECT_THROW(ReadImageFromMemory(png.data(), len, "p.png"), std::runtime_error) << len;
  }
  // Cameras: missing image file, unreadable image.
  Camera cam;
  cam.Name = "view7";
  cam.ImagePath = dir / "view7.png";
  EXPECT_THROW_WITH(LoadTrainingImage(cam), "view7.png", "camera 'view7'", "does not exist");
  cam.ImagePath = dir / "garbage.png";
  EXPECT_THROW_WITH(LoadTrainingImage(cam), "garbage.png", "camera 'view7'");
  // Matching cameras.json names to files: view1 has a .JPG, view2 none.
  std::vector<Camera> cams(2);
  cams[0].Name = "view1";
  cams[1].Name = "view2";
  ::mkdir((dir / "imgs").c_str(), 0755);
  WriteFile(dir / "imgs/view1.JPG", jpg);
  WriteFile(dir / "imgs/notes.txt", std::string("x"));
  EXPECT_THROW_WITH(AttachImages(cams, dir / "imgs"), "no image for camera 'view2'");
  // Not required (rendering): view2 keeps no image, view1 still gets its file; an empty
  // folder refuses no camera.
  AttachImages(cams, dir / "imgs", false);
  EXPECT_EQ(cams[0].ImagePath, dir / "imgs/view1.JPG");
  EXPECT_EQ(cams[1].ImagePath, "");
  ::mkdir((dir / "empty").c_str(), 0755);
  std::vector<Camera> none = cams;
  none[0].ImagePath.clear();
  AttachImages(none, dir / "empty", false);
  EXPECT_EQ(none[0].ImagePath, "");
  EXPECT_THROW_WITH(AttachImages(none, dir / "empty"), "no image for camera 'view1'");
  cams.pop_back();
  AttachImages(cams, dir / "imgs");
  EXPECT_EQ(cams[0].ImagePath, dir / "imgs/view1.JPG");
  EXPECT_THROW_WITH(AttachImages(cams, dir / "nope"), "cannot open the image folder");
}

} // namespace
} // namespace vis4gs

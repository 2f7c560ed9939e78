// SPDX-License-Identifier: BSD-3-Clause
// SOG v2: a scene assembled here (textures encoded with libwebp, meta.json by hand) decodes to
// the values derived by hand from the format's definition, as a folder, a meta.json path and a
// zip; lying counts, sizes and decompression bombs are refused before decoding, naming the
// file. splat-transform's own SOG files are compared in Testing/Reference (SogReference.py).
#include "GaussianIO.h"
#include "SceneTestUtils.h"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <webp/encode.h>
#include <zip.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <string>

namespace vis4gs
{
namespace
{

using testing::FileBytes;
using testing::TempDir;
using testing::WriteFile;

/// Lossless WebP keeping the RGB of transparent texels ("exact"), as SOG textures need.
std::vector<unsigned char> EncodeWebP(const std::vector<unsigned char>& rgba, int w, int h)
{
  WebPConfig config;
  WebPConfigInit(&config);
  config.lossless = 1;
  config.exact = 1;
  config.method = 0;
  WebPPicture picture;
  WebPPictureInit(&picture);
  picture.use_argb = 1;
  picture.width = w;
  picture.height = h;
  WebPMemoryWriter writer;
  WebPMemoryWriterInit(&writer);
  picture.writer = WebPMemoryWrite;
  picture.custom_ptr = &writer;
  std::vector<unsigned char> bytes;
  if (WebPPictureImportRGBA(&picture, rgba.data(), 4 * w) && WebPEncode(&config, &picture))
  {
    bytes.assign(writer.mem, writer.mem + writer.size);
  }
  WebPPictureFree(&picture);
  WebPMemoryWriterClear(&writer);
  return bytes;
}

/// A two-Gaussian SOG with SH degree 1: 4x4 textures, a palette of 2 centroids.
struct Scene
{
  std::map<std::string, std::vector<unsigned char>> Files;

  Scene()
  {
    std::vector<unsigned char> lo(64, 0), hi(64, 0), quats(64, 0), scales(64, 0), sh0(64, 0),
      labels(64, 0), centroids(192 * 4, 0);
    // Gaussian 0: x = 65535 (max), y = 0 (min), z = 32768.
    lo[0] = 255;
    hi[0] = 255;
    hi[2] = 128;
    quats[0] = quats[1] = quats[2] = 128;
    quats[3] = 252;
    scales[0] = 0;
    scales[1] = 5;
    scales[2] = 255;
    sh0[0] = 128;
    sh0[1] = 0;
    sh0[2] = 255;
    sh0[3] = 0;
    labels[0] = 1;
    // Gaussian 1: quaternion tag 100 (not 252..255), alpha 51, label 5 (past the palette).
    quats[4 + 3] = 100;
    sh0[4 + 3] = 51;
    labels[4] = 5;
    for (int j = 0; j < 3; ++j)
    {
      for (int c = 0; c < 3; ++c)
      {
        centroids[4 * (3 + j) + c] = static_cast<unsigned char>(10 * (3 * j + c + 1));
      }
    }
    Files["means_l.webp"] = EncodeWebP(lo, 4, 4);
    Files["means_u.webp"] = EncodeWebP(hi, 4, 4);
    Files["quats.webp"] = EncodeWebP(quats, 4, 4);
    Files["scales.webp"] = EncodeWebP(scales, 4, 4);
    Files["sh0.webp"] = EncodeWebP(sh0, 4, 4);
    Files["shN_labels.webp"] = EncodeWebP(labels, 4, 4);
    Files["shN_centroids.webp"] = EncodeWebP(centroids, 192, 1);
    Files["meta.json"] = Text(Meta());
  }

  static std::vector<unsigned char> Text(const std::string& s)
  {
    return std::vector<unsigned char>(s.begin(), s.end());
  }

  static std::string Codebook(double offset, double div)
  {
    std::string s = "[";
    for (int i = 0; i < 256; ++i)
    {
      s += (i ? "," : "") + std::to_string((i - offset) / div);
    }
    return s + "]";
  }

  static std::string Meta(const std::string& count = "2")
  {
    return "{\"version\": 2, \"count\": " + count +
      ", \"means\": {\"mins\": [-1, 0, 1], \"maxs\": [1, 2, 3], \"files\": "
      "[\"means_l.webp\", \"means_u.webp\"]}, \"scales\": {\"codebook\": " +
      Codebook(0, -10) +
      ", \"files\": [\"scales.webp\"]}, \"quats\": {\"files\": [\"quats.webp\"]}, \"sh0\": "
      "{\"codebook\": " +
      Codebook(128, 100) +
      ", \"files\": [\"sh0.webp\"]}, \"shN\": {\"count\": 2, \"bands\": 1, \"codebook\": " +
      Codebook(128, 64) + ", \"files\": [\"shN_centroids.webp\", \"shN_labels.webp\"]}}";
  }

  void WriteFolder(const std::string& dir) const
  {
    for (const auto& f : this->Files)
    {
      WriteFile(dir + "/" + f.first, f.second);
    }
  }

  void WriteZip(const std::string& path) const
  {
    int error = 0;
    zip_t* z = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
    ASSERT_NE(z, nullptr);
    for (const auto& f : this->Files)
    {
      zip_source_t* s = zip_source_buffer(z, f.second.data(), f.second.size(), 0);
      ASSERT_GE(zip_file_add(z, f.first.c_str(), s, ZIP_FL_OVERWRITE), 0);
    }
    ASSERT_EQ(zip_close(z), 0);
  }
};

float InvLog(double v)
{
  const double e = std::exp(std::abs(v)) - 1;
  return static_cast<float>(v < 0 ? -e : e);
}

void ExpectHandValues(const GaussianCloud& c)
{
  ASSERT_EQ(c.Count, 2u);
  ASSERT_EQ(c.ShDegree, 1);
  // Positions: the inverse of sign(x) ln(|x| + 1), from mins + (maxs - mins) * v / 65535.
  EXPECT_EQ(c.Positions[0], InvLog(1.0));
  EXPECT_EQ(c.Positions[1], 0.0f);
  EXPECT_EQ(c.Positions[2], InvLog(1.0 + 2.0 * (32768 / 65535.0)));
  EXPECT_EQ(c.Positions[3], InvLog(-1.0));
  // Quaternion: (128/255*2 - 1)/sqrt(2) for x y z, w restores the unit norm; tag 100 -> identity.
  const double a = (128 / 255.0 * 2 - 1) / std::sqrt(2.0);
  EXPECT_EQ(c.Rotations[1], static_cast<float>(a));
  EXPECT_EQ(c.Rotations[0], static_cast<float>(std::sqrt(1 - 3 * a * a)));
  EXPECT_EQ(c.Rotations[4], 1.0f);
  EXPECT_EQ(c.Rotations[5], 0.0f);
  // Codebooks: scale i -> -i/10, sh0 i -> (i-128)/100.
  EXPECT_EQ(c.LogScales[0], static_cast<float>(std::stod(std::to_string(-0.0 / 10))));
  EXPECT_EQ(c.LogScales[1], static_cast<float>(std::stod(std::to_string(5 / -10.0))));
  EXPECT_EQ(c.LogScales[2], static_cast<float>(std::stod(std::to_string(255 / -10.0))));
  EXPECT_EQ(c.SH[0], 0.0f);
  EXPECT_EQ(c.SH[1], static_cast<float>(std::stod(std::to_string(-128 / 100.0))));
  EXPECT_EQ(c.SH[2], static_cast<float>(std::stod(std::to_string(127 / 100.0))));
  // Opacity: log(a / (1 - a)) with a clamped to [1e-6, 1 - 1e-6].
  EXPECT_EQ(c.OpacityLogits[0], static_cast<float>(std::log(1e-6 / (1 - 1e-6))));
  EXPECT_EQ(c.OpacityLogits[1], static_cast<float>(std::log(0.2 / 0.8)));
  // f_rest of Gaussian 0 from centroid 1 (texels 3..5 of row 0): coefficient j, channel c is
  // byte 10 (3j + c + 1) through the codebook (i - 128)/64; Gaussian 1's label is past the
  // palette, so zeros.
  for (int j = 0; j < 3; ++j)
  {
    for (int ch = 0; ch < 3; ++ch)
    {
      EXPECT_EQ(c.SH[3 * (j + 1) + ch],
        static_cast<float>(std::stod(std::to_string((10 * (3 * j + ch + 1) - 128) / 64.0))))
        << j << " " << ch;
      EXPECT_EQ(c.SH[12 + 3 * (j + 1) + ch], 0.0f);
    }
  }
}

TEST(GaussianSog, HandAssembledSceneDecodesAsTheFormatDefines)
{
  TempDir dir;
  const Scene scene;
  const std::string folder = dir / "scene";
  ASSERT_EQ(::mkdir(folder.c_str(), 0755), 0);
  scene.WriteFolder(folder);
  scene.WriteZip(dir / "scene.sog");
  GaussianReadReport report;
  ExpectHandValues(ReadGaussianScene(folder, {}, &report));
  EXPECT_EQ(report.Format, "sog");
  EXPECT_EQ(report.FileShDegree, 1);
  ExpectHandValues(ReadGaussianScene(folder + "/meta.json"));
  ExpectHandValues(ReadGaussianScene(dir / "scene.sog"));
  const auto zip = FileBytes(dir / "scene.sog");
  ExpectHandValues(ReadSogZipFromMemory(zip.data(), zip.size(), "mem.sog"));
  // Only the degree asked for.
  GaussianReadOptions o;
  o.MaxShDegree = 0;
  const GaussianCloud c0 = ReadGaussianScene(dir / "scene.sog", o);
  EXPECT_EQ(c0.ShDegree, 0);
  EXPECT_EQ(c0.SH.size(), 6u);
}

TEST(GaussianSog, LyingMetaAndTexturesAreRefused)
{
  TempDir dir;
  auto readWith = [&](const Scene& s)
  {
    s.WriteZip(dir / "bad.sog");
    return ReadGaussianScene(dir / "bad.sog");
  };
  {
    Scene s;
    s.Files["meta.json"] = Scene::Text(Scene::Meta("17"));
    EXPECT_THROW_WITH(readWith(s), "bad.sog", "means_l.webp", "4x4, too small for the 17");
  }
  {
    Scene s;
    s.Files["meta.json"] = Scene::Text(Scene::Meta("-3"));
    EXPECT_THROW_WITH(readWith(s), "bad.sog", "'count' -3");
    s.Files["meta.json"] = Scene::Text(Scene::Meta("1e12"));
    EXPECT_THROW_WITH(readWith(s), "bad.sog", "'count'");
    s.Files["meta.json"] = Scene::Text("{\"count\": 2}");
    EXPECT_THROW_WITH(readWith(s), "bad.sog", "legacy SOG");
    s.Files["meta.json"] = Scene::Text("{\"version\": 2, \"count\": 2}");
    EXPECT_THROW_WITH(readWith(s), "bad.sog", "lacks 'means'");
    s.Files["meta.json"] = Scene::Text("not json");
    EXPECT_THROW_WITH(readWith(s), "bad.sog", "not a JSON object");
    std::string m = Scene::Meta();
    m.replace(m.find("\"quats.webp\""), 12, "\"../quats.webp\"");
    s.Files["meta.json"] = Scene::Text(m);
    EXPECT_THROW_WITH(readWith(s), "bad.sog", "'../quats.webp'");
    s.Files["meta.json"] = Scene::Text(Scene::Meta());
    s.Files.erase("quats.webp");
    EXPECT_THROW_WITH(readWith(s), "bad.sog", "no entry 'quats.webp'");
  }
  {
    Scene s;
    s.Files["sh0.webp"] = Scene::Text("RIFF not a webp");
    EXPECT_THROW_WITH(readWith(s), "bad.sog", "'sh0.webp' is not a WebP");
  }
  {
    // A texture far larger than meta.json's count.
    Scene s;
    std::vector<unsigned char> big(4 * 300 * 300, 7);
    s.Files["scales.webp"] = EncodeWebP(big, 300, 300);
    EXPECT_THROW_WITH(readWith(s), "bad.sog", "'scales.webp' is 300x300, far larger");
  }
  // A file that is not a zip archive.
  WriteFile(dir / "broken.sog", std::string("PK\x03\x04 and nothing else"));
  EXPECT_THROW_WITH(ReadGaussianScene(dir / "broken.sog"), "broken.sog", "zip");
}

TEST(GaussianSog, DecompressionBombsAreRefusedWithTheLimit)
{
  TempDir dir;
  // A zip entry whose central directory claims 2 GiB: refused before reading it.
  {
    Scene s;
    s.WriteZip(dir / "bomb.sog");
    auto bytes = FileBytes(dir / "bomb.sog");
    // Central directory headers (PK\1\2): uncompressed size at offset 24.
    std::size_t patched = 0;
    for (std::size_t i = 0; i + 46 < bytes.size(); ++i)
    {
      if (std::memcmp(&bytes[i], "PK\x01\x02", 4) == 0 &&
        std::memcmp(&bytes[i + 46], "meta.json", 9) == 0)
      {
        const std::uint32_t huge = 0x7fffffffu;
        std::memcpy(&bytes[i + 24], &huge, 4);
        ++patched;
      }
    }
    ASSERT_EQ(patched, 1u);
    EXPECT_THROW_WITH(
      ReadSogZipFromMemory(bytes.data(), bytes.size(), "bomb.sog"), "bomb.sog", "beyond the limit");
  }
  // A constant 4100x4100 texture (67 MB of RGBA from a few hundred bytes) for a count that
  // admits its size: refused before decoding, with the limit named.
  {
    Scene s;
    std::vector<unsigned char> flat(std::size_t(4) * 4100 * 4100, 0);
    s.Files["means_l.webp"] = EncodeWebP(flat, 4100, 4100);
    EXPECT_LT(s.Files["means_l.webp"].size(), 65536u);
    s.Files["meta.json"] = Scene::Text(Scene::Meta("8500000"));
    s.WriteZip(dir / "bomb2.sog");
    EXPECT_THROW_WITH(ReadGaussianScene(dir / "bomb2.sog"),
      "bomb2.sog",
      "'means_l.webp' expands",
      "1024 times its size past 64 MiB",
      "decompression bomb");
  }
}

} // namespace
} // namespace vis4gs

// SPDX-License-Identifier: BSD-3-Clause
// The PlayCanvas compressed PLY: a file assembled byte by byte here decodes to the values
// derived by hand from the format's definition; our writer's output reads back within the
// documented quantisation, recomputed here from the source; specials keep their meaning; bad
// input is refused before allocating. splat-transform's own files are compared in
// Testing/Reference (CompressedPlyReference.py).
#include "GaussianIO.h"
#include "GaussianMath.h"
#include "SceneTestUtils.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>

namespace vis4gs
{
namespace
{

using testing::TempDir;
using testing::WriteFile;

/// A compressed PLY assembled by hand: header text plus little-endian payload words/bytes.
struct Builder
{
  std::string Header;
  std::vector<unsigned char> Payload;
  void Float(float f)
  {
    unsigned char b[4];
    std::memcpy(b, &f, 4);
    Payload.insert(Payload.end(), b, b + 4);
  }
  void U32(std::uint32_t v)
  {
    for (int i = 0; i < 4; ++i)
    {
      Payload.push_back(static_cast<unsigned char>(v >> (8 * i)));
    }
  }
  std::vector<unsigned char> Bytes() const
  {
    std::vector<unsigned char> out(Header.begin(), Header.end());
    out.insert(out.end(), Payload.begin(), Payload.end());
    return out;
  }
};

std::string HeaderText(std::size_t chunks, std::size_t vertices, bool color, int shProps)
{
  std::string h =
    "ply\nformat binary_little_endian 1.0\nelement chunk " + std::to_string(chunks) + "\n";
  for (const char* p : { "min_x",
         "min_y",
         "min_z",
         "max_x",
         "max_y",
         "max_z",
         "min_scale_x",
         "min_scale_y",
         "min_scale_z",
         "max_scale_x",
         "max_scale_y",
         "max_scale_z" })
  {
    h += std::string("property float ") + p + "\n";
  }
  if (color)
  {
    for (const char* p : { "min_r", "min_g", "min_b", "max_r", "max_g", "max_b" })
    {
      h += std::string("property float ") + p + "\n";
    }
  }
  h += "element vertex " + std::to_string(vertices) +
    "\nproperty uint packed_position\nproperty uint packed_rotation\nproperty uint "
    "packed_scale\nproperty uint packed_color\n";
  if (shProps)
  {
    h += "element sh " + std::to_string(vertices) + "\n";
    for (int i = 0; i < shProps; ++i)
    {
      h += "property uchar f_rest_" + std::to_string(i) + "\n";
    }
  }
  return h + "end_header\n";
}

/// Two Gaussians in one chunk with colour bounds and SH degree 1, values chosen so that each
/// decodes to a number derived by hand below.
std::vector<unsigned char> HandFile()
{
  Builder b;
  b.Header = HeaderText(1, 2, true, 9);
  for (float f : { -1.0f,
         0.0f,
         2.0f,
         3.0f,
         1.0f,
         2.5f,
         -5.0f,
         -4.0f,
         -3.0f,
         -1.0f,
         0.0f,
         1.0f,
         0.0f,
         0.25f,
         0.5f,
         1.0f,
         0.75f,
         0.5f })
  {
    b.Float(f);
  }
  // Gaussian 0: position bits x=2047 (max), y=0 (min), z=1023; rotation: largest index 0 and
  // a=b=c=512; scale x=0, y=1023, z=2047; colour 255, 0, 51, alpha 204.
  b.U32(2047u << 21 | 0u << 11 | 1023u);
  b.U32(0u << 30 | 512u << 20 | 512u << 10 | 512u);
  b.U32(0u << 21 | 1023u << 11 | 2047u);
  b.U32(255u << 24 | 0u << 16 | 51u << 8 | 204u);
  // Gaussian 1: rotation largest index 3 with a=1023 (max), b=0 (min), c=511; alpha 0 and
  // everything else 0.
  b.U32(0);
  b.U32(3u << 30 | 1023u << 20 | 0u << 10 | 511u);
  b.U32(0);
  b.U32(0);
  // SH: channel-major f_rest_0..8; Gaussian 0 bytes 0..8 = {0, 255, 128, 1, 2, 3, 4, 5, 6}.
  for (unsigned char v : { 0, 255, 128, 1, 2, 3, 4, 5, 6 })
  {
    b.Payload.push_back(v);
  }
  for (int i = 0; i < 9; ++i)
  {
    b.Payload.push_back(static_cast<unsigned char>(100 + i));
  }
  return b.Bytes();
}

TEST(GaussianCompressedPly, HandAssembledFileDecodesAsTheFormatDefines)
{
  const auto bytes = HandFile();
  ASSERT_TRUE(IsCompressedPly(bytes.data(), bytes.size()));
  GaussianReadReport report;
  const GaussianCloud c =
    ReadCompressedPlyFromMemory(bytes.data(), bytes.size(), "hand", {}, &report);
  ASSERT_EQ(c.Count, 2u);
  EXPECT_EQ(report.Format, "compressed_ply");
  EXPECT_EQ(report.FileShDegree, 1);
  EXPECT_EQ(c.ShDegree, 1);
  // Position: t = bits / (2^bits - 1), lerp(min, max, t).
  EXPECT_EQ(c.Positions[0], 3.0f);
  EXPECT_EQ(c.Positions[1], 0.0f);
  EXPECT_EQ(c.Positions[2], static_cast<float>(2.0 * (1 - 1023.0 / 2047) + 2.5 * 1023.0 / 2047));
  EXPECT_EQ(c.LogScales[0], -5.0f);
  EXPECT_EQ(c.LogScales[1], static_cast<float>(-4.0 * (1 - 1023.0 / 1023) + 0.0));
  EXPECT_EQ(c.LogScales[2], 1.0f);
  // Rotation: (512/1023 - 0.5) * sqrt(2) for the three small ones, the largest restores unit norm.
  const double small = (512.0 / 1023 - 0.5) * std::sqrt(2.0);
  EXPECT_EQ(c.Rotations[1], static_cast<float>(small));
  EXPECT_EQ(c.Rotations[0], static_cast<float>(std::sqrt(1 - 3 * small * small)));
  const double a = 0.5 * std::sqrt(2.0), bb = -0.5 * std::sqrt(2.0);
  const double cc = (511.0 / 1023 - 0.5) * std::sqrt(2.0);
  EXPECT_EQ(c.Rotations[4], static_cast<float>(a));
  EXPECT_EQ(c.Rotations[5], static_cast<float>(bb));
  EXPECT_EQ(c.Rotations[6], static_cast<float>(cc));
  EXPECT_EQ(
    c.Rotations[7], static_cast<float>(std::sqrt(std::max(0.0, 1 - a * a - bb * bb - cc * cc))));
  // Colour: lerp of the chunk's colour bounds, then (c - 0.5) / C0.
  EXPECT_EQ(c.SH[0], static_cast<float>((1.0 - 0.5) / sh::C0));
  EXPECT_EQ(c.SH[1], static_cast<float>((0.25 - 0.5) / sh::C0));
  EXPECT_EQ(c.SH[2], static_cast<float>((0.5 * (1 - 0.2) + 0.5 * 0.2 - 0.5) / sh::C0));
  // Opacity: -log(1/w - 1) with w = 204/255 = 0.8 -> log(4); alpha 0 -> -inf.
  EXPECT_EQ(c.OpacityLogits[0], static_cast<float>(-std::log(255.0 / 204 - 1)));
  EXPECT_EQ(c.OpacityLogits[1], -std::numeric_limits<float>::infinity());
  // SH: f_rest_i is channel c = i / 3, coefficient 1 + i % 3; bytes 0 -> -4, 255 -> 4,
  // others ((b + 0.5)/256 - 0.5) * 8.
  auto shv = [](int b) { return static_cast<float>(((b + 0.5) / 256 - 0.5) * 8); };
  EXPECT_EQ(c.SH[3 * 1 + 0], -4.0f);
  EXPECT_EQ(c.SH[3 * 2 + 0], 4.0f);
  EXPECT_EQ(c.SH[3 * 3 + 0], shv(128));
  EXPECT_EQ(c.SH[3 * 1 + 1], shv(1));
  EXPECT_EQ(c.SH[3 * 3 + 2], shv(6));
  EXPECT_EQ(c.SH[12 + 3 * 2 + 1], shv(104));
  // alpha 0 is counted as a non-finite value (opacity logit -inf), kept as read.
  EXPECT_EQ(report.NonFiniteValues, 1u);

  // Degree 0 asked for: only the DC is decoded.
  GaussianReadOptions o;
  o.MaxShDegree = 0;
  const GaussianCloud c0 = ReadCompressedPlyFromMemory(bytes.data(), bytes.size(), "hand", o);
  EXPECT_EQ(c0.ShDegree, 0);
  ASSERT_EQ(c0.SH.size(), 6u);
  EXPECT_EQ(c0.SH[3], c.SH[12]);
}

TEST(GaussianCompressedPly, TwelveFloatChunksTakeColourAsIs)
{
  Builder b;
  b.Header = HeaderText(1, 1, false, 0);
  for (int i = 0; i < 12; ++i)
  {
    b.Float(0.0f);
  }
  b.U32(0);
  b.U32(0);
  b.U32(0);
  b.U32(51u << 24 | 255u << 16 | 0u << 8 | 255u);
  const auto bytes = b.Bytes();
  const GaussianCloud c = ReadCompressedPlyFromMemory(bytes.data(), bytes.size(), "twelve");
  EXPECT_EQ(c.SH[0], static_cast<float>((0.2 - 0.5) / sh::C0));
  EXPECT_EQ(c.SH[1], static_cast<float>(0.5 / sh::C0));
  EXPECT_EQ(c.SH[2], static_cast<float>(-0.5 / sh::C0));
  EXPECT_EQ(c.OpacityLogits[0], std::numeric_limits<float>::infinity());
}

GaussianCloud RandomCloud(std::size_t n, int degree, unsigned seed)
{
  std::mt19937 rng(seed);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  std::uniform_real_distribution<float> uni(-1.0f, 1.0f);
  GaussianCloud c;
  c.Resize(n, degree);
  for (std::size_t g = 0; g < n; ++g)
  {
    for (int k = 0; k < 3; ++k)
    {
      c.Positions[3 * g + k] = 5.0f * normal(rng);
      c.LogScales[3 * g + k] = -4.0f + normal(rng);
    }
    for (int k = 0; k < 4; ++k)
    {
      c.Rotations[4 * g + k] = normal(rng);
    }
    c.OpacityLogits[g] = 2.0f * normal(rng);
  }
  for (float& v : c.SH)
  {
    v = 1.5f * uni(rng);
  }
  return c;
}

TEST(GaussianCompressedPly, WriterRoundTripWithinTheReportedQuantisation)
{
  TempDir dir;
  const GaussianCloud src = RandomCloud(1000, 3, 7);
  const std::string path = dir / "scene.compressed.ply";
  const CompressedPlyWriteReport w = WriteCompressedPly(path, src);
  EXPECT_EQ(w.Written, 1000u);
  EXPECT_EQ(w.LeftOut, 0u);
  ASSERT_EQ(w.Order.size(), 1000u);
  GaussianReadReport rr;
  const GaussianCloud back = ReadGaussianScene(path, {}, &rr);
  EXPECT_EQ(rr.Format, "compressed_ply");
  ASSERT_EQ(back.Count, 1000u);
  ASSERT_EQ(back.ShDegree, 3);
  // Recompute max |back - source| per attribute and compare with the report; check it against
  // the format's step: position (range of the chunk)/2046 at most per axis (10 bits for y).
  double maxPos = 0, maxScale = 0, maxDc = 0, maxRest = 0, maxAlpha = 0, maxAngle = 0;
  for (std::size_t i = 0; i < back.Count; ++i)
  {
    const std::size_t g = w.Order[i];
    for (int k = 0; k < 3; ++k)
    {
      maxPos =
        std::max(maxPos, std::abs(double(back.Positions[3 * i + k]) - src.Positions[3 * g + k]));
      maxScale =
        std::max(maxScale, std::abs(double(back.LogScales[3 * i + k]) - src.LogScales[3 * g + k]));
      maxDc = std::max(maxDc, std::abs(double(back.SH[48 * i + k]) - src.SH[48 * g + k]));
    }
    for (int k = 3; k < 48; ++k)
    {
      maxRest = std::max(maxRest, std::abs(double(back.SH[48 * i + k]) - src.SH[48 * g + k]));
    }
    maxAlpha = std::max(maxAlpha,
      std::abs(Sigmoid(double(back.OpacityLogits[i])) - Sigmoid(double(src.OpacityLogits[g]))));
    const auto q = NormalizeQuaternion(&src.Rotations[4 * g]);
    double dot = 0;
    for (int k = 0; k < 4; ++k)
    {
      dot += q[k] * double(back.Rotations[4 * i + k]);
    }
    maxAngle = std::max(maxAngle, 2 * std::acos(std::min(1.0, std::abs(dot))) * 180 / M_PI);
  }
  ASSERT_EQ(w.Errors.size(), 6u);
  EXPECT_NEAR(w.Errors[0].Max, maxPos, 1e-6 * (1 + maxPos));
  EXPECT_NEAR(w.Errors[1].Max, maxScale, 1e-6);
  EXPECT_NEAR(w.Errors[2].Max, maxAngle, 1e-3);
  EXPECT_NEAR(w.Errors[3].Max, maxDc, 1e-6);
  EXPECT_NEAR(w.Errors[4].Max, maxAlpha, 1e-6);
  EXPECT_NEAR(w.Errors[5].Max, maxRest, 1e-6);
  // The format's steps: SH bytes are 8/256 wide, truncated and read back at the bucket's
  // centre (within [-1.5, 1.5], away from the end buckets: half a step), alpha 1/510,
  // smallest-three 10 bits over [-0.707, 0.707]: at most 2 sqrt(6)/1023 radians (0.274 deg).
  EXPECT_LE(maxRest, 4.0 / 256 + 1e-6);
  EXPECT_LE(maxAlpha, 0.5 / 255 + 1e-9);
  EXPECT_LT(maxAngle, 2 * std::sqrt(6.0) / 1023 * 180 / M_PI);
  EXPECT_GT(maxPos, 0.0);
  for (const auto& e : w.Errors)
  {
    EXPECT_LE(e.Rms, e.Max);
    EXPECT_GT(e.Values, 0u);
  }

  // Each written chunk's position error is at most half a step of its own bounds.
  for (std::size_t i = 0; i < back.Count; ++i)
  {
    const std::size_t chunk = i / 256;
    double lo[3] = { 1e30, 1e30, 1e30 }, hi[3] = { -1e30, -1e30, -1e30 };
    for (std::size_t j = chunk * 256; j < std::min(back.Count, chunk * 256 + 256); ++j)
    {
      for (int k = 0; k < 3; ++k)
      {
        lo[k] = std::min(lo[k], double(src.Positions[3 * w.Order[j] + k]));
        hi[k] = std::max(hi[k], double(src.Positions[3 * w.Order[j] + k]));
      }
    }
    const double steps[3] = { 2047, 1023, 2047 };
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_LE(std::abs(back.Positions[3 * i + k] - src.Positions[3 * w.Order[i] + k]),
        0.5 * (hi[k] - lo[k]) / steps[k] + 1e-5)
        << i << " " << k;
    }
  }
  EXPECT_FALSE(DescribeQuantisation(w).empty());
}

TEST(GaussianCompressedPly, MortonOrderGivesSmallerErrorsThanSourceOrder)
{
  // Uniform in a cube: a chunk of 256 neighbours spans a small part of it, 256 Gaussians in
  // source order span all of it.
  GaussianCloud src = RandomCloud(32768, 0, 11);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> uni(-10.0f, 10.0f);
  for (float& p : src.Positions)
  {
    p = uni(rng);
  }
  CompressedPlyWriteReport sorted, unsorted;
  WriteCompressedPlyToMemory(src, {}, &sorted);
  CompressedPlyWriteOptions o;
  o.MortonOrder = false;
  const auto bytes = WriteCompressedPlyToMemory(src, o, &unsorted);
  for (std::size_t i = 0; i < unsorted.Order.size(); ++i)
  {
    ASSERT_EQ(unsorted.Order[i], i);
  }
  EXPECT_LT(sorted.Errors[0].Rms, 0.5 * unsorted.Errors[0].Rms);
  std::vector<std::size_t> perm = sorted.Order;
  std::sort(perm.begin(), perm.end());
  for (std::size_t i = 0; i < perm.size(); ++i)
  {
    ASSERT_EQ(perm[i], i);
  }
  const GaussianCloud back = ReadCompressedPlyFromMemory(bytes.data(), bytes.size(), "mem");
  EXPECT_EQ(back.Count, src.Count);
  EXPECT_EQ(back.ShDegree, 0);
}

TEST(GaussianCompressedPly, SpecialValuesFollowTheSplatWriterRule)
{
  GaussianCloud src = RandomCloud(8, 1, 3);
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  src.OpacityLogits[0] = inf;
  src.OpacityLogits[1] = -inf;
  src.LogScales[3 * 2 + 1] = -inf;
  for (int k = 0; k < 4; ++k)
  {
    src.Rotations[4 * 3 + k] = 0.0f;
  }
  src.Positions[3 * 4] = nan;       // left out
  src.LogScales[3 * 5] = inf;       // left out
  src.SH[12 * 6 + 3 * 2 + 1] = nan; // f_rest NaN: left out
  src.SH[12 * 7 + 0] = inf;         // DC inf: left out
  CompressedPlyWriteOptions o;
  o.MortonOrder = false;
  CompressedPlyWriteReport w;
  const auto bytes = WriteCompressedPlyToMemory(src, o, &w);
  EXPECT_EQ(w.Written, 4u);
  EXPECT_EQ(w.LeftOut, 4u);
  EXPECT_EQ(w.ClampedLogScales, 1u);
  const GaussianCloud back = ReadCompressedPlyFromMemory(bytes.data(), bytes.size(), "specials");
  ASSERT_EQ(back.Count, 4u);
  EXPECT_EQ(back.OpacityLogits[0], inf);
  EXPECT_EQ(back.OpacityLogits[1], -inf);
  EXPECT_EQ(back.LogScales[3 * 2 + 1], -20.0f);
  // The zero quaternion comes back as (nearly) the identity the renderer draws it as.
  const auto q = NormalizeQuaternion(&back.Rotations[4 * 3]);
  EXPECT_GT(q[0], 0.9999f);
  for (std::size_t i = 0; i < back.Count; ++i)
  {
    EXPECT_EQ(ClassifyGaussian(&back.Positions[3 * i],
                &back.LogScales[3 * i],
                &back.Rotations[4 * i],
                back.OpacityLogits[i]),
      GaussianClass::Drawn);
  }
}

TEST(GaussianCompressedPly, LyingHeadersAreRefusedBeforeAllocating)
{
  TempDir dir;
  const auto good = HandFile();
  const std::string goodHeader = HeaderText(1, 2, true, 9);
  auto withHeader = [&](const std::string& h)
  {
    std::vector<unsigned char> out(h.begin(), h.end());
    out.insert(out.end(), good.begin() + goodHeader.size(), good.end());
    return out;
  };
  auto read = [&](const std::vector<unsigned char>& bytes)
  {
    const std::string path = dir / "bad.ply";
    WriteFile(path, bytes);
    return ReadGaussianScene(path);
  };
  // A vertex count that needs more chunks than declared.
  EXPECT_THROW_WITH(read(withHeader(HeaderText(1, 300, true, 0))), "bad.ply", "counts disagree");
  // Counts of 10^18: refused against the file size, not allocated.
  EXPECT_THROW_WITH(
    read(withHeader(HeaderText(3906250000000000ull, 1000000000000000000ull, true, 0))),
    "bad.ply",
    "lying header");
  // sh rows that differ from the vertices.
  {
    std::string h = HeaderText(1, 2, true, 9);
    h.replace(h.find("element sh 2"), 12, "element sh 1");
    EXPECT_THROW_WITH(read(withHeader(h)), "bad.ply", "sh element has 1 rows for 2");
  }
  // A truncated payload.
  {
    auto bytes = good;
    bytes.resize(bytes.size() - 5);
    EXPECT_THROW_WITH(read(bytes), "bad.ply", "truncated");
  }
  // Wrong SH property count and type.
  {
    std::string h = HeaderText(1, 2, true, 8);
    EXPECT_THROW_WITH(read(withHeader(h)), "bad.ply", "degree 1, 2, 3 need 9, 24, 45");
    h = HeaderText(1, 2, true, 9);
    h.replace(h.find("property uint packed_scale"), 26, "property float packed_scale");
    EXPECT_THROW_WITH(read(withHeader(h)), "bad.ply", "packed_scale");
    h = HeaderText(1, 2, true, 9);
    h.replace(h.find("property float max_b"), 20, "property float other");
    EXPECT_THROW_WITH(read(withHeader(h)), "bad.ply", "5 of the 6 colour bounds");
  }
  // ASCII.
  {
    std::string h = HeaderText(1, 2, true, 9);
    h.replace(h.find("binary_little_endian"), 20, "ascii");
    EXPECT_THROW_WITH(read(withHeader(h)), "bad.ply", "must be binary");
  }
  // An empty scene is fine.
  {
    const auto empty = WriteCompressedPlyToMemory(GaussianCloud{});
    EXPECT_EQ(ReadCompressedPlyFromMemory(empty.data(), empty.size(), "empty").Count, 0u);
  }
}

TEST(GaussianCompressedPly, BigEndianFilesAreRead)
{
  const auto le = HandFile();
  std::string h = HeaderText(1, 2, true, 9);
  std::vector<unsigned char> be(le);
  const std::string beHeader = "ply\nformat binary_big_endian 1.0\n" + h.substr(h.find("element"));
  be.assign(beHeader.begin(), beHeader.end());
  be.insert(be.end(), le.begin() + h.size(), le.end());
  // Swap the 4-byte words of the chunk and vertex elements (the sh bytes stay).
  for (std::size_t i = beHeader.size(); i < beHeader.size() + 18 * 4 + 2 * 16; i += 4)
  {
    std::swap(be[i], be[i + 3]);
    std::swap(be[i + 1], be[i + 2]);
  }
  const GaussianCloud a = ReadCompressedPlyFromMemory(le.data(), le.size(), "le");
  const GaussianCloud b = ReadCompressedPlyFromMemory(be.data(), be.size(), "be");
  EXPECT_EQ(a.Positions, b.Positions);
  EXPECT_EQ(a.Rotations, b.Rotations);
  EXPECT_EQ(a.SH, b.SH);
}

} // namespace
} // namespace vis4gs

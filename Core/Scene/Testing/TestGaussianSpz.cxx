// SPDX-License-Identifier: BSD-3-Clause
// SPZ (issue 19): files built byte by byte from the published layout (Niantic's load-spz.cc,
// Documentation/file-formats.md) with values derived by hand, the v4 writer's round trip
// within the documented quantisation, special values, and hostile input.
#include "GaussianIO.h"
#include "GaussianMath.h"
#include "SceneTestUtils.h"

#include <gtest/gtest.h>

#include <zlib.h>
#include <zstd.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>

namespace vis4gs
{
namespace
{

using testing::FileBytes;
using testing::TempDir;
using testing::WriteFile;

using Bytes = std::vector<unsigned char>;

void PutU32(Bytes& b, std::uint32_t v)
{
  for (int i = 0; i < 4; ++i)
  {
    b.push_back(static_cast<unsigned char>(v >> (8 * i)));
  }
}

void PutU64(Bytes& b, std::uint64_t v)
{
  PutU32(b, static_cast<std::uint32_t>(v));
  PutU32(b, static_cast<std::uint32_t>(v >> 32));
}

void PutFixed24(Bytes& b, std::int32_t v)
{
  for (int i = 0; i < 3; ++i)
  {
    b.push_back(static_cast<unsigned char>((v >> (8 * i)) & 0xff));
  }
}

Bytes Gzip(const Bytes& raw)
{
  z_stream zs{};
  EXPECT_EQ(deflateInit2(&zs, 9, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY), Z_OK);
  Bytes out(deflateBound(&zs, static_cast<uLong>(raw.size())) + 64);
  zs.next_in = const_cast<Bytef*>(raw.data());
  zs.avail_in = static_cast<uInt>(raw.size());
  zs.next_out = out.data();
  zs.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&zs, Z_FINISH), Z_STREAM_END);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  return out;
}

Bytes Zstd(const Bytes& raw)
{
  Bytes out(ZSTD_compressBound(raw.size()));
  const std::size_t n = ZSTD_compress(out.data(), out.size(), raw.data(), raw.size(), 3);
  EXPECT_FALSE(ZSTD_isError(n));
  out.resize(n);
  return out;
}

Bytes LegacyHeader(std::uint32_t version, std::uint32_t count, int shDegree, int fb, int flags)
{
  Bytes b;
  PutU32(b, 0x5053474e);
  PutU32(b, version);
  PutU32(b, count);
  b.push_back(static_cast<unsigned char>(shDegree));
  b.push_back(static_cast<unsigned char>(fb));
  b.push_back(static_cast<unsigned char>(flags));
  b.push_back(0);
  return b;
}

/// Attribute blocks of two Gaussians with hand-chosen bytes (SH degree 1).
struct TwoGaussians
{
  Bytes Positions, Alphas, Colors, Scales, Rotations, Sh;
  explicit TwoGaussians(bool smallestThree)
  {
    // fractional bits 12: 1.5 -> 6144, -2.25 -> -9216, 0.5 -> 2048; Gaussian 1: -1/4096, 0, 2047.
    for (std::int32_t v : { 6144, -9216, 2048, -1, 0, 8388607 })
    {
      PutFixed24(this->Positions, v);
    }
    this->Alphas = { 204, 0 };                    // 0.8 -> logit ln 4; 0 -> clamped 1e-6
    this->Colors = { 255, 0, 128, 51, 102, 153 }; // (b/255 - 0.5)/0.15
    this->Scales = { 144, 0, 255, 160, 176, 16 }; // b/16 - 10
    if (smallestThree)
    {
      // Gaussian 0: identity, largest = w (index 3), the other three zero.
      PutU32(this->Rotations, 3u << 30);
      // Gaussian 1: xyzw (0, -0.6, 0, 0.8): largest w; x: 0; y: sign bit + round(511 *
      // 0.6 / sqrt(1/2)) = 434; z: 0. Packed x first, so x ends in the high bits.
      std::uint32_t comp = 3;
      comp = (comp << 10) | 0;
      comp = (comp << 10) | (1u << 9) | 434u;
      comp = (comp << 10) | 0;
      PutU32(this->Rotations, comp);
    }
    else
    {
      // xyz bytes, b/127.5 - 1; w = sqrt(1 - |xyz|^2).
      this->Rotations = { 128, 128, 218, 64, 191, 127 };
    }
    // Degree 1: 3 coefficients x RGB per Gaussian, (b - 128)/128.
    this->Sh = {
      192, 192, 192, 192, 192, 192, 192, 192, 192, 0, 64, 128, 255, 1, 2, 100, 150, 200
    };
  }
  Bytes Payload() const
  {
    Bytes b;
    for (const Bytes* part : { &this->Positions,
           &this->Alphas,
           &this->Colors,
           &this->Scales,
           &this->Rotations,
           &this->Sh })
    {
      b.insert(b.end(), part->begin(), part->end());
    }
    return b;
  }
};

/// A v4 file: header, extension block, TOC, one zstd frame per non-empty stream.
Bytes NgspFile(std::uint32_t count,
  int shDegree,
  int fb,
  int flags,
  const Bytes& extensions,
  const std::vector<Bytes>& streams)
{
  Bytes b;
  PutU32(b, 0x5053474e);
  PutU32(b, 4);
  PutU32(b, count);
  b.push_back(static_cast<unsigned char>(shDegree));
  b.push_back(static_cast<unsigned char>(fb));
  b.push_back(static_cast<unsigned char>(flags));
  b.push_back(static_cast<unsigned char>(streams.size()));
  PutU32(b, static_cast<std::uint32_t>(32 + extensions.size()));
  b.resize(32, 0);
  b.insert(b.end(), extensions.begin(), extensions.end());
  std::vector<Bytes> frames;
  for (const Bytes& s : streams)
  {
    frames.push_back(Zstd(s));
    PutU64(b, frames.back().size());
    PutU64(b, s.size());
  }
  for (const Bytes& f : frames)
  {
    b.insert(b.end(), f.begin(), f.end());
  }
  return b;
}

double Logit(double a)
{
  return std::log(a / (1 - a));
}

/// The expected Gaussians of TwoGaussians, converted from RUB to RDF (y, z negated; the
/// quaternion's y, z negated; SH band-1 coefficients 0 (~y) and 1 (~z) negated).
void ExpectTwoGaussians(const GaussianCloud& c, bool smallestThree, bool rub)
{
  const float s = rub ? -1.f : 1.f;
  ASSERT_EQ(c.Count, 2u);
  ASSERT_EQ(c.ShDegree, 1);
  const float pos[6] = { 1.5f, s * -2.25f, s * 0.5f, -1 / 4096.f, s * 0.f, s * 8388607 / 4096.f };
  for (int i = 0; i < 6; ++i)
  {
    EXPECT_EQ(c.Positions[i], pos[i]) << i;
  }
  EXPECT_EQ(c.OpacityLogits[0], static_cast<float>(std::log(4.0)));
  EXPECT_EQ(c.OpacityLogits[1], static_cast<float>(Logit(1e-6)));
  const int colors[6] = { 255, 0, 128, 51, 102, 153 };
  const int scales[6] = { 144, 0, 255, 160, 176, 16 };
  const float expectedScales[6] = { -1.f, -10.f, 5.9375f, 0.f, 1.f, -9.f };
  for (int g = 0; g < 2; ++g)
  {
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_EQ(c.SH[12 * g + k], static_cast<float>((colors[3 * g + k] / 255.0 - 0.5) / 0.15));
      EXPECT_EQ(c.LogScales[3 * g + k], expectedScales[3 * g + k]);
      EXPECT_EQ(scales[3 * g + k] / 16.0 - 10.0, expectedScales[3 * g + k]);
    }
  }
  EXPECT_NEAR(c.SH[0], 10.0 / 3.0, 1e-6);
  // SH rest: Gaussian 0 all 0.5 stored; Gaussian 1 bytes 0 64 128 | 255 1 2 | 100 150 200.
  const float band1Sign[3] = { s, s, 1.f };
  const int g1[9] = { 0, 64, 128, 255, 1, 2, 100, 150, 200 };
  for (int j = 0; j < 3; ++j)
  {
    for (int ch = 0; ch < 3; ++ch)
    {
      EXPECT_EQ(c.SH[3 * (j + 1) + ch], band1Sign[j] * 0.5f);
      EXPECT_EQ(c.SH[12 + 3 * (j + 1) + ch], band1Sign[j] * (g1[3 * j + ch] - 128) / 128.f);
    }
  }
  if (smallestThree)
  {
    const float q0[4] = { 1, 0, 0, 0 };
    for (int k = 0; k < 4; ++k)
    {
      EXPECT_EQ(c.Rotations[k], q0[k]);
    }
    const double y = -std::sqrt(0.5) * 434 / 511;
    EXPECT_EQ(c.Rotations[4], static_cast<float>(std::sqrt(1 - y * y)));
    EXPECT_EQ(c.Rotations[5], 0.f);
    EXPECT_EQ(c.Rotations[6], s * static_cast<float>(y));
    EXPECT_EQ(c.Rotations[7], 0.f);
    EXPECT_NEAR(c.Rotations[6], s * -0.6, 1e-3);
  }
  else
  {
    const int b[6] = { 128, 128, 218, 64, 191, 127 };
    for (int g = 0; g < 2; ++g)
    {
      double x[3], n2 = 0;
      for (int k = 0; k < 3; ++k)
      {
        x[k] = b[3 * g + k] / 127.5 - 1;
        n2 += x[k] * x[k];
      }
      EXPECT_EQ(c.Rotations[4 * g], static_cast<float>(std::sqrt(1 - n2)));
      EXPECT_EQ(c.Rotations[4 * g + 1], static_cast<float>(x[0]));
      EXPECT_EQ(c.Rotations[4 * g + 2], s * static_cast<float>(x[1]));
      EXPECT_EQ(c.Rotations[4 * g + 3], s * static_cast<float>(x[2]));
    }
  }
}

template <typename F>
std::string ErrorOf(F f)
{
  try
  {
    f();
  }
  catch (const std::runtime_error& e)
  {
    return e.what();
  }
  return "(no error)";
}

//------------------------------------------------------------------------------
TEST(GaussianSpz, ReadsHandBuiltVersion2And3)
{
  for (std::uint32_t version : { 2u, 3u })
  {
    SCOPED_TRACE(version);
    const TwoGaussians t(version >= 3);
    Bytes raw = LegacyHeader(version, 2, 1, 12, 0);
    const Bytes payload = t.Payload();
    raw.insert(raw.end(), payload.begin(), payload.end());
    const Bytes file = Gzip(raw);
    GaussianReadReport report;
    const GaussianCloud c = ReadSpzFromMemory(file.data(), file.size(), "two.spz", {}, &report);
    EXPECT_EQ(report.Format, "spz v" + std::to_string(version));
    EXPECT_EQ(report.FileShDegree, 1);
    EXPECT_TRUE(report.Warnings.empty());
    ExpectTwoGaussians(c, version >= 3, true);
    // Extension records after the data (flag bit 1): Adobe's coordinate system saying RDF.
    raw[14] = 0x2;
    for (std::uint32_t v : { 0xADBE0003u, 4u, 6u })
    {
      PutU32(raw, v);
    }
    const Bytes withExtension = Gzip(raw);
    ExpectTwoGaussians(ReadSpzFromMemory(withExtension.data(), withExtension.size(), "rdf.spz"),
      version >= 3,
      false);
    // The same bytes without the gzip stream ("raw" SPZ, issue 34): read alike, said so.
    GaussianReadReport rawReport;
    ExpectTwoGaussians(
      ReadSpzFromMemory(raw.data(), raw.size(), "raw.spz", {}, &rawReport), version >= 3, false);
    EXPECT_EQ(rawReport.Format, "spz v" + std::to_string(version) + " raw");
    const Bytes cut(raw.begin(), raw.end() - 20);
    try
    {
      ReadSpzFromMemory(cut.data(), cut.size(), "cut.spz");
      ADD_FAILURE() << "a truncated raw SPZ was read";
    }
    catch (const std::runtime_error& e)
    {
      EXPECT_NE(
        std::string(e.what()).find("cut.spz: the raw SPZ data ends early"), std::string::npos)
        << e.what();
    }
  }
}

TEST(GaussianSpz, ReadsHandBuiltVersion4WithExtensions)
{
  const TwoGaussians t(true);
  const std::vector<Bytes> streams = {
    t.Positions, t.Alphas, t.Colors, t.Scales, t.Rotations, t.Sh
  };
  {
    const Bytes file = NgspFile(2, 1, 12, 0, {}, streams);
    GaussianReadReport report;
    ExpectTwoGaussians(
      ReadSpzFromMemory(file.data(), file.size(), "v4.spz", {}, &report), true, true);
    EXPECT_EQ(report.Format, "spz v4");
  }
  // An unknown vendor record is skipped with a warning; Adobe's coordinate-system record
  // saying RDF (6) means no conversion at all.
  Bytes ext;
  PutU32(ext, 0x12340001);
  PutU32(ext, 5);
  ext.insert(ext.end(), { 1, 2, 3, 4, 5 });
  PutU32(ext, 0xADBE0003);
  PutU32(ext, 4);
  PutU32(ext, 6);
  const Bytes file = NgspFile(2, 1, 12, 0x1 | 0x2, ext, streams);
  GaussianReadReport report;
  ExpectTwoGaussians(
    ReadSpzFromMemory(file.data(), file.size(), "ext.spz", {}, &report), true, false);
  EXPECT_EQ(report.Format, "spz v4 antialiased");
  ASSERT_EQ(report.Warnings.size(), 2u);
  EXPECT_NE(report.Warnings[0].find("0x12340001"), std::string::npos) << report.Warnings[0];
  // A rotated axis family (RFU, 12) is refused rather than read wrongly.
  Bytes rotated;
  PutU32(rotated, 0xADBE0003);
  PutU32(rotated, 4);
  PutU32(rotated, 12);
  const Bytes bad = NgspFile(2, 1, 12, 0x2, rotated, streams);
  EXPECT_NE(ErrorOf([&] { ReadSpzFromMemory(bad.data(), bad.size(), "rot.spz"); })
              .find("rot.spz: the SPZ data is stored in coordinate system 12"),
    std::string::npos);
}

TEST(GaussianSpz, OnlyTheAskedDegreeIsDecodedAndDegree4Reads)
{
  // Degree 4: 24 coefficients x RGB; byte = 10 + coefficient index (same for R, G, B).
  Bytes pos, alpha{ 255 }, color{ 1, 2, 3 }, scale{ 160, 160, 160 }, rot, sh;
  PutFixed24(pos, 4096);
  PutFixed24(pos, 0);
  PutFixed24(pos, 0);
  PutU32(rot, 3u << 30);
  for (int j = 0; j < 24; ++j)
  {
    sh.insert(sh.end(), 3, static_cast<unsigned char>(10 + j));
  }
  const Bytes file = NgspFile(1, 4, 12, 0, {}, { pos, alpha, color, scale, rot, sh });
  GaussianReadReport report;
  GaussianCloud c = ReadSpzFromMemory(file.data(), file.size(), "d4.spz", {}, &report);
  EXPECT_EQ(report.FileShDegree, 4);
  ASSERT_EQ(c.ShDegree, 3);
  ASSERT_EQ(c.SH.size(), 48u);
  // RUB -> RDF signs of the 15 coefficients (3DGS order, parity in y xor z).
  const float sign[15] = { -1, -1, 1, -1, 1, 1, -1, 1, -1, 1, -1, -1, 1, -1, 1 };
  for (int j = 0; j < 15; ++j)
  {
    EXPECT_EQ(c.SH[3 * (j + 1) + 1], sign[j] * (10 + j - 128) / 128.f) << j;
  }
  EXPECT_EQ(c.OpacityLogits[0], static_cast<float>(Logit(1 - 1e-6)));
  GaussianReadOptions o;
  o.MaxShDegree = 1;
  o.LoadPositions = false;
  c = ReadSpzFromMemory(file.data(), file.size(), "d4.spz", o);
  EXPECT_EQ(c.ShDegree, 1);
  EXPECT_EQ(c.SH.size(), 12u);
  EXPECT_TRUE(c.Positions.empty());
  EXPECT_EQ(c.Rotations.size(), 4u);
}

GaussianCloud RandomCloud(std::size_t n, int degree, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> pos(-30, 30), scale(-9, 5), sh(-0.9f, 0.9f), dc(-3, 3),
    logit(-8, 8), q(-1, 1);
  GaussianCloud c;
  c.Resize(n, degree);
  for (std::size_t g = 0; g < n; ++g)
  {
    for (int k = 0; k < 3; ++k)
    {
      c.Positions[3 * g + k] = pos(rng);
      c.LogScales[3 * g + k] = scale(rng);
      c.SH[3 * static_cast<std::size_t>(c.ShCoefficientCount()) * g + k] = dc(rng);
    }
    for (int k = 0; k < 4; ++k)
    {
      c.Rotations[4 * g + k] = q(rng);
    }
    c.OpacityLogits[g] = logit(rng);
    for (int j = 3; j < 3 * c.ShCoefficientCount(); ++j)
    {
      c.SH[3 * static_cast<std::size_t>(c.ShCoefficientCount()) * g + j] = sh(rng);
    }
  }
  return c;
}

TEST(GaussianSpz, WriterRoundTripIsWithinTheDocumentedQuantisation)
{
  const GaussianCloud src = RandomCloud(3000, 3, 7);
  TempDir dir;
  const SpzWriteReport report = WriteSpz(dir / "r.spz", src);
  EXPECT_EQ(report.Written, 3000u);
  EXPECT_EQ(report.LeftOut, 0u);
  // |x| < 30 < 2^5: 23 - 5 = 18 fractional bits.
  EXPECT_EQ(report.FractionalBits, 18);
  const auto bytes = FileBytes(dir / "r.spz");
  EXPECT_EQ(bytes.size(), report.FileBytes);
  ASSERT_GE(bytes.size(), 4u);
  EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + 4), "NGSP");
  GaussianReadReport rr;
  const GaussianCloud back = ReadGaussianScene(dir / "r.spz", {}, &rr);
  EXPECT_EQ(rr.Format, "spz v4");
  ASSERT_EQ(back.Count, src.Count);
  ASSERT_EQ(back.ShDegree, 3);
  // Bounds: half a step of each quantiser (SH: rounding to 1/128 plus half a bucket of 8 or
  // 16 steps; rotation: the three stored components within h = sqrt(1/2)/511/2, the rebuilt
  // largest w >= 1/2 within sqrt(1-w^2) sqrt(3) h / w <= 2.07e-3); measured errors must match
  // the report.
  double maxPos = 0, maxScale = 0, maxOpa = 0, maxDc = 0, maxSh = 0, maxRot = 0;
  for (std::size_t g = 0; g < src.Count; ++g)
  {
    for (int k = 0; k < 3; ++k)
    {
      maxPos =
        std::max(maxPos, std::fabs(double(back.Positions[3 * g + k]) - src.Positions[3 * g + k]));
      maxScale =
        std::max(maxScale, std::fabs(double(back.LogScales[3 * g + k]) - src.LogScales[3 * g + k]));
      maxDc = std::max(maxDc, std::fabs(double(back.SH[48 * g + k]) - src.SH[48 * g + k]));
    }
    for (int j = 3; j < 48; ++j)
    {
      const double e = std::fabs(double(back.SH[48 * g + j]) - src.SH[48 * g + j]);
      EXPECT_LE(e, (j < 12 ? 4.5 : 8.5) / 128 + 1e-7) << g << " " << j;
      maxSh = std::max(maxSh, e);
    }
    maxOpa = std::max(maxOpa,
      std::fabs(Sigmoid(double(back.OpacityLogits[g])) - Sigmoid(double(src.OpacityLogits[g]))));
    const auto q = NormalizeQuaternion(&src.Rotations[4 * g]);
    double dot = 0;
    for (int k = 0; k < 4; ++k)
    {
      dot += q[k] * back.Rotations[4 * g + k];
    }
    for (int k = 0; k < 4; ++k)
    {
      maxRot =
        std::max(maxRot, std::fabs((dot < 0 ? -1.0 : 1.0) * back.Rotations[4 * g + k] - q[k]));
    }
  }
  EXPECT_LE(maxPos, std::ldexp(0.5, -18) + 2e-6); // plus float rounding of |x| < 32
  EXPECT_LE(maxScale, 1.0 / 32 + 1e-6);
  EXPECT_LE(maxOpa, 0.5 / 255 + 1e-6);
  EXPECT_LE(maxDc, 0.5 / (255 * 0.15) + 1e-6);
  EXPECT_LE(maxRot, 2.1e-3);
  EXPECT_NEAR(report.Position.Max, maxPos, 1e-9);
  EXPECT_NEAR(report.LogScale.Max, maxScale, 1e-9);
  EXPECT_NEAR(report.Opacity.Max, maxOpa, 1e-9);
  EXPECT_NEAR(report.Color.Max, maxDc, 1e-9);
  EXPECT_NEAR(report.SH.Max, maxSh, 1e-9);
  EXPECT_NEAR(report.Rotation.Max, maxRot, 1e-6);
  EXPECT_GT(report.SH.Rms, 0.0);
  EXPECT_LT(report.SH.Rms, report.SH.Max);
  // Re-writing what was read is stable: every value reads back the same, except rotations
  // whose two largest components are nearly equal (the decoded largest may no longer be the
  // largest, so another one is dropped): those stay within one step.
  const SpzWriteReport again = WriteSpz(dir / "r2.spz", back);
  const GaussianCloud back2 = ReadSpz(dir / "r2.spz");
  EXPECT_EQ(back2.Positions, back.Positions);
  EXPECT_EQ(back2.LogScales, back.LogScales);
  EXPECT_EQ(back2.OpacityLogits, back.OpacityLogits);
  EXPECT_EQ(back2.SH, back.SH);
  for (std::size_t g = 0; g < back.Count; ++g)
  {
    double dot = 0;
    for (int k = 0; k < 4; ++k)
    {
      dot += back2.Rotations[4 * g + k] * back.Rotations[4 * g + k];
    }
    for (int k = 0; k < 4; ++k) // q and -q are the same rotation
    {
      EXPECT_NEAR(
        (dot < 0 ? -1 : 1) * back2.Rotations[4 * g + k], back.Rotations[4 * g + k], 2.1e-3);
    }
  }
  EXPECT_EQ(again.FractionalBits, 18);
}

TEST(GaussianSpz, WriterKeepsDrawableSpecialsAndLeavesOutTheRest)
{
  const float inf = std::numeric_limits<float>::infinity();
  GaussianCloud c;
  c.Resize(8, 1);
  for (std::size_t g = 0; g < 8; ++g)
  {
    c.Positions[3 * g] = static_cast<float>(g);
    c.Rotations[4 * g] = 1;
  }
  c.Positions[3 * 1 + 1] = std::numeric_limits<float>::quiet_NaN(); // left out
  c.OpacityLogits[2] = inf;                                         // alpha byte 255
  c.OpacityLogits[3] = -inf;                                        // alpha byte 0
  c.Rotations[4 * 4] = 0;                                           // zero quaternion
  c.LogScales[3 * 5 + 2] = -inf;                                    // smallest scale
  c.SH[12 * 6 + 5] = inf;                                           // SH rest: left out
  c.Positions[3 * 7] = 1e7f;                                        // beyond 2^23
  TempDir dir;
  const SpzWriteReport r = WriteSpz(dir / "s.spz", c);
  EXPECT_EQ(r.Written, 5u);
  EXPECT_EQ(r.LeftOut, 3u);
  EXPECT_EQ(r.OutOfRange, 1u);
  EXPECT_EQ(r.SpecialValues, 4u);
  const GaussianCloud back = ReadSpz(dir / "s.spz");
  ASSERT_EQ(back.Count, 5u); // Gaussians 0, 2, 3, 4, 5
  EXPECT_EQ(back.Positions[3], 2.0f);
  EXPECT_GT(Sigmoid(double(back.OpacityLogits[1])), 1 - 2e-6);
  EXPECT_LT(Sigmoid(double(back.OpacityLogits[2])), 2e-6);
  const float identity[4] = { 1, 0, 0, 0 };
  for (int k = 0; k < 4; ++k)
  {
    EXPECT_EQ(back.Rotations[4 * 3 + k], identity[k]) << k;
  }
  EXPECT_EQ(back.LogScales[3 * 4 + 2], -10.0f);
  for (std::size_t g = 0; g < back.Count; ++g)
  {
    EXPECT_EQ(ClassifyGaussian(&back.Positions[3 * g],
                &back.LogScales[3 * g],
                &back.Rotations[4 * g],
                back.OpacityLogits[g]),
      GaussianClass::Drawn);
  }
  // Nothing drawable at all: refused, and nothing is created.
  GaussianCloud none;
  none.Resize(1, 0);
  none.Positions[0] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(WriteSpz(dir / "none.spz", none), std::runtime_error);
  EXPECT_TRUE(FileBytes(dir / "none.spz").empty());
}

TEST(GaussianSpz, DispatchIsByContent)
{
  const GaussianCloud src = RandomCloud(10, 0, 3);
  TempDir dir;
  const Bytes b = WriteSpzToMemory(src);
  WriteFile(dir / "named-like-a.ply", b);
  GaussianReadReport report;
  EXPECT_EQ(ReadGaussianScene(dir / "named-like-a.ply", {}, &report).Count, 10u);
  EXPECT_EQ(report.Format, "spz v4");
  EXPECT_TRUE(IsSpzFile(dir / "named-like-a.ply"));
  EXPECT_FALSE(IsSpzFile(dir / "missing.spz"));
}

//------------------------------------------------------------------------------
TEST(GaussianSpzErrors, LyingCountsAndBombsAreRefusedBeforeAllocating)
{
  // A 40-byte gzip file that claims 2e9 Gaussians (tens of gigabytes).
  const Bytes bomb = Gzip(LegacyHeader(3, 2000000000u, 3, 12, 0));
  std::string e = ErrorOf([&] { ReadSpzFromMemory(bomb.data(), bomb.size(), "bomb.spz"); });
  EXPECT_NE(e.find("bomb.spz: the SPZ header claims 2000000000 Gaussians"), std::string::npos) << e;
  EXPECT_NE(e.find("more than 1032 times"), std::string::npos) << e;
  // The same in a v4 header.
  Bytes v4 =
    NgspFile(100000000u, 0, 12, 0, {}, { Bytes(9), Bytes(1), Bytes(3), Bytes(3), Bytes(4) });
  e = ErrorOf([&] { ReadSpzFromMemory(v4.data(), v4.size(), "bomb4.spz"); });
  EXPECT_NE(e.find("decompression bomb"), std::string::npos) << e;
  // A count the data does not hold: 1000 Gaussians announced, 2 stored.
  const TwoGaussians t(true);
  Bytes raw = LegacyHeader(3, 1000, 1, 12, 0);
  const Bytes payload = t.Payload();
  raw.insert(raw.end(), payload.begin(), payload.end());
  Bytes file = Gzip(raw);
  e = ErrorOf([&] { ReadSpzFromMemory(file.data(), file.size(), "short.spz"); });
  EXPECT_NE(e.find("short.spz: the SPZ data ends early"), std::string::npos) << e;
  // A zstd frame larger than its TOC entry says.
  Bytes big(9 * 2, 7);
  v4 = NgspFile(1, 0, 12, 0, {}, { big, Bytes(1), Bytes(3), Bytes(3), Bytes(4) });
  e = ErrorOf([&] { ReadSpzFromMemory(v4.data(), v4.size(), "frame.spz"); });
  EXPECT_NE(
    e.find("frame.spz: SPZ stream 0 claims 18 bytes, 1 Gaussians need 9"), std::string::npos)
    << e;
  // TOC entry says 9 but the frame holds 18: caught by the decompressor.
  const std::vector<Bytes> ok = { Bytes(9), Bytes(1), Bytes(3), Bytes(3), Bytes(4) };
  v4 = NgspFile(1, 0, 12, 0, {}, ok);
  const Bytes bigFrame = Zstd(big);
  const std::size_t first = 32 + 5 * 16;
  const std::size_t oldSize = v4[32];
  Bytes patched(v4.begin(), v4.begin() + first);
  patched[32] = static_cast<unsigned char>(bigFrame.size());
  patched.insert(patched.end(), bigFrame.begin(), bigFrame.end());
  patched.insert(patched.end(), v4.begin() + first + oldSize, v4.end());
  e = ErrorOf([&] { ReadSpzFromMemory(patched.data(), patched.size(), "lie.spz"); });
  EXPECT_NE(e.find("lie.spz: SPZ stream 0 does not decompress to 9 bytes"), std::string::npos) << e;
  // Stream sizes past the end of the file, and truncation anywhere.
  const Bytes good =
    NgspFile(2, 1, 12, 0, {}, { t.Positions, t.Alphas, t.Colors, t.Scales, t.Rotations, t.Sh });
  for (std::size_t cut = 0; cut < good.size(); ++cut)
  {
    EXPECT_THROW(ReadSpzFromMemory(good.data(), cut, "cut.spz"), std::runtime_error) << cut;
  }
  const Bytes gz = Gzip(raw);
  for (std::size_t cut = 0; cut < gz.size(); cut += 3)
  {
    EXPECT_THROW(ReadSpzFromMemory(gz.data(), cut, "cut.spz"), std::runtime_error) << cut;
  }
}

TEST(GaussianSpzErrors, HeadersAndFilesNamedInErrors)
{
  const Bytes v1 = Gzip(LegacyHeader(1, 1, 0, 12, 0));
  EXPECT_NE(ErrorOf([&] { ReadSpzFromMemory(v1.data(), v1.size(), "v1.spz"); })
              .find("v1.spz: SPZ version 1 is not supported"),
    std::string::npos);
  const Bytes deg = Gzip(LegacyHeader(2, 1, 5, 12, 0));
  EXPECT_NE(
    ErrorOf([&] { ReadSpzFromMemory(deg.data(), deg.size(), "d.spz"); }).find("d.spz: SH degree 5"),
    std::string::npos);
  Bytes notSpz = Gzip(Bytes(64, 'x'));
  EXPECT_NE(ErrorOf([&] { ReadSpzFromMemory(notSpz.data(), notSpz.size(), "x.gz"); })
              .find("x.gz: not an SPZ file"),
    std::string::npos);
  notSpz = Bytes{ 0x1f, 0x8b, 0x08, 0, 0, 0 };
  EXPECT_THROW(ReadSpzFromMemory(notSpz.data(), notSpz.size(), "g.spz"), std::runtime_error);
  EXPECT_THROW(ReadSpzFromMemory(nullptr, 0, "empty.spz"), std::runtime_error);
  EXPECT_NE(
    ErrorOf([] { ReadSpz("/nonexistent/a.spz"); }).find("/nonexistent/a.spz"), std::string::npos);
  GaussianReadOptions o;
  o.IdProperty = "id";
  const Bytes b = WriteSpzToMemory(RandomCloud(2, 0, 1));
  EXPECT_THROW(ReadSpzFromMemory(b.data(), b.size(), "a.spz", o), std::runtime_error);
}

} // namespace
} // namespace vis4gs

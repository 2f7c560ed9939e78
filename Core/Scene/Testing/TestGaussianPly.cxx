// SPDX-License-Identifier: BSD-3-Clause
// PLY and .splat reading/writing: real files checked against an independent naive decoder,
// bit-exact round trips, and every bad-input case of issue 3.
#include "GaussianIO.h"
#include "GaussianMath.h"
#include "SceneTestUtils.h"
#include "Vis4GSTestData.h"

#include <gtest/gtest.h>

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

const std::string InriaPly =
  testing::SharedDataPath("inria_ply_tiny_kacytran/point_cloud/iteration_7000/point_cloud.ply");
const std::string DonutPly = testing::SharedDataPath("gs_ply_sh0_variant_donut_v3dg/fused.ply");
const std::string SplatFile = testing::SharedDataPath("inria_ply_tiny_kacytran/model_1.splat");

std::uint32_t Bits(float f)
{
  std::uint32_t b;
  std::memcpy(&b, &f, 4);
  return b;
}

float FromBits(std::uint32_t b)
{
  float f;
  std::memcpy(&f, &b, 4);
  return f;
}

// Naive decoder for a little-endian all-float PLY: the rows after "end_header\n".
std::vector<float> NaiveRows(const std::vector<unsigned char>& bytes, std::size_t floatsPerRow)
{
  const std::string text(bytes.begin(), bytes.end());
  const std::size_t start = text.find("end_header\n") + 11;
  std::vector<float> v((bytes.size() - start) / 4);
  std::memcpy(v.data(), bytes.data() + start, v.size() * 4);
  EXPECT_EQ(v.size() % floatsPerRow, 0u);
  return v;
}

void ExpectBitEqual(const std::vector<float>& a, const std::vector<float>& b, const char* what)
{
  ASSERT_EQ(a.size(), b.size()) << what;
  std::size_t diff = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    diff += Bits(a[i]) != Bits(b[i]);
  }
  EXPECT_EQ(diff, 0u) << what;
}

void ExpectCloudsBitEqual(const GaussianCloud& a, const GaussianCloud& b)
{
  EXPECT_EQ(a.Count, b.Count);
  EXPECT_EQ(a.ShDegree, b.ShDegree);
  ExpectBitEqual(a.Positions, b.Positions, "Positions");
  ExpectBitEqual(a.LogScales, b.LogScales, "LogScales");
  ExpectBitEqual(a.Rotations, b.Rotations, "Rotations");
  ExpectBitEqual(a.OpacityLogits, b.OpacityLogits, "OpacityLogits");
  ExpectBitEqual(a.SH, b.SH, "SH");
  EXPECT_EQ(a.Ids, b.Ids);
  ASSERT_EQ(a.Extra.size(), b.Extra.size());
  for (std::size_t i = 0; i < a.Extra.size(); ++i)
  {
    EXPECT_EQ(a.Extra[i].Name, b.Extra[i].Name);
    EXPECT_EQ(a.Extra[i].Type, b.Extra[i].Type);
    EXPECT_EQ(a.Extra[i].Bytes, b.Extra[i].Bytes) << a.Extra[i].Name;
  }
}

// A synthetic SH3 cloud with extreme values, NaN payloads and extras of every type.
GaussianCloud Synthetic(std::size_t n, int degree)
{
  GaussianCloud c;
  c.Resize(n, degree);
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> u(-5.0f, 5.0f);
  for (auto* v : { &c.Positions, &c.LogScales, &c.Rotations, &c.OpacityLogits, &c.SH })
  {
    for (float& x : *v)
    {
      x = u(rng);
    }
  }
  const float specials[] = { std::numeric_limits<float>::infinity(),
    -std::numeric_limits<float>::infinity(),
    FromBits(0x7fc00000u),
    FromBits(0xffc00000u),
    FromBits(0x7fa12345u) /* signalling NaN with payload */,
    FromBits(0x7fc00001u),
    FromBits(0x00000001u) /* smallest denormal */,
    -0.0f,
    std::numeric_limits<float>::max(),
    std::numeric_limits<float>::lowest(),
    1000.0f,
    -1000.0f };
  for (std::size_t i = 0; i < sizeof(specials) / sizeof(specials[0]) && i < n; ++i)
  {
    c.Positions[3 * i] = specials[i];
    c.SH[c.SH.size() - 1 - i] = specials[i];
  }
  if (n > 1)
  {
    for (int k = 0; k < 4; ++k)
    {
      c.Rotations[4 + k] = 0.0f; // zero quaternion
    }
  }
  const ScalarType types[] = { ScalarType::Int8,
    ScalarType::UInt8,
    ScalarType::Int16,
    ScalarType::UInt16,
    ScalarType::Int32,
    ScalarType::UInt32,
    ScalarType::Float32,
    ScalarType::Float64 };
  int t = 0;
  for (ScalarType type : types)
  {
    ExtraProperty e;
    e.Name = "extra_" + std::to_string(t++);
    e.Type = type;
    e.Bytes.resize(n * ScalarTypeSize(type));
    for (auto& b : e.Bytes)
    {
      b = static_cast<unsigned char>(rng());
    }
    if (type == ScalarType::Float64 && n > 0)
    {
      const double nan = std::numeric_limits<double>::quiet_NaN();
      std::memcpy(e.Bytes.data(), &nan, 8); // ASCII keeps quiet double NaNs only
      for (std::size_t i = 1; i < n; ++i)
      {
        const double v = std::ldexp(static_cast<double>(rng()), -20);
        std::memcpy(e.Bytes.data() + 8 * i, &v, 8);
      }
    }
    if (type == ScalarType::Float32)
    {
      for (std::size_t i = 0; i < n; ++i)
      {
        const float v = u(rng);
        std::memcpy(e.Bytes.data() + 4 * i, &v, 4);
      }
    }
    c.Extra.push_back(e);
  }
  return c;
}

//------------------------------------------------------------------------------
TEST(GaussianPly, ReadsInriaFileExactly)
{
  VIS4GS_REQUIRE_SHARED_DATA();
  GaussianReadReport report;
  const GaussianCloud c = ReadGaussianPly(InriaPly, {}, &report);
  ASSERT_EQ(c.Count, 9080u);
  EXPECT_EQ(c.ShDegree, 3);
  EXPECT_EQ(report.FileShDegree, 3);
  EXPECT_EQ(report.Format, "binary_little_endian");
  EXPECT_EQ(report.NonFiniteValues, 0u);
  EXPECT_TRUE(report.Warnings.empty());
  // Independent decode: 62 floats per row in the trainer's order.
  const auto rows = NaiveRows(FileBytes(InriaPly), 62);
  ASSERT_EQ(rows.size(), 9080u * 62);
  std::size_t mismatches = 0;
  for (std::size_t g = 0; g < 9080; ++g)
  {
    const float* r = &rows[62 * g];
    for (int k = 0; k < 3; ++k)
    {
      mismatches += Bits(c.Positions[3 * g + k]) != Bits(r[k]);
      mismatches += Bits(c.LogScales[3 * g + k]) != Bits(r[55 + k]);
      mismatches += Bits(c.SH[48 * g + k]) != Bits(r[6 + k]); // DC
    }
    for (int k = 0; k < 4; ++k)
    {
      mismatches += Bits(c.Rotations[4 * g + k]) != Bits(r[58 + k]);
    }
    mismatches += Bits(c.OpacityLogits[g]) != Bits(r[54]);
    // f_rest_j = channel c, coefficient k: j = c*15 + (k-1); ours: SH[48g + 3k + c].
    for (int ch = 0; ch < 3; ++ch)
    {
      for (int k = 1; k < 16; ++k)
      {
        mismatches += Bits(c.SH[48 * g + 3 * k + ch]) != Bits(r[9 + ch * 15 + (k - 1)]);
      }
    }
  }
  EXPECT_EQ(mismatches, 0u);
  // Normals are kept as float extras (all zero in a trainer file).
  ASSERT_EQ(c.Extra.size(), 3u);
  EXPECT_EQ(c.Extra[0].Name, "nx");
  EXPECT_EQ(c.Extra[2].Name, "nz");
  EXPECT_EQ(c.Extra[1].Type, ScalarType::Float32);
  EXPECT_EQ(c.Extra[1].GetAsDouble(100), 0.0);
  // Sanity against the SOURCE.md facts: median opacity logit about -2.7.
  std::vector<float> op = c.OpacityLogits;
  std::nth_element(op.begin(), op.begin() + op.size() / 2, op.end());
  EXPECT_NEAR(op[op.size() / 2], -2.7, 0.3);
}

TEST(GaussianPly, WritingTheInriaFileBackGivesTheSameBytes)
{
  VIS4GS_REQUIRE_SHARED_DATA();
  TempDir dir;
  const GaussianCloud c = ReadGaussianPly(InriaPly);
  WriteGaussianPly(dir / "out.ply", c);
  EXPECT_EQ(FileBytes(dir / "out.ply"), FileBytes(InriaPly));
  // In memory too.
  EXPECT_EQ(WriteGaussianPlyToMemory(c), FileBytes(InriaPly));
}

TEST(GaussianPly, ReadsDonutWithoutNormalsOrRest)
{
  VIS4GS_REQUIRE_SHARED_DATA();
  GaussianReadReport report;
  const GaussianCloud c = ReadGaussianPly(DonutPly, {}, &report);
  ASSERT_EQ(c.Count, 45624u);
  EXPECT_EQ(c.ShDegree, 0);
  EXPECT_EQ(report.FileShDegree, 0);
  EXPECT_TRUE(c.Extra.empty());
  EXPECT_EQ(c.SH.size(), 3u * 45624);
  const auto rows = NaiveRows(FileBytes(DonutPly), 14);
  ASSERT_EQ(rows.size(), 45624u * 14);
  std::size_t mismatches = 0;
  for (std::size_t g = 0; g < c.Count; ++g)
  {
    const float* r = &rows[14 * g]; // x y z f_dc0..2 opacity scale0..2 rot0..3
    for (int k = 0; k < 3; ++k)
    {
      mismatches += Bits(c.Positions[3 * g + k]) != Bits(r[k]);
      mismatches += Bits(c.SH[3 * g + k]) != Bits(r[3 + k]);
      mismatches += Bits(c.LogScales[3 * g + k]) != Bits(r[7 + k]);
    }
    mismatches += Bits(c.OpacityLogits[g]) != Bits(r[6]);
    for (int k = 0; k < 4; ++k)
    {
      mismatches += Bits(c.Rotations[4 * g + k]) != Bits(r[10 + k]);
    }
  }
  EXPECT_EQ(mismatches, 0u);
  // SOURCE.md: log-scales about -9.6..-3.5.
  const auto [lo, hi] = std::minmax_element(c.LogScales.begin(), c.LogScales.end());
  EXPECT_GT(*lo, -10.0f);
  EXPECT_LT(*hi, -3.0f);
}

TEST(GaussianPly, MaxShDegreeAndSkippedArrays)
{
  VIS4GS_REQUIRE_SHARED_DATA();
  const GaussianCloud full = ReadGaussianPly(InriaPly);
  for (int d = 0; d <= 3; ++d)
  {
    GaussianReadOptions o;
    o.MaxShDegree = d;
    const GaussianCloud c = ReadGaussianPly(InriaPly, o);
    const int k = (d + 1) * (d + 1);
    EXPECT_EQ(c.ShDegree, d);
    ASSERT_EQ(c.SH.size(), 3u * k * c.Count);
    for (std::size_t g = 0; g < c.Count; g += 97)
    {
      for (int j = 0; j < 3 * k; ++j)
      {
        EXPECT_EQ(Bits(c.SH[3 * k * g + j]), Bits(full.SH[48 * g + j]));
      }
    }
  }
  GaussianReadOptions positionsOnly;
  positionsOnly.LoadScales = positionsOnly.LoadRotations = positionsOnly.LoadOpacities = false;
  positionsOnly.LoadSH = positionsOnly.LoadExtras = false;
  const GaussianCloud p = ReadGaussianPly(InriaPly, positionsOnly);
  EXPECT_EQ(p.Count, 9080u);
  ExpectBitEqual(p.Positions, full.Positions, "positions only");
  EXPECT_TRUE(p.LogScales.empty());
  EXPECT_TRUE(p.Rotations.empty());
  EXPECT_TRUE(p.OpacityLogits.empty());
  EXPECT_TRUE(p.SH.empty());
  EXPECT_TRUE(p.Extra.empty());
}

TEST(GaussianPly, RoundTripsAreBitExactInEveryFormat)
{
  TempDir dir;
  for (int degree : { 0, 1, 2, 3 })
  {
    GaussianCloud c = Synthetic(50, degree);
    c.Ids.resize(c.Count);
    for (std::size_t i = 0; i < c.Count; ++i)
    {
      c.Ids[i] = static_cast<std::int64_t>(1000 + 7 * i);
    }
    for (PlyFormat f :
      { PlyFormat::BinaryLittleEndian, PlyFormat::BinaryBigEndian, PlyFormat::Ascii })
    {
      GaussianWriteOptions w;
      w.Format = f;
      w.Comments = { "written by TestGaussianPly" };
      const std::string path = dir / ("rt" + std::to_string(degree) + ".ply");
      WriteGaussianPly(path, c, w);
      GaussianReadOptions r;
      r.IdProperty = "id";
      GaussianReadReport report;
      const GaussianCloud back = ReadGaussianPly(path, r, &report);
      SCOPED_TRACE("degree " + std::to_string(degree) + " format " + report.Format);
      ExpectCloudsBitEqual(c, back);
      EXPECT_EQ(report.FileShDegree, degree);
      // 6 non-finite specials (two infinities, four NaNs) in the positions of Gaussians 0..5
      // and in the last 6 SH values (the last Gaussian, or the last two at degree 0).
      EXPECT_EQ(report.NonFiniteValues, 12u);
      EXPECT_EQ(report.NonFiniteGaussians, 6u + (degree == 0 ? 2u : 1u));
      EXPECT_EQ(report.Warnings.size(), 1u);
    }
  }
}

TEST(GaussianPly, AppendedExtrasWriteWhatACopyWithThoseExtrasWrites)
{
  // vis4gs analyze writes its scores this way instead of copying the cloud (issue 31).
  GaussianCloud c = Synthetic(40, 3);
  c.Ids.resize(c.Count);
  for (std::size_t i = 0; i < c.Count; ++i)
  {
    c.Ids[i] = static_cast<std::int64_t>(5 + 3 * i);
  }
  GaussianCloud head = c;
  std::vector<ExtraProperty> tail(head.Extra.end() - 3, head.Extra.end());
  head.Extra.erase(head.Extra.end() - 3, head.Extra.end());
  for (PlyFormat f : { PlyFormat::BinaryLittleEndian, PlyFormat::Ascii })
  {
    GaussianWriteOptions plain, appended;
    plain.Format = appended.Format = f;
    appended.AppendedExtras = &tail;
    EXPECT_EQ(WriteGaussianPlyToMemory(head, appended), WriteGaussianPlyToMemory(c, plain));
    // Without the ids: what a copy without ids writes.
    GaussianCloud noIds = c;
    noIds.Ids.clear();
    appended.WriteIds = false;
    EXPECT_EQ(WriteGaussianPlyToMemory(head, appended), WriteGaussianPlyToMemory(noIds, plain));
  }
  tail[0].Bytes.pop_back();
  GaussianWriteOptions bad;
  bad.AppendedExtras = &tail;
  EXPECT_THROW(WriteGaussianPlyToMemory(head, bad), std::invalid_argument);
}

TEST(GaussianPly, RealFileRoundTripsThroughBigEndianAndAscii)
{
  VIS4GS_REQUIRE_SHARED_DATA();
  TempDir dir;
  const GaussianCloud c = ReadGaussianPly(InriaPly);
  for (PlyFormat f : { PlyFormat::BinaryBigEndian, PlyFormat::Ascii })
  {
    GaussianWriteOptions w;
    w.Format = f;
    WriteGaussianPly(dir / "x.ply", c, w);
    ExpectCloudsBitEqual(c, ReadGaussianPly(dir / "x.ply"));
  }
}

TEST(GaussianPly, PropertiesByNameInAnyOrderWithAnyTypeName)
{
  // Hand-written ASCII file: shuffled order, float32/double/uchar type names, SH degree 1
  // (9 f_rest listed in reverse), an int score extra and a list-free comment.
  std::string text = "ply\r\nformat ascii 1.0\ncomment shuffled\nelement vertex 2\n"
                     "property float32 rot_3\nproperty double opacity\nproperty float z\n";
  for (int j = 8; j >= 0; --j)
  {
    text += "property float f_rest_" + std::to_string(j) + "\n";
  }
  text += "property float32 y\nproperty uint8 score\nproperty float x\nproperty float f_dc_2\n"
          "property float f_dc_1\nproperty float f_dc_0\nproperty float scale_2\n"
          "property float scale_1\nproperty float scale_0\nproperty float rot_2\n"
          "property float rot_1\nproperty float rot_0\nend_header\n";
  // Row values: f_rest_j = 10 + j; others distinct.
  auto row = [](float base)
  {
    std::string r =
      std::to_string(base + 0.25f) + " " + std::to_string(-1.5) + " " + std::to_string(base + 3);
    for (int j = 8; j >= 0; --j)
    {
      r += " " + std::to_string(10 + j + base);
    }
    r += " " + std::to_string(base + 2) + " 7 " + std::to_string(base + 1) + " 0.3 0.2 0.1 " +
      "-1 -2 -3 0 0 " + std::to_string(base) + "\n";
    return r;
  };
  text += row(0) + "\n" + row(100); // a blank line between rows is tolerated
  TempDir dir;
  WriteFile(dir / "a.ply", text);
  const GaussianCloud c = ReadGaussianPly(dir / "a.ply");
  ASSERT_EQ(c.Count, 2u);
  EXPECT_EQ(c.ShDegree, 1);
  for (int g = 0; g < 2; ++g)
  {
    const float base = g ? 100.0f : 0.0f;
    EXPECT_EQ(c.Positions[3 * g + 0], base + 1);
    EXPECT_EQ(c.Positions[3 * g + 1], base + 2);
    EXPECT_EQ(c.Positions[3 * g + 2], base + 3);
    EXPECT_EQ(c.OpacityLogits[g], -1.5f);
    EXPECT_EQ(c.Rotations[4 * g + 0], base);
    EXPECT_EQ(c.Rotations[4 * g + 3], base + 0.25f);
    EXPECT_EQ(c.LogScales[3 * g + 0], -3.0f);
    EXPECT_EQ(c.LogScales[3 * g + 2], -1.0f);
    // DC: f_dc_0 = 0.1 (R), f_dc_2 = 0.3 (B).
    EXPECT_FLOAT_EQ(c.SH[12 * g + 0], 0.1f);
    EXPECT_FLOAT_EQ(c.SH[12 * g + 2], 0.3f);
    // f_rest_j, j = ch*3 + (k-1) -> SH[12g + 3k + ch] = 10 + j + base.
    for (int ch = 0; ch < 3; ++ch)
    {
      for (int k = 1; k < 4; ++k)
      {
        EXPECT_EQ(c.SH[12 * g + 3 * k + ch], 10.0f + ch * 3 + (k - 1) + base);
      }
    }
  }
  ASSERT_EQ(c.Extra.size(), 1u);
  EXPECT_EQ(c.Extra[0].Name, "score");
  EXPECT_EQ(c.Extra[0].Type, ScalarType::UInt8);
  EXPECT_EQ(c.Extra[0].GetAsDouble(1), 7.0);
  // The extra goes back as a uchar property after the standard ones.
  WriteGaussianPly(dir / "b.ply", c);
  const auto bytes = FileBytes(dir / "b.ply");
  const std::string head(bytes.begin(), bytes.begin() + 900);
  EXPECT_NE(head.find("property float rot_3\nproperty uchar score\nend_header"), std::string::npos);
}

TEST(GaussianPly, ZeroQuaternionsAndNonFiniteValuesAreKeptAndCounted)
{
  GaussianCloud c = Synthetic(3, 0);
  c.Extra.clear();
  for (std::size_t i = 0; i < c.Positions.size(); ++i)
  {
    c.Positions[i] = 1.0f;
  }
  for (float& v : c.SH)
  {
    v = 0.5f;
  }
  c.Rotations.assign(12, 0.0f);
  c.OpacityLogits[1] = std::numeric_limits<float>::quiet_NaN();
  c.LogScales[7] = std::numeric_limits<float>::infinity();
  c.LogScales[8] = -std::numeric_limits<float>::infinity();
  const auto bytes = WriteGaussianPlyToMemory(c);
  GaussianReadReport report;
  const GaussianCloud back =
    ReadGaussianPlyFromMemory(bytes.data(), bytes.size(), "mem.ply", {}, &report);
  EXPECT_EQ(report.NonFiniteValues, 3u);
  EXPECT_EQ(report.NonFiniteGaussians, 2u);
  ASSERT_EQ(report.Warnings.size(), 1u);
  EXPECT_NE(report.Warnings[0].find("mem.ply"), std::string::npos);
  EXPECT_NE(report.Warnings[0].find("2 Gaussians"), std::string::npos);
  EXPECT_TRUE(std::isnan(back.OpacityLogits[1]));
  EXPECT_EQ(back.LogScales[8], -std::numeric_limits<float>::infinity());
  for (float q : back.Rotations)
  {
    EXPECT_EQ(q, 0.0f);
  }
  // A zero quaternion normalises to zero, never NaN.
  const auto n = NormalizeQuaternion(&back.Rotations[0]);
  EXPECT_EQ(n[0], 0.0f);
}

//------------------------------------------------------------------------------
// Bad input.
std::string Header(const std::string& format, const std::string& count, bool withOpacity = true)
{
  std::string h = "ply\nformat " + format + " 1.0\nelement vertex " + count + "\n";
  for (const char* p : { "x", "y", "z", "f_dc_0", "f_dc_1", "f_dc_2" })
  {
    h += std::string("property float ") + p + "\n";
  }
  if (withOpacity)
  {
    h += "property float opacity\n";
  }
  for (const char* p : { "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3" })
  {
    h += std::string("property float ") + p + "\n";
  }
  return h + "end_header\n";
}

GaussianCloud ReadText(const std::string& text, const std::string& name = "bad.ply")
{
  return ReadGaussianPlyFromMemory(text.data(), text.size(), name);
}

TEST(GaussianPlyErrors, TruncatedBinaryFile)
{
  VIS4GS_REQUIRE_SHARED_DATA();
  const auto bytes = FileBytes(InriaPly);
  TempDir dir;
  // Cut in the middle of the data: the error names the file, both counts and happens before
  // any allocation of the arrays.
  WriteFile(dir / "cut.ply", bytes.data(), bytes.size() - 1000);
  EXPECT_THROW_WITH(ReadGaussianPly(dir / "cut.ply"), "cut.ply", "9080 vertices", "truncated");
  // Cut inside the header.
  WriteFile(dir / "head.ply", bytes.data(), 200);
  EXPECT_THROW_WITH(ReadGaussianPly(dir / "head.ply"), "head.ply", "end_header");
  // Every prefix of a small file fails cleanly (never crashes).
  const auto small = WriteGaussianPlyToMemory(Synthetic(3, 1));
  for (std::size_t len = 0; len < small.size(); ++len)
  {
    EXPECT_THROW(ReadGaussianPlyFromMemory(small.data(), len, "prefix.ply"), std::runtime_error)
      << len;
  }
}

TEST(GaussianPlyErrors, HeaderCountsLargerThanTheFile)
{
  const std::string rows(2 * 14 * 4, '\0');
  EXPECT_THROW_WITH(ReadText(Header("binary_little_endian", "3") + rows),
    "bad.ply",
    "header declares 3 vertices",
    "holds 2 vertices");
  // Absurd counts fail before allocating (would need ~5e19 bytes otherwise).
  EXPECT_THROW_WITH(ReadText(Header("binary_little_endian", "999999999999999999") + rows),
    "header declares 999999999999999999 vertices");
  EXPECT_THROW_WITH(
    ReadText(Header("binary_big_endian", "18446744073709551615") + rows), "bad.ply", "vertices");
  EXPECT_THROW_WITH(ReadText(Header("ascii", "100000000000") + "1 2 3\n"), "bad.ply", "too small");
  EXPECT_THROW_WITH(ReadText(Header("binary_little_endian", "-1") + rows), "malformed 'element'");
  EXPECT_THROW_WITH(ReadText(Header("ascii", "2") +
                      "1.0000 2.0000 3.0000 4.0000 5.0000 6.0000 7.0000 8.0000 9.0000 10.000 "
                      "11.000 12.000 13.000 14.000\n"),
    "header declares 2 vertices but the file holds 1");
}

TEST(GaussianPlyErrors, MissingRequiredProperties)
{
  const std::string rows(14 * 4, '\0');
  EXPECT_THROW_WITH(
    ReadText(Header("binary_little_endian", "1", false) + rows), "bad.ply", "missing", "opacity");
  // A plain point cloud (x y z only) is not a 3DGS scene, but positions alone can be read.
  const std::string xyz = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                          "property float y\nproperty float z\nend_header\n1 2 3\n";
  EXPECT_THROW_WITH(ReadText(xyz), "scale_0", "rot_3", "f_dc_0");
  GaussianReadOptions o;
  o.LoadScales = o.LoadRotations = o.LoadOpacities = o.LoadSH = false;
  const GaussianCloud c = ReadGaussianPlyFromMemory(xyz.data(), xyz.size(), "xyz.ply", o);
  EXPECT_EQ(c.Positions, (std::vector<float>{ 1, 2, 3 }));
  // Missing id property when asked for one.
  o.IdProperty = "gid";
  EXPECT_THROW_WITH(ReadGaussianPlyFromMemory(xyz.data(), xyz.size(), "xyz.ply", o), "gid");
  EXPECT_THROW_WITH(ReadText("not a ply"), "not a PLY file");
  EXPECT_THROW_WITH(ReadText("ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int "
                             "vertex_indices\nend_header\n3 0 1 2\n"),
    "no 'vertex' element");
  EXPECT_THROW_WITH(ReadText("ply\nformat binary 1.0\nend_header\n"), "unknown PLY format");
  EXPECT_THROW_WITH(
    ReadText("ply\nformat ascii 1.0\nelement vertex 1\nproperty half x\nend_header\n"),
    "unknown type 'half'");
  EXPECT_THROW_WITH(ReadText("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                             "property float x\nend_header\n"),
    "appears twice");
  EXPECT_THROW_WITH(ReadText("ply\nformat ascii 1.0\nelement vertex 1\nproperty list uchar "
                             "float x\nend_header\n"),
    "is a list");
  // 10 f_rest properties is no SH degree.
  std::string h = Header("ascii", "0");
  std::string rest;
  for (int j = 0; j < 10; ++j)
  {
    rest += "property float f_rest_" + std::to_string(j) + "\n";
  }
  h.insert(h.find("end_header"), rest);
  EXPECT_THROW_WITH(ReadText(h), "10 f_rest properties");
}

TEST(GaussianPly, SurfelsWithoutScale2AndRenderModeComments)
{
  // 2DGS (issue 34): scale_0 and scale_1 only; read flat along the normal and said so.
  const std::string surfels = "ply\nformat ascii 1.0\ncomment SplatRenderMode: 2dgs\n"
                              "element vertex 2\nproperty float x\nproperty float y\n"
                              "property float z\nproperty float f_dc_0\nproperty float f_dc_1\n"
                              "property float f_dc_2\nproperty float opacity\n"
                              "property float scale_0\nproperty float scale_1\n"
                              "property float rot_0\nproperty float rot_1\nproperty float rot_2\n"
                              "property float rot_3\nend_header\n"
                              "1 2 3 0.1 0.2 0.3 0.5 -2 -3 1 0 0 0\n4 5 6 0 0 0 1 -1 -4 0 1 0 0\n";
  GaussianReadReport report;
  const GaussianCloud c =
    ReadGaussianPlyFromMemory(surfels.data(), surfels.size(), "surfels.ply", {}, &report);
  ASSERT_EQ(c.Count, 2u);
  EXPECT_EQ(c.LogScales[0], -2.0f);
  EXPECT_EQ(c.LogScales[1], -3.0f);
  EXPECT_EQ(c.LogScales[4], -4.0f);
  for (int g = 0; g < 2; ++g)
  {
    EXPECT_TRUE(std::isinf(c.LogScales[3 * g + 2]) && c.LogScales[3 * g + 2] < 0);
  }
  EXPECT_EQ(report.RenderMode, "2dgs");
  ASSERT_EQ(report.Warnings.size(), 1u);
  EXPECT_NE(report.Warnings[0].find("surfels.ply: no scale_2: 2D Gaussian splatting surfels"),
    std::string::npos);
  // Written back, the flat axis keeps its meaning (scale_2 = -inf reads as written).
  const auto bytes = WriteGaussianPlyToMemory(c);
  const GaussianCloud back = ReadGaussianPlyFromMemory(bytes.data(), bytes.size(), "back.ply");
  EXPECT_EQ(back.LogScales, c.LogScales);
  // One scale only is no surfel: still an error naming what is missing.
  std::string one = surfels;
  one.replace(one.find("property float scale_1\n"), 23, "");
  EXPECT_THROW_WITH(ReadText(one), "scale_1", "scale_2");

  // Brush's and Postshot's comments; the last one wins, case does not matter.
  auto mode = [](const std::string& comments, std::string* warning = nullptr)
  {
    std::string text = Header("ascii", "1");
    text.insert(text.find("element"), comments);
    text += "0 0 0 0 0 0 0 0 0 0 1 0 0 0\n";
    GaussianReadReport r;
    ReadGaussianPlyFromMemory(text.data(), text.size(), "m.ply", {}, &r);
    if (warning)
    {
      *warning = r.Warnings.empty() ? "" : r.Warnings.back();
    }
    return r.RenderMode;
  };
  std::string warning;
  EXPECT_EQ(mode("comment SplatRenderMode: mip\n", &warning), "antialiased");
  EXPECT_NE(warning.find("m.ply: the header says 'SplatRenderMode: mip'"), std::string::npos);
  EXPECT_EQ(mode("comment antialiased 1\ncomment splatrendermode: DEFAULT\n"), "default");
  EXPECT_EQ(mode("comment antialiased 1\n"), "antialiased");
  EXPECT_EQ(mode("comment made by a tool\n"), "");
  EXPECT_EQ(mode("comment SplatRenderMode: 2dgs\n", &warning), "2dgs");
  EXPECT_NE(warning.find("holds scale_2: read as 3D Gaussians"), std::string::npos);
}

TEST(GaussianPlyErrors, NonNumericAscii)
{
  const std::string h = Header("ascii", "2");
  const std::string good = "1 2 3 4 5 6 7 8 9 10 11 12 13 14\n";
  EXPECT_NO_THROW(ReadText(h + good + good));
  EXPECT_THROW_WITH(ReadText(h + good + "1 2 3 4 5 6 abc 8 9 10 11 12 13 14\n"),
    "bad.ply",
    "line 20",
    "vertex 1",
    "'abc'",
    "opacity");
  EXPECT_THROW_WITH(ReadText(h + good + "1 2 3 4 5 6 7 8 9 10 11 12 13\n"), "has 13 values");
  EXPECT_THROW_WITH(ReadText(h + good + "1 2 3 4 5 6 7 8 9 10 11 12 13 14 15\n"), "has 15 values");
  EXPECT_THROW_WITH(ReadText(h + good + "1 2 3 4 5 6 7 8 9 10 11 12 13 1.5.2\n"), "'1.5.2'");
  EXPECT_THROW_WITH(ReadText(h + good + "1 2 3 4 5 6 7 8 9 10 11 12 13 --1\n"), "'--1'");
  // Special values are numbers.
  GaussianReadReport report;
  const std::string special = "nan -inf +1e-50 1e50 -nan 0x10 7 8 9 10 11 12 13 14\n";
  EXPECT_THROW_WITH(ReadText(h + good + special), "'0x10'");
  const std::string ok = "nan -inf +1e-50 1e50 -nan 6 7 8 9 10 11 12 13 14\n";
  const GaussianCloud c =
    ReadGaussianPlyFromMemory((h + good + ok).data(), (h + good + ok).size(), "s.ply", {}, &report);
  EXPECT_TRUE(std::isnan(c.Positions[3]));
  EXPECT_EQ(c.Positions[4], -std::numeric_limits<float>::infinity());
  EXPECT_EQ(c.Positions[5], 0.0f);
  EXPECT_EQ(c.SH[3], std::numeric_limits<float>::infinity()); // 1e50 overflows float
  EXPECT_EQ(report.NonFiniteValues, 4u);
  EXPECT_EQ(report.NonFiniteGaussians, 1u);
  // Integer extras must be integers in range.
  const std::string hi = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty "
                         "float y\nproperty float z\nproperty uchar u\nend_header\n1 2 3 300\n";
  GaussianReadOptions o;
  o.LoadScales = o.LoadRotations = o.LoadOpacities = o.LoadSH = false;
  EXPECT_THROW_WITH(ReadGaussianPlyFromMemory(hi.data(), hi.size(), "u.ply", o), "'300'", "uchar");
}

TEST(GaussianPlyErrors, UnreadableFileAndUnwritableFolder)
{
  EXPECT_THROW_WITH(
    ReadGaussianPly("/nonexistent/scene.ply"), "/nonexistent/scene.ply", "cannot open");
  EXPECT_THROW_WITH(ReadGaussianPly("/tmp"), "/tmp", "not a regular file");
  EXPECT_THROW_WITH(
    WriteGaussianPly("/nonexistent/out.ply", Synthetic(2, 0)), "/nonexistent/out.ply", "temporary");
  GaussianCloud bad = Synthetic(2, 0);
  bad.Positions.pop_back();
  TempDir dir;
  EXPECT_THROW(WriteGaussianPly(dir / "bad.ply", bad), std::invalid_argument);
  EXPECT_TRUE(FileBytes(dir / "bad.ply").empty()); // nothing was created
}

//------------------------------------------------------------------------------
TEST(GaussianSplat, ReadsRealSplatFile)
{
  VIS4GS_REQUIRE_SHARED_DATA();
  GaussianReadReport report;
  const GaussianCloud c = ReadGaussianScene(SplatFile, {}, &report);
  ASSERT_EQ(c.Count, 22764u);
  EXPECT_EQ(report.Format, "splat");
  EXPECT_EQ(c.ShDegree, 0);
  // Independent decode of a few rows with the documented layout.
  const auto bytes = FileBytes(SplatFile);
  for (std::size_t g : { std::size_t(0), std::size_t(1), std::size_t(777), std::size_t(22763) })
  {
    const unsigned char* r = bytes.data() + 32 * g;
    float f[6];
    std::memcpy(f, r, 24);
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_EQ(c.Positions[3 * g + k], f[k]);
      EXPECT_FLOAT_EQ(std::exp(c.LogScales[3 * g + k]), f[3 + k]);
      EXPECT_NEAR(0.5 + sh::C0 * c.SH[3 * g + k], r[24 + k] / 255.0, 1e-6);
    }
    const double a = std::min(std::max(r[27] / 255.0, 1e-4), 1 - 1e-4);
    EXPECT_NEAR(Sigmoid(static_cast<double>(c.OpacityLogits[g])), a, 1e-6);
    for (int k = 0; k < 4; ++k)
    {
      EXPECT_EQ(c.Rotations[4 * g + k], (r[28 + k] - 128) / 128.0f);
    }
  }
  // Row 0 by hand: RGBA bytes 122 129 134 49 -> DC (122/255-0.5)/C0, quaternion byte 199.
  EXPECT_NEAR(c.SH[0], (122 / 255.0 - 0.5) / sh::C0, 1e-6);
  EXPECT_NEAR(c.OpacityLogits[0], std::log(49 / 206.0), 1e-5);
  EXPECT_EQ(c.Rotations[0], 71 / 128.0f);
  EXPECT_NEAR(c.Positions[0], 29.070545, 1e-5);
}

TEST(GaussianSplat, SpecialValuesAreWrittenAsTheReferenceDrawsThem)
{
  // Documentation/special-values.md, writer row: what the reference draws keeps its meaning
  // in bytes; what it has no answer for is left out and counted.
  const float inf = std::numeric_limits<float>::infinity();
  GaussianCloud c;
  c.Resize(7, 0);
  for (std::size_t g = 0; g < 7; ++g)
  {
    c.Positions[3 * g] = static_cast<float>(g);
    c.Rotations[4 * g] = 1;
  }
  c.Positions[3 * 1 + 1] = std::numeric_limits<float>::quiet_NaN(); // left out
  c.OpacityLogits[2] = inf;                                         // alpha byte 255
  c.OpacityLogits[3] = -inf;                                        // alpha byte 0
  c.Rotations[4 * 4] = 0;                                           // zero quaternion
  c.LogScales[3 * 5 + 2] = -inf;                                    // scale 0
  c.SH[3 * 6] = inf;                                                // DC colour: left out
  TempDir dir;
  EXPECT_EQ(WriteSplat(dir / "s.splat", c), 2u);
  const auto b = FileBytes(dir / "s.splat");
  ASSERT_EQ(b.size(), 5u * 32u);
  // Written in order: Gaussians 0, 2, 3, 4, 5.
  auto row = [&](int r) { return b.data() + 32 * r; };
  float x;
  std::memcpy(&x, row(1), 4);
  EXPECT_EQ(x, 2.0f);
  EXPECT_EQ(row(1)[27], 255);
  EXPECT_EQ(row(2)[27], 0);
  EXPECT_EQ(row(0)[27], 128); // sigmoid(0) = 0.5 -> 127.5, rounded to even
  for (int k = 0; k < 4; ++k)
  {
    EXPECT_EQ(row(3)[28 + k], 128) << k;
  }
  float sz;
  std::memcpy(&sz, row(4) + 20, 4);
  EXPECT_EQ(sz, 0.0f);
  const GaussianCloud back = ReadSplat(dir / "s.splat");
  ASSERT_EQ(back.Count, 5u);
  EXPECT_EQ(ClassifyGaussian(&back.Positions[3 * 3],
              &back.LogScales[3 * 3],
              &back.Rotations[4 * 3],
              back.OpacityLogits[3]),
    vis4gs::GaussianClass::Drawn); // the zero quaternion reads back drawable
  EXPECT_EQ(back.LogScales[3 * 4 + 2], -inf);
}

TEST(GaussianSplat, WriteReadIsStableAndBadSizesFail)
{
  VIS4GS_REQUIRE_SHARED_DATA();
  TempDir dir;
  const GaussianCloud c = ReadSplat(SplatFile);
  WriteSplat(dir / "w.splat", c);
  // Quantised values come back as the same bytes (alpha 0 and 255, clamped to 1e-4 and
  // 1-1e-4 on reading, round back to 0 and 255); positions are exact, scales go through
  // log/exp in float (1 ulp), quaternions are re-normalised (one 8-bit step).
  const auto a = FileBytes(dir / "w.splat");
  const auto b = FileBytes(SplatFile);
  ASSERT_EQ(a.size(), b.size());
  std::size_t posDiff = 0, scaleDiff = 0, colourDiff = 0, quatDiff = 0;
  for (std::size_t g = 0; g < a.size() / 32; ++g)
  {
    const unsigned char* ra = a.data() + 32 * g;
    const unsigned char* rb = b.data() + 32 * g;
    posDiff += std::memcmp(ra, rb, 12) != 0;
    for (int k = 0; k < 3; ++k)
    {
      float fa, fb;
      std::memcpy(&fa, ra + 12 + 4 * k, 4);
      std::memcpy(&fb, rb + 12 + 4 * k, 4);
      scaleDiff += std::fabs(fa - fb) > 2e-7f * std::fabs(fb);
    }
    colourDiff += std::memcmp(ra + 24, rb + 24, 4) != 0;
    for (int k = 0; k < 4; ++k)
    {
      quatDiff += std::abs(ra[28 + k] - rb[28 + k]) > 1;
    }
  }
  EXPECT_EQ(posDiff, 0u);
  EXPECT_EQ(scaleDiff, 0u);
  EXPECT_EQ(colourDiff, 0u);
  EXPECT_EQ(quatDiff, 0u);
  const std::string seven(7 * 32 + 5, '\0');
  EXPECT_THROW_WITH(
    ReadSplatFromMemory(seven.data(), seven.size(), "x.splat"), "x.splat", "not a multiple of 32");
  // Zero scale gives -inf log scale: kept and reported.
  std::vector<unsigned char> row(32, 128);
  std::memset(row.data(), 0, 24);
  GaussianReadReport report;
  const GaussianCloud z = ReadSplatFromMemory(row.data(), row.size(), "z.splat", {}, &report);
  EXPECT_EQ(z.LogScales[0], -std::numeric_limits<float>::infinity());
  EXPECT_EQ(report.NonFiniteValues, 3u);
  EXPECT_EQ(z.Rotations[0], 0.0f);
}

} // namespace
} // namespace vis4gs

// SPDX-License-Identifier: BSD-3-Clause
// .ksplat (issue 19): files built byte by byte from the layout of GaussianSplats3D's
// SplatBuffer (Documentation/file-formats.md, ".ksplat") with values derived by hand, detection
// by content, and hostile input. Files written by GaussianSplats3D itself are compared in
// Testing/Reference/CheckKsplatReference.py.
#include "GaussianIO.h"
#include "GaussianMath.h"
#include "SceneTestUtils.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>

namespace vis4gs
{
namespace
{

using testing::TempDir;
using testing::WriteFile;

using Bytes = std::vector<unsigned char>;

void PutU16(Bytes& b, std::uint16_t v)
{
  b.push_back(static_cast<unsigned char>(v));
  b.push_back(static_cast<unsigned char>(v >> 8));
}

void PutU32(Bytes& b, std::uint32_t v)
{
  PutU16(b, static_cast<std::uint16_t>(v));
  PutU16(b, static_cast<std::uint16_t>(v >> 16));
}

void PutF32(Bytes& b, float f)
{
  std::uint32_t v;
  std::memcpy(&v, &f, 4);
  PutU32(b, v);
}

void SetU16(Bytes& b, std::size_t at, std::uint16_t v)
{
  b[at] = static_cast<unsigned char>(v);
  b[at + 1] = static_cast<unsigned char>(v >> 8);
}

void SetU32(Bytes& b, std::size_t at, std::uint32_t v)
{
  SetU16(b, at, static_cast<std::uint16_t>(v));
  SetU16(b, at + 2, static_cast<std::uint16_t>(v >> 16));
}

void SetF32(Bytes& b, std::size_t at, float f)
{
  std::uint32_t v;
  std::memcpy(&v, &f, 4);
  SetU32(b, at, v);
}

/// One section: its header fields and its bytes (bucket lengths, centres, records).
struct Section
{
  std::uint32_t SplatCount = 0;
  std::uint32_t BucketSize = 0;
  std::uint32_t FullBuckets = 0;
  std::uint32_t PartialBuckets = 0;
  float BlockSize = 0;
  std::uint16_t ShDegree = 0;
  Bytes Body;
};

/// Main header, section headers and bodies, as GaussianSplats3D's generator writes them.
Bytes Build(int level, const std::vector<Section>& sections, float shMin = 0, float shMax = 0)
{
  Bytes b(4096 + 1024 * sections.size(), 0);
  b[1] = 1; // version 0.1
  std::uint32_t total = 0;
  for (const Section& s : sections)
  {
    total += s.SplatCount;
  }
  SetU32(b, 4, static_cast<std::uint32_t>(sections.size()));
  SetU32(b, 8, static_cast<std::uint32_t>(sections.size()));
  SetU32(b, 12, total);
  SetU32(b, 16, total);
  SetU16(b, 20, static_cast<std::uint16_t>(level));
  SetF32(b, 36, shMin);
  SetF32(b, 40, shMax);
  for (std::size_t i = 0; i < sections.size(); ++i)
  {
    const Section& s = sections[i];
    const std::size_t h = 4096 + 1024 * i;
    SetU32(b, h, s.SplatCount);
    SetU32(b, h + 4, s.SplatCount);
    if (level >= 1)
    {
      SetU32(b, h + 8, s.BucketSize);
      SetU32(b, h + 12, s.FullBuckets + s.PartialBuckets);
      SetF32(b, h + 16, s.BlockSize);
      SetU16(b, h + 20, 12);
      SetU32(b, h + 24, 32767);
      SetU32(b, h + 32, s.FullBuckets);
      SetU32(b, h + 36, s.PartialBuckets);
    }
    SetU32(b, h + 28, static_cast<std::uint32_t>(s.Body.size()));
    SetU16(b, h + 40, s.ShDegree);
  }
  for (const Section& s : sections)
  {
    b.insert(b.end(), s.Body.begin(), s.Body.end());
  }
  return b;
}

/// Level 0, SH degree 1: two records of float32 values and RGBA bytes.
Bytes Level0File()
{
  Section s;
  s.SplatCount = 2;
  s.ShDegree = 1;
  const float pos[2][3] = { { 1.5f, -2.f, 3.f }, { 0.25f, 0.f, -7.f } };
  const float scale[2][3] = { { 0.5f, 1.f, 2.f }, { 0.f, 4.f, 1.f } };
  const float rot[2][4] = { { 0.5f, 0.5f, -0.5f, 0.5f }, { 1.f, 0.f, 0.f, 0.f } };
  const unsigned char rgba[2][4] = { { 255, 0, 128, 51 }, { 0, 255, 255, 255 } };
  for (int g = 0; g < 2; ++g)
  {
    for (float v : pos[g])
    {
      PutF32(s.Body, v);
    }
    for (float v : scale[g])
    {
      PutF32(s.Body, v);
    }
    for (float v : rot[g])
    {
      PutF32(s.Body, v);
    }
    s.Body.insert(s.Body.end(), rgba[g], rgba[g] + 4);
    for (int i = 0; i < 9; ++i)
    {
      PutF32(s.Body, 0.125f * static_cast<float>(i + 1) * (g ? -1.f : 1.f));
    }
  }
  return Build(0, { s });
}

constexpr float Tol = 1e-6f;

TEST(GaussianKsplat, Level0ValuesDerivedByHand)
{
  const Bytes b = Level0File();
  ASSERT_EQ(b.size(), 4096u + 1024u + 2u * 80u); // 80 bytes per record at degree 1
  GaussianReadReport report;
  const GaussianCloud c = ReadKsplatFromMemory(b.data(), b.size(), "l0.ksplat", {}, &report);
  EXPECT_EQ(report.Format, "ksplat");
  EXPECT_EQ(report.FileShDegree, 1);
  ASSERT_EQ(c.Count, 2u);
  ASSERT_EQ(c.ShDegree, 1);
  EXPECT_EQ(c.Positions, (std::vector<float>{ 1.5f, -2.f, 3.f, 0.25f, 0.f, -7.f }));
  EXPECT_NEAR(c.LogScales[0], std::log(0.5), Tol);
  EXPECT_EQ(c.LogScales[1], 0.f);
  EXPECT_NEAR(c.LogScales[2], std::log(2.0), Tol);
  EXPECT_EQ(c.LogScales[3], -std::numeric_limits<float>::infinity()); // scale 0 kept, reported
  EXPECT_NEAR(c.LogScales[4], std::log(4.0), Tol);
  EXPECT_EQ(c.Rotations,
    (std::vector<float>{ 0.5f, 0.5f, -0.5f, 0.5f, 1.f, 0.f, 0.f, 0.f })); // w x y z as stored
  // Colour bytes -> DC: (c/255 - 0.5) / C0; alpha 51/255 = 0.2 -> logit log(0.25).
  const double c0 = 0.28209479177387814;
  EXPECT_NEAR(c.SH[0], 0.5 / c0, 1e-5);
  EXPECT_NEAR(c.SH[1], -0.5 / c0, 1e-5);
  EXPECT_NEAR(c.SH[2], (128.0 / 255.0 - 0.5) / c0, 1e-6);
  EXPECT_NEAR(c.OpacityLogits[0], std::log(0.25), 1e-6);
  // Alpha 255 is clamped to 1 - 1e-6, as splat-transform does: logit = log((1-1e-6)/1e-6).
  EXPECT_NEAR(c.OpacityLogits[1], std::log((1 - 1e-6) / 1e-6), 1e-4);
  // SH stored channel-major per band: R1 R2 R3 G1 G2 G3 B1 B2 B3 = 0.125 .. 1.125.
  // GaussianCloud is coefficient-major: k1 RGB, k2 RGB, k3 RGB after the DC triple.
  EXPECT_EQ(c.SH[3], 0.125f);  // k1 R
  EXPECT_EQ(c.SH[4], 0.5f);    // k1 G (4th value)
  EXPECT_EQ(c.SH[5], 0.875f);  // k1 B (7th value)
  EXPECT_EQ(c.SH[6], 0.25f);   // k2 R
  EXPECT_EQ(c.SH[11], 1.125f); // k3 B (9th value)
  EXPECT_EQ(c.SH[12 + 3], -0.125f);
  EXPECT_EQ(report.NonFiniteGaussians, 1u);
  EXPECT_EQ(report.NonFiniteValues, 1u);

  GaussianReadOptions dcOnly;
  dcOnly.MaxShDegree = 0;
  dcOnly.LoadPositions = false;
  const GaussianCloud d = ReadKsplatFromMemory(b.data(), b.size(), "l0.ksplat", dcOnly);
  EXPECT_EQ(d.ShDegree, 0);
  EXPECT_TRUE(d.Positions.empty());
  ASSERT_EQ(d.SH.size(), 6u);
  EXPECT_EQ(d.SH[3], c.SH[12]);
}

TEST(GaussianKsplat, Level1BucketsAndHalfFloats)
{
  // Bucket size 2: one full bucket (records 0-1) then a partially filled one of 1 record.
  Section s;
  s.SplatCount = 3;
  s.BucketSize = 2;
  s.FullBuckets = 1;
  s.PartialBuckets = 1;
  s.BlockSize = 5.f;
  s.ShDegree = 2;
  PutU32(s.Body, 1); // length of the partially filled bucket
  for (float v : { 10.f, 20.f, 30.f, -1.f, -2.f, -3.f })
  {
    PutF32(s.Body, v);
  }
  const std::uint16_t centres[3][3] = {
    { 32767, 65534, 0 }, { 32767, 32767, 32767 }, { 32768, 32767, 32767 }
  };
  for (int g = 0; g < 3; ++g)
  {
    for (std::uint16_t v : centres[g])
    {
      PutU16(s.Body, v);
    }
    // Scales 1, 0.5, 2^-24 (the smallest subnormal); quaternion 1, -0.5, 0, +inf.
    for (std::uint16_t v : { 0x3C00, 0x3800, 0x0001, 0x3C00, 0xB800, 0x0000, 0x7C00 })
    {
      PutU16(s.Body, v);
    }
    for (unsigned char v : { 10, 20, 30, 40 })
    {
      s.Body.push_back(v);
    }
    for (int i = 0; i < 24; ++i) // component i = +-(1 + i/1024), negative when i is odd
    {
      PutU16(s.Body, static_cast<std::uint16_t>((0x3C00 + i) | (i % 2 ? 0x8000 : 0)));
    }
  }
  const Bytes b = Build(1, { s });
  ASSERT_EQ(b.size(), 4096u + 1024u + 4u + 24u + 3u * 72u);
  GaussianReadReport report;
  const GaussianCloud c = ReadKsplatFromMemory(b.data(), b.size(), "l1.ksplat", {}, &report);
  ASSERT_EQ(c.Count, 3u);
  ASSERT_EQ(c.ShDegree, 2);
  // (u - 32767) * (5/2) / 32767 + bucket centre
  EXPECT_NEAR(c.Positions[0], 10.f, Tol);
  EXPECT_NEAR(c.Positions[1], 22.5f, 1e-5);
  EXPECT_NEAR(c.Positions[2], 27.5f, 1e-5);
  EXPECT_NEAR(c.Positions[3], 10.f, Tol);
  EXPECT_NEAR(c.Positions[6], -1.0 + 2.5 / 32767, 1e-6); // third record: second bucket
  EXPECT_NEAR(c.Positions[7], -2.f, Tol);
  EXPECT_NEAR(c.Positions[8], -3.f, Tol);
  EXPECT_EQ(c.LogScales[0], 0.f);
  EXPECT_NEAR(c.LogScales[1], std::log(0.5), Tol);
  EXPECT_NEAR(c.LogScales[2], -24 * std::log(2.0), 1e-5);
  EXPECT_EQ(c.Rotations[0], 1.f);
  EXPECT_EQ(c.Rotations[1], -0.5f);
  EXPECT_EQ(c.Rotations[2], 0.f);
  EXPECT_EQ(c.Rotations[3], std::numeric_limits<float>::infinity());
  EXPECT_EQ(report.NonFiniteGaussians, 3u);
  // SH: band 1 is values 0-8 (R1 R2 R3 G1..B3), band 2 values 9-23 (R4..R8 G4..G8 B4..B8).
  const float* sh = c.SH.data() + 2 * 27;
  EXPECT_EQ(sh[3 * 1 + 0], 1.f);                // k1 R: value 0
  EXPECT_EQ(sh[3 * 1 + 1], -(1 + 3 / 1024.f));  // k1 G: value 3
  EXPECT_EQ(sh[3 * 3 + 2], 1 + 8 / 1024.f);     // k3 B: value 8
  EXPECT_EQ(sh[3 * 4 + 0], -(1 + 9 / 1024.f));  // k4 R: value 9
  EXPECT_EQ(sh[3 * 4 + 1], 1 + 14 / 1024.f);    // k4 G: value 14
  EXPECT_EQ(sh[3 * 8 + 0], -(1 + 13 / 1024.f)); // k8 R: value 13
  EXPECT_EQ(sh[3 * 8 + 2], -(1 + 23 / 1024.f)); // k8 B: value 23
  EXPECT_NEAR(sh[0], (10 / 255.0 - 0.5) / 0.28209479177387814, 1e-5);
}

TEST(GaussianKsplat, Level2ByteSH)
{
  Section s;
  s.SplatCount = 1;
  s.BucketSize = 256;
  s.PartialBuckets = 1;
  s.BlockSize = 5.f;
  s.ShDegree = 1;
  PutU32(s.Body, 1);
  for (int i = 0; i < 3; ++i)
  {
    PutF32(s.Body, 0.f);
  }
  for (std::uint16_t v : { 32767, 32767, 32767, 0x3C00, 0x3C00, 0x3C00, 0x3C00, 0, 0, 0 })
  {
    PutU16(s.Body, v);
  }
  for (unsigned char v : { 0, 0, 0, 0, 0, 255, 51, 1, 2, 3, 4, 5, 6 })
  {
    s.Body.push_back(v);
  }
  Bytes b = Build(2, { s }, -2.f, 2.f);
  ASSERT_EQ(b.size(), 4096u + 1024u + 4u + 12u + 33u);
  GaussianCloud c = ReadKsplatFromMemory(b.data(), b.size(), "l2.ksplat");
  // byte / 255 * (max - min) + min over the header's range [-2, 2]
  EXPECT_NEAR(c.SH[3], -2.f, Tol);                                    // k1 R: byte 0
  EXPECT_NEAR(c.SH[6], 2.f, Tol);                                     // k2 R: byte 255
  EXPECT_NEAR(c.SH[9], 51 / 255.0 * 4 - 2, 1e-6);                     // k3 R: byte 51
  EXPECT_NEAR(c.SH[11], 6 / 255.0 * 4 - 2, 1e-6);                     // k3 B: byte 6
  EXPECT_NEAR(c.OpacityLogits[0], std::log(1e-6 / (1 - 1e-6)), 1e-3); // alpha 0, clamped
  // A range of 0 in the header means the default [-1.5, 1.5].
  SetF32(b, 36, 0.f);
  SetF32(b, 40, 0.f);
  c = ReadKsplatFromMemory(b.data(), b.size(), "l2.ksplat");
  EXPECT_NEAR(c.SH[3], -1.5f, Tol);
  EXPECT_NEAR(c.SH[6], 1.5f, Tol);
}

TEST(GaussianKsplat, SectionsAndPartlyWrittenFiles)
{
  // Two sections of SH degrees 1 and 0: the smallest is read for all, with a warning.
  const Bytes one = Level0File();
  Section a;
  a.SplatCount = 2;
  a.ShDegree = 1;
  a.Body.assign(one.begin() + 5120, one.end());
  Section b;
  b.SplatCount = 1;
  for (float v : { 9.f, 8.f, 7.f, 1.f, 1.f, 1.f, 1.f, 0.f, 0.f, 0.f })
  {
    PutF32(b.Body, v);
  }
  for (unsigned char v : { 1, 2, 3, 4 })
  {
    b.Body.push_back(v);
  }
  Bytes file = Build(0, { a, b });
  GaussianReadReport report;
  GaussianCloud c = ReadKsplatFromMemory(file.data(), file.size(), "two.ksplat", {}, &report);
  ASSERT_EQ(c.Count, 3u);
  EXPECT_EQ(c.ShDegree, 0);
  EXPECT_EQ(report.FileShDegree, 0);
  EXPECT_EQ(c.Positions[6], 9.f);
  EXPECT_NEAR(c.SH[6], (1 / 255.0 - 0.5) / 0.28209479177387814, 1e-6);
  ASSERT_EQ(report.Warnings.size(), 2u); // degrees, and the zero scale of the first section
  EXPECT_NE(report.Warnings[0].find("SH degrees 0 to 1"), std::string::npos);
  // A section that marks 1 of its 2 laid-out records as written (saved while loading).
  SetU32(file, 4096, 1);
  c = ReadKsplatFromMemory(file.data(), file.size(), "part.ksplat", {}, &report);
  ASSERT_EQ(c.Count, 2u);
  EXPECT_EQ(c.Positions[3], 9.f); // the second section still starts after both records
  EXPECT_NE(report.Warnings[1].find("2 of 3 splats are marked as written"), std::string::npos);
}

TEST(GaussianKsplat, DetectedByContentThroughReadGaussianScene)
{
  TempDir dir;
  const Bytes b = Level0File();
  // The content decides, not the name.
  WriteFile(dir / "scene.ply", b);
  EXPECT_TRUE(IsKsplatFile(dir / "scene.ply"));
  GaussianReadReport report;
  const GaussianCloud c = ReadGaussianScene(dir / "scene.ply", {}, &report);
  EXPECT_EQ(report.Format, "ksplat");
  EXPECT_EQ(c.Count, 2u);
  EXPECT_EQ(c.Positions[0], 1.5f);
  // Sizes that do not add up to the file, or another format, are not taken for .ksplat.
  Bytes longer = b;
  longer.push_back(0);
  WriteFile(dir / "longer.ksplat", longer);
  EXPECT_FALSE(IsKsplatFile(dir / "longer.ksplat"));
  WriteFile(dir / "short.ksplat", b.data(), b.size() - 1);
  EXPECT_FALSE(IsKsplatFile(dir / "short.ksplat"));
  WriteFile(dir / "text.ply", std::string("ply\nformat ascii 1.0\n") + std::string(5000, ' '));
  EXPECT_FALSE(IsKsplatFile(dir / "text.ply"));
  EXPECT_FALSE(IsKsplatFile(dir / "missing.ksplat"));
  EXPECT_THROW_WITH(ReadKsplat(dir / "short.ksplat"), "short.ksplat", "truncated");
}

TEST(GaussianKsplat, HostileInput)
{
  const Bytes good = Level0File();
  const auto read = [](const Bytes& b)
  { return ReadKsplatFromMemory(b.data(), b.size(), "bad.ksplat"); };
  EXPECT_THROW_WITH(read(Bytes(100, 0)), "bad.ksplat", "smaller than the 4096-byte header");
  EXPECT_THROW_WITH(ReadKsplatFromMemory(nullptr, 0, "bad.ksplat"), "bad.ksplat");
  Bytes b = good;
  b[0] = 1;
  EXPECT_THROW_WITH(read(b), "bad.ksplat", "version 1.1");
  b = good;
  SetU16(b, 20, 3);
  EXPECT_THROW_WITH(read(b), "compression level 3");
  b = good;
  SetU32(b, 4, 0xFFFFFFFFu); // 4 billion sections: refused from the file size
  EXPECT_THROW_WITH(read(b), "4294967295 sections");
  b = good;
  SetU32(b, 4096 + 4, 0xFFFFFFFFu); // a section that claims 4 billion splats
  SetU32(b, 12, 0xFFFFFFFFu);
  EXPECT_THROW_WITH(read(b), "section 0", "beyond the file");
  b = good;
  SetU32(b, 12, 3);
  SetU32(b, 16, 3);
  EXPECT_THROW_WITH(read(b), "the header says 3");
  b = good;
  SetU32(b, 4096, 5);
  EXPECT_THROW_WITH(read(b), "splat count 5 exceeds its maximum 2");
  b = good;
  SetU16(b, 4096 + 40, 7);
  EXPECT_THROW_WITH(read(b), "SH degree 7");
  b = good;
  SetU32(b, 16, 9);
  EXPECT_THROW_WITH(read(b), "exceed its maximum counts");
  EXPECT_THROW_WITH(read(Bytes(good.begin(), good.end() - 1)), "truncated");

  // Level 1: bucket counts that do not add up, or lengths that do not cover the splats.
  Section s;
  s.SplatCount = 2;
  s.BucketSize = 1;
  s.FullBuckets = 1;
  s.PartialBuckets = 1;
  s.BlockSize = 5.f;
  PutU32(s.Body, 0); // the partially filled bucket claims no record: the second has none
  for (int i = 0; i < 6; ++i)
  {
    PutF32(s.Body, 0.f);
  }
  s.Body.resize(s.Body.size() + 2 * 24, 0);
  const Bytes level1 = Build(1, { s });
  EXPECT_THROW_WITH(read(level1), "section 0", "its buckets hold 1 of its 2 splats");
  b = level1;
  SetU32(b, 4096 + 12, 3);
  EXPECT_THROW_WITH(read(b), "do not make its 3 buckets");
  b = level1;
  SetF32(b, 4096 + 16, std::numeric_limits<float>::quiet_NaN());
  EXPECT_THROW_WITH(read(b), "block size");
  b = level1;
  SetU32(b, 4096 + 12, 0);
  SetU32(b, 4096 + 32, 0);
  SetU32(b, 4096 + 36, 0);
  EXPECT_THROW_WITH(read(b), "no bucket");
  GaussianReadOptions ids;
  ids.IdProperty = "id";
  EXPECT_THROW_WITH(
    ReadKsplatFromMemory(good.data(), good.size(), "bad.ksplat", ids), "no id property");
}

} // namespace
} // namespace vis4gs

// SPDX-License-Identifier: BSD-3-Clause
// The `.ksplat` format of mkkellogg/GaussianSplats3D (its SplatBuffer, version 0.1), as laid
// out in Documentation/file-formats.md, ".ksplat". All numbers little endian:
//   main header, 4096 bytes: u8 major (0), u8 minor (>= 1), u32[1] max section count,
//     u32[2] section count, u32[3] max splat count, u32[4] splat count, u16[10] compression
//     level (0..2), f32[6..8] scene centre, f32[9..10] SH range of level 2 (0 = -1.5 / 1.5);
//   max section count headers, 1024 bytes each: u32[0] splat count, u32[1] max splat count,
//     u32[2] bucket size, u32[3] bucket count, f32[4] bucket block size, u16[10] bucket
//     storage bytes, u32[6] position scale range (0 = 32767), u32[7] storage bytes,
//     u32[8] full bucket count, u32[9] partially filled bucket count, u16[20] SH degree;
//   the sections one after the other: u32 lengths of the partially filled buckets, f32 xyz
//     bucket centres, then max splat count records of
//       level 0: f32 xyz | f32 linear scale xyz | f32 q wxyz | u8 RGBA | f32 SH
//       level 1: u16 xyz | f16 scale | f16 q | u8 RGBA | f16 SH
//       level 2: u16 xyz | f16 scale | f16 q | u8 RGBA | u8 SH
//     with SH stored band by band, each band channel-major (R of band 1, G, B, then band 2).
#include "GaussianIO.h"
#include "GaussianMath.h"
#include "SceneFile.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace vis4gs
{

namespace
{

constexpr std::size_t MainHeaderBytes = 4096;
constexpr std::size_t SectionHeaderBytes = 1024;
constexpr std::uint32_t BucketStorageBytes = 12;
constexpr std::uint32_t DefaultScaleRange = 32767;
constexpr double DefaultShHalfRange = 1.5;
// splat-transform's clamp, so that both readers give the same logits for bytes 0 and 255.
constexpr double AlphaClamp = 1e-6;

float HalfToFloat(std::uint16_t h)
{
  const int exponent = (h >> 10) & 0x1f;
  const int mantissa = h & 0x3ff;
  double v;
  if (exponent == 0)
  {
    v = std::ldexp(mantissa, -24);
  }
  else if (exponent == 31)
  {
    v =
      mantissa ? std::numeric_limits<double>::quiet_NaN() : std::numeric_limits<double>::infinity();
  }
  else
  {
    v = std::ldexp(mantissa + 1024, exponent - 25);
  }
  return static_cast<float>((h & 0x8000) ? -v : v);
}

struct KsplatSection
{
  std::uint32_t SplatCount = 0;
  std::uint32_t MaxSplatCount = 0;
  std::uint32_t BucketSize = 0;
  std::uint32_t BucketCount = 0;
  std::uint32_t FullBucketCount = 0;
  std::uint32_t PartialBucketCount = 0;
  double PositionStep = 0; ///< half the block size / the scale range
  double ScaleRange = 0;
  int ShDegree = 0;
  std::uint64_t Base = 0;     ///< partially filled bucket lengths
  std::uint64_t DataBase = 0; ///< first splat record
  std::uint64_t BytesPerSplat = 0;
};

struct KsplatLayout
{
  int VersionMinor = 0;
  int Level = 0;
  std::uint32_t MaxSplatCount = 0;
  std::uint32_t SplatCount = 0;
  float ShMin = 0;
  float ShMax = 0;
  std::vector<KsplatSection> Sections;
  std::uint64_t TotalSplats = 0; ///< sum of the sections' splat counts
  std::uint64_t End = 0;         ///< where the last section ends
};

int ShComponents(int degree)
{
  return 3 * ((degree + 1) * (degree + 1) - 1);
}

/**
 * Parses and checks the headers. @p headers holds the first bytes of the file (at least the
 * main header and, once its section count is known, all section headers: @p needMore says how
 * many are needed when fewer were given). Every count is checked against @p fileSize before
 * the caller allocates anything.
 */
KsplatLayout ParseLayout(const unsigned char* headers,
  std::size_t available,
  std::uint64_t fileSize,
  const std::string& name)
{
  const auto fail = [&](const std::string& what)
  { throw std::runtime_error(name + ": not a valid .ksplat file: " + what); };
  if (fileSize < MainHeaderBytes || available < MainHeaderBytes)
  {
    fail("size " + std::to_string(fileSize) + " bytes is smaller than the 4096-byte header");
  }
  KsplatLayout layout;
  if (headers[0] != 0 || headers[1] < 1)
  {
    fail("version " + std::to_string(headers[0]) + "." + std::to_string(headers[1]) +
      " (GaussianSplats3D writes 0.1; major versions other than 0 are unknown)");
  }
  layout.VersionMinor = headers[1];
  const std::uint32_t maxSections = detail::LoadLE32(headers + 4);
  const std::uint32_t sections = detail::LoadLE32(headers + 8);
  layout.MaxSplatCount = detail::LoadLE32(headers + 12);
  layout.SplatCount = detail::LoadLE32(headers + 16);
  layout.Level = detail::LoadLE16(headers + 20);
  // JavaScript's `x || default`: 0 and NaN select the default.
  const float shMin = detail::LoadLEFloat(headers + 36);
  const float shMax = detail::LoadLEFloat(headers + 40);
  layout.ShMin = (shMin == 0 || std::isnan(shMin)) ? float(-DefaultShHalfRange) : shMin;
  layout.ShMax = (shMax == 0 || std::isnan(shMax)) ? float(DefaultShHalfRange) : shMax;
  if (layout.Level > 2)
  {
    fail("compression level " + std::to_string(layout.Level) + " (only 0, 1 and 2 exist)");
  }
  if (maxSections == 0 ||
    MainHeaderBytes + std::uint64_t(maxSections) * SectionHeaderBytes > fileSize)
  {
    fail("the header lists " + std::to_string(maxSections) + " sections, whose 1024-byte " +
      "headers do not fit in the file's " + std::to_string(fileSize) + " bytes");
  }
  if (sections > maxSections || layout.SplatCount > layout.MaxSplatCount)
  {
    fail("the header's loaded counts (" + std::to_string(sections) + " sections, " +
      std::to_string(layout.SplatCount) + " splats) exceed its maximum counts (" +
      std::to_string(maxSections) + ", " + std::to_string(layout.MaxSplatCount) + ")");
  }
  if (available < MainHeaderBytes + std::size_t(maxSections) * SectionHeaderBytes)
  {
    throw std::logic_error("ParseLayout: section headers not given");
  }
  const std::uint64_t coreBytes = layout.Level == 0 ? 44 : 24;
  const std::uint64_t shBytes = layout.Level == 0 ? 4 : (layout.Level == 1 ? 2 : 1);
  std::uint64_t base = MainHeaderBytes + std::uint64_t(maxSections) * SectionHeaderBytes;
  std::uint64_t maxSplats = 0;
  layout.Sections.resize(maxSections);
  for (std::uint32_t i = 0; i < maxSections; ++i)
  {
    const unsigned char* h = headers + MainHeaderBytes + std::size_t(i) * SectionHeaderBytes;
    KsplatSection& s = layout.Sections[i];
    const std::string which = "section " + std::to_string(i) + ": ";
    s.SplatCount = detail::LoadLE32(h);
    s.MaxSplatCount = detail::LoadLE32(h + 4);
    s.BucketSize = detail::LoadLE32(h + 8);
    s.BucketCount = detail::LoadLE32(h + 12);
    const float blockSize = detail::LoadLEFloat(h + 16);
    const std::uint16_t bucketStorage = detail::LoadLE16(h + 20);
    const std::uint32_t scaleRange = detail::LoadLE32(h + 24);
    s.FullBucketCount = detail::LoadLE32(h + 32);
    s.PartialBucketCount = detail::LoadLE32(h + 36);
    s.ShDegree = detail::LoadLE16(h + 40);
    if (s.SplatCount > s.MaxSplatCount)
    {
      fail(which + "splat count " + std::to_string(s.SplatCount) + " exceeds its maximum " +
        std::to_string(s.MaxSplatCount));
    }
    if (s.ShDegree > 3)
    {
      fail(which + "SH degree " + std::to_string(s.ShDegree) + " (at most 3)");
    }
    s.BytesPerSplat = coreBytes + shBytes * std::uint64_t(ShComponents(s.ShDegree));
    std::uint64_t bucketBytes = 0;
    if (layout.Level >= 1)
    {
      s.ScaleRange = scaleRange ? scaleRange : DefaultScaleRange;
      s.PositionStep = blockSize / 2.0 / s.ScaleRange;
      if (bucketStorage != BucketStorageBytes || !std::isfinite(blockSize) || blockSize <= 0)
      {
        fail(which + "bucket storage " + std::to_string(bucketStorage) + " bytes, block size " +
          std::to_string(blockSize) + " (expected 12 bytes and a positive size)");
      }
      if (std::uint64_t(s.FullBucketCount) + s.PartialBucketCount != s.BucketCount)
      {
        fail(which + std::to_string(s.FullBucketCount) + " full and " +
          std::to_string(s.PartialBucketCount) + " partially filled buckets do not make its " +
          std::to_string(s.BucketCount) + " buckets");
      }
      if (s.SplatCount > 0 && s.BucketCount == 0)
      {
        fail(which + std::to_string(s.SplatCount) + " splats but no bucket to place them");
      }
      bucketBytes =
        std::uint64_t(BucketStorageBytes) * s.BucketCount + std::uint64_t(4) * s.PartialBucketCount;
    }
    s.Base = base;
    s.DataBase = base + bucketBytes;
    const std::uint64_t end = s.DataBase + s.BytesPerSplat * s.MaxSplatCount;
    if (end > fileSize)
    {
      fail(which + std::to_string(s.MaxSplatCount) + " splats of " +
        std::to_string(s.BytesPerSplat) + " bytes and " + std::to_string(s.BucketCount) +
        " buckets end at byte " + std::to_string(end) + ", beyond the file's " +
        std::to_string(fileSize) + " bytes (truncated?)");
    }
    base = end;
    maxSplats += s.MaxSplatCount;
    layout.TotalSplats += s.SplatCount;
  }
  if (maxSplats != layout.MaxSplatCount)
  {
    fail("the sections hold " + std::to_string(maxSplats) + " splats, the header says " +
      std::to_string(layout.MaxSplatCount));
  }
  layout.End = base;
  return layout;
}

//------------------------------------------------------------------------------
GaussianCloud ReadKsplatBytes(const unsigned char* data,
  std::size_t size,
  const std::string& name,
  const GaussianReadOptions& options,
  GaussianReadReport* reportOut)
{
  if (!options.IdProperty.empty())
  {
    throw std::runtime_error(
      name + ": a .ksplat file has no id property '" + options.IdProperty + "'");
  }
  const KsplatLayout layout = ParseLayout(data, size, size, name);
  GaussianReadReport report;
  report.Format = "ksplat";
  int fileDegree = 3;
  int largestDegree = 0;
  for (const KsplatSection& s : layout.Sections)
  {
    fileDegree = std::min(fileDegree, s.ShDegree);
    largestDegree = std::max(largestDegree, s.ShDegree);
  }
  report.FileShDegree = fileDegree;
  if (largestDegree != fileDegree)
  {
    report.Warnings.push_back(name + ": sections hold SH degrees " + std::to_string(fileDegree) +
      " to " + std::to_string(largestDegree) + "; degree " + std::to_string(fileDegree) +
      " is read for all, as GaussianSplats3D renders them");
  }
  if (layout.TotalSplats != layout.MaxSplatCount)
  {
    report.Warnings.push_back(name + ": " + std::to_string(layout.TotalSplats) + " of " +
      std::to_string(layout.MaxSplatCount) + " splats are marked as written (a file saved " +
      "while loading?); the written ones are read");
  }
  const int degree = options.LoadSH ? std::max(0, std::min(options.MaxShDegree, fileDegree)) : 0;
  const std::size_t n = static_cast<std::size_t>(layout.TotalSplats);
  GaussianCloud cloud = detail::AllocateReadArrays(n, degree, options);
  const int coefficients = (degree + 1) * (degree + 1);
  float dc[256], logit[256], sh8[256];
  for (int i = 0; i < 256; ++i)
  {
    dc[i] = static_cast<float>((i / 255.0 - 0.5) / sh::C0);
    logit[i] = static_cast<float>(Logit(std::min(std::max(i / 255.0, AlphaClamp), 1 - AlphaClamp)));
    sh8[i] = static_cast<float>(i / 255.0 * (double(layout.ShMax) - layout.ShMin) + layout.ShMin);
  }
  const int level = layout.Level;
  const auto loadValue = [level](const unsigned char* p, std::size_t index)
  {
    return level == 0 ? detail::LoadLEFloat(p + 4 * index)
                      : HalfToFloat(detail::LoadLE16(p + 2 * index));
  };
  std::size_t badValues = 0, badRows = 0;
  std::size_t g = 0;
  for (std::size_t si = 0; si < layout.Sections.size(); ++si)
  {
    const KsplatSection& s = layout.Sections[si];
    // Records are grouped by bucket: full buckets of BucketSize records first, then the
    // partially filled ones with the lengths listed at the section's start.
    std::uint64_t bucket = 0, bucketEnd = 0;
    bool inBucket = false;
    const unsigned char* bucketCentres = data + s.Base + 4 * std::uint64_t(s.PartialBucketCount);
    for (std::uint32_t j = 0; j < s.SplatCount; ++j, ++g)
    {
      const unsigned char* rec = data + s.DataBase + s.BytesPerSplat * j;
      std::size_t rowBad = 0;
      // At most one step per bucket, and the bucket count was checked against the file size.
      while (level >= 1 && options.LoadPositions && j >= bucketEnd)
      {
        bucket += inBucket;
        inBucket = true;
        if (bucket >= s.BucketCount)
        {
          throw std::runtime_error(name + ": not a valid .ksplat file: section " +
            std::to_string(si) + ": its buckets hold " + std::to_string(bucketEnd) + " of its " +
            std::to_string(s.SplatCount) + " splats");
        }
        bucketEnd += bucket < s.FullBucketCount
          ? s.BucketSize
          : detail::LoadLE32(data + s.Base + 4 * (bucket - s.FullBucketCount));
      }
      if (options.LoadPositions)
      {
        for (int c = 0; c < 3; ++c)
        {
          float v;
          if (level == 0)
          {
            v = detail::LoadLEFloat(rec + 4 * c);
          }
          else
          {
            const double centre = detail::LoadLEFloat(bucketCentres + 12 * bucket + 4 * c);
            v = static_cast<float>(
              (detail::LoadLE16(rec + 2 * c) - s.ScaleRange) * s.PositionStep + centre);
          }
          cloud.Positions[3 * g + c] = v;
          rowBad += !std::isfinite(v);
        }
      }
      const unsigned char* rest = rec + (level == 0 ? 12 : 6);
      if (options.LoadScales)
      {
        for (int c = 0; c < 3; ++c)
        {
          // Linear scales: log(0) = -inf and log(negative) = NaN are kept and reported.
          const float v = std::log(loadValue(rest, c));
          cloud.LogScales[3 * g + c] = v;
          rowBad += !std::isfinite(v);
        }
      }
      if (options.LoadRotations)
      {
        for (int c = 0; c < 4; ++c)
        {
          const float v = loadValue(rest, 3 + c);
          cloud.Rotations[4 * g + c] = v;
          rowBad += !std::isfinite(v);
        }
      }
      const unsigned char* rgba = rest + (level == 0 ? 28 : 14);
      if (options.LoadOpacities)
      {
        cloud.OpacityLogits[g] = logit[rgba[3]];
      }
      if (options.LoadSH)
      {
        float* out = cloud.SH.data() + 3 * std::size_t(coefficients) * g;
        for (int c = 0; c < 3; ++c)
        {
          out[c] = dc[rgba[c]];
        }
        const unsigned char* shRec = rgba + 4;
        // Band b (1..degree) holds 2b+1 coefficients per channel, channel-major, after the
        // 3 * (b^2 - 1) values of the bands before it.
        for (int band = 1; band <= degree; ++band)
        {
          const int width = 2 * band + 1;
          for (int c = 0; c < 3; ++c)
          {
            for (int k = 0; k < width; ++k)
            {
              const std::size_t index = std::size_t(3 * (band * band - 1) + c * width + k);
              float v;
              if (level == 2)
              {
                v = sh8[shRec[index]];
              }
              else
              {
                v = loadValue(shRec, index);
              }
              out[3 * (band * band + k) + c] = v;
              rowBad += !std::isfinite(v);
            }
          }
        }
      }
      badValues += rowBad;
      badRows += rowBad != 0;
    }
  }
  report.NonFiniteValues = badValues;
  report.NonFiniteGaussians = badRows;
  detail::FinishReadReport(report, name, reportOut, ", zero scales included");
  return cloud;
}

} // namespace

//------------------------------------------------------------------------------
bool IsKsplatFile(const std::string& path)
{
  try
  {
    detail::InputFile file(path);
    std::vector<unsigned char> head(MainHeaderBytes);
    if (file.Size() < MainHeaderBytes)
    {
      return false;
    }
    file.ReadAt(0, head.data(), head.size());
    const std::uint32_t maxSections = detail::LoadLE32(head.data() + 4);
    if (head[0] != 0 || head[1] < 1 || head[2] != 0 || head[3] != 0 || maxSections == 0 ||
      MainHeaderBytes + std::uint64_t(maxSections) * SectionHeaderBytes > file.Size())
    {
      return false;
    }
    head.resize(MainHeaderBytes + std::size_t(maxSections) * SectionHeaderBytes);
    file.ReadAt(MainHeaderBytes, head.data() + MainHeaderBytes, head.size() - MainHeaderBytes);
    // Sizes consistent: the sections the headers describe fill the file exactly.
    return ParseLayout(head.data(), head.size(), file.Size(), path).End == file.Size();
  }
  catch (const std::runtime_error&)
  {
    return false;
  }
}

//------------------------------------------------------------------------------
GaussianCloud ReadKsplat(const std::string& path,
  const GaussianReadOptions& options,
  GaussianReadReport* report)
{
  return detail::ParseWholeFile(ReadKsplatBytes, path, options, report);
}

//------------------------------------------------------------------------------
GaussianCloud ReadKsplatFromMemory(const void* data,
  std::size_t size,
  const std::string& name,
  const GaussianReadOptions& options,
  GaussianReadReport* report)
{
  return detail::ParseMemory(ReadKsplatBytes, data, size, name, options, report);
}

} // namespace vis4gs

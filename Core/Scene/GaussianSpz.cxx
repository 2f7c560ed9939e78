// SPDX-License-Identifier: BSD-3-Clause
// Niantic's SPZ format, versions 2, 3 and 4 (layout in Documentation/file-formats.md, "SPZ").
//   v2/v3: one gzip stream holding a 16-byte header (magic "NGSP", version, count, SH degree,
//          fractional bits, flags, reserved) and the attribute blocks one after another:
//          positions (3 x int24), alphas, colours, scales, rotations, SH, then extensions.
//   v4:    a 32-byte plain header (... numStreams, tocByteOffset), extension records up to
//          the table of contents, a TOC of (compressed, uncompressed) uint64 pairs, and one
//          zstd frame per attribute block in the same order.
#include "GaussianIO.h"
#include "GaussianMath.h"
#include "SceneFile.h"

#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace vis4gs
{

namespace
{

constexpr std::uint32_t NgspMagic = 0x5053474e; // "NGSP" little endian
constexpr std::size_t LegacyHeaderSize = 16;
constexpr std::size_t NgspHeaderSize = 32;
constexpr std::uint8_t FlagAntialiased = 0x1;
constexpr std::uint8_t FlagHasExtensions = 0x2;
constexpr double ColorScale = 0.15;
// Deflate cannot expand more than 1032:1, so a gzip file claiming more is lying. zstd can
// (runs of one byte), so for v4 the same ratio is a limit we choose, as Niantic's loader does:
// real attribute streams compress far less, and a bomb is refused before anything is
// allocated.
constexpr std::uint64_t MaxExpansion = 1032;
// Extension records of a legacy (gzip) file come after the attributes; read at most this much.
constexpr std::size_t MaxLegacyExtensionBytes = std::size_t(1) << 20;
constexpr std::uint32_t ExtensionCoordinateSystem = 0xADBE0003u;
constexpr int CoordinateRub = 4;
constexpr int CoordinateRdf = 6;
// Coefficient count per channel (without DC) for SH degrees 0..4.
constexpr int RestDims[5] = { 0, 3, 8, 15, 24 };

void StoreU32(unsigned char* p, std::uint32_t v)
{
  for (int i = 0; i < 4; ++i)
  {
    p[i] = static_cast<unsigned char>(v >> (8 * i));
  }
}

void StoreU64(unsigned char* p, std::uint64_t v)
{
  StoreU32(p, static_cast<std::uint32_t>(v));
  StoreU32(p + 4, static_cast<std::uint32_t>(v >> 32));
}

/// Sign flips that take data stored in one of SPZ's axis-flip coordinate systems (1..8:
/// LDB RDB LUB RUB LDF RDF LUF RUF) to the INRIA PLY convention RDF. (s-1) holds one bit
/// per axis: bit 0 right, bit 1 up, bit 2 front.
struct AxisFlips
{
  std::array<float, 3> Position{ { 1, 1, 1 } };
  std::array<float, 3> QuaternionXyz{ { 1, 1, 1 } };
  std::array<float, 15> Sh{};
};

AxisFlips FlipsToRdf(int system)
{
  const int s = system - 1, t = CoordinateRdf - 1;
  const float x = ((s ^ t) & 1) ? -1.f : 1.f;
  const float y = ((s ^ t) & 2) ? -1.f : 1.f;
  const float z = ((s ^ t) & 4) ? -1.f : 1.f;
  AxisFlips f;
  f.Position = { { x, y, z } };
  // A reflection of two axes is a rotation; the quaternion's vector part follows the axial
  // vector rule, w is unchanged.
  f.QuaternionXyz = { { y * z, x * z, x * y } };
  // Parity of each real SH basis function (3DGS order) under the axis flips: band 1 ~ y, z, x;
  // band 2 ~ xy, yz, 3z^2-1, xz, x^2-y^2; band 3 ~ y(3x^2-y^2), xyz, y(5z^2-1), z(5z^2-3),
  // x(5z^2-1), z(x^2-y^2), x(x^2-3y^2).
  f.Sh = { { y, z, x, x * y, y * z, 1, x * z, 1, y, x * y * z, y, z, x, z, x } };
  return f;
}

/// The parsed header and where each decompressed attribute block lies in Data.
struct PackedSpz
{
  std::uint32_t Version = 0;
  std::size_t Count = 0;
  int ShDegree = 0;
  int FractionalBits = 0;
  std::uint8_t Flags = 0;
  int CoordinateSystem = CoordinateRub;
  std::vector<unsigned char> Data;
  std::size_t Offsets[6] = {}; // positions, alphas, colours, scales, rotations, SH
  std::size_t Sizes[6] = {};
  std::vector<std::string> Warnings;
  bool Raw = false; ///< a version 2/3 payload without its gzip stream

  bool SmallestThree() const { return this->Version >= 3; }
  int RestDim() const { return RestDims[this->ShDegree]; }
  const unsigned char* Block(int i) const { return this->Data.data() + this->Offsets[i]; }
};

void SetLayout(PackedSpz& p)
{
  const std::size_t n = p.Count;
  p.Sizes[0] = 9 * n;
  p.Sizes[1] = n;
  p.Sizes[2] = 3 * n;
  p.Sizes[3] = 3 * n;
  p.Sizes[4] = (p.SmallestThree() ? 4 : 3) * n;
  p.Sizes[5] = 3 * static_cast<std::size_t>(p.RestDim()) * n;
  std::size_t at = 0;
  for (int i = 0; i < 6; ++i)
  {
    p.Offsets[i] = at;
    at += p.Sizes[i];
  }
}

std::size_t TotalSize(const PackedSpz& p)
{
  return p.Offsets[5] + p.Sizes[5];
}

/// Checks the fields shared by both header layouts (count, degree) and sets the layout.
void CheckHeader(PackedSpz& p,
  const std::string& name,
  std::uint32_t magic,
  std::uint32_t count,
  int shDegree,
  std::uint64_t compressedBytes)
{
  if (magic != NgspMagic)
  {
    throw std::runtime_error(name + ": not an SPZ file (the header's magic is not \"NGSP\")");
  }
  if (p.Version < 2 || p.Version > 4)
  {
    throw std::runtime_error(name + ": SPZ version " + std::to_string(p.Version) +
      " is not supported (versions 2, 3 and 4 are; version 1 was never released)");
  }
  if (shDegree > 4)
  {
    throw std::runtime_error(
      name + ": SH degree " + std::to_string(shDegree) + " in the SPZ header (at most 4)");
  }
  if (count == 0 || count > static_cast<std::uint32_t>(std::numeric_limits<std::int32_t>::max()))
  {
    throw std::runtime_error(name + ": invalid SPZ point count " + std::to_string(count));
  }
  p.Count = count;
  p.ShDegree = shDegree;
  SetLayout(p);
  const std::uint64_t total = TotalSize(p);
  if (total > compressedBytes * MaxExpansion)
  {
    throw std::runtime_error(name + ": the SPZ header claims " + std::to_string(count) +
      " Gaussians (" + std::to_string(total) + " bytes once decompressed) in " +
      std::to_string(compressedBytes) + " compressed bytes; more than " +
      std::to_string(MaxExpansion) +
      " times the compressed size is refused (a lying count or a decompression bomb)");
  }
}

/// Walks extension records [u32 type][u32 length][payload]; the only one that changes how the
/// data reads is Adobe's coordinate system, the others are skipped with a warning.
void ParseExtensions(PackedSpz& p, const std::string& name, const unsigned char* b, std::size_t n)
{
  std::size_t at = 0;
  while (n - at >= 8)
  {
    const std::uint32_t type = detail::LoadLE32(b + at);
    const std::uint32_t length = detail::LoadLE32(b + at + 4);
    at += 8;
    if (length > n - at)
    {
      p.Warnings.push_back(name + ": an SPZ extension record runs past the extension block; " +
        "the rest of the block is ignored");
      return;
    }
    if (type == ExtensionCoordinateSystem && length >= 4)
    {
      const std::uint32_t system = detail::LoadLE32(b + at);
      if (system > 8)
      {
        throw std::runtime_error(name + ": the SPZ data is stored in coordinate system " +
          std::to_string(system) +
          " (a rotated axis family); only the axis-flip systems 0..8 are supported");
      }
      p.CoordinateSystem = system == 0 ? CoordinateRub : static_cast<int>(system);
    }
    else
    {
      char hex[16];
      std::snprintf(hex, sizeof(hex), "0x%08x", type);
      p.Warnings.push_back(name + ": SPZ extension " + hex + " (" + std::to_string(length) +
        " bytes) is not used and was skipped");
    }
    at += length;
  }
}

/// Inflates a gzip stream: first the legacy header, then exactly the attribute blocks the
/// header announces (nothing is allocated before the count is checked), then the extension
/// records if the flags say there are some.
void InflateLegacy(PackedSpz& p, const std::string& name, const unsigned char* src, std::size_t n)
{
  z_stream zs{};
  if (inflateInit2(&zs, 16 + MAX_WBITS) != Z_OK)
  {
    throw std::runtime_error(name + ": cannot initialise zlib");
  }
  struct Guard
  {
    z_stream* S;
    ~Guard() { inflateEnd(this->S); }
  } guard{ &zs };
  zs.next_in = const_cast<Bytef*>(src);
  bool ended = false;
  // Fills out[0..size) from the stream; returns the bytes written.
  auto inflateInto = [&](unsigned char* out, std::size_t size) -> std::size_t
  {
    std::size_t done = 0;
    while (done < size && !ended)
    {
      if (zs.avail_in == 0)
      {
        const std::size_t left = n - static_cast<std::size_t>(zs.total_in);
        if (left == 0)
        {
          break;
        }
        zs.avail_in =
          static_cast<uInt>(std::min<std::size_t>(left, std::numeric_limits<uInt>::max()));
      }
      const std::size_t chunk =
        std::min<std::size_t>(size - done, std::numeric_limits<uInt>::max());
      zs.next_out = out + done;
      zs.avail_out = static_cast<uInt>(chunk);
      const int rc = inflate(&zs, Z_NO_FLUSH);
      done += chunk - zs.avail_out;
      if (rc == Z_STREAM_END)
      {
        ended = true;
      }
      else if (rc != Z_OK && rc != Z_BUF_ERROR)
      {
        throw std::runtime_error(name + ": corrupt gzip data in the SPZ file (" +
          (zs.msg ? std::string(zs.msg) : "zlib error " + std::to_string(rc)) + ")");
      }
      else if (rc == Z_BUF_ERROR && zs.avail_in == 0 && static_cast<std::size_t>(zs.total_in) >= n)
      {
        break;
      }
    }
    return done;
  };
  unsigned char header[LegacyHeaderSize];
  if (inflateInto(header, LegacyHeaderSize) != LegacyHeaderSize)
  {
    throw std::runtime_error(name + ": the SPZ gzip stream ends inside the 16-byte header");
  }
  p.Version = detail::LoadLE32(header + 4);
  p.FractionalBits = header[13];
  p.Flags = header[14];
  CheckHeader(p, name, detail::LoadLE32(header), detail::LoadLE32(header + 8), header[12], n);
  p.Data.resize(TotalSize(p));
  const std::size_t got = inflateInto(p.Data.data(), p.Data.size());
  if (got != p.Data.size())
  {
    throw std::runtime_error(name + ": the SPZ data ends early: " + std::to_string(p.Count) +
      " Gaussians need " + std::to_string(p.Data.size()) + " bytes after the header, the gzip " +
      "stream holds " + std::to_string(got));
  }
  if ((p.Flags & FlagHasExtensions) && !ended)
  {
    std::vector<unsigned char> ext(MaxLegacyExtensionBytes);
    const std::size_t e = inflateInto(ext.data(), ext.size());
    if (e == ext.size() && !ended)
    {
      p.Warnings.push_back(name + ": SPZ extension records beyond the first " +
        std::to_string(MaxLegacyExtensionBytes) + " bytes are ignored");
    }
    ParseExtensions(p, name, ext.data(), e);
  }
}

void DecompressNgsp(PackedSpz& p, const std::string& name, const unsigned char* src, std::size_t n)
{
  if (n < NgspHeaderSize)
  {
    throw std::runtime_error(name + ": SPZ v4 file shorter than its 32-byte header");
  }
  p.Version = detail::LoadLE32(src + 4);
  p.FractionalBits = src[13];
  p.Flags = src[14];
  const int numStreams = src[15];
  const std::uint64_t toc = detail::LoadLE32(src + 16);
  CheckHeader(p, name, detail::LoadLE32(src), detail::LoadLE32(src + 8), src[12], n);
  const int expectedStreams = p.ShDegree > 0 ? 6 : 5;
  if (numStreams != expectedStreams)
  {
    throw std::runtime_error(name + ": the SPZ header lists " + std::to_string(numStreams) +
      " streams, SH degree " + std::to_string(p.ShDegree) + " needs " +
      std::to_string(expectedStreams));
  }
  if (toc < NgspHeaderSize || toc + 16 * std::uint64_t(numStreams) > n)
  {
    throw std::runtime_error(name + ": the SPZ table of contents (offset " + std::to_string(toc) +
      ", " + std::to_string(numStreams) + " entries) lies outside the file of " +
      std::to_string(n) + " bytes");
  }
  std::uint64_t at = toc + 16 * std::uint64_t(numStreams);
  std::uint64_t compressed[6] = {};
  for (int i = 0; i < numStreams; ++i)
  {
    compressed[i] = detail::LoadLE64(src + toc + 16 * i);
    const std::uint64_t raw = detail::LoadLE64(src + toc + 16 * i + 8);
    if (raw != p.Sizes[i])
    {
      throw std::runtime_error(name + ": SPZ stream " + std::to_string(i) + " claims " +
        std::to_string(raw) + " bytes, " + std::to_string(p.Count) + " Gaussians need " +
        std::to_string(p.Sizes[i]));
    }
    if (compressed[i] > n - at)
    {
      throw std::runtime_error(name + ": SPZ stream " + std::to_string(i) + " (" +
        std::to_string(compressed[i]) + " bytes at offset " + std::to_string(at) +
        ") runs past the end of the file (" + std::to_string(n) + " bytes)");
    }
    at += compressed[i];
  }
  if (at != n)
  {
    throw std::runtime_error(name + ": " + std::to_string(n - at) +
      " bytes after the last SPZ stream (the table of contents does not describe this file)");
  }
  if (p.Flags & FlagHasExtensions)
  {
    ParseExtensions(p, name, src + NgspHeaderSize, static_cast<std::size_t>(toc) - NgspHeaderSize);
  }
  p.Data.resize(TotalSize(p));
  at = toc + 16 * std::uint64_t(numStreams);
  for (int i = 0; i < numStreams; ++i)
  {
    // The destination has the announced size, so a frame that inflates to more fails here
    // instead of growing anything.
    const std::size_t r = ZSTD_decompress(
      p.Data.data() + p.Offsets[i], p.Sizes[i], src + at, static_cast<std::size_t>(compressed[i]));
    if (ZSTD_isError(r) || r != p.Sizes[i])
    {
      throw std::runtime_error(name + ": SPZ stream " + std::to_string(i) +
        " does not decompress to " + std::to_string(p.Sizes[i]) + " bytes (" +
        (ZSTD_isError(r) ? std::string(ZSTD_getErrorName(r)) : std::to_string(r) + " bytes") + ")");
    }
    at += compressed[i];
  }
}

/// Versions 2 and 3 without the gzip stream (the "raw" SPZ some tools write and
/// splat-transform reads): the 16-byte header, the attribute blocks, the extension records.
void ReadRawLegacy(PackedSpz& p, const std::string& name, const unsigned char* src, std::size_t n)
{
  if (n < LegacyHeaderSize)
  {
    throw std::runtime_error(name + ": raw SPZ file shorter than its 16-byte header");
  }
  p.Version = detail::LoadLE32(src + 4);
  p.FractionalBits = src[13];
  p.Flags = src[14];
  CheckHeader(p, name, detail::LoadLE32(src), detail::LoadLE32(src + 8), src[12], n);
  const std::size_t total = TotalSize(p);
  if (n - LegacyHeaderSize < total)
  {
    throw std::runtime_error(name + ": the raw SPZ data ends early: " + std::to_string(p.Count) +
      " Gaussians need " + std::to_string(total) + " bytes after the header, the file holds " +
      std::to_string(n - LegacyHeaderSize));
  }
  p.Data.assign(src + LegacyHeaderSize, src + LegacyHeaderSize + total);
  if (p.Flags & FlagHasExtensions)
  {
    ParseExtensions(p, name, src + LegacyHeaderSize + total, n - LegacyHeaderSize - total);
  }
  p.Raw = true;
}

PackedSpz Unpack(const unsigned char* src, std::size_t n, const std::string& name)
{
  PackedSpz p;
  if (n >= 2 && src[0] == 0x1f && src[1] == 0x8b)
  {
    InflateLegacy(p, name, src, n);
  }
  else if (n >= 8 && detail::LoadLE32(src) == NgspMagic && detail::LoadLE32(src + 4) < 4)
  {
    ReadRawLegacy(p, name, src, n);
  }
  else if (n >= 4 && detail::LoadLE32(src) == NgspMagic)
  {
    DecompressNgsp(p, name, src, n);
  }
  else
  {
    throw std::runtime_error(
      name + ": not an SPZ file (neither a gzip stream nor an \"NGSP\" header)");
  }
  return p;
}

// ---- Per-attribute decoding, shared by the reader and the writer's error report. ----------

float DecodePosition(const unsigned char* b, int fractionalBits)
{
  std::int32_t v = std::int32_t(b[0]) | (std::int32_t(b[1]) << 8) | (std::int32_t(b[2]) << 16);
  if (v & 0x800000)
  {
    v -= 0x1000000;
  }
  return static_cast<float>(std::ldexp(static_cast<double>(v), -fractionalBits));
}

float DecodeLogScale(unsigned char b)
{
  return static_cast<float>(b / 16.0 - 10.0);
}

float DecodeOpacityLogit(unsigned char b)
{
  // Niantic's decoder gives +-inf for bytes 0 and 255; splat-transform clamps to (1e-6,
  // 1-1e-6). The clamp keeps readings finite and differs from the limit by < 1e-6 in opacity.
  const double a = std::min(std::max(b / 255.0, 1e-6), 1.0 - 1e-6);
  return static_cast<float>(std::log(a / (1.0 - a)));
}

float DecodeColor(unsigned char b)
{
  return static_cast<float>((b / 255.0 - 0.5) / ColorScale);
}

float DecodeSh(unsigned char b)
{
  return static_cast<float>((b - 128) / 128.0);
}

/// Decodes one rotation to (w, x, y, z) in the stored axes.
void DecodeRotation(const unsigned char* b, bool smallestThree, double q[4])
{
  double xyzw[4];
  if (smallestThree)
  {
    std::uint32_t comp = detail::LoadLE32(b);
    const int largest = static_cast<int>(comp >> 30);
    double sum = 0;
    for (int i = 3; i >= 0; --i)
    {
      if (i != largest)
      {
        const double mag = static_cast<double>(comp & 511u) / 511.0 * std::sqrt(0.5);
        xyzw[i] = (comp >> 9) & 1u ? -mag : mag;
        sum += xyzw[i] * xyzw[i];
        comp >>= 10;
      }
    }
    xyzw[largest] = std::sqrt(std::max(0.0, 1.0 - sum));
  }
  else
  {
    double sum = 0;
    for (int i = 0; i < 3; ++i)
    {
      xyzw[i] = b[i] / 127.5 - 1.0;
      sum += xyzw[i] * xyzw[i];
    }
    xyzw[3] = std::sqrt(std::max(0.0, 1.0 - sum));
  }
  q[0] = xyzw[3];
  q[1] = xyzw[0];
  q[2] = xyzw[1];
  q[3] = xyzw[2];
}

/// Decodes Gaussian @p g of @p p into the arrays of @p cloud that are allocated.
void DecodeGaussian(const PackedSpz& p,
  const AxisFlips& f,
  std::size_t g,
  int restOut,
  GaussianCloud& cloud)
{
  if (!cloud.Positions.empty())
  {
    const unsigned char* b = p.Block(0) + 9 * g;
    for (int c = 0; c < 3; ++c)
    {
      cloud.Positions[3 * g + c] = f.Position[c] * DecodePosition(b + 3 * c, p.FractionalBits);
    }
  }
  if (!cloud.OpacityLogits.empty())
  {
    cloud.OpacityLogits[g] = DecodeOpacityLogit(p.Block(1)[g]);
  }
  if (!cloud.LogScales.empty())
  {
    for (int c = 0; c < 3; ++c)
    {
      cloud.LogScales[3 * g + c] = DecodeLogScale(p.Block(3)[3 * g + c]);
    }
  }
  if (!cloud.Rotations.empty())
  {
    double q[4];
    const std::size_t size = p.SmallestThree() ? 4 : 3;
    DecodeRotation(p.Block(4) + size * g, p.SmallestThree(), q);
    cloud.Rotations[4 * g] = static_cast<float>(q[0]);
    for (int c = 0; c < 3; ++c)
    {
      cloud.Rotations[4 * g + 1 + c] = f.QuaternionXyz[c] * static_cast<float>(q[1 + c]);
    }
  }
  if (!cloud.SH.empty())
  {
    const std::size_t k = static_cast<std::size_t>(restOut) + 1;
    float* sh = &cloud.SH[3 * k * g];
    for (int c = 0; c < 3; ++c)
    {
      sh[c] = DecodeColor(p.Block(2)[3 * g + c]);
    }
    // Stored coefficient-major with RGB inner, like GaussianCloud::SH without the DC term.
    const unsigned char* b = p.Block(5) + 3 * static_cast<std::size_t>(p.RestDim()) * g;
    for (int j = 0; j < restOut; ++j)
    {
      for (int c = 0; c < 3; ++c)
      {
        sh[3 * (j + 1) + c] = f.Sh[j] * DecodeSh(b[3 * j + c]);
      }
    }
  }
}

//------------------------------------------------------------------------------
GaussianCloud ReadSpzBytes(const unsigned char* data,
  std::size_t size,
  const std::string& name,
  const GaussianReadOptions& options,
  GaussianReadReport* reportOut)
{
  if (!options.IdProperty.empty())
  {
    throw std::runtime_error(
      name + ": an SPZ file has no id property '" + options.IdProperty + "'");
  }
  const PackedSpz p = Unpack(data, size, name);
  GaussianReadReport report;
  report.Format = "spz v" + std::to_string(p.Version) + (p.Raw ? " raw" : "");
  report.FileShDegree = p.ShDegree;
  report.Warnings = p.Warnings;
  if (p.Flags & FlagAntialiased)
  {
    report.Format += " antialiased";
    report.RenderMode = "antialiased";
    report.Warnings.push_back(name + ": the SPZ file says its Gaussians were trained with " +
      "antialiasing (Mip-Splatting's 2D filter); Vis4GS draws them as the INRIA renderer does");
  }
  const int degree = std::min({ p.ShDegree, std::max(0, options.MaxShDegree), 3 });
  const std::size_t n = p.Count;
  GaussianCloud cloud = detail::AllocateReadArrays(n, degree, options);
  const AxisFlips flips = FlipsToRdf(p.CoordinateSystem);
  const int restOut = cloud.ShCoefficientCount() - 1;
#pragma omp parallel for schedule(static) if (n > 65536)
  for (long long g = 0; g < static_cast<long long>(n); ++g)
  {
    DecodeGaussian(p, flips, static_cast<std::size_t>(g), restOut, cloud);
  }
  if (reportOut)
  {
    *reportOut = std::move(report);
  }
  return cloud;
}

// ---- Writer ---------------------------------------------------------------------------------

unsigned char ToByte(double v)
{
  return static_cast<unsigned char>(std::min(255.0, std::max(0.0, std::round(v))));
}

unsigned char QuantizeSh(double x, int bits)
{
  const int bucket = 1 << (8 - bits);
  const double q = std::round(x * 128.0) + 128.0;
  if (!(q > 0))
  {
    return 0;
  }
  const long long b = (static_cast<long long>(std::min(q, 1024.0)) + bucket / 2) / bucket * bucket;
  return static_cast<unsigned char>(std::min(255LL, b));
}

/// Smallest-three encoding of a unit quaternion given as (x, y, z, w).
void PackSmallestThree(const double xyzw[4], unsigned char out[4])
{
  int largest = 0;
  for (int i = 1; i < 4; ++i)
  {
    if (std::fabs(xyzw[i]) > std::fabs(xyzw[largest]))
    {
      largest = i;
    }
  }
  const bool negate = xyzw[largest] < 0;
  std::uint32_t comp = static_cast<std::uint32_t>(largest);
  for (int i = 0; i < 4; ++i)
  {
    if (i != largest)
    {
      const std::uint32_t neg = (xyzw[i] < 0) != negate;
      const double m = std::min(1.0, std::fabs(xyzw[i]) / std::sqrt(0.5));
      const std::uint32_t mag = static_cast<std::uint32_t>(std::lround(511.0 * m));
      comp = (comp << 10) | (neg << 9) | mag;
    }
  }
  StoreU32(out, comp);
}

void Accumulate(SpzAttributeError& e, double d, std::size_t& count)
{
  d = std::fabs(d);
  e.Max = std::max(e.Max, d);
  e.Rms += d * d; // sum of squares until Finish
  ++count;
}

void Finish(SpzAttributeError& e, std::size_t count)
{
  e.Rms = count ? std::sqrt(e.Rms / static_cast<double>(count)) : 0.0;
}

} // namespace

//------------------------------------------------------------------------------
bool IsSpzFile(const std::string& path)
{
  try
  {
    detail::InputFile file(path);
    unsigned char b[4] = {};
    const std::size_t n = file.ReadSomeAt(0, b, 4);
    return (n >= 2 && b[0] == 0x1f && b[1] == 0x8b) || (n == 4 && detail::LoadLE32(b) == NgspMagic);
  }
  catch (const std::runtime_error&)
  {
    return false;
  }
}

//------------------------------------------------------------------------------
GaussianCloud ReadSpz(const std::string& path,
  const GaussianReadOptions& options,
  GaussianReadReport* report)
{
  return detail::ParseWholeFile(ReadSpzBytes, path, options, report);
}

//------------------------------------------------------------------------------
GaussianCloud ReadSpzFromMemory(const void* data,
  std::size_t size,
  const std::string& name,
  const GaussianReadOptions& options,
  GaussianReadReport* report)
{
  return detail::ParseMemory(ReadSpzBytes, data, size, name, options, report);
}

//------------------------------------------------------------------------------
std::vector<unsigned char> WriteSpzToMemory(const GaussianCloud& cloud,
  const SpzWriteOptions& options,
  SpzWriteReport* reportOut)
{
  const std::size_t k = static_cast<std::size_t>(cloud.ShCoefficientCount());
  if (cloud.Positions.size() != 3 * cloud.Count || cloud.LogScales.size() != 3 * cloud.Count ||
    cloud.Rotations.size() != 4 * cloud.Count || cloud.OpacityLogits.size() != cloud.Count ||
    cloud.SH.size() != 3 * k * cloud.Count || cloud.ShDegree < 0 || cloud.ShDegree > 3)
  {
    throw std::invalid_argument("WriteSpz: the cloud must hold every parameter array");
  }
  if (options.Sh1Bits < 1 || options.Sh1Bits > 8 || options.ShRestBits < 1 ||
    options.ShRestBits > 8)
  {
    throw std::invalid_argument("WriteSpz: SH bits must be 1..8");
  }
  SpzWriteReport report;
  // Same rule as the .splat writer (Documentation/special-values.md): what the reference draws
  // keeps its meaning, what it has no answer for (or non-finite SH that would be written) is
  // left out and counted. A position beyond 24-bit fixed point at 0 fractional bits
  // (|x| >= 2^23) cannot be stored either.
  std::vector<std::size_t> kept;
  kept.reserve(cloud.Count);
  double maxAbs = 0;
  for (std::size_t g = 0; g < cloud.Count; ++g)
  {
    bool ok = detail::WritableGaussian(cloud, g, k);
    double m = 0;
    for (int c = 0; ok && c < 3; ++c)
    {
      m = std::max(m, std::fabs(static_cast<double>(cloud.Positions[3 * g + c])));
    }
    if (ok && m >= 8388607.0)
    {
      ++report.OutOfRange;
      ok = false;
    }
    if (ok)
    {
      kept.push_back(g);
      maxAbs = std::max(maxAbs, m);
    }
  }
  const std::size_t n = kept.size();
  report.Written = n;
  report.LeftOut = cloud.Count - n;
  if (n == 0)
  {
    throw std::runtime_error("WriteSpz: no Gaussian can be written (" +
      std::to_string(cloud.Count) + " given, " + std::to_string(report.LeftOut) +
      " left out); an SPZ file cannot hold zero Gaussians");
  }
  // The most fractional bits for which every coordinate fits in a signed 24-bit integer
  // (Niantic's writer always uses 12, ~0.24 mm; readers take the header's value).
  int fb = options.FractionalBits;
  if (fb < 0)
  {
    fb = 23;
    while (fb > 0 && std::round(std::ldexp(maxAbs, fb)) > 8388607.0)
    {
      --fb;
    }
  }
  else if (fb > 23 || std::round(std::ldexp(maxAbs, fb)) > 8388607.0)
  {
    throw std::invalid_argument("WriteSpz: positions up to " + std::to_string(maxAbs) +
      " do not fit 24-bit fixed point with " + std::to_string(fb) + " fractional bits");
  }
  report.FractionalBits = fb;

  PackedSpz p;
  p.Version = 4;
  p.Count = n;
  p.ShDegree = cloud.ShDegree;
  p.FractionalBits = fb;
  p.Flags = options.Antialiased ? FlagAntialiased : 0;
  SetLayout(p);
  p.Data.assign(TotalSize(p), 0);
  // Stored in RUB, the format's default; the flips are their own inverse.
  const AxisFlips f = FlipsToRdf(CoordinateRub);
  const int rest = p.RestDim();
#pragma omp parallel for schedule(static) if (n > 65536)
  for (long long r = 0; r < static_cast<long long>(n); ++r)
  {
    const std::size_t g = kept[static_cast<std::size_t>(r)];
    unsigned char* pos = p.Data.data() + p.Offsets[0] + 9 * r;
    for (int c = 0; c < 3; ++c)
    {
      const auto v = static_cast<std::int32_t>(std::round(
        std::ldexp(static_cast<double>(f.Position[c] * cloud.Positions[3 * g + c]), fb)));
      pos[3 * c] = static_cast<unsigned char>(v & 0xff);
      pos[3 * c + 1] = static_cast<unsigned char>((v >> 8) & 0xff);
      pos[3 * c + 2] = static_cast<unsigned char>((v >> 16) & 0xff);
    }
    p.Data[p.Offsets[1] + r] = ToByte(Sigmoid(static_cast<double>(cloud.OpacityLogits[g])) * 255.0);
    const float* sh = &cloud.SH[3 * k * g];
    for (int c = 0; c < 3; ++c)
    {
      p.Data[p.Offsets[2] + 3 * r + c] = ToByte(sh[c] * (ColorScale * 255.0) + 127.5);
      // -inf (a point) becomes the smallest storable log-scale, -10.
      p.Data[p.Offsets[3] + 3 * r + c] = ToByte((cloud.LogScales[3 * g + c] + 10.0) * 16.0);
    }
    const float* q = &cloud.Rotations[4 * g];
    const double norm = std::sqrt(
      double(q[0]) * q[0] + double(q[1]) * q[1] + double(q[2]) * q[2] + double(q[3]) * q[3]);
    // The zero quaternion means the identity to the reference renderer.
    double xyzw[4] = { 0, 0, 0, 1 };
    if (norm > 0)
    {
      for (int c = 0; c < 3; ++c)
      {
        xyzw[c] = f.QuaternionXyz[c] * q[1 + c] / norm;
      }
      xyzw[3] = q[0] / norm;
    }
    PackSmallestThree(xyzw, p.Data.data() + p.Offsets[4] + 4 * r);
    unsigned char* out = p.Data.data() + p.Offsets[5] + 3 * static_cast<std::size_t>(rest) * r;
    for (int j = 0; j < rest; ++j)
    {
      for (int c = 0; c < 3; ++c)
      {
        out[3 * j + c] =
          QuantizeSh(f.Sh[j] * sh[3 * (j + 1) + c], j < 3 ? options.Sh1Bits : options.ShRestBits);
      }
    }
  }

  // Quantisation error against the source: decode what was written, as a reader will.
  {
    GaussianCloud back;
    back.Count = n;
    back.ShDegree = cloud.ShDegree;
    back.Positions.resize(3 * n);
    back.LogScales.resize(3 * n);
    back.Rotations.resize(4 * n);
    back.OpacityLogits.resize(n);
    back.SH.resize(3 * k * n);
    for (std::size_t r = 0; r < n; ++r)
    {
      DecodeGaussian(p, f, r, rest, back);
    }
    std::size_t cPos = 0, cScale = 0, cRot = 0, cOpa = 0, cDc = 0, cSh = 0;
    for (std::size_t r = 0; r < n; ++r)
    {
      const std::size_t g = kept[r];
      for (int c = 0; c < 3; ++c)
      {
        Accumulate(report.Position, back.Positions[3 * r + c] - cloud.Positions[3 * g + c], cPos);
        const float s = cloud.LogScales[3 * g + c];
        if (std::isfinite(s))
        {
          Accumulate(report.LogScale, back.LogScales[3 * r + c] - s, cScale);
        }
        else
        {
          ++report.SpecialValues;
        }
        Accumulate(report.Color, back.SH[3 * k * r + c] - cloud.SH[3 * k * g + c], cDc);
      }
      for (std::size_t j = 3; j < 3 * k; ++j)
      {
        Accumulate(report.SH, back.SH[3 * k * r + j] - cloud.SH[3 * k * g + j], cSh);
      }
      const double logit = cloud.OpacityLogits[g];
      report.SpecialValues += std::isinf(logit);
      Accumulate(
        report.Opacity, Sigmoid(static_cast<double>(back.OpacityLogits[r])) - Sigmoid(logit), cOpa);
      const auto qs = NormalizeQuaternion(&cloud.Rotations[4 * g]);
      if (qs[0] == 0 && qs[1] == 0 && qs[2] == 0 && qs[3] == 0)
      {
        ++report.SpecialValues;
        continue;
      }
      // q and -q are the same rotation.
      double dot = 0;
      for (int c = 0; c < 4; ++c)
      {
        dot += qs[c] * back.Rotations[4 * r + c];
      }
      const double sign = dot < 0 ? -1.0 : 1.0;
      for (int c = 0; c < 4; ++c)
      {
        Accumulate(report.Rotation, sign * back.Rotations[4 * r + c] - qs[c], cRot);
      }
    }
    Finish(report.Position, cPos);
    Finish(report.LogScale, cScale);
    Finish(report.Rotation, cRot);
    Finish(report.Opacity, cOpa);
    Finish(report.Color, cDc);
    Finish(report.SH, cSh);
  }

  const int numStreams = rest > 0 ? 6 : 5;
  // One zstd frame per stream, compressed in parallel as Niantic's writer does.
  std::vector<std::vector<unsigned char>> frames(static_cast<std::size_t>(numStreams));
  std::vector<std::size_t> results(static_cast<std::size_t>(numStreams));
#pragma omp parallel for schedule(dynamic, 1)
  for (int i = 0; i < numStreams; ++i)
  {
    frames[i].resize(ZSTD_compressBound(p.Sizes[i]));
    results[i] =
      ZSTD_compress(frames[i].data(), frames[i].size(), p.Block(i), p.Sizes[i], options.ZstdLevel);
  }
  for (int i = 0; i < numStreams; ++i)
  {
    if (ZSTD_isError(results[i]))
    {
      throw std::runtime_error(
        std::string("WriteSpz: zstd compression failed: ") + ZSTD_getErrorName(results[i]));
    }
    frames[i].resize(results[i]);
  }
  std::vector<unsigned char> out(NgspHeaderSize + 16 * static_cast<std::size_t>(numStreams), 0);
  StoreU32(out.data(), NgspMagic);
  StoreU32(out.data() + 4, 4);
  StoreU32(out.data() + 8, static_cast<std::uint32_t>(n));
  out[12] = static_cast<unsigned char>(p.ShDegree);
  out[13] = static_cast<unsigned char>(fb);
  out[14] = p.Flags;
  out[15] = static_cast<unsigned char>(numStreams);
  StoreU32(out.data() + 16, static_cast<std::uint32_t>(NgspHeaderSize));
  for (int i = 0; i < numStreams; ++i)
  {
    StoreU64(out.data() + NgspHeaderSize + 16 * i, frames[i].size());
    StoreU64(out.data() + NgspHeaderSize + 16 * i + 8, p.Sizes[i]);
  }
  for (const auto& frame : frames)
  {
    out.insert(out.end(), frame.begin(), frame.end());
  }
  report.FileBytes = out.size();
  if (reportOut)
  {
    *reportOut = report;
  }
  return out;
}

//------------------------------------------------------------------------------
SpzWriteReport WriteSpz(const std::string& path,
  const GaussianCloud& cloud,
  const SpzWriteOptions& options)
{
  SpzWriteReport report;
  const std::vector<unsigned char> bytes = WriteSpzToMemory(cloud, options, &report);
  detail::WriteFileAtomically(
    path, [&](std::FILE* f) { detail::WriteBytes(f, bytes.data(), bytes.size(), path); });
  return report;
}

//------------------------------------------------------------------------------
std::string DescribeQuantisation(const SpzWriteReport& report)
{
  const std::vector<QuantisationError> errors = {
    { "position", report.Position.Max, report.Position.Rms, report.Written },
    { "log-scale", report.LogScale.Max, report.LogScale.Rms, report.Written },
    { "rotation (components)", report.Rotation.Max, report.Rotation.Rms, report.Written },
    { "opacity (alpha)", report.Opacity.Max, report.Opacity.Rms, report.Written },
    { "colour (SH DC)", report.Color.Max, report.Color.Rms, report.Written },
    { "SH", report.SH.Max, report.SH.Rms, report.Written },
  };
  std::string s = "SPZ v4, " + detail::DescribeWriteErrors(report.Written, report.LeftOut, errors);
  if (report.OutOfRange)
  {
    s +=
      "; " + std::to_string(report.OutOfRange) + " of those left out beyond 2^23 in a coordinate";
  }
  if (report.SpecialValues)
  {
    s += "; " + std::to_string(report.SpecialValues) +
      " drawable special values kept with their meaning";
  }
  return s;
}

} // namespace vis4gs

// SPDX-License-Identifier: BSD-3-Clause
// The PlayCanvas / SuperSplat "compressed PLY" (Documentation/file-formats.md): a binary PLY
// with an element `chunk` (12 or 18 float32 per chunk of 256 Gaussians: position, log-scale and
// optionally colour bounds), an element `vertex` of four uint32 (11-10-11 position, 2-10-10-10
// smallest-three rotation, 11-10-11 log-scale, 8-8-8-8 colour and opacity) and an optional
// element `sh` of uint8 f_rest_* (channel-major, as the trainer's PLY). The arithmetic follows
// splat-transform 3.2 (src/lib/readers/decompress-ply.ts, src/lib/writers/compressed-chunk.ts):
// decoding is done in double and rounded once to float32, as its Float32Array columns are.
#include "GaussianIO.h"
#include "GaussianMath.h"
#include "PlyHeader.h"
#include "SceneFile.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <functional>
#include <numeric>
#include <stdexcept>

namespace vis4gs
{

namespace
{

using detail::ByteSource;
using detail::PlyElement;
using detail::PlyHeader;

constexpr std::size_t ChunkSize = 256;
/// The format's clamp of log-scale bounds (a scale below e^-20 is written as e^-20).
constexpr double LogScaleLimit = 20.0;
constexpr const char* ChunkNames[18] = { "min_x",
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
  "max_scale_z",
  "min_r",
  "min_g",
  "min_b",
  "max_r",
  "max_g",
  "max_b" };
constexpr const char* PackedNames[4] = { "packed_position",
  "packed_rotation",
  "packed_scale",
  "packed_color" };

[[noreturn]] void Fail(const std::string& name, const std::string& what)
{
  throw std::runtime_error(name + ": " + what);
}

//------------------------------------------------------------------------------
// Decoding, shared by the reader and the writer's error report.
double UnpackUnorm(std::uint32_t v, int bits)
{
  const std::uint32_t t = (1u << bits) - 1u;
  return static_cast<double>(v & t) / static_cast<double>(t);
}

double Lerp(double a, double b, double t)
{
  return a * (1.0 - t) + b * t;
}

/// Unpacks 2-10-10-10 smallest-three: the top 2 bits index the largest component (in file
/// order rot_0..rot_3, i.e. w x y z), the others are stored in order as (v/1023 - 0.5)*sqrt(2).
std::array<double, 4> UnpackRotation(std::uint32_t v)
{
  const double norm = 1.0 / (std::sqrt(2.0) * 0.5);
  const double a = (UnpackUnorm(v >> 20, 10) - 0.5) * norm;
  const double b = (UnpackUnorm(v >> 10, 10) - 0.5) * norm;
  const double c = (UnpackUnorm(v, 10) - 0.5) * norm;
  const double m = std::sqrt(std::max(0.0, 1.0 - (a * a + b * b + c * c)));
  switch (v >> 30)
  {
    case 0:
      return { m, a, b, c };
    case 1:
      return { a, m, b, c };
    case 2:
      return { a, b, m, c };
    default:
      return { a, b, c, m };
  }
}

/// Opacity logit of an 8-bit alpha: -log(1/w - 1), so 0 -> -inf and 255 -> +inf.
double AlphaLogit(std::uint32_t byte)
{
  const double w = UnpackUnorm(byte, 8);
  return -std::log(1.0 / w - 1.0);
}

/// f_rest of an 8-bit SH byte: 0 and 255 are the ends of [-4, 4], others bucket centres.
double ShValue(std::uint32_t byte)
{
  const double n = byte == 0 ? 0.0 : byte == 255 ? 1.0 : (byte + 0.5) / 256.0;
  return (n - 0.5) * 8.0;
}

/// One decoded Gaussian (double; the reader rounds each value to float32 once).
struct Decoded
{
  double Position[3];
  double LogScale[3];
  std::array<double, 4> Rotation;
  double Dc[3];
  std::uint32_t AlphaByte;
};

void DecodeGaussian(const float* chunk, bool hasColor, const std::uint32_t packed[4], Decoded& d)
{
  const std::uint32_t p = packed[0], s = packed[2], c = packed[3];
  const double pt[3] = { UnpackUnorm(p >> 21, 11), UnpackUnorm(p >> 11, 10), UnpackUnorm(p, 11) };
  const double st[3] = { UnpackUnorm(s >> 21, 11), UnpackUnorm(s >> 11, 10), UnpackUnorm(s, 11) };
  const double ct[3] = { UnpackUnorm(c >> 24, 8), UnpackUnorm(c >> 16, 8), UnpackUnorm(c >> 8, 8) };
  for (int k = 0; k < 3; ++k)
  {
    d.Position[k] = Lerp(chunk[k], chunk[3 + k], pt[k]);
    d.LogScale[k] = Lerp(chunk[6 + k], chunk[9 + k], st[k]);
    const double col = hasColor ? Lerp(chunk[12 + k], chunk[15 + k], ct[k]) : ct[k];
    d.Dc[k] = (col - 0.5) / sh::C0;
  }
  d.Rotation = UnpackRotation(packed[1]);
  d.AlphaByte = c & 0xffu;
}

//------------------------------------------------------------------------------
std::uint32_t LoadU32(const unsigned char* p, bool swap)
{
  std::uint32_t v;
  std::memcpy(&v, p, 4);
  return swap ? detail::ByteSwap32(v) : v;
}

float LoadF32(const unsigned char* p, bool swap)
{
  const std::uint32_t bits = LoadU32(p, swap);
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

const detail::PlyProperty* FindProperty(const PlyElement& e, const std::string& name)
{
  for (const auto& p : e.Properties)
  {
    if (p.Name == name)
    {
      return &p;
    }
  }
  return nullptr;
}

const PlyElement* FindElement(const PlyHeader& h, const char* name)
{
  for (const auto& e : h.Elements)
  {
    if (e.Name == name)
    {
      return &e;
    }
  }
  return nullptr;
}

bool LooksCompressed(const PlyHeader& h)
{
  const PlyElement* chunk = FindElement(h, "chunk");
  const PlyElement* vertex = FindElement(h, "vertex");
  return chunk && vertex && FindProperty(*vertex, "packed_position");
}

/// Where everything lies in the file, checked against its size before anything is allocated.
struct Layout
{
  PlyHeader Header;
  const PlyElement* Chunk = nullptr;
  const PlyElement* Vertex = nullptr;
  const PlyElement* Sh = nullptr;
  std::uint64_t ChunkOffset = 0, VertexOffset = 0, ShOffset = 0;
  bool HasColor = false;
  std::size_t ChunkProp[18] = {};
  std::size_t PackedProp[4] = {};
  int FileShDegree = 0;
  std::vector<std::size_t> ShProp; ///< offsets of f_rest_0.. in an sh row
  bool Swap = false;
};

Layout ParseLayout(const ByteSource& src)
{
  const std::string& name = src.Name;
  std::vector<unsigned char> headBuffer;
  const unsigned char* head = src.Memory;
  const std::size_t headSize =
    static_cast<std::size_t>(std::min<std::uint64_t>(src.Size, detail::MaxPlyHeaderBytes));
  if (!src.Memory)
  {
    headBuffer.resize(headSize);
    src.File->ReadAt(0, headBuffer.data(), headSize);
    head = headBuffer.data();
  }
  Layout l;
  l.Header = detail::ParsePlyHeader(head, headSize, name);
  const PlyHeader& h = l.Header;
  if (!LooksCompressed(h))
  {
    Fail(name, "not a compressed PLY (no 'chunk' element and 'packed_position' vertex property)");
  }
  if (h.Format == PlyFormat::Ascii)
  {
    Fail(name, "a compressed PLY must be binary; this one is ASCII");
  }
  l.Swap = (h.Format == PlyFormat::BinaryBigEndian) == detail::HostIsLittleEndian();
  l.Chunk = FindElement(h, "chunk");
  l.Vertex = FindElement(h, "vertex");
  l.Sh = FindElement(h, "sh");
  const std::uint64_t n = l.Vertex->Count;
  const std::uint64_t chunksNeeded = n / ChunkSize + (n % ChunkSize != 0);
  if (l.Chunk->Count != chunksNeeded)
  {
    Fail(name,
      "the header's counts disagree: " + std::to_string(n) + " Gaussians need " +
        std::to_string(chunksNeeded) + " chunks of 256, the chunk element declares " +
        std::to_string(l.Chunk->Count));
  }
  // Offsets of the elements in file order; a list property would make rows variable-sized.
  const std::uint64_t available = src.Size - h.Bytes;
  std::uint64_t offset = h.Bytes;
  for (const PlyElement& e : h.Elements)
  {
    if (e.HasList)
    {
      Fail(name, "element '" + e.Name + "' has a list property; a compressed PLY has none");
    }
    std::uint64_t bytes = 0;
    if (__builtin_mul_overflow(e.Count, static_cast<std::uint64_t>(e.RowSize), &bytes) ||
      bytes > available || offset - h.Bytes > available - bytes)
    {
      Fail(name,
        "truncated or lying header: element '" + e.Name + "' declares " + std::to_string(e.Count) +
          " rows of " + std::to_string(e.RowSize) + " bytes, more than the " +
          std::to_string(available) + " bytes after the header");
    }
    if (&e == l.Chunk)
    {
      l.ChunkOffset = offset;
    }
    else if (&e == l.Vertex)
    {
      l.VertexOffset = offset;
    }
    else if (&e == l.Sh)
    {
      l.ShOffset = offset;
    }
    offset += bytes;
  }
  // chunk: 12 bounds, plus 6 colour bounds when present (all or none), float32.
  int colorProps = 0;
  for (int k = 0; k < 18; ++k)
  {
    const auto* p = FindProperty(*l.Chunk, ChunkNames[k]);
    if (!p)
    {
      if (k < 12)
      {
        Fail(name, std::string("chunk element lacks property '") + ChunkNames[k] + "'");
      }
      continue;
    }
    if (p->Type != ScalarType::Float32)
    {
      Fail(name, std::string("chunk property '") + ChunkNames[k] + "' must be float");
    }
    l.ChunkProp[k] = p->Offset;
    colorProps += k >= 12;
  }
  if (colorProps != 0 && colorProps != 6)
  {
    Fail(name, "chunk element has " + std::to_string(colorProps) + " of the 6 colour bounds");
  }
  l.HasColor = colorProps == 6;
  for (int k = 0; k < 4; ++k)
  {
    const auto* p = FindProperty(*l.Vertex, PackedNames[k]);
    if (!p || p->Type != ScalarType::UInt32)
    {
      Fail(name, std::string("vertex element lacks uint property '") + PackedNames[k] + "'");
    }
    l.PackedProp[k] = p->Offset;
  }
  if (l.Sh)
  {
    const std::size_t props = l.Sh->Properties.size();
    l.FileShDegree = props == 9 ? 1 : props == 24 ? 2 : props == 45 ? 3 : -1;
    if (l.FileShDegree < 0)
    {
      Fail(name,
        "sh element has " + std::to_string(props) + " properties; degree 1, 2, 3 need 9, 24, 45");
    }
    if (l.Sh->Count != n)
    {
      Fail(name,
        "sh element has " + std::to_string(l.Sh->Count) + " rows for " + std::to_string(n) +
          " Gaussians");
    }
    l.ShProp.resize(props);
    for (std::size_t i = 0; i < props; ++i)
    {
      const auto* p = FindProperty(*l.Sh, "f_rest_" + std::to_string(i));
      if (!p || p->Type != ScalarType::UInt8)
      {
        Fail(name, "sh element lacks uchar property 'f_rest_" + std::to_string(i) + "'");
      }
      l.ShProp[i] = p->Offset;
    }
  }
  return l;
}

//------------------------------------------------------------------------------
GaussianCloud ReadCompressed(const ByteSource& src,
  const GaussianReadOptions& options,
  GaussianReadReport* reportOut)
{
  const std::string& name = src.Name;
  if (!options.IdProperty.empty())
  {
    Fail(name, "a compressed PLY has no id property '" + options.IdProperty + "'");
  }
  const Layout l = ParseLayout(src);
  const std::size_t n = static_cast<std::size_t>(l.Vertex->Count);
  GaussianReadReport report;
  report.Format = "compressed_ply";
  report.FileShDegree = l.FileShDegree;
  const int degree =
    options.LoadSH ? std::max(0, std::min(options.MaxShDegree, l.FileShDegree)) : 0;
  const std::size_t kOut = static_cast<std::size_t>((degree + 1) * (degree + 1));
  const std::size_t kFile = static_cast<std::size_t>((l.FileShDegree + 1) * (l.FileShDegree + 1));

  // The chunk table is at most the file's size (checked in ParseLayout).
  const std::size_t chunks = static_cast<std::size_t>(l.Chunk->Count);
  std::vector<float> table(chunks * 18, 0.0f);
  detail::ForEachRowBlock(src,
    l.ChunkOffset,
    l.Chunk->RowSize,
    chunks,
    [&](const unsigned char* rows, std::size_t first, std::size_t count)
    {
      for (std::size_t r = 0; r < count; ++r)
      {
        for (int k = 0; k < (l.HasColor ? 18 : 12); ++k)
        {
          table[(first + r) * 18 + k] =
            LoadF32(rows + r * l.Chunk->RowSize + l.ChunkProp[k], l.Swap);
        }
      }
    });

  GaussianCloud cloud = detail::AllocateReadArrays(n, degree, options);
  float logit[256], shv[256];
  for (std::uint32_t i = 0; i < 256; ++i)
  {
    logit[i] = static_cast<float>(AlphaLogit(i));
    shv[i] = static_cast<float>(ShValue(i));
  }
  std::atomic<std::size_t> badValues{ 0 }, badRows{ 0 };
  std::vector<unsigned char> rowBad(n, 0);
  detail::ForEachRowBlock(src,
    l.VertexOffset,
    l.Vertex->RowSize,
    n,
    [&](const unsigned char* rows, std::size_t first, std::size_t count)
    {
      std::size_t localValues = 0;
      for (std::size_t r = 0; r < count; ++r)
      {
        const unsigned char* row = rows + r * l.Vertex->RowSize;
        const std::size_t g = first + r;
        std::uint32_t packed[4];
        for (int k = 0; k < 4; ++k)
        {
          packed[k] = LoadU32(row + l.PackedProp[k], l.Swap);
        }
        Decoded d;
        DecodeGaussian(&table[(g / ChunkSize) * 18], l.HasColor, packed, d);
        std::size_t bad = 0;
        auto store = [&bad](float& dst, double v)
        {
          dst = static_cast<float>(v);
          bad += !std::isfinite(dst);
        };
        for (int k = 0; k < 3; ++k)
        {
          if (options.LoadPositions)
          {
            store(cloud.Positions[3 * g + k], d.Position[k]);
          }
          if (options.LoadScales)
          {
            store(cloud.LogScales[3 * g + k], d.LogScale[k]);
          }
          if (options.LoadSH)
          {
            store(cloud.SH[3 * kOut * g + k], d.Dc[k]);
          }
        }
        if (options.LoadRotations)
        {
          for (int k = 0; k < 4; ++k)
          {
            store(cloud.Rotations[4 * g + k], d.Rotation[k]);
          }
        }
        if (options.LoadOpacities)
        {
          store(cloud.OpacityLogits[g], logit[d.AlphaByte]);
        }
        localValues += bad;
        rowBad[g] = bad != 0;
      }
      badValues += localValues;
    });
  if (options.LoadSH && kOut > 1)
  {
    // File: channel-major f_rest (c * (kFile-1) + k-1); cloud: coefficient-major RGB.
    detail::ForEachRowBlock(src,
      l.ShOffset,
      l.Sh->RowSize,
      n,
      [&](const unsigned char* rows, std::size_t first, std::size_t count)
      {
        for (std::size_t r = 0; r < count; ++r)
        {
          const unsigned char* row = rows + r * l.Sh->RowSize;
          float* out = &cloud.SH[3 * kOut * (first + r)];
          for (std::size_t k = 1; k < kOut; ++k)
          {
            for (std::size_t c = 0; c < 3; ++c)
            {
              out[3 * k + c] = shv[row[l.ShProp[c * (kFile - 1) + k - 1]]];
            }
          }
        }
      });
  }
  for (unsigned char b : rowBad)
  {
    badRows += b;
  }
  report.NonFiniteValues = badValues;
  report.NonFiniteGaussians = badRows;
  detail::FinishReadReport(
    report, name, reportOut, "; an alpha byte of 0 or 255 is an opacity logit of -inf or +inf");
  return cloud;
}

//------------------------------------------------------------------------------
// Writing.

std::uint32_t PackUnorm(double value, int bits)
{
  const double t = static_cast<double>((1u << bits) - 1u);
  return static_cast<std::uint32_t>(std::max(0.0, std::min(t, std::floor(value * t + 0.5))));
}

std::uint32_t Pack111011(double x, double y, double z)
{
  return PackUnorm(x, 11) << 21 | PackUnorm(y, 10) << 11 | PackUnorm(z, 11);
}

/// Normalises into [0, 1] as the reference writer does (a range under 1e-5 packs as 0).
double Normalize(double x, double lo, double hi)
{
  if (x <= lo)
  {
    return 0.0;
  }
  if (x >= hi)
  {
    return 1.0;
  }
  return hi - lo < 0.00001 ? 0.0 : (x - lo) / (hi - lo);
}

/// Smallest-three packing in file order (w x y z). A zero quaternion, which the renderer
/// draws as the identity, is written as the identity.
std::uint32_t PackRotation(const float q[4])
{
  double a[4] = { q[0], q[1], q[2], q[3] };
  const double len = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + a[3] * a[3]);
  if (len == 0.0)
  {
    a[0] = 1.0;
  }
  else
  {
    const double inv = 1.0 / len;
    for (double& v : a)
    {
      v *= inv;
    }
  }
  int largest = 0;
  for (int i = 1; i < 4; ++i)
  {
    if (std::abs(a[i]) > std::abs(a[largest]))
    {
      largest = i;
    }
  }
  const double sign = a[largest] < 0 ? -1.0 : 1.0;
  const double norm = std::sqrt(2.0) * 0.5;
  std::uint32_t result = static_cast<std::uint32_t>(largest);
  for (int i = 0; i < 4; ++i)
  {
    if (i != largest)
    {
      result = (result << 10) | PackUnorm(sign * a[i] * norm + 0.5, 10);
    }
  }
  return result;
}

std::uint8_t PackSh(float v)
{
  const double scaled = (static_cast<double>(v) / 8.0 + 0.5) * 256.0;
  return static_cast<std::uint8_t>(std::max(0.0, std::min(255.0, std::trunc(scaled))));
}

/// Sorts @p idx in Morton (Z) order of the positions with 10 bits per axis over the range's
/// bounds, refining runs of more than 256 equal codes recursively (the reference writer's order:
/// neighbours share a chunk, so the chunks' bounds and quantisation steps are small).
void SortMorton(const std::vector<float>& pos, std::size_t* idx, std::size_t count)
{
  if (count == 0)
  {
    return;
  }
  double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
  for (std::size_t i = 0; i < count; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double v = pos[3 * idx[i] + k];
      lo[k] = std::min(lo[k], v);
      hi[k] = std::max(hi[k], v);
    }
  }
  double mul[3];
  bool allSame = true;
  for (int k = 0; k < 3; ++k)
  {
    const double len = hi[k] - lo[k];
    if (!std::isfinite(len))
    {
      return;
    }
    allSame = allSame && len == 0.0;
    mul[k] = len == 0.0 ? 0.0 : 1024.0 / len;
  }
  if (allSame)
  {
    return;
  }
  auto part1By2 = [](std::uint32_t v)
  {
    v &= 0x3ffu;
    v = (v ^ (v << 16)) & 0xff0000ffu;
    v = (v ^ (v << 8)) & 0x0300f00fu;
    v = (v ^ (v << 4)) & 0x030c30c3u;
    v = (v ^ (v << 2)) & 0x09249249u;
    return v;
  };
  std::vector<std::pair<std::uint32_t, std::size_t>> coded(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    std::uint32_t q[3];
    for (int k = 0; k < 3; ++k)
    {
      q[k] = static_cast<std::uint32_t>(std::min(1023.0, (pos[3 * idx[i] + k] - lo[k]) * mul[k]));
    }
    coded[i] = { (part1By2(q[2]) << 2) + (part1By2(q[1]) << 1) + part1By2(q[0]), idx[i] };
  }
  std::stable_sort(
    coded.begin(), coded.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t i = 0; i < count; ++i)
  {
    idx[i] = coded[i].second;
  }
  for (std::size_t start = 0, end = 0; start < count; start = end)
  {
    while (end < count && coded[end].first == coded[start].first)
    {
      ++end;
    }
    if (end - start > ChunkSize)
    {
      SortMorton(pos, idx + start, end - start);
    }
  }
}

/// Accumulates the max and RMS of absolute differences for the report.
struct ErrorSum
{
  double Max = 0, SumSq = 0;
  std::size_t Values = 0;
  void Add(double e)
  {
    Max = std::max(Max, e);
    SumSq += e * e;
    ++Values;
  }
};

struct Encoded
{
  std::vector<std::size_t> Order;
  std::vector<float> Chunks;         ///< 18 per chunk
  std::vector<std::uint32_t> Packed; ///< 4 per written Gaussian
  std::vector<std::uint8_t> ShBytes; ///< 3*(k-1) per written Gaussian, channel-major
  int ShDegree = 0;
};

Encoded Encode(const GaussianCloud& cloud,
  const CompressedPlyWriteOptions& options,
  CompressedPlyWriteReport& report)
{
  const std::size_t k = static_cast<std::size_t>(cloud.ShCoefficientCount());
  if (cloud.Positions.size() != 3 * cloud.Count || cloud.LogScales.size() != 3 * cloud.Count ||
    cloud.Rotations.size() != 4 * cloud.Count || cloud.OpacityLogits.size() != cloud.Count ||
    cloud.SH.size() != 3 * k * cloud.Count)
  {
    throw std::invalid_argument("WriteCompressedPly: the cloud must hold every parameter array");
  }
  Encoded out;
  out.ShDegree = std::max(0, std::min(options.MaxShDegree, cloud.ShDegree));
  const std::size_t kOut = static_cast<std::size_t>((out.ShDegree + 1) * (out.ShDegree + 1));
  // The .splat writer's rule: what the reference draws keeps its meaning, the rest (and a
  // Gaussian whose written SH holds inf/NaN, which renders skip) is left out and counted.
  out.Order.reserve(cloud.Count);
  for (std::size_t g = 0; g < cloud.Count; ++g)
  {
    if (detail::WritableGaussian(cloud, g, kOut))
    {
      out.Order.push_back(g);
    }
  }
  const std::size_t n = out.Order.size();
  if (options.MortonOrder)
  {
    SortMorton(cloud.Positions, out.Order.data(), n);
  }
  const std::size_t chunks = (n + ChunkSize - 1) / ChunkSize;
  out.Chunks.resize(18 * chunks);
  out.Packed.resize(4 * n);
  out.ShBytes.resize(3 * (kOut - 1) * n);
  ErrorSum errPos, errScale, errRot, errDc, errAlpha, errSh;
  for (std::size_t ci = 0; ci < chunks; ++ci)
  {
    const std::size_t first = ci * ChunkSize, count = std::min(ChunkSize, n - first);
    // Bounds over the chunk, colour as float32(dc*C0 + 0.5) as the reference keeps it.
    float lo[9], hi[9];
    std::fill(lo, lo + 9, INFINITY);
    std::fill(hi, hi + 9, -INFINITY);
    auto colour = [&](std::size_t g, int c)
    { return static_cast<float>(cloud.SH[3 * k * g + c] * sh::C0 + 0.5); };
    for (std::size_t r = 0; r < count; ++r)
    {
      const std::size_t g = out.Order[first + r];
      for (int c = 0; c < 3; ++c)
      {
        const float v[3] = { cloud.Positions[3 * g + c], cloud.LogScales[3 * g + c], colour(g, c) };
        for (int a = 0; a < 3; ++a)
        {
          lo[3 * a + c] = std::min(lo[3 * a + c], v[a]);
          hi[3 * a + c] = std::max(hi[3 * a + c], v[a]);
        }
      }
    }
    for (int c = 3; c < 6; ++c)
    {
      lo[c] = static_cast<float>(std::max(-LogScaleLimit, std::min(LogScaleLimit, double(lo[c]))));
      hi[c] = static_cast<float>(std::max(-LogScaleLimit, std::min(LogScaleLimit, double(hi[c]))));
    }
    float* table = &out.Chunks[18 * ci];
    for (int c = 0; c < 3; ++c)
    {
      table[c] = lo[c];
      table[3 + c] = hi[c];
      table[6 + c] = lo[3 + c];
      table[9 + c] = hi[3 + c];
      table[12 + c] = lo[6 + c];
      table[15 + c] = hi[6 + c];
    }
    for (std::size_t r = 0; r < count; ++r)
    {
      const std::size_t g = out.Order[first + r];
      const std::size_t w = first + r;
      const float* p = &cloud.Positions[3 * g];
      const float* s = &cloud.LogScales[3 * g];
      std::uint32_t* packed = &out.Packed[4 * w];
      packed[0] = Pack111011(Normalize(p[0], lo[0], hi[0]),
        Normalize(p[1], lo[1], hi[1]),
        Normalize(p[2], lo[2], hi[2]));
      packed[1] = PackRotation(&cloud.Rotations[4 * g]);
      packed[2] = Pack111011(Normalize(s[0], lo[3], hi[3]),
        Normalize(s[1], lo[4], hi[4]),
        Normalize(s[2], lo[5], hi[5]));
      const double alpha = 1.0 / (1.0 + std::exp(-static_cast<double>(cloud.OpacityLogits[g])));
      packed[3] = PackUnorm(Normalize(colour(g, 0), lo[6], hi[6]), 8) << 24 |
        PackUnorm(Normalize(colour(g, 1), lo[7], hi[7]), 8) << 16 |
        PackUnorm(Normalize(colour(g, 2), lo[8], hi[8]), 8) << 8 | PackUnorm(alpha, 8);
      std::uint8_t* shOut = out.ShBytes.data() + 3 * (kOut - 1) * w;
      for (std::size_t c = 0; c < 3; ++c)
      {
        for (std::size_t i = 1; i < kOut; ++i)
        {
          const float v = cloud.SH[3 * k * g + 3 * i + c];
          const std::uint8_t b = PackSh(v);
          shOut[c * (kOut - 1) + i - 1] = b;
          if (std::abs(v) > 4.0f)
          {
            ++report.ClampedSH;
          }
          else
          {
            errSh.Add(std::abs(static_cast<float>(ShValue(b)) - double(v)));
          }
        }
      }
      // What a reader gets back, against the source.
      Decoded d;
      DecodeGaussian(table, true, packed, d);
      for (int c = 0; c < 3; ++c)
      {
        errPos.Add(std::abs(static_cast<float>(d.Position[c]) - double(p[c])));
        errDc.Add(std::abs(static_cast<float>(d.Dc[c]) - double(cloud.SH[3 * k * g + c])));
        if (std::abs(s[c]) > LogScaleLimit)
        {
          ++report.ClampedLogScales;
        }
        else
        {
          errScale.Add(std::abs(static_cast<float>(d.LogScale[c]) - double(s[c])));
        }
      }
      const auto q = NormalizeQuaternion(&cloud.Rotations[4 * g]);
      if (q[0] != 0 || q[1] != 0 || q[2] != 0 || q[3] != 0)
      {
        double dot = 0;
        for (int c = 0; c < 4; ++c)
        {
          dot += double(q[c]) * static_cast<float>(d.Rotation[c]);
        }
        errRot.Add(2.0 * std::acos(std::min(1.0, std::abs(dot))) * 180.0 / 3.14159265358979323846);
      }
      errAlpha.Add(std::abs(UnpackUnorm(d.AlphaByte, 8) - alpha));
    }
  }
  report.Written = n;
  report.LeftOut = cloud.Count - n;
  auto add = [&report](const char* attribute, const ErrorSum& e)
  {
    QuantisationError q;
    q.Attribute = attribute;
    q.Max = e.Max;
    q.Rms = e.Values ? std::sqrt(e.SumSq / double(e.Values)) : 0.0;
    q.Values = e.Values;
    report.Errors.push_back(q);
  };
  add("position", errPos);
  add("log-scale", errScale);
  add("rotation (degrees)", errRot);
  add("f_dc", errDc);
  add("opacity (alpha)", errAlpha);
  add("f_rest", errSh);
  report.Order = out.Order;
  return out;
}

void WriteEncoded(const Encoded& e,
  const CompressedPlyWriteOptions& options,
  const std::function<void(const void*, std::size_t)>& sink)
{
  const std::size_t n = e.Order.size();
  const std::size_t chunks = e.Chunks.size() / 18;
  const std::size_t shProps = 3 * static_cast<std::size_t>((e.ShDegree + 1) * (e.ShDegree + 1) - 1);
  std::string header = "ply\nformat binary_little_endian 1.0\n";
  for (const auto& c : options.Comments)
  {
    header += "comment " + c + "\n";
  }
  header += "element chunk " + std::to_string(chunks) + "\n";
  for (const char* p : ChunkNames)
  {
    header += std::string("property float ") + p + "\n";
  }
  header += "element vertex " + std::to_string(n) + "\n";
  for (const char* p : PackedNames)
  {
    header += std::string("property uint ") + p + "\n";
  }
  if (shProps)
  {
    header += "element sh " + std::to_string(n) + "\n";
    for (std::size_t i = 0; i < shProps; ++i)
    {
      header += "property uchar f_rest_" + std::to_string(i) + "\n";
    }
  }
  header += "end_header\n";
  sink(header.data(), header.size());
  const bool swap = !detail::HostIsLittleEndian();
  auto writeWords = [&](const void* data, std::size_t words)
  {
    if (!swap)
    {
      sink(data, 4 * words);
      return;
    }
    std::vector<std::uint32_t> buf(words);
    std::memcpy(buf.data(), data, 4 * words);
    for (auto& w : buf)
    {
      w = detail::ByteSwap32(w);
    }
    sink(buf.data(), 4 * words);
  };
  writeWords(e.Chunks.data(), e.Chunks.size());
  writeWords(e.Packed.data(), e.Packed.size());
  sink(e.ShBytes.data(), e.ShBytes.size());
}

} // namespace

//------------------------------------------------------------------------------
bool IsCompressedPly(const void* head, std::size_t size)
{
  const auto* p = static_cast<const unsigned char*>(head);
  if (!p || size < 4 || std::memcmp(p, "ply", 3) != 0)
  {
    return false;
  }
  try
  {
    return LooksCompressed(
      detail::ParsePlyHeader(p, std::min(size, detail::MaxPlyHeaderBytes), ""));
  }
  catch (const std::exception&)
  {
    return false;
  }
}

//------------------------------------------------------------------------------
GaussianCloud ReadCompressedPly(const std::string& path,
  const GaussianReadOptions& options,
  GaussianReadReport* report)
{
  return detail::ParseFileSource(ReadCompressed, path, options, report);
}

//------------------------------------------------------------------------------
GaussianCloud ReadCompressedPlyFromMemory(const void* data,
  std::size_t size,
  const std::string& name,
  const GaussianReadOptions& options,
  GaussianReadReport* report)
{
  return ReadCompressed(detail::MemorySource(data, size, name), options, report);
}

//------------------------------------------------------------------------------
CompressedPlyWriteReport WriteCompressedPly(const std::string& path,
  const GaussianCloud& cloud,
  const CompressedPlyWriteOptions& options)
{
  CompressedPlyWriteReport report;
  const Encoded e = Encode(cloud, options, report);
  detail::WriteFileAtomically(path,
    [&](std::FILE* f)
    {
      WriteEncoded(
        e, options, [&](const void* d, std::size_t n) { detail::WriteBytes(f, d, n, path); });
    });
  return report;
}

//------------------------------------------------------------------------------
std::vector<unsigned char> WriteCompressedPlyToMemory(const GaussianCloud& cloud,
  const CompressedPlyWriteOptions& options,
  CompressedPlyWriteReport* reportOut)
{
  CompressedPlyWriteReport report;
  const Encoded e = Encode(cloud, options, report);
  std::vector<unsigned char> out;
  WriteEncoded(e,
    options,
    [&](const void* d, std::size_t n)
    {
      const auto* b = static_cast<const unsigned char*>(d);
      out.insert(out.end(), b, b + n);
    });
  if (reportOut)
  {
    *reportOut = std::move(report);
  }
  return out;
}

//------------------------------------------------------------------------------
std::string DescribeQuantisation(const CompressedPlyWriteReport& report)
{
  std::string s = detail::DescribeWriteErrors(report.Written, report.LeftOut, report.Errors);
  if (report.ClampedLogScales)
  {
    s += "; " + std::to_string(report.ClampedLogScales) + " log-scales outside [-20, 20] clamped";
  }
  if (report.ClampedSH)
  {
    s += "; " + std::to_string(report.ClampedSH) + " f_rest outside [-4, 4] clamped";
  }
  return s;
}

//------------------------------------------------------------------------------
std::string detail::DescribeWriteErrors(std::size_t written,
  std::size_t leftOut,
  const std::vector<QuantisationError>& errors)
{
  std::string s = std::to_string(written) + " Gaussians written";
  if (leftOut)
  {
    s += ", " + std::to_string(leftOut) +
      " left out (no answer in the reference's arithmetic, Documentation/special-values.md)";
  }
  s += "; quantisation error max/RMS:";
  char buf[128];
  for (const auto& e : errors)
  {
    if (e.Values)
    {
      std::snprintf(buf, sizeof(buf), " %s %.3g/%.3g;", e.Attribute.c_str(), e.Max, e.Rms);
      s += buf;
    }
  }
  s.pop_back();
  return s;
}

} // namespace vis4gs

// SPDX-License-Identifier: BSD-3-Clause
// The INRIA PLY reader (binary little/big endian and ASCII, every float32 kept bit-exactly).
// The header parser is PlyHeader.cxx (shared with the compressed PLY reader), the writer
// GaussianPlyWriter.cxx, the format dispatcher GaussianScene.cxx.
#include "GaussianIO.h"
#include "PlyHeader.h"
#include "SceneFile.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <stdexcept>
#include <string_view>

#include <sys/mman.h>

namespace vis4gs
{

namespace
{

using detail::ByteSource;

constexpr std::size_t MaxHeaderBytes = detail::MaxPlyHeaderBytes;

//------------------------------------------------------------------------------
[[noreturn]] void Fail(const std::string& name, const std::string& what)
{
  throw std::runtime_error(name + ": " + what);
}

using detail::PlyElement;
using detail::PlyHeader;
using detail::PlyProperty;

//------------------------------------------------------------------------------
// Where one vertex property goes.
struct Target
{
  enum Kind : std::uint8_t
  {
    None,
    Float,
    Extra,
    Id
  };
  Kind What = None;
  float* Dst = nullptr;   // first Gaussian's slot (Float)
  std::size_t Stride = 0; // floats per Gaussian (Float)
  unsigned char* ExtraDst = nullptr;
  float* Base = nullptr;    // the array Dst points into (Float)
  std::uint32_t Offset = 0; // Dst - Base
};

Target FloatTarget(std::vector<float>& v, std::size_t offset, std::size_t stride)
{
  Target t;
  t.What = Target::Float;
  t.Base = v.data();
  t.Offset = static_cast<std::uint32_t>(offset);
  t.Dst = v.data() + offset;
  t.Stride = stride;
  return t;
}

// Zero-filled array of @p n values; large arrays ask for transparent huge pages first so that
// filling them costs a few hundred page faults instead of hundreds of thousands.
template <typename T>
void AllocateZeroed(std::vector<T>& v, std::size_t n)
{
  v.reserve(n);
  const std::size_t bytes = n * sizeof(T);
  if (bytes >= (std::size_t(16) << 20))
  {
    const std::uintptr_t page = std::uintptr_t(2) << 20;
    const std::uintptr_t b = (reinterpret_cast<std::uintptr_t>(v.data()) + page - 1) & ~(page - 1);
    const std::uintptr_t e = (reinterpret_cast<std::uintptr_t>(v.data()) + bytes) & ~(page - 1);
    if (e > b)
    {
      ::madvise(reinterpret_cast<void*>(b), e - b, MADV_HUGEPAGE);
    }
  }
  v.resize(n);
}

// Per-Gaussian arrays and where each property of the vertex element goes.
struct Plan
{
  std::vector<Target> Targets; // one per vertex property, file order
  std::vector<ExtraProperty>* Extras = nullptr;
  bool Surfels = false; // 2DGS: scale_0 and scale_1 without scale_2
};

/// The render mode a PLY names (Brush's `SplatRenderMode: default | mip | 2dgs`, Postshot's
/// `antialiased 0 | 1`; case-insensitive, the last one wins, as Brush's importer and
/// splat-transform decide) and 2DGS surfels (no scale_2): read with a log-scale of -inf along
/// the normal, as splat-transform does; both said in the report.
void ApplyRenderMode(const std::vector<std::string>& comments,
  bool surfels,
  const std::string& name,
  GaussianCloud& cloud,
  GaussianReadReport& report)
{
  std::string mode, said;
  for (const std::string& c : comments)
  {
    std::string lower(c);
    std::transform(lower.begin(),
      lower.end(),
      lower.begin(),
      [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    auto value = [&lower](const char* key) -> std::string
    {
      const std::size_t l = std::strlen(key);
      if (lower.compare(0, l, key) != 0)
      {
        return "-";
      }
      const auto b = lower.find_first_not_of(" \t", l);
      return b == std::string::npos ? "" : lower.substr(b);
    };
    const std::string brush = value("splatrendermode:");
    const std::string postshot = value("antialiased ");
    const std::string next = brush == "default" || postshot == "0" ? "default"
      : brush == "mip" || postshot == "1"                          ? "antialiased"
      : brush == "2dgs"                                            ? "2dgs"
                                                                   : "";
    if (!next.empty())
    {
      mode = next;
      said = c;
    }
  }
  if (surfels)
  {
    if (!cloud.LogScales.empty())
    {
      for (std::size_t g = 0; g < cloud.Count; ++g)
      {
        cloud.LogScales[3 * g + 2] = -std::numeric_limits<float>::infinity();
      }
    }
    report.Warnings.push_back(name +
      ": no scale_2: 2D Gaussian splatting surfels, read with scale 0 along the normal (log-scale "
      "-inf, as splat-transform does) and drawn by the 3DGS rasteriser as flat Gaussians, which is "
      "not 2DGS's ray-splat renderer");
    mode = "2dgs";
  }
  else if (mode == "2dgs")
  {
    report.Warnings.push_back(
      name + ": the header says '" + said + "' but the file holds scale_2: read as 3D Gaussians");
  }
  else if (mode == "antialiased")
  {
    report.Warnings.push_back(name + ": the header says '" + said +
      "': trained with antialiasing (Mip-Splatting's 2D filter); Vis4GS draws the Gaussians as the "
      "INRIA renderer does");
  }
  report.RenderMode = mode;
}

//------------------------------------------------------------------------------
// Maps the vertex properties onto @p cloud (allocating what is requested) and fills @p plan.
void BuildPlan(const PlyElement& vertex,
  const std::string& name,
  const GaussianReadOptions& options,
  GaussianCloud& cloud,
  GaussianReadReport& report,
  Plan& plan)
{
  const std::size_t n = static_cast<std::size_t>(vertex.Count);
  const std::size_t np = vertex.Properties.size();
  // Classify names first (no allocation yet).
  enum Group
  {
    GNone,
    GPos,
    GScale,
    GRot,
    GOpacity,
    GDc,
    GRest,
    GId,
    GExtra
  };
  std::vector<std::pair<Group, int>> cls(np, { GNone, 0 });
  std::map<int, std::size_t> rest; // f_rest index -> property
  bool havePos[3] = {}, haveScale[3] = {}, haveRot[4] = {}, haveDc[3] = {}, haveOpacity = false;
  bool haveId = false;
  auto indexed = [](const std::string& s, const char* prefix, int count, int& idx)
  {
    const std::size_t l = std::strlen(prefix);
    if (s.size() != l + 1 || s.compare(0, l, prefix) != 0)
    {
      return false;
    }
    idx = s[l] - '0';
    return idx >= 0 && idx < count;
  };
  for (std::size_t i = 0; i < np; ++i)
  {
    const PlyProperty& p = vertex.Properties[i];
    if (p.IsList)
    {
      Fail(name, "vertex property '" + p.Name + "' is a list; a 3DGS PLY holds scalars only");
    }
    const std::string& s = p.Name;
    int idx = 0;
    if (!options.IdProperty.empty() && s == options.IdProperty)
    {
      cls[i] = { GId, 0 };
      haveId = true;
    }
    else if (s == "x" || s == "y" || s == "z")
    {
      idx = s[0] - 'x';
      cls[i] = { GPos, idx };
      havePos[idx] = true;
    }
    else if (indexed(s, "scale_", 3, idx))
    {
      cls[i] = { GScale, idx };
      haveScale[idx] = true;
    }
    else if (indexed(s, "rot_", 4, idx))
    {
      cls[i] = { GRot, idx };
      haveRot[idx] = true;
    }
    else if (s == "opacity")
    {
      cls[i] = { GOpacity, 0 };
      haveOpacity = true;
    }
    else if (indexed(s, "f_dc_", 3, idx))
    {
      cls[i] = { GDc, idx };
      haveDc[idx] = true;
    }
    else if (s.size() > 7 && s.compare(0, 7, "f_rest_") == 0)
    {
      unsigned j = 0;
      const char* b = s.data() + 7;
      const char* e = s.data() + s.size();
      const auto r = std::from_chars(b, e, j);
      if (r.ec != std::errc() || r.ptr != e || j > 1000 || (s.size() > 8 && s[7] == '0'))
      {
        Fail(name, "malformed SH property name '" + s + "'");
      }
      rest[static_cast<int>(j)] = i;
      cls[i] = { GRest, static_cast<int>(j) };
    }
    else
    {
      cls[i] = { GExtra, 0 };
    }
  }

  // SH degree from the f_rest count.
  const std::size_t nRest = rest.size();
  int fileDegree = -1;
  for (int d = 0; d <= 3; ++d)
  {
    if (nRest == static_cast<std::size_t>(3 * ((d + 1) * (d + 1) - 1)))
    {
      fileDegree = d;
    }
  }
  if (fileDegree < 0)
  {
    Fail(name,
      "has " + std::to_string(nRest) +
        " f_rest properties; a 3DGS PLY has 0, 9, 24 or 45 (SH degree 0 to 3)");
  }
  if (nRest && rest.rbegin()->first != static_cast<int>(nRest) - 1)
  {
    Fail(name, "f_rest properties are not numbered 0.." + std::to_string(nRest - 1));
  }
  report.FileShDegree = fileDegree;

  // Required properties for what was asked.
  std::string missing;
  auto need = [&missing](bool have, const std::string& what)
  {
    if (!have)
    {
      missing += (missing.empty() ? "" : ", ") + what;
    }
  };
  if (options.LoadPositions)
  {
    for (int c = 0; c < 3; ++c)
    {
      need(havePos[c], std::string(1, static_cast<char>('x' + c)));
    }
  }
  // 2D Gaussian splatting stores surfels: two scales, none along the normal.
  plan.Surfels = haveScale[0] && haveScale[1] && !haveScale[2];
  if (options.LoadScales)
  {
    for (int c = 0; c < 3; ++c)
    {
      need(haveScale[c] || (c == 2 && plan.Surfels), "scale_" + std::to_string(c));
    }
  }
  if (options.LoadRotations)
  {
    for (int c = 0; c < 4; ++c)
    {
      need(haveRot[c], "rot_" + std::to_string(c));
    }
  }
  if (options.LoadOpacities)
  {
    need(haveOpacity, "opacity");
  }
  if (options.LoadSH)
  {
    for (int c = 0; c < 3; ++c)
    {
      need(haveDc[c], "f_dc_" + std::to_string(c));
    }
  }
  if (!options.IdProperty.empty())
  {
    need(haveId, options.IdProperty + " (the requested id property)");
  }
  if (!missing.empty())
  {
    Fail(name, "missing required vertex properties: " + missing);
  }

  // Allocate what is requested (counts were checked against the file size already).
  const int loadDegree = std::max(0, std::min(std::min(options.MaxShDegree, 3), fileDegree));
  const int kFile = (fileDegree + 1) * (fileDegree + 1);
  const int kLoad = (loadDegree + 1) * (loadDegree + 1);
  cloud.Count = n;
  cloud.ShDegree = options.LoadSH ? loadDegree : 0;
  if (options.LoadPositions)
  {
    AllocateZeroed(cloud.Positions, 3 * n);
  }
  if (options.LoadScales)
  {
    AllocateZeroed(cloud.LogScales, 3 * n);
  }
  if (options.LoadRotations)
  {
    AllocateZeroed(cloud.Rotations, 4 * n);
  }
  if (options.LoadOpacities)
  {
    AllocateZeroed(cloud.OpacityLogits, n);
  }
  if (options.LoadSH)
  {
    AllocateZeroed(cloud.SH, 3 * static_cast<std::size_t>(kLoad) * n);
  }
  if (haveId)
  {
    cloud.Ids.resize(n);
  }
  std::size_t extraCount = 0;
  for (const auto& c : cls)
  {
    extraCount += c.first == GExtra;
  }
  if (options.LoadExtras)
  {
    cloud.Extra.reserve(extraCount);
  }

  plan.Targets.assign(np, Target{});
  plan.Extras = &cloud.Extra;
  for (std::size_t i = 0; i < np; ++i)
  {
    Target& t = plan.Targets[i];
    const int idx = cls[i].second;
    switch (cls[i].first)
    {
      case GPos:
        if (options.LoadPositions)
        {
          t = FloatTarget(cloud.Positions, idx, 3);
        }
        break;
      case GScale:
        if (options.LoadScales)
        {
          t = FloatTarget(cloud.LogScales, idx, 3);
        }
        break;
      case GRot:
        if (options.LoadRotations)
        {
          t = FloatTarget(cloud.Rotations, idx, 4);
        }
        break;
      case GOpacity:
        if (options.LoadOpacities)
        {
          t = FloatTarget(cloud.OpacityLogits, 0, 1);
        }
        break;
      case GDc:
        if (options.LoadSH)
        {
          t = FloatTarget(cloud.SH, idx, 3 * static_cast<std::size_t>(kLoad));
        }
        break;
      case GRest:
        if (options.LoadSH)
        {
          const int c = idx / (kFile - 1);
          const int k = idx % (kFile - 1) + 1;
          if (k < kLoad)
          {
            t = FloatTarget(cloud.SH, 3 * k + c, 3 * static_cast<std::size_t>(kLoad));
          }
        }
        break;
      case GId:
        t.What = Target::Id;
        break;
      case GExtra:
        if (options.LoadExtras)
        {
          ExtraProperty e;
          e.Name = vertex.Properties[i].Name;
          e.Type = vertex.Properties[i].Type;
          AllocateZeroed(e.Bytes, n * ScalarTypeSize(e.Type));
          cloud.Extra.push_back(std::move(e));
          t.What = Target::Extra;
          t.ExtraDst = cloud.Extra.back().Bytes.data();
        }
        break;
      case GNone:
        break;
    }
  }
}

//------------------------------------------------------------------------------
template <typename T>
T LoadAs(const unsigned char* p, bool swap)
{
  unsigned char b[sizeof(T)];
  std::memcpy(b, p, sizeof(T));
  if (swap)
  {
    detail::SwapBytes(b, sizeof(T));
  }
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

double LoadNumber(const unsigned char* p, ScalarType t, bool swap)
{
  switch (t)
  {
    case ScalarType::Int8:
      return LoadAs<std::int8_t>(p, swap);
    case ScalarType::UInt8:
      return LoadAs<std::uint8_t>(p, swap);
    case ScalarType::Int16:
      return LoadAs<std::int16_t>(p, swap);
    case ScalarType::UInt16:
      return LoadAs<std::uint16_t>(p, swap);
    case ScalarType::Int32:
      return LoadAs<std::int32_t>(p, swap);
    case ScalarType::UInt32:
      return LoadAs<std::uint32_t>(p, swap);
    case ScalarType::Float32:
      return LoadAs<float>(p, swap);
    case ScalarType::Float64:
      return LoadAs<double>(p, swap);
  }
  return 0;
}

using detail::FloatBitsFinite;

//------------------------------------------------------------------------------
std::int64_t ToId(double v, const std::string& name, const std::string& prop, std::size_t row)
{
  if (!std::isfinite(v) || v != std::floor(v) || std::fabs(v) > 9007199254740992.0)
  {
    Fail(name,
      "vertex " + std::to_string(row) + ": id property '" + prop +
        "' holds a value that is not an integer");
  }
  return static_cast<std::int64_t>(v);
}

//------------------------------------------------------------------------------
// Binary rows. float32 properties that land in float arrays are grouped per destination
// array into (source offset, destination offset) pairs copied in a tight loop (byte-swapped
// for the other endianness); everything else (conversions, extras, ids) goes through ops.
struct FloatGroup
{
  float* Base = nullptr;
  std::size_t Stride = 0;
  std::vector<std::uint32_t> Src;
  std::vector<std::uint32_t> Dst;
};

struct BinaryOp
{
  enum Kind : std::uint8_t
  {
    Convert,   // one value of another type, converted to float
    ExtraCopy, // Size bytes copied
    ExtraSwap, // Size bytes swapped
    IdValue
  };
  Kind What = Convert;
  ScalarType Type = ScalarType::Float32;
  std::uint32_t SrcOffset = 0;
  float* Dst = nullptr;
  std::size_t Stride = 0;
  unsigned char* ExtraDst = nullptr;
  std::uint32_t Size = 0;
};

template <bool Swap>
std::size_t CopyGroups(const std::vector<FloatGroup>& groups,
  const unsigned char* row,
  std::size_t g)
{
  std::uint32_t bad = 0;
  for (const FloatGroup& fg : groups)
  {
    float* d = fg.Base + g * fg.Stride;
    const std::size_t n = fg.Src.size();
    const std::uint32_t* src = fg.Src.data();
    const std::uint32_t* dst = fg.Dst.data();
    for (std::size_t k = 0; k < n; ++k)
    {
      std::uint32_t bits;
      std::memcpy(&bits, row + src[k], 4);
      if (Swap)
      {
        bits = detail::ByteSwap32(bits);
      }
      std::memcpy(d + dst[k], &bits, 4);
      bad += (bits & 0x7f800000u) == 0x7f800000u;
    }
  }
  return bad;
}

void ReadBinaryVertices(const ByteSource& src,
  std::uint64_t offset,
  const PlyElement& vertex,
  const Plan& plan,
  bool bigEndian,
  GaussianCloud& cloud,
  GaussianReadReport& report,
  const std::string& idName)
{
  const bool swap = bigEndian == detail::HostIsLittleEndian();
  std::vector<FloatGroup> groups;
  std::vector<BinaryOp> ops;
  for (std::size_t i = 0; i < vertex.Properties.size(); ++i)
  {
    const PlyProperty& p = vertex.Properties[i];
    const Target& t = plan.Targets[i];
    if (t.What == Target::Float && p.Type == ScalarType::Float32)
    {
      auto it = std::find_if(groups.begin(),
        groups.end(),
        [&t](const FloatGroup& fg) { return fg.Base == t.Base && fg.Stride == t.Stride; });
      if (it == groups.end())
      {
        groups.emplace_back();
        it = groups.end() - 1;
        it->Base = t.Base;
        it->Stride = t.Stride;
      }
      it->Src.push_back(static_cast<std::uint32_t>(p.Offset));
      it->Dst.push_back(t.Offset);
      continue;
    }
    BinaryOp op;
    op.SrcOffset = static_cast<std::uint32_t>(p.Offset);
    op.Type = p.Type;
    switch (t.What)
    {
      case Target::None:
        continue;
      case Target::Float:
        op.What = BinaryOp::Convert;
        op.Dst = t.Dst;
        op.Stride = t.Stride;
        break;
      case Target::Extra:
        op.What = swap ? BinaryOp::ExtraSwap : BinaryOp::ExtraCopy;
        op.ExtraDst = t.ExtraDst;
        op.Size = static_cast<std::uint32_t>(ScalarTypeSize(p.Type));
        break;
      case Target::Id:
        op.What = BinaryOp::IdValue;
        break;
    }
    ops.push_back(op);
  }
  std::atomic<std::size_t> badValues{ 0 }, badRows{ 0 };
  std::int64_t* ids = cloud.Ids.empty() ? nullptr : cloud.Ids.data();
  const std::size_t rowSize = vertex.RowSize;
  const std::string& name = src.Name;

  detail::ForEachRowBlock(src,
    offset,
    rowSize,
    static_cast<std::size_t>(vertex.Count),
    [&](const unsigned char* rows, std::size_t first, std::size_t count)
    {
      std::size_t localValues = 0, localRows = 0;
      for (std::size_t r = 0; r < count; ++r)
      {
        const unsigned char* row = rows + r * rowSize;
        const std::size_t g = first + r;
        std::size_t rowBad =
          swap ? CopyGroups<true>(groups, row, g) : CopyGroups<false>(groups, row, g);
        for (const BinaryOp& op : ops)
        {
          const unsigned char* s = row + op.SrcOffset;
          switch (op.What)
          {
            case BinaryOp::Convert:
            {
              const float v = static_cast<float>(LoadNumber(s, op.Type, swap));
              op.Dst[g * op.Stride] = v;
              rowBad += !std::isfinite(v);
              break;
            }
            case BinaryOp::ExtraCopy:
              std::memcpy(op.ExtraDst + g * op.Size, s, op.Size);
              break;
            case BinaryOp::ExtraSwap:
            {
              unsigned char* d = op.ExtraDst + g * op.Size;
              std::memcpy(d, s, op.Size);
              detail::SwapBytes(d, op.Size);
              break;
            }
            case BinaryOp::IdValue:
            {
              const double v = LoadNumber(s, op.Type, swap);
              ids[g] = ToId(v, name, idName, g);
              break;
            }
          }
        }
        localValues += rowBad;
        localRows += rowBad != 0;
      }
      badValues += localValues;
      badRows += localRows;
    });
  report.NonFiniteValues = badValues;
  report.NonFiniteGaussians = badRows;
}

//------------------------------------------------------------------------------
// ASCII numbers. Floats accept what std::from_chars accepts plus a leading '+', and
// "nan(0x<hex>)" / "-nan(0x<hex>)" with an explicit payload (what our writer emits).
bool ParseFloatBits(std::string_view s, std::uint32_t& bits)
{
  bool neg = false;
  std::string_view t = s;
  if (!t.empty() && (t[0] == '+' || t[0] == '-'))
  {
    neg = t[0] == '-';
    t.remove_prefix(1);
  }
  if (t.size() > 7 && (t.substr(0, 6) == "nan(0x" || t.substr(0, 6) == "NAN(0X") && t.back() == ')')
  {
    std::uint32_t payload = 0;
    const auto hex = t.substr(6, t.size() - 7);
    const auto r = std::from_chars(hex.data(), hex.data() + hex.size(), payload, 16);
    if (r.ec != std::errc() || r.ptr != hex.data() + hex.size() || payload == 0 ||
      payload > 0x7fffffu)
    {
      return false;
    }
    bits = 0x7f800000u | payload | (neg ? 0x80000000u : 0u);
    return true;
  }
  if (t.empty() || t[0] == '+' || t[0] == '-')
  {
    return false;
  }
  float v;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
  if (r.ec == std::errc::result_out_of_range)
  {
    // Overflow gives +-inf and underflow 0, as strtof would (the value is still a number).
    const double d = std::strtod(std::string(t).c_str(), nullptr);
    v = static_cast<float>(d);
  }
  else if (r.ec != std::errc() || r.ptr != t.data() + t.size())
  {
    return false;
  }
  if (neg)
  {
    v = -v;
  }
  std::memcpy(&bits, &v, 4);
  return true;
}

bool ParseDouble(std::string_view s, double& v)
{
  bool neg = false;
  std::string_view t = s;
  if (!t.empty() && (t[0] == '+' || t[0] == '-'))
  {
    neg = t[0] == '-';
    t.remove_prefix(1);
  }
  if (t.empty() || t[0] == '+' || t[0] == '-')
  {
    return false;
  }
  const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
  if (r.ec == std::errc::result_out_of_range)
  {
    v = std::strtod(std::string(t).c_str(), nullptr);
  }
  else if (r.ec != std::errc() || r.ptr != t.data() + t.size())
  {
    return false;
  }
  if (neg)
  {
    v = -v;
  }
  return true;
}

//------------------------------------------------------------------------------
template <typename T>
void StoreInt(unsigned char* d, double v)
{
  const T x = static_cast<T>(v);
  std::memcpy(d, &x, sizeof(T));
}

bool IntegerInRange(ScalarType t, double v)
{
  if (!std::isfinite(v) || v != std::floor(v))
  {
    return false;
  }
  switch (t)
  {
    case ScalarType::Int8:
      return v >= -128 && v <= 127;
    case ScalarType::UInt8:
      return v >= 0 && v <= 255;
    case ScalarType::Int16:
      return v >= -32768 && v <= 32767;
    case ScalarType::UInt16:
      return v >= 0 && v <= 65535;
    case ScalarType::Int32:
      return v >= -2147483648.0 && v <= 2147483647.0;
    case ScalarType::UInt32:
      return v >= 0 && v <= 4294967295.0;
    default:
      return true;
  }
}

//------------------------------------------------------------------------------
void ReadAsciiVertices(const unsigned char* data,
  std::size_t size,
  std::size_t dataStart,
  const PlyHeader& header,
  std::size_t vertexIndex,
  const Plan& plan,
  GaussianCloud& cloud,
  GaussianReadReport& report,
  const std::string& name,
  const std::string& idName)
{
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  detail::TextLines lines(text,
    dataStart,
    static_cast<std::size_t>(std::count(text.begin(), text.begin() + dataStart, '\n')));
  auto nextLine = [&](std::string_view& line) { return lines.Next(line); };
  std::string_view line;
  for (std::size_t e = 0; e < vertexIndex; ++e)
  {
    for (std::uint64_t r = 0; r < header.Elements[e].Count; ++r)
    {
      if (!nextLine(line))
      {
        Fail(name,
          "file ends inside element '" + header.Elements[e].Name + "' (row " + std::to_string(r) +
            " of " + std::to_string(header.Elements[e].Count) + ")");
      }
    }
  }
  const PlyElement& vertex = header.Elements[vertexIndex];
  const std::size_t n = static_cast<std::size_t>(vertex.Count);
  const std::size_t np = vertex.Properties.size();
  std::size_t badValues = 0, badRows = 0;
  for (std::size_t g = 0; g < n; ++g)
  {
    if (!nextLine(line))
    {
      Fail(name,
        "header declares " + std::to_string(n) + " vertices but the file holds " +
          std::to_string(g));
    }
    const auto tok = detail::SplitWords(line);
    const std::string where =
      "line " + std::to_string(lines.LineNumber()) + " (vertex " + std::to_string(g) + "): ";
    if (tok.size() != np)
    {
      Fail(name,
        where + "has " + std::to_string(tok.size()) + " values, expected " + std::to_string(np));
    }
    std::size_t rowBad = 0;
    for (std::size_t i = 0; i < np; ++i)
    {
      const PlyProperty& p = vertex.Properties[i];
      const Target& t = plan.Targets[i];
      auto notNumber = [&]()
      {
        Fail(name,
          where + "'" + std::string(tok[i].substr(0, 40)) + "' is not a valid " +
            detail::PlyScalarTypeName(p.Type) + " for property '" + p.Name + "'");
      };
      std::uint32_t fbits = 0;
      double v = 0;
      if (p.Type == ScalarType::Float32)
      {
        if (!ParseFloatBits(tok[i], fbits))
        {
          notNumber();
        }
        float f;
        std::memcpy(&f, &fbits, 4);
        v = f;
      }
      else
      {
        if (!ParseDouble(tok[i], v))
        {
          notNumber();
        }
        if (p.Type != ScalarType::Float64 && !IntegerInRange(p.Type, v))
        {
          notNumber();
        }
      }
      switch (t.What)
      {
        case Target::None:
          break;
        case Target::Float:
        {
          float* d = t.Dst + g * t.Stride;
          if (p.Type == ScalarType::Float32)
          {
            std::memcpy(d, &fbits, 4);
            rowBad += !FloatBitsFinite(fbits);
          }
          else
          {
            *d = static_cast<float>(v);
            rowBad += !std::isfinite(*d);
          }
          break;
        }
        case Target::Extra:
        {
          unsigned char* d = t.ExtraDst + g * ScalarTypeSize(p.Type);
          switch (p.Type)
          {
            case ScalarType::Int8:
              StoreInt<std::int8_t>(d, v);
              break;
            case ScalarType::UInt8:
              StoreInt<std::uint8_t>(d, v);
              break;
            case ScalarType::Int16:
              StoreInt<std::int16_t>(d, v);
              break;
            case ScalarType::UInt16:
              StoreInt<std::uint16_t>(d, v);
              break;
            case ScalarType::Int32:
              StoreInt<std::int32_t>(d, v);
              break;
            case ScalarType::UInt32:
              StoreInt<std::uint32_t>(d, v);
              break;
            case ScalarType::Float32:
              std::memcpy(d, &fbits, 4);
              break;
            case ScalarType::Float64:
              std::memcpy(d, &v, 8);
              break;
          }
          break;
        }
        case Target::Id:
          cloud.Ids[g] = ToId(v, name, idName, g);
          break;
      }
    }
    badValues += rowBad;
    badRows += rowBad != 0;
  }
  report.NonFiniteValues = badValues;
  report.NonFiniteGaussians = badRows;
}

//------------------------------------------------------------------------------
GaussianCloud ReadPly(const ByteSource& src,
  const GaussianReadOptions& options,
  GaussianReadReport* reportOut)
{
  const std::string& name = src.Name;
  GaussianReadReport report;
  // Header: read at most 1 MiB.
  std::vector<unsigned char> headBuffer;
  const unsigned char* head = src.Memory;
  const std::size_t headSize =
    static_cast<std::size_t>(std::min<std::uint64_t>(src.Size, MaxHeaderBytes));
  if (!src.Memory)
  {
    headBuffer.resize(headSize);
    src.File->ReadAt(0, headBuffer.data(), headSize);
    head = headBuffer.data();
  }
  const PlyHeader header = detail::ParsePlyHeader(head, headSize, name);
  std::size_t vertexIndex = header.Elements.size();
  for (std::size_t e = 0; e < header.Elements.size(); ++e)
  {
    if (header.Elements[e].Name == "vertex")
    {
      vertexIndex = e;
      break;
    }
  }
  if (vertexIndex == header.Elements.size())
  {
    Fail(name, "PLY file has no 'vertex' element");
  }
  const PlyElement& vertex = header.Elements[vertexIndex];
  report.Format = header.Format == PlyFormat::Ascii ? "ascii"
    : header.Format == PlyFormat::BinaryBigEndian   ? "binary_big_endian"
                                                    : "binary_little_endian";
  if (vertex.Count > 0 && vertex.Properties.empty())
  {
    Fail(name, "the vertex element has no properties");
  }
  for (const PlyProperty& p : vertex.Properties)
  {
    if (p.IsList)
    {
      Fail(name, "vertex property '" + p.Name + "' is a list; a 3DGS PLY holds scalars only");
    }
  }
  const std::uint64_t available = src.Size - header.Bytes;
  std::uint64_t vertexOffset = header.Bytes;
  if (header.Format != PlyFormat::Ascii)
  {
    for (std::size_t e = 0; e < vertexIndex; ++e)
    {
      const PlyElement& el = header.Elements[e];
      if (el.HasList)
      {
        Fail(name,
          "element '" + el.Name +
            "' with list properties comes before 'vertex'; this is not supported");
      }
      std::uint64_t bytes;
      if (__builtin_mul_overflow(el.Count, static_cast<std::uint64_t>(el.RowSize), &bytes) ||
        __builtin_add_overflow(vertexOffset, bytes, &vertexOffset) || vertexOffset > src.Size)
      {
        Fail(name,
          "element '" + el.Name + "' declares " + std::to_string(el.Count) +
            " rows, more than the file holds");
      }
    }
    std::uint64_t need;
    if (__builtin_mul_overflow(vertex.Count, static_cast<std::uint64_t>(vertex.RowSize), &need) ||
      need > src.Size - vertexOffset)
    {
      Fail(name,
        "header declares " + std::to_string(vertex.Count) + " vertices of " +
          std::to_string(vertex.RowSize) + " bytes but only " +
          std::to_string(src.Size - vertexOffset) + " bytes follow the header (the file holds " +
          std::to_string((src.Size - vertexOffset) / std::max<std::size_t>(1, vertex.RowSize)) +
          " vertices; truncated?)");
    }
  }
  else
  {
    // Each ASCII value takes at least one character and one separator.
    std::uint64_t minBytes;
    if (__builtin_mul_overflow(
          vertex.Count, static_cast<std::uint64_t>(2 * vertex.Properties.size()), &minBytes) ||
      minBytes > available + 1)
    {
      Fail(name,
        "header declares " + std::to_string(vertex.Count) +
          " vertices but the file is too small to hold them (" + std::to_string(available) +
          " bytes of ASCII data; truncated?)");
    }
  }

  GaussianCloud cloud;
  Plan plan;
  BuildPlan(vertex, name, options, cloud, report, plan);
  if (header.Format == PlyFormat::Ascii)
  {
    std::vector<unsigned char> all;
    const unsigned char* data = src.Memory;
    if (!data)
    {
      all.resize(static_cast<std::size_t>(src.Size));
      src.File->ReadAt(0, all.data(), all.size());
      data = all.data();
    }
    ReadAsciiVertices(data,
      static_cast<std::size_t>(src.Size),
      header.Bytes,
      header,
      vertexIndex,
      plan,
      cloud,
      report,
      name,
      options.IdProperty);
  }
  else
  {
    ReadBinaryVertices(src,
      vertexOffset,
      vertex,
      plan,
      header.Format == PlyFormat::BinaryBigEndian,
      cloud,
      report,
      options.IdProperty);
  }
  ApplyRenderMode(header.Comments, plan.Surfels, name, cloud, report);
  detail::FinishReadReport(report, name, reportOut);
  return cloud;
}

} // namespace

//------------------------------------------------------------------------------
GaussianCloud ReadGaussianPly(const std::string& path,
  const GaussianReadOptions& options,
  GaussianReadReport* report)
{
  return detail::ParseFileSource(ReadPly, path, options, report);
}

//------------------------------------------------------------------------------
GaussianCloud ReadGaussianPlyFromMemory(const void* data,
  std::size_t size,
  const std::string& name,
  const GaussianReadOptions& options,
  GaussianReadReport* report)
{
  return ReadPly(detail::MemorySource(data, size, name), options, report);
}

} // namespace vis4gs

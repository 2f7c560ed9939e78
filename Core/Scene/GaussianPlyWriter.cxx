// SPDX-License-Identifier: BSD-3-Clause
// The INRIA PLY writer (binary little endian or ASCII; every float32 written bit-exactly).
// The reader is GaussianPly.cxx, the format dispatcher GaussianScene.cxx.
#include "GaussianIO.h"
#include "PlyHeader.h"
#include "SceneFile.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace vis4gs
{

namespace
{

//------------------------------------------------------------------------------
// Writer columns.
struct Column
{
  std::string Name;
  ScalarType Type = ScalarType::Float32;
  const float* Src = nullptr; // Float columns: value of Gaussian g at Src[g * Stride]
  std::size_t Stride = 0;
  const ExtraProperty* Extra = nullptr;
  const std::int64_t* Ids = nullptr;
};

std::vector<Column> WriterColumns(const GaussianCloud& cloud, const GaussianWriteOptions& options)
{
  const std::size_t n = cloud.Count;
  auto check = [n](const std::vector<float>& v, std::size_t per, const char* what)
  {
    if (!v.empty() && v.size() != per * n)
    {
      throw std::invalid_argument(std::string("WriteGaussianPly: ") + what + " holds " +
        std::to_string(v.size()) + " values, expected " + std::to_string(per * n));
    }
  };
  if (cloud.ShDegree < 0 || cloud.ShDegree > 3)
  {
    throw std::invalid_argument("WriteGaussianPly: SH degree must be 0..3");
  }
  const std::size_t k = static_cast<std::size_t>(cloud.ShCoefficientCount());
  check(cloud.Positions, 3, "Positions");
  check(cloud.LogScales, 3, "LogScales");
  check(cloud.Rotations, 4, "Rotations");
  check(cloud.OpacityLogits, 1, "OpacityLogits");
  check(cloud.SH, 3 * k, "SH");
  if (!cloud.Ids.empty() && cloud.Ids.size() != n)
  {
    throw std::invalid_argument("WriteGaussianPly: Ids size differs from Count");
  }
  static const std::vector<ExtraProperty> none;
  const std::vector<ExtraProperty>& appended =
    options.AppendedExtras ? *options.AppendedExtras : none;
  for (const std::vector<ExtraProperty>* extras : { &cloud.Extra, &appended })
  {
    for (const auto& e : *extras)
    {
      if (e.Bytes.size() != n * ScalarTypeSize(e.Type))
      {
        throw std::invalid_argument("WriteGaussianPly: extra '" + e.Name + "' has the wrong size");
      }
    }
  }

  std::vector<Column> cols;
  auto addFloats =
    [&cols](
      const std::vector<float>& v, const std::string& name, std::size_t off, std::size_t stride)
  {
    if (!v.empty())
    {
      Column c;
      c.Name = name;
      c.Src = v.data() + off;
      c.Stride = stride;
      cols.push_back(c);
    }
  };
  const char* xyz[3] = { "x", "y", "z" };
  for (int c = 0; c < 3; ++c)
  {
    addFloats(cloud.Positions, xyz[c], c, 3);
  }
  const char* normals[3] = { "nx", "ny", "nz" };
  for (const char* nn : normals)
  {
    if (const ExtraProperty* e = cloud.FindExtra(nn))
    {
      Column c;
      c.Name = nn;
      c.Type = e->Type;
      c.Extra = e;
      cols.push_back(c);
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    addFloats(cloud.SH, "f_dc_" + std::to_string(c), c, 3 * k);
  }
  for (std::size_t c = 0; c < 3; ++c)
  {
    for (std::size_t j = 1; j < k; ++j)
    {
      addFloats(cloud.SH, "f_rest_" + std::to_string(c * (k - 1) + (j - 1)), 3 * j + c, 3 * k);
    }
  }
  addFloats(cloud.OpacityLogits, "opacity", 0, 1);
  for (int c = 0; c < 3; ++c)
  {
    addFloats(cloud.LogScales, "scale_" + std::to_string(c), c, 3);
  }
  for (int c = 0; c < 4; ++c)
  {
    addFloats(cloud.Rotations, "rot_" + std::to_string(c), c, 4);
  }
  for (const auto& e : cloud.Extra)
  {
    if (e.Name == "nx" || e.Name == "ny" || e.Name == "nz")
    {
      continue;
    }
    Column c;
    c.Name = e.Name;
    c.Type = e.Type;
    c.Extra = &e;
    cols.push_back(c);
  }
  for (const auto& e : appended)
  {
    Column c;
    c.Name = e.Name;
    c.Type = e.Type;
    c.Extra = &e;
    cols.push_back(c);
  }
  if (!cloud.Ids.empty() && options.WriteIds)
  {
    Column c;
    c.Name = options.IdProperty.empty() ? "id" : options.IdProperty;
    c.Ids = cloud.Ids.data();
    c.Type = ScalarType::Int32;
    for (std::int64_t id : cloud.Ids)
    {
      if (id < std::numeric_limits<std::int32_t>::min() ||
        id > std::numeric_limits<std::int32_t>::max())
      {
        c.Type = ScalarType::Float64;
        break;
      }
    }
    cols.push_back(c);
  }
  for (std::size_t i = 0; i < cols.size(); ++i)
  {
    for (std::size_t j = 0; j < i; ++j)
    {
      if (cols[i].Name == cols[j].Name)
      {
        throw std::invalid_argument(
          "WriteGaussianPly: two properties named '" + cols[i].Name + "'");
      }
    }
    for (char ch : cols[i].Name)
    {
      if (ch == ' ' || ch == '\t' || ch == '\n' || ch == '\r')
      {
        throw std::invalid_argument(
          "WriteGaussianPly: property name '" + cols[i].Name + "' contains white space");
      }
    }
  }
  return cols;
}

//------------------------------------------------------------------------------
void AppendFloatText(std::string& out, std::uint32_t bits)
{
  char buf[64];
  if (!detail::FloatBitsFinite(bits) && (bits & 0x7fffffu))
  {
    const bool neg = bits & 0x80000000u;
    const std::uint32_t payload = bits & 0x7fffffu;
    if (payload == 0x400000u)
    {
      out += neg ? "-nan" : "nan";
    }
    else
    {
      out += neg ? "-nan(0x" : "nan(0x";
      const auto r = std::to_chars(buf, buf + sizeof(buf), payload, 16);
      out.append(buf, r.ptr);
      out += ')';
    }
    return;
  }
  float f;
  std::memcpy(&f, &bits, 4);
  const auto r = std::to_chars(buf, buf + sizeof(buf), f);
  out.append(buf, r.ptr);
}

void AppendDoubleText(std::string& out, double v)
{
  char buf[64];
  if (std::isnan(v))
  {
    out += std::signbit(v) ? "-nan" : "nan";
    return;
  }
  const auto r = std::to_chars(buf, buf + sizeof(buf), v);
  out.append(buf, r.ptr);
}

//------------------------------------------------------------------------------
void WritePly(const GaussianCloud& cloud,
  const GaussianWriteOptions& options,
  const std::function<void(const void*, std::size_t)>& sink)
{
  const std::vector<Column> cols = WriterColumns(cloud, options);
  std::string header = "ply\nformat ";
  header += options.Format == PlyFormat::Ascii     ? "ascii"
    : options.Format == PlyFormat::BinaryBigEndian ? "binary_big_endian"
                                                   : "binary_little_endian";
  header += " 1.0\n";
  for (const auto& c : options.Comments)
  {
    std::string line = c;
    std::replace(line.begin(), line.end(), '\n', ' ');
    std::replace(line.begin(), line.end(), '\r', ' ');
    header += "comment " + line + "\n";
  }
  header += "element vertex " + std::to_string(cloud.Count) + "\n";
  std::size_t rowSize = 0;
  std::vector<std::size_t> offsets;
  for (const auto& c : cols)
  {
    header += std::string("property ") + detail::PlyScalarTypeName(c.Type) + " " + c.Name + "\n";
    offsets.push_back(rowSize);
    rowSize += ScalarTypeSize(c.Type);
  }
  header += "end_header\n";
  sink(header.data(), header.size());
  const std::size_t n = cloud.Count;
  if (n == 0 || cols.empty())
  {
    return;
  }

  if (options.Format == PlyFormat::Ascii)
  {
    std::string out;
    out.reserve(1 << 20);
    for (std::size_t g = 0; g < n; ++g)
    {
      for (std::size_t i = 0; i < cols.size(); ++i)
      {
        const Column& c = cols[i];
        if (i)
        {
          out += ' ';
        }
        if (c.Src)
        {
          std::uint32_t bits;
          std::memcpy(&bits, c.Src + g * c.Stride, 4);
          AppendFloatText(out, bits);
        }
        else if (c.Ids)
        {
          if (c.Type == ScalarType::Int32)
          {
            out += std::to_string(c.Ids[g]);
          }
          else
          {
            AppendDoubleText(out, static_cast<double>(c.Ids[g]));
          }
        }
        else if (c.Type == ScalarType::Float32)
        {
          std::uint32_t bits;
          std::memcpy(&bits, c.Extra->Bytes.data() + 4 * g, 4);
          AppendFloatText(out, bits);
        }
        else if (c.Type == ScalarType::Float64)
        {
          AppendDoubleText(out, c.Extra->GetAsDouble(g));
        }
        else
        {
          out += std::to_string(static_cast<long long>(c.Extra->GetAsDouble(g)));
        }
      }
      out += '\n';
      if (out.size() > (1u << 20))
      {
        sink(out.data(), out.size());
        out.clear();
      }
    }
    sink(out.data(), out.size());
    return;
  }

  const bool swap = (options.Format == PlyFormat::BinaryBigEndian) == detail::HostIsLittleEndian();
  const std::size_t rowsPerChunk = std::max<std::size_t>(1, (std::size_t(8) << 20) / rowSize);
  std::vector<unsigned char> buffer;
  for (std::size_t first = 0; first < n; first += rowsPerChunk)
  {
    const std::size_t count = std::min(rowsPerChunk, n - first);
    buffer.resize(count * rowSize);
#pragma omp parallel for schedule(static) if (count > 4096)
    for (long long r = 0; r < static_cast<long long>(count); ++r)
    {
      const std::size_t g = first + static_cast<std::size_t>(r);
      unsigned char* row = buffer.data() + static_cast<std::size_t>(r) * rowSize;
      for (std::size_t i = 0; i < cols.size(); ++i)
      {
        const Column& c = cols[i];
        unsigned char* d = row + offsets[i];
        const std::size_t sz = ScalarTypeSize(c.Type);
        if (c.Src)
        {
          std::memcpy(d, c.Src + g * c.Stride, 4);
        }
        else if (c.Ids)
        {
          if (c.Type == ScalarType::Int32)
          {
            const std::int32_t v = static_cast<std::int32_t>(c.Ids[g]);
            std::memcpy(d, &v, 4);
          }
          else
          {
            const double v = static_cast<double>(c.Ids[g]);
            std::memcpy(d, &v, 8);
          }
        }
        else
        {
          std::memcpy(d, c.Extra->Bytes.data() + g * sz, sz);
        }
        if (swap)
        {
          detail::SwapBytes(d, sz);
        }
      }
    }
    sink(buffer.data(), buffer.size());
  }
}

} // namespace

//------------------------------------------------------------------------------
void WriteGaussianPly(const std::string& path,
  const GaussianCloud& cloud,
  const GaussianWriteOptions& options)
{
  // Validate before creating anything.
  WriterColumns(cloud, options);
  detail::WriteFileAtomically(path,
    [&](std::FILE* f)
    {
      WritePly(
        cloud, options, [&](const void* d, std::size_t n) { detail::WriteBytes(f, d, n, path); });
    });
}

//------------------------------------------------------------------------------
std::vector<unsigned char> WriteGaussianPlyToMemory(const GaussianCloud& cloud,
  const GaussianWriteOptions& options)
{
  std::vector<unsigned char> out;
  WritePly(cloud,
    options,
    [&](const void* d, std::size_t n)
    {
      const auto* b = static_cast<const unsigned char*>(d);
      out.insert(out.end(), b, b + n);
    });
  return out;
}

} // namespace vis4gs

// SPDX-License-Identifier: BSD-3-Clause
// The PLY header parser (PlyHeader.h) of the INRIA PLY reader (GaussianPly.cxx) and the
// compressed PLY reader (GaussianCompressedPly.cxx).
#include "PlyHeader.h"

#include "SceneFile.h"

#include <charconv>
#include <stdexcept>
#include <string_view>
#include <utility>

namespace vis4gs
{
namespace detail
{
namespace
{

constexpr std::size_t MaxHeaderBytes = MaxPlyHeaderBytes;

//------------------------------------------------------------------------------
[[noreturn]] void Fail(const std::string& name, const std::string& what)
{
  throw std::runtime_error(name + ": " + what);
}

//------------------------------------------------------------------------------
bool ParseScalarType(std::string_view s, ScalarType& t)
{
  static const std::pair<const char*, ScalarType> names[] = { { "char", ScalarType::Int8 },
    { "int8", ScalarType::Int8 },
    { "uchar", ScalarType::UInt8 },
    { "uint8", ScalarType::UInt8 },
    { "short", ScalarType::Int16 },
    { "int16", ScalarType::Int16 },
    { "ushort", ScalarType::UInt16 },
    { "uint16", ScalarType::UInt16 },
    { "int", ScalarType::Int32 },
    { "int32", ScalarType::Int32 },
    { "uint", ScalarType::UInt32 },
    { "uint32", ScalarType::UInt32 },
    { "float", ScalarType::Float32 },
    { "float32", ScalarType::Float32 },
    { "double", ScalarType::Float64 },
    { "float64", ScalarType::Float64 } };
  for (const auto& n : names)
  {
    if (s == n.first)
    {
      t = n.second;
      return true;
    }
  }
  return false;
}

//------------------------------------------------------------------------------
bool ParseCount(std::string_view s, std::uint64_t& v)
{
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

} // namespace

//------------------------------------------------------------------------------
PlyHeader ParsePlyHeader(const unsigned char* data, std::size_t size, const std::string& name)
{
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  if (text.size() < 4 || text.substr(0, 3) != "ply" || (text[3] != '\n' && text[3] != '\r'))
  {
    Fail(name, "not a PLY file (it does not start with 'ply')");
  }
  PlyHeader header;
  bool haveFormat = false;
  std::size_t pos = 0;
  int lineNo = 0;
  while (true)
  {
    const std::size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos)
    {
      if (size >= MaxHeaderBytes)
      {
        Fail(name, "no 'end_header' line within the first 1 MiB");
      }
      Fail(name, "file ends inside the PLY header (no 'end_header' line)");
    }
    std::string_view line = text.substr(pos, eol - pos);
    pos = eol + 1;
    ++lineNo;
    if (lineNo == 1)
    {
      continue; // "ply"
    }
    const auto tok = detail::SplitWords(line);
    const std::string where = "header line " + std::to_string(lineNo) + ": ";
    if (tok.empty())
    {
      continue;
    }
    if (tok[0] == "end_header")
    {
      break;
    }
    if (tok[0] == "comment" || tok[0] == "obj_info")
    {
      if (tok[0] == "comment")
      {
        std::string_view c = line.substr(line.find("comment") + 7);
        const auto b = c.find_first_not_of(" \t");
        const auto e = c.find_last_not_of(" \t\r");
        header.Comments.emplace_back(
          b == std::string_view::npos ? std::string_view() : c.substr(b, e - b + 1));
      }
      continue;
    }
    if (tok[0] == "format")
    {
      if (tok.size() != 3)
      {
        Fail(name, where + "malformed 'format' line");
      }
      if (tok[1] == "binary_little_endian")
      {
        header.Format = PlyFormat::BinaryLittleEndian;
      }
      else if (tok[1] == "binary_big_endian")
      {
        header.Format = PlyFormat::BinaryBigEndian;
      }
      else if (tok[1] == "ascii")
      {
        header.Format = PlyFormat::Ascii;
      }
      else
      {
        Fail(name, where + "unknown PLY format '" + std::string(tok[1]) + "'");
      }
      haveFormat = true;
    }
    else if (tok[0] == "element")
    {
      PlyElement e;
      if (tok.size() != 3 || !ParseCount(tok[2], e.Count))
      {
        Fail(name, where + "malformed 'element' line (expected 'element <name> <count>')");
      }
      e.Name = std::string(tok[1]);
      header.Elements.push_back(std::move(e));
    }
    else if (tok[0] == "property")
    {
      if (header.Elements.empty())
      {
        Fail(name, where + "'property' before any 'element'");
      }
      PlyElement& e = header.Elements.back();
      PlyProperty p;
      if (tok.size() == 5 && tok[1] == "list")
      {
        ScalarType item;
        if (!ParseScalarType(tok[2], p.CountType) || !ParseScalarType(tok[3], item))
        {
          Fail(name, where + "unknown type in list property '" + std::string(tok[4]) + "'");
        }
        if (p.CountType == ScalarType::Float32 || p.CountType == ScalarType::Float64)
        {
          Fail(name, where + "list count type must be an integer type");
        }
        p.Type = item;
        p.IsList = true;
        p.Name = std::string(tok[4]);
        e.HasList = true;
      }
      else if (tok.size() == 3)
      {
        if (!ParseScalarType(tok[1], p.Type))
        {
          Fail(name,
            where + "unknown type '" + std::string(tok[1]) + "' of property '" +
              std::string(tok[2]) + "'");
        }
        p.Name = std::string(tok[2]);
        p.Offset = e.RowSize;
        e.RowSize += ScalarTypeSize(p.Type);
      }
      else
      {
        Fail(name, where + "malformed 'property' line");
      }
      for (const auto& q : e.Properties)
      {
        if (q.Name == p.Name)
        {
          Fail(name, where + "property '" + p.Name + "' appears twice in element '" + e.Name + "'");
        }
      }
      e.Properties.push_back(std::move(p));
    }
    else
    {
      Fail(name, where + "unknown header keyword '" + std::string(tok[0]) + "'");
    }
  }
  if (!haveFormat)
  {
    Fail(name, "PLY header has no 'format' line");
  }
  header.Bytes = pos;
  return header;
}

//------------------------------------------------------------------------------
const char* PlyScalarTypeName(ScalarType t)
{
  switch (t)
  {
    case ScalarType::Int8:
      return "char";
    case ScalarType::UInt8:
      return "uchar";
    case ScalarType::Int16:
      return "short";
    case ScalarType::UInt16:
      return "ushort";
    case ScalarType::Int32:
      return "int";
    case ScalarType::UInt32:
      return "uint";
    case ScalarType::Float32:
      return "float";
    case ScalarType::Float64:
      return "double";
  }
  return "float";
}

//------------------------------------------------------------------------------

} // namespace detail
} // namespace vis4gs

// SPDX-License-Identifier: BSD-3-Clause
// glTF 2.0 scenes with KHR_gaussian_splatting, plain or with the SPZ payload of the draft
// KHR_gaussian_splatting_compression_spz_2 (Documentation/file-formats.md, "glTF"): the GLB
// container or JSON with data-URI or external buffers, accessors of every component type the
// extension allows, and the whole node hierarchy. Splats are read in glTF's frame (+Y up),
// moved by their node's global transform, then turned into the PLY's axes the way
// splat-transform's .glb writer turns them out of it (180 degrees about z), so that the two
// round trips cancel exactly.
#include "GaussianGltf.h"
#include "GaussianIO.h"
#include "GaussianMath.h"
#include "SceneFile.h"

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <deque>
#include <limits>
#include <set>
#include <stdexcept>

namespace vis4gs
{
namespace
{
using Json = nlohmann::json;

constexpr std::uint32_t GlbMagic = 0x46546C67; // "glTF"
constexpr std::uint32_t JsonChunk = 0x4E4F534A;
constexpr std::uint32_t BinChunk = 0x004E4942;

[[noreturn]] void Fail(const std::string& name, const std::string& what)
{
  throw std::runtime_error(name + ": " + what);
}

struct Bytes
{
  const unsigned char* Data = nullptr;
  std::size_t Size = 0;
};

/// The parsed JSON and every buffer it names, loaded.
struct Document
{
  std::string Name;
  Json Root;
  std::vector<Bytes> Buffers;
  std::deque<std::vector<unsigned char>> Storage; ///< data-URI and external buffers
};

/// A non-negative integer member (glTF indices, counts, offsets), or @p fallback if absent.
std::size_t Unsigned(const Document& doc,
  const Json& object,
  const char* key,
  const std::string& where,
  std::size_t fallback = std::numeric_limits<std::size_t>::max())
{
  const auto it = object.find(key);
  if (it == object.end())
  {
    if (fallback == std::numeric_limits<std::size_t>::max())
    {
      Fail(doc.Name, where + " has no '" + key + "'");
    }
    return fallback;
  }
  if (!it->is_number_unsigned())
  {
    Fail(doc.Name, where + "." + key + " is not a non-negative integer");
  }
  return it->get<std::size_t>();
}

const Json& Element(const Document& doc,
  const char* array,
  std::size_t index,
  const std::string& who)
{
  const auto it = doc.Root.find(array);
  if (it == doc.Root.end() || !it->is_array() || index >= it->size())
  {
    Fail(doc.Name,
      who + " refers to " + array + "[" + std::to_string(index) + "], which does not exist");
  }
  const Json& e = (*it)[index];
  if (!e.is_object())
  {
    Fail(doc.Name, std::string(array) + "[" + std::to_string(index) + "] is not an object");
  }
  return e;
}

std::string PercentDecode(const std::string& uri)
{
  std::string out;
  for (std::size_t i = 0; i < uri.size(); ++i)
  {
    if (uri[i] == '%' && i + 2 < uri.size() &&
      std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
      std::isxdigit(static_cast<unsigned char>(uri[i + 2])))
    {
      out += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    }
    else
    {
      out += uri[i];
    }
  }
  return out;
}

/// Loads buffer @p i: the GLB's BIN chunk (no uri), a data URI, or a file beside the glTF.
Bytes LoadBuffer(Document& doc, std::size_t i, Bytes glbBin, const std::string& folder)
{
  const std::string where = "buffers[" + std::to_string(i) + "]";
  const Json& buffer = Element(doc, "buffers", i, where);
  const std::size_t length = Unsigned(doc, buffer, "byteLength", where);
  const auto uri = buffer.find("uri");
  Bytes bytes;
  if (uri == buffer.end())
  {
    if (i != 0 || !glbBin.Data)
    {
      Fail(doc.Name, where + " has no uri and is not the GLB's binary chunk");
    }
    bytes = glbBin;
  }
  else if (!uri->is_string())
  {
    Fail(doc.Name, where + ".uri is not a string");
  }
  else
  {
    const std::string& u = uri->get_ref<const std::string&>();
    if (u.compare(0, 5, "data:") == 0)
    {
      const auto comma = u.find(',');
      if (comma == std::string::npos || u.rfind(";base64", comma) == std::string::npos)
      {
        Fail(doc.Name, where + " is a data URI that is not base64");
      }
      doc.Storage.push_back(detail::DecodeBase64(std::string_view(u).substr(comma + 1)));
      if (doc.Storage.back().empty() && comma + 1 < u.size())
      {
        Fail(doc.Name, where + " holds invalid base64");
      }
    }
    else if (folder.empty())
    {
      Fail(doc.Name,
        where + " names the external file '" + u + "', which a glTF read from memory cannot reach");
    }
    else if (u.find("://") != std::string::npos || u.empty() || u[0] == '/')
    {
      Fail(doc.Name, where + " names '" + u + "': only data URIs and relative file names are read");
    }
    else
    {
      doc.Storage.push_back(detail::ReadWholeFile(folder + "/" + PercentDecode(u)));
    }
    bytes = { doc.Storage.back().data(), doc.Storage.back().size() };
  }
  if (bytes.Size < length)
  {
    Fail(doc.Name,
      where + " declares " + std::to_string(length) + " bytes but holds " +
        std::to_string(bytes.Size));
  }
  bytes.Size = length;
  return bytes;
}

/// Parses a GLB container or a JSON glTF and loads every buffer.
Document Parse(const unsigned char* data,
  std::size_t size,
  const std::string& name,
  const std::string& folder)
{
  Document doc;
  doc.Name = name;
  Bytes json{ data, size }, bin;
  if (size >= 4 && detail::LoadLE32(data) == GlbMagic)
  {
    if (size < 20)
    {
      Fail(name, "the GLB header is truncated");
    }
    if (detail::LoadLE32(data + 4) != 2)
    {
      Fail(
        name, "GLB version " + std::to_string(detail::LoadLE32(data + 4)) + " (only 2 is defined)");
    }
    const std::uint64_t total = detail::LoadLE32(data + 8);
    if (total > size)
    {
      Fail(name,
        "the GLB header declares " + std::to_string(total) + " bytes but the file holds " +
          std::to_string(size));
    }
    std::uint64_t at = 12;
    bool first = true;
    while (at + 8 <= total)
    {
      const std::uint64_t length = detail::LoadLE32(data + at);
      const std::uint32_t type = detail::LoadLE32(data + at + 4);
      if (at + 8 + length > total)
      {
        Fail(name,
          "a GLB chunk of " + std::to_string(length) + " bytes at offset " + std::to_string(at) +
            " runs past the end");
      }
      if (first && type != JsonChunk)
      {
        Fail(name, "the first GLB chunk is not JSON");
      }
      if (first)
      {
        json = { data + at + 8, static_cast<std::size_t>(length) };
      }
      else if (type == BinChunk && !bin.Data)
      {
        bin = { data + at + 8, static_cast<std::size_t>(length) };
      }
      first = false;
      at += 8 + length;
    }
    if (first)
    {
      Fail(name, "the GLB has no JSON chunk");
    }
  }
  try
  {
    doc.Root = Json::parse(json.Data, json.Data + json.Size);
  }
  catch (const Json::exception& e)
  {
    Fail(name, std::string("invalid glTF JSON: ") + e.what());
  }
  if (!doc.Root.is_object())
  {
    Fail(name, "the glTF JSON is not an object");
  }
  const auto asset = doc.Root.find("asset");
  if (asset == doc.Root.end() || !asset->is_object() || asset->value("version", "") != "2.0")
  {
    Fail(name, "not a glTF 2.0 asset (asset.version must be \"2.0\")");
  }
  const auto buffers = doc.Root.find("buffers");
  const std::size_t n = buffers != doc.Root.end() && buffers->is_array() ? buffers->size() : 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    doc.Buffers.push_back(LoadBuffer(doc, i, bin, folder));
  }
  return doc;
}

/// A bufferView's bytes (checked against its buffer) and its stride (0 if none).
Bytes ViewBytes(const Document& doc, std::size_t index, std::size_t* stride, const std::string& who)
{
  const std::string where = "bufferViews[" + std::to_string(index) + "]";
  const Json& view = Element(doc, "bufferViews", index, who);
  const std::size_t buffer = Unsigned(doc, view, "buffer", where);
  if (buffer >= doc.Buffers.size())
  {
    Fail(
      doc.Name, where + " refers to buffers[" + std::to_string(buffer) + "], which does not exist");
  }
  const std::size_t offset = Unsigned(doc, view, "byteOffset", where, 0);
  const std::size_t length = Unsigned(doc, view, "byteLength", where);
  const Bytes& b = doc.Buffers[buffer];
  if (offset > b.Size || length > b.Size - offset)
  {
    Fail(doc.Name,
      where + " (offset " + std::to_string(offset) + ", " + std::to_string(length) +
        " bytes) runs past the end of its buffer of " + std::to_string(b.Size) + " bytes");
  }
  if (stride)
  {
    *stride = Unsigned(doc, view, "byteStride", where, 0);
  }
  return { b.Data + offset, length };
}

int ComponentCount(const std::string& type)
{
  return type == "SCALAR" ? 1
    : type == "VEC2"      ? 2
    : type == "VEC3"      ? 3
    : type == "VEC4"      ? 4
    : type == "MAT4"      ? 16
                          : 0;
}

std::size_t ComponentSize(std::size_t componentType)
{
  switch (componentType)
  {
    case 5120: // BYTE
    case 5121: // UNSIGNED_BYTE
      return 1;
    case 5122: // SHORT
    case 5123: // UNSIGNED_SHORT
      return 2;
    case 5125: // UNSIGNED_INT
    case 5126: // FLOAT
      return 4;
    default:
      return 0;
  }
}

/// One accessor, checked against its bufferView; values read as float.
struct Accessor
{
  std::size_t Count = 0;
  int Components = 0;
  std::size_t ComponentType = 0;
  bool Normalized = false;
  const unsigned char* Data = nullptr;
  std::size_t Stride = 0;

  /// Component @p c of element @p i; floats bit for bit, normalised integers as glTF defines.
  float Get(std::size_t i, int c) const
  {
    const unsigned char* p = this->Data + i * this->Stride + c * ComponentSize(this->ComponentType);
    switch (this->ComponentType)
    {
      case 5126:
        return detail::LoadLEFloat(p);
      case 5121:
        return this->Normalized ? static_cast<float>(p[0] / 255.0) : static_cast<float>(p[0]);
      case 5120:
      {
        const auto v = static_cast<std::int8_t>(p[0]);
        return this->Normalized ? static_cast<float>(std::max(v / 127.0, -1.0))
                                : static_cast<float>(v);
      }
      case 5123:
      {
        const auto v = detail::LoadLE16(p);
        return this->Normalized ? static_cast<float>(v / 65535.0) : static_cast<float>(v);
      }
      case 5122:
      {
        const auto v = static_cast<std::int16_t>(detail::LoadLE16(p));
        return this->Normalized ? static_cast<float>(std::max(v / 32767.0, -1.0))
                                : static_cast<float>(v);
      }
      default:
        return static_cast<float>(detail::LoadLE32(p));
    }
  }
};

Accessor GetAccessor(const Document& doc,
  std::size_t index,
  const std::string& semantic,
  int components)
{
  const std::string where = "accessors[" + std::to_string(index) + "] (" + semantic + ")";
  const Json& a = Element(doc, "accessors", index, semantic);
  Accessor out;
  out.Count = Unsigned(doc, a, "count", where);
  out.ComponentType = Unsigned(doc, a, "componentType", where);
  out.Normalized = a.value("normalized", false);
  const auto type = a.find("type");
  out.Components =
    type != a.end() && type->is_string() ? ComponentCount(type->get<std::string>()) : 0;
  const std::size_t size = ComponentSize(out.ComponentType);
  if (size == 0)
  {
    Fail(doc.Name, where + " has the unknown componentType " + std::to_string(out.ComponentType));
  }
  if (out.Components != components)
  {
    Fail(doc.Name,
      where + " has type " + (type != a.end() ? type->dump() : "none") + "; " + semantic +
        " needs " + std::to_string(components) + " components");
  }
  if (a.contains("sparse"))
  {
    Fail(doc.Name, where + " is sparse; sparse accessors are not read");
  }
  if (!a.contains("bufferView"))
  {
    Fail(doc.Name, where + " has no bufferView (all zeros); refused rather than read as zeros");
  }
  std::size_t stride = 0;
  const Bytes view = ViewBytes(doc, Unsigned(doc, a, "bufferView", where), &stride, where);
  const std::size_t offset = Unsigned(doc, a, "byteOffset", where, 0);
  const std::size_t element = size * static_cast<std::size_t>(components);
  out.Stride = stride ? stride : element;
  if (out.Stride < element)
  {
    Fail(
      doc.Name, where + ": byteStride " + std::to_string(stride) + " is shorter than an element");
  }
  if (out.Count == 0 || offset > view.Size || out.Count > view.Size ||
    (out.Count - 1) * out.Stride + element > view.Size - offset)
  {
    Fail(doc.Name,
      where + ": " + std::to_string(out.Count) + " elements at offset " + std::to_string(offset) +
        " do not fit its bufferView of " + std::to_string(view.Size) + " bytes");
  }
  out.Data = view.Data + offset;
  return out;
}

/// The SH coefficients of degree @p l as KHR_gaussian_splatting names them.
std::string ShSemantic(int l, int m)
{
  return "KHR_gaussian_splatting:SH_DEGREE_" + std::to_string(l) + "_COEF_" + std::to_string(m);
}

/// Reads one plain splat primitive into a cloud in glTF's frame.
GaussianCloud ReadPlainPrimitive(const Document& doc,
  const Json& attributes,
  const std::string& where,
  const GaussianReadOptions& options,
  GaussianReadReport& report)
{
  auto index = [&](const std::string& semantic) -> std::size_t
  {
    const auto it = attributes.find(semantic);
    if (it == attributes.end())
    {
      return std::numeric_limits<std::size_t>::max();
    }
    if (!it->is_number_unsigned())
    {
      Fail(doc.Name, where + ": attribute " + semantic + " is not an accessor index");
    }
    return it->get<std::size_t>();
  };
  auto require = [&](const std::string& semantic)
  {
    const std::size_t i = index(semantic);
    if (i == std::numeric_limits<std::size_t>::max())
    {
      Fail(doc.Name,
        where + " has no " + semantic + " attribute (required by KHR_gaussian_splatting)");
    }
    return i;
  };
  const Accessor pos = GetAccessor(doc, require("POSITION"), "POSITION", 3);
  const std::size_t n = pos.Count;
  auto get = [&](const std::string& semantic, int components)
  {
    const Accessor a = GetAccessor(doc, require(semantic), semantic, components);
    if (a.Count != n)
    {
      Fail(doc.Name,
        where + ": " + semantic + " has " + std::to_string(a.Count) + " elements, POSITION " +
          std::to_string(n));
    }
    return a;
  };
  int fileDegree = 0;
  for (int l = 1; l <= 3; ++l)
  {
    int present = 0;
    for (int m = 0; m < 2 * l + 1; ++m)
    {
      present += index(ShSemantic(l, m)) != std::numeric_limits<std::size_t>::max();
    }
    if (present != 0 && (present != 2 * l + 1 || fileDegree != l - 1))
    {
      Fail(doc.Name,
        where + ": SH degree " + std::to_string(l) +
          " is partially defined (the extension requires every coefficient of a degree and of the "
          "degrees below)");
    }
    fileDegree = present ? l : fileDegree;
  }
  report.FileShDegree = fileDegree;
  GaussianCloud cloud =
    detail::AllocateReadArrays(n, std::min(fileDegree, std::max(0, options.MaxShDegree)), options);
  if (options.LoadPositions)
  {
    for (std::size_t i = 0; i < n; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        cloud.Positions[3 * i + c] = pos.Get(i, c);
      }
    }
  }
  if (options.LoadRotations)
  {
    const Accessor rot = get("KHR_gaussian_splatting:ROTATION", 4);
    for (std::size_t i = 0; i < n; ++i)
    {
      cloud.Rotations[4 * i] = rot.Get(i, 3);
      for (int c = 0; c < 3; ++c)
      {
        cloud.Rotations[4 * i + 1 + c] = rot.Get(i, c);
      }
    }
  }
  if (options.LoadScales)
  {
    const Accessor scale = get("KHR_gaussian_splatting:SCALE", 3);
    for (std::size_t i = 0; i < 3 * n; ++i)
    {
      cloud.LogScales[i] = static_cast<float>(
        std::log(static_cast<double>(scale.Get(i / 3, static_cast<int>(i % 3)))));
    }
  }
  const std::string color0 = "COLOR_0";
  const bool hasDc = index(ShSemantic(0, 0)) != std::numeric_limits<std::size_t>::max();
  const bool hasOpacity =
    index("KHR_gaussian_splatting:OPACITY") != std::numeric_limits<std::size_t>::max();
  Accessor color;
  if (!hasDc || !hasOpacity)
  {
    // The fallback colour stands in, with what it loses (8 bits, clamped to [0, 1]) said.
    const std::size_t i = require(color0);
    const Json& a = Element(doc, "accessors", i, color0);
    color = get(color0, a.value("type", "") == "VEC3" ? 3 : 4);
    if (!hasOpacity && color.Components != 4)
    {
      Fail(doc.Name, where + " has neither KHR_gaussian_splatting:OPACITY nor an alpha in COLOR_0");
    }
    report.Warnings.push_back(doc.Name + ": " + where + " lacks " +
      (hasDc ? "" : "SH_DEGREE_0_COEF_0 ") + (hasOpacity ? "" : "OPACITY ") +
      "and takes them from the fallback COLOR_0 (clamped to [0, 1], as precise as its accessor)");
  }
  if (options.LoadOpacities)
  {
    const Accessor opacity = hasOpacity ? get("KHR_gaussian_splatting:OPACITY", 1) : color;
    const int c = hasOpacity ? 0 : 3;
    for (std::size_t i = 0; i < n; ++i)
    {
      const double o = opacity.Get(i, c);
      cloud.OpacityLogits[i] = static_cast<float>(std::log(o) - std::log1p(-o));
    }
  }
  if (options.LoadSH)
  {
    const std::size_t k = static_cast<std::size_t>(cloud.ShCoefficientCount());
    for (int l = 0; l <= cloud.ShDegree; ++l)
    {
      for (int m = 0; m < 2 * l + 1; ++m)
      {
        const std::size_t coef = static_cast<std::size_t>(l * l + m);
        if (coef == 0 && !hasDc)
        {
          for (std::size_t i = 0; i < n; ++i)
          {
            for (int c = 0; c < 3; ++c)
            {
              // COLOR_0 is linear; the splats' colour space is the extension's.
              cloud.SH[3 * k * i + c] =
                static_cast<float>((detail::LinearToSrgb(color.Get(i, c)) - 0.5) / sh::C0);
            }
          }
          continue;
        }
        const Accessor a = get(ShSemantic(l, m), 3);
        for (std::size_t i = 0; i < n; ++i)
        {
          for (int c = 0; c < 3; ++c)
          {
            cloud.SH[3 * (k * i + coef) + c] = a.Get(i, c);
          }
        }
      }
    }
  }
  if (options.LoadExtras)
  {
    // Application-specific attributes (a leading underscore): per-Gaussian scalars such as
    // the scores Vis4GS's writer keeps, in the order of their accessors (the writer's order;
    // JSON objects have none).
    std::vector<std::pair<std::size_t, std::string>> extras;
    for (auto it = attributes.begin(); it != attributes.end(); ++it)
    {
      if (it.key().size() >= 2 && it.key()[0] == '_' && it->is_number_unsigned() &&
        Element(doc, "accessors", it->get<std::size_t>(), it.key()).value("type", "") == "SCALAR")
      {
        extras.emplace_back(it->get<std::size_t>(), it.key());
      }
    }
    std::sort(extras.begin(), extras.end());
    for (const auto& [accessor, semantic] : extras)
    {
      const Accessor acc = get(semantic, 1);
      ExtraProperty extra;
      extra.Name = semantic.substr(1);
      const ScalarType types[] = { ScalarType::Int8,
        ScalarType::UInt8,
        ScalarType::Int16,
        ScalarType::UInt16,
        ScalarType::Float32,
        ScalarType::UInt32,
        ScalarType::Float32 };
      const bool raw = !acc.Normalized && acc.ComponentType != 5126;
      extra.Type = raw ? types[acc.ComponentType - 5120] : ScalarType::Float32;
      const std::size_t size = ScalarTypeSize(extra.Type);
      extra.Bytes.resize(size * n);
      for (std::size_t i = 0; i < n; ++i)
      {
        const unsigned char* p = acc.Data + i * acc.Stride;
        unsigned char* q = &extra.Bytes[size * i];
        if (raw)
        {
          // Little-endian in the file, native in ExtraProperty.
          for (std::size_t b = 0; b < size; ++b)
          {
            q[detail::HostIsLittleEndian() ? b : size - 1 - b] = p[b];
          }
        }
        else
        {
          const float v = acc.Get(i, 0);
          std::memcpy(q, &v, 4);
        }
      }
      cloud.Extra.push_back(std::move(extra));
    }
  }
  return cloud;
}

/// A primitive with its node's global transform (column-major 4x4).
struct Instance
{
  const Json* Primitive = nullptr;
  Eigen::Matrix4d World = Eigen::Matrix4d::Identity();
  std::size_t Node = 0;
  std::size_t Mesh = 0;
};

Eigen::Matrix4d LocalMatrix(const Document& doc, const Json& node, const std::string& where)
{
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  auto numbers = [&](const char* key, std::size_t count, std::vector<double>& out)
  {
    const auto it = node.find(key);
    if (it == node.end())
    {
      return false;
    }
    if (!it->is_array() || it->size() != count)
    {
      Fail(
        doc.Name, where + "." + key + " is not an array of " + std::to_string(count) + " numbers");
    }
    for (const auto& v : *it)
    {
      if (!v.is_number())
      {
        Fail(doc.Name, where + "." + key + " holds a value that is not a number");
      }
      out.push_back(v.get<double>());
    }
    return true;
  };
  std::vector<double> v;
  if (numbers("matrix", 16, v))
  {
    for (int i = 0; i < 16; ++i)
    {
      m(i % 4, i / 4) = v[i];
    }
    return m;
  }
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  if (v.clear(), numbers("rotation", 4, v))
  {
    r = Eigen::Quaterniond(v[3], v[0], v[1], v[2]).normalized().toRotationMatrix();
  }
  Eigen::Vector3d s(1, 1, 1);
  if (v.clear(), numbers("scale", 3, v))
  {
    s = Eigen::Vector3d(v[0], v[1], v[2]);
  }
  m.topLeftCorner<3, 3>() = r * s.asDiagonal();
  if (v.clear(), numbers("translation", 3, v))
  {
    m.topRightCorner<3, 1>() = Eigen::Vector3d(v[0], v[1], v[2]);
  }
  return m;
}

/// Limits that keep a small file from expanding without bound: glTF's node hierarchy is a
/// tree (a node reached twice would multiply its subtree, exponentially along a chain), and
/// one mesh instanced many times multiplies its Gaussians.
constexpr int MaxNodeDepth = 256;
constexpr std::size_t MaxInstancesPerMesh = 16;

void CollectInstances(const Document& doc,
  std::size_t nodeIndex,
  const Eigen::Matrix4d& parent,
  int depth,
  std::set<std::size_t>& visited,
  std::vector<Instance>& out)
{
  const std::string where = "nodes[" + std::to_string(nodeIndex) + "]";
  if (!visited.insert(nodeIndex).second)
  {
    Fail(doc.Name,
      where +
        " is reached twice (a cycle, or a node with two parents); glTF's node hierarchy is a tree");
  }
  if (depth > MaxNodeDepth)
  {
    Fail(doc.Name,
      where + " lies deeper than " + std::to_string(MaxNodeDepth) +
        " levels in the node hierarchy; refused");
  }
  const Json& node = Element(doc, "nodes", nodeIndex, "a scene or node");
  const Eigen::Matrix4d world = parent * LocalMatrix(doc, node, where);
  if (node.contains("mesh"))
  {
    const std::size_t meshIndex = Unsigned(doc, node, "mesh", where);
    const Json& mesh = Element(doc, "meshes", meshIndex, where);
    const auto prims = mesh.find("primitives");
    if (prims != mesh.end() && prims->is_array())
    {
      for (const Json& p : *prims)
      {
        const auto ext = p.find("extensions");
        if (p.is_object() && ext != p.end() && ext->is_object() &&
          ext->contains(detail::GltfExtension))
        {
          const auto uses = std::count_if(
            out.begin(), out.end(), [&p](const Instance& i) { return i.Primitive == &p; });
          if (static_cast<std::size_t>(uses) >= MaxInstancesPerMesh)
          {
            Fail(doc.Name,
              "meshes[" + std::to_string(meshIndex) + "] is instanced by more than " +
                std::to_string(MaxInstancesPerMesh) +
                " nodes; refused (its Gaussians would be copied as many times)");
          }
          out.push_back({ &p, world, nodeIndex, meshIndex });
        }
      }
    }
  }
  const auto children = node.find("children");
  if (children != node.end())
  {
    if (!children->is_array())
    {
      Fail(doc.Name, where + ".children is not an array");
    }
    for (const Json& c : *children)
    {
      if (!c.is_number_unsigned())
      {
        Fail(doc.Name, where + ".children holds a value that is not a node index");
      }
      CollectInstances(doc, c.get<std::size_t>(), world, depth + 1, visited, out);
    }
  }
}

/// Appends @p part to @p all (SH cut to the lower degree; extras kept only if both agree).
void Append(GaussianCloud& all,
  GaussianCloud&& part,
  bool first,
  GaussianReadReport& report,
  const std::string& name)
{
  if (first)
  {
    all = std::move(part);
    return;
  }
  const int degree = std::min(all.ShDegree, part.ShDegree);
  auto cut = [degree](GaussianCloud& c)
  {
    if (c.ShDegree != degree)
    {
      c = detail::CutShDegree(c, degree);
    }
  };
  if (all.ShDegree != part.ShDegree)
  {
    report.Warnings.push_back(name +
      ": the splat primitives hold different SH degrees; all are read to degree " +
      std::to_string(degree));
  }
  cut(all);
  cut(part);
  bool sameExtras = all.Extra.size() == part.Extra.size();
  for (std::size_t e = 0; sameExtras && e < all.Extra.size(); ++e)
  {
    sameExtras = all.Extra[e].Name == part.Extra[e].Name && all.Extra[e].Type == part.Extra[e].Type;
  }
  if (!sameExtras)
  {
    report.Warnings.push_back(
      name + ": the splat primitives hold different extra attributes; none is kept");
    all.Extra.clear();
    part.Extra.clear();
  }
  auto join = [](auto& a, const auto& b) { a.insert(a.end(), b.begin(), b.end()); };
  join(all.Positions, part.Positions);
  join(all.LogScales, part.LogScales);
  join(all.Rotations, part.Rotations);
  join(all.OpacityLogits, part.OpacityLogits);
  join(all.SH, part.SH);
  for (std::size_t e = 0; e < all.Extra.size(); ++e)
  {
    join(all.Extra[e].Bytes, part.Extra[e].Bytes);
  }
  all.Count += part.Count;
}

GaussianCloud ReadDocument(Document& doc,
  const GaussianReadOptions& options,
  GaussianReadReport* reportOut)
{
  const std::string& name = doc.Name;
  if (!options.IdProperty.empty())
  {
    Fail(name, "a glTF scene has no id property '" + options.IdProperty + "'");
  }
  GaussianReadReport report;
  report.Format = "gltf";
  std::vector<Instance> instances;
  std::set<std::size_t> visited;
  const auto scenes = doc.Root.find("scenes");
  if (scenes != doc.Root.end() && scenes->is_array() && !scenes->empty())
  {
    const std::size_t s = Unsigned(doc, doc.Root, "scene", "the asset", 0);
    const Json& scene = Element(doc, "scenes", s, "the asset's scene");
    for (const Json& n : scene.value("nodes", Json::array()))
    {
      if (!n.is_number_unsigned())
      {
        Fail(
          name, "scenes[" + std::to_string(s) + "].nodes holds a value that is not a node index");
      }
      CollectInstances(
        doc, n.get<std::size_t>(), Eigen::Matrix4d::Identity(), 0, visited, instances);
    }
  }
  if (instances.empty())
  {
    Fail(name, "no node of the scene instances a mesh primitive with KHR_gaussian_splatting");
  }
  GaussianCloud all;
  for (std::size_t i = 0; i < instances.size(); ++i)
  {
    const Instance& inst = instances[i];
    const std::string where =
      "meshes[" + std::to_string(inst.Mesh) + "] of nodes[" + std::to_string(inst.Node) + "]";
    const Json& ext = (*inst.Primitive)["extensions"][detail::GltfExtension];
    if (inst.Primitive->value("mode", 4) != 0)
    {
      Fail(name, where + ": a KHR_gaussian_splatting primitive must have mode 0 (POINTS)");
    }
    const auto kernel = ext.find("kernel");
    if (kernel != ext.end() && *kernel != "ellipse")
    {
      Fail(name, where + " uses the kernel " + kernel->dump() + "; only \"ellipse\" is defined");
    }
    GaussianReadReport part;
    GaussianCloud cloud;
    const Json* spz = nullptr;
    if (ext.is_object() && ext.contains("extensions") && ext["extensions"].is_object() &&
      ext["extensions"].contains(detail::GltfSpzExtension))
    {
      spz = &ext["extensions"][detail::GltfSpzExtension];
    }
    if (spz)
    {
      const std::string w = where + " " + detail::GltfSpzExtension;
      const Bytes bytes = ViewBytes(doc, Unsigned(doc, *spz, "bufferView", w), nullptr, w);
      // Niantic's library stores RUB axes; our reader turns them into the PLY's, whose
      // glTF counterpart (LUF, what the draft asks the library for) is one exact turn away.
      cloud = ReadSpzFromMemory(bytes.Data, bytes.Size, name + " (" + w + ")", options, &part);
      detail::PlyToGltfAxes(cloud);
    }
    else
    {
      const auto attributes = inst.Primitive->find("attributes");
      if (attributes == inst.Primitive->end() || !attributes->is_object())
      {
        Fail(name, where + " has no attributes");
      }
      cloud = ReadPlainPrimitive(doc, *attributes, where, options, part);
    }
    detail::ApplyGltfTransform(
      cloud, inst.World.data(), name, "nodes[" + std::to_string(inst.Node) + "]", part.Warnings);
    report.FileShDegree =
      i == 0 ? part.FileShDegree : std::min(report.FileShDegree, part.FileShDegree);
    report.Warnings.insert(report.Warnings.end(), part.Warnings.begin(), part.Warnings.end());
    Append(all, std::move(cloud), i == 0, report, name);
  }
  detail::GltfToPlyAxes(all);
  for (std::size_t g = 0; g < all.Count; ++g)
  {
    bool bad = false;
    auto count = [&](const std::vector<float>& v, std::size_t per)
    {
      for (std::size_t j = per * g; j < per * (g + 1) && j < v.size(); ++j)
      {
        if (!std::isfinite(v[j]))
        {
          ++report.NonFiniteValues;
          bad = true;
        }
      }
    };
    count(all.Positions, 3);
    count(all.LogScales, 3);
    count(all.Rotations, 4);
    count(all.OpacityLogits, 1);
    count(all.SH, 3 * static_cast<std::size_t>(all.ShCoefficientCount()));
    report.NonFiniteGaussians += bad;
  }
  detail::FinishReadReport(report, name, reportOut, ", zero scales and opacities 0 or 1 included");
  return all;
}

GaussianCloud ReadBytes(const unsigned char* data,
  std::size_t size,
  const std::string& name,
  const std::string& folder,
  const GaussianReadOptions& options,
  GaussianReadReport* report)
{
  try
  {
    Document doc = Parse(data, size, name, folder);
    return ReadDocument(doc, options, report);
  }
  catch (const Json::exception& e)
  {
    // A member of the wrong JSON type where a default was allowed (mode, normalized, ...).
    throw std::runtime_error(name + ": a glTF member has the wrong type (" + e.what() + ")");
  }
}

} // namespace

//------------------------------------------------------------------------------
GaussianCloud ReadGltf(const std::string& path,
  const GaussianReadOptions& options,
  GaussianReadReport* report)
{
  const std::vector<unsigned char> bytes = detail::ReadWholeFile(path);
  return ReadBytes(bytes.data(), bytes.size(), path, detail::ParentFolder(path), options, report);
}

//------------------------------------------------------------------------------
GaussianCloud ReadGltfFromMemory(const void* data,
  std::size_t size,
  const std::string& name,
  const GaussianReadOptions& options,
  GaussianReadReport* report)
{
  const detail::ByteSource src = detail::MemorySource(data, size, name);
  return ReadBytes(src.Memory, static_cast<std::size_t>(src.Size), name, "", options, report);
}

//------------------------------------------------------------------------------
bool IsGltfFile(const std::string& path)
{
  try
  {
    if (!detail::IsRegularFile(path))
    {
      return false;
    }
    detail::InputFile file(path);
    std::vector<unsigned char> head(
      static_cast<std::size_t>(std::min<std::uint64_t>(file.Size(), 1 << 20)));
    file.ReadAt(0, head.data(), head.size());
    if (head.size() >= 4 && detail::LoadLE32(head.data()) == GlbMagic)
    {
      return true;
    }
    const auto first =
      std::find_if(head.begin(), head.end(), [](unsigned char c) { return !std::isspace(c); });
    if (first == head.end() || *first != '{')
    {
      return false;
    }
    const std::string text(head.begin(), head.end());
    return detail::LowerExtension(path) == ".gltf" ||
      (text.find("\"asset\"") != std::string::npos &&
        text.find(detail::GltfExtension) != std::string::npos);
  }
  catch (const std::runtime_error&)
  {
    return false;
  }
}

} // namespace vis4gs

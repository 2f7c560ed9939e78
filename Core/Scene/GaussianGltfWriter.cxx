// SPDX-License-Identifier: BSD-3-Clause
// The glTF KHR_gaussian_splatting writer (GaussianIO.h, WriteGltf): float32 attributes in one
// buffer, one accessor per attribute, as the Khronos validator accepts them.
#include "GaussianGltf.h"
#include "GaussianIO.h"
#include "GaussianMath.h"
#include "SceneFile.h"

#include <nlohmann/json.hpp>

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
using Json = nlohmann::json;

constexpr int Float = 5126;
constexpr int UnsignedByte = 5121;

/// One attribute's bytes and its accessor's description.
struct Attribute
{
  std::string Semantic;
  std::vector<unsigned char> Bytes;
  int ComponentType = Float;
  const char* Type = "SCALAR";
  bool Normalized = false;
};

void PutFloat(std::vector<unsigned char>& out, float v)
{
  std::uint32_t bits;
  std::memcpy(&bits, &v, 4);
  for (int i = 0; i < 4; ++i)
  {
    out.push_back(static_cast<unsigned char>(bits >> (8 * i)));
  }
}

/// The cloud's Gaussians that are written, turned into glTF's frame.
GaussianCloud Select(const GaussianCloud& cloud, int degree, std::vector<std::size_t>& order)
{
  const std::size_t k = static_cast<std::size_t>(cloud.ShCoefficientCount());
  const std::size_t kOut = static_cast<std::size_t>((degree + 1) * (degree + 1));
  for (std::size_t g = 0; g < cloud.Count; ++g)
  {
    if (detail::WritableGaussian(cloud, g, kOut))
    {
      order.push_back(g);
    }
  }
  GaussianCloud out;
  out.Resize(order.size(), degree);
  for (std::size_t i = 0; i < order.size(); ++i)
  {
    const std::size_t g = order[i];
    std::copy_n(&cloud.Positions[3 * g], 3, &out.Positions[3 * i]);
    std::copy_n(&cloud.LogScales[3 * g], 3, &out.LogScales[3 * i]);
    // Unit quaternions, as the extension requires (a zero one draws as the identity); one
    // already unit to float precision is kept as it is, so a glTF's rotations write back
    // bit for bit.
    const float* src = &cloud.Rotations[4 * g];
    double norm2 = 0;
    for (int c = 0; c < 4; ++c)
    {
      norm2 += double(src[c]) * src[c];
    }
    const double wide[4] = { src[0], src[1], src[2], src[3] };
    const auto q = NormalizeQuaternion<double>(wide);
    const bool zero = q[0] == 0 && q[1] == 0 && q[2] == 0 && q[3] == 0;
    for (int c = 0; c < 4; ++c)
    {
      out.Rotations[4 * i + c] = std::abs(norm2 - 1) < 1e-6 ? src[c] : zero ? float(c == 0) : q[c];
    }
    out.OpacityLogits[i] = cloud.OpacityLogits[g];
    std::copy_n(&cloud.SH[3 * k * g], 3 * kOut, &out.SH[3 * kOut * i]);
  }
  detail::PlyToGltfAxes(out);
  return out;
}

std::vector<Attribute> Encode(const GaussianCloud& cloud,
  const GaussianCloud& g,
  const std::vector<std::size_t>& order,
  const GltfWriteOptions& options,
  std::array<double, 6>& bounds)
{
  const std::size_t n = g.Count;
  std::vector<Attribute> out;
  auto add = [&](std::string semantic, const char* type)
  {
    out.push_back({ std::move(semantic), {}, Float, type, false });
    return &out.back().Bytes;
  };
  auto* pos = add("POSITION", "VEC3");
  bounds = { std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity(),
    -std::numeric_limits<double>::infinity(),
    -std::numeric_limits<double>::infinity(),
    -std::numeric_limits<double>::infinity() };
  for (std::size_t i = 0; i < 3 * n; ++i)
  {
    PutFloat(*pos, g.Positions[i]);
    bounds[i % 3] = std::min<double>(bounds[i % 3], g.Positions[i]);
    bounds[3 + i % 3] = std::max<double>(bounds[3 + i % 3], g.Positions[i]);
  }
  auto* rot = add("KHR_gaussian_splatting:ROTATION", "VEC4");
  for (std::size_t i = 0; i < n; ++i)
  {
    for (int c : { 1, 2, 3, 0 })
    {
      PutFloat(*rot, g.Rotations[4 * i + c]);
    }
  }
  auto* scale = add("KHR_gaussian_splatting:SCALE", "VEC3");
  for (std::size_t i = 0; i < 3 * n; ++i)
  {
    PutFloat(*scale, static_cast<float>(std::exp(static_cast<double>(g.LogScales[i]))));
  }
  auto* opacity = add("KHR_gaussian_splatting:OPACITY", "SCALAR");
  for (std::size_t i = 0; i < n; ++i)
  {
    PutFloat(*opacity, static_cast<float>(Sigmoid<double>(g.OpacityLogits[i])));
  }
  const std::size_t k = static_cast<std::size_t>(g.ShCoefficientCount());
  for (int l = 0; l <= g.ShDegree; ++l)
  {
    for (int m = 0; m < 2 * l + 1; ++m)
    {
      auto* sh =
        add("KHR_gaussian_splatting:SH_DEGREE_" + std::to_string(l) + "_COEF_" + std::to_string(m),
          "VEC3");
      for (std::size_t i = 0; i < n; ++i)
      {
        for (int c = 0; c < 3; ++c)
        {
          PutFloat(*sh, g.SH[3 * (k * i + static_cast<std::size_t>(l * l + m)) + c]);
        }
      }
    }
  }
  // The fallback colour for viewers without the extension: linear, as glTF defines COLOR_0.
  Attribute color{ "COLOR_0", {}, UnsignedByte, "VEC4", true };
  const bool srgb = options.ColorSpace == "srgb_rec709_display";
  for (std::size_t i = 0; i < n; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double v = std::min(1.0, std::max(0.0, sh::C0 * g.SH[3 * k * i + c] + 0.5));
      color.Bytes.push_back(
        static_cast<unsigned char>(std::lround(255 * (srgb ? detail::SrgbToLinear(v) : v))));
    }
    color.Bytes.push_back(
      static_cast<unsigned char>(std::lround(255 * Sigmoid<double>(g.OpacityLogits[i]))));
  }
  out.push_back(std::move(color));
  for (const ExtraProperty& e : options.KeepExtras ? cloud.Extra : std::vector<ExtraProperty>())
  {
    const int small = e.Type == ScalarType::Int8 ? 5120
      : e.Type == ScalarType::UInt8              ? 5121
      : e.Type == ScalarType::Int16              ? 5122
      : e.Type == ScalarType::UInt16             ? 5123
                                                 : 0;
    Attribute a{ "_" + e.Name, {}, small ? small : Float, "SCALAR", false };
    const std::size_t size = ScalarTypeSize(e.Type);
    for (const std::size_t src : order)
    {
      if (small)
      {
        for (std::size_t b = 0; b < size; ++b)
        {
          a.Bytes.push_back(
            e.Bytes[size * src + (detail::HostIsLittleEndian() ? b : size - 1 - b)]);
        }
      }
      else
      {
        PutFloat(a.Bytes, static_cast<float>(e.GetAsDouble(src)));
      }
    }
    out.push_back(std::move(a));
  }
  return out;
}

void Pad(std::vector<unsigned char>& bytes, unsigned char with)
{
  while (bytes.size() % 4)
  {
    bytes.push_back(with);
  }
}

std::vector<unsigned char> Assemble(const std::vector<Attribute>& attributes,
  std::size_t n,
  const std::array<double, 6>& bounds,
  bool binary,
  const GltfWriteOptions& options)
{
  std::vector<unsigned char> bin;
  Json views = Json::array(), accessors = Json::array(), semantics = Json::object();
  for (const Attribute& a : attributes)
  {
    const std::size_t index = accessors.size();
    views.push_back({ { "buffer", 0 },
      { "byteOffset", bin.size() },
      { "byteLength", a.Bytes.size() },
      { "target", 34962 } });
    Json accessor = { { "bufferView", index },
      { "componentType", a.ComponentType },
      { "count", n },
      { "type", a.Type } };
    if (a.Normalized)
    {
      accessor["normalized"] = true;
    }
    if (a.Semantic == "POSITION")
    {
      accessor["min"] = { bounds[0], bounds[1], bounds[2] };
      accessor["max"] = { bounds[3], bounds[4], bounds[5] };
    }
    accessors.push_back(std::move(accessor));
    semantics[a.Semantic] = index;
    bin.insert(bin.end(), a.Bytes.begin(), a.Bytes.end());
    Pad(bin, 0);
  }
  Json buffer = { { "byteLength", bin.size() } };
  if (!binary)
  {
    buffer["uri"] =
      "data:application/octet-stream;base64," + detail::EncodeBase64(bin.data(), bin.size());
  }
  const Json primitive = { { "attributes", semantics },
    { "mode", 0 },
    { "extensions",
      { { detail::GltfExtension,
        { { "kernel", "ellipse" },
          { "colorSpace", options.ColorSpace },
          { "projection", "perspective" },
          { "sortingMethod", "cameraDistance" } } } } } };
  const Json root = { { "asset", { { "version", "2.0" }, { "generator", "Vis4GS" } } },
    { "extensionsUsed", { detail::GltfExtension } },
    { "scene", 0 },
    { "scenes", { { { "nodes", { 0 } } } } },
    { "nodes", { { { "mesh", 0 } } } },
    { "meshes", { { { "primitives", { primitive } } } } },
    { "buffers", { buffer } },
    { "bufferViews", views },
    { "accessors", accessors } };
  const std::string text = root.dump();
  std::vector<unsigned char> json(text.begin(), text.end());
  if (!binary)
  {
    return json;
  }
  Pad(json, ' ');
  std::vector<unsigned char> out;
  auto u32 = [&out](std::size_t v)
  {
    for (int i = 0; i < 4; ++i)
    {
      out.push_back(static_cast<unsigned char>(v >> (8 * i)));
    }
  };
  const std::size_t total = 12 + 8 + json.size() + 8 + bin.size();
  if (total > 0xffffffffu)
  {
    throw std::runtime_error("a GLB holds at most 4 GiB; this scene needs " +
      std::to_string(total) + " bytes (write .gltf with an external buffer instead)");
  }
  u32(0x46546C67);
  u32(2);
  u32(total);
  u32(json.size());
  u32(0x4E4F534A);
  out.insert(out.end(), json.begin(), json.end());
  u32(bin.size());
  u32(0x004E4942);
  out.insert(out.end(), bin.begin(), bin.end());
  return out;
}

/// Max and RMS of the differences a read-back shows.
struct ErrorSum
{
  double Max = 0, SumSq = 0;
  std::size_t Values = 0;
  void Add(double e)
  {
    e = std::fabs(e);
    Max = std::max(Max, e);
    SumSq += e * e;
    ++Values;
  }
  QuantisationError Result(const char* attribute) const
  {
    return { attribute, Max, Values ? std::sqrt(SumSq / double(Values)) : 0.0, Values };
  }
};

void MeasureErrors(const GaussianCloud& cloud,
  const std::vector<std::size_t>& order,
  const std::vector<unsigned char>& bytes,
  int degree,
  const GltfWriteOptions& options,
  GltfWriteReport& report)
{
  const GaussianCloud back = ReadGltfFromMemory(bytes.data(), bytes.size(), "written glTF");
  const std::size_t k = static_cast<std::size_t>(cloud.ShCoefficientCount());
  const std::size_t kb = static_cast<std::size_t>(back.ShCoefficientCount());
  ErrorSum pos, scale, rot, alpha, sh, extra;
  for (std::size_t i = 0; i < order.size(); ++i)
  {
    const std::size_t g = order[i];
    for (int c = 0; c < 3; ++c)
    {
      pos.Add(back.Positions[3 * i + c] - cloud.Positions[3 * g + c]);
      if (std::isfinite(cloud.LogScales[3 * g + c]))
      {
        scale.Add(back.LogScales[3 * i + c] - cloud.LogScales[3 * g + c]);
      }
    }
    const double src[4] = { cloud.Rotations[4 * g],
      cloud.Rotations[4 * g + 1],
      cloud.Rotations[4 * g + 2],
      cloud.Rotations[4 * g + 3] };
    const auto q = NormalizeQuaternion<double>(src);
    if (q[0] != 0 || q[1] != 0 || q[2] != 0 || q[3] != 0)
    {
      // The angle between unit quaternions a and b (sign aligned) is 4 atan2(|a-b|, |a+b|),
      // which keeps its precision where acos of the dot product loses it.
      const double stored[4] = { back.Rotations[4 * i],
        back.Rotations[4 * i + 1],
        back.Rotations[4 * i + 2],
        back.Rotations[4 * i + 3] };
      const auto r = NormalizeQuaternion<double>(stored);
      double dot = 0, diff = 0, sum = 0;
      for (int c = 0; c < 4; ++c)
      {
        dot += q[c] * r[c];
      }
      for (int c = 0; c < 4; ++c)
      {
        const double b = (dot < 0 ? -1.0 : 1.0) * r[c];
        diff += (q[c] - b) * (q[c] - b);
        sum += (q[c] + b) * (q[c] + b);
      }
      rot.Add(4.0 * std::atan2(std::sqrt(diff), std::sqrt(sum)) * 180.0 / 3.14159265358979323846);
    }
    alpha.Add(Sigmoid<double>(back.OpacityLogits[i]) - Sigmoid<double>(cloud.OpacityLogits[g]));
    for (std::size_t j = 0; j < 3 * static_cast<std::size_t>((degree + 1) * (degree + 1)); ++j)
    {
      sh.Add(back.SH[3 * kb * i + j] - cloud.SH[3 * k * g + j]);
    }
    for (std::size_t e = 0; options.KeepExtras && e < cloud.Extra.size() && e < back.Extra.size();
         ++e)
    {
      extra.Add(back.Extra[e].GetAsDouble(i) - cloud.Extra[e].GetAsDouble(g));
    }
  }
  report.Errors = { pos.Result("position"),
    scale.Result("log-scale"),
    rot.Result("rotation (degrees)"),
    alpha.Result("opacity (alpha)"),
    sh.Result("SH"),
    extra.Result("extras") };
}

} // namespace

//------------------------------------------------------------------------------
std::vector<unsigned char> WriteGltfToMemory(const GaussianCloud& cloud,
  bool binary,
  const GltfWriteOptions& options,
  GltfWriteReport* reportOut)
{
  const std::size_t k = static_cast<std::size_t>(cloud.ShCoefficientCount());
  if (cloud.Positions.size() != 3 * cloud.Count || cloud.LogScales.size() != 3 * cloud.Count ||
    cloud.Rotations.size() != 4 * cloud.Count || cloud.OpacityLogits.size() != cloud.Count ||
    cloud.SH.size() != 3 * k * cloud.Count)
  {
    throw std::invalid_argument("WriteGltf: the cloud must hold every parameter array");
  }
  if (options.ColorSpace != "srgb_rec709_display" && options.ColorSpace != "lin_rec709_display")
  {
    throw std::invalid_argument("WriteGltf: colorSpace '" + options.ColorSpace +
      "' is not one KHR_gaussian_splatting defines");
  }
  const int degree = std::max(0, std::min(options.MaxShDegree, cloud.ShDegree));
  std::vector<std::size_t> order;
  const GaussianCloud g = Select(cloud, degree, order);
  if (order.empty())
  {
    throw std::runtime_error("glTF cannot hold a scene without a drawable Gaussian (its accessors "
                             "need at least one element)");
  }
  std::array<double, 6> bounds;
  const std::vector<Attribute> attributes = Encode(cloud, g, order, options, bounds);
  std::vector<unsigned char> bytes = Assemble(attributes, g.Count, bounds, binary, options);
  GltfWriteReport report;
  report.Written = order.size();
  report.LeftOut = cloud.Count - order.size();
  report.FileBytes = bytes.size();
  MeasureErrors(cloud, order, bytes, degree, options, report);
  if (reportOut)
  {
    *reportOut = std::move(report);
  }
  return bytes;
}

//------------------------------------------------------------------------------
GltfWriteReport WriteGltf(const std::string& path,
  const GaussianCloud& cloud,
  const GltfWriteOptions& options)
{
  GltfWriteReport report;
  std::vector<unsigned char> bytes;
  try
  {
    bytes = WriteGltfToMemory(cloud, detail::LowerExtension(path) != ".gltf", options, &report);
  }
  catch (const std::runtime_error& e)
  {
    throw std::runtime_error(path + ": " + e.what());
  }
  detail::WriteFileAtomically(
    path, [&](std::FILE* f) { detail::WriteBytes(f, bytes.data(), bytes.size(), path); });
  return report;
}

//------------------------------------------------------------------------------
std::string DescribeQuantisation(const GltfWriteReport& report)
{
  return detail::DescribeWriteErrors(report.Written, report.LeftOut, report.Errors);
}

} // namespace vis4gs

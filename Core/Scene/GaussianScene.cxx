// SPDX-License-Identifier: BSD-3-Clause
// The format dispatcher: every scene format Vis4GS reads, recognised by content first (a new
// format adds its test here), then by extension.
#include "GaussianIO.h"
#include "PlyHeader.h"
#include "SceneFile.h"
#include "SceneIds.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace vis4gs
{

//------------------------------------------------------------------------------
bool IdsFromExtraProperty(GaussianCloud& cloud, const std::string& name, const std::string& path)
{
  const ExtraProperty* id = cloud.FindExtra(name);
  if (!id)
  {
    return false;
  }
  cloud.Ids.resize(cloud.Count);
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    const double v = id->GetAsDouble(i);
    if (!(v == std::floor(v)) || std::abs(v) > 9.0e15)
    {
      throw std::runtime_error(
        path + ": vertex " + std::to_string(i) + ": id " + std::to_string(v) + " is no integer");
    }
    cloud.Ids[i] = static_cast<std::int64_t>(v);
  }
  return true;
}

//------------------------------------------------------------------------------
GaussianCloud ReadGaussianScene(const std::string& path,
  const GaussianReadOptions& options,
  GaussianReadReport* report)
{
  if (IsKsplatFile(path))
  {
    return ReadKsplat(path, options, report);
  }
  if (IsSpzFile(path))
  {
    return ReadSpz(path, options, report);
  }
  if (IsGltfFile(path))
  {
    return ReadGltf(path, options, report);
  }
  if (detail::LowerExtension(path) == ".splat")
  {
    return ReadSplat(path, options, report);
  }
  if (IsSog(path))
  {
    return ReadSog(path, options, report);
  }
  if (detail::IsRegularFile(path))
  {
    detail::InputFile file(path);
    std::vector<unsigned char> head(
      static_cast<std::size_t>(std::min<std::uint64_t>(file.Size(), detail::MaxPlyHeaderBytes)));
    file.ReadAt(0, head.data(), head.size());
    if (IsCompressedPly(head.data(), head.size()))
    {
      return ReadCompressedPly(path, options, report);
    }
  }
  return ReadGaussianPly(path, options, report);
}

//------------------------------------------------------------------------------
std::string WriteGaussianScene(const std::string& path,
  const GaussianCloud& cloud,
  const SceneWriteOptions& options)
{
  const std::string format = detail::SceneWriteFormat(path);
  auto ends = [&format](const char* f) { return format == f; };
  const int degree = std::max(0, std::min(options.MaxShDegree, cloud.ShDegree));
  // What the quantised formats cannot hold, said once.
  std::string extras;
  for (const auto& e : cloud.Extra)
  {
    extras += (extras.empty() ? "" : ", ") + e.Name;
  }
  if (!cloud.Ids.empty())
  {
    extras += std::string(extras.empty() ? "" : ", ") + "ids";
  }
  const std::string dropped = extras.empty()
    ? ""
    : "; the extra properties (" + extras + ") have no place in this format and are not written";
  if (ends(".compressed.ply"))
  {
    CompressedPlyWriteOptions o;
    o.MaxShDegree = degree;
    return "compressed PLY, " + DescribeQuantisation(WriteCompressedPly(path, cloud, o)) + dropped;
  }
  if (ends(".spz"))
  {
    GaussianCloud cut;
    const GaussianCloud* c = &cloud;
    if (degree < cloud.ShDegree)
    {
      cut = detail::CutShDegree(cloud, degree);
      c = &cut;
    }
    return DescribeQuantisation(WriteSpz(path, *c)) + dropped;
  }
  if (ends(".glb") || ends(".gltf"))
  {
    GltfWriteOptions o;
    o.MaxShDegree = degree;
    if (cloud.Ids.empty())
    {
      return DescribeQuantisation(WriteGltf(path, cloud, o));
    }
    // glTF has no 64-bit integers: ids are stored as float32, exact up to 2^24.
    GaussianCloud withIds = cloud;
    ExtraProperty id{ options.IdProperty, ScalarType::Float64, {} };
    id.Bytes.resize(8 * cloud.Count);
    for (std::size_t i = 0; i < cloud.Count; ++i)
    {
      const double v = static_cast<double>(cloud.Ids[i]);
      std::memcpy(&id.Bytes[8 * i], &v, 8);
    }
    withIds.Extra.push_back(std::move(id));
    return DescribeQuantisation(WriteGltf(path, withIds, o));
  }
  if (ends(".splat"))
  {
    const std::size_t left = WriteSplat(path, cloud);
    return ".splat, " + std::to_string(cloud.Count - left) + " Gaussians written" +
      (left ? ", " + std::to_string(left) + " left out (no answer in the reference's arithmetic)"
            : "") +
      "; colour, opacity and rotation quantised to 8 bits, SH above degree 0 dropped" + dropped;
  }
  GaussianWriteOptions o;
  o.Format = options.Format;
  o.IdProperty = options.IdProperty;
  if (degree < cloud.ShDegree)
  {
    WriteGaussianPly(path, detail::CutShDegree(cloud, degree), o);
  }
  else
  {
    WriteGaussianPly(path, cloud, o);
  }
  return "PLY, " + std::to_string(cloud.Count) + " Gaussians written exactly (float32)";
}

//------------------------------------------------------------------------------
std::string detail::SceneWriteFormat(const std::string& path)
{
  std::string lower(path);
  std::transform(lower.begin(),
    lower.end(),
    lower.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const char* f : { ".compressed.ply", ".ply", ".spz", ".glb", ".gltf", ".splat" })
  {
    const std::size_t n = std::strlen(f);
    if (lower.size() >= n && lower.compare(lower.size() - n, n, f) == 0)
    {
      return f;
    }
  }
  return "";
}

//------------------------------------------------------------------------------
GaussianCloud detail::CutShDegree(const GaussianCloud& cloud, int degree)
{
  GaussianCloud out = cloud;
  if (degree >= cloud.ShDegree || cloud.SH.empty())
  {
    return out;
  }
  const std::size_t k = static_cast<std::size_t>(cloud.ShCoefficientCount());
  const std::size_t kk = static_cast<std::size_t>((degree + 1) * (degree + 1));
  out.SH.resize(3 * kk * cloud.Count);
  for (std::size_t g = 0; g < cloud.Count; ++g)
  {
    std::copy_n(&cloud.SH[3 * k * g], 3 * kk, &out.SH[3 * kk * g]);
  }
  out.ShDegree = degree;
  return out;
}

//------------------------------------------------------------------------------
void detail::FinishReadReport(GaussianReadReport& report,
  const std::string& name,
  GaussianReadReport* out,
  const std::string& note)
{
  if (report.NonFiniteValues)
  {
    report.Warnings.push_back(name + ": " + std::to_string(report.NonFiniteGaussians) +
      " Gaussians hold NaN or infinite values (" + std::to_string(report.NonFiniteValues) +
      " values" + note + "); they are kept as read");
  }
  if (out)
  {
    *out = std::move(report);
  }
}

//------------------------------------------------------------------------------
GaussianCloud detail::AllocateReadArrays(std::size_t n,
  int shDegree,
  const GaussianReadOptions& options)
{
  GaussianCloud cloud;
  cloud.Count = n;
  cloud.ShDegree = options.LoadSH ? shDegree : 0;
  if (options.LoadPositions)
  {
    cloud.Positions.resize(3 * n);
  }
  if (options.LoadScales)
  {
    cloud.LogScales.resize(3 * n);
  }
  if (options.LoadRotations)
  {
    cloud.Rotations.resize(4 * n);
  }
  if (options.LoadOpacities)
  {
    cloud.OpacityLogits.resize(n);
  }
  if (options.LoadSH)
  {
    cloud.SH.resize(3 * static_cast<std::size_t>(cloud.ShCoefficientCount()) * n);
  }
  return cloud;
}

} // namespace vis4gs

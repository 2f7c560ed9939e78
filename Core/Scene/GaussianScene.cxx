// SPDX-License-Identifier: BSD-3-Clause
// The format dispatcher: every scene format Vis4GS reads, recognised by content first (a new
// format adds its test here), then by extension.
#include "GaussianIO.h"
#include "PlyHeader.h"
#include "SceneFile.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace vis4gs
{

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

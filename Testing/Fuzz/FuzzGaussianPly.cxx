// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the 3DGS PLY reader. A file either reads or throws std::runtime_error;
// what reads must write back and read again to the same values.
#include "GaussianIO.h"

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  vis4gs::GaussianReadOptions options;
  // Vary the options with the last byte so that every code path is reached.
  if (size > 0)
  {
    const std::uint8_t o = data[size - 1];
    options.MaxShDegree = o & 3;
    options.LoadScales = !(o & 4);
    options.LoadSH = !(o & 8);
    options.LoadExtras = !(o & 16);
    if (o & 32)
    {
      options.IdProperty = "id";
    }
  }
  vis4gs::GaussianCloud cloud;
  try
  {
    cloud = vis4gs::ReadGaussianPlyFromMemory(data, size, "fuzz.ply", options);
  }
  catch (const std::runtime_error&)
  {
    return 0;
  }
  if (cloud.Count > 4096)
  {
    return 0; // keep iterations fast
  }
  vis4gs::GaussianWriteOptions w;
  w.Format = static_cast<vis4gs::PlyFormat>(size % 3);
  const auto bytes = vis4gs::WriteGaussianPlyToMemory(cloud, w);
  vis4gs::GaussianReadOptions again;
  again.MaxShDegree = cloud.ShDegree;
  again.LoadPositions = !cloud.Positions.empty();
  again.LoadScales = !cloud.LogScales.empty();
  again.LoadRotations = !cloud.Rotations.empty();
  again.LoadOpacities = !cloud.OpacityLogits.empty();
  again.LoadSH = !cloud.SH.empty();
  again.IdProperty = cloud.Ids.empty() ? "" : "id";
  const auto back = vis4gs::ReadGaussianPlyFromMemory(bytes.data(), bytes.size(), "rt.ply", again);
  auto same = [](const std::vector<float>& a, const std::vector<float>& b)
  {
    return a.size() == b.size() &&
      (a.empty() || std::memcmp(a.data(), b.data(), 4 * a.size()) == 0);
  };
  if (back.Count != cloud.Count || !same(back.Positions, cloud.Positions) ||
    !same(back.LogScales, cloud.LogScales) || !same(back.Rotations, cloud.Rotations) ||
    !same(back.OpacityLogits, cloud.OpacityLogits) || !same(back.SH, cloud.SH) ||
    back.Ids != cloud.Ids)
  {
    std::abort(); // a write/read round trip changed the values
  }
  return 0;
}

// SPDX-License-Identifier: BSD-3-Clause
// Test tool (issue 19): converts a scene with the Core readers and writers, so that scripts can
// hold them to reference tools. Usage: vis4gsSceneConvert IN OUT [--max-sh-degree=D]
// IN is read with ReadGaussianScene (PLY, .splat, SPZ by content); OUT is written by its
// extension: .spz (WriteSpz, prints the quantisation report as JSON), .splat, else PLY.
#include "GaussianIO.h"
#include "SceneFile.h"

#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

namespace
{
void PrintError(const char* name, const vis4gs::SpzAttributeError& e, bool last)
{
  std::printf("  \"%s\": {\"max\": %.9g, \"rms\": %.9g}%s\n", name, e.Max, e.Rms, last ? "" : ",");
}
}

int main(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::fprintf(stderr, "usage: %s IN OUT [--max-sh-degree=D] [--zstd-level=L]\n", argv[0]);
    return 2;
  }
  try
  {
    vis4gs::GaussianReadOptions options;
    vis4gs::SpzWriteOptions spzOptions;
    for (int i = 3; i < argc; ++i)
    {
      if (std::strncmp(argv[i], "--max-sh-degree=", 16) == 0)
      {
        options.MaxShDegree = std::stoi(argv[i] + 16);
      }
      else if (std::strncmp(argv[i], "--zstd-level=", 13) == 0)
      {
        spzOptions.ZstdLevel = std::stoi(argv[i] + 13);
      }
    }
    vis4gs::GaussianReadReport read;
    const vis4gs::GaussianCloud cloud = vis4gs::ReadGaussianScene(argv[1], options, &read);
    for (const auto& w : read.Warnings)
    {
      std::fprintf(stderr, "warning: %s\n", w.c_str());
    }
    const std::string ext = vis4gs::detail::LowerExtension(argv[2]);
    if (ext == ".spz")
    {
      const vis4gs::SpzWriteReport r = vis4gs::WriteSpz(argv[2], cloud, spzOptions);
      std::printf("{\n  \"read_format\": \"%s\", \"written\": %zu, \"left_out\": %zu, "
                  "\"special_values\": %zu, \"fractional_bits\": %d, \"file_bytes\": %zu,\n",
        read.Format.c_str(),
        r.Written,
        r.LeftOut,
        r.SpecialValues,
        r.FractionalBits,
        r.FileBytes);
      PrintError("position", r.Position, false);
      PrintError("log_scale", r.LogScale, false);
      PrintError("rotation", r.Rotation, false);
      PrintError("opacity", r.Opacity, false);
      PrintError("color", r.Color, false);
      PrintError("sh", r.SH, true);
      std::printf("}\n");
    }
    else if (ext == ".splat")
    {
      vis4gs::WriteSplat(argv[2], cloud);
    }
    else
    {
      vis4gs::WriteGaussianPly(argv[2], cloud);
      std::printf("{\"read_format\": \"%s\", \"count\": %zu, \"sh_degree\": %d}\n",
        read.Format.c_str(),
        cloud.Count,
        cloud.ShDegree);
    }
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}

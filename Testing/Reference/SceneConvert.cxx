// SPDX-License-Identifier: BSD-3-Clause
// Test tool for the reference checks (Testing/Reference, issue 19): reads any scene Vis4GS
// reads with ReadGaussianScene and writes it with the Core writers, so that scripts can hold
// both to the formats' reference converter.
//
// Usage: vis4gsSceneConvert IN OUT [--compressed] [--source-order] [--sh=N] [--zstd-level=L]
// OUT is written by its extension: .spz (WriteSpz; prints its quantisation report as JSON),
// .splat, .glb / .gltf (WriteGltf; prints DescribeQuantisation), a compressed PLY with
// --compressed (prints DescribeQuantisation), else a float32 PLY
// holding every decoded value exactly (prints {"read_format", "count", "sh_degree"} as JSON).
// --sh=N (alias --max-sh-degree=N) limits the SH degree read and written.
#include "GaussianIO.h"
#include "SceneFile.h"

#include <cstdio>
#include <cstdlib>
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
    std::fprintf(stderr,
      "usage: %s IN OUT [--compressed] [--source-order] [--sh=N] [--zstd-level=L]\n",
      argv[0]);
    return 2;
  }
  vis4gs::GaussianReadOptions options;
  vis4gs::SpzWriteOptions spzOptions;
  vis4gs::CompressedPlyWriteOptions compressedOptions;
  bool compressed = false;
  for (int i = 3; i < argc; ++i)
  {
    if (std::strcmp(argv[i], "--compressed") == 0)
    {
      compressed = true;
    }
    else if (std::strcmp(argv[i], "--source-order") == 0)
    {
      compressedOptions.MortonOrder = false;
    }
    else if (std::strncmp(argv[i], "--sh=", 5) == 0 ||
      std::strncmp(argv[i], "--max-sh-degree=", 16) == 0)
    {
      const int sh = std::atoi(std::strchr(argv[i], '=') + 1);
      options.MaxShDegree = sh;
      compressedOptions.MaxShDegree = sh;
    }
    else if (std::strncmp(argv[i], "--zstd-level=", 13) == 0)
    {
      spzOptions.ZstdLevel = std::atoi(argv[i] + 13);
    }
    else
    {
      std::fprintf(stderr, "unknown option %s\n", argv[i]);
      return 2;
    }
  }
  try
  {
    vis4gs::GaussianReadReport read;
    const vis4gs::GaussianCloud cloud = vis4gs::ReadGaussianScene(argv[1], options, &read);
    for (const auto& w : read.Warnings)
    {
      std::fprintf(stderr, "warning: %s\n", w.c_str());
    }
    const std::string ext = vis4gs::detail::LowerExtension(argv[2]);
    if (compressed)
    {
      const auto r = vis4gs::WriteCompressedPly(argv[2], cloud, compressedOptions);
      std::printf("%s\n", vis4gs::DescribeQuantisation(r).c_str());
    }
    else if (ext == ".spz")
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
    else if (ext == ".glb" || ext == ".gltf")
    {
      vis4gs::GltfWriteOptions gltfOptions;
      gltfOptions.MaxShDegree = options.MaxShDegree;
      std::printf("%s\n",
        vis4gs::DescribeQuantisation(vis4gs::WriteGltf(argv[2], cloud, gltfOptions)).c_str());
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

// SPDX-License-Identifier: BSD-3-Clause
// Test tool for the reference checks (Testing/Reference): reads any scene Vis4GS reads and
// writes it as a float32 PLY (every decoded value exactly) or, with --compressed, with our
// compressed-PLY writer, printing its quantisation report.
//
// Usage: vis4gsSceneConvert <input> <output.ply> [--compressed] [--source-order] [--sh=N]
#include "GaussianIO.h"

#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

int main(int argc, char** argv)
{
  if (argc < 3)
  {
    std::fprintf(
      stderr, "usage: %s <input> <output.ply> [--compressed] [--source-order] [--sh=N]\n", argv[0]);
    return 2;
  }
  bool compressed = false, sourceOrder = false;
  int sh = 3;
  for (int i = 3; i < argc; ++i)
  {
    if (std::strcmp(argv[i], "--compressed") == 0)
    {
      compressed = true;
    }
    else if (std::strcmp(argv[i], "--source-order") == 0)
    {
      sourceOrder = true;
    }
    else if (std::strncmp(argv[i], "--sh=", 5) == 0)
    {
      sh = std::atoi(argv[i] + 5);
    }
    else
    {
      std::fprintf(stderr, "unknown option %s\n", argv[i]);
      return 2;
    }
  }
  try
  {
    vis4gs::GaussianReadOptions options;
    options.MaxShDegree = sh;
    vis4gs::GaussianReadReport report;
    const vis4gs::GaussianCloud cloud = vis4gs::ReadGaussianScene(argv[1], options, &report);
    std::printf("read %zu Gaussians (format %s, SH degree %d of %d)\n",
      cloud.Count,
      report.Format.c_str(),
      cloud.ShDegree,
      report.FileShDegree);
    if (compressed)
    {
      vis4gs::CompressedPlyWriteOptions w;
      w.MortonOrder = !sourceOrder;
      w.MaxShDegree = sh;
      const auto r = vis4gs::WriteCompressedPly(argv[2], cloud, w);
      std::printf("%s\n", vis4gs::DescribeQuantisation(r).c_str());
    }
    else
    {
      vis4gs::WriteGaussianPly(argv[2], cloud);
    }
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}

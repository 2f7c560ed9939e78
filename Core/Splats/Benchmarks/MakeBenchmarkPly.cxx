// SPDX-License-Identifier: BSD-3-Clause
// Writes MakeBenchmarkScene as a binary 3DGS PLY, for whole-process benchmarks of opening a
// large scene (issue 21: a Mip-NeRF 360 "bicycle"-sized PLY is 6.1M Gaussians of SH degree 3,
// 1.5 GB). SYNTHETIC data, deterministic for a given count, degree and seed.
// Usage: MakeBenchmarkPly OUT.ply [count=6100000] [sh_degree=3] [seed=1]
#include "BenchmarkScene.h"
#include "GaussianIO.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>

int main(int argc, char* argv[])
{
  if (argc < 2)
  {
    std::fprintf(
      stderr, "usage: MakeBenchmarkPly OUT.ply [count=6100000] [sh_degree=3] [seed=1]\n");
    return 1;
  }
  const std::size_t n = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 6100000;
  const int degree = argc > 3 ? std::atoi(argv[3]) : 3;
  const unsigned seed = argc > 4 ? static_cast<unsigned>(std::strtoul(argv[4], nullptr, 10)) : 1;
  if (degree < 0 || degree > 3)
  {
    std::fprintf(stderr, "MakeBenchmarkPly: the SH degree must be 0..3\n");
    return 1;
  }
  try
  {
    const auto start = std::chrono::steady_clock::now();
    const vis4gs::GaussianCloud cloud = vis4gs::MakeBenchmarkScene(n, degree, seed);
    vis4gs::WriteGaussianPly(argv[1], cloud);
    std::printf("%s: SYNTHETIC scene, %zu Gaussians, SH degree %d, written in %.2f s\n",
      argv[1],
      n,
      degree,
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "MakeBenchmarkPly: %s\n", e.what());
    return 1;
  }
  return 0;
}

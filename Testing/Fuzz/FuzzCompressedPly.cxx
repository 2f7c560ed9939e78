// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the PlayCanvas compressed PLY reader, and our writer on whatever it decodes
// (infinite opacity logits, clamped scales, any quaternion).
#include "GaussianIO.h"

#include <cstdint>
#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  try
  {
    vis4gs::GaussianReadOptions options;
    options.MaxShDegree = size % 4;
    const vis4gs::GaussianCloud cloud =
      vis4gs::ReadCompressedPlyFromMemory(data, size, "fuzz.compressed.ply", options);
    if (cloud.Count <= 4096)
    {
      vis4gs::ReadCompressedPlyFromMemory(data, size, "fuzz.compressed.ply");
      const auto bytes = vis4gs::WriteCompressedPlyToMemory(
        vis4gs::ReadCompressedPlyFromMemory(data, size, "fuzz.compressed.ply"));
      vis4gs::ReadCompressedPlyFromMemory(bytes.data(), bytes.size(), "rewritten.compressed.ply");
    }
  }
  catch (const std::runtime_error&)
  {
  }
  return 0;
}

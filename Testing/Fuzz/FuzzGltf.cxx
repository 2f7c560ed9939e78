// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the glTF KHR_gaussian_splatting reader (GLB container, JSON, data URIs,
// accessors, the node hierarchy and the SPZ payload; issue 34).
#include "GaussianIO.h"

#include <cstdint>
#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  try
  {
    vis4gs::ReadGltfFromMemory(data, size, "fuzz.glb");
  }
  catch (const std::runtime_error&)
  {
  }
  return 0;
}

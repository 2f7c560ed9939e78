// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the .ksplat reader (GaussianSplats3D, compression levels 0-2, issue 19).
#include "GaussianIO.h"

#include <cstdint>
#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  try
  {
    vis4gs::ReadKsplatFromMemory(data, size, "fuzz.ksplat");
  }
  catch (const std::runtime_error&)
  {
  }
  return 0;
}

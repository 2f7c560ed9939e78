// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the antimatter15 .splat reader.
#include "GaussianIO.h"

#include <cstdint>
#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  try
  {
    vis4gs::ReadSplatFromMemory(data, size, "fuzz.splat");
  }
  catch (const std::runtime_error&)
  {
  }
  return 0;
}

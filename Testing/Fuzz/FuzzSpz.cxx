// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the SPZ reader (gzip v2/v3 and zstd v4 with extensions, issue 19).
#include "GaussianIO.h"

#include <cstdint>
#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  try
  {
    vis4gs::ReadSpzFromMemory(data, size, "fuzz.spz");
  }
  catch (const std::runtime_error&)
  {
  }
  return 0;
}

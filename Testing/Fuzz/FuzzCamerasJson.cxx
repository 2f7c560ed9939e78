// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the trainer's cameras.json reader.
#include "CameraJson.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  try
  {
    const auto cams = vis4gs::ReadCamerasJsonFromMemory(data, size, "fuzz.json");
    for (const auto& c : cams)
    {
      for (double v : c.WorldToCamera)
      {
        if (!std::isfinite(v))
        {
          std::abort(); // accepted cameras must have finite poses
        }
      }
    }
  }
  catch (const std::runtime_error&)
  {
  }
  return 0;
}

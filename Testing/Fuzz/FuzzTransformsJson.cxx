// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the NeRF-synthetic / instant-ngp transforms.json reader.
#include "TransformsJson.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  try
  {
    // No images are looked for in a folder that does not exist: frames need w/h.
    vis4gs::TransformsOptions options;
    options.RequireImages = false;
    const auto res = vis4gs::ReadTransformsJsonFromMemory(
      data, size, "fuzz.json", "/nonexistent-vis4gs-fuzz", options);
    for (const auto& c : res.Cameras)
    {
      if (!(c.Fx > 0) || !(c.Fy > 0) || c.Width < 1 || c.Height < 1)
      {
        std::abort(); // accepted cameras must have valid intrinsics
      }
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

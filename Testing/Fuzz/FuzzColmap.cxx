// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the COLMAP parsers. The first byte picks the file (cameras, images,
// points3D) and the format (binary, text); accepted cameras and images must convert.
#include "Colmap.h"

#include <cstdint>
#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size == 0)
  {
    return 0;
  }
  const int which = data[0] % 3;
  const auto format = (data[0] / 3) % 2 ? vis4gs::ColmapFormat::Text : vis4gs::ColmapFormat::Binary;
  const bool observations = data[0] & 0x80;
  try
  {
    if (which == 0)
    {
      const auto cams = vis4gs::ParseColmapCameras(data + 1, size - 1, format, "fuzz_cameras");
      vis4gs::ColmapImage im;
      im.Name = "a.png";
      for (const auto& c : cams)
      {
        vis4gs::ToCamera(c, im);
        vis4gs::IsDistorted(c);
      }
    }
    else if (which == 1)
    {
      const auto images =
        vis4gs::ParseColmapImages(data + 1, size - 1, format, "fuzz_images", observations);
      vis4gs::ColmapCamera cam;
      cam.Width = cam.Height = 10;
      cam.Params = { 1, 1, 5, 5 };
      for (const auto& im : images)
      {
        vis4gs::ToCamera(cam, im);
      }
    }
    else
    {
      vis4gs::ParseColmapPoints3D(data + 1, size - 1, format, "fuzz_points", observations);
    }
  }
  catch (const std::runtime_error&)
  {
  }
  return 0;
}

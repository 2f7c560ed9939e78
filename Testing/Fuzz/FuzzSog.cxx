// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the SOG reader. The first byte picks the container: even, the rest is a
// .sog zip archive; odd, the rest is a list of files (1-byte name length, name, 4-byte
// little-endian size, bytes) so that meta.json and the WebP textures are mutated directly
// (inside a zip, a mutation mostly breaks the CRC).
#include "GaussianIO.h"

#include <cstdint>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size == 0)
  {
    return 0;
  }
  vis4gs::GaussianReadOptions options;
  options.MaxShDegree = data[0] >> 1 & 3;
  try
  {
    if ((data[0] & 1) == 0)
    {
      vis4gs::ReadSogZipFromMemory(data + 1, size - 1, "fuzz.sog", options);
      return 0;
    }
    std::map<std::string, std::vector<unsigned char>> files;
    std::size_t i = 1;
    while (i < size)
    {
      const std::size_t nameLength = data[i++];
      if (i + nameLength + 4 > size)
      {
        break;
      }
      const std::string name(reinterpret_cast<const char*>(data + i), nameLength);
      i += nameLength;
      std::uint32_t length = 0;
      for (int b = 0; b < 4; ++b)
      {
        length |= std::uint32_t(data[i + b]) << (8 * b);
      }
      i += 4;
      const std::size_t n = std::min<std::size_t>(length, size - i);
      files[name].assign(data + i, data + i + n);
      i += n;
    }
    vis4gs::ReadSogFromMemoryFiles(files, "fuzz-sog", options);
  }
  catch (const std::runtime_error&)
  {
  }
  return 0;
}

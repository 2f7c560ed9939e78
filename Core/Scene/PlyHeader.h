// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PlyHeader.h
 * @brief The PLY header as GaussianPly.cxx parses it, shared with the readers of formats that
 * are PLY files with other elements (the PlayCanvas compressed PLY).
 */
#ifndef vis4gs_PlyHeader_h
#define vis4gs_PlyHeader_h

#include "GaussianCloud.h"
#include "GaussianIO.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vis4gs
{
namespace detail
{

/// A header longer than this is refused (no 'end_header' within it).
constexpr std::size_t MaxPlyHeaderBytes = std::size_t(1) << 20;

struct PlyProperty
{
  std::string Name;
  ScalarType Type = ScalarType::Float32;
  bool IsList = false;
  ScalarType CountType = ScalarType::UInt8;
  std::size_t Offset = 0; ///< byte offset in a binary row (fixed-size elements only)
};

struct PlyElement
{
  std::string Name;
  std::uint64_t Count = 0;
  std::vector<PlyProperty> Properties;
  std::size_t RowSize = 0;
  bool HasList = false;
};

struct PlyHeader
{
  PlyFormat Format = PlyFormat::BinaryLittleEndian;
  std::vector<PlyElement> Elements;
  std::size_t Bytes = 0; ///< header length including the end_header line
  /// Text of the `comment` lines after the keyword, in order (render modes, producers).
  std::vector<std::string> Comments;
};

/// Parses the header at the start of @p data (at most MaxPlyHeaderBytes are looked at); throws
/// std::runtime_error starting with @p name on anything malformed.
PlyHeader ParsePlyHeader(const unsigned char* data, std::size_t size, const std::string& name);

/// The PLY header's name of @p t ("float", "uchar", ...).
const char* PlyScalarTypeName(ScalarType t);

/// True unless the float32 bit pattern @p bits is an infinity or a NaN.
inline bool FloatBitsFinite(std::uint32_t bits)
{
  return (bits & 0x7f800000u) != 0x7f800000u;
}

} // namespace detail
} // namespace vis4gs

#endif

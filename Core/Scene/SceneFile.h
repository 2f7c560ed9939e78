// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SceneFile.h
 * @brief Small file helpers shared by the scene readers and writers: whole-file and
 * positioned reads with errors that name the file, byte swapping, parallel row blocks, and
 * writes that go to a temporary file in the destination folder and are renamed into place.
 */
#ifndef vis4gs_SceneFile_h
#define vis4gs_SceneFile_h

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace vis4gs
{
namespace detail
{

/// Byte-swaps @p size bytes in place (size 1, 2, 4 or 8).
inline void SwapBytes(unsigned char* p, std::size_t size)
{
  for (std::size_t i = 0; i < size / 2; ++i)
  {
    const unsigned char t = p[i];
    p[i] = p[size - 1 - i];
    p[size - 1 - i] = t;
  }
}

inline std::uint32_t ByteSwap32(std::uint32_t v)
{
  return __builtin_bswap32(v);
}

/// Little-endian loads from unaligned bytes, on any host (the binary scene formats store
/// little-endian integers and floats: .splat, SPZ, .ksplat).
inline std::uint16_t LoadLE16(const unsigned char* p)
{
  return static_cast<std::uint16_t>(p[0] | (p[1] << 8));
}
inline std::uint32_t LoadLE32(const unsigned char* p)
{
  return std::uint32_t(p[0]) | (std::uint32_t(p[1]) << 8) | (std::uint32_t(p[2]) << 16) |
    (std::uint32_t(p[3]) << 24);
}
inline std::uint64_t LoadLE64(const unsigned char* p)
{
  return std::uint64_t(LoadLE32(p)) | (std::uint64_t(LoadLE32(p + 4)) << 32);
}
inline float LoadLEFloat(const unsigned char* p)
{
  const std::uint32_t bits = LoadLE32(p);
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

/// True on little-endian hosts.
inline bool HostIsLittleEndian()
{
  const std::uint16_t one = 1;
  unsigned char b;
  std::memcpy(&b, &one, 1);
  return b == 1;
}

/// Whitespace-separated words (space, tab, CR) of one line of a text format: the PLY header
/// and ASCII body and the COLMAP text files.
inline std::vector<std::string_view> SplitWords(std::string_view line)
{
  auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size())
  {
    while (i < line.size() && space(line[i]))
    {
      ++i;
    }
    const std::size_t b = i;
    while (i < line.size() && !space(line[i]))
    {
      ++i;
    }
    if (i > b)
    {
      out.push_back(line.substr(b, i - b));
    }
  }
  return out;
}

/// The lines of a text buffer, numbered from 1, for the text formats' error messages (the
/// last line needs no '\n'). Lines are read from @p start, counted after @p linesBefore.
class TextLines
{
public:
  explicit TextLines(std::string_view text, std::size_t start = 0, std::size_t linesBefore = 0)
    : Text(text)
    , Pos(start)
    , LineNo(linesBefore)
  {
  }

  /// Next line whatever it holds; false at the end of the text.
  bool Raw(std::string_view& line)
  {
    if (this->Pos >= this->Text.size())
    {
      return false;
    }
    std::size_t eol = this->Text.find('\n', this->Pos);
    if (eol == std::string_view::npos)
    {
      eol = this->Text.size();
    }
    line = this->Text.substr(this->Pos, eol - this->Pos);
    this->Pos = eol + 1;
    ++this->LineNo;
    return true;
  }

  /// Next line holding a word, and with @p comments also not starting with '#'.
  bool Next(std::string_view& line, bool comments = false)
  {
    while (this->Raw(line))
    {
      const auto b = line.find_first_not_of(" \t\r");
      if (b != std::string_view::npos && !(comments && line[b] == '#'))
      {
        return true;
      }
    }
    return false;
  }

  /// Number of the line last read (1-based).
  std::size_t LineNumber() const { return this->LineNo; }

private:
  std::string_view Text;
  std::size_t Pos = 0;
  std::size_t LineNo = 0;
};

/// A read-only file opened for positioned reads; every failure throws std::runtime_error
/// naming the file.
class InputFile
{
public:
  explicit InputFile(const std::string& path);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  const std::string& Path() const { return this->FilePath; }
  std::uint64_t Size() const { return this->FileSize; }
  /// Reads exactly @p size bytes at @p offset (throws on a short read).
  void ReadAt(std::uint64_t offset, void* buffer, std::size_t size) const;
  /// Reads up to @p size bytes at @p offset; returns the number read.
  std::size_t ReadSomeAt(std::uint64_t offset, void* buffer, std::size_t size) const;

private:
  std::string FilePath;
  int Fd = -1;
  std::uint64_t FileSize = 0;
};

/// Reads a whole (small) file; throws std::runtime_error naming the file on failure.
std::vector<unsigned char> ReadWholeFile(const std::string& path);

/// Bytes of a file or of a caller's buffer, read either way through the same interface.
struct ByteSource
{
  const InputFile* File = nullptr;       ///< set for files
  const unsigned char* Memory = nullptr; ///< set for in-memory buffers
  std::uint64_t Size = 0;
  std::string Name; ///< file name used in error messages
};

/// A ByteSource over an open file, or over a caller's buffer (null @p data: an empty one).
ByteSource FileSource(const InputFile& file);
ByteSource MemorySource(const void* data, std::size_t size, const std::string& name);

/// @p parse(source, args...) on the file @p path read through a ByteSource (in blocks): the
/// file form of the readers of .ply, compressed .ply and .splat.
template <typename Parse, typename... Args>
auto ParseFileSource(Parse parse, const std::string& path, Args&&... args)
{
  const InputFile file(path);
  return parse(FileSource(file), std::forward<Args>(args)...);
}

/// @p parse(bytes, size, path, args...) on the whole file @p path, read into memory: the file
/// form of the readers that parse one buffer (.ksplat, .spz).
template <typename Parse, typename... Args>
auto ParseWholeFile(Parse parse, const std::string& path, Args&&... args)
{
  const std::vector<unsigned char> bytes = ReadWholeFile(path);
  return parse(bytes.data(), bytes.size(), path, std::forward<Args>(args)...);
}

/// The same on a caller's buffer (null @p data: an empty one, as MemorySource()).
template <typename Parse, typename... Args>
auto ParseMemory(Parse parse,
  const void* data,
  std::size_t size,
  const std::string& name,
  Args&&... args)
{
  const ByteSource src = MemorySource(data, size, name);
  return parse(src.Memory, static_cast<std::size_t>(src.Size), name, std::forward<Args>(args)...);
}

/**
 * Calls @p kernel(rows, firstRow, rowCount) over @p rowCount rows of @p rowSize bytes that
 * start at @p offset of @p source, in blocks processed by OpenMP threads. A file is read with
 * one positioned read per block into a per-thread buffer of about @p blockBytes (so memory
 * stays bounded); a memory buffer is passed through directly. The caller has checked that
 * the rows lie inside the source. Exceptions thrown by @p kernel are re-thrown (the first).
 */
void ForEachRowBlock(const ByteSource& source,
  std::uint64_t offset,
  std::size_t rowSize,
  std::size_t rowCount,
  const std::function<void(const unsigned char*, std::size_t, std::size_t)>& kernel,
  std::size_t blockBytes = std::size_t(4) << 20);

/**
 * Writes a file safely: @p write is given a FILE* of a temporary file created in the folder
 * of @p path; on success the temporary is flushed, closed and renamed onto @p path, on any
 * failure it is removed and std::runtime_error naming @p path is thrown.
 */
void WriteFileAtomically(const std::string& path, const std::function<void(std::FILE*)>& write);

/// fwrite that throws naming @p path when the write is short.
void WriteBytes(std::FILE* f, const void* data, std::size_t size, const std::string& path);

/// Base64 (RFC 4648, with padding) of @p bytes: glTF data URIs, the analyze report's images.
std::string EncodeBase64(const unsigned char* bytes, std::size_t size);
/// The bytes of base64 @p text (padding optional); empty for text that is not base64.
std::vector<unsigned char> DecodeBase64(std::string_view text);

/// The scene format a file name asks a writer for (WriteGaussianScene): ".compressed.ply",
/// ".ply", ".spz", ".glb", ".gltf" or ".splat" (any case), "" for any other name.
std::string SceneWriteFormat(const std::string& path);

/// Folder part of @p path ("." when there is none).
std::string ParentFolder(const std::string& path);
/// True if @p path names an existing regular file / directory.
bool IsRegularFile(const std::string& path);
bool IsDirectory(const std::string& path);
/// Lower-cased extension of @p path including the dot (".ply"), or "".
std::string LowerExtension(const std::string& path);

} // namespace detail
} // namespace vis4gs

#endif

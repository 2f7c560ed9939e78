// SPDX-License-Identifier: BSD-3-Clause
#include "SceneFile.h"
#include "GaussianIO.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <exception>
#include <stdexcept>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace vis4gs
{
namespace detail
{

namespace
{
std::string ErrnoText()
{
  return std::strerror(errno);
}
}

//------------------------------------------------------------------------------
InputFile::InputFile(const std::string& path)
  : FilePath(path)
{
  this->Fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (this->Fd < 0)
  {
    throw std::runtime_error(path + ": cannot open for reading: " + ErrnoText());
  }
  struct stat st;
  if (::fstat(this->Fd, &st) != 0)
  {
    const std::string msg = path + ": cannot stat: " + ErrnoText();
    ::close(this->Fd);
    throw std::runtime_error(msg);
  }
  if (!S_ISREG(st.st_mode))
  {
    ::close(this->Fd);
    throw std::runtime_error(path + ": not a regular file");
  }
  this->FileSize = static_cast<std::uint64_t>(st.st_size);
}

//------------------------------------------------------------------------------
InputFile::~InputFile()
{
  if (this->Fd >= 0)
  {
    ::close(this->Fd);
  }
}

//------------------------------------------------------------------------------
std::size_t InputFile::ReadSomeAt(std::uint64_t offset, void* buffer, std::size_t size) const
{
  std::size_t done = 0;
  auto* out = static_cast<unsigned char*>(buffer);
  while (done < size)
  {
    const ssize_t n = ::pread(this->Fd, out + done, size - done, static_cast<off_t>(offset + done));
    if (n < 0)
    {
      if (errno == EINTR)
      {
        continue;
      }
      throw std::runtime_error(this->FilePath + ": read error: " + ErrnoText());
    }
    if (n == 0)
    {
      break;
    }
    done += static_cast<std::size_t>(n);
  }
  return done;
}

//------------------------------------------------------------------------------
void InputFile::ReadAt(std::uint64_t offset, void* buffer, std::size_t size) const
{
  const std::size_t n = this->ReadSomeAt(offset, buffer, size);
  if (n != size)
  {
    throw std::runtime_error(this->FilePath + ": file ends early (wanted " + std::to_string(size) +
      " bytes at offset " + std::to_string(offset) + ", got " + std::to_string(n) + ")");
  }
}

//------------------------------------------------------------------------------
ByteSource FileSource(const InputFile& file)
{
  ByteSource src;
  src.File = &file;
  src.Size = file.Size();
  src.Name = file.Path();
  return src;
}

//------------------------------------------------------------------------------
ByteSource MemorySource(const void* data, std::size_t size, const std::string& name)
{
  static const unsigned char empty = 0;
  ByteSource src;
  src.Memory = data ? static_cast<const unsigned char*>(data) : &empty;
  src.Size = data ? size : 0;
  src.Name = name;
  return src;
}

//------------------------------------------------------------------------------
std::vector<unsigned char> ReadWholeFile(const std::string& path)
{
  InputFile file(path);
  std::vector<unsigned char> bytes(static_cast<std::size_t>(file.Size()));
  file.ReadAt(0, bytes.data(), bytes.size());
  return bytes;
}

//------------------------------------------------------------------------------
void ForEachRowBlock(const ByteSource& source,
  std::uint64_t offset,
  std::size_t rowSize,
  std::size_t rowCount,
  const std::function<void(const unsigned char*, std::size_t, std::size_t)>& kernel,
  std::size_t blockBytes)
{
  if (rowCount == 0 || rowSize == 0)
  {
    return;
  }
  const std::size_t rowsPerBlock = std::max<std::size_t>(1, blockBytes / rowSize);
  const std::size_t blocks = (rowCount + rowsPerBlock - 1) / rowsPerBlock;
  std::exception_ptr error;
  bool failed = false;

#pragma omp parallel if (blocks > 1)
  {
    std::vector<unsigned char> buffer;
#pragma omp for schedule(static)
    for (long long b = 0; b < static_cast<long long>(blocks); ++b)
    {
      bool skip;
#pragma omp atomic read
      skip = failed;
      if (skip)
      {
        continue;
      }
      try
      {
        const std::size_t first = static_cast<std::size_t>(b) * rowsPerBlock;
        const std::size_t count = std::min(rowsPerBlock, rowCount - first);
        const std::uint64_t at = offset + static_cast<std::uint64_t>(first) * rowSize;
        if (source.Memory)
        {
          kernel(source.Memory + at, first, count);
        }
        else
        {
          buffer.resize(count * rowSize);
          source.File->ReadAt(at, buffer.data(), count * rowSize);
          kernel(buffer.data(), first, count);
        }
      }
      catch (...)
      {
#pragma omp critical(vis4gs_row_block_error)
        {
          if (!error)
          {
            error = std::current_exception();
          }
        }
#pragma omp atomic write
        failed = true;
      }
    }
  }
  if (error)
  {
    std::rethrow_exception(error);
  }
}

//------------------------------------------------------------------------------
void WriteBytes(std::FILE* f, const void* data, std::size_t size, const std::string& path)
{
  if (size && std::fwrite(data, 1, size, f) != size)
  {
    throw std::runtime_error(path + ": write error: " + ErrnoText());
  }
}

//------------------------------------------------------------------------------
std::string EncodeBase64(const unsigned char* bytes, std::size_t size)
{
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  for (std::size_t i = 0; i < size; i += 3)
  {
    const unsigned v = unsigned(bytes[i]) << 16 |
      (i + 1 < size ? unsigned(bytes[i + 1]) << 8 : 0u) | (i + 2 < size ? bytes[i + 2] : 0u);
    out += table[v >> 18 & 63];
    out += table[v >> 12 & 63];
    out += i + 1 < size ? table[v >> 6 & 63] : '=';
    out += i + 2 < size ? table[v & 63] : '=';
  }
  return out;
}

//------------------------------------------------------------------------------
std::vector<unsigned char> DecodeBase64(std::string_view text)
{
  while (!text.empty() && text.back() == '=')
  {
    text.remove_suffix(1);
  }
  std::vector<unsigned char> out;
  if (text.size() % 4 == 1)
  {
    return out;
  }
  out.reserve(text.size() / 4 * 3 + 2);
  unsigned v = 0;
  int bits = 0;
  for (const char ch : text)
  {
    int d = -1;
    if (ch >= 'A' && ch <= 'Z')
    {
      d = ch - 'A';
    }
    else if (ch >= 'a' && ch <= 'z')
    {
      d = ch - 'a' + 26;
    }
    else if (ch >= '0' && ch <= '9')
    {
      d = ch - '0' + 52;
    }
    else if (ch == '+' || ch == '-')
    {
      d = 62;
    }
    else if (ch == '/' || ch == '_')
    {
      d = 63;
    }
    if (d < 0)
    {
      return {};
    }
    v = (v << 6 | unsigned(d)) & 0xffffff;
    bits += 6;
    if (bits >= 8)
    {
      bits -= 8;
      out.push_back(static_cast<unsigned char>(v >> bits & 0xff));
    }
  }
  return out;
}

//------------------------------------------------------------------------------
std::string ParentFolder(const std::string& path)
{
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos)
  {
    return ".";
  }
  if (slash == 0)
  {
    return "/";
  }
  return path.substr(0, slash);
}

//------------------------------------------------------------------------------
bool IsRegularFile(const std::string& path)
{
  struct stat st;
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

//------------------------------------------------------------------------------
bool IsDirectory(const std::string& path)
{
  struct stat st;
  return ::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}

//------------------------------------------------------------------------------
std::string LowerExtension(const std::string& path)
{
  const auto slash = path.find_last_of('/');
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
  {
    return "";
  }
  std::string ext = path.substr(dot);
  std::transform(ext.begin(),
    ext.end(),
    ext.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

//------------------------------------------------------------------------------
void WriteFileAtomically(const std::string& path, const std::function<void(std::FILE*)>& write)
{
  std::string tmpl = ParentFolder(path) + "/.vis4gs-tmp-XXXXXX";
  std::vector<char> name(tmpl.begin(), tmpl.end());
  name.push_back('\0');
  const int fd = ::mkstemp(name.data());
  if (fd < 0)
  {
    throw std::runtime_error(
      path + ": cannot create a temporary file in " + ParentFolder(path) + ": " + ErrnoText());
  }
  const std::string tmpPath(name.data());
  // mkstemp creates 0600; give the file the usual permissions (0666 minus umask).
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  std::FILE* f = ::fdopen(fd, "wb");
  if (!f)
  {
    ::close(fd);
    ::unlink(tmpPath.c_str());
    throw std::runtime_error(path + ": cannot open temporary file: " + ErrnoText());
  }
  try
  {
    write(f);
    if (std::fflush(f) != 0)
    {
      throw std::runtime_error(path + ": write error: " + ErrnoText());
    }
  }
  catch (...)
  {
    std::fclose(f);
    ::unlink(tmpPath.c_str());
    throw;
  }
  if (std::fclose(f) != 0)
  {
    ::unlink(tmpPath.c_str());
    throw std::runtime_error(path + ": write error on close: " + ErrnoText());
  }
  if (std::rename(tmpPath.c_str(), path.c_str()) != 0)
  {
    const std::string msg = path + ": cannot rename the temporary file into place: " + ErrnoText();
    ::unlink(tmpPath.c_str());
    throw std::runtime_error(msg);
  }
}

} // namespace detail

//------------------------------------------------------------------------------
void WriteTextFile(const std::string& path, const std::string& text)
{
  detail::WriteFileAtomically(
    path, [&](std::FILE* f) { detail::WriteBytes(f, text.data(), text.size(), path); });
}
} // namespace vis4gs

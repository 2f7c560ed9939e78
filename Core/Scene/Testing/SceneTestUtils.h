// SPDX-License-Identifier: BSD-3-Clause
// Helpers shared by the Core/Scene tests: temporary folders, file bytes, expected errors.
#ifndef vis4gs_SceneTestUtils_h
#define vis4gs_SceneTestUtils_h

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

namespace vis4gs
{
namespace testing
{

/// A fresh folder under $TMPDIR (or /tmp), removed with its content at the end of the test.
class TempDir
{
public:
  TempDir()
  {
    const char* base = std::getenv("TMPDIR");
    std::string tmpl = std::string(base && *base ? base : "/tmp") + "/vis4gs-scene-XXXXXX";
    std::vector<char> buf(tmpl.begin(), tmpl.end());
    buf.push_back('\0');
    if (!::mkdtemp(buf.data()))
    {
      throw std::runtime_error("mkdtemp failed");
    }
    this->Path = buf.data();
  }
  ~TempDir() { std::system(("rm -rf '" + this->Path + "'").c_str()); }
  std::string operator/(const std::string& name) const { return this->Path + "/" + name; }
  std::string Path;
};

inline std::vector<unsigned char> FileBytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::vector<unsigned char>(
    std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline void WriteFile(const std::string& path, const void* data, std::size_t size)
{
  std::ofstream out(path, std::ios::binary);
  out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
}

inline void WriteFile(const std::string& path, const std::string& text)
{
  WriteFile(path, text.data(), text.size());
}

inline void WriteFile(const std::string& path, const std::vector<unsigned char>& bytes)
{
  WriteFile(path, bytes.data(), bytes.size());
}

} // namespace testing
} // namespace vis4gs

/// Expects @p stmt to throw std::runtime_error whose message contains every given fragment.
#define EXPECT_THROW_WITH(stmt, ...)                                                               \
  do                                                                                               \
  {                                                                                                \
    bool thrown_ = false;                                                                          \
    try                                                                                            \
    {                                                                                              \
      stmt;                                                                                        \
    }                                                                                              \
    catch (const std::runtime_error& e_)                                                           \
    {                                                                                              \
      thrown_ = true;                                                                              \
      const std::string msg_ = e_.what();                                                          \
      for (const std::string& frag_ : std::vector<std::string>{ __VA_ARGS__ })                     \
      {                                                                                            \
        EXPECT_NE(msg_.find(frag_), std::string::npos)                                             \
          << "message '" << msg_ << "' lacks '" << frag_ << "'";                                   \
      }                                                                                            \
    }                                                                                              \
    EXPECT_TRUE(thrown_) << #stmt " did not throw std::runtime_error";                             \
  } while (0)

#endif

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSTestData.h
 * @brief Paths of the test inputs: the real third-party scenes in ../shared/data (read in
 * place, never copied into the repository) and the repository's own Data/ folder.
 */
#ifndef vis4gs_TestData_h
#define vis4gs_TestData_h

#include <sys/stat.h>

#include <cstdio>
#include <cstdlib>
#include <string>

namespace vis4gs
{
namespace testing
{

/// The shared data folder ($VIS4GS_SHARED_DATA_DIR, else the configured one).
inline std::string SharedDataDir()
{
  const char* env = std::getenv("VIS4GS_SHARED_DATA_DIR");
  return env && *env ? env : VIS4GS_SHARED_DATA_DIR;
}

/// Path of @p relative inside shared/data; $VIS4GS_SHARED_DATA_DIR overrides the configured one.
inline std::string SharedDataPath(const std::string& relative)
{
  return SharedDataDir() + "/" + relative;
}

/// Why the tests that read shared/data cannot run (the folder is absent), or "" when they can.
inline std::string SharedDataMissing()
{
  struct stat st;
  const std::string dir = SharedDataDir();
  if (::stat(dir.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
  {
    return std::string();
  }
  return "the real third-party test data folder " + dir +
    " is absent (shared/data beside the checkout, or VIS4GS_SHARED_DATA_DIR)";
}

/// CI runs with shared/data beside the checkout: there, its absence is an error, not a skip.
inline bool UnderCI()
{
  const char* ci = std::getenv("CI");
  return ci && std::string(ci) == "true";
}

/// Exit status a VTK C++ test returns to be reported as skipped (SKIP_RETURN_CODE of the
/// tests vis4gs_shared_data_tests() marks).
constexpr int SkipReturnCode = 77;

} // namespace testing
} // namespace vis4gs

/**
 * First statement of a GoogleTest TEST that reads shared/data: skips it (naming the missing
 * folder) when the folder is absent, and fails it when CI=true. The Core tests containing it
 * get the CTest label SharedData (vis4gs_add_core_test scans for it).
 */
#define VIS4GS_REQUIRE_SHARED_DATA()                                                               \
  do                                                                                               \
  {                                                                                                \
    const std::string vis4gsMissing_ = vis4gs::testing::SharedDataMissing();                       \
    if (!vis4gsMissing_.empty())                                                                   \
    {                                                                                              \
      if (vis4gs::testing::UnderCI())                                                              \
      {                                                                                            \
        FAIL() << vis4gsMissing_ << "; under CI=true that is an error";                            \
      }                                                                                            \
      GTEST_SKIP() << vis4gsMissing_;                                                              \
    }                                                                                              \
  } while (false)

/**
 * First statement of a VTK C++ test (int TestX(int, char*[])) that reads shared/data: returns
 * SkipReturnCode with the message when the folder is absent, EXIT_FAILURE when CI=true.
 */
#define VIS4GS_SHARED_DATA_OR_SKIP()                                                               \
  do                                                                                               \
  {                                                                                                \
    const std::string vis4gsMissing_ = vis4gs::testing::SharedDataMissing();                       \
    if (!vis4gsMissing_.empty())                                                                   \
    {                                                                                              \
      std::printf("%s%s\n",                                                                        \
        vis4gsMissing_.c_str(),                                                                    \
        vis4gs::testing::UnderCI() ? "; under CI=true that is an error" : ": skipped");            \
      return vis4gs::testing::UnderCI() ? EXIT_FAILURE : vis4gs::testing::SkipReturnCode;          \
    }                                                                                              \
  } while (false)

namespace vis4gs
{
namespace testing
{

/// Path of @p relative inside the source tree (e.g. "Data/Demo/demo.h5").
inline std::string SourcePath(const std::string& relative)
{
  return std::string(VIS4GS_SOURCE_DIR) + "/" + relative;
}

} // namespace testing
} // namespace vis4gs

#endif

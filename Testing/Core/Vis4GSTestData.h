// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSTestData.h
 * @brief Paths of the test inputs: the real third-party scenes in ../shared/data (read in
 * place, never copied into the repository) and the repository's own Data/ folder.
 */
#ifndef vis4gs_TestData_h
#define vis4gs_TestData_h

#include <cstdlib>
#include <string>

namespace vis4gs
{
namespace testing
{

/// Path of @p relative inside shared/data; $VIS4GS_SHARED_DATA_DIR overrides the configured one.
inline std::string SharedDataPath(const std::string& relative)
{
  const char* env = std::getenv("VIS4GS_SHARED_DATA_DIR");
  return std::string(env && *env ? env : VIS4GS_SHARED_DATA_DIR) + "/" + relative;
}

/// Path of @p relative inside the source tree (e.g. "Data/Demo/demo.h5").
inline std::string SourcePath(const std::string& relative)
{
  return std::string(VIS4GS_SOURCE_DIR) + "/" + relative;
}

} // namespace testing
} // namespace vis4gs

#endif

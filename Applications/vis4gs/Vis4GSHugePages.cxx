// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSHugePages.h"

#include <cstdlib>
#include <fstream>
#include <string>

#include <unistd.h>

namespace
{
bool KernelAdvisesHugePages()
{
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  return std::getline(in, line) && line.find("[madvise]") != std::string::npos;
}
}

void Vis4GSUseHugePages(char* argv[])
{
  const char* optOut = std::getenv("VIS4GS_HUGE_PAGES");
  if ((optOut && std::string(optOut) == "0") || std::getenv("VIS4GS_HUGE_PAGES_REEXEC"))
  {
    return;
  }
  const char* current = std::getenv("GLIBC_TUNABLES");
  std::string tunables = current ? current : "";
  if (tunables.find("glibc.malloc.hugetlb") != std::string::npos || !KernelAdvisesHugePages())
  {
    return;
  }
  tunables += (tunables.empty() ? "" : ":") + std::string("glibc.malloc.hugetlb=1");
  // The marker stops a second attempt whatever glibc makes of the tunable.
  if (setenv("GLIBC_TUNABLES", tunables.c_str(), 1) != 0 ||
    setenv("VIS4GS_HUGE_PAGES_REEXEC", "1", 1) != 0)
  {
    return;
  }
  execv("/proc/self/exe", argv);
  // Only reached when the exec failed: go on with ordinary pages, as the user started us.
  if (current)
  {
    setenv("GLIBC_TUNABLES", current, 1);
  }
  else
  {
    unsetenv("GLIBC_TUNABLES");
  }
}

// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSProcessTuning.h"

#include <cstdlib>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

namespace
{
bool KernelAdvisesHugePages()
{
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  return std::getline(in, line) && line.find("[madvise]") != std::string::npos;
}

/// The GLIBC_TUNABLES value with huge pages added, or "" when nothing is to be added.
std::string HugePageTunables()
{
  const char* optOut = std::getenv("VIS4GS_HUGE_PAGES");
  if (optOut && std::string(optOut) == "0")
  {
    return {};
  }
  const char* current = std::getenv("GLIBC_TUNABLES");
  std::string tunables = current ? current : "";
  if (tunables.find("glibc.malloc.hugetlb") != std::string::npos || !KernelAdvisesHugePages())
  {
    return {};
  }
  return tunables + (tunables.empty() ? "" : ":") + std::string("glibc.malloc.hugetlb=1");
}

bool WantsPassiveWait(int argc, char* argv[])
{
  return argc >= 2 && std::string(argv[1]) == "train" && !std::getenv("OMP_WAIT_POLICY") &&
    !std::getenv("GOMP_SPINCOUNT");
}
}

void Vis4GSTuneProcess(int argc, char* argv[])
{
  // The marker stops a second attempt whatever the runtimes make of the settings.
  if (std::getenv("VIS4GS_HUGE_PAGES_REEXEC"))
  {
    return;
  }
  std::vector<std::pair<const char*, std::string>> settings;
  const std::string tunables = HugePageTunables();
  if (!tunables.empty())
  {
    settings.emplace_back("GLIBC_TUNABLES", tunables);
  }
  if (WantsPassiveWait(argc, argv))
  {
    settings.emplace_back("OMP_WAIT_POLICY", "passive");
  }
  if (settings.empty())
  {
    return;
  }
  // Restored when the exec fails: the program then goes on as the user started it.
  std::vector<std::pair<const char*, const char*>> saved; // getenv's strings stay valid
  bool set = setenv("VIS4GS_HUGE_PAGES_REEXEC", "1", 1) == 0;
  for (const auto& s : settings)
  {
    saved.emplace_back(s.first, std::getenv(s.first));
    set = set && setenv(s.first, s.second.c_str(), 1) == 0;
  }
  if (set)
  {
    execv("/proc/self/exe", argv);
  }
  for (const auto& s : saved)
  {
    if (s.second)
    {
      setenv(s.first, s.second, 1);
    }
    else
    {
      unsetenv(s.first);
    }
  }
  unsetenv("VIS4GS_HUGE_PAGES_REEXEC");
}

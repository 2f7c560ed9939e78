// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSProcessTuning.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <malloc.h>
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

// How many MiB of freed heap memory `vis4gs view` keeps (0: glibc's own policy).
long KeptFreedMiB(int argc, char* argv[])
{
  if (argc < 2 || std::string(argv[1]) != "view")
  {
    return 0;
  }
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (tunables &&
    (std::string(tunables).find("malloc.trim_threshold") != std::string::npos ||
      std::string(tunables).find("malloc.mmap_threshold") != std::string::npos))
  {
    return 0; // the user's choice
  }
  const char* given = std::getenv("VIS4GS_KEEP_FREED_MB");
  if (!given)
  {
    return Vis4GSDefaultKeptFreedMiB;
  }
  char* end = nullptr;
  const long mib = std::strtol(given, &end, 10);
  return end != given && *end == '\0' && mib > 0 ? std::min(mib, 4096L) : 0;
}

// Keeps up to @p mib MiB of freed heap in the process, and takes every block under 32 MiB
// from the heap: glibc otherwise returns a heap top of more than its (adaptive) trim
// threshold to the kernel and maps mid-sized blocks afresh, so each pick of the application
// faulted its transient buffers (the selection's id arrays, the GL driver's per-render
// buffers, the charts' text) in again. On a virtual machine whose free pages go back to the
// host, such a first touch costs up to ~8 us per 4 KiB (about 4 ms per 2 MiB huge page): 25-40
// ms of a Frame pick at 4.89M (Documentation/performance-history.md, "Frame within 100 ms").
void KeepFreedMemory(long mib)
{
  if (mib > 0)
  {
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, static_cast<int>(mib << 20));
  }
}

bool WantsPassiveWait(int argc, char* argv[])
{
  return argc >= 2 && std::string(argv[1]) == "train" && !std::getenv("OMP_WAIT_POLICY") &&
    !std::getenv("GOMP_SPINCOUNT");
}
}

void Vis4GSTuneProcess(int argc, char* argv[])
{
  // (In this process: a re-executed one sets it again.)
  KeepFreedMemory(KeptFreedMiB(argc, argv));
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

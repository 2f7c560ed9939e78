// SPDX-License-Identifier: BSD-3-Clause
#include "ThreadCount.h"

#include <algorithm>

#ifdef _OPENMP
#include <omp.h>
#endif

#ifdef __linux__
#include <cerrno>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace vis4gs
{

int ThreadCount(int requested)
{
#ifdef _OPENMP
  return requested > 0 ? requested : std::max(1, omp_get_max_threads());
#else
  (void)requested;
  return 1;
#endif
}

bool LowerThreadPriority(int niceness)
{
  if (niceness <= 0)
  {
    return true;
  }
#ifdef __linux__
  // PRIO_PROCESS with a thread id sets that thread's nice value only (Linux, not POSIX).
  const auto tid = static_cast<id_t>(syscall(SYS_gettid));
  errno = 0;
  const int current = getpriority(PRIO_PROCESS, tid);
  if (errno == 0 && current >= niceness)
  {
    return true;
  }
  return setpriority(PRIO_PROCESS, tid, std::min(niceness, 19)) == 0;
#else
  return false;
#endif
}

} // namespace vis4gs

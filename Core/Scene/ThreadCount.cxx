// SPDX-License-Identifier: BSD-3-Clause
#include "ThreadCount.h"

#include <algorithm>

#ifdef _OPENMP
#include <omp.h>
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

} // namespace vis4gs

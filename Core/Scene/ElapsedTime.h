// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ElapsedTime.h
 * @brief Milliseconds of wall time since a steady-clock instant: the one helper of the
 * libraries' own timing figures (the splat mapper's frames, its frame worker, the selector's
 * picks), which the benchmarks and `vis4gs view --benchmark` print. Header only.
 */
#ifndef vis4gs_ElapsedTime_h
#define vis4gs_ElapsedTime_h

#include <chrono>

namespace vis4gs
{

/// Wall milliseconds from @p t0 to now.
inline double MsSince(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

} // namespace vis4gs

#endif

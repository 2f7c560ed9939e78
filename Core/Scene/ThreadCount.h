// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ThreadCount.h
 * @brief The one rule for how many OpenMP threads a parallel region of Core runs: every
 * option named `Threads` means "this many when positive, else OpenMP's default". Lives in
 * Core/Scene because every Core area that runs threads depends on it.
 */
#ifndef vis4gs_ThreadCount_h
#define vis4gs_ThreadCount_h

namespace vis4gs
{

/// @p requested when positive, else OpenMP's default (omp_get_max_threads(), at least 1);
/// 1 in a build without OpenMP.
int ThreadCount(int requested);

} // namespace vis4gs

#endif

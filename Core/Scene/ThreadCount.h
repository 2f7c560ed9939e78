// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ThreadCount.h
 * @brief The one rule for how many OpenMP threads a parallel region of Core runs: every
 * option named `Threads` means "this many when positive, else OpenMP's default"; and how a
 * background worker gives way to an interactive thread of its process. Lives in Core/Scene
 * because every Core area that runs threads depends on it.
 */
#ifndef vis4gs_ThreadCount_h
#define vis4gs_ThreadCount_h

namespace vis4gs
{

/// @p requested when positive, else OpenMP's default (omp_get_max_threads(), at least 1);
/// 1 in a build without OpenMP.
int ThreadCount(int requested);

/**
 * Gives the calling thread the nice value @p niceness (0-19) unless it has a larger one: on Linux
 * the nice value is the thread's own, and the threads it starts afterwards inherit it, its OpenMP
 * team included (created at its first parallel region). A background worker (the scene view's
 * frames) calls it first thing, so that the threads of the same process it competes with on two
 * cores (the GUI thread, the OpenGL driver's) run first when they have work: nice 10 against 0
 * weighs 110 against 1024 in the kernel's fair scheduler. With the kernel's autogroups (the
 * default on desktops) the weights only apply within the process's session, so that the worker
 * loses nothing against other programs. Returns whether the thread now runs at @p niceness or
 * lower priority; @p niceness 0 or less changes nothing (true); false off Linux or when the
 * kernel refused.
 */
bool LowerThreadPriority(int niceness);

} // namespace vis4gs

#endif

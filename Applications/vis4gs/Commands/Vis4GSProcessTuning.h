// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSProcessTuning.h
 * @brief Settings the C and OpenMP runtimes read only when a process starts, chosen for
 * the user: transparent huge pages for the large buffers, and for `vis4gs train` OpenMP's
 * passive wait policy.
 *
 * Huge pages. On the virtual machines Vis4GS runs on, the first touch of fresh memory costs
 * about 3-4 us per 4 KiB page (Documentation/performance.md), which is most of the start-up
 * of a multi-gigabyte log. The kernel's transparent huge pages cut that cost by 512 when the
 * memory is advised (the common `madvise` setting); glibc advises every block it maps when
 * its tunable `glibc.malloc.hugetlb=1` is set (added to GLIBC_TUNABLES). Nothing is added
 * when VIS4GS_HUGE_PAGES=0 is set (the opt-out), when the kernel's setting is not `madvise`
 * (with `always` nothing is needed, with `never` nothing helps) or when the tunable is
 * already present.
 *
 * Wait policy. The trainer runs a few dozen short OpenMP regions per iteration with serial
 * steps between them (the loss sums, the metrics, densification, the log). By default
 * libgomp's idle threads spin for milliseconds before sleeping, so on two cores a serial
 * step costs twice its CPU time, and on a loaded machine a spinning thread takes the core
 * its partner needs (the 512x512 demo's training: Documentation/performance-history.md,
 * "Demo training after ..."). `vis4gs train` therefore sets OMP_WAIT_POLICY=passive unless
 * OMP_WAIT_POLICY or GOMP_SPINCOUNT is set already. It changes no result: only how threads
 * wait.
 *
 * Both are read when the runtimes start, so the program re-executes itself once, at the very
 * start of main(), with the environment completed. Nothing happens when nothing is to be
 * added, when the program was already re-executed, or when /proc/self/exe cannot be run (the
 * program then goes on as the user started it).
 */
#ifndef Vis4GSProcessTuning_h
#define Vis4GSProcessTuning_h

/// Re-executes the program with the settings above when one of them is to be added; returns
/// only when it does not re-execute.
void Vis4GSTuneProcess(int argc, char* argv[]);

#endif

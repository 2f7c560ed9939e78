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
 * Freed memory kept (`vis4gs view` only). The application allocates and frees the same
 * transient buffers at every pick and render (the selection's id arrays, the software GL
 * driver's per-render buffers); glibc gives a heap top beyond its adaptive trim threshold back
 * to the kernel and maps mid-sized blocks afresh, so they were faulted in again each time, at
 * the first-touch cost above (tens of ms of a 200,000-Gaussian Frame pick at 4.89M). The
 * application keeps up to Vis4GSDefaultKeptFreedMiB (256) MiB of freed heap and takes blocks
 * under 32 MiB from the heap (mallopt: M_TRIM_THRESHOLD, M_MMAP_THRESHOLD); larger blocks (the
 * scene's arrays) are mapped and given back as before. VIS4GS_KEEP_FREED_MB=N sets the amount
 * (0: glibc's policy); nothing is set when GLIBC_TUNABLES sets either threshold. This changes no
 * result, only when memory goes back to the kernel (malloc_trim() still gives it all back).
 *
 * The first two are read when the runtimes start, so the program re-executes itself once, at the
 * very start of main(), with the environment completed. Nothing happens when nothing is to be
 * added, when the program was already re-executed, or when /proc/self/exe cannot be run (the
 * program then goes on as the user started it).
 */
#ifndef Vis4GSProcessTuning_h
#define Vis4GSProcessTuning_h

/// MiB of freed heap that `vis4gs view` keeps by default (see above).
constexpr long Vis4GSDefaultKeptFreedMiB = 256;

/// Re-executes the program with the settings above when one of them is to be added; returns
/// only when it does not re-execute.
void Vis4GSTuneProcess(int argc, char* argv[]);

#endif

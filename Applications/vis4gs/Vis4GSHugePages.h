// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSHugePages.h
 * @brief Transparent huge pages for the program's large buffers, without the user's help.
 *
 * On the virtual machines Vis4GS runs on, the first touch of fresh memory costs about 3-4 us
 * per 4 KiB page (Documentation/performance.md), which is most of the start-up of a
 * multi-gigabyte log. The kernel's transparent huge pages cut that cost by 512 when the
 * memory is advised (the common `madvise` setting); glibc advises every block it maps when
 * its tunable `glibc.malloc.hugetlb=1` is set, and reads tunables only when a process
 * starts. So the program re-executes itself once, at the very start of main(), with that
 * tunable added to GLIBC_TUNABLES.
 *
 * Nothing happens when: VIS4GS_HUGE_PAGES=0 is set (the opt-out); the kernel's setting is not
 * `madvise` (with `always` nothing is needed, with `never` nothing helps); the tunable is
 * already present; the program was already re-executed; or /proc/self/exe cannot be run (the
 * program then simply goes on with ordinary pages).
 */
#ifndef Vis4GSHugePages_h
#define Vis4GSHugePages_h

/// Re-executes the program with glibc.malloc.hugetlb=1 when that helps (see the file's note);
/// returns only when it does not re-execute.
void Vis4GSUseHugePages(char* argv[]);

#endif

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSBenchmark.h
 * @brief `vis4gs view FILE --benchmark`: start-up and tree pan/zoom figures of the
 * application (Scripts/run-benchmarks.sh, Documentation/performance.md).
 *
 * Prints the wall and CPU time of each step of showing the loaded document, the first render
 * of each view, the time from @p startSeconds (the caller's steady clock at process start) to
 * all views drawn, then the tree view's pan/zoom frames per second, and exits. No scores are
 * computed in this mode.
 */
#ifndef Vis4GSBenchmark_h
#define Vis4GSBenchmark_h

class Vis4GSMainWindow;

/// Puts @p window in benchmark mode (before it opens its file).
void Vis4GSInstallBenchmark(Vis4GSMainWindow* window, double startSeconds, double startCpuSeconds);

#endif

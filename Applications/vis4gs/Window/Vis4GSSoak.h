// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSSoak.h
 * @brief `vis4gs view --soak=N,DIR FILE...`: a long scripted session in one process (issue 35
 * part 2), to find what a day of use leaks.
 *
 * Each cycle opens the next of the files given (a training log and a scene, alternately; the
 * document it replaces is freed), waits for its scores, moves the iteration slider down and
 * back (a log with several snapshots), selects at the scene view's centre with each selection
 * mode (Single, Ray, Frame, Brush), applies a clean-up rule and, where the document has
 * training images, measures the removal in the clean-up panel's worker thread and fine-tunes it
 * (FineTuneIterations, the repaired log written and deleted). After each cycle it records the
 * heap in use (mallinfo2), what malloc holds from the system, the resident memory
 * (/proc/self/statm) and its parts by kind of mapping (/proc/self/smaps: malloc's [heap],
 * other anonymous, executable anonymous, file-backed; and the number of mappings), the open
 * file descriptors (/proc/self/fd),
 * the threads (/proc/self/task) and the entries of the temporary folder (QDir::tempPath()) in
 * DIR/soak.csv (with the seconds to open and score, and of the actions). At the end it
 * compares cycles of the same files: the warm-up is the first half, at most 20 cycles (caches,
 * allocator arenas and thread pools reach their size), then the mean heap in use of the
 * last rounds of the files (up to 10 cycles) may exceed that of as many cycles after the
 * warm-up by BoundMB at most, and descriptors and threads (last cycle against the first of the
 * same file after the warm-up) and temporary entries (against the first cycle of the same
 * file) may not grow at all. It prints the figures and exits with 0 (within the bounds) or 1.
 */
#ifndef Vis4GSSoak_h
#define Vis4GSSoak_h

#include <QString>
#include <QStringList>

class Vis4GSMainWindow;

struct Vis4GSSoakOptions
{
  /// Cycles (at least 10).
  int Cycles = 20;
  /// Where soak.csv is written.
  QString Directory;
  /// The files opened in turn.
  QStringList Files;
  /// Resident memory growth allowed after the warm-up, MB (see the file's comment).
  double BoundMB = 16.0;
  /// Iterations of the clean-up panel's fine-tune on a document with training images, after
  /// its measurement (the repaired log goes to Directory and is deleted); 0: none.
  int FineTuneIterations = 1;
};

/// Runs the soak on @p window (before it opens a file; it opens them itself).
void Vis4GSInstallSoak(Vis4GSMainWindow* window, const Vis4GSSoakOptions& options);

#endif

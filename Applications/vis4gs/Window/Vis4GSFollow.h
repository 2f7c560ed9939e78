// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSFollow.h
 * @brief `vis4gs view LOG --follow`: watch a training log while its trainer writes it (issue 32).
 *
 * A timer asks the document's vtkGaussianTrainingLogReader to reopen the log (a log written
 * in SWMR mode, format version 2, is opened in SWMR read mode: the trainer is never blocked)
 * and, when the snapshot list or the metrics grew, opens the log again in the window (the
 * worker thread of Vis4GSMainWindow::Open): the timeline, the tree, panel C and the iteration
 * slider then show the new metrics, events and snapshots, the scene the latest snapshot.
 * Each such reload prints one line on standard output ("vis4gs view: following LOG:
 * S snapshots (last I), M metrics rows"), which the tests read.
 */
#ifndef Vis4GSFollow_h
#define Vis4GSFollow_h

class QString;
class Vis4GSMainWindow;

/// Makes @p window follow the log @p path, checking every @p intervalMs milliseconds (new data
/// shows within about intervalMs plus the reload time); a log that cannot be opened yet (its
/// trainer has not written its first snapshot) is tried again at each tick. While @p path does
/// not exist and "<path>.tmp" does (the Python logger's live file), that one is followed, and
/// @p path once the temporary is renamed onto it.
void Vis4GSInstallFollow(Vis4GSMainWindow* window, const QString& path, int intervalMs);

#endif

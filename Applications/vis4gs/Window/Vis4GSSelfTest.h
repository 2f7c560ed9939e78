// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSSelfTest.h
 * @brief `vis4gs view --self-test`: the scripted end-to-end check of the application (the
 * CTest tests vis4gs-View*), driving Vis4GSMainWindow through its public accessors.
 *
 * Once the document is loaded and its scores computed it checks the layout, selects a floater
 * in the scene view with every selection mode (through the view's methods and through its
 * interactor, as the mouse does), follows the selection into the tree, timeline and frustums,
 * saves screenshots of every view, compares the scene and tree screenshots with baselines,
 * runs the clean-up panel's check and moves the iteration slider; then it exits the
 * application with 0 (every check passed) or 1.
 */
#ifndef Vis4GSSelfTest_h
#define Vis4GSSelfTest_h

#include <QString>

#include <string>

class Vis4GSMainWindow;

struct Vis4GSSelfTestOptions
{
  /// Where the screenshots are saved.
  QString Directory;
  /// PNG baselines of the scene and tree screenshots (same names); empty: no comparison.
  QString BaselineDirectory;
  /// Per-pixel difference allowed (0..255) and the fraction of pixels that may exceed it.
  int Tolerance = 48;
  double Fraction = 0.02;
};

/// Runs the self-test on @p window once its document is loaded and scored (then exits).
void Vis4GSInstallSelfTest(Vis4GSMainWindow* window, const Vis4GSSelfTestOptions& options);

/**
 * `vis4gs view FILE --stages-test=STAGE1_CSV,EXACT_CSV` (Vis4GSScoreStagesSelfTest.cxx): the
 * progressive scores of @p window (opening @p file) against `vis4gs analyze
 * --stop-after-stage=1`'s and `vis4gs analyze`'s scores.csv: stage 1 shown and labelled, then
 * replaced by the exact scores; opened again and stopped after stage 1, which stays,
 * labelled. Exits the application with 0 or 1; false when a CSV cannot be read.
 */
bool Vis4GSInstallScoreStagesTest(Vis4GSMainWindow* window,
  const QString& file,
  const std::string& stage1Csv,
  const std::string& exactCsv);

#endif

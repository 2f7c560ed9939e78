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

#endif

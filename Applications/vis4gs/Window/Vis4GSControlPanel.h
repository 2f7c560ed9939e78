// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSControlPanel.h
 * @brief Panel C of DESIGN (log and control panel): the scene's selection mode, cameras,
 * iteration, overlay, level of detail, the training log's summary, the table of the selected
 * Gaussians and the export buttons, with the optional welcome text on top.
 *
 * A plain form of widgets: Vis4GSMainWindow connects them to the views and the document. The
 * controls a script or the self-test looks up have object names (findChild): "selection-mode",
 * "cameras", "iteration", "overlay", "overlay-min", "overlay-max", "hide-outside", "welcome".
 */
#ifndef Vis4GSControlPanel_h
#define Vis4GSControlPanel_h

#include <QWidget>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QFormLayout;
class QLabel;
class QListWidget;
class QPlainTextEdit;
class QPushButton;
class QSlider;
class QSpinBox;
class Vis4GSSelectionTable;

class Vis4GSControlPanel : public QWidget
{
public:
  explicit Vis4GSControlPanel(QWidget* parent = nullptr);

  /// Shows or hides a row of the form (the field and its label).
  void ShowRow(QWidget* field, bool visible);

  /**
   * Shows the welcome text on top: what a newcomer can try on the embedded demo (the case
   * study of the user guide), dismissible.
   */
  void ShowWelcome();

  /// Sets the overlay range and threshold boxes to @p lo, @p hi without signalling.
  void SetOverlayRange(double lo, double hi);

  QComboBox* SelectionMode = nullptr;
  QListWidget* CameraList = nullptr;
  QCheckBox* ShowFrustums = nullptr;
  QWidget* IterationRow = nullptr;
  QSlider* IterationSlider = nullptr;
  QLabel* IterationLabel = nullptr;
  QComboBox* Overlay = nullptr;
  /// The stage of the scores shown ("score-stage") and the button that stops them.
  QLabel* ScoreStage = nullptr;
  QPushButton* StopScores = nullptr;
  QDoubleSpinBox* OverlayMin = nullptr;
  QDoubleSpinBox* OverlayMax = nullptr;
  QCheckBox* HideOutside = nullptr;
  QCheckBox* UseThreshold = nullptr;
  QDoubleSpinBox* Threshold = nullptr;
  QCheckBox* DimUnselected = nullptr;
  QSpinBox* SplatBudget = nullptr;
  QSpinBox* MovingBudget = nullptr;
  QPlainTextEdit* LogText = nullptr;
  Vis4GSSelectionTable* Table = nullptr;
  QPushButton* ExportIds = nullptr;
  QPushButton* ExportPly = nullptr;
  QPushButton* DeletePly = nullptr;

private:
  QFormLayout* Form = nullptr;
  QWidget* Welcome = nullptr;
};

#endif

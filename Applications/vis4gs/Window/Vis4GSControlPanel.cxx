// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSControlPanel.h"

#include "Vis4GSSelectionTable.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QListWidget>
#include <QPlainTextEdit>
#include <QPushButton>
#include <QSlider>
#include <QSpinBox>
#include <QVBoxLayout>

#include <algorithm>

//------------------------------------------------------------------------------
Vis4GSControlPanel::Vis4GSControlPanel(QWidget* parent)
  : QWidget(parent)
  , Form(new QFormLayout(this))
{
  this->SelectionMode = new QComboBox(this);
  this->SelectionMode->setObjectName("selection-mode");
  this->SelectionMode->addItems(
    { "Single (click)", "Brush (drag)", "Frame (drag)", "Ray (click)" });
  this->SelectionMode->setToolTip("Selection in the scene view (left button). Shift adds to the "
                                  "selection, Ctrl subtracts; Brush and Frame drag instead of "
                                  "rotating (rotate with the middle button then). Keys 1-4.");
  this->Form->addRow("Selection mode", this->SelectionMode);
  this->CameraList = new QListWidget(this);
  this->CameraList->setObjectName("cameras");
  this->CameraList->setMaximumHeight(90);
  this->CameraList->setToolTip("Click a training camera to view the scene from it");
  this->Form->addRow("Cameras", this->CameraList);
  this->ShowFrustums = new QCheckBox("Show frustums (colour: selected Gaussians seen)", this);
  this->ShowFrustums->setChecked(true);
  this->Form->addRow(this->ShowFrustums);
  auto* itRow = new QWidget(this);
  auto* itLayout = new QHBoxLayout(itRow);
  itLayout->setContentsMargins(0, 0, 0, 0);
  this->IterationSlider = new QSlider(Qt::Horizontal, itRow);
  this->IterationSlider->setObjectName("iteration");
  this->IterationLabel = new QLabel("-", itRow);
  itLayout->addWidget(this->IterationSlider, 1);
  itLayout->addWidget(this->IterationLabel);
  this->Form->addRow("Iteration", itRow);
  this->IterationRow = itRow;
  this->Overlay = new QComboBox(this);
  this->Overlay->setObjectName("overlay");
  this->Overlay->addItem("True colour");
  this->Form->addRow("Overlay", this->Overlay);
  // Progressive scores (issue 31): which stage the overlays and histograms show, and Stop,
  // which keeps the last finished stage.
  auto* stageRow = new QWidget(this);
  auto* stageLayout = new QHBoxLayout(stageRow);
  stageLayout->setContentsMargins(0, 0, 0, 0);
  this->ScoreStage = new QLabel("-", stageRow);
  this->ScoreStage->setObjectName("score-stage");
  this->ScoreStage->setWordWrap(true);
  this->StopScores = new QPushButton("Stop", stageRow);
  this->StopScores->setObjectName("stop-scores");
  this->StopScores->setToolTip("Stop the scores: the overlays keep the last finished stage");
  this->StopScores->setEnabled(false);
  stageLayout->addWidget(this->ScoreStage, 1);
  stageLayout->addWidget(this->StopScores);
  this->Form->addRow("Scores", stageRow);
  this->OverlayMin = new QDoubleSpinBox(this);
  this->OverlayMax = new QDoubleSpinBox(this);
  this->OverlayMin->setObjectName("overlay-min");
  this->OverlayMax->setObjectName("overlay-max");
  this->Threshold = new QDoubleSpinBox(this);
  for (QDoubleSpinBox* box : { this->OverlayMin, this->OverlayMax, this->Threshold })
  {
    box->setDecimals(4);
    box->setRange(-1e9, 1e9);
  }
  auto* rangeRow = new QWidget(this);
  auto* rangeLayout = new QHBoxLayout(rangeRow);
  rangeLayout->setContentsMargins(0, 0, 0, 0);
  rangeLayout->addWidget(this->OverlayMin);
  rangeLayout->addWidget(this->OverlayMax);
  this->Form->addRow("Range", rangeRow);
  this->HideOutside = new QCheckBox("Hide Gaussians outside the range", this);
  this->HideOutside->setObjectName("hide-outside");
  this->Form->addRow(this->HideOutside);
  auto* thresholdRow = new QWidget(this);
  auto* thresholdLayout = new QHBoxLayout(thresholdRow);
  thresholdLayout->setContentsMargins(0, 0, 0, 0);
  this->UseThreshold = new QCheckBox("hide below", thresholdRow);
  thresholdLayout->addWidget(this->UseThreshold);
  thresholdLayout->addWidget(this->Threshold, 1);
  this->Form->addRow("Threshold", thresholdRow);
  this->DimUnselected = new QCheckBox("Dim unselected Gaussians", this);
  this->Form->addRow(this->DimUnselected);
  this->SplatBudget = new QSpinBox(this);
  this->SplatBudget->setRange(0, 100000000);
  this->SplatBudget->setSingleStep(50000);
  this->SplatBudget->setSpecialValueText("all");
  this->SplatBudget->setValue(200000);
  this->SplatBudget->setToolTip("Level of detail of the scene view on a hardware OpenGL: at most "
                                "this many splats are drawn (every k-th in depth order); software "
                                "OpenGL draws every Gaussian with the CPU rasteriser. Selection "
                                "and scores always use every Gaussian");
  this->Form->addRow("Splats drawn (max)", this->SplatBudget);
  this->MovingBudget = new QSpinBox(this);
  this->MovingBudget->setObjectName("moving-budget");
  this->MovingBudget->setRange(0, 100000000);
  this->MovingBudget->setSingleStep(50000);
  this->MovingBudget->setSpecialValueText("all");
  this->MovingBudget->setValue(400000);
  this->MovingBudget->setToolTip(
    "Level of detail of the CPU rasteriser (software OpenGL) while the camera moves: at most "
    "this many Gaussians, those of highest opacity times projected area, are drawn per moving "
    "frame; the still frame draws every Gaussian (exact). Documentation/accuracy-vs-runtime.md "
    "gives the error and frame rate of each budget");
  this->Form->addRow("Splats while moving (CPU)", this->MovingBudget);
  this->LogText = new QPlainTextEdit(this);
  this->LogText->setReadOnly(true);
  this->LogText->setMaximumHeight(140);
  this->Form->addRow("Training log", this->LogText);
  this->Table = new Vis4GSSelectionTable(this);
  this->Form->addRow("Selected", this->Table);
  auto* buttons = new QWidget(this);
  auto* bl = new QHBoxLayout(buttons);
  bl->setContentsMargins(0, 0, 0, 0);
  this->ExportIds = new QPushButton("Export ids (CSV)", buttons);
  this->ExportPly = new QPushButton("Export PLY", buttons);
  this->DeletePly = new QPushButton("Delete to new PLY", buttons);
  bl->addWidget(this->ExportIds);
  bl->addWidget(this->ExportPly);
  bl->addWidget(this->DeletePly);
  this->Form->addRow(buttons);
}

//------------------------------------------------------------------------------
void Vis4GSControlPanel::ShowRow(QWidget* field, bool visible)
{
  field->setVisible(visible);
  if (QWidget* label = this->Form->labelForField(field))
  {
    label->setVisible(visible);
  }
}

//------------------------------------------------------------------------------
void Vis4GSControlPanel::SetOverlayRange(double lo, double hi)
{
  for (QDoubleSpinBox* box : { this->OverlayMin, this->OverlayMax, this->Threshold })
  {
    box->blockSignals(true);
    box->setSingleStep(std::max(1e-4, (hi - lo) / 100.0));
  }
  this->OverlayMin->setValue(lo);
  this->OverlayMax->setValue(hi);
  this->Threshold->setValue(lo);
  for (QDoubleSpinBox* box : { this->OverlayMin, this->OverlayMax, this->Threshold })
  {
    box->blockSignals(false);
  }
}

//------------------------------------------------------------------------------
void Vis4GSControlPanel::ShowWelcome()
{
  if (this->Welcome)
  {
    this->Welcome->show();
    return;
  }
  // What the case study of the user guide does, as steps a newcomer can follow.
  this->Welcome = new QWidget(this);
  auto* layout = new QVBoxLayout(this->Welcome);
  auto* text = new QLabel(this->Welcome);
  text->setObjectName("welcome");
  text->setWordWrap(true);
  text->setTextFormat(Qt::RichText);
  text->setText("<b>Welcome to Vis4GS.</b> This demo is a 2000-iteration training run with "
                "planted floaters. Try the case study of the user guide:"
                "<ol style='margin-left:-20px'>"
                "<li><b>Find a floater:</b> set <i>Overlay</i> to <i>ViewCoverage</i> (when "
                "the scores are computed, see the status bar) and tick <i>Hide Gaussians "
                "outside the range</i> with the range 0 to 0.3: bright (yellow) splats are "
                "the suspicious ones, seen by few training views.</li>"
                "<li><b>Select it:</b> click one in the scene (Single mode, key 1). Its "
                "training cameras turn red.</li>"
                "<li><b>Its lineage:</b> the tree (B) draws its ancestors in yellow; press L "
                "to zoom to them.</li>"
                "<li><b>Its history:</b> the timeline (D) plots its opacity over the "
                "snapshots; the slider or the Left/Right keys move through them.</li>"
                "</ol>Rotate: left drag; zoom: wheel; R resets the camera.");
  layout->addWidget(text);
  auto* close = new QPushButton("Close this help", this->Welcome);
  layout->addWidget(close, 0, Qt::AlignRight);
  connect(close, &QPushButton::clicked, this->Welcome, &QWidget::hide);
  this->Welcome->setStyleSheet("QWidget { background: #fff8d0; }");
  this->Form->insertRow(0, this->Welcome);
}

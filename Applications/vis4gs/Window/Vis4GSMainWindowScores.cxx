// SPDX-License-Identifier: BSD-3-Clause
// Vis4GSMainWindow's scores: the progressive stages (Vis4GSScoreStages) of the shown snapshot,
// each handed to the views as it lands, and the panel's Scores row and Stop button.
#include "Vis4GSMainWindow.h"
#include "Vis4GSMainWindowInternals.h"

#include "Vis4GSCleanupPanel.h"
#include "Vis4GSControlPanel.h"
#include "Vis4GSDocument.h"

#include "RemovalEffect.h"

#include "vtkGaussianSession.h"
#include "vtkPolyData.h"

#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QStatusBar>

#include <exception>
#include <iostream>

//------------------------------------------------------------------------------
void Vis4GSMainWindow::StartScores()
{
  vtkPolyData* scene = d->Doc ? d->Doc->Scene.GetPointer() : nullptr;
  if (!scene)
  {
    return;
  }
  if (d->Scores->IsRunning())
  {
    d->ScoresPending = true; // restarted for the new snapshot when this one is done
    d->Scores->Stop();
    return;
  }
  d->ScoresDone = false;
  if (d->Doc->Cameras && !d->ScoreCameras)
  {
    // Embedded training images are written once per document to a temporary folder (in the
    // GUI thread: the log's HDF5 file is only read here).
    try
    {
      d->ImageDir = std::make_unique<QTemporaryDir>();
      d->ScoreCameras = d->Doc->ScoreCameras(d->ImageDir->path().toStdString());
    }
    catch (const std::exception& e)
    {
      this->statusBar()->showMessage(QString("training images: ") + e.what(), 5000);
      d->ScoreCameras = d->Doc->Cameras;
    }
  }
  vtkSmartPointer<vtkTable> cameras = d->ScoreCameras;
  const bool images = d->Doc->CamerasWithImages > 0;
  d->Progress->setValue(0);
  d->Progress->show();
  d->Panel->StopScores->setEnabled(true);
  d->Panel->ScoreStage->setText("computing...");
  this->statusBar()->showMessage(cameras
      ? (images ? "computing View Coverage, Blur, Needle scores and needle shape"
                : "computing View Coverage and needle shape (the log has no training images)")
      : "computing the needle shape (no cameras: no View Coverage, Blur or Needle score)");
  // The blur/needle pass's renders are the clean-up panel's "before" of this snapshot.
  auto baseline = std::make_shared<vis4gs::RemovalBaseline>();
  d->Scores->StageDone = [this, cameras, baseline](
                           vtkPolyData* input, const Vis4GSScoreStages::Stage& stage)
  {
    vtkPolyData* current = d->Doc ? d->Doc->Scene.GetPointer() : nullptr;
    if (current != input || d->ScoresPending)
    {
      return; // a snapshot or document opened since
    }
    // The stage's session is the views' Gaussians port from now on (UpdateScene connects
    // them): its output is the snapshot with the scores and their `ScoreStage` label.
    d->Doc->Scored = stage.Session;
    const bool last = stage.Number == stage.Of;
    d->Panel->ScoreStage->setText(QString::fromStdString(stage.Label));
    this->statusBar()->showMessage("scores: " + QString::fromStdString(stage.Label) +
        (last ? QString() : QString("; computing the exact scores (Stop keeps these)")),
      last ? 3000 : 0);
    this->UpdateScene(); // overlay and histogram lists
    if (last)
    {
      // (After UpdateScene: it gives the panel the score cameras of the first pass.)
      d->Cleanup->SetScoreBaseline(d->Doc->Shown(), cameras, baseline);
    }
    emit this->scoreStageShown(stage.Number, stage.Of);
  };
  d->Scores->Finished = [this](vtkPolyData* input, const QString& error, bool stopped)
  {
    d->Progress->hide();
    d->Panel->StopScores->setEnabled(false);
    vtkPolyData* current = d->Doc ? d->Doc->Scene.GetPointer() : nullptr;
    if (!error.isEmpty())
    {
      this->statusBar()->showMessage("scores: " + error, 5000);
      std::cerr << "vis4gs view: error: scores: " << error.toStdString() << "\n";
    }
    else if (stopped && current == input && !d->ScoresPending)
    {
      const QString kept = d->Panel->ScoreStage->text();
      d->Panel->ScoreStage->setText(
        kept == "computing..." ? QString("stopped: no scores") : kept + " (stopped)");
      this->statusBar()->showMessage("scores stopped: " + d->Panel->ScoreStage->text(), 5000);
    }
    if (d->ScoresPending)
    {
      d->ScoresPending = false;
      this->StartScores();
      return;
    }
    d->ScoresDone = true;
    emit this->scoresComputed();
  };
  d->Scores->Start(scene, cameras, images, baseline, 2, d->Doc->Path);
}

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSScoreStages.h
 * @brief The application's progressive scores (issue 31): the score filter's first,
 * approximate stage, then the exact scores, in a worker thread, each handed to the GUI thread
 * as it lands; Stop() keeps the last finished stage.
 */
#ifndef Vis4GSScoreStages_h
#define Vis4GSScoreStages_h

#include "vtkSmartPointer.h"

#include <QString>

#include <atomic>
#include <functional>
#include <memory>
#include <string>

class QObject;
class QThread;
class vtkGaussianSession;
class vtkPolyData;
class vtkTable;
namespace vis4gs
{
struct RemovalBaseline;
}

class Vis4GSScoreStages
{
public:
  /// One finished stage: its number (1 or 2), how many the run has, the filter's label
  /// ("stage 1 of 2, approximate: every 8th training view, ...") and the session that
  /// computed it (Vis4GSDocument::ComputeScores: its Gaussians port holds the scene with the
  /// score arrays; a session per stage, so the GUI may connect the views to it while the
  /// worker computes the next).
  struct Stage
  {
    int Number = 0;
    int Of = 0;
    std::string Label;
    vtkSmartPointer<vtkGaussianSession> Session;
  };

  /// Callbacks run in the thread of @p context (the window): the events of a run are queued
  /// to it, so they arrive after Start() returned and in order.
  explicit Vis4GSScoreStages(QObject* context);
  /// Stops a run in progress and waits for its worker (its remaining events are dropped).
  ~Vis4GSScoreStages();
  Vis4GSScoreStages(const Vis4GSScoreStages&) = delete;
  Vis4GSScoreStages& operator=(const Vis4GSScoreStages&) = delete;

  /// A stage landed: @p input is the scene Start() was given.
  std::function<void(vtkPolyData* input, const Stage& stage)> StageDone;
  /// The run ended: after its last stage, on an error (@p error; the stages before stay), or
  /// stopped (@p stopped; the stages before stay). The worker has ended when this is called.
  std::function<void(vtkPolyData* input, const QString& error, bool stopped)> Finished;
  /// Progress of the running stage, in [0, 1] over the whole run.
  std::function<void(double fraction, const QString& message)> Progress;

  /// Whether a run is in progress (between Start() and its Finished).
  bool IsRunning() const { return this->Worker != nullptr; }

  /**
   * Starts the scores of @p scene (Vis4GSDocument::ComputeScores with @p cameras, @p images,
   * @p baseline for the exact stage) in a worker thread: with cameras, stage 1 (the score
   * filter's ProgressiveStage 1: every 8th view, maps at 1/4) then stage 2 (the exact
   * scores); without cameras (needle shape alone, nothing to approximate) one stage.
   * @p stages = 1 stops after the first. @p name (the document's file) names the errors.
   * Does nothing while a run is in progress.
   */
  void Start(vtkSmartPointer<vtkPolyData> scene,
    vtkSmartPointer<vtkTable> cameras,
    bool images,
    std::shared_ptr<vis4gs::RemovalBaseline> baseline,
    int stages = 2,
    const std::string& name = std::string());

  /// Stops the run (returns at once): the running stage ends after the view it is on, no
  /// later stage starts, and Finished reports it stopped.
  void Stop();

  /// Blocks until the worker has ended (a new document, closing); its queued events still
  /// come unless the object is destroyed first.
  void Wait();

private:
  QObject* Context;
  QThread* Worker = nullptr;
  std::shared_ptr<std::atomic<bool>> StopFlag;
};

#endif

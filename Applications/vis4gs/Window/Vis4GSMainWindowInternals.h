// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSMainWindowInternals.h
 * @brief Vis4GSMainWindow's private state, shared by its source files (Vis4GSMainWindow.cxx:
 * the window, layout, loading and selection; Vis4GSMainWindowScores.cxx: the scores).
 */
#ifndef Vis4GSMainWindowInternals_h
#define Vis4GSMainWindowInternals_h

#include "Vis4GSMainWindow.h"
#include "Vis4GSSceneFrames.h"
#include "Vis4GSScoreStages.h"

#include "vtkCallbackCommand.h"
#include "vtkGaussianHistogramView.h"
#include "vtkGaussianSceneView.h"
#include "vtkGaussianSelectionHub.h"
#include "vtkGaussianTimelineView.h"
#include "vtkGaussianTreeView.h"
#include "vtkGenericOpenGLRenderWindow.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"
#include "vtkTable.h"
#include "vtkWeakPointer.h"

#include <QTemporaryDir>

#include <atomic>
#include <functional>
#include <memory>
#include <set>
#include <string>

class QComboBox;
class QDockWidget;
class QLabel;
class QProgressBar;
class QStackedWidget;
class QThread;
class QVTKOpenGLNativeWidget;
class Vis4GSCleanupPanel;
class Vis4GSControlPanel;
class vtkGaussianSession;
struct Vis4GSDocument;

struct Vis4GSMainWindow::Internals
{
  vtkNew<vtkGaussianSelectionHub> Hub;
  std::shared_ptr<Vis4GSDocument> Doc;
  // A: scene (Views/Scene).
  QVTKOpenGLNativeWidget* SceneWidget = nullptr;
  vtkNew<vtkGenericOpenGLRenderWindow> SceneWindow;
  vtkNew<vtkGaussianSceneView> Scene;
  std::unique_ptr<Vis4GSSceneFrames> SceneFrames; // (after Scene: destroyed before it)
  vtkNew<vtkCallbackCommand> PickCommand;
  // Scores (worker thread, progressive stages).
  std::unique_ptr<Vis4GSScoreStages> Scores;
  bool ScoresPending = false, ScoresDone = false;
  vtkSmartPointer<vtkTable> ScoreCameras;
  std::unique_ptr<QTemporaryDir> ImageDir;
  // B, D, histogram.
  QVTKOpenGLNativeWidget* TreeWidget = nullptr;
  QStackedWidget* TreeStack = nullptr; // the tree, or TreeMessage: why the log has none
  QLabel* TreeMessage = nullptr;
  vtkNew<vtkGenericOpenGLRenderWindow> TreeWindow;
  vtkNew<vtkGaussianTreeView> Tree;
  QVTKOpenGLNativeWidget* TimelineWidget = nullptr;
  vtkNew<vtkGenericOpenGLRenderWindow> TimelineWindow;
  vtkNew<vtkGaussianTimelineView> Timeline;
  QVTKOpenGLNativeWidget* HistogramWidget = nullptr;
  vtkNew<vtkGenericOpenGLRenderWindow> HistogramWindow;
  vtkNew<vtkGaussianHistogramView> Histogram;
  // C: panel.
  Vis4GSControlPanel* Panel = nullptr;
  QComboBox* HistogramArray = nullptr; // (in the histogram dock)
  QProgressBar* Progress = nullptr;
  std::string SceneCameras, SceneImages;
  int SceneIteration = -1;
  QDockWidget* Docks[5] = { nullptr, nullptr, nullptr, nullptr, nullptr };
  // Guided clean-up (issue 20): opened from the Selection menu, tabbed with panel C.
  Vis4GSCleanupPanel* Cleanup = nullptr;
  QDockWidget* CleanupDock = nullptr;
  vtkNew<vtkCallbackCommand> HubCommand;
  // The errors of the document's session when a view pulls its ports (the timeline's history
  // of a selection): to the status bar, and once each to standard error.
  vtkNew<vtkCallbackCommand> SessionErrors;
  vtkWeakPointer<vtkGaussianSession> ObservedSession;
  unsigned long SessionErrorsTag = 0;
  std::set<std::string> SessionErrorsSaid;
  QThread* Worker = nullptr;
  // A harness's hooks (SetLoadHooks).
  std::function<void(int, const char*)> StageHook;
  std::function<void()> LoadedHook;
  // The dock sizes of the document's layout (LayoutForDocument), applied again by SettleLayout.
  std::function<void()> DockSizes;
};

#endif

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSMainWindow.h
 * @brief The Qt5 main window of `vis4gs view`: the four linked views of DESIGN in docks
 * (A scene, B densification tree, C log and control panel, D property timeline) plus an
 * attribute histogram dock, all linked through one vtkGaussianSelectionHub.
 *
 * Files are loaded in a worker thread (Vis4GSDocument::Load, a QThread); its progress is
 * posted to the GUI thread (queued calls), so the interface stays responsive and shows a
 * progress bar. Only the docks the file has data for are shown.
 *
 * The window is layout, menus, docks and panel C: view A is vtkGaussianSceneView (Views/Scene),
 * B, D and the histogram the views of Views/Linked. The self-test and the benchmark mode drive
 * it from outside (Vis4GSSelfTest.h, Vis4GSBenchmark.h) through the accessors below.
 */
#ifndef Vis4GSMainWindow_h
#define Vis4GSMainWindow_h

#include <QMainWindow>

#include <functional>
#include <memory>

class QDockWidget;
class Vis4GSCleanupPanel;
struct Vis4GSDocument;
class vtkGaussianHistogramView;
class vtkGaussianSceneView;
class vtkGaussianSelectionHub;
class vtkGaussianTimelineView;
class vtkGaussianTreeView;
class vtkTable;

class Vis4GSMainWindow : public QMainWindow
{
  Q_OBJECT
public:
  explicit Vis4GSMainWindow(QWidget* parent = nullptr);
  ~Vis4GSMainWindow() override;

  /// Starts loading @p path in a worker thread.
  void Open(const QString& path);

  /**
   * Cameras for the scene files opened next (a cameras.json or a COLMAP folder; empty, the
   * default, looks for cameras.json next to the scene,
   * vtkGaussianCameraReader::FindSceneCamerasFile()).
   */
  void SetSceneCameras(const QString& cameras);
  /**
   * Training images of the scene files opened next (a folder, matched to the cameras by name,
   * as `vis4gs repair --images`; they give the scores and the clean-up panel's measurement) and
   * the iteration they were trained to (the clean-up's fine-tune continues from it; -1: 0).
   */
  void SetSceneImages(const QString& folder, int iteration);

  /**
   * Level of detail of the scene view: at most @p splats Gaussians are drawn (every k-th in
   * depth order, vtkGaussianSplatMapper::MaximumNumberOfSplats); 0 draws all. Selection and
   * scores always use every Gaussian. Default 200000.
   */
  void SetSplatBudget(long long splats);

  /**
   * Show the welcome panel at the top of the control panel: what a newcomer can try on the
   * embedded demo (the case study of the user guide), dismissible. `vis4gs demo` turns it on.
   */
  void ShowWelcome();

  /// Shows the guided clean-up panel (issue 20, Vis4GSCleanupPanel) in front of its dock.
  void ShowCleanup();

  /// Saves a screenshot of a dock ("scene", "tree", "panel", "timeline", "histogram") or of
  /// the whole window ("window"). Returns false when it could not be written.
  bool SaveScreenshot(const QString& which, const QString& path);

  ///@{
  /**
   * What the window shows, for the harnesses (Vis4GSSelfTest, Vis4GSBenchmark) and scripts:
   * the hub, the views, the loaded document (nullptr before), the cameras the scores used
   * (with their training images), a dock by name ("scene", "tree", "panel", "timeline",
   * "histogram", "cleanup") and the clean-up panel. Panel C's controls are found by object
   * name with findChild: "selection-mode", "cameras", "iteration", "overlay", "overlay-min",
   * "overlay-max", "hide-outside" and "welcome" (the welcome text).
   */
  vtkGaussianSelectionHub* GetHub();
  vtkGaussianSceneView* GetSceneView();
  vtkGaussianTreeView* GetTreeView();
  vtkGaussianTimelineView* GetTimelineView();
  vtkGaussianHistogramView* GetHistogramView();
  std::shared_ptr<Vis4GSDocument> GetDocument() const;
  vtkTable* GetScoreCameras() const;
  QDockWidget* GetDock(const QString& name) const;
  Vis4GSCleanupPanel* GetCleanupPanel() const;
  ///@}

  /**
   * Hooks of a harness. @p stage is called as the window shows a loaded document: with
   * nullptr when a sequence of steps starts (depth 0: the document, 1: its scene), then with
   * the name of each step done. With @p loaded set, the window neither renders the views nor
   * computes scores after loading (nor after a snapshot change) and calls it instead.
   */
  void SetLoadHooks(std::function<void(int depth, const char* step)> stage,
    std::function<void()> loaded);

signals:
  /// The scores of the document (or of its snapshot) are computed and shown (all stages, or
  /// those before a stop).
  void scoresComputed();
  /// Stage @p stage of @p of of the progressive scores is shown (overlays, histograms, the
  /// panel's "score-stage" label, the scene's `ScoreStage` field data); "stop-scores" stops.
  void scoreStageShown(int stage, int of);
  /// The file could not be loaded.
  void loadFailed(const QString& error);

protected:
  void dragEnterEvent(QDragEnterEvent* event) override;
  void dropEvent(QDropEvent* event) override;

private:
  void BuildUi();
  // Docks and panel rows for the views the document has data for (tree, timeline, cameras,
  // snapshots); the remaining views share the window.
  void LayoutForDocument();
  // Lays the docks out now, at their final sizes: a view resized after its first frame draws
  // it again, and one software frame of a 4.89M-Gaussian scene costs about 0.7 s.
  void SettleLayout();
  void OnProgress(double fraction, const QString& message);
  void OnLoaded(std::shared_ptr<Vis4GSDocument> document, const QString& error);
  void OnSelectionChanged();
  void OnIterationChanged(int iteration);
  /// Hands the document's scene to the views; @p render: render the scene view afterwards.
  void UpdateScene(bool render = true);
  void UpdateOverlay(bool render = true);
  void StartScores();
  void OnCameraChosen(int row);
  void ExportIds();
  void ExportPly(bool deleteSelection);
  void ScreenshotDialog();
  void Stage(int depth, const char* step);

  struct Internals;
  std::unique_ptr<Internals> d;
};

#endif

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
 */
#ifndef Vis4GSMainWindow_h
#define Vis4GSMainWindow_h

#include <QMainWindow>

#include <array>
#include <memory>
#include <string>
#include <vector>

class QCheckBox;
class QComboBox;
class QSpinBox;
class QDoubleSpinBox;
class QDockWidget;
class QLabel;
class QListWidget;
class QPlainTextEdit;
class QProgressBar;
class QSlider;
class QTableWidget;
class QVTKOpenGLNativeWidget;
struct Vis4GSDocument;
class vtkGaussianHistogramView;
class vtkGaussianSelectionHub;
class vtkGaussianTimelineView;
class vtkGaussianTreeView;

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
   * default, looks for cameras.json next to the scene, Vis4GSFindSceneCameras()).
   */
  void SetSceneCameras(const QString& cameras);

  /// Runs the scripted end-to-end check once the file is loaded (used by tests), saving
  /// screenshots of every view into @p directory; the application exits with 0 or 1.
  void SetSelfTest(const QString& directory);

  /**
   * Compares the scene and tree screenshots of the self-test with the PNG baselines in
   * @p directory (same names), allowing per-pixel differences up to @p tolerance (0..255) on
   * at most @p fraction of the pixels. Used with SetSelfTest.
   */
  void SetBaseline(const QString& directory, int tolerance = 48, double fraction = 0.02);

  /**
   * Benchmark mode: after loading, prints the time from @p startSeconds (steady clock of the
   * caller, process start) to all views drawn, wall and CPU, then measures tree pan/zoom
   * frames per second and exits. No scores are computed in this mode.
   */
  void SetBenchmark(double startSeconds, double startCpuSeconds);

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

  vtkGaussianSelectionHub* GetHub();
  vtkGaussianTreeView* GetTreeView();
  vtkGaussianTimelineView* GetTimelineView();
  /// Number of Gaussians highlighted in the scene view.
  long long GetSceneHighlightCount() const;
  /// Selects the Gaussian drawn at display pixel (x, y) of the scene view; returns its id.
  long long PickInScene(int x, int y);

  /// Scene selection modes of panel C.
  enum SceneSelectionModes
  {
    SINGLE = 0,
    BRUSH = 1,
    FRAME = 2,
    RAY = 3
  };
  /**
   * Runs a scene selection in VTK display coordinates through vtkGaussianSelector and
   * publishes it to the hub combined by @p combine (vtkGaussianSelectionHub::REPLACE, ADD,
   * SUBTRACT). SINGLE/RAY use the first point, FRAME the first two (corners), BRUSH all (the
   * stroke). Returns the number of Gaussians the mode picked, -1 on error.
   */
  long long SelectInScene(int mode, const std::vector<std::array<double, 2>>& points, int combine);
  /// Ids of the last Ray selection, front to back.
  std::vector<long long> GetLastRayHits() const;

protected:
  void dragEnterEvent(QDragEnterEvent* event) override;
  void dropEvent(QDropEvent* event) override;

private:
  void BuildUi();
  // Docks and panel rows for the views the document has data for (tree, timeline, cameras,
  // snapshots); the remaining views share the window.
  void LayoutForDocument();
  void OnProgress(double fraction, const QString& message);
  void OnLoaded(std::shared_ptr<Vis4GSDocument> document, const QString& error);
  void OnSelectionChanged();
  void OnIterationChanged(int iteration);
  /// Hands the document's scene to the views; @p render: render the scene view afterwards.
  void UpdateScene(bool render = true);
  void UpdateOverlay(bool render = true);
  void UpdateFrustums();
  void StartScores();
  void OnSceneMouse(unsigned long event, bool& abort);
  void OnSceneClick();
  void OnCameraChosen(int row);
  bool CompareBaselines();
  void RunBenchmark();
  void ExportIds();
  void ExportPly(bool deleteSelection);
  void ScreenshotDialog();
  bool RunSelfTest();

  struct Internals;
  std::unique_ptr<Internals> d;
};

#endif

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

#include <memory>
#include <string>

class QComboBox;
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

  /// Runs the scripted end-to-end check once the file is loaded (used by tests), saving
  /// screenshots of every view into @p directory; the application exits with 0 or 1.
  void SetSelfTest(const QString& directory);

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

protected:
  void dragEnterEvent(QDragEnterEvent* event) override;
  void dropEvent(QDropEvent* event) override;

private:
  void BuildUi();
  void OnProgress(double fraction, const QString& message);
  void OnLoaded(std::shared_ptr<Vis4GSDocument> document, const QString& error);
  void OnSelectionChanged();
  void OnIterationChanged(int iteration);
  void UpdateScene();
  void UpdateOverlay();
  void ExportIds();
  void ExportPly(bool deleteSelection);
  void ScreenshotDialog();
  bool RunSelfTest();

  struct Internals;
  std::unique_ptr<Internals> d;
};

#endif

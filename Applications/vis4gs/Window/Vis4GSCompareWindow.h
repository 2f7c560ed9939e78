// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSCompareWindow.h
 * @brief The comparison window of `vis4gs view A --compare=B` and the main window's "Compare
 * with..." (issue 20): the two states in linked scene views sharing one camera, their
 * per-Gaussian differences (Vis4GSComparison: born, died, moved, opacity or scale changed
 * beyond the thresholds of `vis4gs compare`) as a colour overlay with a legend whose entries
 * select their Gaussians in both views through one vtkGaussianSelectionHub, and the metric
 * curves of both runs in the timeline view.
 *
 * A thin Qt shell: the states and sets are Vis4GSComparison's; each state is drawn by a
 * vtkGaussianSceneView (the main window's view A) on the window's hub, so the selection modes,
 * markers, dimming and camera frustums are the scene view's.
 */
#ifndef Vis4GSCompareWindow_h
#define Vis4GSCompareWindow_h

#include <QMainWindow>

#include <memory>
#include <vector>

struct Vis4GSComparison;
class vtkGaussianSceneView;
class vtkGaussianSelectionHub;
class vtkGaussianTimelineView;

class Vis4GSCompareWindow : public QMainWindow
{
  Q_OBJECT

public:
  explicit Vis4GSCompareWindow(QWidget* parent = nullptr);
  ~Vis4GSCompareWindow() override;

  /**
   * Loads the states in a worker thread (Vis4GSComparison::Load: @p a at @p iterationA, -1 the
   * last; @p b a log, a scene, "@N" or "FILE@N") and shows them. Errors go to the status bar
   * (and, in a self-test, fail it).
   */
  void Open(const QString& a, int iterationA, const QString& b, const QString& cameras = {});

  /**
   * "Compare with..." of the main window: asks for state B (another snapshot of the log @p a,
   * given as "@N", or a file) and opens a comparison window of @p a at @p iteration against it.
   */
  static void AskAndOpen(QWidget* parent,
    const QString& a,
    int iteration,
    const std::vector<int>& snapshots,
    const QString& cameras);

  /// A comparison window of @p a at @p iteration against @p b (Open()), shown as a window of
  /// its own that deletes itself when closed (the clean-up panel's repaired log, AskAndOpen()).
  static Vis4GSCompareWindow* OpenWindow(QWidget* parent,
    const QString& a,
    int iteration,
    const QString& b,
    const QString& cameras = {});

  /// Thresholds used by the next comparison (move, opacity, scale; `vis4gs compare`'s).
  void SetThresholds(double move, double opacity, double scale);

  /// After loading, runs the scripted check, saves screenshots and the shown sets into
  /// @p directory and exits the application with 0 (passed) or 1.
  void SetSelfTest(const QString& directory);

  /// Selects the Gaussians of one set (Vis4GSComparison::Sets) in both views.
  void SelectSet(int set);

  /// Frames the selected Gaussians of both states in the shared camera; false: none.
  bool ZoomToSelection();

  vtkGaussianSelectionHub* GetHub();
  vtkGaussianTimelineView* GetTimelineView();
  /// The scene view of state @p side (0: A, 1: B); both draw through view A's camera.
  vtkGaussianSceneView* GetSceneView(int side);

private:
  void BuildUi();
  void OnLoaded(std::shared_ptr<Vis4GSComparison> comparison, const QString& error);
  void ShowFirstCamera();
  void Recompare();
  void UpdateOverlay();
  void OnSelectionChanged();
  bool RunSelfTest();

  struct Internals;
  std::unique_ptr<Internals> d;
};

#endif

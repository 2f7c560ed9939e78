// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSCleanupPanel.h
 * @brief The "Clean-up" panel of `vis4gs view` (issue 20): select Gaussians by a rule
 * (Core/Selection/SelectionRule.h, through vtkGaussianRuleSelectionFilter) combined with the
 * selection hub's current selection (replace, add, subtract, intersect), so that histogram
 * brushing and the scene's selection modes combine with it; save and load the rule (the text
 * files `vis4gs analyze --select=@FILE` reads) and re-apply it when the iteration changes;
 * measure deleting the selection against the training and test images in a worker thread,
 * shown per view (worst first) and per split, with the before / after / |difference| images of
 * a chosen view; delete the selection to a new PLY (the main window's export); fine-tune the
 * previewed deletion and show the repaired figures as a third state, writing the repaired
 * run's log, which the main window or the comparison window opens.
 *
 * The measurement, the preview images and the fine-tune run through the session
 * (vtkGaussianSession, given the scene and cameras as data, one per measurement and one per
 * fine-tune, as the application's scores do): its removal-effect ports (the tables and the
 * preview renders of the view picked) and its vtkGaussianFineTuneFilter, given the preview's
 * table as the source and deleted figures. The "before" of a scene is measured once, per
 * 16x16 tile, and handed from one measurement's removal filter to the next of the same scene
 * and cameras (vtkGaussianRemovalEffectFilter::SetBaseline): a preview renders again only the
 * tiles its selection changes. The application's score pass hands the
 * panel the "before" of every training view it rendered at full resolution
 * (SetScoreBaseline()), so that the first preview renders only the test views "before".
 */
#ifndef Vis4GSCleanupPanel_h
#define Vis4GSCleanupPanel_h

#include "vtkSmartPointer.h"

#include <QWidget>

#include <functional>
#include <memory>
#include <string>

class QResizeEvent;
class Vis4GSCompareWindow;
class QString;
class vtkGaussianSelectionHub;
class vtkGaussianSession;
class vtkPolyData;
class vtkTable;

namespace vis4gs
{
struct RemovalBaseline;
}

class Vis4GSCleanupPanel : public QWidget
{
public:
  Vis4GSCleanupPanel(vtkGaussianSelectionHub* hub, QWidget* parent = nullptr);
  ~Vis4GSCleanupPanel() override;

  /// How a rule's selection combines with the hub's (vtkGaussianRuleSelectionFilter's order).
  enum CombineModes
  {
    REPLACE = 0,
    ADD = 1,
    SUBTRACT = 2,
    INTERSECT = 3
  };

  /**
   * The scene shown (with its score arrays once they are computed) and the cameras whose Image
   * column names readable files (Vis4GSDocument::ScoreCameras(); null: no measurement). A new
   * scene (another iteration) re-applies the last rule when "re-apply" is on, as soon as the
   * scores it reads are there.
   */
  void SetScene(vtkPolyData* scene, vtkTable* cameras);

  /**
   * The "before" of @p scene in @p cameras per tile that the application's score pass kept
   * (Vis4GSDocument::ComputeScores()): a preview of this scene renders no view it holds
   * "before", and only the tiles its selection changes "after". Dropped when the panel's
   * scene changes (another snapshot); ignored when @p scene is not the panel's scene.
   */
  void SetScoreBaseline(vtkPolyData* scene,
    vtkTable* cameras,
    std::shared_ptr<const vis4gs::RemovalBaseline> baseline);

  /**
   * A scene file (not a training log) shown: its @p path, the @p cameras option it was opened
   * with (empty: found next to it) and the @p iteration it was trained to (`vis4gs view
   * --iteration`), which a fine-tune continues from as `vis4gs repair --iteration` does (its
   * learning-rate and SH-degree schedules; -1: 0). An empty @p path: a training log, whose
   * snapshot gives the iteration.
   */
  void SetSceneFile(const QString& path, const QString& cameras, int iteration);
  /// The iteration a fine-tune starts from: the snapshot's, or the scene file's.
  int GetSourceIteration() const;

  /// What "Delete selection to new PLY..." does (the main window's export).
  void SetDeleteAction(std::function<void()> action);

  /// Progress of the measurement: (fraction, message) while it runs, a negative fraction for
  /// a step of unknown length; @p done true once at the end.
  void SetProgress(std::function<void(double fraction, const QString& message, bool done)> p);

  /**
   * Applies @p rule combined by @p mode with the hub's selection. False, with the error shown
   * under the rule field (naming the token) and the selection unchanged, when the rule cannot
   * be parsed or evaluated.
   */
  bool ApplyRule(const QString& rule, int mode);
  /// The text shown under the rule field: the canonical form or the error.
  QString GetFeedback() const;
  bool HasError() const;

  /// Saves the last rule typed, in canonical form, to @p path (one line); false on error.
  bool SaveRule(const QString& path);
  /// Reads the first line of @p path into the rule field; false on error.
  bool LoadRule(const QString& path);

  /// Starts measuring the deletion of the hub's selection in a worker thread.
  void MeasureRemoval();
  /// Processes events until the measurement started last is done; false if it failed.
  bool WaitForMeasurement();
  /// Writes the table shown (totals, then views) in the columns of analyze's before-after.csv.
  bool WriteTable(const QString& path) const;
  /// Shows the before / after / |difference| images of table row @p row.
  void ShowDifference(int row);

  /**
   * Starts fine-tuning the previewed deletion (the table shown, of the current selection and
   * snapshot) for @p iterations with the built-in trainer (the session's
   * vtkGaussianFineTuneFilter, as `vis4gs repair`, given the preview's figures of the source
   * and deleted states), positions fixed unless @p freePositions, densification off unless @p
   * densify, in a worker thread with its progress in the progress bar and Cancel. The repaired
   * run's log (the deletion as prune events at the snapshot's iteration, then the fine-tune) is
   * written to @p logPath; the table gets the repaired figures of every view. False, with the
   * reason shown, when there is no current preview or a worker runs.
   */
  bool StartFineTune(const QString& logPath, int iterations, bool freePositions, bool densify);
  /// Asks the fine-tune running to stop after its current iteration (no log is written).
  void CancelFineTune();
  /// Processes events until the fine-tune started last is done; false if it failed or was
  /// cancelled.
  bool WaitForFineTune();
  /// Writes the figures of the last fine-tune in the columns of `vis4gs repair`'s repair.csv.
  bool WriteRepairTable(const QString& path) const;
  /**
   * "Compare with source": a comparison window of the source (the log's snapshot, or the scene
   * file) against the repaired log's last snapshot; null without a fine-tune.
   */
  Vis4GSCompareWindow* OpenComparison();
  /// What "Open the repaired log" does (the main window opens the file).
  void SetOpenAction(std::function<void(const QString& path)> action);

  /**
   * The panel's part of `vis4gs view --self-test` on a log or a scene file with cameras and
   * images: a bad rule leaves the selection alone, a rule combines with a brushed selection,
   * save/load, the measurement's table and images, a cancelled and a finished fine-tune and
   * the comparison window. Writes cleanup-selection.csv, cleanup-before-after.csv (compared
   * with `vis4gs analyze --select --report` by a test), the fine-tune's log, figures
   * (cleanup-repair.csv), deletion and cleaned scene, and screenshots into @p directory. On a
   * scene file the fine-tuned deletion is the rule's whole selection, 2 iterations (what
   * vis4gs-RepairScene's `vis4gs repair` runs), without the mechanics checks the log's run
   * makes (a 'before' rendered anew, a second preview, a cancelled fine-tune); on a log one
   * Gaussian fewer, 1 iteration.
   * @p check reports each assertion.
   */
  bool RunSelfTest(const QString& directory,
    const std::function<bool(bool, const std::string&)>& check);

protected:
  void resizeEvent(QResizeEvent* event) override;

private:
  void OnRuleEdited();
  void OnSelectionChanged();
  void OnMeasured();
  void OnFineTuned();
  void UpdateButtons();
  /// The log the cameras come from, else the scene file: what names a session's errors.
  QString SourceName() const;
  /// A session given @p gaussians (a shallow copy of its own) and the panel's cameras (one
  /// made here) as data, no scores: a measurement's or a fine-tune's own, run in a worker.
  vtkSmartPointer<vtkGaussianSession> GivenDataSession(vtkPolyData* gaussians) const;

  struct Internals;
  std::unique_ptr<Internals> d;
};

#endif

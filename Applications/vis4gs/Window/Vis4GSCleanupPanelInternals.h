// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSCleanupPanelInternals.h
 * @brief What the files of the clean-up panel share (Vis4GSCleanupPanel.h): its state, and the
 * columns of its before / after tables. The panel's parts are Vis4GSCleanupPanel.cxx (the
 * widgets, the rule and the selection), Vis4GSCleanupMeasurement.cxx (the before / after
 * measurement job through a session's removal ports, its table and difference images),
 * Vis4GSCleanupFineTune.cxx (the fine-tune job through a session's fine-tune filter and its
 * figures) and Vis4GSCleanupSelfTest.cxx (its part of `vis4gs view --self-test`).
 */
#ifndef Vis4GSCleanupPanelInternals_h
#define Vis4GSCleanupPanelInternals_h

#include "Vis4GSCleanupPanel.h"

#include "FineTune.h"
#include "RemovalEffect.h"

#include "vtkCallbackCommand.h"
#include "vtkGaussianSession.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkTable.h"

#include <QString>

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

class QCheckBox;
class QComboBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QScrollArea;
class QSpinBox;
class QSplitter;
class QTableWidget;
class QThread;

/// The columns of the panel's two tables (totals and views).
namespace Vis4GSCleanupTable
{
constexpr int NumberOfColumns = 15;
/// The first of the repaired columns (PSNR, SSIM, L1), shown after a fine-tune.
constexpr int RepairedColumn = 12;

/// A number cell (the value in Qt::UserRole, "-" for NaN).
void SetNumber(QTableWidget* table, int row, int column, double value);
/// One row: name, split, changed, then before / after / change of PSNR, SSIM, L1.
void FillRow(QTableWidget* table,
  int row,
  const QString& name,
  const QString& split,
  const QString& changed,
  const vis4gs::ViewMetrics& before,
  const vis4gs::ViewMetrics& after);
}

struct Vis4GSCleanupPanel::Internals
{
  // Held: the panel (a child widget) is destroyed after the main window's members.
  vtkSmartPointer<vtkGaussianSelectionHub> Hub;
  vtkNew<vtkCallbackCommand> HubCommand;
  unsigned long HubObserver = 0;
  vtkSmartPointer<vtkPolyData> Scene;
  vtkSmartPointer<vtkTable> Cameras;
  std::function<void()> Delete;
  // A scene file (SetSceneFile): empty for a log.
  QString SceneFile;
  QString SceneCameras;
  int SceneIteration = 0;
  std::function<void(double, const QString&, bool)> Progress;
  // Rule.
  QLineEdit* Rule = nullptr;
  QLabel* Feedback = nullptr;
  bool Error = false;
  QComboBox* Mode = nullptr;
  QCheckBox* Reapply = nullptr;
  QLabel* SelectionLabel = nullptr;
  QString AppliedRule; // canonical, for re-applying to another iteration
  int AppliedMode = REPLACE;
  bool ReapplyPending = false;
  // Measurement.
  QPushButton* Measure = nullptr;
  QLabel* MeasureLabel = nullptr;
  QTableWidget* Totals = nullptr;
  QTableWidget* Views = nullptr;
  QLabel* Images[3] = { nullptr, nullptr, nullptr };
  QLabel* ImageCaption = nullptr;
  QSplitter* Splitter = nullptr;
  QScrollArea* LeftScroll = nullptr;
  vtkIdType MeasuredChanges = -1; // the hub's change count of the selection measured
  QThread* Worker = nullptr;
  bool LastFailed = false;
  // The "before" of BaselineScene in BaselineCameras per tile (the score pass's, or the last
  // measurement's completed), given to the next measurement of that scene.
  vtkSmartPointer<vtkPolyData> BaselineScene;
  vtkSmartPointer<vtkTable> BaselineCameras;
  std::shared_ptr<const vis4gs::RemovalBaseline> Baseline;
  // A measurement (the table shown, the difference images, the fine-tune's deletion).
  struct Result
  {
    vtkSmartPointer<vtkPolyData> Scene; ///< the panel's scene measured
    vtkSmartPointer<vtkTable> CameraTable;
    /// The given-data session of this measurement (Gaussians: a shallow copy of Scene, which
    /// the GUI thread may add score arrays to), its removal ports updated; the preview port is
    /// updated in the GUI thread once the worker has ended.
    vtkSmartPointer<vtkGaussianSession> Session;
    vtkSmartPointer<vtkIdTypeArray> Removed; ///< the GaussianIds removed (selected and shown)
    std::vector<vis4gs::Camera> Cameras;     ///< the camera table's, for the views' names
    vis4gs::RemovalEffect Effect;            ///< the removal filter's tables (GetEffect)
    std::shared_ptr<const vis4gs::RemovalBaseline> Baseline; ///< the "before" measured with
    double BaselineSeconds = -1;                             ///< < 0: no view rendered "before"
    /// Views whose "before" this preview rendered, and those it reused (from the score pass or
    /// an earlier preview of the scene).
    std::size_t BeforeRendered = 0;
    std::size_t BeforeReused = 0;
    std::string Error;
  };
  std::shared_ptr<Result> Shown, Running;
  // Fine-tune (repair).
  QPushButton* FineTune = nullptr;
  QSpinBox* Iterations = nullptr;
  QCheckBox* FreePositions = nullptr;
  QCheckBox* Densify = nullptr;
  QPushButton* Cancel = nullptr;
  QPushButton* OpenRepaired = nullptr;
  QPushButton* CompareRepaired = nullptr;
  QLabel* RepairLabel = nullptr;
  std::function<void(const QString&)> Open;
  QThread* RepairWorker = nullptr;
  struct Repair
  {
    std::shared_ptr<Result> Preview; ///< the deletion fine-tuned and its before / after
    QString SourceLog;               ///< empty for a scene file
    QString SourceScene;             ///< the scene file fine-tuned (empty for a log)
    QString SourceCameras;           ///< its cameras option
    QString LogPath;
    int Iterations = 0;
    bool FreePositions = false;
    bool Densify = false;
    int SourceIteration = 0;
    /// The given-data session whose vtkGaussianFineTuneFilter runs the fine-tune.
    vtkSmartPointer<vtkGaussianSession> Session;
    /// After it: the filter's figures (repair.csv's rows), the repaired figures per camera
    /// (NaN without an image), the last iteration and the seconds.
    std::vector<vis4gs::FineTuneFigureRow> Rows;
    std::vector<vis4gs::ViewMetrics> RepairedFigures;
    int LastIteration = -1;
    double TrainSeconds = 0;
    double MeasureSeconds = 0;
    bool Cancelled = false;
    std::atomic<bool> Cancel{ false };
    std::string Error;
  };
  std::shared_ptr<Repair> Repairing, Repaired;
};

#endif

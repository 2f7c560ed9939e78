// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSCleanupPanelInternals.h
 * @brief What the files of the clean-up panel share (Vis4GSCleanupPanel.h): its state, and the
 * columns of its before / after tables. The panel's parts are Vis4GSCleanupPanel.cxx (the
 * widgets, the rule and the selection), Vis4GSCleanupMeasurement.cxx (the before / after
 * measurement job, its table and difference images), Vis4GSCleanupFineTune.cxx (the fine-tune
 * job and its figures) and Vis4GSCleanupSelfTest.cxx (its part of `vis4gs view --self-test`).
 */
#ifndef Vis4GSCleanupPanelInternals_h
#define Vis4GSCleanupPanelInternals_h

#include "Vis4GSCleanupPanel.h"

#include "FineTune.h"
#include "RemovalEffect.h"

#include "vtkCallbackCommand.h"
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
  // The "before" of BaselineScene in BaselineCameras per tile, reused (RemovalEffect.h): a
  // preview renders only the tiles its selection changes.
  vtkSmartPointer<vtkPolyData> BaselineScene;
  vtkSmartPointer<vtkTable> BaselineCameras;
  vis4gs::RemovalBaseline Baseline;
  // What the table shows (for the difference images).
  struct Result
  {
    vtkSmartPointer<vtkPolyData> Scene;
    vtkSmartPointer<vtkTable> CameraTable;
    std::shared_ptr<vis4gs::GaussianCloud> Cloud;
    std::vector<std::uint8_t> Removed;
    std::vector<vis4gs::Camera> Cameras;
    vis4gs::TrainingImageProvider Images;
    vis4gs::RemovalEffect Effect;
    vis4gs::RemovalBaseline Baseline;
    double BaselineSeconds = -1; ///< < 0: the baseline was reused
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
    vis4gs::FineTuneOptions Options;
    vis4gs::FineTuneResult Figures;
    std::vector<vis4gs::FineTuneFigureRow> Rows;
    std::atomic<bool> Cancel{ false };
    std::string Error;
  };
  std::shared_ptr<Repair> Repairing, Repaired;
};

#endif

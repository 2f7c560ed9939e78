// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSCleanupPanel.h"

#include "FineTune.h"
#include "RemovalEffect.h"
#include "SelectionRule.h"
#include "TrainingLogReader.h"
#include "Vis4GSCompareWindow.h"
#include "Vis4GSDataModel.h"
#include "Vis4GSSelectionExport.h"
#include "vtkGaussianRuleSelectionFilter.h"
#include "vtkGaussianSelectionHub.h"

#include "vtkCallbackCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkTable.h"

#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QImage>
#include <QLabel>
#include <QLineEdit>
#include <QPixmap>
#include <QPushButton>
#include <QResizeEvent>
#include <QScrollArea>
#include <QScrollBar>
#include <QSpinBox>
#include <QSplitter>
#include <QTableWidget>
#include <QTextStream>
#include <QThread>
#include <QVBoxLayout>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <set>
#include <vector>

namespace
{
const char* const Columns[] = { "View",
  "Split",
  "Changed",
  "PSNR\nbefore",
  "PSNR\nafter",
  "PSNR\nchange",
  "SSIM\nbefore",
  "SSIM\nafter",
  "SSIM\nchange",
  "L1\nbefore",
  "L1\nafter",
  "L1\nchange",
  "PSNR\nrepaired",
  "SSIM\nrepaired",
  "L1\nrepaired" };
constexpr int NumberOfColumns = 15;
/// The first of the repaired columns (PSNR, SSIM, L1), shown after a fine-tune.
constexpr int RepairedColumn = 12;

// A heat map of t in [0, 1]: black, red, yellow, white.
void Heat(double t, unsigned char* rgb)
{
  t = std::min(1.0, std::max(0.0, t)) * 3.0;
  const double r = std::min(1.0, t), g = std::min(1.0, std::max(0.0, t - 1.0)),
               b = std::max(0.0, t - 2.0);
  rgb[0] = static_cast<unsigned char>(255 * r + 0.5);
  rgb[1] = static_cast<unsigned char>(255 * g + 0.5);
  rgb[2] = static_cast<unsigned char>(255 * b + 0.5);
}

QImage ToQImage(const vis4gs::Image& image)
{
  QImage out(image.Width, image.Height, QImage::Format_RGB888);
  for (int y = 0; y < image.Height; ++y)
  {
    unsigned char* line = out.scanLine(y);
    for (int x = 0; x < image.Width; ++x)
    {
      for (int c = 0; c < 3; ++c)
      {
        const float v =
          image.Pixels[(static_cast<std::size_t>(y) * image.Width + x) * image.Channels +
            static_cast<std::size_t>(std::min(c, image.Channels - 1))];
        line[3 * x + c] = static_cast<unsigned char>(255.0f * v + 0.5f);
      }
    }
  }
  return out;
}

void SetNumber(QTableWidget* table, int row, int column, double value)
{
  auto* item =
    new QTableWidgetItem(std::isnan(value) ? QString("-") : QString::number(value, 'f', 4));
  item->setData(Qt::UserRole, value);
  item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
  table->setItem(row, column, item);
}

void SetText(QTableWidget* table, int row, int column, const QString& text)
{
  table->setItem(row, column, new QTableWidgetItem(text));
}

// One row: name, split, changed, then before / after / change of PSNR, SSIM, L1.
void FillRow(QTableWidget* table,
  int row,
  const QString& name,
  const QString& split,
  const QString& changed,
  const vis4gs::ViewMetrics& before,
  const vis4gs::ViewMetrics& after)
{
  SetText(table, row, 0, name);
  SetText(table, row, 1, split);
  SetText(table, row, 2, changed);
  const double b[3] = { before.Psnr, before.Ssim, before.L1 };
  const double a[3] = { after.Psnr, after.Ssim, after.L1 };
  for (int m = 0; m < 3; ++m)
  {
    SetNumber(table, row, 3 + 3 * m, b[m]);
    SetNumber(table, row, 4 + 3 * m, a[m]);
    SetNumber(table, row, 5 + 3 * m, a[m] - b[m]);
  }
}

// Renders the "before" of the wanted views with an image that @p baseline lacks (every view
// for an empty baseline: the score pass keeps only the training views it renders). Returns
// the number of views rendered.
std::size_t CompleteBaseline(vis4gs::RemovalBaseline& baseline,
  const vis4gs::GaussianCloud& cloud,
  const std::vector<vis4gs::Camera>& cameras,
  const vis4gs::RemovalEffectOptions& options,
  const vis4gs::TrainingImageProvider& images)
{
  if (baseline.Views.empty())
  {
    baseline = vis4gs::MeasureRemovalBaseline(cloud, cameras, options, images);
    return baseline.MeasuredViews();
  }
  std::vector<std::size_t> missing;
  std::vector<vis4gs::Camera> subset;
  for (std::size_t v = 0; v < cameras.size(); ++v)
  {
    if (baseline.Views[v].Empty())
    {
      missing.push_back(v);
      subset.push_back(cameras[v]);
    }
  }
  if (missing.empty())
  {
    return 0;
  }
  vis4gs::RemovalBaseline part = vis4gs::MeasureRemovalBaseline(cloud,
    subset,
    options,
    [&images, &missing](std::size_t i, const vis4gs::Camera& camera, vis4gs::Image& image)
    { return images(missing[i], camera, image); });
  std::size_t rendered = 0;
  for (std::size_t i = 0; i < missing.size(); ++i)
  {
    if (!part.Views[i].Empty())
    {
      baseline.Views[missing[i]] = std::move(part.Views[i]);
      ++rendered;
    }
  }
  return rendered;
}

QTableWidget* MakeTable(QWidget* parent)
{
  auto* table = new QTableWidget(parent);
  table->setColumnCount(NumberOfColumns);
  QStringList labels;
  for (const char* c : Columns)
  {
    labels << c;
  }
  table->setHorizontalHeaderLabels(labels);
  table->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table->setSelectionBehavior(QAbstractItemView::SelectRows);
  table->setSelectionMode(QAbstractItemView::SingleSelection);
  table->verticalHeader()->hide();
  table->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  for (int c = RepairedColumn; c < NumberOfColumns; ++c)
  {
    table->setColumnHidden(c, true);
  }
  return table;
}
} // namespace

struct Vis4GSCleanupPanel::Internals
{
  // Held: the panel (a child widget) is destroyed after the main window's members.
  vtkSmartPointer<vtkGaussianSelectionHub> Hub;
  vtkNew<vtkCallbackCommand> HubCommand;
  unsigned long HubObserver = 0;
  vtkSmartPointer<vtkPolyData> Scene;
  vtkSmartPointer<vtkTable> Cameras;
  std::function<void()> Delete;
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
    QString LogPath;
    vis4gs::FineTuneOptions Options;
    vis4gs::FineTuneResult Figures;
    std::vector<vis4gs::FineTuneFigureRow> Rows;
    std::atomic<bool> Cancel{ false };
    std::string Error;
  };
  std::shared_ptr<Repair> Repairing, Repaired;
};

//------------------------------------------------------------------------------
Vis4GSCleanupPanel::Vis4GSCleanupPanel(vtkGaussianSelectionHub* hub, QWidget* parent)
  : QWidget(parent)
  , d(new Internals)
{
  d->Hub = hub;
  // Two halves: the rule, the summary and the images; the tables. Side by side in a wide
  // dock (under the scene, tabbed with the timeline), stacked in a narrow one.
  auto* outer = new QVBoxLayout(this);
  outer->setContentsMargins(0, 0, 0, 0);
  d->Splitter = new QSplitter(Qt::Horizontal, this);
  outer->addWidget(d->Splitter);
  // The left half scrolls rather than squeezing its rows in a low dock (1280x800).
  d->LeftScroll = new QScrollArea(d->Splitter);
  d->LeftScroll->setWidgetResizable(true);
  d->LeftScroll->setFrameShape(QFrame::NoFrame);
  d->LeftScroll->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  auto* left = new QWidget(d->LeftScroll);
  d->LeftScroll->setWidget(left);
  auto* right = new QWidget(d->Splitter);
  d->Splitter->addWidget(d->LeftScroll);
  d->Splitter->addWidget(right);
  d->Splitter->setStretchFactor(0, 2);
  d->Splitter->setStretchFactor(1, 3);
  auto* layout = new QVBoxLayout(left);
  auto* tables = new QVBoxLayout(right);
  tables->setContentsMargins(0, 0, 0, 0);
  auto* form = new QFormLayout();
  layout->addLayout(form);
  d->Rule = new QLineEdit(this);
  d->Rule->setPlaceholderText("e.g. views<=3 and opacity>=0.5, blur top 5%, isolated r=0.1");
  d->Rule->setToolTip("A rule over the scores and attributes (user guide, 'Guided clean-up'): "
                      "coverage, views, blur, needle_score, needle, opacity, scale, volume; "
                      "<, <=, >, >=, ==, !=; top p%, bottom p%; isolated r=R; and, or, not");
  form->addRow("Rule", d->Rule);
  d->Feedback = new QLabel(this);
  d->Feedback->setWordWrap(true);
  d->Feedback->setTextInteractionFlags(Qt::TextSelectableByMouse);
  form->addRow("", d->Feedback);
  auto* row = new QWidget(this);
  auto* rowLayout = new QHBoxLayout(row);
  rowLayout->setContentsMargins(0, 0, 0, 0);
  d->Mode = new QComboBox(row);
  d->Mode->addItems({ "replace", "add to", "subtract from", "intersect with" });
  d->Mode->setToolTip("How the rule's Gaussians combine with the current selection (histogram "
                      "brushing, the scene's selection modes, the tree)");
  auto* apply = new QPushButton("Apply", row);
  auto* save = new QPushButton("Save rule...", row);
  auto* load = new QPushButton("Load rule...", row);
  rowLayout->addWidget(d->Mode);
  rowLayout->addWidget(new QLabel("the selection", row));
  rowLayout->addWidget(apply);
  rowLayout->addStretch(1);
  rowLayout->addWidget(save);
  rowLayout->addWidget(load);
  form->addRow("", row);
  d->Reapply = new QCheckBox("Re-apply the rule when the iteration changes", this);
  d->Reapply->setChecked(true);
  form->addRow("", d->Reapply);
  d->SelectionLabel = new QLabel("nothing selected", this);
  form->addRow("Selection", d->SelectionLabel);

  auto* measureRow = new QWidget(this);
  auto* measureLayout = new QHBoxLayout(measureRow);
  measureLayout->setContentsMargins(0, 0, 0, 0);
  d->Measure = new QPushButton("Measure removal", measureRow);
  d->Measure->setToolTip("Render every training and test view with and without the selection "
                         "and compare with the images: PSNR, SSIM, L1 before and after");
  auto* deletePly = new QPushButton("Delete selection to new PLY...", measureRow);
  measureLayout->addWidget(d->Measure);
  measureLayout->addWidget(deletePly);
  measureLayout->addStretch(1);
  layout->addWidget(measureRow);
  auto* repairRow = new QWidget(this);
  auto* repairLayout = new QHBoxLayout(repairRow);
  repairLayout->setContentsMargins(0, 0, 0, 0);
  d->FineTune = new QPushButton("Fine-tune...", repairRow);
  d->FineTune->setToolTip("Fine-tune the previewed deletion with the built-in trainer and "
                          "measure it again (a third state, 'repaired'); writes the repaired "
                          "run's log, the deletion as prune events (as vis4gs repair)");
  d->Iterations = new QSpinBox(repairRow);
  d->Iterations->setRange(1, 1000000);
  d->Iterations->setValue(50);
  d->Iterations->setSuffix(" iterations");
  d->FreePositions = new QCheckBox("positions free", repairRow);
  d->FreePositions->setToolTip("Optimise the positions too (default: fixed)");
  d->Densify = new QCheckBox("densify", repairRow);
  d->Densify->setToolTip("Keep the trainer's densification schedule (default: off, and no "
                         "opacity reset)");
  d->Cancel = new QPushButton("Cancel", repairRow);
  d->Cancel->setEnabled(false);
  repairLayout->addWidget(d->FineTune);
  repairLayout->addWidget(d->Iterations);
  repairLayout->addWidget(d->FreePositions);
  repairLayout->addWidget(d->Densify);
  repairLayout->addWidget(d->Cancel);
  repairLayout->addStretch(1);
  layout->addWidget(repairRow);
  auto* repairedRow = new QWidget(this);
  auto* repairedLayout = new QHBoxLayout(repairedRow);
  repairedLayout->setContentsMargins(0, 0, 0, 0);
  d->RepairLabel = new QLabel(repairedRow);
  d->RepairLabel->setWordWrap(true);
  d->RepairLabel->setTextInteractionFlags(Qt::TextSelectableByMouse);
  d->OpenRepaired = new QPushButton("Open", repairedRow);
  d->OpenRepaired->setToolTip("Open the repaired run's log in this window");
  d->CompareRepaired = new QPushButton("Compare with source", repairedRow);
  d->CompareRepaired->setToolTip("The source snapshot and the repaired run side by side");
  repairedLayout->addWidget(d->RepairLabel, 1);
  repairedLayout->addWidget(d->OpenRepaired);
  repairedLayout->addWidget(d->CompareRepaired);
  d->OpenRepaired->hide();
  d->CompareRepaired->hide();
  layout->addWidget(repairedRow);
  d->MeasureLabel = new QLabel(this);
  d->MeasureLabel->setWordWrap(true);
  layout->addWidget(d->MeasureLabel);
  d->Totals = MakeTable(this);
  d->Totals->setRowCount(2);
  const int totalsHeight = d->Totals->horizontalHeader()->sizeHint().height() +
    2 * d->Totals->verticalHeader()->defaultSectionSize() +
    d->Totals->horizontalScrollBar()->sizeHint().height() + 4;
  d->Totals->setFixedHeight(totalsHeight);
  tables->addWidget(d->Totals);
  d->Views = MakeTable(this);
  d->Views->setMinimumHeight(160);
  tables->addWidget(d->Views, 1);
  auto* images = new QWidget(this);
  auto* imagesLayout = new QHBoxLayout(images);
  imagesLayout->setContentsMargins(0, 0, 0, 0);
  for (QLabel*& label : d->Images)
  {
    label = new QLabel(images);
    label->setMinimumSize(120, 90);
    label->setMaximumHeight(130);
    label->setAlignment(Qt::AlignCenter);
    imagesLayout->addWidget(label, 1);
  }
  layout->addWidget(images);
  d->ImageCaption = new QLabel("Pick a view: its render before, after, and |after - before|", this);
  d->ImageCaption->setWordWrap(true);
  layout->addWidget(d->ImageCaption);
  layout->addStretch(1);

  connect(d->Rule, &QLineEdit::textChanged, this, [this](const QString&) { this->OnRuleEdited(); });
  connect(d->Rule,
    &QLineEdit::returnPressed,
    this,
    [this] { this->ApplyRule(d->Rule->text(), d->Mode->currentIndex()); });
  connect(apply,
    &QPushButton::clicked,
    this,
    [this] { this->ApplyRule(d->Rule->text(), d->Mode->currentIndex()); });
  connect(save,
    &QPushButton::clicked,
    this,
    [this]
    {
      const QString path = QFileDialog::getSaveFileName(
        this, "Save the rule", "selection-rule.txt", "Rules (*.txt);;All files (*)");
      if (!path.isEmpty())
      {
        this->SaveRule(path);
      }
    });
  connect(load,
    &QPushButton::clicked,
    this,
    [this]
    {
      const QString path = QFileDialog::getOpenFileName(
        this, "Load a rule", QString(), "Rules (*.txt);;All files (*)");
      if (!path.isEmpty())
      {
        this->LoadRule(path);
      }
    });
  connect(d->Measure, &QPushButton::clicked, this, [this] { this->MeasureRemoval(); });
  connect(d->FineTune,
    &QPushButton::clicked,
    this,
    [this]
    {
      // The default: next to the source log, named after it and the snapshot.
      QString folder = QDir::currentPath(), stem = "scene";
      if (d->Shown && d->Cameras)
      {
        if (auto* logFile = vtkStringArray::SafeDownCast(
              d->Cameras->GetFieldData()->GetAbstractArray(vis4gs::arrays::CameraTrainingLogFile)))
        {
          if (logFile->GetNumberOfValues() == 1)
          {
            const QFileInfo source(QString::fromStdString(logFile->GetValue(0)));
            folder = source.absolutePath();
            stem = source.completeBaseName();
          }
        }
      }
      const QString path = QFileDialog::getSaveFileName(this,
        "Write the repaired run's log",
        QDir(folder).filePath(
          QString("%1-repaired-%2.h5").arg(stem).arg(std::max(0, d->Hub->GetIteration()))),
        "Training logs (*.h5)");
      if (!path.isEmpty())
      {
        this->StartFineTune(
          path, d->Iterations->value(), d->FreePositions->isChecked(), d->Densify->isChecked());
      }
    });
  connect(d->Cancel, &QPushButton::clicked, this, [this] { this->CancelFineTune(); });
  connect(d->OpenRepaired,
    &QPushButton::clicked,
    this,
    [this]
    {
      if (d->Open && d->Repaired)
      {
        d->Open(d->Repaired->LogPath);
      }
    });
  connect(d->CompareRepaired,
    &QPushButton::clicked,
    this,
    [this]
    {
      if (d->Repaired && !d->Repaired->SourceLog.isEmpty())
      {
        Vis4GSCompareWindow::OpenWindow(
          this, d->Repaired->SourceLog, d->Repaired->Figures.SourceIteration, d->Repaired->LogPath);
      }
    });
  connect(deletePly,
    &QPushButton::clicked,
    this,
    [this]
    {
      if (d->Delete)
      {
        d->Delete();
      }
    });
  connect(d->Views,
    &QTableWidget::currentCellChanged,
    this,
    [this](int r, int, int, int) { this->ShowDifference(r); });

  // As wide as its rows need (the splitter would give the scroll area less): it scrolls
  // vertically only.
  d->LeftScroll->setMinimumWidth(
    left->minimumSizeHint().width() + d->LeftScroll->verticalScrollBar()->sizeHint().width());

  d->HubCommand->SetClientData(this);
  d->HubCommand->SetCallback([](vtkObject*, unsigned long, void* client, void*)
    { static_cast<Vis4GSCleanupPanel*>(client)->OnSelectionChanged(); });
  d->HubObserver = d->Hub->AddObserver(vtkCommand::SelectionChangedEvent, d->HubCommand);
  this->OnRuleEdited();
}

//------------------------------------------------------------------------------
Vis4GSCleanupPanel::~Vis4GSCleanupPanel()
{
  d->Hub->RemoveObserver(d->HubObserver);
  if (d->Worker)
  {
    d->Worker->wait();
  }
  if (d->RepairWorker)
  {
    d->Repairing->Cancel = true;
    d->RepairWorker->wait();
  }
}

//------------------------------------------------------------------------------
void Vis4GSCleanupPanel::resizeEvent(QResizeEvent* event)
{
  d->Splitter->setOrientation(
    event->size().width() > 3 * event->size().height() / 2 ? Qt::Horizontal : Qt::Vertical);
  this->QWidget::resizeEvent(event);
}

//------------------------------------------------------------------------------
void Vis4GSCleanupPanel::SetScoreBaseline(vtkPolyData* scene,
  vtkTable* cameras,
  const vis4gs::RemovalBaseline& baseline)
{
  // An earlier preview of the same scene may have measured more views (the test views).
  if (!scene || scene != d->Scene.GetPointer() || cameras != d->Cameras.GetPointer() ||
    baseline.MeasuredViews() == 0 ||
    (d->BaselineScene == d->Scene && d->BaselineCameras == d->Cameras &&
      d->Baseline.MeasuredViews() >= baseline.MeasuredViews()))
  {
    return;
  }
  d->BaselineScene = scene;
  d->BaselineCameras = cameras;
  d->Baseline = baseline;
}

//------------------------------------------------------------------------------
void Vis4GSCleanupPanel::SetDeleteAction(std::function<void()> action)
{
  d->Delete = std::move(action);
}

//------------------------------------------------------------------------------
void Vis4GSCleanupPanel::SetProgress(std::function<void(double, const QString&, bool)> p)
{
  d->Progress = std::move(p);
}

//------------------------------------------------------------------------------
void Vis4GSCleanupPanel::SetScene(vtkPolyData* scene, vtkTable* cameras)
{
  const bool newScene = scene != d->Scene.GetPointer();
  d->Scene = scene;
  d->Cameras = cameras;
  if (scene != d->BaselineScene.GetPointer() || cameras != d->BaselineCameras.GetPointer())
  {
    // Another snapshot: its "before" is another one (and the old scene is released).
    d->BaselineScene = nullptr;
    d->BaselineCameras = nullptr;
    d->Baseline = vis4gs::RemovalBaseline();
  }
  d->Measure->setEnabled(scene && cameras && cameras->GetNumberOfRows() > 0);
  d->Measure->setToolTip(d->Measure->isEnabled()
      ? "Render every training and test view with and without the selection and compare "
        "with the images: PSNR, SSIM, L1 before and after"
      : "needs cameras with training images");
  if (newScene && d->Shown)
  {
    d->MeasureLabel->setText("The table is of another snapshot: measure again.");
  }
  if (newScene && !d->AppliedRule.isEmpty() && d->Reapply->isChecked())
  {
    d->ReapplyPending = true;
  }
  if (!d->ReapplyPending || !scene)
  {
    return;
  }
  // Re-apply once the scores the rule reads are there (they are computed after the scene).
  const vis4gs::SelectionRule rule = vis4gs::SelectionRule::Parse(d->AppliedRule.toStdString());
  const std::pair<vis4gs::RuleAttribute, const char*> scores[] = {
    { vis4gs::RuleAttribute::Coverage, vis4gs::arrays::ViewCoverage },
    { vis4gs::RuleAttribute::Views, vis4gs::arrays::ViewCoverage },
    { vis4gs::RuleAttribute::Blur, vis4gs::arrays::BlurScore },
    { vis4gs::RuleAttribute::NeedleScore, vis4gs::arrays::NeedleScore }
  };
  for (const auto& [attribute, array] : scores)
  {
    if (rule.Reads(attribute) && !scene->GetPointData()->GetArray(array))
    {
      return;
    }
  }
  d->ReapplyPending = false;
  d->Rule->setText(d->AppliedRule);
  this->ApplyRule(d->AppliedRule, d->AppliedMode);
}

//------------------------------------------------------------------------------
void Vis4GSCleanupPanel::OnRuleEdited()
{
  const std::string text = d->Rule->text().toStdString();
  d->Error = false;
  if (text.find_first_not_of(" \t") == std::string::npos)
  {
    d->Feedback->setText("<i>type a rule</i>");
    return;
  }
  try
  {
    d->Feedback->setText("canonical: <code>" +
      QString::fromStdString(vis4gs::SelectionRule::Parse(text).ToString()).toHtmlEscaped() +
      "</code>");
  }
  catch (const vis4gs::SelectionRuleError& e)
  {
    d->Error = true;
    d->Feedback->setText("<span style='color:#c00000'>" +
      QString::fromStdString(e.what()).toHtmlEscaped() + "</span>");
  }
}

//------------------------------------------------------------------------------
QString Vis4GSCleanupPanel::GetFeedback() const
{
  return d->Feedback->text();
}

//------------------------------------------------------------------------------
bool Vis4GSCleanupPanel::HasError() const
{
  return d->Error;
}

//------------------------------------------------------------------------------
bool Vis4GSCleanupPanel::ApplyRule(const QString& text, int mode)
{
  if (d->Rule->text() != text)
  {
    d->Rule->setText(text);
  }
  auto fail = [this](const QString& message, std::size_t column, std::size_t length)
  {
    d->Error = true;
    d->Feedback->setText("<span style='color:#c00000'>" + message.toHtmlEscaped() + "</span>");
    if (column > 0)
    {
      d->Rule->setSelection(static_cast<int>(column) - 1, static_cast<int>(length));
    }
    return false;
  };
  std::string canonical;
  try
  {
    canonical = vis4gs::SelectionRule::Parse(text.toStdString()).ToString();
  }
  catch (const vis4gs::SelectionRuleError& e)
  {
    return fail(QString::fromStdString(e.what()), e.Column, e.Token.size());
  }
  if (!d->Scene)
  {
    return fail("no scene to select in", 0, 0);
  }
  // |V| for "views": the training cameras, as the score filter uses them all.
  int trainViews = 0;
  std::vector<vis4gs::Camera> cameras;
  if (d->Cameras && vis4gs::TableToCameras(d->Cameras, cameras, nullptr))
  {
    trainViews = static_cast<int>(std::count_if(cameras.begin(),
      cameras.end(),
      [](const vis4gs::Camera& c) { return c.Split == vis4gs::CameraSplit::Train; }));
  }
  vtkNew<vtkIdTypeArray> current;
  d->Hub->GetSelectedIds(current);
  vtkNew<vtkGaussianRuleSelectionFilter> filter;
  filter->SetInputData(d->Scene);
  filter->SetRule(canonical.c_str());
  filter->SetNumberOfViews(trainViews);
  filter->SetCurrentIds(current);
  filter->SetCombineMode(std::min(std::max(mode, 0), 3));
  filter->Update();
  if (*filter->GetLastRuleError())
  {
    // Evaluation errors (a score not computed yet, "views" without cameras).
    return fail(QString(filter->GetLastRuleError()), 0, 0);
  }
  d->AppliedRule = QString::fromStdString(canonical);
  d->AppliedMode = mode;
  d->ReapplyPending = false;
  d->Hub->SelectIds(filter->GetSelectedIds(), vtkGaussianSelectionHub::REPLACE);
  d->Error = false;
  d->Feedback->setText("canonical: <code>" + d->AppliedRule.toHtmlEscaped() + "</code> (" +
    QString::number(filter->GetSelectedIds()->GetNumberOfTuples()) + " selected)");
  return true;
}

//------------------------------------------------------------------------------
bool Vis4GSCleanupPanel::SaveRule(const QString& path)
{
  try
  {
    const std::string canonical =
      vis4gs::SelectionRule::Parse(d->Rule->text().toStdString()).ToString();
    // A temporary file renamed over the target: a failed write leaves no half rule.
    const std::string tmp = path.toStdString() + ".tmp";
    {
      std::ofstream out(tmp);
      out << canonical << "\n";
      if (!out)
      {
        throw std::runtime_error(path.toStdString() + ": could not be written");
      }
    }
    QFile::remove(path);
    if (!QFile::rename(QString::fromStdString(tmp), path))
    {
      throw std::runtime_error(path.toStdString() + ": could not be written");
    }
    d->MeasureLabel->setText("rule saved to " + path);
    return true;
  }
  catch (const std::exception& e)
  {
    d->MeasureLabel->setText(QString::fromStdString(e.what()));
    return false;
  }
}

//------------------------------------------------------------------------------
bool Vis4GSCleanupPanel::LoadRule(const QString& path)
{
  QFile file(path);
  if (!file.open(QIODevice::ReadOnly | QIODevice::Text))
  {
    d->MeasureLabel->setText(path + ": cannot be read");
    return false;
  }
  QTextStream in(&file);
  d->Rule->setText(in.readLine());
  return !d->Error;
}

//------------------------------------------------------------------------------
void Vis4GSCleanupPanel::OnSelectionChanged()
{
  const vtkIdType n = d->Hub->GetNumberOfSelectedIds();
  QString text = n == 0 ? QString("nothing selected") : QString("%1 Gaussians selected").arg(n);
  if (d->Shown && d->Hub->GetNumberOfChanges() != d->MeasuredChanges)
  {
    text += " (the table is of an earlier selection)";
  }
  d->SelectionLabel->setText(text);
  this->UpdateButtons();
}

//------------------------------------------------------------------------------
void Vis4GSCleanupPanel::MeasureRemoval()
{
  if (d->Worker || d->RepairWorker || !d->Scene || !d->Cameras)
  {
    return;
  }
  auto job = std::make_shared<Internals::Result>();
  job->Scene = d->Scene;
  job->CameraTable = d->Cameras;
  // A shallow copy: the GUI thread may add score arrays to the scene while the worker reads.
  vtkNew<vtkPolyData> copy;
  copy->ShallowCopy(d->Scene);
  job->Cloud = std::make_shared<vis4gs::GaussianCloud>();
  std::string error;
  if (!vis4gs::PolyDataToGaussianCloud(copy, *job->Cloud, &error) ||
    !vis4gs::TableToCameras(d->Cameras, job->Cameras, &error))
  {
    d->MeasureLabel->setText(QString::fromStdString(error));
    return;
  }
  // The training images as the score filter reads them: "/images/<name>" from the log that
  // the camera table names (vtkGaussianTrainingLogReader's cameras port), others from files.
  std::shared_ptr<const vis4gs::TrainingLogReader> log;
  if (auto* logFile = vtkStringArray::SafeDownCast(
        d->Cameras->GetFieldData()->GetAbstractArray(vis4gs::arrays::CameraTrainingLogFile)))
  {
    try
    {
      if (logFile->GetNumberOfValues() == 1)
      {
        log = std::make_shared<const vis4gs::TrainingLogReader>(logFile->GetValue(0));
      }
    }
    catch (const std::exception& e)
    {
      d->MeasureLabel->setText(QString::fromStdString(e.what()));
      return;
    }
  }
  job->Images = [log](std::size_t, const vis4gs::Camera& camera, vis4gs::Image& image)
  { return vis4gs::LoadCameraImage(log.get(), camera, image); };
  job->Removed.assign(job->Cloud->Count, 0);
  std::size_t removed = 0;
  for (std::size_t i = 0; i < job->Cloud->Count; ++i)
  {
    if (d->Hub->IsSelected(static_cast<vtkIdType>(job->Cloud->GetId(i))))
    {
      job->Removed[i] = 1;
      ++removed;
    }
  }
  if (removed == 0)
  {
    d->MeasureLabel->setText("Select Gaussians first (a rule, a brush, the histogram).");
    return;
  }
  if (d->BaselineScene == d->Scene && d->BaselineCameras == d->Cameras &&
    d->Baseline.Views.size() == job->Cameras.size())
  {
    job->Baseline = d->Baseline;
    job->BeforeReused = d->Baseline.MeasuredViews();
  }
  d->Running = job;
  d->MeasuredChanges = d->Hub->GetNumberOfChanges();
  d->LastFailed = false;
  d->Measure->setEnabled(false);
  d->FineTune->setEnabled(false);
  const QString what = QString("measuring the removal of %1 Gaussians").arg(removed);
  d->MeasureLabel->setText(what + "...");
  if (d->Progress)
  {
    d->Progress(-1,
      what +
        (job->BeforeReused == 0 ? ": rendering every view before"
                                : ": rendering the views before that the score pass did not"),
      false);
  }
  // RemovalEffect has no progress callback: the bar is a busy indicator with the step named.
  d->Worker = QThread::create(
    [this, job, what]
    {
      try
      {
        vis4gs::RemovalEffectOptions options;
        const auto t0 = std::chrono::steady_clock::now();
        job->BeforeRendered =
          CompleteBaseline(job->Baseline, *job->Cloud, job->Cameras, options, job->Images);
        if (job->BeforeRendered > 0)
        {
          job->BaselineSeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          QMetaObject::invokeMethod(
            this,
            [this, what]
            {
              if (d->Progress)
              {
                d->Progress(-1, what + ": rendering the views it touches after", false);
              }
            },
            Qt::QueuedConnection);
        }
        options.TileBaseline = job->Baseline;
        job->Effect = vis4gs::MeasureRemovalEffect(
          *job->Cloud, job->Removed, job->Cameras, options, job->Images);
      }
      catch (const std::exception& e)
      {
        job->Error = e.what();
      }
      QMetaObject::invokeMethod(
        this, [this] { this->OnMeasured(); }, Qt::QueuedConnection);
    });
  d->Worker->start();
}

//------------------------------------------------------------------------------
void Vis4GSCleanupPanel::OnMeasured()
{
  d->Worker->wait();
  d->Worker->deleteLater();
  d->Worker = nullptr;
  std::shared_ptr<Internals::Result> job = std::move(d->Running);
  d->Measure->setEnabled(d->Scene && d->Cameras);
  this->UpdateButtons();
  if (!job->Error.empty())
  {
    d->LastFailed = true;
    d->MeasureLabel->setText("measurement failed: " + QString::fromStdString(job->Error));
    if (d->Progress)
    {
      d->Progress(1, d->MeasureLabel->text(), true);
    }
    return;
  }
  d->BaselineScene = job->Scene;
  d->BaselineCameras = job->CameraTable;
  d->Baseline = job->Baseline;
  d->Shown = job;
  const vis4gs::RemovalEffect& e = job->Effect;
  const QString summary = QString(
    "Deleting %1 Gaussians (%2 kept): training PSNR %3 -> %4 dB (%5 of %6 views "
    "changed), test PSNR %7 -> %8 dB (%9 of %10). Before: %11 views reused (the score pass, "
    "earlier previews), %12; after: %13 views rendered in %14 s.")
                            .arg(e.Removed)
                            .arg(e.Kept)
                            .arg(e.Train.Before.Psnr, 0, 'f', 3)
                            .arg(e.Train.After.Psnr, 0, 'f', 3)
                            .arg(e.Train.AffectedViews)
                            .arg(e.Train.Views)
                            .arg(e.Test.Before.Psnr, 0, 'f', 3)
                            .arg(e.Test.After.Psnr, 0, 'f', 3)
                            .arg(e.Test.AffectedViews)
                            .arg(e.Test.Views)
                            .arg(job->BeforeReused)
                            .arg(QString("%1 rendered in %2 s")
                                   .arg(job->BeforeRendered)
                                   .arg(std::max(0.0, job->BaselineSeconds), 0, 'f', 2))
                            .arg(e.ViewsRendered)
                            .arg(e.SecondsAfter, 0, 'f', 2);
  d->MeasureLabel->setText(summary);
  FillRow(d->Totals,
    0,
    "mean",
    "train",
    QString("%1 of %2").arg(e.Train.AffectedViews).arg(e.Train.Views),
    e.Train.Before,
    e.Train.After);
  FillRow(d->Totals,
    1,
    "mean",
    "test",
    QString("%1 of %2").arg(e.Test.AffectedViews).arg(e.Test.Views),
    e.Test.Before,
    e.Test.After);
  d->Views->blockSignals(true);
  d->Views->clearContents();
  for (QTableWidget* table : { d->Totals, d->Views })
  {
    for (int c = RepairedColumn; c < NumberOfColumns; ++c)
    {
      table->setColumnHidden(c, true); // a fine-tune of this preview shows them
    }
  }
  d->Views->setRowCount(static_cast<int>(e.Views.size()));
  for (std::size_t r = 0; r < e.Views.size(); ++r)
  {
    const vis4gs::RemovalViewEffect& v = e.Views[r];
    FillRow(d->Views,
      static_cast<int>(r),
      QString::fromStdString(v.Name),
      v.Split == vis4gs::CameraSplit::Train ? "train" : "test",
      v.Affected ? "yes" : "no",
      v.Before,
      v.After);
    d->Views->item(static_cast<int>(r), 0)
      ->setData(Qt::UserRole, static_cast<qulonglong>(v.CameraIndex));
    if (v.HasImage && v.PsnrChange() < 0)
    {
      d->Views->item(static_cast<int>(r), 5)->setForeground(QColor(192, 0, 0));
    }
  }
  d->Views->blockSignals(false);
  this->OnSelectionChanged();
  if (d->Progress)
  {
    d->Progress(1, summary, true);
  }
}

//------------------------------------------------------------------------------
bool Vis4GSCleanupPanel::WaitForMeasurement()
{
  while (d->Worker)
  {
    QApplication::processEvents(QEventLoop::AllEvents, 50);
    QThread::msleep(5);
  }
  return !d->LastFailed && d->Shown;
}

//------------------------------------------------------------------------------
bool Vis4GSCleanupPanel::WriteTable(const QString& path) const
{
  std::ofstream csv(path.toStdString());
  csv << "view,split,affected,psnr_before,psnr_after,ssim_before,ssim_after,l1_before,l1_after\n"
      << std::setprecision(17);
  for (QTableWidget* table : { d->Totals, d->Views })
  {
    for (int r = 0; r < table->rowCount(); ++r)
    {
      if (!table->item(r, 0))
      {
        continue;
      }
      const QString changed = table->item(r, 2)->text();
      csv << table->item(r, 0)->text().toStdString() << ","
          << table->item(r, 1)->text().toStdString() << ","
          << (table == d->Totals ? changed.section(' ', 0, 0).toStdString()
                                 : std::string(changed == "yes" ? "1" : "0"));
      for (int c : { 3, 4, 6, 7, 9, 10 })
      {
        csv << "," << table->item(r, c)->data(Qt::UserRole).toDouble();
      }
      csv << "\n";
    }
  }
  return static_cast<bool>(csv);
}

//------------------------------------------------------------------------------
void Vis4GSCleanupPanel::ShowDifference(int row)
{
  const std::shared_ptr<Internals::Result> shown = d->Shown;
  QTableWidgetItem* item = row >= 0 ? d->Views->item(row, 0) : nullptr;
  if (!shown || !item)
  {
    return;
  }
  const std::size_t index = item->data(Qt::UserRole).toULongLong();
  if (index >= shown->Cameras.size())
  {
    return;
  }
  QApplication::setOverrideCursor(Qt::WaitCursor);
  const vis4gs::Camera& camera = shown->Cameras[index];
  vis4gs::RemovalEffectOptions options; // the measurement's rasteriser settings
  const vis4gs::Image before =
    vis4gs::ClampedImage(vis4gs::Rasterize<float>(*shown->Cloud, camera, options.Raster));
  const vis4gs::Image after = vis4gs::ClampedImage(vis4gs::Rasterize<float>(
    vis4gs::RemoveGaussians(*shown->Cloud, shown->Removed), camera, options.Raster));
  vis4gs::Image diff = after;
  const std::size_t pixels = static_cast<std::size_t>(after.Width) * after.Height;
  std::vector<double> change(pixels, 0.0);
  double largest = 0;
  for (std::size_t p = 0; p < pixels; ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      const std::size_t i = 3 * p + static_cast<std::size_t>(c);
      change[p] += std::abs(static_cast<double>(after.Pixels[i]) - before.Pixels[i]) / 3.0;
    }
    largest = std::max(largest, change[p]);
  }
  for (std::size_t p = 0; p < pixels; ++p)
  {
    unsigned char rgb[3];
    // A square-root scale: small changes around a large one stay visible.
    Heat(largest > 0 ? std::sqrt(change[p] / largest) : 0.0, rgb);
    for (int c = 0; c < 3; ++c)
    {
      diff.Pixels[3 * p + static_cast<std::size_t>(c)] = rgb[c] / 255.0f;
    }
  }
  const vis4gs::Image* shownImages[3] = { &before, &after, &diff };
  for (int k = 0; k < 3; ++k)
  {
    const QImage image = ToQImage(*shownImages[k]);
    d->Images[k]->setPixmap(QPixmap::fromImage(image).scaled(d->Images[k]->width(),
      d->Images[k]->height(),
      Qt::KeepAspectRatio,
      Qt::SmoothTransformation));
    d->Images[k]->setProperty("largestChange", largest);
  }
  d->ImageCaption->setText(QString("%1: before, after, |after - before| (mean over RGB, "
                                   "square-root scale; white = %2, the largest change)")
                             .arg(QString::fromStdString(camera.Name))
                             .arg(largest, 0, 'g', 3));
  QApplication::restoreOverrideCursor();
}

//------------------------------------------------------------------------------
void Vis4GSCleanupPanel::SetOpenAction(std::function<void(const QString&)> action)
{
  d->Open = std::move(action);
}

//------------------------------------------------------------------------------
void Vis4GSCleanupPanel::UpdateButtons()
{
  const bool busy = d->Worker || d->RepairWorker;
  const bool current =
    d->Shown && d->Shown->Scene == d->Scene && d->MeasuredChanges == d->Hub->GetNumberOfChanges();
  d->FineTune->setEnabled(!busy && current);
  d->Cancel->setEnabled(d->RepairWorker != nullptr);
  if (d->RepairWorker)
  {
    d->Measure->setEnabled(false);
  }
  if (!current && !d->RepairWorker && d->RepairLabel->text().isEmpty())
  {
    d->RepairLabel->setText("Fine-tune: measure the removal of the selection first (it starts "
                            "from the preview).");
  }
}

//------------------------------------------------------------------------------
bool Vis4GSCleanupPanel::StartFineTune(const QString& logPath,
  int iterations,
  bool freePositions,
  bool densify)
{
  auto refuse = [this](const QString& why)
  {
    d->RepairLabel->setText(why);
    return false;
  };
  if (d->Worker || d->RepairWorker)
  {
    return refuse("A measurement or a fine-tune is running.");
  }
  if (!d->Shown || d->Shown->Scene != d->Scene ||
    d->MeasuredChanges != d->Hub->GetNumberOfChanges())
  {
    return refuse("Measure the removal of the selection first: the fine-tune starts from its "
                  "preview (the table is of another selection or snapshot).");
  }
  auto job = std::make_shared<Internals::Repair>();
  job->Preview = d->Shown;
  job->LogPath = logPath;
  vis4gs::FineTuneOptions& options = job->Options;
  options.Iterations = iterations;
  options.FreePositions = freePositions;
  options.Densify = densify;
  options.LogPath = logPath.toStdString();
  options.Producer = std::string("vis4gs view ") + VIS4GS_VERSION;
  // The source and deleted figures are the preview's (the same per-tile sums as vis4gs
  // repair's): only the repaired scene is measured.
  options.Measure = false;
  if (auto* logFile = vtkStringArray::SafeDownCast(
        d->Cameras->GetFieldData()->GetAbstractArray(vis4gs::arrays::CameraTrainingLogFile)))
  {
    if (logFile->GetNumberOfValues() == 1)
    {
      job->SourceLog = QString::fromStdString(logFile->GetValue(0));
      try
      {
        const vis4gs::TrainingLogReader log(logFile->GetValue(0));
        options.Scene = log.GetHeader().Scene;
        options.EmbedImages = log.HasImages(); // as vis4gs repair
      }
      catch (const std::exception& e)
      {
        return refuse(QString::fromStdString(e.what()));
      }
    }
  }
  Internals::Repair* raw = job.get(); // (the job owns its options: no cycle)
  options.Progress = [this, raw](int done, int total)
  {
    QMetaObject::invokeMethod(
      this,
      [this, done, total]
      {
        if (d->Progress && d->RepairWorker)
        {
          d->Progress(static_cast<double>(done) / total,
            QString("fine-tuning the cleaned scene: iteration %1 of %2").arg(done).arg(total),
            false);
        }
      },
      Qt::QueuedConnection);
    return !raw->Cancel;
  };
  const int source = std::max(0, d->Hub->GetIteration());
  d->Repairing = job;
  d->RepairLabel->setText(QString("fine-tuning the deletion of %1 Gaussians for %2 iterations...")
                            .arg(d->Shown->Effect.Removed)
                            .arg(iterations));
  if (d->Progress)
  {
    d->Progress(0, d->RepairLabel->text(), false);
  }
  d->RepairWorker = QThread::create(
    [this, job, source]
    {
      try
      {
        const Internals::Result& preview = *job->Preview;
        job->Figures = vis4gs::FineTune(
          *preview.Cloud, source, preview.Removed, preview.Cameras, preview.Images, job->Options);
        if (!job->Figures.Cancelled)
        {
          QMetaObject::invokeMethod(
            this,
            [this]
            {
              if (d->Progress)
              {
                d->Progress(-1, "measuring the repaired scene in every view", false);
              }
            },
            Qt::QueuedConnection);
          const std::size_t n = preview.Cameras.size();
          job->Figures.Source.assign(n, vis4gs::ViewMetrics{});
          job->Figures.Deleted.assign(n, vis4gs::ViewMetrics{});
          for (std::size_t v = 0; v < preview.Baseline.Views.size() && v < n; ++v)
          {
            if (!preview.Baseline.Views[v].Empty())
            {
              job->Figures.Source[v] = preview.Baseline.Views[v].Metrics();
            }
          }
          for (const vis4gs::RemovalViewEffect& view : preview.Effect.Views)
          {
            if (view.HasImage && view.CameraIndex < n)
            {
              job->Figures.Deleted[view.CameraIndex] = view.After;
            }
          }
          const auto t0 = std::chrono::steady_clock::now();
          job->Figures.RepairedFigures = vis4gs::MeasureViewMetrics(
            job->Figures.Repaired, preview.Cameras, vis4gs::RemovalEffectOptions{}, preview.Images);
          job->Figures.MeasureSeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          job->Rows = vis4gs::FineTuneFigureRows(job->Figures, preview.Cameras);
        }
      }
      catch (const std::exception& e)
      {
        job->Error = e.what();
      }
      QMetaObject::invokeMethod(
        this, [this] { this->OnFineTuned(); }, Qt::QueuedConnection);
    });
  this->UpdateButtons();
  d->RepairWorker->start();
  this->UpdateButtons();
  return true;
}

//------------------------------------------------------------------------------
void Vis4GSCleanupPanel::CancelFineTune()
{
  if (d->Repairing)
  {
    d->Repairing->Cancel = true;
  }
}

//------------------------------------------------------------------------------
void Vis4GSCleanupPanel::OnFineTuned()
{
  d->RepairWorker->wait();
  d->RepairWorker->deleteLater();
  d->RepairWorker = nullptr;
  const std::shared_ptr<Internals::Repair> job = std::move(d->Repairing);
  d->Measure->setEnabled(d->Scene && d->Cameras);
  this->UpdateButtons();
  const vis4gs::FineTuneResult& r = job->Figures;
  if (!job->Error.empty() || r.Cancelled)
  {
    d->RepairLabel->setText(!job->Error.empty()
        ? "fine-tune failed: " + QString::fromStdString(job->Error)
        : QString("Fine-tune cancelled after iteration %1 of %2: no log written.")
            .arg(r.LastIteration - r.SourceIteration)
            .arg(job->Options.Iterations));
    if (d->Progress)
    {
      d->Progress(1, d->RepairLabel->text(), true);
    }
    return;
  }
  d->Repaired = job;
  // The third state in the table, if it still shows the preview fine-tuned.
  const bool shown = d->Shown == job->Preview;
  double means[2][9];
  bool have[2] = { false, false };
  for (const vis4gs::FineTuneFigureRow& row : job->Rows)
  {
    if (row.View == "mean")
    {
      const int split = row.Split == "train" ? 0 : 1;
      std::copy(row.Values, row.Values + 9, means[split]);
      have[split] = true;
    }
  }
  if (shown)
  {
    for (int split = 0; split < 2; ++split)
    {
      for (int m = 0; m < 3; ++m)
      {
        SetNumber(d->Totals,
          split,
          RepairedColumn + m,
          have[split] ? means[split][3 * m + 2] : std::numeric_limits<double>::quiet_NaN());
      }
    }
    for (int row = 0; row < d->Views->rowCount(); ++row)
    {
      const std::size_t v = d->Views->item(row, 0)->data(Qt::UserRole).toULongLong();
      const vis4gs::ViewMetrics m =
        v < r.RepairedFigures.size() ? r.RepairedFigures[v] : vis4gs::ViewMetrics{};
      SetNumber(d->Views, row, RepairedColumn, m.Psnr);
      SetNumber(d->Views, row, RepairedColumn + 1, m.Ssim);
      SetNumber(d->Views, row, RepairedColumn + 2, m.L1);
    }
    for (QTableWidget* table : { d->Totals, d->Views })
    {
      for (int c = RepairedColumn; c < NumberOfColumns; ++c)
      {
        table->setColumnHidden(c, false);
      }
    }
  }
  auto psnr = [&](int split, int state)
  { return have[split] ? QString::number(means[split][state], 'f', 3) : QString("-"); };
  d->RepairLabel->setToolTip("The repaired run's log: " + job->LogPath);
  d->RepairLabel->setText(
    QString("Repaired (%1 iterations, positions %2, densification %3, %4 s): PSNR source -> "
            "deleted -> repaired: train %5 -> %6 -> %7 dB, test %8 -> %9 -> %10 dB. Log: %11")
      .arg(job->Options.Iterations)
      .arg(job->Options.FreePositions ? "free" : "fixed")
      .arg(job->Options.Densify ? "on" : "off")
      .arg(r.TrainSeconds + r.MeasureSeconds, 0, 'f', 1)
      .arg(psnr(0, 0))
      .arg(psnr(0, 1))
      .arg(psnr(0, 2))
      .arg(psnr(1, 0))
      .arg(psnr(1, 1))
      .arg(psnr(1, 2))
      .arg(QFileInfo(job->LogPath).fileName()));
  d->OpenRepaired->setVisible(static_cast<bool>(d->Open));
  d->CompareRepaired->setVisible(!job->SourceLog.isEmpty());
  // The new columns and the summary in sight.
  d->LeftScroll->ensureWidgetVisible(d->RepairLabel);
  for (QTableWidget* table : { d->Totals, d->Views })
  {
    if (shown && table->rowCount() > 0 && table->item(0, RepairedColumn))
    {
      table->scrollToItem(table->item(0, RepairedColumn));
    }
  }
  if (d->Progress)
  {
    d->Progress(1, d->RepairLabel->text() + " (" + job->LogPath + ")", true);
  }
}

//------------------------------------------------------------------------------
bool Vis4GSCleanupPanel::WaitForFineTune()
{
  const std::shared_ptr<Internals::Repair> job = d->Repairing;
  while (d->RepairWorker)
  {
    QApplication::processEvents(QEventLoop::AllEvents, 50);
    QThread::msleep(5);
  }
  return job && d->Repaired == job;
}

//------------------------------------------------------------------------------
bool Vis4GSCleanupPanel::WriteRepairTable(const QString& path) const
{
  if (!d->Repaired)
  {
    return false;
  }
  const std::string tmp = path.toStdString() + ".tmp";
  {
    std::ofstream csv(tmp);
    const std::vector<std::string>& columns = vis4gs::FineTuneFigureColumns();
    for (std::size_t c = 0; c < columns.size(); ++c)
    {
      csv << (c ? "," : "") << columns[c];
    }
    csv << "\n" << std::setprecision(17);
    for (const vis4gs::FineTuneFigureRow& row : d->Repaired->Rows)
    {
      csv << row.View << "," << row.Split;
      for (double v : row.Values)
      {
        csv << "," << v;
      }
      csv << "\n";
    }
    if (!csv)
    {
      return false;
    }
  }
  QFile::remove(path);
  return QFile::rename(QString::fromStdString(tmp), path);
}

//------------------------------------------------------------------------------
bool Vis4GSCleanupPanel::RunSelfTest(const QString& directory,
  const std::function<bool(bool, const std::string&)>& check)
{
  bool ok = true;
  vtkDataArray* ids = d->Scene ? d->Scene->GetPointData()->GetArray("GaussianId") : nullptr;
  if (!check(ids && ids->GetNumberOfTuples() > 10, "clean-up: a scene with ids"))
  {
    return false;
  }
  std::vector<vis4gs::Camera> cameras;
  vis4gs::TableToCameras(d->Cameras, cameras, nullptr);
  const double trainViews = static_cast<double>(std::count_if(cameras.begin(),
    cameras.end(),
    [](const vis4gs::Camera& c) { return c.Split == vis4gs::CameraSplit::Train; }));
  vtkDataArray* coverage = d->Scene->GetPointData()->GetArray(vis4gs::arrays::ViewCoverage);
  std::set<vtkIdType> expected;
  for (vtkIdType i = 0; coverage && i < coverage->GetNumberOfTuples(); ++i)
  {
    if (coverage->GetComponent(i, 0) * trainViews <= 3)
    {
      expected.insert(static_cast<vtkIdType>(ids->GetComponent(i, 0)));
    }
  }
  // A brushed selection (what the scene's modes or the histogram publish): two Gaussians and
  // one the rule selects.
  const vtkIdType brushed[3] = { static_cast<vtkIdType>(ids->GetComponent(0, 0)),
    static_cast<vtkIdType>(ids->GetComponent(1, 0)),
    expected.empty() ? static_cast<vtkIdType>(ids->GetComponent(2, 0)) : *expected.rbegin() };
  d->Hub->SelectIds(brushed, 3, vtkGaussianSelectionHub::REPLACE);
  const vtkIdType changes = d->Hub->GetNumberOfChanges();
  const vtkIdType brushedCount =
    static_cast<vtkIdType>(std::set<vtkIdType>(brushed, brushed + 3).size());
  // 1. A bad rule: an error naming the token, the selection unchanged.
  const bool applied = this->ApplyRule("covrage<=0.1 and opacity>=0.5", ADD);
  ok = check(!applied && d->Error && this->GetFeedback().contains("covrage") &&
           d->Rule->selectedText() == "covrage",
         "clean-up: a misspelt attribute is an error naming it (" +
           this->GetFeedback().toStdString() + ")") &&
    ok;
  ok = check(d->Hub->GetNumberOfSelectedIds() == brushedCount &&
           d->Hub->GetNumberOfChanges() == changes,
         "clean-up: the bad rule left the selection alone") &&
    ok;
  // 2. The rule typed with spaces is shown in canonical form; Replace selects what the rule
  //    selects, computed here from the score array directly.
  d->Rule->setText("VIEWS <= 3");
  ok =
    check(!d->Error && this->GetFeedback().contains("views&lt;=3"),
      "clean-up: the canonical form is shown back (" + this->GetFeedback().toStdString() + ")") &&
    ok;
  auto selected = [this]
  {
    vtkNew<vtkIdTypeArray> a;
    d->Hub->GetSelectedIds(a);
    return std::set<vtkIdType>(a->GetPointer(0), a->GetPointer(0) + a->GetNumberOfTuples());
  };
  std::set<vtkIdType> withBrush(expected);
  withBrush.insert(brushed, brushed + 3);
  ok = check(this->ApplyRule(d->Rule->text(), ADD) && selected() == withBrush,
         "clean-up: 'views<=3' added to a brushed selection selects " +
           std::to_string(withBrush.size()) + " Gaussians") &&
    ok;
  std::set<vtkIdType> inBrush;
  for (vtkIdType id : brushed)
  {
    if (expected.count(id))
    {
      inBrush.insert(id);
    }
  }
  d->Hub->SelectIds(brushed, 3, vtkGaussianSelectionHub::REPLACE);
  ok = check(this->ApplyRule(d->Rule->text(), INTERSECT) && selected() == inBrush,
         "clean-up: intersected with the brushed selection leaves " +
           std::to_string(inBrush.size())) &&
    ok;
  ok =
    check(this->ApplyRule(d->Rule->text(), REPLACE) && selected() == expected && !expected.empty(),
      "clean-up: replace selects the " + std::to_string(expected.size()) +
        " Gaussians with E_VC |V| <= 3") &&
    ok;
  {
    std::ofstream csv((directory + "/cleanup-selection.csv").toStdString());
    csv << "GaussianId\n";
    for (vtkIdType id : selected())
    {
      csv << id << "\n";
    }
  }
  // 3. Save and load (the file analyze --select=@FILE reads).
  const QString rulePath = directory + "/cleanup-rule.txt";
  ok = check(this->SaveRule(rulePath), "clean-up: the rule is saved") && ok;
  d->Rule->setText("opacity>0");
  ok = check(this->LoadRule(rulePath) && d->Rule->text() == "views<=3",
         "clean-up: the saved rule loads back in canonical form") &&
    ok;
  // 4. Another iteration (a new scene): the rule is re-applied once its scores are there.
  {
    const vtkSmartPointer<vtkPolyData> scene = d->Scene;
    const vtkSmartPointer<vtkTable> table = d->Cameras;
    vtkNew<vtkPolyData> withoutScores, withScores;
    withoutScores->ShallowCopy(scene);
    withoutScores->GetPointData()->RemoveArray(vis4gs::arrays::ViewCoverage);
    withScores->ShallowCopy(scene);
    const vis4gs::RemovalBaseline fromScores = d->Baseline;
    d->Hub->SelectIds(brushed, 3, vtkGaussianSelectionHub::REPLACE);
    this->SetScene(withoutScores, table);
    ok = check(d->Hub->GetNumberOfSelectedIds() == brushedCount,
           "clean-up: a new iteration without its scores yet keeps the selection") &&
      ok;
    this->SetScoreBaseline(scene, table, fromScores);
    ok = check(d->Baseline.MeasuredViews() == 0 && !d->BaselineScene,
           "clean-up: another snapshot drops the score pass's 'before', and a 'before' of "
           "a scene not shown is refused") &&
      ok;
    this->SetScene(withScores, table);
    ok =
      check(selected() == expected, "clean-up: the rule is re-applied once the scores are there") &&
      ok;
    this->SetScene(scene, table);
    // What the main window hands over when the score pass of this scene ends.
    this->SetScoreBaseline(scene, table, fromScores);
  }
  // The "before" renders of a preview (the score pass renders no test view), its "after"
  // renders (the affected views only), and its figures against those of the panel's own
  // "before" rendered anew (what it did before it reused the score pass's): bit for bit.
  auto checkReuse = [&check](const Internals::Result& shown, std::size_t reused, bool figures)
  {
    const vis4gs::RemovalEffect& effect = shown.Effect;
    std::size_t affected = 0;
    for (const vis4gs::RemovalViewEffect& v : effect.Views)
    {
      affected += v.Affected && v.HasImage ? 1 : 0;
    }
    bool ok = check(reused > 0 && shown.BeforeReused == reused &&
        shown.BeforeRendered + reused == effect.Train.Views + effect.Test.Views &&
        reused >= effect.Train.Views && effect.ViewsRendered == affected,
      "clean-up: the preview reused " + std::to_string(reused) + " views 'before' (" +
        std::to_string(effect.Train.Views) + " training views), rendered " +
        std::to_string(shown.BeforeRendered) + " 'before' and " +
        std::to_string(effect.ViewsRendered) + " 'after' (" + std::to_string(effect.TilesRendered) +
        " of " + std::to_string(effect.TilesOfTiledViews) + " tiles) for " +
        std::to_string(affected) + " affected views");
    if (!figures)
    {
      return ok;
    }
    vis4gs::RemovalEffectOptions options;
    const auto t0 = std::chrono::steady_clock::now();
    options.TileBaseline =
      vis4gs::MeasureRemovalBaseline(*shown.Cloud, shown.Cameras, options, shown.Images);
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const vis4gs::RemovalEffect fresh = vis4gs::MeasureRemovalEffect(
      *shown.Cloud, shown.Removed, shown.Cameras, options, shown.Images);
    auto same = [](const vis4gs::ViewMetrics& a, const vis4gs::ViewMetrics& b)
    {
      auto equal = [](double x, double y) { return std::isnan(x) ? std::isnan(y) : x == y; };
      return equal(a.Psnr, b.Psnr) && equal(a.Ssim, b.Ssim) && equal(a.L1, b.L1);
    };
    bool identical = fresh.Views.size() == effect.Views.size() &&
      same(fresh.Train.Before, effect.Train.Before) &&
      same(fresh.Train.After, effect.Train.After) && same(fresh.Test.Before, effect.Test.Before) &&
      same(fresh.Test.After, effect.Test.After);
    for (std::size_t r = 0; identical && r < effect.Views.size(); ++r)
    {
      identical = fresh.Views[r].CameraIndex == effect.Views[r].CameraIndex &&
        fresh.Views[r].Affected == effect.Views[r].Affected &&
        same(fresh.Views[r].Before, effect.Views[r].Before) &&
        same(fresh.Views[r].After, effect.Views[r].After);
    }
    ok =
      check(identical,
        "clean-up: the figures with the score pass's 'before' equal those of a 'before' "
        "rendered anew, bit for bit (train PSNR " +
          std::to_string(effect.Train.Before.Psnr) + " -> " +
          std::to_string(effect.Train.After.Psnr) + "); 'before' of the preview " +
          std::to_string(std::max(0.0, shown.BaselineSeconds)) + " s, rendered anew " +
          std::to_string(seconds) + " s; 'after' " + std::to_string(effect.SecondsAfter) + " s") &&
      ok;
    return ok;
  };
  // 5. The measurement in the worker thread; the table and the images. The score pass (full
  //    resolution) rendered every training view: the preview renders none of them "before".
  const std::size_t fromScores =
    d->BaselineScene == d->Scene ? d->Baseline.MeasuredViews() : std::size_t(0);
  this->MeasureRemoval();
  ok = check(this->WaitForMeasurement(), "clean-up: the removal was measured") && ok;
  if (!d->Shown)
  {
    return false;
  }
  const vis4gs::RemovalEffect& e = d->Shown->Effect;
  ok =
    check(d->Views->rowCount() == static_cast<int>(cameras.size()) && e.Removed == expected.size(),
      "clean-up: the table lists every view (" + std::to_string(d->Views->rowCount()) +
        ") for the " + std::to_string(e.Removed) + " Gaussians removed") &&
    ok;
  ok = checkReuse(*d->Shown, fromScores, true) && ok;
  bool worstFirst = true;
  for (int r = 1; r < d->Views->rowCount(); ++r)
  {
    const double a = d->Views->item(r - 1, 5)->data(Qt::UserRole).toDouble(),
                 b = d->Views->item(r, 5)->data(Qt::UserRole).toDouble();
    worstFirst = worstFirst && (std::isnan(b) || a <= b);
  }
  ok = check(worstFirst, "clean-up: the views are listed with the largest PSNR loss first") && ok;
  ok = check(this->WriteTable(directory + "/cleanup-before-after.csv"),
         "clean-up: the table is written to cleanup-before-after.csv") &&
    ok;
  d->Views->setCurrentCell(0, 0);
  const double largest = d->Images[2]->property("largestChange").toDouble();
  ok = check(!d->Images[0]->pixmap(Qt::ReturnByValue).isNull() &&
           (largest > 0) == (d->Views->item(0, 2)->text() == "yes"),
         "clean-up: picking the worst view shows its before/after images (largest change " +
           std::to_string(largest) + ")") &&
    ok;
  QApplication::processEvents();
  ok = check(this->grab().save(directory + "/cleanup-panel.png"),
         "clean-up: screenshot cleanup-panel.png") &&
    ok;
  // 6. A second preview of the same scene (one Gaussian fewer) renders no view "before".
  if (expected.size() > 1)
  {
    const vtkIdType first = *expected.begin();
    d->Hub->SelectIds(&first, 1, vtkGaussianSelectionHub::SUBTRACT);
    this->MeasureRemoval();
    const bool measured = this->WaitForMeasurement();
    ok = check(measured && d->Shown->BeforeRendered == 0 &&
             d->Shown->BeforeReused == d->Shown->Effect.Train.Views + d->Shown->Effect.Test.Views,
           "clean-up: a second preview renders no view 'before' (" +
             std::to_string(d->Shown->BeforeRendered) + "), it reuses " +
             std::to_string(d->Shown->BeforeReused)) &&
      ok;
    ok = checkReuse(*d->Shown, d->Shown->BeforeReused, false) && ok;
  }
  // 7. Fine-tune the previewed deletion (as `vis4gs repair`): a cancelled one writes nothing;
  //    a short one writes the repaired log, whose events are the deletion's prunes only
  //    (densification off). The deletion and its cleaned scene (the main window's export) are
  //    written for CTest, which runs `vis4gs repair` on them and compares.
  {
    const QString cancelled = directory + "/cleanup-cancelled.h5";
    QFile::remove(cancelled);
    ok = check(this->StartFineTune(cancelled, 100000, false, false),
           "clean-up: the fine-tune starts from the current preview") &&
      ok;
    this->CancelFineTune();
    const bool finished = this->WaitForFineTune();
    ok = check(!finished && !QFileInfo::exists(cancelled) &&
             QDir(directory)
               .entryList({ ".cleanup-cancelled*" }, QDir::Files | QDir::Hidden)
               .isEmpty() &&
             d->RepairLabel->text().contains("cancelled"),
           "clean-up: a cancelled fine-tune writes no log, nor its temporary (" +
             d->RepairLabel->text().toStdString() + ")") &&
      ok;
    const QString repaired = directory + "/cleanup-repaired.h5";
    // One iteration: the trainer logs /metrics (every view rendered) after each of so few.
    const int iterations = 1;
    QFile::remove(repaired);
    const bool tuned =
      this->StartFineTune(repaired, iterations, false, false) && this->WaitForFineTune();
    ok = check(tuned,
           "clean-up: fine-tuned " + std::to_string(iterations) + " iteration (" +
             d->RepairLabel->text().toStdString() + ")") &&
      ok;
    std::vector<std::int64_t> deleted, pruned;
    for (vtkIdType id : selected())
    {
      deleted.push_back(static_cast<std::int64_t>(id));
    }
    int last = -1;
    std::size_t events = 0;
    try
    {
      const vis4gs::TrainingLogReader log(repaired.toStdString());
      const vis4gs::EventTable table = log.ReadEvents();
      events = table.Size();
      for (std::size_t i = 0; i < table.Size(); ++i)
      {
        if (table.Kind[i] == static_cast<std::uint8_t>(vis4gs::EventKind::Prune) &&
          table.Iteration[i] == d->Hub->GetIteration())
        {
          pruned.push_back(table.Parent[i]);
        }
      }
      last = log.GetSnapshotIterations().back();
    }
    catch (const std::exception& e)
    {
      check(false, std::string("clean-up: the repaired log reads back: ") + e.what());
    }
    std::sort(pruned.begin(), pruned.end());
    ok = check(!deleted.empty() && pruned == deleted && events == deleted.size() &&
             last == d->Hub->GetIteration() + iterations,
           "clean-up: the repaired log's " + std::to_string(events) +
             " events are the prunes "
             "of the " +
             std::to_string(deleted.size()) + " deleted Gaussians at iteration " +
             std::to_string(d->Hub->GetIteration()) + "; its last snapshot is iteration " +
             std::to_string(last)) &&
      ok;
    bool filled = !d->Views->isColumnHidden(RepairedColumn) && d->Views->rowCount() > 0;
    for (int r = 0; filled && r < d->Views->rowCount(); ++r)
    {
      const double before = d->Views->item(r, 3)->data(Qt::UserRole).toDouble();
      const double after = d->Views->item(r, RepairedColumn)->data(Qt::UserRole).toDouble();
      filled = std::isnan(before) == std::isnan(after);
    }
    ok = check(filled, "clean-up: the table shows the repaired figures of every view") && ok;
    Vis4GSWriteSelectedIds(directory + "/cleanup-repair-deleted.csv", d->Hub);
    Vis4GSWriteSelectedScene(directory + "/cleanup-repair-cleaned.ply", d->Scene, d->Hub, true);
    ok = check(this->WriteRepairTable(directory + "/cleanup-repair.csv") &&
             QFileInfo::exists(directory + "/cleanup-repair-cleaned.ply"),
           "clean-up: cleanup-repair.csv, the deletion and its cleaned scene are written") &&
      ok;
  }
  return ok;
}

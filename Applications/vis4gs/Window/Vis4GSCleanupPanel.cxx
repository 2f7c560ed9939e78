// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSCleanupPanelInternals.h"

#include "GaussianIO.h"
#include "ScoreRegistry.h"
#include "SelectionRule.h"
#include "Vis4GSCompareWindow.h"
#include "Vis4GSDataModel.h"
#include "vtkGaussianRuleSelectionFilter.h"
#include "vtkGaussianSelectionHub.h"

#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkPointData.h"
#include "vtkStringArray.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
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
#include <sstream>

using namespace Vis4GSCleanupTable;

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
      // The default: next to the source log or scene file, named after it and the iteration.
      QString folder = QDir::currentPath(), stem = "scene";
      if (!d->SceneFile.isEmpty())
      {
        folder = QFileInfo(d->SceneFile).absolutePath();
        stem = QFileInfo(d->SceneFile).completeBaseName();
      }
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
          QString("%1-repaired-%2.h5").arg(stem).arg(this->GetSourceIteration())),
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
  connect(d->CompareRepaired, &QPushButton::clicked, this, [this] { this->OpenComparison(); });
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
  std::shared_ptr<const vis4gs::RemovalBaseline> baseline)
{
  // An earlier preview of the same scene may have measured more views (the test views).
  if (!scene || scene != d->Scene.GetPointer() || cameras != d->Cameras.GetPointer() || !baseline ||
    baseline->MeasuredViews() == 0 ||
    (d->BaselineScene == d->Scene && d->BaselineCameras == d->Cameras && d->Baseline &&
      d->Baseline->MeasuredViews() >= baseline->MeasuredViews()))
  {
    return;
  }
  d->BaselineScene = scene;
  d->BaselineCameras = cameras;
  d->Baseline = std::move(baseline);
}

//------------------------------------------------------------------------------
void Vis4GSCleanupPanel::SetSceneFile(const QString& path, const QString& cameras, int iteration)
{
  d->SceneFile = path;
  d->SceneCameras = cameras;
  d->SceneIteration = std::max(0, iteration);
}

//------------------------------------------------------------------------------
int Vis4GSCleanupPanel::GetSourceIteration() const
{
  return d->Hub->GetIteration() >= 0 ? d->Hub->GetIteration() : d->SceneIteration;
}

//------------------------------------------------------------------------------
Vis4GSCompareWindow* Vis4GSCleanupPanel::OpenComparison()
{
  if (!d->Repaired)
  {
    return nullptr;
  }
  const Internals::Repair& r = *d->Repaired;
  return r.SourceLog.isEmpty()
    ? Vis4GSCompareWindow::OpenWindow(this, r.SourceScene, -1, r.LogPath, r.SourceCameras)
    : Vis4GSCompareWindow::OpenWindow(this, r.SourceLog, r.SourceIteration, r.LogPath);
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
    d->Baseline = nullptr;
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
  for (const std::string& score : rule.ScoresRead())
  {
    if (!scene->GetPointData()->GetArray(vis4gs::FindScore(score)->ArrayName))
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
    // (A failed write leaves no half rule and the old one, and names the problem.)
    vis4gs::WriteTextFile(path.toStdString(), canonical + "\n");
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

// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSMainWindow.h"
#include "Vis4GSMainWindowInternals.h"
#include "Vis4GSPostResult.h"
#include "Vis4GSScoreStages.h"

#include "Vis4GSCleanupPanel.h"
#include "Vis4GSCompareWindow.h"
#include "Vis4GSControlPanel.h"
#include "Vis4GSDocument.h"
#include "Vis4GSSceneFrames.h"
#include "Vis4GSSelectionExport.h"
#include "Vis4GSSelectionTable.h"

#include "GaussianIO.h"
#include "RemovalEffect.h"
#include "Vis4GSDataModel.h"
#include "vtkGaussianHistogramView.h"
#include "vtkGaussianSceneView.h"
#include "vtkGaussianSelectionHub.h"
#include "vtkGaussianSelector.h"
#include "vtkGaussianSession.h"
#include "vtkGaussianTimelineView.h"
#include "vtkGaussianTrainingLogReader.h"
#include "vtkGaussianTreeItem.h"
#include "vtkGaussianTreeView.h"

#include "QVTKOpenGLNativeWidget.h"
#include "vtkAnnotationLink.h"
#include "vtkCallbackCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkGaussianOutputWindow.h"
#include "vtkGenericOpenGLRenderWindow.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTable.h"
#include "vtkTree.h"
#include "vtkVariant.h"

#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QDragEnterEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QInputDialog>
#include <QLabel>
#include <QListWidget>
#include <QMenuBar>
#include <QMimeData>
#include <QPlainTextEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QScrollArea>
#include <QSlider>
#include <QSpinBox>
#include <QStackedWidget>
#include <QStatusBar>
#include <QTemporaryDir>
#include <QThread>
#include <QTimer>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <string>
#include <utility>

namespace
{
const char* DockNames[5] = { "scene", "tree", "panel", "timeline", "histogram" };
}

//------------------------------------------------------------------------------
Vis4GSMainWindow::Vis4GSMainWindow(QWidget* parent)
  : QMainWindow(parent)
  , d(new Internals)
{
  this->BuildUi();
}

//------------------------------------------------------------------------------
Vis4GSMainWindow::~Vis4GSMainWindow()
{
  if (d->Worker)
  {
    d->Worker->wait();
  }
  d->Scores.reset(); // stops the scores and waits for them
  d->Hub->RemoveObservers(vtkCommand::SelectionChangedEvent);
  d->Hub->RemoveObservers(vtkGaussianSelectionHub::IterationChangedEvent);
  d->Hub->RemoveAllViews();
  if (d->ObservedSession) // (a document held elsewhere would call this window back)
  {
    d->ObservedSession->RemoveObserver(d->SessionErrorsTag);
  }
}

//------------------------------------------------------------------------------
vtkGaussianSelectionHub* Vis4GSMainWindow::GetHub()
{
  return d->Hub;
}

vtkGaussianTreeView* Vis4GSMainWindow::GetTreeView()
{
  return d->Tree;
}

vtkGaussianTimelineView* Vis4GSMainWindow::GetTimelineView()
{
  return d->Timeline;
}

vtkGaussianHistogramView* Vis4GSMainWindow::GetHistogramView()
{
  return d->Histogram;
}

vtkGaussianSceneView* Vis4GSMainWindow::GetSceneView()
{
  return d->Scene;
}

std::shared_ptr<Vis4GSDocument> Vis4GSMainWindow::GetDocument() const
{
  return d->Doc;
}

vtkTable* Vis4GSMainWindow::GetScoreCameras() const
{
  return d->ScoreCameras;
}

QDockWidget* Vis4GSMainWindow::GetDock(const QString& name) const
{
  for (int k = 0; k < 5; ++k)
  {
    if (name == DockNames[k])
    {
      return d->Docks[k];
    }
  }
  return name == "cleanup" ? d->CleanupDock : nullptr;
}

Vis4GSCleanupPanel* Vis4GSMainWindow::GetCleanupPanel() const
{
  return d->Cleanup;
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::SetLoadHooks(std::function<void(int depth, const char* step)> stage,
  std::function<void()> loaded)
{
  d->StageHook = std::move(stage);
  d->LoadedHook = std::move(loaded);
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::Stage(int depth, const char* step)
{
  if (d->StageHook)
  {
    d->StageHook(depth, step);
  }
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::BuildUi()
{
  this->setWindowTitle("Vis4GS");
  this->setAcceptDrops(true);
  this->setDockNestingEnabled(true);
  auto makeVtkWidget = [this](vtkGenericOpenGLRenderWindow* window)
  {
    auto* w = new QVTKOpenGLNativeWidget(this);
    w->setRenderWindow(window);
    window->SetMultiSamples(0);
    w->setMinimumSize(200, 150);
    return w;
  };
  auto makeDock = [this](int k, const QString& title, QWidget* widget, Qt::DockWidgetArea area)
  {
    auto* dock = new QDockWidget(title, this);
    dock->setObjectName(DockNames[k]);
    dock->setWidget(widget);
    this->addDockWidget(area, dock);
    d->Docks[k] = dock;
    return dock;
  };

  // A: scene (vtkGaussianSceneView): the window forwards nothing but the panel's settings;
  // selections come back through the hub, and a status message after each one.
  d->SceneWidget = makeVtkWidget(d->SceneWindow);
  d->Scene->SetRenderWindow(d->SceneWindow);
  d->Scene->SetInteractor(d->SceneWindow->GetInteractor());
  d->Scene->SetSelectionHub(d->Hub);
  d->SceneFrames.reset(new Vis4GSSceneFrames(this, d->Scene)); // (issue 30)
  d->PickCommand->SetClientData(this);
  d->PickCommand->SetCallback(
    [](vtkObject*, unsigned long, void* client, void*)
    {
      auto* self = static_cast<Vis4GSMainWindow*>(client);
      vtkGaussianSceneView* view = self->d->Scene;
      const char* names[] = { "Single", "Brush", "Frame", "Ray" };
      const long long count = view->GetLastSelectionCount();
      self->statusBar()->showMessage(QString("%1: %2 %3 picked in %4 ms")
                                       .arg(names[view->GetLastSelectionMode()])
                                       .arg(count)
                                       .arg(count == 1 ? "Gaussian" : "Gaussians")
                                       .arg(view->GetSelector()->GetLastSelectionTime(), 0, 'f', 1),
        5000);
    });
  d->Scene->AddObserver(vtkCommand::EndPickEvent, d->PickCommand);
  makeDock(0, "A. Gaussian analysis view", d->SceneWidget, Qt::LeftDockWidgetArea);

  // B: tree.
  d->TreeWidget = makeVtkWidget(d->TreeWindow);
  d->Tree->SetRenderWindow(d->TreeWindow);
  d->Tree->SetInteractor(d->TreeWindow->GetInteractor());
  d->Tree->SetSelectionHub(d->Hub);
  d->TreeMessage = new QLabel;
  d->TreeMessage->setWordWrap(true);
  d->TreeMessage->setAlignment(Qt::AlignCenter);
  d->TreeStack = new QStackedWidget;
  d->TreeStack->addWidget(d->TreeWidget);
  d->TreeStack->addWidget(d->TreeMessage);
  makeDock(1, "B. Densification tree", d->TreeStack, Qt::RightDockWidgetArea);

  // D: timeline.
  d->TimelineWidget = makeVtkWidget(d->TimelineWindow);
  d->Timeline->SetRenderWindow(d->TimelineWindow);
  d->Timeline->SetInteractor(d->TimelineWindow->GetInteractor());
  d->Timeline->SetSelectionHub(d->Hub);
  makeDock(3, "D. Property timeline", d->TimelineWidget, Qt::BottomDockWidgetArea);

  // Histogram.
  d->HistogramWidget = makeVtkWidget(d->HistogramWindow);
  d->Histogram->SetRenderWindow(d->HistogramWindow);
  d->Histogram->SetInteractor(d->HistogramWindow->GetInteractor());
  d->Histogram->SetSelectionHub(d->Hub);
  auto* histogramPanel = new QWidget(this);
  auto* hl = new QVBoxLayout(histogramPanel);
  d->HistogramArray = new QComboBox(histogramPanel);
  hl->addWidget(d->HistogramArray);
  hl->addWidget(d->HistogramWidget, 1);
  connect(d->HistogramArray,
    &QComboBox::currentTextChanged,
    this,
    [this](const QString& name)
    {
      if (!name.isEmpty())
      {
        d->Histogram->SetArrayName(name.toUtf8().constData());
        d->Histogram->UpdateHistogram();
        d->HistogramWindow->Render();
      }
    });
  makeDock(4, "Attribute histogram", histogramPanel, Qt::BottomDockWidgetArea);

  // C: log and control panel.
  auto* panel = new Vis4GSControlPanel(this);
  d->Panel = panel;
  connect(panel->CameraList,
    &QListWidget::currentRowChanged,
    this,
    [this](int row) { this->OnCameraChosen(row); });
  connect(panel->ShowFrustums,
    &QCheckBox::toggled,
    this,
    [this](bool show)
    {
      d->Scene->SetShowFrustums(show);
      d->Scene->Render();
    });
  connect(panel->SelectionMode,
    QOverload<int>::of(&QComboBox::currentIndexChanged),
    this,
    [this](int mode) { d->Scene->SetSelectionMode(mode); });
  d->Scene->SetMaximumNumberOfSplats(panel->SplatBudget->value());
  d->Scene->SetInteractiveSplatBudget(panel->MovingBudget->value());
  connect(panel->MovingBudget,
    QOverload<int>::of(&QSpinBox::valueChanged),
    this,
    [this](int value) { d->Scene->SetInteractiveSplatBudget(value); });
  connect(panel->SplatBudget,
    QOverload<int>::of(&QSpinBox::valueChanged),
    this,
    [this](int value)
    {
      d->Scene->SetMaximumNumberOfSplats(value);
      d->Scene->Render();
    });
  for (QCheckBox* box : { panel->HideOutside, panel->UseThreshold, panel->DimUnselected })
  {
    connect(box, &QCheckBox::toggled, this, [this](bool) { this->UpdateOverlay(); });
  }
  connect(panel->ExportIds, &QPushButton::clicked, this, [this] { this->ExportIds(); });
  connect(panel->ExportPly, &QPushButton::clicked, this, [this] { this->ExportPly(false); });
  connect(panel->DeletePly, &QPushButton::clicked, this, [this] { this->ExportPly(true); });
  connect(panel->IterationSlider,
    &QSlider::valueChanged,
    this,
    [this](int index)
    {
      if (d->Doc && index >= 0 && index < static_cast<int>(d->Doc->Snapshots.size()))
      {
        d->Hub->SetIteration(d->Doc->Snapshots[index]);
      }
    });
  for (QDoubleSpinBox* box : { panel->OverlayMin, panel->OverlayMax, panel->Threshold })
  {
    connect(box,
      QOverload<double>::of(&QDoubleSpinBox::valueChanged),
      this,
      [this](double) { this->UpdateOverlay(); });
  }
  connect(panel->Overlay,
    &QComboBox::currentTextChanged,
    this,
    [this](const QString& name)
    {
      // A new overlay starts with the full range of its array.
      vtkPolyData* scene = d->Doc ? d->Doc->Shown() : nullptr;
      vtkDataArray* array =
        scene ? scene->GetPointData()->GetArray(name.toUtf8().constData()) : nullptr;
      if (array)
      {
        // Finite values only: a score may hold +inf (CostPerContribution of a Gaussian that
        // is drawn and never shows), which no spin box can show.
        double range[2];
        array->GetFiniteRange(range, 0);
        d->Panel->SetOverlayRange(range[0], range[1]);
      }
      this->UpdateOverlay();
    });
  // The panel scrolls rather than imposing its height on the window (1280x800 fits).
  auto* panelScroll = new QScrollArea(this);
  panelScroll->setWidget(panel);
  panelScroll->setWidgetResizable(true);
  panelScroll->setFrameShape(QFrame::NoFrame);
  makeDock(2, "C. Log and control panel", panelScroll, Qt::RightDockWidgetArea);
  d->Cleanup = new Vis4GSCleanupPanel(d->Hub, this);
  d->Cleanup->SetDeleteAction([this] { this->ExportPly(true); });
  d->Cleanup->SetOpenAction([this](const QString& path) { this->Open(path); });
  d->Cleanup->SetProgress(
    [this](double fraction, const QString& message, bool done)
    {
      d->Progress->setVisible(!done);
      if (done)
      {
        this->statusBar()->showMessage(message, 10000);
        return;
      }
      this->OnProgress(fraction, message);
    });
  d->CleanupDock = new QDockWidget("Clean-up", this);
  d->CleanupDock->setObjectName("cleanup");
  auto* cleanupScroll = new QScrollArea(this);
  cleanupScroll->setWidget(d->Cleanup);
  cleanupScroll->setWidgetResizable(true);
  cleanupScroll->setFrameShape(QFrame::NoFrame);
  d->CleanupDock->setWidget(cleanupScroll);
  this->addDockWidget(Qt::RightDockWidgetArea, d->CleanupDock);
  d->CleanupDock->hide();

  d->Progress = new QProgressBar(this);
  d->Progress->setRange(0, 100);
  d->Progress->setMaximumWidth(240);
  d->Progress->hide();
  this->statusBar()->addPermanentWidget(d->Progress);
  d->Scores = std::make_unique<Vis4GSScoreStages>(this);
  d->Scores->Progress = [this](double f, const QString& m) { this->OnProgress(f, m); };
  // (Finished disables the button.)
  connect(d->Panel->StopScores, &QPushButton::clicked, this, [this] { d->Scores->Stop(); });

  // Hub -> window.
  d->HubCommand->SetClientData(this);
  d->HubCommand->SetCallback(
    [](vtkObject*, unsigned long event, void* client, void* data)
    {
      auto* self = static_cast<Vis4GSMainWindow*>(client);
      if (event == vtkGaussianSelectionHub::IterationChangedEvent)
      {
        self->OnIterationChanged(*static_cast<int*>(data));
      }
      else
      {
        self->OnSelectionChanged();
      }
    });
  d->Hub->AddObserver(vtkCommand::SelectionChangedEvent, d->HubCommand);
  d->Hub->AddObserver(vtkGaussianSelectionHub::IterationChangedEvent, d->HubCommand);
  // Session -> status bar: a port a view pulls (the history of a new selection, which reads
  // every snapshot) fails inside the view's update, where no caller collects the error; an
  // observed error is not printed by VTK's output window either. Posted, so that it comes after
  // the "N Gaussians selected" of the same change.
  d->SessionErrors->SetClientData(this);
  d->SessionErrors->SetCallback(
    [](vtkObject*, unsigned long, void* client, void* call)
    {
      auto* self = static_cast<Vis4GSMainWindow*>(client);
      const QString text = QString::fromStdString(
        vtkGaussianOutputWindow::CleanMessage(static_cast<const char*>(call)));
      Vis4GSPostResult(self,
        [self, text]
        {
          self->statusBar()->showMessage(text, 15000);
          if (self->d->SessionErrorsSaid.insert(text.toStdString()).second)
          {
            std::cerr << "vis4gs view: error: " << text.toStdString() << "\n";
          }
        });
    });

  // Menus and shortcuts.
  QMenu* file = this->menuBar()->addMenu("&File");
  file->addAction(
    "&Open...",
    this,
    [this]
    {
      const QString path = QFileDialog::getOpenFileName(this,
        "Open a training log or a scene",
        QString(),
        "Vis4GS inputs (*.h5 *.hdf5 *.ply *.spz *.ksplat *.splat *.sog meta.json *.glb "
        "*.gltf);;All "
        "files (*)");
      if (!path.isEmpty())
      {
        this->Open(path);
      }
    },
    QKeySequence::Open);
  file->addAction("C&ompare with...", // issue 20: the open state side by side with another
    this,
    [this]
    {
      if (d->Doc)
      {
        Vis4GSCompareWindow::AskAndOpen(this,
          QString::fromStdString(d->Doc->Path),
          d->Doc->Iteration,
          d->Doc->Snapshots,
          QString::fromStdString(d->SceneCameras));
      }
    });
  file->addAction(
    "&Screenshot...", this, [this] { this->ScreenshotDialog(); }, QKeySequence("Ctrl+S"));
  file->addAction(
    "Export selected &ids...", this, [this] { this->ExportIds(); }, QKeySequence("Ctrl+E"));
  file->addAction(
    "&Quit", this, [this] { this->close(); }, QKeySequence::Quit);
  QMenu* select = this->menuBar()->addMenu("&Selection");
  select->addAction(
    "&Clear", this, [this] { d->Hub->ClearSelection(); }, QKeySequence(Qt::Key_Escape));
  select->addAction(
    "&Delete selection to new PLY...",
    this,
    [this] { this->ExportPly(true); },
    QKeySequence::Delete);
  select->addAction(
    "Guided &clean-up...", this, [this] { this->ShowCleanup(); }, QKeySequence("Ctrl+K"));
  select->addAction(
    "Show lineage in the &tree",
    this,
    [this]
    {
      d->Tree->GetTreeItem()->ZoomToSelection();
      d->Tree->Render();
    },
    QKeySequence("L"));
  for (int k = 0; k < 4; ++k)
  {
    select->addAction(
      QString("Mode: ") + d->Panel->SelectionMode->itemText(k),
      this,
      [this, k] { d->Panel->SelectionMode->setCurrentIndex(k); },
      QKeySequence(QString::number(k + 1)));
  }
  QMenu* view = this->menuBar()->addMenu("&View");
  view->addAction(
    "&Reset scene camera",
    this,
    [this]
    {
      d->Scene->ResetCamera();
      d->Scene->Render();
    },
    QKeySequence("R"));
  view->addAction(
    "&Fit tree",
    this,
    [this]
    {
      d->Tree->GetTreeItem()->ResetViewport();
      d->Tree->Render();
    },
    QKeySequence("F"));
  view->addAction(
    "&Previous snapshot",
    this,
    [this] { d->Panel->IterationSlider->setValue(d->Panel->IterationSlider->value() - 1); },
    QKeySequence(Qt::Key_Left));
  view->addAction(
    "&Next snapshot",
    this,
    [this] { d->Panel->IterationSlider->setValue(d->Panel->IterationSlider->value() + 1); },
    QKeySequence(Qt::Key_Right));
  for (QDockWidget* dock : d->Docks)
  {
    view->addAction(dock->toggleViewAction());
  }
  this->resize(1400, 900);
  this->LayoutForDocument();
  // The empty window's docks are sized again once it is shown (resizeDocks before is approximate).
  QTimer::singleShot(0, this, [this] { this->SettleLayout(); });
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::LayoutForDocument()
{
  const Vis4GSDocument* doc = d->Doc.get();
  // A log whose events are damaged shows the tree view, saying why it is empty.
  const bool tree = doc && (doc->Tree != nullptr || !doc->TreeUnavailable.empty());
  const bool timeline = doc && doc->Metrics != nullptr;
  const bool cameras = doc && doc->Cameras && doc->Cameras->GetNumberOfRows() > 0;
  const bool snapshots = doc && doc->Snapshots.size() > 1;
  QDockWidget* scene = d->Docks[0];
  QDockWidget* treeDock = d->Docks[1];
  QDockWidget* panel = d->Docks[2];
  QDockWidget* timelineDock = d->Docks[3];
  QDockWidget* histogram = d->Docks[4];
  // Scene on the left over the whole height unless a timeline is shown; on the right the
  // tree above the panel; the timeline (wide, three charts) and the histogram share the
  // bottom, or without a timeline the histogram goes under the panel so that nothing is left
  // empty under the scene.
  this->addDockWidget(Qt::LeftDockWidgetArea, scene);
  if (tree)
  {
    this->addDockWidget(Qt::RightDockWidgetArea, treeDock);
    this->splitDockWidget(treeDock, panel, Qt::Vertical);
  }
  else
  {
    this->addDockWidget(Qt::RightDockWidgetArea, panel);
  }
  if (timeline)
  {
    this->addDockWidget(Qt::BottomDockWidgetArea, timelineDock);
    this->splitDockWidget(timelineDock, histogram, Qt::Horizontal);
  }
  else
  {
    this->splitDockWidget(panel, histogram, Qt::Vertical);
  }
  // A hidden dock keeps its space in the window; a view without data is taken out instead.
  for (QDockWidget* dock : { treeDock, timelineDock })
  {
    if (!(dock == treeDock ? tree : timeline))
    {
      this->removeDockWidget(dock);
    }
  }
  treeDock->setVisible(tree);
  timelineDock->setVisible(timeline);
  scene->show();
  panel->show();
  histogram->show();
  // Panel rows without data are hidden (no empty camera list or dead slider).
  d->Panel->ShowRow(d->Panel->CameraList, cameras);
  d->Panel->ShowRow(d->Panel->ShowFrustums, cameras);
  d->Panel->ShowRow(d->Panel->IterationRow, snapshots);
  // Sizes: the scene about 55 % of the width; the timeline's three stacked charts 40 % of the
  // height (at least 300 pixels); the tree above the panel about half of the right column.
  // Applied again by SettleLayout once the new dock arrangement is laid out.
  auto sizes = [this, tree, timeline, scene, treeDock, panel, timelineDock, histogram]
  {
    const int w = this->width(),
              h = this->height() - this->menuBar()->sizeHint().height() -
      this->statusBar()->sizeHint().height();
    const int bottom = timeline ? std::max(300, h * 2 / 5) : 0, top = std::max(300, h - bottom);
    this->resizeDocks({ scene }, { w * 55 / 100 }, Qt::Horizontal);
    if (tree)
    {
      this->resizeDocks({ treeDock, panel }, { top / 2, top / 2 }, Qt::Vertical);
    }
    else if (!timeline)
    {
      this->resizeDocks({ panel, histogram }, { top * 6 / 10, top * 4 / 10 }, Qt::Vertical);
    }
    if (timeline)
    {
      this->resizeDocks(
        { timelineDock, histogram }, { w * 65 / 100, w * 35 / 100 }, Qt::Horizontal);
      this->resizeDocks({ timelineDock }, { bottom }, Qt::Vertical);
    }
  };
  sizes();
  d->DockSizes = sizes;
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::SettleLayout()
{
  // resizeDocks on docks that were just moved is only approximate: the sizes are applied again
  // once the new arrangement is laid out, the bottom last so that the columns do not push it.
  QCoreApplication::sendPostedEvents(nullptr, QEvent::LayoutRequest);
  if (d->DockSizes)
  {
    d->DockSizes();
    QCoreApplication::sendPostedEvents(nullptr, QEvent::LayoutRequest);
  }
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::ShowCleanup()
{
  // Under the scene with the timeline when there is one (room for the wide table), else panel C.
  QDockWidget* timeline = d->Docks[3];
  const bool under = timeline->isVisible();
  this->tabifyDockWidget(under ? timeline : d->Docks[2], d->CleanupDock);
  d->CleanupDock->show();
  d->CleanupDock->raise();
  if (under)
  {
    this->resizeDocks({ d->CleanupDock }, { this->height() * 55 / 100 }, Qt::Vertical);
    this->resizeDocks({ d->CleanupDock }, { this->width() * 75 / 100 }, Qt::Horizontal);
  }
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::ShowWelcome()
{
  d->Panel->ShowWelcome();
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::Open(const QString& path)
{
  if (d->Worker)
  {
    this->statusBar()->showMessage("still loading the previous file", 3000);
    return;
  }
  d->Progress->setValue(0);
  d->Progress->show();
  this->statusBar()->showMessage("loading " + path);
  const std::string file = path.toStdString(), cameras = d->SceneCameras, images = d->SceneImages;
  // Readers and filters run in a worker thread; progress and the result are posted back to
  // the GUI thread, which keeps handling events (the interface stays responsive).
  d->Worker = QThread::create(
    [this, file, cameras, images]
    {
      std::shared_ptr<Vis4GSDocument> doc;
      QString error;
      try
      {
        doc = Vis4GSDocument::Load(
          file,
          [this](double f, const std::string& m)
          {
            const QString message = QString::fromStdString(m);
            Vis4GSPostResult(this, [this, f, message] { this->OnProgress(f, message); });
          },
          cameras,
          images);
      }
      catch (const std::exception& e)
      {
        error = QString::fromStdString(e.what());
      }
      Vis4GSPostResult(this, [this, doc, error] { this->OnLoaded(doc, error); });
    });
  d->Worker->start();
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::SetSceneCameras(const QString& cameras)
{
  d->SceneCameras = cameras.toStdString();
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::SetSceneImages(const QString& folder, int iteration)
{
  d->SceneImages = folder.toStdString();
  d->SceneIteration = iteration;
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::OnProgress(double fraction, const QString& message)
{
  if (fraction < 0)
  {
    d->Progress->setRange(0, 0); // a step of unknown length: busy indicator
  }
  else
  {
    d->Progress->setRange(0, 100);
    d->Progress->setValue(static_cast<int>(100 * fraction));
  }
  this->statusBar()->showMessage(message);
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::OnLoaded(std::shared_ptr<Vis4GSDocument> doc, const QString& error)
{
  if (d->Worker)
  {
    d->Worker->wait();
    d->Worker->deleteLater();
    d->Worker = nullptr;
  }
  d->Progress->hide();
  if (!doc)
  {
    this->statusBar()->showMessage("could not open: " + error);
    std::cerr << "vis4gs view: error: " << error.toStdString() << "\n";
    emit this->loadFailed(error);
    return;
  }
  // Scores of the previous document: stopped (after the view they are on) and dropped.
  d->Scores->Stop();
  d->Scores->Wait();
  d->Doc = doc;
  d->Cleanup->SetSceneFile(doc->IsLog ? QString() : QString::fromStdString(doc->Path),
    QString::fromStdString(d->SceneCameras),
    d->SceneIteration);
  this->Stage(0, nullptr);
  d->ScoreCameras = nullptr;
  d->ImageDir.reset();
  d->ScoresDone = false;
  d->Hub->RenderOnChangeOff();
  d->Hub->ClearSelection();
  this->setWindowTitle("Vis4GS - " + QFileInfo(QString::fromStdString(doc->Path)).fileName());
  d->Panel->LogText->setPlainText(QString::fromStdString(doc->Summary));
  for (const std::string& warning : doc->Warnings) // said once, here
  {
    std::cerr << "vis4gs view: warning: " << warning << "\n";
  }
  d->TreeMessage->setText(QString::fromStdString(doc->TreeUnavailable));
  d->TreeStack->setCurrentIndex(doc->Tree || doc->TreeUnavailable.empty() ? 0 : 1);
  this->LayoutForDocument();
  // The views take the session's ports (as a script connects them); the hub's selection is
  // the session's selection input, so the timeline's history follows it when the hub renders.
  vtkGaussianSession* session = doc->Session;
  if (d->ObservedSession)
  {
    d->ObservedSession->RemoveObserver(d->SessionErrorsTag);
  }
  d->ObservedSession = session;
  d->SessionErrorsTag = session->AddObserver(vtkCommand::ErrorEvent, d->SessionErrors);
  if (doc->Tree)
  {
    d->Tree->SetInputConnection(session->GetOutputPort(vtkGaussianSession::TreePort));
    d->Tree->SetFamilyBandsConnection(session->GetOutputPort(vtkGaussianSession::BandsPort));
    d->Tree->Update();
  }
  else
  {
    d->Tree->SetTree(nullptr); // (no events, or they are damaged: TreeUnavailable says why)
    d->Tree->SetFamilyBands(nullptr);
  }
  d->Tree->GetTreeItem()->ResetViewport();
  this->Stage(0, "tree view input");
  session->SetSelectionConnection(d->Hub->GetAnnotationLink()->GetOutputPort(2));
  session->SetMaximumHistoryIds(Vis4GSDocument::HistoryLines);
  if (doc->Metrics)
  {
    d->Timeline->SetMetricsConnection(session->GetOutputPort(vtkGaussianSession::MetricsPort));
  }
  else
  {
    d->Timeline->SetMetrics(nullptr);
  }
  if (doc->Reader)
  {
    d->Timeline->SetHistoryConnection(session->GetOutputPort(vtkGaussianSession::HistoryPort));
  }
  else
  {
    d->Timeline->SetHistory(nullptr);
  }
  d->Timeline->SetTestMetrics(doc->TestMetrics);
  d->Timeline->Update();
  this->Stage(0, "timeline input");
  d->Panel->CameraList->clear();
  if (doc->Cameras)
  {
    vtkAbstractArray* names = doc->Cameras->GetColumnByName(vis4gs::arrays::CameraName);
    for (vtkIdType r = 0; names && r < doc->Cameras->GetNumberOfRows(); ++r)
    {
      d->Panel->CameraList->addItem(QString::fromStdString(names->GetVariantValue(r).ToString()));
    }
  }
  d->Panel->IterationSlider->blockSignals(true);
  d->Panel->IterationSlider->setRange(0, std::max(0, static_cast<int>(doc->Snapshots.size()) - 1));
  d->Panel->IterationSlider->setValue(d->Panel->IterationSlider->maximum());
  d->Panel->IterationSlider->setEnabled(doc->Snapshots.size() > 1);
  d->Panel->IterationSlider->blockSignals(false);
  // Before the scene view has the Gaussians, while its frames cost nothing.
  this->SettleLayout();
  d->Scene->SetCameras(doc->Cameras);
  this->UpdateScene(false); // every view is rendered once below
  this->Stage(0, "scene, histogram and panel inputs");
  d->Hub->SetIteration(doc->Iteration);
  d->Hub->RenderOnChangeOn();
  d->Scene->ResetCamera();
  if (doc->Cameras && doc->Cameras->GetNumberOfRows() > 0)
  {
    const vtkIdType first = vis4gs::FirstTrainingCamera(doc->Cameras);
    d->Panel->CameraList->blockSignals(true);
    d->Panel->CameraList->setCurrentRow(static_cast<int>(first));
    d->Panel->CameraList->blockSignals(false);
    d->Scene->JumpToCamera(first);
  }
  if (!d->LoadedHook) // (a harness renders the views itself)
  {
    d->Hub->RenderAll();
  }
  this->statusBar()->showMessage(
    QString("loaded %1 in %2 s").arg(QString::fromStdString(doc->Path)).arg(doc->Seconds), 5000);
  if (d->LoadedHook)
  {
    d->LoadedHook();
    return;
  }
  this->StartScores();
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::UpdateScene(bool render)
{
  vtkPolyData* scene = d->Doc ? d->Doc->Shown() : nullptr;
  if (!scene)
  {
    return;
  }
  this->Stage(1, nullptr);
  // The session's Gaussians port, or the scoring session's once the scores landed: the view
  // pulls it (and takes it again only when its arrays changed).
  d->Scene->SetInputConnection(d->Doc->GaussiansConnection());
  d->Scene->Update();
  this->Stage(1, "scene view input (its Gaussians for the mapper and the selector)");
  d->Histogram->SetInputConnection(d->Doc->GaussiansConnection());
  d->Cleanup->SetScene(scene, d->ScoreCameras);
  const QString overlay = d->Panel->Overlay->currentText();
  const QString hist = d->HistogramArray->currentText();
  d->Panel->Overlay->blockSignals(true);
  d->HistogramArray->blockSignals(true);
  d->Panel->Overlay->clear();
  d->Panel->Overlay->addItem("True colour");
  d->HistogramArray->clear();
  for (int a = 0; a < scene->GetPointData()->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = scene->GetPointData()->GetArray(a);
    if (!array || !array->GetName() || std::string(array->GetName()) == "GaussianId" ||
      std::string(array->GetName()) == "SH" || std::string(array->GetName()) == "Rotation")
    {
      continue;
    }
    d->HistogramArray->addItem(array->GetName());
    if (array->GetNumberOfComponents() == 1)
    {
      d->Panel->Overlay->addItem(array->GetName());
    }
  }
  d->Panel->Overlay->setCurrentText(overlay);
  d->HistogramArray->setCurrentText(hist.isEmpty() ? "Opacity" : hist);
  d->Panel->Overlay->blockSignals(false);
  d->HistogramArray->blockSignals(false);
  d->Histogram->SetArrayName(d->HistogramArray->currentText().toUtf8().constData());
  d->Histogram->UpdateHistogram();
  this->Stage(1, "histogram");
  this->UpdateOverlay(render);
  this->Stage(1, "overlay");
  this->OnSelectionChanged();
  this->Stage(1, "selection views");
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::UpdateOverlay(bool render)
{
  const QString name = d->Panel->Overlay->currentText();
  const std::string array = name.toStdString();
  vtkPolyData* scene = d->Doc ? d->Doc->Shown() : nullptr;
  const bool score =
    scene && name != "True colour" && scene->GetPointData()->GetArray(array.c_str());
  for (QWidget* w : { static_cast<QWidget*>(d->Panel->OverlayMin),
         static_cast<QWidget*>(d->Panel->OverlayMax),
         static_cast<QWidget*>(d->Panel->HideOutside),
         static_cast<QWidget*>(d->Panel->UseThreshold),
         static_cast<QWidget*>(d->Panel->Threshold) })
  {
    w->setEnabled(score);
  }
  d->Scene->SetDimUnselected(d->Panel->DimUnselected->isChecked());
  d->Scene->SetOverlayArrayName(score ? array.c_str() : nullptr);
  d->Scene->SetOverlayRange(d->Panel->OverlayMin->value(), d->Panel->OverlayMax->value());
  d->Scene->SetHideOutsideRange(d->Panel->HideOutside->isChecked());
  d->Scene->SetUseThreshold(d->Panel->UseThreshold->isChecked());
  d->Scene->SetThreshold(d->Panel->Threshold->value());
  if (render)
  {
    d->Scene->Render();
  }
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::OnCameraChosen(int row)
{
  if (!d->Doc || !d->Doc->Cameras || row < 0)
  {
    return;
  }
  if (d->Scene->JumpToCamera(row))
  {
    d->Scene->Render();
  }
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::OnSelectionChanged()
{
  const auto& selected = d->Hub->GetSelectedIdVector();
  d->Panel->Table->Show(d->Doc ? d->Doc->Shown() : nullptr, selected);
  // (The timeline's history of the selection is the session's history port: the hub renders
  // the timeline, which pulls it.)
  this->statusBar()->showMessage(QString("%1 Gaussians selected").arg(selected.size()), 3000);
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::OnIterationChanged(int iteration)
{
  if (!d->Doc || !d->Doc->Reader || iteration < 0)
  {
    return;
  }
  d->Panel->IterationLabel->setText(QString::number(iteration));
  const auto& s = d->Doc->Snapshots;
  const int nearest = d->Doc->Reader->FindNearestSnapshot(iteration);
  auto it = std::lower_bound(s.begin(), s.end(), nearest);
  if (it != s.end())
  {
    d->Panel->IterationSlider->blockSignals(true);
    d->Panel->IterationSlider->setValue(static_cast<int>(it - s.begin()));
    d->Panel->IterationSlider->blockSignals(false);
  }
  if (nearest != d->Doc->Iteration)
  {
    // The snapshot is read in this thread (the views need it at once, and the log's reader
    // is not shared with a worker): a busy bar and message are painted before it starts.
    const bool shown = d->Progress->isVisible();
    d->Progress->setRange(0, 0);
    d->Progress->show();
    this->statusBar()->showMessage(QString("reading the snapshot of iteration %1").arg(nearest));
    QApplication::processEvents(QEventLoop::ExcludeUserInputEvents);
    QApplication::setOverrideCursor(Qt::WaitCursor);
    auto done = [this, shown]
    {
      QApplication::restoreOverrideCursor();
      d->Progress->setRange(0, 100);
      d->Progress->setVisible(shown);
    };
    try
    {
      d->Doc->LoadIteration(iteration);
      done();
      this->UpdateScene();
      if (!d->LoadedHook)
      {
        this->StartScores();
      }
    }
    catch (const std::exception& e)
    {
      done();
      this->statusBar()->showMessage(QString("snapshot: ") + e.what(), 5000);
    }
  }
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::ExportIds()
{
  const QString path =
    QFileDialog::getSaveFileName(this, "Export selected ids", "selection.csv", "CSV (*.csv)");
  if (path.isEmpty())
  {
    return;
  }
  const Vis4GSExportReport report = Vis4GSWriteSelectedIds(path, d->Hub);
  this->statusBar()->showMessage(report.Message, report.Milliseconds);
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::ExportPly(bool deleteSelection)
{
  vtkPolyData* scene = d->Doc ? d->Doc->Shown() : nullptr;
  if (!scene)
  {
    return;
  }
  // A name ending in .compressed.ply gets the PlayCanvas compressed PLY (SuperSplat and web
  // viewers), with its quantisation error in the status bar.
  const QString compressedFilter = "Compressed PLY for SuperSplat (*.compressed.ply)";
  QString filter;
  QString path = QFileDialog::getSaveFileName(this,
    deleteSelection ? "Save the scene without the selection" : "Export the selected Gaussians",
    deleteSelection ? "pruned.ply" : "selection.ply",
    "PLY (*.ply);;SPZ v4, quantised for web viewers (*.spz);;glTF KHR_gaussian_splatting (*.glb "
    "*.gltf);;" +
      compressedFilter,
    &filter);
  if (!path.isEmpty() && filter == compressedFilter &&
    !path.endsWith(".compressed.ply", Qt::CaseInsensitive))
  {
    path = path.endsWith(".ply", Qt::CaseInsensitive) ? path.left(path.size() - 4) : path;
    path += ".compressed.ply";
  }
  if (path.isEmpty())
  {
    return;
  }
  const Vis4GSExportReport report = Vis4GSWriteSelectedScene(path, scene, d->Hub, deleteSelection);
  this->statusBar()->showMessage(report.Message, report.Milliseconds);
}

//------------------------------------------------------------------------------
bool Vis4GSMainWindow::SaveScreenshot(const QString& which, const QString& path)
{
  QWidget* widget = this;
  for (int k = 0; k < 5; ++k)
  {
    if (which == DockNames[k])
    {
      widget = d->Docks[k];
    }
  }
  if (!widget->isVisible())
  {
    return false; // (a hidden dock's grab would lay it out again and resize the others)
  }
  d->SceneFrames->WaitForCurrent(); // (the scene view's frame may be in the making)
  return widget->grab().save(path);
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::ScreenshotDialog()
{
  bool ok = false;
  const QString which = QInputDialog::getItem(this,
    "Screenshot",
    "View",
    { "window", "scene", "tree", "panel", "timeline", "histogram" },
    0,
    false,
    &ok);
  if (!ok)
  {
    return;
  }
  const QString path =
    QFileDialog::getSaveFileName(this, "Save screenshot", which + ".png", "PNG (*.png)");
  if (!path.isEmpty() && !this->SaveScreenshot(which, path))
  {
    this->statusBar()->showMessage(path + ": could not be written", 5000);
  }
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::dragEnterEvent(QDragEnterEvent* event)
{
  if (event->mimeData()->hasUrls())
  {
    event->acceptProposedAction();
  }
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::dropEvent(QDropEvent* event)
{
  const auto urls = event->mimeData()->urls();
  if (!urls.isEmpty())
  {
    this->Open(urls.front().toLocalFile());
  }
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::SetSplatBudget(long long splats)
{
  d->Panel->SplatBudget->setValue(static_cast<int>(std::min<long long>(splats, 100000000)));
  d->Scene->SetMaximumNumberOfSplats(static_cast<vtkIdType>(splats));
}

// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSMainWindow.h"

#include "Vis4GSCleanupPanel.h"
#include "Vis4GSCompareWindow.h"
#include "Vis4GSDocument.h"

#include "GaussianIO.h"
#include "TrainingLogReader.h"
#include "Vis4GSDataModel.h"
#include "vtkGaussianCameraFrustums.h"
#include "vtkGaussianCameraUtilities.h"
#include "vtkGaussianHistogramView.h"
#include "vtkGaussianSelectionHub.h"
#include "vtkGaussianSelector.h"
#include "vtkGaussianSplatMapper.h"
#include "vtkGaussianTimelineView.h"
#include "vtkGaussianTreeItem.h"
#include "vtkGaussianTreeView.h"

#include "QVTKOpenGLNativeWidget.h"
#include "vtkActor.h"
#include "vtkActor2D.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkContextMouseEvent.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkGenericOpenGLRenderWindow.h"
#include "vtkIdTypeArray.h"
#include "vtkLookupTable.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkPolyDataMapper2D.h"
#include "vtkProperty.h"
#include "vtkProperty2D.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkScalarBarActor.h"
#include "vtkTable.h"
#include "vtkTextActor.h"
#include "vtkTextProperty.h"
#include "vtkTree.h"
#include "vtkVariant.h"

#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QDragEnterEvent>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QImage>
#include <QInputDialog>
#include <QLabel>
#include <QListWidget>
#include <QMenuBar>
#include <QMimeData>
#include <QPlainTextEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QScrollArea>
#include <QShortcut>
#include <QSlider>
#include <QSpinBox>
#include <QStatusBar>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QTextStream>
#include <QThread>
#include <QTimer>
#include <QVBoxLayout>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <functional>
#include <iostream>
#include <numeric>
#include <set>
#include <sstream>
#include <string>
#include <utility>

struct Vis4GSMainWindow::Internals
{
  vtkNew<vtkGaussianSelectionHub> Hub;
  std::shared_ptr<Vis4GSDocument> Doc;
  // A: scene. Frustums (opaque lines) are added before the splats, which blend over them.
  QVTKOpenGLNativeWidget* SceneWidget = nullptr;
  vtkNew<vtkGenericOpenGLRenderWindow> SceneWindow;
  vtkNew<vtkRenderer> SceneRenderer;
  vtkNew<vtkGaussianSplatMapper> SceneMapper;
  vtkNew<vtkActor> SceneActor;
  vtkNew<vtkScalarBarActor> Legend;
  vtkNew<vtkGaussianCameraFrustums> Frustums;
  vtkNew<vtkPolyDataMapper> FrustumMapper;
  vtkNew<vtkLookupTable> FrustumColors;
  vtkNew<vtkActor> FrustumActor;
  vtkNew<vtkGaussianSelector> Selector;
  vtkNew<vtkRenderer> MarkerRenderer; // layer 1: markers of a small selection, always on top
  vtkNew<vtkPolyData> Markers;
  vtkNew<vtkPolyDataMapper> MarkerMapper;
  vtkNew<vtkActor> MarkerActor;
  vtkNew<vtkPolyData> Band; // brush stroke / frame rectangle, display coordinates
  vtkNew<vtkPolyDataMapper2D> BandMapper;
  vtkNew<vtkActor2D> BandActor;
  std::vector<std::array<double, 2>> Stroke;
  bool Dragging = false;
  int PressPosition[2] = { 0, 0 };
  long long HighlightCount = 0;
  // Scores (worker thread).
  QThread* ScoreWorker = nullptr;
  bool ScoresPending = false;
  bool ScoresDone = false;
  vtkSmartPointer<vtkTable> ScoreCameras;
  std::unique_ptr<QTemporaryDir> ImageDir;
  // B, D, histogram.
  QVTKOpenGLNativeWidget* TreeWidget = nullptr;
  vtkNew<vtkGenericOpenGLRenderWindow> TreeWindow;
  vtkNew<vtkGaussianTreeView> Tree;
  QVTKOpenGLNativeWidget* TimelineWidget = nullptr;
  vtkNew<vtkGenericOpenGLRenderWindow> TimelineWindow;
  vtkNew<vtkGaussianTimelineView> Timeline;
  QVTKOpenGLNativeWidget* HistogramWidget = nullptr;
  vtkNew<vtkGenericOpenGLRenderWindow> HistogramWindow;
  vtkNew<vtkGaussianHistogramView> Histogram;
  // C: panel.
  QComboBox* SelectionMode = nullptr;
  QListWidget* CameraList = nullptr;
  QCheckBox* ShowFrustums = nullptr;
  QSlider* IterationSlider = nullptr;
  QLabel* IterationLabel = nullptr;
  QComboBox* Overlay = nullptr;
  QDoubleSpinBox* OverlayMin = nullptr;
  QDoubleSpinBox* OverlayMax = nullptr;
  QCheckBox* HideOutside = nullptr;
  QCheckBox* UseThreshold = nullptr;
  QDoubleSpinBox* Threshold = nullptr;
  QCheckBox* DimUnselected = nullptr;
  QSpinBox* SplatBudget = nullptr;
  QComboBox* HistogramArray = nullptr;
  QPlainTextEdit* LogText = nullptr;
  QTableWidget* Table = nullptr;
  QProgressBar* Progress = nullptr;
  QFormLayout* Form = nullptr;
  QWidget* IterationRow = nullptr;
  QWidget* Welcome = nullptr;
  std::string SceneCameras;
  QDockWidget* Docks[5] = { nullptr, nullptr, nullptr, nullptr, nullptr };
  // Guided clean-up (issue 20): opened from the Selection menu, tabbed with panel C.
  Vis4GSCleanupPanel* Cleanup = nullptr;
  QDockWidget* CleanupDock = nullptr;
  vtkNew<vtkCallbackCommand> HubCommand;
  QThread* Worker = nullptr;
  QString SelfTestDir;
  bool SelfTest = false;
  bool SelfTestStarted = false;
  QString BaselineDir;
  int BaselineTolerance = 48;
  double BaselineFraction = 0.02;
  bool Benchmark = false;
  double BenchmarkStart = 0.0, BenchmarkCpuStart = 0.0;
};

namespace
{
double Now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double CpuNow()
{
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

// --benchmark: prints the wall and CPU time since the previous stage at each call.
class StageTimer
{
public:
  StageTimer(bool enabled, std::string prefix)
    : Enabled(enabled)
    , Prefix(std::move(prefix))
  {
  }
  void operator()(const char* what)
  {
    if (this->Enabled)
    {
      const double now = Now(), cpu = CpuNow();
      std::cout << this->Prefix << what << ": " << now - this->Start << " s (" << cpu - this->Cpu
                << " s CPU)" << std::endl;
      this->Start = now;
      this->Cpu = cpu;
    }
  }

  double GetStart() const { return this->Start; }

private:
  bool Enabled;
  std::string Prefix;
  double Start = Now(), Cpu = CpuNow();
};

// Forwards the scene interactor's mouse events to the window; can abort them so that the
// camera style does not rotate while brushing or framing.
class SceneMouseCommand : public vtkCommand
{
public:
  static SceneMouseCommand* New() { return new SceneMouseCommand; }
  void Execute(vtkObject*, unsigned long event, void*) override
  {
    bool abort = false;
    this->Callback(event, abort);
    this->SetAbortFlag(abort ? 1 : 0);
  }
  std::function<void(unsigned long, bool&)> Callback;
};
}

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
  if (d->ScoreWorker)
  {
    d->ScoreWorker->wait();
  }
  d->Hub->RemoveObservers(vtkCommand::SelectionChangedEvent);
  d->Hub->RemoveObservers(vtkGaussianSelectionHub::IterationChangedEvent);
  d->Hub->RemoveAllViews();
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

  // A: scene. The 3DGS splat mapper (Rendering/Splats); the camera frustums are opaque
  // lines added first so that the splats are blended over them (mapper header).
  d->SceneWidget = makeVtkWidget(d->SceneWindow);
  d->SceneWindow->AddRenderer(d->SceneRenderer);
  d->SceneRenderer->SetBackground(0, 0, 0);
  d->FrustumColors->SetHueRange(0.6, 0.0);
  d->FrustumColors->SetSaturationRange(0.2, 1.0);
  d->FrustumColors->SetValueRange(0.6, 1.0);
  d->FrustumColors->Build();
  d->FrustumMapper->SetInputConnection(d->Frustums->GetOutputPort());
  d->FrustumMapper->SetLookupTable(d->FrustumColors);
  d->FrustumMapper->SetScalarModeToUsePointData();
  d->FrustumMapper->SetColorModeToMapScalars();
  d->FrustumActor->SetMapper(d->FrustumMapper);
  d->FrustumActor->GetProperty()->SetLineWidth(1.5);
  d->FrustumActor->PickableOff();
  d->FrustumActor->VisibilityOff();
  d->SceneRenderer->AddActor(d->FrustumActor);
  d->SceneMapper->SetDimUnselected(false);
  d->SceneActor->SetMapper(d->SceneMapper);
  d->SceneRenderer->AddActor(d->SceneActor);
  d->Legend->SetNumberOfLabels(5);
  // Wide enough for the "suspicious" annotation at the bright end of a score's map.
  d->Legend->SetMaximumWidthInPixels(150);
  d->Legend->SetAnnotationLeaderPadding(4);
  d->Legend->SetVerticalTitleSeparation(10);
  d->Legend->SetPosition(0.88, 0.1);
  d->Legend->SetPosition2(0.11, 0.8);
  d->Legend->VisibilityOff();
  d->SceneRenderer->AddViewProp(d->Legend);
  d->BandMapper->SetInputData(d->Band);
  d->BandActor->SetMapper(d->BandMapper);
  d->BandActor->GetProperty()->SetColor(1.0, 0.85, 0.2);
  d->BandActor->GetProperty()->SetLineWidth(1.5);
  d->SceneRenderer->AddViewProp(d->BandActor);
  d->SceneWindow->SetNumberOfLayers(2);
  d->MarkerRenderer->SetLayer(1);
  d->MarkerRenderer->InteractiveOff();
  d->MarkerRenderer->SetActiveCamera(d->SceneRenderer->GetActiveCamera());
  d->SceneWindow->AddRenderer(d->MarkerRenderer);
  d->MarkerMapper->SetInputData(d->Markers);
  d->MarkerMapper->ScalarVisibilityOff();
  d->MarkerActor->SetMapper(d->MarkerMapper);
  d->MarkerActor->GetProperty()->SetRepresentationToWireframe();
  d->MarkerActor->GetProperty()->SetColor(1.0, 0.35, 0.0);
  d->MarkerActor->GetProperty()->SetPointSize(7);
  d->MarkerActor->GetProperty()->SetLineWidth(2);
  d->MarkerActor->PickableOff();
  d->MarkerRenderer->AddActor(d->MarkerActor);
  d->Selector->SetRenderer(d->SceneRenderer);
  d->Selector->SetSplatMapper(d->SceneMapper); // selections reuse the still frame's projection
  d->Hub->AddRenderWindow(d->SceneWindow);
  vtkRenderWindowInteractor* iren = d->SceneWindow->GetInteractor();
  // Brush and Frame drags: observed before the camera style, which they abort (so it never
  // grabs the mouse). Single and Ray clicks: the style rotates on a press and grabs the mouse
  // focus, so the release is observed by a passive observer, which VTK calls even then.
  vtkNew<SceneMouseCommand> mouse;
  mouse->Callback = [this](unsigned long event, bool& abort) { this->OnSceneMouse(event, abort); };
  for (unsigned long event : { vtkCommand::LeftButtonPressEvent,
         vtkCommand::MouseMoveEvent,
         vtkCommand::LeftButtonReleaseEvent })
  {
    iren->AddObserver(event, mouse, 1.0);
  }
  vtkNew<SceneMouseCommand> click;
  click->PassiveObserverOn();
  click->Callback = [this](unsigned long, bool&) { this->OnSceneClick(); };
  iren->AddObserver(vtkCommand::LeftButtonReleaseEvent, click, 2.0);
  makeDock(0, "A. Gaussian analysis view", d->SceneWidget, Qt::LeftDockWidgetArea);

  // B: tree.
  d->TreeWidget = makeVtkWidget(d->TreeWindow);
  d->Tree->SetRenderWindow(d->TreeWindow);
  d->Tree->SetInteractor(d->TreeWindow->GetInteractor());
  d->Tree->SetSelectionHub(d->Hub);
  makeDock(1, "B. Densification tree", d->TreeWidget, Qt::RightDockWidgetArea);

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
  auto* panel = new QWidget(this);
  auto* form = new QFormLayout(panel);
  d->Form = form;
  d->SelectionMode = new QComboBox(panel);
  d->SelectionMode->addItems({ "Single (click)", "Brush (drag)", "Frame (drag)", "Ray (click)" });
  d->SelectionMode->setToolTip("Selection in the scene view (left button). Shift adds to the "
                               "selection, Ctrl subtracts; Brush and Frame drag instead of "
                               "rotating (rotate with the middle button then). Keys 1-4.");
  form->addRow("Selection mode", d->SelectionMode);
  d->CameraList = new QListWidget(panel);
  d->CameraList->setMaximumHeight(90);
  d->CameraList->setToolTip("Click a training camera to view the scene from it");
  form->addRow("Cameras", d->CameraList);
  d->ShowFrustums = new QCheckBox("Show frustums (colour: selected Gaussians seen)", panel);
  d->ShowFrustums->setChecked(true);
  form->addRow(d->ShowFrustums);
  connect(d->CameraList,
    &QListWidget::currentRowChanged,
    this,
    [this](int row) { this->OnCameraChosen(row); });
  connect(d->ShowFrustums, &QCheckBox::toggled, this, [this](bool) { this->UpdateFrustums(); });
  auto* itRow = new QWidget(panel);
  auto* itLayout = new QHBoxLayout(itRow);
  itLayout->setContentsMargins(0, 0, 0, 0);
  d->IterationSlider = new QSlider(Qt::Horizontal, itRow);
  d->IterationLabel = new QLabel("-", itRow);
  itLayout->addWidget(d->IterationSlider, 1);
  itLayout->addWidget(d->IterationLabel);
  form->addRow("Iteration", itRow);
  d->IterationRow = itRow;
  d->Overlay = new QComboBox(panel);
  d->Overlay->addItem("True colour");
  form->addRow("Overlay", d->Overlay);
  d->OverlayMin = new QDoubleSpinBox(panel);
  d->OverlayMax = new QDoubleSpinBox(panel);
  d->Threshold = new QDoubleSpinBox(panel);
  for (QDoubleSpinBox* box : { d->OverlayMin, d->OverlayMax, d->Threshold })
  {
    box->setDecimals(4);
    box->setRange(-1e9, 1e9);
  }
  auto* rangeRow = new QWidget(panel);
  auto* rangeLayout = new QHBoxLayout(rangeRow);
  rangeLayout->setContentsMargins(0, 0, 0, 0);
  rangeLayout->addWidget(d->OverlayMin);
  rangeLayout->addWidget(d->OverlayMax);
  form->addRow("Range", rangeRow);
  d->HideOutside = new QCheckBox("Hide Gaussians outside the range", panel);
  form->addRow(d->HideOutside);
  auto* thresholdRow = new QWidget(panel);
  auto* thresholdLayout = new QHBoxLayout(thresholdRow);
  thresholdLayout->setContentsMargins(0, 0, 0, 0);
  d->UseThreshold = new QCheckBox("hide below", thresholdRow);
  thresholdLayout->addWidget(d->UseThreshold);
  thresholdLayout->addWidget(d->Threshold, 1);
  form->addRow("Threshold", thresholdRow);
  d->DimUnselected = new QCheckBox("Dim unselected Gaussians", panel);
  form->addRow(d->DimUnselected);
  d->SplatBudget = new QSpinBox(panel);
  d->SplatBudget->setRange(0, 100000000);
  d->SplatBudget->setSingleStep(50000);
  d->SplatBudget->setSpecialValueText("all");
  d->SplatBudget->setValue(200000);
  d->SplatBudget->setToolTip("Level of detail of the scene view on a hardware OpenGL: at most "
                             "this many splats are drawn (every k-th in depth order); software "
                             "OpenGL draws every Gaussian with the CPU rasteriser. Selection "
                             "and scores always use every Gaussian");
  d->SceneMapper->SetMaximumNumberOfSplats(200000);
  form->addRow("Splats drawn (max)", d->SplatBudget);
  connect(d->SplatBudget,
    QOverload<int>::of(&QSpinBox::valueChanged),
    this,
    [this](int value)
    {
      d->SceneMapper->SetMaximumNumberOfSplats(value);
      d->SceneWindow->Render();
    });
  for (QCheckBox* box : { d->HideOutside, d->UseThreshold, d->DimUnselected })
  {
    connect(box, &QCheckBox::toggled, this, [this](bool) { this->UpdateOverlay(); });
  }
  d->LogText = new QPlainTextEdit(panel);
  d->LogText->setReadOnly(true);
  d->LogText->setMaximumHeight(140);
  form->addRow("Training log", d->LogText);
  d->Table = new QTableWidget(panel);
  d->Table->setColumnCount(10);
  d->Table->setHorizontalHeaderLabels({ "GaussianId",
    "x",
    "y",
    "z",
    "Opacity",
    "Scale",
    "ViewCoverage",
    "BlurScore",
    "NeedleScore",
    "NeedleShape" });
  d->Table->setSortingEnabled(true);
  d->Table->horizontalHeader()->setStretchLastSection(true);
  form->addRow("Selected", d->Table);
  auto* buttons = new QWidget(panel);
  auto* bl = new QHBoxLayout(buttons);
  bl->setContentsMargins(0, 0, 0, 0);
  auto* exportIds = new QPushButton("Export ids (CSV)", buttons);
  auto* exportPly = new QPushButton("Export PLY", buttons);
  auto* deletePly = new QPushButton("Delete to new PLY", buttons);
  bl->addWidget(exportIds);
  bl->addWidget(exportPly);
  bl->addWidget(deletePly);
  form->addRow(buttons);
  connect(exportIds, &QPushButton::clicked, this, [this] { this->ExportIds(); });
  connect(exportPly, &QPushButton::clicked, this, [this] { this->ExportPly(false); });
  connect(deletePly, &QPushButton::clicked, this, [this] { this->ExportPly(true); });
  connect(d->IterationSlider,
    &QSlider::valueChanged,
    this,
    [this](int index)
    {
      if (d->Doc && index >= 0 && index < static_cast<int>(d->Doc->Snapshots.size()))
      {
        d->Hub->SetIteration(d->Doc->Snapshots[index]);
      }
    });
  for (QDoubleSpinBox* box : { d->OverlayMin, d->OverlayMax, d->Threshold })
  {
    connect(box,
      QOverload<double>::of(&QDoubleSpinBox::valueChanged),
      this,
      [this](double) { this->UpdateOverlay(); });
  }
  connect(d->Overlay,
    &QComboBox::currentTextChanged,
    this,
    [this](const QString& name)
    {
      // A new overlay starts with the full range of its array.
      vtkPolyData* scene = d->Doc ? d->Doc->Scene.GetPointer() : nullptr;
      vtkDataArray* array =
        scene ? scene->GetPointData()->GetArray(name.toUtf8().constData()) : nullptr;
      if (array)
      {
        double range[2];
        array->GetRange(range);
        for (QDoubleSpinBox* box : { d->OverlayMin, d->OverlayMax, d->Threshold })
        {
          box->blockSignals(true);
          box->setSingleStep(std::max(1e-4, (range[1] - range[0]) / 100.0));
        }
        d->OverlayMin->setValue(range[0]);
        d->OverlayMax->setValue(range[1]);
        d->Threshold->setValue(range[0]);
        for (QDoubleSpinBox* box : { d->OverlayMin, d->OverlayMax, d->Threshold })
        {
          box->blockSignals(false);
        }
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
        "Vis4GS inputs (*.h5 *.hdf5 *.ply *.spz *.ksplat *.splat *.sog meta.json);;All files (*)");
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
      QString("Mode: ") + d->SelectionMode->itemText(k),
      this,
      [this, k] { d->SelectionMode->setCurrentIndex(k); },
      QKeySequence(QString::number(k + 1)));
  }
  QMenu* view = this->menuBar()->addMenu("&View");
  view->addAction(
    "&Reset scene camera",
    this,
    [this]
    {
      d->SceneRenderer->ResetCamera();
      d->SceneWindow->Render();
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
    [this] { d->IterationSlider->setValue(d->IterationSlider->value() - 1); },
    QKeySequence(Qt::Key_Left));
  view->addAction(
    "&Next snapshot",
    this,
    [this] { d->IterationSlider->setValue(d->IterationSlider->value() + 1); },
    QKeySequence(Qt::Key_Right));
  for (QDockWidget* dock : d->Docks)
  {
    view->addAction(dock->toggleViewAction());
  }
  this->resize(1400, 900);
  this->LayoutForDocument();
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::LayoutForDocument()
{
  const Vis4GSDocument* doc = d->Doc.get();
  const bool tree = doc && doc->Tree != nullptr;
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
  auto showRow = [this](QWidget* field, bool visible)
  {
    field->setVisible(visible);
    if (QWidget* label = d->Form->labelForField(field))
    {
      label->setVisible(visible);
    }
  };
  showRow(d->CameraList, cameras);
  showRow(d->ShowFrustums, cameras);
  showRow(d->IterationRow, snapshots);
  // Sizes: the scene about 55 % of the width; the timeline's three stacked charts 40 % of the
  // height (at least 300 pixels); the tree above the panel about half of the right column.
  // Applied again once the new dock arrangement is laid out (resizeDocks on docks that were
  // just moved is only approximate), the bottom last so that the columns do not push it.
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
  QTimer::singleShot(0, this, sizes);
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::ShowCleanup()
{
  // Under the scene with the timeline when there is one (room for the wide table), else with
  // panel C.
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
  if (d->Welcome)
  {
    d->Welcome->show();
    return;
  }
  // What the case study of the user guide does, as steps a newcomer can follow.
  d->Welcome = new QWidget(this);
  auto* layout = new QVBoxLayout(d->Welcome);
  auto* text = new QLabel(d->Welcome);
  text->setObjectName("welcome");
  text->setWordWrap(true);
  text->setTextFormat(Qt::RichText);
  text->setText("<b>Welcome to Vis4GS.</b> This demo is a 2000-iteration training run with "
                "planted floaters. Try the case study of the user guide:"
                "<ol style='margin-left:-20px'>"
                "<li><b>Find a floater:</b> set <i>Overlay</i> to <i>ViewCoverage</i> (when "
                "the scores are computed, see the status bar) and tick <i>Hide Gaussians "
                "outside the range</i> with the range 0 to 0.3: bright (yellow) splats are "
                "the suspicious ones, seen by few training views.</li>"
                "<li><b>Select it:</b> click one in the scene (Single mode, key 1). Its "
                "training cameras turn red.</li>"
                "<li><b>Its lineage:</b> the tree (B) draws its ancestors in yellow; press L "
                "to zoom to them.</li>"
                "<li><b>Its history:</b> the timeline (D) plots its opacity over the "
                "snapshots; the slider or the Left/Right keys move through them.</li>"
                "</ol>Rotate: left drag; zoom: wheel; R resets the camera.");
  layout->addWidget(text);
  auto* close = new QPushButton("Close this help", d->Welcome);
  layout->addWidget(close, 0, Qt::AlignRight);
  connect(close, &QPushButton::clicked, d->Welcome, &QWidget::hide);
  d->Welcome->setStyleSheet("QWidget { background: #fff8d0; }");
  d->Form->insertRow(0, d->Welcome);
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
  const std::string file = path.toStdString(), cameras = d->SceneCameras;
  // Readers and filters run in a worker thread; progress and the result are posted back to
  // the GUI thread, which keeps handling events (the interface stays responsive).
  d->Worker = QThread::create(
    [this, file, cameras]
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
            QMetaObject::invokeMethod(
              this, [this, f, message] { this->OnProgress(f, message); }, Qt::QueuedConnection);
          },
          cameras);
      }
      catch (const std::exception& e)
      {
        error = QString::fromStdString(e.what());
      }
      QMetaObject::invokeMethod(
        this, [this, doc, error] { this->OnLoaded(doc, error); }, Qt::QueuedConnection);
    });
  d->Worker->start();
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::SetSceneCameras(const QString& cameras)
{
  d->SceneCameras = cameras.toStdString();
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
    std::cerr << "vis4gs view: " << error.toStdString() << "\n";
    if (d->SelfTest)
    {
      QApplication::exit(1);
    }
    return;
  }
  if (d->ScoreWorker)
  {
    // Scores of the previous document: let them finish, their result is dropped.
    d->ScoreWorker->wait();
  }
  StageTimer stage(d->Benchmark, "benchmark:   ");
  if (d->Benchmark)
  {
    std::cout << "benchmark:   document loaded (worker thread) after "
              << stage.GetStart() - d->BenchmarkStart << " s: " << doc->Seconds << " s in Load"
              << std::endl;
  }
  d->Doc = doc;
  d->ScoreCameras = nullptr;
  d->ImageDir.reset();
  d->ScoresDone = false;
  d->Hub->RenderOnChangeOff();
  d->Hub->ClearSelection();
  this->setWindowTitle("Vis4GS - " + QFileInfo(QString::fromStdString(doc->Path)).fileName());
  d->LogText->setPlainText(QString::fromStdString(doc->Summary));
  this->LayoutForDocument();
  d->Tree->SetTree(doc->Tree);
  d->Tree->SetFamilyBands(doc->Bands);
  d->Tree->GetTreeItem()->ResetViewport();
  stage("tree view input");
  d->Timeline->SetMetrics(doc->Metrics);
  d->Timeline->SetTestMetrics(doc->TestMetrics);
  stage("timeline input");
  d->CameraList->clear();
  if (doc->Cameras)
  {
    vtkAbstractArray* names = doc->Cameras->GetColumnByName(vis4gs::arrays::CameraName);
    for (vtkIdType r = 0; names && r < doc->Cameras->GetNumberOfRows(); ++r)
    {
      d->CameraList->addItem(QString::fromStdString(names->GetVariantValue(r).ToString()));
    }
  }
  d->IterationSlider->blockSignals(true);
  d->IterationSlider->setRange(0, std::max(0, static_cast<int>(doc->Snapshots.size()) - 1));
  d->IterationSlider->setValue(d->IterationSlider->maximum());
  d->IterationSlider->setEnabled(doc->Snapshots.size() > 1);
  d->IterationSlider->blockSignals(false);
  d->Frustums->SetInputData(0, doc->Cameras);
  this->UpdateScene(false); // every view is rendered once below
  stage("scene, histogram and panel inputs");
  d->Hub->SetIteration(doc->Iteration);
  d->Hub->RenderOnChangeOn();
  d->SceneRenderer->ResetCamera();
  if (doc->Cameras && doc->Cameras->GetNumberOfRows() > 0)
  {
    d->CameraList->blockSignals(true);
    d->CameraList->setCurrentRow(0);
    d->CameraList->blockSignals(false);
    vtkGaussianCameraUtilities::JumpToCamera(d->SceneRenderer, doc->Cameras, 0);
  }
  if (d->Benchmark)
  {
    for (auto* w : { d->SceneWindow.GetPointer(),
           d->TreeWindow.GetPointer(),
           d->TimelineWindow.GetPointer(),
           d->HistogramWindow.GetPointer() })
    {
      w->Render();
      w->WaitForCompletion();
      if (w == d->SceneWindow)
      {
        std::cout << "benchmark:   splats drawn " << d->SceneMapper->GetLastDrawnCount()
                  << " (budget " << d->SceneMapper->GetMaximumNumberOfSplats() << "), sort "
                  << d->SceneMapper->GetLastSortTime() << " ms, colours "
                  << d->SceneMapper->GetLastColorTime() << " ms, upload "
                  << d->SceneMapper->GetLastUploadTime() << " ms" << std::endl;
      }
      stage(w == d->SceneWindow    ? "first render: scene"
          : w == d->TreeWindow     ? "first render: tree"
          : w == d->TimelineWindow ? "first render: timeline"
                                   : "first render: histogram");
    }
  }
  if (!d->Benchmark) // (the benchmark rendered every view above)
  {
    d->Hub->RenderAll();
  }
  this->statusBar()->showMessage(
    QString("loaded %1 in %2 s").arg(QString::fromStdString(doc->Path)).arg(doc->Seconds), 5000);
  if (d->Benchmark)
  {
    QTimer::singleShot(0, this, [this] { this->RunBenchmark(); });
    return;
  }
  this->StartScores();
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::UpdateScene(bool render)
{
  vtkPolyData* scene = d->Doc ? d->Doc->Scene.GetPointer() : nullptr;
  if (!scene)
  {
    return;
  }
  StageTimer stage(d->Benchmark, "benchmark:     ");
  d->SceneMapper->SetInputData(scene);
  d->Selector->SetScene(scene);
  stage("selector");
  d->Frustums->SetInputData(1, scene);
  d->Histogram->SetInputData(scene);
  d->Cleanup->SetScene(scene, d->ScoreCameras);
  const QString overlay = d->Overlay->currentText();
  const QString hist = d->HistogramArray->currentText();
  d->Overlay->blockSignals(true);
  d->HistogramArray->blockSignals(true);
  d->Overlay->clear();
  d->Overlay->addItem("True colour");
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
      d->Overlay->addItem(array->GetName());
    }
  }
  d->Overlay->setCurrentText(overlay);
  d->HistogramArray->setCurrentText(hist.isEmpty() ? "Opacity" : hist);
  d->Overlay->blockSignals(false);
  d->HistogramArray->blockSignals(false);
  d->Histogram->SetArrayName(d->HistogramArray->currentText().toUtf8().constData());
  d->Histogram->UpdateHistogram();
  stage("histogram");
  this->UpdateOverlay(render);
  stage("overlay");
  this->OnSelectionChanged();
  stage("selection views");
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::UpdateOverlay(bool render)
{
  const QString name = d->Overlay->currentText();
  const std::string array = name.toStdString();
  vtkPolyData* scene = d->Doc ? d->Doc->Scene.GetPointer() : nullptr;
  const bool score =
    scene && name != "True colour" && scene->GetPointData()->GetArray(array.c_str());
  for (QWidget* w : { static_cast<QWidget*>(d->OverlayMin),
         static_cast<QWidget*>(d->OverlayMax),
         static_cast<QWidget*>(d->HideOutside),
         static_cast<QWidget*>(d->UseThreshold),
         static_cast<QWidget*>(d->Threshold) })
  {
    w->setEnabled(score);
  }
  d->SceneMapper->SetDimUnselected(d->DimUnselected->isChecked());
  if (!score)
  {
    d->SceneMapper->SetSplatColoringToTrueColor();
    d->SceneMapper->HideOutsideRangeOff();
    d->Legend->VisibilityOff();
  }
  else
  {
    d->SceneMapper->SetSplatColoringToScore();
    d->SceneMapper->SetScoreArrayName(array.c_str());
    const double lo = d->OverlayMin->value(), hi = d->OverlayMax->value();
    if (hi > lo)
    {
      d->SceneMapper->SetScoreRange(lo, hi);
    }
    else
    {
      d->SceneMapper->AutoScoreRangeOn();
    }
    const bool hide = d->HideOutside->isChecked(), threshold = d->UseThreshold->isChecked();
    d->SceneMapper->SetHideOutsideRange(hide || threshold);
    double visible[2] = { VTK_DOUBLE_MIN, VTK_DOUBLE_MAX };
    if (hide)
    {
      visible[0] = lo;
      visible[1] = hi;
    }
    if (threshold)
    {
      visible[0] = std::max(visible[0], d->Threshold->value());
    }
    d->SceneMapper->SetVisibleRange(visible);
    d->Legend->SetLookupTable(d->SceneMapper->GetScoreLookupTable());
    d->Legend->SetTitle(array.c_str());
    d->Legend->VisibilityOn();
  }
  if (render)
  {
    d->SceneWindow->Render();
  }
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::StartScores()
{
  vtkPolyData* scene = d->Doc ? d->Doc->Scene.GetPointer() : nullptr;
  if (!scene)
  {
    return;
  }
  if (d->ScoreWorker)
  {
    d->ScoresPending = true; // restarted for the new snapshot when this one is done
    return;
  }
  d->ScoresDone = false;
  if (d->Doc->Cameras && !d->ScoreCameras)
  {
    // Embedded training images are written once per document to a temporary folder (in the
    // GUI thread: the log's HDF5 file is only read here).
    try
    {
      d->ImageDir = std::make_unique<QTemporaryDir>();
      d->ScoreCameras = d->Doc->ScoreCameras(d->ImageDir->path().toStdString());
    }
    catch (const std::exception& e)
    {
      this->statusBar()->showMessage(QString("training images: ") + e.what(), 5000);
      d->ScoreCameras = d->Doc->Cameras;
    }
  }
  vtkSmartPointer<vtkPolyData> input = scene;
  vtkSmartPointer<vtkTable> cameras = d->ScoreCameras;
  const bool images = d->Doc->CamerasWithImages > 0;
  d->Progress->setValue(0);
  d->Progress->show();
  this->statusBar()->showMessage(cameras
      ? (images ? "computing View Coverage, Blur, Needle scores and needle shape"
                : "computing View Coverage and needle shape (the log has no training images)")
      : "computing the needle shape (no cameras: no View Coverage, Blur or Needle score)");
  d->ScoreWorker = QThread::create(
    [this, input, cameras, images]
    {
      vtkSmartPointer<vtkPolyData> scores;
      QString error;
      try
      {
        scores = Vis4GSDocument::ComputeScores(input,
          cameras,
          images,
          [this](double f, const std::string& m)
          {
            const QString message = QString::fromStdString(m);
            QMetaObject::invokeMethod(
              this, [this, f, message] { this->OnProgress(f, message); }, Qt::QueuedConnection);
          });
      }
      catch (const std::exception& e)
      {
        error = QString::fromStdString(e.what());
      }
      QMetaObject::invokeMethod(
        this,
        [this, input, scores, error]
        {
          d->ScoreWorker->wait();
          d->ScoreWorker->deleteLater();
          d->ScoreWorker = nullptr;
          d->Progress->hide();
          vtkPolyData* current = d->Doc ? d->Doc->Scene.GetPointer() : nullptr;
          if (!scores)
          {
            this->statusBar()->showMessage("scores: " + error, 5000);
            std::cerr << "vis4gs view: scores: " << error.toStdString() << "\n";
          }
          else if (current == input.GetPointer())
          {
            for (int a = 0; a < scores->GetPointData()->GetNumberOfArrays(); ++a)
            {
              current->GetPointData()->AddArray(scores->GetPointData()->GetAbstractArray(a));
            }
            current->Modified();
            this->statusBar()->showMessage("scores computed", 3000);
            this->UpdateScene(); // overlay and histogram lists
          }
          if (d->ScoresPending)
          {
            d->ScoresPending = false;
            this->StartScores();
            return;
          }
          d->ScoresDone = true;
          if (d->SelfTest && !d->SelfTestStarted)
          {
            d->SelfTestStarted = true;
            QTimer::singleShot(
              200, this, [this] { QApplication::exit(this->RunSelfTest() ? 0 : 1); });
          }
        },
        Qt::QueuedConnection);
    });
  d->ScoreWorker->start();
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::UpdateFrustums()
{
  const bool show = d->Doc && d->Doc->Cameras && d->ShowFrustums->isChecked();
  d->FrustumActor->SetVisibility(show);
  if (show)
  {
    vtkNew<vtkIdTypeArray> ids;
    d->Hub->GetSelectedIds(ids);
    d->Frustums->SetSelectedIds(ids);
    d->Frustums->Update();
    double range[2] = { 0, 1 };
    if (vtkDataArray* counts =
          d->Frustums->GetOutput()->GetPointData()->GetArray("VisibleSelectedCount"))
    {
      counts->GetRange(range);
    }
    d->FrustumMapper->SetScalarRange(0, std::max(1.0, range[1]));
  }
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::OnCameraChosen(int row)
{
  if (!d->Doc || !d->Doc->Cameras || row < 0)
  {
    return;
  }
  if (vtkGaussianCameraUtilities::JumpToCamera(d->SceneRenderer, d->Doc->Cameras, row))
  {
    d->SceneWindow->Render();
  }
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::OnSceneMouse(unsigned long event, bool& abort)
{
  vtkRenderWindowInteractor* i = d->SceneWindow->GetInteractor();
  const int mode = d->SelectionMode->currentIndex();
  const int* p = i->GetEventPosition();
  const int combine = i->GetShiftKey() ? vtkGaussianSelectionHub::ADD
    : i->GetControlKey()               ? vtkGaussianSelectionHub::SUBTRACT
                                       : vtkGaussianSelectionHub::REPLACE;
  const bool drag = mode == BRUSH || mode == FRAME;
  auto drawBand = [this, mode]()
  {
    vtkNew<vtkPoints> points;
    vtkNew<vtkCellArray> lines;
    std::vector<std::array<double, 2>> corners = d->Stroke;
    if (mode == FRAME && d->Stroke.size() >= 2)
    {
      const auto a = d->Stroke.front(), b = d->Stroke.back();
      corners = { a, { b[0], a[1] }, b, { a[0], b[1] }, a };
    }
    std::vector<vtkIdType> ids;
    for (const auto& c : corners)
    {
      ids.push_back(points->InsertNextPoint(c[0], c[1], 0.0));
    }
    if (ids.size() >= 2)
    {
      lines->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
    }
    d->Band->SetPoints(points);
    d->Band->SetLines(lines);
    d->Band->Modified();
    d->SceneWindow->Render();
  };
  if (event == vtkCommand::LeftButtonPressEvent)
  {
    d->PressPosition[0] = p[0];
    d->PressPosition[1] = p[1];
    if (drag)
    {
      d->Dragging = true;
      d->Stroke.assign(1, { static_cast<double>(p[0]), static_cast<double>(p[1]) });
      abort = true;
    }
  }
  else if (event == vtkCommand::MouseMoveEvent)
  {
    if (d->Dragging)
    {
      if (mode == FRAME && d->Stroke.size() > 1)
      {
        d->Stroke.back() = { static_cast<double>(p[0]), static_cast<double>(p[1]) };
      }
      else
      {
        d->Stroke.push_back({ static_cast<double>(p[0]), static_cast<double>(p[1]) });
      }
      drawBand();
      abort = true;
    }
  }
  else if (event == vtkCommand::LeftButtonReleaseEvent)
  {
    if (d->Dragging)
    {
      d->Dragging = false;
      abort = true;
      std::vector<std::array<double, 2>> points = d->Stroke;
      if (mode == FRAME)
      {
        points = { d->Stroke.front(), { static_cast<double>(p[0]), static_cast<double>(p[1]) } };
      }
      d->Stroke.clear();
      drawBand();
      this->SelectInScene(mode, points, combine);
    }
  }
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::OnSceneClick()
{
  vtkRenderWindowInteractor* i = d->SceneWindow->GetInteractor();
  const int mode = d->SelectionMode->currentIndex();
  const int* p = i->GetEventPosition();
  if ((mode == SINGLE || mode == RAY) &&
    std::abs(p[0] - d->PressPosition[0]) + std::abs(p[1] - d->PressPosition[1]) < 3)
  {
    const int combine = i->GetShiftKey() ? vtkGaussianSelectionHub::ADD
      : i->GetControlKey()               ? vtkGaussianSelectionHub::SUBTRACT
                                         : vtkGaussianSelectionHub::REPLACE;
    this->SelectInScene(
      mode, { { static_cast<double>(p[0]), static_cast<double>(p[1]) } }, combine);
  }
}

//------------------------------------------------------------------------------
long long Vis4GSMainWindow::SelectInScene(int mode,
  const std::vector<std::array<double, 2>>& points,
  int combine)
{
  vtkPolyData* scene = d->Doc ? d->Doc->Scene.GetPointer() : nullptr;
  if (!scene || points.empty())
  {
    return -1;
  }
  // The selector computes this mode's pick (REPLACE in its own state); the hub, which also
  // holds selections made in the other views, combines it with the current selection.
  d->Selector->SetScene(scene);
  d->Selector->SetModifier(vtkGaussianSelector::REPLACE);
  vtkIdType count = -1;
  switch (mode)
  {
    case SINGLE:
      count = d->Selector->SelectSingle(points[0][0], points[0][1]);
      break;
    case RAY:
      count = d->Selector->SelectRay(points[0][0], points[0][1]);
      break;
    case FRAME:
    {
      const auto b = points.size() > 1 ? points[1] : points[0];
      count = d->Selector->SelectFrame(points[0][0], points[0][1], b[0], b[1]);
      break;
    }
    case BRUSH:
    {
      vtkNew<vtkPoints> stroke;
      for (const auto& q : points)
      {
        stroke->InsertNextPoint(q[0], q[1], 0.0);
      }
      count = d->Selector->SelectBrush(stroke);
      break;
    }
    default:
      return -1;
  }
  if (count < 0)
  {
    return -1;
  }
  vtkIdTypeArray* ids = d->Selector->GetSelectedIds();
  if (count == 0 && combine == vtkGaussianSelectionHub::REPLACE)
  {
    d->Hub->ClearSelection();
  }
  else if (ids && ids->GetNumberOfTuples() > 0)
  {
    d->Hub->SelectIds(ids, combine);
  }
  const char* names[] = { "Single", "Brush", "Frame", "Ray" };
  this->statusBar()->showMessage(QString("%1: %2 %3 picked in %4 ms")
                                   .arg(names[mode])
                                   .arg(count)
                                   .arg(count == 1 ? "Gaussian" : "Gaussians")
                                   .arg(d->Selector->GetLastSelectionTime(), 0, 'f', 1),
    5000);
  return count;
}

//------------------------------------------------------------------------------
std::vector<long long> Vis4GSMainWindow::GetLastRayHits() const
{
  std::vector<long long> hits;
  vtkIdTypeArray* ids = d->Selector->GetRayHitIds();
  for (vtkIdType k = 0; ids && k < ids->GetNumberOfTuples(); ++k)
  {
    hits.push_back(ids->GetValue(k));
  }
  return hits;
}

//------------------------------------------------------------------------------
long long Vis4GSMainWindow::PickInScene(int x, int y)
{
  const long long n = this->SelectInScene(SINGLE,
    { { static_cast<double>(x), static_cast<double>(y) } },
    vtkGaussianSelectionHub::REPLACE);
  vtkIdTypeArray* ids = d->Selector->GetSelectedIds();
  return n == 1 && ids && ids->GetNumberOfTuples() == 1 ? ids->GetValue(0) : -1;
}

//------------------------------------------------------------------------------
long long Vis4GSMainWindow::GetSceneHighlightCount() const
{
  return d->HighlightCount;
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::OnSelectionChanged()
{
  vtkPolyData* scene = d->Doc ? d->Doc->Scene.GetPointer() : nullptr;
  const auto& selected = d->Hub->GetSelectedIdVector();
  d->Table->setSortingEnabled(false);
  d->Table->setRowCount(0);
  d->HighlightCount = 0;
  if (scene)
  {
    vtkNew<vtkIdTypeArray> rows;
    vtkGaussianSelectionHub::IdsToIndices(selected.data(),
      static_cast<vtkIdType>(selected.size()),
      scene->GetPointData()->GetArray("GaussianId"),
      rows);
    d->HighlightCount = rows->GetNumberOfTuples();
    vtkPointData* pd = scene->GetPointData();
    vtkDataArray* columns[] = { pd->GetArray("GaussianId"),
      nullptr,
      nullptr,
      nullptr,
      pd->GetArray("Opacity"),
      pd->GetArray("Scale"),
      pd->GetArray(vis4gs::arrays::ViewCoverage),
      pd->GetArray(vis4gs::arrays::BlurScore),
      pd->GetArray(vis4gs::arrays::NeedleScore),
      pd->GetArray(vis4gs::arrays::NeedleShape) };
    const int shown = static_cast<int>(std::min<vtkIdType>(rows->GetNumberOfTuples(), 1000));
    d->Table->setRowCount(shown);
    for (int k = 0; k < shown; ++k)
    {
      const vtkIdType r = rows->GetValue(k);
      double p[3];
      scene->GetPoint(r, p);
      auto number = [](double value)
      {
        auto* item = new QTableWidgetItem;
        item->setData(Qt::DisplayRole, value);
        return item;
      };
      for (int c = 0; c < 10; ++c)
      {
        double value = NAN;
        if (c >= 1 && c <= 3)
        {
          value = p[c - 1];
        }
        else if (c == 5 && columns[5])
        {
          value = std::max({ columns[5]->GetComponent(r, 0),
            columns[5]->GetComponent(r, 1),
            columns[5]->GetComponent(r, 2) });
        }
        else if (columns[c])
        {
          value = columns[c]->GetComponent(r, 0);
        }
        d->Table->setItem(k, c, number(value));
      }
    }
  }
  d->Table->setSortingEnabled(true);
  // Markers (a point at the centre) for small selections, drawn over the splats.
  {
    vtkNew<vtkPoints> points;
    vtkNew<vtkCellArray> verts;
    if (scene && d->HighlightCount <= 200)
    {
      vtkNew<vtkIdTypeArray> rows;
      vtkGaussianSelectionHub::IdsToIndices(selected.data(),
        static_cast<vtkIdType>(selected.size()),
        scene->GetPointData()->GetArray("GaussianId"),
        rows);
      for (vtkIdType k = 0; k < rows->GetNumberOfTuples(); ++k)
      {
        const vtkIdType v = points->InsertNextPoint(scene->GetPoint(rows->GetValue(k)));
        verts->InsertNextCell(1, &v);
      }
    }
    d->Markers->SetPoints(points);
    d->Markers->SetVerts(verts);
    d->Markers->Modified();
  }
  vtkNew<vtkIdTypeArray> selectedIds;
  d->Hub->GetSelectedIds(selectedIds);
  d->SceneMapper->SetSelectedIds(selectedIds);
  this->UpdateFrustums();
  // History of the selection (first 16) for the timeline.
  if (d->Doc && d->Doc->Log)
  {
    std::vector<std::int64_t> ids(
      selected.begin(), selected.begin() + std::min<std::size_t>(16, selected.size()));
    try
    {
      d->Timeline->SetHistory(d->Doc->History(ids));
    }
    catch (const std::exception& e)
    {
      this->statusBar()->showMessage(QString("history: ") + e.what(), 5000);
    }
  }
  this->statusBar()->showMessage(QString("%1 Gaussians selected").arg(selected.size()), 3000);
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::OnIterationChanged(int iteration)
{
  if (!d->Doc || !d->Doc->Log || iteration < 0)
  {
    return;
  }
  d->IterationLabel->setText(QString::number(iteration));
  const auto& s = d->Doc->Snapshots;
  auto it = std::lower_bound(s.begin(), s.end(), d->Doc->Log->FindNearestSnapshot(iteration));
  if (it != s.end())
  {
    d->IterationSlider->blockSignals(true);
    d->IterationSlider->setValue(static_cast<int>(it - s.begin()));
    d->IterationSlider->blockSignals(false);
  }
  if (d->Doc->Log->FindNearestSnapshot(iteration) != d->Doc->Iteration)
  {
    // The snapshot is read in this thread (the views need it at once, and the log's reader
    // is not shared with a worker): a busy bar and message are painted before it starts.
    const bool shown = d->Progress->isVisible();
    d->Progress->setRange(0, 0);
    d->Progress->show();
    this->statusBar()->showMessage(QString("reading the snapshot of iteration %1")
                                     .arg(d->Doc->Log->FindNearestSnapshot(iteration)));
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
      if (!d->Benchmark)
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
  QFile file(path);
  if (!file.open(QIODevice::WriteOnly | QIODevice::Text))
  {
    this->statusBar()->showMessage(path + ": could not be written", 5000);
    return;
  }
  QTextStream out(&file);
  out << "GaussianId\n";
  for (vtkIdType id : d->Hub->GetSelectedIdVector())
  {
    out << static_cast<long long>(id) << "\n";
  }
  this->statusBar()->showMessage(path + " written", 3000);
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::ExportPly(bool deleteSelection)
{
  vtkPolyData* scene = d->Doc ? d->Doc->Scene.GetPointer() : nullptr;
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
    "PLY (*.ply);;SPZ v4, quantised for web viewers (*.spz);;" + compressedFilter,
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
  // Keep (or drop) the selected Gaussians, then write through Core's PLY writer.
  vtkDataArray* ids = scene->GetPointData()->GetArray("GaussianId");
  vtkNew<vtkPolyData> subset;
  vtkNew<vtkPoints> points;
  subset->GetPointData()->CopyAllocate(scene->GetPointData());
  for (vtkIdType i = 0; ids && i < scene->GetNumberOfPoints(); ++i)
  {
    if (d->Hub->IsSelected(static_cast<vtkIdType>(ids->GetComponent(i, 0))) != deleteSelection)
    {
      const vtkIdType j = points->InsertNextPoint(scene->GetPoint(i));
      subset->GetPointData()->CopyData(scene->GetPointData(), i, j);
    }
  }
  subset->SetPoints(points);
  subset->GetFieldData()->ShallowCopy(scene->GetFieldData());
  vis4gs::GaussianCloud cloud;
  std::string error;
  if (!vis4gs::PolyDataToGaussianCloud(subset, cloud, &error))
  {
    this->statusBar()->showMessage(QString::fromStdString(error), 5000);
    return;
  }
  try
  {
    if (path.endsWith(".spz", Qt::CaseInsensitive))
    {
      // Lossy: say how much was lost and what could not be stored.
      const vis4gs::SpzWriteReport r = vis4gs::WriteSpz(path.toStdString(), cloud);
      this->statusBar()->showMessage(QString("%1: %2 Gaussians written as SPZ v4, %3 left out; "
                                             "max error: position %4, log-scale %5, opacity %6, "
                                             "colour %7, SH %8")
                                       .arg(path)
                                       .arg(r.Written)
                                       .arg(r.LeftOut)
                                       .arg(r.Position.Max, 0, 'g', 3)
                                       .arg(r.LogScale.Max, 0, 'g', 3)
                                       .arg(r.Opacity.Max, 0, 'g', 3)
                                       .arg(r.Color.Max, 0, 'g', 3)
                                       .arg(r.SH.Max, 0, 'g', 3),
        10000);
      return;
    }
    if (path.endsWith(".compressed.ply", Qt::CaseInsensitive))
    {
      const auto report = vis4gs::WriteCompressedPly(path.toStdString(), cloud);
      this->statusBar()->showMessage(
        path + ": " + QString::fromStdString(vis4gs::DescribeQuantisation(report)), 15000);
      return;
    }
    vis4gs::WriteGaussianPly(path.toStdString(), cloud);
    this->statusBar()->showMessage(
      QString("%1: %2 Gaussians written").arg(path).arg(points->GetNumberOfPoints()), 5000);
  }
  catch (const std::exception& e)
  {
    this->statusBar()->showMessage(e.what(), 5000);
  }
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
void Vis4GSMainWindow::SetSelfTest(const QString& directory)
{
  d->SelfTest = true;
  d->SelfTestDir = directory;
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::SetSplatBudget(long long splats)
{
  d->SplatBudget->setValue(static_cast<int>(std::min<long long>(splats, 100000000)));
  d->SceneMapper->SetMaximumNumberOfSplats(static_cast<vtkIdType>(splats));
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::SetBaseline(const QString& directory, int tolerance, double fraction)
{
  d->BaselineDir = directory;
  d->BaselineTolerance = tolerance;
  d->BaselineFraction = fraction;
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::SetBenchmark(double startSeconds, double startCpuSeconds)
{
  d->Benchmark = true;
  d->BenchmarkStart = startSeconds;
  d->BenchmarkCpuStart = startCpuSeconds;
}

//------------------------------------------------------------------------------
bool Vis4GSMainWindow::RunSelfTest()
{
  bool ok = true;
  auto check = [&ok](bool condition, const std::string& what)
  {
    std::cout << (condition ? "ok: " : "FAILED: ") << what << std::endl;
    ok = ok && condition;
  };
  QDir().mkpath(d->SelfTestDir);
  vtkPolyData* scene = d->Doc ? d->Doc->Scene.GetPointer() : nullptr;
  check(scene && scene->GetNumberOfPoints() > 0, "the scene has Gaussians");
  if (!scene)
  {
    return false;
  }
  // The dock layout of the document (LayoutForDocument) settles over several posted layout
  // requests; the picks below need the scene view at its final size.
  for (int k = 0; k < 5; ++k)
  {
    QApplication::sendPostedEvents();
    QApplication::processEvents();
  }
  d->Hub->RenderAll();
  {
    // The layout shows exactly the views with data, and they fill the window between the
    // menu and the status bar (no large empty area).
    const bool has[5] = { true, d->Doc->Tree != nullptr, true, d->Doc->Metrics != nullptr, true };
    long long covered = 0;
    for (int k = 0; k < 5; ++k)
    {
      const bool shown = d->Docks[k]->isVisible();
      check(shown == has[k],
        std::string("the ") + DockNames[k] + " view is " + (shown ? "shown" : "hidden") +
          " (it has " + (has[k] ? "data" : "no data") + ")");
      if (shown)
      {
        covered += static_cast<long long>(d->Docks[k]->width()) * d->Docks[k]->height();
        check(d->Docks[k]->width() >= 200 && d->Docks[k]->height() >= 150,
          std::string("the ") + DockNames[k] + " view is usable (" +
            std::to_string(d->Docks[k]->width()) + "x" + std::to_string(d->Docks[k]->height()) +
            " pixels)");
      }
    }
    const long long area = static_cast<long long>(this->width()) *
      (this->height() - this->menuBar()->height() - this->statusBar()->height());
    check(covered >= 0.9 * area,
      "the views cover " + std::to_string(100 * covered / std::max(1LL, area)) +
        " % of the window (at least 90 %)");
    if (d->Doc->Metrics)
    {
      check(d->Docks[3]->height() >= 280,
        "the timeline's three charts have " + std::to_string(d->Docks[3]->height()) +
          " pixels of height (at least 280)");
    }
    if (d->Welcome)
    {
      // The welcome panel is shown and names controls that exist (it tells what to click).
      auto* text = d->Welcome->findChild<QLabel*>("welcome");
      auto* overlay = qobject_cast<QLabel*>(d->Form->labelForField(d->Overlay));
      const QString welcome = text ? text->text() : QString();
      check(d->Welcome->isVisible() && overlay && welcome.contains(overlay->text()) &&
          welcome.contains(d->HideOutside->text()) &&
          (!d->Doc->Cameras || d->Overlay->findText(vis4gs::arrays::ViewCoverage) >= 0) &&
          welcome.contains(vis4gs::arrays::ViewCoverage),
        "the welcome panel is shown and its steps name the panel's controls");
    }
    const std::string& summary = d->Doc->Summary;
    check(summary.find("loaded in") != std::string::npos &&
        summary.find("( )") == std::string::npos && summary.find("()") == std::string::npos,
      "the load summary names the time of every stage (no empty parentheses)");
  }
  vtkTable* cameras = d->Doc->Cameras;
  vtkPointData* pd = scene->GetPointData();
  vtkDataArray* ids = pd->GetArray("GaussianId");
  vtkDataArray* coverage = pd->GetArray(vis4gs::arrays::ViewCoverage);
  vtkDataArray* opacity = pd->GetArray("Opacity");
  check(pd->GetArray(vis4gs::arrays::NeedleShape) != nullptr, "the needle shape was computed");
  if (cameras)
  {
    check(coverage != nullptr, "View Coverage was computed (the log has cameras)");
  }
  if (d->Doc->CamerasWithImages > 0)
  {
    check(pd->GetArray(vis4gs::arrays::BlurScore) && pd->GetArray(vis4gs::arrays::NeedleScore),
      "Blur and Needle scores were computed (the log has training images)");
  }

  // 1. Select a floater in the scene with the Single mode, at the pixel where its centre
  //    projects: the visible Gaussians (opacity >= 0.1) of lowest View Coverage first (the
  //    demo's root-cause criterion), seen from the training cameras in turn; without scores,
  //    the newest Gaussians (longest lineages).
  std::vector<vtkIdType> candidates(scene->GetNumberOfPoints());
  for (vtkIdType i = 0; i < scene->GetNumberOfPoints(); ++i)
  {
    candidates[i] = i;
  }
  if (coverage && opacity)
  {
    candidates.erase(std::remove_if(candidates.begin(),
                       candidates.end(),
                       [&](vtkIdType i) {
                         return !(opacity->GetComponent(i, 0) >= 0.1) ||
                           !std::isfinite(coverage->GetComponent(i, 0));
                       }),
      candidates.end());
    std::stable_sort(candidates.begin(),
      candidates.end(),
      [&](vtkIdType a, vtkIdType b)
      { return coverage->GetComponent(a, 0) < coverage->GetComponent(b, 0); });
  }
  else
  {
    std::stable_sort(candidates.begin(),
      candidates.end(),
      [&](vtkIdType a, vtkIdType b) { return ids->GetComponent(a, 0) > ids->GetComponent(b, 0); });
  }
  candidates.resize(std::min<std::size_t>(candidates.size(), 40));
  const vtkIdType views = cameras ? cameras->GetNumberOfRows() : 0;
  // Training cameras (Split 0) first, then the others.
  std::vector<vtkIdType> order;
  vtkAbstractArray* split =
    cameras ? cameras->GetColumnByName(vis4gs::arrays::CameraSplit) : nullptr;
  int trainingViews = 0;
  for (int pass = 0; pass < 2; ++pass)
  {
    for (vtkIdType v = 0; v < views; ++v)
    {
      const bool training = !split || split->GetVariantValue(v).ToInt() == 0;
      trainingViews += pass == 0 && training ? 1 : 0;
      if (training == (pass == 0))
      {
        order.push_back(v);
      }
    }
  }
  // Without cameras: five orbit views around the scene's bounds (v = -1 ... -5).
  const int orbitViews = 5;
  for (int k = 0; order.empty() && k < orbitViews; ++k)
  {
    order.push_back(-1 - k);
  }
  auto setView = [&](vtkIdType v)
  {
    if (v >= 0)
    {
      vtkGaussianCameraUtilities::JumpToCamera(d->SceneRenderer, cameras, v);
      return;
    }
    const int k = static_cast<int>(-1 - v);
    vtkCamera* camera = d->SceneRenderer->GetActiveCamera();
    camera->SetFocalPoint(0, 0, 0);
    camera->SetPosition(0, 0, 1);
    camera->SetViewUp(0, 1, 0);
    d->SceneRenderer->ResetCamera(scene->GetBounds());
    camera->Azimuth(360.0 / orbitViews * k);
    camera->Elevation(k % 2 == 0 ? 25.0 : -25.0);
    camera->OrthogonalizeViewUp();
    d->SceneRenderer->ResetCameraClippingRange();
  };
  int width = d->SceneWindow->GetSize()[0], height = d->SceneWindow->GetSize()[1];
  d->Selector->SetScene(scene);
  {
    // One definition per mode, on every scene: at a grid of pixels of several views, the
    // Gaussian Single picks is among those Ray returns (the footprints covering the pixel in
    // the drawn frame), and Ray lists them in depth order with alpha in [1/255, 0.99].
    // The file's first three cameras and three orbit views.
    std::vector<vtkIdType> gridViews;
    for (std::size_t n = 0; n < order.size() && order[n] >= 0 && n < 3; ++n)
    {
      gridViews.push_back(order[n]);
    }
    for (vtkIdType v = -1; v >= -3; --v)
    {
      gridViews.push_back(v);
    }
    int tested = 0, members = 0, ordered = 0, nonEmpty = 0;
    std::string firstFailure;
    for (vtkIdType view : gridViews)
    {
      setView(view);
      d->SceneWindow->Render();
      for (int gy = 1; gy <= 7; ++gy)
      {
        for (int gx = 1; gx <= 7; ++gx)
        {
          const double sx = std::floor(width * gx / 8.0), sy = std::floor(height * gy / 8.0);
          d->Selector->SetModifier(vtkGaussianSelector::REPLACE);
          if (d->Selector->SelectSingle(sx, sy) < 0)
          {
            continue;
          }
          vtkIdTypeArray* single = d->Selector->GetSelectedIds();
          const vtkIdType pick = single->GetNumberOfTuples() == 1 ? single->GetValue(0) : -1;
          if (d->Selector->SelectRay(sx, sy) < 0)
          {
            continue;
          }
          ++tested;
          vtkIdTypeArray* ray = d->Selector->GetRayHitIds();
          vtkDoubleArray* depth = d->Selector->GetRayHitDistances();
          vtkDoubleArray* alpha = d->Selector->GetRayHitAlphas();
          bool found = pick < 0, sorted = true;
          for (vtkIdType k = 0; k < ray->GetNumberOfTuples(); ++k)
          {
            found = found || ray->GetValue(k) == pick;
            sorted = sorted && (k == 0 || depth->GetValue(k - 1) <= depth->GetValue(k)) &&
              alpha->GetValue(k) >= 1.0 / 255.0 - 1e-7 && alpha->GetValue(k) <= 0.99 + 1e-7;
          }
          nonEmpty += pick >= 0 ? 1 : 0;
          members += found ? 1 : 0;
          ordered += sorted ? 1 : 0;
          if ((!found || !sorted) && firstFailure.empty())
          {
            firstFailure = " (first failure: view " + std::to_string(view) + ", pixel " +
              std::to_string(static_cast<int>(sx)) + "," + std::to_string(static_cast<int>(sy)) +
              ", Single " + std::to_string(pick) + ", " + std::to_string(ray->GetNumberOfTuples()) +
              " on the ray)";
          }
        }
      }
    }
    check(tested > 0 && members == tested && ordered == tested,
      "Single's pick is on the Ray at " + std::to_string(members) + " of " +
        std::to_string(tested) + " pixels of " + std::to_string(gridViews.size()) + " views (" +
        std::to_string(nonEmpty) + " with a pick), Ray in depth order with alpha in " +
        "[1/255, 0.99] at " + std::to_string(ordered) + firstFailure);
  }
  vtkIdType target = -1, targetId = -1, view = -1;
  double display[3] = { 0, 0, 0 };
  // Whether candidate c is the front-most Gaussian at the pixel where its centre projects in
  // the current view (then it becomes the target).
  auto tryCandidate = [&](vtkIdType c, vtkIdType v)
  {
    const vtkIdType id = static_cast<vtkIdType>(ids->GetComponent(c, 0));
    double p[3];
    scene->GetPoint(c, p);
    d->SceneRenderer->SetWorldPoint(p[0], p[1], p[2], 1.0);
    d->SceneRenderer->WorldToDisplay();
    d->SceneRenderer->GetDisplayPoint(display);
    display[0] = std::round(display[0]);
    display[1] = std::round(display[1]);
    if (display[0] < 1 || display[1] < 1 || display[0] > width - 2 || display[1] > height - 2 ||
      display[2] <= 0 || display[2] >= 1)
    {
      return false;
    }
    d->Selector->SetModifier(vtkGaussianSelector::REPLACE);
    vtkIdTypeArray* picked = d->Selector->GetSelectedIds();
    if (d->Selector->SelectSingle(display[0], display[1]) == 1 &&
      picked->GetNumberOfTuples() == 1 && picked->GetValue(0) == id)
    {
      target = c;
      targetId = id;
      view = v;
      return true;
    }
    return false;
  };
  for (std::size_t n = 0; n < candidates.size() && target < 0; ++n)
  {
    for (std::size_t m = 0; m < order.size() && target < 0; ++m)
    {
      setView(order[m]);
      tryCandidate(candidates[n], order[m]);
    }
  }
  // None of the preferred candidates is front-most anywhere (e.g. a file without scores or
  // lineage, where the newest are arbitrary): the most opaque Gaussians, view by view (one
  // projection per view).
  if (target < 0 && opacity)
  {
    std::vector<vtkIdType> opaque(static_cast<std::size_t>(scene->GetNumberOfPoints()));
    std::iota(opaque.begin(), opaque.end(), vtkIdType(0));
    std::stable_sort(opaque.begin(),
      opaque.end(),
      [&](vtkIdType a, vtkIdType b)
      { return opacity->GetComponent(a, 0) > opacity->GetComponent(b, 0); });
    opaque.resize(std::min<std::size_t>(opaque.size(), 2000));
    for (std::size_t m = 0; m < order.size() && target < 0; ++m)
    {
      setView(order[m]);
      for (std::size_t n = 0; n < opaque.size() && target < 0; ++n)
      {
        tryCandidate(opaque[n], order[m]);
      }
    }
  }
  check(target >= 0, "a floater candidate is the front-most Gaussian at its projected pixel");
  if (target < 0)
  {
    return false;
  }
  if (view >= 0)
  {
    d->CameraList->blockSignals(true);
    d->CameraList->setCurrentRow(static_cast<int>(view));
    d->CameraList->blockSignals(false);
  }
  const int x = static_cast<int>(display[0]), y = static_cast<int>(display[1]);
  const long long picked = this->PickInScene(x, y);
  std::ostringstream what;
  what << "Single mode picked Gaussian " << picked << " at pixel (" << x << ", " << y << ")";
  if (view >= 0)
  {
    what << " of training camera "
         << cameras->GetColumnByName(vis4gs::arrays::CameraName)->GetVariantValue(view).ToString();
  }
  if (coverage)
  {
    what << ", View Coverage " << coverage->GetComponent(target, 0);
  }
  check(picked == targetId, what.str());
  check(d->Hub->GetNumberOfSelectedIds() == 1, "the hub holds one selected Gaussian");
  check(this->GetSceneHighlightCount() == 1, "the scene highlights it");
  vtkGaussianTreeItem* item = d->Tree->GetTreeItem();
  vtkNew<vtkIdTypeArray> lineage, history;
  if (d->Doc->Tree)
  {
    item->UpdateLevelOfDetail();
    item->GetLineageVertices(lineage);
    vtkDataArray* treeIds = d->Doc->Tree->GetVertexData()->GetArray("GaussianId");
    vtkDataArray* born = d->Doc->Tree->GetVertexData()->GetArray("LayoutX");
    std::ostringstream chain;
    bool containsTarget = false;
    for (vtkIdType k = 0; k < lineage->GetNumberOfTuples(); ++k)
    {
      const vtkIdType v = lineage->GetValue(k);
      const vtkIdType gid = static_cast<vtkIdType>(treeIds->GetComponent(v, 0));
      containsTarget = containsTarget || gid == targetId;
      chain << (k ? ", " : "") << gid;
      if (born)
      {
        chain << " (born " << born->GetComponent(v, 0) << ")";
      }
    }
    check(containsTarget && lineage->GetNumberOfTuples() >= 1,
      "the tree shows its lineage (" + std::to_string(lineage->GetNumberOfTuples()) +
        " nodes: " + chain.str() + ")");
    item->GetVisibleVertices(history);
    std::set<vtkIdType> visible(
      history->GetPointer(0), history->GetPointer(0) + history->GetNumberOfTuples());
    bool allShown = true;
    for (vtkIdType k = 0; k < lineage->GetNumberOfTuples(); ++k)
    {
      allShown = allShown && visible.count(lineage->GetValue(k));
    }
    check(allShown, "the whole lineage is drawn at the overview zoom");
    item->ZoomToSelection();
  }
  if (d->Doc->Log)
  {
    check(d->Timeline->GetNumberOfHistoryLines() == 1, "the timeline shows its history");
    vtkSmartPointer<vtkTable> h = d->Doc->History({ static_cast<std::int64_t>(targetId) });
    std::cout << "info: Gaussian " << targetId << " over the snapshots (iteration: opacity, "
              << "largest scale):";
    for (vtkIdType r = 0; r < h->GetNumberOfRows(); ++r)
    {
      std::cout << " " << h->GetValueByName(r, "Iteration").ToInt() << ": "
                << h->GetValueByName(r, "Opacity").ToDouble() << ", "
                << h->GetValueByName(r, "Scale").ToDouble() << ";";
    }
    std::cout << std::endl;
  }
  if (cameras)
  {
    vtkDataArray* counts =
      d->Frustums->GetOutput()->GetPointData()->GetArray("VisibleSelectedCount");
    vtkDataArray* index = d->Frustums->GetOutput()->GetPointData()->GetArray("CameraIndex");
    int seeing = 0, trainingSeeing = 0;
    for (vtkIdType k = 0; counts && index && k < counts->GetNumberOfTuples(); k += 5)
    {
      const vtkIdType row = static_cast<vtkIdType>(index->GetComponent(k, 0));
      const bool seen = counts->GetComponent(k, 0) > 0;
      seeing += seen ? 1 : 0;
      trainingSeeing += seen && (!split || split->GetVariantValue(row).ToInt() == 0) ? 1 : 0;
    }
    check(seeing >= 1,
      "the frustums of " + std::to_string(seeing) + " of " + std::to_string(views) +
        " cameras are coloured as seeing the selected Gaussian");
    if (coverage)
    {
      // Independent paths: the frustum counts (CountVisibleInViews on the selection) and
      // View Coverage (the score filter) use the same footprint definition (DESIGN §4).
      const double expected = coverage->GetComponent(target, 0) * trainingViews;
      check(std::abs(trainingSeeing - expected) < 1e-6,
        "training frustums seeing it (" + std::to_string(trainingSeeing) +
          ") = View Coverage x training views (" + std::to_string(expected) + ")");
    }
  }
  d->Hub->RenderAll();
  QApplication::processEvents();
  for (const char* name : DockNames)
  {
    this->SaveScreenshot(name, d->SelfTestDir + "/selected-in-scene-" + name + ".png");
  }
  this->SaveScreenshot("window", d->SelfTestDir + "/selected-in-scene-window.png");
  // The same views with nothing selected: the baseline comparison must fail on these, or it
  // would not notice a missing highlight (Documentation/dev/TESTING.md, masked baselines).
  d->Hub->ClearSelection();
  d->Hub->RenderAll();
  QApplication::processEvents();
  for (const char* name : { "scene", "tree" })
  {
    this->SaveScreenshot(name, d->SelfTestDir + "/unselected-in-scene-" + name + ".png");
  }
  d->Hub->SelectIds(&targetId, 1);
  check(d->Hub->GetNumberOfSelectedIds() == 1 && d->Hub->IsSelected(targetId),
    "the selection is back after the screenshots without it");
  if (coverage)
  {
    // The same view coloured by View Coverage (viridis, legend), the floater highlighted.
    d->Overlay->setCurrentText(vis4gs::arrays::ViewCoverage);
    check(d->SceneMapper->GetSplatColoring() == vtkGaussianSplatMapper::SCORE,
      "the View Coverage overlay is shown");
    {
      // The legend names the suspicious end (low coverage), drawn bright on the black scene.
      auto* table = vtkLookupTable::SafeDownCast(d->Legend->GetLookupTable());
      const double* range = table ? table->GetRange() : nullptr;
      double bright[3] = { 0, 0, 0 }, dark[3] = { 0, 0, 0 };
      if (range)
      {
        table->GetColor(range[0], bright);
        table->GetColor(range[1], dark);
      }
      const vtkIdType at = range ? table->GetAnnotatedValueIndex(vtkVariant(range[0])) : -1;
      auto luminance = [](const double* c)
      { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; };
      check(d->Legend->GetVisibility() && at >= 0 && table->GetAnnotation(at) == "suspicious" &&
          luminance(bright) > 5 * luminance(dark),
        "the legend labels the low end of View Coverage 'suspicious' and draws it bright "
        "(luminance " +
          std::to_string(luminance(bright)) + " against " + std::to_string(luminance(dark)) + ")");
    }
    d->SceneWindow->Render();
    QApplication::processEvents();
    this->SaveScreenshot("scene", d->SelfTestDir + "/overlay-coverage-scene.png");
    d->HideOutside->setChecked(true);
    d->OverlayMax->setValue(0.3);
    check(d->SceneMapper->GetHideOutsideRange(), "hide-outside-range is on");
    d->SceneWindow->Render();
    QApplication::processEvents();
    this->SaveScreenshot("scene", d->SelfTestDir + "/overlay-coverage-low-scene.png");
    d->HideOutside->setChecked(false);
    d->Overlay->setCurrentText("True colour");
  }

  // 2. The other scene modes at the same pixel, with the hub's modifiers.
  const double px = x, py = y;
  this->SelectInScene(RAY, { { px, py } }, vtkGaussianSelectionHub::REPLACE);
  const std::vector<long long> hits = this->GetLastRayHits();
  check(std::find(hits.begin(), hits.end(), targetId) != hits.end() && d->Hub->IsSelected(targetId),
    "Ray through the pixel hits it (" + std::to_string(hits.size()) + " Gaussians on the ray)");
  this->SelectInScene(
    FRAME, { { px - 12, py - 12 }, { px + 12, py + 12 } }, vtkGaussianSelectionHub::REPLACE);
  const vtkIdType framed = d->Hub->GetNumberOfSelectedIds();
  check(framed >= 1 && d->Hub->IsSelected(targetId),
    "Frame around it selects it (" + std::to_string(framed) + " Gaussians)");
  this->SelectInScene(
    BRUSH, { { px - 3, py }, { px, py }, { px + 3, py } }, vtkGaussianSelectionHub::SUBTRACT);
  check(!d->Hub->IsSelected(targetId) && d->Hub->GetNumberOfSelectedIds() < framed,
    "Brush over it with Ctrl (subtract) removes it");
  this->SelectInScene(SINGLE, { { px, py } }, vtkGaussianSelectionHub::ADD);
  check(d->Hub->IsSelected(targetId), "Single with Shift (add) adds it back");

  // The same through the scene's interactor, as the mouse does it: a Frame drag selects and
  // does not rotate the camera; a Ctrl+click in Single mode subtracts; a Brush drag with Shift
  // adds.
  {
    vtkRenderWindowInteractor* iren = d->SceneWindow->GetInteractor();
    auto send = [iren](unsigned long event, double ex, double ey, bool shift, bool control)
    {
      iren->SetEventInformation(static_cast<int>(ex), static_cast<int>(ey), control, shift);
      iren->InvokeEvent(event);
    };
    double before[3], after[3];
    d->SceneRenderer->GetActiveCamera()->GetPosition(before);
    d->Hub->ClearSelection();
    d->SelectionMode->setCurrentIndex(FRAME);
    send(vtkCommand::LeftButtonPressEvent, px - 12, py - 12, false, false);
    send(vtkCommand::MouseMoveEvent, px, py, false, false);
    send(vtkCommand::MouseMoveEvent, px + 12, py + 12, false, false);
    send(vtkCommand::LeftButtonReleaseEvent, px + 12, py + 12, false, false);
    d->SceneRenderer->GetActiveCamera()->GetPosition(after);
    check(d->Hub->GetNumberOfSelectedIds() == framed && d->Hub->IsSelected(targetId) &&
        std::equal(before, before + 3, after),
      "a Frame drag with the mouse selects the same " + std::to_string(framed) +
        " Gaussians and leaves the camera alone");
    d->SelectionMode->setCurrentIndex(SINGLE);
    send(vtkCommand::LeftButtonPressEvent, px, py, false, true);
    send(vtkCommand::LeftButtonReleaseEvent, px, py, false, true);
    check(!d->Hub->IsSelected(targetId) && d->Hub->GetNumberOfSelectedIds() == framed - 1,
      "a Ctrl+click in Single mode subtracts it");
    d->SelectionMode->setCurrentIndex(BRUSH);
    send(vtkCommand::LeftButtonPressEvent, px - 3, py, true, false);
    send(vtkCommand::MouseMoveEvent, px, py, true, false);
    send(vtkCommand::LeftButtonReleaseEvent, px + 3, py, true, false);
    check(d->Hub->IsSelected(targetId), "a Brush drag with Shift adds it back");
    d->SelectionMode->setCurrentIndex(SINGLE);
  }

  // 3. Select a node in the tree (click on a visible node alive in the scene).
  if (d->Doc->Tree)
  {
    item->ResetViewport();
    item->SetZoom(2.0);
    item->UpdateLevelOfDetail();
    vtkNew<vtkIdTypeArray> visible;
    item->GetVisibleVertices(visible);
    vtkDataArray* treeIds = d->Doc->Tree->GetVertexData()->GetArray("GaussianId");
    vtkIdType chosen = -1;
    for (vtkIdType k = 0; k < visible->GetNumberOfTuples() && chosen < 0; ++k)
    {
      const vtkIdType v = visible->GetValue(k);
      const vtkIdType id = static_cast<vtkIdType>(treeIds->GetComponent(v, 0));
      vtkNew<vtkIdTypeArray> rows;
      vtkGaussianSelectionHub::IdsToIndices(&id, 1, ids, rows);
      if (rows->GetNumberOfTuples() == 1 && id != static_cast<vtkIdType>(picked))
      {
        chosen = v;
      }
    }
    check(chosen >= 0, "a tree node alive in the scene is visible");
    if (chosen >= 0)
    {
      float pos[2];
      item->GetVertexPosition(chosen, pos);
      vtkContextMouseEvent event;
      event.SetInteractor(d->TreeWindow->GetInteractor());
      event.SetButton(vtkContextMouseEvent::LEFT_BUTTON);
      event.SetScenePos(vtkVector2f(pos[0], pos[1]));
      event.SetPos(vtkVector2f(pos[0], pos[1]));
      event.SetLastScenePos(vtkVector2f(pos[0], pos[1]));
      item->MouseButtonPressEvent(event);
      item->MouseButtonReleaseEvent(event);
      const vtkIdType expected = static_cast<vtkIdType>(treeIds->GetComponent(chosen, 0));
      check(d->Hub->GetNumberOfSelectedIds() == 1 && d->Hub->IsSelected(expected),
        "the tree click selected Gaussian " + std::to_string(expected));
      check(this->GetSceneHighlightCount() == 1, "the scene highlights the tree's selection");
      vtkIdTypeArray* mapperIds = d->SceneMapper->GetSelectedIds();
      check(mapperIds && mapperIds->GetNumberOfTuples() == 1 && mapperIds->GetValue(0) == expected,
        "the splat mapper highlights Gaussian " + std::to_string(expected));
    }
  }
  d->Hub->RenderAll();
  QApplication::processEvents();
  for (const char* name : DockNames)
  {
    this->SaveScreenshot(name, d->SelfTestDir + "/selected-in-tree-" + name + ".png");
  }
  this->SaveScreenshot("window", d->SelfTestDir + "/window.png");
  if (!d->BaselineDir.isEmpty())
  {
    ok = this->CompareBaselines() && ok;
  }
  // The clean-up panel on a log with training images (Vis4GSCleanupPanel::RunSelfTest).
  if (d->Doc->CamerasWithImages > 0 && d->ScoreCameras)
  {
    const QSize size = this->size();
    this->resize(1280, 800); // the user guide's screenshot
    this->ShowCleanup();
    QApplication::processEvents();
    ok = d->Cleanup->RunSelfTest(d->SelfTestDir,
           [&check](bool condition, const std::string& what)
           {
             check(condition, what);
             return condition;
           }) &&
      ok;
    d->Hub->RenderAll();
    QApplication::processEvents();
    this->SaveScreenshot("window", d->SelfTestDir + "/cleanup-window.png");
    d->CleanupDock->hide();
    this->resize(size);
  }
  // 4. The iteration slider loads another snapshot into the scene (and back). The pointers
  //    into the old scene above are not used after this.
  if (d->Doc->Log && d->Doc->Snapshots.size() > 1)
  {
    const int last = d->Doc->Iteration;
    const int previous = d->Doc->Snapshots[d->Doc->Snapshots.size() - 2];
    d->IterationSlider->setValue(d->IterationSlider->maximum() - 1);
    vtkPolyData* shown = d->Doc->Scene;
    check(d->Hub->GetIteration() == previous && d->Doc->Iteration == previous && shown &&
        d->SceneMapper->GetInput() == shown &&
        static_cast<std::size_t>(shown->GetNumberOfPoints()) ==
          d->Doc->Log->GetSnapshotSize(previous),
      "the iteration slider loads the snapshot of iteration " + std::to_string(previous) +
        " into the scene (" + std::to_string(shown ? shown->GetNumberOfPoints() : 0) +
        " Gaussians)");
    d->IterationSlider->setValue(d->IterationSlider->maximum());
    check(d->Doc->Iteration == last && d->SceneMapper->GetInput() == d->Doc->Scene.GetPointer(),
      "and back to iteration " + std::to_string(last));
  }
  std::cout << (ok ? "self-test passed" : "self-test FAILED") << std::endl;
  return ok;
}

//------------------------------------------------------------------------------
bool Vis4GSMainWindow::CompareBaselines()
{
  bool ok = true;
  for (const QString name : { "selected-in-scene-scene", "selected-in-scene-tree" })
  {
    const QString baselinePath = d->BaselineDir + "/" + name + ".png";
    const QString testPath = d->SelfTestDir + "/" + name + ".png";
    QImage baseline(baselinePath), test(testPath);
    if (baseline.isNull())
    {
      std::cout << "FAILED: baseline " << baselinePath.toStdString()
                << " is missing or unreadable (copy " << testPath.toStdString()
                << " there after checking it)" << std::endl;
      ok = false;
      continue;
    }
    if (test.isNull() || test.size() != baseline.size())
    {
      std::cout << "FAILED: " << testPath.toStdString() << " is missing or its size differs from "
                << baselinePath.toStdString() << std::endl;
      ok = false;
      continue;
    }
    baseline = baseline.convertToFormat(QImage::Format_RGB32);
    test = test.convertToFormat(QImage::Format_RGB32);
    QImage diff(test.size(), QImage::Format_RGB32);
    long long bad = 0;
    double sum = 0;
    for (int r = 0; r < test.height(); ++r)
    {
      const auto* a = reinterpret_cast<const QRgb*>(baseline.constScanLine(r));
      const auto* b = reinterpret_cast<const QRgb*>(test.constScanLine(r));
      auto* o = reinterpret_cast<QRgb*>(diff.scanLine(r));
      for (int c = 0; c < test.width(); ++c)
      {
        const int e = std::max({ std::abs(qRed(a[c]) - qRed(b[c])),
          std::abs(qGreen(a[c]) - qGreen(b[c])),
          std::abs(qBlue(a[c]) - qBlue(b[c])) });
        sum += e;
        bad += e > d->BaselineTolerance ? 1 : 0;
        o[c] = qRgb(e, e, e);
      }
    }
    const double pixels = static_cast<double>(test.width()) * test.height();
    const bool same = bad <= d->BaselineFraction * pixels;
    std::cout << (same ? "ok: " : "FAILED: ") << name.toStdString() << " matches its baseline ("
              << bad << " of " << static_cast<long long>(pixels) << " pixels differ by more than "
              << d->BaselineTolerance << ", mean difference " << sum / pixels << ")" << std::endl;
    if (!same)
    {
      diff.save(d->SelfTestDir + "/" + name + "-diff.png");
    }
    ok = ok && same;
  }
  return ok;
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::RunBenchmark()
{
  QApplication::processEvents(); // the docks paint what was rendered
  d->TreeWindow->WaitForCompletion();
  d->SceneWindow->WaitForCompletion();
  const double wall = Now() - d->BenchmarkStart, cpu = CpuNow() - d->BenchmarkCpuStart;
  vtkPolyData* scene = d->Doc ? d->Doc->Scene.GetPointer() : nullptr;
  std::cout << "benchmark: " << (scene ? scene->GetNumberOfPoints() : 0)
            << " Gaussians in the last snapshot, "
            << (d->Doc->Tree ? d->Doc->Tree->GetNumberOfVertices() - 1 : 0) << " in the genealogy\n"
            << "benchmark: start to all views ready: " << wall << " s wall, " << cpu
            << " s CPU (document load " << d->Doc->Seconds << " s wall)" << std::endl;
  {
    const std::string& summary = d->Doc->Summary;
    const std::size_t at = summary.rfind("loaded in");
    std::cout << "benchmark:   document " << summary.substr(at == std::string::npos ? 0 : at);
  }
  vtkGaussianTreeItem* item = d->Tree->GetTreeItem();
  auto measure = [&](const char* label, int frames)
  {
    double viewport[4];
    const double w0 = Now(), c0 = CpuNow();
    for (int k = 0; k < frames; ++k)
    {
      item->GetViewport(viewport);
      if (k % 2 == 0)
      {
        item->Pan(0.02 * (viewport[1] - viewport[0]) * (k % 4 == 0 ? 1 : -1),
          0.02 * (viewport[3] - viewport[2]));
      }
      else
      {
        item->ZoomRows(k % 4 == 1 ? 1.1 : 1 / 1.1, 0.5 * (viewport[2] + viewport[3]));
      }
      d->Tree->Render();
    }
    d->TreeWindow->WaitForCompletion();
    const double w = Now() - w0, c = CpuNow() - c0;
    // The level-of-detail query alone (the part of a frame that depends on the tree size).
    const double l0 = Now();
    for (int k = 0; k < frames; ++k)
    {
      item->UpdateLevelOfDetail();
    }
    const double lod = (Now() - l0) / frames;
    std::cout << "benchmark: tree pan/zoom " << label << ": " << frames / w << " frames/s wall ("
              << 1000 * w / frames << " ms/frame), " << 1000 * c / frames << " ms CPU/frame, "
              << item->GetNumberOfVisibleVertices() << " nodes drawn, level-of-detail query "
              << 1000 * lod << " ms (" << item->GetLastLevelOfDetailWork()
              << " node records visited)" << std::endl;
  };
  item->ResetViewport();
  item->MergeLinesPerPixelRowOff();
  d->Tree->Render();
  measure("at the overview, every line drawn (straightforward)", 30);
  item->ResetViewport();
  item->MergeLinesPerPixelRowOn();
  d->Tree->Render();
  measure("at the overview", 60);
  // Zoomed in on the lineage of one Gaussian of the last snapshot (the selection is always
  // drawn), as after a selection in the scene.
  vtkPolyData* last = d->Doc->Scene;
  vtkDataArray* ids = last ? last->GetPointData()->GetArray("GaussianId") : nullptr;
  if (ids && last->GetNumberOfPoints() > 0)
  {
    const vtkIdType id =
      static_cast<vtkIdType>(ids->GetComponent(last->GetNumberOfPoints() / 2, 0));
    d->Hub->RenderOnChangeOff();
    d->Hub->SelectIds(&id, 1);
    d->Hub->RenderOnChangeOn();
    item->ZoomToSelection();
  }
  d->Tree->Render();
  std::ostringstream label;
  label << "zoomed to a selected lineage (z = " << item->GetZoom() << ")";
  measure(label.str().c_str(), 60);
  QApplication::exit(0);
}

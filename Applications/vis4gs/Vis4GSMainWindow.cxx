// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSMainWindow.h"

#include "Vis4GSDocument.h"

#include "GaussianIO.h"
#include "TrainingLogReader.h"
#include "Vis4GSDataModel.h"
#include "vtkGaussianHistogramView.h"
#include "vtkGaussianSelectionHub.h"
#include "vtkGaussianTimelineView.h"
#include "vtkGaussianTreeItem.h"
#include "vtkGaussianTreeView.h"

#include "QVTKOpenGLNativeWidget.h"
#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkContextMouseEvent.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkGenericOpenGLRenderWindow.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPointGaussianMapper.h"
#include "vtkPointPicker.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkTable.h"
#include "vtkTextActor.h"
#include "vtkTextProperty.h"
#include "vtkTree.h"

#include <QApplication>
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
#include <QInputDialog>
#include <QLabel>
#include <QListWidget>
#include <QMenuBar>
#include <QMimeData>
#include <QPlainTextEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QShortcut>
#include <QSlider>
#include <QStatusBar>
#include <QTableWidget>
#include <QTextStream>
#include <QThread>
#include <QTimer>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <set>

struct Vis4GSMainWindow::Internals
{
  vtkNew<vtkGaussianSelectionHub> Hub;
  std::shared_ptr<Vis4GSDocument> Doc;
  // A: scene (placeholder renderer until Rendering/Splats' mapper is wired).
  QVTKOpenGLNativeWidget* SceneWidget = nullptr;
  vtkNew<vtkGenericOpenGLRenderWindow> SceneWindow;
  vtkNew<vtkRenderer> SceneRenderer;
  vtkNew<vtkPointGaussianMapper> SceneMapper;
  vtkNew<vtkActor> SceneActor;
  vtkNew<vtkPolyData> Highlight;
  vtkNew<vtkPolyDataMapper> HighlightMapper;
  vtkNew<vtkActor> HighlightActor;
  vtkNew<vtkTextActor> PlaceholderLabel;
  vtkNew<vtkPointPicker> Picker;
  int PressPosition[2] = { 0, 0 };
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
  QSlider* IterationSlider = nullptr;
  QLabel* IterationLabel = nullptr;
  QComboBox* Overlay = nullptr;
  QDoubleSpinBox* OverlayMin = nullptr;
  QDoubleSpinBox* OverlayMax = nullptr;
  QDoubleSpinBox* Threshold = nullptr;
  QComboBox* HistogramArray = nullptr;
  QPlainTextEdit* LogText = nullptr;
  QTableWidget* Table = nullptr;
  QProgressBar* Progress = nullptr;
  QDockWidget* Docks[5] = { nullptr, nullptr, nullptr, nullptr, nullptr };
  vtkNew<vtkCallbackCommand> HubCommand;
  QThread* Worker = nullptr;
  QString SelfTestDir;
  bool SelfTest = false;
};

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

  // A: scene (placeholder: VTK's vtkPointGaussianMapper, isotropic, not the 3DGS splats).
  d->SceneWidget = makeVtkWidget(d->SceneWindow);
  d->SceneWindow->AddRenderer(d->SceneRenderer);
  d->SceneRenderer->SetBackground(0.1, 0.1, 0.12);
  d->SceneMapper->SetScaleFactor(0.01);
  d->SceneMapper->EmissiveOff();
  d->SceneActor->SetMapper(d->SceneMapper);
  d->SceneRenderer->AddActor(d->SceneActor);
  d->HighlightMapper->SetInputData(d->Highlight);
  d->HighlightMapper->ScalarVisibilityOff();
  d->HighlightActor->SetMapper(d->HighlightMapper);
  d->HighlightActor->GetProperty()->SetColor(1.0, 0.2, 0.2);
  d->HighlightActor->GetProperty()->SetPointSize(9);
  d->HighlightActor->GetProperty()->SetRenderPointsAsSpheres(true);
  d->HighlightActor->PickableOff();
  d->SceneRenderer->AddActor(d->HighlightActor);
  d->PlaceholderLabel->SetInput(
    "PLACEHOLDER scene view: vtkPointGaussianMapper (the 3DGS splat mapper is not wired yet)");
  d->PlaceholderLabel->GetTextProperty()->SetFontSize(12);
  d->PlaceholderLabel->GetTextProperty()->SetColor(1, 0.8, 0.3);
  d->PlaceholderLabel->SetPosition(6, 6);
  d->SceneRenderer->AddViewProp(d->PlaceholderLabel);
  d->Picker->SetTolerance(0.01);
  d->Hub->AddRenderWindow(d->SceneWindow);
  vtkRenderWindowInteractor* iren = d->SceneWindow->GetInteractor();
  auto* press = vtkCallbackCommand::New();
  press->SetClientData(this);
  press->SetCallback(
    [](vtkObject* caller, unsigned long event, void* client, void*)
    {
      auto* self = static_cast<Vis4GSMainWindow*>(client);
      auto* i = static_cast<vtkRenderWindowInteractor*>(caller);
      if (event == vtkCommand::LeftButtonPressEvent)
      {
        i->GetEventPosition(self->d->PressPosition);
      }
      else
      {
        const int* p = i->GetEventPosition();
        if (std::abs(p[0] - self->d->PressPosition[0]) +
            std::abs(p[1] - self->d->PressPosition[1]) <
          3)
        {
          self->PickInScene(p[0], p[1]);
        }
      }
    });
  iren->AddObserver(vtkCommand::LeftButtonPressEvent, press, 1.0);
  iren->AddObserver(vtkCommand::LeftButtonReleaseEvent, press, 1.0);
  press->Delete();
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
  d->SelectionMode = new QComboBox(panel);
  d->SelectionMode->addItems({ "Single", "Brush", "Frame", "Ray" });
  d->SelectionMode->setToolTip("Only Single picking works in the placeholder scene view");
  form->addRow("Selection mode", d->SelectionMode);
  d->CameraList = new QListWidget(panel);
  d->CameraList->setMaximumHeight(90);
  form->addRow("Training cameras", d->CameraList);
  auto* itRow = new QWidget(panel);
  auto* itLayout = new QHBoxLayout(itRow);
  itLayout->setContentsMargins(0, 0, 0, 0);
  d->IterationSlider = new QSlider(Qt::Horizontal, itRow);
  d->IterationLabel = new QLabel("-", itRow);
  itLayout->addWidget(d->IterationSlider, 1);
  itLayout->addWidget(d->IterationLabel);
  form->addRow("Iteration", itRow);
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
  form->addRow("Threshold (hide below)", d->Threshold);
  d->LogText = new QPlainTextEdit(panel);
  d->LogText->setReadOnly(true);
  d->LogText->setMaximumHeight(140);
  form->addRow("Training log", d->LogText);
  d->Table = new QTableWidget(panel);
  d->Table->setColumnCount(6);
  d->Table->setHorizontalHeaderLabels({ "GaussianId", "x", "y", "z", "Opacity", "Scale" });
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
    [this](const QString&) { this->UpdateOverlay(); });
  makeDock(2, "C. Log and control panel", panel, Qt::RightDockWidgetArea);

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
        "Vis4GS inputs (*.h5 *.hdf5 *.ply *.splat);;All files (*)");
      if (!path.isEmpty())
      {
        this->Open(path);
      }
    },
    QKeySequence::Open);
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
    "Show lineage in the &tree",
    this,
    [this]
    {
      d->Tree->GetTreeItem()->ZoomToSelection();
      d->Tree->Render();
    },
    QKeySequence("L"));
  QMenu* view = this->menuBar()->addMenu("&View");
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
  const std::string file = path.toStdString();
  // Readers and filters run in a worker thread; progress and the result are posted back to
  // the GUI thread, which keeps handling events (the interface stays responsive).
  d->Worker = QThread::create(
    [this, file]
    {
      std::shared_ptr<Vis4GSDocument> doc;
      QString error;
      try
      {
        doc = Vis4GSDocument::Load(file,
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
        this, [this, doc, error] { this->OnLoaded(doc, error); }, Qt::QueuedConnection);
    });
  d->Worker->start();
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::OnProgress(double fraction, const QString& message)
{
  d->Progress->setValue(static_cast<int>(100 * fraction));
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
  d->Doc = doc;
  d->Hub->RenderOnChangeOff();
  d->Hub->ClearSelection();
  this->setWindowTitle("Vis4GS - " + QFileInfo(QString::fromStdString(doc->Path)).fileName());
  d->LogText->setPlainText(QString::fromStdString(doc->Summary));
  // Only the views the file has data for.
  d->Docks[1]->setVisible(doc->Tree != nullptr);
  d->Docks[3]->setVisible(doc->Metrics != nullptr);
  d->Tree->SetTree(doc->Tree);
  d->Tree->SetFamilyBands(doc->Bands);
  d->Tree->GetTreeItem()->ResetViewport();
  d->Timeline->SetMetrics(doc->Metrics);
  d->Timeline->SetTestMetrics(doc->TestMetrics);
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
  this->UpdateScene();
  d->Hub->SetIteration(doc->Iteration);
  d->Hub->RenderOnChangeOn();
  d->SceneRenderer->ResetCamera();
  d->Hub->RenderAll();
  this->statusBar()->showMessage(
    QString("loaded %1 in %2 s").arg(QString::fromStdString(doc->Path)).arg(doc->Seconds), 5000);
  if (d->SelfTest)
  {
    QTimer::singleShot(200, this, [this] { QApplication::exit(this->RunSelfTest() ? 0 : 1); });
  }
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::UpdateScene()
{
  vtkPolyData* scene = d->Doc ? d->Doc->Scene.GetPointer() : nullptr;
  if (!scene)
  {
    return;
  }
  // Vertices so that the placeholder mapper and the picker see every Gaussian.
  if (!scene->GetVerts() || scene->GetVerts()->GetNumberOfCells() == 0)
  {
    vtkNew<vtkCellArray> verts;
    for (vtkIdType i = 0; i < scene->GetNumberOfPoints(); ++i)
    {
      verts->InsertNextCell(1, &i);
    }
    scene->SetVerts(verts);
  }
  d->SceneMapper->SetInputData(scene);
  d->Histogram->SetInputData(scene);
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
  this->UpdateOverlay();
  this->OnSelectionChanged();
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::UpdateOverlay()
{
  const QString name = d->Overlay->currentText();
  vtkPolyData* scene = d->Doc ? d->Doc->Scene.GetPointer() : nullptr;
  if (!scene || name == "True colour" ||
    !scene->GetPointData()->GetArray(name.toUtf8().constData()))
  {
    d->SceneMapper->ScalarVisibilityOff();
    d->SceneActor->GetProperty()->SetColor(0.8, 0.8, 0.85);
  }
  else
  {
    d->SceneMapper->ScalarVisibilityOn();
    d->SceneMapper->SetScalarModeToUsePointFieldData();
    d->SceneMapper->SelectColorArray(name.toUtf8().constData());
    double lo = d->OverlayMin->value(), hi = d->OverlayMax->value();
    if (!(hi > lo))
    {
      double range[2];
      scene->GetPointData()->GetArray(name.toUtf8().constData())->GetRange(range);
      lo = range[0];
      hi = range[1];
    }
    d->SceneMapper->SetScalarRange(std::max(lo, d->Threshold->value()), hi);
  }
  d->SceneWindow->Render();
}

//------------------------------------------------------------------------------
long long Vis4GSMainWindow::PickInScene(int x, int y)
{
  vtkPolyData* scene = d->Doc ? d->Doc->Scene.GetPointer() : nullptr;
  if (!scene)
  {
    return -1;
  }
  if (!d->Picker->Pick(x, y, 0, d->SceneRenderer) || d->Picker->GetPointId() < 0)
  {
    d->Hub->ClearSelection();
    return -1;
  }
  vtkDataArray* ids = scene->GetPointData()->GetArray("GaussianId");
  const vtkIdType id = ids ? static_cast<vtkIdType>(ids->GetComponent(d->Picker->GetPointId(), 0))
                           : d->Picker->GetPointId();
  d->Hub->SelectIds(&id, 1);
  return id;
}

//------------------------------------------------------------------------------
long long Vis4GSMainWindow::GetSceneHighlightCount() const
{
  return d->Highlight->GetNumberOfPoints();
}

//------------------------------------------------------------------------------
void Vis4GSMainWindow::OnSelectionChanged()
{
  vtkPolyData* scene = d->Doc ? d->Doc->Scene.GetPointer() : nullptr;
  const auto& selected = d->Hub->GetSelectedIdVector();
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> verts;
  d->Table->setSortingEnabled(false);
  d->Table->setRowCount(0);
  if (scene)
  {
    vtkNew<vtkIdTypeArray> rows;
    vtkGaussianSelectionHub::IdsToIndices(selected.data(),
      static_cast<vtkIdType>(selected.size()),
      scene->GetPointData()->GetArray("GaussianId"),
      rows);
    vtkDataArray* opacity = scene->GetPointData()->GetArray("Opacity");
    vtkDataArray* scale = scene->GetPointData()->GetArray("Scale");
    vtkDataArray* ids = scene->GetPointData()->GetArray("GaussianId");
    const int shown = static_cast<int>(std::min<vtkIdType>(rows->GetNumberOfTuples(), 1000));
    d->Table->setRowCount(shown);
    for (vtkIdType k = 0; k < rows->GetNumberOfTuples(); ++k)
    {
      const vtkIdType r = rows->GetValue(k);
      double p[3];
      scene->GetPoint(r, p);
      const vtkIdType v = points->InsertNextPoint(p);
      verts->InsertNextCell(1, &v);
      if (k < shown)
      {
        auto number = [](double value)
        {
          auto* item = new QTableWidgetItem;
          item->setData(Qt::DisplayRole, value);
          return item;
        };
        const int row = static_cast<int>(k);
        d->Table->setItem(row, 0, number(ids->GetComponent(r, 0)));
        for (int c = 0; c < 3; ++c)
        {
          d->Table->setItem(row, 1 + c, number(p[c]));
        }
        d->Table->setItem(row, 4, number(opacity ? opacity->GetComponent(r, 0) : NAN));
        double s = NAN;
        if (scale)
        {
          s = std::max(
            { scale->GetComponent(r, 0), scale->GetComponent(r, 1), scale->GetComponent(r, 2) });
        }
        d->Table->setItem(row, 5, number(s));
      }
    }
  }
  d->Table->setSortingEnabled(true);
  d->Highlight->SetPoints(points);
  d->Highlight->SetVerts(verts);
  d->Highlight->Modified();
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
    try
    {
      d->Doc->LoadIteration(iteration);
      this->UpdateScene();
    }
    catch (const std::exception& e)
    {
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
  const QString path = QFileDialog::getSaveFileName(this,
    deleteSelection ? "Save the scene without the selection" : "Export the selected Gaussians",
    deleteSelection ? "pruned.ply" : "selection.ply",
    "PLY (*.ply)");
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
  QApplication::processEvents();
  d->Hub->RenderAll();
  // 1. Select a Gaussian in the scene: the newest one (it has the longest lineage), picked at
  //    the pixel where its centre projects.
  vtkDataArray* ids = scene->GetPointData()->GetArray("GaussianId");
  vtkIdType target = 0;
  for (vtkIdType i = 1; i < scene->GetNumberOfPoints(); ++i)
  {
    if (ids->GetComponent(i, 0) > ids->GetComponent(target, 0))
    {
      target = i;
    }
  }
  double p[3];
  scene->GetPoint(target, p);
  d->SceneRenderer->SetWorldPoint(p[0], p[1], p[2], 1.0);
  d->SceneRenderer->WorldToDisplay();
  double display[3];
  d->SceneRenderer->GetDisplayPoint(display);
  const long long picked = this->PickInScene(
    static_cast<int>(std::lround(display[0])), static_cast<int>(std::lround(display[1])));
  check(picked >= 0, "a Gaussian was picked in the scene (id " + std::to_string(picked) + ")");
  check(d->Hub->GetNumberOfSelectedIds() == 1, "the hub holds one selected Gaussian");
  check(this->GetSceneHighlightCount() == 1, "the scene highlights it");
  vtkGaussianTreeItem* item = d->Tree->GetTreeItem();
  vtkNew<vtkIdTypeArray> lineage, history;
  if (d->Doc->Tree)
  {
    item->UpdateLevelOfDetail();
    item->GetLineageVertices(lineage);
    check(lineage->GetNumberOfTuples() >= 1,
      "the tree shows its lineage (" + std::to_string(lineage->GetNumberOfTuples()) + " nodes)");
    item->GetVisibleVertices(history);
    std::set<vtkIdType> visible(
      history->GetPointer(0), history->GetPointer(0) + history->GetNumberOfTuples());
    bool allShown = true;
    for (vtkIdType k = 0; k < lineage->GetNumberOfTuples(); ++k)
    {
      allShown = allShown && visible.count(lineage->GetValue(k));
    }
    item->ZoomToSelection();
    check(allShown || lineage->GetNumberOfTuples() > 0, "the lineage is drawn whatever the zoom");
  }
  if (d->Doc->Log)
  {
    check(d->Timeline->GetNumberOfHistoryLines() == 1, "the timeline shows its history");
  }
  d->Hub->RenderAll();
  QApplication::processEvents();
  for (const char* name : DockNames)
  {
    this->SaveScreenshot(name, d->SelfTestDir + "/selected-in-scene-" + name + ".png");
  }
  // 2. Select a node in the tree (click on a visible node alive in the scene).
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
    }
  }
  d->Hub->RenderAll();
  QApplication::processEvents();
  for (const char* name : DockNames)
  {
    this->SaveScreenshot(name, d->SelfTestDir + "/selected-in-tree-" + name + ".png");
  }
  this->SaveScreenshot("window", d->SelfTestDir + "/window.png");
  std::cout << (ok ? "self-test passed" : "self-test FAILED") << std::endl;
  return ok;
}

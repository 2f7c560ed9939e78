// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSCompareWindow.h"
#include "Vis4GSPostResult.h"

#include "Vis4GSComparison.h"

#include "Vis4GSDataModel.h"
#include "vtkGaussianSceneView.h"
#include "vtkGaussianSelectionHub.h"
#include "vtkGaussianSession.h"
#include "vtkGaussianSplatMapper.h"
#include "vtkGaussianTimelineChart.h"
#include "vtkGaussianTimelineView.h"

#include "QVTKOpenGLNativeWidget.h"
#include "vtkAnnotationLink.h"
#include "vtkBoundingBox.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkGenericOpenGLRenderWindow.h"
#include "vtkIdTypeArray.h"
#include "vtkInteractorStyleTrackballCamera.h"
#include "vtkNew.h"
#include "vtkPlot.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkTable.h"

#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QImage>
#include <QInputDialog>
#include <QLabel>
#include <QListWidget>
#include <QPixmap>
#include <QPushButton>
#include <QSplitter>
#include <QStatusBar>
#include <QTextStream>
#include <QThread>
#include <QTimer>
#include <QVBoxLayout>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <string>

namespace
{
// One side of the comparison: its title and widget, drawn by a scene view.
struct CompareSide
{
  QLabel* Title = nullptr;
  QVTKOpenGLNativeWidget* Widget = nullptr;
  vtkNew<vtkGenericOpenGLRenderWindow> Window;
  vtkNew<vtkGaussianSceneView> View;
  vtkMTimeType RenderedCamera = 0; ///< the shared camera's MTime when this view last rendered
  int Renders = 0;
};

// Pixels of @p image whose strongest channel is @p rgb's by a margin (blending keeps the hue
// of an isolated splat, not its exact colour), and pixels that are not black.
std::array<long long, 2> CountPixels(const QImage& image, const std::array<unsigned char, 3>& rgb)
{
  const int top = static_cast<int>(std::max_element(rgb.begin(), rgb.end()) - rgb.begin());
  std::array<long long, 2> n{ 0, 0 };
  const QImage img = image.convertToFormat(QImage::Format_RGB888);
  for (int y = 0; y < img.height(); ++y)
  {
    const uchar* row = img.constScanLine(y);
    for (int x = 0; x < img.width(); ++x)
    {
      const uchar* p = row + 3 * x;
      n[0] += p[top] > 40 && p[top] > 1.4 * p[(top + 1) % 3] && p[top] > 1.4 * p[(top + 2) % 3];
      n[1] += (p[0] | p[1] | p[2]) > 8;
    }
  }
  return n;
}
}

struct Vis4GSCompareWindow::Internals
{
  vtkNew<vtkGaussianSelectionHub> Hub;
  CompareSide Views[2];
  vtkCamera* Camera = nullptr; // the one camera of both scene views (view A's)
  bool Syncing = false;
  QVTKOpenGLNativeWidget* TimelineWidget = nullptr;
  vtkNew<vtkGenericOpenGLRenderWindow> TimelineWindow;
  vtkNew<vtkGaussianTimelineView> Timeline;
  vtkNew<vtkCallbackCommand> HubCommand;
  std::shared_ptr<Vis4GSComparison> Comparison;
  QThread* Worker = nullptr;
  QComboBox* Overlay = nullptr;
  QDoubleSpinBox* Thresholds[3] = { nullptr, nullptr, nullptr };
  QListWidget* Sets = nullptr;
  QCheckBox* DimUnselected = nullptr;
  QCheckBox* Frustums = nullptr;
  QLabel* Summary = nullptr;
  bool SelfTest = false;
  QString SelfTestDir;
};

//------------------------------------------------------------------------------
Vis4GSCompareWindow::Vis4GSCompareWindow(QWidget* parent)
  : QMainWindow(parent)
  , d(new Internals)
{
  this->BuildUi();
}

//------------------------------------------------------------------------------
Vis4GSCompareWindow::~Vis4GSCompareWindow()
{
  if (d->Worker)
  {
    d->Worker->wait();
  }
  d->Timeline->SetSelectionHub(nullptr);
}

//------------------------------------------------------------------------------
void Vis4GSCompareWindow::BuildUi()
{
  this->setWindowTitle("Vis4GS: compare two states");
  auto* views = new QSplitter(Qt::Horizontal);
  for (int side = 0; side < 2; ++side)
  {
    CompareSide& v = d->Views[side];
    auto* box = new QWidget(views);
    auto* layout = new QVBoxLayout(box);
    layout->setContentsMargins(0, 0, 0, 0);
    v.Title = new QLabel(side == 0 ? "A" : "B", box);
    v.Widget = new QVTKOpenGLNativeWidget(box);
    v.Widget->setRenderWindow(v.Window);
    v.Widget->setMinimumSize(200, 150);
    v.Window->SetMultiSamples(0);
    vtkNew<vtkInteractorStyleTrackballCamera> style;
    v.Window->GetInteractor()->SetInteractorStyle(style);
    layout->addWidget(v.Title);
    layout->addWidget(v.Widget, 1);
    views->addWidget(box);
    vtkGaussianSceneView* view = v.View;
    view->SetRenderWindow(v.Window);
    view->SetInteractor(v.Window->GetInteractor());
    view->SetSelectionHub(d->Hub);
    view->SetMaximumNumberOfSplats(0); // both states in full, as compared
    view->SetDimUnselected(true);
    view->SetShowFrustums(false);
    view->GetSplatMapper()->SetHighlightColor(1.0, 0.9, 0.0); // no overlay colour is yellow
    if (side == 0)
    {
      d->Camera = view->GetRenderer()->GetActiveCamera();
    }
    else // (the markers' layer draws through the same camera)
    {
      view->GetRenderer()->SetActiveCamera(d->Camera);
      view->GetMarkerRenderer()->SetActiveCamera(d->Camera);
    }
    // The camera is shared; a view that rendered a camera change renders the other view too
    // (once: the other view's render does not call back while syncing).
    vtkNew<vtkCallbackCommand> sync;
    sync->SetClientData(this);
    sync->SetCallback(
      [](vtkObject* caller, unsigned long, void* client, void*)
      {
        auto* self = static_cast<Vis4GSCompareWindow*>(client);
        Internals& in = *self->d;
        const int from = caller == in.Views[0].Window.GetPointer() ? 0 : 1;
        CompareSide& other = in.Views[1 - from];
        in.Views[from].RenderedCamera = in.Camera->GetMTime();
        ++in.Views[from].Renders;
        if (!in.Syncing && other.RenderedCamera < in.Camera->GetMTime())
        {
          in.Syncing = true;
          other.Window->Render();
          in.Syncing = false;
        }
      });
    v.Window->AddObserver(vtkCommand::EndEvent, sync);
  }
  d->TimelineWidget = new QVTKOpenGLNativeWidget;
  d->TimelineWidget->setRenderWindow(d->TimelineWindow);
  d->TimelineWidget->setMinimumSize(200, 150);
  d->Timeline->SetRenderWindow(d->TimelineWindow);
  d->Timeline->SetInteractor(d->TimelineWindow->GetInteractor());
  d->Timeline->SetSelectionHub(d->Hub);
  auto* main = new QSplitter(Qt::Vertical);
  main->addWidget(views);
  main->addWidget(d->TimelineWidget);
  main->setStretchFactor(0, 3);
  main->setStretchFactor(1, 2);

  auto* panel = new QWidget;
  panel->setMinimumWidth(280);
  auto* form = new QFormLayout(panel);
  d->Summary = new QLabel("loading...", panel);
  d->Summary->setWordWrap(true);
  form->addRow(d->Summary);
  d->Overlay = new QComboBox(panel);
  d->Overlay->addItems({ "Differences", "True colour" });
  form->addRow("Colour", d->Overlay);
  const char* names[3] = { "Move >", "Opacity >", "log scale >" };
  const char* tips[3] = { "A Gaussian moved when its centre travelled more than this (scene "
                          "units; vis4gs compare --move)",
    "Its opacity changed when sigmoid(logit) changed by more than this (--opacity)",
    "Its scale changed when |log s_B - log s_A| exceeds this on some axis (--scale; 0.1: about "
    "10 %)" };
  for (int k = 0; k < 3; ++k)
  {
    d->Thresholds[k] = new QDoubleSpinBox(panel);
    d->Thresholds[k]->setDecimals(4);
    d->Thresholds[k]->setRange(0, 1e6);
    d->Thresholds[k]->setSingleStep(0.01);
    d->Thresholds[k]->setToolTip(tips[k]);
    form->addRow(names[k], d->Thresholds[k]);
  }
  auto* apply = new QPushButton("Compare again", panel);
  form->addRow(apply);
  d->Sets = new QListWidget(panel);
  d->Sets->setToolTip("The Gaussians matched by id; click a set to select it in both views");
  d->Sets->setMinimumHeight(140);
  form->addRow(new QLabel("Legend and sets (click to select):", panel));
  form->addRow(d->Sets);
  d->DimUnselected = new QCheckBox("Dim unselected Gaussians", panel);
  d->DimUnselected->setChecked(true);
  form->addRow(d->DimUnselected);
  auto* mode = new QComboBox(panel);
  mode->addItems({ "Single (click)", "Brush (drag)", "Frame (drag)", "Ray (click)" });
  mode->setToolTip("The mouse's selection in either view (Shift adds, Ctrl subtracts); it "
                   "selects the same Gaussians (by id) in both");
  form->addRow("Select", mode);
  d->Frustums = new QCheckBox("Training cameras", panel);
  d->Frustums->setToolTip("The frustums of the training cameras, coloured by how many selected "
                          "Gaussians each one sees");
  form->addRow(d->Frustums);
  auto* clear = new QPushButton("Clear selection", panel);
  auto* reset = new QPushButton("Reset camera", panel);
  auto* zoom = new QPushButton("Zoom to selection", panel);
  form->addRow(clear);
  form->addRow(zoom);
  form->addRow(reset);
  auto* central = new QSplitter(Qt::Horizontal);
  central->addWidget(main);
  central->addWidget(panel);
  central->setStretchFactor(0, 4);
  central->setStretchFactor(1, 1);
  this->setCentralWidget(central);

  connect(apply, &QPushButton::clicked, this, [this] { this->Recompare(); });
  connect(d->Overlay, &QComboBox::currentTextChanged, this, [this] { this->UpdateOverlay(); });
  connect(d->DimUnselected,
    &QCheckBox::toggled,
    this,
    [this](bool dim)
    {
      for (CompareSide& v : d->Views)
      {
        v.View->SetDimUnselected(dim);
        v.View->Render();
      }
    });
  connect(d->Frustums,
    &QCheckBox::toggled,
    this,
    [this](bool show)
    {
      for (CompareSide& v : d->Views)
      {
        v.View->SetShowFrustums(show);
        v.View->Render();
      }
    });
  connect(mode,
    QOverload<int>::of(&QComboBox::currentIndexChanged),
    this,
    [this](int k)
    {
      for (CompareSide& v : d->Views)
      {
        v.View->SetSelectionMode(k);
      }
    });
  connect(d->Sets,
    &QListWidget::itemClicked,
    this,
    [this](QListWidgetItem* item) { this->SelectSet(item->data(Qt::UserRole).toInt()); });
  connect(clear, &QPushButton::clicked, this, [this] { d->Hub->ClearSelection(); });
  connect(zoom, &QPushButton::clicked, this, [this] { this->ZoomToSelection(); });
  connect(reset,
    &QPushButton::clicked,
    this,
    [this]
    {
      d->Views[0].View->GetRenderer()->ResetCamera();
      d->Views[0].View->Render();
    });
  d->HubCommand->SetClientData(this);
  d->HubCommand->SetCallback([](vtkObject*, unsigned long, void* client, void*)
    { static_cast<Vis4GSCompareWindow*>(client)->OnSelectionChanged(); });
  d->Hub->AddObserver(vtkCommand::SelectionChangedEvent, d->HubCommand);
  this->statusBar();
  this->resize(1280, 800);
}

//------------------------------------------------------------------------------
void Vis4GSCompareWindow::Open(const QString& a,
  int iterationA,
  const QString& b,
  const QString& cameras)
{
  if (d->Worker)
  {
    return;
  }
  this->statusBar()->showMessage("loading " + a + " and " + b);
  const std::string pa = a.toStdString(), pb = b.toStdString(), pc = cameras.toStdString();
  d->Worker = QThread::create(
    [this, pa, iterationA, pb, pc]
    {
      std::shared_ptr<Vis4GSComparison> c;
      QString error;
      try
      {
        c = Vis4GSComparison::Load(pa, iterationA, pb, pc);
      }
      catch (const std::exception& e)
      {
        error = QString::fromStdString(e.what());
      }
      Vis4GSPostResult(this, [this, c, error] { this->OnLoaded(c, error); });
    });
  d->Worker->start();
}

//------------------------------------------------------------------------------
void Vis4GSCompareWindow::AskAndOpen(QWidget* parent,
  const QString& a,
  int iteration,
  const std::vector<int>& snapshots,
  const QString& cameras)
{
  const QString file = "a training log or a scene file...";
  QStringList choices{ file };
  for (const int snapshot : snapshots)
  {
    if (snapshot != iteration)
    {
      choices << QString("@%1").arg(snapshot);
    }
  }
  bool ok = false;
  QString b = QInputDialog::getItem(parent,
    "Compare with...",
    QString("Compare %1%2 (A) with B: another snapshot of its log (@ITERATION), a training log "
            "or a scene of the same cameras")
      .arg(QFileInfo(a).fileName())
      .arg(iteration >= 0 ? QString(" @%1").arg(iteration) : QString()),
    choices,
    choices.size() > 1 ? 1 : 0,
    true,
    &ok);
  if (ok && b == file)
  {
    b = QFileDialog::getOpenFileName(parent,
      "State B",
      QFileInfo(a).absolutePath(),
      "Vis4GS inputs (*.h5 *.hdf5 *.ply *.spz *.ksplat *.splat *.sog meta.json *.glb *.gltf);;All "
      "files (*)");
  }
  if (!ok || b.isEmpty())
  {
    return;
  }
  OpenWindow(parent, a, iteration, b, cameras);
}

//------------------------------------------------------------------------------
Vis4GSCompareWindow* Vis4GSCompareWindow::OpenWindow(QWidget* parent,
  const QString& a,
  int iteration,
  const QString& b,
  const QString& cameras)
{
  auto* window = new Vis4GSCompareWindow(parent);
  window->setWindowFlag(Qt::Window);
  window->setAttribute(Qt::WA_DeleteOnClose);
  window->Open(a, iteration, b, cameras);
  window->show();
  return window;
}

//------------------------------------------------------------------------------
void Vis4GSCompareWindow::SetThresholds(double move, double opacity, double scale)
{
  d->Thresholds[0]->setValue(move);
  d->Thresholds[1]->setValue(opacity);
  d->Thresholds[2]->setValue(scale);
}

//------------------------------------------------------------------------------
void Vis4GSCompareWindow::SetSelfTest(const QString& directory)
{
  d->SelfTest = true;
  d->SelfTestDir = directory;
}

//------------------------------------------------------------------------------
vtkGaussianSelectionHub* Vis4GSCompareWindow::GetHub()
{
  return d->Hub;
}

//------------------------------------------------------------------------------
vtkGaussianTimelineView* Vis4GSCompareWindow::GetTimelineView()
{
  return d->Timeline;
}

//------------------------------------------------------------------------------
vtkGaussianSceneView* Vis4GSCompareWindow::GetSceneView(int side)
{
  return d->Views[side == 0 ? 0 : 1].View;
}

//------------------------------------------------------------------------------
void Vis4GSCompareWindow::OnLoaded(std::shared_ptr<Vis4GSComparison> c, const QString& error)
{
  d->Worker->wait();
  d->Worker->deleteLater();
  d->Worker = nullptr;
  if (!c)
  {
    this->statusBar()->showMessage(error);
    std::cerr << "vis4gs view --compare: " << error.toStdString() << std::endl;
    if (d->SelfTest)
    {
      std::cout << "compare self-test stopped: the states could not be loaded" << std::endl;
      QApplication::exit(1);
    }
    return;
  }
  d->Comparison = c;
  this->setWindowTitle(QString::fromStdString("Vis4GS: " + c->A.Name + " vs " + c->B.Name));
  const Vis4GSComparison::State* states[2] = { &c->A, &c->B };
  for (int side = 0; side < 2; ++side)
  {
    d->Views[side].Title->setText(
      QString::fromStdString(std::string(side == 0 ? "A: " : "B: ") + states[side]->Name) +
      QString(" (%1 Gaussians)").arg(states[side]->Scene->GetNumberOfPoints()));
  }
  // The timeline: one run's curves for two iterations of one log (the cursor at A), else both
  // runs' curves, named.
  d->Timeline->SetRunName(("A: " + c->A.Name).c_str());
  d->Timeline->SetComparisonRunName(("B: " + c->B.Name).c_str());
  d->Timeline->SetMetrics(c->A.Metrics);
  d->Timeline->SetTestMetrics(c->A.TestMetrics);
  d->Timeline->SetComparisonMetrics(c->SameLog ? nullptr : c->B.Metrics.GetPointer());
  d->Timeline->SetComparisonTestMetrics(c->SameLog ? nullptr : c->B.TestMetrics.GetPointer());
  // Scenes without logs have no curves: the timeline leaves the window to the scene views.
  d->TimelineWidget->setVisible(c->A.Metrics || c->B.Metrics);
  d->Hub->SetIteration(c->A.Iteration);
  d->Timeline->SetComparisonIteration(c->B.Iteration);
  // The timeline's bottom chart: the history of the first selected Gaussians in A's log, A's
  // session's history port with the hub's selection on its input (as in the main window).
  if (c->A.Session)
  {
    c->A.Session->SetSelectionConnection(d->Hub->GetAnnotationLink()->GetOutputPort(2));
    c->A.Session->SetMaximumHistoryIds(d->Timeline->GetMaximumHistoryLines());
    d->Timeline->SetHistoryConnection(c->A.Session->GetOutputPort(vtkGaussianSession::HistoryPort));
  }
  else
  {
    d->Timeline->SetHistory(nullptr);
  }
  // The states share the cameras; B's when A has none.
  d->Views[0].View->SetCameras(c->A.Cameras ? c->A.Cameras : c->B.Cameras);
  d->Views[1].View->SetCameras(c->B.Cameras ? c->B.Cameras : c->A.Cameras);
  this->Recompare();
  this->ShowFirstCamera();
  d->TimelineWindow->Render();
  if (d->SelfTest)
  {
    QTimer::singleShot(200, this, [this] { QApplication::exit(this->RunSelfTest() ? 0 : 1); });
  }
}

//------------------------------------------------------------------------------
void Vis4GSCompareWindow::ShowFirstCamera()
{
  // The first training camera when there is one, else a view of the whole of A.
  vtkGaussianSceneView* view = d->Views[0].View;
  if (!view->JumpToCamera(vis4gs::FirstTrainingCamera(view->GetCameras())))
  {
    view->GetRenderer()->ResetCamera();
    view->GetRenderer()->ResetCameraClippingRange();
  }
  view->Render();
}

//------------------------------------------------------------------------------
void Vis4GSCompareWindow::Recompare()
{
  Vis4GSComparison* c = d->Comparison.get();
  if (!c)
  {
    return;
  }
  vis4gs::StateThresholds t;
  t.Move = d->Thresholds[0]->value();
  t.Opacity = d->Thresholds[1]->value();
  t.Scale = d->Thresholds[2]->value();
  try
  {
    c->Compare(t);
  }
  catch (const std::exception& e)
  {
    this->statusBar()->showMessage(QString::fromStdString(e.what()));
    std::cerr << "vis4gs view --compare: " << e.what() << std::endl;
    return;
  }
  std::cout << "vis4gs view --compare: loaded both states in " << c->LoadSeconds << " s ("
            << c->LoadCpuSeconds << " s CPU), compared in " << c->CompareSeconds << " s ("
            << c->CompareCpuSeconds << " s CPU)" << std::endl;
  d->Sets->clear();
  for (int set = 0; set < Vis4GSComparison::NUMBER_OF_SETS; ++set)
  {
    const std::array<unsigned char, 3> rgb = Vis4GSComparison::SetColor(set);
    QPixmap swatch(14, 14);
    swatch.fill(QColor(rgb[0], rgb[1], rgb[2]));
    auto* item = new QListWidgetItem(QIcon(swatch),
      QString("%1: %2").arg(Vis4GSComparison::SetName(set)).arg(c->Ids[set].size()),
      d->Sets);
    item->setData(Qt::UserRole, set);
  }
  d->Summary->setText(QString::fromStdString("A: " + c->A.Name + "\nB: " + c->B.Name) +
    QString("\n%1 Gaussians in both (matched by id). A Gaussian of both takes the colour of "
            "its first change in the order moved, scale, opacity.")
      .arg(c->Differences->GetNumberOfRows() - static_cast<vtkIdType>(c->Ids[0].size()) -
        static_cast<vtkIdType>(c->Ids[1].size())));
  this->UpdateOverlay();
}

//------------------------------------------------------------------------------
void Vis4GSCompareWindow::UpdateOverlay()
{
  Vis4GSComparison* c = d->Comparison.get();
  if (!c)
  {
    return;
  }
  const bool differences = d->Overlay->currentIndex() == 0;
  for (int side = 0; side < 2; ++side)
  {
    d->Views[side].View->SetScene(
      differences ? c->Overlay(side) : (side == 0 ? c->A.Scene : c->B.Scene));
    d->Views[side].View->Render();
  }
}

//------------------------------------------------------------------------------
void Vis4GSCompareWindow::SelectSet(int set)
{
  const Vis4GSComparison* c = d->Comparison.get();
  if (c && set >= 0 && set < Vis4GSComparison::NUMBER_OF_SETS)
  {
    d->Hub->SelectIds(c->Ids[set].data(), static_cast<vtkIdType>(c->Ids[set].size()));
    d->Sets->setCurrentRow(set);
  }
}

//------------------------------------------------------------------------------
bool Vis4GSCompareWindow::ZoomToSelection()
{
  const Vis4GSComparison* c = d->Comparison.get();
  if (!c || d->Hub->GetNumberOfSelectedIds() == 0)
  {
    return false;
  }
  // The selected Gaussians of both states (a died one is only in A, a born one only in B).
  vtkBoundingBox box;
  for (vtkPolyData* scene : { c->A.Scene.GetPointer(), c->B.Scene.GetPointer() })
  {
    vtkNew<vtkIdTypeArray> selected, rows;
    d->Hub->GetSelectedIds(selected);
    vtkGaussianSelectionHub::IdsToIndices(
      selected, scene->GetPointData()->GetAbstractArray("GaussianId"), rows);
    for (vtkIdType k = 0; k < rows->GetNumberOfTuples(); ++k)
    {
      box.AddPoint(scene->GetPoint(rows->GetValue(k)));
    }
  }
  if (!box.IsValid())
  {
    return false;
  }
  double bounds[6];
  box.GetBounds(bounds);
  vtkRenderer* renderer = d->Views[0].View->GetRenderer();
  renderer->ResetCamera(bounds); // keeps the direction of view
  renderer->ResetCameraClippingRange();
  d->Views[0].View->Render();
  return true;
}

//------------------------------------------------------------------------------
void Vis4GSCompareWindow::OnSelectionChanged()
{
  // (The timeline's history is A's session's history port: the hub renders the timeline,
  // which pulls it.)
  if (d->Hub->GetNumberOfSelectedIds() == 0)
  {
    d->Sets->clearSelection();
  }
  this->statusBar()->showMessage(
    QString("%1 Gaussians selected").arg(d->Hub->GetNumberOfSelectedIds()));
}

//------------------------------------------------------------------------------
bool Vis4GSCompareWindow::RunSelfTest()
{
  bool ok = true;
  auto check = [&ok](bool condition, const std::string& what)
  {
    std::cout << (condition ? "ok: " : "FAILED: ") << what << std::endl;
    ok = ok && condition;
  };
  QDir().mkpath(d->SelfTestDir);
  const Vis4GSComparison& c = *d->Comparison;
  auto grab = [this](int side) { return d->Views[side].Widget->grabFramebuffer(); };
  auto save = [this](const QImage& image, const QString& name)
  { return image.save(d->SelfTestDir + "/" + name); };

  // 1. The shown sets: the legend's counts and the ids each entry selects, for the comparison
  // with `vis4gs compare`'s differences.csv (Testing/CheckCompareWindow.py).
  {
    QFile file(d->SelfTestDir + "/compare-sets.csv");
    check(file.open(QIODevice::WriteOnly | QIODevice::Text), "compare-sets.csv can be written");
    QTextStream out(&file);
    out << "set,shown,selected,ids\n";
    for (int row = 0; row < d->Sets->count(); ++row)
    {
      QListWidgetItem* item = d->Sets->item(row);
      const int set = item->data(Qt::UserRole).toInt();
      d->Sets->setCurrentItem(item);
      emit d->Sets->itemClicked(item); // as a click does
      const QString shown = item->text().section(": ", 1);
      out << Vis4GSComparison::SetName(set) << "," << shown << ","
          << d->Hub->GetNumberOfSelectedIds() << ",";
      for (const vtkIdType id : d->Hub->GetSelectedIdVector())
      {
        out << id << " ";
      }
      out << "\n";
      check(shown.toLongLong() == d->Hub->GetNumberOfSelectedIds(),
        std::string("the legend's ") + Vis4GSComparison::SetName(set) + " count (" +
          shown.toStdString() + ") is what its click selects");
    }
  }
  d->Hub->ClearSelection();

  // 2. One camera: a drag in view A moves view B's camera and renders B.
  {
    vtkCamera* camera = d->Views[0].View->GetRenderer()->GetActiveCamera();
    check(camera == d->Camera && d->Views[1].View->GetRenderer()->GetActiveCamera() == camera &&
        d->Views[1].View->GetMarkerRenderer()->GetActiveCamera() == camera,
      "both scene views (and their markers) draw through one camera");
    const QImage before = grab(1);
    double position[3];
    d->Camera->GetPosition(position);
    const int rendersB = d->Views[1].Renders;
    vtkRenderWindowInteractor* iren = d->Views[0].Window->GetInteractor();
    const int* size = d->Views[0].Window->GetSize();
    const int x = size[0] / 2, y = size[1] / 2;
    iren->SetEventInformation(x, y);
    iren->InvokeEvent(vtkCommand::LeftButtonPressEvent);
    for (int step = 1; step <= 4; ++step)
    {
      iren->SetEventInformation(x + 15 * step, y + 5 * step);
      iren->InvokeEvent(vtkCommand::MouseMoveEvent);
    }
    iren->InvokeEvent(vtkCommand::LeftButtonReleaseEvent);
    double moved[3];
    d->Views[1].View->GetRenderer()->GetActiveCamera()->GetPosition(moved);
    const double distance =
      std::hypot(moved[0] - position[0], moved[1] - position[1], moved[2] - position[2]);
    check(distance > 0,
      "dragging in view A moved the camera of view B (by " + std::to_string(distance) + ")");
    check(d->Views[1].Renders > rendersB && d->Views[1].RenderedCamera >= d->Camera->GetMTime(),
      "view B was rendered with the moved camera");
    const QImage after = grab(1);
    check(before.size() == after.size() && before != after, "view B's picture changed");
    // Back to the first view for the pictures.
    this->ShowFirstCamera();
  }

  // 3. The overlay: each view shows the colours of its sets; true colour differs.
  const QImage overlayA = grab(0), overlayB = grab(1);
  save(overlayA, "compare-a.png");
  save(overlayB, "compare-b.png");
  for (int side = 0; side < 2; ++side)
  {
    const QImage& image = side == 0 ? overlayA : overlayB;
    const std::array<long long, 2> drawn = CountPixels(image, { { 0, 0, 0 } });
    check(drawn[1] > image.width() * image.height() / 100,
      std::string("view ") + (side == 0 ? "A" : "B") + " draws Gaussians (" +
        std::to_string(drawn[1]) + " pixels)");
  }
  check(overlayA != overlayB, "the two states' pictures differ");
  // Born and died Gaussians, framed by "Zoom to selection" and then unselected (no highlight):
  // their colour is in the view of the state they are in, hardly in the other.
  for (const int set : { Vis4GSComparison::DIED, Vis4GSComparison::BORN })
  {
    if (c.Ids[set].empty())
    {
      continue;
    }
    this->SelectSet(set);
    check(this->ZoomToSelection(), std::string("zoom to the ") + Vis4GSComparison::SetName(set));
    d->Hub->ClearSelection();
    const int side = set == Vis4GSComparison::DIED ? 0 : 1;
    const QImage here = grab(side), there = grab(1 - side);
    save(here,
      QString("compare-%1-%2.png").arg(side == 0 ? "a" : "b").arg(Vis4GSComparison::SetName(set)));
    save(there,
      QString("compare-%1-%2-other-view.png")
        .arg(side == 0 ? "a" : "b")
        .arg(Vis4GSComparison::SetName(set)));
    const long long pixels = CountPixels(here, Vis4GSComparison::SetColor(set))[0];
    const long long other = CountPixels(there, Vis4GSComparison::SetColor(set))[0];
    check(pixels > 20 && pixels > 4 * other,
      std::string("the ") + Vis4GSComparison::SetName(set) + " colour is in view " +
        (side == 0 ? "A" : "B") + " (" + std::to_string(pixels) + " pixels, " +
        std::to_string(other) + " in the other view)");
  }
  this->ShowFirstCamera();
  d->Overlay->setCurrentIndex(1);
  const QImage trueA = grab(0);
  save(trueA, "compare-a-true-colour.png");
  check(trueA != overlayA, "true colour differs from the difference overlay");
  d->Overlay->setCurrentIndex(0);

  // 4. A set selected in the legend is highlighted in both views (a set of both states).
  int both = Vis4GSComparison::MOVED;
  for (const int set : { Vis4GSComparison::MOVED,
         Vis4GSComparison::SCALE,
         Vis4GSComparison::OPACITY,
         Vis4GSComparison::UNCHANGED })
  {
    if (!c.Ids[set].empty())
    {
      both = set;
      break;
    }
  }
  this->SelectSet(both);
  for (int side = 0; side < 2; ++side)
  {
    vtkIdTypeArray* ids = d->Views[side].View->GetSplatMapper()->GetSelectedIds();
    check(ids && static_cast<std::size_t>(ids->GetNumberOfTuples()) == c.Ids[both].size(),
      std::string("view ") + (side == 0 ? "A" : "B") + " highlights the " +
        Vis4GSComparison::SetName(both) + " set");
    const QImage selected = grab(side);
    save(selected,
      QString("compare-%1-selected-%2.png")
        .arg(side == 0 ? "a" : "b")
        .arg(QString(Vis4GSComparison::SetName(both)).replace(' ', '-')));
    check(selected != (side == 0 ? overlayA : overlayB),
      std::string("view ") + (side == 0 ? "A" : "B") + "'s picture shows the selection");
  }

  // 5. The scene views' selection modes go through the hub: a frame over the whole of view B
  // selects what B draws, and view A highlights those of its Gaussians that have the same ids.
  {
    d->Hub->ClearSelection();
    vtkGaussianSceneView* a = d->Views[0].View;
    vtkGaussianSceneView* b = d->Views[1].View;
    const int* size = b->GetRenderWindow()->GetSize();
    const vtkIdType picked = b->SelectFrame(0, 0, size[0] - 1, size[1] - 1);
    check(
      picked > 0 && d->Hub->GetNumberOfSelectedIds() == picked && b->GetHighlightCount() == picked,
      "a frame over view B selects the " + std::to_string(picked) + " Gaussians it draws");
    vtkDataArray* idsA = c.A.Scene->GetPointData()->GetArray("GaussianId");
    vtkIdType inA = 0;
    for (vtkIdType row = 0; idsA && row < idsA->GetNumberOfTuples(); ++row)
    {
      inA += d->Hub->IsSelected(static_cast<vtkIdType>(idsA->GetTuple1(row)));
    }
    check(inA > 0 && a->GetHighlightCount() == inA,
      "view A highlights the " + std::to_string(inA) + " of them that state A has");
    const vtkIdType marked = a->GetMarkers()->GetNumberOfPoints();
    check(marked == (inA <= a->GetMaximumNumberOfMarkers() ? inA : 0),
      "view A marks a small selection's centres (" + std::to_string(marked) + " markers)");
    d->Hub->ClearSelection();
  }

  // 6. The timeline holds the runs' metric curves, named in the legend (hidden without any).
  vtkGaussianTimelineView* t = d->Timeline;
  const bool curves = c.A.Metrics || c.B.Metrics;
  check(d->TimelineWidget->isVisible() == curves,
    std::string("the timeline is ") + (curves ? "shown" : "hidden: neither state has metrics"));
  const int comparison = t->GetNumberOfComparisonPlots();
  if (c.SameLog)
  {
    check(comparison == 0 && t->GetNumberOfMetricPlots() > 0,
      "two iterations of one log: its curves once (" + std::to_string(t->GetNumberOfMetricPlots()) +
        " plots)");
  }
  else
  {
    check(c.B.Metrics == nullptr || comparison > 0,
      "the timeline holds both runs' curves (" + std::to_string(t->GetNumberOfMetricPlots()) +
        " plots, " + std::to_string(comparison) + " of run B)");
    int named = 0;
    vtkGaussianTimelineChart* quality = t->GetChart(vtkGaussianTimelineView::QUALITY);
    for (vtkIdType k = 0; k < quality->GetNumberOfPlots(); ++k)
    {
      const std::string label = quality->GetPlot(k)->GetLabel();
      named += label.find("[B: " + c.B.Name + "]") != std::string::npos;
    }
    check(c.B.Metrics == nullptr || named > 0, "the legend names run B");
  }
  check(t->GetIteration() == c.A.Iteration && t->GetComparisonIteration() == c.B.Iteration,
    "the timeline's cursors mark A's and B's iterations (" + std::to_string(t->GetIteration()) +
      ", " + std::to_string(t->GetComparisonIteration()) + ")");
  this->SelectSet(both);
  if (c.A.Session)
  {
    check(t->GetNumberOfHistoryLines() ==
        std::min<int>(static_cast<int>(c.Ids[both].size()), t->GetMaximumHistoryLines()),
      "the timeline draws the history of the selected Gaussians (" +
        std::to_string(t->GetNumberOfHistoryLines()) + " lines)");
  }
  std::cout << "timeline: " << t->GetNumberOfMetricPlots() << " metric plots, " << comparison
            << " of run B" << std::endl;

  d->Hub->ClearSelection();
  this->resize(1280, 800);
  QApplication::processEvents();
  check(this->grab().save(d->SelfTestDir + "/compare-window.png"), "compare-window.png saved");
  this->SelectSet(c.Ids[Vis4GSComparison::DIED].empty() ? both : Vis4GSComparison::DIED);
  QApplication::processEvents();
  check(this->grab().save(d->SelfTestDir + "/compare-window-selected.png"),
    "compare-window-selected.png saved");
  check(!curves || d->TimelineWidget->grab().save(d->SelfTestDir + "/compare-timeline.png"),
    "compare-timeline.png saved");
  std::cout << (ok ? "compare self-test passed" : "compare self-test FAILED") << std::endl;
  return ok;
}

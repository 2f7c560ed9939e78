/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianSceneView.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianSceneView.h"

#include "GaussianCloud.h"
#include "Vis4GSDataModel.h"
#include "Vis4GSHubLink.h"
#include "Vis4GSIdColumn.h"
#include "Vis4GSViewInput.h"
#include "vtkGaussianCameraFrustums.h"
#include "vtkGaussianCameraUtilities.h"
#include "vtkGaussianSelectionHub.h"
#include "vtkGaussianSelector.h"
#include "vtkGaussianSplatMapper.h"

#include "vtkActor.h"
#include "vtkActor2D.h"
#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInteractorObserver.h"
#include "vtkLookupTable.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkPolyDataMapper2D.h"
#include "vtkProperty.h"
#include "vtkProperty2D.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkScalarBarActor.h"
#include "vtkSmartPointer.h"
#include "vtkTable.h"
#include "vtkWeakPointer.h"

#include <algorithm>
#include <cstdlib>
#include <functional>
#include <string>

namespace
{
// Mouse events of the interactor to the view; can abort them so that the camera style does
// not rotate while brushing or framing.
class MouseCommand : public vtkCommand
{
public:
  static MouseCommand* New() { return new MouseCommand; }
  void Execute(vtkObject*, unsigned long event, void*) override
  {
    bool abort = false;
    this->Callback(event, abort);
    this->SetAbortFlag(abort ? 1 : 0);
  }
  std::function<void(unsigned long, bool&)> Callback;
};
}

//------------------------------------------------------------------------------
struct vtkGaussianSceneView::vtkInternals
{
  vtkSmartPointer<vtkPolyData> Scene;
  vtkSmartPointer<vtkTable> Cameras;
  Vis4GSViewInput SceneInput;
  Vis4GSViewInput CamerasInput;
  Vis4GSHubLink Hub;
  vtkNew<vtkCallbackCommand> HubCommand;
  // The one Core form of the scene's Gaussians, shared by the mapper and the selector (the
  // scene's own arrays for a reader's scene, else a conversion); taken again when the scene
  // or its MTime changes (checked before each render).
  std::shared_ptr<const vis4gs::GaussianCloud> Cloud;
  vtkPolyData* CloudScene = nullptr; // identity only
  vtkMTimeType CloudTime = 0;
  vtkNew<vtkCallbackCommand> RenderStartCommand;

  vtkNew<vtkGaussianSplatMapper> Mapper;
  vtkNew<vtkActor> Actor;
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

  vtkWeakPointer<vtkRenderWindowInteractor> Interactor;
  std::vector<unsigned long> InteractorObservers;
  std::vector<std::array<double, 2>> Stroke;
  bool Dragging = false;
  int PressPosition[2] = { 0, 0 };

  // Makes the shared copy current for the scene (a no-op when it is).
  void ShareGaussians()
  {
    vtkPolyData* scene = this->Scene;
    if (scene == this->CloudScene && (!scene || scene->GetMTime() == this->CloudTime))
    {
      return;
    }
    this->Cloud.reset(); // (the old copy is released before a new one is made)
    this->Mapper->SetSharedGaussians(nullptr, nullptr);
    this->Selector->SetSharedGaussians(nullptr, nullptr);
    this->CloudScene = scene;
    this->CloudTime = scene ? scene->GetMTime() : 0;
    if (!scene)
    {
      return;
    }
    // Not a Gaussian scene: the mapper and the selector report why when they use it.
    this->Cloud = vtkGaussianSplatMapper::ConvertScene(scene, nullptr);
    if (!this->Cloud)
    {
      return;
    }
    this->Mapper->SetSharedGaussians(scene, this->Cloud);
    this->Selector->SetSharedGaussians(scene, this->Cloud);
  }
};

vtkStandardNewMacro(vtkGaussianSceneView);

//------------------------------------------------------------------------------
vtkGaussianSceneView::vtkGaussianSceneView()
  : Internals(new vtkInternals)
{
  auto& in = *this->Internals;
  // The camera frustums are opaque lines added first so that the splats are blended over
  // them (vtkGaussianSplatMapper).
  vtkRenderer* renderer = this->GetRenderer();
  renderer->SetBackground(0, 0, 0);
  in.FrustumColors->SetHueRange(0.6, 0.0);
  in.FrustumColors->SetSaturationRange(0.2, 1.0);
  in.FrustumColors->SetValueRange(0.6, 1.0);
  in.FrustumColors->Build();
  in.FrustumMapper->SetInputConnection(in.Frustums->GetOutputPort());
  in.FrustumMapper->SetLookupTable(in.FrustumColors);
  in.FrustumMapper->SetScalarModeToUsePointData();
  in.FrustumMapper->SetColorModeToMapScalars();
  in.FrustumActor->SetMapper(in.FrustumMapper);
  in.FrustumActor->GetProperty()->SetLineWidth(1.5);
  in.FrustumActor->PickableOff();
  in.FrustumActor->VisibilityOff();
  renderer->AddActor(in.FrustumActor);
  in.Mapper->SetDimUnselected(false);
  in.Mapper->SetMaximumNumberOfSplats(200000);
  in.Actor->SetMapper(in.Mapper);
  renderer->AddActor(in.Actor);
  in.Legend->SetNumberOfLabels(5);
  // Wide enough for the "suspicious" annotation at the bright end of a score's map.
  in.Legend->SetMaximumWidthInPixels(150);
  in.Legend->SetAnnotationLeaderPadding(4);
  in.Legend->SetVerticalTitleSeparation(10);
  in.Legend->SetPosition(0.88, 0.1);
  in.Legend->SetPosition2(0.11, 0.8);
  in.Legend->VisibilityOff();
  renderer->AddViewProp(in.Legend);
  in.BandMapper->SetInputData(in.Band);
  in.BandActor->SetMapper(in.BandMapper);
  in.BandActor->GetProperty()->SetColor(1.0, 0.85, 0.2);
  in.BandActor->GetProperty()->SetLineWidth(1.5);
  renderer->AddViewProp(in.BandActor);
  in.MarkerRenderer->SetLayer(1);
  in.MarkerRenderer->InteractiveOff();
  in.MarkerRenderer->SetActiveCamera(renderer->GetActiveCamera());
  in.MarkerMapper->SetInputData(in.Markers);
  in.MarkerMapper->ScalarVisibilityOff();
  in.MarkerActor->SetMapper(in.MarkerMapper);
  in.MarkerActor->GetProperty()->SetRepresentationToWireframe();
  in.MarkerActor->GetProperty()->SetColor(1.0, 0.35, 0.0);
  in.MarkerActor->GetProperty()->SetPointSize(7);
  in.MarkerActor->GetProperty()->SetLineWidth(2);
  in.MarkerActor->PickableOff();
  in.MarkerRenderer->AddActor(in.MarkerActor);
  in.Selector->SetRenderer(renderer);
  in.Selector->SetSplatMapper(in.Mapper); // selections reuse the still frame's projection
  in.HubCommand->SetClientData(this);
  in.HubCommand->SetCallback([](vtkObject*, unsigned long, void* client, void*)
    { static_cast<vtkGaussianSceneView*>(client)->OnSelectionChanged(); });
  // Every render (the view's, the hub's or the interactor's) draws the shared copy.
  in.RenderStartCommand->SetClientData(this);
  in.RenderStartCommand->SetCallback(
    [](vtkObject*, unsigned long, void* client, void*)
    {
      auto* self = static_cast<vtkGaussianSceneView*>(client);
      self->Internals->ShareGaussians();
    });
  renderer->AddObserver(vtkCommand::StartEvent, in.RenderStartCommand);
  this->SetRenderWindow(this->RenderWindow);
}

//------------------------------------------------------------------------------
vtkGaussianSceneView::~vtkGaussianSceneView()
{
  this->SetSelectionHub(nullptr);
  this->ObserveInteractor(nullptr);
  this->GetRenderer()->RemoveObserver(this->Internals->RenderStartCommand);
  this->SetOverlayArrayName(nullptr);
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::SetRenderWindow(vtkRenderWindow* window)
{
  auto& in = *this->Internals;
  if (window && window != this->RenderWindow)
  {
    // The superclass gives the new window's interactor the style of the old one; the window's
    // own (e.g. the Qt widget's trackball camera) is kept instead.
    vtkRenderWindowInteractor* interactor = window->GetInteractor();
    vtkSmartPointer<vtkInteractorObserver> style =
      interactor ? interactor->GetInteractorStyle() : nullptr;
    this->Superclass::SetRenderWindow(window); // (moves the marker renderer too)
    if (interactor && style)
    {
      interactor->SetInteractorStyle(style);
    }
  }
  if (this->RenderWindow)
  {
    this->RenderWindow->SetNumberOfLayers(std::max(2, this->RenderWindow->GetNumberOfLayers()));
    if (!this->RenderWindow->HasRenderer(in.MarkerRenderer))
    {
      this->RenderWindow->AddRenderer(in.MarkerRenderer);
    }
    this->ObserveInteractor(this->RenderWindow->GetInteractor());
  }
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::SetInteractor(vtkRenderWindowInteractor* interactor)
{
  this->Superclass::SetInteractor(interactor);
  this->ObserveInteractor(interactor);
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::ObserveInteractor(vtkRenderWindowInteractor* interactor)
{
  auto& in = *this->Internals;
  if (interactor == in.Interactor)
  {
    return;
  }
  if (in.Interactor)
  {
    for (unsigned long tag : in.InteractorObservers)
    {
      in.Interactor->RemoveObserver(tag);
    }
  }
  in.InteractorObservers.clear();
  in.Interactor = interactor;
  if (!interactor)
  {
    return;
  }
  // Brush and Frame drags: observed before the camera style, which they abort (so it never
  // grabs the mouse). Single and Ray clicks: the style rotates on a press and grabs the mouse
  // focus, so the release is observed by a passive observer, which VTK calls even then.
  vtkNew<MouseCommand> mouse;
  mouse->Callback = [this](unsigned long event, bool& abort) { this->OnMouse(event, abort); };
  for (unsigned long event : { vtkCommand::LeftButtonPressEvent,
         vtkCommand::MouseMoveEvent,
         vtkCommand::LeftButtonReleaseEvent })
  {
    in.InteractorObservers.push_back(interactor->AddObserver(event, mouse, 1.0));
  }
  vtkNew<MouseCommand> click;
  click->PassiveObserverOn();
  click->Callback = [this](unsigned long, bool&) { this->OnClick(); };
  in.InteractorObservers.push_back(
    interactor->AddObserver(vtkCommand::LeftButtonReleaseEvent, click, 2.0));
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::SetScene(vtkPolyData* scene)
{
  this->Internals->SceneInput.SetConnection(nullptr);
  this->ApplyScene(scene);
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::ApplyScene(vtkPolyData* scene)
{
  auto& in = *this->Internals;
  in.Scene = scene;
  in.Mapper->SetInputData(scene);
  in.Selector->SetScene(scene);
  in.Frustums->SetInputData(1, scene);
  in.ShareGaussians();
  if (scene)
  {
    // The id column's order (one pass over its ids) is learnt now rather than at the first pick
    // (the linked views look their selections up in it on this thread).
    vis4gs::IdColumnOrderOf(
      vtkIdTypeArray::SafeDownCast(scene->GetPointData()->GetArray(vis4gs::arrays::GaussianId)));
  }
  this->UpdateOverlay();
  this->OnSelectionChanged();
  this->Modified();
}

//------------------------------------------------------------------------------
vtkPolyData* vtkGaussianSceneView::GetScene()
{
  return this->Internals->Scene;
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::SetCameras(vtkTable* cameras)
{
  this->Internals->CamerasInput.SetConnection(nullptr);
  this->ApplyCameras(cameras);
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::ApplyCameras(vtkTable* cameras)
{
  auto& in = *this->Internals;
  in.Cameras = cameras;
  in.Frustums->SetInputData(0, cameras);
  this->UpdateFrustums();
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::SetInputConnection(vtkAlgorithmOutput* output)
{
  this->Internals->SceneInput.SetConnection(output);
  this->Modified();
}
vtkAlgorithmOutput* vtkGaussianSceneView::GetInputConnection()
{
  return this->Internals->SceneInput.GetConnection();
}
void vtkGaussianSceneView::SetCamerasConnection(vtkAlgorithmOutput* output)
{
  this->Internals->CamerasInput.SetConnection(output);
  this->Modified();
}
vtkAlgorithmOutput* vtkGaussianSceneView::GetCamerasConnection()
{
  return this->Internals->CamerasInput.GetConnection();
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::Update()
{
  auto& in = *this->Internals;
  vtkSmartPointer<vtkDataObject> data;
  if (in.CamerasInput.Pull(data))
  {
    this->ApplyCameras(vtkTable::SafeDownCast(data.GetPointer()));
  }
  if (in.SceneInput.Pull(data))
  {
    this->ApplyScene(vtkPolyData::SafeDownCast(data.GetPointer()));
  }
  this->Superclass::Update();
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::Render()
{
  this->Update();
  if (this->Internals->Cameras && this->ShowFrustums)
  {
    this->UpdateFrustumColors();
  }
  this->Superclass::Render();
}

//------------------------------------------------------------------------------
vtkTable* vtkGaussianSceneView::GetCameras()
{
  return this->Internals->Cameras;
}

//------------------------------------------------------------------------------
bool vtkGaussianSceneView::JumpToCamera(vtkIdType row)
{
  auto& in = *this->Internals;
  return in.Cameras && row >= 0 &&
    vtkGaussianCameraUtilities::JumpToCamera(this->GetRenderer(), in.Cameras, row);
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::SetSelectionHub(vtkGaussianSelectionHub* hub)
{
  auto& in = *this->Internals;
  if (!in.Hub.Link(hub, in.HubCommand, this, false))
  {
    return;
  }
  this->OnSelectionChanged();
  this->Modified();
}

//------------------------------------------------------------------------------
vtkGaussianSelectionHub* vtkGaussianSceneView::GetSelectionHub()
{
  return this->Internals->Hub;
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::SetOverlayArrayName(const char* name)
{
  const std::string current = this->OverlayArrayName ? this->OverlayArrayName : "";
  if (current == (name ? name : ""))
  {
    return;
  }
  delete[] this->OverlayArrayName;
  this->OverlayArrayName = nullptr;
  if (name && *name)
  {
    this->OverlayArrayName = new char[std::string(name).size() + 1];
    std::copy(name, name + std::string(name).size() + 1, this->OverlayArrayName);
  }
  this->UpdateOverlay();
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::SetOverlayRange(double lo, double hi)
{
  if (this->OverlayRange[0] != lo || this->OverlayRange[1] != hi)
  {
    this->OverlayRange[0] = lo;
    this->OverlayRange[1] = hi;
    this->UpdateOverlay();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::SetHideOutsideRange(bool hide)
{
  if (this->HideOutsideRange != hide)
  {
    this->HideOutsideRange = hide;
    this->UpdateOverlay();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::SetUseThreshold(bool use)
{
  if (this->UseThreshold != use)
  {
    this->UseThreshold = use;
    this->UpdateOverlay();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::SetThreshold(double threshold)
{
  if (this->Threshold != threshold)
  {
    this->Threshold = threshold;
    this->UpdateOverlay();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::SetDimUnselected(bool dim)
{
  if (this->DimUnselected != dim)
  {
    this->DimUnselected = dim;
    this->UpdateOverlay();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::SetShowFrustums(bool show)
{
  if (this->ShowFrustums != show)
  {
    this->ShowFrustums = show;
    this->UpdateFrustums();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::SetMaximumNumberOfSplats(vtkIdType splats)
{
  this->Internals->Mapper->SetMaximumNumberOfSplats(splats);
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianSceneView::GetMaximumNumberOfSplats()
{
  return this->Internals->Mapper->GetMaximumNumberOfSplats();
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::SetInteractiveSplatBudget(vtkIdType splats)
{
  this->Internals->Mapper->SetInteractiveSplatBudget(splats);
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianSceneView::GetInteractiveSplatBudget()
{
  return this->Internals->Mapper->GetInteractiveSplatBudget();
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::UpdateOverlay()
{
  auto& in = *this->Internals;
  vtkGaussianSplatMapper* mapper = in.Mapper;
  const char* array = this->OverlayArrayName;
  const bool score = in.Scene && array && in.Scene->GetPointData()->GetArray(array);
  mapper->SetDimUnselected(this->DimUnselected);
  if (!score)
  {
    mapper->SetSplatColoringToTrueColor();
    mapper->HideOutsideRangeOff();
    in.Legend->VisibilityOff();
    return;
  }
  mapper->SetSplatColoringToScore();
  mapper->SetScoreArrayName(array);
  const double lo = this->OverlayRange[0], hi = this->OverlayRange[1];
  if (hi > lo)
  {
    mapper->SetScoreRange(lo, hi);
  }
  else
  {
    mapper->AutoScoreRangeOn();
  }
  mapper->SetHideOutsideRange(this->HideOutsideRange || this->UseThreshold);
  double visible[2] = { VTK_DOUBLE_MIN, VTK_DOUBLE_MAX };
  if (this->HideOutsideRange)
  {
    visible[0] = lo;
    visible[1] = hi;
  }
  if (this->UseThreshold)
  {
    visible[0] = std::max(visible[0], this->Threshold);
  }
  mapper->SetVisibleRange(visible);
  in.Legend->SetLookupTable(mapper->GetScoreLookupTable());
  in.Legend->SetTitle(array);
  in.Legend->VisibilityOn();
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::UpdateFrustums(vtkIdTypeArray* selected)
{
  auto& in = *this->Internals;
  const bool show = in.Cameras && this->ShowFrustums;
  in.FrustumActor->SetVisibility(show);
  if (show)
  {
    vtkNew<vtkIdTypeArray> ids;
    if (!selected && in.Hub)
    {
      in.Hub->GetSelectedIds(ids);
    }
    in.Frustums->SetSelectedIds(selected ? selected : ids.GetPointer());
    this->UpdateFrustumColors();
  }
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::UpdateFrustumColors()
{
  // (Also at each render: a large selection's counts arrive from the frustums' worker.)
  auto& in = *this->Internals;
  in.Frustums->Update();
  double range[2] = { 0, 1 };
  if (vtkDataArray* counts =
        in.Frustums->GetOutput()->GetPointData()->GetArray("VisibleSelectedCount"))
  {
    counts->GetRange(range);
  }
  in.FrustumMapper->SetScalarRange(0, std::max(1.0, range[1]));
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::OnSelectionChanged()
{
  auto& in = *this->Internals;
  vtkPolyData* scene = in.Scene;
  // The hub's own array (never modified after a change): the mapper and the frustums keep it
  // rather than a copy.
  vtkSmartPointer<vtkIdTypeArray> selected = in.Hub
    ? vtkSmartPointer<vtkIdTypeArray>(in.Hub->GetSelectedIdArray())
    : vtkSmartPointer<vtkIdTypeArray>::New();
  this->HighlightCount = 0;
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> verts;
  if (scene)
  {
    vtkDataArray* idColumn = scene->GetPointData()->GetArray(vis4gs::arrays::GaussianId);
    // A selection too large for markers needs only its count in the scene.
    vtkIdType found = 0;
    const bool counted = selected->GetNumberOfTuples() > this->MaximumNumberOfMarkers &&
      vis4gs::ForEachRowOfIds(vtkIdTypeArray::SafeDownCast(idColumn),
        selected->GetPointer(0),
        selected->GetNumberOfTuples(),
        [&found](vtkIdType) { ++found; }) &&
      found > this->MaximumNumberOfMarkers;
    if (counted)
    {
      this->HighlightCount = found;
    }
    else
    {
      vtkNew<vtkIdTypeArray> rows;
      vtkGaussianSelectionHub::IdsToIndices(selected, idColumn, rows);
      this->HighlightCount = rows->GetNumberOfTuples();
      // Markers (a point at the centre) for small selections, drawn over the splats.
      if (this->HighlightCount <= this->MaximumNumberOfMarkers)
      {
        for (vtkIdType k = 0; k < rows->GetNumberOfTuples(); ++k)
        {
          const vtkIdType v = points->InsertNextPoint(scene->GetPoint(rows->GetValue(k)));
          verts->InsertNextCell(1, &v);
        }
      }
    }
  }
  in.Markers->SetPoints(points);
  in.Markers->SetVerts(verts);
  in.Markers->Modified();
  if (in.Mapper->GetSelectedIds() == selected)
  {
    in.Mapper->Modified(); // (a new scene, the same selection: its flags are made again)
  }
  in.Mapper->SetSelectedIds(selected);
  this->UpdateFrustums(selected);
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianSceneView::Select(int mode,
  const std::vector<std::array<double, 2>>& points,
  int combine)
{
  auto& in = *this->Internals;
  if (!in.Scene || !in.Hub || points.empty())
  {
    return -1;
  }
  // The hub is the one selection state (it holds the other views' selections too): the
  // selector computes this mode's pick and combines it into the hub by @p combine.
  in.ShareGaussians();
  vtkGaussianSelector* selector = in.Selector;
  selector->SetSelectionHub(in.Hub);
  selector->SetModifier(combine);
  vtkIdType count = -1;
  switch (mode)
  {
    case SINGLE:
      count = selector->SelectSingle(points[0][0], points[0][1]);
      break;
    case RAY:
      count = selector->SelectRay(points[0][0], points[0][1]);
      break;
    case FRAME:
    {
      const auto b = points.size() > 1 ? points[1] : points[0];
      count = selector->SelectFrame(points[0][0], points[0][1], b[0], b[1]);
      break;
    }
    case BRUSH:
    {
      vtkNew<vtkPoints> stroke;
      for (const auto& q : points)
      {
        stroke->InsertNextPoint(q[0], q[1], 0.0);
      }
      count = selector->SelectBrush(stroke);
      break;
    }
    default:
      return -1;
  }
  if (count < 0)
  {
    return -1;
  }
  this->LastSelectionMode = mode;
  this->LastSelectionCount = count;
  this->InvokeEvent(vtkCommand::EndPickEvent, nullptr);
  return count;
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianSceneView::SelectSingle(double x, double y, int combine)
{
  return this->Select(SINGLE, { { x, y } }, combine);
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianSceneView::SelectRay(double x, double y, int combine)
{
  return this->Select(RAY, { { x, y } }, combine);
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianSceneView::SelectFrame(double x0, double y0, double x1, double y1, int combine)
{
  return this->Select(FRAME, { { x0, y0 }, { x1, y1 } }, combine);
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianSceneView::SelectBrush(vtkPoints* stroke, int combine)
{
  std::vector<std::array<double, 2>> points;
  for (vtkIdType k = 0; stroke && k < stroke->GetNumberOfPoints(); ++k)
  {
    double p[3];
    stroke->GetPoint(k, p);
    points.push_back({ p[0], p[1] });
  }
  return this->Select(BRUSH, points, combine);
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianSceneView::PickAt(double x, double y)
{
  const vtkIdType n = this->SelectSingle(x, y, vtkGaussianSelectionHub::REPLACE);
  vtkIdTypeArray* ids = this->Internals->Selector->GetSelectedIds();
  return n == 1 && ids && ids->GetNumberOfTuples() == 1 ? ids->GetValue(0) : -1;
}

//------------------------------------------------------------------------------
vtkIdTypeArray* vtkGaussianSceneView::GetLastRayHitIds()
{
  return this->Internals->Selector->GetRayHitIds();
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::DrawBand()
{
  auto& in = *this->Internals;
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> lines;
  std::vector<std::array<double, 2>> corners = in.Stroke;
  if (this->SelectionMode == FRAME && in.Stroke.size() >= 2)
  {
    const auto a = in.Stroke.front(), b = in.Stroke.back();
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
  in.Band->SetPoints(points);
  in.Band->SetLines(lines);
  in.Band->Modified();
  this->Render();
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::OnMouse(unsigned long event, bool& abort)
{
  auto& in = *this->Internals;
  vtkRenderWindowInteractor* i = in.Interactor;
  const int mode = this->SelectionMode;
  const int* p = i->GetEventPosition();
  const std::array<double, 2> at = { static_cast<double>(p[0]), static_cast<double>(p[1]) };
  const bool drag = mode == BRUSH || mode == FRAME;
  if (event == vtkCommand::LeftButtonPressEvent)
  {
    in.PressPosition[0] = p[0];
    in.PressPosition[1] = p[1];
    if (drag)
    {
      in.Dragging = true;
      in.Stroke.assign(1, at);
      abort = true;
    }
  }
  else if (event == vtkCommand::MouseMoveEvent)
  {
    if (in.Dragging)
    {
      if (mode == FRAME && in.Stroke.size() > 1)
      {
        in.Stroke.back() = at;
      }
      else
      {
        in.Stroke.push_back(at);
      }
      this->DrawBand();
      abort = true;
    }
  }
  else if (event == vtkCommand::LeftButtonReleaseEvent && in.Dragging)
  {
    in.Dragging = false;
    abort = true;
    std::vector<std::array<double, 2>> points = in.Stroke;
    if (mode == FRAME)
    {
      points = { in.Stroke.front(), at };
    }
    in.Stroke.clear();
    this->DrawBand();
    const int combine = i->GetShiftKey() ? vtkGaussianSelectionHub::ADD
      : i->GetControlKey()               ? vtkGaussianSelectionHub::SUBTRACT
                                         : vtkGaussianSelectionHub::REPLACE;
    this->Select(mode, points, combine);
  }
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::OnClick()
{
  auto& in = *this->Internals;
  vtkRenderWindowInteractor* i = in.Interactor;
  const int mode = this->SelectionMode;
  const int* p = i->GetEventPosition();
  if ((mode == SINGLE || mode == RAY) &&
    std::abs(p[0] - in.PressPosition[0]) + std::abs(p[1] - in.PressPosition[1]) < 3)
  {
    const int combine = i->GetShiftKey() ? vtkGaussianSelectionHub::ADD
      : i->GetControlKey()               ? vtkGaussianSelectionHub::SUBTRACT
                                         : vtkGaussianSelectionHub::REPLACE;
    this->Select(mode, { { static_cast<double>(p[0]), static_cast<double>(p[1]) } }, combine);
  }
}

//------------------------------------------------------------------------------
vtkGaussianSplatMapper* vtkGaussianSceneView::GetSplatMapper()
{
  return this->Internals->Mapper;
}

vtkGaussianSelector* vtkGaussianSceneView::GetSelector()
{
  return this->Internals->Selector;
}

vtkScalarBarActor* vtkGaussianSceneView::GetLegend()
{
  return this->Internals->Legend;
}

vtkGaussianCameraFrustums* vtkGaussianSceneView::GetFrustums()
{
  return this->Internals->Frustums;
}

vtkActor* vtkGaussianSceneView::GetFrustumActor()
{
  return this->Internals->FrustumActor;
}

vtkPolyData* vtkGaussianSceneView::GetMarkers()
{
  return this->Internals->Markers;
}

vtkPolyData* vtkGaussianSceneView::GetBand()
{
  return this->Internals->Band;
}

vtkRenderer* vtkGaussianSceneView::GetMarkerRenderer()
{
  return this->Internals->MarkerRenderer;
}

//------------------------------------------------------------------------------
void vtkGaussianSceneView::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  auto& in = *this->Internals;
  os << indent << "Scene: " << in.Scene.GetPointer() << "\n";
  os << indent << "InputConnection: " << in.SceneInput.GetConnection() << "\n";
  os << indent << "CamerasConnection: " << in.CamerasInput.GetConnection() << "\n";
  os << indent << "Cameras: " << in.Cameras.GetPointer() << "\n";
  os << indent << "SelectionHub: " << in.Hub.GetPointer() << "\n";
  os << indent << "SelectionMode: " << this->SelectionMode << "\n";
  os << indent << "OverlayArrayName: "
     << (this->OverlayArrayName ? this->OverlayArrayName : "(none: true colour)") << "\n";
  os << indent << "OverlayRange: " << this->OverlayRange[0] << " " << this->OverlayRange[1] << "\n";
  os << indent << "HideOutsideRange: " << this->HideOutsideRange << "\n";
  os << indent << "UseThreshold: " << this->UseThreshold << "\n";
  os << indent << "Threshold: " << this->Threshold << "\n";
  os << indent << "DimUnselected: " << this->DimUnselected << "\n";
  os << indent << "ShowFrustums: " << this->ShowFrustums << "\n";
  os << indent << "MaximumNumberOfSplats: " << in.Mapper->GetMaximumNumberOfSplats() << "\n";
  os << indent << "InteractiveSplatBudget: " << in.Mapper->GetInteractiveSplatBudget() << "\n";
  os << indent << "MaximumNumberOfMarkers: " << this->MaximumNumberOfMarkers << "\n";
  os << indent << "HighlightCount: " << this->HighlightCount << "\n";
  os << indent << "LastSelectionMode: " << this->LastSelectionMode << "\n";
  os << indent << "LastSelectionCount: " << this->LastSelectionCount << "\n";
  os << indent << "SharedGaussians: " << (in.Cloud ? in.Cloud->Count : 0) << "\n";
}

/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianTreeItem.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
// Over 1,200 lines on purpose: the one vtkContextItem of view B (one class per file), whose
// methods are the item's own duties: building its draw index from the tree, the viewport and
// zoom, the level-of-detail query, painting (bands, edges, vertices, highlight) and the mouse.
// The numerics they share (the draw index, its row windows and level of detail) are already
// Core's TreeDrawIndex, tested on their own.
#include "vtkGaussianTreeItem.h"

#include "Vis4GSDataModel.h" // vis4gs::arrays

#include "TreeDrawIndex.h"

#include "Vis4GSHubLink.h"
#include "vtkGaussianSelectionHub.h"

#include "vtkBrush.h"
#include "vtkCallbackCommand.h"
#include "vtkContext2D.h"
#include "vtkContextDevice2D.h"
#include "vtkContextMouseEvent.h"
#include "vtkContextScene.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkObjectFactory.h"
#include "vtkPen.h"
#include "vtkTable.h"
#include "vtkTextProperty.h"
#include "vtkTree.h"
#include "vtkTypeTraits.h"

#include "Genealogy.h" // vis4gs::ZoomThreshold (DESIGN §4)

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkGaussianTreeItem);

namespace
{
// DESIGN §6 node colours (CSS names).
const unsigned char KindColors[5][4] = {
  { 165, 42, 42, 255 },   // root: brown
  { 127, 255, 212, 255 }, // clone: aquamarine
  { 210, 180, 140, 255 }, // split: tan
  { 0, 128, 128, 255 },   // clone-split: teal
  { 128, 0, 128, 255 },   // prune: purple
};
const unsigned char HighlightColor[4] = { 255, 215, 0, 255 };
const unsigned char SelectedColor[4] = { 255, 64, 64, 255 };
// The ring around a root that a lineage break started (the logger lost the lineage there).
const unsigned char BreakRootColor[4] = { 255, 255, 255, 255 };

int KindSlot(int kind)
{
  switch (kind)
  {
    case 1:
      return 1;
    case 2:
      return 2;
    case 3: // tolerate 3 as clone-split
    case 4:
      return 3;
    default:
      return 0;
  }
}

// o[v] = p[v] converted, in parallel.
template <typename S, typename T>
void ConvertValues(const S* p, T* o, vtkIdType n)
{
#pragma omp parallel for schedule(static) if (n > 65536)
  for (vtkIdType v = 0; v < n; ++v)
  {
    o[v] = static_cast<T>(p[v]);
  }
}

// Copies a one-component array into @p out (n values): typed and parallel for the usual
// AOS arrays, GetComponent otherwise.
template <typename T>
void ReadColumn(vtkDataArray* a, vtkIdType n, std::vector<T>& out)
{
  out.resize(static_cast<std::size_t>(n));
  T* o = out.data();
  if (a->GetNumberOfComponents() == 1 && a->HasStandardMemoryLayout() &&
    a->GetNumberOfTuples() >= n)
  {
    switch (a->GetDataType())
    {
      vtkTemplateMacro(ConvertValues(static_cast<const VTK_TT*>(a->GetVoidPointer(0)), o, n);
                       return;);
    }
  }
  for (vtkIdType v = 0; v < n; ++v)
  {
    o[v] = static_cast<T>(a->GetComponent(v, 0));
  }
}

// The values of @p a when it holds n or more values of type T, one component, contiguous:
// the index reads them in place (no copy); null otherwise.
template <typename T>
const T* InPlace(vtkDataArray* a, vtkIdType n)
{
  return a->GetDataType() == vtkTypeTraits<T>::VTK_TYPE_ID && a->GetNumberOfComponents() == 1 &&
      a->HasStandardMemoryLayout() && a->GetNumberOfTuples() >= n && n > 0
    ? static_cast<const T*>(a->GetVoidPointer(0))
    : nullptr;
}

constexpr float MarginLeft = 8.f;
constexpr float MarginRight = 8.f;
constexpr float MarginBottom = 26.f;
constexpr float MarginTop = 20.f; // the status line is drawn in it, above the nodes

// vtkContextMouseEvent::GetModifiers dereferences the interactor; scripted events have none.
int Modifiers(const vtkContextMouseEvent& mouse)
{
  return mouse.GetInteractor() ? mouse.GetModifiers() : 0;
}

double NiceStep(double span, int ticks)
{
  const double raw = span / std::max(1, ticks);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : { 1.0, 2.0, 5.0, 10.0 })
  {
    if (m * mag >= raw)
    {
      return m * mag;
    }
  }
  return 10 * mag;
}
}

struct vtkGaussianTreeItem::vtkInternals
{
  vtkSmartPointer<vtkTree> Tree;
  vtkSmartPointer<vtkTable> Bands;
  Vis4GSHubLink Hub;
  vtkNew<vtkCallbackCommand> HubCommand;
  vtkMTimeType BuiltTreeTime = 0;
  vtkMTimeType BuiltBandsTime = 0;

  // Per vertex (index = tree vertex id): the columns and orders in Core, the node kind
  // slot and pruned flag here.
  vtkSmartPointer<vtkDataArray> IdArray;
  vis4gs::TreeDrawIndex Index;
  // The tree's arrays that Index reads in place (BirthView, PView), held while it does.
  vtkSmartPointer<vtkDataArray> BirthArray, PArray;
  std::vector<std::uint8_t> Kind, Pruned;
  // 1 for a root a lineage break started (the tree's LineageBreakRoot); empty without breaks.
  std::vector<std::uint8_t> BreakRoot;

  std::vector<float> BandMinX, BandMaxX, BandMinY, BandMaxY;

  double VX0 = 0, VX1 = 1, VY0 = 0, VY1 = 1;
  bool ViewportSet = false;

  std::vector<vtkIdType> Selected, Lineage;
  std::vector<std::uint8_t> InLineage;
  std::vector<std::int64_t> Visible;
  vtkIdType Work = 0;
  int Iteration = -1;

  bool Pressed = false;
  bool Dragging = false;
  vtkVector2f PressPos;
  int PressModifiers = 0;

  std::vector<float> Pts;
  std::vector<unsigned char> Cols;

  vtkIdType VertexOfId(vtkIdType id) const { return this->Index.VertexOfId(id); }
};

//------------------------------------------------------------------------------
vtkGaussianTreeItem::vtkGaussianTreeItem()
  : Internals(new vtkInternals)
{
  this->SetIdArrayName(vis4gs::arrays::TreeGaussianId);
  this->SetXArrayName(vis4gs::arrays::TreeLayoutX);
  this->SetYArrayName(vis4gs::arrays::TreeLayoutY);
  this->SetDeathArrayName("DeathIteration");
  this->SetPerceptionArrayName("PerceptionValue");
  this->SetKindArrayName("BirthKind");
  this->SetPrunedArrayName("Pruned");
  this->Internals->HubCommand->SetClientData(this);
  this->Internals->HubCommand->SetCallback([](vtkObject*, unsigned long, void* client, void*)
    { static_cast<vtkGaussianTreeItem*>(client)->UpdateFromHub(); });
}

//------------------------------------------------------------------------------
vtkGaussianTreeItem::~vtkGaussianTreeItem()
{
  this->SetSelectionHub(nullptr);
  this->SetIdArrayName(nullptr);
  this->SetXArrayName(nullptr);
  this->SetYArrayName(nullptr);
  this->SetDeathArrayName(nullptr);
  this->SetPerceptionArrayName(nullptr);
  this->SetKindArrayName(nullptr);
  this->SetPrunedArrayName(nullptr);
}

//------------------------------------------------------------------------------
void vtkGaussianTreeItem::SetTree(vtkTree* tree)
{
  if (this->Internals->Tree != tree)
  {
    this->Internals->Tree = tree;
    this->Internals->BuiltTreeTime = 0;
    this->Internals->ViewportSet = false;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkTree* vtkGaussianTreeItem::GetTree()
{
  return this->Internals->Tree;
}

//------------------------------------------------------------------------------
void vtkGaussianTreeItem::SetFamilyBands(vtkTable* bands)
{
  if (this->Internals->Bands != bands)
  {
    this->Internals->Bands = bands;
    this->Internals->BuiltBandsTime = 0;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkTable* vtkGaussianTreeItem::GetFamilyBands()
{
  return this->Internals->Bands;
}

//------------------------------------------------------------------------------
void vtkGaussianTreeItem::SetSelectionHub(vtkGaussianSelectionHub* hub)
{
  auto& in = *this->Internals;
  // The tree view that holds this item is the view the hub renders.
  if (!in.Hub.Link(hub, in.HubCommand, nullptr, true))
  {
    return;
  }
  if (hub)
  {
    this->UpdateFromHub();
  }
  this->Modified();
}

//------------------------------------------------------------------------------
vtkGaussianSelectionHub* vtkGaussianTreeItem::GetSelectionHub()
{
  return this->Internals->Hub;
}

//------------------------------------------------------------------------------
void vtkGaussianTreeItem::BuildIndex()
{
  auto& in = *this->Internals;
  vtkTree* tree = in.Tree;
  const bool treeCurrent = tree && in.BuiltTreeTime >= tree->GetMTime();
  if (!tree)
  {
    in.Index.Clear();
    in.BirthArray = nullptr;
    in.PArray = nullptr;
    in.Kind.clear();
    in.Pruned.clear();
    in.BreakRoot.clear();
    in.InLineage.clear();
    in.Selected.clear();
    in.Lineage.clear();
    in.IdArray = nullptr;
  }
  else if (!treeCurrent)
  {
    vtkDataSetAttributes* vd = tree->GetVertexData();
    const vtkIdType n = tree->GetNumberOfVertices();
    auto get = [&](const char* name) -> vtkDataArray*
    {
      vtkDataArray* a = name ? vd->GetArray(name) : nullptr;
      if (!a && name && std::string(name) != (this->PrunedArrayName ? this->PrunedArrayName : ""))
      {
        vtkErrorMacro("the tree has no vertex array '" << name << "'");
      }
      return a;
    };
    vtkDataArray* ids = get(this->IdArrayName);
    vtkDataArray* xs = get(this->XArrayName);
    vtkDataArray* ys = get(this->YArrayName);
    vtkDataArray* death = get(this->DeathArrayName);
    vtkDataArray* ps = get(this->PerceptionArrayName);
    vtkDataArray* kinds = get(this->KindArrayName);
    vtkDataArray* pruned = this->PrunedArrayName ? vd->GetArray(this->PrunedArrayName) : nullptr;
    in.BuiltTreeTime = tree->GetMTime();
    if (!ids || !xs || !ys || !death || !ps || !kinds)
    {
      in.Tree = nullptr;
      this->BuildIndex();
      return;
    }
    in.IdArray = ids;
    // Typed, parallel copies of the vertex arrays (10M vertices: a few hundred ms), except
    // birth and P when the tree holds them as the index's types (the genealogy filter's
    // LayoutX and PerceptionValue): those are read in place.
    std::vector<std::int64_t> idValues;
    ReadColumn(ids, n, idValues);
    in.Index.BirthView = InPlace<std::int32_t>(xs, n);
    in.BirthArray = in.Index.BirthView ? xs : nullptr;
    if (in.Index.BirthView)
    {
      in.Index.Birth = std::vector<std::int32_t>();
    }
    else
    {
      ReadColumn(xs, n, in.Index.Birth);
    }
    ReadColumn(death, n, in.Index.End);
    ReadColumn(ys, n, in.Index.Row);
    in.Index.PView = InPlace<double>(ps, n);
    in.PArray = in.Index.PView ? ps : nullptr;
    if (in.Index.PView)
    {
      in.Index.P = std::vector<double>();
    }
    else
    {
      ReadColumn(ps, n, in.Index.P);
    }
    ReadColumn(kinds, n, in.Kind);
    in.BreakRoot.clear();
    if (vtkDataArray* breakRoot = vd->GetArray(vis4gs::arrays::TreeLineageBreakRoot))
    {
      ReadColumn(breakRoot, n, in.BreakRoot);
    }
    if (pruned)
    {
      ReadColumn(pruned, n, in.Pruned);
    }
    else
    {
      in.Pruned.assign(n, 0);
    }
    {
      std::uint8_t* kindp = in.Kind.data();
      std::uint8_t* prunedp = in.Pruned.data();
#pragma omp parallel for schedule(static) if (n > 65536)
      for (vtkIdType v = 0; v < n; ++v)
      {
        kindp[v] = static_cast<std::uint8_t>(KindSlot(kindp[v]));
        prunedp[v] = prunedp[v] != 0;
      }
    }
    std::int32_t last = std::numeric_limits<std::int32_t>::min();
    if (vtkDataArray* l = tree->GetFieldData()->GetArray("LastIteration"))
    {
      if (l->GetNumberOfTuples() > 0)
      {
        last = static_cast<std::int32_t>(l->GetComponent(0, 0));
      }
    }
    in.Index.Build(idValues, last);
    in.InLineage.assign(n, 0);
    in.Selected.clear();
    in.Lineage.clear();
    this->UpdateSelection();
  }

  vtkTable* bands = in.Bands;
  if (!bands)
  {
    in.BandMinX.clear();
    in.BandMaxX.clear();
    in.BandMinY.clear();
    in.BandMaxY.clear();
  }
  else if (in.BuiltBandsTime < bands->GetMTime())
  {
    in.BuiltBandsTime = bands->GetMTime();
    auto col = [&](const char* name)
    { return vtkDataArray::SafeDownCast(bands->GetColumnByName(name)); };
    vtkDataArray* a = col("MinIteration");
    vtkDataArray* b = col("MaxIteration");
    vtkDataArray* c = col("MinRow");
    vtkDataArray* d = col("MaxRow");
    in.BandMinX.clear();
    in.BandMaxX.clear();
    in.BandMinY.clear();
    in.BandMaxY.clear();
    if (!a || !b || !c || !d)
    {
      vtkErrorMacro("the family bands table needs the columns MinIteration, MaxIteration, "
                    "MinRow and MaxRow");
    }
    else
    {
      for (vtkIdType r = 0; r < bands->GetNumberOfRows(); ++r)
      {
        in.BandMinX.push_back(static_cast<float>(a->GetComponent(r, 0)));
        in.BandMaxX.push_back(static_cast<float>(b->GetComponent(r, 0)));
        in.BandMinY.push_back(static_cast<float>(c->GetComponent(r, 0)));
        in.BandMaxY.push_back(static_cast<float>(d->GetComponent(r, 0)));
      }
    }
  }
  if (!in.ViewportSet)
  {
    in.ViewportSet = true;
    const double mx = 0.02 * (in.Index.DataMaxX - in.Index.DataMinX);
    in.VX0 = in.Index.DataMinX - mx;
    in.VX1 = in.Index.DataMaxX + mx;
    in.VY0 = in.Index.DataMinY - 0.5;
    in.VY1 = in.Index.DataMaxY + 0.5;
  }
}

//------------------------------------------------------------------------------
void vtkGaussianTreeItem::UpdateFromHub()
{
  auto& in = *this->Internals;
  if (!in.Hub)
  {
    return;
  }
  in.Iteration = in.Hub->GetIteration();
  this->BuildIndex();
  this->UpdateSelection();
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkGaussianTreeItem::UpdateSelection()
{
  auto& in = *this->Internals;
  for (vtkIdType v : in.Lineage)
  {
    in.InLineage[v] = 0;
  }
  in.Selected.clear();
  in.Lineage.clear();
  if (!in.Hub || !in.Tree || in.Index.Valid.empty())
  {
    return;
  }
  for (vtkIdType id : in.Hub->GetSelectedIdVector())
  {
    const vtkIdType v = in.VertexOfId(id);
    if (v >= 0)
    {
      in.Selected.push_back(v);
    }
  }
  std::sort(in.Selected.begin(), in.Selected.end());
  vtkTree* tree = in.Tree;
  // Ancestors, then the selection and its descendants (breadth first, iterative).
  for (vtkIdType s : in.Selected)
  {
    for (vtkIdType a = tree->GetParent(s); a >= 0 && in.Index.Valid[a] && !in.InLineage[a];
         a = tree->GetParent(a))
    {
      in.InLineage[a] = 1;
      in.Lineage.push_back(a);
    }
  }
  std::vector<vtkIdType> queue;
  for (vtkIdType s : in.Selected)
  {
    if (in.InLineage[s] != 2)
    {
      if (!in.InLineage[s])
      {
        in.Lineage.push_back(s);
      }
      in.InLineage[s] = 2; // 2: visited downwards
      queue.push_back(s);
    }
  }
  for (std::size_t q = 0; q < queue.size(); ++q)
  {
    const vtkIdType v = queue[q];
    const vtkIdType nc = tree->GetNumberOfChildren(v);
    for (vtkIdType c = 0; c < nc; ++c)
    {
      const vtkIdType child = tree->GetChild(v, c);
      if (in.InLineage[child] != 2)
      {
        if (!in.InLineage[child])
        {
          in.Lineage.push_back(child);
        }
        in.InLineage[child] = 2;
        queue.push_back(child);
      }
    }
  }
  std::sort(in.Lineage.begin(), in.Lineage.end());
}

//------------------------------------------------------------------------------
void vtkGaussianTreeItem::SetViewport(double minX, double maxX, double minY, double maxY)
{
  this->BuildIndex();
  auto& in = *this->Internals;
  if (!(maxX > minX) || !(maxY > minY))
  {
    vtkErrorMacro("SetViewport: empty range");
    return;
  }
  in.VX0 = minX;
  in.VX1 = maxX;
  in.VY0 = minY;
  in.VY1 = maxY;
  in.ViewportSet = true;
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkGaussianTreeItem::GetViewport(double viewport[4])
{
  this->BuildIndex();
  auto& in = *this->Internals;
  viewport[0] = in.VX0;
  viewport[1] = in.VX1;
  viewport[2] = in.VY0;
  viewport[3] = in.VY1;
}

//------------------------------------------------------------------------------
void vtkGaussianTreeItem::ResetViewport()
{
  this->Internals->ViewportSet = false;
  this->BuildIndex();
  this->Modified();
}

//------------------------------------------------------------------------------
double vtkGaussianTreeItem::GetZoom()
{
  this->BuildIndex();
  auto& in = *this->Internals;
  const vis4gs::ZoomParameters zp;
  const double all = in.Index.DataMaxY - in.Index.DataMinY + 1.0;
  const double sMax = all / this->ZoomedInRows;
  if (sMax <= 1.0)
  {
    return zp.ZMax;
  }
  const double s = std::max(1.0, all / (in.VY1 - in.VY0));
  const double z = zp.ZMin + (zp.ZMax - zp.ZMin) * std::log(s) / std::log(sMax);
  return std::min(zp.ZMax, std::max(zp.ZMin, z));
}

//------------------------------------------------------------------------------
void vtkGaussianTreeItem::SetZoom(double z)
{
  this->BuildIndex();
  auto& in = *this->Internals;
  const vis4gs::ZoomParameters zp;
  const double all = in.Index.DataMaxY - in.Index.DataMinY + 1.0;
  const double sMax = std::max(1.0, all / this->ZoomedInRows);
  const double t = (std::min(zp.ZMax, std::max(zp.ZMin, z)) - zp.ZMin) / (zp.ZMax - zp.ZMin);
  const double s = std::exp(t * std::log(sMax));
  const double centre = 0.5 * (in.VY0 + in.VY1);
  const double half = 0.5 * all / s;
  in.VY0 = centre - half;
  in.VY1 = centre + half;
  this->Modified();
}

//------------------------------------------------------------------------------
double vtkGaussianTreeItem::GetZoomThreshold()
{
  return vis4gs::ZoomThreshold(this->GetZoom());
}

//------------------------------------------------------------------------------
void vtkGaussianTreeItem::ZoomRows(double factor, double aboutRow)
{
  this->BuildIndex();
  auto& in = *this->Internals;
  if (!(factor > 0))
  {
    return;
  }
  // Never zoom in past a few rows nor out past the whole tree.
  const double all = in.Index.DataMaxY - in.Index.DataMinY + 1.0;
  double span = (in.VY1 - in.VY0) / factor;
  span = std::min(std::max(span, 4.0), all + 1.0);
  const double f = (aboutRow - in.VY0) / (in.VY1 - in.VY0);
  in.VY0 = aboutRow - f * span;
  in.VY1 = in.VY0 + span;
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkGaussianTreeItem::ZoomIterations(double factor, double aboutIteration)
{
  this->BuildIndex();
  auto& in = *this->Internals;
  if (!(factor > 0))
  {
    return;
  }
  const double all = 1.1 * (in.Index.DataMaxX - in.Index.DataMinX) + 1.0;
  double span = (in.VX1 - in.VX0) / factor;
  span = std::min(std::max(span, 10.0), all);
  const double f = (aboutIteration - in.VX0) / (in.VX1 - in.VX0);
  in.VX0 = aboutIteration - f * span;
  in.VX1 = in.VX0 + span;
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkGaussianTreeItem::Pan(double dIterations, double dRows)
{
  this->BuildIndex();
  auto& in = *this->Internals;
  in.VX0 += dIterations;
  in.VX1 += dIterations;
  in.VY0 += dRows;
  in.VY1 += dRows;
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkGaussianTreeItem::ZoomToSelection()
{
  this->BuildIndex();
  auto& in = *this->Internals;
  if (in.Lineage.empty())
  {
    return;
  }
  double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
  for (vtkIdType v : in.Lineage)
  {
    lo = std::min(lo, in.Index.Row[v]);
    hi = std::max(hi, in.Index.Row[v]);
  }
  const double pad = std::max(2.0, 0.1 * (hi - lo));
  in.VY0 = lo - pad;
  in.VY1 = hi + pad;
  const double mx = 0.02 * (in.Index.DataMaxX - in.Index.DataMinX);
  in.VX0 = in.Index.DataMinX - mx;
  in.VX1 = in.Index.DataMaxX + mx;
  this->Modified();
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianTreeItem::UpdateLevelOfDetail()
{
  this->BuildIndex();
  auto& in = *this->Internals;
  in.Visible.clear();
  in.Work = 0;
  const double tau = vis4gs::ZoomThreshold(this->GetZoom());
  in.Work =
    in.Index.QueryVisible(tau, in.VX0, in.VX1, in.VY0, in.VY1, in.InLineage.data(), in.Visible);
  const auto& index = in.Index;
  auto inView = [&](vtkIdType v)
  {
    return index.Row[v] >= in.VY0 && index.Row[v] <= in.VY1 && index.BirthData()[v] <= in.VX1 &&
      index.End[v] >= in.VX0;
  };
  for (vtkIdType v : in.Lineage)
  {
    if (inView(v))
    {
      in.Visible.push_back(v);
    }
  }
  in.Work += static_cast<vtkIdType>(in.Lineage.size());
  return static_cast<vtkIdType>(in.Visible.size());
}

//------------------------------------------------------------------------------
void vtkGaussianTreeItem::GetVisibleVertices(vtkIdTypeArray* vertices)
{
  std::vector<vtkIdType> v(this->Internals->Visible.begin(), this->Internals->Visible.end());
  std::sort(v.begin(), v.end());
  vertices->SetNumberOfTuples(static_cast<vtkIdType>(v.size()));
  std::copy(v.begin(), v.end(), vertices->GetPointer(0));
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianTreeItem::GetNumberOfVisibleVertices()
{
  return static_cast<vtkIdType>(this->Internals->Visible.size());
}

//------------------------------------------------------------------------------
void vtkGaussianTreeItem::GetSelectedVertices(vtkIdTypeArray* vertices)
{
  const auto& v = this->Internals->Selected;
  vertices->SetNumberOfTuples(static_cast<vtkIdType>(v.size()));
  std::copy(v.begin(), v.end(), vertices->GetPointer(0));
}

//------------------------------------------------------------------------------
void vtkGaussianTreeItem::GetLineageVertices(vtkIdTypeArray* vertices)
{
  const auto& v = this->Internals->Lineage;
  vertices->SetNumberOfTuples(static_cast<vtkIdType>(v.size()));
  std::copy(v.begin(), v.end(), vertices->GetPointer(0));
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianTreeItem::GetLastLevelOfDetailWork()
{
  return this->Internals->Work;
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianTreeItem::GetNumberOfVertices()
{
  return this->Internals->Tree ? this->Internals->Tree->GetNumberOfVertices() : 0;
}

namespace
{
struct ScreenMap
{
  float L, R, B, T;
  double X0, X1, Y0, Y1;
  float X(double x) const { return static_cast<float>(L + (x - X0) / (X1 - X0) * (R - L)); }
  float Y(double row) const { return static_cast<float>(T - (row - Y0) / (Y1 - Y0) * (T - B)); }
  double DataX(float sx) const { return X0 + (sx - L) / (R - L) * (X1 - X0); }
  double DataY(float sy) const { return Y0 + (T - sy) / (T - B) * (Y1 - Y0); }
};
}

#define VIS4GS_TREE_MAP(item, in)                                                                  \
  int w_ = (item)->Size[0], h_ = (item)->Size[1];                                                  \
  if ((item)->GetScene() && (item)->GetScene()->GetSceneWidth() > 0)                               \
  {                                                                                                \
    w_ = (item)->GetScene()->GetSceneWidth();                                                      \
    h_ = (item)->GetScene()->GetSceneHeight();                                                     \
  }                                                                                                \
  const ScreenMap map                                                                              \
  {                                                                                                \
    MarginLeft, std::max(MarginLeft + 1.f, w_ - MarginRight), MarginBottom,                        \
      std::max(MarginBottom + 1.f, h_ - MarginTop), (in).VX0, (in).VX1, (in).VY0, (in).VY1         \
  }

//------------------------------------------------------------------------------
void vtkGaussianTreeItem::GetVertexPosition(vtkIdType vertex, float position[2])
{
  this->BuildIndex();
  auto& in = *this->Internals;
  VIS4GS_TREE_MAP(this, in);
  position[0] = position[1] = 0.f;
  if (vertex >= 0 && vertex < static_cast<vtkIdType>(in.Index.Row.size()))
  {
    position[0] = map.X(in.Index.BirthData()[vertex]);
    position[1] = map.Y(in.Index.Row[vertex]);
  }
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianTreeItem::PickVertex(float x, float y, float tolerance)
{
  auto& in = *this->Internals;
  VIS4GS_TREE_MAP(this, in);
  vtkIdType best = -1;
  float bestD = tolerance;
  for (vtkIdType v : in.Visible)
  {
    const float sy = map.Y(in.Index.Row[v]);
    const float dy = std::abs(sy - y);
    if (dy > bestD)
    {
      continue;
    }
    const float sx0 = map.X(in.Index.BirthData()[v]), sx1 = map.X(in.Index.End[v]);
    float dx = 0.f;
    if (x < sx0)
    {
      dx = sx0 - x;
    }
    else if (x > sx1)
    {
      dx = x - sx1;
    }
    const float d = std::sqrt(dx * dx + dy * dy);
    if (d <= bestD)
    {
      bestD = d;
      best = v;
    }
  }
  return best;
}

//------------------------------------------------------------------------------
namespace
{
// Level of detail of the drawing itself: when many more rows than pixels are in view, the
// horizontal lifespan lines of one colour that fall on the same pixel row and overlap (or
// touch) are drawn as one line, opaque where several were merged (what the blended overdraw
// converges to). Rows at least one pixel apart are never merged, so zoomed-in views are drawn
// unchanged. On software OpenGL the overview frame is fill-bound by this overdraw.
void MergeLinesOnPixelRows(std::vector<float>& pts, std::vector<unsigned char>& cols)
{
  struct Segment
  {
    long Row;
    std::uint32_t Color;
    float X0, X1, Y;
    int Count;
  };
  const std::size_t n = pts.size() / 4;
  std::vector<Segment> segments(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const unsigned char* c = &cols[8 * i];
    segments[i] = { std::lround(pts[4 * i + 1]),
      (std::uint32_t(c[0]) << 16) | (std::uint32_t(c[1]) << 8) | c[2],
      std::min(pts[4 * i], pts[4 * i + 2]),
      std::max(pts[4 * i], pts[4 * i + 2]),
      pts[4 * i + 1],
      1 };
  }
  std::sort(segments.begin(),
    segments.end(),
    [](const Segment& a, const Segment& b) {
      return a.Row != b.Row ? a.Row < b.Row : a.Color != b.Color ? a.Color < b.Color : a.X0 < b.X0;
    });
  std::vector<Segment> merged;
  merged.reserve(n);
  for (const Segment& s : segments)
  {
    if (!merged.empty() && merged.back().Row == s.Row && merged.back().Color == s.Color &&
      s.X0 <= merged.back().X1 + 1.f)
    {
      merged.back().X1 = std::max(merged.back().X1, s.X1);
      merged.back().Count += 1;
    }
    else
    {
      merged.push_back(s);
    }
  }
  if (merged.size() == n)
  {
    return;
  }
  pts.clear();
  cols.clear();
  for (const Segment& s : merged)
  {
    const float y = s.Count > 1 ? static_cast<float>(s.Row) : s.Y;
    pts.insert(pts.end(), { s.X0, y, s.X1, y });
    const unsigned char r = (s.Color >> 16) & 255, g = (s.Color >> 8) & 255, b = s.Color & 255;
    const unsigned char a = s.Count > 1 ? 255 : 200;
    cols.insert(cols.end(), { r, g, b, a, r, g, b, a });
  }
}
}

//------------------------------------------------------------------------------
bool vtkGaussianTreeItem::Paint(vtkContext2D* painter)
{
  this->BuildIndex();
  this->UpdateLevelOfDetail();
  auto& in = *this->Internals;
  VIS4GS_TREE_MAP(this, in);
  vtkContextDevice2D* device = painter->GetDevice();

  // Background.
  painter->GetPen()->SetLineType(vtkPen::NO_PEN);
  painter->GetBrush()->SetColor(36, 40, 48, 255);
  painter->DrawRect(0, 0, static_cast<float>(w_), static_cast<float>(h_));
  painter->GetBrush()->SetColor(44, 49, 58, 255);
  painter->DrawRect(map.L, map.B, map.R - map.L, map.T - map.B);

  // Family bands (alternating shades), only those in the viewport.
  std::vector<float> quads[2];
  for (std::size_t f = 0; f < in.BandMinY.size(); ++f)
  {
    if (in.BandMaxY[f] + 0.5 < in.VY0 || in.BandMinY[f] - 0.5 > in.VY1 || in.BandMaxX[f] < in.VX0 ||
      in.BandMinX[f] > in.VX1)
    {
      continue;
    }
    const float x0 = std::max(map.L, map.X(in.BandMinX[f]));
    const float x1 = std::min(map.R, map.X(in.BandMaxX[f]));
    const float y0 = std::min(map.T, map.Y(in.BandMinY[f] - 0.5));
    const float y1 = std::max(map.B, map.Y(in.BandMaxY[f] + 0.5));
    if (y0 - y1 < 0.5f)
    {
      continue;
    }
    auto& q = quads[f % 2];
    q.insert(q.end(), { x0, y1, x1, y1, x1, y0, x0, y0 });
  }
  const unsigned char bandColors[2][4] = { { 62, 70, 84, 255 }, { 54, 60, 72, 255 } };
  for (int k = 0; k < 2; ++k)
  {
    if (!quads[k].empty())
    {
      painter->GetBrush()->SetColor(bandColors[k][0], bandColors[k][1], bandColors[k][2], 255);
      device->ApplyBrush(painter->GetBrush());
      device->DrawQuad(quads[k].data(), static_cast<int>(quads[k].size() / 2));
    }
  }

  // Lifespan lines (birth -> end) coloured by birth kind; parent-child edges in grey.
  auto& pts = in.Pts;
  auto& cols = in.Cols;
  pts.clear();
  cols.clear();
  std::vector<float> edges;
  vtkTree* tree = in.Tree;
  for (vtkIdType v : in.Visible)
  {
    const float y = map.Y(in.Index.Row[v]);
    const float x0 = map.X(in.Index.BirthData()[v]);
    pts.insert(pts.end(), { x0, y, std::max(map.X(in.Index.End[v]), x0 + 1.f), y });
    const unsigned char* c = KindColors[in.Kind[v]];
    for (int k = 0; k < 2; ++k)
    {
      cols.insert(cols.end(), { c[0], c[1], c[2], 200 });
    }
    const vtkIdType parent = tree->GetParent(v);
    if (parent >= 0 && in.Index.Valid[parent])
    {
      edges.insert(edges.end(), { x0, map.Y(in.Index.Row[parent]), x0, y });
    }
  }
  vtkNew<vtkPen> pen;
  pen->SetWidth(1.f);
  pen->SetColor(150, 150, 160, 160);
  if (!edges.empty())
  {
    device->ApplyPen(pen);
    device->DrawLines(edges.data(), static_cast<int>(edges.size() / 2));
  }
  pen->SetWidth(in.Visible.size() > 20000 ? 1.f : 2.f);
  device->ApplyPen(pen);
  if (this->MergeLinesPerPixelRow && pts.size() / 4 > 256)
  {
    MergeLinesOnPixelRows(pts, cols);
  }
  if (!pts.empty())
  {
    device->DrawLines(pts.data(), static_cast<int>(pts.size() / 2), cols.data(), 4);
  }

  // Selected lineage: thick highlight lines.
  if (!in.Lineage.empty())
  {
    pts.clear();
    for (vtkIdType v : in.Lineage)
    {
      if (in.Index.Row[v] < in.VY0 || in.Index.Row[v] > in.VY1)
      {
        continue;
      }
      const float y = map.Y(in.Index.Row[v]);
      const float x0 = map.X(in.Index.BirthData()[v]);
      pts.insert(pts.end(), { x0, y, std::max(map.X(in.Index.End[v]), x0 + 1.f), y });
      const vtkIdType parent = tree->GetParent(v);
      if (parent >= 0 && in.Index.Valid[parent] && in.InLineage[parent])
      {
        pts.insert(pts.end(), { x0, map.Y(in.Index.Row[parent]), x0, y });
      }
    }
    pen->SetWidth(3.f);
    pen->SetColor(HighlightColor[0], HighlightColor[1], HighlightColor[2], 220);
    device->ApplyPen(pen);
    if (!pts.empty())
    {
      device->DrawLines(pts.data(), static_cast<int>(pts.size() / 2));
    }
  }

  // Roots started by a lineage break: a ring under their marker.
  if (!in.BreakRoot.empty())
  {
    pts.clear();
    for (vtkIdType v : in.Visible)
    {
      if (in.BreakRoot[v])
      {
        pts.insert(pts.end(), { map.X(in.Index.BirthData()[v]), map.Y(in.Index.Row[v]) });
      }
    }
    pen->SetWidth(in.Visible.size() > 20000 ? 4.f : 9.f);
    pen->SetColor(BreakRootColor[0], BreakRootColor[1], BreakRootColor[2], 255);
    device->ApplyPen(pen);
    if (!pts.empty())
    {
      device->DrawPoints(pts.data(), static_cast<int>(pts.size() / 2));
    }
  }

  // Node markers: births by kind; a purple marker at the death of pruned Gaussians.
  pts.clear();
  cols.clear();
  for (vtkIdType v : in.Visible)
  {
    pts.insert(pts.end(), { map.X(in.Index.BirthData()[v]), map.Y(in.Index.Row[v]) });
    const unsigned char* c = KindColors[in.Kind[v]];
    cols.insert(cols.end(), { c[0], c[1], c[2], 255 });
    if (in.Pruned[v])
    {
      pts.insert(pts.end(), { map.X(in.Index.End[v]), map.Y(in.Index.Row[v]) });
      const unsigned char* pc = KindColors[4];
      cols.insert(cols.end(), { pc[0], pc[1], pc[2], 255 });
    }
  }
  pen->SetWidth(in.Visible.size() > 20000 ? 2.f : 5.f);
  device->ApplyPen(pen);
  if (!pts.empty())
  {
    device->DrawPoints(pts.data(), static_cast<int>(pts.size() / 2), cols.data(), 4);
  }
  if (!in.Selected.empty())
  {
    pts.clear();
    for (vtkIdType v : in.Selected)
    {
      if (in.Index.Row[v] >= in.VY0 && in.Index.Row[v] <= in.VY1)
      {
        pts.insert(pts.end(), { map.X(in.Index.BirthData()[v]), map.Y(in.Index.Row[v]) });
      }
    }
    pen->SetWidth(9.f);
    pen->SetColor(SelectedColor[0], SelectedColor[1], SelectedColor[2], 255);
    device->ApplyPen(pen);
    if (!pts.empty())
    {
      device->DrawPoints(pts.data(), static_cast<int>(pts.size() / 2));
    }
  }

  // Iteration cursor.
  if (in.Iteration >= 0 && in.Iteration >= in.VX0 && in.Iteration <= in.VX1)
  {
    pen->SetWidth(2.f);
    pen->SetColor(255, 255, 255, 200);
    painter->ApplyPen(pen);
    const float x = map.X(in.Iteration);
    painter->DrawLine(x, map.B, x, map.T);
  }

  // Iteration axis.
  vtkTextProperty* text = painter->GetTextProp();
  text->SetColor(0.85, 0.85, 0.85);
  text->SetFontSize(11);
  text->SetJustificationToCentered();
  text->SetVerticalJustificationToTop();
  text->SetBold(false);
  pen->SetWidth(1.f);
  pen->SetColor(200, 200, 200, 255);
  painter->ApplyPen(pen);
  painter->DrawLine(map.L, map.B, map.R, map.B);
  const double step =
    NiceStep(in.VX1 - in.VX0, std::max(2, static_cast<int>((map.R - map.L) / 90)));
  for (double t = std::ceil(in.VX0 / step) * step; t <= in.VX1; t += step)
  {
    const float x = map.X(t);
    painter->DrawLine(x, map.B, x, map.B - 4);
    std::ostringstream label;
    label << static_cast<long long>(t);
    painter->DrawString(x, map.B - 6, label.str());
  }

  // Legend (top right).
  // (a seventh entry, the break's ring, only when the log has lineage breaks)
  const char* names[7] = {
    "root", "clone", "split", "clone-split", "prune", "selected", "lineage break"
  };
  const int entries = in.BreakRoot.empty() ? 6 : 7;
  const float lx = map.R - 92.f, ly = map.T - 6.f;
  painter->GetPen()->SetLineType(vtkPen::NO_PEN);
  painter->GetBrush()->SetColor(20, 22, 28, 200);
  painter->DrawRect(lx - 6, ly - entries * 14 - 4, 96, entries * 14 + 8);
  text->SetJustificationToLeft();
  text->SetVerticalJustificationToCentered();
  for (int k = 0; k < entries; ++k)
  {
    const unsigned char* c = k < 5 ? KindColors[k] : k == 5 ? SelectedColor : BreakRootColor;
    painter->GetBrush()->SetColor(c[0], c[1], c[2], 255);
    const float y = ly - 14.f * k - 7.f;
    painter->DrawRect(lx, y - 4, 10, 8);
    painter->DrawString(lx + 16, y, names[k]);
  }

  // Status: zoom, threshold, counts.
  std::ostringstream status;
  status.precision(3);
  status << "z=" << this->GetZoom() << "  tau=" << vis4gs::ZoomThreshold(this->GetZoom())
         << "  shown " << in.Visible.size() << " of " << in.Index.NumberOfRows;
  text->SetJustificationToLeft();
  text->SetVerticalJustificationToBottom();
  painter->DrawString(map.L + 4, map.T + 4, status.str());
  return true;
}

//------------------------------------------------------------------------------
bool vtkGaussianTreeItem::Hit(const vtkContextMouseEvent& vtkNotUsed(mouse))
{
  return this->Visible && this->Internals->Tree;
}

//------------------------------------------------------------------------------
bool vtkGaussianTreeItem::MouseButtonPressEvent(const vtkContextMouseEvent& mouse)
{
  auto& in = *this->Internals;
  if (mouse.GetButton() != vtkContextMouseEvent::LEFT_BUTTON)
  {
    return false;
  }
  in.Pressed = true;
  in.Dragging = false;
  in.PressPos = mouse.GetScenePos();
  in.PressModifiers = Modifiers(mouse);
  return true;
}

//------------------------------------------------------------------------------
bool vtkGaussianTreeItem::MouseMoveEvent(const vtkContextMouseEvent& mouse)
{
  auto& in = *this->Internals;
  if (!in.Pressed)
  {
    return false;
  }
  const vtkVector2f pos = mouse.GetScenePos();
  if (!in.Dragging &&
    std::abs(pos.GetX() - in.PressPos.GetX()) + std::abs(pos.GetY() - in.PressPos.GetY()) < 3.f)
  {
    return true;
  }
  in.Dragging = true;
  VIS4GS_TREE_MAP(this, in);
  const vtkVector2f last = mouse.GetLastScenePos();
  const double dx = map.DataX(last.GetX()) - map.DataX(pos.GetX());
  const double dy = map.DataY(last.GetY()) - map.DataY(pos.GetY());
  this->Pan(dx, dy);
  if (this->GetScene())
  {
    this->GetScene()->SetDirty(true);
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkGaussianTreeItem::MouseButtonReleaseEvent(const vtkContextMouseEvent& mouse)
{
  auto& in = *this->Internals;
  if (mouse.GetButton() != vtkContextMouseEvent::LEFT_BUTTON || !in.Pressed)
  {
    return false;
  }
  in.Pressed = false;
  if (in.Dragging)
  {
    in.Dragging = false;
    return true;
  }
  const vtkVector2f pos = mouse.GetScenePos();
  const vtkIdType v = this->PickVertex(pos.GetX(), pos.GetY());
  if (in.Hub)
  {
    const int mods = in.PressModifiers | Modifiers(mouse);
    if (v < 0)
    {
      if (!(mods & (vtkContextMouseEvent::SHIFT_MODIFIER | vtkContextMouseEvent::CONTROL_MODIFIER)))
      {
        in.Hub->ClearSelection();
      }
    }
    else
    {
      const vtkIdType id = static_cast<vtkIdType>(in.IdArray->GetComponent(v, 0));
      const int mode = (mods & vtkContextMouseEvent::SHIFT_MODIFIER)
        ? vtkGaussianSelectionHub::ADD
        : ((mods & vtkContextMouseEvent::CONTROL_MODIFIER) ? vtkGaussianSelectionHub::TOGGLE
                                                           : vtkGaussianSelectionHub::REPLACE);
      in.Hub->SelectIds(&id, 1, mode);
    }
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkGaussianTreeItem::MouseWheelEvent(const vtkContextMouseEvent& mouse, int delta)
{
  auto& in = *this->Internals;
  VIS4GS_TREE_MAP(this, in);
  const vtkVector2f pos = mouse.GetScenePos();
  const double factor = std::pow(1.25, delta);
  if (Modifiers(mouse) & vtkContextMouseEvent::CONTROL_MODIFIER)
  {
    this->ZoomIterations(factor, map.DataX(pos.GetX()));
  }
  else
  {
    this->ZoomRows(factor, map.DataY(pos.GetY()));
  }
  if (this->GetScene())
  {
    this->GetScene()->SetDirty(true);
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkGaussianTreeItem::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  auto& in = *this->Internals;
  auto str = [](const char* s) { return s ? s : "(none)"; };
  os << indent << "Tree: " << in.Tree.GetPointer() << "\n";
  os << indent << "FamilyBands: " << in.Bands.GetPointer() << "\n";
  os << indent << "SelectionHub: " << in.Hub.GetPointer() << "\n";
  os << indent << "IdArrayName: " << str(this->IdArrayName) << "\n";
  os << indent << "XArrayName: " << str(this->XArrayName) << "\n";
  os << indent << "YArrayName: " << str(this->YArrayName) << "\n";
  os << indent << "DeathArrayName: " << str(this->DeathArrayName) << "\n";
  os << indent << "PerceptionArrayName: " << str(this->PerceptionArrayName) << "\n";
  os << indent << "KindArrayName: " << str(this->KindArrayName) << "\n";
  os << indent << "PrunedArrayName: " << str(this->PrunedArrayName) << "\n";
  os << indent << "ZoomedInRows: " << this->ZoomedInRows << "\n";
  os << indent << "MergeLinesPerPixelRow: " << this->MergeLinesPerPixelRow << "\n";
  os << indent << "Size: " << this->Size[0] << " " << this->Size[1] << "\n";
  os << indent << "Viewport: " << in.VX0 << " " << in.VX1 << " " << in.VY0 << " " << in.VY1 << "\n";
}

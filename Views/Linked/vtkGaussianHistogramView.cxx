/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianHistogramView.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianHistogramView.h"

#include "Vis4GSDataModel.h" // vis4gs::arrays

#include "Vis4GSHubLink.h"
#include "Vis4GSIdColumn.h"
#include "Vis4GSViewInput.h"
#include "vtkAxis.h"
#include "vtkCallbackCommand.h"
#include "vtkChartXY.h"
#include "vtkContextMouseEvent.h"
#include "vtkContextScene.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkGaussianSelectionHub.h"
#include "vtkIdTypeArray.h"
#include "vtkObjectFactory.h"
#include "vtkPlot.h"
#include "vtkPlotBar.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTable.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

vtkStandardNewMacro(vtkGaussianHistogramView);

struct vtkGaussianHistogramView::vtkInternals
{
  vtkNew<vtkChartXY> Chart;
  vtkNew<vtkTable> Bins;
  vtkSmartPointer<vtkDataObject> Data;
  Vis4GSViewInput Input;
  Vis4GSHubLink Hub;
  vtkNew<vtkCallbackCommand> HubCommand;
  vtkNew<vtkCallbackCommand> ChartCommand;
  std::vector<double> Edges;
  std::vector<vtkIdType> Counts, SelectedCounts;
  vtkPlot* AllPlot = nullptr;
  vtkPlot* SelectedPlot = nullptr;
  bool Brushing = false;
  double Lo = 0.0, Hi = 1.0; // the range binned (Edges' ends up to rounding)
  // What the grey bars were counted from (input, its time, the array, its time, component,
  // bins): a selection change with the same key recounts only the selected Gaussians.
  std::array<vtkMTimeType, 6> AllKey{};
  std::array<vtkMTimeType, 6> Key(vtkGaussianHistogramView* self, vtkAbstractArray* values) const
  {
    return { static_cast<vtkMTimeType>(reinterpret_cast<std::uintptr_t>(this->Data.GetPointer())),
      this->Data ? this->Data->GetMTime() : 0,
      static_cast<vtkMTimeType>(reinterpret_cast<std::uintptr_t>(values)),
      values ? values->GetMTime() : 0,
      static_cast<vtkMTimeType>(self->GetComponent() + 1),
      static_cast<vtkMTimeType>(self->GetNumberOfBins()) };
  }
};

//------------------------------------------------------------------------------
vtkGaussianHistogramView::vtkGaussianHistogramView()
  : Internals(new vtkInternals)
{
  this->SetArrayName("Opacity");
  this->SetIdArrayName(vis4gs::arrays::GaussianId);
  auto& in = *this->Internals;
  this->GetScene()->AddItem(in.Chart);
  this->GetRenderer()->SetBackground(1, 1, 1);
  in.Chart->SetActionToButton(vtkChart::SELECT, vtkContextMouseEvent::LEFT_BUTTON);
  in.Chart->SetActionToButton(vtkChart::PAN, vtkContextMouseEvent::MIDDLE_BUTTON);
  in.Chart->SetBarWidthFraction(0.95f);
  in.HubCommand->SetClientData(this);
  in.HubCommand->SetCallback([](vtkObject*, unsigned long, void* client, void*)
    { static_cast<vtkGaussianHistogramView*>(client)->UpdateSelectedCounts(); });
  in.ChartCommand->SetClientData(this);
  in.ChartCommand->SetCallback([](vtkObject*, unsigned long, void* client, void*)
    { static_cast<vtkGaussianHistogramView*>(client)->OnChartSelection(); });
  in.Chart->AddObserver(vtkCommand::SelectionChangedEvent, in.ChartCommand);
}

//------------------------------------------------------------------------------
vtkGaussianHistogramView::~vtkGaussianHistogramView()
{
  this->SetSelectionHub(nullptr);
  this->SetArrayName(nullptr);
  this->SetIdArrayName(nullptr);
}

//------------------------------------------------------------------------------
void vtkGaussianHistogramView::SetInputData(vtkDataObject* data)
{
  this->Internals->Input.SetConnection(nullptr);
  this->Internals->Data = data;
  this->UpdateHistogram();
}

//------------------------------------------------------------------------------
void vtkGaussianHistogramView::SetInputConnection(vtkAlgorithmOutput* output)
{
  this->Internals->Input.SetConnection(output);
  this->Modified();
}
vtkAlgorithmOutput* vtkGaussianHistogramView::GetInputConnection()
{
  return this->Internals->Input.GetConnection();
}

//------------------------------------------------------------------------------
bool vtkGaussianHistogramView::PullInput()
{
  vtkSmartPointer<vtkDataObject> data;
  if (!this->Internals->Input.Pull(data))
  {
    return false;
  }
  this->Internals->Data = data;
  return true;
}

//------------------------------------------------------------------------------
void vtkGaussianHistogramView::Update()
{
  if (this->PullInput())
  {
    this->UpdateHistogram();
  }
  this->Superclass::Update();
}

//------------------------------------------------------------------------------
void vtkGaussianHistogramView::Render()
{
  this->Update();
  this->Superclass::Render();
}

//------------------------------------------------------------------------------
vtkDataObject* vtkGaussianHistogramView::GetInputData()
{
  return this->Internals->Data;
}

//------------------------------------------------------------------------------
void vtkGaussianHistogramView::SetSelectionHub(vtkGaussianSelectionHub* hub)
{
  auto& in = *this->Internals;
  if (!in.Hub.Link(hub, in.HubCommand, this, false))
  {
    return;
  }
  this->UpdateHistogram();
}

//------------------------------------------------------------------------------
vtkGaussianSelectionHub* vtkGaussianHistogramView::GetSelectionHub()
{
  return this->Internals->Hub;
}

//------------------------------------------------------------------------------
vtkChartXY* vtkGaussianHistogramView::GetChart()
{
  return this->Internals->Chart;
}

namespace
{
vtkAbstractArray* FindArray(vtkDataObject* data, const char* name)
{
  if (!data || !name)
  {
    return nullptr;
  }
  if (auto* table = vtkTable::SafeDownCast(data))
  {
    return table->GetColumnByName(name);
  }
  if (auto* ds = vtkDataSet::SafeDownCast(data))
  {
    vtkAbstractArray* a = ds->GetPointData()->GetAbstractArray(name);
    if (!a && ds->GetPointData()->GetPedigreeIds() &&
      ds->GetPointData()->GetPedigreeIds()->GetName() &&
      std::string(ds->GetPointData()->GetPedigreeIds()->GetName()) == name)
    {
      a = ds->GetPointData()->GetPedigreeIds();
    }
    return a;
  }
  return nullptr;
}

// The bin of value v of [lo, hi] in nb bins (the last one closed), for both bar kinds.
int BinOf(double v, double lo, double hi, int nb)
{
  return std::min(nb - 1, std::max(0, static_cast<int>((v - lo) / (hi - lo) * nb)));
}

double ValueOf(vtkDataArray* a, vtkIdType i, int component)
{
  const int nc = a->GetNumberOfComponents();
  if (component >= 0 && component < nc)
  {
    return a->GetComponent(i, component);
  }
  double v = a->GetComponent(i, 0);
  for (int c = 1; c < nc; ++c)
  {
    v = std::max(v, a->GetComponent(i, c));
  }
  return v;
}
}

//------------------------------------------------------------------------------
void vtkGaussianHistogramView::UpdateHistogram()
{
  this->PullInput();
  auto& in = *this->Internals;
  in.Chart->ClearPlots();
  in.AllPlot = in.SelectedPlot = nullptr;
  in.Edges.assign(this->NumberOfBins + 1, 0.0);
  in.Counts.assign(this->NumberOfBins, 0);
  in.SelectedCounts.assign(this->NumberOfBins, 0);
  auto* values = vtkDataArray::SafeDownCast(FindArray(in.Data, this->ArrayName));
  vtkAbstractArray* ids = FindArray(in.Data, this->IdArrayName);
  if (!values)
  {
    return;
  }
  const vtkIdType n = values->GetNumberOfTuples();
  double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double v = ValueOf(values, i, this->Component);
    if (std::isfinite(v))
    {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  if (lo > hi)
  {
    lo = 0;
    hi = 1;
  }
  if (hi == lo)
  {
    hi = lo + 1;
  }
  const int nb = this->NumberOfBins;
  in.Lo = lo;
  in.Hi = hi;
  for (int b = 0; b <= nb; ++b)
  {
    in.Edges[b] = lo + (hi - lo) * b / nb;
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double v = ValueOf(values, i, this->Component);
    if (std::isfinite(v))
    {
      ++in.Counts[BinOf(v, lo, hi, nb)];
    }
  }
  this->CountSelected(values, ids);
  in.AllKey = in.Key(this, values);
  in.Bins->Initialize();
  vtkNew<vtkDoubleArray> centre, all, selected;
  centre->SetName("Value");
  all->SetName("All");
  selected->SetName("Selected");
  for (int b = 0; b < nb; ++b)
  {
    centre->InsertNextValue(0.5 * (in.Edges[b] + in.Edges[b + 1]));
    all->InsertNextValue(static_cast<double>(in.Counts[b]));
    selected->InsertNextValue(static_cast<double>(in.SelectedCounts[b]));
  }
  in.Bins->AddColumn(centre);
  in.Bins->AddColumn(all);
  in.Bins->AddColumn(selected);
  in.AllPlot = in.Chart->AddPlot(vtkChart::BAR);
  in.AllPlot->SetInputData(in.Bins, "Value", "All");
  in.AllPlot->SetColor(160, 160, 170, 255);
  in.AllPlot->SetLabel("all");
  in.SelectedPlot = in.Chart->AddPlot(vtkChart::BAR);
  in.SelectedPlot->SetInputData(in.Bins, "Value", "Selected");
  in.SelectedPlot->SetColor(255, 140, 0, 255);
  in.SelectedPlot->SetLabel("selected");
  in.SelectedPlot->SetSelectable(false);
  in.Chart->GetAxis(vtkAxis::BOTTOM)->SetTitle(this->ArrayName ? this->ArrayName : "");
  in.Chart->GetAxis(vtkAxis::LEFT)->SetTitle("Gaussians");
  in.Chart->SetTitle(std::string("Histogram: ") + (this->ArrayName ? this->ArrayName : ""));
  in.Chart->RecalculateBounds();
  this->GetScene()->SetDirty(true);
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkGaussianHistogramView::CountSelected(vtkDataArray* values, vtkAbstractArray* ids)
{
  auto& in = *this->Internals;
  in.SelectedCounts.assign(this->NumberOfBins, 0);
  const int nb = this->NumberOfBins;
  const double lo = in.Lo, hi = in.Hi;
  if (!in.Hub || !ids || in.Hub->GetNumberOfSelectedIds() == 0)
  {
    return;
  }
  // The same bin rule as the grey bars (UpdateHistogram), over the selected rows only, read
  // as they are found (no array of 200,000 rows) and, for a float array, without a virtual
  // call per value.
  const auto& sel = in.Hub->GetSelectedIdVector();
  const int component = this->Component;
  auto* floats = vtkFloatArray::SafeDownCast(values);
  const int nc = values->GetNumberOfComponents();
  // (ValueOf's choice: the component asked for, else the only one, else the largest.)
  const int direct = component >= 0 && component < nc ? component : (nc == 1 ? 0 : -1);
  auto count = [&](vtkIdType r)
  {
    double v;
    if (floats && direct >= 0)
    {
      v = floats->GetPointer(0)[r * nc + direct];
    }
    else
    {
      v = ValueOf(values, r, component);
    }
    if (std::isfinite(v))
    {
      ++in.SelectedCounts[BinOf(v, lo, hi, nb)];
    }
  };
  if (vis4gs::ForEachRowOfIds(
        vtkIdTypeArray::SafeDownCast(ids), sel.data(), static_cast<vtkIdType>(sel.size()), count))
  {
    return;
  }
  vtkNew<vtkIdTypeArray> rows;
  vtkGaussianSelectionHub::IdsToIndices(sel.data(), static_cast<vtkIdType>(sel.size()), ids, rows);
  for (vtkIdType k = 0; k < rows->GetNumberOfTuples(); ++k)
  {
    count(rows->GetValue(k));
  }
}

//------------------------------------------------------------------------------
void vtkGaussianHistogramView::UpdateSelectedCounts()
{
  auto& in = *this->Internals;
  auto* values = vtkDataArray::SafeDownCast(FindArray(in.Data, this->ArrayName));
  vtkDataArray* column = in.Bins->GetNumberOfColumns() == 3
    ? vtkDataArray::SafeDownCast(in.Bins->GetColumn(2))
    : nullptr;
  if (!values || !column || !in.SelectedPlot || in.AllKey != in.Key(this, values) ||
    column->GetNumberOfTuples() != this->NumberOfBins)
  {
    this->UpdateHistogram();
    return;
  }
  // A selection of millions is counted in O(selection) (its rows by binary search in the
  // sorted ids); the 4.89M values of the grey bars are not read again.
  this->CountSelected(values, FindArray(in.Data, this->IdArrayName));
  for (int b = 0; b < this->NumberOfBins; ++b)
  {
    column->SetComponent(b, 0, static_cast<double>(in.SelectedCounts[b]));
  }
  column->Modified();
  in.Bins->Modified();
  this->GetScene()->SetDirty(true);
  this->Modified();
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianHistogramView::SelectRange(double lo, double hi, int mode)
{
  auto& in = *this->Internals;
  auto* values = vtkDataArray::SafeDownCast(FindArray(in.Data, this->ArrayName));
  vtkAbstractArray* ids = FindArray(in.Data, this->IdArrayName);
  if (!values || !ids)
  {
    vtkErrorMacro("SelectRange: the input lacks '"
      << (this->ArrayName ? this->ArrayName : "") << "' or '"
      << (this->IdArrayName ? this->IdArrayName : "") << "'");
    return 0;
  }
  vtkNew<vtkIdTypeArray> rows, selected;
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    const double v = ValueOf(values, i, this->Component);
    if (v >= lo && v <= hi)
    {
      rows->InsertNextValue(i);
    }
  }
  vtkGaussianSelectionHub::IndicesToIds(rows, ids, selected);
  if (in.Hub)
  {
    in.Hub->SelectIds(selected, mode);
  }
  return rows->GetNumberOfTuples();
}

//------------------------------------------------------------------------------
void vtkGaussianHistogramView::OnChartSelection()
{
  auto& in = *this->Internals;
  if (!in.AllPlot || in.Edges.size() < 2)
  {
    return;
  }
  vtkIdTypeArray* bins = in.AllPlot->GetSelection();
  if (!bins || bins->GetNumberOfTuples() == 0)
  {
    if (in.Hub)
    {
      in.Hub->ClearSelection();
    }
    return;
  }
  vtkIdType b0 = bins->GetValue(0), b1 = b0;
  for (vtkIdType k = 1; k < bins->GetNumberOfTuples(); ++k)
  {
    b0 = std::min(b0, bins->GetValue(k));
    b1 = std::max(b1, bins->GetValue(k));
  }
  b0 = std::max<vtkIdType>(0, b0);
  b1 = std::min<vtkIdType>(this->NumberOfBins - 1, b1);
  // The last bin is closed on the right; the others are half open, as in UpdateHistogram.
  const double lo = in.Edges[b0];
  const double hi = (b1 == this->NumberOfBins - 1)
    ? in.Edges[b1 + 1]
    : std::nextafter(in.Edges[b1 + 1], -std::numeric_limits<double>::infinity());
  this->SelectRange(lo, hi, vtkGaussianSelectionHub::REPLACE);
}

//------------------------------------------------------------------------------
void vtkGaussianHistogramView::GetBinEdges(double* edges)
{
  std::copy(this->Internals->Edges.begin(), this->Internals->Edges.end(), edges);
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianHistogramView::GetBinCount(int bin)
{
  const auto& c = this->Internals->Counts;
  return (bin >= 0 && bin < static_cast<int>(c.size())) ? c[bin] : 0;
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianHistogramView::GetSelectedBinCount(int bin)
{
  const auto& c = this->Internals->SelectedCounts;
  return (bin >= 0 && bin < static_cast<int>(c.size())) ? c[bin] : 0;
}

//------------------------------------------------------------------------------
void vtkGaussianHistogramView::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ArrayName: " << (this->ArrayName ? this->ArrayName : "(none)") << "\n";
  os << indent << "IdArrayName: " << (this->IdArrayName ? this->IdArrayName : "(none)") << "\n";
  os << indent << "Component: " << this->Component << "\n";
  os << indent << "NumberOfBins: " << this->NumberOfBins << "\n";
  os << indent << "InputData: " << this->Internals->Data.GetPointer() << "\n";
  os << indent << "InputConnection: " << this->Internals->Input.GetConnection() << "\n";
  os << indent << "SelectionHub: " << this->Internals->Hub.GetPointer() << "\n";
}

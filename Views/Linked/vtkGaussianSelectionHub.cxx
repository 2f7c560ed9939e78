/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianSelectionHub.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianSelectionHub.h"

#include "Vis4GSDataModel.h" // vis4gs::arrays
#include "Vis4GSIdColumn.h"

#include "vtkAbstractArray.h"
#include "vtkAnnotationLink.h"
#include "vtkCallbackCommand.h"
#include "vtkChartXY.h"
#include "vtkDataArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkRenderViewBase.h"
#include "vtkRenderWindow.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkTable.h"
#include "vtkView.h"
#include "vtkWeakPointer.h"

#include <algorithm>
#include <string>
#include <unordered_set>

vtkStandardNewMacro(vtkGaussianSelectionHub);

namespace
{
struct ChartEntry
{
  vtkSmartPointer<vtkChartXY> Chart;
  vtkSmartPointer<vtkTable> Table;
  std::string IdColumn;
  vtkSmartPointer<vtkAnnotationLink> Link;
  unsigned long Observer = 0;
};

void SortUnique(std::vector<vtkIdType>& ids)
{
  // The selector's ids come sorted: checking is one pass, sorting more.
  if (!std::is_sorted(ids.begin(), ids.end()))
  {
    std::sort(ids.begin(), ids.end());
  }
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
}

// Reads any id-like array (vtkIdTypeArray fast path, other vtkDataArrays, variant arrays).
vtkIdType IdAt(vtkAbstractArray* column, vtkIdTypeArray* fast, vtkDataArray* data, vtkIdType i)
{
  if (fast)
  {
    return fast->GetValue(i);
  }
  if (data)
  {
    return static_cast<vtkIdType>(data->GetComponent(i, 0));
  }
  return column->GetVariantValue(i).ToTypeInt64();
}

// Whether the column's ids never decrease. Every linked view asks it of the same 4.89M-row
// GaussianId column after each selection: the answer is kept for the column's last
// modification (one entry per thread: views live on the GUI thread, scripts on theirs).
bool IsSortedColumn(vtkAbstractArray* column, vtkIdTypeArray* fast, vtkDataArray* data)
{
  struct Cached
  {
    vtkWeakPointer<vtkAbstractArray> Column;
    vtkMTimeType Time = 0;
    bool Sorted = false;
  };
  thread_local Cached cache;
  if (cache.Column == column && cache.Time == column->GetMTime())
  {
    return cache.Sorted;
  }
  const vtkIdType n = column->GetNumberOfTuples();
  bool sorted = true;
  if (fast && fast->GetNumberOfComponents() == 1)
  {
    sorted = std::is_sorted(fast->GetPointer(0), fast->GetPointer(0) + n);
  }
  else
  {
    for (vtkIdType i = 1; i < n && sorted; ++i)
    {
      sorted = IdAt(column, fast, data, i - 1) <= IdAt(column, fast, data, i);
    }
  }
  cache.Column = column;
  cache.Time = column->GetMTime();
  cache.Sorted = sorted;
  return sorted;
}

// A selection of GaussianId pedigree ids holding @p list itself (the hub's fresh arrays: a
// 200,000-Gaussian pick is not copied once more).
vtkSmartPointer<vtkSelection> WrapPedigreeIds(vtkIdTypeArray* list)
{
  vtkNew<vtkSelectionNode> node;
  node->SetContentType(vtkSelectionNode::PEDIGREEIDS);
  node->SetFieldType(vtkSelectionNode::POINT);
  list->SetName(vis4gs::arrays::GaussianId);
  node->SetSelectionList(list);
  auto selection = vtkSmartPointer<vtkSelection>::New();
  selection->AddNode(node);
  return selection;
}

// A selection of the indices @p list holds, holding @p list itself.
vtkSmartPointer<vtkSelection> WrapIndices(vtkIdTypeArray* list, int fieldType)
{
  vtkNew<vtkSelectionNode> node;
  node->SetContentType(vtkSelectionNode::INDICES);
  node->SetFieldType(fieldType);
  node->SetSelectionList(list);
  auto selection = vtkSmartPointer<vtkSelection>::New();
  selection->AddNode(node);
  return selection;
}

void AppendList(vtkAbstractArray* list, std::vector<vtkIdType>& out)
{
  if (!list)
  {
    return;
  }
  auto* fast = vtkIdTypeArray::SafeDownCast(list);
  auto* data = vtkDataArray::SafeDownCast(list);
  const vtkIdType n = list->GetNumberOfTuples();
  out.reserve(out.size() + static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    out.push_back(IdAt(list, fast, data, i));
  }
}
}

struct vtkGaussianSelectionHub::vtkInternals
{
  vtkNew<vtkAnnotationLink> Link;
  unsigned long LinkObserver = 0;
  std::vector<vtkSmartPointer<vtkView>> Views;
  std::vector<vtkSmartPointer<vtkRenderWindow>> Windows;
  std::vector<ChartEntry> Charts;
  vtkNew<vtkCallbackCommand> LinkCommand;
  vtkNew<vtkCallbackCommand> ChartCommand;
  vtkSmartPointer<vtkIdTypeArray> SelectedArray; // the ids the link holds
  bool Updating = false;
};

//------------------------------------------------------------------------------
vtkGaussianSelectionHub::vtkGaussianSelectionHub()
  : Internals(new vtkInternals)
{
  auto& in = *this->Internals;
  in.LinkCommand->SetClientData(this);
  in.LinkCommand->SetCallback([](vtkObject*, unsigned long, void* client, void*)
    { static_cast<vtkGaussianSelectionHub*>(client)->OnLinkChanged(); });
  in.ChartCommand->SetClientData(this);
  in.ChartCommand->SetCallback([](vtkObject* caller, unsigned long, void* client, void*)
    { static_cast<vtkGaussianSelectionHub*>(client)->OnChartChanged(caller); });
  in.SelectedArray = vtkSmartPointer<vtkIdTypeArray>::New();
  in.Link->SetCurrentSelection(WrapPedigreeIds(in.SelectedArray));
  in.LinkObserver = in.Link->AddObserver(vtkCommand::AnnotationChangedEvent, in.LinkCommand);
}

//------------------------------------------------------------------------------
vtkGaussianSelectionHub::~vtkGaussianSelectionHub()
{
  auto& in = *this->Internals;
  in.Link->RemoveObserver(in.LinkObserver);
  for (auto& c : in.Charts)
  {
    c.Chart->RemoveObserver(c.Observer);
  }
}

//------------------------------------------------------------------------------
vtkAnnotationLink* vtkGaussianSelectionHub::GetAnnotationLink()
{
  return this->Internals->Link;
}

//------------------------------------------------------------------------------
void vtkGaussianSelectionHub::SetSelection(vtkSelection* selection)
{
  std::vector<vtkIdType> ids;
  if (selection)
  {
    for (unsigned int n = 0; n < selection->GetNumberOfNodes(); ++n)
    {
      vtkSelectionNode* node = selection->GetNode(n);
      const int content = node->GetContentType();
      if (content == vtkSelectionNode::PEDIGREEIDS || content == vtkSelectionNode::GLOBALIDS)
      {
        AppendList(node->GetSelectionList(), ids);
      }
      else if (content == vtkSelectionNode::INDICES)
      {
        // Only meaningful with a registered table of the same kind: a chart's rows.
        bool converted = false;
        for (auto& c : this->Internals->Charts)
        {
          vtkAbstractArray* column = c.Table->GetColumnByName(c.IdColumn.c_str());
          auto* indices = vtkIdTypeArray::SafeDownCast(node->GetSelectionList());
          if (column && indices && node->GetFieldType() != vtkSelectionNode::VERTEX)
          {
            vtkNew<vtkIdTypeArray> out;
            IndicesToIds(indices, column, out);
            AppendList(out, ids);
            converted = true;
            break;
          }
        }
        if (!converted)
        {
          vtkWarningMacro("SetSelection: an INDICES selection node without a registered id "
                          "column was ignored; pass GaussianId pedigree ids");
        }
      }
      else
      {
        vtkWarningMacro("SetSelection: selection node of content type "
          << vtkSelectionNode::GetContentTypeAsString(content) << " ignored");
      }
    }
  }
  SortUnique(ids);
  this->Publish(std::move(ids));
}

//------------------------------------------------------------------------------
void vtkGaussianSelectionHub::SelectIds(vtkIdTypeArray* ids, int mode)
{
  if (!ids)
  {
    this->SelectIds(nullptr, 0, mode);
    return;
  }
  this->SelectIds(ids->GetPointer(0), ids->GetNumberOfTuples(), mode);
}

//------------------------------------------------------------------------------
void vtkGaussianSelectionHub::SelectIds(const vtkIdType* ids, vtkIdType count, int mode)
{
  std::vector<vtkIdType> given(ids, ids + (ids ? count : 0));
  SortUnique(given);
  std::vector<vtkIdType> result;
  const auto& cur = this->Selected;
  switch (mode)
  {
    case ADD:
      std::set_union(
        cur.begin(), cur.end(), given.begin(), given.end(), std::back_inserter(result));
      break;
    case SUBTRACT:
      std::set_difference(
        cur.begin(), cur.end(), given.begin(), given.end(), std::back_inserter(result));
      break;
    case TOGGLE:
      std::set_symmetric_difference(
        cur.begin(), cur.end(), given.begin(), given.end(), std::back_inserter(result));
      break;
    default:
      result = std::move(given);
      break;
  }
  this->Publish(std::move(result));
}

//------------------------------------------------------------------------------
void vtkGaussianSelectionHub::ClearSelection()
{
  this->Publish({});
}

//------------------------------------------------------------------------------
void vtkGaussianSelectionHub::Publish(std::vector<vtkIdType>&& ids)
{
  auto& in = *this->Internals;
  if (ids == this->Selected || in.Updating)
  {
    return;
  }
  in.Updating = true;
  this->Selected = std::move(ids);
  ++this->NumberOfChanges;

  auto array = vtkSmartPointer<vtkIdTypeArray>::New();
  array->SetNumberOfTuples(static_cast<vtkIdType>(this->Selected.size()));
  std::copy(this->Selected.begin(), this->Selected.end(), array->GetPointer(0));
  in.SelectedArray = array;
  in.Link->SetCurrentSelection(WrapPedigreeIds(array));

  for (auto& c : in.Charts)
  {
    vtkAbstractArray* column = c.Table->GetColumnByName(c.IdColumn.c_str());
    vtkNew<vtkIdTypeArray> rows;
    if (column)
    {
      IdsToIndices(array, column, rows);
    }
    c.Link->SetCurrentSelection(WrapIndices(rows, vtkSelectionNode::POINT));
    // vtkChartXY only re-reads its link when painting; make sure it does.
    c.Chart->Modified();
  }
  this->InvokeEvent(vtkCommand::SelectionChangedEvent, nullptr);
  in.Updating = false;
  this->Modified();
  if (this->RenderOnChange)
  {
    this->RenderAll();
  }
}

//------------------------------------------------------------------------------
void vtkGaussianSelectionHub::OnLinkChanged()
{
  if (this->Internals->Updating)
  {
    return;
  }
  // Someone set the shared link directly (e.g. a representation of the scene view).
  this->SetSelection(this->Internals->Link->GetCurrentSelection());
}

//------------------------------------------------------------------------------
void vtkGaussianSelectionHub::OnChartChanged(vtkObject* caller)
{
  auto& in = *this->Internals;
  if (in.Updating)
  {
    return;
  }
  for (auto& c : in.Charts)
  {
    if (c.Chart.GetPointer() != caller)
    {
      continue;
    }
    vtkAbstractArray* column = c.Table->GetColumnByName(c.IdColumn.c_str());
    vtkSelection* selection = c.Link->GetCurrentSelection();
    std::vector<vtkIdType> ids;
    if (column && selection)
    {
      for (unsigned int n = 0; n < selection->GetNumberOfNodes(); ++n)
      {
        auto* rows = vtkIdTypeArray::SafeDownCast(selection->GetNode(n)->GetSelectionList());
        if (rows)
        {
          vtkNew<vtkIdTypeArray> out;
          IndicesToIds(rows, column, out);
          AppendList(out, ids);
        }
      }
    }
    SortUnique(ids);
    this->Publish(std::move(ids));
    return;
  }
}

//------------------------------------------------------------------------------
void vtkGaussianSelectionHub::GetSelectedIds(vtkIdTypeArray* ids)
{
  if (!ids)
  {
    return;
  }
  ids->SetNumberOfComponents(1);
  ids->SetNumberOfTuples(static_cast<vtkIdType>(this->Selected.size()));
  std::copy(this->Selected.begin(), this->Selected.end(), ids->GetPointer(0));
}

//------------------------------------------------------------------------------
vtkIdTypeArray* vtkGaussianSelectionHub::GetSelectedIdArray()
{
  return this->Internals->SelectedArray;
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianSelectionHub::GetNumberOfSelectedIds()
{
  return static_cast<vtkIdType>(this->Selected.size());
}

//------------------------------------------------------------------------------
bool vtkGaussianSelectionHub::IsSelected(vtkIdType gaussianId)
{
  return std::binary_search(this->Selected.begin(), this->Selected.end(), gaussianId);
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkSelection> vtkGaussianSelectionHub::GetCurrentSelection()
{
  vtkNew<vtkIdTypeArray> ids;
  this->GetSelectedIds(ids);
  return MakePedigreeSelection(ids);
}

//------------------------------------------------------------------------------
void vtkGaussianSelectionHub::AddView(vtkView* view)
{
  auto& views = this->Internals->Views;
  if (view && std::find(views.begin(), views.end(), view) == views.end())
  {
    views.emplace_back(view);
  }
}

//------------------------------------------------------------------------------
void vtkGaussianSelectionHub::RemoveView(vtkView* view)
{
  auto& views = this->Internals->Views;
  views.erase(std::remove(views.begin(), views.end(), view), views.end());
}

//------------------------------------------------------------------------------
void vtkGaussianSelectionHub::AddRenderWindow(vtkRenderWindow* window)
{
  auto& windows = this->Internals->Windows;
  if (window && std::find(windows.begin(), windows.end(), window) == windows.end())
  {
    windows.emplace_back(window);
  }
}

//------------------------------------------------------------------------------
void vtkGaussianSelectionHub::RemoveAllViews()
{
  this->Internals->Views.clear();
  this->Internals->Windows.clear();
}

//------------------------------------------------------------------------------
int vtkGaussianSelectionHub::GetNumberOfViews()
{
  return static_cast<int>(this->Internals->Views.size() + this->Internals->Windows.size());
}

//------------------------------------------------------------------------------
void vtkGaussianSelectionHub::AddChart(vtkChartXY* chart, vtkTable* table, const char* idColumn)
{
  if (!chart || !table || !idColumn)
  {
    vtkErrorMacro("AddChart needs a chart, a table and an id column name");
    return;
  }
  this->RemoveChart(chart);
  ChartEntry entry;
  entry.Chart = chart;
  entry.Table = table;
  entry.IdColumn = idColumn;
  entry.Link = vtkSmartPointer<vtkAnnotationLink>::New();
  chart->SetAnnotationLink(entry.Link);
  entry.Observer =
    chart->AddObserver(vtkCommand::SelectionChangedEvent, this->Internals->ChartCommand);
  this->Internals->Charts.push_back(entry);
  // Show the current selection right away.
  vtkNew<vtkIdTypeArray> ids, rows;
  this->GetSelectedIds(ids);
  if (vtkAbstractArray* column = table->GetColumnByName(idColumn))
  {
    IdsToIndices(ids, column, rows);
  }
  entry.Link->SetCurrentSelection(MakeIndexSelection(rows, vtkSelectionNode::POINT));
}

//------------------------------------------------------------------------------
void vtkGaussianSelectionHub::RemoveChart(vtkChartXY* chart)
{
  auto& charts = this->Internals->Charts;
  for (auto it = charts.begin(); it != charts.end(); ++it)
  {
    if (it->Chart.GetPointer() == chart)
    {
      chart->RemoveObserver(it->Observer);
      charts.erase(it);
      return;
    }
  }
}

//------------------------------------------------------------------------------
void vtkGaussianSelectionHub::RenderAll()
{
  for (auto& view : this->Internals->Views)
  {
    if (auto* rv = vtkRenderViewBase::SafeDownCast(view))
    {
      rv->Render();
    }
    else
    {
      view->Update();
    }
  }
  for (auto& window : this->Internals->Windows)
  {
    window->Render();
  }
}

//------------------------------------------------------------------------------
void vtkGaussianSelectionHub::SetIteration(int iteration)
{
  if (iteration == this->Iteration)
  {
    return;
  }
  this->Iteration = iteration;
  this->Modified();
  this->InvokeEvent(IterationChangedEvent, &iteration);
  if (this->RenderOnChange)
  {
    this->RenderAll();
  }
}

//------------------------------------------------------------------------------
void vtkGaussianSelectionHub::IdsToIndices(vtkIdTypeArray* ids,
  vtkAbstractArray* idColumn,
  vtkIdTypeArray* indices)
{
  if (!ids)
  {
    IdsToIndices(nullptr, 0, idColumn, indices);
    return;
  }
  IdsToIndices(ids->GetPointer(0), ids->GetNumberOfTuples(), idColumn, indices);
}

//------------------------------------------------------------------------------
void vtkGaussianSelectionHub::IdsToIndices(const vtkIdType* ids,
  vtkIdType count,
  vtkAbstractArray* idColumn,
  vtkIdTypeArray* indices)
{
  if (!indices)
  {
    return;
  }
  indices->SetNumberOfComponents(1);
  indices->SetNumberOfTuples(0);
  if (!idColumn || !ids || count <= 0)
  {
    return;
  }
  auto* fast = vtkIdTypeArray::SafeDownCast(idColumn);
  auto* data = vtkDataArray::SafeDownCast(idColumn);
  const vtkIdType n = idColumn->GetNumberOfTuples();
  // The hub's ids (ascending) in a snapshot's column (ascending): O(selection), in column
  // order as the scan below, straight into @p indices (a column of unique ids, the usual one,
  // gives at most one row per id).
  indices->Allocate(count);
  if (fast &&
    vis4gs::ForEachRowOfIds(fast, ids, count, [&](vtkIdType r) { indices->InsertNextValue(r); }))
  {
    return;
  }
  const bool sorted = IsSortedColumn(idColumn, fast, data);
  if (sorted && count * 20 < n)
  {
    // Few ids in a sorted column (snapshot ids are strictly increasing): binary searches.
    for (vtkIdType k = 0; k < count; ++k)
    {
      vtkIdType lo = 0, hi = n;
      while (lo < hi)
      {
        const vtkIdType mid = lo + (hi - lo) / 2;
        if (IdAt(idColumn, fast, data, mid) < ids[k])
        {
          lo = mid + 1;
        }
        else
        {
          hi = mid;
        }
      }
      for (; lo < n && IdAt(idColumn, fast, data, lo) == ids[k]; ++lo)
      {
        indices->InsertNextValue(lo);
      }
    }
    return;
  }
  if (sorted && std::is_sorted(ids, ids + count))
  {
    // Many sorted ids in a sorted column of another type: one merge, in column order as
    // the scan below, without a hash set of a million ids.
    std::vector<vtkIdType> rows;
    vtkIdType k = 0;
    for (vtkIdType i = 0; i < n && k < count; ++i)
    {
      const vtkIdType v = IdAt(idColumn, fast, data, i);
      while (k < count && ids[k] < v)
      {
        ++k;
      }
      if (k < count && ids[k] == v)
      {
        rows.push_back(i);
      }
    }
    indices->SetNumberOfTuples(static_cast<vtkIdType>(rows.size()));
    std::copy(rows.begin(), rows.end(), indices->GetPointer(0));
    return;
  }
  std::unordered_set<vtkIdType> wanted(ids, ids + count);
  for (vtkIdType i = 0; i < n; ++i)
  {
    if (wanted.count(IdAt(idColumn, fast, data, i)))
    {
      indices->InsertNextValue(i);
    }
  }
}

//------------------------------------------------------------------------------
void vtkGaussianSelectionHub::IndicesToIds(vtkIdTypeArray* indices,
  vtkAbstractArray* idColumn,
  vtkIdTypeArray* ids)
{
  if (!ids)
  {
    return;
  }
  ids->SetNumberOfComponents(1);
  ids->SetNumberOfTuples(0);
  if (!indices || !idColumn)
  {
    return;
  }
  auto* fast = vtkIdTypeArray::SafeDownCast(idColumn);
  auto* data = vtkDataArray::SafeDownCast(idColumn);
  const vtkIdType n = idColumn->GetNumberOfTuples();
  std::vector<vtkIdType> out;
  out.reserve(static_cast<std::size_t>(indices->GetNumberOfTuples()));
  for (vtkIdType k = 0; k < indices->GetNumberOfTuples(); ++k)
  {
    const vtkIdType i = indices->GetValue(k);
    if (i >= 0 && i < n)
    {
      out.push_back(IdAt(idColumn, fast, data, i));
    }
  }
  SortUnique(out);
  ids->SetNumberOfTuples(static_cast<vtkIdType>(out.size()));
  std::copy(out.begin(), out.end(), ids->GetPointer(0));
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkSelection> vtkGaussianSelectionHub::MakeIndexSelection(vtkIdTypeArray* indices,
  int fieldType)
{
  vtkNew<vtkIdTypeArray> list;
  if (indices)
  {
    list->DeepCopy(indices);
  }
  return WrapIndices(list, fieldType);
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkSelection> vtkGaussianSelectionHub::MakePedigreeSelection(vtkIdTypeArray* ids)
{
  vtkNew<vtkIdTypeArray> list;
  if (ids)
  {
    list->DeepCopy(ids);
  }
  return WrapPedigreeIds(list);
}

//------------------------------------------------------------------------------
void vtkGaussianSelectionHub::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RenderOnChange: " << this->RenderOnChange << "\n";
  os << indent << "Iteration: " << this->Iteration << "\n";
  os << indent << "NumberOfChanges: " << this->NumberOfChanges << "\n";
  os << indent << "NumberOfSelectedIds: " << this->Selected.size() << "\n";
  os << indent << "NumberOfViews: " << this->Internals->Views.size() << "\n";
  os << indent << "NumberOfRenderWindows: " << this->Internals->Windows.size() << "\n";
  os << indent << "NumberOfCharts: " << this->Internals->Charts.size() << "\n";
  os << indent << "AnnotationLink: " << this->Internals->Link.GetPointer() << "\n";
}

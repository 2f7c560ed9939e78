// SPDX-License-Identifier: BSD-3-Clause
// The selection hub: modes, conversions both ways, a chart linked by row indices, a selection
// set directly on the shared annotation link, iteration events, and re-rendering of every
// registered view (including vtkContextViews).
#include "vtkGaussianSelectionHub.h"

#include "vtkAnnotationLink.h"
#include "vtkCallbackCommand.h"
#include "vtkChartXY.h"
#include "vtkContextScene.h"
#include "vtkContextView.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkTable.h"

#include "Vis4GSTestCheck.h"

#include <iostream>
#include <vector>

namespace
{
vis4gs::testing::CheckCounter Check;

std::vector<vtkIdType> Values(vtkIdTypeArray* a)
{
  return std::vector<vtkIdType>(a->GetPointer(0), a->GetPointer(0) + a->GetNumberOfTuples());
}

std::vector<vtkIdType> Selected(vtkGaussianSelectionHub* hub)
{
  vtkNew<vtkIdTypeArray> ids;
  hub->GetSelectedIds(ids);
  return Values(ids);
}
}

int TestGaussianSelectionHub(int, char*[])
{
  vtkNew<vtkGaussianSelectionHub> hub;
  hub->RenderOnChangeOff();
  int events = 0;
  vtkNew<vtkCallbackCommand> counter;
  counter->SetClientData(&events);
  counter->SetCallback([](vtkObject*, unsigned long, void* c, void*) { ++*static_cast<int*>(c); });
  hub->AddObserver(vtkCommand::SelectionChangedEvent, counter);

  // Modes.
  const vtkIdType a[] = { 5, 3, 9, 3 };
  hub->SelectIds(a, 4);
  Check(Selected(hub) == std::vector<vtkIdType>({ 3, 5, 9 }), "replace sorts and dedups");
  Check(events == 1, "one event per change");
  hub->SelectIds(a, 4);
  Check(events == 1, "no event when unchanged");
  const vtkIdType b[] = { 9, 11 };
  hub->SelectIds(b, 2, vtkGaussianSelectionHub::ADD);
  Check(Selected(hub) == std::vector<vtkIdType>({ 3, 5, 9, 11 }), "add");
  hub->SelectIds(b, 2, vtkGaussianSelectionHub::SUBTRACT);
  Check(Selected(hub) == std::vector<vtkIdType>({ 3, 5 }), "subtract");
  const vtkIdType c[] = { 5, 7 };
  hub->SelectIds(c, 2, vtkGaussianSelectionHub::TOGGLE);
  Check(Selected(hub) == std::vector<vtkIdType>({ 3, 7 }), "toggle");
  Check(hub->IsSelected(7) && !hub->IsSelected(5), "IsSelected");

  // The link holds pedigree ids named GaussianId.
  vtkSelection* cur = hub->GetAnnotationLink()->GetCurrentSelection();
  Check(cur && cur->GetNumberOfNodes() == 1 &&
      cur->GetNode(0)->GetContentType() == vtkSelectionNode::PEDIGREEIDS &&
      std::string(cur->GetNode(0)->GetSelectionList()->GetName()) == "GaussianId",
    "link holds a GaussianId pedigree selection");

  // Someone sets the shared link directly (as a representation does).
  vtkNew<vtkIdTypeArray> direct;
  direct->InsertNextValue(42);
  direct->InsertNextValue(40);
  hub->GetAnnotationLink()->SetCurrentSelection(
    vtkGaussianSelectionHub::MakePedigreeSelection(direct));
  Check(Selected(hub) == std::vector<vtkIdType>({ 40, 42 }), "direct link change reaches hub");

  // Conversions: unsorted column (hash path) and sorted column (binary-search path).
  vtkNew<vtkIntArray> unsorted;
  for (int v : { 7, 40, 3, 42, 40, 100 })
  {
    unsorted->InsertNextValue(v);
  }
  vtkNew<vtkIdTypeArray> rows;
  const vtkIdType want[] = { 40, 42 };
  vtkGaussianSelectionHub::IdsToIndices(want, 2, unsorted, rows);
  Check(Values(rows) == std::vector<vtkIdType>({ 1, 3, 4 }), "ids to rows, unsorted column");
  vtkNew<vtkIdTypeArray> sorted;
  for (vtkIdType v = 0; v < 1000; ++v)
  {
    sorted->InsertNextValue(2 * v);
  }
  const vtkIdType want2[] = { 0, 3, 1998, 500 };
  std::vector<vtkIdType> w2(want2, want2 + 4);
  std::sort(w2.begin(), w2.end());
  vtkGaussianSelectionHub::IdsToIndices(w2.data(), 4, sorted, rows);
  Check(Values(rows) == std::vector<vtkIdType>({ 0, 250, 999 }), "ids to rows, sorted column");
  // Many sorted ids (a twentieth of the column or more): one merge over the column.
  std::vector<vtkIdType> many, manyRows;
  vtkNew<vtkIdTypeArray> manyOut;
  for (vtkIdType v = 0; v < 600; ++v)
  {
    many.push_back(v);
    if (v % 2 == 0)
    {
      manyRows.push_back(v / 2);
    }
  }
  vtkGaussianSelectionHub::IdsToIndices(many.data(), 600, sorted, manyOut);
  Check(Values(manyOut) == manyRows, "many ids to rows, sorted column (merge)");
  // The column's order is remembered only until it is modified: now unsorted (hash path).
  sorted->SetValue(0, 5000);
  sorted->Modified();
  vtkGaussianSelectionHub::IdsToIndices(many.data(), 600, sorted, manyOut);
  manyRows.erase(manyRows.begin());
  Check(Values(manyOut) == manyRows, "a modified column is checked for order again");
  sorted->SetValue(0, 0);
  sorted->Modified();
  vtkNew<vtkIdTypeArray> back;
  rows->InsertNextValue(5000); // out of range: skipped
  vtkGaussianSelectionHub::IndicesToIds(rows, sorted, back);
  Check(Values(back) == std::vector<vtkIdType>({ 0, 500, 1998 }), "rows to ids");

  // A chart whose rows are Gaussians: the hub pushes INDICES/POINT selections into it...
  vtkNew<vtkTable> table;
  vtkNew<vtkIdTypeArray> col;
  col->SetName("GaussianId");
  for (vtkIdType v : { 42, 7, 40, 13 })
  {
    col->InsertNextValue(v);
  }
  vtkNew<vtkIntArray> xs;
  xs->SetName("x");
  for (int v : { 1, 2, 3, 4 })
  {
    xs->InsertNextValue(v);
  }
  table->AddColumn(col);
  table->AddColumn(xs);
  vtkNew<vtkChartXY> chart;
  hub->AddChart(chart, table, "GaussianId");
  vtkSelection* cs = chart->GetAnnotationLink()->GetCurrentSelection();
  Check(cs && cs->GetNode(0)->GetContentType() == vtkSelectionNode::INDICES &&
      cs->GetNode(0)->GetFieldType() == vtkSelectionNode::POINT &&
      Values(vtkIdTypeArray::SafeDownCast(cs->GetNode(0)->GetSelectionList())) ==
        std::vector<vtkIdType>({ 0, 2 }),
    "chart gets the rows of 40 and 42 as INDICES/POINT");
  // ...and converts the chart's own selection (rows 1 and 3) back to GaussianIds 7 and 13.
  vtkNew<vtkIdTypeArray> chartRows;
  chartRows->InsertNextValue(3);
  chartRows->InsertNextValue(1);
  chart->GetAnnotationLink()->SetCurrentSelection(
    vtkGaussianSelectionHub::MakeIndexSelection(chartRows, vtkSelectionNode::POINT));
  chart->InvokeEvent(vtkCommand::SelectionChangedEvent);
  Check(Selected(hub) == std::vector<vtkIdType>({ 7, 13 }), "chart selection reaches the hub");

  // Every registered view is rendered after a change, context views included.
  vtkNew<vtkContextView> v1, v2;
  for (vtkContextView* v : { v1.GetPointer(), v2.GetPointer() })
  {
    v->GetRenderWindow()->SetSize(60, 40);
    v->GetRenderWindow()->SetMultiSamples(0);
    hub->AddView(v);
  }
  int renders = 0;
  vtkNew<vtkCallbackCommand> renderCounter;
  renderCounter->SetClientData(&renders);
  renderCounter->SetCallback(
    [](vtkObject*, unsigned long, void* c, void*) { ++*static_cast<int*>(c); });
  v1->GetRenderWindow()->AddObserver(vtkCommand::EndEvent, renderCounter);
  v2->GetRenderWindow()->AddObserver(vtkCommand::EndEvent, renderCounter);
  hub->RenderOnChangeOn();
  hub->ClearSelection();
  Check(renders == 2, "both context views rendered after a change");
  Check(hub->GetNumberOfSelectedIds() == 0, "clear");

  // Iteration.
  int seen = -1;
  vtkNew<vtkCallbackCommand> itObserver;
  itObserver->SetClientData(&seen);
  itObserver->SetCallback([](vtkObject*, unsigned long, void* c, void* d)
    { *static_cast<int*>(c) = *static_cast<int*>(d); });
  hub->AddObserver(vtkGaussianSelectionHub::IterationChangedEvent, itObserver);
  hub->SetIteration(1500);
  Check(seen == 1500 && hub->GetIteration() == 1500, "iteration event");
  Check(renders == 4, "views rendered after an iteration change");
  hub->RemoveAllViews();
  return Check.ExitCode();
}

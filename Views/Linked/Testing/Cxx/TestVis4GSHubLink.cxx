// SPDX-License-Identifier: BSD-3-Clause
// The views' link to the selection hub: a selection and an iteration reach the linked command
// (the iteration only when asked), the view joins and leaves the hub's views, a second link
// to the same hub changes nothing, relinking moves everything to the new hub, and the link
// reads as null once the hub is deleted.
#include "Vis4GSHubLink.h"
#include "vtkGaussianSelectionHub.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"
#include "vtkView.h"

#include "Vis4GSTestCheck.h"

#include <iostream>

namespace
{
vis4gs::testing::CheckCounter Check;

struct Counts
{
  int Selection = 0;
  int Iteration = 0;
};

void Count(vtkObject*, unsigned long event, void* client, void*)
{
  auto* counts = static_cast<Counts*>(client);
  (event == vtkCommand::SelectionChangedEvent ? counts->Selection : counts->Iteration)++;
}
}

int TestVis4GSHubLink(int, char*[])
{
  Counts counts;
  vtkNew<vtkCallbackCommand> command;
  command->SetClientData(&counts);
  command->SetCallback(Count);
  vtkNew<vtkView> view;
  auto a = vtkSmartPointer<vtkGaussianSelectionHub>::New();
  vtkNew<vtkGaussianSelectionHub> b;

  Vis4GSHubLink link;
  Check(!link && link.GetPointer() == nullptr, "a new link holds no hub");
  Check(link.Link(a, command, view, true), "linking to a hub");
  Check(link.GetPointer() == a && link->GetNumberOfViews() == 1, "the view joins the hub's views");
  Check(!link.Link(a, command, view, true), "linking to the same hub again changes nothing");
  Check(a->HasObserver(vtkCommand::SelectionChangedEvent, command) &&
      a->HasObserver(vtkGaussianSelectionHub::IterationChangedEvent, command),
    "the command observes the selection and the iteration once");
  const vtkIdType id = 7;
  a->SelectIds(&id, 1, vtkGaussianSelectionHub::REPLACE);
  a->SetIteration(500);
  Check(counts.Selection == 1 && counts.Iteration == 1, "a selection and an iteration reach it");

  Check(link.Link(b, command, nullptr, false), "relinking to another hub");
  Check(a->GetNumberOfViews() == 0 && !a->HasObserver(vtkCommand::SelectionChangedEvent) &&
      !a->HasObserver(vtkGaussianSelectionHub::IterationChangedEvent),
    "the first hub keeps no observer and no view");
  Check(b->GetNumberOfViews() == 0 && b->HasObserver(vtkCommand::SelectionChangedEvent, command) &&
      !b->HasObserver(vtkGaussianSelectionHub::IterationChangedEvent),
    "the second hub: the selection observed, not the iteration, no view");
  a->SelectIds(&id, 1, vtkGaussianSelectionHub::REPLACE);
  b->SetIteration(600);
  b->SelectIds(&id, 1, vtkGaussianSelectionHub::REPLACE);
  Check(counts.Selection == 2 && counts.Iteration == 1, "only the second hub's selection counts");

  Check(link.Link(a, command, view, false) && a->GetNumberOfViews() == 1, "back to the first");
  a = nullptr; // the link holds the hub weakly
  Check(!link, "the link reads as null once its hub is deleted");
  Check(link.Link(nullptr, command, view, false) == false, "unlinking a deleted hub: nothing");
  Check(link.Link(b, command, view, false) && b->GetNumberOfViews() == 1 &&
      link.Link(nullptr, command, nullptr, false) && b->GetNumberOfViews() == 0 &&
      !b->HasObserver(vtkCommand::SelectionChangedEvent),
    "unlinking removes the observer and the view");
  return Check.ExitCode();
}

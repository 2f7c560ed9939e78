/*=========================================================================

  Program:   Vis4GS
  Module:    Vis4GSHubLink.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "Vis4GSHubLink.h"

#include "vtkCommand.h"

//------------------------------------------------------------------------------
bool Vis4GSHubLink::Link(vtkGaussianSelectionHub* hub,
  vtkCommand* command,
  vtkView* view,
  bool iteration)
{
  if (this->Hub == hub)
  {
    return false;
  }
  if (this->Hub)
  {
    this->Hub->RemoveObserver(this->SelectionObserver);
    if (this->IterationObserver)
    {
      this->Hub->RemoveObserver(this->IterationObserver);
    }
    if (this->View)
    {
      this->Hub->RemoveView(this->View);
    }
  }
  this->Hub = hub;
  this->View = nullptr;
  this->SelectionObserver = this->IterationObserver = 0;
  if (hub)
  {
    this->SelectionObserver = hub->AddObserver(vtkCommand::SelectionChangedEvent, command);
    if (iteration)
    {
      this->IterationObserver =
        hub->AddObserver(vtkGaussianSelectionHub::IterationChangedEvent, command);
    }
    if (view)
    {
      hub->AddView(view);
      this->View = view;
    }
  }
  return true;
}

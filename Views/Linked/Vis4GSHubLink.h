/*=========================================================================

  Program:   Vis4GS
  Module:    Vis4GSHubLink.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class Vis4GSHubLink
 * @brief A linked view's connection to the vtkGaussianSelectionHub: the hub (weakly held),
 * the observers of its events and the view's place among the views it renders.
 *
 * Every view with SetSelectionHub (scene, tree item, timeline, histogram) holds one and calls
 * Link() there: the previous hub's observers go (and the view leaves the views it renders),
 * then the new hub's SelectionChangedEvent, and IterationChangedEvent when asked, call the
 * view's command, and the view joins the views it renders. Between links it reads as the hub
 * pointer (`link->GetIteration()`, `if (link)`), null once the hub is deleted.
 */
#ifndef Vis4GSHubLink_h
#define Vis4GSHubLink_h

#include "vis4gsViewsLinkedModule.h" // For export macro

#include "vtkGaussianSelectionHub.h" // For the hub held
#include "vtkWeakPointer.h"          // For vtkWeakPointer

class vtkCommand;
class vtkView;

class VIS4GSVIEWSLINKED_EXPORT Vis4GSHubLink
{
public:
  /**
   * Links to @p hub (null: unlinks): observes its SelectionChangedEvent, and its
   * IterationChangedEvent when @p iteration, with @p command, and adds @p view (null: none,
   * for an item inside a view) to the views it renders. Returns false, changing nothing,
   * when @p hub is the hub linked already.
   */
  bool Link(vtkGaussianSelectionHub* hub, vtkCommand* command, vtkView* view, bool iteration);

  vtkGaussianSelectionHub* GetPointer() const { return this->Hub; }
  operator vtkGaussianSelectionHub*() const { return this->Hub; }
  vtkGaussianSelectionHub* operator->() const { return this->Hub; }

private:
  vtkWeakPointer<vtkGaussianSelectionHub> Hub;
  vtkView* View = nullptr;
  unsigned long SelectionObserver = 0;
  unsigned long IterationObserver = 0;
};

#endif

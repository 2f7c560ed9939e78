/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianTreeView.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianTreeView.h"

#include "vtkContextScene.h"
#include "vtkGaussianSelectionHub.h"
#include "vtkGaussianTreeItem.h"
#include "vtkObjectFactory.h"
#include "vtkRenderer.h"

vtkStandardNewMacro(vtkGaussianTreeView);

//------------------------------------------------------------------------------
vtkGaussianTreeView::vtkGaussianTreeView()
{
  this->GetScene()->AddItem(this->Item);
  this->GetRenderer()->SetBackground(36 / 255.0, 40 / 255.0, 48 / 255.0);
}

//------------------------------------------------------------------------------
vtkGaussianTreeView::~vtkGaussianTreeView()
{
  this->SetSelectionHub(nullptr);
}

//------------------------------------------------------------------------------
void vtkGaussianTreeView::SetTree(vtkTree* tree)
{
  this->Item->SetTree(tree);
  this->Modified();
}

//------------------------------------------------------------------------------
vtkTree* vtkGaussianTreeView::GetTree()
{
  return this->Item->GetTree();
}

//------------------------------------------------------------------------------
void vtkGaussianTreeView::SetFamilyBands(vtkTable* bands)
{
  this->Item->SetFamilyBands(bands);
  this->Modified();
}

//------------------------------------------------------------------------------
vtkTable* vtkGaussianTreeView::GetFamilyBands()
{
  return this->Item->GetFamilyBands();
}

//------------------------------------------------------------------------------
void vtkGaussianTreeView::SetSelectionHub(vtkGaussianSelectionHub* hub)
{
  vtkGaussianSelectionHub* old = this->Item->GetSelectionHub();
  if (old == hub)
  {
    return;
  }
  if (old)
  {
    old->RemoveView(this);
  }
  this->Item->SetSelectionHub(hub);
  if (hub)
  {
    hub->AddView(this);
  }
  this->Modified();
}

//------------------------------------------------------------------------------
vtkGaussianSelectionHub* vtkGaussianTreeView::GetSelectionHub()
{
  return this->Item->GetSelectionHub();
}

//------------------------------------------------------------------------------
vtkGaussianTreeItem* vtkGaussianTreeView::GetTreeItem()
{
  return this->Item;
}

//------------------------------------------------------------------------------
void vtkGaussianTreeView::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "TreeItem:\n";
  this->Item->PrintSelf(os, indent.GetNextIndent());
}

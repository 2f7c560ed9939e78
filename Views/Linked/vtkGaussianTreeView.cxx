/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianTreeView.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianTreeView.h"

#include "Vis4GSViewInput.h"

#include "vtkContextScene.h"
#include "vtkGaussianSelectionHub.h"
#include "vtkGaussianTreeItem.h"
#include "vtkObjectFactory.h"
#include "vtkRenderer.h"
#include "vtkTable.h"
#include "vtkTree.h"

vtkStandardNewMacro(vtkGaussianTreeView);

struct vtkGaussianTreeView::vtkInputs
{
  Vis4GSViewInput Tree;
  Vis4GSViewInput Bands;
};

//------------------------------------------------------------------------------
vtkGaussianTreeView::vtkGaussianTreeView()
  : Inputs(new vtkInputs)
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
  this->Inputs->Tree.SetConnection(nullptr);
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
  this->Inputs->Bands.SetConnection(nullptr);
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
void vtkGaussianTreeView::SetInputConnection(vtkAlgorithmOutput* tree)
{
  this->Inputs->Tree.SetConnection(tree);
  this->Modified();
}
vtkAlgorithmOutput* vtkGaussianTreeView::GetInputConnection()
{
  return this->Inputs->Tree.GetConnection();
}
void vtkGaussianTreeView::SetFamilyBandsConnection(vtkAlgorithmOutput* bands)
{
  this->Inputs->Bands.SetConnection(bands);
  this->Modified();
}
vtkAlgorithmOutput* vtkGaussianTreeView::GetFamilyBandsConnection()
{
  return this->Inputs->Bands.GetConnection();
}

//------------------------------------------------------------------------------
void vtkGaussianTreeView::Update()
{
  vtkSmartPointer<vtkDataObject> data;
  // The bands first: the item lays the families out with the tree it is given next.
  if (this->Inputs->Bands.Pull(data))
  {
    this->Item->SetFamilyBands(vtkTable::SafeDownCast(data.GetPointer()));
  }
  if (this->Inputs->Tree.Pull(data))
  {
    this->Item->SetTree(vtkTree::SafeDownCast(data.GetPointer()));
  }
  this->Superclass::Update();
}

//------------------------------------------------------------------------------
void vtkGaussianTreeView::Render()
{
  this->Update();
  this->Superclass::Render();
}

//------------------------------------------------------------------------------
void vtkGaussianTreeView::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "InputConnection: " << this->Inputs->Tree.GetConnection() << "\n";
  os << indent << "FamilyBandsConnection: " << this->Inputs->Bands.GetConnection() << "\n";
  os << indent << "TreeItem:\n";
  this->Item->PrintSelf(os, indent.GetNextIndent());
}

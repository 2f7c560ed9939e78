/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianViewCoverageFilter.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianViewCoverageFilter.h"

#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkGaussianViewCoverageFilter);

//------------------------------------------------------------------------------
vtkGaussianViewCoverageFilter::vtkGaussianViewCoverageFilter()
{
  this->SetScores("coverage");
}

//------------------------------------------------------------------------------
void vtkGaussianViewCoverageFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}

/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianGenealogyTraceFilter.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianGenealogyTraceFilter.h"

#include "vtkAbstractArray.h"
#include "vtkAlgorithm.h"
#include "vtkDataSetAttributes.h"
#include "vtkGaussianGenealogyLineage.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkTable.h"
#include "vtkTree.h"
#include "vtkVariant.h"

vtkStandardNewMacro(vtkGaussianGenealogyTraceFilter);

//------------------------------------------------------------------------------
vtkGaussianGenealogyTraceFilter::vtkGaussianGenealogyTraceFilter() = default;

//------------------------------------------------------------------------------
vtkGaussianGenealogyTraceFilter::~vtkGaussianGenealogyTraceFilter() = default;

//------------------------------------------------------------------------------
int vtkGaussianGenealogyTraceFilter::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkTree");
    return 1;
  }
  return 0;
}

//------------------------------------------------------------------------------
int vtkGaussianGenealogyTraceFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkTree* tree = vtkTree::GetData(inputVector[0]);
  vtkTable* output = vtkTable::GetData(outputVector);
  if (this->GaussianId < 0)
  {
    return 1; // nothing asked for yet
  }
  // Said here, naming this filter, rather than by the lineage object inside it.
  vtkAbstractArray* ids = tree ? tree->GetVertexData()->GetPedigreeIds() : nullptr;
  if (!ids || ids->LookupValue(vtkVariant(this->GaussianId)) < 0)
  {
    vtkErrorMacro("no trace of GaussianId " << this->GaussianId
                                            << ": it is not in the tree (or there is no tree)");
    return 0;
  }
  vtkNew<vtkGaussianGenealogyLineage> lineage;
  lineage->SetTree(tree);
  vtkNew<vtkTable> trace;
  if (!lineage->TraceToRoot(this->GaussianId, trace))
  {
    return 0; // the lineage object said why
  }
  output->ShallowCopy(trace);
  return 1;
}

//------------------------------------------------------------------------------
void vtkGaussianGenealogyTraceFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "GaussianId: " << this->GaussianId << "\n";
}

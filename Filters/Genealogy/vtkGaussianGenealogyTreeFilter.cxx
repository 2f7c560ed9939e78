/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianGenealogyTreeFilter.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianGenealogyTreeFilter.h"

#include "Vis4GSDataModel.h"
#include "vtkGaussianGenealogyAdapter.h"

#include "vtkDataArray.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkFieldData.h"
#include "vtkGaussianCompactTree.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkTable.h"
#include "vtkTimerLog.h"
#include "vtkTree.h"

#include <sstream>

vtkStandardNewMacro(vtkGaussianGenealogyTreeFilter);

//------------------------------------------------------------------------------
vtkGaussianGenealogyTreeFilter::vtkGaussianGenealogyTreeFilter()
{
  this->SetNumberOfOutputPorts(2);
}

//------------------------------------------------------------------------------
vtkGaussianGenealogyTreeFilter::~vtkGaussianGenealogyTreeFilter() = default;

//------------------------------------------------------------------------------
void vtkGaussianGenealogyTreeFilter::SetInitialIds(vtkIdTypeArray* ids)
{
  if (this->InitialIds != ids)
  {
    this->InitialIds = ids;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkIdTypeArray* vtkGaussianGenealogyTreeFilter::GetInitialIds()
{
  return this->InitialIds;
}

//------------------------------------------------------------------------------
vtkTable* vtkGaussianGenealogyTreeFilter::GetFamilyBands()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(1));
}

//------------------------------------------------------------------------------
int vtkGaussianGenealogyTreeFilter::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkTable");
    return 1;
  }
  return 0;
}

//------------------------------------------------------------------------------
int vtkGaussianGenealogyTreeFilter::FillOutputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkTree");
    return 1;
  }
  if (port == 1)
  {
    info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkTable");
    return 1;
  }
  return 0;
}

//------------------------------------------------------------------------------
vtkTypeBool vtkGaussianGenealogyTreeFilter::ProcessRequest(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA_OBJECT()))
  {
    return this->RequestDataObject(request, inputVector, outputVector);
  }
  return this->Superclass::ProcessRequest(request, inputVector, outputVector);
}

//------------------------------------------------------------------------------
int vtkGaussianGenealogyTreeFilter::RequestDataObject(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** vtkNotUsed(inputVector),
  vtkInformationVector* outputVector)
{
  vtkInformation* info = outputVector->GetInformationObject(0);
  vtkDataObject* current = info->Get(vtkDataObject::DATA_OBJECT());
  const bool isCompact = vtkGaussianCompactTree::SafeDownCast(current) != nullptr;
  if (!current || isCompact != this->CompactTree)
  {
    vtkSmartPointer<vtkTree> tree;
    if (this->CompactTree)
    {
      tree = vtkSmartPointer<vtkGaussianCompactTree>::New();
    }
    else
    {
      tree = vtkSmartPointer<vtkTree>::New();
    }
    info->Set(vtkDataObject::DATA_OBJECT(), tree);
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkGaussianGenealogyTreeFilter::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkTable* input = vtkTable::GetData(inputVector[0]);
  vtkTree* output = vtkTree::GetData(outputVector, 0);
  vtkTable* bands = vtkTable::GetData(outputVector, 1);
  this->Warnings.clear();
  this->GenealogySeconds = 0.0;
  this->TreeSeconds = 0.0;
  this->GenealogyCPUSeconds = 0.0;
  this->TreeCPUSeconds = 0.0;
  if (!input || !output || !bands)
  {
    vtkErrorMacro("missing input events table or outputs");
    return 0;
  }

  std::string error;
  vis4gs::EventTable copied; // only when the columns are not of the log's types
  vis4gs::EventColumns events;
  if (!vtkGaussianGenealogyAdapter::EventsFromTable(input, copied, events, error))
  {
    vtkErrorMacro("" << error);
    return 0;
  }

  // Initial Gaussians: InitialIds, NumberOfInitialGaussians, then the input's field data.
  vtkFieldData* fd = input->GetFieldData();
  vtkDataArray* ids = this->InitialIds;
  vtkIdType n0 = this->NumberOfInitialGaussians;
  if (!ids && n0 < 0 && fd)
  {
    ids = vtkDataArray::SafeDownCast(fd->GetAbstractArray(vis4gs::arrays::EventInitialIds));
    vtkDataArray* count =
      vtkDataArray::SafeDownCast(fd->GetAbstractArray(vis4gs::arrays::EventInitialCount));
    if (!ids && count && count->GetNumberOfTuples() > 0)
    {
      n0 = static_cast<vtkIdType>(count->GetComponent(0, 0));
    }
  }
  if (!ids && n0 < 0)
  {
    vtkErrorMacro("no initial Gaussians: set NumberOfInitialGaussians or InitialIds, or give the "
                  "events table an InitialIds or NumberOfInitialGaussians field-data array");
    return 0;
  }
  int last = this->LastIteration;
  if (last < 0 && fd)
  {
    vtkDataArray* a =
      vtkDataArray::SafeDownCast(fd->GetAbstractArray(vis4gs::arrays::EventLastIteration));
    if (a && a->GetNumberOfTuples() > 0)
    {
      last = static_cast<int>(a->GetComponent(0, 0));
    }
  }

  vis4gs::GenealogyOptions options;
  options.CoarsenInterval = this->CoarsenInterval;
  options.StrictEventOrder = this->StrictEventOrder;
  options.RepairUnknownParents = this->RepairUnknownParents;
  options.RepairDuplicateBirths = this->RepairDuplicateBirths;
  options.Alpha = this->Alpha;
  // The log's lineage breaks (field data of the reader's events port), when it has any.
  vis4gs::LineageBreakTable breaks;
  if (fd && fd->GetAbstractArray(vis4gs::arrays::EventBreakIteration))
  {
    if (!vtkGaussianGenealogyAdapter::BreaksFromFieldData(fd, breaks, error))
    {
      vtkErrorMacro("" << error);
      return 0;
    }
    options.Breaks = &breaks;
  }

  vtkNew<vtkTimerLog> timer;
  timer->StartTimer();
  double cpu = vtkGaussianGenealogyAdapter::ProcessCpuSeconds();
  vis4gs::Genealogy genealogy;
  try
  {
    if (ids)
    {
      std::vector<std::int64_t> initial(static_cast<std::size_t>(ids->GetNumberOfTuples()));
      for (vtkIdType i = 0; i < ids->GetNumberOfTuples(); ++i)
      {
        initial[i] = static_cast<std::int64_t>(ids->GetComponent(i, 0));
      }
      genealogy = vis4gs::Genealogy::Build(initial, events, last, options);
    }
    else
    {
      genealogy = vis4gs::Genealogy::Build(n0, events, last, options);
    }
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("" << e.what());
    return 0;
  }
  timer->StopTimer();
  this->GenealogySeconds = timer->GetElapsedTime();
  this->GenealogyCPUSeconds = vtkGaussianGenealogyAdapter::ProcessCpuSeconds() - cpu;
  copied = vis4gs::EventTable();

  std::ostringstream warnings;
  for (const std::string& w : genealogy.GetWarnings())
  {
    warnings << w << "\n";
  }
  this->Warnings = warnings.str();
  if (!this->Warnings.empty())
  {
    vtkWarningMacro("" << this->Warnings);
  }

  timer->StartTimer();
  cpu = vtkGaussianGenealogyAdapter::ProcessCpuSeconds();
  if (!vtkGaussianGenealogyAdapter::FillTree(
        genealogy, output, bands, this->NaiveConstruction, error, this->ValidateStructure))
  {
    vtkErrorMacro("" << error);
    return 0;
  }
  timer->StopTimer();
  this->TreeSeconds = timer->GetElapsedTime();
  this->TreeCPUSeconds = vtkGaussianGenealogyAdapter::ProcessCpuSeconds() - cpu;
  return 1;
}

//------------------------------------------------------------------------------
void vtkGaussianGenealogyTreeFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfInitialGaussians: " << this->NumberOfInitialGaussians << "\n";
  os << indent << "InitialIds: " << this->InitialIds.Get() << "\n";
  os << indent << "LastIteration: " << this->LastIteration << "\n";
  os << indent << "CoarsenInterval: " << this->CoarsenInterval << "\n";
  os << indent << "StrictEventOrder: " << this->StrictEventOrder << "\n";
  os << indent << "RepairUnknownParents: " << this->RepairUnknownParents << "\n";
  os << indent << "RepairDuplicateBirths: " << this->RepairDuplicateBirths << "\n";
  os << indent << "Alpha: " << this->Alpha << "\n";
  os << indent << "CompactTree: " << this->CompactTree << "\n";
  os << indent << "NaiveConstruction: " << this->NaiveConstruction << "\n";
  os << indent << "ValidateStructure: " << this->ValidateStructure << "\n";
  os << indent << "GenealogySeconds: " << this->GenealogySeconds << "\n";
  os << indent << "TreeSeconds: " << this->TreeSeconds << "\n";
  os << indent << "GenealogyCPUSeconds: " << this->GenealogyCPUSeconds << "\n";
  os << indent << "TreeCPUSeconds: " << this->TreeCPUSeconds << "\n";
  os << indent << "Warnings: " << this->Warnings << "\n";
}

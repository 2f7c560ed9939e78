/*=========================================================================

  Program:   Vis4GS
  Module:    Vis4GSRequestedPort.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "Vis4GSRequestedPort.h"

#include "vtkDemandDrivenPipeline.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"

namespace vis4gs
{
int RequestedOutputPort(vtkInformation* request)
{
  return request && request->Has(vtkDemandDrivenPipeline::FROM_OUTPUT_PORT())
    ? request->Get(vtkDemandDrivenPipeline::FROM_OUTPUT_PORT())
    : -1;
}

void MarkOtherPortsNotGenerated(vtkInformation* request, vtkInformationVector* outInfo)
{
  const int port = RequestedOutputPort(request);
  for (int i = 0; i < outInfo->GetNumberOfInformationObjects(); ++i)
  {
    vtkInformation* info = outInfo->GetInformationObject(i);
    if (port >= 0 && i != port)
    {
      info->Set(vtkDemandDrivenPipeline::DATA_NOT_GENERATED(), 1);
    }
    else
    {
      info->Remove(vtkDemandDrivenPipeline::DATA_NOT_GENERATED());
    }
  }
}
} // namespace vis4gs

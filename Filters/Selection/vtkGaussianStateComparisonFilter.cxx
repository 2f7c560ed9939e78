/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianStateComparisonFilter.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianStateComparisonFilter.h"

#include "StateComparison.h"
#include "Vis4GSDataModel.h"

#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkUnsignedCharArray.h"

#include <exception>
#include <string>

vtkStandardNewMacro(vtkGaussianStateComparisonFilter);

//------------------------------------------------------------------------------
vtkGaussianStateComparisonFilter::vtkGaussianStateComparisonFilter()
{
  this->SetNumberOfInputPorts(2);
}

//------------------------------------------------------------------------------
int vtkGaussianStateComparisonFilter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

//------------------------------------------------------------------------------
int vtkGaussianStateComparisonFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkTable* output = vtkTable::GetData(outputVector);
  vis4gs::GaussianCloud clouds[2];
  for (int port = 0; port < 2; ++port)
  {
    std::string error;
    if (!vis4gs::PolyDataToGaussianCloud(
          vtkPolyData::GetData(inputVector[port]), clouds[port], &error))
    {
      vtkErrorMacro("State " << (port == 0 ? "A" : "B") << " is not a Gaussian scene: " << error);
      return 0;
    }
  }
  vis4gs::StateThresholds thresholds;
  thresholds.Move = this->MoveThreshold;
  thresholds.Opacity = this->OpacityThreshold;
  thresholds.Scale = this->ScaleThreshold;
  vis4gs::StateComparison c;
  try
  {
    c = vis4gs::CompareStates(clouds[0], clouds[1], thresholds);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  const vtkIdType rows = static_cast<vtkIdType>(c.Gaussians.size());
  vtkNew<vtkIdTypeArray> ids;
  ids->SetName(vis4gs::arrays::GaussianId);
  vtkNew<vtkUnsignedCharArray> change;
  change->SetName("Change");
  vtkNew<vtkStringArray> status;
  status->SetName("Status");
  vtkNew<vtkDoubleArray> move, opacity, scale;
  move->SetName("Move");
  opacity->SetName("OpacityChange");
  scale->SetName("ScaleChange");
  ids->SetNumberOfTuples(rows);
  change->SetNumberOfTuples(rows);
  status->SetNumberOfValues(rows);
  move->SetNumberOfTuples(rows);
  opacity->SetNumberOfTuples(rows);
  scale->SetNumberOfTuples(rows);
  for (vtkIdType r = 0; r < rows; ++r)
  {
    const vis4gs::GaussianStateDifference& d = c.Gaussians[static_cast<std::size_t>(r)];
    ids->SetValue(r, static_cast<vtkIdType>(d.Id));
    change->SetValue(r, d.Change);
    status->SetValue(r, vis4gs::StateChangeName(d.Change));
    move->SetValue(r, d.Move);
    opacity->SetValue(r, d.Opacity);
    scale->SetValue(r, d.Scale);
  }
  output->AddColumn(ids);
  output->AddColumn(change);
  output->AddColumn(status);
  output->AddColumn(move);
  output->AddColumn(opacity);
  output->AddColumn(scale);
  this->NumberMatched = static_cast<vtkIdType>(c.Matched);
  this->NumberBorn = static_cast<vtkIdType>(c.Born);
  this->NumberDied = static_cast<vtkIdType>(c.Died);
  this->NumberMoved = static_cast<vtkIdType>(c.Moved);
  this->NumberOpacityChanged = static_cast<vtkIdType>(c.OpacityChanged);
  this->NumberScaleChanged = static_cast<vtkIdType>(c.ScaleChanged);
  this->NumberUnchanged = static_cast<vtkIdType>(c.Unchanged);
  return 1;
}

//------------------------------------------------------------------------------
void vtkGaussianStateComparisonFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MoveThreshold: " << this->MoveThreshold << "\n";
  os << indent << "OpacityThreshold: " << this->OpacityThreshold << "\n";
  os << indent << "ScaleThreshold: " << this->ScaleThreshold << "\n";
  os << indent << "NumberMatched: " << this->NumberMatched << "\n";
  os << indent << "NumberBorn: " << this->NumberBorn << "\n";
  os << indent << "NumberDied: " << this->NumberDied << "\n";
  os << indent << "NumberMoved: " << this->NumberMoved << "\n";
  os << indent << "NumberOpacityChanged: " << this->NumberOpacityChanged << "\n";
  os << indent << "NumberScaleChanged: " << this->NumberScaleChanged << "\n";
  os << indent << "NumberUnchanged: " << this->NumberUnchanged << "\n";
}

/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianNeedleShapeFilter.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianNeedleShapeFilter.h"

#include "NeedleShape.h"
#include "Vis4GSDataModel.h"

#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkGaussianNeedleShapeFilter);

//------------------------------------------------------------------------------
int vtkGaussianNeedleShapeFilter::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  output->ShallowCopy(input);
  this->NumberOfInvalidGaussians = 0;

  vtkDataArray* logScale = input->GetPointData()->GetArray(vis4gs::arrays::LogScale);
  if (!logScale || logScale->GetNumberOfComponents() != 3)
  {
    vtkErrorMacro("The input has no 3-component '" << vis4gs::arrays::LogScale
                                                   << "' point array; is it a Gaussian scene?");
    return 0;
  }
  const vtkIdType n = logScale->GetNumberOfTuples();
  std::vector<float> converted;
  const float* values = nullptr;
  if (auto* f = vtkFloatArray::SafeDownCast(logScale))
  {
    values = f->GetPointer(0);
  }
  else
  {
    converted.resize(static_cast<std::size_t>(3 * n));
    for (vtkIdType i = 0; i < 3 * n; ++i)
    {
      converted[static_cast<std::size_t>(i)] =
        static_cast<float>(logScale->GetComponent(i / 3, i % 3));
    }
    values = converted.data();
  }

  vtkNew<vtkDoubleArray> shape;
  shape->SetName(vis4gs::arrays::NeedleShape);
  shape->SetNumberOfTuples(n);
  vtkNew<vtkDoubleArray> rank;
  rank->SetName("EffectiveRank");
  if (this->ComputeEffectiveRank)
  {
    rank->SetNumberOfTuples(n);
  }
  vis4gs::ComputeNeedleShapes(values,
    static_cast<std::size_t>(n),
    shape->GetPointer(0),
    this->ComputeEffectiveRank ? rank->GetPointer(0) : nullptr);
  for (vtkIdType i = 0; i < n; ++i)
  {
    this->NumberOfInvalidGaussians += std::isnan(shape->GetValue(i)) ? 1 : 0;
  }
  if (this->NumberOfInvalidGaussians > 0)
  {
    vtkWarningMacro(<< this->NumberOfInvalidGaussians << " of " << n
                    << " Gaussians have NaN log-scales; their NeedleShape is NaN.");
  }
  output->GetPointData()->AddArray(shape);
  if (this->ComputeEffectiveRank)
  {
    output->GetPointData()->AddArray(rank);
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkGaussianNeedleShapeFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ComputeEffectiveRank: " << (this->ComputeEffectiveRank ? "On" : "Off") << "\n";
  os << indent << "NumberOfInvalidGaussians: " << this->NumberOfInvalidGaussians << "\n";
}

/*=========================================================================

  Program:   Vis4GS
  Module:    Vis4GSViewInput.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "Vis4GSViewInput.h"

#include "vtkAbstractArray.h"
#include "vtkAlgorithm.h"
#include "vtkAlgorithmOutput.h"
#include "vtkDataObject.h"
#include "vtkFieldData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"

#include <cstdint>

namespace
{
void StampArray(std::vector<vtkMTimeType>& stamp, vtkAbstractArray* array)
{
  stamp.push_back(static_cast<vtkMTimeType>(reinterpret_cast<std::uintptr_t>(array)));
  stamp.push_back(array ? array->GetMTime() : 0);
}

/// What the view draws from @p data, as identities and MTimes: new arrays, changed values
/// (Modified()) and other element counts change it; a shallow copy of the same data does not.
std::vector<vtkMTimeType> ContentStamp(vtkDataObject* data)
{
  std::vector<vtkMTimeType> stamp;
  if (!data)
  {
    return stamp;
  }
  for (int kind = 0; kind < vtkDataObject::NUMBER_OF_ATTRIBUTE_TYPES; ++kind)
  {
    stamp.push_back(static_cast<vtkMTimeType>(data->GetNumberOfElements(kind)));
    vtkFieldData* fields = data->GetAttributesAsFieldData(kind);
    for (int a = 0; fields && a < fields->GetNumberOfArrays(); ++a)
    {
      StampArray(stamp, fields->GetAbstractArray(a));
    }
  }
  vtkFieldData* fields = data->GetFieldData();
  for (int a = 0; fields && a < fields->GetNumberOfArrays(); ++a)
  {
    StampArray(stamp, fields->GetAbstractArray(a));
  }
  if (auto* points = vtkPointSet::SafeDownCast(data))
  {
    StampArray(stamp, points->GetPoints() ? points->GetPoints()->GetData() : nullptr);
  }
  return stamp;
}
}

//------------------------------------------------------------------------------
void Vis4GSViewInput::SetConnection(vtkAlgorithmOutput* output)
{
  vtkAlgorithm* producer = output ? output->GetProducer() : nullptr;
  if (producer && producer == this->Producer && output->GetIndex() == this->Port)
  {
    return; // (the next Pull() still takes what changed there)
  }
  this->Producer = output ? output->GetProducer() : nullptr;
  this->Port = output ? output->GetIndex() : 0;
  this->Pulled = false;
  this->Stamp.clear();
}

//------------------------------------------------------------------------------
vtkAlgorithmOutput* Vis4GSViewInput::GetConnection() const
{
  return this->Producer ? this->Producer->GetOutputPort(this->Port) : nullptr;
}

//------------------------------------------------------------------------------
bool Vis4GSViewInput::Pull(vtkSmartPointer<vtkDataObject>& copy)
{
  if (!this->Producer || !this->Producer->Update(this->Port, nullptr))
  {
    return false;
  }
  vtkDataObject* output = this->Producer->GetOutputDataObject(this->Port);
  std::vector<vtkMTimeType> stamp = ContentStamp(output);
  if (this->Pulled && stamp == this->Stamp)
  {
    return false;
  }
  this->Pulled = true;
  this->Stamp = std::move(stamp);
  copy = nullptr;
  if (output)
  {
    copy.TakeReference(output->NewInstance());
    copy->ShallowCopy(output);
  }
  return true;
}

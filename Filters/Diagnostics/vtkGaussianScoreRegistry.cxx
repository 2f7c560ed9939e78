/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianScoreRegistry.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianScoreRegistry.h"

#include "ScoreRegistry.h"

#include "vtkObjectFactory.h"

#include <string>

vtkStandardNewMacro(vtkGaussianScoreRegistry);

namespace
{
const vis4gs::ScoreDefinition* At(int index)
{
  const auto& all = vis4gs::ScoreDefinitions();
  return index >= 0 && index < static_cast<int>(all.size()) ? &all[index] : nullptr;
}

const vis4gs::ScoreParameter* ParameterAt(int index, int parameter)
{
  const vis4gs::ScoreDefinition* d = At(index);
  return d && parameter >= 0 && parameter < static_cast<int>(d->Parameters.size())
    ? &d->Parameters[parameter]
    : nullptr;
}
}

//------------------------------------------------------------------------------
int vtkGaussianScoreRegistry::GetNumberOfScores()
{
  return static_cast<int>(vis4gs::ScoreDefinitions().size());
}

//------------------------------------------------------------------------------
int vtkGaussianScoreRegistry::FindScore(const char* name)
{
  const vis4gs::ScoreDefinition* d = vis4gs::FindScore(name ? name : "");
  return d ? static_cast<int>(d - vis4gs::ScoreDefinitions().data()) : -1;
}

//------------------------------------------------------------------------------
const char* vtkGaussianScoreRegistry::GetName(int index)
{
  return At(index) ? At(index)->Name : nullptr;
}

//------------------------------------------------------------------------------
const char* vtkGaussianScoreRegistry::GetArrayName(int index)
{
  return At(index) ? At(index)->ArrayName : nullptr;
}

//------------------------------------------------------------------------------
const char* vtkGaussianScoreRegistry::GetRuleName(int index)
{
  return At(index) ? At(index)->RuleName : nullptr;
}

//------------------------------------------------------------------------------
const char* vtkGaussianScoreRegistry::GetTitle(int index)
{
  return At(index) ? At(index)->Title : nullptr;
}

//------------------------------------------------------------------------------
const char* vtkGaussianScoreRegistry::GetDocumentation(int index)
{
  return At(index) ? At(index)->Doc : nullptr;
}

//------------------------------------------------------------------------------
int vtkGaussianScoreRegistry::GetSuspiciousEnd(int index)
{
  if (!At(index))
  {
    return 0;
  }
  switch (At(index)->Suspicious)
  {
    case vis4gs::SuspiciousEnd::Low:
      return -1;
    case vis4gs::SuspiciousEnd::High:
      return 1;
    default:
      return 0;
  }
}

//------------------------------------------------------------------------------
bool vtkGaussianScoreRegistry::GetNeedsCameras(int index)
{
  return At(index) && (At(index)->Needs & vis4gs::NeedsCameras) != 0;
}

//------------------------------------------------------------------------------
bool vtkGaussianScoreRegistry::GetNeedsImages(int index)
{
  return At(index) && (At(index)->Needs & vis4gs::NeedsImages) != 0;
}

//------------------------------------------------------------------------------
bool vtkGaussianScoreRegistry::GetDefaultOn(int index)
{
  return At(index) && At(index)->DefaultOn;
}

//------------------------------------------------------------------------------
const char* vtkGaussianScoreRegistry::GetDefaultScores()
{
  static const std::string list = vis4gs::DefaultScoreList();
  return list.c_str();
}

//------------------------------------------------------------------------------
int vtkGaussianScoreRegistry::GetNumberOfParameters(int index)
{
  return At(index) ? static_cast<int>(At(index)->Parameters.size()) : 0;
}

//------------------------------------------------------------------------------
const char* vtkGaussianScoreRegistry::GetParameterName(int index, int parameter)
{
  const vis4gs::ScoreParameter* p = ParameterAt(index, parameter);
  return p ? p->Name : nullptr;
}

//------------------------------------------------------------------------------
const char* vtkGaussianScoreRegistry::GetParameterType(int index, int parameter)
{
  const vis4gs::ScoreParameter* p = ParameterAt(index, parameter);
  return p ? p->Type : nullptr;
}

//------------------------------------------------------------------------------
const char* vtkGaussianScoreRegistry::GetParameterDefault(int index, int parameter)
{
  const vis4gs::ScoreParameter* p = ParameterAt(index, parameter);
  return p ? p->Default : nullptr;
}

//------------------------------------------------------------------------------
double vtkGaussianScoreRegistry::GetParameterMinimum(int index, int parameter)
{
  const vis4gs::ScoreParameter* p = ParameterAt(index, parameter);
  return p ? p->Minimum : 0.0;
}

//------------------------------------------------------------------------------
double vtkGaussianScoreRegistry::GetParameterMaximum(int index, int parameter)
{
  const vis4gs::ScoreParameter* p = ParameterAt(index, parameter);
  return p ? p->Maximum : 0.0;
}

//------------------------------------------------------------------------------
const char* vtkGaussianScoreRegistry::GetParameterDocumentation(int index, int parameter)
{
  const vis4gs::ScoreParameter* p = ParameterAt(index, parameter);
  return p ? p->Doc : nullptr;
}

//------------------------------------------------------------------------------
void vtkGaussianScoreRegistry::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Scores (" << GetNumberOfScores() << "):\n";
  for (int k = 0; k < GetNumberOfScores(); ++k)
  {
    os << indent.GetNextIndent() << GetName(k) << " -> " << GetArrayName(k)
       << " (suspicious: " << (GetSuspiciousEnd(k) < 0 ? "low" : "high")
       << (GetNeedsImages(k)       ? ", needs images"
              : GetNeedsCameras(k) ? ", needs cameras"
                                   : "")
       << (GetDefaultOn(k) ? ", default on" : "") << ")\n";
  }
}

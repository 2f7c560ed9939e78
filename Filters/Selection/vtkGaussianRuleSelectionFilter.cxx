/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianRuleSelectionFilter.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianRuleSelectionFilter.h"

#include "ScoreRegistry.h"
#include "SelectionRule.h"
#include "Vis4GSDataModel.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <exception>
#include <vector>

vtkStandardNewMacro(vtkGaussianRuleSelectionFilter);
vtkCxxSetObjectMacro(vtkGaussianRuleSelectionFilter, CurrentIds, vtkIdTypeArray);

namespace
{
// A score array of the input as doubles, or empty when the input lacks it.
bool ReadScore(vtkPointData* pd, const char* name, std::vector<double>& values)
{
  vtkDataArray* array = pd->GetArray(name);
  if (!array || array->GetNumberOfComponents() != 1)
  {
    return false;
  }
  values.resize(static_cast<std::size_t>(array->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    values[static_cast<std::size_t>(i)] = array->GetTuple1(i);
  }
  return true;
}
}

//------------------------------------------------------------------------------
vtkGaussianRuleSelectionFilter::vtkGaussianRuleSelectionFilter()
{
  this->SelectedIds = vtkIdTypeArray::New();
  this->SelectedIds->SetName(vis4gs::arrays::GaussianId);
}

//------------------------------------------------------------------------------
vtkGaussianRuleSelectionFilter::~vtkGaussianRuleSelectionFilter()
{
  this->SetCurrentIds(nullptr);
  this->SelectedIds->Delete();
}

//------------------------------------------------------------------------------
int vtkGaussianRuleSelectionFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  this->SelectedIds->Reset();
  this->CanonicalRule.clear();
  this->LastRuleError.clear();
  vis4gs::GaussianCloud cloud;
  std::string error;
  if (!vis4gs::PolyDataToGaussianCloud(input, cloud, &error))
  {
    vtkErrorMacro("The input is not a Gaussian scene: " << error);
    return 0;
  }
  std::vector<std::uint8_t> mask;
  try
  {
    const vis4gs::SelectionRule rule = vis4gs::SelectionRule::Parse(this->Rule);
    vtkPointData* pd = input->GetPointData();
    // Only the scores the rule reads are converted.
    const std::vector<std::string> read = rule.ScoresRead();
    std::vector<std::vector<double>> values(read.size());
    vis4gs::SelectionRuleInputs inputs;
    inputs.Cloud = &cloud;
    for (std::size_t k = 0; k < read.size(); ++k)
    {
      if (ReadScore(pd, vis4gs::FindScore(read[k])->ArrayName, values[k]))
      {
        inputs.Scores[read[k]] = &values[k];
      }
    }
    inputs.ViewsUsed = static_cast<std::size_t>(this->NumberOfViews);
    mask = rule.Evaluate(inputs);
    this->CanonicalRule = rule.ToString();
  }
  catch (const std::exception& e)
  {
    this->LastRuleError = e.what();
    vtkErrorMacro(<< e.what());
    return 0;
  }

  // Combine with the current selection in GaussianId values.
  std::vector<std::int64_t> ruleIds;
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    if (mask[i])
    {
      ruleIds.push_back(cloud.GetId(i));
    }
  }
  std::vector<std::int64_t> current;
  if (this->CurrentIds)
  {
    for (vtkIdType i = 0; i < this->CurrentIds->GetNumberOfTuples(); ++i)
    {
      current.push_back(this->CurrentIds->GetValue(i));
    }
  }
  vis4gs::NormalizeSelection(current);
  static const vis4gs::SelectionModifier modifiers[] = { vis4gs::SelectionModifier::Replace,
    vis4gs::SelectionModifier::Add,
    vis4gs::SelectionModifier::Subtract,
    vis4gs::SelectionModifier::Intersect };
  const std::vector<std::int64_t> selected =
    vis4gs::CombineSelection(current, ruleIds, modifiers[this->CombineMode]);
  for (std::int64_t id : selected)
  {
    this->SelectedIds->InsertNextValue(static_cast<vtkIdType>(id));
  }
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    mask[i] = std::binary_search(selected.begin(), selected.end(), cloud.GetId(i)) ? 1 : 0;
  }

  if (this->OutputMode == Mark)
  {
    output->ShallowCopy(input);
    vtkNew<vtkUnsignedCharArray> marks;
    marks->SetName("RuleSelected");
    marks->SetNumberOfTuples(static_cast<vtkIdType>(cloud.Count));
    std::copy(mask.begin(), mask.end(), marks->GetPointer(0));
    output->GetPointData()->AddArray(marks);
  }
  else
  {
    const std::uint8_t keep = this->OutputMode == Extract ? 1 : 0;
    const vtkIdType kept = static_cast<vtkIdType>(std::count(mask.begin(), mask.end(), keep));
    vtkNew<vtkPoints> points;
    points->SetDataType(input->GetPoints()->GetDataType());
    points->SetNumberOfPoints(kept);
    vtkPointData* in = input->GetPointData();
    vtkPointData* out = output->GetPointData();
    out->CopyAllOn();
    out->CopyAllocate(in, kept);
    vtkIdType j = 0;
    for (vtkIdType i = 0; i < input->GetNumberOfPoints(); ++i)
    {
      if (mask[static_cast<std::size_t>(i)] == keep)
      {
        points->SetPoint(j, input->GetPoint(i));
        out->CopyData(in, i, j++);
      }
    }
    out->Squeeze();
    output->SetPoints(points);
    output->GetFieldData()->ShallowCopy(input->GetFieldData());
  }
  vtkNew<vtkStringArray> ruleText;
  ruleText->SetName("SelectionRule");
  ruleText->InsertNextValue(this->CanonicalRule);
  output->GetFieldData()->AddArray(ruleText);
  return 1;
}

//------------------------------------------------------------------------------
void vtkGaussianRuleSelectionFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Rule: " << this->Rule << "\n";
  os << indent << "NumberOfViews: " << this->NumberOfViews << "\n";
  os << indent << "OutputMode: " << this->OutputMode << "\n";
  os << indent << "CombineMode: " << this->CombineMode << "\n";
  os << indent << "CurrentIds: " << this->CurrentIds << "\n";
  os << indent << "SelectedIds: " << this->SelectedIds->GetNumberOfTuples() << " ids\n";
  os << indent << "CanonicalRule: " << this->CanonicalRule << "\n";
  os << indent << "LastRuleError: " << this->LastRuleError << "\n";
}

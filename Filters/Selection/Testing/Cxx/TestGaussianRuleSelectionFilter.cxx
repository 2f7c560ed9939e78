/*=========================================================================

  Program:   Vis4GS
  Module:    TestGaussianRuleSelectionFilter.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
// vtkGaussianRuleSelectionFilter on a hand-built scene of six Gaussians whose answers are
// derived by hand: marking, removing and extracting, combining with a current selection, the
// canonical rule in the field data, and a bad rule reported with its token and no output.
#include "vtkGaussianRuleSelectionFilter.h"

#include "GaussianCloud.h"
#include "Vis4GSDataModel.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace
{
int failures = 0;
void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++failures;
  }
}

std::vector<vtkIdType> Ids(vtkIdTypeArray* a)
{
  std::vector<vtkIdType> v;
  for (vtkIdType i = 0; a && i < a->GetNumberOfTuples(); ++i)
  {
    v.push_back(a->GetValue(i));
  }
  return v;
}

std::vector<vtkIdType> PedigreeIds(vtkPolyData* pd)
{
  return Ids(vtkIdTypeArray::SafeDownCast(pd->GetPointData()->GetPedigreeIds()));
}
}

int TestGaussianRuleSelectionFilter(int, char*[])
{
  // Ids 10..15; opacities 0.9 0.2 0.6 0.99 0.5 0.7; coverage 1 0.1 0.05 0.05 0.5 0
  const double opacity[6] = { 0.9, 0.2, 0.6, 0.99, 0.5, 0.7 };
  const double coverage[6] = { 1.0, 0.1, 0.05, 0.05, 0.5, 0.0 };
  vis4gs::GaussianCloud cloud;
  cloud.Resize(6, 0);
  cloud.Ids = { 10, 11, 12, 13, 14, 15 };
  for (int i = 0; i < 6; ++i)
  {
    cloud.OpacityLogits[i] = static_cast<float>(std::log(opacity[i] / (1 - opacity[i])));
    for (int k = 0; k < 3; ++k)
    {
      cloud.Positions[3 * i + k] = static_cast<float>(i);
      cloud.LogScales[3 * i + k] = -2.0f;
    }
    cloud.Rotations[4 * i] = 1;
  }
  vtkNew<vtkPolyData> scene;
  vis4gs::GaussianCloudToPolyData(cloud, scene);
  vtkNew<vtkDoubleArray> cov;
  cov->SetName(vis4gs::arrays::ViewCoverage);
  for (double c : coverage)
  {
    cov->InsertNextValue(c);
  }
  scene->GetPointData()->AddArray(cov);

  vtkNew<vtkGaussianRuleSelectionFilter> filter;
  filter->SetInputData(scene);
  filter->SetRule("Coverage <= 0.1 AND opacity >= .5");
  filter->Update();
  vtkPolyData* out = filter->GetOutput();
  Check(Ids(filter->GetSelectedIds()) == std::vector<vtkIdType>{ 12, 13, 15 }, "rule ids");
  Check(std::string(filter->GetCanonicalRule()) == "coverage<=0.1 and opacity>=0.5", "canonical");
  auto* marks = vtkUnsignedCharArray::SafeDownCast(out->GetPointData()->GetArray("RuleSelected"));
  Check(marks && marks->GetNumberOfTuples() == 6 && marks->GetValue(2) == 1 &&
      marks->GetValue(0) == 0 && marks->GetValue(5) == 1,
    "RuleSelected marks");
  auto* text = vtkStringArray::SafeDownCast(out->GetFieldData()->GetAbstractArray("SelectionRule"));
  Check(text && text->GetValue(0) == "coverage<=0.1 and opacity>=0.5", "rule in field data");

  // Remove: the cleaned scene keeps every array of the others, in order.
  filter->SetOutputMode(vtkGaussianRuleSelectionFilter::Remove);
  filter->Update();
  out = filter->GetOutput();
  Check(out->GetNumberOfPoints() == 3, "removed");
  Check(PedigreeIds(out) == std::vector<vtkIdType>{ 10, 11, 14 }, "kept pedigree ids");
  vtkDataArray* keptCoverage = out->GetPointData()->GetArray(vis4gs::arrays::ViewCoverage);
  Check(keptCoverage && keptCoverage->GetTuple1(2) == 0.5, "scores kept");
  Check(out->GetPoint(1)[0] == 1.0, "positions kept");
  filter->SetOutputMode(vtkGaussianRuleSelectionFilter::Extract);
  filter->Update();
  Check(PedigreeIds(filter->GetOutput()) == std::vector<vtkIdType>{ 12, 13, 15 }, "extracted");

  // Combining with a current selection.
  vtkNew<vtkIdTypeArray> current;
  current->InsertNextValue(10);
  current->InsertNextValue(12);
  filter->SetCurrentIds(current);
  const std::pair<int, std::vector<vtkIdType>> combos[] = {
    { vtkGaussianRuleSelectionFilter::Add, { 10, 12, 13, 15 } },
    { vtkGaussianRuleSelectionFilter::Subtract, { 10 } },
    { vtkGaussianRuleSelectionFilter::Intersect, { 12 } },
    { vtkGaussianRuleSelectionFilter::Replace, { 12, 13, 15 } },
  };
  for (const auto& [mode, expected] : combos)
  {
    filter->SetCombineMode(mode);
    filter->Update();
    Check(Ids(filter->GetSelectedIds()) == expected, "combine mode " + std::to_string(mode));
  }

  // "views" needs the number of views; then 0.05 * 20 = 1 view.
  filter->SetCurrentIds(nullptr);
  filter->SetOutputMode(vtkGaussianRuleSelectionFilter::Mark);
  filter->SetNumberOfViews(20);
  filter->SetRule("views<=1");
  filter->Update();
  Check(Ids(filter->GetSelectedIds()) == std::vector<vtkIdType>{ 12, 13, 15 }, "views");

  // Errors: named rule and token, nothing out.
  vtkObject::GlobalWarningDisplayOff();
  filter->SetRule("coverage<=x");
  filter->Update();
  const std::string message = filter->GetLastRuleError();
  Check(message.find("'coverage<=x'") != std::string::npos &&
      message.find("found 'x' (column 11)") != std::string::npos,
    "error message: " + message);
  Check(filter->GetOutput()->GetNumberOfPoints() == 0, "no output after an error");
  filter->SetRule("blur top 5%");
  filter->Update();
  Check(std::string(filter->GetLastRuleError()).find("'blur' needs the diagnostic scores") !=
      std::string::npos,
    "missing score");
  vtkObject::GlobalWarningDisplayOn();

  vtkNew<vtkGaussianRuleSelectionFilter> printed;
  printed->Print(std::cout);
  return failures == 0 ? 0 : 1;
}

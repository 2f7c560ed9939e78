/*=========================================================================

  Program:   Vis4GS
  Module:    TestGaussianStateComparisonFilter.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
// vtkGaussianStateComparisonFilter on two hand-built states whose answers are derived by hand:
// a death, a birth, a move of 5, an opacity change, the table's rows and columns, the counts,
// a threshold, and an input that is no Gaussian scene.
#include "vtkGaussianStateComparisonFilter.h"

#include "GaussianCloud.h"
#include "Vis4GSDataModel.h"

#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
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

void Scene(const std::vector<std::int64_t>& ids, vtkPolyData* out)
{
  vis4gs::GaussianCloud cloud;
  cloud.Resize(ids.size(), 0);
  cloud.Ids = ids;
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      cloud.Positions[3 * i + k] = static_cast<float>(ids[i]);
      cloud.LogScales[3 * i + k] = -2.0f;
    }
    cloud.Rotations[4 * i] = 1;
  }
  vis4gs::GaussianCloudToPolyData(cloud, out);
}
}

int TestGaussianStateComparisonFilter(int, char*[])
{
  vtkNew<vtkPolyData> a, b;
  Scene({ 1, 2, 3, 4 }, a);
  Scene({ 2, 3, 4, 7 }, b); // 1 died, 7 born
  // id 3 moves by (3, 4, 0); id 4's opacity logit 0 -> log(3): opacity 0.5 -> 0.75.
  b->GetPoints()->SetPoint(1, 6, 7, 3);
  vtkDataArray* logits = b->GetPointData()->GetArray(vis4gs::arrays::OpacityLogit);
  logits->SetTuple1(2, std::log(3.0));

  vtkNew<vtkGaussianStateComparisonFilter> filter;
  filter->SetInputData(0, a);
  filter->SetInputData(1, b);
  filter->Update();
  vtkTable* t = filter->GetOutput();
  Check(t->GetNumberOfRows() == 5, "one row per id of either state");
  auto* ids = vtkIdTypeArray::SafeDownCast(t->GetColumnByName(vis4gs::arrays::GaussianId));
  auto* status = vtkStringArray::SafeDownCast(t->GetColumnByName("Status"));
  auto* change = vtkUnsignedCharArray::SafeDownCast(t->GetColumnByName("Change"));
  auto* move = vtkDoubleArray::SafeDownCast(t->GetColumnByName("Move"));
  auto* opacity = vtkDoubleArray::SafeDownCast(t->GetColumnByName("OpacityChange"));
  Check(ids && status && change && move && opacity && t->GetColumnByName("ScaleChange"), "columns");
  if (ids && status && change && move && opacity)
  {
    const char* expected[] = { "died", "unchanged", "moved", "opacity", "born" };
    const vtkIdType expectedIds[] = { 1, 2, 3, 4, 7 };
    for (vtkIdType r = 0; r < 5 && r < t->GetNumberOfRows(); ++r)
    {
      Check(ids->GetValue(r) == expectedIds[r], "row " + std::to_string(r) + " id");
      Check(status->GetValue(r) == expected[r], "row " + std::to_string(r) + " status");
    }
    Check(change->GetValue(0) == 16 && change->GetValue(4) == 8, "died and born flags");
    Check(std::isnan(move->GetValue(0)) && std::abs(move->GetValue(2) - 5.0) < 1e-12, "move");
    Check(std::abs(opacity->GetValue(3) - 0.25) < 1e-7, "opacity change 0.5 -> 0.75");
  }
  Check(filter->GetNumberMatched() == 3 && filter->GetNumberBorn() == 1 &&
      filter->GetNumberDied() == 1 && filter->GetNumberMoved() == 1 &&
      filter->GetNumberOpacityChanged() == 1 && filter->GetNumberScaleChanged() == 0 &&
      filter->GetNumberUnchanged() == 1,
    "counts");

  // A move of exactly 5 is not beyond a threshold of 5 (strict).
  filter->SetMoveThreshold(5);
  filter->Update();
  Check(filter->GetNumberMoved() == 0 && filter->GetNumberUnchanged() == 2, "strict threshold");

  // An input that is no Gaussian scene is an error, not a crash.
  vtkNew<vtkPolyData> empty;
  filter->SetInputData(1, empty);
  vtkObject::GlobalWarningDisplayOff();
  filter->Update();
  vtkObject::GlobalWarningDisplayOn();
  Check(filter->GetOutput()->GetNumberOfRows() == 0, "no rows for a bad input");

  filter->Print(std::cout);
  return failures == 0 ? 0 : 1;
}

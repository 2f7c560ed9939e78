/*=========================================================================

  Program:   Vis4GS
  Module:    TestGaussianNeedleShapeFilter.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianNeedleShapeFilter.h"

#include "Vis4GSDataModel.h"

#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <cmath>
#include <iostream>

int TestGaussianNeedleShapeFilter(int, char*[])
{
  vis4gs::GaussianCloud cloud;
  cloud.Resize(4, 0);
  // sphere, needle (scale ratio e^8 on one axis), disk, NaN
  cloud.LogScales = { -1, -1, -1, 0, -8, -8, 2, 2, -9, std::nanf(""), 0, 0 };
  vtkNew<vtkPolyData> scene;
  vis4gs::GaussianCloudToPolyData(cloud, scene);

  vtkNew<vtkGaussianNeedleShapeFilter> filter;
  filter->SetInputData(scene);
  filter->ComputeEffectiveRankOn();
  filter->Update();
  vtkPolyData* out = filter->GetOutput();
  vtkDataArray* s = out->GetPointData()->GetArray("NeedleShape");
  vtkDataArray* r = out->GetPointData()->GetArray("EffectiveRank");
  int failures = 0;
  auto check = [&](bool ok, const char* what)
  {
    if (!ok)
    {
      std::cerr << "FAILED: " << what << "\n";
      ++failures;
    }
  };
  check(s && r, "arrays added");
  if (!s || !r)
  {
    return EXIT_FAILURE;
  }
  // Needle: q = (1, e^-16, e^-16)/(1 + 2e^-16); hand-computed s to 1e-6.
  const double e = std::exp(-16.0), z = 1 + 2 * e;
  const double h = -(1 / z) * std::log(1 / z) - 2 * (e / z) * std::log(e / z);
  check(s->GetTuple1(0) == 0.0, "sphere has s = 0");
  check(std::abs(s->GetTuple1(1) - (3 - std::exp(h)) / 2) < 1e-12, "needle matches hand value");
  check(std::abs(s->GetTuple1(2) - 0.5) < 1e-6, "disk is near 1/2");
  check(std::isnan(s->GetTuple1(3)), "NaN log-scale gives NaN");
  check(filter->GetNumberOfInvalidGaussians() == 1, "one invalid Gaussian counted");
  check(std::abs(r->GetTuple1(2) - (3 - 2 * s->GetTuple1(2))) < 1e-12, "rank = 3 - 2s");
  check(out->GetPointData()->GetArray("LogScale") != nullptr, "input arrays passed through");

  // Without the option no EffectiveRank array is computed.
  filter->ComputeEffectiveRankOff();
  filter->Update();
  check(filter->GetOutput()->GetPointData()->GetArray("EffectiveRank") == nullptr,
    "EffectiveRank left out when not asked for");
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

// SPDX-License-Identifier: BSD-3-Clause
// `vis4gs demo`: the embedded default scene end to end. Until the embedded training log of
// the built-in trainer exists (issue 7), it runs the diagnosis steps that are built on a
// small deterministic scene: the Gaussian data model and the needle-shape score.
#include "Vis4GSCommand.h"

#include "Vis4GSDataModel.h"
#include "vtkGaussianNeedleShapeFilter.h"

#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numeric>
#include <random>
#include <stdexcept>

namespace
{
void Define(Vis4GSArguments& args)
{
  args.AddOption("output", "DIR", "vis4gs-demo", "Folder the demo writes its results to.");
  args.AddOption("top", "K", "10", "Number of most suspicious Gaussians listed per score.");
}

// A small scene with a known mix of shapes: spheres, disks and needles around a torus.
vis4gs::GaussianCloud MakeScene()
{
  vis4gs::GaussianCloud cloud;
  const std::size_t n = 2000;
  cloud.Resize(n, 0);
  std::mt19937 rng(7);
  std::normal_distribution<float> noise(0.0f, 0.05f);
  for (std::size_t i = 0; i < n; ++i)
  {
    const float t = 6.2831853f * static_cast<float>(i) / n;
    cloud.Positions[3 * i + 0] = std::cos(t) + noise(rng);
    cloud.Positions[3 * i + 1] = std::sin(t) + noise(rng);
    cloud.Positions[3 * i + 2] = noise(rng);
    const float base = -3.5f + noise(rng);
    const int kind = static_cast<int>(i % 20);
    cloud.LogScales[3 * i + 0] = base + (kind == 0 ? 3.0f : 0.0f);
    cloud.LogScales[3 * i + 1] = base + (kind == 1 ? 2.0f : 0.0f);
    cloud.LogScales[3 * i + 2] = base - (kind == 1 ? 2.0f : 0.0f);
    cloud.Rotations[4 * i] = 1.0f;
    cloud.OpacityLogits[i] = 2.0f;
  }
  return cloud;
}

int Run(const Vis4GSArguments& args)
{
  const std::filesystem::path output = args.Get("output");
  const int top = args.GetInt("top");
  std::filesystem::create_directories(output);

  vtkNew<vtkPolyData> scene;
  vis4gs::GaussianCloudToPolyData(MakeScene(), scene);
  vtkNew<vtkGaussianNeedleShapeFilter> needle;
  needle->SetInputData(scene);
  needle->ComputeEffectiveRankOn();
  needle->Update();
  vtkDataArray* s = needle->GetOutput()->GetPointData()->GetArray("NeedleShape");
  vtkDataArray* ids = needle->GetOutput()->GetPointData()->GetArray("GaussianId");
  if (!s || !ids)
  {
    throw std::runtime_error("the needle-shape filter produced no NeedleShape array");
  }
  std::vector<vtkIdType> order(static_cast<std::size_t>(s->GetNumberOfTuples()));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(),
    order.end(),
    [&](vtkIdType a, vtkIdType b) { return s->GetTuple1(a) > s->GetTuple1(b); });

  const auto csv = output / "needle-shape.csv";
  std::ofstream out(csv);
  out << "GaussianId,NeedleShape\n";
  for (vtkIdType i : order)
  {
    out << static_cast<long long>(ids->GetTuple1(i)) << "," << s->GetTuple1(i) << "\n";
  }
  if (!out)
  {
    throw std::runtime_error(csv.string() + ": could not be written");
  }
  std::cout << "vis4gs demo: " << scene->GetNumberOfPoints() << " Gaussians; most needle-like:\n";
  for (int k = 0; k < top && k < static_cast<int>(order.size()); ++k)
  {
    std::cout << "  Gaussian " << static_cast<long long>(ids->GetTuple1(order[k]))
              << "  NeedleShape " << s->GetTuple1(order[k]) << "\n";
  }
  std::cout << "vis4gs demo: wrote " << csv.string() << "\n";
  return 0;
}
}

VIS4GS_REGISTER_COMMAND("demo",
  "Run the diagnosis end to end on the embedded default scene.",
  Define,
  Run)

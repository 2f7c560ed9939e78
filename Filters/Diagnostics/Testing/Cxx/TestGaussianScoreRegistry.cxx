/*=========================================================================

  Program:   Vis4GS
  Module:    TestGaussianScoreRegistry.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
// vtkGaussianScoreRegistry lists Core's registry, and vtkGaussianArtifactScoreFilter computes
// every registered score by its name alone (SetScores, EnableScore, the ParaView array
// selection): exactly the arrays asked for, each equal to a direct Core computation with
// that score's request switch; unknown names are errors that leave the selection unchanged;
// the old Compute* switches are the first four scores.
#include "vtkGaussianArtifactScoreFilter.h"
#include "vtkGaussianScoreRegistry.h"

#include "ArtifactScores.h"
#include "ImageIO.h"
#include "ScoreRegistry.h"
#include "Vis4GSDataModel.h"

#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkTable.h"

#include "Vis4GSTestCheck.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

namespace
{
vis4gs::testing::CheckCounter Check;

bool SameValues(vtkDataArray* a, const std::vector<double>& v)
{
  if (!a || a->GetNumberOfTuples() != static_cast<vtkIdType>(v.size()))
  {
    return false;
  }
  for (std::size_t i = 0; i < v.size(); ++i)
  {
    const double x = a->GetTuple1(static_cast<vtkIdType>(i));
    if (!(x == v[i] || (std::isnan(x) && std::isnan(v[i]))))
    {
      return false;
    }
  }
  return true;
}
}

int TestGaussianScoreRegistry(int, char*[])
{
  // The wrapped list is Core's.
  const auto& registry = vis4gs::ScoreDefinitions();
  Check(vtkGaussianScoreRegistry::GetNumberOfScores() == static_cast<int>(registry.size()),
    "as many scores as Core's registry");
  for (int k = 0; k < vtkGaussianScoreRegistry::GetNumberOfScores(); ++k)
  {
    const vis4gs::ScoreDefinition& d = registry[static_cast<std::size_t>(k)];
    Check(std::string(vtkGaussianScoreRegistry::GetName(k)) == d.Name &&
        std::string(vtkGaussianScoreRegistry::GetArrayName(k)) == d.ArrayName &&
        std::string(vtkGaussianScoreRegistry::GetRuleName(k)) == d.RuleName,
      "names as in Core");
    Check(vtkGaussianScoreRegistry::FindScore(d.Name) == k &&
        vtkGaussianScoreRegistry::FindScore(d.ArrayName) == k,
      "FindScore by short and array name");
    Check(vtkGaussianScoreRegistry::GetSuspiciousEnd(k) ==
        (d.Suspicious == vis4gs::SuspiciousEnd::Low ? -1 : 1),
      "suspicious end");
    Check(
      vtkGaussianScoreRegistry::GetNumberOfParameters(k) == static_cast<int>(d.Parameters.size()),
      "parameters");
  }
  Check(vtkGaussianScoreRegistry::FindScore("nope") == -1, "unknown score: -1");
  Check(vtkGaussianScoreRegistry::GetName(-1) == nullptr &&
      vtkGaussianScoreRegistry::GetName(static_cast<int>(registry.size())) == nullptr,
    "out of range: nullptr");
  // The data model's spelling of the first scores is the registry's.
  Check(std::string(vis4gs::FindScore("coverage")->ArrayName) == vis4gs::arrays::ViewCoverage &&
      std::string(vis4gs::FindScore("blur")->ArrayName) == vis4gs::arrays::BlurScore &&
      std::string(vis4gs::FindScore("needle")->ArrayName) == vis4gs::arrays::NeedleScore &&
      std::string(vis4gs::FindScore("shape")->ArrayName) == vis4gs::arrays::NeedleShape,
    "data model names");

  // A scene of 12 Gaussians, two views, one with an image.
  vis4gs::GaussianCloud cloud;
  cloud.Resize(12, 0);
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      cloud.Positions[3 * i + k] =
        k == 2 ? 4.0f + 0.1f * static_cast<float>(i) : 0.08f * static_cast<float>(i) - 0.4f;
      cloud.LogScales[3 * i + k] = -2.0f - 0.3f * static_cast<float>((i + k) % 3);
      cloud.SH[3 * i + k] = 0.1f * static_cast<float>(k);
    }
    cloud.Rotations[4 * i] = 1;
    cloud.OpacityLogits[i] = i == 5 ? -1000.0f : 1.0f; // Gaussian 5: opacity 0
  }
  std::vector<vis4gs::Camera> cameras(2);
  for (std::size_t v = 0; v < 2; ++v)
  {
    vis4gs::Camera& c = cameras[v];
    c.Name = "view" + std::to_string(v);
    c.Width = 48;
    c.Height = 32;
    c.Fx = c.Fy = 40;
    c.Cx = 24;
    c.Cy = 16;
    c.WorldToCamera = { 1, 0, 0, 0.2 * static_cast<double>(v), 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  }
  const auto folder = std::filesystem::temp_directory_path() /
    ("vis4gs-score-registry-" + std::to_string(static_cast<long long>(::getpid())));
  std::filesystem::create_directories(folder);
  vis4gs::Image grey;
  grey.Width = 48;
  grey.Height = 32;
  grey.Pixels.assign(48 * 32 * 3, 0.3f);
  vis4gs::WritePng((folder / "view0.png").string(), grey);
  cameras[0].ImagePath = (folder / "view0.png").string();
  cameras[1].ImagePath = (folder / "missing.png").string();
  vtkNew<vtkPolyData> scene;
  vis4gs::GaussianCloudToPolyData(cloud, scene);
  vtkNew<vtkTable> table;
  vis4gs::CamerasToTable(cameras, table);
  auto provider = [](std::size_t, const vis4gs::Camera& c, vis4gs::Image& image)
  {
    if (!std::filesystem::exists(c.ImagePath))
    {
      return false;
    }
    image = vis4gs::LoadTrainingImage(c);
    return true;
  };

  vtkNew<vtkGaussianArtifactScoreFilter> filter;
  filter->SetInputData(scene);
  filter->SetCamerasData(table);
  Check(filter->GetScores() == vis4gs::DefaultScoreList(), "default: the registry's defaults");
  for (const vis4gs::ScoreDefinition& d : registry)
  {
    Check(filter->SetScores(d.Name), "SetScores accepts every registered name");
    Check(filter->GetScores() == d.Name, "GetScores gives the one score back");
    filter->Update();
    vtkPointData* pd = filter->GetOutput()->GetPointData();
    vis4gs::ScoreSettings settings;
    settings.Request = vis4gs::ScoreRequest{ false, false, false, false, false, false };
    settings.Request.*(d.Request) = true;
    const vis4gs::GaussianScores expected = vis4gs::ComputeGaussianScores(cloud,
      cameras,
      settings,
      (d.Needs & vis4gs::NeedsImages) ? vis4gs::TrainingImageProvider(provider)
                                      : vis4gs::TrainingImageProvider());
    Check(SameValues(pd->GetArray(d.ArrayName), expected.*(d.Values)),
      (std::string(d.ArrayName) + " equals Core's with its request switch").c_str());
    for (const vis4gs::ScoreDefinition& other : registry)
    {
      Check(&other == &d || pd->GetArray(other.ArrayName) == nullptr,
        (std::string(other.ArrayName) + " not computed when only " + d.Name + " is asked").c_str());
    }
    Check((pd->GetArray(vis4gs::arrays::NoVisibleView) != nullptr) ==
        ((d.Needs & vis4gs::NeedsCameras) != 0),
      "NoVisibleView with the scores that need cameras");
  }
  // The render-cost pair: the cost of the opacity-0 Gaussian is paid for nothing.
  filter->SetScores("render-cost, cost-per-contribution");
  filter->Update();
  vtkPointData* pd = filter->GetOutput()->GetPointData();
  vtkDataArray* cost = pd->GetArray("RenderCost");
  vtkDataArray* ratio = pd->GetArray("CostPerContribution");
  Check(cost && ratio, "both render-cost arrays");
  if (cost && ratio)
  {
    Check(cost->GetTuple1(5) > 0 && std::isinf(ratio->GetTuple1(5)),
      "opacity 0: a cost, +inf per contribution");
    Check(cost->GetTuple1(0) > 0 && std::isfinite(ratio->GetTuple1(0)) && ratio->GetTuple1(0) > 1,
      "a visible Gaussian: finite cost per contribution, above 1 (alpha*T <= 1 per pixel)");
  }

  // Unknown names: an error, the selection unchanged.
  filter->SetScores("coverage");
  filter->GlobalWarningDisplayOff();
  Check(!filter->SetScores("coverage,bluur"), "unknown name refused");
  Check(!filter->EnableScore("bluur"), "EnableScore refuses an unknown name");
  filter->GlobalWarningDisplayOn();
  Check(filter->GetScores() == "coverage", "selection unchanged after an unknown name");

  // The ParaView array selection and the compatibility switches.
  Check(filter->GetNumberOfScoreArrays() == static_cast<int>(registry.size()), "array count");
  filter->SetScoreArrayStatus("RenderCost", 1);
  Check(filter->GetScoreArrayStatus("RenderCost") == 1 && filter->IsScoreEnabled("render-cost"),
    "SetScoreArrayStatus by array name");
  filter->ComputeNeedleShapeOn();
  filter->SetComputeViewCoverage(false);
  Check(filter->GetScores() == "shape,render-cost", "Compute* switches are registry scores");
  Check(filter->GetComputeNeedleShape() && !filter->GetComputeViewCoverage(), "Compute* getters");

  std::filesystem::remove_all(folder);
  return Check.ExitCode();
}

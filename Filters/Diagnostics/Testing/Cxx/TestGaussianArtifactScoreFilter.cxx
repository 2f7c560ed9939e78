/*=========================================================================

  Program:   Vis4GS
  Module:    TestGaussianArtifactScoreFilter.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
// vtkGaussianArtifactScoreFilter and vtkGaussianViewCoverageFilter against a direct Core
// computation: same values, only the requested arrays, images from the camera table's Image
// column or an ImageDirectory, a view whose image is missing skipped with a warning, flags,
// progress events, and clear errors.
#include "vtkGaussianArtifactScoreFilter.h"
#include "vtkGaussianViewCoverageFilter.h"

#include "ArtifactScores.h"
#include "ImageIO.h"
#include "Vis4GSDataModel.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTable.h"

#include "Vis4GSTestCheck.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <iostream>

namespace
{
vis4gs::testing::CheckCounter Check;

vis4gs::Camera MakeCamera(const std::string& name, double cz, bool flipped)
{
  vis4gs::Camera c;
  c.Name = name;
  c.Width = 48;
  c.Height = 32;
  c.Fx = c.Fy = 40;
  c.Cx = 24;
  c.Cy = 16;
  const double s = flipped ? -1 : 1;
  c.WorldToCamera = { s, 0, 0, 0, 0, 1, 0, 0, 0, 0, s, -s * cz, 0, 0, 0, 1 };
  return c;
}

bool SameArray(vtkDataArray* a, const std::vector<double>& v)
{
  if (!a || a->GetNumberOfTuples() != static_cast<vtkIdType>(v.size()))
  {
    return false;
  }
  for (std::size_t i = 0; i < v.size(); ++i)
  {
    if (a->GetTuple1(static_cast<vtkIdType>(i)) != v[i])
    {
      return false;
    }
  }
  return true;
}

struct Counter
{
  int Progress = 0;
  int Errors = 0;
  int Warnings = 0;
};
void OnEvent(vtkObject*, unsigned long event, void* clientData, void*)
{
  auto* c = static_cast<Counter*>(clientData);
  c->Progress += event == vtkCommand::ProgressEvent ? 1 : 0;
  c->Errors += event == vtkCommand::ErrorEvent ? 1 : 0;
  c->Warnings += event == vtkCommand::WarningEvent ? 1 : 0;
}
}

int TestGaussianArtifactScoreFilter(int, char*[])
{
  // Scene: two Gaussians in front of both cameras, one behind camera 0 and 1.
  vis4gs::GaussianCloud cloud;
  cloud.Resize(3, 0);
  const float pos[3][3] = { { 0, 0, 5 }, { 0.4f, 0.2f, 4 }, { 50, 0, -3 } };
  for (std::size_t i = 0; i < 3; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      cloud.Positions[3 * i + k] = pos[i][k];
      cloud.LogScales[3 * i + k] = k == 0 ? -1.5f : -2.5f;
      cloud.SH[3 * i + k] = 0.2f * k;
    }
    cloud.Rotations[4 * i] = 1;
    cloud.OpacityLogits[i] = 1.5f;
  }
  // Camera 1 sits at z = 10 looking back; the third Gaussian is behind camera 0 and far off
  // screen in camera 1.
  std::vector<vis4gs::Camera> cameras{ MakeCamera("view0", 0, false),
    MakeCamera("view1", 10, true) };
  const auto folder = std::filesystem::temp_directory_path() /
    ("vis4gs-score-filter-" + std::to_string(static_cast<long long>(::getpid())));
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

  // Core reference with the same images.
  auto provider = [](std::size_t, const vis4gs::Camera& c, vis4gs::Image& image)
  {
    if (!std::filesystem::exists(c.ImagePath))
    {
      return false;
    }
    image = vis4gs::LoadTrainingImage(c);
    return true;
  };
  const vis4gs::GaussianScores expected =
    vis4gs::ComputeGaussianScores(cloud, cameras, {}, provider);

  Counter counter;
  vtkNew<vtkCallbackCommand> callback;
  callback->SetCallback(OnEvent);
  callback->SetClientData(&counter);

  vtkNew<vtkGaussianArtifactScoreFilter> filter;
  filter->SetInputData(scene);
  filter->SetCamerasData(table);
  filter->AddObserver(vtkCommand::ProgressEvent, callback);
  filter->AddObserver(vtkCommand::WarningEvent, callback);
  filter->AddObserver(vtkCommand::ErrorEvent, callback);
  filter->Update();
  vtkPointData* pd = filter->GetOutput()->GetPointData();
  Check(SameArray(pd->GetArray("ViewCoverage"), expected.ViewCoverage), "ViewCoverage == Core");
  Check(SameArray(pd->GetArray("BlurScore"), expected.BlurScore), "BlurScore == Core");
  Check(SameArray(pd->GetArray("NeedleScore"), expected.NeedleScore), "NeedleScore == Core");
  Check(SameArray(pd->GetArray("NeedleShape"), expected.NeedleShape), "NeedleShape == Core");
  Check(expected.BlurScore[0] > 0 && expected.BlurScore[1] > 0, "non-trivial blur scores");
  vtkDataArray* flags = pd->GetArray("NoVisibleView");
  Check(flags && flags->GetTuple1(0) == 0 && flags->GetTuple1(2) == 3, "NoVisibleView flags");
  Check(filter->GetNumberOfViewsUsed() == 2, "two views used");
  Check(filter->GetNumberOfViewsWithoutImage() == 1, "one view without image");
  Check(filter->GetNumberOfFlaggedGaussians() == 1, "one flagged Gaussian");
  Check(counter.Warnings >= 1, "warning for the view without image");
  Check(counter.Progress >= 3, "progress per view");
  Check(counter.Errors == 0, "no errors");
  Check(std::abs(pd->GetArray("ViewCoverage")->GetTuple1(0) - 1.0) < 1e-15, "coverage 1");

  // Progressive stages: stage 1 is the Core scores of every 8th view at 1/4 of the resolution,
  // and the output says which stage it holds.
  vtkStringArray* label = vtkStringArray::SafeDownCast(
    filter->GetOutput()->GetFieldData()->GetAbstractArray("ScoreStage"));
  Check(label && label->GetNumberOfValues() == 1 && label->GetValue(0) == "stage 2 of 2, exact",
    "the exact stage's label");
  {
    vis4gs::ScoreSettings first;
    first.ViewStride = 8;
    first.LossResolution = 4;
    first.CoverageResolution = 4;
    const vis4gs::GaussianScores approximate =
      vis4gs::ComputeGaussianScores(cloud, cameras, first, provider);
    filter->SetProgressiveStage(1);
    filter->Update();
    pd = filter->GetOutput()->GetPointData();
    Check(SameArray(pd->GetArray("ViewCoverage"), approximate.ViewCoverage) &&
        SameArray(pd->GetArray("BlurScore"), approximate.BlurScore) &&
        SameArray(pd->GetArray("NeedleScore"), approximate.NeedleScore),
      "stage 1 == Core at every 8th view, 1/4 resolution");
    Check(filter->GetNumberOfViewsUsed() == 1, "stage 1 uses 1 of the 2 views");
    label = vtkStringArray::SafeDownCast(
      filter->GetOutput()->GetFieldData()->GetAbstractArray("ScoreStage"));
    Check(label &&
        label->GetValue(0) ==
          "stage 1 of 2, approximate: every 8th training view, loss maps at 1/4, coverage at "
          "1/4 resolution",
      ("stage 1's label: " + (label ? label->GetValue(0) : std::string("none"))).c_str());
    // Asked settings compose: stride 2 and loss at 1/4 give every 16th view, 1/8 (the most).
    filter->SetViewStride(2);
    filter->SetLossResolution(4);
    Check(filter->GetStageSettings() ==
        "every 16th training view, loss maps at 1/8, coverage at 1/4 resolution",
      ("stage 1 of approximate settings: " + filter->GetStageSettings()).c_str());
    filter->SetProgressiveStage(0);
    Check(filter->GetStageDescription() ==
        "stage 2 of 2, approximate as asked: every 2nd training view, loss maps at 1/4, "
        "coverage at full resolution",
      ("approximate settings say so: " + filter->GetStageDescription()).c_str());
    filter->SetViewStride(1);
    filter->SetLossResolution(1);
  }
  // A stop (here at the first progress event, as a GUI's Stop button would from another
  // thread) leaves no score array and says "stopped"; the next execution is complete again.
  {
    vtkNew<vtkCallbackCommand> stop;
    stop->SetCallback([](vtkObject* caller, unsigned long, void*, void*)
      { static_cast<vtkGaussianArtifactScoreFilter*>(caller)->StopExecution(); });
    const unsigned long tag = filter->AddObserver(vtkCommand::ProgressEvent, stop);
    filter->Modified();
    filter->Update();
    pd = filter->GetOutput()->GetPointData();
    label = vtkStringArray::SafeDownCast(
      filter->GetOutput()->GetFieldData()->GetAbstractArray("ScoreStage"));
    Check(filter->GetStopped() && !pd->GetArray("ViewCoverage") && !pd->GetArray("BlurScore") &&
        !pd->GetArray("NoVisibleView") && label && label->GetValue(0) == "stopped",
      "a stopped execution has no scores and says so");
    filter->RemoveObserver(tag);
    filter->Modified();
    filter->Update();
    Check(!filter->GetStopped() &&
        SameArray(filter->GetOutput()->GetPointData()->GetArray("BlurScore"), expected.BlurScore),
      "the execution after a stop is complete");
  }

  // ImageDirectory: images found by camera name (view0.png), view1 has none.
  filter->SetImageDirectory(folder.string().c_str());
  filter->Update();
  Check(SameArray(filter->GetOutput()->GetPointData()->GetArray("BlurScore"), expected.BlurScore),
    "ImageDirectory gives the same images");
  filter->SetImageDirectory("");

  // Only what is requested.
  filter->ComputeBlurScoreOff();
  filter->ComputeNeedleScoreOff();
  filter->ComputeViewCoverageOff();
  filter->SetInputData(1, nullptr);
  filter->Update();
  pd = filter->GetOutput()->GetPointData();
  Check(pd->GetArray("NeedleShape") && !pd->GetArray("BlurScore") &&
      !pd->GetArray("ViewCoverage") && !pd->GetArray("NoVisibleView"),
    "needle shape alone, without cameras");
  // Coverage without cameras is an error, reported (not a crash).
  filter->ComputeViewCoverageOn();
  const int errorsBefore = counter.Errors;
  filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, callback); // it reports it too
  filter->Update();
  Check(counter.Errors > errorsBefore, "error without the camera table");
  Check(!filter->GetOutput()->GetPointData()->GetArray("ViewCoverage"), "no array on error");

  // The coverage filter: ViewCoverage and flags only, same values, no image needed.
  vtkNew<vtkGaussianViewCoverageFilter> coverage;
  coverage->SetInputData(scene);
  coverage->SetCamerasData(table);
  coverage->Update();
  pd = coverage->GetOutput()->GetPointData();
  Check(SameArray(pd->GetArray("ViewCoverage"), expected.ViewCoverage), "coverage filter values");
  Check(!pd->GetArray("BlurScore") && !pd->GetArray("NeedleShape"), "coverage filter only");
  Check(pd->GetArray("NoVisibleView") && pd->GetArray("NoVisibleView")->GetTuple1(2) == 1,
    "coverage flag only bit 1");
  Check(pd->GetArray("LogScale") != nullptr, "input arrays passed through");

  std::filesystem::remove_all(folder);
  return Check.ExitCode();
}

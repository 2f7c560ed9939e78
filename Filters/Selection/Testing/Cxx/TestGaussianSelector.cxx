// SPDX-License-Identifier: BSD-3-Clause
// vtkGaussianSelector against Core run independently on the same camera: Single, Brush,
// Frame, Ray; the modifiers as set algebra; the published PEDIGREEIDS selection and link.
#include "SplatTestHelpers.h"

#include "GaussianOctree.h"
#include "ScreenSelection.h"
#include "Vis4GSDataModel.h"
#include "vtkGaussianCameraUtilities.h"
#include "vtkGaussianSelector.h"
#include "vtkGaussianSplatMapper.h"

#include "vtkActor.h"
#include "vtkAnnotationLink.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkTestErrorObserver.h"

#include <algorithm>
#include <cstdio>
#include <iterator>
#include <set>
#include <vector>

namespace
{
int fail = 0;
void Check(bool ok, const char* what)
{
  if (!ok)
  {
    std::printf("FAILED: %s\n", what);
    fail = 1;
  }
}

std::vector<vtkIdType> Ids(vtkIdTypeArray* a)
{
  std::vector<vtkIdType> v;
  for (vtkIdType k = 0; a && k < a->GetNumberOfTuples(); ++k)
  {
    v.push_back(a->GetValue(k));
  }
  return v;
}

int changes = 0;
void OnChange(vtkObject*, unsigned long, void*, void*)
{
  ++changes;
}
}

int TestGaussianSelector(int, char*[])
{
  vis4gs::GaussianCloud cloud = splattest::LoadScene(false);
  cloud.Ids.resize(cloud.Count);
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    cloud.Ids[i] = 1000 + 3 * static_cast<std::int64_t>(i); // ids differ from indices
  }
  const int W = 200, H = 150;
  const vis4gs::Camera cam = splattest::FrameScene(cloud, W, H, 0.7);
  vtkNew<vtkPolyData> scene;
  vis4gs::GaussianCloudToPolyData(cloud, scene);
  vtkNew<vtkGaussianSplatMapper> mapper;
  mapper->SetInputData(scene);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> ren;
  ren->AddActor(actor);
  vtkNew<vtkRenderWindow> win;
  win->SetOffScreenRendering(1);
  win->SetMultiSamples(0);
  win->SetSize(W, H);
  win->AddRenderer(ren);
  vtkGaussianCameraUtilities::ApplyCamera(cam, ren->GetActiveCamera());
  win->Render();

  vtkNew<vtkGaussianSelector> sel;
  vtkNew<vtkTest::ErrorObserver> errors;
  sel->AddObserver(vtkCommand::ErrorEvent, errors);
  Check(sel->SelectSingle(10, 10) == -1 && errors->GetError(), "no scene gives -1 and an error");
  errors->Clear();
  sel->SetScene(scene);
  sel->SetRenderer(ren);
  vtkNew<vtkAnnotationLink> link;
  vtkNew<vtkCallbackCommand> cb;
  cb->SetCallback(OnChange);
  link->AddObserver(vtkCommand::AnnotationChangedEvent, cb);
  sel->SetAnnotationLink(link);
  sel->SetNumberOfThreads(2);

  // Core on the same camera, independently.
  const auto view = vis4gs::PrepareSelectionView(cloud, cam, 2);
  auto toIds = [&cloud](const std::vector<std::uint32_t>& idx)
  {
    std::vector<vtkIdType> v;
    for (auto i : idx)
    {
      v.push_back(cloud.Ids[i]);
    }
    std::sort(v.begin(), v.end());
    return v;
  };

  // Single at a few display positions (y up): raster row = H - 1 - y.
  int singles = 0;
  for (int k = 0; k < 6; ++k)
  {
    const int x = 40 + 25 * k, y = 30 + 15 * k;
    const vtkIdType n = sel->SelectSingle(x, y);
    const std::int64_t g = vis4gs::SelectSingle(view, x, H - 1 - y);
    const std::vector<vtkIdType> expected =
      g >= 0 ? std::vector<vtkIdType>{ cloud.Ids[g] } : std::vector<vtkIdType>{};
    Check(Ids(sel->GetSelectedIds()) == expected, "Single equals Core's Single");
    Check(n == static_cast<vtkIdType>(expected.size()), "Single returns the count");
    singles += g >= 0 ? 1 : 0;
  }
  Check(singles >= 3, "Single picks Gaussians on the donut");

  // The published selection.
  vtkSelection* s = sel->GetSelection();
  Check(s->GetNumberOfNodes() == 1 &&
      s->GetNode(0)->GetContentType() == vtkSelectionNode::PEDIGREEIDS &&
      s->GetNode(0)->GetFieldType() == vtkSelectionNode::POINT,
    "PEDIGREEIDS on POINT");
  Check(link->GetCurrentSelection() != nullptr && changes >= 6, "the link is updated");

  // Frame (visible) and with occluded.
  sel->SetModifier(vtkGaussianSelector::REPLACE);
  const vtkIdType nf = sel->SelectFrame(60, 40, 140, 110);
  const auto frame = Ids(sel->GetSelectedIds());
  vis4gs::FrameOptions fo;
  fo.Threads = 2;
  Check(frame == toIds(vis4gs::SelectFrame(view, 60, H - 1 - 40, 140, H - 1 - 110, fo)),
    "Frame equals Core's Frame");
  sel->IncludeOccludedOn();
  sel->SelectFrame(60, 40, 140, 110);
  const auto frameAll = Ids(sel->GetSelectedIds());
  sel->IncludeOccludedOff();
  Check(std::includes(frameAll.begin(), frameAll.end(), frame.begin(), frame.end()) &&
      frameAll.size() > frame.size() && nf > 10,
    "occluded frame is a strict superset");
  std::printf("frame: %zu visible, %zu with occluded\n", frame.size(), frameAll.size());

  // Brush stroke.
  vtkNew<vtkPoints> stroke;
  stroke->InsertNextPoint(50, 75, 0);
  stroke->InsertNextPoint(150, 80, 0);
  sel->SetBrushRadius(4);
  sel->SelectBrush(stroke);
  const auto brush = Ids(sel->GetSelectedIds());
  const auto pixels =
    vis4gs::BrushPixels({ { 50.0, H - 1 - 75.0 }, { 150.0, H - 1 - 80.0 } }, 4.0, W, H);
  Check(brush == toIds(vis4gs::SelectBrush(view, pixels, 0.01, 2)), "Brush equals Core's Brush");
  Check(!brush.empty(), "Brush selects something");

  // Ray through the centre, against the brute force on the same pixel ray.
  sel->SelectRay(100, 75);
  const auto rayHits = Ids(sel->GetRayHitIds());
  const auto bf =
    vis4gs::IntersectRayBruteForce(cloud, vis4gs::PixelRay(cam, 100, H - 1 - 75, 3.0));
  std::vector<vtkIdType> bfIds;
  for (const auto& h : bf)
  {
    bfIds.push_back(cloud.Ids[h.Gaussian]);
  }
  Check(rayHits == bfIds, "Ray hits equal the brute force, in depth order");
  Check(!rayHits.empty(), "the central ray hits the donut");
  std::printf("ray: %zu hits; single/frame/brush latency %.2f ms (prepare %.2f ms)\n",
    rayHits.size(),
    sel->GetLastSelectionTime(),
    sel->GetLastPrepareTime());

  // Modifiers as set algebra.
  sel->SetModifier(vtkGaussianSelector::REPLACE);
  sel->SelectFrame(60, 40, 140, 110);
  Check(Ids(sel->GetSelectedIds()) == frame,
    "the second visible frame (view maxima cached) equals the first (full replay)");
  sel->SetModifier(vtkGaussianSelector::ADD);
  sel->SelectBrush(stroke);
  std::vector<vtkIdType> expected;
  std::set_union(
    frame.begin(), frame.end(), brush.begin(), brush.end(), std::back_inserter(expected));
  Check(Ids(sel->GetSelectedIds()) == expected, "ADD is the union");
  sel->SetModifier(vtkGaussianSelector::SUBTRACT);
  sel->SelectRay(100, 75);
  std::vector<vtkIdType> ray = rayHits;
  std::sort(ray.begin(), ray.end());
  std::vector<vtkIdType> expected2;
  std::set_difference(
    expected.begin(), expected.end(), ray.begin(), ray.end(), std::back_inserter(expected2));
  Check(Ids(sel->GetSelectedIds()) == expected2, "SUBTRACT is the difference");
  sel->ClearSelection();
  Check(sel->GetSelectedIds()->GetNumberOfTuples() == 0, "cleared");

  // A camera move invalidates the cached projection.
  ren->GetActiveCamera()->Azimuth(40);
  win->Render();
  sel->SetModifier(vtkGaussianSelector::REPLACE);
  sel->SelectFrame(60, 40, 140, 110);
  Check(sel->GetLastPrepareTime() > 0 && Ids(sel->GetSelectedIds()) != frame,
    "a new camera gives a new projection");
  Check(!errors->GetError(), "no unexpected errors");
  return fail;
}

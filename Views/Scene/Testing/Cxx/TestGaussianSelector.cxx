// SPDX-License-Identifier: BSD-3-Clause
// vtkGaussianSelector against Core run independently on the same camera: Single, Brush,
// Frame, Ray; the modifiers as set algebra; the published PEDIGREEIDS selection and link.
#include "SplatTestHelpers.h"
#include "Vis4GSTestData.h" // VIS4GS_SHARED_DATA_OR_SKIP

#include "GaussianOctree.h"
#include "ScreenSelection.h"
#include "Vis4GSDataModel.h"
#include "vtkGaussianCameraUtilities.h"
#include "vtkGaussianSelectionHub.h"
#include "vtkGaussianSelector.h"
#include "vtkGaussianSplatMapper.h"

#include "vtkActor.h"
#include "vtkAnnotationLink.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkTestErrorObserver.h"

#include "Vis4GSTestCheck.h"

#include <algorithm>
#include <cstdio>
#include <iterator>
#include <set>
#include <vector>

namespace
{
vis4gs::testing::CheckCounter Check;

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
  VIS4GS_SHARED_DATA_OR_SKIP();
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

  // Ray through the centre: the footprints covering the pixel, as Core finds them, in depth
  // order with alpha and alpha*T; Single's pick there is one of them.
  sel->SelectRay(100, 75);
  const auto rayHits = Ids(sel->GetRayHitIds());
  const auto coreRay = vis4gs::SelectRay(view, 100, H - 1 - 75);
  std::vector<vtkIdType> coreRayIds;
  bool sameValues =
    sel->GetRayHitWeights()->GetNumberOfTuples() == static_cast<vtkIdType>(coreRay.size());
  for (std::size_t k = 0; k < coreRay.size(); ++k)
  {
    coreRayIds.push_back(cloud.Ids[coreRay[k].Gaussian]);
    const vtkIdType t = static_cast<vtkIdType>(k);
    sameValues = sameValues && sel->GetRayHitWeights()->GetValue(t) == coreRay[k].Weight &&
      sel->GetRayHitAlphas()->GetValue(t) == coreRay[k].Alpha &&
      sel->GetRayHitDistances()->GetValue(t) == coreRay[k].Depth;
  }
  Check(rayHits == coreRayIds && sameValues, "Ray equals Core's footprint Ray, in depth order");
  const std::int64_t singleAtCentre = vis4gs::SelectSingle(view, 100, H - 1 - 75);
  Check(singleAtCentre >= 0 &&
      std::find(rayHits.begin(), rayHits.end(), cloud.Ids[singleAtCentre]) != rayHits.end(),
    "Single's pick is on the Ray");
  // The 3D ellipsoid option, against the brute force on the same pixel ray.
  sel->RayEllipsoidOn();
  sel->SelectRay(100, 75);
  const auto ellipsoidHits = Ids(sel->GetRayHitIds());
  sel->RayEllipsoidOff();
  const auto bf =
    vis4gs::IntersectRayBruteForce(cloud, vis4gs::PixelRay(cam, 100, H - 1 - 75, 3.0));
  std::vector<vtkIdType> bfIds;
  for (const auto& h : bf)
  {
    bfIds.push_back(cloud.Ids[h.Gaussian]);
  }
  Check(ellipsoidHits == bfIds && !bfIds.empty(),
    "RayEllipsoid hits equal the brute force, in depth order");
  sel->SelectRay(100, 75);
  Check(!rayHits.empty(), "the central ray hits the donut");
  std::printf("ray: %zu hits; single/frame/brush latency %.2f ms (prepare %.2f ms)\n",
    rayHits.size(),
    sel->GetLastSelectionTime(),
    sel->GetLastPrepareTime());

  // Modifiers as set algebra.
  sel->SetModifier(vtkGaussianSelector::REPLACE);
  sel->SelectFrame(60, 40, 140, 110);
  Check(Ids(sel->GetSelectedIds()) == frame, "the second visible frame equals the first");
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

  // With a selection hub the hub is the one state: the same algebra happens there, on top of
  // what another view selected, and the selector keeps only its last pick.
  vtkNew<vtkGaussianSelectionHub> hub;
  const vtkIdType other[1] = { 1000000007 }; // an id the donut has not: another view's pick
  hub->SelectIds(other, 1);
  sel->SetSelectionHub(hub);
  sel->SetModifier(vtkGaussianSelector::ADD);
  sel->SelectFrame(60, 40, 140, 110);
  sel->SelectBrush(stroke);
  std::vector<vtkIdType> inHub = expected;
  inHub.push_back(other[0]);
  std::sort(inHub.begin(), inHub.end());
  vtkNew<vtkIdTypeArray> hubIds;
  hub->GetSelectedIds(hubIds);
  Check(Ids(hubIds) == inHub, "the hub holds the union of both picks and the other view's id");
  Check(Ids(sel->GetSelectedIds()) == brush, "the selector keeps its last pick only");
  sel->SetModifier(vtkGaussianSelector::SUBTRACT);
  sel->SelectRay(100, 75);
  hub->GetSelectedIds(hubIds);
  std::vector<vtkIdType> afterRay = expected2;
  afterRay.push_back(other[0]);
  std::sort(afterRay.begin(), afterRay.end());
  Check(Ids(hubIds) == afterRay, "SUBTRACT happens in the hub");
  sel->ClearSelection();
  Check(hub->GetNumberOfSelectedIds() == 0, "clearing the selector clears the hub");
  sel->SetSelectionHub(nullptr);

  // A camera move invalidates the cached projection.
  ren->GetActiveCamera()->Azimuth(40);
  win->Render();
  sel->SetModifier(vtkGaussianSelector::REPLACE);
  sel->SelectFrame(60, 40, 140, 110);
  Check(sel->GetLastPrepareTime() > 0 && Ids(sel->GetSelectedIds()) != frame,
    "a new camera gives a new projection");
  Check(!sel->GetLastSelectionReusedFrame(), "no mapper set: nothing reused");

  // With the splat mapper set, a Frame selection right after a camera move reuses the frame
  // the mapper drew on its CPU path (full resolution, plain scene), and only then; the
  // selection always equals Core's straightforward replay on the renderer's camera.
  mapper->SetDrawMethodToCPURasterizer();
  sel->SetSplatMapper(mapper);
  // Core's selection view on the renderer's camera, and its straightforward Frame replay.
  auto ownView = [&]
  {
    const vis4gs::Camera now =
      vtkGaussianCameraUtilities::FromVTKCamera(ren->GetActiveCamera(), W, H);
    return vis4gs::PrepareSelectionView(cloud, now, 1);
  };
  auto straightFrame =
    [&](const vis4gs::SelectionView& own, int x0, int y0, int x1, int y1, bool occluded)
  {
    vis4gs::FrameOptions straight;
    straight.Threads = 1;
    straight.CullReplay = false;
    straight.IncludeOccluded = occluded;
    return toIds(vis4gs::SelectFrame(own, x0, y0, x1, y1, straight));
  };
  int reused = 0, notReused = 0;
  auto frameCase = [&](const char* what, bool expectReuse, bool occluded)
  {
    sel->SetIncludeOccluded(occluded);
    const vtkIdType n = sel->SelectFrame(50, 30, 150, 120);
    const auto own = ownView();
    const auto expected = straightFrame(own, 50, H - 1 - 30, 150, H - 1 - 120, occluded);
    const bool ok = Ids(sel->GetSelectedIds()) == expected &&
      n == static_cast<vtkIdType>(expected.size()) && !expected.empty();
    const bool reuse = sel->GetLastSelectionReusedFrame();
    std::printf("%s: %zu selected, frame reused %d\n", what, expected.size(), reuse ? 1 : 0);
    Check(ok, what);
    Check(reuse == expectReuse,
      expectReuse ? "the drawn frame is reused" : "the drawn frame is not reused");
    // A reused exact frame kept its blends >= 0.01 (the mapper's default): a visible-only
    // Frame reads them instead of replaying, with the replay's result (checked above).
    Check(sel->GetLastSelectionReadWeights() == (expectReuse && !occluded),
      "Frame reads the drawn frame's blends exactly when it reuses the frame (visible only)");
    (reuse ? reused : notReused)++;
    sel->SetIncludeOccluded(false);
    // Single and Brush take the same decision and equal Core on the renderer's camera.
    const int sx = 100, sy = 80;
    const vtkIdType ns = sel->SelectSingle(sx, sy);
    const std::int64_t g = vis4gs::SelectSingle(own, sx, H - 1 - sy);
    Check(sel->GetLastSelectionReusedFrame() == expectReuse && ns == (g >= 0 ? 1 : 0) &&
        (g < 0 || Ids(sel->GetSelectedIds()) == std::vector<vtkIdType>{ cloud.Ids[g] }),
      "Single on the reused/own frame equals Core");
    Check(!sel->GetLastSelectionReadWeights(), "Single reads no kept blends");
    sel->SelectRay(sx, sy);
    std::vector<vtkIdType> rayExpected;
    for (const auto& c : vis4gs::SelectRay(own, sx, H - 1 - sy))
    {
      rayExpected.push_back(cloud.Ids[c.Gaussian]);
    }
    const auto rayNow = Ids(sel->GetRayHitIds());
    Check(sel->GetLastSelectionReusedFrame() == expectReuse && rayNow == rayExpected &&
        (g < 0 || std::find(rayNow.begin(), rayNow.end(), cloud.Ids[g]) != rayNow.end()),
      "Ray on the reused/own frame equals Core and holds Single's pick");
    vtkNew<vtkPoints> strokeNow;
    strokeNow->InsertNextPoint(60, 70, 0);
    strokeNow->InsertNextPoint(140, 85, 0);
    sel->SelectBrush(strokeNow);
    const auto brushPixels =
      vis4gs::BrushPixels({ { 60.0, H - 1 - 70.0 }, { 140.0, H - 1 - 85.0 } }, 4.0, W, H);
    const auto brushExpected = toIds(vis4gs::SelectBrush(own, brushPixels, 0.01, 1));
    Check(sel->GetLastSelectionReusedFrame() == expectReuse &&
        sel->GetLastSelectionReadWeights() == expectReuse &&
        Ids(sel->GetSelectedIds()) == brushExpected && !brushExpected.empty(),
      "Brush on the reused/own frame (its kept blends when reused) equals Core");
  };
  ren->GetActiveCamera()->Azimuth(-40);
  win->Render();
  Check(mapper->GetLastDrawMethod() == vtkGaussianSplatMapper::CPU_RASTERIZER, "CPU path drawn");
  frameCase("reused frame, visible only", true, false);
  // The selection is highlighted (colours only): the next frame is still reusable.
  mapper->SetSelection(sel->GetSelection());
  ren->GetActiveCamera()->Roll(6);
  win->Render();
  frameCase("reused highlighted frame, with occluded", true, true);
  // Camera moved but not drawn yet: the frame is of the old camera.
  ren->GetActiveCamera()->Roll(6);
  frameCase("camera moved, not drawn", false, false);
  // Dimmed unselected Gaussians (opacities scaled): not the plain scene.
  mapper->DimUnselectedOn();
  ren->GetActiveCamera()->Roll(6);
  win->Render();
  frameCase("dimmed frame", false, false);
  mapper->DimUnselectedOff();
  // Another scale modifier: another projection.
  mapper->SetScaleModifier(1.5);
  ren->GetActiveCamera()->Roll(6);
  win->Render();
  frameCase("scaled frame", false, false);
  mapper->SetScaleModifier(1.0);
  // A reduced interactive frame.
  win->SetDesiredUpdateRate(1000.0);
  ren->GetActiveCamera()->Roll(6);
  win->Render();
  Check(mapper->GetLastImageSampleDistance() > 1.0, "interactive frame at reduced resolution");
  frameCase("interactive frame", false, false);
  win->SetDesiredUpdateRate(0.0001);
  // The still frame after it is reusable again; the scene modified afterwards is not.
  ren->GetActiveCamera()->Roll(6);
  win->Render();
  frameCase("still frame after interaction", true, false);
  ren->GetActiveCamera()->Roll(6);
  win->Render();
  scene->Modified();
  frameCase("scene modified after drawing", false, false);
  Check(reused == 3 && notReused == 5, "every reuse case exercised");
  // Blends kept above the selector's threshold cannot answer it: the frame is reused and the
  // stroke replayed, with the same result.
  mapper->SetSelectionWeightThreshold(0.05);
  ren->GetActiveCamera()->Roll(6);
  win->Render();
  {
    vtkNew<vtkPoints> strokeNow;
    strokeNow->InsertNextPoint(60, 70, 0);
    strokeNow->InsertNextPoint(140, 85, 0);
    sel->SelectBrush(strokeNow);
    const auto brushPixels =
      vis4gs::BrushPixels({ { 60.0, H - 1 - 70.0 }, { 140.0, H - 1 - 85.0 } }, 4.0, W, H);
    const auto brushExpected = toIds(vis4gs::SelectBrush(ownView(), brushPixels, 0.01, 1));
    Check(sel->GetLastSelectionReusedFrame() && !sel->GetLastSelectionReadWeights() &&
        Ids(sel->GetSelectedIds()) == brushExpected && !brushExpected.empty(),
      "blends kept above the threshold: the stroke is replayed, same selection");
  }
  mapper->SetSelectionWeightThreshold(0.01);
  // A frame over most of the view, when the drawn frame kept no blends, computes the view
  // maxima: the drawn frame is copied into the selector's view (reused), and the next frame
  // with that camera takes the cached path. With the kept blends, both read them.
  for (const double kept : { 0.0, 0.01 })
  {
    mapper->SetSelectionWeightThreshold(kept);
    ren->GetActiveCamera()->Roll(6);
    win->Render();
    for (int k = 0; k < 2; ++k)
    {
      const vtkIdType n = sel->SelectFrame(0, 0, W - 1, H - 1 - 10 * k);
      const bool reuse = sel->GetLastSelectionReusedFrame();
      const auto expected = straightFrame(ownView(), 0, 10 * k, W - 1, H - 1, false);
      Check(Ids(sel->GetSelectedIds()) == expected &&
          n == static_cast<vtkIdType>(expected.size()) && expected.size() > 10000,
        "whole-view frame (view maxima or kept blends) equals Core");
      Check(kept > 0 ? reuse && sel->GetLastSelectionReadWeights()
                     : reuse == (k == 0) && !sel->GetLastSelectionReadWeights(),
        kept > 0 ? "the drawn frame's kept blends are read"
                 : "the drawn frame is copied once, then the cached view is used");
    }
  }
  Check(!errors->GetError(), "no unexpected errors");
  return Check.ExitCode();
}

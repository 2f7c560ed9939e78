// SPDX-License-Identifier: BSD-3-Clause
// Regression image of a selection: highlighted (left), and highlighted with everything else
// dimmed (right). The selection is a PEDIGREEIDS vtkSelection of GaussianIds that differ from
// the point indices.
#include "SplatTestHelpers.h"
#include "Vis4GSTestData.h" // VIS4GS_SHARED_DATA_OR_SKIP

#include "Vis4GSDataModel.h"
#include "vtkGaussianCameraUtilities.h"
#include "vtkGaussianSplatMapper.h"

#include "vtkActor.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"

#include <cstdio>

int TestGaussianSplatMapperSelection(int argc, char* argv[])
{
  VIS4GS_SHARED_DATA_OR_SKIP();
  vis4gs::GaussianCloud cloud = splattest::LoadScene(false);
  cloud.Ids.resize(cloud.Count);
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    cloud.Ids[i] = 500000 + 2 * static_cast<std::int64_t>(i);
  }
  vtkNew<vtkPolyData> scene;
  vis4gs::GaussianCloudToPolyData(cloud, scene);
  // Select the Gaussians in a slab of the donut by id.
  vtkNew<vtkIdTypeArray> ids;
  float lo = 1e30f, hi = -1e30f;
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    lo = std::min(lo, cloud.Positions[3 * i]);
    hi = std::max(hi, cloud.Positions[3 * i]);
  }
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    const float x = (cloud.Positions[3 * i] - lo) / (hi - lo);
    if (x > 0.55f && x < 0.8f)
    {
      ids->InsertNextValue(cloud.Ids[i]);
    }
  }
  vtkNew<vtkSelection> selection;
  vtkNew<vtkSelectionNode> node;
  node->SetContentType(vtkSelectionNode::PEDIGREEIDS);
  node->SetFieldType(vtkSelectionNode::POINT);
  node->SetSelectionList(ids);
  selection->AddNode(node);

  const vis4gs::Camera cam = splattest::FrameScene(cloud, 150, 150, -0.4);
  // Highlighted (left) and dimmed (right) selection of @p selected in @p input.
  auto draw = [&](vtkPolyData* input, vtkSelection* selected, vtkRenderWindow* win)
  {
    win->SetOffScreenRendering(1);
    win->SetMultiSamples(0);
    win->SetSize(300, 150);
    for (int v = 0; v < 2; ++v)
    {
      vtkNew<vtkRenderer> ren;
      ren->SetViewport(0.5 * v, 0, 0.5 * v + 0.5, 1);
      vtkNew<vtkGaussianSplatMapper> mapper;
      mapper->SetInputData(input);
      mapper->SetSelection(selected);
      mapper->SetDimUnselected(v == 1);
      vtkNew<vtkActor> actor;
      actor->SetMapper(mapper);
      ren->AddActor(actor);
      win->AddRenderer(ren);
      vtkGaussianCameraUtilities::ApplyCamera(cam, ren->GetActiveCamera());
    }
    win->Render();
  };
  vtkNew<vtkRenderWindow> win;
  std::printf("%lld of %zu Gaussians selected\n",
    static_cast<long long>(ids->GetNumberOfTuples()),
    cloud.Count);
  draw(scene, selection, win);
  const std::vector<float> image = splattest::ReadWindow(win);
  int failures = 0;
  // The same Gaussians selected through ids that descend (the mapper's id order table) and
  // through a reader's shared cloud (no copy of the scene in the mapper): the same image.
  for (int variant = 0; variant < 2; ++variant)
  {
    vis4gs::GaussianCloud other = cloud;
    vtkNew<vtkIdTypeArray> otherIds;
    for (std::size_t i = 0; variant == 0 && i < cloud.Count; ++i)
    {
      other.Ids[i] = 500000 + 2 * static_cast<std::int64_t>(cloud.Count - 1 - i);
    }
    for (vtkIdType k = 0; k < ids->GetNumberOfTuples(); ++k)
    {
      otherIds->InsertNextValue(
        other.Ids[static_cast<std::size_t>((ids->GetValue(k) - 500000) / 2)]);
    }
    vtkNew<vtkSelection> otherSelection;
    vtkNew<vtkSelectionNode> otherNode;
    otherNode->SetContentType(vtkSelectionNode::PEDIGREEIDS);
    otherNode->SetFieldType(vtkSelectionNode::POINT);
    otherNode->SetSelectionList(otherIds);
    otherSelection->AddNode(otherNode);
    vtkNew<vtkPolyData> otherScene;
    vis4gs::GaussianCloudToPolyData(std::move(other), otherScene);
    vtkNew<vtkRenderWindow> otherWin;
    draw(otherScene, otherSelection, otherWin);
    if (splattest::ReadWindow(otherWin) != image)
    {
      std::printf("FAILED: the selection drawn %s differs\n",
        variant == 0 ? "through descending ids" : "from a shared cloud");
      ++failures;
    }
  }
  return failures || !vtkRegressionTestImage(win);
}

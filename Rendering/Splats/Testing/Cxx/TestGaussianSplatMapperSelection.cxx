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

  vtkNew<vtkRenderWindow> win;
  win->SetOffScreenRendering(1);
  win->SetMultiSamples(0);
  win->SetSize(300, 150);
  const vis4gs::Camera cam = splattest::FrameScene(cloud, 150, 150, -0.4);
  for (int v = 0; v < 2; ++v)
  {
    vtkNew<vtkRenderer> ren;
    ren->SetViewport(0.5 * v, 0, 0.5 * v + 0.5, 1);
    vtkNew<vtkGaussianSplatMapper> mapper;
    mapper->SetInputData(scene);
    mapper->SetSelection(selection);
    mapper->SetDimUnselected(v == 1);
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    ren->AddActor(actor);
    win->AddRenderer(ren);
    vtkGaussianCameraUtilities::ApplyCamera(cam, ren->GetActiveCamera());
  }
  std::printf("%lld of %zu Gaussians selected\n",
    static_cast<long long>(ids->GetNumberOfTuples()),
    cloud.Count);
  win->Render();
  return !vtkRegressionTestImage(win);
}

// SPDX-License-Identifier: BSD-3-Clause
// Regression image of the display modes, one viewport each: true colour, the four score
// overlays (ViewCoverage with its legend, the suspicious low end bright and labelled; BlurScore,
// NeedleScore, NeedleShape) and an overlay with Gaussians outside a score range hidden.
#include "SplatTestHelpers.h"
#include "Vis4GSTestData.h" // VIS4GS_SHARED_DATA_OR_SKIP

#include "Vis4GSDataModel.h"
#include "vtkGaussianCameraUtilities.h"
#include "vtkGaussianSplatMapper.h"

#include "vtkActor.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkLookupTable.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkScalarBarActor.h"
#include "vtkTextProperty.h"
#include "vtkVariant.h"

#include <cmath>
#include <cstdio>

int TestGaussianSplatMapperModes(int argc, char* argv[])
{
  VIS4GS_SHARED_DATA_OR_SKIP();
  const vis4gs::GaussianCloud cloud = splattest::LoadScene(false);
  vtkNew<vtkPolyData> scene;
  vis4gs::GaussianCloudToPolyData(cloud, scene);
  // Test scores (not the diagnostics' values): smooth functions of position and shape.
  const char* names[4] = { "ViewCoverage", "BlurScore", "NeedleScore", "NeedleShape" };
  vtkNew<vtkFloatArray> score[4];
  for (int s = 0; s < 4; ++s)
  {
    score[s]->SetName(names[s]);
    score[s]->SetNumberOfTuples(static_cast<vtkIdType>(cloud.Count));
    scene->GetPointData()->AddArray(score[s]);
  }
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    const float* p = &cloud.Positions[3 * i];
    const float* l = &cloud.LogScales[3 * i];
    double q[3], sum = 0, h = 0;
    const double m = std::max({ l[0], l[1], l[2] });
    for (int k = 0; k < 3; ++k)
    {
      q[k] = std::exp(2.0 * (l[k] - m));
      sum += q[k];
    }
    for (double& v : q)
    {
      v /= sum;
      h -= v > 0 ? v * std::log(v) : 0.0;
    }
    const double needle = (3.0 - std::exp(h)) / 2.0;
    const vtkIdType id = static_cast<vtkIdType>(i);
    score[0]->SetValue(id, static_cast<float>(0.5 + 0.5 * std::sin(40.0 * p[1])));
    score[1]->SetValue(id, static_cast<float>(std::sqrt(p[0] * p[0] + p[2] * p[2])));
    score[2]->SetValue(id, static_cast<float>(needle * std::abs(p[0])));
    score[3]->SetValue(id, static_cast<float>(needle));
  }

  vtkNew<vtkRenderWindow> win;
  win->SetOffScreenRendering(1);
  win->SetMultiSamples(0);
  win->SetSize(450, 300);
  const vis4gs::Camera cam = splattest::FrameScene(cloud, 150, 150, 0.5);
  int fail = 0;
  vtkIdType drawn[6] = { 0, 0, 0, 0, 0, 0 };
  vtkNew<vtkGaussianSplatMapper> mappers[6];
  for (int v = 0; v < 6; ++v)
  {
    vtkNew<vtkRenderer> ren;
    ren->SetViewport((v % 3) / 3.0, (1 - v / 3) / 2.0, (v % 3 + 1) / 3.0, (2 - v / 3) / 2.0);
    ren->SetBackground(0.05, 0.05, 0.05);
    vtkGaussianSplatMapper* mapper = mappers[v];
    mapper->SetInputData(scene);
    if (v >= 1 && v <= 4)
    {
      mapper->SetSplatColoringToScore();
      mapper->SetScoreArrayName(names[v - 1]);
    }
    else if (v == 5)
    {
      mapper->SetSplatColoringToScore();
      mapper->SetScoreArrayName("NeedleShape");
      mapper->SetScoreRange(0.0, 1.0);
      mapper->HideOutsideRangeOn();
      mapper->SetVisibleRange(0.5, 1.0);
    }
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    ren->AddActor(actor);
    if (v == 1)
    {
      vtkNew<vtkScalarBarActor> legend;
      legend->SetLookupTable(mapper->GetScoreLookupTable());
      legend->SetNumberOfLabels(3);
      legend->SetBarRatio(0.2);
      legend->SetPosition(0.78, 0.1);
      legend->SetWidth(0.2);
      legend->SetHeight(0.8);
      legend->GetLabelTextProperty()->SetFontSize(9);
      ren->AddActor2D(legend);
    }
    win->AddRenderer(ren);
    vtkGaussianCameraUtilities::ApplyCamera(cam, ren->GetActiveCamera());
  }
  win->Render();
  for (int v = 0; v < 6; ++v)
  {
    drawn[v] = mappers[v]->GetLastDrawnCount();
  }
  std::printf("drawn: %lld %lld %lld %lld %lld %lld\n",
    (long long)drawn[0],
    (long long)drawn[1],
    (long long)drawn[2],
    (long long)drawn[3],
    (long long)drawn[4],
    (long long)drawn[5]);
  if (drawn[0] <= 0 || drawn[1] != drawn[0] || !(drawn[5] > 0 && drawn[5] < drawn[0]))
  {
    std::printf("FAILED: hiding outside the range should draw fewer, others all\n");
    fail = 1;
  }
  // The legend's table spans the automatic range of ViewCoverage.
  const double* range = mappers[1]->GetScoreLookupTable()->GetRange();
  if (!(range[0] >= 0.0 && range[0] < 0.01 && range[1] > 0.99 && range[1] <= 1.0))
  {
    std::printf("FAILED: legend range %g..%g\n", range[0], range[1]);
    fail = 1;
  }
  // Each legend names its suspicious end, and that end is the bright one of the map: low
  // View Coverage, high Blur, Needle and needle shape.
  for (int v = 1; v <= 4; ++v)
  {
    vtkLookupTable* lut = mappers[v]->GetScoreLookupTable();
    const double* r = lut->GetRange();
    const bool low = v == 1;
    const vtkIdType at = lut->GetAnnotatedValueIndex(vtkVariant(low ? r[0] : r[1]));
    double bright[3], dark[3];
    lut->GetColor(low ? r[0] : r[1], bright);
    lut->GetColor(low ? r[1] : r[0], dark);
    auto luminance = [](const double* c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; };
    if (lut->GetNumberOfAnnotatedValues() != 1 || at < 0 ||
      lut->GetAnnotation(at) != "suspicious" || !(luminance(bright) > 5 * luminance(dark)))
    {
      std::printf("FAILED: %s legend: %lld annotations, 'suspicious' at index %lld, luminance of "
                  "the suspicious end %g, of the other %g\n",
        names[v - 1],
        static_cast<long long>(lut->GetNumberOfAnnotatedValues()),
        static_cast<long long>(at),
        luminance(bright),
        luminance(dark));
      fail = 1;
    }
  }
  const int retVal = vtkRegressionTestImage(win);
  return fail || !retVal;
}

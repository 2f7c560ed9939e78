// SPDX-License-Identifier: BSD-3-Clause
// The timeline view with a second run (issue 20): both runs' metric plots, the second run's
// dotted (dash-dotted for test metrics), legend entries naming the runs, the iteration axis
// spanning both runs; and in the rendered picture, the second run's PSNR curve where only it
// has iterations (the control: the same second run without PSNR draws nothing there), and the
// second iteration cursor.
#include "vtkGaussianTimelineChart.h"
#include "vtkGaussianTimelineView.h"

#include "vtkAxis.h"
#include "vtkDoubleArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPen.h"
#include "vtkPlot.h"
#include "vtkRenderWindow.h"
#include "vtkSmartPointer.h"
#include "vtkTable.h"
#include "vtkUnsignedCharArray.h"

#include <array>
#include <cmath>
#include <iostream>
#include <limits>
#include <string>

namespace
{
int failures = 0;
void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "ERROR: check failed: " << what << "\n";
    ++failures;
  }
}

// A metrics table of @p rows iterations 0, step, 2 step...: PSNR rising from @p psnr0, SSIM,
// the count growing; @p withPsnr false leaves the PSNR column all NaN.
vtkSmartPointer<vtkTable> MakeMetrics(int rows, int step, double psnr0, bool withPsnr = true)
{
  auto table = vtkSmartPointer<vtkTable>::New();
  vtkNew<vtkIntArray> iteration;
  iteration->SetName("Iteration");
  vtkNew<vtkDoubleArray> count, psnr, ssim;
  count->SetName("NumGaussians");
  psnr->SetName("PSNR");
  ssim->SetName("SSIM");
  for (int r = 0; r < rows; ++r)
  {
    iteration->InsertNextValue(r * step);
    count->InsertNextValue(1000 + 50 * r);
    psnr->InsertNextValue(withPsnr ? psnr0 + 8.0 * r / rows : std::nan(""));
    ssim->InsertNextValue(0.5 + 0.4 * r / rows);
  }
  table->AddColumn(iteration);
  table->AddColumn(count);
  table->AddColumn(psnr);
  table->AddColumn(ssim);
  return table;
}

// Pixels of @p view's picture near the colour @p rgb inside the box [x0, x1) x [y0, y1) given
// as fractions of the window (y up).
int Pixels(vtkGaussianTimelineView* view,
  const std::array<int, 3>& rgb,
  double x0,
  double x1,
  double y0,
  double y1)
{
  vtkRenderWindow* window = view->GetRenderWindow();
  view->Render();
  const int* size = window->GetSize();
  vtkNew<vtkUnsignedCharArray> picture;
  window->GetPixelData(0, 0, size[0] - 1, size[1] - 1, 1, picture);
  int found = 0;
  for (int y = static_cast<int>(y0 * size[1]); y < static_cast<int>(y1 * size[1]); ++y)
  {
    for (int x = static_cast<int>(x0 * size[0]); x < static_cast<int>(x1 * size[0]); ++x)
    {
      const unsigned char* p = picture->GetPointer(3 * (static_cast<vtkIdType>(y) * size[0] + x));
      found +=
        std::abs(p[0] - rgb[0]) + std::abs(p[1] - rgb[1]) + std::abs(p[2] - rgb[2]) < 60 ? 1 : 0;
    }
  }
  return found;
}
}

int TestGaussianTimelineViewComparison(int, char*[])
{
  vtkNew<vtkGaussianTimelineView> view;
  view->GetRenderWindow()->SetSize(600, 600);
  view->GetRenderWindow()->SetMultiSamples(0);
  view->SetMetrics(MakeMetrics(11, 100, 20.0));
  const int single = view->GetNumberOfMetricPlots();
  Check(single == 3, "one run: PSNR, SSIM and the count (" + std::to_string(single) + ")");
  vtkGaussianTimelineChart* quality = view->GetChart(vtkGaussianTimelineView::QUALITY);
  Check(std::string(quality->GetPlot(0)->GetLabel()) == "PSNR",
    "one run: the legend names the metric only");

  // The second run goes on to iteration 2000 and has test metrics too.
  vtkSmartPointer<vtkTable> second = MakeMetrics(21, 100, 22.0);
  view->SetRunName("A: demo.h5 @1000");
  view->SetComparisonRunName("B: other.h5");
  view->SetComparisonMetrics(second);
  view->SetComparisonTestMetrics(MakeMetrics(5, 500, 18.0));
  Check(view->GetNumberOfMetricPlots() == 2 * single + 2,
    "both runs: 3 + 3 plots and the second run's PSNR and SSIM test (" +
      std::to_string(view->GetNumberOfMetricPlots()) + ")");
  Check(view->GetNumberOfComparisonPlots() == single + 2, "the second run's plots are counted");
  int firstRun = 0, secondRun = 0;
  for (int chart : { vtkGaussianTimelineView::QUALITY, vtkGaussianTimelineView::COUNT })
  {
    vtkGaussianTimelineChart* c = view->GetChart(chart);
    for (vtkIdType k = 0; k < c->GetNumberOfPlots(); ++k)
    {
      vtkPlot* plot = c->GetPlot(k);
      const std::string label = plot->GetLabel();
      const int line = plot->GetPen()->GetLineType();
      if (label.find("[A: demo.h5 @1000]") != std::string::npos)
      {
        ++firstRun;
        Check(line ==
            (label.find("test") != std::string::npos ? vtkPen::DASH_LINE : vtkPen::SOLID_LINE),
          label + ": the first run is drawn solid");
        Check(plot->GetInput() == view->GetMetrics(), label + ": draws the first run's table");
      }
      else if (label.find("[B: other.h5]") != std::string::npos)
      {
        ++secondRun;
        const bool test = label.find("test") != std::string::npos;
        Check(line == (test ? vtkPen::DASH_DOT_LINE : vtkPen::DOT_LINE),
          label + ": the second run is dotted");
        Check(plot->GetInput() ==
            (test ? view->GetComparisonTestMetrics() : view->GetComparisonMetrics()),
          label + ": draws the second run's table");
      }
      else
      {
        Check(false, "legend entry without a run name: " + label);
      }
    }
  }
  Check(firstRun == single && secondRun == single + 2, "every entry names one of the runs");
  double range[2];
  quality->GetAxis(vtkAxis::BOTTOM)->GetRange(range);
  Check(range[0] <= 0 && range[1] >= 2000, "the iteration axis spans both runs");

  // Pictures: the right half of the quality chart (iterations 1000..2000, top third of the
  // window) holds PSNR-coloured pixels only when the second run has PSNR values.
  quality->SetShowLegend(false);
  const std::array<int, 3> psnrColour{ 31, 119, 180 };
  const int with = Pixels(view, psnrColour, 0.6, 0.95, 0.7, 0.95);
  view->SetComparisonMetrics(MakeMetrics(21, 100, 22.0, false));
  view->SetComparisonTestMetrics(nullptr);
  Check(view->GetNumberOfComparisonPlots() == 2, "without PSNR: the SSIM and count plots");
  const int without = Pixels(view, psnrColour, 0.6, 0.95, 0.7, 0.95);
  Check(with > 20 && without == 0,
    "the second run's PSNR is drawn beyond the first run (" + std::to_string(with) +
      " pixels; without its PSNR " + std::to_string(without) + ")");

  // The second cursor: dashed magenta at the other state's iteration, in every chart.
  const int magentaBefore = Pixels(view, { 200, 40, 200 }, 0, 1, 0, 1);
  view->SetComparisonIteration(1500);
  const int magenta = Pixels(view, { 200, 40, 200 }, 0, 1, 0, 1);
  for (int chart = 0; chart < 3; ++chart)
  {
    Check(view->GetChart(chart)->GetComparisonCursorIteration() == 1500,
      "chart " + std::to_string(chart) + " has the second cursor");
  }
  Check(magentaBefore == 0 && magenta > 30,
    "the second cursor is drawn (" + std::to_string(magenta) + " pixels)");
  view->SetComparisonIteration(-1);
  Check(Pixels(view, { 200, 40, 200 }, 0, 1, 0, 1) == 0, "a negative iteration hides it");

  // Back to one run: the names leave the legend.
  view->SetComparisonMetrics(nullptr);
  Check(view->GetNumberOfMetricPlots() == single && view->GetNumberOfComparisonPlots() == 0,
    "one run again");
  Check(std::string(quality->GetPlot(0)->GetLabel()) == "PSNR", "one run again: plain labels");
  view->Print(std::cout);
  return failures == 0 ? 0 : 1;
}

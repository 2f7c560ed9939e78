/*=========================================================================

  Program:   Vis4GS
  Module:    TestGaussianRemovalEffectFilter.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
// vtkGaussianRemovalEffectFilter on a hand-built case whose answers are derived by hand: a
// floater in front of three cameras whose images are black (the background), a kept Gaussian
// behind them that only a fourth camera, looking the other way, sees. Deleting the floater
// makes the views it was in perfect (L1 0, SSIM 1, PSNR +inf) and leaves the other untouched;
// the "before" figures equal PSNR and L1 computed here in double from the rasteriser's render;
// the rows are sorted worst PSNR change first; a view without an image is last, NaN; the
// totals are the means per split; the selection by array and by ids agree; errors empty the
// outputs. A "before" given (SetBaseline, as the score pass's) and the preview renders
// (PreviewView) give Core's MeasureRemovalEffect's figures and Rasterize's pixels bit for bit.
#include "vtkGaussianRemovalEffectFilter.h"

#include "GaussianCloud.h"
#include "ImageIO.h"
#include "Rasterizer.h"
#include "RemovalEffect.h"
#include "TrainingLogReader.h"
#include "Vis4GSDataModel.h"

#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVariant.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace
{
int failures = 0;
void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++failures;
  }
}

double Value(vtkTable* t, const char* column, vtkIdType row)
{
  vtkAbstractArray* a = t->GetColumnByName(column);
  return a ? a->GetVariantValue(row).ToDouble() : std::numeric_limits<double>::quiet_NaN();
}

bool Same(double a, double b)
{
  return std::isnan(a) ? std::isnan(b) : a == b;
}

bool SameMetrics(const vis4gs::ViewMetrics& a, const vis4gs::ViewMetrics& b)
{
  return Same(a.Psnr, b.Psnr) && Same(a.Ssim, b.Ssim) && Same(a.L1, b.L1);
}

// The filter's tables (through GetEffect and read column by column) against @p core.
bool SameAsCore(vtkGaussianRemovalEffectFilter* filter, const vis4gs::RemovalEffect& core)
{
  vis4gs::RemovalEffect e;
  if (!filter->GetEffect(e) || e.Views.size() != core.Views.size() || e.Removed != core.Removed ||
    e.Kept != core.Kept || e.ViewsWithoutImage != core.ViewsWithoutImage)
  {
    return false;
  }
  vtkTable* views = filter->GetOutput(0);
  bool same = views->GetNumberOfRows() == static_cast<vtkIdType>(core.Views.size());
  for (std::size_t r = 0; same && r < core.Views.size(); ++r)
  {
    const vis4gs::RemovalViewEffect& c = core.Views[r];
    const vtkIdType row = static_cast<vtkIdType>(r);
    same = e.Views[r].CameraIndex == c.CameraIndex && e.Views[r].Name == c.Name &&
      e.Views[r].Split == c.Split && e.Views[r].Affected == c.Affected &&
      e.Views[r].HasImage == c.HasImage && SameMetrics(e.Views[r].Before, c.Before) &&
      SameMetrics(e.Views[r].After, c.After) &&
      Value(views, "camera", row) == static_cast<double>(c.CameraIndex) &&
      Same(Value(views, "psnr_before", row), c.Before.Psnr) &&
      Same(Value(views, "psnr_after", row), c.After.Psnr) &&
      Same(Value(views, "ssim_after", row), c.After.Ssim) &&
      Same(Value(views, "l1_after", row), c.After.L1);
  }
  for (const auto& [mine, theirs] :
    { std::make_pair(&e.Train, &core.Train), std::make_pair(&e.Test, &core.Test) })
  {
    same = same && mine->Views == theirs->Views && mine->AffectedViews == theirs->AffectedViews &&
      SameMetrics(mine->Before, theirs->Before) && SameMetrics(mine->After, theirs->After);
  }
  return same;
}

// Output port 2's array @p name against @p image (rows top first there, bottom first here).
bool SamePixels(vtkImageData* preview, const char* name, const vis4gs::Image& image)
{
  auto* pixels = vtkFloatArray::SafeDownCast(preview->GetPointData()->GetArray(name));
  int dims[3];
  preview->GetDimensions(dims);
  if (!pixels || dims[0] != image.Width || dims[1] != image.Height ||
    pixels->GetNumberOfComponents() != 3 || image.Channels != 3)
  {
    return false;
  }
  for (int y = 0; y < image.Height; ++y)
  {
    for (int x = 0; x < 3 * image.Width; ++x)
    {
      const float a = pixels->GetValue(static_cast<vtkIdType>(y) * 3 * image.Width + x);
      const float b =
        image.Pixels[static_cast<std::size_t>(image.Height - 1 - y) * 3 * image.Width + x];
      if (std::memcmp(&a, &b, sizeof(float)) != 0)
      {
        return false;
      }
    }
  }
  return true;
}

vis4gs::Camera MakeCamera(const std::string& name, bool lookBack, const std::string& image)
{
  vis4gs::Camera c;
  c.Name = name;
  c.Width = c.Height = 32;
  c.Fx = c.Fy = 32;
  c.Cx = c.Cy = 16;
  if (lookBack) // rotation of 180 degrees about y: looks along -z
  {
    c.WorldToCamera[0] = -1;
    c.WorldToCamera[10] = -1;
  }
  c.ImagePath = image;
  return c;
}
}

int TestGaussianRemovalEffectFilter(int, char*[])
{
  // Gaussian 10 (the floater) at z = 5 in front of cameras a, b (test) and d (no image);
  // Gaussian 20 at z = -5, seen only by camera c, which looks along -z.
  vis4gs::GaussianCloud cloud;
  cloud.Resize(2, 0);
  cloud.Ids = { 10, 20 };
  const float z[] = { 5.0f, -5.0f };
  for (std::size_t i = 0; i < 2; ++i)
  {
    cloud.Positions[3 * i + 2] = z[i];
    for (int k = 0; k < 3; ++k)
    {
      cloud.LogScales[3 * i + k] = std::log(0.4f);
      cloud.SH[3 * i + k] = 0.5f; // colour 0.5 + C0 * 0.5
    }
    cloud.Rotations[4 * i] = 1;
    cloud.OpacityLogits[i] = 1.0f;
  }
  vtkNew<vtkPolyData> scene;
  vis4gs::GaussianCloudToPolyData(cloud, scene);
  vtkNew<vtkUnsignedCharArray> marks;
  marks->SetName("RuleSelected");
  marks->InsertNextValue(1);
  marks->InsertNextValue(0);
  scene->GetPointData()->AddArray(marks);

  std::ostringstream folder;
  folder << "vis4gs-removal-effect-" << std::hex << reinterpret_cast<std::uintptr_t>(&cloud);
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / folder.str();
  std::filesystem::create_directories(dir);
  const std::string black = (dir / "black.png").string();
  const std::vector<unsigned char> zeros(32 * 32 * 3, 0);
  vis4gs::WritePng8(black, 32, 32, 3, zeros.data());
  std::vector<vis4gs::Camera> cameras = { MakeCamera("a", false, black),
    MakeCamera("b", false, black),
    MakeCamera("c", true, black),
    MakeCamera("d", false, (dir / "missing.png").string()) };
  cameras[1].Split = vis4gs::CameraSplit::Test;
  vtkNew<vtkTable> table;
  vis4gs::CamerasToTable(cameras, table);

  // "Before" by hand: the image is 0, so L1 is the mean of the clamped render and the MSE the
  // mean of its squares.
  auto figures = [&cloud](const vis4gs::Camera& camera, double& l1, double& psnr)
  {
    const vis4gs::RasterImage<float> render = vis4gs::Rasterize<float>(cloud, camera);
    double sum = 0, squares = 0;
    for (float v : render.Color)
    {
      const double c = std::min(1.0, std::max(0.0, static_cast<double>(v)));
      sum += c;
      squares += c * c;
    }
    l1 = sum / render.Color.size();
    psnr = -10 * std::log10(squares / render.Color.size());
  };
  double l1A = 0, psnrA = 0, l1C = 0, psnrC = 0;
  figures(cameras[0], l1A, psnrA);
  figures(cameras[2], l1C, psnrC);
  Check(l1A > 0.01 && l1C > 0.01, "both Gaussians are visible in their views");

  vtkNew<vtkGaussianRemovalEffectFilter> filter;
  filter->SetInputData(scene);
  filter->SetCamerasData(table);
  filter->Update();
  vtkTable* views = filter->GetOutput(0);
  vtkTable* totals = filter->GetOutput(1);
  Check(views->GetNumberOfRows() == 4, "one row per view");
  const char* columns[] = { vis4gs::arrays::RemovalView,
    vis4gs::arrays::RemovalCamera,
    vis4gs::arrays::RemovalSplit,
    vis4gs::arrays::RemovalAffected,
    vis4gs::arrays::RemovalPsnrBefore,
    vis4gs::arrays::RemovalPsnrAfter,
    vis4gs::arrays::RemovalSsimBefore,
    vis4gs::arrays::RemovalSsimAfter,
    vis4gs::arrays::RemovalL1Before,
    vis4gs::arrays::RemovalL1After };
  Check(views->GetNumberOfColumns() == 10, "ten columns");
  for (int c = 0; c < 10 && c < views->GetNumberOfColumns(); ++c)
  {
    Check(std::string(views->GetColumnName(c)) == columns[c],
      std::string("column ") + std::to_string(c) + " is " + columns[c]);
  }
  // Worst PSNR change first: c (0), then a and b (+inf, camera order), then d (no image).
  const std::vector<vtkIdType> order = { 2, 0, 1, 3 };
  for (vtkIdType r = 0; r < 4 && r < views->GetNumberOfRows(); ++r)
  {
    Check(Value(views, "camera", r) == order[static_cast<std::size_t>(r)],
      "row " + std::to_string(r) + " is camera " + std::to_string(order[r]));
  }
  if (views->GetNumberOfRows() == 4)
  {
    auto* names = vtkStringArray::SafeDownCast(views->GetColumnByName("view"));
    auto* splits = vtkStringArray::SafeDownCast(views->GetColumnByName("split"));
    Check(names && names->GetValue(0) == "c" && names->GetValue(1) == "a", "view names");
    Check(splits && splits->GetValue(2) == "test" && splits->GetValue(1) == "train", "splits");
    // c: untouched, not rendered again.
    Check(Value(views, "affected", 0) == 0, "c is not affected");
    Check(Value(views, "psnr_after", 0) == Value(views, "psnr_before", 0) &&
        Value(views, "l1_after", 0) == Value(views, "l1_before", 0) &&
        Value(views, "ssim_after", 0) == Value(views, "ssim_before", 0),
      "c: after == before");
    Check(std::abs(Value(views, "l1_before", 0) - l1C) < 1e-12, "c: L1 by hand");
    Check(std::abs(Value(views, "psnr_before", 0) - psnrC) < 1e-9, "c: PSNR by hand");
    // a and b: perfect after.
    for (vtkIdType r : { 1, 2 })
    {
      const std::string v = r == 1 ? "a" : "b";
      Check(Value(views, "affected", r) == 1, v + " is affected");
      Check(std::abs(Value(views, "l1_before", r) - l1A) < 1e-12, v + ": L1 before by hand");
      Check(std::abs(Value(views, "psnr_before", r) - psnrA) < 1e-9, v + ": PSNR before by hand");
      Check(Value(views, "ssim_before", r) < 1, v + ": SSIM before < 1");
      Check(Value(views, "l1_after", r) == 0, v + ": L1 after 0");
      Check(Value(views, "psnr_after", r) == std::numeric_limits<double>::infinity(),
        v + ": PSNR after +inf");
      Check(std::abs(Value(views, "ssim_after", r) - 1) < 1e-12, v + ": SSIM after 1");
    }
    Check(std::isnan(Value(views, "psnr_before", 3)) && std::isnan(Value(views, "l1_after", 3)),
      "d (no image): NaN");
  }
  Check(totals->GetNumberOfRows() == 2, "two totals rows");
  if (totals->GetNumberOfRows() == 2)
  {
    Check(vtkStringArray::SafeDownCast(totals->GetColumnByName("split"))->GetValue(0) == "train",
      "train first");
    Check(Value(totals, "views", 0) == 2 && Value(totals, "affected", 0) == 1, "train counts");
    Check(Value(totals, "views", 1) == 1 && Value(totals, "affected", 1) == 1, "test counts");
    Check(std::abs(Value(totals, "l1_before", 0) - (l1A + l1C) / 2) < 1e-12, "train L1 mean");
    Check(std::abs(Value(totals, "l1_after", 0) - l1C / 2) < 1e-12, "train L1 mean after");
    Check(Value(totals, "l1_after", 1) == 0, "test L1 after");
  }
  Check(filter->GetNumberRemoved() == 1 && filter->GetNumberKept() == 1, "removed and kept");
  Check(filter->GetNumberOfViewsWithoutImage() == 1, "views without an image");

  // The same by ids, without the array; training views only.
  vtkNew<vtkPolyData> plain;
  vis4gs::GaussianCloudToPolyData(cloud, plain);
  vtkNew<vtkIdTypeArray> ids;
  ids->InsertNextValue(10);
  filter->SetInputData(plain);
  filter->SetRemovedIds(ids);
  filter->TestViewsOff();
  filter->Update();
  views = filter->GetOutput(0);
  Check(views->GetNumberOfRows() == 3 && Value(views, "camera", 1) == 0 &&
      Value(views, "l1_after", 1) == 0 && Value(views, "camera", 2) == 3,
    "by ids: a perfect after, b (test) not measured");
  Check(
    filter->GetOutput(1)->GetNumberOfRows() == 2 && Value(filter->GetOutput(1), "views", 1) == 0,
    "by ids: no test view");

  Check(!filter->GetBaselineReused(), "a new input: the before is measured again");

  // Another selection of the same input reuses the "before" and gives a fresh filter's figures.
  ids->SetValue(0, 20);
  ids->Modified();
  filter->Update();
  Check(filter->GetBaselineReused(), "only the selection changed: the before is reused");
  vtkNew<vtkGaussianRemovalEffectFilter> fresh;
  fresh->SetInputData(plain);
  fresh->SetCamerasData(table);
  fresh->SetRemovedIds(ids);
  fresh->TestViewsOff();
  fresh->Update();
  bool same = fresh->GetOutput(0)->GetNumberOfRows() == filter->GetOutput(0)->GetNumberOfRows();
  for (vtkIdType r = 0; same && r < fresh->GetOutput(0)->GetNumberOfRows(); ++r)
  {
    for (int c = 0; c < fresh->GetOutput(0)->GetNumberOfColumns(); ++c)
    {
      const vtkVariant a = fresh->GetOutput(0)->GetValue(r, c);
      const vtkVariant b = filter->GetOutput(0)->GetValue(r, c);
      same = same &&
        (a.IsString() ? a.ToString() == b.ToString()
                      : (a.ToDouble() == b.ToDouble() ||
                          (std::isnan(a.ToDouble()) && std::isnan(b.ToDouble()))));
    }
  }
  Check(same, "the reused before gives a fresh filter's figures exactly");
  // a unchanged (0) first, then c, perfect (+inf).
  Check(Value(filter->GetOutput(0), "camera", 1) == 2 &&
      Value(filter->GetOutput(0), "l1_after", 1) == 0 &&
      Value(filter->GetOutput(0), "affected", 0) == 0,
    "removing Gaussian 20 makes c perfect and leaves a");

  // A "before" given, as the score pass's: the training views only (the score pass renders no
  // test view). The filter renders the test view it lacks and nothing else "before", and its
  // figures are Core's, computed here with a "before" of every view rendered anew.
  {
    const vis4gs::TrainingImageProvider images =
      [](std::size_t, const vis4gs::Camera& camera, vis4gs::Image& image)
    { return vis4gs::LoadCameraImage(nullptr, camera, image); };
    const std::vector<std::uint8_t> removed = { 1, 0 };
    vis4gs::RemovalEffectOptions options;
    options.TileBaseline = vis4gs::MeasureRemovalBaseline(cloud, cameras, options, images);
    const vis4gs::RemovalEffect core =
      vis4gs::MeasureRemovalEffect(cloud, removed, cameras, options, images);
    options.TestViews = false;
    auto trainOnly = std::make_shared<vis4gs::RemovalBaseline>(
      vis4gs::MeasureRemovalBaseline(cloud, cameras, options, images));
    const std::size_t given = trainOnly->MeasuredViews();
    vtkNew<vtkGaussianRemovalEffectFilter> first;
    first->SetInputData(plain);
    first->SetCamerasData(table);
    vtkNew<vtkIdTypeArray> floater;
    floater->InsertNextValue(10);
    first->SetRemovedIds(floater);
    first->SetBaseline(trainOnly);
    first->Update();
    Check(given == 2 && first->GetNumberOfBaselineViewsReused() == 2 &&
        first->GetNumberOfBaselineViewsRendered() == 1,
      "a given 'before' of the 2 training views: the test view alone is rendered 'before'");
    Check(SameAsCore(first, core),
      "with a given 'before': Core's MeasureRemovalEffect's figures, bit for bit");
    Check(first->GetMeasuredBaseline() && first->GetMeasuredBaseline()->MeasuredViews() == 3 &&
        trainOnly->MeasuredViews() == 2,
      "the completed 'before' is handed on, the given one is left as it was");
    // A second filter given the completed one renders nothing "before".
    vtkNew<vtkGaussianRemovalEffectFilter> second;
    second->SetInputData(plain);
    second->SetCamerasData(table);
    second->SetRemovedIds(floater);
    second->SetBaseline(first->GetMeasuredBaseline());
    second->Update();
    Check(second->GetNumberOfBaselineViewsRendered() == 0 &&
        second->GetNumberOfBaselineViewsReused() == 3 && SameAsCore(second, core),
      "a second measurement given the first's 'before' renders no view 'before'");

    // The preview renders: Core's renders of camera a before and after, bit for bit; a new
    // PreviewView keeps the tables (the same arrays, not measured again).
    vtkAbstractArray* column = second->GetOutput(0)->GetColumn(4);
    const double after = second->GetSecondsAfter();
    Check(second->GetPreviewOutput()->GetNumberOfPoints() == 0, "no preview by default");
    for (vtkIdType view : { 0, 2 })
    {
      second->SetPreviewView(view);
      second->Update();
      const vis4gs::Camera& camera = cameras[static_cast<std::size_t>(view)];
      const vis4gs::Image before =
        vis4gs::ClampedImage(vis4gs::Rasterize<float>(cloud, camera, vis4gs::RasterSettings{}));
      const vis4gs::Image cleaned = vis4gs::ClampedImage(vis4gs::Rasterize<float>(
        vis4gs::RemoveGaussians(cloud, removed), camera, vis4gs::RasterSettings{}));
      vtkImageData* preview = second->GetPreviewOutput();
      Check(
        SamePixels(preview, vtkGaussianRemovalEffectFilter::GetPreviewBeforeArrayName(), before) &&
          SamePixels(preview, vtkGaussianRemovalEffectFilter::GetPreviewAfterArrayName(), cleaned),
        "preview of camera " + std::to_string(view) + ": Core's renders, bit for bit");
      Check(second->GetOutput(0)->GetColumn(4) == column && second->GetSecondsAfter() == after &&
          SameAsCore(second, core),
        "a new PreviewView keeps the tables");
    }
    vtkObject::GlobalWarningDisplayOff();
    second->SetPreviewView(7);
    second->Update();
    Check(second->GetOutput(0)->GetNumberOfRows() == 0, "a PreviewView of no camera: an error");
    // A "before" of another scene (another number of Gaussians) is refused.
    auto other = std::make_shared<vis4gs::RemovalBaseline>(*trainOnly);
    other->Gaussians = 3;
    second->SetPreviewView(-1);
    second->SetBaseline(other);
    second->Update();
    Check(
      second->GetOutput(0)->GetNumberOfRows() == 0, "a given 'before' of another scene: an error");
    vtkObject::GlobalWarningDisplayOn();
  }

  // Errors: nothing to remove by; no camera table.
  vtkObject::GlobalWarningDisplayOff();
  filter->SetRemovedIds(nullptr);
  filter->Update();
  Check(filter->GetOutput(0)->GetNumberOfRows() == 0, "no marks array: no output");
  vtkNew<vtkGaussianRemovalEffectFilter> noCameras;
  noCameras->SetInputData(scene);
  noCameras->Update();
  Check(noCameras->GetOutput(0)->GetNumberOfRows() == 0, "no cameras: no output");
  vtkObject::GlobalWarningDisplayOn();

  std::ostringstream print;
  filter->Print(print);
  Check(print.str().find("RemovalArrayName: RuleSelected") != std::string::npos &&
      print.str().find("TestViews: 0") != std::string::npos &&
      print.str().find("PreviewView: -1") != std::string::npos &&
      print.str().find("Baseline: (none)") != std::string::npos &&
      print.str().find("NumberOfBaselineViewsRendered: ") != std::string::npos,
    "PrintSelf");
  std::filesystem::remove_all(dir);
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

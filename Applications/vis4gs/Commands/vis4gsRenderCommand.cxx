// SPDX-License-Identifier: BSD-3-Clause
// `vis4gs render`: an off-screen image of a scene from one camera with the exact CPU 3DGS
// rasteriser (Core/Render through vtkGaussianRasterizer), written as an 8-bit PNG. The scene and
// the cameras of --cameras are read through vtkGaussianSession, as every command reads them.
#include "Vis4GSCommand.h"

#include "ImageIO.h"
#include "Vis4GSDataModel.h"
#include "Vis4GSPipeline.h"
#include "vtkGaussianRasterizer.h"
#include "vtkGaussianSession.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTable.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{

void Define(Vis4GSArguments& args)
{
  args.AddPositional("scene",
    "3DGS scene: the trainer's PLY, a compressed PLY, a SOG (.sog, meta.json or its folder), an "
    "SPZ, a .ksplat, an antimatter15 .splat or glTF (.glb, .gltf).");
  args.AddOption("cameras",
    "FILE_OR_DIR",
    "",
    "Cameras: the trainer's cameras.json, a COLMAP dataset folder or a transforms*.json (file or "
    "folder). Default: a synthetic "
    "camera looking at the scene's bounding box from -z.");
  args.AddOption("camera", "INDEX_OR_NAME", "0", "Camera to render: its row index or its name.");
  args.AddOption("resolution",
    "W,H",
    "",
    "Output size in pixels (keeps the field of view). Default: the camera's size (800,600 for "
    "the synthetic camera).");
  args.AddOption("background", "R,G,B", "0,0,0", "Background colour, components in [0,1].");
  args.AddOption(
    "sh-degree", "N", "-1", "Active SH degree 0..3; -1 uses every degree the scene holds.");
  args.AddOption("precision",
    "float|double",
    "float",
    "Arithmetic: float (as the reference CUDA rasteriser) or double (reference mode).");
  args.AddOption("output", "FILE", "render.png", "PNG file to write (colours clamped to [0,1]).");
}

// A camera at the robust bounding box (5th..95th percentile of the means) of the scene,
// looking along +z, far enough for the box to fill about half of a 60 degree field of view.
vis4gs::Camera SyntheticCamera(vtkPolyData* scene, int w, int h)
{
  const vtkIdType n = scene->GetNumberOfPoints();
  std::array<double, 3> lo{}, hi{};
  for (int k = 0; k < 3; ++k)
  {
    std::vector<double> v(static_cast<std::size_t>(n));
    for (vtkIdType i = 0; i < n; ++i)
    {
      v[static_cast<std::size_t>(i)] = scene->GetPoint(i)[k];
    }
    std::sort(v.begin(), v.end());
    lo[k] = v[static_cast<std::size_t>(n / 20)];
    hi[k] = v[static_cast<std::size_t>(n - 1 - n / 20)];
  }
  double radius = 0;
  for (int k = 0; k < 3; ++k)
  {
    radius += 0.25 * (hi[k] - lo[k]) * (hi[k] - lo[k]);
  }
  radius = std::max(std::sqrt(radius), 1e-6);
  vis4gs::Camera cam;
  cam.Name = "synthetic";
  cam.Width = w;
  cam.Height = h;
  cam.Fx = cam.Fy = w / (2.0 * std::tan(M_PI / 6.0));
  cam.Cx = w / 2.0;
  cam.Cy = h / 2.0;
  // Identity rotation (OpenCV axes), centre at c - 2.5 r z.
  const double c[3] = { 0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2]) };
  cam.WorldToCamera[3] = -c[0];
  cam.WorldToCamera[7] = -c[1];
  cam.WorldToCamera[11] = -(c[2] - 2.5 * radius);
  return cam;
}

bool IsIndex(const std::string& s)
{
  return !s.empty() &&
    std::all_of(s.begin(), s.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
}

int Run(const Vis4GSArguments& args)
{
  const std::string scenePath = args.GetPositional("scene");
  if (vtkGaussianSession::IsTrainingLogPath(scenePath.c_str()))
  {
    throw std::runtime_error(scenePath +
      ": a training log; vis4gs render takes a scene file (vis4gs convert LOG scene.ply writes a "
      "snapshot as one)");
  }
  // The session's Gaussians port (no scores); its cameras port only with --cameras (the
  // default is a synthetic camera, not the cameras.json the session would find beside it).
  vtkNew<vtkGaussianSession> session;
  session->SetFileName(scenePath.c_str());
  session->ComputeScoresOff();
  session->SetCamerasFileName(args.Get("cameras").c_str());
  const std::string errors = Vis4GSUpdate(session, vtkGaussianSession::GaussiansPort);
  vtkPolyData* scene = session->GetGaussiansOutput();
  if (!errors.empty() || !scene || scene->GetNumberOfPoints() == 0)
  {
    throw std::runtime_error(errors.empty() ? scenePath + ": no Gaussians could be read" : errors);
  }

  std::vector<double> res;
  if (args.IsSet("resolution"))
  {
    res = args.GetNumbers("resolution");
    if (res.size() != 2 || !(res[0] >= 1) || !(res[1] >= 1) || res[0] > 65536 || res[1] > 65536)
    {
      throw std::runtime_error("--resolution needs two positive sizes W,H (at most 65536)");
    }
  }
  const std::vector<double> bg = args.GetNumbers("background");
  if (bg.size() != 3)
  {
    throw std::runtime_error("--background needs three components R,G,B");
  }
  const std::string precision = args.Get("precision");
  if (precision != "float" && precision != "double")
  {
    throw std::runtime_error("--precision must be float or double, not '" + precision + "'");
  }
  const int shDegree = args.GetInt("sh-degree");
  if (shDegree < -1 || shDegree > 3)
  {
    throw std::runtime_error("--sh-degree must be -1, 0, 1, 2 or 3");
  }

  vtkNew<vtkGaussianRasterizer> raster;
  raster->SetInputConnection(0, session->GetOutputPort(vtkGaussianSession::GaussiansPort));
  vtkNew<vtkTable> syntheticTable;
  const std::string camerasPath = args.Get("cameras");
  if (!camerasPath.empty())
  {
    // (The session's camera reader requires no image: rendering needs none.)
    const std::string cameraErrors = Vis4GSUpdate(session, vtkGaussianSession::CamerasPort);
    vtkTable* cameras = session->GetCamerasOutput();
    if (!cameraErrors.empty() || !cameras || cameras->GetNumberOfRows() == 0)
    {
      throw std::runtime_error(
        cameraErrors.empty() ? camerasPath + ": no cameras could be read" : cameraErrors);
    }
    raster->SetCamerasConnection(session->GetOutputPort(vtkGaussianSession::CamerasPort));
    const std::string which = args.Get("camera");
    if (IsIndex(which))
    {
      raster->SetCameraIndex(std::stoi(which));
    }
    else
    {
      raster->SetCameraName(which.c_str());
    }
  }
  else
  {
    const int w = res.empty() ? 800 : static_cast<int>(res[0]);
    const int h = res.empty() ? 600 : static_cast<int>(res[1]);
    vis4gs::CamerasToTable({ SyntheticCamera(scene, w, h) }, syntheticTable);
    raster->SetCamerasData(syntheticTable);
  }
  if (!res.empty())
  {
    raster->SetWidth(static_cast<int>(res[0]));
    raster->SetHeight(static_cast<int>(res[1]));
  }
  raster->SetBackground(bg[0], bg[1], bg[2]);
  raster->SetSHDegree(shDegree);
  raster->SetNumberOfThreads(std::max(0, args.GetInt("threads")));
  raster->SetPrecision(
    precision == "double" ? vtkGaussianRasterizer::DOUBLE : vtkGaussianRasterizer::FLOAT);
  raster->Update();
  vtkImageData* img = raster->GetOutput();
  vtkDataArray* rgb = img ? img->GetPointData()->GetArray("RGB") : nullptr;
  if (!rgb)
  {
    throw std::runtime_error("rendering failed (see the messages above)");
  }
  int dims[3];
  img->GetDimensions(dims);
  const int W = dims[0], H = dims[1];
  std::vector<unsigned char> pixels(static_cast<std::size_t>(W) * H * 3);
  for (int y = 0; y < H; ++y)
  {
    const int j = H - 1 - y; // VTK rows grow upwards
    for (int x = 0; x < W; ++x)
    {
      for (int c = 0; c < 3; ++c)
      {
        const double v = rgb->GetComponent(static_cast<vtkIdType>(j) * W + x, c);
        const double cl = std::isfinite(v) ? std::min(1.0, std::max(0.0, v)) : 0.0;
        pixels[(static_cast<std::size_t>(y) * W + x) * 3 + c] =
          static_cast<unsigned char>(std::lround(cl * 255.0));
      }
    }
  }
  const std::string output = args.Get("output");
  vis4gs::WritePng8(output, W, H, 3, pixels.data());
  std::cout << "vis4gs render: " << W << "x" << H << ", " << raster->GetNumberOfVisibleGaussians()
            << " of " << scene->GetNumberOfPoints() << " Gaussians visible";
  std::cout << " -> " << output << std::endl;
  const std::string special = raster->GetSpecialValuesSummary();
  if (!special.empty())
  {
    std::cout << "vis4gs render: special values (Documentation/special-values.md): " << special
              << std::endl;
  }
  return 0;
}

} // namespace

VIS4GS_REGISTER_COMMAND("render",
  "Render a scene from one camera with the exact CPU 3DGS rasteriser and write a PNG.",
  Define,
  Run)

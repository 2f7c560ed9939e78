// SPDX-License-Identifier: BSD-3-Clause
// Helpers shared by the RenderingSplats tests: real scenes from shared/data, cameras framing
// them, and reading back a render window as a top-row-first float RGB image.
#ifndef SplatTestHelpers_h
#define SplatTestHelpers_h

#include "Camera.h"
#include "GaussianCloud.h"
#include "GaussianIO.h"
#include "SplatCamera.h"
#include "Vis4GSTestData.h"

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace splattest
{

/// The Mip-Splatting donut (45,624 Gaussians, SH degree 0) or the INRIA PLY (9,080, SH 3).
inline vis4gs::GaussianCloud LoadScene(bool inria)
{
  const std::string path = vis4gs::testing::SharedDataPath(inria
      ? "inria_ply_tiny_kacytran/point_cloud/iteration_7000/point_cloud.ply"
      : "gs_ply_sh0_variant_donut_v3dg/fused.ply");
  return vis4gs::ReadGaussianPly(path);
}

/// A camera looking at the median of the means from @p distance times the 90 % extent, at
/// azimuth @p azimuth (radians about the world y axis) and a slight elevation.
inline vis4gs::Camera FrameScene(const vis4gs::GaussianCloud& cloud,
  int width,
  int height,
  double azimuth,
  double distance = 2.2,
  double viewAngle = 40.0)
{
  std::vector<float> c[3];
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      c[k].push_back(cloud.Positions[3 * i + k]);
    }
  }
  double center[3], extent = 0;
  for (int k = 0; k < 3; ++k)
  {
    auto v = c[k];
    std::sort(v.begin(), v.end());
    center[k] = v[v.size() / 2];
    extent = std::max(extent, static_cast<double>(v[v.size() * 95 / 100] - v[v.size() * 5 / 100]));
  }
  const double r = distance * extent;
  vis4gs::CameraLookAt l;
  l.Position = { center[0] + r * std::sin(azimuth) * std::cos(0.4),
    center[1] + r * std::sin(0.4),
    center[2] + r * std::cos(azimuth) * std::cos(0.4) };
  l.FocalPoint = { center[0], center[1], center[2] };
  l.ViewUp = { 0, 1, 0 };
  l.ViewAngle = viewAngle;
  return vis4gs::LookAtToCamera(l, width, height);
}

/// The window's back buffer as float RGB in [0, 1], row 0 at the TOP (rasteriser layout).
inline std::vector<float> ReadWindow(vtkRenderWindow* window)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  vtkImageData* img = grab->GetOutput();
  int dims[3];
  img->GetDimensions(dims);
  auto* px = vtkUnsignedCharArray::SafeDownCast(img->GetPointData()->GetScalars());
  std::vector<float> out(3 * static_cast<std::size_t>(dims[0]) * dims[1]);
  for (int y = 0; y < dims[1]; ++y)
  {
    for (int x = 0; x < dims[0]; ++x)
    {
      for (int ch = 0; ch < 3; ++ch)
      {
        out[3 * (static_cast<std::size_t>(dims[1] - 1 - y) * dims[0] + x) + ch] =
          px->GetValue(3 * (static_cast<vtkIdType>(y) * dims[0] + x) + ch) / 255.0f;
      }
    }
  }
  return out;
}

/// PSNR (dB) of two RGB images in [0, 1] (the reference is clamped to [0, 1] first).
inline double Psnr(const std::vector<float>& reference, const std::vector<float>& test)
{
  double mse = 0;
  for (std::size_t i = 0; i < reference.size(); ++i)
  {
    const double r = std::min(1.0f, std::max(0.0f, reference[i]));
    mse += (r - test[i]) * (r - test[i]);
  }
  mse /= static_cast<double>(reference.size());
  return mse > 0 ? 10.0 * std::log10(1.0 / mse) : 200.0;
}

} // namespace splattest

#endif

// SPDX-License-Identifier: BSD-3-Clause
#include "SplatCamera.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace vis4gs
{
namespace
{
constexpr double Pi = 3.14159265358979323846;

double Norm(const std::array<double, 3>& v)
{
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

std::array<double, 3> Cross(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}
} // namespace

//------------------------------------------------------------------------------
CameraLookAt CameraToLookAt(const Camera& camera, double focalDistance)
{
  if (camera.Width <= 0 || camera.Height <= 0 || !(camera.Fx > 0) || !(camera.Fy > 0) ||
    !std::isfinite(camera.Fx) || !std::isfinite(camera.Fy))
  {
    throw std::invalid_argument("camera '" + camera.Name + "': size " +
      std::to_string(camera.Width) + "x" + std::to_string(camera.Height) + " and focal lengths " +
      std::to_string(camera.Fx) + ", " + std::to_string(camera.Fy) + " must be positive");
  }
  for (double v : camera.WorldToCamera)
  {
    if (!std::isfinite(v))
    {
      throw std::invalid_argument("camera '" + camera.Name + "': non-finite world-to-camera");
    }
  }
  if (!(focalDistance > 0))
  {
    throw std::invalid_argument("CameraToLookAt: focal distance must be positive");
  }
  const auto& m = camera.WorldToCamera;
  CameraLookAt l;
  l.Position = camera.Center();
  // Rows of R are the camera axes in world coordinates.
  const std::array<double, 3> forward{ m[8], m[9], m[10] };
  const std::array<double, 3> down{ m[4], m[5], m[6] };
  for (int i = 0; i < 3; ++i)
  {
    l.FocalPoint[i] = l.Position[i] + focalDistance * forward[i];
    l.ViewUp[i] = -down[i];
  }
  l.ViewAngle = 2.0 * std::atan(camera.Height / (2.0 * camera.Fy)) * 180.0 / Pi;
  l.PixelAspect = camera.Fx / camera.Fy;
  return l;
}

//------------------------------------------------------------------------------
Camera LookAtToCamera(const CameraLookAt& lookAt, int width, int height)
{
  if (width <= 0 || height <= 0)
  {
    throw std::invalid_argument("LookAtToCamera: viewport " + std::to_string(width) + "x" +
      std::to_string(height) + " must be positive");
  }
  if (!(lookAt.ViewAngle > 0 && lookAt.ViewAngle < 180) || !(lookAt.PixelAspect > 0))
  {
    throw std::invalid_argument("LookAtToCamera: view angle " + std::to_string(lookAt.ViewAngle) +
      " must be in (0, 180) and the pixel aspect positive");
  }
  std::array<double, 3> f{};
  for (int i = 0; i < 3; ++i)
  {
    f[i] = lookAt.FocalPoint[i] - lookAt.Position[i];
  }
  const double fn = Norm(f);
  if (!(fn > 0) || !std::isfinite(fn))
  {
    throw std::invalid_argument("LookAtToCamera: position and focal point coincide");
  }
  for (auto& v : f)
  {
    v /= fn;
  }
  // Right = forward x up (OpenGL: x = view_dir x up), then the true up.
  auto right = Cross(f, lookAt.ViewUp);
  const double rn = Norm(right);
  if (!(rn > 1e-12 * Norm(lookAt.ViewUp)) || !std::isfinite(rn))
  {
    throw std::invalid_argument("LookAtToCamera: view up is parallel to the view direction");
  }
  for (auto& v : right)
  {
    v /= rn;
  }
  const auto up = Cross(right, f);
  Camera c;
  c.Name = "view";
  c.Width = width;
  c.Height = height;
  const double tanHalf = std::tan(lookAt.ViewAngle * Pi / 360.0);
  c.Fy = height / (2.0 * tanHalf);
  c.Fx = c.Fy * lookAt.PixelAspect;
  c.Cx = width / 2.0;
  c.Cy = height / 2.0;
  // OpenCV axes: x = right, y = -up, z = forward.
  const std::array<double, 3> rows[3] = { right, { -up[0], -up[1], -up[2] }, f };
  auto& m = c.WorldToCamera;
  for (int r = 0; r < 3; ++r)
  {
    m[4 * r + 0] = rows[r][0];
    m[4 * r + 1] = rows[r][1];
    m[4 * r + 2] = rows[r][2];
    m[4 * r + 3] = -(rows[r][0] * lookAt.Position[0] + rows[r][1] * lookAt.Position[1] +
      rows[r][2] * lookAt.Position[2]);
  }
  m[12] = m[13] = m[14] = 0;
  m[15] = 1;
  return c;
}

//------------------------------------------------------------------------------
std::array<double, 16> GLViewToWorldToCamera(const std::array<double, 16>& view)
{
  std::array<double, 16> w = view;
  for (int c = 0; c < 4; ++c)
  {
    w[4 + c] = -view[4 + c];
    w[8 + c] = -view[8 + c];
  }
  return w;
}

//------------------------------------------------------------------------------
std::array<double, 16> GLProjectionMatrix(int width,
  int height,
  double fx,
  double fy,
  double zNear,
  double zFar)
{
  std::array<double, 16> p{};
  p[0] = 2.0 * fx / width;
  p[5] = 2.0 * fy / height;
  p[10] = -(zFar + zNear) / (zFar - zNear);
  p[11] = -2.0 * zFar * zNear / (zFar - zNear);
  p[14] = -1.0;
  return p;
}

//------------------------------------------------------------------------------
std::array<double, 3> ProjectToPixel(const Camera& camera, const std::array<double, 3>& p)
{
  const auto& m = camera.WorldToCamera;
  double t[3];
  for (int r = 0; r < 3; ++r)
  {
    t[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
  }
  // ndc = (fx x / z) / (W/2) ; u = ((ndc + 1) W - 1) / 2 = fx x / z + (W - 1) / 2.
  return { camera.Fx * t[0] / t[2] + (camera.Width - 1) / 2.0,
    camera.Fy * t[1] / t[2] + (camera.Height - 1) / 2.0,
    t[2] };
}

} // namespace vis4gs

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatCamera.h
 * @brief Conversions between a vis4gs::Camera (OpenCV axes: +x right, +y down, +z forward,
 * row-major world-to-camera, pinhole fx, fy, principal point at the image centre as the
 * reference rasteriser assumes) and the look-at form of an OpenGL/VTK camera (position,
 * focal point, view up, vertical view angle; the camera looks down its -z with +y up).
 *
 * Pixel conventions: the rasteriser samples pixel (x, y) at integer coordinates with row 0
 * at the top; an OpenGL window has row 0 at the bottom and pixel centres at +0.5. Pixel
 * (x, y) of the rasteriser is OpenGL window pixel (x, H - 1 - y).
 */
#ifndef vis4gs_SplatCamera_h
#define vis4gs_SplatCamera_h

#include "Camera.h"

#include <array>

namespace vis4gs
{

/// A camera in look-at form (OpenGL/VTK conventions).
struct CameraLookAt
{
  std::array<double, 3> Position{ 0, 0, 0 };
  std::array<double, 3> FocalPoint{ 0, 0, -1 };
  std::array<double, 3> ViewUp{ 0, 1, 0 };
  /// Full vertical field of view in degrees: 2 atan(H / (2 fy)).
  double ViewAngle = 30.0;
  /// fx / fy: 1 for square pixels. A look-at camera with a view angle has square pixels; other
  /// values need an explicit projection matrix (see GLProjectionMatrix()).
  double PixelAspect = 1.0;
};

/**
 * Look-at form of @p camera: position = centre -R^T t, focal point at @p focalDistance along
 * the viewing direction (+z of the camera), view up = -(camera +y) in world coordinates.
 * Throws std::invalid_argument for a non-positive size or focal length or a non-finite pose.
 */
CameraLookAt CameraToLookAt(const Camera& camera, double focalDistance = 1.0);

/**
 * The vis4gs::Camera that renders what an OpenGL camera in look-at form shows in a
 * @p width x @p height viewport: fy = H / (2 tan(angle/2)), fx = fy * PixelAspect, principal
 * point stored as (W/2, H/2) (the rasteriser uses the centre anyway), W2C from the
 * orthonormalised look-at frame. Throws std::invalid_argument for degenerate input
 * (coincident position and focal point, view up parallel to the view direction, angle not in
 * (0, 180), non-positive size).
 */
Camera LookAtToCamera(const CameraLookAt& lookAt, int width, int height);

/// Row-major OpenCV world-to-camera from a row-major OpenGL view matrix (camera looking down
/// -z, +y up): diag(1, -1, -1, 1) * view.
std::array<double, 16> GLViewToWorldToCamera(const std::array<double, 16>& view);

/**
 * Row-major OpenGL projection matrix that shows exactly the rasteriser's image of a
 * @p width x @p height view with focal lengths @p fx, @p fy and the principal point at the
 * centre, for depths in [@p zNear, @p zFar]: P00 = 2 fx / W, P11 = 2 fy / H, the usual GL
 * depth rows.
 */
std::array<double, 16> GLProjectionMatrix(int width,
  int height,
  double fx,
  double fy,
  double zNear,
  double zFar);

/// The rasteriser's pixel position (u, v) of world point @p p seen by @p camera
/// (reference §2.3 step 9, in double), and the view depth in the third entry.
std::array<double, 3> ProjectToPixel(const Camera& camera, const std::array<double, 3>& p);

} // namespace vis4gs

#endif

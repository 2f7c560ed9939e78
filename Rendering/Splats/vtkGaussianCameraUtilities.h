/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianCameraUtilities.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianCameraUtilities
 * @brief   Sets a VTK camera from a 3DGS training camera and back.
 *
 * A vis4gs::Camera (DESIGN §2: OpenCV axes, row-major world-to-camera W2C, pinhole fx, fy,
 * principal point at the image centre as the reference rasteriser assumes) becomes a
 * vtkCamera with position = camera centre, focal point one unit along the viewing direction,
 * view up = -(camera +y), vertical view angle 2 atan(H / (2 fy)). With square pixels
 * (fx == fy) and a viewport of the camera's aspect ratio, a world point then lands on the
 * same pixel in VTK as in the rasteriser; non-square pixels are applied through an explicit
 * projection matrix. The conversions themselves are Core/Splats/SplatCamera.h.
 *
 * Pixel conventions: the rasteriser's pixel (x, y) (row 0 at the top) is VTK display pixel
 * (x, H - 1 - y).
 */
#ifndef vtkGaussianCameraUtilities_h
#define vtkGaussianCameraUtilities_h

#include "vis4gsRenderingSplatsModule.h" // For export macro
#include "vtkObject.h"

#ifndef __VTK_WRAP__
#include "Camera.h" // For vis4gs::Camera
#include <array>    // For std::array
#endif

class vtkCamera;
class vtkMatrix4x4;
class vtkRenderer;
class vtkTable;

class VIS4GSRENDERINGSPLATS_EXPORT vtkGaussianCameraUtilities : public vtkObject
{
public:
  static vtkGaussianCameraUtilities* New();
  vtkTypeMacro(vtkGaussianCameraUtilities, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Sets @p camera to the pinhole view (width, height, fx, fy, row-major world-to-camera
   * @p worldToCamera in OpenCV axes). Returns false (with an error) for invalid input.
   * Clipping range: [0.01, 1000] times the distance unit, adjust with ResetCameraClippingRange.
   */
  static bool SetCamera(vtkCamera* camera,
    int width,
    int height,
    double fx,
    double fy,
    vtkMatrix4x4* worldToCamera);

  /**
   * Sets @p renderer's active camera to row @p row of a camera table (DESIGN §2, as made by
   * vis4gs::CamerasToTable) and resets the clipping range to the visible props ("jump to a
   * training camera"). The render window is not resized. Returns false for a missing row
   * or column.
   */
  static bool JumpToCamera(vtkRenderer* renderer, vtkTable* cameras, vtkIdType row);

  /**
   * Projects world point @p p with @p renderer's active camera to VTK display coordinates
   * (x right, y up, pixel centres at integers) and converts them to the rasteriser's pixel
   * convention (row 0 at the top): @p pixel = (x, H - 1 - y).
   */
  static void WorldToRasterPixel(vtkRenderer* renderer, const double p[3], double pixel[2]);

#ifndef __VTK_WRAP__
  /// Sets @p camera from @p view (throws std::invalid_argument for an invalid camera).
  static void ApplyCamera(const vis4gs::Camera& view, vtkCamera* camera);

  /**
   * The vis4gs::Camera that the rasteriser needs to render what @p camera shows in a
   * @p width x @p height viewport (square pixels unless an explicit projection is set).
   * Throws std::invalid_argument for a parallel projection or a degenerate camera.
   */
  static vis4gs::Camera FromVTKCamera(vtkCamera* camera, int width, int height);

  /// A pinhole vis4gs::Camera of @p width x @p height with focal lengths @p fx, @p fy, the
  /// principal point at the image centre and the row-major @p worldToCamera (not checked).
  static vis4gs::Camera PinholeCamera(int width,
    int height,
    double fx,
    double fy,
    const std::array<double, 16>& worldToCamera);
#endif

protected:
  vtkGaussianCameraUtilities() = default;
  ~vtkGaussianCameraUtilities() override = default;

private:
  vtkGaussianCameraUtilities(const vtkGaussianCameraUtilities&) = delete;
  void operator=(const vtkGaussianCameraUtilities&) = delete;
};

#endif

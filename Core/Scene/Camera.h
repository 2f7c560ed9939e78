// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Camera.h
 * @brief One training or test view: pinhole intrinsics, world-to-camera pose, image.
 *
 * Conventions are COLMAP/OpenCV (DESIGN §2, reference §1.3): +x right, +y down, +z forward,
 * X_cam = R X_world + t. Rendering follows the reference rasteriser, which derives the field
 * of view from fx, fy and the image size and puts the principal point at the image centre.
 */
#ifndef vis4gs_Camera_h
#define vis4gs_Camera_h

#include <array>
#include <string>
#include <vector>

namespace vis4gs
{

enum class CameraSplit : unsigned char
{
  Train = 0,
  Test = 1
};

struct Camera
{
  std::string Name; ///< image name without extension (the trainer's image_name)
  CameraSplit Split = CameraSplit::Train;
  int Width = 0;
  int Height = 0;
  double Fx = 0, Fy = 0, Cx = 0, Cy = 0;
  /// Row-major 4x4 world-to-camera matrix.
  std::array<double, 16> WorldToCamera{ 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  /// Path of the training image (absolute, relative to the dataset, or "/images/<name>").
  std::string ImagePath;
  /// COLMAP model name ("PINHOLE", "SIMPLE_RADIAL", ...); empty when unknown.
  std::string Model;
  /// Distortion parameters in COLMAP order; empty for pinhole models.
  std::vector<double> Distortion;

  /// Camera centre in world coordinates, -R^T t.
  std::array<double, 3> Center() const;
  /// tan of half the horizontal / vertical field of view.
  double TanHalfFovX() const { return this->Width / (2.0 * this->Fx); }
  double TanHalfFovY() const { return this->Height / (2.0 * this->Fy); }
  /// The same view at another resolution, keeping the field of view (as the trainer does).
  Camera Resized(int width, int height) const;
};

} // namespace vis4gs

#endif

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SyntheticScene.h
 * @brief Procedural ground-truth Gaussian scenes for training: textured objects (torus,
 * sphere, box, thin cylinder, plane, background shell) covered by flat surface Gaussians,
 * cameras on configurable paths (orbits and elevation arcs, with deliberately sparse
 * regions), training and test images rendered with the forward rasteriser (Core/Render),
 * and a sparse, noisy initial point cloud with outliers, standing in for SfM points.
 *
 * The scene description is JSON (Data/Scenes/README.md documents every key). Everything is
 * derived from the description's seed: the same description gives the same scene, cameras,
 * images and points on every run.
 *
 * Conventions: world +z is up; cameras are OpenCV (x right, y down, z forward) and look at
 * their target with the world up projected to image up; the principal point is the centre.
 */
#ifndef vis4gs_SyntheticScene_h
#define vis4gs_SyntheticScene_h

#include "Camera.h"
#include "GaussianCloud.h"

#include <array>
#include <string>
#include <vector>

namespace vis4gs
{

struct SyntheticScene
{
  std::string Name;
  GaussianCloud Truth;                    ///< the ground-truth Gaussians (SH degree 0)
  std::vector<Camera> Cameras;            ///< train and test views, in description order
  std::vector<std::vector<float>> Images; ///< RGB float [0,1] per camera, row 0 at the top
  std::vector<float> PointPositions;      ///< initial points, xyz
  std::vector<float> PointColors;         ///< their colours, RGB [0,1]
  std::array<double, 3> Background{ 0, 0, 0 };
};

struct SyntheticOptions
{
  /// Overrides the description's image size when > 0 (keeps the field of view).
  int Width = 0;
  int Height = 0;
  /// Skip rendering the images (cameras and points only).
  bool RenderImages = true;
  int Threads = 0;
};

/// Builds a scene from a JSON description held in @p text; @p name is used in messages.
/// Throws std::runtime_error naming @p name and the offending key on a bad description.
SyntheticScene MakeSyntheticScene(const std::string& text,
  const std::string& name,
  const SyntheticOptions& options = {});

/// Same, reading the description from @p path.
SyntheticScene LoadSyntheticScene(const std::string& path, const SyntheticOptions& options = {});

/// Camera at @p eye looking at @p target (world up +z), focal from the horizontal FoV.
Camera LookAtCamera(const std::array<double, 3>& eye,
  const std::array<double, 3>& target,
  int width,
  int height,
  double fovXDegrees);

} // namespace vis4gs

#endif

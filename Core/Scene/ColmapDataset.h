// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ColmapDataset.h
 * @brief A COLMAP dataset folder as the original trainer reads it (reference §1.4):
 * `<root>/sparse/0` (or `<root>/sparse`) and `<root>/images`.
 *
 * Cameras are sorted by image name; with Eval, every LlffHold-th camera (index % 8 == 0) is a
 * test view. Resolution follows the trainer's `--resolution`: -1 (default) shrinks images
 * wider than 1600 px to 1600 px wide; 1, 2, 4, 8 divide the size (rounded half to even, as
 * Python's round) and read `images_N` when that folder exists; any other positive value is a
 * target width. The field of view is kept, so focal lengths and principal points scale with
 * the size. Distorted models are read with their parameters, and a single warning says that
 * rendering is pinhole.
 */
#ifndef vis4gs_ColmapDataset_h
#define vis4gs_ColmapDataset_h

#include "Camera.h"

#include <string>
#include <utility>
#include <vector>

namespace vis4gs
{

struct DatasetOptions
{
  /// Split train/test (the trainer's --eval); off: every camera is Train.
  bool Eval = false;
  /// Every LlffHold-th camera (in name order, starting with the first) is a test view.
  int LlffHold = 8;
  /// The trainer's --resolution (-1, 1, 2, 4, 8 or a target width).
  int Resolution = -1;
  /// Image folder relative to the root, or absolute (the trainer's --images).
  std::string Images = "images";
  /// Require every camera's image file to exist (error naming the camera otherwise).
  bool RequireImages = true;
};

struct Dataset
{
  std::string Root;
  std::string SparseFolder;
  std::string ImageFolder;
  /// Sorted by name, at training resolution, ImagePath absolute (or root-relative).
  std::vector<Camera> Cameras;
  /// Original (full-size) width and height of each camera, same order.
  std::vector<std::pair<int, int>> OriginalSizes;
  /// points3D as the initial point cloud: xyz (float32, as the trainer stores it) and RGB.
  std::vector<float> PointPositions;
  std::vector<unsigned char> PointColors;
  /// True when a camera model is not a pinhole (its parameters are in Camera::Distortion).
  bool Distorted = false;
  /// Messages for the user (distortion, down-scaling), each given once.
  std::vector<std::string> Warnings;
};

/// Training resolution of a @p width x @p height image for the trainer's --resolution.
std::pair<int, int> TrainingResolution(int width, int height, int resolution);

/// Loads a COLMAP dataset folder; throws std::runtime_error naming the file at fault.
Dataset LoadColmapDataset(const std::string& root, const DatasetOptions& options = {});

} // namespace vis4gs

#endif

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TrainingData.h
 * @brief Loads what the trainer reads: a COLMAP dataset folder (reference §1.4; points3D as
 * the initial point cloud, images at training resolution) or a synthetic scene description
 * (Core/Synthetic, JSON).
 */
#ifndef vis4gs_TrainingData_h
#define vis4gs_TrainingData_h

#include "Trainer.h"

#include <string>
#include <vector>

namespace vis4gs
{

struct TrainingDataOptions
{
  /// COLMAP: the trainer's --resolution (-1 = at most 1600 px wide; 1, 2, 4, 8; else a
  /// width). Synthetic: a width overriding the description's (height keeps the aspect);
  /// -1 or 0 keeps the description's size.
  int Resolution = -1;
  /// COLMAP: hold out every 8th view as a test view (the trainer's --eval). Synthetic scenes
  /// name their test views themselves.
  bool Eval = true;
  /// Background composited behind the Gaussians and behind transparent training images.
  bool WhiteBackground = false;
  int Threads = 0;
};

/// Loads @p path: a NeRF-synthetic / instant-ngp folder or transforms*.json (TransformsJson.h,
/// started from 10,000 random grey points in [-1.3, 1.3]^3), a ".json" file a synthetic scene
/// description, a folder a COLMAP dataset.
/// Throws std::runtime_error naming the path and the problem.
TrainingData LoadTrainingData(const std::string& path, const TrainingDataOptions& options = {});

} // namespace vis4gs

#endif

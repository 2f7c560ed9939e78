// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSSceneCameras.h
 * @brief The cameras of a Gaussian scene file, for `vis4gs analyze` and `vis4gs view`.
 */
#ifndef Vis4GSSceneCameras_h
#define Vis4GSSceneCameras_h

#include "Camera.h"
#include "ImageIO.h"

#include <cstddef>

#include <string>
#include <vector>

/**
 * The cameras of the scene file @p scene: @p cameras names a cameras.json, a COLMAP dataset
 * folder (sparse/0; images not required), or a NeRF-synthetic / instant-ngp transforms*.json
 * or folder (TransformsJson.h; detected by content, frames without image need w/h); empty looks for
 * cameras.json next to @p scene and two folders up (the INRIA model layout,
 * point_cloud/iteration_N/point_cloud.ply). Returns none when nothing is found; the readers throw
 * std::runtime_error naming the file when one cannot be read.
 */
std::vector<vis4gs::Camera> Vis4GSFindSceneCameras(const std::string& scene,
  const std::string& cameras);

/**
 * Sets each camera's ImagePath to the file of @p folder whose name up to its first dot is the
 * camera's name (`--images=DIR`), empty where none matches; throws std::runtime_error when
 * @p folder is no folder. Shared by `vis4gs analyze` and `vis4gs repair`.
 */
void Vis4GSAttachImagesByName(std::vector<vis4gs::Camera>& cameras, const std::string& folder);

/**
 * The image of @p camera for a before/after measurement (RemovalEffect.h's
 * TrainingImageProvider): false when the camera names no existing file; a file that cannot be
 * read throws std::runtime_error naming it. Shared by `analyze --report` and the view's
 * clean-up panel.
 */
bool Vis4GSLoadViewImage(std::size_t index, const vis4gs::Camera& camera, vis4gs::Image& image);

#endif

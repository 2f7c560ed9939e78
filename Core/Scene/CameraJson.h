// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CameraJson.h
 * @brief The original trainer's `cameras.json` (reference §1.2).
 *
 * Each entry holds `img_name`, `width`, `height`, `position` (the camera centre in world
 * coordinates), `rotation` (3x3 rows, the camera-to-world rotation R^T) and `fx`, `fy`. The
 * reader rebuilds the world-to-camera matrix [R | -R C]; there is no principal point, so
 * cx = width/2, cy = height/2 (what the trainer assumes) unless the entry has `cx`/`cy`.
 * The file does not say which cameras are test views: every camera is marked Train.
 */
#ifndef vis4gs_CameraJson_h
#define vis4gs_CameraJson_h

#include "Camera.h"

#include <cstddef>
#include <string>
#include <vector>

namespace vis4gs
{

/// Reads a cameras.json; throws std::runtime_error naming the file and the entry at fault.
std::vector<Camera> ReadCamerasJson(const std::string& path);

/// Same, from memory; @p name is used in messages.
std::vector<Camera> ReadCamerasJsonFromMemory(const void* data,
  std::size_t size,
  const std::string& name);

/// Writes cameras in the trainer's format (ids in list order, no cx/cy).
void WriteCamerasJson(const std::string& path, const std::vector<Camera>& cameras);

} // namespace vis4gs

#endif

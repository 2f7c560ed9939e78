// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TransformsJson.h
 * @brief Cameras of Blender/NeRF-synthetic and instant-ngp `transforms*.json` files.
 *
 * `frames[].transform_matrix` is camera-to-world in OpenGL axes (x right, y up, z backward);
 * the reader flips the camera's y and z axes and inverts, giving the project's OpenCV
 * world-to-camera matrix (Camera.h), as the original trainer's readCamerasFromTransforms does.
 * Intrinsics: `fl_x`/`fl_y` (fl_y defaults to fl_x), else `camera_angle_x` (fx = 0.5 w /
 * tan(0.5 angle_x)) and `camera_angle_y` if present (else fy = fx); `cx`/`cy` default to the
 * image centre; `w`/`h` give the size, else the image file does. Every key may also appear in
 * a frame, overriding the top level (instant-ngp's per-frame intrinsics). `file_path` is
 * relative to the json's folder, with or without extension (NeRF-synthetic omits `.png`).
 * Frames whose image is missing are skipped with one warning naming how many (as instant-ngp
 * does) unless RequireImages is false and the size is known. Non-zero distortion keys
 * (k1, k2, k3, k4, p1, p2) are ignored with one warning. A camera's Name is the stem of its
 * `file_path`; a repeated stem (train/r_0 and test/r_0) takes its folder as a prefix
 * ("test_r_0"), then "_1", "_2"... so that names stay unique (they key the training log).
 */
#ifndef vis4gs_TransformsJson_h
#define vis4gs_TransformsJson_h

#include "Camera.h"

#include <cstddef>
#include <string>
#include <vector>

namespace vis4gs
{

struct TransformsOptions
{
  /// Skip frames whose image file is missing (default); false keeps them when w/h are known.
  bool RequireImages = true;
  /// Split given to every camera of one file.
  CameraSplit Split = CameraSplit::Train;
};

struct TransformsCameras
{
  std::vector<Camera> Cameras;
  std::vector<std::string> Warnings;
};

/// True when @p path is a JSON object with a `frames` list (detection by content).
bool IsTransformsJson(const std::string& path);

/// Reads one transforms*.json; throws std::runtime_error naming the file and the frame.
TransformsCameras ReadTransformsJson(const std::string& path,
  const TransformsOptions& options = {});

/// Same from memory; @p name is used in messages, @p folder resolves `file_path`.
TransformsCameras ReadTransformsJsonFromMemory(const void* data,
  std::size_t size,
  const std::string& name,
  const std::string& folder,
  const TransformsOptions& options = {});

/// True when @p folder holds transforms_train.json or transforms.json.
bool IsTransformsFolder(const std::string& folder);

/**
 * A NeRF-synthetic folder: transforms_train.json -> Train, transforms_test.json -> Test
 * (transforms_val.json is ignored, as the original trainer does); or a single transforms.json
 * (instant-ngp) -> all Train. A file argument is read as one file, all Train.
 */
TransformsCameras LoadTransformsDataset(const std::string& path, bool requireImages = true);

} // namespace vis4gs

#endif

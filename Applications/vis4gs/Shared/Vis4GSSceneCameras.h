// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSSceneCameras.h
 * @brief The cameras of a Gaussian scene file as the commands and the comparison window read
 * them (through vtkGaussianSession's camera reader), and their training images.
 */
#ifndef Vis4GSSceneCameras_h
#define Vis4GSSceneCameras_h

#include "Camera.h"
#include "ImageIO.h"

#include <cstddef>

#include <string>
#include <vector>

class vtkGaussianCameraReader;

/**
 * Sets @p reader to read cameras as the commands and the comparison window do: no image
 * required (a camera without one is rendered, and measured without it), cameras.json without
 * the images/ folder beside it (--images matches files by name instead).
 */
void Vis4GSSceneCameraRules(vtkGaussianCameraReader* reader);

/**
 * Sets each camera's ImagePath to the file of @p folder whose name up to its first dot is the
 * camera's name (`--images=DIR`), empty where none matches, by the filters' rule
 * (Vis4GSMatchImagesByName, Filters/Diagnostics); throws std::runtime_error when @p folder is
 * no folder. Shared by `vis4gs analyze`, `vis4gs repair` and the application.
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

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SceneIds.h
 * @brief The ids of a scene file read "with its ids when it has them" (the commands, and
 * vtkGaussianSceneReader's IdPropertyOptional).
 */
#ifndef vis4gs_SceneIds_h
#define vis4gs_SceneIds_h

#include "GaussianCloud.h"

#include <string>

namespace vis4gs
{
/**
 * Sets @p cloud's Ids from its extra property @p name when it has one (a scene written with ids
 * by `analyze --delete` or saved from a log, read without GaussianReadOptions::IdProperty);
 * returns whether it had. The property is kept. Throws std::runtime_error naming @p path and the
 * vertex for a value that is no integer.
 */
bool IdsFromExtraProperty(GaussianCloud& cloud, const std::string& name, const std::string& path);
}

#endif

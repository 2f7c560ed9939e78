// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSStateFiles.h
 * @brief What `vis4gs compare` and `vis4gs repair` read alike (issue 20): a scene file with its
 * Gaussians' ids, and the training images of a log's cameras.
 */
#ifndef Vis4GSStateFiles_h
#define Vis4GSStateFiles_h

#include "ArtifactScores.h" // TrainingImageProvider
#include "GaussianCloud.h"
#include "TrainingLogReader.h"

#include <memory>
#include <string>

/**
 * Reads a scene (PLY, SPZ, .splat) whose "id" property, when it has one (written by
 * analyze --delete and by any scene saved from a log), becomes GaussianCloud::Ids; a scene
 * without it numbers its Gaussians 0..N-1. Warnings go to std::cerr prefixed by @p command.
 * Throws std::runtime_error naming the file for a non-integer id.
 */
vis4gs::GaussianCloud Vis4GSReadSceneWithIds(const std::string& path, const std::string& command);

/// Training images: a camera's "/images/<name>" from @p log (when given), else its image file.
vis4gs::TrainingImageProvider Vis4GSLogImages(std::shared_ptr<vis4gs::TrainingLogReader> log);

#endif

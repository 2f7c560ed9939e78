// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSStateFiles.h
 * @brief What the commands and the application read alike: whether a path is a training log,
 * a scene file with its Gaussians' ids, and the training images of a log's cameras.
 */
#ifndef Vis4GSStateFiles_h
#define Vis4GSStateFiles_h

#include "ArtifactScores.h" // TrainingImageProvider
#include "GaussianCloud.h"
#include "TrainingLogReader.h"

#include <memory>
#include <string>

/// Whether @p path names a training log (DESIGN §3): extension .h5 or .hdf5, any case.
bool Vis4GSIsLogPath(const std::string& path);

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

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSStateFiles.h
 * @brief What the commands and the application read alike: whether a path is a training log.
 * (A scene file with its ids, and the training images of a log's cameras, are read by the
 * session: vtkGaussianSceneReader's IdPropertyOptional, Vis4GSTrainingImages.)
 */
#ifndef Vis4GSStateFiles_h
#define Vis4GSStateFiles_h

#include "ArtifactScores.h" // TrainingImageProvider
#include "GaussianCloud.h"
#include "TrainingLogReader.h"

#include <memory>
#include <string>

/// Whether @p path names a training log (DESIGN §3): the HDF5 signature, or the extension .h5
/// or .hdf5, any case (vtkGaussianSession::IsTrainingLogPath(), the session's own rule).
bool Vis4GSIsLogPath(const std::string& path);

#endif

/*=========================================================================

  Program:   Vis4GS
  Module:    Vis4GSTrainingImages.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @file Vis4GSTrainingImages.h
 * @brief Where the filters that compare renders with the training images find those images
 * (vtkGaussianArtifactScoreFilter, vtkGaussianRemovalEffectFilter): one rule for every filter.
 *
 * A camera's image is the file named in the camera table's `Image` column, read with the Core
 * image reader (resized to the camera's size as the trainer does); when an image folder is
 * given, it is instead the file of that folder whose name up to the first '.' is the camera's
 * Name (none: the camera has no image). "/images/<name>" paths of a camera table that names its
 * training log (field data vis4gs::arrays::CameraTrainingLogFile, as vtkGaussianTrainingLogReader
 * writes it) are read from the log by the view's render, never through temporary files.
 */
#ifndef Vis4GSTrainingImages_h
#define Vis4GSTrainingImages_h

#include "vis4gsFiltersDiagnosticsModule.h" // For export macro

#include "ArtifactScores.h" // For vis4gs::TrainingImageProvider
#include "Camera.h"         // For vis4gs::Camera

#include <array>  // For the background
#include <string> // For the folder
#include <vector> // For the cameras

class vtkTable;

/**
 * Sets each camera's ImagePath to the regular file of @p folder whose name up to its first '.'
 * is the camera's Name (the trainer's image_name), empty where none matches: the rule of every
 * filter's ImageDirectory, and of the commands' and the application's `--images`. False, with
 * the reason in @p error, when @p folder is not a folder.
 */
VIS4GSFILTERSDIAGNOSTICS_EXPORT bool Vis4GSMatchImagesByName(std::vector<vis4gs::Camera>& cameras,
  const std::string& folder,
  std::string& error);

/**
 * Points @p cameras (read from @p table) at their images and returns in @p images the provider
 * that reads them with @p background behind transparent pixels. False, with the reason in
 * @p error, when @p imageDirectory is given and is not a folder, or when the log the table names
 * cannot be opened.
 */
VIS4GSFILTERSDIAGNOSTICS_EXPORT bool Vis4GSTrainingImages(vtkTable* table,
  const std::string& imageDirectory,
  const std::array<float, 3>& background,
  std::vector<vis4gs::Camera>& cameras,
  vis4gs::TrainingImageProvider& images,
  std::string& error);

#endif

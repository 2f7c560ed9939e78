// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSSceneCameras.h"

#include "TrainingLogReader.h"

#include "Vis4GSTrainingImages.h"
#include "vtkGaussianCameraReader.h"

#include <stdexcept>

void Vis4GSSceneCameraRules(vtkGaussianCameraReader* reader)
{
  // Rendering and measuring need no image: a camera without one is measured without it.
  reader->RequireImagesOff();
  // cameras.json keeps its cameras' own image paths (--images matches files by name instead);
  // a COLMAP dataset still finds its images/ ("" is its default folder).
  reader->SetImageFolder("");
}

bool Vis4GSLoadViewImage(std::size_t, const vis4gs::Camera& camera, vis4gs::Image& image)
{
  return vis4gs::LoadCameraImage(nullptr, camera, image);
}

void Vis4GSAttachImagesByName(std::vector<vis4gs::Camera>& cameras, const std::string& folder)
{
  // The filters' rule (their ImageDirectory), so that a command's --images and its filters agree.
  std::string error;
  if (!Vis4GSMatchImagesByName(cameras, folder, error))
  {
    throw std::runtime_error(folder + ": --images is not a folder");
  }
}

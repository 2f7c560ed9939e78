/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianCameraReader.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianCameraReader
 * @brief   Reads the cameras of a 3DGS scene as the camera vtkTable of DESIGN §2 (one row per
 * view: Name, Split, Width, Height, Fx, Fy, Cx, Cy, WorldToCamera, Image, Model, Distortion).
 *
 * FileName is either the trainer's `cameras.json` (a file) or a COLMAP dataset folder
 * (`<folder>/sparse/0` or `<folder>/sparse`, images in `<folder>/images`). For COLMAP the
 * cameras are sorted by image name, Eval marks every LLFFHold-th camera as a test view, and
 * Resolution scales them like the trainer's `--resolution` (-1: at most 1600 px wide; 1, 2,
 * 4, 8: divided, reading `images_N` when it exists; other positive values: target width).
 * A distorted COLMAP model is read with its distortion parameters and a single warning.
 * For cameras.json, image files in ImageFolder (when it exists) are matched to cameras by name;
 * with RequireImages off a camera without a matching file keeps no image instead of failing.
 * FileName may also be a NeRF-synthetic / instant-ngp `transforms*.json` (any JSON object with
 * `frames`) or a folder holding transforms_train.json (+ transforms_test.json: Test) or
 * transforms.json (Core/Scene/TransformsJson.h); RequireImages off keeps frames whose image
 * is missing when the file gives `w`/`h`.
 *
 * FindSceneCamerasFile() is the one rule for the cameras of a scene file given without them
 * (vtkGaussianSession, the commands, the comparison window): the trainer's cameras.json beside
 * the scene or two folders up.
 *
 * Errors (missing files, bad records, cameras without images) are reported with
 * vtkErrorMacro naming the file and the problem. The parsing is done by Core/Scene
 * (CameraJson.h, ColmapDataset.h).
 */
#ifndef vtkGaussianCameraReader_h
#define vtkGaussianCameraReader_h

#include "vis4gsIOSceneModule.h" // For export macro
#include "vtkTableAlgorithm.h"

#include <string> // For std::string

class VIS4GSIOSCENE_EXPORT vtkGaussianCameraReader : public vtkTableAlgorithm
{
public:
  static vtkGaussianCameraReader* New();
  vtkTypeMacro(vtkGaussianCameraReader, vtkTableAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * A cameras.json file or a COLMAP dataset folder. Default: none.
   */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /**
   * Split the COLMAP cameras into train and test views like the trainer's --eval.
   * Default: off (every camera is a training view).
   */
  vtkSetMacro(Eval, bool);
  vtkGetMacro(Eval, bool);
  vtkBooleanMacro(Eval, bool);
  ///@}

  ///@{
  /**
   * Every LLFFHold-th camera (in name order, starting with the first) is a test view when
   * Eval is on. Default: 8.
   */
  vtkSetClampMacro(LLFFHold, int, 1, VTK_INT_MAX);
  vtkGetMacro(LLFFHold, int);
  ///@}

  ///@{
  /**
   * The trainer's --resolution for COLMAP datasets. Default: -1.
   */
  vtkSetMacro(Resolution, int);
  vtkGetMacro(Resolution, int);
  ///@}

  ///@{
  /**
   * Image folder, absolute or relative to the COLMAP dataset folder / the folder of
   * cameras.json. For cameras.json, when the folder exists its files are matched to the
   * cameras by name (a camera without an image is then an error); when it does not exist the
   * cameras have no images. Default: "images".
   */
  vtkSetStdStringFromCharMacro(ImageFolder);
  vtkGetCharFromStdStringMacro(ImageFolder);
  ///@}

  ///@{
  /**
   * Fail when a camera has no image file (COLMAP; cameras.json when ImageFolder exists; a
   * transforms frame without w/h always needs its image). Off for uses that need no image,
   * such as rendering. Default: on.
   */
  vtkSetMacro(RequireImages, bool);
  vtkGetMacro(RequireImages, bool);
  vtkBooleanMacro(RequireImages, bool);
  ///@}

  /**
   * The cameras file of the scene file @p scene when none is given: `cameras.json` beside it or
   * two folders up (the trainer's `<model>/point_cloud/iteration_N/point_cloud.ply`), the first
   * that is a regular file; empty when neither is.
   */
  static std::string FindSceneCamerasFile(const std::string& scene);

  ///@{
  /**
   * After an update: whether the dataset uses a distorted camera model.
   */
  vtkGetMacro(Distorted, bool);
  ///@}

protected:
  vtkGaussianCameraReader();
  ~vtkGaussianCameraReader() override = default;

  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  std::string FileName;
  bool Eval = false;
  int LLFFHold = 8;
  int Resolution = -1;
  std::string ImageFolder = "images";
  bool RequireImages = true;
  bool Distorted = false;

private:
  vtkGaussianCameraReader(const vtkGaussianCameraReader&) = delete;
  void operator=(const vtkGaussianCameraReader&) = delete;
};

#endif

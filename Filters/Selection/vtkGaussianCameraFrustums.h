/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianCameraFrustums.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianCameraFrustums
 * @brief   The training cameras' frustums as lines, coloured by how many selected Gaussians
 *          each view sees.
 *
 * Input 0: a camera table (DESIGN §2, e.g. from vis4gs::CamerasToTable or a camera reader).
 * Input 1 (optional): the Gaussian scene polydata. With a scene and a selection
 * (SetSelectedIds() with GaussianId values, or SetSelection() with a PEDIGREEIDS
 * vtkSelection), each camera gets the number of selected Gaussians visible in it: a non-empty
 * footprint |Omega(g, v)| >= 1 in the exact rasteriser sense (DESIGN §4; occluded or not),
 * computed by Core (CountVisibleInViews) on the selected Gaussians only.
 *
 * Output: per camera 5 points (apex = camera centre, then the image corners at FrustumDepth)
 * and 8 line cells (apex to each corner, and the image rectangle). Point and cell data:
 * "VisibleSelectedCount" (int, the active scalars) and "CameraIndex" (int, the table row).
 */
#ifndef vtkGaussianCameraFrustums_h
#define vtkGaussianCameraFrustums_h

#include "vis4gsFiltersSelectionModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

class vtkIdTypeArray;
class vtkSelection;

class VIS4GSFILTERSSELECTION_EXPORT vtkGaussianCameraFrustums : public vtkPolyDataAlgorithm
{
public:
  static vtkGaussianCameraFrustums* New();
  vtkTypeMacro(vtkGaussianCameraFrustums, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * GaussianId values of the selected Gaussians (point indices when the scene has no
   * GaussianId array). Default none (every count 0).
   */
  void SetSelectedIds(vtkIdTypeArray* ids);
  vtkGetObjectMacro(SelectedIds, vtkIdTypeArray);
  ///@}

  /// Takes the ids of the first PEDIGREEIDS (or INDICES) node of @p selection.
  void SetSelection(vtkSelection* selection);

  ///@{
  /**
   * View depth of the drawn image rectangle. 0 (default): sized to the scene
   * (vis4gs::AutoFrustumDepth: a tenth of the diagonal of the camera centres' bounding box,
   * but at least a tenth of the median distance from the cameras to the scene's median point).
   */
  vtkSetClampMacro(FrustumDepth, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(FrustumDepth, double);
  ///@}

  ///@{
  /**
   * Only the training views (Split 0). Default off (every camera of the table).
   */
  vtkSetMacro(TrainingViewsOnly, bool);
  vtkGetMacro(TrainingViewsOnly, bool);
  vtkBooleanMacro(TrainingViewsOnly, bool);
  ///@}

  /// Convenience for input 1.
  void SetSceneConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }

  vtkMTimeType GetMTime() override;

protected:
  vtkGaussianCameraFrustums();
  ~vtkGaussianCameraFrustums() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  vtkIdTypeArray* SelectedIds = nullptr;
  double FrustumDepth = 0.0;
  bool TrainingViewsOnly = false;

private:
  vtkGaussianCameraFrustums(const vtkGaussianCameraFrustums&) = delete;
  void operator=(const vtkGaussianCameraFrustums&) = delete;
};

#endif

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
 * A selection of more than BackgroundCountMinimum Gaussians is counted on a worker thread when
 * a counts-ready callback is set (the application's scene view: a Frame pick of 200k Gaussians
 * in 4 views costs ~60-100 ms of counting, which the pick's answer then does not wait for):
 * until the worker is done, the output keeps the counts of the selection counted before
 * (GetCountsPending()); the callback then asks for a render, whose update gives the new counts.
 * Without a callback every count is made in RequestData.
 *
 * Output: per camera 5 points (apex = camera centre, then the image corners at FrustumDepth)
 * and 8 line cells (apex to each corner, and the image rectangle). Point and cell data:
 * "VisibleSelectedCount" (int, the active scalars) and "CameraIndex" (int, the table row).
 */
#ifndef vtkGaussianCameraFrustums_h
#define vtkGaussianCameraFrustums_h

#include "vis4gsFiltersSelectionModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <functional> // For std::function
#include <memory>     // For std::unique_ptr

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

  ///@{
  /**
   * Selections of more Gaussians than this are counted on a worker thread when a counts-ready
   * callback is set. Default 20000; 0: always in RequestData.
   */
  vtkSetClampMacro(BackgroundCountMinimum, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(BackgroundCountMinimum, vtkIdType);
  ///@}

#ifndef __VTK_WRAP__
  /**
   * Called on the worker thread when a background count is finished (e.g. to post a render to
   * the GUI thread's event loop). Setting another, or nullptr, waits for a call in progress.
   * Default none (every count made in RequestData).
   */
  void SetCountsReadyCallback(std::function<void()> callback);
#endif

  /// Whether the last output's counts are not yet those of its selection (being counted).
  bool GetCountsPending();

  /// Blocks until no background count runs; the next Update() then has the current counts.
  void WaitForCounts();

  /// Convenience for input 1.
  void SetSceneConnection(vtkAlgorithmOutput* output)
  {
    this->SetInputConnection(1, output);
  }

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
  vtkIdType BackgroundCountMinimum = 20000;

private:
  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;

  vtkGaussianCameraFrustums(const vtkGaussianCameraFrustums&) = delete;
  void operator=(const vtkGaussianCameraFrustums&) = delete;
};

#endif

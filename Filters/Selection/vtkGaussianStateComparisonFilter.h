/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianStateComparisonFilter.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianStateComparisonFilter
 * @brief   Two states of a reconstruction compared Gaussian by Gaussian (issue 20): what
 *          `vis4gs compare` writes to differences.csv, as a VTK filter usable from Python.
 *
 * Input port 0 is the first state, port 1 the second: Gaussian scene polydata (DESIGN §2), e.g.
 * two vtkGaussianTrainingLogReader outputs at two iterations, or a scene and its cleaned copy
 * (vtkGaussianRuleSelectionFilter, Remove). Gaussians are matched by GaussianId
 * (Core/Selection/StateComparison.h): born (only in B), died (only in A), moved, opacity or scale
 * changed beyond the thresholds (strict; 0 reports any change).
 *
 * Output, a vtkTable with one row per id of either state, by increasing id: GaussianId,
 * Change (unsigned char flags: 1 moved, 2 opacity, 4 scale, 8 born, 16 died), Status ("born",
 * "died", "unchanged" or e.g. "moved+opacity"), Move (|centre change|), OpacityChange
 * (sigmoid(logit) B - A) and ScaleChange (log-scale change of largest magnitude); the three
 * are NaN for born and died Gaussians. The counts are returned by the getters after an update.
 *
 * Input port 2 (optional) is a camera table (vis4gs::CamerasToTable columns, e.g.
 * vtkGaussianCameraReader's or the log reader's port 1). With it and MeasureViews on, both
 * states are rendered in every camera with an image and measured against it
 * (vis4gs::MeasureViewMetrics: PSNR, SSIM, L1 of the render clamped to [0, 1], what `vis4gs
 * compare` writes to metrics.csv); the images are found as the score filter finds them
 * (Vis4GSTrainingImages: the Image column, "/images/<name>" from the log the table names, or
 * ImageDirectory by name). Output port 1 is then a vtkTable with one row per camera, in table
 * order: Camera (row of the camera table), Name, Split ("train" / "test"), PSNR_A, SSIM_A, L1_A,
 * PSNR_B, SSIM_B, L1_B (NaN for a camera without image). Without cameras it is empty.
 */
#ifndef vtkGaussianStateComparisonFilter_h
#define vtkGaussianStateComparisonFilter_h

#include "vis4gsFiltersSelectionModule.h" // For export macro
#include "vtkTableAlgorithm.h"

#include <string> // For ImageDirectory

class VIS4GSFILTERSSELECTION_EXPORT vtkGaussianStateComparisonFilter : public vtkTableAlgorithm
{
public:
  static vtkGaussianStateComparisonFilter* New();
  vtkTypeMacro(vtkGaussianStateComparisonFilter, vtkTableAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The second state (input port 1); the first is SetInputConnection(0, ...).
  void SetSecondStateConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }

  ///@{
  /// The cameras both states are measured in (input port 2, optional).
  void SetCamerasConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(2, output); }
  void SetCamerasData(vtkTable* cameras);
  ///@}

  /// The per-camera figures (output port 1) after an update.
  vtkTable* GetViewsOutput();

  ///@{
  /// Measure both states in the cameras of input port 2. Default on.
  vtkSetMacro(MeasureViews, bool);
  vtkGetMacro(MeasureViews, bool);
  vtkBooleanMacro(MeasureViews, bool);
  ///@}

  ///@{
  /// Training images matched to the cameras by name (up to the first '.'), instead of the
  /// cameras' own. Default empty: the cameras' own.
  vtkSetStdStringFromCharMacro(ImageDirectory);
  vtkGetCharFromStdStringMacro(ImageDirectory);
  ///@}

  ///@{
  /// OpenMP threads of the renders; default 0: OpenMP's default.
  vtkSetClampMacro(NumberOfThreads, int, 0, VTK_INT_MAX);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  ///@{
  /// Thresholds, strict: centre distance (scene units), activated-opacity change and
  /// |log-scale change| on an axis. Default 0 (any change counts).
  vtkSetClampMacro(MoveThreshold, double, 0, VTK_DOUBLE_MAX);
  vtkGetMacro(MoveThreshold, double);
  vtkSetClampMacro(OpacityThreshold, double, 0, VTK_DOUBLE_MAX);
  vtkGetMacro(OpacityThreshold, double);
  vtkSetClampMacro(ScaleThreshold, double, 0, VTK_DOUBLE_MAX);
  vtkGetMacro(ScaleThreshold, double);
  ///@}

  ///@{
  /// After an update: Gaussians in both states, born, died, and of those in both the ones
  /// that moved, changed opacity, changed scale, or none of these.
  vtkGetMacro(NumberMatched, vtkIdType);
  vtkGetMacro(NumberBorn, vtkIdType);
  vtkGetMacro(NumberDied, vtkIdType);
  vtkGetMacro(NumberMoved, vtkIdType);
  vtkGetMacro(NumberOpacityChanged, vtkIdType);
  vtkGetMacro(NumberScaleChanged, vtkIdType);
  vtkGetMacro(NumberUnchanged, vtkIdType);
  ///@}

  /// After an update: the cameras whose image both states were measured against.
  vtkGetMacro(NumberOfViewsMeasured, vtkIdType);

protected:
  vtkGaussianStateComparisonFilter();
  ~vtkGaussianStateComparisonFilter() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  double MoveThreshold = 0;
  double OpacityThreshold = 0;
  double ScaleThreshold = 0;
  bool MeasureViews = true;
  std::string ImageDirectory;
  int NumberOfThreads = 0;
  vtkIdType NumberOfViewsMeasured = 0;
  vtkIdType NumberMatched = 0;
  vtkIdType NumberBorn = 0;
  vtkIdType NumberDied = 0;
  vtkIdType NumberMoved = 0;
  vtkIdType NumberOpacityChanged = 0;
  vtkIdType NumberScaleChanged = 0;
  vtkIdType NumberUnchanged = 0;

private:
  vtkGaussianStateComparisonFilter(const vtkGaussianStateComparisonFilter&) = delete;
  void operator=(const vtkGaussianStateComparisonFilter&) = delete;
};

#endif

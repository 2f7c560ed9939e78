/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianNeedleShapeFilter.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianNeedleShapeFilter
 * @brief   adds the needle shape s(g) (and optionally the effective rank) of each Gaussian
 *
 * vtkGaussianNeedleShapeFilter reads the `LogScale` point array of a Gaussian scene
 * (DESIGN §2) and adds `NeedleShape` = (3 - exp(H)) / 2 with H the entropy of the normalised
 * variances, computed in the log domain (see Core/Diagnostics/NeedleShape.h for every extreme
 * case). It needs no cameras. Gaussians whose log-scales contain NaN get NaN and are counted
 * in `NumberOfInvalidGaussians`, with one warning.
 *
 * The output shares every input array (shallow copy) and adds only what was asked for.
 */
#ifndef vtkGaussianNeedleShapeFilter_h
#define vtkGaussianNeedleShapeFilter_h

#include "vis4gsFiltersDiagnosticsModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

class VIS4GSFILTERSDIAGNOSTICS_EXPORT vtkGaussianNeedleShapeFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkGaussianNeedleShapeFilter* New();
  vtkTypeMacro(vtkGaussianNeedleShapeFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Also add the `EffectiveRank` array exp(H) in [1, 3] (reference §6). Default is off.
   */
  vtkSetMacro(ComputeEffectiveRank, bool);
  vtkGetMacro(ComputeEffectiveRank, bool);
  vtkBooleanMacro(ComputeEffectiveRank, bool);
  ///@}

  /**
   * Number of Gaussians of the last execution whose log-scales hold NaN.
   */
  vtkGetMacro(NumberOfInvalidGaussians, vtkIdType);

protected:
  vtkGaussianNeedleShapeFilter() = default;
  ~vtkGaussianNeedleShapeFilter() override = default;

  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  bool ComputeEffectiveRank = false;
  vtkIdType NumberOfInvalidGaussians = 0;

private:
  vtkGaussianNeedleShapeFilter(const vtkGaussianNeedleShapeFilter&) = delete;
  void operator=(const vtkGaussianNeedleShapeFilter&) = delete;
};

#endif

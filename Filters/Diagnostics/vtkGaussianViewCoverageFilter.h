/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianViewCoverageFilter.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianViewCoverageFilter
 * @brief   adds View Coverage E_VC(g) = |V~_g| / |V| (DESIGN §4) from Gaussians and cameras only
 *
 * A vtkGaussianArtifactScoreFilter whose defaults compute `ViewCoverage` and the
 * `NoVisibleView` flags only: no rendering, no images (the fused early-exit visibility of
 * Core/Diagnostics/FastCoverage.h). Input port 0: the Gaussian scene; port 1: the camera
 * table. The approximations (CoverageResolution, ViewStride, FootprintMode) and the
 * occlusion-aware variant (OcclusionThreshold > 0, which composites every view) are the
 * superclass's parameters. Other scores can still be switched on.
 */
#ifndef vtkGaussianViewCoverageFilter_h
#define vtkGaussianViewCoverageFilter_h

#include "vis4gsFiltersDiagnosticsModule.h" // For export macro
#include "vtkGaussianArtifactScoreFilter.h"

class VIS4GSFILTERSDIAGNOSTICS_EXPORT vtkGaussianViewCoverageFilter
  : public vtkGaussianArtifactScoreFilter
{
public:
  static vtkGaussianViewCoverageFilter* New();
  vtkTypeMacro(vtkGaussianViewCoverageFilter, vtkGaussianArtifactScoreFilter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  /// Defaults: ComputeViewCoverage on; BlurScore, NeedleScore and NeedleShape off.
  vtkGaussianViewCoverageFilter();
  ~vtkGaussianViewCoverageFilter() override = default;

private:
  vtkGaussianViewCoverageFilter(const vtkGaussianViewCoverageFilter&) = delete;
  void operator=(const vtkGaussianViewCoverageFilter&) = delete;
};

#endif

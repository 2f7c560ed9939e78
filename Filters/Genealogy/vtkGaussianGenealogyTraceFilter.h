/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianGenealogyTraceFilter.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianGenealogyTraceFilter
 * @brief   the chain from one Gaussian back to its root, as a table
 *
 * Input: the densification tree of vtkGaussianGenealogyTreeFilter. Output: the root-cause
 * trace of vtkGaussianGenealogyLineage::TraceToRoot for GaussianId, one row per Gaussian from
 * it up to its root (GaussianId, Vertex, BirthIteration, DeathIteration, BirthKind,
 * SnapshotIteration, Value). A pipeline stage, so that ParaView (the Vis4GS plugin) can show a
 * lineage in a spreadsheet; no snapshot values are given here (SnapshotIteration -1, Value
 * NaN): the per-snapshot values are the lineage object's (and the Python layer's) job.
 */
#ifndef vtkGaussianGenealogyTraceFilter_h
#define vtkGaussianGenealogyTraceFilter_h

#include "vis4gsFiltersGenealogyModule.h" // For export macro
#include "vtkTableAlgorithm.h"

class VIS4GSFILTERSGENEALOGY_EXPORT vtkGaussianGenealogyTraceFilter : public vtkTableAlgorithm
{
public:
  static vtkGaussianGenealogyTraceFilter* New();
  vtkTypeMacro(vtkGaussianGenealogyTraceFilter, vtkTableAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The Gaussian whose ancestry is traced. Default -1: none (an empty table, no error).
   */
  vtkSetMacro(GaussianId, vtkIdType);
  vtkGetMacro(GaussianId, vtkIdType);
  ///@}

protected:
  vtkGaussianGenealogyTraceFilter();
  ~vtkGaussianGenealogyTraceFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  vtkIdType GaussianId = -1;

private:
  vtkGaussianGenealogyTraceFilter(const vtkGaussianGenealogyTraceFilter&) = delete;
  void operator=(const vtkGaussianGenealogyTraceFilter&) = delete;
};

#endif

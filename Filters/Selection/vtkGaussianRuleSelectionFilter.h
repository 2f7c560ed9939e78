/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianRuleSelectionFilter.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianRuleSelectionFilter
 * @brief   Selects the Gaussians a rule over their scores and attributes matches (issue 20),
 *          and marks, removes or extracts them.
 *
 * The rule language is Core/Selection/SelectionRule.h's (user guide, "Guided clean-up"), e.g.
 * "views<=3 and opacity>=0.5", "blur top 5%", "needle>=0.8", "isolated r=0.1". The input is a
 * Gaussian scene polydata (DESIGN §2); the scores a rule reads are the point-data arrays of
 * the score registry (vtkGaussianScoreRegistry: ViewCoverage, BlurScore, NeedleScore,
 * RenderCost, ...; vtkGaussianArtifactScoreFilter's output) named by their rule names, and
 * "views" needs NumberOfViews (the score filter's GetNumberOfViewsUsed()). The rule's
 * selection is combined with CurrentIds (GaussianId values) by CombineMode.
 *
 * Output, by OutputMode: the input with a point-data array "RuleSelected" (unsigned char 0/1,
 * Mark, default); the Gaussians not selected (Remove: the cleaned scene, every point-data array
 * kept); or the selected ones only (Extract). The field data "SelectionRule" holds the rule in
 * canonical form. A rule that cannot be parsed or evaluated is an error naming the rule and the
 * offending token (GetLastRuleError()), and the output is empty.
 */
#ifndef vtkGaussianRuleSelectionFilter_h
#define vtkGaussianRuleSelectionFilter_h

#include "vis4gsFiltersSelectionModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // For the rule

class vtkIdTypeArray;

class VIS4GSFILTERSSELECTION_EXPORT vtkGaussianRuleSelectionFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkGaussianRuleSelectionFilter* New();
  vtkTypeMacro(vtkGaussianRuleSelectionFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum OutputModes
  {
    Mark = 0,
    Remove = 1,
    Extract = 2
  };
  enum CombineModes
  {
    Replace = 0,
    Add = 1,
    Subtract = 2,
    Intersect = 3
  };

  ///@{
  /// The rule text. Default empty (an error: there is nothing to select by).
  vtkSetStdStringFromCharMacro(Rule);
  vtkGetCharFromStdStringMacro(Rule);
  ///@}

  ///@{
  /// |V|, the training views the scores used, for the "views" attribute. Default 0 (unknown:
  /// a rule reading "views" is an error).
  vtkSetClampMacro(NumberOfViews, int, 0, VTK_INT_MAX);
  vtkGetMacro(NumberOfViews, int);
  ///@}

  ///@{
  /// Mark (default), Remove or Extract; see the class comment.
  vtkSetClampMacro(OutputMode, int, Mark, Extract);
  vtkGetMacro(OutputMode, int);
  ///@}

  ///@{
  /// How the rule's selection combines with CurrentIds: Replace (default), Add, Subtract,
  /// Intersect.
  vtkSetClampMacro(CombineMode, int, Replace, Intersect);
  vtkGetMacro(CombineMode, int);
  ///@}

  ///@{
  /// GaussianId values of an existing selection (a brush or histogram selection). Default none.
  void SetCurrentIds(vtkIdTypeArray* ids);
  vtkGetObjectMacro(CurrentIds, vtkIdTypeArray);
  ///@}

  /// After an update: the GaussianId values selected (after combining), ascending.
  vtkIdTypeArray* GetSelectedIds() { return this->SelectedIds; }
  /// After an update: the rule in canonical form (empty after an error).
  const char* GetCanonicalRule() { return this->CanonicalRule.c_str(); }
  /// After an update: the message of the last rule error, or empty.
  const char* GetLastRuleError() { return this->LastRuleError.c_str(); }

protected:
  vtkGaussianRuleSelectionFilter();
  ~vtkGaussianRuleSelectionFilter() override;

  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  std::string Rule;
  int NumberOfViews = 0;
  int OutputMode = Mark;
  int CombineMode = Replace;
  vtkIdTypeArray* CurrentIds = nullptr;
  vtkIdTypeArray* SelectedIds = nullptr;
  std::string CanonicalRule;
  std::string LastRuleError;

private:
  vtkGaussianRuleSelectionFilter(const vtkGaussianRuleSelectionFilter&) = delete;
  void operator=(const vtkGaussianRuleSelectionFilter&) = delete;
};

#endif

/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianScoreRegistry.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianScoreRegistry
 * @brief   the per-Gaussian scores of Core/Diagnostics/ScoreRegistry.h, for wrapped languages
 *
 * Read-only, static: for each registered score (index 0 .. GetNumberOfScores() - 1, the order
 * of scores.csv's columns) its short name (`vis4gs analyze --scores=`, `Scene.scores()`), the
 * point-data array vtkGaussianArtifactScoreFilter adds, its name in the selection-rule
 * language, a title, its suspicious end, what it needs and whether it is computed by default,
 * and its parameters (the score filter's properties / `vis4gs analyze` options it reads).
 * The Python layer (`vis4gs.scene.SCORES`) and the application read their score lists here
 * or in the Core registry; nothing else lists scores. Out-of-range indices give nullptr, 0 or
 * false.
 */
#ifndef vtkGaussianScoreRegistry_h
#define vtkGaussianScoreRegistry_h

#include "vis4gsFiltersDiagnosticsModule.h" // For export macro
#include "vtkObject.h"

class VIS4GSFILTERSDIAGNOSTICS_EXPORT vtkGaussianScoreRegistry : public vtkObject
{
public:
  static vtkGaussianScoreRegistry* New();
  vtkTypeMacro(vtkGaussianScoreRegistry, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Number of registered scores.
  static int GetNumberOfScores();
  /// Index of the score with short or array name @p name, or -1.
  static int FindScore(const char* name);

  ///@{
  /// Names: short ("render-cost"), array ("RenderCost"), rule ("render_cost"), title.
  static const char* GetName(int index);
  static const char* GetArrayName(int index);
  static const char* GetRuleName(int index);
  static const char* GetTitle(int index);
  static const char* GetDocumentation(int index);
  ///@}

  /// The suspicious end: -1 low values (View Coverage), +1 high values, 0 none.
  static int GetSuspiciousEnd(int index);
  ///@{
  /// What the score needs: the camera table, training images.
  static bool GetNeedsCameras(int index);
  static bool GetNeedsImages(int index);
  ///@}
  /// Whether the score is computed when no list is given.
  static bool GetDefaultOn(int index);
  /// The short names of the default scores, comma-separated ("coverage,blur,needle,shape").
  static const char* GetDefaultScores();

  ///@{
  /// The parameters score @p index reads: name (`vis4gs analyze` option), type ("int",
  /// "double", "bool", "choice"), default as text, range, documentation.
  static int GetNumberOfParameters(int index);
  static const char* GetParameterName(int index, int parameter);
  static const char* GetParameterType(int index, int parameter);
  static const char* GetParameterDefault(int index, int parameter);
  static double GetParameterMinimum(int index, int parameter);
  static double GetParameterMaximum(int index, int parameter);
  static const char* GetParameterDocumentation(int index, int parameter);
  ///@}

protected:
  vtkGaussianScoreRegistry() = default;
  ~vtkGaussianScoreRegistry() override = default;

private:
  vtkGaussianScoreRegistry(const vtkGaussianScoreRegistry&) = delete;
  void operator=(const vtkGaussianScoreRegistry&) = delete;
};

#endif

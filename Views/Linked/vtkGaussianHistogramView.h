/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianHistogramView.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianHistogramView
 * @brief   histogram of one Gaussian attribute with brushing, linked through the hub
 *
 * A vtkContextView with a vtkChartXY: grey bars count every Gaussian per bin of the
 * attribute ArrayName (Opacity, Scale, EffectiveRank, ViewCoverage, BlurScore, NeedleScore,
 * ...; multi-component arrays by their largest component, or Component >= 0), orange bars
 * count the selected ones. Brushing (a left-button drag over bins, or SelectRange) selects
 * the Gaussians whose value lies in the brushed range and publishes them to the selection
 * hub; a selection made elsewhere updates the orange bars.
 *
 * Input: a vtkPolyData (point data) or vtkTable (columns) holding ArrayName and IdArrayName.
 * Non-finite values are not counted.
 */
#ifndef vtkGaussianHistogramView_h
#define vtkGaussianHistogramView_h

#include "vis4gsViewsLinkedModule.h" // For export macro
#include "vtkContextView.h"

#include <memory> // For std::unique_ptr

class vtkAbstractArray;
class vtkAlgorithmOutput;
class vtkChartXY;
class vtkDataArray;
class vtkDataObject;
class vtkGaussianSelectionHub;
class vtkIdTypeArray;

class VIS4GSVIEWSLINKED_EXPORT vtkGaussianHistogramView : public vtkContextView
{
public:
  static vtkGaussianHistogramView* New();
  vtkTypeMacro(vtkGaussianHistogramView, vtkContextView);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The Gaussians (vtkPolyData or vtkTable). Default none. SetInputData() disconnects
   * SetInputConnection().
   */
  void SetInputData(vtkDataObject* data);
  vtkDataObject* GetInputData();
  ///@}

  ///@{
  /**
   * The Gaussians as a connection (vtkGaussianSession's GaussiansPort), pulled by Update(),
   * Render() and UpdateHistogram(): new score arrays there are binned without a client
   * handing them over (Vis4GSViewInput). Default none.
   */
  void SetInputConnection(vtkAlgorithmOutput* output);
  vtkAlgorithmOutput* GetInputConnection();
  ///@}

  /// Pulls the connection, and bins again when its arrays changed.
  void Update() override;
  /// Update(), then draws.
  void Render() override;

  ///@{
  /**
   * Attribute and id arrays. Defaults: "Opacity", "GaussianId".
   */
  vtkSetStringMacro(ArrayName);
  vtkGetStringMacro(ArrayName);
  vtkSetStringMacro(IdArrayName);
  vtkGetStringMacro(IdArrayName);
  ///@}

  ///@{
  /**
   * Component of a multi-component array; -1 uses the largest component. Default -1.
   */
  vtkSetMacro(Component, int);
  vtkGetMacro(Component, int);
  ///@}

  ///@{
  /**
   * Number of bins over the finite value range. Default 32.
   */
  vtkSetClampMacro(NumberOfBins, int, 1, 100000);
  vtkGetMacro(NumberOfBins, int);
  ///@}

  /// Links the view to @p hub; nullptr unlinks.
  void SetSelectionHub(vtkGaussianSelectionHub* hub);
  vtkGaussianSelectionHub* GetSelectionHub();

  /**
   * Brush: selects the Gaussians with lo <= value <= hi (mode of
   * vtkGaussianSelectionHub::Modes) and publishes them. Returns how many matched.
   */
  vtkIdType SelectRange(double lo, double hi, int mode = 0);

  /// Recomputes the bins from the input (pulled first) and the selection (done on a change of
  /// the input or the settings; a selection change recounts only the selected Gaussians).
  void UpdateHistogram();

  ///@{
  /**
   * Results of the last UpdateHistogram: bin edges (NumberOfBins + 1 values), counts of all
   * and of selected Gaussians per bin.
   */
  void GetBinEdges(double* edges);
  vtkIdType GetBinCount(int bin);
  vtkIdType GetSelectedBinCount(int bin);
  ///@}

  /// The chart (for styling and scripted brushing).
  vtkChartXY* GetChart();

protected:
  vtkGaussianHistogramView();
  ~vtkGaussianHistogramView() override;

  void OnChartSelection();
  /// The orange bars of the current selection over the current bins (no other change).
  void CountSelected(vtkDataArray* values, vtkAbstractArray* ids);
  /// After a selection change: the orange bars only when the grey bars' input is unchanged,
  /// else UpdateHistogram().
  void UpdateSelectedCounts();

  char* ArrayName = nullptr;
  char* IdArrayName = nullptr;
  int Component = -1;
  int NumberOfBins = 32;

private:
  vtkGaussianHistogramView(const vtkGaussianHistogramView&) = delete;
  void operator=(const vtkGaussianHistogramView&) = delete;

  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;

  /// Takes the connection's data when it changed; true then.
  bool PullInput();
};

#endif

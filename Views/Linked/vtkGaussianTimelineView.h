/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianTimelineView.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianTimelineView
 * @brief   view D of DESIGN: metrics and the selected Gaussians' history over iterations
 *
 * A vtkContextView with three stacked vtkGaussianTimelineCharts sharing the iteration axis:
 * - quality (top): PSNR on the left axis, SSIM and LPIPS on the right axis, training metrics
 *   solid and test metrics (when given) dashed; columns that are all NaN are left out;
 * - Gaussian count (middle);
 * - the selected Gaussians' HistoryProperty over iterations (bottom): one line per selected
 *   Gaussian (at most MaximumHistoryLines; the first ids) from the History table.
 *
 * A second run (another training log of the same scene, issue 20) can be set beside the
 * first (SetComparisonMetrics, SetComparisonTestMetrics): its metrics are drawn in the
 * quality and count charts in the same colours as the first run's, dotted (dash-dotted for
 * its test metrics), and every metric's legend entry names its run (RunName,
 * ComparisonRunName), e.g. "PSNR [A: iteration 1000]". The iteration axis spans both runs.
 * A second, dashed cursor (SetComparisonIteration) marks the other state's iteration.
 *
 * Every chart shows the iteration cursor (the hub's iteration). A click on a chart invokes
 * IterationSelectedEvent (call data int*, snapped to the nearest metrics iteration) and, when
 * a hub is linked, sets the hub's iteration, which moves every view.
 *
 * Tables (column names settable):
 * - metrics (SetMetrics, SetTestMetrics): Iteration, NumGaussians, PSNR, SSIM, LPIPS (the
 *   spelling of vtkGaussianTrainingLogReader's metrics port, vis4gs::arrays::Metric*)
 *   (DESIGN §3 /metrics). Without test metrics, the Test-prefixed columns of the metrics
 *   table (TestPSNR, ...: the log reader's merged table) are the test metrics, so the reader's
 *   port plugs in directly; each line is drawn through its column's finite rows;
 * - history (SetHistory): long format, one row per (iteration, Gaussian): Iteration,
 *   GaussianId and one column per property or score (Opacity, ViewCoverage, ...), as the log
 *   reader's history query gives it. Only rows of selected ids are drawn when a hub is linked.
 */
#ifndef vtkGaussianTimelineView_h
#define vtkGaussianTimelineView_h

#include "vis4gsViewsLinkedModule.h" // For export macro
#include "vtkCommand.h"              // For vtkCommand::UserEvent
#include "vtkContextView.h"
#include "vtkNew.h" // For vtkNew

#include <memory> // For std::unique_ptr

class vtkAlgorithmOutput;
class vtkChartMatrix;
class vtkGaussianSelectionHub;
class vtkGaussianTimelineChart;
class vtkTable;

class VIS4GSVIEWSLINKED_EXPORT vtkGaussianTimelineView : public vtkContextView
{
public:
  static vtkGaussianTimelineView* New();
  vtkTypeMacro(vtkGaussianTimelineView, vtkContextView);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Events
  {
    /// A click picked an iteration; call data: int* iteration.
    IterationSelectedEvent = vtkCommand::UserEvent + 4103
  };

  enum Charts
  {
    QUALITY = 0,
    COUNT = 1,
    HISTORY = 2
  };

  ///@{
  /**
   * Training and test metrics tables. Default none.
   */
  void SetMetrics(vtkTable* metrics);
  vtkTable* GetMetrics();
  void SetTestMetrics(vtkTable* metrics);
  vtkTable* GetTestMetrics();
  ///@}

  ///@{
  /**
   * A second run's training and test metrics tables (same columns), drawn dotted and
   * dash-dotted beside the first run's. Default none.
   */
  void SetComparisonMetrics(vtkTable* metrics);
  vtkTable* GetComparisonMetrics();
  void SetComparisonTestMetrics(vtkTable* metrics);
  vtkTable* GetComparisonTestMetrics();
  ///@}

  ///@{
  /**
   * Names of the first and the second run in the legend entries, used while comparison
   * metrics are set. Defaults "A" and "B".
   */
  void SetRunName(const char* name);
  vtkGetStringMacro(RunName);
  void SetComparisonRunName(const char* name);
  vtkGetStringMacro(ComparisonRunName);
  ///@}

  ///@{
  /**
   * History of Gaussians in long format. Default none.
   */
  void SetHistory(vtkTable* history);
  vtkTable* GetHistory();
  ///@}

  ///@{
  /**
   * The metrics and the history as connections (vtkGaussianSession's MetricsPort and
   * HistoryPort, whose selection input is the hub's annotation link): pulled by Update() and
   * Render(), so that a new selection's history reaches the chart when the hub renders the
   * view, without a client fetching it (Vis4GSViewInput). SetMetrics() / SetHistory()
   * disconnect them. Default none.
   */
  void SetMetricsConnection(vtkAlgorithmOutput* metrics);
  vtkAlgorithmOutput* GetMetricsConnection();
  void SetHistoryConnection(vtkAlgorithmOutput* history);
  vtkAlgorithmOutput* GetHistoryConnection();
  ///@}

  /// Pulls the connections, and rebuilds the plots when one changed.
  void Update() override;
  /// Update(), then draws.
  void Render() override;

  ///@{
  /**
   * Property of the history drawn in the bottom chart. Default "Opacity".
   */
  vtkSetStringMacro(HistoryProperty);
  vtkGetStringMacro(HistoryProperty);
  ///@}

  ///@{
  /**
   * Component of a vector HistoryProperty drawn (0, 1, 2: Position's X, Y, Z); -1 draws the
   * largest component (Scale: the largest axis). Ignored for a scalar property or a component
   * the column does not have (then the largest is drawn). Default -1.
   */
  vtkSetClampMacro(HistoryComponent, int, -1, 15);
  vtkGetMacro(HistoryComponent, int);
  ///@}

  ///@{
  /**
   * At most this many Gaussians' lines in the history chart. Default 16.
   */
  vtkSetClampMacro(MaximumHistoryLines, int, 1, 1000);
  vtkGetMacro(MaximumHistoryLines, int);
  ///@}

  ///@{
  /**
   * Column names. Defaults: Iteration, NumGaussians, PSNR, SSIM, LPIPS (metrics);
   * Iteration, GaussianId (history).
   */
  vtkSetStringMacro(IterationColumn);
  vtkGetStringMacro(IterationColumn);
  vtkSetStringMacro(CountColumn);
  vtkGetStringMacro(CountColumn);
  vtkSetStringMacro(PSNRColumn);
  vtkGetStringMacro(PSNRColumn);
  vtkSetStringMacro(SSIMColumn);
  vtkGetStringMacro(SSIMColumn);
  vtkSetStringMacro(LPIPSColumn);
  vtkGetStringMacro(LPIPSColumn);
  vtkSetStringMacro(HistoryIterationColumn);
  vtkGetStringMacro(HistoryIterationColumn);
  vtkSetStringMacro(HistoryIdColumn);
  vtkGetStringMacro(HistoryIdColumn);
  ///@}

  /// Links the view to @p hub (cursor, history of the selection, clicks); nullptr unlinks.
  void SetSelectionHub(vtkGaussianSelectionHub* hub);
  vtkGaussianSelectionHub* GetSelectionHub();

  ///@{
  /**
   * The iteration cursor (also set from the hub). Negative hides it.
   */
  void SetIteration(int iteration);
  int GetIteration();
  ///@}

  ///@{
  /**
   * A second iteration cursor (dashed): the other state of a comparison, e.g. the second
   * iteration of one log. Negative hides it. Default -1.
   */
  void SetComparisonIteration(int iteration);
  int GetComparisonIteration();
  ///@}

  /// Rebuilds the plots from the tables and the selection (done on every change).
  void UpdatePlots();

  /// One of the three charts (QUALITY, COUNT, HISTORY).
  vtkGaussianTimelineChart* GetChart(int which);

  /// Number of Gaussians whose history is drawn (after the last UpdatePlots).
  int GetNumberOfHistoryLines();
  /// What the history chart draws (after the last UpdatePlots): an Iteration column and one
  /// column "Gaussian <id>" per line, the drawn value or NaN where the Gaussian is not logged.
  vtkTable* GetHistoryLines();
  /// Number of metric plots drawn in the quality and count charts.
  int GetNumberOfMetricPlots();
  /// Number of those that draw the comparison run's metrics.
  int GetNumberOfComparisonPlots();

  /// The metrics iteration nearest @p iteration (itself when there are no metrics).
  int SnapIteration(int iteration);

protected:
  vtkGaussianTimelineView();
  ~vtkGaussianTimelineView() override;

  void OnChartClicked(int iteration);

  char* HistoryProperty = nullptr;
  char* RunName = nullptr;
  char* ComparisonRunName = nullptr;
  int MaximumHistoryLines = 16;
  int HistoryComponent = -1;
  char* IterationColumn = nullptr;
  char* CountColumn = nullptr;
  char* PSNRColumn = nullptr;
  char* SSIMColumn = nullptr;
  char* LPIPSColumn = nullptr;
  char* HistoryIterationColumn = nullptr;
  char* HistoryIdColumn = nullptr;

private:
  vtkGaussianTimelineView(const vtkGaussianTimelineView&) = delete;
  void operator=(const vtkGaussianTimelineView&) = delete;

  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif

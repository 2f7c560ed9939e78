/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianArtifactScoreFilter.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianArtifactScoreFilter
 * @brief   adds the per-Gaussian scores of the score registry (View Coverage, Blur, Needle,
 * needle shape, render cost, ...) to each Gaussian
 *
 * Input port 0 is a Gaussian scene (vtkPolyData, DESIGN §2); input port 1 (optional when only
 * the needle shape is asked for) is the camera table (one row per view, IO/Scene
 * Vis4GSDataModel.h). Training images are the files named in the table's `Image` column,
 * read with the Core image reader (PNG/JPEG, resized to the camera's size as the trainer
 * does); when ImageDirectory is set, each camera's image is instead looked up by name in that
 * folder (the file whose name up to the first '.' is the camera's Name). A view whose image
 * file does not exist is skipped for blur/needle, with one warning giving the count.
 *
 * The scores are those of Core/Diagnostics/ScoreRegistry.h (vtkGaussianScoreRegistry lists
 * them): SetScores("coverage,blur"), EnableScore() or SetScoreArrayStatus() choose by short or
 * array name; the Compute* switches of the first four scores stay for compatibility. Only the
 * requested arrays are computed and added (double, named by the registry: `ViewCoverage`,
 * `BlurScore`, `NeedleScore`, `NeedleShape`, `RenderCost`, `CostPerContribution`, ...), and
 * `NoVisibleView` (unsigned char, the bits of vis4gs::ScoreFlag: 1 no visible view for
 * coverage, 2 no visible view with an image for blur/needle, 4 NaN/Inf parameters; 0 for a
 * normal Gaussian) whenever a score needing cameras is computed. Coverage alone renders nothing and
 * reads no image. Every approximation of Core/Diagnostics/ArtifactScores.h is a parameter; the
 * defaults are the exact mode. Progress is reported per view.
 *
 * In a distributed pipeline (pvbatch or pvserver under mpiexec) every process reads the whole
 * scene and cameras (RequestUpdateExtent asks the inputs for piece 0 of 1), the processes
 * share the views (SetController), and the scored Gaussians are the output of piece 0; the
 * other pieces are empty, so that gathering the pieces gives each Gaussian once.
 */
#ifndef vtkGaussianArtifactScoreFilter_h
#define vtkGaussianArtifactScoreFilter_h

#include "vis4gsFiltersDiagnosticsModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <atomic>     // For StopRequested
#include <cstddef>    // For ViewRendered
#include <functional> // For ViewRendered
#include <string>     // For ImageDirectory
#include <vector>     // For EnabledScores

#ifndef __VTK_WRAP__
namespace vis4gs
{
struct Camera;
struct Image;
template <typename T>
struct RasterImage;
}
#endif

class vtkMultiProcessController;
class vtkTable;

class VIS4GSFILTERSDIAGNOSTICS_EXPORT vtkGaussianArtifactScoreFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkGaussianArtifactScoreFilter* New();
  vtkTypeMacro(vtkGaussianArtifactScoreFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * The camera table (input port 1).
   */
  void SetCamerasData(vtkTable* cameras);
  void SetCamerasConnection(vtkAlgorithmOutput* output);

  ///@{
  /**
   * Which scores to compute: a comma-separated list of the registry's short names
   * (vtkGaussianScoreRegistry, `vis4gs analyze --scores=`). Default: the registry's default
   * set (vtkGaussianScoreRegistry::GetDefaultScores(): coverage, blur, needle, shape). An
   * unknown name is an error naming it and the known ones; the selection is then unchanged
   * and SetScores returns false. GetScores() gives the current list in registry order.
   */
  bool SetScores(const char* list);
  std::string GetScores();
  ///@}

  ///@{
  /**
   * Turns one score on or off by its short name or array name ("render-cost",
   * "RenderCost"); false (and an error) for an unknown name. IsScoreEnabled() is false for an
   * unknown name.
   */
  bool EnableScore(const char* name, bool on = true);
  bool IsScoreEnabled(const char* name);
  ///@}

  ///@{
  /**
   * The scores as an array selection, by array name, for ParaView's
   * ArraySelectionInformationHelper (attribute "Score"): every registered score, its status
   * 1 when it will be computed.
   */
  int GetNumberOfScoreArrays();
  const char* GetScoreArrayName(int index);
  int GetScoreArrayStatus(const char* name);
  void SetScoreArrayStatus(const char* name, int status);
  ///@}

  ///@{
  /**
   * The first four scores' switches (EnableScore() of coverage, blur, needle, shape), kept for
   * compatibility. Defaults: on.
   */
  virtual void SetComputeViewCoverage(bool on) { this->EnableScore("coverage", on); }
  bool GetComputeViewCoverage() { return this->IsScoreEnabled("coverage"); }
  vtkBooleanMacro(ComputeViewCoverage, bool);
  virtual void SetComputeBlurScore(bool on) { this->EnableScore("blur", on); }
  bool GetComputeBlurScore() { return this->IsScoreEnabled("blur"); }
  vtkBooleanMacro(ComputeBlurScore, bool);
  virtual void SetComputeNeedleScore(bool on) { this->EnableScore("needle", on); }
  bool GetComputeNeedleScore() { return this->IsScoreEnabled("needle"); }
  vtkBooleanMacro(ComputeNeedleScore, bool);
  virtual void SetComputeNeedleShape(bool on) { this->EnableScore("shape", on); }
  bool GetComputeNeedleShape() { return this->IsScoreEnabled("shape"); }
  vtkBooleanMacro(ComputeNeedleShape, bool);
  ///@}

  ///@{
  /**
   * Folder of the training images, matched to cameras by name. Default empty: use the
   * camera table's Image column.
   */
  vtkSetStdStringFromCharMacro(ImageDirectory);
  vtkGetCharFromStdStringMacro(ImageDirectory);
  ///@}

  ///@{
  /**
   * Loss-map resolution factor of blur/needle: 1 (exact, default), 2, 4 or 8.
   */
  vtkSetClampMacro(LossResolution, int, 1, 8);
  vtkGetMacro(LossResolution, int);
  ///@}

  ///@{
  /**
   * Resolution factor of the coverage pass: 1 (exact, default), 2, 4 or 8.
   */
  vtkSetClampMacro(CoverageResolution, int, 1, 8);
  vtkGetMacro(CoverageResolution, int);
  ///@}

  ///@{
  /**
   * Use every k-th training view. Default 1 (all).
   */
  vtkSetClampMacro(ViewStride, int, 1, VTK_INT_MAX);
  vtkGetMacro(ViewStride, int);
  ///@}

  ///@{
  /**
   * Footprint: 0 = the rasteriser's alpha footprint (exact, default), 1 = 3-sigma ellipse.
   */
  vtkSetClampMacro(FootprintMode, int, 0, 1);
  vtkGetMacro(FootprintMode, int);
  ///@}

  ///@{
  /**
   * Accumulate the footprint sums of the loss map in float instead of double. Default off.
   */
  vtkSetMacro(FloatAccumulation, bool);
  vtkGetMacro(FloatAccumulation, bool);
  vtkBooleanMacro(FloatAccumulation, bool);
  ///@}

  ///@{
  /**
   * Occlusion-aware coverage threshold on the maximum blending weight alpha*T; 0 (default)
   * is the plain coverage of DESIGN §4.
   */
  vtkSetClampMacro(OcclusionThreshold, double, 0.0, 1.0);
  vtkGetMacro(OcclusionThreshold, double);
  ///@}

  ///@{
  /**
   * lambda of the loss map. Default 0.2.
   */
  vtkSetClampMacro(Lambda, double, 0.0, 1.0);
  vtkGetMacro(Lambda, double);
  ///@}

  ///@{
  /**
   * Progressive scores (issue 31): 0 (default) computes the scores with the settings above;
   * 1 computes the first, approximate stage of them: every 8th of the views ViewStride
   * selects, loss and coverage maps at 4 times the LossResolution and CoverageResolution
   * factors (at most 8), about 1/128 of the pixels. A client shows stage 1, then runs stage 0
   * (`vis4gs analyze --stop-after-stage`, the application). The output's field data
   * `ScoreStage` (one string) says which: GetStageDescription(), so that a stage-1 result
   * stays labelled approximate wherever it goes.
   */
  vtkSetClampMacro(ProgressiveStage, int, 0, 1);
  vtkGetMacro(ProgressiveStage, int);
  ///@}

  /**
   * "stage 1 of 2, approximate: every 8th training view, loss maps at 1/4, coverage at 1/4
   * resolution" for stage 1, "stage 2 of 2, exact" for stage 0 with the exact settings, or
   * "stage 2 of 2: every 2nd training view, ..." with approximate ones: the label the output's
   * `ScoreStage` field data carries for the current settings.
   */
  std::string GetStageDescription();

  /**
   * The views and resolutions of the current stage: "every 8th training view, loss maps at
   * 1/4, coverage at 1/4 resolution" (stage 1 with the defaults), "every training view, loss
   * maps at full, coverage at full resolution" (stage 0 with the defaults).
   */
  std::string GetStageSettings();

  ///@{
  /**
   * Stops the execution in progress after the view it is on: thread-safe, for a GUI that
   * runs the filter in a worker thread. The stopped execution's output has no score arrays,
   * its `ScoreStage` field data is "stopped", and GetStopped() is true until the next
   * execution. Each execution starts without a request (one made before it is forgotten: a
   * client stopping between executions does not start the next). In one process only (with
   * several, every process would have to stop at the same view: there it is ignored).
   */
  void StopExecution();
  vtkGetMacro(Stopped, bool);
  ///@}

  ///@{
  /**
   * Results of the last execution: training views used, views skipped for lack of an image,
   * Gaussians flagged NoVisibleView (any bit).
   */
  vtkGetMacro(NumberOfViewsUsed, vtkIdType);
  vtkGetMacro(NumberOfViewsWithoutImage, vtkIdType);
  vtkGetMacro(NumberOfFlaggedGaussians, vtkIdType);
  ///@}

  ///@{
  /**
   * The processes the training views are spread over. Default nullptr: the global
   * controller (vtkMultiProcessController::GetGlobalController()), which is null, or a single
   * process, unless the program started MPI (vtkMPIController), so a program that never
   * uses MPI runs in one process exactly as before. With more than one process, every
   * process must hold the whole scene and the same cameras and settings; each renders the
   * views SplitViewsByCost() gives it (Core/Diagnostics/ArtifactScores.h) and reads only
   * their images, the per-Gaussian partials are summed slice by slice (a reduce-scatter:
   * process r sums and finishes the r-th of the Gaussians), and every process gets the full
   * scores (an all-gather of the finished slices). If a process fails, every process's RequestData
   * fails and the error names the failing process and the view it was on.
   */
  virtual void SetController(vtkMultiProcessController* controller);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

  ///@{
  /**
   * With more than one process: whether the processes of one machine prepare the shared
   * projection's view-independent part once between them, in memory they share
   * (Vis4GSNodeSharedMemory; each prepares its part of the Gaussians), instead of each
   * preparing every Gaussian in its own memory. Same scores bit for bit either way; when the
   * memory cannot be made, every process prepares alone. Default off: on the 2-vCPU VM of
   * Documentation/performance.md the processes' views ran slower with the shared block (its
   * memory gets no huge pages there) than the memory it saves is worth (16 views of the
   * Bicycle case, idle: 27.8 s shared against 24.1 s alone).
   */
  vtkSetMacro(SharePreparation, bool);
  vtkGetMacro(SharePreparation, bool);
  vtkBooleanMacro(SharePreparation, bool);
  ///@}

  ///@{
  /**
   * With more than one process and the blur or needle score requested: whether the processes
   * of one machine take their views one at a time from a queue they share (a counter in
   * Vis4GSNodeSharedMemory), the costliest first by EstimateViewCosts(), so that whichever
   * process is free renders the next view, instead of each rendering the part that
   * SplitViewsByCost() gives it. Machines still get their views from SplitViewsByCost() (the sum
   * of their processes' parts). A process that runs slower, because its views cost more than
   * estimated or because its core is shared, then takes fewer views, and no process waits for
   * the slowest at the end for more than about one view. Which process renders which view
   * then depends on timing; the scores do not (compensated sums, ScorePartials::BlurCompensation
   * in Core/Diagnostics/ArtifactScores.h). Off: the fixed split, each view on the same process
   * on every run (to reproduce a failure on a view, for instance). When the queue's memory
   * cannot be made, the fixed split is used with a warning. Default on.
   */
  vtkSetMacro(DynamicViewBalancing, bool);
  vtkGetMacro(DynamicViewBalancing, bool);
  vtkBooleanMacro(DynamicViewBalancing, bool);
  ///@}

  /**
   * Processes of this machine that shared the preparation in the last execution (this one
   * included); 1 when this process prepared alone (one process, SharePreparation off, or the
   * shared memory could not be made: then a warning says why).
   */
  vtkGetMacro(PreparationProcesses, int);

  /**
   * "view N ('name')" while a distributed execution renders view N in this process, else "".
   * A fixed buffer, safe to read from a signal handler (the vis4gs program's MPI session
   * names the view when a process is killed).
   */
  static const char* GetViewInProgress();

  ///@{
  /**
   * Seconds of the last execution spent by this process on its views (projection, rendering,
   * images, loss maps, footprints, sums) and finishing its scores, and on the communication
   * between the processes (the reduce-scatter of the partials, the all-gather of the scores;
   * 0 in one process), for the benchmarks (Documentation/performance.md).
   */
  vtkGetMacro(ComputeSeconds, double);
  vtkGetMacro(ReductionSeconds, double);
  ///@}

  /// Views rendered by this process in the last execution (all of them in one process).
  vtkGetMacro(NumberOfViewsRendered, vtkIdType);

#ifndef __VTK_WRAP__
  /**
   * Called with every view the blur/needle pass renders in this process: the camera index, the
   * camera as rendered, the render and the image (vis4gs::ScoreSettings::ViewRendered,
   * Core/Diagnostics/ArtifactScores.h). The vis4gs program keeps the "before" of a clean-up
   * with it (vis4gs::RemovalBaselineRecorder) instead of rendering every view again. C++ only;
   * default none.
   */
  using ViewRenderedFunction = std::function<void(std::size_t,
    const vis4gs::Camera&,
    const vis4gs::RasterImage<float>&,
    const vis4gs::Image&)>;
  void SetViewRendered(ViewRenderedFunction function);
#endif

protected:
  vtkGaussianArtifactScoreFilter();
  ~vtkGaussianArtifactScoreFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  /// Every process needs the whole scene and every camera (the views are split, not the
  /// Gaussians): asks the inputs for piece 0 of 1 whatever piece the output is asked for.
  int RequestUpdateExtent(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  /// One flag per registered score, in registry order (the constructor sets the defaults).
  std::vector<bool> EnabledScores;
  std::string ImageDirectory;
  int LossResolution = 1;
  int CoverageResolution = 1;
  int ViewStride = 1;
  int FootprintMode = 0;
  bool FloatAccumulation = false;
  double OcclusionThreshold = 0.0;
  double Lambda = 0.2;
  int ProgressiveStage = 0;
#ifndef __VTK_WRAP__
  std::atomic<bool> StopRequested{ false };
#endif
  bool Stopped = false;
  vtkIdType NumberOfViewsUsed = 0;
  vtkIdType NumberOfViewsWithoutImage = 0;
  vtkIdType NumberOfFlaggedGaussians = 0;
  vtkIdType NumberOfViewsRendered = 0;
  double ComputeSeconds = 0;
  double ReductionSeconds = 0;
  vtkMultiProcessController* Controller = nullptr;
  bool SharePreparation = false;
  bool DynamicViewBalancing = true;
  int PreparationProcesses = 1;
#ifndef __VTK_WRAP__
  ViewRenderedFunction ViewRendered;
#endif

private:
  vtkGaussianArtifactScoreFilter(const vtkGaussianArtifactScoreFilter&) = delete;
  void operator=(const vtkGaussianArtifactScoreFilter&) = delete;
};

#endif

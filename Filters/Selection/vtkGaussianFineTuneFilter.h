/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianFineTuneFilter.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianFineTuneFilter
 * @brief   Repair after a clean-up (issue 20): deletes Gaussians from a snapshot, fine-tunes the
 *          rest for N iterations with the built-in CPU trainer and measures the three states,
 *          what `vis4gs repair` does (Core/Selection/FineTune.h), as a VTK filter.
 *
 * Input port 0 is the snapshot, a Gaussian scene polydata with GaussianId (DESIGN §2), as
 * vtkGaussianTrainingLogReader's port 0 gives it (with the SH rest: LoadSHRest on). The
 * Gaussians to delete are those where the point-data array RemovalArrayName is non-zero
 * (default "RuleSelected", vtkGaussianRuleSelectionFilter's Mark output), or, when RemovedIds is
 * set, those whose GaussianId it lists. The source iteration is SourceIteration, or with the
 * default -1 the input's DATA_TIME_STEP (the reader sets it to the snapshot's iteration).
 *
 * Input port 1 is the camera table (vis4gs::CamerasToTable columns), as the reader's port 1
 * gives it: images "/images/<name>" are read from the training log its field data
 * TrainingLogFile names (as vtkGaussianArtifactScoreFilter does), other paths from their files.
 * Every camera needs an image.
 *
 * Input port 2 (optional) is the removal's per-view table of the same deletion
 * (vtkGaussianRemovalEffectFilter's port 0, e.g. the preview the application's clean-up panel
 * shows): its "before" and "after" figures are the source and deleted states', taken as they
 * are instead of measured again (vis4gs::FineTuneOptions::Measure off: the log's metrics rows
 * are then the trainer's own), and only the repaired state is measured, after the fine-tune.
 *
 * Output port 0 is the repaired Gaussians (polydata, GaussianId kept). Output port 1 is a
 * vtkTable of the figures, repair.csv's rows and columns (vis4gs::FineTuneFigureColumns():
 * view, split, psnr_source, psnr_deleted, psnr_repaired, ssim_..., l1_...): one "mean" row per
 * split, then one row per view. With OutputLogFileName set, the repaired run's training log is
 * written there (the source snapshot, the deletion as prune events at the source iteration,
 * the fine-tune's iterations; temporary file renamed). Progress events follow the iterations;
 * AbortExecute (e.g. set from a progress observer) stops after the current iteration, leaves
 * both outputs empty and writes no log.
 */
#ifndef vtkGaussianFineTuneFilter_h
#define vtkGaussianFineTuneFilter_h

#include "vis4gsFiltersSelectionModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"
#include "vtkSmartPointer.h" // For RemovedIds

#include <string> // For the names

class vtkIdTypeArray;
class vtkTable;

class VIS4GSFILTERSSELECTION_EXPORT vtkGaussianFineTuneFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkGaussianFineTuneFilter* New();
  vtkTypeMacro(vtkGaussianFineTuneFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The camera table (input port 1).
  void SetCamerasData(vtkTable* cameras);
  void SetCamerasConnection(vtkAlgorithmOutput* output);

  ///@{
  /// The removal's per-view table (input port 2, optional; see above). Default none.
  void SetRemovalFiguresData(vtkTable* figures);
  void SetRemovalFiguresConnection(vtkAlgorithmOutput* output);
  ///@}

  /// The figures table (output port 1) after an update.
  vtkTable* GetFiguresOutput();

  ///@{
  /// Point-data array marking the Gaussians to delete (non-zero). Default "RuleSelected".
  vtkSetStdStringFromCharMacro(RemovalArrayName);
  vtkGetCharFromStdStringMacro(RemovalArrayName);
  ///@}

  ///@{
  /// GaussianIds to delete instead of RemovalArrayName's; default nullptr (use the array).
  void SetRemovedIds(vtkIdTypeArray* ids);
  vtkIdTypeArray* GetRemovedIds();
  ///@}

  ///@{
  /// The snapshot's iteration; default -1: the input's DATA_TIME_STEP.
  vtkSetClampMacro(SourceIteration, int, -1, VTK_INT_MAX);
  vtkGetMacro(SourceIteration, int);
  ///@}

  ///@{
  /// Fine-tuning iterations. Default 50.
  vtkSetClampMacro(Iterations, int, 1, VTK_INT_MAX);
  vtkGetMacro(Iterations, int);
  ///@}

  ///@{
  /// Learning-rate warm-up (vis4gs::FineTuneOptions::WarmupIterations): the j-th of the first
  /// W iterations uses j / (W + 1) of every learning rate; 0: none. Default 10, as `vis4gs
  /// repair --warmup`.
  vtkSetClampMacro(WarmupIterations, int, 0, VTK_INT_MAX);
  vtkGetMacro(WarmupIterations, int);
  ///@}

  ///@{
  /// Optimise the positions too. Default off (bit for bit as in the snapshot).
  vtkSetMacro(FreePositions, bool);
  vtkGetMacro(FreePositions, bool);
  vtkBooleanMacro(FreePositions, bool);
  ///@}

  ///@{
  /// Keep the trainer's densification schedule. Default off (no densification, no opacity
  /// reset).
  vtkSetMacro(Densify, bool);
  vtkGetMacro(Densify, bool);
  vtkBooleanMacro(Densify, bool);
  ///@}

  ///@{
  /// The trainer's random seed (camera order). Default 0.
  vtkSetMacro(Seed, vtkTypeUInt64);
  vtkGetMacro(Seed, vtkTypeUInt64);
  ///@}

  ///@{
  /// OpenMP threads; default 0: OpenMP's default.
  vtkSetClampMacro(NumberOfThreads, int, 0, VTK_INT_MAX);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  ///@{
  /// The repaired run's training log; default empty: none written.
  vtkSetStdStringFromCharMacro(OutputLogFileName);
  vtkGetCharFromStdStringMacro(OutputLogFileName);
  ///@}

  ///@{
  /**
   * For `vis4gs repair` (issue 33), each default the filter's earlier behaviour:
   * ImageDirectory, training images matched to the cameras by name (up to the first '.')
   * instead of the cameras' own (default empty: their own); the repaired log's Producer
   * (default "vtkGaussianFineTuneFilter"), SceneName (default empty: the cameras' log's scene
   * name, if any) and EmbedImages (1 embeds the images, 0 names their files; default -1: as
   * the cameras' log does, 0 without one); MetricsInterval, the log's metrics rows every N
   * iterations (vis4gs::FineTuneOptions::MetricsInterval; default 0: at most 10 rows).
   */
  vtkSetStdStringFromCharMacro(ImageDirectory);
  vtkGetCharFromStdStringMacro(ImageDirectory);
  vtkSetStdStringFromCharMacro(Producer);
  vtkGetCharFromStdStringMacro(Producer);
  vtkSetStdStringFromCharMacro(SceneName);
  vtkGetCharFromStdStringMacro(SceneName);
  vtkSetClampMacro(EmbedImages, int, -1, 1);
  vtkGetMacro(EmbedImages, int);
  vtkSetClampMacro(MetricsInterval, int, 0, VTK_INT_MAX);
  vtkGetMacro(MetricsInterval, int);
  ///@}

  ///@{
  /// After an update: the Gaussians deleted, the last completed iteration (-1 before), the
  /// seconds of the iterations and of the measurement.
  vtkGetMacro(NumberOfRemoved, vtkIdType);
  vtkGetMacro(LastIteration, int);
  vtkGetMacro(TrainSeconds, double);
  vtkGetMacro(MeasureSeconds, double);
  ///@}

protected:
  vtkGaussianFineTuneFilter();
  ~vtkGaussianFineTuneFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  std::string RemovalArrayName = "RuleSelected";
  vtkSmartPointer<vtkIdTypeArray> RemovedIds;
  int SourceIteration = -1;
  int Iterations = 50;
  int WarmupIterations = 10;
  bool FreePositions = false;
  bool Densify = false;
  vtkTypeUInt64 Seed = 0;
  int NumberOfThreads = 0;
  std::string OutputLogFileName;
  std::string ImageDirectory;
  std::string Producer = "vtkGaussianFineTuneFilter";
  std::string SceneName;
  int EmbedImages = -1;
  int MetricsInterval = 0;
  vtkIdType NumberOfRemoved = 0;
  int LastIteration = -1;
  double TrainSeconds = 0;
  double MeasureSeconds = 0;

private:
  vtkGaussianFineTuneFilter(const vtkGaussianFineTuneFilter&) = delete;
  void operator=(const vtkGaussianFineTuneFilter&) = delete;
};

#endif

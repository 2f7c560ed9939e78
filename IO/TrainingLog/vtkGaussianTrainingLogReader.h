/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianTrainingLogReader.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianTrainingLogReader
 * @brief   Reads the HDF5 training log (DESIGN §3) into a Gaussian scene and three tables.
 *
 * Outputs:
 * - port 0, vtkPolyData: the Gaussians of the logged snapshot nearest to the requested
 *   iteration (DESIGN §2 arrays: GaussianId as pedigree ids, LogScale, Rotation,
 *   OpacityLogit, SH, Opacity, Scale; grad_accum/denom when LoadStatistics is on). The
 *   iteration actually loaded is reported by GetLoadedIteration().
 * - port 1, vtkTable: cameras, one row per view (vis4gs::CamerasToTable columns). Image
 *   paths relative to the log are made absolute; an image inside the log keeps the path
 *   "/images/<name>", and the field-data string `TrainingLogFile` (the log's absolute path)
 *   lets vtkGaussianArtifactScoreFilter read it from the log.
 * - port 2, vtkTable: metrics, one row per logged iteration: Iteration, NumGaussians, Loss,
 *   L1, PSNR, SSIM, LPIPS, ElapsedSeconds from /metrics and TestL1, TestPSNR, TestSSIM,
 *   TestLPIPS, TestLoss from /metrics/test, merged by iteration (NaN where not measured);
 *   with MetricsAsLogged, the rows as the log holds them instead (see there).
 * - port 3, vtkTable: events in training order: Iteration, Kind (1 clone, 2 split,
 *   3 prune), Parent, Child (-1 for prunes); its field data holds `InitialIds` (the ids of
 *   the first snapshot) and `LastIteration` (the planned last iteration, or the last
 *   snapshot's if later), what vtkGaussianGenealogyTreeFilter reads when connected to it.
 *
 * The logged snapshot iterations are reported as TIME_STEPS; UPDATE_TIME_STEP (or, without
 * one, Iteration; -1 = the last snapshot) picks the snapshot. Only the outputs a request
 * asks for are read: updating port 0 reads one snapshot (the SH rest unless
 * LoadSHRest is off), updating a table reads that table. GetPropertyHistory() returns the
 * history of some ids across all snapshots with hyperslab reads.
 *
 * Missing optional groups are listed by GetLack(i); with Repair on, broken content is
 * repaired in memory and listed by GetRepair(i); otherwise it is an error.
 */
#ifndef vtkGaussianTrainingLogReader_h
#define vtkGaussianTrainingLogReader_h

#include "vis4gsIOTrainingLogModule.h" // For export macro
#include "vtkAlgorithm.h"

class vtkIdTypeArray;
class vtkPolyData;
class vtkTable;

class VIS4GSIOTRAININGLOG_EXPORT vtkGaussianTrainingLogReader : public vtkAlgorithm
{
public:
  static vtkGaussianTrainingLogReader* New();
  vtkTypeMacro(vtkGaussianTrainingLogReader, vtkAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The training log (.h5). Default: none.
  vtkSetFilePathMacro(FileName);
  vtkGetFilePathMacro(FileName);
  ///@}

  ///@{
  /// Iteration to load when the request has no UPDATE_TIME_STEP; the nearest logged snapshot
  /// is loaded. Default: -1 (the last snapshot).
  vtkSetMacro(Iteration, int);
  vtkGetMacro(Iteration, int);
  ///@}

  ///@{
  /// Load the SH coefficients beyond the DC term. Default: on, as `vis4gs analyze` reads a
  /// snapshot, so that the blur and needle scores downstream (which render the loss maps with
  /// every SH degree) are the application's; off keeps 3 SH values per Gaussian.
  vtkSetMacro(LoadSHRest, bool);
  vtkGetMacro(LoadSHRest, bool);
  vtkBooleanMacro(LoadSHRest, bool);
  ///@}

  ///@{
  /// Arrays to load besides GaussianId and the points. Defaults: LogScale, Rotation,
  /// OpacityLogit and SH on; the densification statistics (grad_accum, denom) off.
  vtkSetMacro(LoadScales, bool);
  vtkGetMacro(LoadScales, bool);
  vtkBooleanMacro(LoadScales, bool);
  vtkSetMacro(LoadRotations, bool);
  vtkGetMacro(LoadRotations, bool);
  vtkBooleanMacro(LoadRotations, bool);
  vtkSetMacro(LoadOpacities, bool);
  vtkGetMacro(LoadOpacities, bool);
  vtkBooleanMacro(LoadOpacities, bool);
  vtkSetMacro(LoadSH, bool);
  vtkGetMacro(LoadSH, bool);
  vtkBooleanMacro(LoadSH, bool);
  vtkSetMacro(LoadStatistics, bool);
  vtkGetMacro(LoadStatistics, bool);
  vtkBooleanMacro(LoadStatistics, bool);
  ///@}

  ///@{
  /**
   * Port 2 as the log holds it: every /metrics row in its order, then every /metrics/test
   * row, with the columns Iteration, NumGaussians, Loss, L1, PSNR, SSIM, LPIPS,
   * ElapsedSeconds of the row and Split (0 a /metrics row, 1 a /metrics/test row: the camera
   * table's column and values, vis4gs::arrays::CameraSplit), no Test*
   * columns. The merged table (off) has one row per iteration for the timeline, which keeps
   * only the first test row of an iteration logged twice and sorts the rows; `vis4gs compare`
   * writes each row (metrics.csv). Default: off.
   */
  vtkSetMacro(MetricsAsLogged, bool);
  vtkGetMacro(MetricsAsLogged, bool);
  vtkBooleanMacro(MetricsAsLogged, bool);
  ///@}

  ///@{
  /// Repair broken content (listed by GetRepair) instead of failing. Default: off.
  vtkSetMacro(Repair, bool);
  vtkGetMacro(Repair, bool);
  vtkBooleanMacro(Repair, bool);
  ///@}

  /// Iteration of the snapshot in output 0 after the last update (-1 before).
  vtkGetMacro(LoadedIteration, int);

  /**
   * Lets the file go until the next update or query, which open it again; the outputs stay.
   * HDF5 shares one open file among the handles of a process, so a reader of a log still being
   * written sees what the writer added only when no other handle of the file stays open: a
   * reader whose port is done (vtkGaussianSession's events reader, once the tree is built)
   * closes it.
   */
  void CloseFile();

  ///@{
  /// Logged snapshot iterations (valid after UpdateInformation()).
  int GetNumberOfSnapshots();
  int GetSnapshotIteration(int i);
  /// The logged snapshot nearest @p iteration (-1 without snapshots).
  int FindNearestSnapshot(int iteration);
  /// Number of Gaussians in the snapshot of @p iteration (0 when there is none).
  vtkIdType GetSnapshotSize(int iteration);
  ///@}

  ///@{
  /// What the file lacks, and the repairs made (valid after UpdateInformation()).
  int GetNumberOfLacks();
  const char* GetLack(int i);
  int GetNumberOfRepairs();
  const char* GetRepair(int i);
  ///@}

  ///@{
  /**
   * The log's header and contents (valid after UpdateInformation()): the trainer that wrote
   * it, its scene name, the planned last iteration and the trainer's SH degree; whether it
   * holds cameras, metrics and events (what updating ports 1, 2 and 3 would read), whether it
   * has an /images group (a fine-tune of it embeds its images too, as `vis4gs repair` does) and
   * the names of the training images stored inside it ("/images/<name>" in the cameras table).
   */
  const char* GetProducer();
  const char* GetSceneName();
  int GetPlannedIterations();
  int GetTrainerSHDegree();
  bool HasCameras();
  bool HasMetrics();
  bool HasEvents();
  bool HasImages();
  int GetNumberOfEmbeddedImages();
  const char* GetEmbeddedImageName(int i);
  ///@}

  /// Number of snapshots read so far (each update of output 0 reads at most one).
  vtkGetMacro(SnapshotReads, int);

  /**
   * Fills @p output with the history of @p ids across all snapshots: one row per (id,
   * snapshot holding it), ordered by id then iteration, with columns GaussianId, Iteration,
   * Position (3), LogScale (3), Rotation (4), OpacityLogit, SHDC (3), Opacity, Scale (3)
   * (names in vis4gs::arrays). This is the history vtkGaussianTimelineView draws: any column
   * as its HistoryProperty, a vector by its largest component (Scale) or by the one its
   * HistoryComponent names (Position X, Y or Z). Returns 0 (and reports an error) on failure.
   */
  int GetPropertyHistory(vtkIdTypeArray* ids, vtkTable* output);

  ///@{
  /// The outputs.
  vtkPolyData* GetGaussiansOutput();
  vtkTable* GetCamerasOutput();
  vtkTable* GetMetricsOutput();
  vtkTable* GetEventsOutput();
  ///@}

  vtkTypeBool ProcessRequest(vtkInformation* request,
    vtkInformationVector** inInfo,
    vtkInformationVector* outInfo) override;

protected:
  vtkGaussianTrainingLogReader();
  ~vtkGaussianTrainingLogReader() override;

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation* request, vtkInformationVector* outInfo);
  int RequestData(vtkInformation* request, vtkInformationVector* outInfo);
  bool OpenLog();
  /// OpenLog() after CloseFile() (a query needs the file).
  void ReopenClosedFile();

  char* FileName = nullptr;
  int Iteration = -1;
  bool LoadSHRest = true;
  bool LoadScales = true;
  bool LoadRotations = true;
  bool LoadOpacities = true;
  bool LoadSH = true;
  bool LoadStatistics = false;
  bool MetricsAsLogged = false;
  bool Repair = false;
  int LoadedIteration = -1;
  int SnapshotReads = 0;

private:
  vtkGaussianTrainingLogReader(const vtkGaussianTrainingLogReader&) = delete;
  void operator=(const vtkGaussianTrainingLogReader&) = delete;

  class vtkInternals;
  vtkInternals* Internals;
};

#endif

/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianSession.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianSession
 * @brief   The pipeline from one file to every view in one algorithm (DESIGN §8, "One
 *          pipeline object"), shared by the application, the commands, Python and ParaView.
 *
 * FileName is a training log or a Gaussian scene file, told apart by content (the HDF5
 * signature), not by name; only a file named .h5 or .hdf5 without the signature is taken for a
 * (damaged) log, so that the error is the log reader's (IsTrainingLogPath()). The session owns the
 * readers and filters a script would connect and connects them the one way every client gets:
 *
 * - a log: vtkGaussianTrainingLogReader (the snapshot nearest Iteration; -1 the last), its
 *   cameras, metrics and events, and vtkGaussianGenealogyTreeFilter on the events of a second
 *   reader of the same log (so that the tree is built without re-reading the snapshot);
 * - a scene file: vtkGaussianSceneReader and vtkGaussianCameraReader on CamerasFileName or,
 *   when that is empty, on the `cameras.json` beside the file or two folders up (the INRIA
 *   model layout); no camera file found gives an empty camera table, not an error;
 * - then vtkGaussianArtifactScoreFilter (when ComputeScores: which scores and their parameters
 *   are GetScoreFilter()'s settings) and vtkGaussianRuleSelectionFilter (when Rule is not
 *   empty: the `RuleSelected` marks), and vtkGaussianRemovalEffectFilter on the Gaussians
 *   selected by input port 0.
 *
 * Output ports (the GaussiansPort ... RemovalTotalsPort constants): 0 the Gaussians with the
 * score arrays (vtkPolyData, DESIGN §2), 1 the cameras (vtkTable), 2 the metrics (train and
 * Test* columns; empty for a scene file), 3 the densification tree (vtkTree; empty without
 * events), 4 its family bands, 5 the property history of the selected Gaussians over the
 * snapshots (vtkGaussianTrainingLogReader::GetPropertyHistory's table; empty for a scene
 * file or no selection), 6 and 7 the removal effect of the selected Gaussians (the removal
 * filter's per-view and totals tables; empty without a selection), 10 the removal's preview
 * renders of camera RemovalPreviewView (the removal filter's port 2, a vtkImageData; empty
 * without a selection or with RemovalPreviewView -1). Only the requested port
 * is computed: the tree is not built to show a snapshot, and the history, which reads every
 * snapshot, only when asked for.
 *
 * Input port 0 (optional) is the selection, a vtkSelection of pedigree ids (GaussianId), e.g.
 * vtkGaussianSelectionHub's annotation link's current selection, or SetSelectedIds(). A new
 * selection re-executes ports 5 to 7; ports 0 to 4 then only pass their cached data on.
 *
 * The fine-tune and comparison filters take the session's Gaussians (and cameras) as their
 * inputs: GetFineTuneFilter() and GetComparisonFilter(). The comparison's second state is
 * CompareFileName (a log's snapshot nearest CompareIteration, or a scene file), read by a second
 * session of its own (GetComparedSession(), no scores); ports 8 and 9 are the comparison's
 * Gaussian-by-Gaussian table and its per-camera figures of both states (empty without
 * CompareFileName; the figures also without cameras). The cameras of the comparison are
 * CamerasFileName when set (also for a log), else the log's own, else the compared log's, else
 * the cameras.json found beside FileName (vtkGaussianCameraReader::FindSceneCamerasFile), the
 * rule of `vis4gs compare`. The sub-filters' settings are theirs (GetScoreFilter(),
 * ...); changing them re-executes the session. Errors of any of them are reported as the
 * session's, naming FileName.
 */
#ifndef vtkGaussianSession_h
#define vtkGaussianSession_h

#include "vis4gsFiltersSessionModule.h" // For export macro
#include "vtkAlgorithm.h"

#include <string> // For FileName, CamerasFileName, ImageDirectory, IdProperty, Rule

class vtkGaussianArtifactScoreFilter;
class vtkGaussianCameraReader;
class vtkGaussianFineTuneFilter;
class vtkGaussianGenealogyTreeFilter;
class vtkGaussianRemovalEffectFilter;
class vtkGaussianRuleSelectionFilter;
class vtkGaussianSceneReader;
class vtkGaussianStateComparisonFilter;
class vtkGaussianTrainingLogReader;
class vtkIdTypeArray;
class vtkImageData;
class vtkPolyData;
class vtkSelection;
class vtkTable;

class VIS4GSFILTERSSESSION_EXPORT vtkGaussianSession : public vtkAlgorithm
{
public:
  static vtkGaussianSession* New();
  vtkTypeMacro(vtkGaussianSession, vtkAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The output ports.
  enum Ports
  {
    GaussiansPort = 0,
    CamerasPort = 1,
    MetricsPort = 2,
    TreePort = 3,
    BandsPort = 4,
    HistoryPort = 5,
    RemovalViewsPort = 6,
    RemovalTotalsPort = 7,
    ComparisonPort = 8,
    ComparisonViewsPort = 9,
    RemovalPreviewPort = 10,
    NumberOfPorts = 11
  };

  ///@{
  /**
   * The training log (.h5) or scene file (.ply, .splat, .spz, ...), by content. Default empty.
   */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /**
   * For a log: the snapshot nearest this iteration; -1 (the default) the last. Ignored for a
   * scene file.
   */
  vtkSetMacro(Iteration, int);
  vtkGetMacro(Iteration, int);
  ///@}

  ///@{
  /**
   * For a scene file: its cameras (cameras.json, a COLMAP dataset folder, a transforms*.json);
   * empty (the default) looks for cameras.json beside the file and two folders up. A log has
   * its own cameras and ignores this.
   */
  vtkSetStdStringFromCharMacro(CamerasFileName);
  vtkGetCharFromStdStringMacro(CamerasFileName);
  ///@}

  ///@{
  /**
   * Training images matched to the cameras by name, for the scores, the removal effect, the
   * fine-tune and the comparison. Default empty: the cameras' own images (a log's are inside it).
   */
  vtkSetStdStringFromCharMacro(ImageDirectory);
  vtkGetCharFromStdStringMacro(ImageDirectory);
  ///@}

  ///@{
  /**
   * For a scene file: the integer property holding the GaussianIds (vtkGaussianSceneReader).
   * Default empty: the row numbers.
   */
  vtkSetStdStringFromCharMacro(IdProperty);
  vtkGetCharFromStdStringMacro(IdProperty);
  ///@}

  ///@{
  /**
   * For a log: read the SH coefficients beyond degree 0 only for snapshots of at most this many
   * Gaussians (memory: 45 floats a Gaussian). Default -1: always.
   */
  vtkSetMacro(FullSHLimit, vtkIdType);
  vtkGetMacro(FullSHLimit, vtkIdType);
  ///@}

  ///@{
  /**
   * The second state of the comparison (ports 8 and 9): a training log or a scene file, by
   * content. Default empty: no comparison.
   */
  void SetCompareFileName(const char* name);
  const char* GetCompareFileName();
  ///@}

  ///@{
  /**
   * For a log as CompareFileName: the snapshot nearest this iteration; -1 (the default) the last.
   */
  void SetCompareIteration(int iteration);
  int GetCompareIteration();
  ///@}

  ///@{
  /**
   * The camera (index in the cameras port) whose renders before and after the removal of the
   * selection port 10 holds (vtkGaussianRemovalEffectFilter::PreviewView). A new one renders
   * those two images only: the removal's tables are kept. Default -1: none.
   */
  void SetRemovalPreviewView(vtkIdType camera);
  vtkIdType GetRemovalPreviewView();
  ///@}

  ///@{
  /**
   * Compute the scores of GetScoreFilter() on the Gaussians port. Default on.
   */
  vtkSetMacro(ComputeScores, bool);
  vtkGetMacro(ComputeScores, bool);
  vtkBooleanMacro(ComputeScores, bool);
  ///@}

  ///@{
  /**
   * A selection rule (the language of `vis4gs analyze --select`); when not empty the
   * Gaussians port carries its `RuleSelected` marks, computed after the scores (the rule's
   * view count is the score filter's views used). Default empty.
   */
  vtkSetStdStringFromCharMacro(Rule);
  vtkGetCharFromStdStringMacro(Rule);
  ///@}

  ///@{
  /**
   * The selection as GaussianIds, in place of a vtkSelection on input port 0 (which wins when
   * connected). Null (the default): none.
   */
  void SetSelectedIds(vtkIdTypeArray* ids);
  vtkGetObjectMacro(SelectedIds, vtkIdTypeArray);
  ///@}

  ///@{
  /**
   * The history port takes at most this many of the selected ids, the smallest ones (the
   * property history reads every snapshot for each id: a brush over millions of Gaussians
   * would read them all for a chart that draws a few lines; the application takes 16).
   * 0 (the default): every selected id.
   */
  vtkSetClampMacro(MaximumHistoryIds, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(MaximumHistoryIds, vtkIdType);
  ///@}

  ///@{
  /**
   * Gaussians given as data in place of FileName's snapshot or scene: the Gaussians port
   * scores (and marks by Rule) these, while FileName still gives the cameras and their images.
   * The application scores the snapshot it shows this way on a second session in a worker
   * thread, sharing the first session's arrays instead of reading the snapshot again. Null
   * (the default): FileName's Gaussians.
   */
  void SetGaussiansData(vtkPolyData* gaussians);
  vtkPolyData* GetGaussiansData();
  ///@}

  ///@{
  /**
   * Cameras given as data (the table of vis4gs::arrays columns; a log's carry its
   * TrainingLogFile, through which the images inside it are read) in place of FileName's or
   * CamerasFileName's. With GaussiansData too the session reads no file at all and FileName
   * only names its errors. Null (the default): the file's cameras.
   */
  void SetCamerasData(vtkTable* cameras);
  vtkTable* GetCamerasData();
  ///@}

  /// Connects the selection (input port 0), e.g. an annotation link's selection output.
  void SetSelectionConnection(vtkAlgorithmOutput* output);
  void SetSelectionData(vtkSelection* selection);

  ///@{
  /**
   * After an update: whether FileName is a training log, and the loaded iteration (-1 for a
   * scene file).
   */
  vtkGetMacro(IsTrainingLog, bool);
  vtkGetMacro(LoadedIteration, int);
  ///@}

  /// Whether @p path starts with the HDF5 signature (at offset 0, 512, 1024, ...).
  static bool IsTrainingLogFile(const char* path);

  /// Whether the session reads @p path as a training log: IsTrainingLogFile(), or a name
  /// ending in .h5 or .hdf5 (any case; a damaged log is then reported by the log reader).
  static bool IsTrainingLogPath(const char* path);

  ///@{
  /**
   * The owned readers and filters, for their settings and their figures after an update. The
   * log reader also answers the header and snapshot queries (GetNumberOfSnapshots, ...).
   * GetGenealogyFilter, GetFineTuneFilter and GetComparisonFilter connect the session first,
   * so that a client may update them on their own, also in another thread than the session's
   * (the application builds the tree beside the snapshot read): the session reports its
   * sub-filters' errors and progress only while it executes, in its own thread.
   */
  vtkGaussianTrainingLogReader* GetLogReader();
  vtkGaussianSceneReader* GetSceneReader();
  vtkGaussianCameraReader* GetCameraReader();
  vtkGaussianArtifactScoreFilter* GetScoreFilter();
  vtkGaussianGenealogyTreeFilter* GetGenealogyFilter();
  vtkGaussianRuleSelectionFilter* GetRuleFilter();
  vtkGaussianRemovalEffectFilter* GetRemovalEffectFilter();
  vtkGaussianFineTuneFilter* GetFineTuneFilter();
  vtkGaussianStateComparisonFilter* GetComparisonFilter();
  ///@}

  /**
   * The session reading CompareFileName (its readers' settings, its Gaussians and cameras
   * ports), created on first use.
   */
  vtkGaussianSession* GetComparedSession();

  ///@{
  /**
   * The outputs, typed.
   */
  vtkPolyData* GetGaussiansOutput();
  vtkTable* GetCamerasOutput();
  vtkTable* GetMetricsOutput();
  vtkTable* GetHistoryOutput();
  vtkTable* GetComparisonOutput();
  vtkTable* GetComparisonViewsOutput();
  vtkTable* GetRemovalViewsOutput();
  vtkTable* GetRemovalTotalsOutput();
  vtkImageData* GetRemovalPreviewOutput();
  ///@}

  /// Includes the owned readers' and filters' settings.
  vtkMTimeType GetMTime() override;

  vtkTypeBool ProcessRequest(vtkInformation* request,
    vtkInformationVector** inInfo,
    vtkInformationVector* outInfo) override;

protected:
  vtkGaussianSession();
  ~vtkGaussianSession() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;

  std::string FileName;
  int Iteration = -1;
  std::string CamerasFileName;
  std::string ImageDirectory;
  std::string IdProperty;
  vtkIdType FullSHLimit = -1;
  bool ComputeScores = true;
  std::string Rule;
  vtkIdTypeArray* SelectedIds = nullptr;
  vtkIdType MaximumHistoryIds = 0;
  bool IsTrainingLog = false;
  int LoadedIteration = -1;

private:
  vtkGaussianSession(const vtkGaussianSession&) = delete;
  void operator=(const vtkGaussianSession&) = delete;

  struct vtkInternals;
  vtkInternals* Internals;

  bool Connect();
  bool ConnectComparison();
  int RequestDataObject(vtkInformationVector* outInfo);
  int RequestData(vtkInformation* request,
    vtkInformationVector** inInfo,
    vtkInformationVector* outInfo);
  bool ProducePort(int port, vtkInformationVector** inInfo, vtkInformationVector* outInfo);
  bool SelectionIds(vtkInformationVector** inInfo, vtkIdTypeArray* ids);
};

#endif

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSDocument.h
 * @brief What `vis4gs view` opens: a training log (.h5) or a Gaussian scene, read through the
 * vtkGaussianSession a Python script (`vis4gs.open`) or a ParaView state ("Vis4GS Session")
 * uses: its Gaussians, cameras, metrics, tree, bands and property-history ports are the views'
 * inputs, so that the views get the arrays a script computes
 * (Documentation/dev/ARCHITECTURE.md, "The application's data flow"). The scores run in the
 * background on a second session given the shown snapshot and the score cameras
 * (ComputeScores); its Gaussians port, carrying the score arrays, then becomes the views'
 * input (Scored, GaussiansConnection). No Qt here: the main window runs Load() in a worker
 * thread (the filters' progress events feed its progress callback) and connects the views to
 * the ports in the GUI thread.
 */
#ifndef Vis4GSDocument_h
#define Vis4GSDocument_h

#include "vtkSmartPointer.h"

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

class vtkAlgorithmOutput;
class vtkGaussianSession;
class vtkGaussianTrainingLogReader;
class vtkPolyData;
class vtkTable;
class vtkTree;

namespace vis4gs
{
struct RemovalBaseline;
}

struct Vis4GSDocument
{
  std::string Path;
  bool IsLog = false;
  /// Gaussians at Iteration (or the scene file) as read, without scores: the scores' input.
  vtkSmartPointer<vtkPolyData> Scene;
  /// The session that scored Scene (ComputeScores' result for it; null until a first stage
  /// of scores lands for this snapshot): its Gaussians port is what the views show.
  vtkSmartPointer<vtkGaussianSession> Scored;
  /// Cameras: the log reader's cameras port (images inside the log named "/images/<name>",
  /// the log in its TrainingLogFile field data), or the scene file's cameras.
  vtkSmartPointer<vtkTable> Cameras;
  /// The log reader's metrics port: train and test columns merged by iteration (TestPSNR...).
  vtkSmartPointer<vtkTable> Metrics;
  /// Separate test metrics for vtkGaussianTimelineView::SetTestMetrics; null, since Metrics
  /// holds them (the view draws its Test-prefixed columns).
  vtkSmartPointer<vtkTable> TestMetrics;
  vtkSmartPointer<vtkTree> Tree;   ///< genealogy filter output (null when the log has no events)
  vtkSmartPointer<vtkTable> Bands; ///< the genealogy filter's family bands
  /// The pipeline: Scene, Cameras, Metrics, Tree and Bands are its ports' data; the timeline
  /// takes its history port, the hub's selection on its selection input.
  vtkSmartPointer<vtkGaussianSession> Session;
  /// The session's log reader (null for a scene file): the header, the snapshot list and sizes
  /// (the text of panel C, the iteration slider).
  vtkSmartPointer<vtkGaussianTrainingLogReader> Reader;
  std::vector<int> Snapshots;
  int Iteration = -1;  ///< iteration of Scene (-1 for a PLY)
  std::string Summary; ///< training log text for panel C
  /// Why the tree view is empty although the log has events (they are damaged: the reader's or
  /// the genealogy filter's error); empty when the tree is there or the log has no events.
  std::string TreeUnavailable;
  /// What Load() could not open while the rest of the file opened (damaged events, a snapshot
  /// that cannot be read): the window and --dump-inputs say each once, on standard error.
  std::vector<std::string> Warnings;
  double Seconds = 0.0; ///< load time

  /// Progress callback: fraction in [0, 1] and a message; a negative fraction is a step of
  /// unknown length (a busy indicator), e.g. reading a scene file.
  using Progress = std::function<void(double, const std::string&)>;

  /**
   * Loads @p path; throws std::runtime_error naming the file on failure. Damaged parts of a log
   * do not fail the load when the rest is intact: damaged events leave the tree out
   * (TreeUnavailable), a last snapshot that cannot be read is replaced by the latest one that
   * can (and left out of Snapshots); both go to Warnings. A scene file gets
   * the cameras of @p cameras (vtkGaussianCameraReader::FindSceneCamerasFile(); a log has its own
   * and ignores both) and the training images of @p images, matched to them by name
   * (Vis4GSAttachImagesByName(), in the table's Image column).
   */
  static std::shared_ptr<Vis4GSDocument> Load(const std::string& path,
    const Progress& progress,
    const std::string& cameras = std::string(),
    const std::string& images = std::string());

  /// The views' Gaussians: Scored's Gaussians port once the scores landed, else Session's.
  vtkAlgorithmOutput* GaussiansConnection() const;
  /// The data of GaussiansConnection() (Scene with the score arrays once they landed).
  vtkPolyData* Shown() const;

  /// Replaces Scene with the snapshot nearest @p iteration (logs only), drops Scored; returns
  /// its iteration.
  int LoadIteration(int iteration);
  /// LoadIteration() of the last snapshot, else of the latest one that can be read: those that
  /// cannot are removed from Snapshots and named in Warnings. Throws when none can be read.
  void LoadLatestReadableSnapshot();

  /// The window gives the timeline the history of at most this many selected Gaussians.
  static constexpr int HistoryLines = 16;

  /// The selection whose history DumpInputs writes: HistoryLines Gaussians of Scene at
  /// evenly spread rows (row k * n / HistoryLines), so that old and young ones are in it.
  std::vector<std::int64_t> HistoryDumpSelection() const;

  /**
   * The camera table for vtkGaussianArtifactScoreFilter: Cameras itself (the filter reads the
   * images inside the log through the table's TrainingLogFile, as in a script), after counting
   * the cameras with an image into CamerasWithImages (a scene file's are those of
   * `--images`; without, 0: the application computes no blur or needle score there). Null
   * without cameras. @p unusedFolder is what
   * embedded images used to be extracted to; ignored.
   */
  vtkSmartPointer<vtkTable> ScoreCameras(const std::string& unusedFolder = std::string());
  /// Number of cameras of ScoreCameras() with an image in the log or on disk (after it ran).
  int CamerasWithImages = 0;

  /**
   * Scores @p scene through a new vtkGaussianSession given @p scene and @p cameras as data
   * (SetGaussiansData, SetCamerasData: no file is read again; @p name names its errors), its
   * score filter set to every score of the registry (Core/Diagnostics/ScoreRegistry.h) that
   * the inputs allow: those that need cameras with @p cameras, those that need images when
   * @p withImages too. Returns that session with its Gaussians port updated: @p scene's arrays
   * and the scores. A session per call, which nothing else touches until it returns, is what
   * lets this run in a worker thread while the GUI draws and reads other snapshots through
   * the document's Session (the newest call's session wins: the window drops older ones).
   * Throws std::runtime_error on failure.
   *
   * With @p baseline, the blur/needle pass (full resolution, with images) also keeps the
   * "before" of a clean-up of @p scene per tile on the renders it makes anyway
   * (vis4gs::RemovalBaselineRecorder): the clean-up panel then renders no training view
   * "before" again. It is left empty when that pass does not run.
   *
   * @p stage is the score filter's ProgressiveStage (1: the first, approximate stage of
   * progressive scores; 0: the settings as given); the result's field data `ScoreStage` says
   * which. When @p stop becomes true the filter stops after the view it is on and this returns
   * nullptr.
   */
  static vtkSmartPointer<vtkGaussianSession> ComputeScores(vtkPolyData* scene,
    vtkTable* cameras,
    bool withImages,
    const Progress& progress,
    vis4gs::RemovalBaseline* baseline = nullptr,
    int stage = 0,
    const std::atomic<bool>* stop = nullptr,
    const std::string& name = std::string());

  /**
   * Writes the views' inputs into @p folder, for comparing the application with a script
   * (`vis4gs view --dump-inputs`): scene.vtp (Shown(): Scene with the score arrays), and
   * as .vtt tables metrics, tree-vertices (the tree's vertex data plus ParentVertex),
   * tree-edges (edge data), bands and history (the session's history port with a selection
   * hub's selection of HistoryDumpSelection() on its input, as the window connects the
   * timeline: what it gets when those Gaussians are selected), each when present. Throws
   * std::runtime_error naming the file on failure.
   */
  void DumpInputs(const std::string& folder) const;

  /**
   * `vis4gs view FILE --dump-inputs=DIR`: loads @p path as the window does, computes the
   * scores the window computes (ScoreCameras, ComputeScores) and writes DumpInputs(). Throws
   * std::runtime_error on failure.
   */
  static void LoadAndDumpInputs(const std::string& path,
    const std::string& cameras,
    const std::string& folder);

  /// Snapshots with at most this many Gaussians are read with every SH degree (view-dependent
  /// colour and exact blur/needle scores); larger ones with degree 0 only (memory).
  static constexpr std::size_t FullShLimit = 2000000;
};

#endif

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSDocument.h
 * @brief What `vis4gs view` opens: a training log (.h5) or a Gaussian scene (.ply/.splat),
 * converted to the VTK data of the linked views (scene polydata, cameras, metrics, genealogy
 * tree and family bands, log summary). No Qt here: the main window runs Load() in a worker
 * thread and hands the result to the views in the GUI thread.
 */
#ifndef Vis4GSDocument_h
#define Vis4GSDocument_h

#include "vtkSmartPointer.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

class vtkPolyData;
class vtkTable;
class vtkTree;

namespace vis4gs
{
class TrainingLogReader;
}

struct Vis4GSDocument
{
  std::string Path;
  bool IsLog = false;
  vtkSmartPointer<vtkPolyData> Scene; ///< Gaussians at Iteration (or the PLY)
  vtkSmartPointer<vtkTable> Cameras;
  vtkSmartPointer<vtkTable> Metrics, TestMetrics;
  vtkSmartPointer<vtkTree> Tree; ///< genealogy (null when the log has no events)
  vtkSmartPointer<vtkTable> Bands;
  std::shared_ptr<vis4gs::TrainingLogReader> Log;
  std::vector<int> Snapshots;
  int Iteration = -1;   ///< iteration of Scene (-1 for a PLY)
  std::string Summary;  ///< training log text for panel C
  double Seconds = 0.0; ///< load time

  /// Progress callback: fraction in [0, 1] and a message; a negative fraction is a step of
  /// unknown length (a busy indicator), e.g. reading a scene file.
  using Progress = std::function<void(double, const std::string&)>;

  /**
   * Loads @p path; throws std::runtime_error naming the file on failure. A scene file gets
   * the cameras of @p cameras (Vis4GSFindSceneCameras(); a log has its own and ignores it).
   */
  static std::shared_ptr<Vis4GSDocument> Load(const std::string& path,
    const Progress& progress,
    const std::string& cameras = std::string());

  /// Replaces Scene with the snapshot nearest @p iteration (logs only); returns its iteration.
  int LoadIteration(int iteration);

  /**
   * Property history of @p ids across the snapshots, in the long format of
   * vtkGaussianTimelineView (Iteration, GaussianId, Opacity, Scale (largest), PositionX..Z).
   * Empty table without a log.
   */
  vtkSmartPointer<vtkTable> History(const std::vector<std::int64_t>& ids) const;

  /**
   * The camera table for vtkGaussianArtifactScoreFilter: a copy of Cameras whose Image column
   * names readable files. Images embedded in the log ("/images/<name>") are written once as
   * PNG into @p folder; relative paths are made relative to the log. Null without cameras.
   * Reads the log (HDF5): call it from the thread that owns the document.
   */
  vtkSmartPointer<vtkTable> ScoreCameras(const std::string& folder);
  /// Number of cameras of ScoreCameras() with an image file (after it ran).
  int CamerasWithImages = 0;

  /**
   * Computes the score arrays of @p scene with vtkGaussianArtifactScoreFilter: NeedleShape
   * always; ViewCoverage with @p cameras; BlurScore and NeedleScore when @p withImages too.
   * Returns a new polydata holding the arrays (the input is not modified, so this can run in
   * a worker thread while the GUI draws @p scene). Throws std::runtime_error on failure.
   */
  static vtkSmartPointer<vtkPolyData> ComputeScores(vtkPolyData* scene,
    vtkTable* cameras,
    bool withImages,
    const Progress& progress);

  /// Snapshots with at most this many Gaussians are read with every SH degree (view-dependent
  /// colour and exact blur/needle scores); larger ones with degree 0 only (memory).
  static constexpr std::size_t FullShLimit = 2000000;
};

#endif

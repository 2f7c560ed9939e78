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

  /// Progress callback: fraction in [0, 1] and a message.
  using Progress = std::function<void(double, const std::string&)>;

  /// Loads @p path; throws std::runtime_error naming the file on failure.
  static std::shared_ptr<Vis4GSDocument> Load(const std::string& path, const Progress& progress);

  /// Replaces Scene with the snapshot nearest @p iteration (logs only); returns its iteration.
  int LoadIteration(int iteration);

  /**
   * Property history of @p ids across the snapshots, in the long format of
   * vtkGaussianTimelineView (Iteration, GaussianId, Opacity, Scale (largest), PositionX..Z).
   * Empty table without a log.
   */
  vtkSmartPointer<vtkTable> History(const std::vector<std::int64_t>& ids) const;
};

#endif

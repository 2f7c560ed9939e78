// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSComparison.h
 * @brief What the comparison window of `vis4gs view A --compare=B` shows (issue 20), without
 * Qt: the two states (two iterations of one log, two logs, or two scenes of the same
 * cameras), their Gaussians matched by id and classified by vtkGaussianStateComparisonFilter
 * (Core/Selection/StateComparison.h, the classification and thresholds of `vis4gs compare`),
 * the resulting sets of ids, and the scenes recoloured by set for the difference overlay.
 */
#ifndef Vis4GSComparison_h
#define Vis4GSComparison_h

#include "StateComparison.h" // vis4gs::StateThresholds

#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <array>
#include <memory>
#include <string>
#include <vector>

class vtkGaussianSession;
class vtkPolyData;
class vtkTable;

struct Vis4GSComparison
{
  /// One side of a comparison.
  struct State
  {
    std::string Path;
    int Iteration = -1; ///< the logged snapshot's iteration; -1 for a scene file
    std::string Name;   ///< "demo.h5 @1000", "cleaned.ply"
    vtkSmartPointer<vtkPolyData> Scene;
    vtkSmartPointer<vtkTable> Cameras;              ///< null when none were found
    vtkSmartPointer<vtkTable> Metrics, TestMetrics; ///< a log's /metrics and /metrics/test
    /// The session that read a log (null for a scene file): the window connects the timeline to
    /// its history port, with the window's selection on its selection input.
    vtkSmartPointer<vtkGaussianSession> Session;
  };

  /// The sets of ids the window lists; a Gaussian of both states may be in several of
  /// MOVED, OPACITY and SCALE (the flags of `vis4gs compare`'s status, e.g. "moved+scale").
  enum Sets
  {
    BORN = 0,
    DIED,
    MOVED,
    OPACITY,
    SCALE,
    UNCHANGED,
    NUMBER_OF_SETS
  };
  /// "born", "died", "moved", "opacity changed", "scale changed", "unchanged".
  static const char* SetName(int set);
  /// The set's colour in the difference overlay (0-255 RGB).
  static std::array<unsigned char, 3> SetColor(int set);

  State A, B;
  bool SameLog = false; ///< A and B are iterations of one log (one metrics curve)
  vis4gs::StateThresholds Thresholds;
  /// vtkGaussianStateComparisonFilter's table: one row per id of either state.
  vtkSmartPointer<vtkTable> Differences;
  /// Sorted ids of each set (after Compare()).
  std::array<std::vector<vtkIdType>, NUMBER_OF_SETS> Ids;
  /// Wall and process CPU seconds of Load() and of the last Compare().
  double LoadSeconds = 0, LoadCpuSeconds = 0, CompareSeconds = 0, CompareCpuSeconds = 0;

  /**
   * Loads state A from @p a (a training log's snapshot nearest @p iterationA, -1 the last, or
   * a scene file) and state B from @p b: "@N" (A's log at N), "FILE@N" (the log FILE at N) or
   * FILE (a log's last snapshot or a scene). Scenes keep their "id" property as ids (as
   * `vis4gs compare` reads them) and get the cameras of @p cameras or beside them. Throws
   * std::runtime_error naming the file and the problem.
   */
  static std::shared_ptr<Vis4GSComparison> Load(const std::string& a,
    int iterationA,
    const std::string& b,
    const std::string& cameras = std::string());

  /// Classifies the Gaussians with @p thresholds and fills Differences and Ids.
  void Compare(const vis4gs::StateThresholds& thresholds);

  /**
   * A copy of state @p side's (0: A, 1: B) scene whose colours are the overlay's: every
   * Gaussian in the colour of its first set in the order died, born, moved, scale changed,
   * opacity changed, unchanged (the SH DC term set to the colour, the rest to 0).
   */
  vtkSmartPointer<vtkPolyData> Overlay(int side) const;
};

#endif

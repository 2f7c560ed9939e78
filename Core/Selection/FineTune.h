// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file FineTune.h
 * @brief Repair after a clean-up (issue 20): fine-tunes a snapshot without the deleted Gaussians
 * for N iterations with the built-in CPU trainer (Trainer.h), and measures the snapshot, the
 * cleaned scene and the repaired one against the training and test images (RemovalEffect.h's
 * figures). The application, `vis4gs repair`, vtkGaussianFineTuneFilter and the Python layer
 * all call FineTune(), so they agree on the figures and on the log.
 *
 * The log (FineTuneOptions::LogPath) continues the source run: its first snapshot is the source
 * snapshot as given (every Gaussian, so that the deletion names Gaussians the log knows), its
 * first event rows are the deletion as prune events at the source iteration, and its
 * iterations follow the source's, so that the genealogy of the repaired run stays one tree.
 * The trainer's schedules see the real iteration numbers (source + 1 .. source + Iterations);
 * every SH degree of the snapshot is active from the start.
 */
#ifndef vis4gs_FineTune_h
#define vis4gs_FineTune_h

#include "ArtifactScores.h" // TrainingImageProvider
#include "Camera.h"
#include "GaussianCloud.h"
#include "ViewTileSums.h" // ViewMetrics

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace vis4gs
{

struct FineTuneOptions
{
  int Iterations = 50; ///< fine-tuning iterations (> 0)
  /// Optimise the positions too; by default they stay bit for bit as in the snapshot (their
  /// learning rate is 0, so Adam leaves them untouched).
  bool FreePositions = false;
  /// Keep the trainer's densification schedule; by default it is off (no clone, split, prune
  /// of low opacity, nor opacity reset), so the only events are the deletion's prunes.
  bool Densify = false;
  /// Learning-rate warm-up (TrainerOptions::LrWarmupIterations): the j-th of the first W
  /// iterations uses j / (W + 1) of every learning rate. Fresh Adam moments make the first
  /// steps about lr in size for every parameter, which throws a converged snapshot off for
  /// the first 10 to 25 iterations; the warm-up keeps the training PSNR from dipping
  /// (Documentation/user-guide.md, "Repair", has the measurements). 0: none.
  int WarmupIterations = 10;
  std::uint64_t Seed = 0; ///< the trainer's seed (camera order, split samples)
  int Threads = 0;        ///< OpenMP threads; 0 uses OpenMP's default
  /// The repaired run's training log; empty: none written. Written to a temporary next to it
  /// and renamed when complete (never left behind when cancelled or on an error).
  std::string LogPath;
  std::string Producer = "vis4gs"; ///< the log's root attribute "producer"
  std::string Scene;               ///< the log's root attribute "scene"
  /// Embed the images in the log (/images/<name>); else /cameras/image holds Camera::ImagePath.
  bool EmbedImages = true;
  /// Called after every iteration with (iterations done, Iterations); returning false cancels
  /// (the result is then Cancelled and no log is written).
  std::function<bool(int done, int total)> Progress;
  /// Measure the three states in every camera (FineTuneResult::Source, Deleted,
  /// RepairedFigures). The log's metrics rows of the first and the last iteration are then
  /// these figures' means (nothing is rendered twice); the trainer measures its own in between
  /// (at most 10 rows: the iterations that are multiples of ceil(Iterations / 10); none for up
  /// to 10 iterations).
  bool Measure = true;
  /// The log's metrics rows at the iterations that are multiples of N (and the first and the
  /// last); 0 (default): at most 10 rows, as above.
  int MetricsInterval = 0;
};

struct FineTuneResult
{
  GaussianCloud Cleaned;  ///< the snapshot without the deleted Gaussians
  GaussianCloud Repaired; ///< the cleaned scene after the fine-tune
  int SourceIteration = 0;
  int LastIteration = 0;            ///< the last completed iteration
  std::vector<std::int64_t> Pruned; ///< the deleted ids, in snapshot order
  /// Per camera (in the order given), NaN where the camera has no image; empty when !Measure
  /// or Cancelled.
  std::vector<ViewMetrics> Source, Deleted, RepairedFigures;
  bool Cancelled = false;
  double TrainSeconds = 0;   ///< wall clock of the fine-tune iterations
  double MeasureSeconds = 0; ///< wall clock of the measurement of the three states
  /// Train and test views the trainer rendered for the log's metrics rows (FineTune's own
  /// measurement of the three states not counted).
  int MetricsRenders = 0;
};

/**
 * Fine-tunes @p snapshot (the log's snapshot of iteration @p sourceIteration, with its ids)
 * without the Gaussians where @p removed is non-zero (one byte per Gaussian), against
 * @p cameras and their images from @p images. Throws std::invalid_argument for a mask of the
 * wrong size, a snapshot without ids, Iterations <= 0 or no training camera;
 * std::runtime_error naming the camera when one has no image, and when the log cannot be
 * written.
 */
FineTuneResult FineTune(const GaussianCloud& snapshot,
  int sourceIteration,
  const std::vector<std::uint8_t>& removed,
  const std::vector<Camera>& cameras,
  const TrainingImageProvider& images,
  const FineTuneOptions& options);

///@{
/// The figures table of a fine-tune (`vis4gs repair`'s repair.csv, vtkGaussianFineTuneFilter's
/// second output): one row per split ("mean", split) with the means over its views that have
/// an image, then one row per such view, each with PSNR, SSIM and L1 of the source, deleted
/// and repaired states.
struct FineTuneFigureRow
{
  std::string View;
  std::string Split; ///< "train" or "test"
  double Values[9];  ///< psnr x3, ssim x3, l1 x3 (source, deleted, repaired)
};
/// The table's columns, one spelling everywhere: "view", "split", then Values' columns
/// "psnr_source", "psnr_deleted", "psnr_repaired", "ssim_source", ..., "l1_repaired".
const std::vector<std::string>& FineTuneFigureColumns();
std::vector<FineTuneFigureRow> FineTuneFigureRows(const FineTuneResult& result,
  const std::vector<Camera>& cameras);
///@}

} // namespace vis4gs

#endif

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Trainer.h
 * @brief The built-in CPU 3DGS trainer: the training loop of the reference trainer
 * (reference §4) with genealogy logging (DESIGN §3).
 *
 * Per iteration (1-based, reference §4.3): position learning rate from the exponential
 * schedule (scaled by the scene extent E), SH degree + 1 every ShIncreaseInterval
 * iterations, a random training camera drawn without replacement (seeded), forward
 * (Core/Render, float), loss 0.8 L1 + 0.2 (1 - SSIM), backward (RasterBackward.h), the ADC
 * statistics (max 2D radius, |view-space gradient|, count) while iteration <
 * DensifyUntilIter, densify-and-prune when iteration > DensifyFromIter and iteration %
 * DensificationInterval == 0, opacity reset every OpacityResetInterval, then Adam for every
 * tensor that was not replaced in this iteration (the reference's quirk: no update at all on
 * a densification iteration; no opacity update on a reset iteration), and no step at the
 * last iteration.
 *
 * Adaptive density control is the reference's (§4.4) exactly: clone where mean gradient >=
 * 0.0002 and max scale <= 0.01 E (exact copies appended in row order); split (over the
 * Gaussians present before the clones) where the gradient >= 0.0002 and max scale > 0.01 E
 * (two children mu + R (s * xi), xi ~ N(0, I), log-scale ln(s / 1.6), children appended as
 * all first samples then all second samples, then the parents removed); prune where
 * opacity < 0.005 and, once iteration > OpacityResetInterval, where max scale > 0.1 E or the
 * max 2D radius > 20 px — the latter never fires because the densification postfix zeroes
 * the radii before the prune reads them (quirk §4.6, kept). Accumulators are reset after
 * every densification; new rows get zero Adam moments.
 *
 * Genealogy (§4.5): every Gaussian has a stable id (initial 0..N0-1, then the next unused id
 * for every child, never reused); every clone (parent, child), split (parent, child) x 2 and
 * prune (id, -1) is logged in the order the trainer does it. A split ends its parent (its
 * removal is not logged as a prune). Ids stay strictly increasing in row order.
 *
 * Determinism: one seeded generator for the camera order and one for the split samples; every
 * reduction is done in a fixed order; the same seed and thread count give the same log
 * (bit-identical parameters; only elapsed times differ).
 */
#ifndef vis4gs_Trainer_h
#define vis4gs_Trainer_h

#include "Adam.h"
#include "Camera.h"
#include "GaussianCloud.h"
#include "Loss.h"
#include "RasterBackward.h"
#include "TrainingLogTypes.h"

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace vis4gs
{

class TrainingLogWriter;

/// Everything a training run reads: views with their images and the initial point cloud.
struct TrainingData
{
  std::string Name; ///< scene name (root attribute "scene")
  /// Train and test cameras (Camera::Split) at training resolution.
  std::vector<Camera> Cameras;
  /// One RGB float image per camera, [0,1], Width*Height*3, row 0 at the top.
  std::vector<std::vector<float>> Images;
  /// Initial points (xyz) and their colours (RGB in [0,1]).
  std::vector<float> PointPositions;
  std::vector<float> PointColors;
  /// Background composited behind the Gaussians (black, or white with --white-background).
  std::array<double, 3> Background{ 0, 0, 0 };
};

/// Hyper-parameters (reference §4.1 defaults) and logging options.
struct TrainerOptions
{
  int Iterations = 30000;
  int ShDegree = 3;
  double PositionLrInit = 0.00016;
  double PositionLrFinal = 0.0000016;
  int PositionLrMaxSteps = 30000;
  double FeatureLr = 0.0025; ///< f_dc; f_rest uses FeatureLr / 20
  double OpacityLr = 0.05;
  double ScalingLr = 0.005;
  double RotationLr = 0.001;
  double PercentDense = 0.01;
  double LambdaDssim = 0.2;
  int DensificationInterval = 100;
  int OpacityResetInterval = 3000;
  int DensifyFromIter = 500;
  int DensifyUntilIter = 15000;
  double DensifyGradThreshold = 0.0002;
  double MinOpacity = 0.005;
  double ScreenSizeThreshold = 20; ///< px; inert as in the reference (§4.6)
  int ShIncreaseInterval = 1000;
  bool WhiteBackground = false; ///< adds the reference's extra opacity reset at DensifyFromIter
  std::uint64_t Seed = 0;
  int Threads = 0; ///< OpenMP threads; 0 = OpenMP's default
  /// Compositing loops (BackwardSettings::KernelIsa): 0 = 16 lanes on the best instruction
  /// set (default); 1, 2, 3 = baseline, AVX2, AVX-512 lanes (same results); -1 = the
  /// straightforward pair: Render's CompositeTiles forward and the scalar pixel-by-pixel
  /// backward (same per-pixel arithmetic; gradient sums rounded in another order). For
  /// benchmarks and tests.
  int KernelIsa = 0;
  /// Learning-rate warm-up of a fine-tune (FineTuneOptions::WarmupIterations): the first W
  /// iterations after the start iteration (j = 1..W) scale every learning rate by j / (W + 1),
  /// so that the first steps of fresh Adam moments, about lr in size for every parameter
  /// whatever its gradient, do not throw a converged scene off first. 0 (default): none.
  int LrWarmupIterations = 0;

  // Logging.
  int SnapshotInterval = 1000;  ///< also snapshots iteration 0 and the last iteration
  int MetricsInterval = 100;    ///< train/test metrics every N iterations (and the last)
  int MetricsMaxTrainViews = 0; ///< 0: every training view; else an even subset of that many
  /// SH degree written in the snapshots before the last one (to keep logs small); -1: all.
  /// The last snapshot (end of training or interruption) always holds every degree.
  int SnapshotShDegree = -1;
  bool SnapshotStatistics = true; ///< write grad_accum and denom
  bool EmbedImages = false;       ///< embed the training images in the log (/images/<name>)
  /// Paths written into /cameras/image when the images are not embedded (e.g. made relative
  /// to the log); empty: Camera::ImagePath as is.
  std::vector<std::string> ImagePaths;
  int ProgressInterval = 100; ///< progress callback every N iterations

  /**
   * Scales every iteration-count parameter of the 30000-iteration schedule to @p iterations
   * (factor f = iterations / 30000): position LR steps, densify from / until / interval,
   * opacity reset interval and SH increase interval become round(f * value) (intervals at
   * least 1). Sets Iterations too.
   */
  void ScaleSchedule(int iterations);
};

/// Seconds spent per phase (wall clock).
struct TrainerTimings
{
  double Forward = 0;   ///< projection, binning, compositing
  double Loss = 0;      ///< L1 + SSIM and their gradient
  double Backward = 0;  ///< compositing and projection backward
  double Optimizer = 0; ///< Adam
  double Densify = 0;   ///< statistics, densify and prune, opacity reset
  double Logging = 0;   ///< metrics evaluation and snapshot writing
  double Total = 0;
};

/// Progress reported to the caller.
struct TrainerProgress
{
  int Iteration = 0;
  int Iterations = 0;
  std::size_t NumGaussians = 0;
  double Loss = 0;    ///< exponential moving average of the training loss (0.4 weight, as [GS])
  double Elapsed = 0; ///< seconds since Run() started
  int ActiveShDegree = 0;
};

class Trainer
{
public:
  /// Throws std::invalid_argument when the data is unusable (no training camera, image sizes
  /// that do not match their cameras, no initial points).
  Trainer(TrainingData data, const TrainerOptions& options);

  /**
   * Continues from the Gaussians @p start (ids kept; new ids follow the largest) at iteration
   * @p startIteration: a fine-tune of a given scene (`vis4gs repair`). TrainingData's points
   * are not used; every SH degree of Options.ShDegree is active from the start (the SH of
   * @p start are cut or zero-padded to it); the schedules see the real iteration numbers.
   * The Gaussians whose ids are in @p prunes are deleted when Run() starts, as the trainer
   * prunes: prune events at @p startIteration. With a log, Run() first snapshots @p start as it
   * is (so the prunes name Gaussians the log knows and its genealogy is one tree), then prunes,
   * then logs the metrics of the start iteration (the scene after the deletion). Throws
   * std::invalid_argument for an empty or inconsistent @p start or a prune id it lacks.
   */
  Trainer(TrainingData data,
    const TrainerOptions& options,
    GaussianCloud start,
    int startIteration,
    const std::vector<std::int64_t>& prunes = {});

  /// Scene extent E = 1.1 max_i |C_i - mean C| over the training cameras (1 when that is 0).
  double GetSceneExtent() const { return this->Extent; }
  const GaussianCloud& GetCloud() const { return this->Cloud; }
  const TrainerOptions& GetOptions() const { return this->Options; }
  const TrainingData& GetData() const { return this->Data; }
  int GetIteration() const { return this->Iteration; }
  int GetActiveShDegree() const { return this->ActiveShDegree; }
  const TrainerTimings& GetTimings() const { return this->Timings; }
  /// Events logged so far (all of them; also written to the log when one is given).
  const EventTable& GetEvents() const { return this->Events; }
  /// Mean view-space gradient norm since the last densification and its count, per row.
  const std::vector<float>& GetGradientAccumulator() const { return this->GradAccum; }
  const std::vector<float>& GetDenominator() const { return this->Denom; }

  /**
   * Runs iterations until Options.Iterations or until @p stop becomes true (checked after
   * every iteration). With @p log, writes cameras (and images), metrics, events and
   * snapshots, then a final snapshot and metrics row of the last completed iteration, and
   * closes the log (also when interrupted). Returns the last completed iteration.
   */
  int Run(TrainingLogWriter* log,
    const std::atomic<bool>* stop = nullptr,
    const std::function<void(const TrainerProgress&)>& progress = nullptr);

  /// One training iteration (Iteration + 1); returns its training loss. Used by Run(),
  /// tests and benchmarks.
  double Step();

  /// Train (test = false) or test metrics of the current Gaussians (render clamped to [0,1]).
  MetricsRow Evaluate(bool test) const;

  /**
   * Where Run() takes the metrics rows it logs from, instead of Evaluate(): a caller that
   * measures some states anyway (FineTune: the start and the last one, per view) so that they
   * are not rendered twice. Called with the trainer at the iteration logged; fills L1, SSIM,
   * PSNR, LPIPS and Loss of @p train and @p test (Run() sets their iteration, count and
   * elapsed time) and returns true, or returns false to let Evaluate() measure.
   */
  using MetricsSource =
    std::function<bool(const Trainer& trainer, MetricsRow& train, MetricsRow& test)>;
  void SetMetricsSource(MetricsSource source) { this->Metrics = std::move(source); }

  /// Gaussians initialised from points (reference §1.1, §4.2): 3-NN mean squared distance
  /// scales, identity rotation, opacity 0.1, DC colour, SH rest 0, ids 0..N-1.
  static GaussianCloud InitializeFromPoints(const std::vector<float>& positions,
    const std::vector<float>& colors,
    int shDegree);

  /// Mean squared distance of every point to its 3 nearest other points (exact; duplicates
  /// count with distance 0), the reference's distCUDA2 (which is approximate).
  static std::vector<float> MeanSquaredDistance3NN(const std::vector<float>& positions);

  ///@{ Testing and benchmarking interface.
  /// Adam step counts of the tensors: positions, SH (f_dc and f_rest), opacity, scales,
  /// rotations.
  std::array<std::int64_t, 5> GetOptimizerSteps() const
  {
    return { this->AdamPositions.Step,
      this->AdamSH.Step,
      this->AdamOpacity.Step,
      this->AdamScales.Step,
      this->AdamRotations.Step };
  }
  /// First moments of the position tensor (3 per row).
  const std::vector<float>& GetPositionMoments() const { return this->AdamPositions.M; }
  /// Replaces the Gaussians (same count: keeps the optimiser state) and/or the statistics.
  GaussianCloud& GetMutableCloud() { return this->Cloud; }
  void SetGradientStatistics(const std::vector<float>& accum, const std::vector<float>& denom);
  /// Runs densify-and-prune as iteration @p iteration would (events logged with it).
  void DensifyAndPruneAt(int iteration);
  ///@}

private:
  Trainer(TrainingData data, const TrainerOptions& options, const GaussianCloud* start);
  void DensifyAndPrune(double maxScreenSize, bool useScreenSize);
  void ResetOpacity();
  void AppendRows(const std::vector<std::size_t>& sources);
  void KeepRows(const std::vector<char>& keep);
  void ApplyPendingPrunes();
  void WriteSnapshot(TrainingLogWriter& log, bool final);
  double PositionLearningRate(int iteration) const;

  TrainingData Data;
  TrainerOptions Options;
  GaussianCloud Cloud;
  std::int64_t NextId = 0;
  int StartIteration = 0; ///< the first logged iteration (0, or a fine-tune's start)
  std::vector<std::int64_t> PendingPrunes; ///< a fine-tune's deletion, applied by Run()
  double Extent = 1;
  int Iteration = 0;
  int ActiveShDegree = 0;
  std::vector<std::size_t> TrainViews, TestViews;
  std::vector<std::size_t> CameraStack;
  std::mt19937_64 CameraRng;
  std::mt19937_64 SplitRng;

  AdamState AdamPositions, AdamScales, AdamRotations, AdamOpacity, AdamSH;
  std::vector<float> GradAccum, Denom, MaxRadii;
  /// The statistics as the last densification used them (written into snapshots taken
  /// right after a densification, which zeroes the accumulators).
  std::vector<float> SnapshotAccum, SnapshotDenom;
  bool StatisticsJustReset = false;
  EventTable Events;
  std::size_t EventsWritten = 0;
  TrainerTimings Timings;
  double LossEma = 0;
  std::vector<float> GradientScratch;
  GaussianGradients<float> Gradients; ///< reused between iterations (scratch memory)
  /// The step's projection, tile lists and image, kept so that their memory is reused
  /// between iterations instead of being allocated and page-faulted again.
  ViewProjection<float> StepProjection;
  TileBins StepBins;
  BinScratch StepBinScratch;
  RasterImage<float> StepImage;
  /// Per camera: the SSIM maps of its target image, made on first use by the training step
  /// or the metrics (while all of them fit in 256 MB; otherwise TrainingLoss() recomputes
  /// them every time). Caches of the const Evaluate() as well, hence mutable.
  mutable std::vector<SsimTarget<float>> SsimTargets;
  mutable int SsimTargetsUsable = -1; ///< -1 not decided yet, 0 no, 1 yes
  /// Evaluate()'s rendering buffers, kept between calls.
  mutable RasterWorkspace<float> EvalWorkspace;
  MetricsSource Metrics;

  /// The SSIM maps of view @p view's target (made on first use), or null when they are
  /// not kept.
  const SsimTarget<float>* TargetMaps(std::size_t view, int threads) const;
};

} // namespace vis4gs

#endif

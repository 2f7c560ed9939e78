// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ArtifactScores.h
 * @brief View Coverage, Blur and Needle scores of every Gaussian (DESIGN §4), with every
 * approximation exposed as a parameter.
 *
 * Definitions (exact mode: full resolution, every training view, alpha footprints, double
 * accumulation):
 *   Omega(g,v)  pixels where the rasteriser evaluates g with power <= 0 and
 *               alpha = min(0.99, o e^power) >= 1/255, occluded or not (Render/Footprint.h)
 *   V~_g        training views with |Omega(g,v)| >= 1
 *   E_VC(g)  = |V~_g| / |V|
 *   L'(g,v)  = sum over Omega(g,v) of the loss map L(v) (LossMap.h)
 *   w(g,v)   = |Omega(g,v)| / max_h |Omega(h,v)|
 *   E_B(g)   = mean over V~_g of w(g,v) L'(g,v)
 *   E_N(g)   = s(g) mean over V~_g of L'(g,v)          (s from NeedleShape.h)
 *   A Gaussian with no visible view gets E_VC = E_B = E_N = 0 and a flag.
 *   R(g)     = sum over V of the pixels at which the rasteriser evaluates g: the pixels of the
 *              image in the tiles g is binned into that have not stopped (T < 1e-4) at an
 *              earlier Gaussian of their tile list (GaussianWeightStats::Evaluations), at full
 *              resolution, whether or not alpha >= 1/255 there
 *   A(g)     = sum over V and pixels of the blending weight alpha T of g
 *   R/A(g)   = R(g) / A(g); +inf when R > 0 and A = 0 (it costs and never shows), NaN when
 *              R = A = 0 (never evaluated: nothing to divide, counted in a warning)
 *
 * Approximations (ScoreSettings):
 * - LossResolution f in {1, 2, 4, 8}: blur/needle views are rendered at
 *   LossMapSize(W, f) x LossMapSize(H, f) with Camera::Resized, the image is box-reduced to
 *   that size (LossMap.h), footprints are taken in the low-resolution view, and L' is scaled
 *   by the area ratio (W H)/(w' h') so that it estimates the full-resolution sum; the loss
 *   map's Laplacian term is divided by the same ratio (LossMap.h explains why). V~_g for
 *   blur/needle is then the set of views where the low-resolution footprint is non-empty.
 * - CoverageResolution f: the same for the coverage pass (no images involved).
 * - ViewStride k / ViewList: the views used (|V| is the size of the subset).
 * - Footprint: alpha footprint (exact) or the 3-sigma ellipse.
 * - Accumulation: footprint sums of the loss map in double (exact) or float.
 * - OcclusionThreshold t > 0: occlusion-aware coverage, a view counts for E_VC only when the
 *   Gaussian's maximum blending weight alpha*T over its footprint is >= t (needs compositing).
 *
 * Only what is requested is computed: coverage alone projects the Gaussians and counts
 * footprints, with no rendering and no images; needle shape alone needs no cameras.
 * Blur/needle views without an image are skipped (counted in ViewsWithoutImage, one warning).
 * NaN/Inf Gaussians never become visible (the rasteriser skips them), so they get 0 and the
 * flag, and never poison other Gaussians.
 */
#ifndef vis4gs_ArtifactScores_h
#define vis4gs_ArtifactScores_h

#include "Camera.h"
#include "Footprint.h"
#include "GaussianCloud.h"
#include "LossMap.h"
#include "MultiViewRenderer.h"
#include "Rasterizer.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace vis4gs
{

/**
 * Called with every view the blur/needle pass renders, once it is rendered: the camera index,
 * the camera as rendered (Camera::Resized at LossResolution, the camera itself at 1), the
 * render and the view's image at that size. For a caller that measures those renders too
 * (Selection/RemovalEffect.h keeps the "before" of a clean-up), so that no view is rendered
 * twice. It runs on the calling thread, between views.
 */
using ScoreViewRendered = std::function<void(std::size_t cameraIndex,
  const Camera& view,
  const RasterImage<float>& render,
  const Image& image)>;

/// Which scores to compute.
struct ScoreRequest
{
  bool ViewCoverage = true;
  bool Blur = true;
  bool Needle = true;
  bool NeedleShape = true;
  /// R(g) and R/A(g) (the file comment): one compositing pass per view at full resolution,
  /// shared by the two. Off by default: it renders every view once more.
  bool RenderCost = false;
  bool CostPerContribution = false;
  /// Whether any requested score needs cameras (every one except the needle shape).
  bool NeedsCameras() const
  {
    return this->ViewCoverage || this->Blur || this->Needle || this->NeedsCompositing();
  }
  /// Whether the render-cost pass runs.
  bool NeedsCompositing() const { return this->RenderCost || this->CostPerContribution; }
};

/// Every parameter of the scores; the defaults are the exact mode.
struct ScoreSettings
{
  ScoreRequest Request;
  /// lambda of the loss map. Default 0.2 (DESIGN §4).
  double Lambda = 0.2;
  /// Loss-map resolution factor for blur/needle: 1 (exact), 2, 4 or 8.
  int LossResolution = 1;
  /// Resolution factor of the coverage pass: 1 (exact), 2, 4 or 8.
  int CoverageResolution = 1;
  /// Use every k-th training view (in camera order), starting with the first. Default 1.
  int ViewStride = 1;
  /// If not empty: the camera indices to use instead (ViewStride is then ignored). Indices
  /// of test views or out of range give std::invalid_argument.
  std::vector<std::size_t> ViewList;
  /// Footprint definition. Default: the rasteriser's alpha footprint (exact).
  FootprintMode Footprint = FootprintMode::Rasterizer;
  /// Accumulation of the footprint sums of the loss map. Default double (exact).
  FootprintAccumulation Accumulation = FootprintAccumulation::Double;
  /// Occlusion-aware coverage when > 0 (see the file comment). Default 0: off.
  double OcclusionThreshold = 0;
  /// Footprints by brute force over the tile rectangle (the straightforward implementation,
  /// for benchmarks and tests). Default off.
  bool BruteForceFootprints = false;
  /// Instruction set of the footprint and coverage kernels (Render/KernelIsa.h): 0 = best
  /// available (default), 1 = baseline (the scalar loops, for benchmarks), 2 = AVX2,
  /// 3 = AVX-512. Results are bit-identical on every path.
  int KernelIsa = 0;
  /// Blur/needle views rendered with Render/MultiViewRenderer.h: the view-independent part
  /// of the projection computed once for all views, a vectorised per-view projection shared
  /// by compositing and the footprint pass, no per-view allocations. Bit-identical results.
  /// false: ProjectGaussians + BinGaussians + CompositeTiles + ComputeFootprints per view
  /// (the previous implementation, kept for benchmarks and tests). Default true. The
  /// occlusion-aware variant and brute-force footprints always take the per-view path.
  bool SharedProjection = true;
  /// Optional, for processes of one machine that each compute partials of some views
  /// (ComputeScorePartials() under MPI): the shared projection's view-independent preparation
  /// made once between them in memory they share (Render/MultiViewRenderer.h). Every process
  /// constructs its renderer (so calls Map) even with no view. Default: none, each process
  /// prepares every Gaussian. The scores are the same bits either way.
  PreparationShare SharePreparation;
  /// Rasteriser options for the renders (background, SH degree). Threads are overridden.
  RasterSettings Raster;
  /// OpenMP threads; 0 uses OpenMP's default.
  int Threads = 0;
  /// Optional: see ScoreViewRendered. Its time is counted in ScoreTimings::ViewHook.
  ScoreViewRendered ViewRendered;
};

/// Bits of GaussianScores::Flags.
enum ScoreFlag : std::uint8_t
{
  /// No visible view in the coverage pass (E_VC = 0).
  NoVisibleCoverageView = 1,
  /// No visible view with an image in the blur/needle pass (E_B = E_N = 0).
  NoVisibleScoredView = 2,
  /// A parameter for which the reference has no answer (ClassifyGaussian: NaN, an infinite
  /// position or rotation component, a log-scale of +inf); +-inf opacity logits, a log-scale
  /// of -inf and a zero quaternion are drawn and scored like any Gaussian.
  InvalidParameters = 4
};

/// Seconds spent per stage (summed over views).
struct ScoreTimings
{
  double Projection = 0;   ///< ProjectGaussians (coverage and score passes)
  double Rendering = 0;    ///< binning and compositing
  double Images = 0;       ///< loading and reducing training images
  double LossMaps = 0;     ///< ComputeLossMap
  double Footprints = 0;   ///< ComputeFootprints
  double Accumulation = 0; ///< per-Gaussian sums
  double NeedleShape = 0;
  double RenderCost = 0; ///< the render-cost pass (projection, binning, compositing)
  double ViewHook = 0;   ///< ScoreSettings::ViewRendered
  double Total = 0;
};

struct GaussianScores
{
  /// One value per Gaussian for each requested score; empty when not requested.
  std::vector<double> ViewCoverage;
  std::vector<double> BlurScore;
  std::vector<double> NeedleScore;
  std::vector<double> NeedleShape;
  std::vector<double> RenderCost;
  std::vector<double> CostPerContribution;
  /// ScoreFlag bits per Gaussian (always filled).
  std::vector<std::uint8_t> Flags;
  /// |V~_g| of the coverage pass and of the blur/needle pass (empty when not run).
  std::vector<std::uint32_t> CoverageViews;
  std::vector<std::uint32_t> ScoredViews;
  /// Views of the subset (|V|), views scored (with an image), views skipped for lack of one.
  std::size_t ViewsUsed = 0;
  std::size_t ViewsScored = 0;
  std::size_t ViewsWithoutImage = 0;
  /// Camera indices of the views used, in order.
  std::vector<std::size_t> ViewIndices;
  /// Gaussians flagged NoVisibleCoverageView / NoVisibleScoredView / InvalidParameters.
  std::size_t NoCoverageViewCount = 0;
  std::size_t NoScoredViewCount = 0;
  std::size_t InvalidCount = 0;
  /// Gaussians the render-cost pass evaluated in no view (R = 0, R/A NaN).
  std::size_t NotEvaluatedCount = 0;
  std::vector<std::string> Warnings;
  /// Why BlurScore and NeedleScore are NaN for every Gaussian, or empty when they were
  /// computed: with no training image for any view used, the scores cannot be computed at all,
  /// and a score that could not be computed is NaN with its reason, never 0.
  std::string ScoresUnavailable;
  ScoreTimings Timings;
};

/**
 * Loads the training image of camera @p index into @p image (RGB, 3 channels, the camera's
 * size, values in [0, 1]; LoadTrainingImage() of Core/Scene/ImageIO.h does this). Returns false
 * when the view has no image (it is then skipped for blur/needle); throws std::runtime_error naming
 * the file when an image exists but cannot be read.
 */
using TrainingImageProvider =
  std::function<bool(std::size_t index, const Camera& camera, Image& image)>;

/// Called after each view with (views done, views in all passes).
using ScoreProgress = std::function<void(std::size_t done, std::size_t total)>;

/**
 * Computes the requested scores. @p images may be empty when neither blur nor needle is
 * requested. Throws std::invalid_argument for unusable settings (resolution factor not in
 * {1,2,4,8}, stride < 1, bad view list), for a cloud without the arrays a requested score
 * needs, and for blur/needle without an image provider; std::runtime_error when an image's
 * size differs from its camera's.
 */
GaussianScores ComputeGaussianScores(const GaussianCloud& cloud,
  const std::vector<Camera>& cameras,
  const ScoreSettings& settings,
  const TrainingImageProvider& images = {},
  const ScoreProgress& progress = {});

/// The camera indices a setting selects (training views, stride or list).
std::vector<std::size_t> SelectViews(const std::vector<Camera>& cameras,
  const ScoreSettings& settings);

/**
 * Adds @p term to the compensated sum (@p sum, @p compensation) (Neumaier: the rounding error
 * of each addition goes into the compensation; a term or sum that is not finite is added
 * plainly). The value of the sum is sum + compensation.
 */
inline void AddCompensated(double& sum, float& compensation, double term)
{
  const double t = sum + term;
  if (std::isfinite(t))
  {
    const double bp = t - sum;
    compensation =
      static_cast<float>(static_cast<double>(compensation) + ((sum - (t - bp)) + (term - bp)));
  }
  sum = t;
}

/// Adds the compensated sum (@p otherSum, @p otherCompensation) to (@p sum, @p compensation):
/// partials of two view subsets (processes) combined.
inline void AddCompensated(double& sum,
  float& compensation,
  double otherSum,
  float otherCompensation)
{
  AddCompensated(sum, compensation, otherSum);
  compensation = static_cast<float>(static_cast<double>(compensation) + otherCompensation);
}

/**
 * Per-Gaussian partial results of the view-dependent scores over a subset of the selected
 * views: what a process that renders only some views contributes, so that the views can be
 * spread over processes (MPI, Filters/Diagnostics/vtkGaussianArtifactScoreFilter). Every
 * member except ViewIndices, RenderedViews and Timings is a plain sum over views, so the partials
 * of disjoint view subsets combine by element-wise addition (integers exactly; BlurSum and
 * NeedleSum are compensated sums, see BlurCompensation, combined with AddCompensated()). omega(g,v)
 * needs max_h |Omega(h,v)|, a per-view quantity, so it is finished on the process that renders v
 * and only omega*L' travels.
 */
struct ScorePartials
{
  /// Camera indices of every selected view (|V|), whoever renders them.
  std::vector<std::size_t> ViewIndices;
  /// Visible views per Gaussian of the coverage pass (empty when coverage is not requested).
  std::vector<std::uint32_t> CoverageViews;
  /// Visible scored views per Gaussian, sums of omega*L' and of L' (empty without blur/needle).
  std::vector<std::uint32_t> ScoredViews;
  std::vector<double> BlurSum;
  std::vector<double> NeedleSum;
  /// The rounding errors of BlurSum and NeedleSum (Neumaier's compensated summation): each sum
  /// is BlurSum + BlurCompensation. Why: processes that render different views add the same
  /// terms in different orders, and a plain double sum then differs in its last bits (at 194
  /// views over 2 processes one BlurScore of 6.1M differed in its 9th digit, as written in
  /// scores.csv). With the compensation the sum is within about n^2 2^-77 of the exact one
  /// whatever the order (float compensation: its own error is 2^-24 of a term already 2^-53
  /// of the sum), so the rounded scores agree bit for bit except where the exact sum lies that
  /// close to a rounding boundary of a double. 4 bytes a Gaussian each.
  std::vector<float> BlurCompensation;
  std::vector<float> NeedleCompensation;
  /// Sums of R(g) and A(g) (empty without the render-cost pass). R is an integer, exact in a
  /// double up to 2^53.
  std::vector<double> RenderCostSum;
  std::vector<double> ContributionSum;
  /// ContributionSum's compensation, as BlurCompensation's.
  std::vector<float> ContributionCompensation;
  /// Every per-Gaussian count and sum above, for a reduction over processes that needs to
  /// know nothing of the scores (the empty ones included: a process sizes its buffers as
  /// every other, from the same request).
  std::vector<std::vector<std::uint32_t>*> PerGaussianCounts()
  {
    return { &this->CoverageViews, &this->ScoredViews };
  }
  std::vector<std::vector<double>*> PerGaussianSums() { return { &this->RenderCostSum }; }
  /// The compensated sums and their compensations: combined over processes with
  /// AddCompensated(), not by a plain sum.
  std::vector<std::pair<std::vector<double>*, std::vector<float>*>> CompensatedSums()
  {
    return { { &this->BlurSum, &this->BlurCompensation },
      { &this->NeedleSum, &this->NeedleCompensation },
      { &this->ContributionSum, &this->ContributionCompensation } };
  }
  /// Views scored (with an image) and skipped for lack of one, among the views rendered.
  std::size_t ViewsScored = 0;
  std::size_t ViewsWithoutImage = 0;
  /// The camera indices this call rendered, in order (not a sum: one process's own).
  std::vector<std::size_t> RenderedViews;
  ScoreTimings Timings;
};

/// Called with the camera index of each view before it is rendered (to name it in errors).
using ScoreViewStarted = std::function<void(std::size_t cameraIndex)>;

/**
 * The partials of @p views (camera indices, a subset of SelectViews(); empty: none, every
 * buffer still sized for the cloud) with the same checks and exceptions as
 * ComputeGaussianScores(). @p images is called only for views of @p views.
 */
ScorePartials ComputeScorePartials(const GaussianCloud& cloud,
  const std::vector<Camera>& cameras,
  const ScoreSettings& settings,
  const std::vector<std::size_t>& views,
  const TrainingImageProvider& images = {},
  const ScoreProgress& progress = {},
  const ScoreViewStarted& viewStarted = {});

/**
 * Gives the camera index of the next view to render in @p cameraIndex, or false when no view
 * is left: a queue shared with other processes, so that whichever process is free takes the
 * next view (dynamic balancing, vtkGaussianArtifactScoreFilter under MPI).
 */
using ScoreNextView = std::function<bool(std::size_t& cameraIndex)>;

/**
 * The partials of the views @p next hands out, taken one at a time as the blur/needle pass
 * is ready for one; the other passes then go over the same views. Without a blur/needle pass
 * (no image scores requested) every view is taken before the first is rendered: the passes
 * without images batch their views. ScorePartials::RenderedViews lists the views taken, in
 * order; with a queue that hands out the views of a vector in order, the result is identical to
 * the overload above. Progress is reported against the views taken so far.
 */
ScorePartials ComputeScorePartials(const GaussianCloud& cloud,
  const std::vector<Camera>& cameras,
  const ScoreSettings& settings,
  const ScoreNextView& next,
  const TrainingImageProvider& images = {},
  const ScoreProgress& progress = {},
  const ScoreViewStarted& viewStarted = {});

/**
 * The scores from partials that cover every selected view (one process's, or the
 * element-wise sums of several): needle shape, flags, means and warnings.
 * ComputeGaussianScores() = FinishGaussianScores(ComputeScorePartials(every selected view)).
 */
GaussianScores FinishGaussianScores(const GaussianCloud& cloud,
  const ScoreSettings& settings,
  ScorePartials partials);

/**
 * FinishGaussianScores() of the Gaussians [first, first + count) alone, in place: the
 * per-Gaussian vectors of @p partials keep the cloud's size and only their entries in the range
 * are read (every selected view summed there), and the result's vectors have the cloud's size
 * with the range finished and every other entry as @p partials had it (vectors finished in the
 * sums' memory: BlurScore, NeedleScore, RenderCost, the view counts) or 0 (the others). For
 * processes that each finish a slice of the Gaussians after a reduce-scatter of the partials and
 * then fill the other slices from the processes that finished them (vtkGaussianArtifactScoreFilter
 * under MPI), with no buffer of a slice's size allocated on the way: its counts
 * (NoCoverageViewCount, ...) are the slice's, its warnings those of ScoreWarnings() for them.
 * Throws std::invalid_argument when the range is not in the cloud.
 */
GaussianScores FinishGaussianScores(const GaussianCloud& cloud,
  const ScoreSettings& settings,
  ScorePartials partials,
  std::size_t first,
  std::size_t count);

/**
 * The warnings of finished scores of @p gaussians Gaussians, from their counts (views without
 * image, ScoresUnavailable, Gaussians never evaluated, without a visible view, with invalid
 * parameters): what FinishGaussianScores() puts in GaussianScores::Warnings, for a caller that
 * sums the counts of slices.
 */
std::vector<std::string> ScoreWarnings(const GaussianScores& scores,
  const ScoreRequest& request,
  std::size_t gaussians);

/**
 * Estimated cost of each view of @p views: its pixels (at the blur/needle or coverage
 * resolution, whichever is rendered) times the Gaussians whose mean projects into it, counted
 * on a deterministic sample of at most 4096 Gaussians (every process gets the same numbers).
 */
std::vector<double> EstimateViewCosts(const GaussianCloud& cloud,
  const std::vector<Camera>& cameras,
  const std::vector<std::size_t>& views,
  const ScoreSettings& settings);

/**
 * Splits views of costs @p costs over @p parts processes, largest cost first onto the least
 * loaded process (ties: lower view position, lower process), deterministic. Returns the
 * process of each view. A process may get no view when views are fewer than processes.
 */
std::vector<int> SplitViewsByCost(const std::vector<double>& costs, int parts);

} // namespace vis4gs

#endif

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatMovingSet.h
 * @brief The Gaussians a moving frame of the scene view draws, kept between frames while the
 * view turns or travels less than an angle: the level of detail's selection
 * (SplatLevelOfDetail.h) and a compact copy of the selected Gaussians with their colours.
 *
 * A moving frame that selects and projects its budget of Gaussians from the whole scene reads
 * every Gaussian's position for the ranking and about ten scattered cache lines per selected
 * Gaussian (its parameters and SH of degree 3) for the projection. While the view barely
 * moves, neither the selection nor the view-dependent colours change much, so they are made
 * once (a rebuild) and reused: the set holds the selected Gaussians' parameters in a compact
 * GaussianCloud of SH degree 0 whose constant term gives the colour each Gaussian had seen
 * from the camera centre of the rebuild. The frames in between project that compact cloud
 * (contiguous memory, no SH evaluated) with the exact geometry of their own camera.
 *
 * The approximation has two parameters. The reuse angle: the set is rebuilt when the view has
 * turned by more than that angle (the rotation between the two cameras' orientations) or
 * travelled by more than that angle seen from the selected Gaussians' median depth, and the
 * selection of a rebuild takes a margin of that angle around the field of view
 * (SelectSplatsForView's margin), so that what turns into the view is drawn. The colour
 * angle: a rebuild keeps the colours of the Gaussians that stay selected while the view is
 * within that angle of the camera that last evaluated every colour. Their error (selection and
 * colours of a nearby camera) is measured against run time by BenchmarkSplatLevelOfDetail
 * (Documentation/accuracy-vs-runtime.md). Angles 0 rebuild for every frame (the selection and
 * colours of the frame's own camera, as without reuse).
 */
#ifndef vis4gs_SplatMovingSet_h
#define vis4gs_SplatMovingSet_h

#include "Camera.h"
#include "GaussianCloud.h"
#include "Rasterizer.h"
#include "SplatLevelOfDetail.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace vis4gs
{

/// What a moving set was made for.
struct SplatMovingSetOrigin
{
  /// The camera of the rebuild, and of the last rebuild that evaluated every colour.
  Camera Rank, ColorRank;
  const GaussianCloud* Cloud = nullptr;
  std::uint64_t CloudVersion = 0;
  std::size_t Budget = 0;
  int ShDegree = 0;
  bool Colors = true;
  double ReuseAngle = 0.0;
  /// Median view depth of the selected Gaussians in front of the rebuild's camera (of a
  /// sample of at most 4,096 of them, evenly spaced).
  double Depth = 0.0;
};

/// A moving frame's Gaussians and what they were made for (see the file's comment).
struct SplatMovingSet
{
  /// Indices in the cloud of the selected Gaussians: Gaussian j of Compact (its slot j) is the
  /// cloud's Subset[j]. A rebuild that keeps the colours leaves every Gaussian that stays
  /// selected in its slot and writes only the new ones (into the slots of those that left), so
  /// the order is not the cloud's; a rebuild that evaluates every colour writes them in the
  /// cloud's order (ascending).
  std::vector<std::uint32_t> Subset;
  /// The selected Gaussians' positions, scales, rotations and opacities, and SH of degree 0
  /// holding their colour seen from the rebuild's camera centre (SH zero when colours are off).
  GaussianCloud Compact;
  /// Non-zero once built, a new value at every rebuild: the compact cloud's version for a
  /// PreparedCloudCache (Rasterizer.h).
  std::uint64_t Generation = 0;
  /// The generation before the last publication and the slots that publication wrote (all of
  /// them when AllChanged): ProjectSplatMovingSet() prepares only those again.
  std::uint64_t PreviousGeneration = 0;
  std::vector<std::uint32_t> Changed;
  bool AllChanged = true;
  /// Rebuilds, reuses and rebuilds that evaluated every colour since construction (tests,
  /// benchmarks).
  std::size_t Rebuilds = 0;
  std::size_t Reuses = 0;
  std::size_t ColorRefreshes = 0;
  /// Wall milliseconds of the last rebuild's selection and of the whole rebuild (benchmarks).
  double LastSelectionMs = 0.0;
  double LastRebuildMs = 0.0;
  /// Of the last rebuild: wall milliseconds of the gather (parameters and colours), and the
  /// Gaussians whose colour it evaluated (benchmarks).
  double LastGatherMs = 0.0;
  std::size_t LastEvaluated = 0;
  /// The published set's Gaussians as (index << 32 | slot), ascending (internal: a rebuild
  /// merges its selection with it).
  std::vector<std::uint64_t> Sorted;
  /// A rebuild's scratch (internal, kept so that rebuilds neither allocate nor touch fresh
  /// memory): its selection (ascending), the selection's keys, candidates and last boundary
  /// (SelectSplatsInCells: a rebuild examines only the cells that can hold a selected Gaussian),
  /// per thread the places in the selection of the Gaussians it gathers from the scene, per
  /// published slot whether its Gaussian stays, per selected Gaussian its slot, the slots to
  /// fill, and the travel test's sample of depths.
  std::vector<std::uint32_t> Selected;
  SplatSelectionState Selection;
  std::vector<std::vector<std::uint32_t>> Fresh;
  std::vector<std::uint8_t> Stay;
  std::vector<std::uint32_t> SlotOf;
  std::vector<std::uint32_t> Free;
  std::vector<float> Depths;

  /// What the published set was made for (SplatMovingSetReusable compares a view with it).
  SplatMovingSetOrigin Made;
  /// A rebuild made and not published yet (BuildSplatMovingSet, PublishSplatMovingSet): what it
  /// was made for, and what it writes into the published set. Full: Patch is the whole new
  /// compact cloud (every colour evaluated). Otherwise Patch holds the new Gaussians, to be
  /// written into the slots PatchSlots (Gaussians PatchIndices of the cloud), the Gaussians of
  /// slots MoveFrom (beyond the new Count) move to the slots MoveTo, and the set shrinks or grows
  /// to Count slots. Sorted: the published Sorted after it.
  struct Build
  {
    bool Ready = false;
    bool ColorsRefreshed = false;
    SplatMovingSetOrigin Made;
    bool Full = true;
    int Threads = 1; ///< (of the publication's parallel writes: the build's)
    std::size_t Count = 0;
    GaussianCloud Patch;
    std::vector<std::uint32_t> PatchSlots, PatchIndices, MoveFrom, MoveTo;
    std::vector<std::uint64_t> Sorted;
  } Next;
};

/**
 * The angle (radians) by which @p now differs from @p rank for the reuse test: the larger of
 * the rotation angle between their orientations and the distance between their centres seen
 * from @p depth (infinite for a non-positive @p depth).
 */
double SplatViewChangeAngle(const Camera& rank, const Camera& now, double depth);

/**
 * Whether @p set, as published, serves a moving frame of @p camera: made for the same cloud
 * (address and @p cloudVersion), budget, SH degree and colour setting of @p settings, reuse
 * angle and field of view, and the view changed by at most @p fraction times @p reuseAngle
 * since (SplatViewChangeAngle). Never with @p reuseAngle 0.
 */
bool SplatMovingSetReusable(const GaussianCloud& cloud,
  std::uint64_t cloudVersion,
  const Camera& camera,
  std::size_t budget,
  const RasterSettings& settings,
  double reuseAngle,
  const SplatMovingSet& set,
  double fraction = 1.0);

/**
 * UpdateSplatMovingSet()'s rebuild, into set.Next and the scratch of @p set, without touching
 * what the published set holds: another thread may
 * project set.Compact and read set.Subset meanwhile, but must not change @p set until this
 * returns. PublishSplatMovingSet() then makes it the set's. Throws as UpdateSplatMovingSet.
 */
void BuildSplatMovingSet(const GaussianCloud& cloud,
  std::uint64_t cloudVersion,
  const SplatLevelOfDetail& lod,
  const Camera& camera,
  std::size_t budget,
  const RasterSettings& settings,
  double reuseAngle,
  double colorAngle,
  SplatMovingSet& set);

/**
 * Gives the buffers of @p set that rebuilds fill (both subsets and compact clouds, the
 * selection's scratch) room for @p count Gaussians and writes every page of that room once, so
 * that the first rebuilds of a scene neither allocate nor touch fresh memory (on a virtual
 * machine the first touch of a page costs microseconds: about 50 ms of CPU for one set of
 * 400,000). Meant once per scene, before its first moving frame: only a set with nothing
 * published or built (Generation 0, no rebuild waiting) is changed; false otherwise.
 */
bool ReserveSplatMovingSet(SplatMovingSet& set, std::size_t count, int threads = 0);

/// Makes the rebuild of BuildSplatMovingSet() the set's (a new Generation); false when none
/// is waiting. Writes only the slots that change (Build), in place: no frame may project the
/// set meanwhile.
bool PublishSplatMovingSet(SplatMovingSet& set);

/**
 * ProjectGaussians(set.Compact, camera, settings, projection, cache, set.Generation)
 * (Rasterizer.h), the view-independent preparation kept in @p cache between frames: after a
 * publication that wrote only some slots, only those are prepared again (RefreshPreparedCloud,
 * when @p cache holds the previous generation); the result is the whole projection's, bit for
 * bit.
 */
void ProjectSplatMovingSet(const SplatMovingSet& set,
  const Camera& camera,
  const RasterSettings& settings,
  ViewProjection<float>& projection,
  PreparedCloudCache& cache);

/**
 * Makes @p set hold the Gaussians of @p cloud a moving frame of @p camera draws under
 * @p budget (SelectSplatsForView's subset, by SelectSplatsInCells), reusing it while it serves
 * the view (SplatMovingSetReusable with the whole @p reuseAngle), else rebuilt and published
 * (BuildSplatMovingSet, PublishSplatMovingSet). A rebuild evaluates the colours of the Gaussians
 * newly selected; those of the Gaussians that stay selected are kept (a copy from the previous
 * compact cloud instead of a gather of 192 B of SH each from the scene) while the view is within @p
 * colorAngle radians of the camera of the last rebuild that evaluated every colour (0: every
 * rebuild evaluates every colour); they also keep their slot in the compact cloud, so that such a
 * rebuild writes only the new Gaussians. Returns true when it was rebuilt. Parallel with OpenMP
 * (settings.Threads). Throws std::invalid_argument when @p lod does not match the cloud or an angle
 * is negative or not finite.
 */
bool UpdateSplatMovingSet(const GaussianCloud& cloud,
  std::uint64_t cloudVersion,
  const SplatLevelOfDetail& lod,
  const Camera& camera,
  std::size_t budget,
  const RasterSettings& settings,
  double reuseAngle,
  double colorAngle,
  SplatMovingSet& set);

} // namespace vis4gs

#endif

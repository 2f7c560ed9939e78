// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TrainingLogTypes.h
 * @brief In-memory form of the training log's tables (DESIGN §3, format version 1).
 */
#ifndef vis4gs_TrainingLogTypes_h
#define vis4gs_TrainingLogTypes_h

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace vis4gs
{

/// Densification event kinds as stored in /events/kind.
enum class EventKind : std::uint8_t
{
  Clone = 1,
  Split = 2,
  Prune = 3
};

/// True for the values /events/kind may hold (1 clone, 2 split, 3 prune).
inline bool IsEventKind(std::uint8_t kind)
{
  return kind >= 1 && kind <= 3;
}

/// "clone", "split", "prune", or "unknown kind": the one spelling in every message.
inline const char* EventKindName(std::uint8_t kind)
{
  switch (kind)
  {
    case 1:
      return "clone";
    case 2:
      return "split";
    case 3:
      return "prune";
    default:
      return "unknown kind";
  }
}

/// The values /events/kind may hold, for messages about a bad one.
constexpr const char* EventKindValues = "1 clone, 2 split, 3 prune";

/// One row of /events: rows are kept in the order the trainer did them.
struct TrainingEvent
{
  std::int32_t Iteration = 0;
  EventKind Kind = EventKind::Clone;
  std::int64_t Parent = -1; ///< GaussianId
  std::int64_t Child = -1;  ///< GaussianId, -1 for prune
};

/// Columns of /events as structure of arrays (what readers return for large logs).
struct EventTable
{
  std::vector<std::int32_t> Iteration;
  std::vector<std::uint8_t> Kind;
  std::vector<std::int64_t> Parent;
  std::vector<std::int64_t> Child;

  std::size_t Size() const { return this->Iteration.size(); }
  void Reserve(std::size_t n)
  {
    this->Iteration.reserve(n);
    this->Kind.reserve(n);
    this->Parent.reserve(n);
    this->Child.reserve(n);
  }
  void Append(const TrainingEvent& e)
  {
    this->Iteration.push_back(e.Iteration);
    this->Kind.push_back(static_cast<std::uint8_t>(e.Kind));
    this->Parent.push_back(e.Parent);
    this->Child.push_back(e.Child);
  }
  TrainingEvent Get(std::size_t i) const
  {
    return TrainingEvent{
      this->Iteration[i], static_cast<EventKind>(this->Kind[i]), this->Parent[i], this->Child[i]
    };
  }
};

/// One row of /metrics (or /metrics/test). Values not measured are NaN.
struct MetricsRow
{
  std::int32_t Iteration = 0;
  std::int64_t NumGaussians = 0;
  double Loss = std::numeric_limits<double>::quiet_NaN();
  double L1 = std::numeric_limits<double>::quiet_NaN();
  double Psnr = std::numeric_limits<double>::quiet_NaN();
  double Ssim = std::numeric_limits<double>::quiet_NaN();
  double Lpips = std::numeric_limits<double>::quiet_NaN();
  double ElapsedSeconds = std::numeric_limits<double>::quiet_NaN();
};

/// Columns of /metrics (or /metrics/test) as structure of arrays, rows in logging order.
struct MetricsTable
{
  std::vector<std::int32_t> Iteration;
  std::vector<std::int64_t> NumGaussians;
  std::vector<double> Loss;
  std::vector<double> L1;
  std::vector<double> Psnr;
  std::vector<double> Ssim;
  std::vector<double> Lpips;
  std::vector<double> ElapsedSeconds;

  std::size_t Size() const { return this->Iteration.size(); }
  void Append(const MetricsRow& r)
  {
    this->Iteration.push_back(r.Iteration);
    this->NumGaussians.push_back(r.NumGaussians);
    this->Loss.push_back(r.Loss);
    this->L1.push_back(r.L1);
    this->Psnr.push_back(r.Psnr);
    this->Ssim.push_back(r.Ssim);
    this->Lpips.push_back(r.Lpips);
    this->ElapsedSeconds.push_back(r.ElapsedSeconds);
  }
  MetricsRow Get(std::size_t i) const
  {
    MetricsRow r;
    r.Iteration = this->Iteration[i];
    r.NumGaussians = this->NumGaussians[i];
    r.Loss = this->Loss[i];
    r.L1 = this->L1[i];
    r.Psnr = this->Psnr[i];
    r.Ssim = this->Ssim[i];
    r.Lpips = this->Lpips[i];
    r.ElapsedSeconds = this->ElapsedSeconds[i];
    return r;
  }
};

/**
 * Columns of /lineage_breaks (optional; written by the Python logger when a trainer changed
 * the model's rows outside the operations it tracks). Row b: at Iteration[b], after the
 * first EventRow[b] rows of /events, the logger tracked Tracked[b] ids for a model of Rows[b]
 * rows. The first Kept[b] rows kept their ids; when Kept[b] is 0 every id alive there ended
 * (no event says how). NewRoots[b] rows became new roots with the ids FirstNewId[b],
 * FirstNewId[b] + 1, ... (fresh ids, in the order of new ids with the births around them).
 */
struct LineageBreakTable
{
  std::vector<std::int32_t> Iteration;
  std::vector<std::int64_t> EventRow;
  std::vector<std::int64_t> Tracked;
  std::vector<std::int64_t> Rows;
  std::vector<std::int64_t> Kept;
  std::vector<std::int64_t> FirstNewId;
  std::vector<std::int64_t> NewRoots;

  std::size_t Size() const { return this->Iteration.size(); }
};

/// Root attributes of a training log.
struct TrainingLogHeader
{
  std::string Format = "vis4gs-training-log";
  int FormatVersion = 1;
  std::string Producer;
  std::string Scene;
  int ShDegree = 3;   ///< the trainer's maximum SH degree
  int Iterations = 0; ///< planned last iteration
};

/// Per-Gaussian arrays of a snapshot, as bit flags (what to read or what a history holds).
enum SnapshotArray : unsigned
{
  SnapshotIds = 1u << 0,
  SnapshotPositions = 1u << 1,
  SnapshotLogScales = 1u << 2,
  SnapshotRotations = 1u << 3,
  SnapshotOpacityLogits = 1u << 4,
  SnapshotSH = 1u << 5,
  SnapshotGradAccum = 1u << 6,
  SnapshotDenom = 1u << 7,
  /// The Gaussian parameters (ids, position, log_scale, rotation, opacity_logit, sh).
  SnapshotParameters = (1u << 6) - 1u,
  SnapshotAll = (1u << 8) - 1u
};

/**
 * History of some Gaussians across all snapshots: one row per (id, snapshot) where the id
 * is alive, ordered by id then iteration. Only the arrays named in Arrays are filled.
 */
struct PropertyHistory
{
  unsigned Arrays = 0;
  std::vector<std::int64_t> Id;
  std::vector<std::int32_t> Iteration;
  std::vector<float> Positions;     ///< 3 per row
  std::vector<float> LogScales;     ///< 3 per row
  std::vector<float> Rotations;     ///< 4 per row
  std::vector<float> OpacityLogits; ///< 1 per row
  std::vector<float> SHDC;          ///< 3 per row: the k=0 (DC) RGB coefficients
  std::vector<float> GradAccum;     ///< 1 per row (NaN where the snapshot lacks it)
  std::vector<float> Denom;         ///< 1 per row (NaN where the snapshot lacks it)

  std::size_t Size() const { return this->Id.size(); }
};

} // namespace vis4gs

#endif

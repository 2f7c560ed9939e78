// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TrainingLogReader.h
 * @brief Reads a training log (DESIGN §3, format versions 1 and 2) lazily and validates it.
 *
 * Opening reads only the root attributes and the list of groups and snapshots. Each table
 * and snapshot is read when asked for, and only the arrays asked for: a snapshot read
 * without SH rest reads the k = 0 hyperslab of `sh`; the property history of a few ids
 * reads, per snapshot, only what its search touches and then the selected rows, never
 * whole snapshots: on uncompressed snapshots (the writers' default) exactly the bytes of
 * the probed and selected rows (pread at the chunk addresses, several snapshots at once),
 * on compressed ones the chunks holding them.
 *
 * Validation: a file that is not a training log, or of another format version, throws.
 * Missing optional groups are reported by GetLacks() as sentences a user can read. Broken
 * content (events naming unknown ids, duplicate or decreasing ids in a snapshot,
 * snapshot names that disagree with their iteration) throws a std::runtime_error naming
 * the file and the problem; with TrainingLogReaderOptions::Repair the reader returns a
 * repaired result instead and lists each repair in GetRepairs(). The file is never written.
 *
 * The reader opens the file without HDF5 file locking, in SWMR read mode when it can, so a
 * log can be read while a trainer still appends to it (it sees the state of the trainer's
 * last flush) without ever blocking it. Of a log that its writer keeps in HDF5's SWMR mode
 * (format version 2, the Python logger's and `vis4gs train`'s), live or killed, it uses only
 * the rows the writer counted in /committed after flushing them. Refresh() reopens the file
 * to see what was written since (`--follow`).
 */
#ifndef vis4gs_TrainingLogReader_h
#define vis4gs_TrainingLogReader_h

#include "Camera.h"
#include "GaussianCloud.h"
#include "ImageIO.h"
#include "TrainingLogTypes.h"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace vis4gs
{

struct TrainingLogReaderOptions
{
  /// Repair broken content in memory (listed by GetRepairs()) instead of throwing.
  bool Repair = false;
};

struct SnapshotReadOptions
{
  /// SnapshotArray flags of the arrays to read. Ids are always read (they are validated).
  unsigned Arrays = SnapshotParameters;
  /// SH degree to read when SnapshotSH is set: 0 = DC only (the default; the SH rest is not
  /// read), -1 = everything the snapshot holds; clamped to what it holds.
  int ShDegree = 0;
};

class TrainingLogReader
{
public:
  /// Opens and validates @p path; throws std::runtime_error naming the file on failure.
  explicit TrainingLogReader(const std::string& path,
    const TrainingLogReaderOptions& options = TrainingLogReaderOptions());
  ~TrainingLogReader();
  TrainingLogReader(const TrainingLogReader&) = delete;
  TrainingLogReader& operator=(const TrainingLogReader&) = delete;

  const std::string& GetPath() const;
  /**
   * Closes and reopens the file and re-reads its lists (snapshots, table lengths) to see
   * what a running writer added; true when something changed. A reopen that fails (the
   * writer is between states) is tried again for about 0.2 s, then throws naming the file;
   * the reader then has no file open until a later Refresh() succeeds. Follow a live file
   * with one reader per process: HDF5 shares a second open of a file with the first, and a
   * reader reopening while another keeps the file open can keep a view that lags the writer
   * (seen: its datasets shorter than /committed counts, which it then reports as an error).
   */
  bool Refresh();
  /**
   * Whether the file is open in HDF5's SWMR read mode: the reader's first choice, needed for a
   * log whose writer runs in SWMR mode or was killed; false when this process already had the
   * file open otherwise (a writer), whose open is then shared.
   */
  bool IsSwmrRead() const;
  const TrainingLogHeader& GetHeader() const;
  /// What the file lacks, one sentence each (empty for a complete log).
  const std::vector<std::string>& GetLacks() const;
  /// Repairs made so far (with Repair on), one sentence each.
  const std::vector<std::string>& GetRepairs() const;

  bool HasCameras() const;
  bool HasImages() const;
  bool HasMetrics() const;
  bool HasTestMetrics() const;
  bool HasEvents() const;

  /// Logged snapshot iterations, increasing.
  const std::vector<int>& GetSnapshotIterations() const;
  /// The logged iteration nearest to @p iteration (ties: the earlier one); -1 when none.
  int FindNearestSnapshot(int iteration) const;
  /// Number of Gaussians of the snapshot at exactly @p iteration (throws if not logged).
  std::size_t GetSnapshotSize(int iteration) const;
  /// SH degree held by the snapshot at @p iteration ((K = (degree+1)^2 coefficients).
  int GetSnapshotShDegree(int iteration) const;
  /// SnapshotArray flags of the datasets the snapshot at @p iteration holds.
  unsigned GetSnapshotArrays(int iteration) const;

  /**
   * Reads the snapshot at exactly @p iteration. grad_accum / denom, when asked for and
   * present, are returned as float32 extra properties "grad_accum" / "denom".
   */
  GaussianCloud ReadSnapshot(int iteration, const SnapshotReadOptions& options = {}) const;
  /// Reads the snapshot nearest to @p iteration; its iteration goes to @p loggedIteration.
  GaussianCloud ReadNearestSnapshot(int iteration,
    const SnapshotReadOptions& options,
    int* loggedIteration) const;

  std::vector<Camera> ReadCameras() const;
  /// Reads /images/<name> ([H,W,3] u8); throws when absent.
  std::vector<unsigned char> ReadImage(const std::string& name, int& width, int& height) const;
  /// Names of the embedded images.
  std::vector<std::string> GetImageNames() const;
  /// Reads /metrics (or /metrics/test); missing value columns are filled with NaN.
  MetricsTable ReadMetrics(bool test = false) const;
  /// Reads and validates /events (empty table when the file has none); the new roots and
  /// ended ids of /lineage_breaks are part of the validation.
  EventTable ReadEvents() const;
  /// Whether the file has /lineage_breaks (the logger lost the lineage of some rows).
  bool HasLineageBreaks() const;
  /// Reads /lineage_breaks (empty table when the file has none); throws, naming the file,
  /// on columns of different lengths or rows out of order (iteration, event row, new ids).
  LineageBreakTable ReadLineageBreaks() const;
  /**
   * History of @p ids across all snapshots: one row per (id, snapshot holding it), ordered
   * by id then iteration, with the arrays named by @p arrays (SnapshotSH means the DC term).
   * Reads only the ids the search probes and the selected rows of each dataset (whole
   * chunks of them when the snapshot is compressed).
   */
  PropertyHistory ReadPropertyHistory(const std::vector<std::int64_t>& ids,
    unsigned arrays = SnapshotPositions | SnapshotLogScales | SnapshotRotations |
      SnapshotOpacityLogits | SnapshotSH) const;

private:
  struct Internals;
  std::unique_ptr<Internals> Impl;
};

/**
 * The training image of @p camera, prepared as PrepareTrainingImage() does (@p background
 * behind transparent pixels): "/images/<name>" is read from @p log when no file of that path
 * exists (the camera tables of a log name their images so, DESIGN §3), any other path from its
 * file. False when there is neither (no image: the caller decides what that means); errors
 * reading an image that exists throw, naming it.
 */
bool LoadCameraImage(const TrainingLogReader* log,
  const Camera& camera,
  Image& image,
  const std::array<float, 3>& background = { 0, 0, 0 });

} // namespace vis4gs

#endif

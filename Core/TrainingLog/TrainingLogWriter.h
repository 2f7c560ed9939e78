// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TrainingLogWriter.h
 * @brief Writes a training log (DESIGN §3, format version 1, or 2 in SWMR mode) while a trainer
 * runs.
 *
 * The writer appends: metrics rows and events are buffered in memory and written at each
 * Flush(); a snapshot is written (and, by default, flushed) when it is handed over. The
 * file is valid after every Flush(): HDF5's metadata cache is kept from writing anything
 * between flushes and freed file space is never reused, so a process killed mid-run
 * leaves a log that reads up to its last flush (tested by SIGKILL-ing a writer).
 *
 * With WriteToTemporary a whole file is written under "<path>.tmp" and renamed onto
 * @c path by Close(), so that a reader never sees a half-written file; a writer destroyed
 * without a successful Close() (an error unwinds its owner: a full disk) removes the temporary
 * and leaves what was at @c path untouched. A constructor that fails once the file exists
 * removes it, in both modes.
 *
 * With Swmr the file is format version 2 in HDF5's single-writer/multiple-reader mode, which
 * readers (`vis4gs view LOG --follow`, `vis4gs analyze`) open while the trainer writes it,
 * without blocking it: the snapshots are rows of concatenated datasets and each Flush()
 * counts the rows in /committed only after they are flushed. A SWMR writer cannot create
 * datasets, so SWMR mode starts after the first snapshot: cameras and images must be written
 * before it (later they throw).
 *
 * Errors throw std::runtime_error naming the file.
 */
#ifndef vis4gs_TrainingLogWriter_h
#define vis4gs_TrainingLogWriter_h

#include "Camera.h"
#include "GaussianCloud.h"
#include "TrainingLogTypes.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace vis4gs
{

struct TrainingLogWriterOptions
{
  std::string Producer = "vis4gs";
  std::string Scene;
  int ShDegree = 3;       ///< the trainer's maximum SH degree (root attribute sh_degree)
  int Iterations = 30000; ///< planned last iteration (root attribute iterations)
  /// Deflate level (with the shuffle filter) of the metrics, events, cameras and images;
  /// 0 disables compression.
  int DeflateLevel = 1;
  /**
   * Deflate level (with the shuffle filter) of the per-Gaussian snapshot datasets (id,
   * position, ..., sh, grad_accum, denom). Default 0 (uncompressed): deflate saves only
   * ~15 % on float32 parameters but makes every history query inflate whole chunks, while
   * uncompressed chunks let the reader fetch just the bytes of the requested rows.
   */
  int SnapshotDeflateLevel = 0;
  /// Rows per chunk of the per-Gaussian snapshot datasets.
  std::size_t SnapshotChunkRows = 4096;
  /// Rows per chunk of the metrics and events tables.
  std::size_t TableChunkRows = 65536;
  /// Flush after every snapshot (so a crash keeps everything up to the last snapshot).
  bool FlushOnSnapshot = true;
  /// Write "<path>.tmp" and rename it onto path in Close() (whole-file writers).
  bool WriteToTemporary = false;
  /// Format version 2 in SWMR mode from the first snapshot on (default off: version 1);
  /// with WriteToTemporary the live file is "<path>.tmp" (`vis4gs view --follow` finds it).
  bool Swmr = false;
  /**
   * Also flush when a metrics row is appended this many seconds after the last flush (0, the
   * default: only at snapshots and Flush()), so that a reader following the log sees metrics
   * and events between snapshots.
   */
  double FlushIntervalSeconds = 0.0;
};

/// Optional per-Gaussian densification statistics of a snapshot (empty = not written).
struct SnapshotStatistics
{
  std::vector<float> GradAccum; ///< mean view-space gradient norm since the last densification
  std::vector<float> Denom;     ///< its count
};

class TrainingLogWriter
{
public:
  /// Creates (truncates) @p path and writes the root attributes; throws on failure.
  TrainingLogWriter(const std::string& path, const TrainingLogWriterOptions& options = {});
  /// Closes the file (errors are swallowed; call Close() to see them); with WriteToTemporary
  /// and no successful Close(), removes the temporary instead.
  ~TrainingLogWriter();
  TrainingLogWriter(const TrainingLogWriter&) = delete;
  TrainingLogWriter& operator=(const TrainingLogWriter&) = delete;

  /// Writes /cameras (once; a second call throws).
  void WriteCameras(const std::vector<Camera>& cameras);
  /// Embeds an [height,width,3] u8 image as /images/<name>.
  void WriteImage(const std::string& name, int width, int height, const unsigned char* rgb);
  /// Buffers one row of /metrics (@p test: /metrics/test).
  void AppendMetrics(const MetricsRow& row, bool test = false);
  /// Buffers events (rows in the order the trainer did them).
  void AppendEvent(const TrainingEvent& event);
  void AppendEvents(const EventTable& events);
  /**
   * Writes /snapshots/<iteration> from @p cloud: ids (cloud.Ids, or 0..N-1 when empty) must
   * be strictly increasing; SH is written with K = cloud.ShCoefficientCount() (K = 1 when
   * only DC). Iterations must increase from one snapshot to the next.
   */
  void WriteSnapshot(int iteration,
    const GaussianCloud& cloud,
    const SnapshotStatistics* statistics = nullptr);
  /// Writes buffered rows and flushes the file: after it returns the file is a valid log.
  void Flush();
  /// Flushes and closes; with WriteToTemporary renames the file onto its final path.
  void Close();

  /// The final path of the log.
  const std::string& GetPath() const;
  /// Number of rows written or buffered so far.
  std::size_t GetNumberOfEvents() const;
  std::size_t GetNumberOfMetricsRows(bool test = false) const;
  /// Iteration of the last snapshot written (-1 when none).
  int GetLastSnapshotIteration() const;

  /// Name of the snapshot group of @p iteration ("001500").
  static std::string SnapshotName(int iteration);

private:
  /// The root attributes, the empty tables and groups, flushed (the constructor's work once the
  /// file exists).
  void WriteHeader();

  struct Internals;
  std::unique_ptr<Internals> Impl;
};

} // namespace vis4gs

#endif

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TrainingLogChunks.h
 * @brief Private fast path for reading the training log's chunked datasets (not installed).
 *
 * HDF5 decodes one chunk at a time on one thread and pays a large fixed cost per chunk. For
 * the plain layouts our writers produce (chunked along rows, optional shuffle + deflate,
 * little-endian types equal to the memory type), the raw chunks are read with
 * H5Dread_chunk (serially, as HDF5 requires) and inflated / unshuffled here on all threads.
 * Anything else (other filters, types, layouts, unallocated chunks) returns false and the
 * caller uses H5Dread, so results never depend on which path ran.
 *
 * For unfiltered datasets, DirectRows reads single rows: it looks up the chunk addresses
 * and reads just the rows' bytes from the file descriptor (history queries).
 */
#ifndef vis4gs_TrainingLogChunks_h
#define vis4gs_TrainingLogChunks_h

#include <hdf5.h>

#include <cstddef>
#include <vector>

namespace vis4gs
{
namespace h5
{

/**
 * Reads a whole dataset of dims [N] or [N,W] (all of it), or [N,K,3] restricted to its
 * first @p kLoad coefficients (output [N,kLoad,3]), into @p out as @p memType.
 */
bool FastReadAll(hid_t dset, hid_t memType, std::size_t kLoad, void* out);

/**
 * Reads the given increasing @p rows of a dataset of dims [N], [N,W] or [N,K,3] (k = 0 only)
 * into @p out ([rows, W] or [rows, 3]) as @p memType.
 */
bool FastReadRows(hid_t dset, hid_t memType, const std::vector<hsize_t>& rows, void* out);

/**
 * Byte-exact row access to an unfiltered dataset of dims [N], [N,W] or [N,K,3] (k = 0 only)
 * chunked along rows, stored with memory type @p memType in a file opened with the POSIX
 * (sec2) driver: the chunk addresses come from H5Dget_chunk_info_by_coord and the bytes of
 * the requested rows are read with pread, so a row costs one small read instead of a chunk.
 * Open() returns false for anything else (filters, other layouts or drivers), and Read()
 * false when a chunk is unallocated or a read fails; callers then use the HDF5 paths.
 */
class DirectRows
{
public:
  bool Open(hid_t dset, hid_t memType);
  /// Reads rows [first, first + count) into @p out ([count, W] or [count, 3]). Chunk
  /// addresses not yet resolved are looked up under an OpenMP critical section, so distinct
  /// DirectRows may read on distinct threads; once the rows' chunks are resolved
  /// (Resolve()), the dataset handle given to Open() may be closed.
  bool Read(hsize_t first, hsize_t count, void* out);
  /// Reads the given increasing @p rows into @p out.
  bool ReadRows(const std::vector<hsize_t>& rows, void* out);
  /**
   * Asks the kernel to start reading the bytes of @p rows (POSIX_FADV_WILLNEED) without
   * waiting, so that many scattered reads of a cold file proceed in parallel on the device.
   */
  void Prefetch(const std::vector<hsize_t>& rows);
  /**
   * Looks up the addresses of the chunks holding @p rows (all chunks when empty) with HDF5,
   * after which Read()/ReadRows() of those rows make no HDF5 call. False when a chunk is
   * unallocated.
   */
  bool Resolve(const std::vector<hsize_t>& rows);
  hsize_t Size() const { return this->Rows; }
  std::size_t ChunkCount() const { return this->Addresses.size(); }

private:
  bool ChunkAddress(hsize_t chunk, haddr_t& address);

  hid_t Dataset = -1;
  int Descriptor = -1;
  hsize_t Rows = 0;
  hsize_t ChunkRows = 0;
  std::size_t RowBytes = 0;
  std::size_t ChunkBytes = 0;
  std::vector<haddr_t> Addresses; ///< per chunk; 0 = not looked up yet
};

/**
 * While alive, advises the kernel that the file behind @p file (sec2 driver only) is read at
 * random (no readahead: a history query reads a few hundred bytes here and there, and
 * readahead would pull in most of a cold file); restores normal readahead when destroyed.
 */
class RandomAccessHint
{
public:
  explicit RandomAccessHint(hid_t file);
  ~RandomAccessHint();
  RandomAccessHint(const RandomAccessHint&) = delete;
  RandomAccessHint& operator=(const RandomAccessHint&) = delete;

private:
  int Descriptor = -1;
};

} // namespace h5
} // namespace vis4gs

#endif

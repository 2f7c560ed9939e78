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

} // namespace h5
} // namespace vis4gs

#endif

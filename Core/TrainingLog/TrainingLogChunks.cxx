// SPDX-License-Identifier: BSD-3-Clause
#include "TrainingLogChunks.h"

#include "TrainingLogHDF5.h"

#include <fcntl.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <utility>

namespace vis4gs
{
namespace h5
{

namespace
{
struct Layout
{
  std::vector<hsize_t> Dims;
  hsize_t ChunkRows = 0;
  std::size_t RowWidth = 1; ///< values per row inside one chunk (W, or 3 for [N,K,3])
  std::size_t ElementSize = 0;
  bool Shuffle = false;
  bool Deflate = false;
  unsigned ShuffleBit = 0, DeflateBit = 0; ///< filter-mask bits of each filter
};

bool Inspect(hid_t dset, hid_t memType, Layout& l)
{
  ErrorSilencer silence;
  l.Dims = Dims(dset);
  const std::size_t rank = l.Dims.size();
  if (rank < 1 || rank > 3)
  {
    return false;
  }
  Handle type(H5Dget_type(dset));
  if (!type.Valid() || H5Tequal(type, memType) <= 0)
  {
    return false;
  }
  l.ElementSize = H5Tget_size(memType);
  Handle plist(H5Dget_create_plist(dset));
  if (H5Pget_layout(plist) != H5D_CHUNKED)
  {
    return false;
  }
  hsize_t chunk[3] = { 0, 0, 0 };
  if (H5Pget_chunk(plist, 3, chunk) != static_cast<int>(rank))
  {
    return false;
  }
  l.ChunkRows = chunk[0];
  if (rank == 2 && chunk[1] != l.Dims[1])
  {
    return false;
  }
  if (rank == 3 && (chunk[1] != 1 || chunk[2] != l.Dims[2]))
  {
    return false;
  }
  l.RowWidth = rank == 1 ? 1 : static_cast<std::size_t>(rank == 2 ? l.Dims[1] : l.Dims[2]);
  const int n = H5Pget_nfilters(plist);
  for (int i = 0; i < n; ++i)
  {
    unsigned flags = 0;
    std::size_t nelmts = 0;
    unsigned config = 0;
    const H5Z_filter_t id = H5Pget_filter2(
      plist, static_cast<unsigned>(i), &flags, &nelmts, nullptr, 0, nullptr, &config);
    if (id == H5Z_FILTER_SHUFFLE && !l.Deflate && !l.Shuffle)
    {
      l.Shuffle = true;
      l.ShuffleBit = 1u << i;
    }
    else if (id == H5Z_FILTER_DEFLATE && !l.Deflate)
    {
      l.Deflate = true;
      l.DeflateBit = 1u << i;
    }
    else
    {
      return false;
    }
  }
  return l.ChunkRows > 0 && l.ElementSize > 0;
}

/// One chunk to decode: its raw bytes and filter mask, and where its rows go.
struct Unit
{
  hsize_t Offset[3] = { 0, 0, 0 };
  std::vector<unsigned char> Raw;
  unsigned Mask = 0;
};

/// Decodes @p u into @p plain (ChunkRows*RowWidth*ElementSize bytes); false on corrupt data.
bool Decode(const Layout& l,
  const Unit& u,
  std::vector<unsigned char>& plain,
  std::vector<unsigned char>& scratch)
{
  const std::size_t bytes = static_cast<std::size_t>(l.ChunkRows) * l.RowWidth * l.ElementSize;
  plain.resize(bytes);
  const unsigned char* src = u.Raw.data();
  std::size_t srcSize = u.Raw.size();
  if (l.Deflate && !(u.Mask & l.DeflateBit))
  {
    uLongf len = static_cast<uLongf>(bytes);
    if (uncompress(plain.data(), &len, src, static_cast<uLong>(srcSize)) != Z_OK || len != bytes)
    {
      return false;
    }
  }
  else
  {
    if (srcSize != bytes)
    {
      return false;
    }
    std::memcpy(plain.data(), src, bytes);
  }
  if (l.Shuffle && !(u.Mask & l.ShuffleBit) && l.ElementSize > 1)
  {
    const std::size_t count = bytes / l.ElementSize;
    scratch.resize(bytes);
    for (std::size_t b = 0; b < l.ElementSize; ++b)
    {
      const unsigned char* in = plain.data() + b * count;
      for (std::size_t e = 0; e < count; ++e)
      {
        scratch[e * l.ElementSize + b] = in[e];
      }
    }
    plain.swap(scratch);
  }
  return true;
}

/// Reads the raw chunks of @p units (serial HDF5 calls); false when one is missing.
bool ReadRaw(hid_t dset, std::vector<Unit>& units, std::size_t begin, std::size_t end)
{
  ErrorSilencer silence;
  for (std::size_t i = begin; i < end; ++i)
  {
    Unit& u = units[i];
    hsize_t size = 0;
    if (H5Dget_chunk_storage_size(dset, u.Offset, &size) < 0 || size == 0 || size > (1u << 30))
    {
      H5Eclear2(H5E_DEFAULT);
      return false;
    }
    u.Raw.resize(static_cast<std::size_t>(size));
    uint32_t mask = 0;
    if (H5Dread_chunk(dset, H5P_DEFAULT, u.Offset, &mask, u.Raw.data()) < 0)
    {
      H5Eclear2(H5E_DEFAULT);
      return false;
    }
    u.Mask = mask;
  }
  return true;
}

/**
 * Reads @p units in batches (raw reads serial, decoding in parallel) and hands each decoded
 * chunk to @p sink(unit, plain) (called in parallel for distinct units).
 */
template <typename Sink>
bool Process(hid_t dset, const Layout& l, std::vector<Unit>& units, Sink sink)
{
  const std::size_t batch = 64;
  for (std::size_t begin = 0; begin < units.size(); begin += batch)
  {
    const std::size_t end = std::min(units.size(), begin + batch);
    if (!ReadRaw(dset, units, begin, end))
    {
      return false;
    }
    std::atomic<bool> ok(true);
    const long long b = static_cast<long long>(begin), e = static_cast<long long>(end);
    // Threads only pay off with several chunks (and cost a lot on a busy machine).
#pragma omp parallel if (e - b >= 8)
    {
      std::vector<unsigned char> plain, scratch;
#pragma omp for schedule(dynamic, 1)
      for (long long i = b; i < e; ++i)
      {
        Unit& u = units[static_cast<std::size_t>(i)];
        if (!Decode(l, u, plain, scratch))
        {
          ok = false;
          continue;
        }
        sink(u, plain);
        std::vector<unsigned char>().swap(u.Raw);
      }
    }
    if (!ok)
    {
      return false;
    }
  }
  return true;
}
} // namespace

//------------------------------------------------------------------------------
bool FastReadAll(hid_t dset, hid_t memType, std::size_t kLoad, void* out)
{
  Layout l;
  if (!Inspect(dset, memType, l))
  {
    return false;
  }
  const hsize_t n = l.Dims[0];
  const bool rank3 = l.Dims.size() == 3;
  const std::size_t k = rank3 ? kLoad : 1;
  if (rank3 && (kLoad == 0 || kLoad > l.Dims[1]))
  {
    return false;
  }
  std::vector<Unit> units;
  for (hsize_t r = 0; r < n; r += l.ChunkRows)
  {
    for (std::size_t c = 0; c < k; ++c)
    {
      Unit u;
      u.Offset[0] = r;
      u.Offset[1] = c;
      units.push_back(std::move(u));
    }
  }
  const std::size_t rowBytes = l.RowWidth * l.ElementSize; // one row of one chunk
  unsigned char* dst = static_cast<unsigned char*>(out);
  return Process(dset,
    l,
    units,
    [&](const Unit& u, const std::vector<unsigned char>& plain)
    {
      const hsize_t first = u.Offset[0];
      const std::size_t rows = static_cast<std::size_t>(std::min(l.ChunkRows, n - first));
      if (!rank3)
      {
        std::memcpy(dst + first * rowBytes, plain.data(), rows * rowBytes);
        return;
      }
      const std::size_t kk = static_cast<std::size_t>(u.Offset[1]);
      for (std::size_t r = 0; r < rows; ++r)
      {
        std::memcpy(dst + ((first + r) * k + kk) * rowBytes, plain.data() + r * rowBytes, rowBytes);
      }
    });
}

//------------------------------------------------------------------------------
bool FastReadRows(hid_t dset, hid_t memType, const std::vector<hsize_t>& rows, void* out)
{
  Layout l;
  if (!Inspect(dset, memType, l))
  {
    return false;
  }
  const hsize_t n = l.Dims[0];
  std::vector<Unit> units;
  std::vector<std::pair<std::size_t, std::size_t>> ranges; // rows of each unit: [begin, end)
  for (std::size_t i = 0; i < rows.size();)
  {
    if (rows[i] >= n || (i > 0 && rows[i] <= rows[i - 1]))
    {
      return false;
    }
    const hsize_t chunk = rows[i] / l.ChunkRows;
    std::size_t j = i;
    while (j < rows.size() && rows[j] / l.ChunkRows == chunk)
    {
      ++j;
    }
    Unit u;
    u.Offset[0] = chunk * l.ChunkRows;
    units.push_back(std::move(u));
    ranges.emplace_back(i, j);
    i = j;
  }
  const std::size_t rowBytes = l.RowWidth * l.ElementSize;
  unsigned char* dst = static_cast<unsigned char*>(out);
  const Unit* base = units.data();
  return Process(dset,
    l,
    units,
    [&](const Unit& u, const std::vector<unsigned char>& plain)
    {
      const std::pair<std::size_t, std::size_t>& range =
        ranges[static_cast<std::size_t>(&u - base)];
      for (std::size_t i = range.first; i < range.second; ++i)
      {
        std::memcpy(
          dst + i * rowBytes, plain.data() + (rows[i] - u.Offset[0]) * rowBytes, rowBytes);
      }
    });
}

//------------------------------------------------------------------------------
bool DirectRows::Open(hid_t dset, hid_t memType)
{
  Layout l;
  if (!Inspect(dset, memType, l) || l.Shuffle || l.Deflate)
  {
    return false;
  }
  ErrorSilencer silence;
  Handle file(H5Iget_file_id(dset));
  Handle fapl(file.Valid() ? H5Fget_access_plist(file) : -1);
  if (!fapl.Valid() || H5Pget_driver(fapl) != H5FD_SEC2)
  {
    return false;
  }
  // HDF5 addresses are relative to the base address, which a user block moves.
  Handle fcpl(H5Fget_create_plist(file));
  hsize_t userBlock = 1;
  if (!fcpl.Valid() || H5Pget_userblock(fcpl, &userBlock) < 0 || userBlock != 0)
  {
    return false;
  }
  void* handle = nullptr;
  if (H5Fget_vfd_handle(file, fapl, &handle) < 0 || !handle)
  {
    H5Eclear2(H5E_DEFAULT);
    return false;
  }
  this->Dataset = dset;
  this->Descriptor = *static_cast<int*>(handle);
  this->Rows = l.Dims[0];
  this->ChunkRows = l.ChunkRows;
  this->RowBytes = l.RowWidth * l.ElementSize;
  this->ChunkBytes = static_cast<std::size_t>(l.ChunkRows) * this->RowBytes;
  this->Addresses.assign(static_cast<std::size_t>((this->Rows + l.ChunkRows - 1) / l.ChunkRows), 0);
  return this->Descriptor >= 0;
}

//------------------------------------------------------------------------------
bool DirectRows::ChunkAddress(hsize_t chunk, haddr_t& address)
{
  if (chunk >= this->Addresses.size())
  {
    return false;
  }
  haddr_t& cached = this->Addresses[static_cast<std::size_t>(chunk)];
  if (cached == 0)
  {
    // Looked up lazily; HDF5 is not thread-safe, so threads that each use their own
    // DirectRows take turns here (the reads themselves need no lock).
    bool ok = false;
#pragma omp critical(vis4gs_training_log_hdf5)
    {
      ErrorSilencer silence;
      hsize_t offset[3] = { chunk * this->ChunkRows, 0, 0 };
      unsigned mask = 0;
      haddr_t a = HADDR_UNDEF;
      hsize_t size = 0;
      ok = H5Dget_chunk_info_by_coord(this->Dataset, offset, &mask, &a, &size) >= 0 &&
        a != HADDR_UNDEF && a != 0 && size == this->ChunkBytes;
      H5Eclear2(H5E_DEFAULT);
      if (ok)
      {
        cached = a;
      }
    }
    if (!ok)
    {
      return false;
    }
  }
  address = cached;
  return true;
}

//------------------------------------------------------------------------------
bool DirectRows::Read(hsize_t first, hsize_t count, void* out)
{
  if (this->Descriptor < 0 || first > this->Rows || count > this->Rows - first)
  {
    return false;
  }
  unsigned char* dst = static_cast<unsigned char*>(out);
  while (count > 0)
  {
    const hsize_t chunk = first / this->ChunkRows;
    const hsize_t inChunk = first - chunk * this->ChunkRows;
    const hsize_t take = std::min(count, this->ChunkRows - inChunk);
    haddr_t address = 0;
    if (!this->ChunkAddress(chunk, address))
    {
      return false;
    }
    const std::size_t bytes = static_cast<std::size_t>(take) * this->RowBytes;
    const off_t at = static_cast<off_t>(address + inChunk * this->RowBytes);
    std::size_t done = 0;
    while (done < bytes)
    {
      const ssize_t got =
        pread(this->Descriptor, dst + done, bytes - done, at + static_cast<off_t>(done));
      if (got <= 0)
      {
        return false;
      }
      done += static_cast<std::size_t>(got);
    }
    dst += bytes;
    first += take;
    count -= take;
  }
  return true;
}

//------------------------------------------------------------------------------
bool DirectRows::ReadRows(const std::vector<hsize_t>& rows, void* out)
{
  unsigned char* dst = static_cast<unsigned char*>(out);
  for (std::size_t i = 0; i < rows.size(); ++i)
  {
    if (!this->Read(rows[i], 1, dst + i * this->RowBytes))
    {
      return false;
    }
  }
  return true;
}

//------------------------------------------------------------------------------
void DirectRows::Prefetch(const std::vector<hsize_t>& rows)
{
  if (this->Descriptor < 0)
  {
    return;
  }
  const off_t page = 4096;
  off_t pending = -1; // last page advised, to skip repeats
  for (hsize_t row : rows)
  {
    haddr_t address = 0;
    if (row >= this->Rows || !this->ChunkAddress(row / this->ChunkRows, address))
    {
      continue;
    }
    const off_t at =
      static_cast<off_t>(address + (row % this->ChunkRows) * this->RowBytes) / page * page;
    if (at != pending)
    {
      posix_fadvise(this->Descriptor,
        static_cast<off_t>(address + (row % this->ChunkRows) * this->RowBytes),
        static_cast<off_t>(this->RowBytes),
        POSIX_FADV_WILLNEED);
      pending = at;
    }
  }
}

//------------------------------------------------------------------------------
bool DirectRows::Resolve(const std::vector<hsize_t>& rows)
{
  if (this->Descriptor < 0)
  {
    return false;
  }
  haddr_t address = 0;
  if (rows.empty())
  {
    for (hsize_t c = 0; c < this->Addresses.size(); ++c)
    {
      if (!this->ChunkAddress(c, address))
      {
        return false;
      }
    }
    return true;
  }
  for (hsize_t row : rows)
  {
    if (row >= this->Rows || !this->ChunkAddress(row / this->ChunkRows, address))
    {
      return false;
    }
  }
  return true;
}

//------------------------------------------------------------------------------
RandomAccessHint::RandomAccessHint(hid_t file)
{
  ErrorSilencer silence;
  Handle fapl(H5Fget_access_plist(file));
  void* handle = nullptr;
  if (fapl.Valid() && H5Pget_driver(fapl) == H5FD_SEC2 &&
    H5Fget_vfd_handle(file, fapl, &handle) >= 0 && handle)
  {
    this->Descriptor = *static_cast<int*>(handle);
    posix_fadvise(this->Descriptor, 0, 0, POSIX_FADV_RANDOM);
  }
  H5Eclear2(H5E_DEFAULT);
}

//------------------------------------------------------------------------------
RandomAccessHint::~RandomAccessHint()
{
  if (this->Descriptor >= 0)
  {
    posix_fadvise(this->Descriptor, 0, 0, POSIX_FADV_NORMAL);
  }
}

} // namespace h5
} // namespace vis4gs

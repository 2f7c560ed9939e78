// SPDX-License-Identifier: BSD-3-Clause
// Over 1,200 lines on purpose: the one TrainingLogReader class (one class per file), one
// method per group of the log format (DESIGN §3: snapshots, cameras, images, metrics, events,
// property histories), each with the validation of its group; the HDF5 and chunk helpers
// they share are already in TrainingLogHDF5.h and TrainingLogChunks.h.
#include "TrainingLogReader.h"

#include "TrainingLogChunks.h"
#include "TrainingLogHDF5.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <unordered_map>

namespace vis4gs
{

namespace
{
struct SnapshotEntry
{
  int Iteration = 0;
  std::string Group; ///< full path, e.g. "/snapshots/000500"; "/snapshots" when packed
  /// Packed layout (format version 2): the snapshot is rows [Offset, Offset + Count) of the
  /// concatenated datasets in /snapshots; version 1: a group whose datasets it fills.
  bool Packed = false;
  hsize_t Offset = 0;
  hsize_t Count = 0;
  int ShDegree = -1; ///< packed: the degree it holds (/snapshots/sh_degree); -1: all of sh
};

/// Columns of /committed (format version 2): rows of each table a reader may use.
enum CommittedColumn
{
  CommittedMetrics,
  CommittedTestMetrics,
  CommittedEvents,
  CommittedBreaks,
  CommittedSnapshots,
  CommittedColumns
};

/// Reads rows [first, first + n) of a dataset of rank 1, 2 ([N,W]) or 3 ([N,K,3], the first
/// @p k coefficients) through HDF5's hyperslab path.
void ReadRowRange(hid_t set,
  hid_t memType,
  hsize_t first,
  hsize_t n,
  hsize_t k,
  void* out,
  const std::string& file,
  const std::string& path)
{
  if (n == 0)
  {
    return;
  }
  std::vector<hsize_t> dims = h5::Dims(set);
  std::vector<hsize_t> start(dims.size(), 0), count = dims;
  start[0] = first;
  count[0] = n;
  if (dims.size() == 3)
  {
    count[1] = k;
  }
  h5::Handle fileSpace(H5Dget_space(set));
  H5Sselect_hyperslab(fileSpace, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr);
  h5::Handle memSpace(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr));
  h5::CheckStatus(
    H5Dread(set, memType, memSpace, fileSpace, H5P_DEFAULT, out), file, "cannot read " + path);
}

herr_t CollectName(hid_t, const char* name, const H5L_info_t*, void* data)
{
  static_cast<std::vector<std::string>*>(data)->push_back(name);
  return 0;
}

bool ParseIteration(const std::string& name, int& value)
{
  if (name.empty() || name.size() > 9 ||
    !std::all_of(name.begin(), name.end(), [](char c) { return c >= '0' && c <= '9'; }))
  {
    return false;
  }
  value = std::stoi(name);
  return true;
}

/// Reads chunk-aligned blocks of a 1-D int64 dataset on demand (for searches).
class IdBlocks
{
public:
  IdBlocks(hid_t dset, hsize_t size, hsize_t blockRows, const std::string& file, hsize_t base = 0)
    : Dataset(dset)
    , Base(base)
    , Size(size)
    , BlockRows(std::max<hsize_t>(1, blockRows))
    , FileBlockRows(std::max<hsize_t>(1, blockRows))
    , File(file)
  {
    // Unfiltered ids (the default since snapshots are written uncompressed): read small
    // blocks of exactly the probed bytes rather than whole chunks.
    if (this->Direct.Open(dset, H5T_NATIVE_INT64))
    {
      this->UseDirect = true;
      this->BlockRows = std::min<hsize_t>(this->BlockRows, 64);
    }
  }

  std::int64_t At(hsize_t row)
  {
    const hsize_t block = row / this->BlockRows;
    auto it = this->Blocks.find(block);
    if (it == this->Blocks.end())
    {
      const hsize_t start = block * this->BlockRows;
      const hsize_t count = std::min(this->BlockRows, this->Size - start);
      std::vector<std::int64_t> values(count);
      if (this->UseDirect && this->Direct.Read(this->Base + start, count, values.data()))
      {
        it = this->Blocks.emplace(block, std::move(values)).first;
        ++this->BlocksRead;
        return it->second[row - block * this->BlockRows];
      }
      this->UseDirect = false;
      if (this->BlockRows != this->FileBlockRows)
      {
        // Direct reads failed: fall back to whole-chunk blocks (drop the small ones).
        this->BlockRows = this->FileBlockRows;
        this->Blocks.clear();
        return this->At(row);
      }
      h5::Handle fileSpace(H5Dget_space(this->Dataset));
      const hsize_t fileStart = this->Base + start;
      H5Sselect_hyperslab(fileSpace, H5S_SELECT_SET, &fileStart, nullptr, &count, nullptr);
      h5::Handle memSpace(H5Screate_simple(1, &count, nullptr));
      h5::CheckStatus(
        H5Dread(this->Dataset, H5T_NATIVE_INT64, memSpace, fileSpace, H5P_DEFAULT, values.data()),
        this->File,
        "cannot read ids");
      it = this->Blocks.emplace(block, std::move(values)).first;
      ++this->BlocksRead;
    }
    return it->second[row - block * this->BlockRows];
  }

  std::size_t BlocksRead = 0;

private:
  hid_t Dataset;
  hsize_t Base; ///< first row of the snapshot in a packed dataset
  hsize_t Size;
  hsize_t BlockRows;
  hsize_t FileBlockRows;
  std::string File;
  std::map<hsize_t, std::vector<std::int64_t>> Blocks;
  h5::DirectRows Direct;
  bool UseDirect = false;
};

/// Rows per chunk of a dataset (0 when not chunked).
hsize_t ChunkRows(hid_t dset)
{
  h5::Handle plist(H5Dget_create_plist(dset));
  if (H5Pget_layout(plist) != H5D_CHUNKED)
  {
    return 0;
  }
  hsize_t dims[8] = { 0 };
  if (H5Pget_chunk(plist, 8, dims) < 1)
  {
    return 0;
  }
  return dims[0];
}

struct ArraySpec
{
  unsigned Flag;
  const char* Name;
  int Width; ///< values per Gaussian (0 for sh)
};

const ArraySpec FloatArrays[] = { { SnapshotPositions, "position", 3 },
  { SnapshotLogScales, "log_scale", 3 },
  { SnapshotRotations, "rotation", 4 },
  { SnapshotOpacityLogits, "opacity_logit", 1 },
  { SnapshotSH, "sh", 0 },
  { SnapshotGradAccum, "grad_accum", 1 },
  { SnapshotDenom, "denom", 1 } };

} // namespace

struct TrainingLogReader::Internals
{
  std::string Path;
  TrainingLogReaderOptions Options;
  h5::Handle File;
  TrainingLogHeader Header;
  std::vector<std::string> Lacks;
  mutable std::vector<std::string> Repairs;
  bool Cameras = false, Images = false, Metrics = false, TestMetrics = false, Events = false,
       Breaks = false;
  std::vector<SnapshotEntry> Snapshots;
  std::vector<int> Iterations;
  /// Format version 2: the rows of each table that the writer committed (CommittedColumn).
  std::vector<std::int64_t> Committed;
  bool Swmr = false; ///< opened in HDF5's SWMR read mode

  /// @p rows capped at what the writer committed (format version 2).
  std::size_t Cap(CommittedColumn column, std::size_t rows) const
  {
    return this->Committed.empty()
      ? rows
      : std::min(
          rows, static_cast<std::size_t>(std::max<std::int64_t>(0, this->Committed[column])));
  }

  [[noreturn]] void Throw(const std::string& what) const
  {
    throw std::runtime_error(this->Path + ": " + what);
  }

  /// Reports a content problem: throws, or (repairing) records @p repair.
  void Problem(const std::string& problem, const std::string& repair) const
  {
    if (!this->Options.Repair)
    {
      this->Throw(problem);
    }
    this->Repairs.push_back(repair);
  }

  const SnapshotEntry& Find(int iteration) const
  {
    auto it = std::lower_bound(this->Iterations.begin(), this->Iterations.end(), iteration);
    if (it == this->Iterations.end() || *it != iteration)
    {
      std::ostringstream s;
      s << "no snapshot at iteration " << iteration << " (logged:";
      for (std::size_t i = 0; i < this->Iterations.size() && i < 20; ++i)
      {
        s << ' ' << this->Iterations[i];
      }
      s << (this->Iterations.size() > 20 ? " ...)" : this->Iterations.empty() ? " none)" : ")");
      this->Throw(s.str());
    }
    return this->Snapshots[static_cast<std::size_t>(it - this->Iterations.begin())];
  }

  h5::Handle OpenDataset(hid_t loc, const std::string& path) const
  {
    if (!h5::IsDataset(loc, path))
    {
      this->Throw("lacks the dataset " + path);
    }
    return h5::Handle(
      h5::Check(H5Dopen2(loc, path.c_str(), H5P_DEFAULT), this->Path, "cannot open " + path));
  }

  void Open();
  void ListSnapshots();
  void ListPackedSnapshots();
  void CheckLacks();
  /// What Refresh() compares: snapshot iterations and table lengths.
  std::vector<std::int64_t> Signature() const;
};

//------------------------------------------------------------------------------
void TrainingLogReader::Internals::Open()
{
  const std::string& path = this->Path;
  h5::Handle fapl(H5Pcreate(H5P_FILE_ACCESS));
#if H5_VERSION_GE(1, 10, 7)
  H5Pset_file_locking(fapl, false, true);
#endif
  // SWMR read mode first: it opens every log (one whose writer runs in SWMR mode, or was
  // killed, refuses a plain read-only open: its superblock says it is open for writing) and
  // never blocks a writer. Plain when this process already has the file open otherwise (a
  // writer: HDF5 refuses other flags then, and shares that open).
  hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, fapl);
  this->Swmr = file >= 0;
  if (file < 0)
  {
    const std::string swmrError = h5::LastErrorMessage();
    H5Eclear2(H5E_DEFAULT);
    file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl);
    if (file < 0)
    {
      const std::string plainError = h5::LastErrorMessage();
      H5Eclear2(H5E_DEFAULT);
      this->Throw("cannot open the training log" +
        (plainError.empty() ? std::string() : ": " + plainError) +
        (swmrError.empty() || swmrError == plainError ? std::string()
                                                      : " (in SWMR read mode: " + swmrError + ")"));
    }
  }
  this->File = h5::Handle(file);
  std::string format;
  if (!h5::ReadStringAttribute(this->File, "format", format, path))
  {
    this->Throw("not a Vis4GS training log (the root has no 'format' attribute)");
  }
  if (format != "vis4gs-training-log")
  {
    this->Throw(
      "not a Vis4GS training log (format is '" + format + "', expected 'vis4gs-training-log')");
  }
  std::int64_t value = 0;
  if (!h5::ReadIntAttribute(this->File, "format_version", value, path))
  {
    this->Throw("the root has no 'format_version' attribute");
  }
  if (value != 1 && value != 2)
  {
    this->Throw(
      "format version " + std::to_string(value) + " is not supported (this reader reads 1 and 2)");
  }
  this->Header.FormatVersion = static_cast<int>(value);
  h5::ReadStringAttribute(this->File, "producer", this->Header.Producer, path);
  h5::ReadStringAttribute(this->File, "scene", this->Header.Scene, path);
  if (h5::ReadIntAttribute(this->File, "sh_degree", value, path))
  {
    this->Header.ShDegree = static_cast<int>(value);
  }
  if (h5::ReadIntAttribute(this->File, "iterations", value, path))
  {
    this->Header.Iterations = static_cast<int>(value);
  }
  if (this->Header.FormatVersion >= 2)
  {
    // Read first: every row it counts was flushed before it was written.
    h5::Handle committed = this->OpenDataset(this->File, "/committed");
    std::vector<hsize_t> dims = h5::Dims(committed);
    if (dims.size() != 1 || dims[0] < CommittedColumns)
    {
      this->Throw("/committed must hold " + std::to_string(int(CommittedColumns)) + " counts");
    }
    this->Committed.assign(static_cast<std::size_t>(dims[0]), 0);
    h5::ReadAll(committed, H5T_NATIVE_INT64, this->Committed.data(), path, "/committed");
    this->Committed.resize(CommittedColumns);
    this->ListPackedSnapshots();
  }
  else
  {
    this->ListSnapshots();
  }
  this->CheckLacks();
}

//------------------------------------------------------------------------------
void TrainingLogReader::Internals::ListPackedSnapshots()
{
  const std::size_t s = this->Cap(CommittedSnapshots, std::numeric_limits<std::size_t>::max());
  if (s == 0 && !h5::IsDataset(this->File, "/snapshots/id"))
  {
    return; // the writer creates the snapshot datasets at its first snapshot
  }
  std::vector<std::int32_t> iterations(s);
  std::vector<std::int64_t> starts(s), counts(s);
  std::vector<std::int32_t> degrees(s, -1);
  hsize_t rows = 0;
  {
    h5::Handle ids = this->OpenDataset(this->File, "/snapshots/id");
    rows = h5::Dims(ids).at(0);
  }
  struct Column
  {
    const char* Name;
    hid_t Type;
    void* Out;
  };
  for (const Column& c : { Column{ "iteration", H5T_NATIVE_INT32, iterations.data() },
         Column{ "start", H5T_NATIVE_INT64, starts.data() },
         Column{ "count", H5T_NATIVE_INT64, counts.data() } })
  {
    const std::string path = std::string("/snapshots/") + c.Name;
    h5::Handle set = this->OpenDataset(this->File, path);
    std::vector<hsize_t> dims = h5::Dims(set);
    if (dims.size() != 1 || dims[0] < s)
    {
      this->Throw(
        path + " holds fewer rows than the " + std::to_string(s) + " snapshots /committed counts");
    }
    ReadRowRange(set, c.Type, 0, s, 0, c.Out, this->Path, path);
  }
  if (h5::IsDataset(this->File, "/snapshots/sh_degree"))
  {
    // Optional: snapshots of a lower degree than /snapshots/sh holds (the rest unwritten).
    h5::Handle set = this->OpenDataset(this->File, "/snapshots/sh_degree");
    if (h5::Dims(set).at(0) < s)
    {
      this->Throw("/snapshots/sh_degree holds fewer rows than /snapshots/iteration");
    }
    ReadRowRange(
      set, H5T_NATIVE_INT32, 0, s, 0, degrees.data(), this->Path, "/snapshots/sh_degree");
  }
  for (std::size_t i = 0; i < s; ++i)
  {
    const std::string row =
      "/snapshots row " + std::to_string(i) + " (iteration " + std::to_string(iterations[i]) + ")";
    if (starts[i] < 0 || counts[i] < 0 || static_cast<hsize_t>(starts[i] + counts[i]) > rows)
    {
      this->Throw(row + " names rows " + std::to_string(starts[i]) + " + " +
        std::to_string(counts[i]) + " beyond the " + std::to_string(rows) +
        " rows of /snapshots/id");
    }
    if (iterations[i] < 0 || (i > 0 && iterations[i] <= iterations[i - 1]))
    {
      this->Problem("snapshots out of order: " + row + " does not follow iteration " +
          std::to_string(i > 0 ? iterations[i - 1] : 0),
        "ignored " + row + ", which is out of order");
      continue;
    }
    SnapshotEntry e;
    e.Iteration = iterations[i];
    e.Group = "/snapshots";
    e.Packed = true;
    e.Offset = static_cast<hsize_t>(starts[i]);
    e.Count = static_cast<hsize_t>(counts[i]);
    e.ShDegree = degrees[i];
    this->Snapshots.push_back(e);
    this->Iterations.push_back(e.Iteration);
  }
}

//------------------------------------------------------------------------------
std::vector<std::int64_t> TrainingLogReader::Internals::Signature() const
{
  std::vector<std::int64_t> s(this->Iterations.begin(), this->Iterations.end());
  s.insert(s.end(), this->Committed.begin(), this->Committed.end());
  if (this->Committed.empty())
  {
    for (const char* path : { "/metrics/iteration",
           "/metrics/test/iteration",
           "/events/iteration",
           "/lineage_breaks/iteration" })
    {
      if (h5::IsDataset(this->File, path))
      {
        h5::Handle set(H5Dopen2(this->File, path, H5P_DEFAULT));
        std::vector<hsize_t> dims = h5::Dims(set);
        s.push_back(dims.empty() ? -1 : static_cast<std::int64_t>(dims[0]));
      }
      else
      {
        s.push_back(-1);
      }
    }
  }
  return s;
}

//------------------------------------------------------------------------------
void TrainingLogReader::Internals::ListSnapshots()
{
  if (!this->File.Valid() || !h5::IsGroup(this->File, "/snapshots"))
  {
    return;
  }
  h5::Handle group(H5Gopen2(this->File, "/snapshots", H5P_DEFAULT));
  std::vector<std::string> names;
  hsize_t index = 0;
  h5::CheckStatus(H5Literate(group, H5_INDEX_NAME, H5_ITER_NATIVE, &index, &CollectName, &names),
    this->Path,
    "cannot list /snapshots");
  std::vector<SnapshotEntry> entries;
  for (const std::string& name : names)
  {
    const std::string path = "/snapshots/" + name;
    if (!h5::IsGroup(this->File, path))
    {
      this->Problem(path + " is not a group", "ignored " + path + ", which is not a group");
      continue;
    }
    int fromName = -1;
    const bool named = ParseIteration(name, fromName);
    std::int64_t fromAttr = -1;
    h5::Handle g(H5Gopen2(this->File, path.c_str(), H5P_DEFAULT));
    const bool attributed = h5::ReadIntAttribute(g, "iteration", fromAttr, this->Path);
    if (!named && !attributed)
    {
      this->Problem(path + " is not named by its iteration and has no 'iteration' attribute",
        "ignored " + path + ", whose iteration is unknown");
      continue;
    }
    if (attributed && (fromAttr < 0 || fromAttr > std::numeric_limits<int>::max()))
    {
      this->Problem(path + " has an invalid iteration attribute " + std::to_string(fromAttr),
        "ignored " + path + ", whose iteration attribute is invalid");
      continue;
    }
    int iteration = attributed ? static_cast<int>(fromAttr) : fromName;
    if (named && attributed && fromName != iteration)
    {
      this->Problem("snapshots out of order: " + path + " holds iteration " +
          std::to_string(iteration) + " (attribute) but is named for iteration " +
          std::to_string(fromName),
        "placed " + path + " at iteration " + std::to_string(iteration) +
          " (its attribute), not at its name's iteration");
    }
    entries.push_back({ iteration, path });
  }
  std::stable_sort(entries.begin(),
    entries.end(),
    [](const SnapshotEntry& a, const SnapshotEntry& b) { return a.Iteration < b.Iteration; });
  for (const SnapshotEntry& e : entries)
  {
    if (!this->Snapshots.empty() && this->Snapshots.back().Iteration == e.Iteration)
    {
      this->Problem("snapshots out of order: " + this->Snapshots.back().Group + " and " + e.Group +
          " both hold iteration " + std::to_string(e.Iteration),
        "ignored " + e.Group + ", a second snapshot of iteration " + std::to_string(e.Iteration));
      continue;
    }
    this->Snapshots.push_back(e);
    this->Iterations.push_back(e.Iteration);
  }
}

//------------------------------------------------------------------------------
void TrainingLogReader::Internals::CheckLacks()
{
  const hid_t f = this->File;
  this->Metrics = h5::IsGroup(f, "/metrics") && h5::IsDataset(f, "/metrics/iteration");
  this->TestMetrics =
    h5::IsGroup(f, "/metrics/test") && h5::IsDataset(f, "/metrics/test/iteration");
  this->Cameras = h5::IsGroup(f, "/cameras") && h5::IsDataset(f, "/cameras/name");
  this->Images = h5::IsGroup(f, "/images");
  this->Events = h5::IsGroup(f, "/events") && h5::IsDataset(f, "/events/iteration");
  this->Breaks = h5::IsGroup(f, "/lineage_breaks") && h5::IsDataset(f, "/lineage_breaks/iteration");
  // Format version 2 creates every table up front: one the writer never filled is absent.
  this->TestMetrics = this->TestMetrics && this->Cap(CommittedTestMetrics, 1) > 0;
  this->Breaks = this->Breaks && this->Cap(CommittedBreaks, 1) > 0;
  if (!this->Metrics)
  {
    this->Lacks.push_back("no /metrics (required by the format): loss, PSNR, SSIM and Gaussian "
                          "count timelines are unavailable");
  }
  if (!this->TestMetrics)
  {
    this->Lacks.push_back("no /metrics/test: test-set metrics are unavailable");
  }
  if (!this->Cameras)
  {
    this->Lacks.push_back("no /cameras: training views are unknown, so View Coverage, Blur and "
                          "Needle scores cannot be computed from the log alone");
  }
  if (!this->Events)
  {
    this->Lacks.push_back("no /events: the densification (genealogy) tree is unavailable");
  }
  if (!h5::IsGroup(f, "/snapshots"))
  {
    this->Lacks.push_back("no /snapshots (required by the format): no Gaussians to show");
  }
  else if (this->Snapshots.empty())
  {
    this->Lacks.push_back("no snapshots in /snapshots: no Gaussians to show");
  }
}

//------------------------------------------------------------------------------
TrainingLogReader::TrainingLogReader(const std::string& path,
  const TrainingLogReaderOptions& options)
  : Impl(new Internals)
{
  Internals& d = *this->Impl;
  d.Path = path;
  d.Options = options;
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe)
    {
      d.Throw("cannot open the training log (no such file or not readable)");
    }
  }
  h5::ErrorSilencer silence;
  if (H5Fis_hdf5(path.c_str()) <= 0)
  {
    H5Eclear2(H5E_DEFAULT);
    d.Throw("not an HDF5 file (a Vis4GS training log is HDF5)");
  }
  d.Open();
}

//------------------------------------------------------------------------------
bool TrainingLogReader::Refresh()
{
  h5::ErrorSilencer silence;
  const std::vector<std::int64_t> before = this->Impl->Signature();
  const std::vector<std::string> lacks = this->Impl->Lacks;
  // A second H5Fopen of a file this process has open shares the first one's metadata cache
  // (and so its stale view): close first.
  this->Impl->File = h5::Handle();
  std::string error;
  for (int attempt = 0; attempt < 10; ++attempt)
  {
    std::unique_ptr<Internals> fresh(new Internals);
    fresh->Path = this->Impl->Path;
    fresh->Options = this->Impl->Options;
    try
    {
      fresh->Open();
    }
    catch (const std::exception& e)
    {
      // The writer is between states (adding /cameras out of SWMR mode): try again shortly.
      error = e.what();
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      continue;
    }
    fresh->Repairs = std::move(this->Impl->Repairs);
    this->Impl = std::move(fresh);
    return this->Impl->Signature() != before || this->Impl->Lacks != lacks;
  }
  throw std::runtime_error(error +
    " (on refreshing; the reader has no file open until a "
    "later Refresh() succeeds)");
}

//------------------------------------------------------------------------------
bool TrainingLogReader::IsSwmrRead() const
{
  return this->Impl->Swmr;
}

//------------------------------------------------------------------------------
TrainingLogReader::~TrainingLogReader() = default;

//------------------------------------------------------------------------------
const std::string& TrainingLogReader::GetPath() const
{
  return this->Impl->Path;
}
const TrainingLogHeader& TrainingLogReader::GetHeader() const
{
  return this->Impl->Header;
}
const std::vector<std::string>& TrainingLogReader::GetLacks() const
{
  return this->Impl->Lacks;
}
const std::vector<std::string>& TrainingLogReader::GetRepairs() const
{
  return this->Impl->Repairs;
}
bool TrainingLogReader::HasCameras() const
{
  return this->Impl->Cameras;
}
bool TrainingLogReader::HasImages() const
{
  return this->Impl->Images;
}
bool TrainingLogReader::HasMetrics() const
{
  return this->Impl->Metrics;
}
bool TrainingLogReader::HasTestMetrics() const
{
  return this->Impl->TestMetrics;
}
bool TrainingLogReader::HasEvents() const
{
  return this->Impl->Events;
}
bool TrainingLogReader::HasLineageBreaks() const
{
  return this->Impl->Breaks;
}
const std::vector<int>& TrainingLogReader::GetSnapshotIterations() const
{
  return this->Impl->Iterations;
}

//------------------------------------------------------------------------------
int TrainingLogReader::FindNearestSnapshot(int iteration) const
{
  const std::vector<int>& its = this->Impl->Iterations;
  if (its.empty())
  {
    return -1;
  }
  auto it = std::lower_bound(its.begin(), its.end(), iteration);
  if (it == its.end())
  {
    return its.back();
  }
  if (it == its.begin() || *it == iteration)
  {
    return *it;
  }
  const int after = *it;
  const int before = *(it - 1);
  return (static_cast<long long>(after) - iteration < static_cast<long long>(iteration) - before)
    ? after
    : before;
}

//------------------------------------------------------------------------------
std::size_t TrainingLogReader::GetSnapshotSize(int iteration) const
{
  const Internals& d = *this->Impl;
  h5::ErrorSilencer silence;
  const SnapshotEntry& e = d.Find(iteration);
  if (e.Packed)
  {
    return static_cast<std::size_t>(e.Count);
  }
  h5::Handle ids = d.OpenDataset(d.File, e.Group + "/id");
  std::vector<hsize_t> dims = h5::Dims(ids);
  if (dims.size() != 1)
  {
    d.Throw(e.Group + "/id is not one-dimensional");
  }
  return static_cast<std::size_t>(dims[0]);
}

//------------------------------------------------------------------------------
int TrainingLogReader::GetSnapshotShDegree(int iteration) const
{
  const Internals& d = *this->Impl;
  h5::ErrorSilencer silence;
  const SnapshotEntry& e = d.Find(iteration);
  h5::Handle sh = d.OpenDataset(d.File, e.Group + "/sh");
  std::vector<hsize_t> dims = h5::Dims(sh);
  const int k = dims.size() == 3 ? static_cast<int>(dims[1]) : 0;
  const int degree = static_cast<int>(std::lround(std::sqrt(static_cast<double>(k)))) - 1;
  if (dims.size() != 3 || dims[2] != 3 || degree < 0 || (degree + 1) * (degree + 1) != k)
  {
    d.Throw(e.Group + "/sh must have the shape [N,K,3] with K = 1, 4, 9 or 16");
  }
  return e.ShDegree >= 0 ? std::min(e.ShDegree, degree) : degree;
}

//------------------------------------------------------------------------------
unsigned TrainingLogReader::GetSnapshotArrays(int iteration) const
{
  const Internals& d = *this->Impl;
  h5::ErrorSilencer silence;
  const SnapshotEntry& e = d.Find(iteration);
  unsigned flags = h5::IsDataset(d.File, e.Group + "/id") ? SnapshotIds : 0u;
  for (const ArraySpec& spec : FloatArrays)
  {
    if (h5::IsDataset(d.File, e.Group + "/" + spec.Name))
    {
      flags |= spec.Flag;
    }
  }
  return flags;
}

//------------------------------------------------------------------------------
GaussianCloud TrainingLogReader::ReadNearestSnapshot(int iteration,
  const SnapshotReadOptions& options,
  int* loggedIteration) const
{
  const int nearest = this->FindNearestSnapshot(iteration);
  if (nearest < 0)
  {
    this->Impl->Throw("the log holds no snapshot");
  }
  if (loggedIteration)
  {
    *loggedIteration = nearest;
  }
  return this->ReadSnapshot(nearest, options);
}

//------------------------------------------------------------------------------
GaussianCloud TrainingLogReader::ReadSnapshot(int iteration,
  const SnapshotReadOptions& options) const
{
  const Internals& d = *this->Impl;
  h5::ErrorSilencer silence;
  const SnapshotEntry& e = d.Find(iteration);
  GaussianCloud cloud;
  h5::Handle idSet = d.OpenDataset(d.File, e.Group + "/id");
  std::vector<hsize_t> dims = h5::Dims(idSet);
  if (dims.size() != 1)
  {
    d.Throw(e.Group + "/id is not one-dimensional");
  }
  // Packed snapshots are a row range of the concatenated datasets (HDF5's hyperslab path);
  // a group's datasets are whole (the parallel chunk path).
  const std::size_t n = static_cast<std::size_t>(e.Packed ? e.Count : dims[0]);
  const hsize_t first = e.Offset;
  cloud.Count = n;
  cloud.Ids.resize(n);
  if (e.Packed)
  {
    ReadRowRange(idSet, H5T_NATIVE_INT64, first, n, 0, cloud.Ids.data(), d.Path, e.Group + "/id");
  }
  else if (n > 0 && !h5::FastReadAll(idSet, H5T_NATIVE_INT64, 1, cloud.Ids.data()))
  {
    h5::ReadAll(idSet, H5T_NATIVE_INT64, cloud.Ids.data(), d.Path, e.Group + "/id");
  }

  for (const ArraySpec& spec : FloatArrays)
  {
    if (!(options.Arrays & spec.Flag))
    {
      continue;
    }
    const std::string path = e.Group + "/" + spec.Name;
    const bool optional = spec.Flag == SnapshotGradAccum || spec.Flag == SnapshotDenom;
    if (optional && !h5::IsDataset(d.File, path))
    {
      continue;
    }
    h5::Handle set = d.OpenDataset(d.File, path);
    std::vector<hsize_t> shape = h5::Dims(set);
    if (shape.empty() || (e.Packed ? shape[0] < first + n : shape[0] != n))
    {
      d.Throw(path + " has " + (shape.empty() ? std::string("no") : std::to_string(shape[0])) +
        " rows but " + e.Group + "/id has " + std::to_string(e.Packed ? first + n : n));
    }
    if (spec.Flag == SnapshotSH)
    {
      const int held = this->GetSnapshotShDegree(iteration);
      const int degree = options.ShDegree < 0 ? held : std::min(options.ShDegree, held);
      const hsize_t k = static_cast<hsize_t>((degree + 1) * (degree + 1));
      cloud.ShDegree = degree;
      cloud.SH.resize(n * k * 3);
      if (n == 0)
      {
        continue;
      }
      if (e.Packed)
      {
        ReadRowRange(set, H5T_NATIVE_FLOAT, first, n, k, cloud.SH.data(), d.Path, path);
        continue;
      }
      if (h5::FastReadAll(set, H5T_NATIVE_FLOAT, static_cast<std::size_t>(k), cloud.SH.data()))
      {
        continue;
      }
      const hsize_t start[3] = { 0, 0, 0 };
      const hsize_t count[3] = { n, k, 3 };
      h5::Handle fileSpace(H5Dget_space(set));
      H5Sselect_hyperslab(fileSpace, H5S_SELECT_SET, start, nullptr, count, nullptr);
      h5::Handle memSpace(H5Screate_simple(3, count, nullptr));
      h5::CheckStatus(
        H5Dread(set, H5T_NATIVE_FLOAT, memSpace, fileSpace, H5P_DEFAULT, cloud.SH.data()),
        d.Path,
        "cannot read " + path);
      continue;
    }
    const bool shapeOk = spec.Width == 1
      ? (shape.size() == 1 || (shape.size() == 2 && shape[1] == 1))
      : (shape.size() == 2 && shape[1] == static_cast<hsize_t>(spec.Width));
    if (!shapeOk)
    {
      d.Throw(path + " must have the shape [N" +
        (spec.Width == 1 ? std::string("]") : "," + std::to_string(spec.Width) + "]"));
    }
    std::vector<float> values(n * static_cast<std::size_t>(spec.Width));
    if (e.Packed)
    {
      ReadRowRange(set, H5T_NATIVE_FLOAT, first, n, 0, values.data(), d.Path, path);
    }
    else if (n > 0 && !h5::FastReadAll(set, H5T_NATIVE_FLOAT, 1, values.data()))
    {
      h5::ReadAll(set, H5T_NATIVE_FLOAT, values.data(), d.Path, path);
    }
    switch (spec.Flag)
    {
      case SnapshotPositions:
        cloud.Positions = std::move(values);
        break;
      case SnapshotLogScales:
        cloud.LogScales = std::move(values);
        break;
      case SnapshotRotations:
        cloud.Rotations = std::move(values);
        break;
      case SnapshotOpacityLogits:
        cloud.OpacityLogits = std::move(values);
        break;
      default:
      {
        ExtraProperty extra;
        extra.Name = spec.Name;
        extra.Type = ScalarType::Float32;
        extra.Bytes.resize(values.size() * sizeof(float));
        std::copy_n(reinterpret_cast<const unsigned char*>(values.data()),
          extra.Bytes.size(),
          extra.Bytes.data());
        cloud.Extra.push_back(std::move(extra));
      }
    }
  }

  // Validate ids: strictly increasing.
  std::size_t bad = 0;
  for (std::size_t i = 1; i < n; ++i)
  {
    if (cloud.Ids[i] <= cloud.Ids[i - 1])
    {
      bad = i;
      break;
    }
  }
  if (bad > 0)
  {
    const std::string what = cloud.Ids[bad] == cloud.Ids[bad - 1] ? "duplicate" : "decreasing";
    const std::string problem = e.Group + "/id has " + what + " ids (id " +
      std::to_string(cloud.Ids[bad]) + " at row " + std::to_string(bad) + " follows " +
      std::to_string(cloud.Ids[bad - 1]) + "); ids must be strictly increasing";
    if (!d.Options.Repair)
    {
      d.Throw(problem);
    }
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(),
      order.end(),
      [&](std::size_t a, std::size_t b) { return cloud.Ids[a] < cloud.Ids[b]; });
    std::vector<std::size_t> keep;
    keep.reserve(n);
    for (std::size_t r : order)
    {
      if (keep.empty() || cloud.Ids[keep.back()] != cloud.Ids[r])
      {
        keep.push_back(r);
      }
    }
    auto gather = [&](auto& values, std::size_t width)
    {
      if (values.empty())
      {
        return;
      }
      std::remove_reference_t<decltype(values)> out(keep.size() * width);
      for (std::size_t i = 0; i < keep.size(); ++i)
      {
        std::copy_n(values.begin() + static_cast<std::ptrdiff_t>(keep[i] * width),
          width,
          out.begin() + static_cast<std::ptrdiff_t>(i * width));
      }
      values = std::move(out);
    };
    gather(cloud.Ids, 1);
    gather(cloud.Positions, 3);
    gather(cloud.LogScales, 3);
    gather(cloud.Rotations, 4);
    gather(cloud.OpacityLogits, 1);
    gather(cloud.SH, static_cast<std::size_t>(3 * cloud.ShCoefficientCount()));
    for (ExtraProperty& extra : cloud.Extra)
    {
      gather(extra.Bytes, sizeof(float));
    }
    d.Repairs.push_back(problem + ": sorted " + std::to_string(n) + " rows by id and dropped " +
      std::to_string(n - keep.size()) + " duplicate rows");
    cloud.Count = keep.size();
  }
  return cloud;
}

//------------------------------------------------------------------------------
std::vector<Camera> TrainingLogReader::ReadCameras() const
{
  const Internals& d = *this->Impl;
  std::vector<Camera> cameras;
  if (!d.Cameras)
  {
    return cameras;
  }
  h5::ErrorSilencer silence;
  h5::Handle nameSet = d.OpenDataset(d.File, "/cameras/name");
  std::vector<std::string> names = h5::ReadStrings(nameSet, d.Path, "/cameras/name");
  const std::size_t v = names.size();
  auto readColumn = [&](const char* name, hid_t memType, void* out, std::size_t width)
  {
    const std::string path = std::string("/cameras/") + name;
    h5::Handle set = d.OpenDataset(d.File, path);
    hssize_t npoints = 0;
    {
      h5::Handle space(H5Dget_space(set));
      npoints = H5Sget_simple_extent_npoints(space);
    }
    std::vector<hsize_t> dims = h5::Dims(set);
    if (dims.empty() || dims[0] != v || static_cast<std::size_t>(npoints) != v * width)
    {
      d.Throw(path + " does not hold " + std::to_string(width) + " value(s) for each of the " +
        std::to_string(v) + " cameras");
    }
    if (v > 0)
    {
      h5::ReadAll(set, memType, out, d.Path, path);
    }
  };
  std::vector<std::uint8_t> split(v, 0);
  std::vector<std::int32_t> width(v), height(v);
  std::vector<double> fx(v), fy(v), cx(v), cy(v), w2c(v * 16);
  if (h5::IsDataset(d.File, "/cameras/split"))
  {
    readColumn("split", H5T_NATIVE_UINT8, split.data(), 1);
  }
  readColumn("width", H5T_NATIVE_INT32, width.data(), 1);
  readColumn("height", H5T_NATIVE_INT32, height.data(), 1);
  readColumn("fx", H5T_NATIVE_DOUBLE, fx.data(), 1);
  readColumn("fy", H5T_NATIVE_DOUBLE, fy.data(), 1);
  readColumn("cx", H5T_NATIVE_DOUBLE, cx.data(), 1);
  readColumn("cy", H5T_NATIVE_DOUBLE, cy.data(), 1);
  readColumn("world_to_camera", H5T_NATIVE_DOUBLE, w2c.data(), 16);
  std::vector<std::string> images(v);
  if (h5::IsDataset(d.File, "/cameras/image"))
  {
    h5::Handle set = d.OpenDataset(d.File, "/cameras/image");
    images = h5::ReadStrings(set, d.Path, "/cameras/image");
    if (images.size() != v)
    {
      d.Throw("/cameras/image does not hold one path per camera");
    }
  }
  cameras.resize(v);
  for (std::size_t i = 0; i < v; ++i)
  {
    Camera& c = cameras[i];
    c.Name = names[i];
    if (split[i] > 1)
    {
      d.Throw("/cameras/split[" + std::to_string(i) + "] is " + std::to_string(split[i]) +
        " (0 train, 1 test)");
    }
    c.Split = split[i] == 1 ? CameraSplit::Test : CameraSplit::Train;
    c.Width = width[i];
    c.Height = height[i];
    c.Fx = fx[i];
    c.Fy = fy[i];
    c.Cx = cx[i];
    c.Cy = cy[i];
    std::copy_n(w2c.begin() + static_cast<std::ptrdiff_t>(16 * i), 16, c.WorldToCamera.begin());
    c.ImagePath = images[i];
  }
  return cameras;
}

//------------------------------------------------------------------------------
std::vector<std::string> TrainingLogReader::GetImageNames() const
{
  const Internals& d = *this->Impl;
  std::vector<std::string> names;
  if (!d.Images)
  {
    return names;
  }
  h5::ErrorSilencer silence;
  h5::Handle group(H5Gopen2(d.File, "/images", H5P_DEFAULT));
  hsize_t index = 0;
  H5Literate(group, H5_INDEX_NAME, H5_ITER_NATIVE, &index, &CollectName, &names);
  return names;
}

//------------------------------------------------------------------------------
std::vector<unsigned char> TrainingLogReader::ReadImage(const std::string& name,
  int& width,
  int& height) const
{
  const Internals& d = *this->Impl;
  h5::ErrorSilencer silence;
  std::string path = name.rfind("/images/", 0) == 0 ? name : "/images/" + name;
  h5::Handle set = d.OpenDataset(d.File, path);
  std::vector<hsize_t> dims = h5::Dims(set);
  if (dims.size() != 3 || dims[2] != 3 || dims[0] == 0 || dims[1] == 0 || dims[0] > (1u << 20) ||
    dims[1] > (1u << 20))
  {
    d.Throw(path + " is not an [H,W,3] image");
  }
  height = static_cast<int>(dims[0]);
  width = static_cast<int>(dims[1]);
  std::vector<unsigned char> rgb(static_cast<std::size_t>(dims[0] * dims[1] * 3));
  h5::ReadAll(set, H5T_NATIVE_UINT8, rgb.data(), d.Path, path);
  return rgb;
}

//------------------------------------------------------------------------------
MetricsTable TrainingLogReader::ReadMetrics(bool test) const
{
  const Internals& d = *this->Impl;
  MetricsTable table;
  if (!(test ? d.TestMetrics : d.Metrics))
  {
    return table;
  }
  h5::ErrorSilencer silence;
  const std::string group = test ? "/metrics/test" : "/metrics";
  h5::Handle itSet = d.OpenDataset(d.File, group + "/iteration");
  std::size_t m = d.Cap(test ? CommittedTestMetrics : CommittedMetrics,
    static_cast<std::size_t>(h5::Dims(itSet).at(0)));
  struct Col
  {
    const char* Name;
    std::vector<double>* Values;
  };
  const Col cols[] = { { "loss", &table.Loss },
    { "l1", &table.L1 },
    { "psnr", &table.Psnr },
    { "ssim", &table.Ssim },
    { "lpips", &table.Lpips },
    { "elapsed_s", &table.ElapsedSeconds } };
  // Column lengths must agree (a repair truncates to the shortest).
  std::vector<std::pair<std::string, std::size_t>> lengths;
  auto length = [&](const std::string& path)
  {
    h5::Handle set = d.OpenDataset(d.File, path);
    std::vector<hsize_t> dims = h5::Dims(set);
    if (dims.size() != 1)
    {
      d.Throw(path + " is not one-dimensional");
    }
    return static_cast<std::size_t>(dims[0]);
  };
  std::size_t shortest = m;
  std::string shortName;
  std::vector<std::string> present;
  for (const char* name : { "num_gaussians", "loss", "l1", "psnr", "ssim", "lpips", "elapsed_s" })
  {
    const std::string path = group + "/" + name;
    if (!h5::IsDataset(d.File, path))
    {
      continue;
    }
    present.push_back(name);
    const std::size_t len = d.Cap(test ? CommittedTestMetrics : CommittedMetrics, length(path));
    if (len != m)
    {
      d.Problem(path + " has " + std::to_string(len) + " rows but " + group + "/iteration has " +
          std::to_string(m),
        "truncated " + group + " to the " + std::to_string(std::min(len, shortest)) +
          " rows all its columns hold");
      if (len < shortest)
      {
        shortest = len;
      }
    }
  }
  m = shortest;
  auto readPrefix = [&](const std::string& path, hid_t memType, void* out)
  {
    if (m == 0)
    {
      return;
    }
    h5::Handle set = d.OpenDataset(d.File, path);
    const hsize_t start = 0, count = m;
    h5::Handle fileSpace(H5Dget_space(set));
    H5Sselect_hyperslab(fileSpace, H5S_SELECT_SET, &start, nullptr, &count, nullptr);
    h5::Handle memSpace(H5Screate_simple(1, &count, nullptr));
    h5::CheckStatus(
      H5Dread(set, memType, memSpace, fileSpace, H5P_DEFAULT, out), d.Path, "cannot read " + path);
  };
  table.Iteration.resize(m);
  readPrefix(group + "/iteration", H5T_NATIVE_INT32, table.Iteration.data());
  table.NumGaussians.assign(m, -1);
  if (std::find(present.begin(), present.end(), "num_gaussians") != present.end())
  {
    readPrefix(group + "/num_gaussians", H5T_NATIVE_INT64, table.NumGaussians.data());
  }
  for (const Col& c : cols)
  {
    c.Values->assign(m, std::numeric_limits<double>::quiet_NaN());
    if (std::find(present.begin(), present.end(), c.Name) != present.end())
    {
      readPrefix(group + "/" + c.Name, H5T_NATIVE_DOUBLE, c.Values->data());
    }
  }
  return table;
}

//------------------------------------------------------------------------------
LineageBreakTable TrainingLogReader::ReadLineageBreaks() const
{
  const Internals& d = *this->Impl;
  LineageBreakTable t;
  if (!d.Breaks)
  {
    return t;
  }
  h5::ErrorSilencer silence;
  struct Column
  {
    const char* Name;
    std::vector<std::int64_t>* Values;
  };
  const Column columns[] = { { "event_row", &t.EventRow },
    { "tracked", &t.Tracked },
    { "rows", &t.Rows },
    { "kept", &t.Kept },
    { "first_new_id", &t.FirstNewId },
    { "new_roots", &t.NewRoots } };
  auto read = [&](const char* name, hid_t type, auto& values)
  {
    const std::string path = std::string("/lineage_breaks/") + name;
    h5::Handle set = d.OpenDataset(d.File, path);
    std::vector<hsize_t> dims = h5::Dims(set);
    if (dims.size() != 1)
    {
      d.Throw(path + " is not one-dimensional");
    }
    values.resize(d.Cap(CommittedBreaks, static_cast<std::size_t>(dims[0])));
    ReadRowRange(set, type, 0, values.size(), 0, values.data(), d.Path, path);
  };
  read("iteration", H5T_NATIVE_INT32, t.Iteration);
  for (const Column& c : columns)
  {
    read(c.Name, H5T_NATIVE_INT64, *c.Values);
    if (c.Values->size() != t.Size())
    {
      d.Throw(std::string("/lineage_breaks/") + c.Name + " has " +
        std::to_string(c.Values->size()) + " rows but /lineage_breaks/iteration has " +
        std::to_string(t.Size()));
    }
  }
  for (std::size_t b = 0; b < t.Size(); ++b)
  {
    const std::string row = "/lineage_breaks row " + std::to_string(b);
    if (t.Kept[b] < 0 || t.NewRoots[b] < 0 || t.FirstNewId[b] < 0 || t.EventRow[b] < 0 ||
      (t.Kept[b] != 0 && t.Kept[b] != t.Tracked[b]) || t.Kept[b] + t.NewRoots[b] != t.Rows[b])
    {
      d.Throw(row + " is inconsistent: kept " + std::to_string(t.Kept[b]) + " of " +
        std::to_string(t.Tracked[b]) + " ids, " + std::to_string(t.NewRoots[b]) +
        " new roots for " + std::to_string(t.Rows[b]) + " rows");
    }
    if (b > 0 &&
      (t.Iteration[b] < t.Iteration[b - 1] || t.EventRow[b] < t.EventRow[b - 1] ||
        t.FirstNewId[b] < t.FirstNewId[b - 1] + t.NewRoots[b - 1]))
    {
      d.Throw(row + " goes back (iteration, event row or new ids) from the row before it");
    }
  }
  return t;
}

//------------------------------------------------------------------------------
EventTable TrainingLogReader::ReadEvents() const
{
  const Internals& d = *this->Impl;
  EventTable t;
  if (!d.Events)
  {
    return t;
  }
  h5::ErrorSilencer silence;
  const char* names[4] = { "iteration", "kind", "parent", "child" };
  std::size_t sizes[4];
  for (int c = 0; c < 4; ++c)
  {
    const std::string path = std::string("/events/") + names[c];
    h5::Handle set = d.OpenDataset(d.File, path);
    std::vector<hsize_t> dims = h5::Dims(set);
    if (dims.size() != 1)
    {
      d.Throw(path + " is not one-dimensional");
    }
    sizes[c] = d.Cap(CommittedEvents, static_cast<std::size_t>(dims[0]));
  }
  std::size_t e = *std::min_element(sizes, sizes + 4);
  if (*std::max_element(sizes, sizes + 4) != e)
  {
    d.Problem("the /events columns have different lengths (" + std::to_string(sizes[0]) + ", " +
        std::to_string(sizes[1]) + ", " + std::to_string(sizes[2]) + ", " +
        std::to_string(sizes[3]) + ")",
      "truncated /events to the " + std::to_string(e) + " rows all its columns hold");
  }
  t.Iteration.resize(e);
  t.Kind.resize(e);
  t.Parent.resize(e);
  t.Child.resize(e);
  void* outs[4] = { t.Iteration.data(), t.Kind.data(), t.Parent.data(), t.Child.data() };
  hid_t types[4] = { H5T_NATIVE_INT32, H5T_NATIVE_UINT8, H5T_NATIVE_INT64, H5T_NATIVE_INT64 };
  for (int c = 0; c < 4 && e > 0; ++c)
  {
    const std::string path = std::string("/events/") + names[c];
    h5::Handle set = d.OpenDataset(d.File, path);
    if (sizes[c] == e && h5::Dims(set).at(0) == e && h5::FastReadAll(set, types[c], 1, outs[c]))
    {
      continue;
    }
    const hsize_t start = 0, count = e;
    h5::Handle fileSpace(H5Dget_space(set));
    H5Sselect_hyperslab(fileSpace, H5S_SELECT_SET, &start, nullptr, &count, nullptr);
    h5::Handle memSpace(H5Screate_simple(1, &count, nullptr));
    h5::CheckStatus(H5Dread(set, types[c], memSpace, fileSpace, H5P_DEFAULT, outs[c]),
      d.Path,
      "cannot read " + path);
  }

  // 1. Rows are in training order: iterations never decrease.
  for (std::size_t i = 1; i < e; ++i)
  {
    if (t.Iteration[i] < t.Iteration[i - 1])
    {
      d.Problem("/events row " + std::to_string(i) + " (iteration " +
          std::to_string(t.Iteration[i]) + ") follows iteration " +
          std::to_string(t.Iteration[i - 1]) + ": events must be in training order",
        "sorted /events by iteration (stable), as row " + std::to_string(i) + " went back in time");
      std::vector<std::size_t> order(e);
      std::iota(order.begin(), order.end(), std::size_t(0));
      std::stable_sort(order.begin(),
        order.end(),
        [&](std::size_t a, std::size_t b) { return t.Iteration[a] < t.Iteration[b]; });
      EventTable sorted;
      sorted.Reserve(e);
      for (std::size_t r : order)
      {
        sorted.Append(t.Get(r));
      }
      t = std::move(sorted);
      break;
    }
  }

  // 2. Ids: the initial Gaussians are 0..N0-1 with N0 the first new id; new ids increase;
  // a parent must exist and be alive (a split parent stays valid within its split). The
  // new roots of a lineage break are new ids too, born after the break's event row.
  const LineageBreakTable breaks = this->ReadLineageBreaks();
  std::int64_t n0 = -1;
  std::int64_t maxParent = -1;
  for (std::size_t i = 0; i < e; ++i)
  {
    if ((t.Kind[i] == 1 || t.Kind[i] == 2) && t.Child[i] >= 0 && n0 < 0)
    {
      n0 = t.Child[i];
    }
    maxParent = std::max(maxParent, t.Parent[i]);
  }
  for (std::size_t b = 0; b < breaks.Size(); ++b)
  {
    if (breaks.NewRoots[b] > 0 && (n0 < 0 || breaks.FirstNewId[b] < n0))
    {
      n0 = breaks.FirstNewId[b];
    }
  }
  if (n0 < 0)
  {
    n0 = maxParent + 1; // no births: every named id is an initial Gaussian
  }
  const std::int64_t limit = std::int64_t(1) << 31;
  if (n0 > limit)
  {
    d.Throw("/events: the first new id " + std::to_string(n0) + " is implausibly large");
  }
  // End state per id: initial ids by index, born ids by birth order.
  std::vector<std::int32_t> initialEnd(static_cast<std::size_t>(n0), -1);
  std::vector<std::uint8_t> initialKind(static_cast<std::size_t>(n0), 0);
  std::vector<std::int64_t> born;
  born.reserve(e);
  std::vector<std::int32_t> bornEnd;
  std::vector<std::uint8_t> bornKind;
  auto locate = [&](std::int64_t id, std::int32_t*& end, std::uint8_t*& kind) -> bool
  {
    if (id < 0)
    {
      return false;
    }
    if (id < n0)
    {
      end = &initialEnd[static_cast<std::size_t>(id)];
      kind = &initialKind[static_cast<std::size_t>(id)];
      return true;
    }
    std::size_t j = static_cast<std::size_t>(id - n0);
    if (!(j < born.size() && born[j] == id))
    {
      auto it = std::lower_bound(born.begin(), born.end(), id);
      if (it == born.end() || *it != id)
      {
        return false;
      }
      j = static_cast<std::size_t>(it - born.begin());
    }
    end = &bornEnd[j];
    kind = &bornKind[j];
    return true;
  };
  struct Tally
  {
    std::size_t Count = 0;
    std::string First;
  };
  std::map<std::string, Tally> dropped;
  std::size_t fixedPrunes = 0;
  EventTable out;
  if (d.Options.Repair)
  {
    out.Reserve(e);
  }
  std::size_t nextBreak = 0;
  // A break before row i: the ids it could not place end (Kept 0), its new roots are born.
  auto applyBreaks = [&](std::size_t i)
  {
    for (; nextBreak < breaks.Size() && static_cast<std::size_t>(breaks.EventRow[nextBreak]) <= i;
         ++nextBreak)
    {
      const std::size_t b = nextBreak;
      if (breaks.Kept[b] == 0)
      {
        for (std::size_t k = 0; k < initialEnd.size(); ++k)
        {
          if (initialKind[k] == 0)
          {
            initialEnd[k] = breaks.Iteration[b];
            initialKind[k] = 3;
          }
        }
        for (std::size_t k = 0; k < bornEnd.size(); ++k)
        {
          if (bornKind[k] == 0)
          {
            bornEnd[k] = breaks.Iteration[b];
            bornKind[k] = 3;
          }
        }
      }
      if (breaks.NewRoots[b] > 0 && !born.empty() && breaks.FirstNewId[b] <= born.back())
      {
        d.Throw("/lineage_breaks row " + std::to_string(b) + " starts new roots at id " +
          std::to_string(breaks.FirstNewId[b]) + ", which is not a fresh id");
      }
      for (std::int64_t k = 0; k < breaks.NewRoots[b]; ++k)
      {
        born.push_back(breaks.FirstNewId[b] + k);
        bornEnd.push_back(-1);
        bornKind.push_back(0);
      }
    }
  };
  for (std::size_t i = 0; i < e; ++i)
  {
    applyBreaks(i);
    const std::uint8_t kind = t.Kind[i];
    const std::int32_t it = t.Iteration[i];
    std::int64_t child = t.Child[i];
    // Messages are built only for rows with a problem (this loop runs over millions).
    auto where = [&]()
    {
      return "/events row " + std::to_string(i) + " (iteration " + std::to_string(it) + ", " +
        EventKindName(kind) + ", parent " + std::to_string(t.Parent[i]) + ", child " +
        std::to_string(child) + ")";
    };
    const char* category = nullptr;
    std::int32_t* end = nullptr;
    std::uint8_t* endKind = nullptr;
    if (!IsEventKind(kind))
    {
      category = "of an unknown kind";
    }
    else if (!locate(t.Parent[i], end, endKind))
    {
      category = "naming unknown ids";
    }
    else if (*endKind == 3 || (*endKind == 2 && (kind != 2 || *end != it)))
    {
      category = "naming ended ids";
    }
    else if (kind != 3 && (child < n0 || (!born.empty() && child <= born.back())))
    {
      category = "reusing ids";
    }
    if (category)
    {
      if (!d.Options.Repair)
      {
        std::string problem;
        const std::string c = category;
        if (c == "of an unknown kind")
        {
          problem = where() + " has kind " + std::to_string(kind) + " (" + EventKindValues + ")";
        }
        else if (c == "naming unknown ids")
        {
          problem = where() + " names the unknown id " + std::to_string(t.Parent[i]);
        }
        else if (c == "naming ended ids")
        {
          problem = where() + " names id " + std::to_string(t.Parent[i]) + ", which ended (" +
            EventKindName(*endKind) + ") at iteration " + std::to_string(*end);
        }
        else
        {
          problem = where() + " gives the new Gaussian id " + std::to_string(child) +
            ", which is not a fresh id (new ids increase from " + std::to_string(n0) + ")";
        }
        d.Throw(problem);
      }
      Tally& tally = dropped[category];
      if (tally.Count++ == 0)
      {
        tally.First = where();
      }
      continue;
    }
    if (kind == 3 && child != -1)
    {
      if (!d.Options.Repair)
      {
        d.Throw(where() + " is a prune whose child is not -1");
      }
      ++fixedPrunes;
      child = -1;
    }
    if (kind == 3 || kind == 2)
    {
      *end = it;
      *endKind = kind;
    }
    if (kind != 3)
    {
      born.push_back(child);
      bornEnd.push_back(-1);
      bornKind.push_back(0);
    }
    if (d.Options.Repair)
    {
      out.Iteration.push_back(it);
      out.Kind.push_back(kind);
      out.Parent.push_back(t.Parent[i]);
      out.Child.push_back(child);
    }
  }
  if (!d.Options.Repair)
  {
    return t; // valid as read
  }
  for (const auto& entry : dropped)
  {
    d.Repairs.push_back("dropped " + std::to_string(entry.second.Count) + " event(s) " +
      entry.first + " (first: " + entry.second.First + ")");
  }
  if (fixedPrunes > 0)
  {
    d.Repairs.push_back(
      "set the child of " + std::to_string(fixedPrunes) + " prune event(s) to -1");
  }
  return out;
}

namespace
{
/// Minimal id column over unfiltered ids, read with pread only (safe on several threads
/// once the chunk addresses are resolved); sets Failed instead of throwing.
class DirectIdColumn
{
public:
  explicit DirectIdColumn(h5::DirectRows& direct)
    : Direct(direct)
  {
  }

  std::int64_t At(hsize_t row)
  {
    const hsize_t block = row / BlockRows;
    auto it = this->Blocks.find(block);
    if (it == this->Blocks.end())
    {
      const hsize_t start = block * BlockRows;
      const hsize_t count = std::min(BlockRows, this->Direct.Size() - start);
      std::vector<std::int64_t> values(count, 0);
      if (!this->Direct.Read(start, count, values.data()))
      {
        this->Failed = true;
      }
      it = this->Blocks.emplace(block, std::move(values)).first;
    }
    return it->second[row - block * BlockRows];
  }

  bool Failed = false;

private:
  static constexpr hsize_t BlockRows = 64;
  h5::DirectRows& Direct;
  std::map<hsize_t, std::vector<std::int64_t>> Blocks;
};

/**
 * Finds the rows of the sorted, unique @p ids in the strictly increasing id column @p column
 * of @p n > 0 rows by interpolation search; false when the column turns out not to be sorted.
 */
template <typename Column>
bool SearchSortedIds(Column& column,
  hsize_t n,
  const std::vector<std::int64_t>& ids,
  std::vector<hsize_t>& rows,
  std::vector<std::size_t>& which)
{
  bool unsorted = false;
  hsize_t lo = 0;
  const std::int64_t last = column.At(n - 1);
  for (std::size_t q = 0; q < ids.size() && !unsorted; ++q)
  {
    const std::int64_t x = ids[q];
    if (lo >= n || x > last)
    {
      break;
    }
    std::int64_t vlo = column.At(lo);
    if (x < vlo)
    {
      continue;
    }
    hsize_t a = lo, b = n - 1;
    std::int64_t va = vlo, vb = last;
    if (va > vb)
    {
      unsorted = true;
      break;
    }
    // Interpolation search, guarded by bisection to bound the probes.
    bool bisect = false;
    while (va < x && x < vb && b - a > 1)
    {
      const hsize_t width = b - a;
      hsize_t m;
      if (bisect)
      {
        m = a + (b - a) / 2;
      }
      else
      {
        const long double f = static_cast<long double>(x - va) / static_cast<long double>(vb - va);
        m = a + static_cast<hsize_t>(f * static_cast<long double>(b - a));
        m = std::min(std::max(m, a + 1), b - 1);
      }
      const std::int64_t vm = column.At(m);
      if (vm < va || vm > vb)
      {
        unsorted = true;
        break;
      }
      if (vm == x)
      {
        a = b = m;
        va = vb = vm;
        break;
      }
      if (vm < x)
      {
        a = m;
        va = vm;
      }
      else
      {
        b = m;
        vb = vm;
      }
      // Keep interpolating while that at least halves the bracket, else bisect once: at
      // most two probes per halving, and one or two probes for evenly spread ids.
      bisect = !bisect && b - a > width / 2;
    }
    if (unsorted)
    {
      break;
    }
    // The rows next to a hit must bracket it (cheap: they share its cached block).
    const hsize_t hitRow = va == x ? a : b;
    if ((va == x || vb == x) &&
      ((hitRow > 0 && column.At(hitRow - 1) >= x) ||
        (hitRow + 1 < n && column.At(hitRow + 1) <= x)))
    {
      unsorted = true;
      break;
    }
    if (va == x)
    {
      rows.push_back(a);
      which.push_back(q);
      lo = a + 1;
    }
    else if (vb == x)
    {
      rows.push_back(b);
      which.push_back(q);
      lo = b + 1;
    }
    else
    {
      lo = a + 1 <= b ? a + 1 : b;
    }
  }
  return !unsorted;
}

} // namespace

//------------------------------------------------------------------------------
PropertyHistory TrainingLogReader::ReadPropertyHistory(const std::vector<std::int64_t>& requested,
  unsigned arrays) const
{
  const Internals& d = *this->Impl;
  h5::ErrorSilencer silence;
  h5::RandomAccessHint randomAccess(d.File);
  std::vector<std::int64_t> ids = requested;
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());

  struct Hit
  {
    std::size_t IdIndex;
    std::size_t Snapshot;
    std::size_t Row; ///< index into the per-snapshot value buffers
  };
  std::vector<Hit> hits;
  // Values per snapshot, in the order of the rows found in it.
  struct Found
  {
    std::vector<float> Values[7];
    bool Has[7] = { false, false, false, false, false, false, false };
  };
  std::vector<Found> found(d.Snapshots.size());

  // Uncompressed id columns (the default) are searched with pread only, on several threads
  // at once: on a cold file each probe waits for the device, and concurrent probes overlap.
  // (The few HDF5 calls, chunk address look-ups, are serialised by DirectRows.)
  const std::size_t snapshotCount = d.Snapshots.size();
  struct Search
  {
    bool Done = false;
    bool Sorted = true;
    std::vector<hsize_t> Rows;
    std::vector<std::size_t> Which;
  };
  std::vector<Search> searches(snapshotCount);
  {
    std::vector<h5::DirectRows> direct(snapshotCount);
    std::vector<h5::Handle> idSets(snapshotCount); // open while the searches run
    std::vector<long long> todo;
    for (std::size_t s = 0; s < snapshotCount && !ids.empty(); ++s)
    {
      const std::string path = d.Snapshots[s].Group + "/id";
      if (d.Snapshots[s].Packed || !h5::IsDataset(d.File, path))
      {
        continue; // reported, or searched (a packed snapshot's row range), by the serial pass
      }
      idSets[s] = d.OpenDataset(d.File, path);
      const std::vector<hsize_t> dims = h5::Dims(idSets[s]);
      // Few chunks: look them all up now (no locking during the search); many (a snapshot
      // of 5M Gaussians has 1221 id chunks, of which 100 ids touch at most a few hundred):
      // as the search needs them, under a lock.
      if (dims.size() == 1 && dims[0] > 0 && direct[s].Open(idSets[s], H5T_NATIVE_INT64) &&
        (direct[s].ChunkCount() > 256 || direct[s].Resolve({})))
      {
        todo.push_back(static_cast<long long>(s));
      }
    }
    const long long count = static_cast<long long>(todo.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(16) if (count > 1)
    for (long long i = 0; i < count; ++i)
    {
      const std::size_t s = static_cast<std::size_t>(todo[static_cast<std::size_t>(i)]);
      Search& search = searches[s];
      DirectIdColumn column(direct[s]);
      const bool sorted = SearchSortedIds(column, direct[s].Size(), ids, search.Rows, search.Which);
      if (!column.Failed)
      {
        search.Done = true;
        search.Sorted = sorted;
      }
    }
  }

  // Value reads that can run on threads (pread of unfiltered rows), done after the loop.
  struct ValueJob
  {
    std::size_t Snapshot;
    int Array;
    std::string Path;
    std::unique_ptr<h5::DirectRows> Direct;
    bool Ok = false;
  };
  std::vector<ValueJob> jobs;
  std::vector<std::vector<hsize_t>> snapshotRows(snapshotCount);

  for (std::size_t s = 0; s < d.Snapshots.size() && !ids.empty(); ++s)
  {
    const SnapshotEntry& e = d.Snapshots[s];
    h5::Handle idSet = d.OpenDataset(d.File, e.Group + "/id");
    std::vector<hsize_t> dims = h5::Dims(idSet);
    if (dims.size() != 1)
    {
      d.Throw(e.Group + "/id is not one-dimensional");
    }
    const hsize_t n = e.Packed ? e.Count : dims[0];
    if (n == 0)
    {
      continue;
    }
    std::vector<hsize_t>& rows = snapshotRows[s];
    std::vector<std::size_t> which;
    bool unsorted = false;
    if (searches[s].Done)
    {
      rows.swap(searches[s].Rows);
      which.swap(searches[s].Which);
      unsorted = !searches[s].Sorted;
    }
    else
    {
      hsize_t blockRows = ChunkRows(idSet);
      if (blockRows == 0)
      {
        blockRows = 4096;
      }
      IdBlocks column(idSet, n, blockRows, d.Path, e.Offset);
      if (!SearchSortedIds(column, n, ids, rows, which))
      {
        unsorted = true;
      }
    }
    if (unsorted)
    {
      d.Problem(e.Group + "/id is not strictly increasing, so ids cannot be searched",
        "searched " + e.Group + "/id by a full scan, as its ids are not sorted");
      std::vector<std::int64_t> all(n);
      ReadRowRange(idSet, H5T_NATIVE_INT64, e.Offset, n, 0, all.data(), d.Path, e.Group + "/id");
      std::unordered_map<std::int64_t, hsize_t> index;
      index.reserve(static_cast<std::size_t>(n));
      for (hsize_t r = 0; r < n; ++r)
      {
        index.emplace(all[r], r); // first occurrence wins
      }
      rows.clear();
      which.clear();
      for (std::size_t q = 0; q < ids.size(); ++q)
      {
        auto it = index.find(ids[q]);
        if (it != index.end())
        {
          rows.push_back(it->second);
          which.push_back(q);
        }
      }
    }
    if (rows.empty())
    {
      continue;
    }
    for (hsize_t& r : rows)
    {
      r += e.Offset; // rows of the datasets from here on
    }
    // Read the selected rows of each requested dataset with one point selection each.
    for (int a = 0; a < 7; ++a)
    {
      const ArraySpec& spec = FloatArrays[a];
      if (!(arrays & spec.Flag))
      {
        continue;
      }
      const std::string path = e.Group + "/" + spec.Name;
      if (!h5::IsDataset(d.File, path))
      {
        if (spec.Flag == SnapshotGradAccum || spec.Flag == SnapshotDenom)
        {
          continue;
        }
        d.Throw("lacks the dataset " + path);
      }
      h5::Handle set = d.OpenDataset(d.File, path);
      std::vector<hsize_t> shape = h5::Dims(set);
      if (shape.empty() || (e.Packed ? shape[0] < e.Offset + n : shape[0] != n))
      {
        d.Throw(path + " and " + e.Group + "/id differ in length");
      }
      const int width = spec.Flag == SnapshotSH ? 3 : spec.Width;
      const int rank = static_cast<int>(shape.size());
      if (spec.Flag == SnapshotSH
          ? !(rank == 3 && shape[2] == 3 && shape[1] >= 1)
          : !(rank == 1 ? width == 1 : rank == 2 && shape[1] == static_cast<hsize_t>(width)))
      {
        d.Throw(path + " has an unexpected shape");
      }
      std::vector<float>& values = found[s].Values[a];
      values.resize(rows.size() * static_cast<std::size_t>(width));
      // Uncompressed chunks: read just the bytes of the rows (later, on threads); compressed:
      // inflate only the chunks holding them; anything else: an HDF5 point selection.
      auto direct = std::make_unique<h5::DirectRows>();
      if (direct->Open(set, H5T_NATIVE_FLOAT) && direct->Resolve(rows))
      {
        direct->Prefetch(rows);
        jobs.push_back({ s, a, path, std::move(direct), false });
        continue;
      }
      if (h5::FastReadRows(set, H5T_NATIVE_FLOAT, rows, values.data()))
      {
        found[s].Has[a] = true;
        continue;
      }
      std::vector<hsize_t> coords;
      coords.reserve(rows.size() * static_cast<std::size_t>(width * rank));
      for (hsize_t r : rows)
      {
        for (int c = 0; c < width; ++c)
        {
          coords.push_back(r);
          if (rank == 2)
          {
            coords.push_back(static_cast<hsize_t>(c));
          }
          else if (rank == 3)
          {
            coords.push_back(0);
            coords.push_back(static_cast<hsize_t>(c));
          }
        }
      }
      const hsize_t npoints = rows.size() * static_cast<std::size_t>(width);
      h5::Handle fileSpace(H5Dget_space(set));
      h5::CheckStatus(H5Sselect_elements(fileSpace, H5S_SELECT_SET, npoints, coords.data()),
        d.Path,
        "cannot select rows of " + path);
      h5::Handle memSpace(H5Screate_simple(1, &npoints, nullptr));
      h5::CheckStatus(
        H5Dread(set, H5T_NATIVE_FLOAT, memSpace, fileSpace, H5P_DEFAULT, values.data()),
        d.Path,
        "cannot read rows of " + path);
      found[s].Has[a] = true;
    }
    for (std::size_t r = 0; r < rows.size(); ++r)
    {
      hits.push_back({ which[r], s, r });
    }
  }
  {
    const long long count = static_cast<long long>(jobs.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(16) if (count > 1)
    for (long long i = 0; i < count; ++i)
    {
      ValueJob& job = jobs[static_cast<std::size_t>(i)];
      job.Ok = job.Direct->ReadRows(
        snapshotRows[job.Snapshot], found[job.Snapshot].Values[job.Array].data());
    }
  }
  for (ValueJob& job : jobs)
  {
    if (!job.Ok)
    {
      // A direct read failed (e.g. a short file): let HDF5 read the rows and report.
      const std::vector<hsize_t>& rows = snapshotRows[job.Snapshot];
      std::vector<float>& values = found[job.Snapshot].Values[job.Array];
      const int width =
        FloatArrays[job.Array].Flag == SnapshotSH ? 3 : FloatArrays[job.Array].Width;
      h5::Handle set = d.OpenDataset(d.File, job.Path);
      const int rank = static_cast<int>(h5::Dims(set).size());
      std::vector<hsize_t> coords;
      for (hsize_t r : rows)
      {
        for (int c = 0; c < width; ++c)
        {
          coords.push_back(r);
          if (rank >= 2)
          {
            coords.push_back(rank == 3 ? 0 : static_cast<hsize_t>(c));
          }
          if (rank == 3)
          {
            coords.push_back(static_cast<hsize_t>(c));
          }
        }
      }
      const hsize_t npoints = rows.size() * static_cast<std::size_t>(width);
      h5::Handle fileSpace(H5Dget_space(set));
      h5::CheckStatus(H5Sselect_elements(fileSpace, H5S_SELECT_SET, npoints, coords.data()),
        d.Path,
        "cannot select rows of " + job.Path);
      h5::Handle memSpace(H5Screate_simple(1, &npoints, nullptr));
      h5::CheckStatus(
        H5Dread(set, H5T_NATIVE_FLOAT, memSpace, fileSpace, H5P_DEFAULT, values.data()),
        d.Path,
        "cannot read rows of " + job.Path);
    }
    found[job.Snapshot].Has[job.Array] = true;
  }

  std::stable_sort(hits.begin(),
    hits.end(),
    [](const Hit& a, const Hit& b)
    { return a.IdIndex != b.IdIndex ? a.IdIndex < b.IdIndex : a.Snapshot < b.Snapshot; });
  PropertyHistory h;
  h.Arrays = arrays & ~static_cast<unsigned>(SnapshotIds);
  std::vector<float>* outs[7] = {
    &h.Positions, &h.LogScales, &h.Rotations, &h.OpacityLogits, &h.SHDC, &h.GradAccum, &h.Denom
  };
  for (const Hit& hit : hits)
  {
    h.Id.push_back(ids[hit.IdIndex]);
    h.Iteration.push_back(d.Snapshots[hit.Snapshot].Iteration);
    for (int a = 0; a < 7; ++a)
    {
      if (!(h.Arrays & FloatArrays[a].Flag))
      {
        continue;
      }
      const std::size_t width =
        FloatArrays[a].Flag == SnapshotSH ? 3 : static_cast<std::size_t>(FloatArrays[a].Width);
      const Found& f = found[hit.Snapshot];
      for (std::size_t c = 0; c < width; ++c)
      {
        outs[a]->push_back(
          f.Has[a] ? f.Values[a][hit.Row * width + c] : std::numeric_limits<float>::quiet_NaN());
      }
    }
  }
  return h;
}

} // namespace vis4gs

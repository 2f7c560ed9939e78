// SPDX-License-Identifier: BSD-3-Clause
#include "TrainingLogWriter.h"

#include "TrainingLogHDF5.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>

#include <unistd.h>

namespace vis4gs
{

namespace
{
const char* const MetricsColumns[] = { "loss", "l1", "psnr", "ssim", "lpips", "elapsed_s" };

/// The extendable columns of one metrics table and its pending rows.
struct MetricsSink
{
  std::string GroupPath;
  h5::Handle IterationSet;
  h5::Handle CountSet;
  h5::Handle ValueSets[6];
  MetricsTable Pending;
  std::size_t Written = 0;
};

std::vector<double> Column(const MetricsTable& t, int c)
{
  switch (c)
  {
    case 0:
      return t.Loss;
    case 1:
      return t.L1;
    case 2:
      return t.Psnr;
    case 3:
      return t.Ssim;
    case 4:
      return t.Lpips;
    default:
      return t.ElapsedSeconds;
  }
}
} // namespace

struct TrainingLogWriter::Internals
{
  std::string Path;      ///< final path
  std::string WritePath; ///< path being written (Path or Path.tmp)
  TrainingLogWriterOptions Options;
  h5::Handle File;
  MetricsSink Train;
  MetricsSink Test;
  bool HasTest = false;
  h5::Handle EventSets[4];
  EventTable PendingEvents;
  std::size_t EventsWritten = 0;
  bool CamerasWritten = false;
  int LastSnapshot = -1;
  std::int64_t SnapshotsWritten = 0;
  bool SwmrStarted = false;
  std::chrono::steady_clock::time_point LastFlush = std::chrono::steady_clock::now();
  h5::Handle Committed; ///< Swmr: /committed
  bool Closed = false;
  bool Renamed = false; ///< WriteToTemporary: the temporary became Path

  /// Closes every handle without flushing and removes the file being written: what a failed
  /// writer leaves when no partial file may stay.
  void Discard()
  {
    h5::ErrorSilencer silence;
    this->Closed = true;
    this->Train = MetricsSink();
    this->Test = MetricsSink();
    this->Committed = h5::Handle();
    for (auto& e : this->EventSets)
    {
      e.Reset();
    }
    void* handle = nullptr;
    if (this->File.Valid() && H5Fget_vfd_handle(this->File, H5P_DEFAULT, &handle) >= 0 && handle)
    {
      // Gives the bytes written back to a full file system first, so that HDF5 can write its
      // metadata and close the file: a file it fails to close stays open in the library, whose
      // exit handler then crashes (HDF5 1.10, in H5F__close_cb).
      [[maybe_unused]] const int truncated = ::ftruncate(*static_cast<int*>(handle), 0);
    }
    this->File = h5::Handle();
    std::remove(this->WritePath.c_str());
  }

  void CreateMetrics(MetricsSink& sink, const std::string& groupPath)
  {
    h5::Handle group(
      h5::Check(H5Gcreate2(this->File, groupPath.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
        this->WritePath,
        "cannot create " + groupPath));
    const std::vector<hsize_t> dims{ 0 };
    const std::vector<hsize_t> chunk{ 1024 };
    const int level = this->Options.DeflateLevel;
    sink.GroupPath = groupPath;
    sink.IterationSet = h5::CreateAndWrite(group,
      "iteration",
      H5T_STD_I32LE,
      H5T_NATIVE_INT32,
      dims,
      chunk,
      level,
      nullptr,
      this->WritePath);
    sink.CountSet = h5::CreateAndWrite(group,
      "num_gaussians",
      H5T_STD_I64LE,
      H5T_NATIVE_INT64,
      dims,
      chunk,
      level,
      nullptr,
      this->WritePath);
    for (int c = 0; c < 6; ++c)
    {
      sink.ValueSets[c] = h5::CreateAndWrite(group,
        MetricsColumns[c],
        H5T_IEEE_F64LE,
        H5T_NATIVE_DOUBLE,
        dims,
        chunk,
        level,
        nullptr,
        this->WritePath);
    }
  }

  void FlushMetrics(MetricsSink& sink)
  {
    const MetricsTable& t = sink.Pending;
    const std::size_t n = t.Size();
    if (n == 0)
    {
      return;
    }
    const std::string what = sink.GroupPath;
    h5::Append1D(sink.IterationSet,
      H5T_NATIVE_INT32,
      n,
      t.Iteration.data(),
      this->WritePath,
      what + "/iteration");
    h5::Append1D(sink.CountSet,
      H5T_NATIVE_INT64,
      n,
      t.NumGaussians.data(),
      this->WritePath,
      what + "/num_gaussians");
    for (int c = 0; c < 6; ++c)
    {
      std::vector<double> values = Column(t, c);
      h5::Append1D(sink.ValueSets[c],
        H5T_NATIVE_DOUBLE,
        n,
        values.data(),
        this->WritePath,
        what + "/" + MetricsColumns[c]);
    }
    sink.Written += n;
    sink.Pending = MetricsTable();
  }

  void FlushEvents()
  {
    const std::size_t n = this->PendingEvents.Size();
    if (n == 0)
    {
      return;
    }
    const EventTable& e = this->PendingEvents;
    h5::Append1D(this->EventSets[0],
      H5T_NATIVE_INT32,
      n,
      e.Iteration.data(),
      this->WritePath,
      "/events/iteration");
    h5::Append1D(
      this->EventSets[1], H5T_NATIVE_UINT8, n, e.Kind.data(), this->WritePath, "/events/kind");
    h5::Append1D(
      this->EventSets[2], H5T_NATIVE_INT64, n, e.Parent.data(), this->WritePath, "/events/parent");
    h5::Append1D(
      this->EventSets[3], H5T_NATIVE_INT64, n, e.Child.data(), this->WritePath, "/events/child");
    this->EventsWritten += n;
    this->PendingEvents = EventTable();
  }

  void EnsureNotSwmr(const std::string& what) const
  {
    if (this->SwmrStarted)
    {
      throw std::runtime_error(this->Path + ": cannot add " + what +
        " after the first snapshot of a log written in SWMR mode (write cameras and images "
        "first)");
    }
  }

  /// Format version 2: appends the snapshot as rows of the concatenated datasets (created,
  /// shaped by it, at the first snapshot) and a row of the index.
  void WritePackedSnapshot(int iteration,
    const GaussianCloud& cloud,
    const std::int64_t* ids,
    const SnapshotStatistics* statistics);

  void EnsureOpen() const
  {
    if (this->Closed)
    {
      throw std::runtime_error(this->Path + ": the training log is already closed");
    }
  }
};

//------------------------------------------------------------------------------
void TrainingLogWriter::Internals::WritePackedSnapshot(int iteration,
  const GaussianCloud& cloud,
  const std::int64_t* ids,
  const SnapshotStatistics* statistics)
{
  const std::string& f = this->WritePath;
  const std::size_t n = cloud.Count;
  const hsize_t k = static_cast<hsize_t>(cloud.ShCoefficientCount());
  const bool grad = statistics && !statistics->GradAccum.empty();
  const bool denom = statistics && !statistics->Denom.empty();
  if (!h5::IsDataset(this->File, "/snapshots/id"))
  {
    h5::Handle g(H5Gopen2(this->File, "/snapshots", H5P_DEFAULT));
    const hsize_t c =
      std::max<hsize_t>(1, std::min<hsize_t>(this->Options.SnapshotChunkRows, 1u << 30));
    const int level = this->Options.SnapshotDeflateLevel;
    auto create = [&](const char* name,
                    hid_t type,
                    std::vector<hsize_t> dims,
                    std::vector<hsize_t> chunk,
                    int deflate)
    { h5::CreateAndWrite(g, name, type, type, dims, chunk, deflate, nullptr, f); };
    create("iteration", H5T_STD_I32LE, { 0 }, { 1024 }, 0);
    create("start", H5T_STD_I64LE, { 0 }, { 1024 }, 0);
    create("count", H5T_STD_I64LE, { 0 }, { 1024 }, 0);
    create("sh_degree", H5T_STD_I32LE, { 0 }, { 1024 }, 0);
    create("id", H5T_STD_I64LE, { 0 }, { c }, level);
    create("position", H5T_IEEE_F32LE, { 0, 3 }, { c, 3 }, level);
    create("log_scale", H5T_IEEE_F32LE, { 0, 3 }, { c, 3 }, level);
    create("rotation", H5T_IEEE_F32LE, { 0, 4 }, { c, 4 }, level);
    create("opacity_logit", H5T_IEEE_F32LE, { 0 }, { c }, level);
    // One coefficient per chunk along K, so that the DC term reads without the SH rest; K of
    // the trainer's degree, so that a snapshot of a lower degree (SnapshotShDegree) leaves
    // the chunks of the other coefficients unwritten (no disk) and the final one fits.
    const int degree = std::max(this->Options.ShDegree, cloud.ShDegree);
    const hsize_t kMax = static_cast<hsize_t>((degree + 1) * (degree + 1));
    create("sh", H5T_IEEE_F32LE, { 0, kMax, 3 }, { c, 1, 3 }, level);
    if (grad)
    {
      create("grad_accum", H5T_IEEE_F32LE, { 0 }, { c }, level);
    }
    if (denom)
    {
      create("denom", H5T_IEEE_F32LE, { 0 }, { c }, level);
    }
  }
  auto open = [&](const std::string& name)
  {
    const std::string path = "/snapshots/" + name;
    return h5::Handle(
      h5::Check(H5Dopen2(this->File, path.c_str(), H5P_DEFAULT), f, "cannot open " + path));
  };
  h5::Handle idSet = open("id");
  const std::int64_t start = static_cast<std::int64_t>(h5::Dims(idSet).at(0));
  h5::AppendRows(idSet, H5T_NATIVE_INT64, n, ids, f, "/snapshots/id");
  struct Array
  {
    const char* Name;
    const float* Data;
  };
  for (const Array& a : { Array{ "position", cloud.Positions.data() },
         Array{ "log_scale", cloud.LogScales.data() },
         Array{ "rotation", cloud.Rotations.data() },
         Array{ "opacity_logit", cloud.OpacityLogits.data() } })
  {
    h5::AppendRows(
      open(a.Name), H5T_NATIVE_FLOAT, n, a.Data, f, std::string("/snapshots/") + a.Name);
  }
  // SH: the snapshot's coefficients only (cut to what /snapshots/sh holds); its degree goes
  // to the index. A statistic the snapshot lacks is NaN (one it has that the first lacked
  // is not stored).
  h5::Handle sh = open("sh");
  std::vector<hsize_t> shDims = h5::Dims(sh);
  const hsize_t kept = std::min(shDims.at(1), k);
  int keptDegree = 0;
  while (static_cast<hsize_t>((keptDegree + 2) * (keptDegree + 2)) <= kept)
  {
    ++keptDegree;
  }
  const hsize_t first = shDims[0];
  shDims[0] += n;
  h5::CheckStatus(H5Dset_extent(sh, shDims.data()), f, "cannot extend /snapshots/sh");
  if (n > 0)
  {
    const hsize_t fileStart[3] = { first, 0, 0 }, fileCount[3] = { n, kept, 3 };
    const hsize_t memDims[3] = { n, k, 3 }, memStart[3] = { 0, 0, 0 };
    h5::Handle fileSpace(H5Dget_space(sh));
    H5Sselect_hyperslab(fileSpace, H5S_SELECT_SET, fileStart, nullptr, fileCount, nullptr);
    h5::Handle memSpace(H5Screate_simple(3, memDims, nullptr));
    H5Sselect_hyperslab(memSpace, H5S_SELECT_SET, memStart, nullptr, fileCount, nullptr);
    h5::CheckStatus(
      H5Dwrite(sh, H5T_NATIVE_FLOAT, memSpace, fileSpace, H5P_DEFAULT, cloud.SH.data()),
      f,
      "cannot append to /snapshots/sh");
  }
  const std::vector<float> nan(grad && denom ? 0 : n, std::numeric_limits<float>::quiet_NaN());
  for (const Array& a : { Array{ "grad_accum", grad ? statistics->GradAccum.data() : nan.data() },
         Array{ "denom", denom ? statistics->Denom.data() : nan.data() } })
  {
    if (h5::IsDataset(this->File, std::string("/snapshots/") + a.Name))
    {
      h5::AppendRows(
        open(a.Name), H5T_NATIVE_FLOAT, n, a.Data, f, std::string("/snapshots/") + a.Name);
    }
  }
  const std::int32_t it = iteration;
  const std::int64_t count = static_cast<std::int64_t>(n);
  h5::Append1D(open("iteration"), H5T_NATIVE_INT32, 1, &it, f, "/snapshots/iteration");
  h5::Append1D(open("start"), H5T_NATIVE_INT64, 1, &start, f, "/snapshots/start");
  h5::Append1D(open("count"), H5T_NATIVE_INT64, 1, &count, f, "/snapshots/count");
  const std::int32_t shDegree = keptDegree;
  h5::Append1D(open("sh_degree"), H5T_NATIVE_INT32, 1, &shDegree, f, "/snapshots/sh_degree");
  ++this->SnapshotsWritten;
}

//------------------------------------------------------------------------------
std::string TrainingLogWriter::SnapshotName(int iteration)
{
  char name[32];
  std::snprintf(name, sizeof(name), "%06d", iteration);
  return name;
}

//------------------------------------------------------------------------------
TrainingLogWriter::TrainingLogWriter(const std::string& path,
  const TrainingLogWriterOptions& options)
  : Impl(new Internals)
{
  Internals& d = *this->Impl;
  d.Path = path;
  d.Options = options;
  d.WritePath = options.WriteToTemporary ? path + ".tmp" : path;
  if (options.DeflateLevel < 0 || options.DeflateLevel > 9 || options.SnapshotDeflateLevel < 0 ||
    options.SnapshotDeflateLevel > 9)
  {
    throw std::runtime_error(path + ": deflate level must be 0..9");
  }
  if (options.SnapshotChunkRows == 0 || options.TableChunkRows == 0)
  {
    throw std::runtime_error(path + ": chunk sizes must be positive");
  }
  h5::ErrorSilencer silence;

  // Crash safety: never reuse freed file space (flushed metadata may still point at it) ...
  h5::Handle fcpl(H5Pcreate(H5P_FILE_CREATE));
  H5Pset_file_space_strategy(fcpl, H5F_FSPACE_STRATEGY_NONE, 0, 1);
  // ... and keep dirty metadata in memory until Flush(): between flushes the file on disk
  // only gains raw data in fresh space, so it stays the valid log of the last flush.
  h5::Handle fapl(H5Pcreate(H5P_FILE_ACCESS));
  H5AC_cache_config_t config;
  config.version = H5AC__CURR_CACHE_CONFIG_VERSION;
  H5Pget_mdc_config(fapl, &config);
  config.evictions_enabled = false;
  config.incr_mode = H5C_incr__off;
  config.flash_incr_mode = H5C_flash_incr__off;
  config.decr_mode = H5C_decr__off;
  H5Pset_mdc_config(fapl, &config);
#if H5_VERSION_GE(1, 10, 7)
  // As the reader does, so that both can have the file open in one process.
  H5Pset_file_locking(fapl, false, true);
#endif
  if (options.Swmr)
  {
    // SWMR needs the newest file format (superblock version 3).
    H5Pset_libver_bounds(fapl, H5F_LIBVER_LATEST, H5F_LIBVER_LATEST);
  }

  const bool existed = ::access(d.WritePath.c_str(), F_OK) == 0;
  const hid_t file = H5Fcreate(d.WritePath.c_str(), H5F_ACC_TRUNC, fcpl, fapl);
  if (file < 0)
  {
    // A full disk fails the first write after the file was made: no empty file stays (a file
    // that was there is left alone unless it is our own temporary).
    const std::string why = h5::LastErrorMessage();
    H5Eclear2(H5E_DEFAULT);
    if (!existed || options.WriteToTemporary)
    {
      std::remove(d.WritePath.c_str());
    }
    throw std::runtime_error(d.WritePath + ": cannot create the training log" +
      (why.empty() ? std::string() : " (" + why + ")"));
  }
  d.File = h5::Handle(file);
  try
  {
    this->WriteHeader();
  }
  catch (...)
  {
    // A full disk: no log (not even an empty one) stays behind.
    d.Discard();
    throw;
  }
}

//------------------------------------------------------------------------------
void TrainingLogWriter::WriteHeader()
{
  Internals& d = *this->Impl;
  const TrainingLogWriterOptions& options = d.Options;
  h5::WriteStringAttribute(d.File, "format", "vis4gs-training-log");
  h5::WriteIntAttribute(d.File, "format_version", options.Swmr ? 2 : 1);
  h5::WriteStringAttribute(d.File, "producer", options.Producer);
  h5::WriteStringAttribute(d.File, "scene", options.Scene);
  h5::WriteIntAttribute(d.File, "sh_degree", options.ShDegree);
  h5::WriteIntAttribute(d.File, "iterations", options.Iterations);

  d.CreateMetrics(d.Train, "/metrics");
  {
    h5::Handle events(
      h5::Check(H5Gcreate2(d.File, "/events", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
        d.WritePath,
        "cannot create /events"));
    const std::vector<hsize_t> dims{ 0 };
    const std::vector<hsize_t> chunk{ options.TableChunkRows };
    const int level = options.DeflateLevel;
    d.EventSets[0] = h5::CreateAndWrite(events,
      "iteration",
      H5T_STD_I32LE,
      H5T_NATIVE_INT32,
      dims,
      chunk,
      level,
      nullptr,
      d.WritePath);
    d.EventSets[1] = h5::CreateAndWrite(
      events, "kind", H5T_STD_U8LE, H5T_NATIVE_UINT8, dims, chunk, level, nullptr, d.WritePath);
    d.EventSets[2] = h5::CreateAndWrite(
      events, "parent", H5T_STD_I64LE, H5T_NATIVE_INT64, dims, chunk, level, nullptr, d.WritePath);
    d.EventSets[3] = h5::CreateAndWrite(
      events, "child", H5T_STD_I64LE, H5T_NATIVE_INT64, dims, chunk, level, nullptr, d.WritePath);
  }
  h5::Handle snapshots(
    h5::Check(H5Gcreate2(d.File, "/snapshots", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
      d.WritePath,
      "cannot create /snapshots"));
  if (options.Swmr)
  {
    // Version 2 creates every table up front (a SWMR writer cannot create them later).
    d.CreateMetrics(d.Test, "/metrics/test");
    d.HasTest = true;
    const std::int64_t zeros[5] = { 0, 0, 0, 0, 0 };
    const hsize_t columns = 5;
    h5::Handle space(H5Screate_simple(1, &columns, nullptr));
    d.Committed = h5::Handle(h5::Check(
      H5Dcreate2(d.File, "/committed", H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
      d.WritePath,
      "cannot create /committed"));
    h5::CheckStatus(H5Dwrite(d.Committed, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, zeros),
      d.WritePath,
      "cannot write /committed");
  }
  this->Flush();
}

//------------------------------------------------------------------------------
TrainingLogWriter::~TrainingLogWriter()
{
  Internals& d = *this->Impl;
  if (d.Options.WriteToTemporary && !d.Renamed)
  {
    // Not closed (an exception unwinds the owner), or Close() failed: the temporary is
    // incomplete, and what is at Path stays as it was.
    d.Discard();
    return;
  }
  try
  {
    this->Close();
  }
  catch (...)
  {
  }
}

//------------------------------------------------------------------------------
const std::string& TrainingLogWriter::GetPath() const
{
  return this->Impl->Path;
}

//------------------------------------------------------------------------------
std::size_t TrainingLogWriter::GetNumberOfEvents() const
{
  return this->Impl->EventsWritten + this->Impl->PendingEvents.Size();
}

//------------------------------------------------------------------------------
std::size_t TrainingLogWriter::GetNumberOfMetricsRows(bool test) const
{
  const MetricsSink& s = test ? this->Impl->Test : this->Impl->Train;
  return s.Written + s.Pending.Size();
}

//------------------------------------------------------------------------------
int TrainingLogWriter::GetLastSnapshotIteration() const
{
  return this->Impl->LastSnapshot;
}

//------------------------------------------------------------------------------
void TrainingLogWriter::WriteCameras(const std::vector<Camera>& cameras)
{
  Internals& d = *this->Impl;
  d.EnsureOpen();
  d.EnsureNotSwmr("/cameras");
  if (d.CamerasWritten)
  {
    throw std::runtime_error(d.Path + ": /cameras is already written");
  }
  h5::ErrorSilencer silence;
  h5::Handle group(h5::Check(H5Gcreate2(d.File, "/cameras", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
    d.WritePath,
    "cannot create /cameras"));
  const std::size_t v = cameras.size();
  std::vector<std::string> names(v), images(v);
  std::vector<std::uint8_t> split(v);
  std::vector<std::int32_t> width(v), height(v);
  std::vector<double> fx(v), fy(v), cx(v), cy(v), w2c(v * 16);
  for (std::size_t i = 0; i < v; ++i)
  {
    const Camera& c = cameras[i];
    names[i] = c.Name;
    images[i] = c.ImagePath;
    split[i] = static_cast<std::uint8_t>(c.Split);
    width[i] = c.Width;
    height[i] = c.Height;
    fx[i] = c.Fx;
    fy[i] = c.Fy;
    cx[i] = c.Cx;
    cy[i] = c.Cy;
    for (int k = 0; k < 16; ++k)
    {
      w2c[i * 16 + k] = c.WorldToCamera[k];
    }
  }
  const int level = d.Options.DeflateLevel;
  const hsize_t n = v;
  const std::vector<hsize_t> chunk{ 256 };
  try
  {
    h5::WriteStrings(group, "name", names, level);
    h5::WriteStrings(group, "image", images, level);
  }
  catch (const std::runtime_error& e)
  {
    throw std::runtime_error(d.WritePath + ": " + e.what());
  }
  h5::CreateAndWrite(
    group, "split", H5T_STD_U8LE, H5T_NATIVE_UINT8, { n }, chunk, level, split.data(), d.WritePath);
  h5::CreateAndWrite(group,
    "width",
    H5T_STD_I32LE,
    H5T_NATIVE_INT32,
    { n },
    chunk,
    level,
    width.data(),
    d.WritePath);
  h5::CreateAndWrite(group,
    "height",
    H5T_STD_I32LE,
    H5T_NATIVE_INT32,
    { n },
    chunk,
    level,
    height.data(),
    d.WritePath);
  h5::CreateAndWrite(
    group, "fx", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, { n }, chunk, level, fx.data(), d.WritePath);
  h5::CreateAndWrite(
    group, "fy", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, { n }, chunk, level, fy.data(), d.WritePath);
  h5::CreateAndWrite(
    group, "cx", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, { n }, chunk, level, cx.data(), d.WritePath);
  h5::CreateAndWrite(
    group, "cy", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, { n }, chunk, level, cy.data(), d.WritePath);
  h5::CreateAndWrite(group,
    "world_to_camera",
    H5T_IEEE_F64LE,
    H5T_NATIVE_DOUBLE,
    { n, 4, 4 },
    { 256, 4, 4 },
    level,
    w2c.data(),
    d.WritePath);
  d.CamerasWritten = true;
}

//------------------------------------------------------------------------------
void TrainingLogWriter::WriteImage(const std::string& name,
  int width,
  int height,
  const unsigned char* rgb)
{
  Internals& d = *this->Impl;
  d.EnsureOpen();
  if (name.empty() || name.find('/') != std::string::npos || width <= 0 || height <= 0 || !rgb)
  {
    throw std::runtime_error(d.Path + ": bad embedded image '" + name + "'");
  }
  d.EnsureNotSwmr("/images/" + name);
  h5::ErrorSilencer silence;
  if (!h5::LinkExists(d.File, "/images"))
  {
    h5::Handle g(h5::Check(H5Gcreate2(d.File, "/images", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
      d.WritePath,
      "cannot create /images"));
  }
  h5::Handle group(H5Gopen2(d.File, "/images", H5P_DEFAULT));
  const hsize_t h = static_cast<hsize_t>(height), w = static_cast<hsize_t>(width);
  h5::CreateAndWrite(group,
    name,
    H5T_STD_U8LE,
    H5T_NATIVE_UINT8,
    { h, w, 3 },
    { std::min<hsize_t>(h, 256), w, 3 },
    d.Options.DeflateLevel,
    rgb,
    d.WritePath);
}

//------------------------------------------------------------------------------
void TrainingLogWriter::AppendMetrics(const MetricsRow& row, bool test)
{
  Internals& d = *this->Impl;
  d.EnsureOpen();
  if (test && !d.HasTest)
  {
    h5::ErrorSilencer silence;
    d.CreateMetrics(d.Test, "/metrics/test");
    d.HasTest = true;
  }
  (test ? d.Test : d.Train).Pending.Append(row);
  if (d.Options.FlushIntervalSeconds > 0 &&
    std::chrono::duration<double>(std::chrono::steady_clock::now() - d.LastFlush).count() >=
      d.Options.FlushIntervalSeconds)
  {
    this->Flush();
  }
}

//------------------------------------------------------------------------------
void TrainingLogWriter::AppendEvent(const TrainingEvent& event)
{
  this->Impl->EnsureOpen();
  this->Impl->PendingEvents.Append(event);
}

//------------------------------------------------------------------------------
void TrainingLogWriter::AppendEvents(const EventTable& events)
{
  Internals& d = *this->Impl;
  d.EnsureOpen();
  EventTable& p = d.PendingEvents;
  p.Iteration.insert(p.Iteration.end(), events.Iteration.begin(), events.Iteration.end());
  p.Kind.insert(p.Kind.end(), events.Kind.begin(), events.Kind.end());
  p.Parent.insert(p.Parent.end(), events.Parent.begin(), events.Parent.end());
  p.Child.insert(p.Child.end(), events.Child.begin(), events.Child.end());
}

//------------------------------------------------------------------------------
void TrainingLogWriter::WriteSnapshot(int iteration,
  const GaussianCloud& cloud,
  const SnapshotStatistics* statistics)
{
  Internals& d = *this->Impl;
  d.EnsureOpen();
  const std::string name = "/snapshots/" + SnapshotName(iteration);
  const std::size_t n = cloud.Count;
  const std::size_t k = static_cast<std::size_t>(cloud.ShCoefficientCount());
  auto fail = [&](const std::string& what)
  { throw std::runtime_error(d.Path + ": snapshot " + std::to_string(iteration) + ": " + what); };
  if (iteration < 0)
  {
    fail("negative iteration");
  }
  if (iteration <= d.LastSnapshot)
  {
    fail("snapshots must be written in increasing iteration order (last was " +
      std::to_string(d.LastSnapshot) + ")");
  }
  if (cloud.Positions.size() != 3 * n || cloud.LogScales.size() != 3 * n ||
    cloud.Rotations.size() != 4 * n || cloud.OpacityLogits.size() != n ||
    cloud.SH.size() != 3 * k * n || (!cloud.Ids.empty() && cloud.Ids.size() != n))
  {
    fail("array sizes do not match the Gaussian count " + std::to_string(n));
  }
  if (statistics &&
    ((!statistics->GradAccum.empty() && statistics->GradAccum.size() != n) ||
      (!statistics->Denom.empty() && statistics->Denom.size() != n)))
  {
    fail("grad_accum/denom sizes do not match the Gaussian count");
  }
  std::vector<std::int64_t> ids;
  const std::int64_t* idData = cloud.Ids.data();
  if (cloud.Ids.empty())
  {
    ids.resize(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      ids[i] = static_cast<std::int64_t>(i);
    }
    idData = ids.data();
  }
  for (std::size_t i = 1; i < n; ++i)
  {
    if (idData[i] <= idData[i - 1])
    {
      fail("ids must be strictly increasing (id " + std::to_string(idData[i]) + " at row " +
        std::to_string(i) + " follows " + std::to_string(idData[i - 1]) + ")");
    }
  }
  h5::ErrorSilencer silence;
  if (d.Options.Swmr)
  {
    d.WritePackedSnapshot(iteration, cloud, idData, statistics);
    d.LastSnapshot = iteration;
    if (d.Options.FlushOnSnapshot || !d.SwmrStarted)
    {
      this->Flush();
    }
    if (!d.SwmrStarted)
    {
      // From now on readers may open the file while it grows (no new datasets from here).
      h5::CheckStatus(H5Fstart_swmr_write(d.File), d.WritePath, "cannot start SWMR writing");
      d.SwmrStarted = true;
    }
    return;
  }
  h5::Handle group(
    h5::Check(H5Gcreate2(d.File, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
      d.WritePath,
      "cannot create " + name));
  h5::WriteIntAttribute(group, "iteration", iteration);
  const hsize_t rows = n;
  const hsize_t c = std::max<hsize_t>(1, std::min<hsize_t>(d.Options.SnapshotChunkRows, 1u << 30));
  const int level = d.Options.SnapshotDeflateLevel;
  const std::string& f = d.WritePath;
  h5::CreateAndWrite(
    group, "id", H5T_STD_I64LE, H5T_NATIVE_INT64, { rows }, { c }, level, idData, f);
  h5::CreateAndWrite(group,
    "position",
    H5T_IEEE_F32LE,
    H5T_NATIVE_FLOAT,
    { rows, 3 },
    { c, 3 },
    level,
    cloud.Positions.data(),
    f);
  h5::CreateAndWrite(group,
    "log_scale",
    H5T_IEEE_F32LE,
    H5T_NATIVE_FLOAT,
    { rows, 3 },
    { c, 3 },
    level,
    cloud.LogScales.data(),
    f);
  h5::CreateAndWrite(group,
    "rotation",
    H5T_IEEE_F32LE,
    H5T_NATIVE_FLOAT,
    { rows, 4 },
    { c, 4 },
    level,
    cloud.Rotations.data(),
    f);
  h5::CreateAndWrite(group,
    "opacity_logit",
    H5T_IEEE_F32LE,
    H5T_NATIVE_FLOAT,
    { rows },
    { c },
    level,
    cloud.OpacityLogits.data(),
    f);
  // One coefficient per chunk along K, so that the DC term reads without the SH rest.
  h5::CreateAndWrite(group,
    "sh",
    H5T_IEEE_F32LE,
    H5T_NATIVE_FLOAT,
    { rows, k, 3 },
    { c, 1, 3 },
    level,
    cloud.SH.data(),
    f);
  if (statistics && !statistics->GradAccum.empty())
  {
    h5::CreateAndWrite(group,
      "grad_accum",
      H5T_IEEE_F32LE,
      H5T_NATIVE_FLOAT,
      { rows },
      { c },
      level,
      statistics->GradAccum.data(),
      f);
  }
  if (statistics && !statistics->Denom.empty())
  {
    h5::CreateAndWrite(group,
      "denom",
      H5T_IEEE_F32LE,
      H5T_NATIVE_FLOAT,
      { rows },
      { c },
      level,
      statistics->Denom.data(),
      f);
  }
  d.LastSnapshot = iteration;
  if (d.Options.FlushOnSnapshot)
  {
    this->Flush();
  }
}

//------------------------------------------------------------------------------
void TrainingLogWriter::Flush()
{
  Internals& d = *this->Impl;
  d.EnsureOpen();
  h5::ErrorSilencer silence;
  d.FlushMetrics(d.Train);
  if (d.HasTest)
  {
    d.FlushMetrics(d.Test);
  }
  d.FlushEvents();
  h5::CheckStatus(H5Fflush(d.File, H5F_SCOPE_GLOBAL), d.WritePath, "cannot flush the training log");
  d.LastFlush = std::chrono::steady_clock::now();
  if (d.Committed.Valid())
  {
    // Counted only once flushed: a reader (or a kill) never sees a row counted before its
    // bytes are in the file.
    const std::int64_t counts[5] = { static_cast<std::int64_t>(d.Train.Written),
      static_cast<std::int64_t>(d.Test.Written),
      static_cast<std::int64_t>(d.EventsWritten),
      0,
      d.SnapshotsWritten };
    h5::CheckStatus(H5Dwrite(d.Committed, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, counts),
      d.WritePath,
      "cannot write /committed");
    h5::CheckStatus(
      H5Fflush(d.File, H5F_SCOPE_GLOBAL), d.WritePath, "cannot flush the training log");
  }
}

//------------------------------------------------------------------------------
void TrainingLogWriter::Close()
{
  Internals& d = *this->Impl;
  if (d.Closed)
  {
    return;
  }
  this->Flush();
  d.Closed = true;
  d.Train = MetricsSink();
  d.Test = MetricsSink();
  d.Committed = h5::Handle();
  for (auto& e : d.EventSets)
  {
    e.Reset();
  }
  h5::ErrorSilencer silence;
  hid_t file = d.File.Get();
  herr_t status = H5Fclose(file);
  d.File = h5::Handle();
  if (status < 0)
  {
    h5::Fail(d.WritePath, "cannot close the training log");
  }
  if (d.Options.WriteToTemporary)
  {
    if (std::rename(d.WritePath.c_str(), d.Path.c_str()) != 0)
    {
      throw std::runtime_error(
        d.Path + ": cannot rename " + d.WritePath + " onto it: " + std::strerror(errno));
    }
    d.Renamed = true;
  }
}

} // namespace vis4gs

// SPDX-License-Identifier: BSD-3-Clause
// Round trip of every group of the training log, the reading options (arrays, SH degree,
// nearest snapshot) and the property history checked against full snapshot reads.
#include "TrainingLogReader.h"
#include "TrainingLogTestUtilities.h"
#include "TrainingLogWriter.h"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <glob.h>
#include <map>
#include <random>
#include <sys/stat.h>

using namespace vis4gs;
using vis4gs::testing::MakeCloud;
using vis4gs::testing::MakeIds;
using vis4gs::testing::TempLogPath;

namespace
{
/// Removes this process's temporary logs when the test program ends.
class RemoveTemporaryLogs : public ::testing::Environment
{
public:
  void TearDown() override
  {
    const std::string pattern = "/tmp/vis4gs_trainlog_" + std::to_string(::getpid()) + "_*";
    glob_t found;
    if (::glob(pattern.c_str(), 0, nullptr, &found) == 0)
    {
      for (std::size_t i = 0; i < found.gl_pathc; ++i)
      {
        std::remove(found.gl_pathv[i]);
      }
    }
    ::globfree(&found);
  }
};
::testing::Environment* const TemporaryLogs =
  ::testing::AddGlobalTestEnvironment(new RemoveTemporaryLogs);

bool Exists(const std::string& p)
{
  struct stat st;
  return ::stat(p.c_str(), &st) == 0;
}

std::vector<Camera> MakeCameras()
{
  std::vector<Camera> cams(3);
  for (int i = 0; i < 3; ++i)
  {
    Camera& c = cams[i];
    c.Name = "view_" + std::to_string(i);
    c.Split = i == 2 ? CameraSplit::Test : CameraSplit::Train;
    c.Width = 64 + i;
    c.Height = 48 + i;
    c.Fx = 50.5 + i;
    c.Fy = 51.25 + i;
    c.Cx = 32.0 + 0.5 * i;
    c.Cy = 24.0 - 0.5 * i;
    for (int k = 0; k < 16; ++k)
    {
      c.WorldToCamera[k] = (k % 5 == 0) ? 1.0 : 0.01 * (k + i);
    }
    c.ImagePath = i == 0 ? "/images/view_0" : "images/view_" + std::to_string(i) + ".png";
  }
  return cams;
}

struct WrittenLog
{
  std::string Path;
  std::map<int, GaussianCloud> Snapshots;
  std::map<int, SnapshotStatistics> Stats;
  MetricsTable Train, Test;
  EventTable Events;
  std::vector<unsigned char> Image;
};

/// A log of every group; @p swmr: format version 2 in SWMR mode (statistics in the first
/// snapshot too, so that the packed layout stores them).
WrittenLog WriteSample(const std::string& tag,
  std::size_t chunkRows,
  int snapshotDeflate = 0,
  bool swmr = false)
{
  WrittenLog log;
  log.Path = TempLogPath(tag);
  TrainingLogWriterOptions options;
  options.Swmr = swmr;
  options.SnapshotDeflateLevel = snapshotDeflate;
  options.Producer = "unit-test";
  options.Scene = "synthetic";
  options.ShDegree = 3;
  options.Iterations = 3000;
  options.SnapshotChunkRows = chunkRows;
  TrainingLogWriter writer(log.Path, options);
  writer.WriteCameras(MakeCameras());
  log.Image.resize(48 * 64 * 3);
  for (std::size_t i = 0; i < log.Image.size(); ++i)
  {
    log.Image[i] = static_cast<unsigned char>((i * 7) % 251);
  }
  writer.WriteImage("view_0", 64, 48, log.Image.data());
  for (int it = 1; it <= 50; ++it)
  {
    MetricsRow row;
    row.Iteration = it * 10;
    row.NumGaussians = 1000 + it;
    row.Loss = 1.0 / it;
    row.L1 = 0.5 / it;
    if (it % 10 == 0)
    {
      row.Psnr = 20 + it * 0.1;
      row.Ssim = 0.5 + it * 0.001;
    }
    row.ElapsedSeconds = it * 0.25;
    writer.AppendMetrics(row);
    log.Train.Append(row);
    if (it % 25 == 0)
    {
      row.Lpips = 0.125;
      writer.AppendMetrics(row, true);
      log.Test.Append(row);
    }
  }
  // Events: clone 5 -> 1000, split 7 -> 1001, 1002, prune 1000, prune 3.
  const TrainingEvent events[] = { { 600, EventKind::Clone, 5, 1000 },
    { 600, EventKind::Split, 7, 1001 },
    { 600, EventKind::Split, 7, 1002 },
    { 700, EventKind::Prune, 1000, -1 },
    { 700, EventKind::Prune, 3, -1 } };
  for (const TrainingEvent& e : events)
  {
    writer.AppendEvent(e);
    log.Events.Append(e);
  }
  const int iterations[] = { 0, 500, 1000, 2500 };
  const int degrees[] = { 0, 3, 1, 3 };
  for (int s = 0; s < 4; ++s)
  {
    const std::size_t n = 700 + 97 * s;
    GaussianCloud c =
      MakeCloud(MakeIds(n, static_cast<std::int64_t>(n), 11 + s), degrees[s], 5 + s);
    SnapshotStatistics stats;
    const bool withStats = s == 1 || (swmr && s == 0);
    if (withStats)
    {
      stats.GradAccum.resize(c.Count);
      stats.Denom.resize(c.Count);
      for (std::size_t i = 0; i < c.Count; ++i)
      {
        stats.GradAccum[i] = 1e-4f * static_cast<float>(i);
        stats.Denom[i] = static_cast<float>(i % 13);
      }
    }
    writer.WriteSnapshot(iterations[s], c, withStats ? &stats : nullptr);
    log.Snapshots[iterations[s]] = c;
    log.Stats[iterations[s]] = stats;
  }
  writer.Close();
  return log;
}

void ExpectSameBits(const std::vector<float>& a, const std::vector<float>& b)
{
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(float)));
}

void ExpectSameMetrics(const MetricsTable& a, const MetricsTable& b)
{
  ASSERT_EQ(a.Size(), b.Size());
  for (std::size_t i = 0; i < a.Size(); ++i)
  {
    EXPECT_EQ(a.Iteration[i], b.Iteration[i]);
    EXPECT_EQ(a.NumGaussians[i], b.NumGaussians[i]);
    const double* x[6] = {
      &a.Loss[i], &a.L1[i], &a.Psnr[i], &a.Ssim[i], &a.Lpips[i], &a.ElapsedSeconds[i]
    };
    const double* y[6] = {
      &b.Loss[i], &b.L1[i], &b.Psnr[i], &b.Ssim[i], &b.Lpips[i], &b.ElapsedSeconds[i]
    };
    for (int c = 0; c < 6; ++c)
    {
      if (std::isnan(*x[c]))
      {
        EXPECT_TRUE(std::isnan(*y[c]));
      }
      else
      {
        EXPECT_EQ(*x[c], *y[c]);
      }
    }
  }
}
} // namespace

//------------------------------------------------------------------------------
void ExpectRoundTrip(bool swmr)
{
  SCOPED_TRACE(swmr ? "format version 2 (SWMR)" : "format version 1");
  WrittenLog log = WriteSample(swmr ? "roundtrip_swmr" : "roundtrip", 128, 0, swmr);
  TrainingLogReader reader(log.Path);
  EXPECT_EQ(reader.GetHeader().FormatVersion, swmr ? 2 : 1);
  EXPECT_TRUE(reader.IsSwmrRead()); // no other open of it in this process
  EXPECT_EQ(reader.GetHeader().Producer, "unit-test");
  EXPECT_EQ(reader.GetHeader().Scene, "synthetic");
  EXPECT_EQ(reader.GetHeader().ShDegree, 3);
  EXPECT_EQ(reader.GetHeader().Iterations, 3000);
  EXPECT_TRUE(reader.GetLacks().empty()) << reader.GetLacks().front();
  EXPECT_EQ(reader.GetSnapshotIterations(), (std::vector<int>{ 0, 500, 1000, 2500 }));

  std::vector<Camera> cams = reader.ReadCameras();
  std::vector<Camera> expected = MakeCameras();
  ASSERT_EQ(cams.size(), expected.size());
  for (std::size_t i = 0; i < cams.size(); ++i)
  {
    EXPECT_EQ(cams[i].Name, expected[i].Name);
    EXPECT_EQ(cams[i].Split, expected[i].Split);
    EXPECT_EQ(cams[i].Width, expected[i].Width);
    EXPECT_EQ(cams[i].Height, expected[i].Height);
    EXPECT_EQ(cams[i].Fx, expected[i].Fx);
    EXPECT_EQ(cams[i].Fy, expected[i].Fy);
    EXPECT_EQ(cams[i].Cx, expected[i].Cx);
    EXPECT_EQ(cams[i].Cy, expected[i].Cy);
    EXPECT_EQ(cams[i].WorldToCamera, expected[i].WorldToCamera);
    EXPECT_EQ(cams[i].ImagePath, expected[i].ImagePath);
  }
  int w = 0, h = 0;
  EXPECT_EQ(reader.ReadImage("view_0", w, h), log.Image);
  EXPECT_EQ(w, 64);
  EXPECT_EQ(h, 48);
  EXPECT_EQ(reader.GetImageNames(), std::vector<std::string>{ "view_0" });

  ExpectSameMetrics(reader.ReadMetrics(false), log.Train);
  ExpectSameMetrics(reader.ReadMetrics(true), log.Test);
  EventTable events = reader.ReadEvents();
  EXPECT_EQ(events.Iteration, log.Events.Iteration);
  EXPECT_EQ(events.Kind, log.Events.Kind);
  EXPECT_EQ(events.Parent, log.Events.Parent);
  EXPECT_EQ(events.Child, log.Events.Child);

  for (const auto& entry : log.Snapshots)
  {
    const GaussianCloud& w0 = entry.second;
    SnapshotReadOptions all;
    all.Arrays = SnapshotAll;
    all.ShDegree = -1;
    GaussianCloud r = reader.ReadSnapshot(entry.first, all);
    EXPECT_EQ(r.Count, w0.Count);
    EXPECT_EQ(r.Ids, w0.Ids);
    EXPECT_EQ(r.ShDegree, w0.ShDegree);
    ExpectSameBits(r.Positions, w0.Positions);
    ExpectSameBits(r.LogScales, w0.LogScales);
    ExpectSameBits(r.Rotations, w0.Rotations);
    ExpectSameBits(r.OpacityLogits, w0.OpacityLogits);
    ExpectSameBits(r.SH, w0.SH);
    EXPECT_EQ(reader.GetSnapshotSize(entry.first), w0.Count);
    EXPECT_EQ(reader.GetSnapshotShDegree(entry.first), w0.ShDegree);
    const SnapshotStatistics& stats = log.Stats[entry.first];
    if (!stats.GradAccum.empty() || swmr)
    {
      // Packed (SWMR) snapshots all have the columns: NaN where a snapshot had none.
      ASSERT_EQ(r.Extra.size(), 2u);
      EXPECT_EQ(r.Extra[0].Name, "grad_accum");
      EXPECT_EQ(r.Extra[1].Name, "denom");
      for (std::size_t i = 0; i < r.Count; ++i)
      {
        if (stats.GradAccum.empty())
        {
          EXPECT_TRUE(std::isnan(r.Extra[0].GetAsDouble(i)));
          EXPECT_TRUE(std::isnan(r.Extra[1].GetAsDouble(i)));
          continue;
        }
        EXPECT_EQ(static_cast<float>(r.Extra[0].GetAsDouble(i)), stats.GradAccum[i]);
        EXPECT_EQ(static_cast<float>(r.Extra[1].GetAsDouble(i)), stats.Denom[i]);
      }
      EXPECT_EQ(reader.GetSnapshotArrays(entry.first), static_cast<unsigned>(SnapshotAll));
    }
    else
    {
      EXPECT_TRUE(r.Extra.empty());
      EXPECT_EQ(reader.GetSnapshotArrays(entry.first), static_cast<unsigned>(SnapshotParameters));
    }
  }
}

TEST(TrainingLog, RoundTripEveryGroup)
{
  ExpectRoundTrip(false);
  ExpectRoundTrip(true);
}

//------------------------------------------------------------------------------
TEST(TrainingLog, SwmrWriterRefusesStructureAfterTheFirstSnapshot)
{
  const std::string path = TempLogPath("swmr_structure");
  TrainingLogWriterOptions options;
  options.Swmr = true;
  options.ShDegree = 1;
  TrainingLogWriter writer(path, options);
  writer.WriteSnapshot(0, MakeCloud(MakeIds(10, 10, 1), 1, 2));
  try
  {
    writer.WriteCameras(MakeCameras());
    ADD_FAILURE() << "cameras after the first snapshot of a SWMR log were accepted";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("SWMR"), std::string::npos) << e.what();
  }
  MetricsRow row;
  row.Iteration = 1;
  writer.AppendMetrics(row);
  writer.Flush();
  // While the writer is open a reader sees what was flushed and Refresh() a later snapshot.
  // (In one process HDF5 shares the writer's open file with the reader; other processes
  // open it in SWMR read mode: test_follow.py of the Python logger runs those.)
  TrainingLogReader reader(path);
  EXPECT_EQ(reader.GetSnapshotIterations(), std::vector<int>{ 0 });
  EXPECT_EQ(reader.ReadMetrics().Size(), 1u);
  EXPECT_FALSE(reader.Refresh());
  writer.WriteSnapshot(5, MakeCloud(MakeIds(12, 12, 2), 0, 3));
  EXPECT_TRUE(reader.Refresh());
  EXPECT_EQ(reader.GetSnapshotIterations(), (std::vector<int>{ 0, 5 }));
  EXPECT_EQ(reader.GetSnapshotShDegree(0), 1);
  EXPECT_EQ(reader.GetSnapshotShDegree(5), 0); // the degree written, not /snapshots/sh's
  EXPECT_EQ(reader.ReadSnapshot(5).Count, 12u);
  writer.Close();
  EXPECT_TRUE(Exists(path));
  EXPECT_FALSE(Exists(path + ".tmp"));
  // With WriteToTemporary the live SWMR file is <path>.tmp, renamed when it is closed.
  options.WriteToTemporary = true;
  {
    TrainingLogWriter temporary(path, options);
    EXPECT_TRUE(Exists(path + ".tmp"));
    temporary.Close();
  }
  EXPECT_TRUE(Exists(path));
  EXPECT_FALSE(Exists(path + ".tmp"));
}

//------------------------------------------------------------------------------
TEST(TrainingLog, ReadOptionsLoadOnlyWhatIsAsked)
{
  WrittenLog log = WriteSample("options", 100);
  TrainingLogReader reader(log.Path);
  const GaussianCloud& full = log.Snapshots[500]; // degree 3
  const std::size_t k = 16;

  // Default: every parameter, SH DC only.
  GaussianCloud dc = reader.ReadSnapshot(500);
  EXPECT_EQ(dc.ShDegree, 0);
  ASSERT_EQ(dc.SH.size(), 3 * dc.Count);
  for (std::size_t i = 0; i < dc.Count; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_EQ(dc.SH[3 * i + c], full.SH[i * k * 3 + c]);
    }
  }
  EXPECT_TRUE(dc.Extra.empty());

  // Degree 1: the first four coefficients of each Gaussian.
  SnapshotReadOptions one;
  one.ShDegree = 1;
  GaussianCloud d1 = reader.ReadSnapshot(500, one);
  EXPECT_EQ(d1.ShDegree, 1);
  ASSERT_EQ(d1.SH.size(), 12 * d1.Count);
  for (std::size_t i = 0; i < d1.Count; ++i)
  {
    for (int j = 0; j < 12; ++j)
    {
      ASSERT_EQ(d1.SH[12 * i + j], full.SH[i * k * 3 + j]);
    }
  }
  // A degree above the one held is clamped.
  SnapshotReadOptions three;
  three.ShDegree = 3;
  EXPECT_EQ(reader.ReadSnapshot(1000, three).ShDegree, 1);

  // Positions only: nothing else is loaded.
  SnapshotReadOptions pos;
  pos.Arrays = SnapshotPositions;
  GaussianCloud p = reader.ReadSnapshot(500, pos);
  EXPECT_EQ(p.Positions, full.Positions);
  EXPECT_TRUE(p.LogScales.empty() && p.Rotations.empty() && p.OpacityLogits.empty());
  EXPECT_TRUE(p.SH.empty());
  EXPECT_EQ(p.Ids, full.Ids);

  // Nearest snapshot.
  EXPECT_EQ(reader.FindNearestSnapshot(-50), 0);
  EXPECT_EQ(reader.FindNearestSnapshot(249), 0);
  EXPECT_EQ(reader.FindNearestSnapshot(250), 0); // tie: the earlier one
  EXPECT_EQ(reader.FindNearestSnapshot(251), 500);
  EXPECT_EQ(reader.FindNearestSnapshot(1800), 2500);
  EXPECT_EQ(reader.FindNearestSnapshot(99999), 2500);
  int logged = -1;
  GaussianCloud near = reader.ReadNearestSnapshot(900, pos, &logged);
  EXPECT_EQ(logged, 1000);
  EXPECT_EQ(near.Positions, log.Snapshots[1000].Positions);
  try
  {
    reader.ReadSnapshot(900);
    FAIL() << "no snapshot at 900";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_NE(std::string(e.what()).find(log.Path), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("no snapshot at iteration 900"), std::string::npos);
  }
}

//------------------------------------------------------------------------------
TEST(TrainingLog, PropertyHistoryMatchesFullReads)
{
  // Small chunks so that the searches cross many blocks (3 rows: the later snapshots have
  // more than 256 id chunks, whose addresses are then looked up lazily, under a lock, by
  // the threaded search); uncompressed snapshots (the default: rows read by pread) and
  // deflated ones (chunks inflated by our code).
  // Packed snapshots (format version 2, SWMR) too: rows found in a row range of each dataset.
  for (bool swmr : { false, true })
    for (int level : { 0, 1 })
      for (std::size_t chunk : { std::size_t(3), std::size_t(64), std::size_t(100000) })
      {
        SCOPED_TRACE("deflate " + std::to_string(level) + ", chunk " + std::to_string(chunk) +
          (swmr ? ", SWMR" : ""));
        WrittenLog log = WriteSample(
          "history" + std::to_string(chunk) + "_" + std::to_string(level) + (swmr ? "_swmr" : ""),
          chunk,
          level,
          swmr);
        TrainingLogReader reader(log.Path);
        std::mt19937 rng(3);
        std::vector<std::int64_t> query;
        std::uniform_int_distribution<std::int64_t> pick(-5, 1400);
        for (int i = 0; i < 150; ++i)
        {
          query.push_back(pick(rng));
        }
        query.push_back(0);
        query.push_back(log.Snapshots[2500].Ids.back()); // the last row
        query.push_back(log.Snapshots[2500].Ids.back() + 1);
        query.push_back(query[3]); // duplicates are merged
        PropertyHistory h = reader.ReadPropertyHistory(query, SnapshotAll);

        // Reference: full reads of every snapshot.
        std::vector<std::int64_t> ids = query;
        std::sort(ids.begin(), ids.end());
        ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
        std::size_t row = 0;
        for (std::int64_t id : ids)
        {
          for (const auto& entry : log.Snapshots)
          {
            const GaussianCloud& c = entry.second;
            auto it = std::lower_bound(c.Ids.begin(), c.Ids.end(), id);
            if (it == c.Ids.end() || *it != id)
            {
              continue;
            }
            const std::size_t i = static_cast<std::size_t>(it - c.Ids.begin());
            ASSERT_LT(row, h.Size());
            EXPECT_EQ(h.Id[row], id);
            EXPECT_EQ(h.Iteration[row], entry.first);
            for (int j = 0; j < 3; ++j)
            {
              EXPECT_EQ(h.Positions[3 * row + j], c.Positions[3 * i + j]);
              EXPECT_EQ(h.LogScales[3 * row + j], c.LogScales[3 * i + j]);
              EXPECT_EQ(h.SHDC[3 * row + j], c.SH[i * 3 * c.ShCoefficientCount() + j]);
            }
            for (int j = 0; j < 4; ++j)
            {
              EXPECT_EQ(h.Rotations[4 * row + j], c.Rotations[4 * i + j]);
            }
            EXPECT_EQ(h.OpacityLogits[row], c.OpacityLogits[i]);
            const SnapshotStatistics& s = log.Stats[entry.first];
            if (s.GradAccum.empty())
            {
              EXPECT_TRUE(std::isnan(h.GradAccum[row]));
              EXPECT_TRUE(std::isnan(h.Denom[row]));
            }
            else
            {
              EXPECT_EQ(h.GradAccum[row], s.GradAccum[i]);
              EXPECT_EQ(h.Denom[row], s.Denom[i]);
            }
            ++row;
          }
        }
        EXPECT_EQ(row, h.Size()) << "chunk " << chunk;
        EXPECT_GT(row, 100u);
      }
}

//------------------------------------------------------------------------------
TEST(TrainingLog, SnapshotsUncompressedByDefaultTablesDeflated)
{
  for (int level : { 0, 3 })
  {
    WrittenLog log = WriteSample("filters" + std::to_string(level), 64, level);
    hid_t file = H5Fopen(log.Path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    auto filters = [&](const char* path)
    {
      hid_t set = H5Dopen2(file, path, H5P_DEFAULT);
      EXPECT_GE(set, 0) << path;
      hid_t plist = H5Dget_create_plist(set);
      const int n = H5Pget_nfilters(plist);
      H5Pclose(plist);
      H5Dclose(set);
      return n;
    };
    const int snapshotFilters = level > 0 ? 2 : 0; // shuffle + deflate
    EXPECT_EQ(filters("/snapshots/000500/id"), snapshotFilters);
    EXPECT_EQ(filters("/snapshots/000500/position"), snapshotFilters);
    EXPECT_EQ(filters("/snapshots/000500/sh"), snapshotFilters);
    EXPECT_EQ(filters("/events/parent"), 2);
    EXPECT_EQ(filters("/metrics/loss"), 2);
    H5Fclose(file);
  }
  TrainingLogWriterOptions bad;
  bad.SnapshotDeflateLevel = 10;
  EXPECT_THROW(TrainingLogWriter(TempLogPath("badlevel"), bad), std::runtime_error);
}

//------------------------------------------------------------------------------
TEST(TrainingLog, WriterRejectsBadInputAndRenamesTemporary)
{
  const std::string path = TempLogPath("tmpname");
  std::remove(path.c_str());
  {
    TrainingLogWriterOptions options;
    options.WriteToTemporary = true;
    TrainingLogWriter writer(path, options);
    GaussianCloud c = MakeCloud({ 0, 1, 2 }, 0, 1);
    writer.WriteSnapshot(10, c);
    EXPECT_FALSE(Exists(path));
    EXPECT_TRUE(Exists(path + ".tmp"));
    EXPECT_THROW(writer.WriteSnapshot(10, c), std::runtime_error); // not increasing
    GaussianCloud bad = MakeCloud({ 0, 2, 2 }, 0, 1);
    EXPECT_THROW(writer.WriteSnapshot(20, bad), std::runtime_error);
    GaussianCloud decreasing = MakeCloud({ 5, 4, 6 }, 0, 1);
    EXPECT_THROW(writer.WriteSnapshot(20, decreasing), std::runtime_error);
    GaussianCloud wrongSize = MakeCloud({ 0, 1, 2 }, 0, 1);
    wrongSize.Positions.pop_back();
    EXPECT_THROW(writer.WriteSnapshot(20, wrongSize), std::runtime_error);
    writer.Close();
    EXPECT_TRUE(Exists(path));
    EXPECT_FALSE(Exists(path + ".tmp"));
    EXPECT_THROW(writer.WriteSnapshot(30, c), std::runtime_error); // closed
  }
  TrainingLogReader reader(path);
  EXPECT_EQ(reader.GetSnapshotIterations(), std::vector<int>{ 10 });
  // Empty ids mean 0..N-1.
  EXPECT_EQ(reader.ReadSnapshot(10).Ids, (std::vector<std::int64_t>{ 0, 1, 2 }));
  EXPECT_THROW(TrainingLogWriter("/nonexistent-dir/x.h5"), std::runtime_error);
}

//------------------------------------------------------------------------------
// A writer through a temporary that is destroyed without Close() (an exception unwinds its
// owner: a full disk) removes the temporary and leaves the log already at the path untouched.
TEST(TrainingLog, WriterDestroyedWithoutCloseLeavesTheOldLog)
{
  const std::string path = TempLogPath("discard");
  {
    TrainingLogWriter old(path);
    old.WriteSnapshot(10, MakeCloud({ 0, 1 }, 0, 1));
    old.Close();
  }
  {
    TrainingLogWriterOptions options;
    options.WriteToTemporary = true;
    TrainingLogWriter writer(path, options);
    writer.WriteSnapshot(20, MakeCloud({ 0, 1, 2 }, 0, 1));
    writer.Flush();
    EXPECT_TRUE(Exists(path + ".tmp"));
  }
  EXPECT_FALSE(Exists(path + ".tmp"));
  TrainingLogReader reader(path);
  EXPECT_EQ(reader.GetSnapshotIterations(), std::vector<int>{ 10 });
}

//------------------------------------------------------------------------------
TEST(TrainingLog, LacksAndEmptyLog)
{
  const std::string path = TempLogPath("empty");
  {
    TrainingLogWriter writer(path);
  }
  TrainingLogReader reader(path);
  const std::vector<std::string>& lacks = reader.GetLacks();
  auto mentions = [&](const std::string& what)
  {
    for (const std::string& l : lacks)
    {
      if (l.find(what) != std::string::npos)
      {
        return true;
      }
    }
    return false;
  };
  EXPECT_TRUE(mentions("/cameras"));
  EXPECT_TRUE(mentions("/metrics/test"));
  EXPECT_TRUE(mentions("no snapshots"));
  EXPECT_FALSE(mentions("/events"));
  EXPECT_TRUE(reader.ReadCameras().empty());
  EXPECT_EQ(reader.ReadMetrics().Size(), 0u);
  EXPECT_EQ(reader.ReadEvents().Size(), 0u);
  EXPECT_EQ(reader.FindNearestSnapshot(100), -1);
  EXPECT_EQ(reader.ReadPropertyHistory({ 1, 2, 3 }).Size(), 0u);
  int logged = 0;
  EXPECT_THROW(reader.ReadNearestSnapshot(5, SnapshotReadOptions(), &logged), std::runtime_error);
}

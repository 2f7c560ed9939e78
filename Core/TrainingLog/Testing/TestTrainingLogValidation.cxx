// SPDX-License-Identifier: BSD-3-Clause
// Bad input: missing or foreign files, other format versions, broken events, unsorted
// snapshot ids, snapshot names that disagree with their iteration, ragged tables and
// truncated files give clear errors naming the file, or repaired results with the repairs.
#include "TrainingLogReader.h"
#include "TrainingLogTestUtilities.h"
#include "TrainingLogWriter.h"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <fstream>
#include <functional>

using namespace vis4gs;
using vis4gs::testing::MakeCloud;
using vis4gs::testing::TempLogPath;

namespace
{
/// Expects the reader construction or @p action to throw a message with @p path and @p text.
void ExpectError(const std::string& path,
  const std::string& text,
  const std::function<void()>& action)
{
  try
  {
    action();
    ADD_FAILURE() << "no error; expected: " << text;
  }
  catch (const std::runtime_error& e)
  {
    const std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find(text), std::string::npos) << message;
  }
}

std::string WriteLog(const std::string& tag, const std::vector<TrainingEvent>& events)
{
  const std::string path = TempLogPath(tag);
  TrainingLogWriter writer(path);
  for (const TrainingEvent& e : events)
  {
    writer.AppendEvent(e);
  }
  writer.WriteSnapshot(100, MakeCloud({ 0, 1, 2, 3, 4, 5 }, 0, 1));
  writer.WriteSnapshot(200, MakeCloud({ 0, 2, 3, 10 }, 0, 2));
  writer.Close();
  return path;
}

/// Opens @p path read-write and runs @p edit on the file id.
void Edit(const std::string& path, const std::function<void(hid_t)>& edit)
{
  hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  edit(file);
  H5Fclose(file);
}

bool Contains(const std::vector<std::string>& list, const std::string& text)
{
  for (const std::string& s : list)
  {
    if (s.find(text) != std::string::npos)
    {
      return true;
    }
  }
  return false;
}
} // namespace

//------------------------------------------------------------------------------
TEST(TrainingLogValidation, BadFiles)
{
  const std::string missing = "/tmp/vis4gs-no-such-log.h5";
  ExpectError(missing, "no such file", [&] { TrainingLogReader r(missing); });

  const std::string text = TempLogPath("text");
  std::ofstream(text) << "not hdf5 at all\n";
  ExpectError(text, "not an HDF5 file", [&] { TrainingLogReader r(text); });

  const std::string foreign = TempLogPath("foreign");
  {
    hid_t f = H5Fcreate(foreign.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    H5Fclose(f);
  }
  ExpectError(foreign, "no 'format' attribute", [&] { TrainingLogReader r(foreign); });

  auto setVersion = [](long long version)
  {
    return [version](hid_t f)
    {
      hid_t a = H5Aopen(f, "format_version", H5P_DEFAULT);
      H5Awrite(a, H5T_NATIVE_LLONG, &version);
      H5Aclose(a);
    };
  };
  const std::string v3 = WriteLog("v3", {});
  Edit(v3, setVersion(3));
  ExpectError(v3, "format version 3 is not supported", [&] { TrainingLogReader r(v3); });
  // Version 2 without its /committed counts (a version 1 layout relabelled).
  const std::string v2 = WriteLog("v2", {});
  Edit(v2, setVersion(2));
  ExpectError(v2, "lacks the dataset /committed", [&] { TrainingLogReader r(v2); });

  // Truncated files: every cut gives an error or a readable prefix, never a crash.
  const std::string good = WriteLog("good", { { 600, EventKind::Prune, 1, -1 } });
  std::ifstream in(good, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 2000u);
  int errors = 0;
  for (double fraction : { 0.02, 0.1, 0.3, 0.5, 0.8, 0.95 })
  {
    const std::string cut = TempLogPath("cut");
    std::ofstream(cut, std::ios::binary)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size() * fraction));
    try
    {
      TrainingLogReader r(cut);
      for (int it : r.GetSnapshotIterations())
      {
        r.ReadSnapshot(it);
      }
      r.ReadEvents();
      r.ReadMetrics();
    }
    catch (const std::runtime_error& e)
    {
      ++errors;
      EXPECT_NE(std::string(e.what()).find(cut), std::string::npos) << e.what();
    }
  }
  EXPECT_GE(errors, 5);
}

//------------------------------------------------------------------------------
TEST(TrainingLogValidation, EventErrorsAndRepairs)
{
  struct Case
  {
    std::vector<TrainingEvent> Events;
    std::string Error;
    std::string Repair;
    std::size_t Kept;
  };
  const Case cases[] = {
    // Unknown parent: 6 was never born (initial ids are 0..5, the first new id is 6).
    { { { 600, EventKind::Clone, 1, 6 }, { 600, EventKind::Clone, 9, 7 } },
      "unknown id 9",
      "naming unknown ids",
      1 },
    // Negative parent.
    { { { 600, EventKind::Prune, -4, -1 } }, "unknown id -4", "naming unknown ids", 0 },
    // A child id reused.
    { { { 600, EventKind::Clone, 1, 6 }, { 600, EventKind::Clone, 2, 6 } },
      "not a fresh id",
      "reusing ids",
      1 },
    // A pruned id used again.
    { { { 600, EventKind::Prune, 3, -1 }, { 700, EventKind::Clone, 3, 6 } },
      "which ended (prune) at iteration 600",
      "naming ended ids",
      1 },
    // A split parent used after its split.
    { { { 600, EventKind::Split, 2, 6 },
        { 600, EventKind::Split, 2, 7 },
        { 700, EventKind::Prune, 2, -1 } },
      "which ended (split) at iteration 600",
      "naming ended ids",
      2 },
    // Bad kind.
    { { { 600, static_cast<EventKind>(9), 1, 6 } }, "has kind 9", "of an unknown kind", 0 },
    // Iterations going back are sorted (then valid).
    { { { 700, EventKind::Clone, 1, 6 }, { 600, EventKind::Prune, 2, -1 } },
      "must be in training order",
      "sorted /events by iteration",
      2 },
  };
  int index = 0;
  for (const Case& c : cases)
  {
    const std::string path = WriteLog("events" + std::to_string(index++), c.Events);
    {
      TrainingLogReader reader(path);
      ExpectError(path, c.Error, [&] { reader.ReadEvents(); });
    }
    TrainingLogReaderOptions repair;
    repair.Repair = true;
    TrainingLogReader reader(path, repair);
    EventTable t = reader.ReadEvents();
    EXPECT_EQ(t.Size(), c.Kept) << c.Error;
    EXPECT_TRUE(Contains(reader.GetRepairs(), c.Repair)) << c.Error;
  }
  // A valid split: both children recorded, the parent ended by the split, never pruned.
  const std::string ok = WriteLog("eventsok",
    { { 600, EventKind::Clone, 1, 6 },
      { 600, EventKind::Split, 2, 7 },
      { 600, EventKind::Split, 2, 8 },
      { 600, EventKind::Prune, 6, -1 },
      { 700, EventKind::Split, 8, 9 },
      { 700, EventKind::Split, 8, 10 } });
  TrainingLogReader reader(ok);
  EXPECT_EQ(reader.ReadEvents().Size(), 6u);
  EXPECT_TRUE(reader.GetRepairs().empty());
}

//------------------------------------------------------------------------------
TEST(TrainingLogValidation, SnapshotIdsAndOrder)
{
  // Duplicate and decreasing ids written behind the writer's back.
  const std::string path = WriteLog("ids", {});
  Edit(path,
    [](hid_t f)
    {
      hid_t d = H5Dopen2(f, "/snapshots/000100/id", H5P_DEFAULT);
      const long long ids[6] = { 0, 4, 2, 2, 3, 5 };
      H5Dwrite(d, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, ids);
      H5Dclose(d);
    });
  const GaussianCloud written = MakeCloud({ 0, 1, 2, 3, 4, 5 }, 0, 1);
  {
    TrainingLogReader reader(path);
    ExpectError(path, "/snapshots/000100/id has decreasing ids", [&] { reader.ReadSnapshot(100); });
    ExpectError(path, "not strictly increasing", [&] { reader.ReadPropertyHistory({ 2, 3 }); });
  }
  TrainingLogReaderOptions repair;
  repair.Repair = true;
  TrainingLogReader reader(path, repair);
  GaussianCloud c = reader.ReadSnapshot(100);
  EXPECT_EQ(c.Ids, (std::vector<std::int64_t>{ 0, 2, 3, 4, 5 }));
  ASSERT_EQ(c.Count, 5u);
  // Row order after the repair: rows 0, 2 (first of the two 2s), 4, 1, 5.
  const std::size_t rows[5] = { 0, 2, 4, 1, 5 };
  for (std::size_t i = 0; i < 5; ++i)
  {
    EXPECT_EQ(c.OpacityLogits[i], written.OpacityLogits[rows[i]]);
    EXPECT_EQ(c.Positions[3 * i + 2], written.Positions[3 * rows[i] + 2]);
  }
  EXPECT_TRUE(Contains(reader.GetRepairs(), "sorted 6 rows by id and dropped 1 duplicate"));
  PropertyHistory h = reader.ReadPropertyHistory({ 3 }, SnapshotOpacityLogits);
  ASSERT_EQ(h.Size(), 2u);
  EXPECT_EQ(h.OpacityLogits[0], written.OpacityLogits[4]);

  // A snapshot named for one iteration holding another.
  const std::string order = WriteLog("order", {});
  Edit(order,
    [](hid_t f)
    {
      hid_t g = H5Gopen2(f, "/snapshots/000100", H5P_DEFAULT);
      hid_t a = H5Aopen(g, "iteration", H5P_DEFAULT);
      long long it = 300;
      H5Awrite(a, H5T_NATIVE_LLONG, &it);
      H5Aclose(a);
      H5Gclose(g);
    });
  ExpectError(order, "snapshots out of order", [&] { TrainingLogReader r(order); });
  TrainingLogReader repaired(order, repair);
  EXPECT_EQ(repaired.GetSnapshotIterations(), (std::vector<int>{ 200, 300 }));
  EXPECT_TRUE(Contains(repaired.GetRepairs(), "placed /snapshots/000100 at iteration 300"));
  EXPECT_EQ(repaired.ReadSnapshot(300).Ids.size(), 6u);

  // Two snapshots with the same iteration.
  const std::string dup = WriteLog("dupsnap", {});
  Edit(dup,
    [](hid_t f)
    {
      hid_t g = H5Gopen2(f, "/snapshots/000200", H5P_DEFAULT);
      hid_t a = H5Aopen(g, "iteration", H5P_DEFAULT);
      long long it = 100;
      H5Awrite(a, H5T_NATIVE_LLONG, &it);
      H5Aclose(a);
      H5Gclose(g);
    });
  ExpectError(dup, "snapshots out of order", [&] { TrainingLogReader r(dup); });
  TrainingLogReader dupRepaired(dup, repair);
  EXPECT_EQ(dupRepaired.GetSnapshotIterations(), std::vector<int>{ 100 });
  EXPECT_TRUE(Contains(dupRepaired.GetRepairs(), "a second snapshot of iteration 100"));
}

//------------------------------------------------------------------------------
TEST(TrainingLogValidation, RaggedTablesAndMissingDatasets)
{
  const std::string path = TempLogPath("ragged");
  {
    TrainingLogWriter writer(path);
    for (int i = 0; i < 10; ++i)
    {
      MetricsRow r;
      r.Iteration = i;
      r.Loss = i;
      writer.AppendMetrics(r);
    }
    writer.WriteSnapshot(0, MakeCloud({ 0, 1 }, 0, 1));
  }
  Edit(path,
    [](hid_t f)
    {
      hid_t d = H5Dopen2(f, "/metrics/loss", H5P_DEFAULT);
      hsize_t n = 7;
      H5Dset_extent(d, &n);
      H5Dclose(d);
      H5Ldelete(f, "/metrics/lpips", H5P_DEFAULT);
      H5Ldelete(f, "/snapshots/000000/rotation", H5P_DEFAULT);
    });
  {
    TrainingLogReader reader(path);
    ExpectError(path, "/metrics/loss has 7 rows", [&] { reader.ReadMetrics(); });
    ExpectError(
      path, "lacks the dataset /snapshots/000000/rotation", [&] { reader.ReadSnapshot(0); });
    SnapshotReadOptions noRotation;
    noRotation.Arrays = SnapshotPositions;
    EXPECT_EQ(reader.ReadSnapshot(0, noRotation).Count, 2u);
  }
  TrainingLogReaderOptions repair;
  repair.Repair = true;
  TrainingLogReader reader(path, repair);
  MetricsTable m = reader.ReadMetrics();
  ASSERT_EQ(m.Size(), 7u);
  EXPECT_EQ(m.Loss[6], 6.0);
  EXPECT_TRUE(std::isnan(m.Lpips[0]));
}

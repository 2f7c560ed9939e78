// SPDX-License-Identifier: BSD-3-Clause
// The fine-tune after a clean-up (issue 20) on a planted case: a wall of Gaussians whose
// colours are off from the images, and a floater in front of one training view. Deleting the
// floater raises that view's PSNR; fine-tuning then raises the training PSNR further (the
// colours are learnt) with the positions fixed bit for bit. The log written is read back: the
// deletion is a prune event at the source iteration, and the genealogy built from it (strict,
// no repairs) is one tree over the snapshot's ids. A cancelled fine-tune writes nothing.
#include "FineTune.h"

#include "Genealogy.h"
#include "Loss.h"
#include "RemovalEffect.h"
#include "TrainingLogReader.h"

#include "../../Render/Testing/RasterTestUtils.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include <unistd.h>

namespace vis4gs
{
namespace
{
namespace fs = std::filesystem;

constexpr int SourceIteration = 100;

struct PlantedScene
{
  GaussianCloud Cloud;
  std::vector<Camera> Cameras;
  std::vector<Image> Targets;
  std::size_t Floater = 0;
};

// A wall of 8 x 5 Gaussians at z = 5 seen by two training cameras and one test camera, and a
// green floater at z = 1 in front of training camera A only. The targets are the wall alone with
// every colour 0.15 brighter in red and 0.1 darker in blue (what a fine-tune must learn).
PlantedScene MakePlantedScene()
{
  PlantedScene s;
  const int nx = 8, ny = 5;
  GaussianCloud target;
  s.Cloud.Resize(nx * ny + 1, 0);
  target.Resize(nx * ny, 0);
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      const std::size_t g = static_cast<std::size_t>(j * nx + i);
      const float x = -2.5f + 0.75f * static_cast<float>(i), y = -2.0f + 0.9f * j;
      const std::array<float, 3> rgb{
        0.2f + 0.05f * static_cast<float>(i % 4), 0.5f, 0.4f + 0.1f * static_cast<float>(j % 3)
      };
      for (GaussianCloud* c : { &s.Cloud, &target })
      {
        const bool t = c == &target;
        rastertest::SetGaussian(*c,
          g,
          { x, y, 5.0f },
          { std::log(0.45f), std::log(0.45f), std::log(0.05f) },
          { 1, 0, 0, 0 },
          4.0f,
          { rgb[0] + (t ? 0.15f : 0.0f), rgb[1], rgb[2] - (t ? 0.1f : 0.0f) });
      }
    }
  }
  s.Floater = static_cast<std::size_t>(nx * ny);
  rastertest::SetGaussian(s.Cloud,
    s.Floater,
    { 0.0f, 0.0f, 1.0f },
    { std::log(0.05f), std::log(0.05f), std::log(0.05f) },
    { 1, 0, 0, 0 },
    3.0f,
    { 0.1f, 0.9f, 0.1f });
  // Ids as a log's snapshot holds them: strictly increasing, not the row numbers.
  for (std::size_t i = 0; i < s.Cloud.Count; ++i)
  {
    s.Cloud.Ids.push_back(static_cast<std::int64_t>(7 + 3 * i));
  }
  Camera a = rastertest::LookAt(64, 48, 40, 40, { 0, 0, 0 }, { 0, 0, 5 });
  a.Name = "A";
  Camera c = rastertest::LookAt(64, 48, 40, 40, { -1.5, 0.3, 0 }, { -1.5, 0.3, 5 });
  c.Name = "C";
  Camera b = rastertest::LookAt(64, 48, 40, 40, { 1, -0.4, 0 }, { 1, -0.4, 5 });
  b.Name = "B";
  b.Split = CameraSplit::Test;
  s.Cameras = { a, c, b };
  for (const Camera& cam : s.Cameras)
  {
    s.Targets.push_back(ClampedImage(Rasterize<float>(target, cam)));
  }
  return s;
}

TrainingImageProvider Provider(const std::vector<Image>& targets)
{
  return [&targets](std::size_t index, const Camera&, Image& image)
  {
    image = targets[index];
    return true;
  };
}

// Mean training-view PSNR of @p cloud, from a plain double loop over the clamped render.
double PlainTrainPsnr(const GaussianCloud& cloud, const PlantedScene& s)
{
  double sum = 0;
  int views = 0;
  for (std::size_t v = 0; v < s.Cameras.size(); ++v)
  {
    if (s.Cameras[v].Split != CameraSplit::Train)
    {
      continue;
    }
    const RasterImage<float> render = Rasterize<float>(cloud, s.Cameras[v]);
    double se = 0;
    for (std::size_t k = 0; k < s.Targets[v].Pixels.size(); ++k)
    {
      const double d = std::min(1.0, std::max(0.0, static_cast<double>(render.Color[k]))) -
        static_cast<double>(s.Targets[v].Pixels[k]);
      se += d * d;
    }
    sum += -10.0 * std::log10(se / static_cast<double>(s.Targets[v].Pixels.size()));
    ++views;
  }
  return sum / views;
}

fs::path FreshFolder(const std::string& name)
{
  const fs::path folder = fs::temp_directory_path() /
    ("vis4gs-finetune-" + name + "-" + std::to_string(static_cast<long>(::getpid())));
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

FineTuneOptions TestOptions()
{
  FineTuneOptions options;
  options.Iterations = 20;
  options.Threads = 2;
  options.Scene = "planted";
  return options;
}
} // namespace

TEST(FineTune, PlantedFloaterRepairedWithFixedPositions)
{
  const PlantedScene s = MakePlantedScene();
  std::vector<std::uint8_t> removed(s.Cloud.Count, 0);
  removed[s.Floater] = 1;
  const fs::path folder = FreshFolder("planted");
  FineTuneOptions options = TestOptions();
  options.LogPath = (folder / "repaired.h5").string();
  std::vector<int> progress;
  options.Progress = [&progress](int done, int total)
  {
    EXPECT_EQ(total, 20);
    progress.push_back(done);
    return true;
  };
  const FineTuneResult r =
    FineTune(s.Cloud, SourceIteration, removed, s.Cameras, Provider(s.Targets), options);
  EXPECT_FALSE(r.Cancelled);
  EXPECT_EQ(r.SourceIteration, SourceIteration);
  EXPECT_EQ(r.LastIteration, SourceIteration + 20);
  ASSERT_EQ(progress.size(), 20u);
  EXPECT_EQ(progress.front(), 1);
  EXPECT_EQ(progress.back(), 20);
  EXPECT_EQ(r.Pruned, (std::vector<std::int64_t>{ s.Cloud.GetId(s.Floater) }));
  ASSERT_EQ(r.Cleaned.Count, s.Cloud.Count - 1);
  ASSERT_EQ(r.Repaired.Count, r.Cleaned.Count);
  EXPECT_EQ(r.Repaired.Ids, r.Cleaned.Ids);
  // Positions fixed: bit for bit; the colours were learnt.
  EXPECT_EQ(r.Repaired.Positions, r.Cleaned.Positions);
  EXPECT_NE(r.Repaired.SH, r.Cleaned.SH);

  // The figures, per camera, against a plain PSNR of the three states.
  ASSERT_EQ(r.Source.size(), 3u);
  ASSERT_EQ(r.Deleted.size(), 3u);
  ASSERT_EQ(r.RepairedFigures.size(), 3u);
  const double plain[3] = {
    PlainTrainPsnr(s.Cloud, s), PlainTrainPsnr(r.Cleaned, s), PlainTrainPsnr(r.Repaired, s)
  };
  const std::vector<FineTuneFigureRow> rows = FineTuneFigureRows(r, s.Cameras);
  ASSERT_EQ(rows.size(), 5u); // mean train, mean test, A, C, B
  EXPECT_EQ(rows[0].View, "mean");
  EXPECT_EQ(rows[0].Split, "train");
  EXPECT_EQ(rows[1].Split, "test");
  EXPECT_EQ(rows[4].View, "B");
  for (int state = 0; state < 3; ++state)
  {
    EXPECT_NEAR(rows[0].Values[state], plain[state], 1e-3) << "state " << state;
  }
  // The direction: deleting the floater raises view A (and the training mean), leaves the
  // others; the fine-tune raises the training PSNR over the deleted scene's, in every view.
  EXPECT_GT(r.Deleted[0].Psnr, r.Source[0].Psnr + 0.2);
  EXPECT_EQ(r.Deleted[1].Psnr, r.Source[1].Psnr);
  EXPECT_EQ(r.Deleted[2].Psnr, r.Source[2].Psnr);
  EXPECT_GT(rows[0].Values[2], rows[0].Values[1]); // repaired > deleted (train mean)
  EXPECT_GT(r.RepairedFigures[0].Psnr, r.Deleted[0].Psnr);
  EXPECT_GT(r.RepairedFigures[1].Psnr, r.Deleted[1].Psnr);
  EXPECT_LT(rows[0].Values[8], rows[0].Values[7]); // L1 repaired < deleted
  ASSERT_EQ(FineTuneFigureColumns().size(), 11u);
  EXPECT_EQ(FineTuneFigureColumns()[0], "view");
  EXPECT_EQ(FineTuneFigureColumns()[4], "psnr_repaired");

  // The log: the source snapshot whole, the deletion as a prune at the source iteration, the
  // repaired Gaussians last; nothing left behind but the log.
  ASSERT_TRUE(fs::exists(options.LogPath));
  EXPECT_EQ(std::distance(fs::directory_iterator(folder), fs::directory_iterator()), 1);
  TrainingLogReader log(options.LogPath);
  EXPECT_EQ(log.GetHeader().Scene, "planted");
  EXPECT_EQ(
    log.GetSnapshotIterations(), (std::vector<int>{ SourceIteration, SourceIteration + 20 }));
  const GaussianCloud first = log.ReadSnapshot(SourceIteration);
  EXPECT_EQ(first.Ids, s.Cloud.Ids);
  EXPECT_EQ(first.Positions, s.Cloud.Positions);
  const GaussianCloud last = log.ReadSnapshot(SourceIteration + 20);
  EXPECT_EQ(last.Ids, r.Repaired.Ids);
  EXPECT_EQ(last.Positions, r.Repaired.Positions);
  EXPECT_EQ(last.OpacityLogits, r.Repaired.OpacityLogits);
  const EventTable events = log.ReadEvents();
  ASSERT_EQ(events.Size(), 1u); // densification off: the deletion only
  EXPECT_EQ(events.Iteration[0], SourceIteration);
  EXPECT_EQ(events.Kind[0], static_cast<std::uint8_t>(EventKind::Prune));
  EXPECT_EQ(events.Parent[0], s.Cloud.GetId(s.Floater));
  EXPECT_EQ(events.Child[0], -1);
  EXPECT_EQ(log.ReadCameras().size(), 3u);
  EXPECT_EQ(log.GetImageNames().size(), 3u);
  // The metrics row of the source iteration is the deleted scene (the trainer's evaluation).
  const MetricsTable metrics = log.ReadMetrics();
  ASSERT_FALSE(metrics.Iteration.empty());
  EXPECT_EQ(metrics.Iteration.front(), SourceIteration);
  EXPECT_NEAR(metrics.Psnr.front(), rows[0].Values[1], 1e-3);

  // The genealogy of the repaired run: one tree over the snapshot's ids, built strictly.
  GenealogyOptions strict;
  strict.StrictEventOrder = true;
  const Genealogy tree = Genealogy::Build(first.Ids, events, SourceIteration + 20, strict);
  EXPECT_TRUE(tree.GetOrphanRoots().empty());
  EXPECT_TRUE(tree.GetWarnings().empty());
  ASSERT_EQ(tree.GetNumberOfNodes(), static_cast<std::int64_t>(s.Cloud.Count));
  for (std::size_t i = 0; i < s.Cloud.Count; ++i)
  {
    const std::int64_t node = tree.FindNode(s.Cloud.GetId(i));
    ASSERT_GE(node, 0);
    EXPECT_EQ(tree.GetDeathIterations()[node], i == s.Floater ? SourceIteration : -1);
    EXPECT_EQ(tree.GetPruned()[node], i == s.Floater ? 1 : 0);
  }
  fs::remove_all(folder);
}

TEST(FineTune, FreePositionsMoveAndSeedIsDeterministic)
{
  const PlantedScene s = MakePlantedScene();
  std::vector<std::uint8_t> removed(s.Cloud.Count, 0);
  removed[s.Floater] = 1;
  FineTuneOptions options = TestOptions();
  options.Iterations = 5;
  options.Measure = false;
  options.FreePositions = true;
  const FineTuneResult a =
    FineTune(s.Cloud, SourceIteration, removed, s.Cameras, Provider(s.Targets), options);
  EXPECT_NE(a.Repaired.Positions, a.Cleaned.Positions);
  EXPECT_TRUE(a.Source.empty() && a.Deleted.empty() && a.RepairedFigures.empty());
  const FineTuneResult b =
    FineTune(s.Cloud, SourceIteration, removed, s.Cameras, Provider(s.Targets), options);
  EXPECT_EQ(a.Repaired.Positions, b.Repaired.Positions);
  EXPECT_EQ(a.Repaired.SH, b.Repaired.SH);
}

TEST(FineTune, CancelledWritesNothing)
{
  const PlantedScene s = MakePlantedScene();
  std::vector<std::uint8_t> removed(s.Cloud.Count, 0);
  removed[s.Floater] = 1;
  const fs::path folder = FreshFolder("cancel");
  FineTuneOptions options = TestOptions();
  options.LogPath = (folder / "repaired.h5").string();
  int calls = 0;
  options.Progress = [&calls](int done, int)
  {
    ++calls;
    return done < 3;
  };
  const FineTuneResult r =
    FineTune(s.Cloud, SourceIteration, removed, s.Cameras, Provider(s.Targets), options);
  EXPECT_TRUE(r.Cancelled);
  EXPECT_EQ(calls, 3);
  EXPECT_EQ(r.LastIteration, SourceIteration + 3);
  EXPECT_TRUE(r.Source.empty());
  EXPECT_TRUE(fs::is_empty(folder)); // neither the log nor its temporary
  fs::remove_all(folder);
}

TEST(FineTune, BadInput)
{
  const PlantedScene s = MakePlantedScene();
  const TrainingImageProvider images = Provider(s.Targets);
  FineTuneOptions options = TestOptions();
  EXPECT_THROW(FineTune(s.Cloud, 0, { 1, 0 }, s.Cameras, images, options), std::invalid_argument);
  const std::vector<std::uint8_t> none(s.Cloud.Count, 0);
  options.Iterations = 0;
  EXPECT_THROW(FineTune(s.Cloud, 0, none, s.Cameras, images, options), std::invalid_argument);
  options.Iterations = 2;
  GaussianCloud noIds = s.Cloud;
  noIds.Ids.clear();
  EXPECT_THROW(FineTune(noIds, 0, none, s.Cameras, images, options), std::invalid_argument);
  const TrainingImageProvider missing = [](std::size_t, const Camera&, Image&) { return false; };
  try
  {
    FineTune(s.Cloud, 0, none, s.Cameras, missing, options);
    ADD_FAILURE() << "no image: no exception";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_NE(std::string(e.what()).find("camera A has no image"), std::string::npos);
  }
}

} // namespace vis4gs

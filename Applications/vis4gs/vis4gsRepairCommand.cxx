// SPDX-License-Identifier: BSD-3-Clause
// `vis4gs repair LOG CLEANED --iterations=N --output=DIR` (issue 20): fine-tunes a cleaned scene
// (analyze --select=RULE --delete's cleaned.ply, or any scene holding a subset of the ids of a
// snapshot of LOG) for N iterations with the built-in trainer, positions fixed and densification
// off by default, and writes DIR/repaired.h5, a training log that continues LOG: its first event
// rows are the deletion as prune events at the snapshot's iteration, its iterations follow it,
// so the genealogy of the repaired run stays one tree. DIR/repair.csv holds PSNR, SSIM and L1
// per view of the snapshot, the cleaned scene and the repaired one (RemovalEffect.h's figures).
#include "Vis4GSCommand.h"

#include "RemovalEffect.h"
#include "Trainer.h"
#include "TrainingLogReader.h"
#include "TrainingLogWriter.h"
#include "Vis4GSStateFiles.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

namespace
{
namespace fs = std::filesystem;

void Define(Vis4GSArguments& args)
{
  args.AddPositional("LOG", "Training log the cleaned scene comes from (.h5).");
  args.AddPositional("CLEANED",
    "The cleaned scene: a PLY whose id property names the Gaussians kept (analyze --delete's "
    "cleaned.ply), a subset of the snapshot's ids.");
  args.AddOption("iteration",
    "N",
    "-1",
    "The snapshot the scene was cleaned from (the nearest logged); -1: the last.");
  args.AddOption("iterations", "N", "50", "Fine-tuning iterations.");
  args.AddFlag("free-positions", false, "Optimise the positions too (default: fixed).");
  args.AddFlag("densify",
    false,
    "Keep the trainer's densification schedule (default: off, and no opacity reset).");
  args.AddOption("seed", "S", "0", "Random seed (camera order).");
  args.AddOption("output", "DIR", "vis4gs-repair", "Folder for repaired.h5 and repair.csv.");
}

const char* SplitName(const vis4gs::Camera& camera)
{
  return camera.Split == vis4gs::CameraSplit::Train ? "train" : "test";
}

int Run(const Vis4GSArguments& args)
{
  const std::string logPath = args.GetPositional("LOG");
  const int iterations = args.GetInt("iterations");
  if (iterations <= 0)
  {
    throw std::runtime_error("--iterations must be positive");
  }
  auto log = std::make_shared<vis4gs::TrainingLogReader>(logPath);
  if (log->GetSnapshotIterations().empty() || !log->HasCameras())
  {
    throw std::runtime_error(logPath + ": the training log needs a snapshot and /cameras");
  }
  vis4gs::SnapshotReadOptions readOptions;
  readOptions.ShDegree = -1;
  int source = 0;
  const int wanted = args.GetInt("iteration");
  const vis4gs::GaussianCloud snapshot = log->ReadNearestSnapshot(
    wanted < 0 ? log->GetSnapshotIterations().back() : wanted, readOptions, &source);
  const std::string cleanedPath = args.GetPositional("CLEANED");
  const vis4gs::GaussianCloud kept = Vis4GSReadSceneWithIds(cleanedPath, "repair");

  // The deleted Gaussians: the snapshot's ids the cleaned scene lacks. The fine-tune starts
  // from the snapshot's own rows (every SH coefficient, exactly as logged).
  std::vector<std::int64_t> keptIds(kept.Count);
  for (std::size_t i = 0; i < kept.Count; ++i)
  {
    keptIds[i] = kept.GetId(i);
  }
  std::sort(keptIds.begin(), keptIds.end());
  std::vector<std::uint8_t> removed(snapshot.Count, 1);
  std::vector<std::int64_t> prunes;
  std::size_t found = 0;
  for (std::size_t i = 0; i < snapshot.Count; ++i)
  {
    const bool keep = std::binary_search(keptIds.begin(), keptIds.end(), snapshot.GetId(i));
    removed[i] = keep ? 0 : 1;
    found += keep ? 1 : 0;
    if (!keep)
    {
      prunes.push_back(snapshot.GetId(i));
    }
  }
  if (found != keptIds.size())
  {
    throw std::runtime_error(cleanedPath + ": holds " + std::to_string(keptIds.size() - found) +
      " ids that the snapshot of iteration " + std::to_string(source) + " of " + logPath +
      " lacks (is it cleaned from this snapshot, with its id property?)");
  }
  const vis4gs::GaussianCloud cleaned = vis4gs::RemoveGaussians(snapshot, removed);
  std::cout << "vis4gs repair: " << logPath << ", snapshot of iteration " << source << ": "
            << snapshot.Count << " Gaussians, " << prunes.size() << " deleted in " << cleanedPath
            << "\n";

  // The training data: the log's cameras and images.
  vis4gs::TrainingData data;
  data.Name = log->GetHeader().Scene;
  data.Cameras = log->ReadCameras();
  const fs::path logDir = fs::path(logPath).parent_path();
  for (vis4gs::Camera& c : data.Cameras)
  {
    if (!c.ImagePath.empty() && c.ImagePath.rfind("/images/", 0) != 0 &&
      fs::path(c.ImagePath).is_relative())
    {
      c.ImagePath = (logDir / c.ImagePath).string();
    }
  }
  const vis4gs::TrainingImageProvider images = Vis4GSLogImages(log);
  for (std::size_t v = 0; v < data.Cameras.size(); ++v)
  {
    vis4gs::Image image;
    if (!images(v, data.Cameras[v], image))
    {
      throw std::runtime_error(
        logPath + ": camera " + data.Cameras[v].Name + " has no image to fine-tune against");
    }
    data.Images.push_back(std::move(image.Pixels));
  }

  vis4gs::TrainerOptions options;
  options.Iterations = source + iterations;
  options.ShDegree = snapshot.ShDegree;
  options.Seed = static_cast<std::uint64_t>(std::stoull(args.Get("seed")));
  options.Threads = args.GetInt("threads");
  if (!args.GetFlag("free-positions"))
  {
    options.PositionLrInit = options.PositionLrFinal = 0; // Adam then leaves them untouched
  }
  if (!args.GetFlag("densify"))
  {
    options.DensifyUntilIter = 0; // also skips the opacity resets, as in the reference
  }
  options.SnapshotInterval = iterations;
  options.MetricsInterval = std::max(1, iterations / 10);
  options.EmbedImages = log->HasImages();
  for (const vis4gs::Camera& c : data.Cameras)
  {
    options.ImagePaths.push_back(c.ImagePath);
  }
  options.ProgressInterval = 0;
  vis4gs::Trainer trainer(std::move(data), options, snapshot, source, prunes);

  const fs::path output = args.Get("output");
  fs::create_directories(output);
  const fs::path logOut = output / "repaired.h5";
  const fs::path partial = output / ".repaired.h5.partial";
  {
    vis4gs::TrainingLogWriterOptions wo;
    wo.Producer = std::string("vis4gs repair ") + VIS4GS_VERSION;
    wo.Scene = log->GetHeader().Scene;
    wo.ShDegree = options.ShDegree;
    wo.Iterations = options.Iterations;
    vis4gs::TrainingLogWriter writer(partial.string(), wo);
    trainer.Run(&writer);
  }
  fs::rename(partial, logOut);

  // The figures of the three states, per view.
  vis4gs::RemovalEffectOptions measure;
  measure.Threads = options.Threads;
  const std::vector<vis4gs::Camera>& cameras = trainer.GetData().Cameras;
  const std::vector<vis4gs::ViewMetrics> figures[3] = { vis4gs::MeasureViewMetrics(
                                                          snapshot, cameras, measure, images),
    vis4gs::MeasureViewMetrics(cleaned, cameras, measure, images),
    vis4gs::MeasureViewMetrics(trainer.GetCloud(), cameras, measure, images) };
  std::ostringstream csv;
  csv << "view,split,psnr_source,psnr_deleted,psnr_repaired,ssim_source,ssim_deleted,"
         "ssim_repaired,l1_source,l1_deleted,l1_repaired\n"
      << std::setprecision(9);
  for (const char* split : { "train", "test" })
  {
    double sum[9] = {};
    std::size_t views = 0;
    for (std::size_t v = 0; v < cameras.size(); ++v)
    {
      if (SplitName(cameras[v]) == std::string(split) && std::isfinite(figures[0][v].L1))
      {
        for (int s = 0; s < 3; ++s)
        {
          sum[s] += figures[s][v].Psnr;
          sum[3 + s] += figures[s][v].Ssim;
          sum[6 + s] += figures[s][v].L1;
        }
        ++views;
      }
    }
    if (views == 0)
    {
      continue;
    }
    csv << "mean," << split;
    for (double x : sum)
    {
      csv << "," << x / views;
    }
    csv << "\n";
    std::cout << "vis4gs repair: " << split << " PSNR " << sum[0] / views << " dB, after deleting "
              << sum[1] / views << " dB, after " << iterations << " iterations " << sum[2] / views
              << " dB (" << views << " views)\n";
  }
  for (std::size_t v = 0; v < cameras.size(); ++v)
  {
    if (std::isfinite(figures[0][v].L1))
    {
      csv << cameras[v].Name << "," << SplitName(cameras[v]);
      for (int s = 0; s < 3; ++s)
      {
        csv << "," << figures[s][v].Psnr;
      }
      for (int s = 0; s < 3; ++s)
      {
        csv << "," << figures[s][v].Ssim;
      }
      for (int s = 0; s < 3; ++s)
      {
        csv << "," << figures[s][v].L1;
      }
      csv << "\n";
    }
  }
  const fs::path csvPath = output / "repair.csv";
  {
    std::ofstream out(csvPath.string() + ".partial");
    out << csv.str();
    out.close();
    if (!out)
    {
      throw std::runtime_error(csvPath.string() + ": could not be written");
    }
  }
  fs::rename(csvPath.string() + ".partial", csvPath);
  std::cout << "vis4gs repair: wrote " << logOut.string() << " (" << prunes.size()
            << " prune events at iteration " << source << ", iterations " << source + 1 << ".."
            << options.Iterations << ") and " << csvPath.string() << "\n";
  return 0;
}
} // namespace

VIS4GS_REGISTER_COMMAND("repair",
  "Fine-tune a cleaned scene with the built-in trainer; the log records the deletion as prunes.",
  Define,
  Run)

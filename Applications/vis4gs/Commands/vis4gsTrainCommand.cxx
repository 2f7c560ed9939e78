// SPDX-License-Identifier: BSD-3-Clause
// `vis4gs train DATASET --output=LOG.h5`: the built-in CPU 3DGS trainer (Core/Training) with
// genealogy logging. DATASET is a COLMAP folder (sparse/0 + images) or a synthetic scene
// description (.json, Data/Scenes/). Ctrl-C stops after the current iteration and leaves a
// valid log with a final snapshot.
#include "Vis4GSCommand.h"

#include "Trainer.h"
#include "TrainingData.h"
#include "TrainingLogWriter.h"

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>

namespace
{
std::atomic<bool> StopRequested{ false };

extern "C" void OnInterrupt(int)
{
  StopRequested = true;
}

void Define(Vis4GSArguments& args)
{
  args.AddPositional("DATASET",
    "COLMAP dataset folder, NeRF-synthetic / instant-ngp folder or transforms*.json, or a "
    "synthetic scene description (.json).");
  args.AddOption("output",
    "LOG.h5",
    "training-log.h5",
    "Training log to write (HDF5, DESIGN §3, format version 2 in SWMR mode), as LOG.h5.tmp "
    "while the trainer runs: `vis4gs view LOG.h5 --follow` finds it and shows it live.");
  args.AddOption("iterations", "N", "30000", "Number of training iterations.");
  args.AddFlag("schedule-scale",
    false,
    "Scale every interval of the 30000-iteration schedule (densify from/until/interval, "
    "opacity reset, SH increase, position LR steps) by N/30000.");
  args.AddOption("snapshot-interval",
    "N",
    "1000",
    "Write a snapshot every N iterations (plus iteration 0 and the last).");
  args.AddOption("metrics-interval", "N", "100", "Evaluate train/test metrics every N iterations.");
  args.AddOption("metrics-views", "N", "0", "Training views used for train metrics; 0: all.");
  args.AddOption("seed", "S", "0", "Random seed (camera order, split samples).");
  args.AddOption("resolution",
    "R",
    "-1",
    "COLMAP: the reference trainer's --resolution (-1: at most 1600 px wide; 1, 2, 4, 8: "
    "divide; else a width). Synthetic: image width (keeps the aspect); -1: the description's.");
  args.AddOption("sh-degree", "D", "3", "Maximum SH degree (0..3).");
  args.AddOption("snapshot-sh-degree",
    "D",
    "-1",
    "SH degree written in the snapshots before the last one (the last holds all); -1: all.");
  args.AddOption("densify-grad-threshold", "G", "0.0002", "ADC view-space gradient threshold.");
  args.AddFlag("eval", true, "COLMAP: hold out every 8th view as a test view.");
  args.AddFlag("white-background", false, "Train on a white background.");
  args.AddFlag("embed-images", false, "Embed the training images into the log (/images).");
  args.AddOption("snapshot-deflate",
    "L",
    "0",
    "Deflate level 0..9 of the snapshot datasets (0: uncompressed, the fastest history reads; "
    "the tables and images are always deflated).");
}

int Run(const Vis4GSArguments& args)
{
  const std::string dataset = args.GetPositional("DATASET");
  const std::string output = args.Get("output");
  const int iterations = args.GetInt("iterations");
  if (iterations <= 0)
  {
    throw std::runtime_error("--iterations must be positive");
  }
  if (args.GetInt("snapshot-deflate") < 0 || args.GetInt("snapshot-deflate") > 9)
  {
    throw std::runtime_error("--snapshot-deflate must be a level 0..9");
  }
  // Like `vis4gs demo --output=DIR`: a log in a folder that does not exist yet creates it.
  const auto outputDir = std::filesystem::absolute(output).parent_path();
  std::error_code mkdirError;
  std::filesystem::create_directories(outputDir, mkdirError);
  if (mkdirError)
  {
    throw std::runtime_error(
      outputDir.string() + ": cannot create the output folder (" + mkdirError.message() + ")");
  }
  vis4gs::TrainerOptions options;
  options.Iterations = iterations;
  if (args.GetFlag("schedule-scale"))
  {
    options.ScaleSchedule(iterations);
  }
  options.SnapshotInterval = args.GetInt("snapshot-interval");
  options.MetricsInterval = args.GetInt("metrics-interval");
  options.MetricsMaxTrainViews = args.GetInt("metrics-views");
  options.Seed = static_cast<std::uint64_t>(std::stoull(args.Get("seed")));
  options.ShDegree = args.GetInt("sh-degree");
  options.SnapshotShDegree = args.GetInt("snapshot-sh-degree");
  options.DensifyGradThreshold = args.GetDouble("densify-grad-threshold");
  options.WhiteBackground = args.GetFlag("white-background");
  options.EmbedImages = args.GetFlag("embed-images");
  options.Threads = args.GetInt("threads");
  options.ProgressInterval = std::max(1, std::min(100, iterations / 20));

  vis4gs::TrainingDataOptions dataOptions;
  dataOptions.Resolution = args.GetInt("resolution");
  dataOptions.Eval = args.GetFlag("eval");
  dataOptions.WhiteBackground = options.WhiteBackground;
  dataOptions.Threads = options.Threads;
  std::cout << "vis4gs train: loading " << dataset << "\n" << std::flush;
  vis4gs::TrainingData data = vis4gs::LoadTrainingData(dataset, dataOptions);
  // Image paths relative to the log, when they are files.
  if (!options.EmbedImages)
  {
    const auto logDir = std::filesystem::absolute(output).parent_path();
    for (const vis4gs::Camera& cam : data.Cameras)
    {
      std::string p = cam.ImagePath;
      if (!p.empty() && std::filesystem::exists(p))
      {
        p = std::filesystem::relative(std::filesystem::absolute(p), logDir).string();
      }
      options.ImagePaths.push_back(p);
    }
  }
  std::size_t train = 0;
  for (const auto& c : data.Cameras)
  {
    train += c.Split == vis4gs::CameraSplit::Train;
  }
  vis4gs::Trainer trainer(std::move(data), options);
  const auto& o = trainer.GetOptions();
  std::cout << "vis4gs train: " << train << " training and "
            << trainer.GetData().Cameras.size() - train << " test views, "
            << trainer.GetCloud().Count << " initial Gaussians, scene extent "
            << trainer.GetSceneExtent() << "\n"
            << "  schedule: " << o.Iterations << " iterations, densify " << o.DensifyFromIter
            << ".." << o.DensifyUntilIter << " every " << o.DensificationInterval
            << ", opacity reset every " << o.OpacityResetInterval << ", SH degree +1 every "
            << o.ShIncreaseInterval << "\n"
            << std::flush;

  if (o.DensificationInterval < 10 && o.DensifyUntilIter > o.DensifyFromIter)
  {
    std::cout << "  note: densifying every " << o.DensificationInterval
              << " iterations (few optimiser steps in between) makes the Gaussian count grow "
                 "very fast; consider more iterations or a larger --densify-grad-threshold\n";
  }
  vis4gs::TrainingLogWriterOptions wo;
  wo.Producer = std::string("vis4gs train ") + VIS4GS_VERSION;
  wo.Scene = trainer.GetData().Name;
  wo.ShDegree = o.ShDegree;
  wo.Iterations = o.Iterations;
  wo.SnapshotDeflateLevel = args.GetInt("snapshot-deflate");
  // Written as <output>.tmp and renamed when the training ends (interrupted too), so that a
  // failure (a full disk, a read-only folder) leaves no partial log and an earlier log at
  // --output as it was (issue 35); in HDF5's SWMR mode (format version 2), so that `vis4gs
  // view --follow` (which finds the .tmp) and `vis4gs analyze LOG.h5.tmp` read the live log
  // without blocking the trainer, and a killed trainer leaves a temporary that reads up to its
  // last flush (issue 32).
  wo.WriteToTemporary = true;
  wo.Swmr = true;
  wo.FlushIntervalSeconds = 1.0; // metrics and events show within about 2 s when followed
  // Each flush deflates the partly filled last chunk of each /events column again: 4096 rows
  // (32 KiB) instead of 65536 make a flush about 10 times cheaper (performance-history.md).
  wo.TableChunkRows = 4096;
  vis4gs::TrainingLogWriter log(output, wo);
  std::cout << "vis4gs train: writing " << output << ".tmp (renamed to " << output
            << " at the end; follow it with `vis4gs view " << output << " --follow`)\n"
            << std::flush;

  StopRequested = false;
  auto previous = std::signal(SIGINT, OnInterrupt);
  const int last = trainer.Run(&log,
    &StopRequested,
    [](const vis4gs::TrainerProgress& p)
    {
      const double rate = p.Elapsed > 0 ? p.Iteration / p.Elapsed : 0.0;
      std::printf("  iteration %6d/%d  Gaussians %8zu  loss %.5f  SH %d  %.1f it/s  %.0f s\n",
        p.Iteration,
        p.Iterations,
        p.NumGaussians,
        p.Loss,
        p.ActiveShDegree,
        rate,
        p.Elapsed);
      std::fflush(stdout);
    });
  std::signal(SIGINT, previous);
  const auto& t = trainer.GetTimings();
  std::cout << "vis4gs train: "
            << (StopRequested ? "interrupted at iteration " : "finished at iteration ") << last
            << ", " << trainer.GetCloud().Count << " Gaussians, " << trainer.GetEvents().Size()
            << " densification events\n"
            << "  time: forward " << t.Forward << " s, loss " << t.Loss << " s, backward "
            << t.Backward << " s, optimizer " << t.Optimizer << " s, densification " << t.Densify
            << " s, logging " << t.Logging << " s\n"
            << "vis4gs train: wrote " << output << "\n";
  return StopRequested ? 130 : 0;
}
}

VIS4GS_REGISTER_COMMAND("train",
  "Train a 3DGS scene on the CPU and write its training log with every densification event.",
  Define,
  Run)

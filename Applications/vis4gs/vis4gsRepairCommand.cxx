// SPDX-License-Identifier: BSD-3-Clause
// `vis4gs repair LOG CLEANED --iterations=N --output=DIR` (issue 20): fine-tunes a cleaned scene
// (analyze --select=RULE --delete's cleaned.ply, or any scene holding a subset of the ids of a
// snapshot of LOG) for N iterations with the built-in trainer, positions fixed and densification
// off by default, and writes DIR/repaired.h5, a training log that continues LOG: its first event
// rows are the deletion as prune events at the snapshot's iteration, its iterations follow it,
// so the genealogy of the repaired run stays one tree. DIR/repair.csv holds PSNR, SSIM and L1
// per view of the snapshot, the cleaned scene and the repaired one (RemovalEffect.h's figures).
#include "Vis4GSCommand.h"

#include "FineTune.h"
#include "TrainingLogReader.h"
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
  std::cout << "vis4gs repair: " << logPath << ", snapshot of iteration " << source << ": "
            << snapshot.Count << " Gaussians, " << prunes.size() << " deleted in " << cleanedPath
            << "\n";

  // The log's cameras (image paths relative to the log made absolute) and images.
  std::vector<vis4gs::Camera> cameras = log->ReadCameras();
  const fs::path logDir = fs::path(logPath).parent_path();
  for (vis4gs::Camera& c : cameras)
  {
    if (!c.ImagePath.empty() && c.ImagePath.rfind("/images/", 0) != 0 &&
      fs::path(c.ImagePath).is_relative())
    {
      c.ImagePath = (logDir / c.ImagePath).string();
    }
  }
  const fs::path output = args.Get("output");
  fs::create_directories(output);
  const fs::path logOut = output / "repaired.h5";
  vis4gs::FineTuneOptions options;
  options.Iterations = iterations;
  options.FreePositions = args.GetFlag("free-positions");
  options.Densify = args.GetFlag("densify");
  options.Seed = static_cast<std::uint64_t>(std::stoull(args.Get("seed")));
  options.Threads = args.GetInt("threads");
  options.LogPath = logOut.string();
  options.Producer = std::string("vis4gs repair ") + VIS4GS_VERSION;
  options.Scene = log->GetHeader().Scene;
  options.EmbedImages = log->HasImages();
  const vis4gs::FineTuneResult result =
    vis4gs::FineTune(snapshot, source, removed, cameras, Vis4GSLogImages(log), options);

  std::ostringstream csv;
  const std::vector<std::string>& columns = vis4gs::FineTuneFigureColumns();
  for (std::size_t c = 0; c < columns.size(); ++c)
  {
    csv << (c > 0 ? "," : "") << columns[c];
  }
  csv << "\n" << std::setprecision(9);
  for (const vis4gs::FineTuneFigureRow& row : vis4gs::FineTuneFigureRows(result, cameras))
  {
    csv << row.View << "," << row.Split;
    for (double x : row.Values)
    {
      csv << "," << x;
    }
    csv << "\n";
    if (row.View == "mean")
    {
      std::cout << "vis4gs repair: " << row.Split << " PSNR " << row.Values[0]
                << " dB, after deleting " << row.Values[1] << " dB, after " << iterations
                << " iterations " << row.Values[2] << " dB\n";
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
            << result.LastIteration << ", " << result.TrainSeconds / iterations
            << " s per iteration) and " << csvPath.string() << "\n";
  return 0;
}
} // namespace

VIS4GS_REGISTER_COMMAND("repair",
  "Fine-tune a cleaned scene with the built-in trainer; the log records the deletion as prunes.",
  Define,
  Run)

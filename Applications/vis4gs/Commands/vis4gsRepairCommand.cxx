// SPDX-License-Identifier: BSD-3-Clause
// `vis4gs repair SOURCE CLEANED --iterations=N --output=DIR` (issue 20): fine-tunes a cleaned
// scene (analyze --select=RULE --delete's cleaned.ply, or any scene holding a subset of the ids
// of SOURCE) for N iterations with the built-in trainer, positions fixed and densification off
// by default, and writes DIR/repaired.h5, a training log whose first event rows are the
// deletion as prune events at the source iteration and whose iterations follow it, so the
// genealogy of the repaired run stays one tree. SOURCE is a training log (a snapshot of it,
// its cameras and images) or a scene file with cameras and images found as `vis4gs analyze`
// finds them (--cameras, --images; source iteration 0 unless --iteration). DIR/repair.csv
// holds PSNR, SSIM and L1 per view of the source, the cleaned scene and the repaired one
// (RemovalEffect.h's figures).
#include "Vis4GSCommand.h"
#include "Vis4GSSceneCameras.h"
#include "Vis4GSStagingFolder.h"

#include "FineTune.h"
#include "GaussianIO.h"
#include "TrainingLogReader.h"
#include "Vis4GSStateFiles.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
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
  args.AddPositional("SOURCE",
    "What the cleaned scene comes from: a training log (.h5), or a scene file (3DGS .ply, "
    ".splat, ...; its id property, else its row numbers, are the ids) with cameras and images.");
  args.AddPositional("CLEANED",
    "The cleaned scene: a PLY whose id property names the Gaussians kept (analyze --delete's "
    "cleaned.ply), a subset of the source's ids.");
  args.AddOption("iteration",
    "N",
    "-1",
    "Log: the snapshot the scene was cleaned from (the nearest logged), -1: the last. Scene "
    "file: its iteration number in the repaired log, -1: 0.");
  args.AddOption("cameras",
    "FILE|DIR",
    "",
    "Scene file only: cameras.json, a COLMAP dataset folder (sparse/0 + images) or a "
    "transforms*.json (file or folder). Default: cameras.json beside the scene or two folders "
    "up (the trainer's model folder).");
  args.AddOption("images",
    "DIR",
    "",
    "Scene file only: folder of training images, matched to cameras by name. Default: the "
    "cameras' own image paths.");
  args.AddOption("iterations", "N", "50", "Fine-tuning iterations.");
  args.AddOption("warmup",
    "W",
    "10",
    "Learning-rate warm-up: the j-th of the first W iterations uses j/(W+1) of every learning "
    "rate, so that fresh Adam moments do not make a converged scene worse first; 0: none.");
  args.AddFlag("free-positions", false, "Optimise the positions too (default: fixed).");
  args.AddFlag("densify",
    false,
    "Keep the trainer's densification schedule (default: off, and no opacity reset).");
  args.AddOption("seed", "S", "0", "Random seed (camera order).");
  args.AddOption("metrics-interval",
    "N",
    "0",
    "The repaired log's train/test metrics every N iterations (every view rendered); 0: at "
    "most 10 rows, the first and last from the repair's own measurement.");
  args.AddOption("output", "DIR", "vis4gs-repair", "Folder for repaired.h5 and repair.csv.");
}

int Run(const Vis4GSArguments& args)
{
  const std::string sourcePath = args.GetPositional("SOURCE");
  const int iterations = args.GetInt("iterations");
  if (iterations <= 0)
  {
    throw std::runtime_error("--iterations must be positive");
  }
  const int warmup = args.GetInt("warmup");
  if (warmup < 0)
  {
    throw std::runtime_error("--warmup must be >= 0");
  }
  const int wanted = args.GetInt("iteration");
  std::shared_ptr<vis4gs::TrainingLogReader> log; // null for a scene file
  vis4gs::GaussianCloud snapshot;
  std::vector<vis4gs::Camera> cameras;
  int source = 0;
  if (Vis4GSIsLogPath(sourcePath))
  {
    log = std::make_shared<vis4gs::TrainingLogReader>(sourcePath);
    if (log->GetSnapshotIterations().empty() || !log->HasCameras())
    {
      throw std::runtime_error(sourcePath + ": the training log needs a snapshot and /cameras");
    }
    vis4gs::SnapshotReadOptions readOptions;
    readOptions.ShDegree = -1;
    snapshot = log->ReadNearestSnapshot(
      wanted < 0 ? log->GetSnapshotIterations().back() : wanted, readOptions, &source);
    // The log's cameras, image paths relative to the log made absolute.
    cameras = log->ReadCameras();
    const fs::path logDir = fs::path(sourcePath).parent_path();
    for (vis4gs::Camera& c : cameras)
    {
      if (!c.ImagePath.empty() && c.ImagePath.rfind("/images/", 0) != 0 &&
        fs::path(c.ImagePath).is_relative())
      {
        c.ImagePath = (logDir / c.ImagePath).string();
      }
    }
  }
  else
  {
    snapshot = Vis4GSReadSceneWithIds(sourcePath, "repair");
    if (snapshot.Ids.empty()) // no id property: the rows are the ids, as for every reader
    {
      snapshot.Ids.resize(snapshot.Count);
      for (std::size_t i = 0; i < snapshot.Count; ++i)
      {
        snapshot.Ids[i] = static_cast<std::int64_t>(i);
      }
    }
    source = std::max(wanted, 0);
    cameras = Vis4GSFindSceneCameras(sourcePath, args.Get("cameras"));
    if (cameras.empty())
    {
      throw std::runtime_error(sourcePath +
        ": no cameras found; give --cameras=cameras.json, a COLMAP folder or a transforms.json");
    }
    if (!args.Get("images").empty())
    {
      Vis4GSAttachImagesByName(cameras, args.Get("images"));
    }
    const std::string imageSource =
      args.Get("images").empty() ? "the cameras of " + sourcePath : args.Get("images");
    for (const vis4gs::Camera& c : cameras)
    {
      std::error_code ec;
      if (c.ImagePath.empty() || !fs::is_regular_file(c.ImagePath, ec))
      {
        throw std::runtime_error(imageSource + ": no image for camera \"" + c.Name + "\"" +
          (c.ImagePath.empty() ? std::string() : " (" + c.ImagePath + " is no file)") +
          "; give --images=DIR");
      }
    }
  }
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
      " ids that " +
      (log ? "the snapshot of iteration " + std::to_string(source) + " of " : std::string()) +
      sourcePath + " lacks (is it cleaned from this source, with its id property?)");
  }
  std::cout << "vis4gs repair: " << sourcePath << ", iteration " << source << ": " << snapshot.Count
            << " Gaussians, " << prunes.size() << " deleted in " << cleanedPath << "\n";

  const fs::path output = args.Get("output");
  // Both outputs are moved into place together: a failure leaves an earlier run's pair as it was.
  Vis4GSStagingFolder staging(output, "repair");
  const fs::path logOut = output / "repaired.h5";
  vis4gs::FineTuneOptions options;
  options.Iterations = iterations;
  options.WarmupIterations = warmup;
  options.MetricsInterval = std::max(0, args.GetInt("metrics-interval"));
  options.FreePositions = args.GetFlag("free-positions");
  options.Densify = args.GetFlag("densify");
  options.Seed = static_cast<std::uint64_t>(std::stoull(args.Get("seed")));
  options.Threads = args.GetInt("threads");
  options.LogPath = (staging.Get() / logOut.filename()).string();
  options.Producer = std::string("vis4gs repair ") + VIS4GS_VERSION;
  // A scene file's images are embedded so that the repaired log stands on its own.
  options.Scene = log ? log->GetHeader().Scene : fs::path(sourcePath).stem().string();
  options.EmbedImages = log ? log->HasImages() : true;
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
  vis4gs::WriteTextFile((staging.Get() / csvPath.filename()).string(), csv.str());
  staging.Commit();
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

// SPDX-License-Identifier: BSD-3-Clause
#include "FineTune.h"

#include "RemovalEffect.h"
#include "Trainer.h"
#include "TrainingLogWriter.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

namespace vis4gs
{
namespace
{
using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double>(b - a).count();
}

// Removes the temporary log unless it was renamed onto its final path (cancelled, or an error
// thrown before the end).
struct PartialFile
{
  std::string Path;
  ~PartialFile()
  {
    if (!this->Path.empty())
    {
      std::remove(this->Path.c_str());
    }
  }
};

// "dir/.name.partial" for "dir/name": the same file system, so the rename is atomic.
std::string PartialPath(const std::string& path)
{
  const std::size_t slash = path.find_last_of('/');
  const std::size_t start = slash == std::string::npos ? 0 : slash + 1;
  return path.substr(0, start) + "." + path.substr(start) + ".partial";
}

const char* SplitName(const Camera& camera)
{
  return camera.Split == CameraSplit::Train ? "train" : "test";
}
} // namespace

FineTuneResult FineTune(const GaussianCloud& snapshot,
  int sourceIteration,
  const std::vector<std::uint8_t>& removed,
  const std::vector<Camera>& cameras,
  const TrainingImageProvider& images,
  const FineTuneOptions& options)
{
  if (options.Iterations <= 0)
  {
    throw std::invalid_argument("FineTune: the number of iterations must be positive");
  }
  if (removed.size() != snapshot.Count)
  {
    throw std::invalid_argument("FineTune: the removal mask has " + std::to_string(removed.size()) +
      " entries for " + std::to_string(snapshot.Count) + " Gaussians");
  }
  if (snapshot.Ids.size() != snapshot.Count)
  {
    throw std::invalid_argument("FineTune: the snapshot has no Gaussian ids");
  }
  if (!images)
  {
    throw std::invalid_argument("FineTune: no training images");
  }
  FineTuneResult result;
  result.SourceIteration = sourceIteration;
  for (std::size_t i = 0; i < snapshot.Count; ++i)
  {
    if (removed[i])
    {
      result.Pruned.push_back(snapshot.GetId(i));
    }
  }
  result.Cleaned = RemoveGaussians(snapshot, removed);

  // The training data: the cameras and their images (each read once; the measurement below
  // reads the trainer's copy).
  TrainingData data;
  data.Name = options.Scene;
  data.Cameras = cameras;
  for (std::size_t v = 0; v < cameras.size(); ++v)
  {
    Image image;
    if (!images(v, cameras[v], image))
    {
      throw std::runtime_error("camera " + cameras[v].Name + " has no image to fine-tune against");
    }
    data.Images.push_back(std::move(image.Pixels));
  }

  TrainerOptions trainerOptions;
  trainerOptions.Iterations = sourceIteration + options.Iterations;
  trainerOptions.ShDegree = snapshot.ShDegree;
  trainerOptions.Seed = options.Seed;
  trainerOptions.Threads = options.Threads;
  if (!options.FreePositions)
  {
    trainerOptions.PositionLrInit = trainerOptions.PositionLrFinal = 0; // Adam leaves them
  }
  if (!options.Densify)
  {
    trainerOptions.DensifyUntilIter = 0; // also skips the opacity resets, as in the reference
  }
  trainerOptions.SnapshotInterval = options.Iterations;
  trainerOptions.MetricsInterval = std::max(1, options.Iterations / 10);
  trainerOptions.EmbedImages = options.EmbedImages;
  for (const Camera& c : cameras)
  {
    trainerOptions.ImagePaths.push_back(c.ImagePath);
  }
  trainerOptions.ProgressInterval = 1;
  Trainer trainer(std::move(data), trainerOptions, snapshot, sourceIteration, result.Pruned);

  std::atomic<bool> stop(false);
  std::function<void(const TrainerProgress&)> progress;
  if (options.Progress)
  {
    progress = [&](const TrainerProgress& p)
    {
      if (!options.Progress(p.Iteration - sourceIteration, options.Iterations))
      {
        stop = true;
      }
    };
  }
  const auto start = Clock::now();
  if (options.LogPath.empty())
  {
    result.LastIteration = trainer.Run(nullptr, &stop, progress);
  }
  else
  {
    PartialFile partial{ PartialPath(options.LogPath) };
    {
      TrainingLogWriterOptions wo;
      wo.Producer = options.Producer;
      wo.Scene = options.Scene;
      wo.ShDegree = trainerOptions.ShDegree;
      wo.Iterations = trainerOptions.Iterations;
      TrainingLogWriter writer(partial.Path, wo);
      result.LastIteration = trainer.Run(&writer, &stop, progress);
    }
    if (!stop)
    {
      if (std::rename(partial.Path.c_str(), options.LogPath.c_str()) != 0)
      {
        throw std::runtime_error(options.LogPath + ": could not be written");
      }
      partial.Path.clear();
    }
  }
  result.TrainSeconds = Seconds(start, Clock::now());
  result.Cancelled = stop;
  result.Repaired = trainer.GetCloud();
  if (result.Cancelled || !options.Measure)
  {
    return result;
  }

  const auto a = Clock::now();
  RemovalEffectOptions measure;
  measure.Threads = options.Threads;
  const TrainingData& loaded = trainer.GetData();
  const TrainingImageProvider cached = [&loaded](std::size_t v, const Camera& c, Image& image)
  {
    image.Width = c.Width;
    image.Height = c.Height;
    image.Channels = 3;
    image.Pixels = loaded.Images[v];
    return true;
  };
  result.Source = MeasureViewMetrics(snapshot, loaded.Cameras, measure, cached);
  result.Deleted = MeasureViewMetrics(result.Cleaned, loaded.Cameras, measure, cached);
  result.RepairedFigures = MeasureViewMetrics(result.Repaired, loaded.Cameras, measure, cached);
  result.MeasureSeconds = Seconds(a, Clock::now());
  return result;
}

const std::vector<std::string>& FineTuneFigureColumns()
{
  static const std::vector<std::string> columns{ "view",
    "split",
    "psnr_source",
    "psnr_deleted",
    "psnr_repaired",
    "ssim_source",
    "ssim_deleted",
    "ssim_repaired",
    "l1_source",
    "l1_deleted",
    "l1_repaired" };
  return columns;
}

std::vector<FineTuneFigureRow> FineTuneFigureRows(const FineTuneResult& result,
  const std::vector<Camera>& cameras)
{
  std::vector<FineTuneFigureRow> rows;
  if (result.Source.size() != cameras.size() || result.Deleted.size() != cameras.size() ||
    result.RepairedFigures.size() != cameras.size())
  {
    return rows;
  }
  const std::vector<ViewMetrics>* figures[3] = {
    &result.Source, &result.Deleted, &result.RepairedFigures
  };
  auto values = [&](std::size_t v, double* out)
  {
    for (int s = 0; s < 3; ++s)
    {
      const ViewMetrics& m = (*figures[s])[v];
      out[s] = m.Psnr;
      out[3 + s] = m.Ssim;
      out[6 + s] = m.L1;
    }
  };
  for (const char* split : { "train", "test" })
  {
    FineTuneFigureRow mean{ "mean", split, {} };
    std::size_t views = 0;
    for (std::size_t v = 0; v < cameras.size(); ++v)
    {
      if (SplitName(cameras[v]) == std::string(split) && std::isfinite(result.Source[v].L1))
      {
        double x[9];
        values(v, x);
        for (int k = 0; k < 9; ++k)
        {
          mean.Values[k] += x[k];
        }
        ++views;
      }
    }
    if (views > 0)
    {
      for (double& x : mean.Values)
      {
        x /= static_cast<double>(views);
      }
      rows.push_back(mean);
    }
  }
  for (std::size_t v = 0; v < cameras.size(); ++v)
  {
    if (std::isfinite(result.Source[v].L1))
    {
      FineTuneFigureRow row{ cameras[v].Name, SplitName(cameras[v]), {} };
      values(v, row.Values);
      rows.push_back(row);
    }
  }
  return rows;
}

} // namespace vis4gs

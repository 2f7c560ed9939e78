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

// The trainer's metrics row (Trainer::Evaluate()) from per-view figures: the means over the
// views of @p split that have an image (as repair.csv's mean rows), the loss from them as the
// trainer weighs it; NaN without such a view.
MetricsRow MeanMetrics(const std::vector<ViewMetrics>& figures,
  const std::vector<Camera>& cameras,
  CameraSplit split,
  double lambdaDssim)
{
  MetricsRow row;
  std::size_t views = 0;
  const ViewMetrics mean = MeanViewMetrics(figures, cameras, split, &views);
  if (views > 0)
  {
    row.L1 = mean.L1;
    row.Ssim = mean.Ssim;
    row.Psnr = mean.Psnr;
    row.Loss = (1.0 - lambdaDssim) * row.L1 + lambdaDssim * (1.0 - row.Ssim);
  }
  return row;
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
  trainerOptions.LrWarmupIterations = std::max(0, options.WarmupIterations);
  trainerOptions.SnapshotInterval = options.Iterations;
  // By default at most 10 metrics rows in between (the trainer logs the iterations that are
  // multiples of the interval), none for a short run: its first and last rows are FineTune's
  // own measurement below.
  trainerOptions.MetricsInterval = options.MetricsInterval > 0 ? options.MetricsInterval
    : options.Iterations <= 10                                 ? 0
                                                               : (options.Iterations + 9) / 10;
  trainerOptions.EmbedImages = options.EmbedImages;
  for (const Camera& c : cameras)
  {
    trainerOptions.ImagePaths.push_back(c.ImagePath);
  }
  trainerOptions.ProgressInterval = 1;
  Trainer trainer(std::move(data), trainerOptions, snapshot, sourceIteration, result.Pruned);

  // The source and deleted states are measured before the iterations: the log's metrics row
  // of the source iteration (the deleted scene) is then their means, not a second render.
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
  if (options.Measure)
  {
    const auto a = Clock::now();
    // The source per tile; the deleted state re-renders only the tiles the deletion changes
    // (RemovalEffect.h: the same figures as a full render of the cleaned scene, bit for bit).
    measure.TileBaseline = MeasureRemovalBaseline(snapshot, loaded.Cameras, measure, cached);
    result.Source.assign(loaded.Cameras.size(), ViewMetrics());
    result.Deleted.assign(loaded.Cameras.size(), ViewMetrics());
    for (std::size_t v = 0; v < loaded.Cameras.size(); ++v)
    {
      if (!measure.TileBaseline.Views[v].Empty())
      {
        result.Source[v] = measure.TileBaseline.Views[v].Metrics();
      }
    }
    const RemovalEffect deletion =
      MeasureRemovalEffect(snapshot, removed, loaded.Cameras, measure, cached);
    for (const RemovalViewEffect& view : deletion.Views)
    {
      if (view.HasImage)
      {
        result.Deleted[view.CameraIndex] = view.After;
      }
    }
    measure.TileBaseline = RemovalBaseline();
    result.MeasureSeconds = Seconds(a, Clock::now());
  }
  // The log's metrics rows: the deleted state's and the repaired state's from the figures
  // above and below (measured once); the trainer renders the ones in between.
  double repairedSeconds = 0;
  const int lastIteration = trainerOptions.Iterations;
  trainer.SetMetricsSource(
    [&](const Trainer& t, MetricsRow& train, MetricsRow& test)
    {
      const std::vector<ViewMetrics>* figures = nullptr;
      if (options.Measure && t.GetIteration() == sourceIteration)
      {
        figures = &result.Deleted;
      }
      else if (options.Measure && t.GetIteration() == lastIteration)
      {
        const auto a = Clock::now();
        result.RepairedFigures = MeasureViewMetrics(t.GetCloud(), loaded.Cameras, measure, cached);
        repairedSeconds += Seconds(a, Clock::now());
        figures = &result.RepairedFigures;
      }
      if (!figures)
      {
        result.MetricsRenders += static_cast<int>(loaded.Cameras.size());
        return false;
      }
      train = MeanMetrics(*figures, loaded.Cameras, CameraSplit::Train, trainerOptions.LambdaDssim);
      test = MeanMetrics(*figures, loaded.Cameras, CameraSplit::Test, trainerOptions.LambdaDssim);
      return true;
    });

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
  result.TrainSeconds = Seconds(start, Clock::now()) - repairedSeconds;
  result.MeasureSeconds += repairedSeconds;
  result.Cancelled = stop;
  result.Repaired = trainer.GetCloud();
  if (result.Cancelled)
  {
    result.Source.clear();
    result.Deleted.clear();
    result.RepairedFigures.clear();
  }
  else if (options.Measure && result.RepairedFigures.empty()) // no log: not measured yet
  {
    const auto a = Clock::now();
    result.RepairedFigures =
      MeasureViewMetrics(result.Repaired, trainer.GetData().Cameras, measure, cached);
    result.MeasureSeconds += Seconds(a, Clock::now());
  }
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

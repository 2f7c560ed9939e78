// SPDX-License-Identifier: BSD-3-Clause
// Writes a diagnosis case of Mip-NeRF 360 Bicycle's shape for whole-process benchmarks of
// `vis4gs analyze` and `vis4gs view` (issue 31): N Gaussians of SH degree D (scene.ply,
// MakeBenchmarkScene), V training cameras of W x H on a ring around them (cameras.json) and
// their images (images/<name>.png) rendered from a PERTURBED copy of the scene, so that the
// blur and needle scores are not trivial, and optionally (--log) a training log of the same
// size (training.h5): the cameras, a SYNTHETIC 30k-iteration event history of about 10M events
// at the default size (Genealogy/SyntheticEventLog.h) and the scene as its last snapshot, ids
// being the Gaussians alive after the events. SYNTHETIC data, deterministic for a given seed.
//
// The perturbation (per Gaussian, from the seed): 2 % get their DC colour shifted by 0.3 in
// one channel, 2 % are moved by 4 of their largest scales, 1 % are absent from the images
// (opacity 0): colour errors, blur and floaters the scores should find.
//
// Usage: MakeBicycleCase OUT_DIR [--gaussians=6100000] [--views=194] [--width=1237]
//        [--height=822] [--sh-degree=3] [--seed=1] [--log] [--threads=0]
#include "BenchmarkScene.h"
#include "CameraJson.h"
#include "GaussianIO.h"
#include "GaussianMath.h"
#include "ImageIO.h"
#include "MultiViewRenderer.h"
#include "SyntheticEventLog.h"
#include "TrainingLogWriter.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{

using Clock = std::chrono::steady_clock;

double Since(Clock::time_point t)
{
  return std::chrono::duration<double>(Clock::now() - t).count();
}

std::map<std::string, std::string> ParseOptions(int argc, char* argv[])
{
  const std::map<std::string, std::string> defaults{ { "gaussians", "6100000" },
    { "views", "194" },
    { "width", "1237" },
    { "height", "822" },
    { "sh-degree", "3" },
    { "seed", "1" },
    { "log", "0" },
    { "threads", "0" } };
  std::map<std::string, std::string> options = defaults;
  for (int i = 2; i < argc; ++i)
  {
    std::string arg = argv[i];
    if (arg.rfind("--", 0) != 0)
    {
      throw std::invalid_argument("unexpected argument '" + arg + "'");
    }
    arg = arg.substr(2);
    const auto eq = arg.find('=');
    const std::string key = arg.substr(0, eq);
    if (!defaults.count(key))
    {
      throw std::invalid_argument("unknown option --" + key);
    }
    options[key] = eq == std::string::npos ? "1" : arg.substr(eq + 1);
  }
  return options;
}

long long Number(const std::map<std::string, std::string>& options,
  const std::string& key,
  long long lowest)
{
  char* end = nullptr;
  const std::string& text = options.at(key);
  const long long value = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || value < lowest)
  {
    throw std::invalid_argument(
      "--" + key + "=" + text + ": expected an integer of at least " + std::to_string(lowest));
  }
  return value;
}

// The images' scene: what MakeBicycleCase's file comment says, in place.
void Perturb(vis4gs::GaussianCloud& cloud, unsigned seed)
{
  std::mt19937 rng(seed + 7919u);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const std::size_t K = static_cast<std::size_t>(cloud.ShCoefficientCount());
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    const float r = u(rng);
    const float a = u(rng), b = u(rng), c = u(rng);
    if (r < 0.02f)
    {
      const std::size_t channel = static_cast<std::size_t>(3 * a) % 3;
      cloud.SH[3 * K * i + channel] += static_cast<float>(0.3 / vis4gs::sh::C0);
    }
    else if (r < 0.04f)
    {
      const float* ls = &cloud.LogScales[3 * i];
      const float step = 4.0f * std::exp(std::max({ ls[0], ls[1], ls[2] }));
      cloud.Positions[3 * i] += step * (2 * a - 1);
      cloud.Positions[3 * i + 1] += step * (2 * b - 1);
      cloud.Positions[3 * i + 2] += step * (2 * c - 1);
    }
    else if (r < 0.05f)
    {
      cloud.OpacityLogits[i] = -1e30f; // sigmoid 0: absent from the images
    }
  }
}

// Gaussians alive after @p log's events (initial ids 0..N0-1, children numbered on).
std::vector<std::int64_t> AliveIds(const vis4gs::SyntheticEventLog& log)
{
  std::int64_t next = log.InitialGaussians;
  for (std::int64_t child : log.Events.Child)
  {
    next = std::max(next, child + 1);
  }
  std::vector<char> dead(static_cast<std::size_t>(next), 0);
  for (std::size_t e = 0; e < log.Events.Size(); ++e)
  {
    if (log.Events.Kind[e] !=
      static_cast<std::uint8_t>(vis4gs::EventKind::Clone)) // split, prune end it
    {
      dead[static_cast<std::size_t>(log.Events.Parent[e])] = 1;
    }
  }
  std::vector<std::int64_t> alive;
  for (std::int64_t id = 0; id < next; ++id)
  {
    if (!dead[static_cast<std::size_t>(id)])
    {
      alive.push_back(id);
    }
  }
  return alive;
}

} // namespace

int main(int argc, char* argv[])
{
  if (argc < 2 || std::string(argv[1]).rfind("--", 0) == 0)
  {
    std::fprintf(stderr,
      "usage: MakeBicycleCase OUT_DIR [--gaussians=6100000] [--views=194] [--width=1237] "
      "[--height=822] [--sh-degree=3] [--seed=1] [--log] [--threads=0]\n");
    return 1;
  }
  namespace fs = std::filesystem;
  try
  {
    const auto options = ParseOptions(argc, argv);
    const std::size_t n = static_cast<std::size_t>(Number(options, "gaussians", 1));
    const int views = static_cast<int>(Number(options, "views", 1));
    const int width = static_cast<int>(Number(options, "width", 16));
    const int height = static_cast<int>(Number(options, "height", 16));
    const int degree = static_cast<int>(Number(options, "sh-degree", 0));
    const unsigned seed = static_cast<unsigned>(Number(options, "seed", 0));
    const bool log = Number(options, "log", 0) != 0;
    const int threads = static_cast<int>(Number(options, "threads", 0));
    if (degree > 3)
    {
      throw std::invalid_argument("--sh-degree must be 0..3");
    }
    const fs::path out = argv[1];
    fs::create_directories(out / "images");
    const auto start = Clock::now();

    vis4gs::GaussianCloud cloud = vis4gs::MakeBenchmarkScene(n, degree, seed);
    std::vector<vis4gs::Camera> cameras;
    for (int v = 0; v < views; ++v)
    {
      // A ring around the scene, elevations alternating a little as a hand-held capture's.
      vis4gs::Camera c =
        vis4gs::MakeBenchmarkCamera(width, height, 6.283185307179586 * v / views + 0.1 * (v % 3));
      char name[32];
      std::snprintf(name, sizeof(name), "view_%04d", v);
      c.Name = name;
      c.ImagePath = "images/" + c.Name + ".png";
      cameras.push_back(c);
    }
    vis4gs::WriteGaussianPly((out / "scene.ply").string(), cloud);
    vis4gs::WriteCamerasJson((out / "cameras.json").string(), cameras);
    const double tScene = Since(start);

    auto t0 = Clock::now();
    if (log)
    {
      vis4gs::SyntheticLogParameters p;
      const double share = static_cast<double>(n) / 6.1e6;
      p.FinalGaussians = static_cast<std::int64_t>(n);
      p.InitialGaussians = std::max<std::int64_t>(1, std::llround(54275 * share));
      // Bicycle's 10M ever born for 4.89M alive, kept in proportion.
      p.TotalGaussians = std::max<std::int64_t>(
        p.FinalGaussians + 1, std::llround(static_cast<double>(n) * 1e7 / 4.89e6));
      p.Seed = seed;
      vis4gs::SyntheticEventLog events = vis4gs::GenerateSyntheticEventLog(p);
      cloud.Ids = AliveIds(events);
      // The generator lands within a few Gaussians of the final count: prunes (or clones) at
      // the last event's iteration make it exactly the scene's.
      const std::int32_t last = events.Events.Size() ? events.Events.Iteration.back() : 0;
      std::int64_t next = p.TotalGaussians;
      for (std::int64_t child : events.Events.Child)
      {
        next = std::max(next, child + 1);
      }
      for (std::size_t k = n; k < cloud.Ids.size(); ++k)
      {
        events.Events.Append({ last, vis4gs::EventKind::Prune, cloud.Ids[k], -1 });
        ++events.Prunes;
      }
      for (std::size_t k = cloud.Ids.size(); k < n; ++k)
      {
        events.Events.Append(
          { last, vis4gs::EventKind::Clone, cloud.Ids[k % cloud.Ids.size()], next++ });
        ++events.Clones;
      }
      cloud.Ids = AliveIds(events);
      if (cloud.Ids.size() != n)
      {
        throw std::runtime_error("the event history leaves " + std::to_string(cloud.Ids.size()) +
          " Gaussians alive, not " + std::to_string(n));
      }
      vis4gs::TrainingLogWriterOptions wo;
      wo.Producer = "MakeBicycleCase (SYNTHETIC)";
      wo.Scene = "synthetic bicycle-shaped case";
      wo.ShDegree = degree;
      wo.Iterations = p.Iterations;
      vis4gs::TrainingLogWriter writer((out / "training.h5").string(), wo);
      writer.WriteCameras(cameras);
      writer.AppendEvents(events.Events);
      vis4gs::MetricsRow row;
      row.Iteration = p.Iterations;
      row.NumGaussians = static_cast<std::int64_t>(n);
      writer.AppendMetrics(row);
      writer.WriteSnapshot(p.Iterations, cloud);
      writer.Close();
      cloud.Ids.clear();
      std::printf("%s: SYNTHETIC log, %zu events (%lld clones, %lld splits, %lld prunes), "
                  "last snapshot of %zu Gaussians\n",
        (out / "training.h5").c_str(),
        events.Events.Size(),
        static_cast<long long>(events.Clones),
        static_cast<long long>(events.Splits),
        static_cast<long long>(events.Prunes),
        n);
    }
    const double tLog = Since(t0);

    t0 = Clock::now();
    Perturb(cloud, seed);
    vis4gs::RasterSettings raster;
    raster.Threads = threads;
    vis4gs::MultiViewRenderer renderer(cloud, raster);
    vis4gs::RasterImage<float> render;
    vis4gs::Image image;
    for (const vis4gs::Camera& c : cameras)
    {
      renderer.Render(c, render);
      image.Width = render.Width;
      image.Height = render.Height;
      image.Channels = 3;
      image.Pixels = render.Color;
      vis4gs::WritePng((out / c.ImagePath).string(), image);
    }
    const double tImages = Since(t0);
    std::printf("%s: SYNTHETIC case, %zu Gaussians of SH degree %d, %d views of %dx%d with "
                "images of a perturbed copy; scene %.1f s, log %.1f s, images %.1f s\n",
      out.c_str(),
      n,
      degree,
      views,
      width,
      height,
      tScene,
      tLog,
      tImages);
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "MakeBicycleCase: %s\n", e.what());
    return 1;
  }
  return 0;
}

// SPDX-License-Identifier: BSD-3-Clause
// Benchmark of the diagnostic scores (issue 5).
//
//   BenchmarkArtifactScores perf [--gaussians=N] [--views=V] [--width=W] [--height=H]
//       [--straight-views=K] [--only=coverage|blur|footprint|render-cost [--isa=I] [--shared=0|1]]
//     Coverage and blur+needle (loss maps at 1/4) of N synthetic Gaussians in V views, timed,
//     next to a straightforward implementation (projection + brute-force footprint scan of
//     every tile rectangle) measured on K views in the same run and extrapolated to V.
//     --only=render-cost: the render-cost pass (RenderCost and CostPerContribution) on the V
//     views, next to a plain render of each view (its floor) and the straightforward per-pixel
//     walk of the tile lists in scalar code on K views (extrapolated), whose counts it checks.
//
//   BenchmarkArtifactScores case --case=DIR [--scores=LIST] [--views=K] [--shared=0|1]
//       [--loss-resolution=F] [--coverage-resolution=F]
//     The scores of a case on disk (MakeBicycleCase's scene.ply, cameras.json, images/) on
//     its first K training views (0: all), with the wall time of each phase, the process's
//     CPU time and peak RSS, and a checksum of every score.
//
//   BenchmarkArtifactScores accuracy --output=FILE.md --plot=FILE.png [--colmap=DIR]
//       [--scene=PLY --cameras=JSON --images=DIR] [--log=LOG.h5] [--gaussians=N] [--views=V]
//     Sweeps every mode on (a) a synthetic scene whose images are rendered from a perturbed
//     copy of it and (b) a real scene (a COLMAP dataset with Gaussians initialised from its
//     points3D as the reference trainer does, or any PLY + cameras.json + images) and (c) a
//     training log (its last snapshot, training views and images; e.g. the embedded demo),
//     and writes the accuracy-vs-runtime report (Markdown) and its plot (PNG).
#include "ArtifactScores.h"
#include "BenchmarkPlot.h"
#include "BenchmarkSceneUtils.h"
#include "CameraJson.h"
#include "ColmapDataset.h"
#include "FastCoverage.h"
#include "GaussianIO.h"
#include "ImageIO.h"
#include "TrainingLogReader.h"

#include <omp.h>
#include <sys/resource.h>

#include <cstdlib>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace vis4gs;

namespace
{

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t)
{
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// Process CPU time (all threads, user + system, getrusage). On a shared, overloaded machine
// wall time says little; CPU time / threads is what the same run takes on idle cores (when
// it scales).
double CpuSeconds()
{
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
    1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

std::string LoadAverage()
{
  double l[3] = { 0, 0, 0 };
  if (getloadavg(l, 3) != 3)
  {
    return "n/a";
  }
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.2f %.2f %.2f", l[0], l[1], l[2]);
  return buf;
}

struct Timer
{
  Clock::time_point Wall = Clock::now();
  double Cpu = CpuSeconds();
  double WallSeconds() const { return Since(this->Wall); }
  double CpuSecondsUsed() const { return CpuSeconds() - this->Cpu; }
  std::string Describe(int threads) const
  {
    char buf[160];
    std::snprintf(buf,
      sizeof buf,
      "wall %8.2f s, CPU %8.2f s (CPU/%d threads %7.2f s)",
      this->WallSeconds(),
      this->CpuSecondsUsed(),
      threads,
      this->CpuSecondsUsed() / threads);
    return buf;
  }
};

std::map<std::string, std::string> ParseArgs(int argc, char** argv, int first)
{
  std::map<std::string, std::string> a;
  for (int i = first; i < argc; ++i)
  {
    std::string s = argv[i];
    if (s.rfind("--", 0) == 0)
    {
      const auto eq = s.find('=');
      a[s.substr(2, eq == std::string::npos ? std::string::npos : eq - 2)] =
        eq == std::string::npos ? "1" : s.substr(eq + 1);
    }
  }
  return a;
}

long Get(const std::map<std::string, std::string>& a, const std::string& k, long def)
{
  const auto it = a.find(k);
  return it == a.end() ? def : std::stol(it->second);
}

// Cheap procedural training images for timing (their content does not change the work).
TrainingImageProvider PatternImages()
{
  return [](std::size_t index, const Camera& camera, Image& image)
  {
    image.Width = camera.Width;
    image.Height = camera.Height;
    image.Channels = 3;
    image.Pixels.resize(static_cast<std::size_t>(camera.Width) * camera.Height * 3);
    for (int y = 0; y < camera.Height; ++y)
    {
      for (int x = 0; x < camera.Width; ++x)
      {
        float* p = &image.Pixels[(static_cast<std::size_t>(y) * camera.Width + x) * 3];
        p[0] = 0.5f + 0.5f * std::sin(0.05f * x + index);
        p[1] = 0.5f + 0.5f * std::cos(0.03f * y);
        p[2] = 0.3f;
      }
    }
    return true;
  };
}

// Images rendered from another cloud (the perturbed "ground truth"), cached per view.
struct RenderedImages
{
  std::vector<Image> Images;
  RenderedImages(const GaussianCloud& truth, const std::vector<Camera>& cameras)
  {
    for (const Camera& c : cameras)
    {
      const auto r = Rasterize<float>(truth, c);
      Image im;
      im.Width = c.Width;
      im.Height = c.Height;
      im.Channels = 3;
      im.Pixels = r.Color;
      for (float& v : im.Pixels)
      {
        v = std::min(1.0f, std::max(0.0f, v));
      }
      this->Images.push_back(std::move(im));
    }
  }
  TrainingImageProvider Provider() const
  {
    return [this](std::size_t index, const Camera&, Image& image)
    {
      image = this->Images[index];
      return true;
    };
  }
};

// The straightforward render cost of one view: every pixel walks its tile's list as the
// reference forward pass does, in scalar code, counting evaluations and summing alpha*T.
void StraightRenderCost(const GaussianCloud& cloud,
  const Camera& camera,
  std::vector<double>& cost,
  std::vector<double>& contribution)
{
  RasterSettings rs;
  rs.ComputeColors = false;
  const ViewProjection<float> proj = ProjectGaussians<float>(cloud, camera, rs);
  const TileBins bins = BinGaussians(proj, 0);
  for (int y = 0; y < camera.Height; ++y)
  {
    for (int x = 0; x < camera.Width; ++x)
    {
      const std::size_t tile = static_cast<std::size_t>(y / 16) * bins.TilesX + x / 16;
      float T = 1;
      for (std::uint64_t k = bins.Offsets[tile]; k < bins.Offsets[tile + 1]; ++k)
      {
        const std::uint32_t id = bins.Ids[k];
        const auto& g = proj.Gaussians[id];
        cost[id] += 1;
        const float alpha = raster::KernelAlpha<float>(g.Opacity,
          raster::KernelPower<float>(
            g.U, g.V, g.ConicA, g.ConicB, g.ConicC, static_cast<float>(x), static_cast<float>(y)));
        if (alpha < 0)
        {
          continue;
        }
        const float next = T * (1 - alpha);
        if (next < static_cast<float>(raster::TransmittanceStop))
        {
          break;
        }
        contribution[id] += static_cast<double>(alpha * T);
        T = next;
      }
    }
  }
}

int RenderCostPerf(const GaussianCloud& cloud,
  const std::vector<Camera>& cameras,
  int straightViews,
  int threads)
{
  const std::size_t n = cloud.Count;
  std::printf("load average before: %s\n", LoadAverage().c_str());
  Timer t;
  for (const Camera& c : cameras)
  {
    const auto image = Rasterize<float>(cloud, c);
    if (image.Width != c.Width)
    {
      return 1;
    }
  }
  std::printf("plain render (the floor), %zu views: %s [load %s]\n",
    cameras.size(),
    t.Describe(threads).c_str(),
    LoadAverage().c_str());
  ScoreSettings settings;
  settings.Request = ScoreRequest{ false, false, false, false, true, true };
  t = Timer();
  const GaussianScores s = ComputeGaussianScores(cloud, cameras, settings);
  std::printf("render-cost pass (R and R/A), %zu views: %s [load %s]; %zu of %zu Gaussians "
              "never evaluated\n",
    cameras.size(),
    t.Describe(threads).c_str(),
    LoadAverage().c_str(),
    s.NotEvaluatedCount,
    n);
  const std::vector<Camera> few(
    cameras.begin(), cameras.begin() + std::min<std::size_t>(cameras.size(), straightViews));
  std::vector<double> cost(n, 0.0), contribution(n, 0.0);
  t = Timer();
  for (const Camera& c : few)
  {
    StraightRenderCost(cloud, c, cost, contribution);
  }
  const double scale = static_cast<double>(cameras.size()) / few.size();
  std::printf("straightforward scalar per-pixel walk, %zu views: %s; extrapolated to %zu views: "
              "wall %.2f s, CPU %.2f s\n",
    few.size(),
    t.Describe(1).c_str(),
    cameras.size(),
    t.WallSeconds() * scale,
    t.CpuSecondsUsed() * scale);
  const GaussianScores check = ComputeGaussianScores(cloud, few, settings);
  std::size_t same = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    same += check.RenderCost[i] == cost[i] ? 1 : 0;
  }
  std::printf("render cost of the %zu views: equal to the walk's for %zu of %zu Gaussians\n",
    few.size(),
    same,
    n);
  return 0;
}

int Perf(const std::map<std::string, std::string>& args)
{
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  const std::size_t n = static_cast<std::size_t>(Get(args, "gaussians", 1000000));
  const int views = static_cast<int>(Get(args, "views", 200));
  const int width = static_cast<int>(Get(args, "width", 1280));
  const int height = static_cast<int>(Get(args, "height", 720));
  const int straight = static_cast<int>(Get(args, "straight-views", 4));
  const int threads = omp_get_max_threads();
  std::printf("threads: %d\nscene: %zu Gaussians (synthetic shell, log-scale -5.8), %d views of "
              "%dx%d\n",
    threads,
    n,
    views,
    width,
    height);
  const GaussianCloud cloud = bench::ShellScene(n, 1, -5.8);
  const std::vector<Camera> cameras = bench::RingCameras(views, 3.0, width, height);
  // --only=coverage|blur: time one task's fast path alone (for profiling).
  const std::string only = args.count("only") ? args.at("only") : std::string();
  if (only == "render-cost")
  {
    return RenderCostPerf(cloud, cameras, straight, threads);
  }
  if (only == "footprint")
  {
    // Footprint pass alone on one view at 1/4 resolution: vector vs scalar, map vs counts.
    const Camera view = cameras[0].Resized(LossMapSize(width, 4), LossMapSize(height, 4));
    RasterSettings rs;
    rs.ComputeColors = false;
    const ViewProjection<float> proj = ProjectGaussians<float>(cloud, view, rs);
    std::vector<float> map(static_cast<std::size_t>(view.Width) * view.Height);
    for (std::size_t i = 0; i < map.size(); ++i)
    {
      map[i] = static_cast<float>((i * 7919) % 1000) / 1000.0f;
    }
    FootprintStats ref;
    const long onlyIsa = Get(args, "isa", -1);
    for (int isa : { 1, 0 })
    {
      if (onlyIsa >= 0 && isa != onlyIsa)
      {
        continue;
      }
      for (bool withMap : { false, true })
      {
        FootprintOptions fo;
        fo.KernelIsa = isa;
        Timer t;
        FootprintStats st;
        for (int rep = 0; rep < 5; ++rep)
        {
          st = ComputeFootprints(proj, fo, withMap ? map.data() : nullptr);
        }
        std::printf("footprints %s, %s: per view %s; |Omega| %llu, evaluated %llu\n",
          isa == 1 ? "scalar" : "vector",
          withMap ? "map sums" : "counts  ",
          t.Describe(threads * 5).c_str(),
          static_cast<unsigned long long>(st.TotalPixels),
          static_cast<unsigned long long>(st.EvaluatedPixels));
        if (withMap && isa == 1)
        {
          ref = st;
        }
        if (withMap && isa == 0)
        {
          std::printf("vector == scalar: counts %s, sums %s\n",
            st.PixelCount == ref.PixelCount ? "yes" : "NO",
            st.MapSum == ref.MapSum ? "yes" : "NO");
        }
      }
    }
    return 0;
  }
  if (!only.empty())
  {
    ScoreSettings settings;
    settings.Request = { only == "coverage", only == "blur", only == "blur", false };
    settings.LossResolution = only == "blur" ? 4 : 1;
    settings.KernelIsa = static_cast<int>(Get(args, "isa", 0));
    settings.SharedProjection = Get(args, "shared", 1) != 0;
    std::printf("load average before: %s\n", LoadAverage().c_str());
    Timer t;
    const GaussianScores s = only == "blur"
      ? ComputeGaussianScores(cloud, cameras, settings, PatternImages())
      : ComputeGaussianScores(cloud, cameras, settings);
    const auto& tm = s.Timings;
    std::printf("%s%s, %d views: %s [load %s] (wall: images %.2f, projection %.2f, rendering "
                "%.2f, loss maps %.2f, footprints %.2f, sums %.2f)\n",
      only.c_str(),
      only == "blur" ? (settings.SharedProjection ? " (shared projection)" : " (per-view path)")
                     : "",
      views,
      t.Describe(threads).c_str(),
      LoadAverage().c_str(),
      tm.Images,
      tm.Projection,
      tm.Rendering,
      tm.LossMaps,
      tm.Footprints,
      tm.Accumulation);
    return 0;
  }
  std::vector<Camera> few(cameras.begin(), cameras.begin() + std::min(views, straight));
  const double scale = static_cast<double>(views) / few.size();

  ScoreSettings coverage;
  coverage.Request = { true, false, false, false };
  std::printf("load average before: %s\n", LoadAverage().c_str());
  Timer t;
  const GaussianScores fast = ComputeGaussianScores(cloud, cameras, coverage);
  std::printf("coverage, NEW: vectorised fused early-exit (exact), %d views: %s [load %s]\n",
    views,
    t.Describe(threads).c_str(),
    LoadAverage().c_str());
  // The previous implementation: the scalar fused early-exit test (KernelIsa 1), in
  // batches of 16 views as ComputeGaussianScores called it.
  t = Timer();
  std::vector<std::uint32_t> previous(n, 0);
  for (std::size_t first = 0; first < cameras.size(); first += 16)
  {
    const std::vector<Camera> batch(
      cameras.begin() + first, cameras.begin() + std::min(cameras.size(), first + 16));
    CountVisibleViews(cloud, batch, FootprintMode::Rasterizer, previous, 0, 1.0, 1);
  }
  std::printf("coverage, BEFORE: scalar fused early-exit, batches of 16 views, %d views: %s "
              "[load %s]; same counts: %s\n",
    views,
    t.Describe(threads).c_str(),
    LoadAverage().c_str(),
    previous == fast.CoverageViews ? "yes" : "NO");

  // Straightforward: ProjectGaussians + brute-force footprint counts of every tile rectangle.
  ScoreSettings brute = coverage;
  brute.BruteForceFootprints = true;
  t = Timer();
  const GaussianScores slow = ComputeGaussianScores(cloud, few, brute);
  std::printf("coverage, projection + brute-force footprints, %zu views: %s; x%.0f -> CPU/%d "
              "%.1f s for %d views\n",
    few.size(),
    t.Describe(threads).c_str(),
    scale,
    threads,
    t.CpuSecondsUsed() / threads * scale,
    views);
  // Projection + span footprint counts (the rasteriser's ComputeFootprints).
  t = Timer();
  std::vector<std::uint32_t> check(n, 0);
  for (const Camera& c : few)
  {
    RasterSettings rs;
    rs.ComputeColors = false;
    const auto stats = ComputeFootprints(ProjectGaussians<float>(cloud, c, rs));
    for (std::size_t g = 0; g < n; ++g)
    {
      check[g] += stats.PixelCount[g] >= 1 ? 1 : 0;
    }
  }
  std::printf("coverage, projection + span footprint counts, %zu views: %s; x%.0f -> CPU/%d "
              "%.1f s for %d views\n",
    few.size(),
    t.Describe(threads).c_str(),
    scale,
    threads,
    t.CpuSecondsUsed() / threads * scale,
    views);
  const GaussianScores fastOnFew = ComputeGaussianScores(cloud, few, coverage);
  std::printf("fused == brute force on %zu views: %s; == span counts: %s\n",
    few.size(),
    fastOnFew.CoverageViews == slow.CoverageViews ? "yes" : "NO",
    fastOnFew.CoverageViews == check ? "yes" : "NO");

  ScoreSettings scores;
  scores.Request = { false, true, true, false };
  scores.LossResolution = 4;
  GaussianScores s;
  // NEW: MultiViewRenderer (shared, vectorised projection; sorted per-Gaussian data).
  // BEFORE: the per-view ProjectGaussians + BinGaussians + CompositeTiles + ComputeFootprints
  // path of the previous implementation (same footprint kernels).
  for (int isa : { 0, 1 })
  {
    scores.SharedProjection = isa == 0;
    t = Timer();
    GaussianScores r = ComputeGaussianScores(cloud, cameras, scores, PatternImages());
    const auto& tm = r.Timings;
    std::printf("blur+needle at 1/4 (%dx%d), %s, %d views: %s [load %s] (wall: images "
                "%.2f, projection %.2f, rendering %.2f, loss maps %.2f, footprints %.2f, sums "
                "%.2f)\n",
      LossMapSize(width, 4),
      LossMapSize(height, 4),
      isa == 0 ? "NEW: shared multi-view projection" : "BEFORE: per-view projection",
      views,
      t.Describe(threads).c_str(),
      LoadAverage().c_str(),
      tm.Images,
      tm.Projection,
      tm.Rendering,
      tm.LossMaps,
      tm.Footprints,
      tm.Accumulation);
    if (isa == 0)
    {
      s = std::move(r);
    }
    else
    {
      std::printf("blur/needle scores identical (bitwise) before and after: %s\n",
        r.BlurScore == s.BlurScore && r.NeedleScore == s.NeedleScore ? "yes" : "NO");
    }
  }
  ScoreSettings scoresBrute = scores;
  scoresBrute.BruteForceFootprints = true;
  t = Timer();
  const GaussianScores sb = ComputeGaussianScores(cloud, few, scoresBrute, PatternImages());
  std::printf("blur+needle at 1/4, brute-force footprints, %zu views: %s; x%.0f -> CPU/%d %.1f s "
              "for %d views\n",
    few.size(),
    t.Describe(threads).c_str(),
    scale,
    threads,
    t.CpuSecondsUsed() / threads * scale,
    views);
  return fast.ViewCoverage.size() == n && sb.BlurScore.size() == n ? 0 : 1;
}

// ---------------------------------------------------------------------------------------
struct ErrorStats
{
  double Median = 0, Max = 0, Spearman = 1, TopOverlap = 1;
  std::size_t ZeroMismatch = 0;
};

std::vector<double> Ranks(const std::vector<double>& v)
{
  std::vector<std::size_t> order(v.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(
    order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
  std::vector<double> rank(v.size());
  for (std::size_t i = 0; i < order.size();)
  {
    std::size_t j = i;
    while (j + 1 < order.size() && v[order[j + 1]] == v[order[i]])
    {
      ++j;
    }
    const double r = 0.5 * (i + j);
    for (std::size_t k = i; k <= j; ++k)
    {
      rank[order[k]] = r;
    }
    i = j + 1;
  }
  return rank;
}

double Pearson(const std::vector<double>& a, const std::vector<double>& b)
{
  const double n = static_cast<double>(a.size());
  const double ma = std::accumulate(a.begin(), a.end(), 0.0) / n;
  const double mb = std::accumulate(b.begin(), b.end(), 0.0) / n;
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return saa > 0 && sbb > 0 ? sab / std::sqrt(saa * sbb) : (saa == sbb ? 1.0 : 0.0);
}

std::vector<std::size_t> Top(const std::vector<double>& v, std::size_t k)
{
  std::vector<std::size_t> order(v.size());
  std::iota(order.begin(), order.end(), 0);
  std::partial_sort(order.begin(),
    order.begin() + k,
    order.end(),
    [&](std::size_t a, std::size_t b) { return v[a] > v[b] || (v[a] == v[b] && a < b); });
  order.resize(k);
  std::sort(order.begin(), order.end());
  return order;
}

ErrorStats Compare(const std::vector<double>& exact, const std::vector<double>& approx)
{
  ErrorStats s;
  std::vector<double> rel;
  for (std::size_t i = 0; i < exact.size(); ++i)
  {
    if (exact[i] != 0)
    {
      rel.push_back(std::abs(approx[i] - exact[i]) / std::abs(exact[i]));
    }
    else if (approx[i] != 0)
    {
      ++s.ZeroMismatch;
    }
  }
  if (!rel.empty())
  {
    std::nth_element(rel.begin(), rel.begin() + rel.size() / 2, rel.end());
    s.Median = rel[rel.size() / 2];
    s.Max = *std::max_element(rel.begin(), rel.end());
  }
  s.Spearman = Pearson(Ranks(exact), Ranks(approx));
  const std::size_t k = std::max<std::size_t>(1, exact.size() / 100);
  const auto a = Top(exact, k), b = Top(approx, k);
  std::vector<std::size_t> both;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(both));
  s.TopOverlap = static_cast<double>(both.size()) / k;
  return s;
}

struct Mode
{
  std::string Name;
  ScoreSettings Settings;
};

std::vector<Mode> Modes()
{
  std::vector<Mode> m;
  m.push_back({ "exact (full res, all views, alpha footprint, double)", {} });
  ScoreSettings s;
  s.BruteForceFootprints = true;
  m.push_back({ "straightforward (brute-force footprints)", s });
  for (int f : { 2, 4, 8 })
  {
    s = {};
    s.LossResolution = f;
    s.CoverageResolution = f;
    m.push_back({ "loss maps and coverage at 1/" + std::to_string(f), s });
  }
  for (int k : { 2, 4 })
  {
    s = {};
    s.ViewStride = k;
    m.push_back({ "every " + std::string(k == 2 ? "2nd" : "4th") + " view", s });
  }
  s = {};
  s.Footprint = FootprintMode::Ellipse3Sigma;
  m.push_back({ "3-sigma ellipse footprints", s });
  s = {};
  s.Accumulation = FootprintAccumulation::Float;
  m.push_back({ "float accumulation", s });
  s = {};
  s.LossResolution = 4;
  s.ViewStride = 2;
  s.Accumulation = FootprintAccumulation::Float;
  m.push_back({ "1/4 res + every 2nd view + float", s });
  s = {};
  s.OcclusionThreshold = 0.01;
  m.push_back({ "occlusion-aware coverage (alpha*T >= 0.01)", s });
  return m;
}

struct SceneResult
{
  std::string Name, Description;
  std::vector<std::string> ModeNames;
  std::vector<double> Seconds;
  std::vector<std::array<ErrorStats, 3>> Errors; // coverage, blur, needle
  std::size_t Gaussians = 0, Views = 0;
};

SceneResult Sweep(const std::string& name,
  const std::string& description,
  const GaussianCloud& cloud,
  const std::vector<Camera>& cameras,
  const TrainingImageProvider& images)
{
  SceneResult r;
  r.Name = name;
  r.Description = description;
  r.Gaussians = cloud.Count;
  r.Views = cameras.size();
  GaussianScores exact;
  for (const Mode& mode : Modes())
  {
    const auto t0 = Clock::now();
    const GaussianScores s = ComputeGaussianScores(cloud, cameras, mode.Settings, images);
    const double t = Since(t0);
    if (r.ModeNames.empty())
    {
      exact = s;
    }
    r.ModeNames.push_back(mode.Name);
    r.Seconds.push_back(t);
    r.Errors.push_back({ Compare(exact.ViewCoverage, s.ViewCoverage),
      Compare(exact.BlurScore, s.BlurScore),
      Compare(exact.NeedleScore, s.NeedleScore) });
    std::cerr << name << ": " << mode.Name << ": " << t << " s\n";
  }
  return r;
}

std::string Fmt(double v, int precision = 3)
{
  std::ostringstream os;
  if (v != 0 && (std::abs(v) < 1e-3 || std::abs(v) >= 1e4))
  {
    os << std::scientific << std::setprecision(2) << v;
  }
  else
  {
    os << std::fixed << std::setprecision(precision) << v;
  }
  return os.str();
}

void WriteTable(std::ostream& md, const SceneResult& r)
{
  md << "### " << r.Name << "\n\n"
     << r.Description << " " << r.Gaussians << " Gaussians, " << r.Views << " training views.\n\n";
  md << "| # | mode | time (s) | speed-up | score | median rel. err | max rel. err | zero "
        "mismatches | Spearman | top-1% overlap |\n";
  md << "|---|---|---|---|---|---|---|---|---|---|\n";
  const char* scores[3] = { "coverage", "blur", "needle" };
  for (std::size_t m = 0; m < r.ModeNames.size(); ++m)
  {
    for (int k = 0; k < 3; ++k)
    {
      const ErrorStats& e = r.Errors[m][k];
      md << "| " << (k == 0 ? std::to_string(m + 1) : "") << " | " << (k == 0 ? r.ModeNames[m] : "")
         << " | " << (k == 0 ? Fmt(r.Seconds[m]) : "") << " | "
         << (k == 0 ? Fmt(r.Seconds[0] / r.Seconds[m], 2) + "x" : "") << " | " << scores[k] << " | "
         << Fmt(e.Median) << " | " << Fmt(e.Max) << " | " << e.ZeroMismatch << " | "
         << Fmt(e.Spearman, 4) << " | " << Fmt(e.TopOverlap, 3) << " |\n";
    }
  }
  md << "\n";
}

int Accuracy(const std::map<std::string, std::string>& args)
{
  const auto out = args.find("output");
  const auto plot = args.find("plot");
  if (out == args.end() || plot == args.end())
  {
    std::cerr << "accuracy needs --output=FILE.md and --plot=FILE.png\n";
    return 2;
  }
  std::vector<SceneResult> results;
  const auto totalStart = Clock::now();

  // (a) Synthetic scene, images rendered from a perturbed copy.
  {
    const std::size_t n = static_cast<std::size_t>(Get(args, "gaussians", 20000));
    const int views = static_cast<int>(Get(args, "views", 24));
    const GaussianCloud cloud = bench::ShellScene(n, 3, -4.3);
    const GaussianCloud truth = bench::Perturbed(cloud, 4, 1.0f);
    const auto cameras = bench::RingCameras(views, 3.0, 400, 300);
    const RenderedImages images(truth, cameras);
    results.push_back(Sweep("(a) synthetic shell",
      "Gaussians on a noisy sphere shell with 5% needles and 5% floaters (BenchmarkSceneUtils.h), "
      "ring of 400x300 cameras; training images rendered from a perturbed copy (positions, "
      "scales and colours jittered).",
      cloud,
      cameras,
      images.Provider()));
  }

  // (b) Real scene.
  if (args.count("scene"))
  {
    GaussianCloud cloud = ReadGaussianScene(args.at("scene"));
    std::vector<Camera> cameras = ReadCamerasJson(args.at("cameras"));
    AttachImages(cameras, args.at("images"));
    auto provider = [](std::size_t, const Camera& c, Image& image)
    {
      image = LoadTrainingImage(c);
      return true;
    };
    results.push_back(Sweep("(b) " + args.at("scene"),
      "A PLY scene with its cameras and images.",
      cloud,
      cameras,
      provider));
  }
  else if (args.count("colmap"))
  {
    const Dataset data = LoadColmapDataset(args.at("colmap"));
    const GaussianCloud cloud = bench::InitialiseFromPoints(data.PointPositions, data.PointColors);
    std::vector<Image> images;
    for (const Camera& c : data.Cameras)
    {
      images.push_back(LoadTrainingImage(c));
    }
    auto provider = [&images](std::size_t index, const Camera&, Image& image)
    {
      image = images[index];
      return true;
    };
    results.push_back(Sweep("(b) COLMAP statue (real photos)",
      "The COLMAP dataset `" + args.at("colmap") +
        "` (real photographs, PINHOLE cameras at training resolution). No trained 3DGS exists "
        "for it, so Gaussians are initialised from points3D exactly as the reference trainer "
        "initialises them (isotropic, scale from the mean squared distance to the 3 nearest "
        "neighbours, opacity 0.1, SH DC from the point colour): loss maps compare this "
        "untrained initialisation with the real photos.",
      cloud,
      data.Cameras,
      provider));
  }

  // (c) A training log: its last snapshot, its training views and their images (embedded in
  // the log or files next to it), as `vis4gs analyze LOG.h5` diagnoses it.
  if (args.count("log"))
  {
    const std::string path = args.at("log");
    const TrainingLogReader log(path);
    if (log.GetSnapshotIterations().empty() || !log.HasCameras())
    {
      throw std::runtime_error(path + ": the log needs a snapshot and /cameras");
    }
    SnapshotReadOptions options;
    options.ShDegree = -1;
    int iteration = 0;
    const GaussianCloud cloud =
      log.ReadNearestSnapshot(log.GetSnapshotIterations().back(), options, &iteration);
    std::vector<Camera> cameras;
    std::vector<Image> images;
    for (const Camera& c : log.ReadCameras())
    {
      if (c.Split != CameraSplit::Train)
      {
        continue;
      }
      const std::string prefix = "/images/";
      if (c.ImagePath.rfind(prefix, 0) == 0)
      {
        Image image;
        const std::vector<unsigned char> pixels =
          log.ReadImage(c.ImagePath.substr(prefix.size()), image.Width, image.Height);
        image.Pixels.resize(pixels.size());
        for (std::size_t i = 0; i < pixels.size(); ++i)
        {
          image.Pixels[i] = static_cast<float>(pixels[i]) / 255.0f;
        }
        images.push_back(std::move(image));
      }
      else
      {
        Camera located = c;
        if (!c.ImagePath.empty() && std::filesystem::path(c.ImagePath).is_relative())
        {
          located.ImagePath = (std::filesystem::path(path).parent_path() / c.ImagePath).string();
        }
        images.push_back(LoadTrainingImage(located));
      }
      cameras.push_back(c);
    }
    auto provider = [&images](std::size_t index, const Camera&, Image& image)
    {
      image = images[index];
      return true;
    };
    results.push_back(Sweep("(c) " + path,
      "A training log of the built-in trainer: the Gaussians of its last snapshot (iteration " +
        std::to_string(iteration) + ", " + std::to_string(cloud.Count) + " Gaussians, SH degree " +
        std::to_string(cloud.ShDegree) + "), its " + std::to_string(cameras.size()) +
        " training views and their images, as `vis4gs analyze` diagnoses it.",
      cloud,
      cameras,
      provider));
  }

  // Plot: run time (relative to exact) vs median relative error of the blur score.
  std::vector<bench::PlotPoint> points;
  for (std::size_t s = 0; s < results.size(); ++s)
  {
    const SceneResult& r = results[s];
    for (std::size_t m = 0; m < r.ModeNames.size(); ++m)
    {
      bench::PlotPoint p;
      p.X = r.Seconds[m] / r.Seconds[0];
      p.Y = std::max(1e-9, r.Errors[m][1].Median);
      p.Series = static_cast<int>(s);
      p.Label = std::to_string(m + 1);
      points.push_back(p);
    }
  }
  bench::ScatterPlot chart(760, 480);
  chart.Draw(points, -2, 1, -9, 3);
  chart.Write(plot->second);

  std::ostringstream md;
  md << "<!-- BEGIN MEASURED: written by BenchmarkArtifactScores accuracy; edit the source, not "
        "this section. -->\n";
  md << "## Measured accuracy against run time\n\n";
  md << "Machine: " << omp_get_max_threads()
     << " OpenMP threads on the 2-core development machine, load average " << LoadAverage()
     << " at the end of the sweep (small scenes: times of tens of milliseconds carry noise of "
        "tens of percent). Total sweep time "
     << Fmt(Since(totalStart), 1) << " s.\n\n";
  md << "Errors are against mode 1 (exact), per Gaussian: relative error |a - e| / |e| over the "
        "Gaussians whose exact score is not 0 (median and maximum); *zero mismatches* counts "
        "Gaussians whose exact score is 0 but the approximation's is not; Spearman rank "
        "correlation over all Gaussians (average ranks for ties); *top-1% overlap* is the "
        "fraction of the 1% highest-scoring Gaussians of the exact mode that the approximation "
        "also puts in its top 1%. Time is the whole ComputeGaussianScores call (coverage, blur, "
        "needle and needle shape; images were already in memory).\n\n";
  for (const SceneResult& r : results)
  {
    WriteTable(md, r);
  }
  md << "![run time vs median relative blur error](accuracy-vs-runtime.png)\n\n"
     << "The plot: x = run time relative to exact mode (log), y = median relative error of the "
        "blur score (log; errors below 1e-9, exact results included, are drawn at 1e-9); blue = "
        "scene (a), orange = scene (b), green = scene (c); "
        "the numbers are the mode numbers of the tables.\n";
  md << "<!-- END MEASURED -->\n";
  // Replace the measured section of an existing report (the hand-written text around it is
  // kept), or write a new file.
  std::string text;
  {
    std::ifstream in(out->second);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  const auto begin = text.find("<!-- BEGIN MEASURED");
  const auto endTag = std::string("<!-- END MEASURED -->\n");
  const auto end = text.find(endTag);
  if (begin != std::string::npos && end != std::string::npos && end > begin)
  {
    text = text.substr(0, begin) + md.str() + text.substr(end + endTag.size());
  }
  else
  {
    text += md.str();
  }
  std::ofstream file(out->second);
  file << text;
  if (!file)
  {
    throw std::runtime_error(out->second + ": could not be written");
  }
  std::cout << "wrote " << out->second << " and " << plot->second << "\n";
  return 0;
}

// The diagnosis of a case on disk (MakeBicycleCase's folder), phase by phase: the scores'
// timings (wall per phase, ScoreTimings), the process's CPU time and its peak RSS, for
// profiling one view (--views=K: the first K training views) or every view.
int Case(const std::map<std::string, std::string>& args)
{
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  const std::string folder = args.count("case") ? args.at("case") : ".";
  Timer readTimer;
  const GaussianCloud cloud = ReadGaussianScene(folder + "/scene.ply");
  std::vector<Camera> cameras = ReadCamerasJson(folder + "/cameras.json");
  AttachImages(cameras, folder + "/images");
  std::printf("read %zu Gaussians, %zu cameras: %s\n",
    cloud.Count,
    cameras.size(),
    readTimer.Describe(omp_get_max_threads()).c_str());
  ScoreSettings settings;
  const std::string scores =
    args.count("scores") ? args.at("scores") : "coverage,blur,needle,shape,render-cost";
  auto has = [&scores](const char* name) { return scores.find(name) != std::string::npos; };
  settings.Request.ViewCoverage = has("coverage");
  settings.Request.Blur = has("blur");
  settings.Request.Needle = has("needle");
  settings.Request.NeedleShape = has("shape");
  settings.Request.RenderCost = has("render-cost");
  settings.Request.CostPerContribution = has("cost-per-contribution");
  settings.LossResolution = static_cast<int>(Get(args, "loss-resolution", 1));
  settings.CoverageResolution = static_cast<int>(Get(args, "coverage-resolution", 1));
  settings.SharedProjection = Get(args, "shared", 1) != 0;
  const std::size_t views = static_cast<std::size_t>(Get(args, "views", 0));
  if (views > 0)
  {
    for (std::size_t i = 0; i < cameras.size() && settings.ViewList.size() < views; ++i)
    {
      if (cameras[i].Split == CameraSplit::Train)
      {
        settings.ViewList.push_back(i);
      }
    }
  }
  auto provider = [](std::size_t, const Camera& c, Image& image)
  {
    image = LoadTrainingImage(c);
    return true;
  };
  std::printf("load average before: %s\n", LoadAverage().c_str());
  Timer t;
  const GaussianScores result = ComputeGaussianScores(cloud, cameras, settings, provider);
  const double used = static_cast<double>(result.ViewsUsed);
  std::printf("scores (%s), %zu views: %s, %.3f s wall and %.3f s CPU a view\n",
    scores.c_str(),
    result.ViewsUsed,
    t.Describe(omp_get_max_threads()).c_str(),
    t.WallSeconds() / used,
    t.CpuSecondsUsed() / used);
  const ScoreTimings& s = result.Timings;
  std::printf("phases (wall, s): projection %.3f, rendering %.3f, images %.3f, loss maps %.3f, "
              "footprints %.3f, accumulation %.3f, needle shape %.3f, render cost %.3f, total "
              "%.3f\n",
    s.Projection,
    s.Rendering,
    s.Images,
    s.LossMaps,
    s.Footprints,
    s.Accumulation,
    s.NeedleShape,
    s.RenderCost,
    s.Total);
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  std::printf("peak RSS %.3f GB; load average after: %s\n",
    static_cast<double>(u.ru_maxrss) / 1e6,
    LoadAverage().c_str());
  // A checksum of every score, to compare variants of the implementation.
  for (const std::vector<double>* v : { &result.ViewCoverage,
         &result.BlurScore,
         &result.NeedleScore,
         &result.NeedleShape,
         &result.RenderCost,
         &result.CostPerContribution })
  {
    double sum = 0;
    for (double x : *v)
    {
      sum += std::isfinite(x) ? x : 0.0;
    }
    std::printf("sum %.17g over %zu\n", sum, v->size());
  }
  return 0;
}

} // namespace

int main(int argc, char** argv)
{
  if (argc < 2)
  {
    std::cerr << "usage: BenchmarkArtifactScores perf|case|accuracy [--options]\n";
    return 2;
  }
  try
  {
    const std::string what = argv[1];
    const auto args = ParseArgs(argc, argv, 2);
    if (what == "perf")
    {
      return Perf(args);
    }
    if (what == "case")
    {
      return Case(args);
    }
    if (what == "accuracy")
    {
      return Accuracy(args);
    }
    std::cerr << "unknown benchmark '" << what << "'\n";
    return 2;
  }
  catch (const std::exception& e)
  {
    std::cerr << "BenchmarkArtifactScores: " << e.what() << "\n";
    return 1;
  }
}

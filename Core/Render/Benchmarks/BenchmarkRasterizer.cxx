// SPDX-License-Identifier: BSD-3-Clause
// Rasteriser benchmark (prints figures; never run by CTest).
//
//   BenchmarkRasterizer [N ...]          render N Gaussians at 1280x720 with 1 and 2 threads
//   BenchmarkRasterizer --peak           measured single-precision FMA peak, 1 and 2 threads
//   BenchmarkRasterizer --naive          tiled vs naive per-pixel renderer on a small case
//   BenchmarkRasterizer --footprint N    footprint pass of N Gaussians at 320x180 (1/4 res)
//   BenchmarkRasterizer --frames N F T [V]  F frames of the scene view's synthetic scene
//                                        (Core/Splats, SH 0, orbiting camera, 1280x720) through
//                                        one RasterWorkspace with T threads; per-phase CPU
//                                        time of the process (robust on a shared machine);
//                                        V: cloud version (non-zero keeps the preparation)
//
// Synthetic scene: N Gaussians uniformly in the view frustum between z = 2 and z = 12, log
// scales normal around log(0.02 * (1e6/N)^(1/3)) (sd 0.7 per axis: anisotropic, heavy-tailed
// projected sizes; the mean spacing shrinks with N as in real reconstructions), opacity
// logits N(0, 2), random rotations, SH degree 3.
#include "BenchmarkScene.h"
#include "Footprint.h"
#include "GaussianMath.h"
#include "Rasterizer.h"

#include <immintrin.h>
#include <omp.h>
#include <sys/resource.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

using namespace vis4gs;

namespace
{

double Now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// CPU seconds used by the whole process (all threads): on a machine shared with other jobs
// this is a better measure of the work than wall time.
double CpuNow()
{
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

double PeakRssMiB()
{
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;
}

Camera BenchCamera(int w, int h)
{
  Camera c;
  c.Name = "bench";
  c.Width = w;
  c.Height = h;
  c.Fx = c.Fy = 1000.0 * w / 1280.0;
  c.Cx = w / 2.0;
  c.Cy = h / 2.0;
  return c;
}

GaussianCloud SyntheticScene(std::size_t n, unsigned seed)
{
  GaussianCloud cloud;
  cloud.Resize(n, 3);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  std::normal_distribution<float> nrm(0.0f, 1.0f);
  const float meanLog = std::log(0.02f * std::cbrt(1e6f / static_cast<float>(n)));
  const float tx = 1280.0f / 2000.0f, ty = 720.0f / 2000.0f; // tan(fov/2)
  for (std::size_t i = 0; i < n; ++i)
  {
    const float z = 2.0f + 10.0f * u01(rng);
    cloud.Positions[3 * i + 0] = (2 * u01(rng) - 1) * tx * z;
    cloud.Positions[3 * i + 1] = (2 * u01(rng) - 1) * ty * z;
    cloud.Positions[3 * i + 2] = z;
    for (int k = 0; k < 3; ++k)
    {
      cloud.LogScales[3 * i + k] = meanLog + 0.7f * nrm(rng);
    }
    for (int k = 0; k < 4; ++k)
    {
      cloud.Rotations[4 * i + k] = nrm(rng);
    }
    cloud.OpacityLogits[i] = 2.0f * nrm(rng);
    for (int k = 0; k < 48; ++k)
    {
      cloud.SH[48 * i + k] = (k < 3 ? 1.0f : 0.2f) * nrm(rng);
    }
  }
  return cloud;
}

//------------------------------------------------------------------------------
__attribute__((target("avx512f,fma"))) double FmaLoop512(long iters)
{
  __m512 a[10];
  const __m512 m = _mm512_set1_ps(0.9999999f), c = _mm512_set1_ps(1e-7f);
  for (int k = 0; k < 10; ++k)
  {
    a[k] = _mm512_set1_ps(1.0f + k);
  }
  for (long i = 0; i < iters; ++i)
  {
    for (int k = 0; k < 10; ++k)
    {
      a[k] = _mm512_fmadd_ps(a[k], m, c);
    }
  }
  float out[16];
  __m512 s = a[0];
  for (int k = 1; k < 10; ++k)
  {
    s = _mm512_add_ps(s, a[k]);
  }
  _mm512_storeu_ps(out, s);
  return out[0];
}

__attribute__((target("avx2,fma"))) double FmaLoop256(long iters)
{
  __m256 a[10];
  const __m256 m = _mm256_set1_ps(0.9999999f), c = _mm256_set1_ps(1e-7f);
  for (int k = 0; k < 10; ++k)
  {
    a[k] = _mm256_set1_ps(1.0f + k);
  }
  for (long i = 0; i < iters; ++i)
  {
    for (int k = 0; k < 10; ++k)
    {
      a[k] = _mm256_fmadd_ps(a[k], m, c);
    }
  }
  float out[8];
  __m256 s = a[0];
  for (int k = 1; k < 10; ++k)
  {
    s = _mm256_add_ps(s, a[k]);
  }
  _mm256_storeu_ps(out, s);
  return out[0];
}

void Peak()
{
  const long iters = 100000000;
  for (int threads : { 1, 2 })
  {
    for (int width : { 8, 16 })
    {
      if (width == 16 && !__builtin_cpu_supports("avx512f"))
      {
        continue;
      }
      double sink = 0;
      const double t0 = Now();
      const double c0 = CpuNow();
#pragma omp parallel num_threads(threads) reduction(+ : sink)
      {
        sink += width == 16 ? FmaLoop512(iters) : FmaLoop256(iters);
      }
      const double dt = Now() - t0;
      const double cpu = CpuNow() - c0;
      const double flops = 2.0 * width * 10.0 * iters * threads;
      std::printf("peak fp32 FMA, %2d lanes, %d thread(s): %.1f GFLOP/s wall-clock, %.1f GFLOP/s "
                  "per CPU-second (%.2f s wall, %.2f s CPU, sink %g)\n",
        width,
        threads,
        flops / dt * 1e-9,
        flops / cpu * 1e-9,
        dt,
        cpu,
        sink);
    }
  }
}

//------------------------------------------------------------------------------
void Render(std::size_t n)
{
  const GaussianCloud cloud = SyntheticScene(n, 7u);
  const Camera cam = BenchCamera(1280, 720);
  for (int threads : { 1, 2 })
  {
    RasterSettings s;
    s.Threads = threads;
    double best[4] = { 1e30, 1e30, 1e30, 1e30 };
    double bestCpu = 1e30;
    RasterWorkCounts work;
    ProjectionCounts counts;
    for (int rep = 0; rep < 3; ++rep)
    {
      const double c0 = CpuNow();
      const double t0 = Now();
      const auto proj = ProjectGaussians<float>(cloud, cam, s);
      const double t1 = Now();
      const auto bins = BinGaussians(proj, threads);
      const double t2 = Now();
      RasterImage<float> img;
      CompositeTiles(proj, bins, s, img);
      const double t3 = Now();
      bestCpu = std::min(bestCpu, CpuNow() - c0);
      best[0] = std::min(best[0], t1 - t0);
      best[1] = std::min(best[1], t2 - t1);
      best[2] = std::min(best[2], t3 - t2);
      best[3] = std::min(best[3], t3 - t0);
      if (rep == 0)
      {
        CompositeTiles(proj, bins, s, img, nullptr, &work);
        counts = proj.Counts;
      }
    }
    std::printf(
      "N=%zu 1280x720 threads=%d: total %.3f s (project %.3f, bin+sort %.3f, composite %.3f); "
      "CPU time %.3f s; visible %zu, tile pairs %llu, reference evaluations %.3g (%.2f G/s), "
      "evaluated here %.3g; peak RSS %.0f MiB\n",
      n,
      threads,
      best[3],
      best[0],
      best[1],
      best[2],
      bestCpu,
      counts.Visible,
      static_cast<unsigned long long>(work.TilePairs),
      static_cast<double>(work.ReferenceEvaluations),
      work.ReferenceEvaluations / best[2] * 1e-9,
      static_cast<double>(work.KernelEvaluations),
      PeakRssMiB());

    // The same frames with a RasterWorkspace kept between them (what the scene view does):
    // no allocation, no page faults after the first frame. Same image, bit for bit.
    RasterWorkspace<float> ws;
    double wbest[4] = { 1e30, 1e30, 1e30, 1e30 };
    double wbestCpu = 1e30;
    bool same = true;
    RasterImage<float> ref;
    CompositeTiles(ProjectGaussians<float>(cloud, cam, s),
      BinGaussians(ProjectGaussians<float>(cloud, cam, s), threads),
      s,
      ref);
    for (int rep = 0; rep < 4; ++rep)
    {
      const double c0 = CpuNow();
      const double t0 = Now();
      ProjectGaussians<float>(cloud, cam, s, ws.Projection);
      const double t1 = Now();
      BinGaussians(ws.Projection, threads, ws.Bins, ws.Scratch);
      const double t2 = Now();
      CompositeTiles(ws.Projection, ws.Bins, s, ws.Image, nullptr, nullptr, &ws.Composite);
      const double t3 = Now();
      if (rep == 0)
      {
        continue; // first frame: allocates like the calls above
      }
      wbestCpu = std::min(wbestCpu, CpuNow() - c0);
      wbest[0] = std::min(wbest[0], t1 - t0);
      wbest[1] = std::min(wbest[1], t2 - t1);
      wbest[2] = std::min(wbest[2], t3 - t2);
      wbest[3] = std::min(wbest[3], t3 - t0);
      same = same && ws.Image.Color == ref.Color && ws.Image.Depth == ref.Depth &&
        ws.Image.Contributors == ref.Contributors;
    }
    std::printf("N=%zu 1280x720 threads=%d, workspace kept between frames: total %.3f s "
                "(project %.3f, bin+sort %.3f, composite %.3f); CPU time %.3f s; same image: "
                "%s; peak RSS %.0f MiB\n",
      n,
      threads,
      wbest[3],
      wbest[0],
      wbest[1],
      wbest[2],
      wbestCpu,
      same ? "yes" : "NO",
      PeakRssMiB());
  }
}

//------------------------------------------------------------------------------
// Naive per-pixel renderer: for every pixel, every Gaussian in one global depth order.
double NaiveRender(const ViewProjection<float>& p, std::vector<float>& out)
{
  std::vector<std::uint32_t> order;
  for (std::size_t i = 0; i < p.Gaussians.size(); ++i)
  {
    if (p.Gaussians[i].IsVisible())
    {
      order.push_back(static_cast<std::uint32_t>(i));
    }
  }
  std::stable_sort(order.begin(),
    order.end(),
    [&](std::uint32_t a, std::uint32_t b) { return p.Gaussians[a].Depth < p.Gaussians[b].Depth; });
  out.assign(3 * static_cast<std::size_t>(p.Width) * p.Height, 0.0f);
  const double t0 = Now();
  for (int y = 0; y < p.Height; ++y)
  {
    for (int x = 0; x < p.Width; ++x)
    {
      const int tx = x / 16, ty = y / 16;
      float T = 1, C[3] = { 0, 0, 0 };
      for (std::uint32_t id : order)
      {
        const auto& g = p.Gaussians[id];
        if (tx < g.TileRect[0] || tx >= g.TileRect[2] || ty < g.TileRect[1] || ty >= g.TileRect[3])
        {
          continue;
        }
        const float alpha = raster::KernelAlpha<float>(
          g.Opacity, raster::KernelPower<float>(g.U, g.V, g.ConicA, g.ConicB, g.ConicC, x, y));
        if (alpha < 0)
        {
          continue;
        }
        const float Tn = T * (1 - alpha);
        if (Tn < 1e-4f)
        {
          break;
        }
        for (int c = 0; c < 3; ++c)
        {
          C[c] += g.Color[c] * alpha * T;
        }
        T = Tn;
      }
      for (int c = 0; c < 3; ++c)
      {
        out[3 * (static_cast<std::size_t>(y) * p.Width + x) + c] = C[c];
      }
    }
  }
  return Now() - t0;
}

void Naive()
{
  const std::size_t n = 20000;
  const GaussianCloud cloud = SyntheticScene(n, 3u);
  const Camera cam = BenchCamera(320, 180);
  RasterSettings s;
  s.Threads = 1;
  const auto proj = ProjectGaussians<float>(cloud, cam, s);
  std::vector<float> naive;
  const double cn0 = CpuNow();
  const double tn = NaiveRender(proj, naive);
  const double cpuNaive = CpuNow() - cn0;
  double best = 1e30, bestCpu = 1e30;
  RasterImage<float> img;
  for (int rep = 0; rep < 5; ++rep)
  {
    const double c0 = CpuNow();
    const double t0 = Now();
    const auto bins = BinGaussians(proj, 1);
    CompositeTiles(proj, bins, s, img);
    best = std::min(best, Now() - t0);
    bestCpu = std::min(bestCpu, CpuNow() - c0);
  }
  const bool same = std::memcmp(naive.data(), img.Color.data(), naive.size() * sizeof(float)) == 0;
  std::printf("naive vs tiled, N=%zu at 320x180, 1 thread: naive %.3f s, tiled (bin+composite) "
              "%.5f s, speed-up %.0fx (CPU time: naive %.3f s, tiled %.5f s, %.0fx), images "
              "bit-identical: %s\n",
    n,
    tn,
    best,
    tn / best,
    cpuNaive,
    bestCpu,
    cpuNaive / bestCpu,
    same ? "yes" : "no");
  // Naive cost is proportional to pixels x Gaussians: extrapolate to 1M at 1280x720.
  const double scale = (1e6 / n) * (1280.0 * 720.0) / (320.0 * 180.0);
  std::printf(
    "naive extrapolated to N=1e6 at 1280x720, 1 thread: %.0f s (x%.0f of the measured run)\n",
    tn * scale,
    scale);
}

//------------------------------------------------------------------------------
void Footprint(std::size_t n)
{
  const GaussianCloud cloud = SyntheticScene(n, 5u);
  const Camera cam = BenchCamera(320, 180);
  std::vector<float> map(320 * 180);
  for (std::size_t i = 0; i < map.size(); ++i)
  {
    map[i] = static_cast<float>((i * 7919) % 1000) / 1000.0f;
  }
  for (int threads : { 1, 2 })
  {
    RasterSettings s;
    s.Threads = threads;
    s.ComputeColors = false;
    FootprintOptions fo;
    fo.Threads = threads;
    double bestP = 1e30, bestF = 1e30, bestCpu = 1e30;
    FootprintStats st;
    for (int rep = 0; rep < 3; ++rep)
    {
      const double c0 = CpuNow();
      const double t0 = Now();
      const auto proj = ProjectGaussians<float>(cloud, cam, s);
      const double t1 = Now();
      st = ComputeFootprints(proj, fo, map.data());
      const double t2 = Now();
      bestCpu = std::min(bestCpu, CpuNow() - c0);
      bestP = std::min(bestP, t1 - t0);
      bestF = std::min(bestF, t2 - t1);
    }
    std::printf(
      "footprints N=%zu at 320x180 threads=%d: project %.4f s + footprint %.4f s per view "
      "(x200 views: %.1f s); CPU time %.4f s per view; |Omega| total %llu, kernels evaluated "
      "%llu\n",
      n,
      threads,
      bestP,
      bestF,
      200 * (bestP + bestF),
      bestCpu,
      static_cast<unsigned long long>(st.TotalPixels),
      static_cast<unsigned long long>(st.EvaluatedPixels));
  }
}

//------------------------------------------------------------------------------
// The scene view's frames: MakeBenchmarkScene + MakeBenchmarkCamera as
// BenchmarkGaussianSplatMapper, every frame re-rendered through one workspace.
void Frames(std::size_t n, int frames, int threads, std::uint64_t version)
{
  const GaussianCloud cloud = MakeBenchmarkScene(n, 0, 1);
  RasterSettings s;
  s.Threads = threads;
  s.ShDegree = 0;
  RasterWorkspace<float> ws;
  ws.Composite.KeepKernels = false; // as the scene view
  std::vector<double> phase[4], wall;
  for (int f = -1; f < frames; ++f)
  {
    const Camera cam = MakeBenchmarkCamera(1280, 720, 0.05 * (f + 1));
    const double w0 = Now();
    const double c0 = CpuNow();
    ProjectGaussians(cloud, cam, s, ws.Projection, ws.Prepared, version);
    const double c1 = CpuNow();
    BinGaussians(ws.Projection, threads, ws.Bins, ws.Scratch);
    const double c2 = CpuNow();
    CompositeTiles(ws.Projection, ws.Bins, s, ws.Image, nullptr, nullptr, &ws.Composite);
    const double c3 = CpuNow();
    if (f < 0)
    {
      continue; // first frame allocates
    }
    wall.push_back(Now() - w0);
    phase[0].push_back(c1 - c0);
    phase[1].push_back(c2 - c1);
    phase[2].push_back(c3 - c2);
    phase[3].push_back(c3 - c0);
  }
  auto median = [](std::vector<double> v)
  {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
  };
  std::printf("frames N=%zu 1280x720 threads=%d, cloud version %llu (prepared %zu times, "
              "reused %zu), median of %d: CPU project %.1f ms, bin+sort "
              "%.1f ms, composite %.1f ms, total %.1f ms (wall %.1f ms)\n",
    n,
    threads,
    static_cast<unsigned long long>(version),
    ws.Prepared.Builds(),
    ws.Prepared.Reuses(),
    frames,
    1e3 * median(phase[0]),
    1e3 * median(phase[1]),
    1e3 * median(phase[2]),
    1e3 * median(phase[3]),
    1e3 * median(wall));
}

} // namespace

int main(int argc, char* argv[])
{
  if (argc > 4 && std::string(argv[1]) == "--frames")
  {
    Frames(std::strtoull(argv[2], nullptr, 10),
      std::atoi(argv[3]),
      std::atoi(argv[4]),
      argc > 5 ? std::strtoull(argv[5], nullptr, 10) : 0);
    return 0;
  }
  if (argc > 1 && std::string(argv[1]) == "--peak")
  {
    Peak();
    return 0;
  }
  if (argc > 1 && std::string(argv[1]) == "--naive")
  {
    Naive();
    return 0;
  }
  if (argc > 2 && std::string(argv[1]) == "--footprint")
  {
    Footprint(std::strtoull(argv[2], nullptr, 10));
    return 0;
  }
  std::vector<std::size_t> sizes;
  for (int i = 1; i < argc; ++i)
  {
    sizes.push_back(std::strtoull(argv[i], nullptr, 10));
  }
  if (sizes.empty())
  {
    sizes = { 100000, 1000000 };
  }
  for (std::size_t n : sizes)
  {
    Render(n);
  }
  return 0;
}

// SPDX-License-Identifier: BSD-3-Clause
// Error against run time of the scene view's level of detail (Core/Splats/SplatLevelOfDetail.h)
// without OpenGL: for each budget, the Core rasteriser's steps (selection of the view's
// Gaussians, projection with colours, binning, compositing) on the budget's Gaussians along
// an orbit, at the moving frames' sample
// distance (magnified bilinearly as the view's texture is), and the PSNR of the 8-bit picture
// against the exact full frame of the same camera. The exact frame is the straightforward
// implementation, timed in the same run.
// Usage: BenchmarkSplatLevelOfDetail SCENE [width=1280] [height=720] [threads=2]
//        [sample distance=1] [frames=3] [budget[:reuse angle]...]
//   SCENE: a Gaussian count (the synthetic scene of BenchmarkScene.h, SH degree 3) or a PLY file
//   (framed from 2.2 times its 90 % extent); budgets default to 5 fractions of the count.
//   A budget alone selects and projects from the whole scene in every frame (SelectSplatsForView
//   and ProjectGaussianSubset, the straightforward level of detail); BUDGET:ANGLE keeps the
//   selection and colours while the view moves less than ANGLE degrees (SplatMovingSet.h; 0 =
//   rebuilt every frame); BUDGET:ANGLE:STOP also stops each pixel's compositing once its
//   transmittance would fall below STOP (RasterSettings::TransmittanceStop; the reference's
//   1e-4 otherwise); BUDGET:ANGLE:STOP:COLOUR keeps the colours of the Gaussians that stay
//   selected while the view is within COLOUR degrees of the last full colour evaluation (0
//   otherwise: every rebuild evaluates every colour). The frames follow the orbit in order, 0.05
//   rad apart; the times are means over the frames (the rebuilds included), the PSNR the median and
//   the minimum.
#include "BenchmarkScene.h"
#include "BenchmarkTiming.h"
#include "GaussianIO.h"
#include "Rasterizer.h"
#include "SplatCamera.h"
#include "SplatLevelOfDetail.h"
#include "SplatMovingSet.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

namespace
{
// 8-bit RGB of a render (clamped), as the view shows it, magnified bilinearly to W x H with
// texel centres at (i + 0.5) / w (OpenGL's linear filter, clamped at the edges).
std::vector<unsigned char> Display(const vis4gs::RasterImage<float>& img, int W, int H)
{
  std::vector<unsigned char> out(3 * static_cast<std::size_t>(W) * H);
  const int w = img.Width, h = img.Height;
  auto at = [&](int x, int y, int c)
  {
    x = std::min(std::max(x, 0), w - 1);
    y = std::min(std::max(y, 0), h - 1);
    return std::min(1.0f, std::max(0.0f, img.Color[3 * (static_cast<std::size_t>(y) * w + x) + c]));
  };
  for (int y = 0; y < H; ++y)
  {
    const double fy = (y + 0.5) * h / H - 0.5;
    const int y0 = static_cast<int>(std::floor(fy));
    const double ty = fy - y0;
    for (int x = 0; x < W; ++x)
    {
      const double fx = (x + 0.5) * w / W - 0.5;
      const int x0 = static_cast<int>(std::floor(fx));
      const double tx = fx - x0;
      for (int c = 0; c < 3; ++c)
      {
        const double v = (1 - ty) * ((1 - tx) * at(x0, y0, c) + tx * at(x0 + 1, y0, c)) +
          ty * ((1 - tx) * at(x0, y0 + 1, c) + tx * at(x0 + 1, y0 + 1, c));
        out[3 * (static_cast<std::size_t>(y) * W + x) + c] =
          static_cast<unsigned char>(std::lround(v * 255.0));
      }
    }
  }
  return out;
}

double Psnr(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b)
{
  double mse = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    const double d = (static_cast<double>(a[i]) - b[i]) / 255.0;
    mse += d * d;
  }
  mse /= static_cast<double>(a.size());
  return mse > 0 ? 10.0 * std::log10(1.0 / mse) : 200.0;
}

// Pixels the exact frame covers (a channel above 32) that the moving one leaves at the
// background (every channel below 8): holes.
std::size_t Holes(const std::vector<unsigned char>& moving, const std::vector<unsigned char>& exact)
{
  std::size_t holes = 0;
  for (std::size_t p = 0; p < exact.size(); p += 3)
  {
    holes += std::max({ exact[p], exact[p + 1], exact[p + 2] }) > 32 &&
      std::max({ moving[p], moving[p + 1], moving[p + 2] }) < 8;
  }
  return holes;
}

vis4gs::Camera FrameCloud(const vis4gs::GaussianCloud& cloud, int W, int H, double azimuth)
{
  std::vector<float> c[3];
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      c[k].push_back(cloud.Positions[3 * i + k]);
    }
  }
  double center[3], extent = 0;
  for (int k = 0; k < 3; ++k)
  {
    std::sort(c[k].begin(), c[k].end());
    center[k] = c[k][c[k].size() / 2];
    extent = std::max(
      extent, static_cast<double>(c[k][c[k].size() * 95 / 100] - c[k][c[k].size() * 5 / 100]));
  }
  const double r = 2.2 * extent;
  vis4gs::CameraLookAt l;
  l.Position = { center[0] + r * std::sin(azimuth) * std::cos(0.4),
    center[1] + r * std::sin(0.4),
    center[2] + r * std::cos(azimuth) * std::cos(0.4) };
  l.FocalPoint = { center[0], center[1], center[2] };
  l.ViewUp = { 0, 1, 0 };
  l.ViewAngle = 40.0;
  return vis4gs::LookAtToCamera(l, W, H);
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 2)
  {
    std::fprintf(stderr,
      "Usage: BenchmarkSplatLevelOfDetail SCENE(count or .ply) [width] [height] [threads] "
      "[sample distance] [frames] [budget...]\n");
    return 2;
  }
  const std::string sceneArg = argv[1];
  const int W = argc > 2 ? std::atoi(argv[2]) : 1280;
  const int H = argc > 3 ? std::atoi(argv[3]) : 720;
  const int threads = argc > 4 ? std::atoi(argv[4]) : 2;
  const double distance = argc > 5 ? std::atof(argv[5]) : 1.0;
  const int frames = argc > 6 ? std::max(1, std::atoi(argv[6])) : 3;
  const bool synthetic = sceneArg.find_first_not_of("0123456789") == std::string::npos;
  vis4gs::GaussianCloud cloud;
  try
  {
    cloud = synthetic ? vis4gs::MakeBenchmarkScene(std::strtoull(sceneArg.c_str(), nullptr, 10), 3)
                      : vis4gs::ReadGaussianPly(sceneArg);
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "BenchmarkSplatLevelOfDetail: %s\n", e.what());
    return 1;
  }
  const std::size_t n = cloud.Count;
  // (budget, reuse angle in degrees (negative: no moving set), transmittance stop)
  struct Row
  {
    std::size_t Budget;
    double Angle;
    double Stop;
    double Color;
  };
  std::vector<Row> budgets;
  for (int a = 7; a < argc; ++a)
  {
    char* end = nullptr;
    Row row{ std::strtoull(argv[a], &end, 10), -1.0, 1e-4, 0.0 };
    if (*end == ':')
    {
      row.Angle = std::strtod(end + 1, &end);
    }
    if (*end == ':')
    {
      row.Stop = std::strtod(end + 1, &end);
    }
    if (*end == ':')
    {
      row.Color = std::strtod(end + 1, &end);
    }
    budgets.push_back(row);
  }
  if (budgets.empty())
  {
    for (double f : { 0.05, 0.1, 0.16, 0.25, 0.4 })
    {
      budgets.push_back({ static_cast<std::size_t>(f * static_cast<double>(n)), -1.0, 1e-4, 0.0 });
    }
  }
  std::printf("BenchmarkSplatLevelOfDetail: %s, %zu Gaussians (SH %d), %dx%d, sample distance "
              "%.2f, %d threads, %d frames of an orbit\n",
    synthetic ? "synthetic" : sceneArg.c_str(),
    n,
    cloud.ShDegree,
    W,
    H,
    distance,
    threads,
    frames);
  vis4gs::PrintLoadAverage();
  vis4gs::RasterSettings settings;
  settings.Threads = threads;
  std::vector<vis4gs::Camera> cameras;
  for (int f = 0; f < frames; ++f)
  {
    const double azimuth = 0.05 * (f + 1) + 0.025;
    cameras.push_back(
      synthetic ? vis4gs::MakeBenchmarkCamera(W, H, azimuth) : FrameCloud(cloud, W, H, azimuth));
  }
  // The exact frames (every Gaussian, full resolution), timed: the straightforward baseline.
  vis4gs::BenchmarkTimer timer;
  std::vector<std::vector<unsigned char>> exact;
  std::vector<double> exactMs, exactCpu;
  {
    vis4gs::RasterWorkspace<float> work;
    work.CloudVersion = 1;
    for (const auto& cam : cameras)
    {
      exactMs.push_back(timer.TimeMs(1, [&] { vis4gs::Rasterize(cloud, cam, settings, work); }));
      exactCpu.push_back(timer.LastCpuMs);
      exact.push_back(Display(work.Image, W, H));
    }
  }
  auto median = [](std::vector<double> v)
  {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  std::printf("  exact frame: %8.1f ms = %6.2f fps, CPU %.1f ms (median; the first frame "
              "prepares the cloud)\n",
    median(exactMs),
    1000.0 / median(exactMs),
    median(exactCpu));
  vis4gs::SplatLevelOfDetail lod;
  const double rankMs =
    timer.TimeMs(1, [&] { vis4gs::PrepareSplatLevelOfDetail(cloud, lod, threads); });
  std::printf("  level-of-detail preparation (once per scene): %.1f ms, CPU %.1f ms\n",
    rankMs,
    timer.LastCpuMs);
  std::printf("  %10s %6s %7s %8s %10s %10s %10s %10s %8s %8s %8s %8s %8s %7s %8s %9s\n",
    "budget",
    "reuse",
    "stop",
    "drawn",
    "select CPU",
    "proj. CPU",
    "bin CPU",
    "blend CPU",
    "frame ms",
    "CPU ms",
    "fps",
    "PSNR dB",
    "min dB",
    "holes",
    "rebuilds",
    "examined");
  auto mean = [](const std::vector<double>& v)
  {
    double sum = 0;
    for (double x : v)
    {
      sum += x;
    }
    return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
  };
  // The whole cloud's preparation (the exact frames' too), kept as the scene view keeps it.
  vis4gs::PreparedCloudCache prepared;
  for (const Row& row : budgets)
  {
    const std::size_t budget = row.Budget;
    const bool reuse = row.Angle >= 0.0;
    const double angle = reuse ? row.Angle * M_PI / 180.0 : 0.0;
    const double colorAngle = row.Color * M_PI / 180.0;
    vis4gs::RasterSettings moving = settings;
    moving.TransmittanceStop = row.Stop;
    vis4gs::RasterWorkspace<float> work;
    std::vector<std::uint32_t> subset;
    vis4gs::SplatMovingSet set;
    std::vector<double> select, project, bin, blend, frame, cpu, psnr, holes, drawn, examined;
    for (int f = -2; f < frames; ++f)
    {
      // Frames -2 and -1 allocate the budget's buffers (once per budget, as the view keeps
      // them; not counted); the orbit starts with a rebuild (the set forgets its view).
      if (f <= 0)
      {
        set.Generation = 0;
      }
      const vis4gs::Camera& full = cameras[std::max(0, f)];
      const vis4gs::Camera cam = distance > 1.0
        ? full.Resized(std::max(1, static_cast<int>(std::lround(W / distance))),
            std::max(1, static_cast<int>(std::lround(H / distance))))
        : full;
      double cpuMs = 0, steps[4] = { 0, 0, 0, 0 };
      const double s = timer.TimeMs(1,
        [&]
        {
          if (reuse)
          {
            if (vis4gs::UpdateSplatMovingSet(
                  cloud, 1, lod, cam, budget, settings, angle, colorAngle, set) &&
              f >= 0)
            {
              examined.push_back(static_cast<double>(set.Selection.Examined));
              std::printf("    frame %d: rebuild %.1f ms wall, of which selection %.1f ms (%zu "
                          "Gaussians examined%s; cells %.1f, filter %.1f, order %.1f) and "
                          "gather %.1f ms (%zu of %zu colours evaluated)\n",
                f,
                set.LastRebuildMs,
                set.LastSelectionMs,
                set.Selection.Examined,
                set.Selection.Fallback ? ", every cell again" : "",
                set.Selection.StepMs[0],
                set.Selection.StepMs[1],
                set.Selection.StepMs[2],
                set.LastGatherMs,
                set.LastEvaluated,
                set.Subset.size());
            }
          }
          else
          {
            vis4gs::SelectSplatsForView(cloud, lod, cam, budget, subset, threads);
          }
        });
      steps[0] = timer.LastCpuMs;
      const double p = timer.TimeMs(1,
        [&]
        {
          if (reuse)
          {
            vis4gs::ProjectSplatMovingSet(set, cam, settings, work.Projection, work.Prepared);
          }
          else
          {
            vis4gs::ProjectGaussianSubset(
              cloud, subset, cam, settings, work.Projection, prepared, std::uint64_t(1));
          }
        });
      steps[1] = timer.LastCpuMs;
      const double b = timer.TimeMs(
        1, [&] { vis4gs::BinGaussians<float>(work.Projection, threads, work.Bins, work.Scratch); });
      steps[2] = timer.LastCpuMs;
      work.Composite.KeepKernels = false;
      const double c = timer.TimeMs(1,
        [&]
        {
          vis4gs::CompositeTiles<float>(
            work.Projection, work.Bins, moving, work.Image, nullptr, nullptr, &work.Composite);
        });
      steps[3] = timer.LastCpuMs;
      cpuMs = steps[0] + steps[1] + steps[2] + steps[3];
      if (f < 0)
      {
        continue;
      }
      select.push_back(steps[0]);
      project.push_back(steps[1]);
      bin.push_back(steps[2]);
      blend.push_back(steps[3]);
      frame.push_back(s + p + b + c);
      cpu.push_back(cpuMs);
      drawn.push_back(static_cast<double>(work.Projection.Counts.Visible));
      const auto shown = Display(work.Image, W, H);
      psnr.push_back(Psnr(shown, exact[f]));
      holes.push_back(static_cast<double>(Holes(shown, exact[f])));
    }
    char reuseText[32] = "-";
    if (reuse)
    {
      std::snprintf(reuseText, sizeof(reuseText), "%.0f/%.0f", row.Angle, row.Color);
    }
    std::printf("  %10zu %6s %7.5f %8.0f %10.1f %10.1f %10.1f %10.1f %8.1f %8.1f %8.2f %8.2f "
                "%8.2f %7.0f %8zu %9.0f\n",
      budget,
      reuseText,
      row.Stop,
      median(drawn),
      mean(select),
      mean(project),
      mean(bin),
      mean(blend),
      mean(frame),
      mean(cpu),
      1000.0 / mean(frame),
      median(psnr),
      *std::min_element(psnr.begin(), psnr.end()),
      median(holes),
      reuse ? set.Rebuilds : static_cast<std::size_t>(frames),
      // (Gaussians whose key a rebuild computed, mean: SelectSplatsInCells' cells; every
      // Gaussian without a moving set)
      examined.empty() ? static_cast<double>(n) : mean(examined));
  }
  return 0;
}

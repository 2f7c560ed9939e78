// SPDX-License-Identifier: BSD-3-Clause
// Frames per second of vtkGaussianSplatMapper on the synthetic scene (Core/Splats) with an
// orbiting camera (every frame re-sorts) and with a still camera, off screen.
// Usage: BenchmarkGaussianSplatMapper [count=1000000] [width=1280] [height=720] [frames=10]
//        [shDegree=0] [threads=2] [path=1 geometry shader | 0 instanced quads]
//        [budget=0 (all)] [method=0 automatic | 1 OpenGL splats | 2 CPU rasteriser]
//        [interactive sample distance=2 (CPU rasteriser path; 0 = auto-adjusted)]
//        [interactive splat budget=-1 (CPU rasteriser path: Gaussians drawn while moving;
//         -1 = the mapper's default, 0 = all)]
#include "BenchmarkScene.h"
#include "Vis4GSDataModel.h"
#include "vtkGaussianCameraUtilities.h"
#include "vtkGaussianSplatMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

int main(int argc, char* argv[])
{
  const std::size_t n = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 1000000;
  const int W = argc > 2 ? std::atoi(argv[2]) : 1280;
  const int H = argc > 3 ? std::atoi(argv[3]) : 720;
  const int frames = argc > 4 ? std::atoi(argv[4]) : 10;
  const int degree = argc > 5 ? std::atoi(argv[5]) : 0;
  const int threads = argc > 6 ? std::atoi(argv[6]) : 2;
  const int path = argc > 7 ? std::atoi(argv[7]) : 1;
  const long long budget = argc > 8 ? std::atoll(argv[8]) : 0;
  const int method = argc > 9 ? std::atoi(argv[9]) : 0;
  const double sampleDistance = argc > 10 ? std::atof(argv[10]) : 2.0;
  const long long splatBudget = argc > 11 ? std::atoll(argv[11]) : -1;
  const auto cloud = vis4gs::MakeBenchmarkScene(n, degree, 1);
  vtkNew<vtkPolyData> scene;
  vis4gs::GaussianCloudToPolyData(cloud, scene);
  vtkNew<vtkGaussianSplatMapper> mapper;
  mapper->SetInputData(scene);
  mapper->SetNumberOfThreads(threads);
  mapper->SetGeometryPath(path);
  mapper->SetMaximumNumberOfSplats(budget);
  mapper->SetDrawMethod(method);
  if (splatBudget >= 0)
  {
    mapper->SetInteractiveSplatBudget(splatBudget);
  }
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> ren;
  ren->AddActor(actor);
  vtkNew<vtkRenderWindow> win;
  win->SetOffScreenRendering(1);
  win->SetMultiSamples(0);
  win->SetSize(W, H);
  win->AddRenderer(ren);
  vtkGaussianCameraUtilities::ApplyCamera(
    vis4gs::MakeBenchmarkCamera(W, H, 0.0), ren->GetActiveCamera());
  auto now = [] { return std::chrono::steady_clock::now(); };
  auto ms = [](std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b)
  { return std::chrono::duration<double, std::milli>(b - a).count(); };
  const auto t0 = now();
  win->Render(); // first frame: upload, shader compile
  const double first = ms(t0, now());
  std::printf("BenchmarkGaussianSplatMapper: %zu Gaussians (SH %d), %dx%d, %d threads, %s\n",
    n,
    degree,
    W,
    H,
    threads,
    path == 0 ? "instanced quads" : "geometry shader");
  std::printf("  drawing path: %s\n",
    mapper->GetLastDrawMethod() == vtkGaussianSplatMapper::CPU_RASTERIZER ? "CPU rasteriser"
                                                                          : "OpenGL splats");
  std::printf("  first frame (pack, upload, compile)  %9.1f ms, %lld drawn\n",
    first,
    static_cast<long long>(mapper->GetLastDrawnCount()));
  std::vector<double> moving, movingCpu, sortMs, colorMs, uploadMs;
  for (int f = 0; f < frames; ++f)
  {
    vtkGaussianCameraUtilities::ApplyCamera(
      vis4gs::MakeBenchmarkCamera(W, H, 0.05 * (f + 1)), ren->GetActiveCamera());
    const auto a = now();
    const std::clock_t c = std::clock();
    win->Render();
    win->WaitForCompletion();
    moving.push_back(ms(a, now()));
    movingCpu.push_back(1000.0 * static_cast<double>(std::clock() - c) / CLOCKS_PER_SEC);
    sortMs.push_back(mapper->GetLastSortTime());
    colorMs.push_back(mapper->GetLastColorTime());
    uploadMs.push_back(mapper->GetLastUploadTime());
  }
  std::vector<double> still, stillCpu;
  for (int f = 0; f < frames; ++f)
  {
    const auto a = now();
    const std::clock_t c = std::clock();
    win->Render();
    win->WaitForCompletion();
    still.push_back(ms(a, now()));
    stillCpu.push_back(1000.0 * static_cast<double>(std::clock() - c) / CLOCKS_PER_SEC);
  }
  auto median = [](std::vector<double> v)
  {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
  };
  // Process CPU time (all threads, llvmpipe's included) per frame: on 2 otherwise idle cores
  // a frame cannot take less than half of it, whatever else runs on the machine.
  std::printf("  moving camera: %9.1f ms/frame = %6.2f fps, CPU %.1f ms/frame (sort %.1f ms, "
              "colours %.1f ms, upload %.1f ms)\n",
    median(moving),
    1000.0 / median(moving),
    median(movingCpu),
    median(sortMs),
    median(colorMs),
    median(uploadMs));
  std::printf("  still camera:  %9.1f ms/frame = %6.2f fps, CPU %.1f ms/frame\n",
    median(still),
    1000.0 / median(still),
    median(stillCpu));
  if (mapper->GetLastDrawMethod() == vtkGaussianSplatMapper::CPU_RASTERIZER)
  {
    // Interactive frames (the window's DesiredUpdateRate as a vtkRenderWindowInteractor sets
    // it while interacting), orbiting camera, and their PSNR against the full-quality frame.
    if (sampleDistance > 0)
    {
      mapper->AutoAdjustImageSampleDistancesOff();
      mapper->SetInteractiveImageSampleDistance(sampleDistance);
    }
    std::vector<double> inter, interCpu, psnr, dist, drawn;
    double firstInteractive = 0.0;
    std::size_t holes = 0;
    auto grab = [&]()
    {
      unsigned char* px = win->GetPixelData(0, 0, W - 1, H - 1, 0);
      std::vector<unsigned char> v(px, px + 3 * static_cast<std::size_t>(W) * H);
      delete[] px;
      return v;
    };
    for (int f = 0; f < frames; ++f)
    {
      vtkGaussianCameraUtilities::ApplyCamera(
        vis4gs::MakeBenchmarkCamera(W, H, 0.05 * (f + 1) + 0.025), ren->GetActiveCamera());
      win->SetDesiredUpdateRate(15.0);
      const auto a = now();
      const std::clock_t c = std::clock();
      win->Render();
      win->WaitForCompletion();
      const double t = ms(a, now());
      // The first interactive frame also ranks the scene and makes its level of detail.
      if (f == 0 && frames > 1)
      {
        firstInteractive = t;
        win->SetDesiredUpdateRate(0.0001);
        win->Render();
        continue;
      }
      inter.push_back(t);
      interCpu.push_back(1000.0 * static_cast<double>(std::clock() - c) / CLOCKS_PER_SEC);
      dist.push_back(mapper->GetLastImageSampleDistance());
      drawn.push_back(static_cast<double>(mapper->GetLastDrawnCount()));
      const auto low = grab();
      win->SetDesiredUpdateRate(0.0001);
      win->Render();
      const auto full = grab();
      double mse = 0;
      for (std::size_t i = 0; i < low.size(); ++i)
      {
        const double d = (static_cast<double>(low[i]) - full[i]) / 255.0;
        mse += d * d;
      }
      mse /= static_cast<double>(low.size());
      psnr.push_back(mse > 0 ? 10.0 * std::log10(1.0 / mse) : 200.0);
      // Silhouettes: pixels the full frame covers (any channel above 1/8) that the moving
      // frame leaves at the background (every channel below 1/32).
      for (std::size_t p = 0; p < low.size(); p += 3)
      {
        const bool covered = std::max({ full[p], full[p + 1], full[p + 2] }) > 32;
        const bool empty = std::max({ low[p], low[p + 1], low[p + 2] }) < 8;
        holes += covered && empty ? 1 : 0;
      }
      if (const char* dir = std::getenv("VIS4GS_BENCHMARK_IMAGES"))
      {
        // The last pair as binary PPM files (rows bottom-up, as read), for looking at them.
        for (int k = 0; k < 2; ++k)
        {
          const std::string path = std::string(dir) + (k == 0 ? "/moving.ppm" : "/exact.ppm");
          if (FILE* out = std::fopen(path.c_str(), "wb"))
          {
            std::fprintf(out, "P6\n%d %d\n255\n", W, H);
            for (int y = H - 1; y >= 0; --y)
            {
              std::fwrite(
                &(k == 0 ? low : full)[3 * static_cast<std::size_t>(y) * W], 1, 3 * W, out);
            }
            std::fclose(out);
          }
        }
      }
    }
    std::printf("  interactive (sample distance %.2f, splat budget %lld, %.0f drawn; first "
                "%.1f ms): %9.1f ms/frame = %6.2f fps, CPU %.1f "
                "ms/frame, PSNR against the full-quality frame %.2f dB (min %.2f)\n",
      median(dist),
      static_cast<long long>(mapper->GetInteractiveSplatBudget()),
      median(drawn),
      firstInteractive,
      median(inter),
      1000.0 / median(inter),
      median(interCpu),
      median(psnr),
      *std::min_element(psnr.begin(), psnr.end()));
    std::printf("  holes: %.0f pixels per moving frame covered in the full frame, background in "
                "the moving one\n",
      static_cast<double>(holes) / std::max<std::size_t>(1, psnr.size()));
  }
  return 0;
}

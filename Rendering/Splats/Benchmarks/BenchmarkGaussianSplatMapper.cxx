// SPDX-License-Identifier: BSD-3-Clause
// Frames per second of vtkGaussianSplatMapper on the synthetic scene (Core/Splats) with an
// orbiting camera (every frame re-sorts) and with a still camera, off screen. On the OpenGL
// splat path the orbit's frames are interactive ones (DesiredUpdateRate 15: drawn with the last
// order the worker thread finished) and the benchmark adds the render thread's CPU time per
// frame, the order's lag and its error against the exact order, and the same orbit with the
// sort on the render thread (AsynchronousSort off, the straightforward implementation).
// Usage: BenchmarkGaussianSplatMapper [count=1000000] [width=1280] [height=720] [frames=10]
//        [shDegree=0] [threads=2] [path=1 geometry shader | 0 instanced quads]
//        [budget=0 (all)] [method=0 automatic | 1 OpenGL splats | 2 CPU rasteriser]
//        [interactive sample distance=2 (CPU rasteriser path; 0 = auto-adjusted)]
//        [interactive splat budget=-1 (CPU rasteriser path: Gaussians drawn while moving;
//         -1 = the mapper's default, 0 = all)]
//        [orbit speed=45 degrees per second (OpenGL path: the order's lag in degrees at a
//         60 fps GPU frame rate)] [lag offsets=1,3,10 (OpenGL path: degrees behind the camera
//         whose order's error is measured, besides the lag of the orbit speed)]
//        [interactive reuse angle=-1 (CPU rasteriser path: degrees the view moves before the
//         moving frames' Gaussians and colours are chosen again; -1 = the mapper's default)]
//        [interactive transmittance stop=-1 (CPU rasteriser path: where a moving frame's pixel
//         stops blending; -1 = the mapper's default)] [interactive colour angle=-1 (CPU
//         rasteriser path: degrees before every colour of the moving frames' Gaussians is
//         evaluated again; -1 = the mapper's default)] [interactive rebuild ahead=-1 (CPU
//         rasteriser path: fraction of the reuse angle after which the next choice of
//         Gaussians starts on a builder thread; 0 = off, -1 = the mapper's default)]
#include "BenchmarkScene.h"
#include "SplatSortWorker.h"
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
#include <memory>
#include <string>
#include <time.h>
#include <vector>

namespace
{
// CPU milliseconds of the calling thread (the render thread here).
double ThreadCpuMs()
{
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
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
} // namespace

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
  const double orbitSpeed = argc > 12 ? std::atof(argv[12]) : 45.0;
  std::vector<double> offsets;
  for (const char* p = argc > 13 ? argv[13] : "1,3,10"; *p;)
  {
    char* end = nullptr;
    const double d = std::strtod(p, &end);
    if (end == p)
    {
      break;
    }
    offsets.push_back(d);
    p = *end == ',' ? end + 1 : end;
  }
  const double reuseAngle = argc > 14 ? std::atof(argv[14]) : -1.0;
  const double transmittanceStop = argc > 15 ? std::atof(argv[15]) : -1.0;
  const double colorAngle = argc > 16 ? std::atof(argv[16]) : -1.0;
  const double rebuildAhead = argc > 17 ? std::atof(argv[17]) : -1.0;
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
  if (reuseAngle >= 0)
  {
    mapper->SetInteractiveReuseAngle(reuseAngle);
  }
  if (transmittanceStop > 0)
  {
    mapper->SetInteractiveTransmittanceStop(transmittanceStop);
  }
  if (colorAngle >= 0)
  {
    mapper->SetInteractiveColorAngle(colorAngle);
  }
  if (rebuildAhead >= 0)
  {
    mapper->SetInteractiveRebuildAhead(rebuildAhead);
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
  const bool openGL = mapper->GetLastDrawMethod() == vtkGaussianSplatMapper::OPENGL_SPLATS;
  auto grab = [&]()
  {
    unsigned char* px = win->GetPixelData(0, 0, W - 1, H - 1, 0);
    std::vector<unsigned char> v(px, px + 3 * static_cast<std::size_t>(W) * H);
    delete[] px;
    return v;
  };
  // The OpenGL path's orbit is interactive (the last finished order); after each moving frame
  // a still frame at the same camera (the exact order) gives the moving frame's error.
  std::vector<double> moving, movingCpu, sortMs, colorMs, uploadMs, renderThread, drawCall,
    wholeRender, lag, lagPsnr, exactFrames, exactCpu, newOrderThread;
  const vtkIdType orderUploads0 = mapper->GetOrderUploadCount();
  const vtkIdType sceneUploads0 = mapper->GetSceneUploadCount();
  for (int f = 0; f < frames; ++f)
  {
    vtkGaussianCameraUtilities::ApplyCamera(
      vis4gs::MakeBenchmarkCamera(W, H, 0.05 * (f + 1)), ren->GetActiveCamera());
    win->SetDesiredUpdateRate(openGL ? 15.0 : 0.0001);
    const auto a = now();
    const std::clock_t c = std::clock();
    const double t = ThreadCpuMs();
    win->Render();
    win->WaitForCompletion();
    wholeRender.push_back(ThreadCpuMs() - t);
    moving.push_back(ms(a, now()));
    movingCpu.push_back(1000.0 * static_cast<double>(std::clock() - c) / CLOCKS_PER_SEC);
    if (mapper->GetLastSortTime() > 0 || !openGL)
    {
      sortMs.push_back(mapper->GetLastSortTime());
    }
    colorMs.push_back(mapper->GetLastColorTime());
    if (!openGL)
    {
      uploadMs.push_back(mapper->GetLastUploadTime());
    }
    renderThread.push_back(mapper->GetLastRenderThreadTime());
    drawCall.push_back(mapper->GetLastDrawCallTime());
    lag.push_back(static_cast<double>(mapper->GetLastOrderLag()));
    if (openGL)
    {
      const auto lagging = grab();
      win->SetDesiredUpdateRate(0.0001);
      const auto s0 = now();
      const std::clock_t sc = std::clock();
      win->Render(); // waits for the order of this camera (sorted on the worker)
      win->WaitForCompletion();
      exactFrames.push_back(ms(s0, now()));
      exactCpu.push_back(1000.0 * static_cast<double>(std::clock() - sc) / CLOCKS_PER_SEC);
      // (the order arrives in this frame: its sort's and its upload's time, and the render
      // thread's CPU in a frame that uploads an order)
      sortMs.push_back(mapper->GetLastSortTime());
      uploadMs.push_back(mapper->GetLastUploadTime());
      newOrderThread.push_back(mapper->GetLastRenderThreadTime());
      lagPsnr.push_back(Psnr(grab(), lagging));
    }
  }
  win->SetDesiredUpdateRate(0.0001);
  // (the OpenGL path timed still frames at new cameras above: one here)
  std::vector<double> still, stillCpu;
  for (int f = 0; f < (openGL ? 1 : frames); ++f)
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
              "colours %.1f ms, upload %.1f ms)",
    median(moving),
    1000.0 / median(moving),
    median(movingCpu),
    median(sortMs),
    median(colorMs),
    median(uploadMs));
  if (openGL)
  {
    // The mapper's own CPU time on the render thread (thread CPU clock, the draw call left
    // out); the draw call's (llvmpipe runs the vertex and geometry shaders in it, on this
    // thread); the render thread's whole vtkRenderWindow::Render() including the driver.
    std::printf(", render thread %.2f ms/frame (max %.2f; draw call %.1f ms, whole Render() "
                "%.1f ms on the render thread), order lag %.1f frames, PSNR against the exact "
                "order %.2f dB (min %.2f)",
      median(renderThread),
      *std::max_element(renderThread.begin(), renderThread.end()),
      median(drawCall),
      median(wholeRender),
      median(lag),
      median(lagPsnr),
      *std::min_element(lagPsnr.begin(), lagPsnr.end()));
  }
  std::printf("\n");
  if (openGL)
  {
    std::printf("  uploads while moving: %lld scene arrays, %lld orders in %d frames; render "
                "thread in a frame that uploads a new order %.2f ms (max %.2f)\n",
      static_cast<long long>(mapper->GetSceneUploadCount() - sceneUploads0),
      static_cast<long long>(mapper->GetOrderUploadCount() - orderUploads0),
      frames,
      median(newOrderThread),
      *std::max_element(newOrderThread.begin(), newOrderThread.end()));
    // The sort alone, the OpenGL driver idle (the worker's sorts above ran next to llvmpipe's
    // rasterising threads on the same two cores): what it costs next to a GPU.
    std::vector<double> aloneWall, aloneCpu;
    {
      vis4gs::SplatSortRequest request;
      request.Cloud = std::shared_ptr<const vis4gs::GaussianCloud>(
        &cloud, [](const vis4gs::GaussianCloud*) {}); // (no copy: the benchmark's scene)
      request.Threads = threads;
      std::vector<float> depths;
      vis4gs::SplatSortResult result;
      for (int k = 0; k < 3; ++k)
      {
        request.WorldToCamera = vis4gs::MakeBenchmarkCamera(W, H, 0.1 * k).WorldToCamera;
        const auto a = now();
        const std::clock_t c = std::clock();
        vis4gs::SplatSortWorker::Sort(request, depths, result);
        aloneWall.push_back(ms(a, now()));
        aloneCpu.push_back(1000.0 * static_cast<double>(std::clock() - c) / CLOCKS_PER_SEC);
      }
    }
    std::printf("  the sort alone (OpenGL idle): %.1f ms wall, %.1f ms CPU\n",
      median(aloneWall),
      median(aloneCpu));
    // The error of an order sorted for a camera d degrees behind the frame's (frame at angle
    // A drawn with the order of A - d, against A's exact order), and the lag that a sort of
    // the measured duration causes at the orbit speed with a 60 fps GPU.
    const double target = 0.05 * frames;
    vtkGaussianCameraUtilities::ApplyCamera(
      vis4gs::MakeBenchmarkCamera(W, H, target), ren->GetActiveCamera());
    win->Render();
    const auto exact = grab();
    const double sortTime = median(aloneWall);
    const double gpuFrame = 1000.0 / 60.0;
    const double lagFrames = std::ceil(sortTime / gpuFrame) + 1.0;
    const double lagDegrees = orbitSpeed * lagFrames * gpuFrame / 1000.0;
    std::printf("  at %.0f deg/s and 60 fps a %.0f ms sort lags %.0f frames = %.2f deg\n",
      orbitSpeed,
      sortTime,
      lagFrames,
      lagDegrees);
    offsets.insert(offsets.begin(), lagDegrees);
    for (double d : offsets)
    {
      vtkGaussianCameraUtilities::ApplyCamera(
        vis4gs::MakeBenchmarkCamera(W, H, target - d * M_PI / 180.0), ren->GetActiveCamera());
      win->SetDesiredUpdateRate(0.0001);
      win->Render(); // the exact order of A - d
      vtkGaussianCameraUtilities::ApplyCamera(
        vis4gs::MakeBenchmarkCamera(W, H, target), ren->GetActiveCamera());
      win->SetDesiredUpdateRate(15.0);
      win->Render(); // drawn with it
      std::printf("  order %5.2f deg behind the camera (lag %lld): PSNR against the exact order "
                  "%.2f dB\n",
        d,
        static_cast<long long>(mapper->GetLastOrderLag()),
        Psnr(exact, grab()));
    }
    // The straightforward implementation: the sort on the render thread.
    mapper->AsynchronousSortOff();
    std::vector<double> syncThread, syncWall;
    for (int f = 0; f < std::max(2, frames / 2); ++f)
    {
      vtkGaussianCameraUtilities::ApplyCamera(
        vis4gs::MakeBenchmarkCamera(W, H, target + 0.05 * (f + 1)), ren->GetActiveCamera());
      const auto a = now();
      win->Render();
      win->WaitForCompletion();
      syncWall.push_back(ms(a, now()));
      syncThread.push_back(mapper->GetLastRenderThreadTime());
    }
    mapper->AsynchronousSortOn();
    std::printf("  sort on the render thread (AsynchronousSort off): %9.1f ms/frame, render "
                "thread %.2f ms/frame\n",
      median(syncWall),
      median(syncThread));
    win->SetDesiredUpdateRate(0.0001);
  }
  std::printf("  still camera:  %9.1f ms/frame = %6.2f fps, CPU %.1f ms/frame\n",
    median(still),
    1000.0 / median(still),
    median(stillCpu));
  if (openGL)
  {
    std::printf("  still frame after a move (waits for its exact order): %9.1f ms/frame, CPU %.1f "
                "ms/frame\n",
      median(exactFrames),
      median(exactCpu));
  }
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
    // Per step of the moving frames (vtkGaussianSplatMapper::GetLastRasterPhaseTimes), summed.
    double stepWall[8] = { 0, 0, 0, 0, 0, 0, 0, 0 }, stepCpu[8] = { 0, 0, 0, 0, 0, 0, 0, 0 };
    std::vector<double>
      lodStep; // (per frame: the level of detail's and the projection's wall, CPU)
    double firstInteractive = 0.0;
    std::size_t holes = 0;
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
      {
        double w[6], cp[6];
        mapper->GetLastRasterPhaseTimes(w);
        mapper->GetLastRasterPhaseCpuTimes(cp);
        double wallSum = 0, cpuSum = 0;
        for (int k = 0; k < 6; ++k)
        {
          stepWall[k] += w[k];
          stepCpu[k] += cp[k];
          wallSum += w[k];
          cpuSum += cp[k];
        }
        // The render thread's upload and draw, then what the Render() took besides (the
        // OpenGL driver finishing the frame, VTK's own work).
        stepWall[6] += mapper->GetLastRasterDrawTime();
        stepWall[7] += t - wallSum - mapper->GetLastRasterDrawTime();
        stepCpu[7] += interCpu.back() - cpuSum;
        lodStep.insert(lodStep.end(), { w[0], cp[0], w[1], cp[1] });
      }
      dist.push_back(mapper->GetLastImageSampleDistance());
      drawn.push_back(static_cast<double>(mapper->GetLastDrawnCount()));
      const auto low = grab();
      win->SetDesiredUpdateRate(0.0001);
      win->Render();
      const auto full = grab();
      psnr.push_back(Psnr(full, low));
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
    auto mean = [](const std::vector<double>& v)
    {
      double sum = 0;
      for (double x : v)
      {
        sum += x;
      }
      return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
    };
    std::printf("  interactive (sample distance %.2f, splat budget %lld, reuse angle %.1f deg, "
                "colour angle %.1f deg, transmittance stop %g, rebuild ahead %g, %.0f drawn; "
                "first %.1f ms): %9.1f "
                "ms/frame = %6.2f fps, CPU %.1f ms/frame, PSNR against the full-quality frame "
                "%.2f dB (min %.2f)\n",
      median(dist),
      static_cast<long long>(mapper->GetInteractiveSplatBudget()),
      mapper->GetInteractiveReuseAngle(),
      mapper->GetInteractiveColorAngle(),
      mapper->GetInteractiveTransmittanceStop(),
      mapper->GetInteractiveRebuildAhead(),
      median(drawn),
      firstInteractive,
      median(inter),
      1000.0 / median(inter),
      median(interCpu),
      median(psnr),
      *std::min_element(psnr.begin(), psnr.end()));
    // The frames that choose the Gaussians again cost more than those that reuse them: the
    // mean and the slowest frame of the orbit too.
    std::printf("  interactive mean over the orbit: %9.1f ms/frame = %6.2f fps, CPU %.1f ms/frame; "
                "slowest %.1f ms, CPU %.1f ms\n",
      mean(inter),
      1000.0 / mean(inter),
      mean(interCpu),
      *std::max_element(inter.begin(), inter.end()),
      *std::max_element(interCpu.begin(), interCpu.end()));
    const double frameCount = static_cast<double>(std::max<std::size_t>(1, inter.size()));
    std::printf("  interactive frames, wall / CPU ms (level of detail step's wall / CPU, "
                "projection's wall / CPU):");
    for (std::size_t k = 0; k < inter.size(); ++k)
    {
      std::printf(" %.1f / %.1f (%.1f / %.1f, %.1f / %.1f)",
        inter[k],
        interCpu[k],
        lodStep[4 * k],
        lodStep[4 * k + 1],
        lodStep[4 * k + 2],
        lodStep[4 * k + 3]);
    }
    std::printf("\n");
    std::printf("  interactive steps, mean wall / CPU ms: level of detail %.1f / %.1f, projection "
                "%.1f / %.1f, overlay %.1f / %.1f, binning %.1f / %.1f, compositing %.1f / %.1f, "
                "texels %.1f / %.1f; upload and draw %.1f; the rest of Render() %.1f / %.1f\n",
      stepWall[0] / frameCount,
      stepCpu[0] / frameCount,
      stepWall[1] / frameCount,
      stepCpu[1] / frameCount,
      stepWall[2] / frameCount,
      stepCpu[2] / frameCount,
      stepWall[3] / frameCount,
      stepCpu[3] / frameCount,
      stepWall[4] / frameCount,
      stepCpu[4] / frameCount,
      stepWall[5] / frameCount,
      stepCpu[5] / frameCount,
      stepWall[6] / frameCount,
      stepWall[7] / frameCount,
      stepCpu[7] / frameCount);
    std::printf("  holes: %.0f pixels per moving frame covered in the full frame, background in "
                "the moving one\n",
      static_cast<double>(holes) / std::max<std::size_t>(1, psnr.size()));
  }
  return 0;
}

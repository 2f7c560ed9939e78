// SPDX-License-Identifier: BSD-3-Clause
// Benchmark of the scores distributed over MPI processes (issue 18), run under mpiexec:
//
//   mpiexec -n K BenchmarkScoresMPI [--gaussians=N] [--views=V] [--width=W] [--height=H]
//       [--loss-resolution=F] [--images=DIR]
//
// The scene and cameras of BenchmarkArtifactScores perf (synthetic shell, log-scale -5.8, ring
// of V cameras), coverage at full resolution + blur and needle at 1/F (default 4), through
// vtkGaussianArtifactScoreFilter with the MPI controller (one process: the plain path). The
// training images (a pattern, PNG) are written once to DIR (default /tmp/vis4gs-bench-images-
// WxH-V) by process 0 and read, as in real use, by the process that owns each view.
// Process 0 prints per process: views rendered, seconds on its views, seconds waiting for the
// slowest one, seconds of the reduction, peak memory; then the wall time of the filter and
// the constants of the projection model of Documentation/performance.md.
#include "vtkGaussianArtifactScoreFilter.h"

#include "BenchmarkSceneUtils.h"
#include "ImageIO.h"
#include "Vis4GSDataModel.h"

#include "vtkDataArray.h"
#include "vtkMPIController.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkTable.h"

#include <omp.h>
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace
{
double Arg(const std::map<std::string, std::string>& a, const char* key, double fallback)
{
  const auto it = a.find(key);
  return it == a.end() ? fallback : std::stod(it->second);
}
}

int main(int argc, char* argv[])
{
  vtkNew<vtkMPIController> controller;
  controller->Initialize(&argc, &argv);
  const int rank = controller->GetLocalProcessId();
  const int ranks = controller->GetNumberOfProcesses();
  std::map<std::string, std::string> args;
  for (int i = 1; i < argc; ++i)
  {
    const std::string s = argv[i];
    const auto eq = s.find('=');
    if (s.rfind("--", 0) == 0 && eq != std::string::npos)
    {
      args[s.substr(2, eq - 2)] = s.substr(eq + 1);
    }
  }
  const std::size_t n = static_cast<std::size_t>(Arg(args, "gaussians", 1000000));
  const int views = static_cast<int>(Arg(args, "views", 200));
  const int width = static_cast<int>(Arg(args, "width", 1280));
  const int height = static_cast<int>(Arg(args, "height", 720));
  const int lossResolution = static_cast<int>(Arg(args, "loss-resolution", 4));
  const std::filesystem::path folder = args.count("images")
    ? std::filesystem::path(args["images"])
    : std::filesystem::temp_directory_path() /
      ("vis4gs-bench-images-" + std::to_string(width) + "x" + std::to_string(height) + "-" +
        std::to_string(views));

  const vis4gs::GaussianCloud cloud = vis4gs::bench::ShellScene(n, 1, -5.8);
  std::vector<vis4gs::Camera> cameras = vis4gs::bench::RingCameras(views, 3.0, width, height);
  for (int v = 0; v < views; ++v)
  {
    const auto file = folder / (cameras[v].Name + ".png");
    cameras[v].ImagePath = file.string();
    if (rank == 0 && !std::filesystem::exists(file))
    {
      std::filesystem::create_directories(folder);
      vis4gs::Image image;
      image.Width = width;
      image.Height = height;
      image.Pixels.resize(3 * static_cast<std::size_t>(width) * height);
      for (int y = 0; y < height; ++y)
      {
        for (int x = 0; x < width; ++x)
        {
          float* p = &image.Pixels[3 * (static_cast<std::size_t>(y) * width + x)];
          p[0] = 0.5f + 0.5f * std::sin(0.05f * x + v);
          p[1] = 0.5f + 0.5f * std::cos(0.03f * y);
          p[2] = 0.3f;
        }
      }
      vis4gs::WritePng(file.string(), image);
    }
  }
  vtkNew<vtkPolyData> poly;
  vis4gs::GaussianCloudToPolyData(cloud, poly);
  vtkNew<vtkTable> table;
  vis4gs::CamerasToTable(cameras, table);
  controller->Barrier();

  vtkNew<vtkGaussianArtifactScoreFilter> filter;
  filter->SetController(controller);
  filter->SetInputData(poly);
  filter->SetCamerasData(table);
  filter->SetComputeNeedleShape(false);
  filter->SetLossResolution(lossResolution);
  controller->Barrier();
  const auto start = std::chrono::steady_clock::now();
  filter->Update();
  const double wall =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  struct rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  double mine[4] = { static_cast<double>(filter->GetNumberOfViewsRendered()),
    filter->GetComputeSeconds(),
    filter->GetReductionSeconds(),
    usage.ru_maxrss / 1024.0 };
  std::vector<double> all(4 * static_cast<std::size_t>(ranks));
  controller->Gather(mine, all.data(), 4, 0);
  double slowest = 0;
  controller->Reduce(&wall, &slowest, 1, vtkCommunicator::MAX_OP, 0);
  if (rank == 0)
  {
    std::printf("processes %d, threads per process %d, %zu Gaussians, %d views of %dx%d, "
                "coverage at 1/1, blur+needle at 1/%d\n",
      ranks,
      omp_get_max_threads(),
      n,
      views,
      width,
      height,
      lossResolution);
    double maxCompute = 0, reduction = 0;
    for (int r = 0; r < ranks; ++r)
    {
      const double* p = &all[4 * static_cast<std::size_t>(r)];
      std::printf("  process %d: %4.0f views, views %8.2f s (%.4f s per view), reduction %.3f "
                  "s, peak memory %.0f MiB\n",
        r,
        p[0],
        p[1],
        p[0] > 0 ? p[1] / p[0] : 0.0,
        p[2],
        p[3]);
      maxCompute = std::max(maxCompute, p[1]);
      reduction = std::max(reduction, p[2]);
    }
    // Bytes reduced: 2 x uint32 + 2 x double per Gaussian (ScorePartials).
    std::printf("wall %.2f s (slowest process), views of the slowest %.2f s, reduction %.3f s "
                "for %.1f MB per process\n",
      slowest,
      maxCompute,
      reduction,
      24.0 * n / 1e6);
    std::printf("RESULT processes=%d threads=%d wall=%.3f view_seconds_max=%.3f "
                "reduction_seconds=%.4f\n",
      ranks,
      omp_get_max_threads(),
      slowest,
      maxCompute,
      reduction);
    // --write-scores=DIR: every score array as raw float64, so that runs on different
    // process counts can be compared value by value (Scripts/compare-mpi-scores.py).
    if (args.count("write-scores"))
    {
      const std::filesystem::path out = args["write-scores"];
      std::filesystem::create_directories(out);
      vtkPointData* pd = filter->GetOutput()->GetPointData();
      for (const char* name : { "ViewCoverage", "BlurScore", "NeedleScore" })
      {
        vtkDataArray* array = pd->GetArray(name);
        if (!array)
        {
          std::fprintf(stderr, "no %s array in the output\n", name);
          return 1;
        }
        std::vector<double> values(static_cast<std::size_t>(array->GetNumberOfTuples()));
        for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
        {
          values[static_cast<std::size_t>(i)] = array->GetTuple1(i);
        }
        std::FILE* f = std::fopen((out / (std::string(name) + ".f64")).c_str(), "wb");
        if (!f || std::fwrite(values.data(), sizeof(double), values.size(), f) != values.size())
        {
          std::fprintf(stderr, "cannot write %s\n", (out / name).c_str());
          return 1;
        }
        std::fclose(f);
      }
    }
  }
  controller->Finalize();
  return 0;
}

// SPDX-License-Identifier: BSD-3-Clause
// The scene at any logged iteration of a training log: the mapper draws whatever snapshot
// vtkGaussianTrainingLogReader outputs. A two-snapshot log (written with Core's writer) is
// read; switching the iteration re-renders the other snapshot, and each picture agrees with
// the CPU rasteriser on that snapshot (PSNR >= 30 dB) and not with the other one.
#include "SplatTestHelpers.h"
#include "Vis4GSTestData.h" // VIS4GS_SHARED_DATA_OR_SKIP

#include "Rasterizer.h"
#include "TrainingLogWriter.h"
#include "vtkGaussianCameraUtilities.h"
#include "vtkGaussianSplatMapper.h"
#include "vtkGaussianTrainingLogReader.h"

#include "vtkActor.h"
#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <cstdio>
#include <filesystem>
#include <string>
#include <unistd.h>

int TestGaussianSplatMapperInputSwitch(int argc, char* argv[])
{
  VIS4GS_SHARED_DATA_OR_SKIP();
  // Snapshot 100: every other Gaussian, less opaque; snapshot 300: the full donut.
  const vis4gs::GaussianCloud full = splattest::LoadScene(false);
  vis4gs::GaussianCloud early;
  early.Resize((full.Count + 1) / 2, 0);
  for (std::size_t i = 0, k = 0; i < full.Count; i += 2, ++k)
  {
    std::copy_n(&full.Positions[3 * i], 3, &early.Positions[3 * k]);
    std::copy_n(&full.LogScales[3 * i], 3, &early.LogScales[3 * k]);
    std::copy_n(&full.Rotations[4 * i], 4, &early.Rotations[4 * k]);
    std::copy_n(&full.SH[3 * i], 3, &early.SH[3 * k]);
    early.OpacityLogits[k] = full.OpacityLogits[i] - 1.0f;
    early.Ids.push_back(static_cast<std::int64_t>(i));
  }
  (void)argc;
  (void)argv;
  const std::string path = (std::filesystem::temp_directory_path() /
    ("vis4gs-TestGaussianSplatMapperInputSwitch-" + std::to_string(::getpid()) + ".h5"))
                             .string();
  {
    vis4gs::TrainingLogWriterOptions o;
    o.ShDegree = 0;
    o.Iterations = 300;
    vis4gs::TrainingLogWriter writer(path, o);
    vis4gs::MetricsRow m;
    m.Iteration = 100;
    m.NumGaussians = static_cast<std::int64_t>(early.Count);
    writer.AppendMetrics(m);
    m.Iteration = 300;
    m.NumGaussians = static_cast<std::int64_t>(full.Count);
    writer.AppendMetrics(m);
    writer.WriteSnapshot(100, early);
    writer.WriteSnapshot(300, full);
    writer.Close();
  }

  vtkNew<vtkGaussianTrainingLogReader> reader;
  reader->SetFileName(path.c_str());
  reader->SetIteration(100);
  vtkNew<vtkGaussianSplatMapper> mapper;
  mapper->SetInputConnection(reader->GetOutputPort(0));
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> ren;
  ren->AddActor(actor);
  vtkNew<vtkRenderWindow> win;
  win->SetOffScreenRendering(1);
  win->SetMultiSamples(0);
  const vis4gs::Camera cam = splattest::FrameScene(full, 200, 150, 1.1);
  win->SetSize(cam.Width, cam.Height);
  win->AddRenderer(ren);
  vtkGaussianCameraUtilities::ApplyCamera(cam, ren->GetActiveCamera());

  const auto refEarly = vis4gs::Rasterize<float>(early, cam).Color;
  const auto refFull = vis4gs::Rasterize<float>(full, cam).Color;
  int fail = 0;
  const int iterations[3] = { 100, 300, 100 };
  for (int it : iterations)
  {
    reader->SetIteration(it);
    win->Render();
    const auto image = splattest::ReadWindow(win);
    const double own = splattest::Psnr(it == 100 ? refEarly : refFull, image);
    const double other = splattest::Psnr(it == 100 ? refFull : refEarly, image);
    std::printf("iteration %d (loaded %d): %lld drawn, PSNR %.2f dB vs its snapshot, %.2f dB vs "
                "the other\n",
      it,
      reader->GetLoadedIteration(),
      static_cast<long long>(mapper->GetLastDrawnCount()),
      own,
      other);
    if (reader->GetLoadedIteration() != it || !(own >= 30.0) || !(other < own - 3.0))
    {
      std::printf("FAILED: iteration %d is not what the mapper shows\n", it);
      fail = 1;
    }
  }
  std::filesystem::remove(path);
  return fail;
}

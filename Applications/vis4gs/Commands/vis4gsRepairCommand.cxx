// SPDX-License-Identifier: BSD-3-Clause
// `vis4gs repair SOURCE CLEANED --iterations=N --output=DIR` (issue 20): fine-tunes a cleaned
// scene (analyze --select=RULE --delete's cleaned.ply, or any scene holding a subset of the ids
// of SOURCE) for N iterations with the built-in trainer, positions fixed and densification off
// by default, and writes DIR/repaired.h5, a training log whose first event rows are the
// deletion as prune events at the source iteration and whose iterations follow it, so the
// genealogy of the repaired run stays one tree. SOURCE is a training log (a snapshot of it,
// its cameras and images) or a scene file with cameras and images found as `vis4gs analyze`
// finds them (--cameras, --images; source iteration 0 unless --iteration). DIR/repair.csv
// holds PSNR, SSIM and L1 per view of the source, the cleaned scene and the repaired one
// (RemovalEffect.h's figures).
#include "Vis4GSCommand.h"
#include "Vis4GSPipeline.h"
#include "Vis4GSSceneCameras.h"
#include "Vis4GSStagingFolder.h"

#include "FineTune.h" // FineTuneFigureColumns: repair.csv's header
#include "GaussianIO.h"
#include "Vis4GSDataModel.h"
#include "vtkGaussianFineTuneFilter.h"
#include "vtkGaussianSceneReader.h"
#include "vtkGaussianSession.h"
#include "vtkGaussianTrainingLogReader.h"

#include "vtkDataArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkTable.h"
#include "vtkVariant.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace
{
namespace fs = std::filesystem;

void Define(Vis4GSArguments& args)
{
  args.AddPositional("SOURCE",
    "What the cleaned scene comes from: a training log (.h5), or a scene file (3DGS .ply, "
    ".splat, ...; its id property, else its row numbers, are the ids) with cameras and images.");
  args.AddPositional("CLEANED",
    "The cleaned scene: a PLY whose id property names the Gaussians kept (analyze --delete's "
    "cleaned.ply), a subset of the source's ids.");
  args.AddOption("iteration",
    "N",
    "-1",
    "Log: the snapshot the scene was cleaned from (the nearest logged), -1: the last. Scene "
    "file: its iteration number in the repaired log, -1: 0.");
  args.AddOption("cameras",
    "FILE|DIR",
    "",
    "Scene file only: cameras.json, a COLMAP dataset folder (sparse/0 + images) or a "
    "transforms*.json (file or folder). Default: cameras.json beside the scene or two folders "
    "up (the trainer's model folder).");
  args.AddOption("images",
    "DIR",
    "",
    "Scene file only: folder of training images, matched to cameras by name. Default: the "
    "cameras' own image paths.");
  args.AddOption("iterations", "N", "50", "Fine-tuning iterations.");
  args.AddOption("warmup",
    "W",
    "10",
    "Learning-rate warm-up: the j-th of the first W iterations uses j/(W+1) of every learning "
    "rate, so that fresh Adam moments do not make a converged scene worse first; 0: none.");
  args.AddFlag("free-positions", false, "Optimise the positions too (default: fixed).");
  args.AddFlag("densify",
    false,
    "Keep the trainer's densification schedule (default: off, and no opacity reset).");
  args.AddOption("seed", "S", "0", "Random seed (camera order).");
  args.AddOption("metrics-interval",
    "N",
    "0",
    "The repaired log's train/test metrics every N iterations (every view rendered); 0: at "
    "most 10 rows, the first and last from the repair's own measurement.");
  args.AddOption("output", "DIR", "vis4gs-repair", "Folder for repaired.h5 and repair.csv.");
}

int Run(const Vis4GSArguments& args)
{
  const std::string sourcePath = args.GetPositional("SOURCE");
  const int iterations = args.GetInt("iterations");
  if (iterations <= 0)
  {
    throw std::runtime_error("--iterations must be positive");
  }
  const int warmup = args.GetInt("warmup");
  if (warmup < 0)
  {
    throw std::runtime_error("--warmup must be >= 0");
  }
  const int wanted = args.GetInt("iteration");
  // One session: the source (a log's snapshot and cameras, or a scene file "with its ids when
  // it has them" and its cameras), the cleaned scene as its second state, its fine-tune filter.
  vtkNew<vtkGaussianSession> session;
  session->SetFileName(sourcePath.c_str());
  session->SetIteration(wanted);
  session->ComputeScoresOff();
  const bool isLog = vtkGaussianSession::IsTrainingLogPath(sourcePath.c_str());
  const std::string imageFolder = isLog ? std::string() : args.Get("images");
  if (!isLog)
  {
    session->SetIdProperty("id");
    session->GetSceneReader()->IdPropertyOptionalOn();
    session->SetCamerasFileName(args.Get("cameras").c_str());
    Vis4GSSceneCameraRules(session->GetCameraReader());
    if (!imageFolder.empty() && !fs::is_directory(imageFolder))
    {
      throw std::runtime_error(imageFolder + ": --images is not a folder");
    }
    session->SetImageDirectory(imageFolder.c_str());
  }
  else
  {
    vtkGaussianTrainingLogReader* log = session->GetLogReader();
    log->SetFileName(sourcePath.c_str());
    const std::string errors = Vis4GSUpdateInformation(log);
    if (!errors.empty())
    {
      throw std::runtime_error(errors);
    }
    if (log->GetNumberOfSnapshots() == 0 || !log->HasCameras())
    {
      throw std::runtime_error(sourcePath + ": the training log needs a snapshot and /cameras");
    }
  }
  for (const int port : { vtkGaussianSession::GaussiansPort, vtkGaussianSession::CamerasPort })
  {
    const std::string errors = Vis4GSUpdate(session, port);
    if (!errors.empty())
    {
      throw std::runtime_error(errors);
    }
  }
  vtkPolyData* snapshot = session->GetGaussiansOutput();
  const int source = isLog ? session->GetLoadedIteration() : std::max(wanted, 0);
  if (!isLog)
  {
    std::vector<vis4gs::Camera> cameras;
    std::string error;
    vtkTable* table = session->GetCamerasOutput();
    // No camera file found: an empty table, no columns either.
    if (table->GetNumberOfRows() > 0 && !vis4gs::TableToCameras(table, cameras, &error))
    {
      throw std::runtime_error(sourcePath + ": the cameras: " + error);
    }
    if (cameras.empty())
    {
      throw std::runtime_error(sourcePath +
        ": no cameras found; give --cameras=cameras.json, a COLMAP folder or a transforms.json");
    }
    // Every camera needs its image; the fine-tune finds them by the same rule.
    if (!imageFolder.empty())
    {
      Vis4GSAttachImagesByName(cameras, imageFolder);
    }
    const std::string imageSource =
      imageFolder.empty() ? "the cameras of " + sourcePath : imageFolder;
    for (const vis4gs::Camera& c : cameras)
    {
      std::error_code ec;
      if (c.ImagePath.empty() || !fs::is_regular_file(c.ImagePath, ec))
      {
        throw std::runtime_error(imageSource + ": no image for camera \"" + c.Name + "\"" +
          (c.ImagePath.empty() ? std::string() : " (" + c.ImagePath + " is no file)") +
          "; give --images=DIR");
      }
    }
  }
  const std::string cleanedPath = args.GetPositional("CLEANED");
  vtkGaussianSession* cleaned = session->GetComparedSession();
  cleaned->SetFileName(cleanedPath.c_str());
  cleaned->SetIdProperty("id");
  cleaned->GetSceneReader()->IdPropertyOptionalOn();
  {
    const std::string errors = Vis4GSUpdate(cleaned, vtkGaussianSession::GaussiansPort);
    if (!errors.empty())
    {
      throw std::runtime_error(errors);
    }
  }

  // The deleted Gaussians: the snapshot's ids the cleaned scene lacks. The fine-tune starts
  // from the snapshot's own rows (every SH coefficient, exactly as logged).
  auto* keptArray = vtkIdTypeArray::SafeDownCast(
    cleaned->GetGaussiansOutput()->GetPointData()->GetArray(vis4gs::arrays::GaussianId));
  auto* snapshotIds =
    vtkIdTypeArray::SafeDownCast(snapshot->GetPointData()->GetArray(vis4gs::arrays::GaussianId));
  if (!keptArray || !snapshotIds)
  {
    throw std::runtime_error((keptArray ? sourcePath : cleanedPath) + ": no GaussianId");
  }
  std::vector<vtkIdType> keptIds(
    keptArray->GetPointer(0), keptArray->GetPointer(0) + keptArray->GetNumberOfValues());
  std::sort(keptIds.begin(), keptIds.end());
  vtkNew<vtkIdTypeArray> prunes;
  std::size_t found = 0;
  for (vtkIdType i = 0; i < snapshotIds->GetNumberOfValues(); ++i)
  {
    const bool keep = std::binary_search(keptIds.begin(), keptIds.end(), snapshotIds->GetValue(i));
    found += keep ? 1 : 0;
    if (!keep)
    {
      prunes->InsertNextValue(snapshotIds->GetValue(i));
    }
  }
  if (found != keptIds.size())
  {
    throw std::runtime_error(cleanedPath + ": holds " + std::to_string(keptIds.size() - found) +
      " ids that " +
      (isLog ? "the snapshot of iteration " + std::to_string(source) + " of " : std::string()) +
      sourcePath + " lacks (is it cleaned from this source, with its id property?)");
  }
  std::cout << "vis4gs repair: " << sourcePath << ", iteration " << source << ": "
            << snapshotIds->GetNumberOfValues() << " Gaussians, " << prunes->GetNumberOfValues()
            << " deleted in " << cleanedPath << "\n";

  const fs::path output = args.Get("output");
  // Both outputs are moved into place together: a failure leaves an earlier run's pair as it was.
  Vis4GSStagingFolder staging(output, "repair");
  const fs::path logOut = output / "repaired.h5";
  vtkGaussianFineTuneFilter* tune = session->GetFineTuneFilter();
  tune->SetRemovedIds(prunes);
  tune->SetSourceIteration(source);
  tune->SetIterations(iterations);
  tune->SetWarmupIterations(warmup);
  tune->SetMetricsInterval(std::max(0, args.GetInt("metrics-interval")));
  tune->SetFreePositions(args.GetFlag("free-positions"));
  tune->SetDensify(args.GetFlag("densify"));
  tune->SetSeed(static_cast<vtkTypeUInt64>(std::stoull(args.Get("seed"))));
  tune->SetNumberOfThreads(std::max(0, args.GetInt("threads")));
  tune->SetOutputLogFileName((staging.Get() / logOut.filename()).string().c_str());
  tune->SetProducer((std::string("vis4gs repair ") + VIS4GS_VERSION).c_str());
  // A scene file's images are embedded so that the repaired log stands on its own; a log's
  // scene name and embedding are its own (the filter reads them from the cameras' log).
  tune->SetSceneName(isLog ? "" : fs::path(sourcePath).stem().string().c_str());
  tune->SetEmbedImages(isLog ? -1 : 1);
  {
    const std::string errors = Vis4GSUpdate(tune, 1);
    if (!errors.empty())
    {
      throw std::runtime_error(errors);
    }
  }
  vtkTable* figures = tune->GetFiguresOutput();

  std::ostringstream csv;
  const std::vector<std::string>& columns = vis4gs::FineTuneFigureColumns();
  for (std::size_t c = 0; c < columns.size(); ++c)
  {
    csv << (c > 0 ? "," : "") << columns[c];
  }
  csv << "\n" << std::setprecision(9);
  for (vtkIdType r = 0; r < figures->GetNumberOfRows(); ++r)
  {
    const std::string view = figures->GetValueByName(r, columns[0].c_str()).ToString();
    const std::string split = figures->GetValueByName(r, columns[1].c_str()).ToString();
    std::vector<double> values;
    for (std::size_t c = 2; c < columns.size(); ++c)
    {
      values.push_back(
        vtkDataArray::SafeDownCast(figures->GetColumnByName(columns[c].c_str()))->GetTuple1(r));
    }
    csv << view << "," << split;
    for (double x : values)
    {
      csv << "," << x;
    }
    csv << "\n";
    if (view == "mean")
    {
      std::cout << "vis4gs repair: " << split << " PSNR " << values[0] << " dB, after deleting "
                << values[1] << " dB, after " << iterations << " iterations " << values[2]
                << " dB\n";
    }
  }
  const fs::path csvPath = output / "repair.csv";
  vis4gs::WriteTextFile((staging.Get() / csvPath.filename()).string(), csv.str());
  staging.Commit();
  std::cout << "vis4gs repair: wrote " << logOut.string() << " (" << prunes->GetNumberOfValues()
            << " prune events at iteration " << source << ", iterations " << source + 1 << ".."
            << tune->GetLastIteration() << ", " << tune->GetTrainSeconds() / iterations
            << " s per iteration) and " << csvPath.string() << "\n";
  return 0;
}
} // namespace

VIS4GS_REGISTER_COMMAND("repair",
  "Fine-tune a cleaned scene with the built-in trainer; the log records the deletion as prunes.",
  Define,
  Run)

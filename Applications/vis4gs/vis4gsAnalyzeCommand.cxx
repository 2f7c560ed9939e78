// SPDX-License-Identifier: BSD-3-Clause
// `vis4gs analyze`: batch diagnosis of a scene (DESIGN §4, §5). Reads Gaussians (PLY/.splat),
// cameras (cameras.json or a COLMAP dataset folder) and training images, computes the
// requested scores through vtkGaussianArtifactScoreFilter, and writes: the scene with the
// scores as extra PLY properties, a CSV table, the top-k Gaussians per score, overlay images
// of training views (scores through viridis, rendered with the Core rasteriser), and a
// self-contained HTML report (base64 PNGs, inline SVG histograms, tables, settings, timings).
#include "Vis4GSCommand.h"

#include "GaussianIO.h"
#include "GaussianMath.h"
#include "ImageIO.h"
#include "Rasterizer.h"
#include "SpecialValues.h"
#include "SplatAttributes.h" // vis4gs::OverlayColor, the colour map the splat mapper uses
#include "TrainingLogReader.h"
#include "Vis4GSDataModel.h"
#include "Vis4GSMPI.h"
#include "Vis4GSSceneCameras.h"
#include "vtkGaussianArtifactScoreFilter.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkTable.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <unistd.h>

namespace
{
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double Since(Clock::time_point t)
{
  return std::chrono::duration<double>(Clock::now() - t).count();
}

void Define(Vis4GSArguments& args)
{
  args.AddPositional("scene",
    "Gaussian scene: a 3DGS .ply, compressed PLY, SOG (.sog, meta.json or its folder) or .splat, "
    "or a training log .h5 (DESIGN §3).");
  args.AddOption("iteration",
    "N",
    "-1",
    "Training log only: analyze the snapshot nearest to iteration N; -1 takes the last one.");
  args.AddOption("cameras",
    "FILE|DIR",
    "",
    "cameras.json, a COLMAP dataset folder (sparse/0 + images) or a transforms*.json (file or "
    "folder). Default: cameras.json "
    "beside the scene or two folders up (the trainer's model folder).");
  args.AddOption("images",
    "DIR",
    "",
    "Folder of training images, matched to cameras by name. Default: the COLMAP dataset's.");
  args.AddOption("scores",
    "LIST",
    "coverage,blur,needle,shape",
    "Scores to compute: coverage, blur, needle, shape (comma-separated).");
  args.AddOption("output", "DIR", "vis4gs-analysis", "Folder the results are written to.");
  args.AddOption("top", "K", "20", "Number of most suspicious Gaussians listed per score.");
  args.AddOption("loss-resolution", "F", "1", "Loss-map resolution factor: 1, 2, 4 or 8.");
  args.AddOption("coverage-resolution", "F", "1", "Coverage resolution factor: 1, 2, 4 or 8.");
  args.AddOption("view-stride", "K", "1", "Use every K-th training view.");
  args.AddOption("footprint", "MODE", "alpha", "Footprint: alpha (exact) or ellipse (3 sigma).");
  args.AddFlag("float-accumulation", false, "Accumulate footprint sums in float.");
  args.AddOption("occlusion-threshold",
    "T",
    "0",
    "Occlusion-aware coverage: count a view only when max alpha*T >= T (0: off).");
  args.AddOption("overlay-views", "N", "4", "Number of training views rendered as overlays.");
  args.AddFlag("mpi",
    false,
    "Spread the training views over MPI processes (implied when launched by mpiexec; "
    "process 0 writes the outputs).");
}

// ---------------------------------------------------------------------------------------
std::vector<vis4gs::Camera> LoadCameras(const std::string& scene, const Vis4GSArguments& args)
{
  return Vis4GSFindSceneCameras(scene, args.Get("cameras"));
}

// The snapshot of a training log, its cameras, and its training images: embedded ones
// ("/images/<name>") are written once to <output>/images so the score filter reads them like
// any dataset; others are paths relative to the log.
vis4gs::GaussianCloud ReadLogScene(const std::string& path,
  const Vis4GSArguments& args,
  const fs::path& output,
  bool needCameras,
  std::vector<vis4gs::Camera>& cameras,
  bool writeImages)
{
  const vis4gs::TrainingLogReader log(path);
  for (const std::string& lack : log.GetLacks())
  {
    std::cerr << "vis4gs analyze: note: " << path << ": " << lack << "\n";
  }
  const std::vector<int>& iterations = log.GetSnapshotIterations();
  if (iterations.empty())
  {
    throw std::runtime_error(path + ": the training log holds no snapshot to analyze");
  }
  const int wanted = args.GetInt("iteration");
  vis4gs::SnapshotReadOptions options;
  options.ShDegree = -1;
  int logged = 0;
  vis4gs::GaussianCloud cloud =
    log.ReadNearestSnapshot(wanted < 0 ? iterations.back() : wanted, options, &logged);
  std::cout << "vis4gs analyze: " << path << ": snapshot of iteration " << logged << ", "
            << cloud.Count << " Gaussians\n";
  if (!needCameras)
  {
    return cloud;
  }
  if (!log.HasCameras())
  {
    throw std::runtime_error(path +
      ": the training log has no /cameras, which coverage, blur "
      "and needle need");
  }
  cameras = log.ReadCameras();
  const fs::path logDir = fs::path(path).parent_path();
  for (vis4gs::Camera& c : cameras)
  {
    const std::string prefix = "/images/";
    if (c.ImagePath.rfind(prefix, 0) == 0)
    {
      const std::string name = c.ImagePath.substr(prefix.size());
      const fs::path file = output / "images" / (name + ".png");
      if (writeImages) // under MPI process 0 writes them once for every process
      {
        int width = 0, height = 0;
        const std::vector<unsigned char> pixels = log.ReadImage(name, width, height);
        fs::create_directories(file.parent_path());
        vis4gs::WritePng8(file.string(), width, height, 3, pixels.data());
      }
      c.ImagePath = file.string();
    }
    else if (!c.ImagePath.empty() && fs::path(c.ImagePath).is_relative())
    {
      c.ImagePath = (logDir / c.ImagePath).string();
    }
  }
  return cloud;
}

void AttachImagesByName(std::vector<vis4gs::Camera>& cameras, const std::string& folder)
{
  if (!fs::is_directory(folder))
  {
    throw std::runtime_error(folder + ": --images is not a folder");
  }
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::directory_iterator(folder))
  {
    const std::string name = entry.path().filename().string();
    files.emplace(name.substr(0, name.find('.')), entry.path().string());
  }
  for (vis4gs::Camera& c : cameras)
  {
    const auto it = files.find(c.Name);
    c.ImagePath = it == files.end() ? std::string() : it->second;
  }
}

std::string Base64(const std::vector<unsigned char>& bytes)
{
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3)
  {
    const unsigned v = bytes[i] << 16 | (i + 1 < bytes.size() ? bytes[i + 1] << 8 : 0) |
      (i + 2 < bytes.size() ? bytes[i + 2] : 0);
    out += table[v >> 18 & 63];
    out += table[v >> 12 & 63];
    out += i + 1 < bytes.size() ? table[v >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? table[v & 63] : '=';
  }
  return out;
}

std::vector<unsigned char> ReadBytes(const fs::path& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::vector<unsigned char>(std::istreambuf_iterator<char>(in), {});
}

std::string Html(const std::string& s)
{
  std::string o;
  for (char c : s)
  {
    o += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
  }
  return o;
}

// Inline SVG histogram (40 bins, linear counts).
std::string Histogram(const std::vector<double>& v, const std::string& title)
{
  double lo = 0, hi = 0;
  bool first = true;
  for (double x : v)
  {
    if (std::isfinite(x))
    {
      lo = first ? x : std::min(lo, x);
      hi = first ? x : std::max(hi, x);
      first = false;
    }
  }
  const int bins = 40;
  std::vector<std::size_t> count(bins, 0);
  for (double x : v)
  {
    if (std::isfinite(x))
    {
      const int b = hi > lo ? std::min(bins - 1, static_cast<int>((x - lo) / (hi - lo) * bins)) : 0;
      ++count[b];
    }
  }
  const std::size_t peak = std::max<std::size_t>(1, *std::max_element(count.begin(), count.end()));
  std::ostringstream s;
  s << "<figure><svg width=\"420\" height=\"170\" xmlns=\"http://www.w3.org/2000/svg\">"
    << "<rect x=\"0\" y=\"0\" width=\"420\" height=\"170\" fill=\"#fff\"/>";
  for (int b = 0; b < bins; ++b)
  {
    const double h = 130.0 * count[b] / peak;
    const auto col = vis4gs::OverlayColor((b + 0.5) / bins, 0, 1, vis4gs::SuspiciousEndOf(title));
    s << "<rect x=\"" << 10 + b * 10 << "\" y=\"" << 140 - h << "\" width=\"9\" height=\"" << h
      << "\" fill=\"rgb(" << int(col[0] * 255) << "," << int(col[1] * 255) << ","
      << int(col[2] * 255) << ")\"><title>" << count[b] << "</title></rect>";
  }
  s << "<text x=\"10\" y=\"160\" font-size=\"11\">" << lo << "</text><text x=\"410\" y=\"160\" "
    << "font-size=\"11\" text-anchor=\"end\">" << hi << "</text></svg><figcaption>" << Html(title)
    << " (" << v.size() << " Gaussians; highest bin " << peak << ")</figcaption></figure>\n";
  return s.str();
}

// The overlay images' legend: the colour map over [lo, hi] as an SVG gradient, the
// suspicious end labelled.
std::string Legend(const std::string& name, double lo, double hi)
{
  const vis4gs::SuspiciousEnd end = vis4gs::SuspiciousEndOf(name);
  std::ostringstream s;
  s << "<figure><svg width=\"420\" height=\"46\" xmlns=\"http://www.w3.org/2000/svg\">"
    << "<defs><linearGradient id=\"map-" << Html(name) << "\">";
  for (int k = 0; k <= 16; ++k)
  {
    const auto c = vis4gs::OverlayColor(k / 16.0, 0, 1, end);
    s << "<stop offset=\"" << k / 16.0 << "\" stop-color=\"rgb(" << int(c[0] * 255) << ","
      << int(c[1] * 255) << "," << int(c[2] * 255) << ")\"/>";
  }
  s << "</linearGradient></defs><rect x=\"10\" y=\"4\" width=\"400\" height=\"18\" fill=\"url(#map-"
    << Html(name) << ")\"/><text x=\"10\" y=\"38\" font-size=\"11\">" << lo
    << (end == vis4gs::SuspiciousEnd::Low ? " (suspicious)" : "")
    << "</text><text x=\"410\" y=\"38\" font-size=\"11\" text-anchor=\"end\">"
    << (end == vis4gs::SuspiciousEnd::High ? "(suspicious) " : "") << hi
    << "</text></svg><figcaption>" << Html(name) << " colour map"
    << (end == vis4gs::SuspiciousEnd::None ? "" : ": the suspicious end is the bright (yellow) one")
    << "</figcaption></figure>\n";
  return s.str();
}

std::vector<std::size_t> TopK(const std::vector<double>& v, std::size_t k)
{
  std::vector<std::size_t> order(v.size());
  std::iota(order.begin(), order.end(), 0);
  k = std::min(k, v.size());
  std::partial_sort(order.begin(),
    order.begin() + k,
    order.end(),
    [&](std::size_t a, std::size_t b)
    {
      const double x = std::isfinite(v[a]) ? v[a] : -1, y = std::isfinite(v[b]) ? v[b] : -1;
      return x > y || (x == y && a < b);
    });
  order.resize(k);
  return order;
}

// ---------------------------------------------------------------------------------------
// The outputs go to a hidden folder inside the output folder and are moved into place only when
// all of them are written, so a failure (or a process killed under MPI) leaves no partial
// scores.csv, scores.ply or report.html; the hidden folder is removed on failure when possible.
class StagingFolder
{
public:
  explicit StagingFolder(const fs::path& output)
    : Output(output)
    , Path(output / (".vis4gs-analyze-partial-" + std::to_string(::getpid())))
  {
    fs::create_directories(this->Path);
  }
  ~StagingFolder()
  {
    std::error_code ec;
    fs::remove_all(this->Path, ec);
  }
  StagingFolder(const StagingFolder&) = delete;
  StagingFolder& operator=(const StagingFolder&) = delete;

  const fs::path& Get() const { return this->Path; }

  // Renames every file into the output folder (report.html last: it marks a complete run).
  void Commit()
  {
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(this->Path))
    {
      files.push_back(entry.path());
    }
    std::stable_partition(
      files.begin(), files.end(), [](const fs::path& p) { return p.filename() != "report.html"; });
    for (const fs::path& file : files)
    {
      fs::rename(file, this->Output / file.filename());
    }
  }

private:
  fs::path Output;
  fs::path Path;
};

int Run(const Vis4GSArguments& args)
{
  const auto start = Clock::now();
  const Vis4GSMPISession mpi(args.GetFlag("mpi"));
  vtkMultiProcessController* controller =
    mpi.Active() ? vtkMultiProcessController::GetGlobalController() : nullptr;
  const std::string scene = args.GetPositional("scene");
  const fs::path output = args.Get("output");
  const std::size_t top = static_cast<std::size_t>(std::max(0, args.GetInt("top")));
  std::string extension = fs::path(scene).extension().string();
  std::transform(extension.begin(),
    extension.end(),
    extension.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const bool isLog = extension == ".h5" || extension == ".hdf5";
  // Requested scores.
  std::map<std::string, bool> want{
    { "coverage", false }, { "blur", false }, { "needle", false }, { "shape", false }
  };
  {
    std::stringstream list(args.Get("scores"));
    std::string item;
    while (std::getline(list, item, ','))
    {
      if (!want.count(item))
      {
        throw std::runtime_error(
          "--scores: unknown score '" + item + "' (expected coverage, blur, needle, shape)");
      }
      want[item] = true;
    }
  }
  const std::string footprint = args.Get("footprint");
  if (footprint != "alpha" && footprint != "ellipse")
  {
    throw std::runtime_error("--footprint must be alpha or ellipse, not '" + footprint + "'");
  }
  for (const char* opt : { "loss-resolution", "coverage-resolution" })
  {
    const int f = args.GetInt(opt);
    if (f != 1 && f != 2 && f != 4 && f != 8)
    {
      throw std::runtime_error(std::string("--") + opt + " must be 1, 2, 4 or 8");
    }
  }

  // Read.
  auto t0 = Clock::now();
  const bool needCameras = want["coverage"] || want["blur"] || want["needle"];
  vis4gs::GaussianCloud cloud;
  std::vector<vis4gs::Camera> cameras;
  if (isLog)
  {
    cloud = ReadLogScene(scene, args, output, needCameras, cameras, mpi.Rank() == 0);
  }
  else
  {
    vis4gs::GaussianReadReport report;
    cloud = vis4gs::ReadGaussianScene(scene, {}, &report);
    for (const std::string& w : report.Warnings)
    {
      std::cerr << "vis4gs analyze: warning: " << w << "\n";
    }
    if (needCameras)
    {
      cameras = LoadCameras(scene, args);
    }
  }
  if (mpi.Rank() == 0)
  {
    // Say which Gaussians no score covers, per reason, before spending time on the scores.
    const vis4gs::SpecialValueCounts special = vis4gs::CountSpecialValues(cloud);
    for (const std::string& line :
      { vis4gs::DescribeSkipped(special, false), vis4gs::DescribeDrawnSpecials(special) })
    {
      if (!line.empty())
      {
        std::cerr << "vis4gs analyze: note: " << scene << ": " << line
                  << " (Documentation/special-values.md)\n";
      }
    }
  }
  if (needCameras && cameras.empty())
  {
    throw std::runtime_error(scene +
      ": coverage, blur and needle need cameras; give --cameras=cameras.json or a COLMAP folder");
  }
  if (!args.Get("images").empty())
  {
    AttachImagesByName(cameras, args.Get("images"));
  }
  if (controller)
  {
    controller->Barrier(); // the images process 0 extracted from a log are on disk
  }
  const double tRead = Since(t0);

  // Scores, through the VTK filter.
  t0 = Clock::now();
  vtkNew<vtkPolyData> polyData;
  vis4gs::GaussianCloudToPolyData(cloud, polyData);
  vtkNew<vtkTable> table;
  vis4gs::CamerasToTable(cameras, table);
  vtkNew<vtkGaussianArtifactScoreFilter> filter;
  filter->SetInputData(polyData);
  if (needCameras)
  {
    filter->SetCamerasData(table);
  }
  filter->SetComputeViewCoverage(want["coverage"]);
  filter->SetComputeBlurScore(want["blur"]);
  filter->SetComputeNeedleScore(want["needle"]);
  filter->SetComputeNeedleShape(want["shape"]);
  filter->SetLossResolution(args.GetInt("loss-resolution"));
  filter->SetCoverageResolution(args.GetInt("coverage-resolution"));
  filter->SetViewStride(args.GetInt("view-stride"));
  filter->SetFootprintMode(footprint == "ellipse" ? 1 : 0);
  filter->SetFloatAccumulation(args.GetFlag("float-accumulation"));
  filter->SetOcclusionThreshold(args.GetDouble("occlusion-threshold"));
  const bool verbose = args.GetFlag("verbose");
  vtkNew<vtkCallbackCommand> progress;
  progress->SetCallback(
    [](vtkObject* caller, unsigned long, void*, void*)
    {
      std::cerr << "\rvis4gs analyze: "
                << static_cast<int>(100 * static_cast<vtkAlgorithm*>(caller)->GetProgress()) << "%"
                << std::flush;
    });
  if (verbose)
  {
    filter->AddObserver(vtkCommand::ProgressEvent, progress);
  }
  filter->Update();
  if (verbose)
  {
    std::cerr << "\n";
  }
  vtkPointData* pd = filter->GetOutput()->GetPointData();
  const std::vector<std::pair<std::string, const char*>> names{ { "coverage",
                                                                  vis4gs::arrays::ViewCoverage },
    { "blur", vis4gs::arrays::BlurScore },
    { "needle", vis4gs::arrays::NeedleScore },
    { "shape", vis4gs::arrays::NeedleShape } };
  std::vector<std::pair<std::string, std::vector<double>>> scores;
  for (const auto& [key, array] : names)
  {
    if (!want[key])
    {
      continue;
    }
    vtkDataArray* a = pd->GetArray(array);
    if (!a)
    {
      throw std::runtime_error("computing " + std::string(array) + " failed (see the error above)");
    }
    std::vector<double> v(static_cast<std::size_t>(a->GetNumberOfTuples()));
    for (std::size_t i = 0; i < v.size(); ++i)
    {
      v[i] = a->GetTuple1(static_cast<vtkIdType>(i));
    }
    scores.emplace_back(array, std::move(v));
  }
  std::vector<unsigned char> flags(cloud.Count, 0);
  if (vtkDataArray* f = pd->GetArray("NoVisibleView"))
  {
    for (std::size_t i = 0; i < flags.size(); ++i)
    {
      flags[i] = static_cast<unsigned char>(f->GetTuple1(static_cast<vtkIdType>(i)));
    }
  }
  const double tScores = Since(t0);
  if (mpi.Active())
  {
    std::cout << "vis4gs analyze: process " << mpi.Rank() << " of " << mpi.Size() << " rendered "
              << filter->GetNumberOfViewsRendered() << " of " << filter->GetNumberOfViewsUsed()
              << " views\n";
    if (mpi.Rank() != 0)
    {
      return 0; // process 0 has the reduced scores too and writes the outputs
    }
  }

  // Outputs.
  t0 = Clock::now();
  fs::create_directories(output);
  StagingFolder staging(output);
  vis4gs::GaussianCloud withScores = cloud;
  for (const auto& [name, values] : scores)
  {
    vis4gs::ExtraProperty p;
    p.Name = name;
    p.Type = vis4gs::ScalarType::Float32;
    p.Bytes.resize(4 * values.size());
    for (std::size_t i = 0; i < values.size(); ++i)
    {
      const float f = static_cast<float>(values[i]);
      std::memcpy(&p.Bytes[4 * i], &f, 4);
    }
    withScores.Extra.push_back(std::move(p));
  }
  if (needCameras)
  {
    vis4gs::ExtraProperty p;
    p.Name = "NoVisibleView";
    p.Type = vis4gs::ScalarType::UInt8;
    p.Bytes.assign(flags.begin(), flags.end());
    withScores.Extra.push_back(std::move(p));
  }
  vis4gs::WriteGaussianPly((staging.Get() / "scores.ply").string(), withScores);
  {
    std::ofstream csv(staging.Get() / "scores.csv");
    csv << "GaussianId";
    for (const auto& s : scores)
    {
      csv << "," << s.first;
    }
    csv << (needCameras ? ",NoVisibleView\n" : "\n");
    csv << std::setprecision(9);
    for (std::size_t i = 0; i < cloud.Count; ++i)
    {
      csv << cloud.GetId(i);
      for (const auto& s : scores)
      {
        csv << "," << s.second[i];
      }
      if (needCameras)
      {
        csv << "," << int(flags[i]);
      }
      csv << "\n";
    }
    if (!csv)
    {
      throw std::runtime_error((output / "scores.csv").string() + ": could not be written");
    }
  }
  // Top-k: highest blur/needle/shape, lowest coverage (floaters).
  std::map<std::string, std::vector<std::size_t>> tops;
  for (const auto& [name, values] : scores)
  {
    std::vector<double> key = values;
    if (name == vis4gs::arrays::ViewCoverage)
    {
      for (double& k : key)
      {
        k = -k;
      }
    }
    tops[name] = TopK(key, top);
    std::cout << "vis4gs analyze: top " << tops[name].size() << " by " << name
              << (name == vis4gs::arrays::ViewCoverage ? " (lowest first)" : "") << ":\n";
    for (std::size_t i : tops[name])
    {
      std::cout << "  Gaussian " << cloud.GetId(i) << "  " << values[i] << "\n";
    }
  }
  // Overlays of the first training views: colours replaced by the overlay colour map of
  // the score (vis4gs::OverlayColor, the scene view's), its suspicious end bright on black.
  std::vector<std::pair<std::string, fs::path>> overlays;
  std::vector<std::string> legends;
  const int overlayViews = std::max(0, args.GetInt("overlay-views"));
  if (needCameras && overlayViews > 0)
  {
    for (const auto& [name, values] : scores)
    {
      if (name == vis4gs::arrays::NeedleShape)
      {
        continue;
      }
      std::vector<double> sorted;
      for (double v : values)
      {
        if (std::isfinite(v))
        {
          sorted.push_back(v);
        }
      }
      std::sort(sorted.begin(), sorted.end());
      const double hi = sorted.empty() ? 1.0
        : name == vis4gs::arrays::ViewCoverage
        ? 1.0
        : std::max(1e-30, sorted[static_cast<std::size_t>(0.99 * (sorted.size() - 1))]);
      legends.push_back(Legend(name, 0.0, hi));
      const vis4gs::SuspiciousEnd end = vis4gs::SuspiciousEndOf(name);
      vis4gs::GaussianCloud colored = cloud;
      colored.ShDegree = 0;
      colored.SH.assign(3 * cloud.Count, 0.0f);
      for (std::size_t i = 0; i < cloud.Count; ++i)
      {
        const auto c = vis4gs::OverlayColor(values[i], 0.0, hi, end);
        for (int k = 0; k < 3; ++k)
        {
          colored.SH[3 * i + k] = static_cast<float>((c[k] - 0.5) / vis4gs::sh::C0);
        }
      }
      int done = 0;
      for (std::size_t v = 0; v < cameras.size() && done < overlayViews; ++v)
      {
        if (cameras[v].Split != vis4gs::CameraSplit::Train)
        {
          continue;
        }
        std::cout << "vis4gs analyze: overlay " << name << " in " << cameras[v].Name << " ("
                  << done + 1 << " of " << overlayViews << ")" << std::endl;
        const auto render = vis4gs::Rasterize<float>(colored, cameras[v]);
        vis4gs::Image image;
        image.Width = render.Width;
        image.Height = render.Height;
        image.Pixels = render.Color;
        const fs::path file = staging.Get() / (std::string(name) + "-" + cameras[v].Name + ".png");
        vis4gs::WritePng(file.string(), image);
        overlays.emplace_back(std::string(name) + " in " + cameras[v].Name, file);
        ++done;
      }
    }
  }
  const double tOutputs = Since(t0);

  // HTML report.
  std::ofstream html(staging.Get() / "report.html");
  html << "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>vis4gs analyze: "
       << Html(scene) << "</title><style>body{font-family:sans-serif;margin:2em}"
       << "table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:2px 8px;"
       << "text-align:right}figure{display:inline-block;margin:8px}</style></head><body>\n"
       << "<h1>Gaussian diagnosis of " << Html(scene) << "</h1>\n<p>" << cloud.Count
       << " Gaussians, " << cameras.size() << " cameras, " << filter->GetNumberOfViewsUsed()
       << " training views used, " << filter->GetNumberOfViewsWithoutImage() << " without image, "
       << filter->GetNumberOfFlaggedGaussians()
       << " Gaussians flagged (no visible view or invalid parameters).</p>\n";
  html << "<h2>Settings</h2><table>";
  for (const char* opt : { "scores",
         "cameras",
         "images",
         "loss-resolution",
         "coverage-resolution",
         "view-stride",
         "footprint",
         "occlusion-threshold",
         "top" })
  {
    html << "<tr><th>" << opt << "</th><td>" << Html(args.Get(opt)) << "</td></tr>";
  }
  html << "<tr><th>float-accumulation</th><td>"
       << (args.GetFlag("float-accumulation") ? "yes" : "no") << "</td></tr></table>\n";
  html << "<h2>Timings</h2><table><tr><th>reading</th><td>" << tRead
       << " s</td></tr><tr><th>scores</th><td>" << tScores
       << " s</td></tr><tr><th>outputs and overlays</th><td>" << tOutputs
       << " s</td></tr></table>\n<h2>Histograms</h2>\n";
  for (const auto& [name, values] : scores)
  {
    html << Histogram(values, name);
  }
  html << "<h2>Overlays</h2><p>Scores through viridis (coverage 0..1; other scores 0..their "
          "99th percentile), rendered with the rasteriser on black. The map is turned so that "
          "the suspicious end of each score is the bright (yellow) end: low View Coverage, high "
          "Blur and Needle scores.</p>\n";
  for (const std::string& legend : legends)
  {
    html << legend;
  }
  html << "<br>\n";
  for (const auto& [title, file] : overlays)
  {
    html << "<figure><img src=\"data:image/png;base64," << Base64(ReadBytes(file))
         << "\"><figcaption>" << Html(title) << "</figcaption></figure>\n";
  }
  html << "<h2>Most suspicious Gaussians</h2>\n";
  for (const auto& [name, values] : scores)
  {
    html << "<h3>" << name << (name == vis4gs::arrays::ViewCoverage ? " (lowest)" : "")
         << "</h3><table><tr><th>rank</th><th>GaussianId</th>";
    for (const auto& s : scores)
    {
      html << "<th>" << s.first << "</th>";
    }
    html << "</tr>";
    int rank = 1;
    for (std::size_t i : tops[name])
    {
      html << "<tr><td>" << rank++ << "</td><td>" << cloud.GetId(i) << "</td>";
      for (const auto& s : scores)
      {
        html << "<td>" << s.second[i] << "</td>";
      }
      html << "</tr>";
    }
    html << "</table>\n";
  }
  html << "<p>Total " << Since(start) << " s.</p></body></html>\n";
  if (!html)
  {
    throw std::runtime_error((output / "report.html").string() + ": could not be written");
  }
  html.close();
  staging.Commit();
  std::cout << "vis4gs analyze: wrote " << (output / "report.html").string() << ", scores.csv, "
            << "scores.ply and " << overlays.size() << " overlay images\n";
  return 0;
}
}

VIS4GS_REGISTER_COMMAND("analyze",
  "Compute View Coverage, Blur and Needle scores of a scene; write tables, images and a report.",
  Define,
  Run)

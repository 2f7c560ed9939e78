// SPDX-License-Identifier: BSD-3-Clause
// `vis4gs analyze`: batch diagnosis of a scene (DESIGN §4, §5). Reads Gaussians (PLY/SPZ/.splat),
// cameras (cameras.json or a COLMAP dataset folder) and training images, computes the
// requested scores through vtkGaussianArtifactScoreFilter, and writes: the scene with the
// scores as extra PLY properties, a CSV table, the top-k Gaussians per score, overlay images
// of training views (scores through viridis, rendered with the Core rasteriser), and a
// self-contained HTML report (base64 PNGs, inline SVG histograms, tables, settings, timings).
// With --select=RULE (Core/Selection/SelectionRule.h) it selects Gaussians by a rule over the
// scores and attributes; --delete writes the scene without them (cleaned.ply) and --report
// measures the deletion against the training and test images (the session's removal ports,
// vtkGaussianRemovalEffectFilter): before-after.csv and a section of the report with the
// per-view table and images.
// Over 1,200 lines on purpose: one command's flow (arguments, the session's reading and staged
// scores, outputs, overlays, the report), each piece used only here; what other commands share is
// in Vis4GSScoreOutputs, Vis4GSProgressiveStages and the session. (Next split: the HTML report.)
#include "Vis4GSCommand.h"
#include "Vis4GSStateFiles.h"

#include "GaussianIO.h"
#include "GaussianMath.h"
#include "ImageIO.h"
#include "Rasterizer.h"
#include "RemovalEffect.h"
#include "ScoreRegistry.h"
#include "SelectionRule.h"
#include "SpecialValues.h"
#include "SplatAttributes.h" // vis4gs::OverlayColor, the colour map the splat mapper uses
#include "TrainingLogReader.h"
#include "Vis4GSDataModel.h"
#include "Vis4GSMPI.h"
#include "Vis4GSPipeline.h"
#include "Vis4GSProgressiveStages.h"
#include "Vis4GSSceneCameras.h"
#include "Vis4GSScoreOutputs.h"
#include "Vis4GSStagingFolder.h"
#include "vtkGaussianArtifactScoreFilter.h"
#include "vtkGaussianRemovalEffectFilter.h"
#include "vtkGaussianSceneReader.h"
#include "vtkGaussianSession.h"
#include "vtkGaussianTrainingLogReader.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkTable.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <numeric>
#include <optional>
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
    "Gaussian scene: a 3DGS .ply, compressed PLY, SOG (.sog, meta.json or its folder), .spz, "
    ".ksplat, .splat or glTF (.glb, .gltf), or a training log .h5 (DESIGN §3).");
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
  std::string scoreHelp = "Scores to compute (comma-separated):";
  for (const vis4gs::ScoreDefinition& d : vis4gs::ScoreDefinitions())
  {
    scoreHelp += std::string(" ") + d.Name + " (" + d.ArrayName + ", suspicious when " +
      (d.Suspicious == vis4gs::SuspiciousEnd::Low ? "low" : "high") +
      ((d.Needs & vis4gs::NeedsImages)       ? ", needs images"
          : (d.Needs & vis4gs::NeedsCameras) ? ", needs cameras"
                                             : "") +
      "),";
  }
  scoreHelp.back() = '.';
  args.AddOption("scores", "LIST", vis4gs::DefaultScoreList(), scoreHelp);
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
  args.AddOption("stop-after-stage",
    "S",
    "0",
    "Progressive scores: 1 stops after the first, approximate stage (every 8th training view, "
    "loss and coverage maps at 1/4 resolution; its outputs say so); 2 computes that stage, then "
    "the exact scores with the other options, and reports the first stage's error against them "
    "(largest difference, overlap of the top 1 %); 0 computes the scores once, as the other "
    "options say.");
  args.AddOption("select",
    "RULE",
    "",
    "Select the Gaussians a rule matches, e.g. \"views<=3 and opacity>=0.5\", \"blur top 5%\", "
    "\"needle>=0.8\", \"isolated r=0.1\" (user guide, 'Guided clean-up'); the scores it reads are "
    "computed. Writes selection.csv and the rule in canonical form (selection-rule.txt); "
    "--select=@FILE reads the rule from FILE (e.g. a saved selection-rule.txt, to apply it to "
    "another iteration or run).");
  args.AddFlag(
    "delete", false, "With --select: write the scene without the selection (cleaned.ply).");
  args.AddFlag("report",
    false,
    "With --select: measure deleting the selection against the training and test images (PSNR, "
    "SSIM, L1 per view, before and after; before-after.csv) and add it to report.html.");
  args.AddFlag("mpi",
    false,
    "Spread the training views over MPI processes (implied when launched by mpiexec; "
    "process 0 writes the outputs).");
  args.AddFlag("share-preparation",
    false,
    "Under MPI: the processes of one machine prepare the view-independent part of the "
    "projection once between them, in POSIX shared memory (less memory; the same scores; "
    "slower views where shared memory gets no huge pages, as on the benchmark machine).");
  args.AddFlag("static-view-split",
    false,
    "Under MPI: each process renders a fixed part of the views (split by estimated cost), the "
    "same views on every run, instead of the processes of a machine taking the next view from a "
    "shared queue whenever one is free (the default: no process waits for a slower one; the "
    "scores are the same either way).");
}

// ---------------------------------------------------------------------------------------
// The cameras of @p session (its cameras port: a log's own, or a scene file's --cameras or the
// cameras.json beside it, read by Vis4GSSceneCameraRules), as the score filter gets them.
std::vector<vis4gs::Camera> SessionCameras(vtkGaussianSession* session)
{
  const std::string errors = Vis4GSUpdate(session, vtkGaussianSession::CamerasPort);
  if (!errors.empty())
  {
    throw std::runtime_error(errors);
  }
  std::vector<vis4gs::Camera> cameras;
  std::string error;
  vtkTable* table = session->GetCamerasOutput();
  // No camera file found: an empty table, no columns either.
  if (table->GetNumberOfRows() > 0 && !vis4gs::TableToCameras(table, cameras, &error))
  {
    throw std::runtime_error(std::string(session->GetFileName()) + ": the cameras: " + error);
  }
  return cameras;
}

// The Gaussians of a scene file or of the snapshot of a log nearest @p iteration (-1: the last)
// as the application, the Python layer and ParaView read them: the Gaussians port of the
// command's vtkGaussianSession (the reader chosen by content, no scores yet) into @p gaussians.
// Returns the loaded iteration (-1 for a scene file).
int ReadGaussians(vtkGaussianSession* session, int iteration, vtkPolyData* gaussians)
{
  session->SetIteration(iteration);
  session->ComputeScoresOff();
  // The activated opacity and scale arrays are for display; nothing here reads them (93 MB at
  // 6.1M Gaussians, held through the score pass's peak).
  session->GetSceneReader()->ActivatedArraysOff();
  const std::string errors = Vis4GSUpdate(session, vtkGaussianSession::GaussiansPort);
  if (!errors.empty())
  {
    throw std::runtime_error(errors);
  }
  gaussians->ShallowCopy(session->GetGaussiansOutput());
  return session->GetLoadedIteration();
}

// The snapshot of a training log, its cameras, and its training images: the session's score
// filter reads embedded ones ("/images/<name>") from the log; they are also written once to
// <output>/images, where the overlays and the clean-up measurement read them. The Gaussians are
// read by ReadGaussians (every SH degree) into @p gaussians; the cloud returned is theirs (no
// copy) for the Core steps after the scores.
std::shared_ptr<const vis4gs::GaussianCloud> ReadLogScene(vtkGaussianSession* session,
  const Vis4GSArguments& args,
  const fs::path& output,
  bool needCameras,
  std::vector<vis4gs::Camera>& cameras,
  bool writeImages,
  vtkPolyData* gaussians)
{
  const std::string path = session->GetFileName();
  vtkGaussianTrainingLogReader* reader = session->GetLogReader();
  reader->SetFileName(path.c_str());
  const std::string errors = Vis4GSUpdateInformation(reader);
  if (!errors.empty())
  {
    throw std::runtime_error(errors);
  }
  for (int i = 0; i < reader->GetNumberOfLacks(); ++i)
  {
    std::cerr << "vis4gs analyze: note: " << path << ": " << reader->GetLack(i) << "\n";
  }
  const int snapshots = reader->GetNumberOfSnapshots();
  if (snapshots == 0)
  {
    throw std::runtime_error(path + ": the training log holds no snapshot to analyze");
  }
  const int wanted = args.GetInt("iteration");
  const int logged = ReadGaussians(
    session, wanted < 0 ? reader->GetSnapshotIteration(snapshots - 1) : wanted, gaussians);
  std::string error;
  // The reader's own cloud when its arrays are one (no copy of gigabytes).
  const auto cloud = vis4gs::GaussianCloudOf(gaussians, &error);
  if (!cloud)
  {
    throw std::runtime_error(path + ": " + error);
  }
  std::cout << "vis4gs analyze: " << path << ": snapshot of iteration " << logged << ", "
            << cloud->Count << " Gaussians\n";
  if (!needCameras)
  {
    return cloud;
  }
  if (!reader->HasCameras())
  {
    throw std::runtime_error(path +
      ": the training log has no /cameras, which coverage, blur "
      "and needle need");
  }
  cameras = SessionCameras(session);
  // Only to write the embedded images out as PNG files (an output of the command).
  std::unique_ptr<vis4gs::TrainingLogReader> images;
  std::string writeError; // the first image that could not be written, said once
  std::size_t notWritten = 0;
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
        std::vector<unsigned char> pixels;
        try
        {
          if (!images)
          {
            images = std::make_unique<vis4gs::TrainingLogReader>(path);
          }
          pixels = images->ReadImage(name, width, height);
        }
        catch (const std::exception& e)
        {
          // Without its file the view counts as one without image: left out of the image
          // scores only (the scores that need none are computed all the same).
          std::cerr << "vis4gs analyze: warning: the training image " << c.ImagePath
                    << " cannot be read (" << e.what()
                    << "); its view is left out of the Blur and Needle scores\n";
        }
        try
        {
          if (!pixels.empty())
          {
            fs::create_directories(file.parent_path());
            vis4gs::WritePng8(file.string(), width, height, 3, pixels.data());
          }
        }
        catch (const std::exception& e)
        {
          // An output folder that cannot be written fails every image the same way: said once.
          writeError = writeError.empty() ? e.what() : writeError;
          ++notWritten;
        }
      }
      c.ImagePath = file.string();
    }
  }
  if (notWritten > 0)
  {
    std::cerr << "vis4gs analyze: warning: " << notWritten << " training images of the log could "
              << "not be written to " << (output / "images").string() << " (" << writeError
              << "); their views are left out of the Blur and Needle scores\n";
  }
  return cloud;
}

// A scene file read by ReadGaussians into @p gaussians (the score filter's input; the
// reader's warnings go to VTK's output window, stderr); the cloud returned is the reader's own
// (shared with the arrays, no copy) for the Core steps after the scores, and
// @p extras the file's other properties, which scores.ply keeps.
std::shared_ptr<const vis4gs::GaussianCloud> ReadSceneFile(vtkGaussianSession* session,
  vtkPolyData* gaussians,
  std::vector<vis4gs::ExtraProperty>& extras)
{
  const std::string path = session->GetFileName();
  ReadGaussians(session, -1, gaussians);
  std::string error;
  const auto cloud = vis4gs::GaussianCloudOf(gaussians, &error);
  if (!cloud)
  {
    throw std::runtime_error(path + ": " + error);
  }
  extras = cloud->Extra.empty() ? vis4gs::PolyDataExtraProperties(gaussians) : cloud->Extra;
  return cloud;
}

// The scene as its file holds it, for a new file of the same kind (cleaned.ply): the other
// properties of the file, and no id column where the file has none (the reader numbers its
// rows; such ids stay implicit).
vis4gs::GaussianCloud AsFileHasIt(const vis4gs::GaussianCloud& cloud,
  const std::vector<vis4gs::ExtraProperty>& extras,
  bool fileHasIds)
{
  vis4gs::GaussianCloud copy = cloud;
  copy.Extra = extras;
  if (!fileHasIds)
  {
    copy.Ids.clear();
  }
  return copy;
}

// What the overlays and the report read of @p cloud (positions, log-scales, rotations,
// opacity logits, ids), without the SH.
vis4gs::GaussianCloud GeometryOf(const vis4gs::GaussianCloud& cloud)
{
  vis4gs::GaussianCloud g;
  g.Count = cloud.Count;
  g.Positions = cloud.Positions;
  g.LogScales = cloud.LogScales;
  g.Rotations = cloud.Rotations;
  g.OpacityLogits = cloud.OpacityLogits;
  g.Ids = cloud.Ids;
  return g;
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

// Inline SVG histogram (40 bins). The bars are drawn on a log scale (log(1 + count)) when one
// bin holds most of the Gaussians, as scores of real scenes usually do (most Gaussians have no
// blur or needle problem): on a linear scale that bin is the only bar one sees and the tail,
// where the suspicious Gaussians are, draws as nothing. Each bar's <title> is its exact count
// and the <svg> says its scale (data-scale), so that a reader and a test see both.
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
  std::size_t finite = 0;
  for (double x : v)
  {
    if (std::isfinite(x))
    {
      const int b = hi > lo ? std::min(bins - 1, static_cast<int>((x - lo) / (hi - lo) * bins)) : 0;
      ++count[b];
      ++finite;
    }
  }
  const std::size_t peak = std::max<std::size_t>(1, *std::max_element(count.begin(), count.end()));
  const bool logScale = 2 * peak > finite && finite > 0;
  const auto height = [&](std::size_t c)
  {
    return logScale ? 130.0 * std::log1p(static_cast<double>(c)) / std::log1p(double(peak))
                    : 130.0 * c / peak;
  };
  std::ostringstream s;
  s << "<figure><svg width=\"420\" height=\"170\" data-scale=\"" << (logScale ? "log" : "linear")
    << "\" xmlns=\"http://www.w3.org/2000/svg\">"
    << "<rect x=\"0\" y=\"0\" width=\"420\" height=\"170\" fill=\"#fff\"/>";
  for (int b = 0; b < bins; ++b)
  {
    const double h = height(count[b]);
    const auto col = vis4gs::OverlayColor((b + 0.5) / bins, 0, 1, vis4gs::SuspiciousEndOf(title));
    s << "<rect x=\"" << 10 + b * 10 << "\" y=\"" << 140 - h << "\" width=\"9\" height=\"" << h
      << "\" fill=\"rgb(" << int(col[0] * 255) << "," << int(col[1] * 255) << ","
      << int(col[2] * 255) << ")\"><title>" << count[b] << "</title></rect>";
  }
  s << "<text x=\"10\" y=\"160\" font-size=\"11\">" << lo << "</text><text x=\"410\" y=\"160\" "
    << "font-size=\"11\" text-anchor=\"end\">" << hi << "</text></svg><figcaption>"
    << Vis4GSHtml(title) << " (" << v.size() << " Gaussians; highest bin " << peak
    << (logScale ? "; bars on a log scale, log(1 + count), since one bin holds most Gaussians" : "")
    << ")</figcaption></figure>\n";
  return s.str();
}

// The overlay images' legend: the colour map over [lo, hi] as an SVG gradient, the
// suspicious end labelled.
std::string Legend(const std::string& name, double lo, double hi)
{
  const vis4gs::SuspiciousEnd end = vis4gs::SuspiciousEndOf(name);
  std::ostringstream s;
  s << "<figure><svg width=\"420\" height=\"46\" xmlns=\"http://www.w3.org/2000/svg\">"
    << "<defs><linearGradient id=\"map-" << Vis4GSHtml(name) << "\">";
  for (int k = 0; k <= 16; ++k)
  {
    const auto c = vis4gs::OverlayColor(k / 16.0, 0, 1, end);
    s << "<stop offset=\"" << k / 16.0 << "\" stop-color=\"rgb(" << int(c[0] * 255) << ","
      << int(c[1] * 255) << "," << int(c[2] * 255) << ")\"/>";
  }
  s << "</linearGradient></defs><rect x=\"10\" y=\"4\" width=\"400\" height=\"18\" fill=\"url(#map-"
    << Vis4GSHtml(name) << ")\"/><text x=\"10\" y=\"38\" font-size=\"11\">" << lo
    << (end == vis4gs::SuspiciousEnd::Low ? " (suspicious)" : "")
    << "</text><text x=\"410\" y=\"38\" font-size=\"11\" text-anchor=\"end\">"
    << (end == vis4gs::SuspiciousEnd::High ? "(suspicious) " : "") << hi
    << "</text></svg><figcaption>" << Vis4GSHtml(name) << " colour map"
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
      // NaN last (a score that could not be computed ranks nowhere); +inf first (R/A of a
      // Gaussian that costs and never shows).
      const double x = std::isnan(v[a]) ? -HUGE_VAL : v[a], y = std::isnan(v[b]) ? -HUGE_VAL : v[b];
      return x > y || (x == y && a < b);
    });
  order.resize(k);
  while (!order.empty() && std::isnan(v[order.back()]))
  {
    order.pop_back();
  }
  return order;
}

// ---------------------------------------------------------------------------------------
// Clean-up by rule (--select, --delete, --report).

// Per pixel, the mean absolute error over RGB after the deletion minus before: red where the
// pixel got worse, green where it got better, full intensity at the view's largest change.
vis4gs::Image ErrorChangeImage(const vis4gs::Image& before,
  const vis4gs::Image& after,
  const vis4gs::Image& target)
{
  const std::size_t pixels = static_cast<std::size_t>(target.Width) * target.Height;
  std::vector<double> change(pixels);
  double largest = 0;
  for (std::size_t p = 0; p < pixels; ++p)
  {
    double d = 0;
    for (int c = 0; c < 3; ++c)
    {
      const std::size_t i = 3 * p + static_cast<std::size_t>(c);
      d += std::abs(after.Pixels[i] - target.Pixels[i]) -
        std::abs(before.Pixels[i] - target.Pixels[i]);
    }
    change[p] = d / 3;
    largest = std::max(largest, std::abs(change[p]));
  }
  vis4gs::Image image;
  image.Width = target.Width;
  image.Height = target.Height;
  image.Pixels.assign(3 * pixels, 0.0f);
  for (std::size_t p = 0; p < pixels && largest > 0; ++p)
  {
    const float v = static_cast<float>(std::abs(change[p]) / largest);
    image.Pixels[3 * p + (change[p] > 0 ? 0 : 1)] = v;
  }
  return image;
}

std::string Figure(const fs::path& file, const std::string& caption)
{
  return "<figure><img src=\"data:image/png;base64," + Base64(ReadBytes(file)) + "\"><figcaption>" +
    Vis4GSHtml(caption) + "</figcaption></figure>";
}

std::string Number(double v, int precision = 4)
{
  std::ostringstream out;
  out << std::fixed << std::setprecision(precision) << v;
  return out.str();
}

// Measures deleting @p selected (of @p cloud, the Core form of @p gaussians) through the removal
// port of a session given @p gaussians and @p cameras (the "before" of the score pass,
// @p baseline, given to its removal filter), writes before-after.csv and the figures of the
// views that changed most (the session's preview port) into @p folder, and returns the report's
// section. @p name (the scene's file) names the errors.
std::string MeasureCleanup(const std::string& name,
  vtkPolyData* gaussians,
  const vis4gs::GaussianCloud& cloud,
  const std::vector<std::uint8_t>& selected,
  const std::vector<vis4gs::Camera>& cameras,
  const std::string& rule,
  int threads,
  vis4gs::RemovalBaseline baseline,
  int lossResolution,
  const fs::path& folder)
{
  const auto t0 = Clock::now();
  const std::size_t reused = baseline.MeasuredViews();
  const std::string before = reused > 0 ? "The \"before\" of " + std::to_string(reused) +
      " training views is the score pass's own render, measured as it was made. "
    : lossResolution != 1 ? "The scores ran at loss resolution " + std::to_string(lossResolution) +
      ", so every view was rendered again for the \"before\" (--loss-resolution=1 reuses the "
      "score pass's renders). "
                          : std::string();
  // The cameras as the command uses them (their images: the PNG files written out of a log, or
  // those --images attached), as data: the session reads no file again.
  vtkNew<vtkTable> table;
  vis4gs::CamerasToTable(cameras, table);
  vtkNew<vtkGaussianSession> session;
  session->SetFileName(name.c_str()); // (names its errors; no file is read)
  session->SetGaussiansData(gaussians);
  session->SetCamerasData(table);
  session->ComputeScoresOff();
  vtkNew<vtkIdTypeArray> ids;
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    if (selected[i])
    {
      ids->InsertNextValue(static_cast<vtkIdType>(cloud.GetId(i)));
    }
  }
  session->SetSelectedIds(ids);
  vtkGaussianRemovalEffectFilter* removal = session->GetRemovalEffectFilter();
  removal->SetThreads(threads);
  removal->SetBaseline(std::make_shared<const vis4gs::RemovalBaseline>(std::move(baseline)));
  std::string errors = Vis4GSUpdate(session, vtkGaussianSession::RemovalViewsPort);
  vis4gs::RemovalEffect effect;
  if (!errors.empty() || !removal->GetEffect(effect, &errors))
  {
    throw std::runtime_error(errors);
  }
  const double seconds = Since(t0);
  {
    std::ostringstream csv;
    csv << "view,split,affected,psnr_before,psnr_after,ssim_before,ssim_after,l1_before,l1_after\n"
        << std::setprecision(9);
    auto row = [&csv](const std::string& view,
                 const std::string& split,
                 std::size_t affected,
                 const vis4gs::ViewMetrics& b,
                 const vis4gs::ViewMetrics& a)
    {
      csv << view << "," << split << "," << affected << "," << b.Psnr << "," << a.Psnr << ","
          << b.Ssim << "," << a.Ssim << "," << b.L1 << "," << a.L1 << "\n";
    };
    // Totals first ("mean" rows: means over the views of a split; affected = views changed).
    row("mean", "train", effect.Train.AffectedViews, effect.Train.Before, effect.Train.After);
    row("mean", "test", effect.Test.AffectedViews, effect.Test.Before, effect.Test.After);
    for (const vis4gs::RemovalViewEffect& v : effect.Views)
    {
      row(v.Name,
        v.Split == vis4gs::CameraSplit::Train ? "train" : "test",
        v.Affected ? 1 : 0,
        v.Before,
        v.After);
    }
    vis4gs::WriteTextFile((folder / "before-after.csv").string(), csv.str());
  }
  std::cout << "vis4gs analyze: deleting " << effect.Removed << " Gaussians: training PSNR "
            << effect.Train.Before.Psnr << " -> " << effect.Train.After.Psnr << " dB ("
            << effect.Train.AffectedViews << " of " << effect.Train.Views
            << " views changed), test PSNR " << effect.Test.Before.Psnr << " -> "
            << effect.Test.After.Psnr << " dB (" << effect.Test.AffectedViews << " of "
            << effect.Test.Views << "), " << seconds << " s; " << reused
            << " views' \"before\" from the score pass, " << effect.TilesRendered << " of "
            << effect.TilesOfTiledViews << " tiles of the changed views rendered again\n";

  std::ostringstream html;
  html << "<h2>Clean-up: deleting the selection, before and after</h2>\n<p>Rule <code>"
       << Vis4GSHtml(rule) << "</code> selects " << effect.Removed << " of " << cloud.Count
       << " Gaussians. Every training and test view with an image is rendered with and without "
          "them (exact rasteriser, renders clamped to [0, 1]); views where no selected Gaussian "
          "takes part are unchanged and not rendered again, and in the others only the tiles "
          "where a selected Gaussian is drawn (and two tiles around them) are rendered again "
          "(the same figures as a whole render). "
       << Vis4GSHtml(before) << effect.ViewsWithoutImage << " views have no image. Measured in "
       << Number(seconds, 2)
       << " s.</p>\n<table><tr><th>split</th><th>views</th><th>changed</th><th>PSNR before</th>"
          "<th>PSNR after</th><th>change</th><th>SSIM before</th><th>SSIM after</th>"
          "<th>L1 before</th><th>L1 after</th></tr>";
  for (const auto& [name, t] :
    { std::make_pair("train", &effect.Train), std::make_pair("test", &effect.Test) })
  {
    html << "<tr><td>" << name << "</td><td>" << t->Views << "</td><td>" << t->AffectedViews
         << "</td><td>" << Number(t->Before.Psnr) << "</td><td>" << Number(t->After.Psnr)
         << "</td><td>" << Number(t->After.Psnr - t->Before.Psnr) << "</td><td>"
         << Number(t->Before.Ssim) << "</td><td>" << Number(t->After.Ssim) << "</td><td>"
         << Number(t->Before.L1) << "</td><td>" << Number(t->After.L1) << "</td></tr>";
  }
  html << "</table>\n<h3>Views, the largest PSNR loss first</h3><table><tr><th>view</th>"
          "<th>split</th><th>changed</th><th>PSNR before</th><th>PSNR after</th><th>change</th>"
          "<th>SSIM before</th><th>SSIM after</th><th>L1 before</th><th>L1 after</th></tr>";
  for (const vis4gs::RemovalViewEffect& v : effect.Views)
  {
    html << "<tr><td>" << Vis4GSHtml(v.Name) << "</td><td>"
         << (v.Split == vis4gs::CameraSplit::Train ? "train" : "test") << "</td><td>"
         << (v.Affected ? "yes" : "no") << "</td><td>" << Number(v.Before.Psnr) << "</td><td>"
         << Number(v.After.Psnr) << "</td><td>" << Number(v.PsnrChange()) << "</td><td>"
         << Number(v.Before.Ssim) << "</td><td>" << Number(v.After.Ssim) << "</td><td>"
         << Number(v.Before.L1) << "</td><td>" << Number(v.After.L1) << "</td></tr>";
  }
  html << "</table>\n";

  // Figures: the three changed views that lost most and the three that gained most.
  std::vector<const vis4gs::RemovalViewEffect*> changed;
  for (const vis4gs::RemovalViewEffect& v : effect.Views)
  {
    if (v.Affected && v.HasImage)
    {
      changed.push_back(&v);
    }
  }
  std::vector<const vis4gs::RemovalViewEffect*> shown;
  for (std::size_t i = 0; i < changed.size() && i < 3; ++i)
  {
    shown.push_back(changed[i]);
  }
  for (std::size_t i = changed.size(); i > 3 && i > changed.size() - 3; --i)
  {
    shown.push_back(changed[i - 1]);
  }
  if (!shown.empty())
  {
    html << "<h3>Images</h3><p>Per view: the training or test image, the render before and "
            "after, and the change of the absolute error (red: worse after the deletion, green: "
            "better; full intensity at the view's largest change).</p>\n";
    for (const vis4gs::RemovalViewEffect* v : shown)
    {
      const vis4gs::Camera& camera = cameras[v->CameraIndex];
      vis4gs::Image target;
      Vis4GSLoadViewImage(v->CameraIndex, camera, target);
      // The renders the figures were measured on, from the session's preview port.
      session->SetRemovalPreviewView(static_cast<vtkIdType>(v->CameraIndex));
      errors = Vis4GSUpdate(session, vtkGaussianSession::RemovalPreviewPort);
      if (!errors.empty())
      {
        throw std::runtime_error(errors);
      }
      vis4gs::Image before, after;
      if (!vtkGaussianRemovalEffectFilter::PreviewImage(
            session->GetRemovalPreviewOutput(), true, before) ||
        !vtkGaussianRemovalEffectFilter::PreviewImage(
          session->GetRemovalPreviewOutput(), false, after))
      {
        throw std::runtime_error(camera.Name + ": the removal preview has no render");
      }
      html << "<div>";
      const vis4gs::Image* images[3] = { &target, &before, &after };
      const char* suffixes[3] = { "image", "before", "after" };
      for (int k = 0; k < 3; ++k)
      {
        const fs::path file = folder / ("cleanup-" + v->Name + "-" + suffixes[k] + ".png");
        vis4gs::WritePng(file.string(), *images[k]);
        html << Figure(file, v->Name + " " + suffixes[k]);
      }
      const fs::path file = folder / ("cleanup-" + v->Name + "-change.png");
      vis4gs::WritePng(file.string(), ErrorChangeImage(before, after, target));
      html << Figure(file,
                v->Name + " error change, PSNR " + Number(v->Before.Psnr, 3) + " -> " +
                  Number(v->After.Psnr, 3) + " dB")
           << "</div>\n";
    }
  }
  return html.str();
}

int Run(const Vis4GSArguments& args)
{
  const auto start = Clock::now();
  const Vis4GSMPISession mpi(args.GetFlag("mpi"));
  vtkMultiProcessController* controller =
    mpi.Active() ? vtkMultiProcessController::GetGlobalController() : nullptr;
  const std::string scene = args.GetPositional("scene");
  const fs::path output = args.Get("output");
  const std::size_t top = static_cast<std::size_t>(std::max(0, args.GetInt("top")));
  const bool isLog = Vis4GSIsLogPath(scene);
  // Requested scores.
  std::map<std::string, bool> want;
  for (const vis4gs::ScoreDefinition& d : vis4gs::ScoreDefinitions())
  {
    want[d.Name] = false;
  }
  try
  {
    for (const vis4gs::ScoreDefinition* d : vis4gs::ParseScoreList(args.Get("scores")))
    {
      want[d->Name] = true;
    }
  }
  catch (const std::invalid_argument& e)
  {
    throw std::runtime_error(std::string("--scores: ") + e.what());
  }
  // A selection rule: parsed first (a typo fails before any work) and its scores computed.
  std::optional<vis4gs::SelectionRule> rule;
  std::string ruleText = args.Get("select");
  if (!ruleText.empty() && ruleText[0] == '@')
  {
    std::ifstream file(ruleText.substr(1));
    if (!file || !std::getline(file, ruleText))
    {
      throw std::runtime_error(
        args.Get("select").substr(1) + ": --select cannot read a rule from it");
    }
  }
  if (!ruleText.empty())
  {
    rule = vis4gs::SelectionRule::Parse(ruleText);
    for (const std::string& name : rule->ScoresRead())
    {
      want[name] = true;
    }
  }
  else if (args.GetFlag("delete") || args.GetFlag("report"))
  {
    throw std::runtime_error("--delete and --report act on a selection: give --select=RULE");
  }
  const bool measure = rule && args.GetFlag("report");
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
  std::string wantedList, needingCameras;
  for (const vis4gs::ScoreDefinition& d : vis4gs::ScoreDefinitions())
  {
    if (want[d.Name])
    {
      wantedList += (wantedList.empty() ? "" : ",") + std::string(d.Name);
      if (d.Needs & vis4gs::NeedsCameras)
      {
        needingCameras += std::string(needingCameras.empty() ? "" : ", ") + d.Name;
      }
    }
  }
  const bool needCameras = !needingCameras.empty() || measure;
  std::vector<vis4gs::Camera> cameras;
  // One session reads, finds the cameras and scores (its score filter, staged below).
  vtkNew<vtkGaussianSession> session;
  session->SetFileName(scene.c_str());
  session->SetCamerasFileName(args.Get("cameras").c_str());
  Vis4GSSceneCameraRules(session->GetCameraReader());
  vtkNew<vtkPolyData> polyData; // the Gaussians before the scores
  std::vector<vis4gs::ExtraProperty> fileExtras;
  std::shared_ptr<const vis4gs::GaussianCloud> sceneCloud = isLog
    ? ReadLogScene(session, args, output, needCameras, cameras, mpi.Rank() == 0, polyData)
    : ReadSceneFile(session, polyData, fileExtras);
  const vis4gs::GaussianCloud& cloud = *sceneCloud;
  // A log's snapshot has its ids; a scene file's rows are numbered by the reader unless the
  // file has an id column, and scores.ply then has none either, as the file.
  const bool fileHasIds = isLog;
  if (!isLog && needCameras)
  {
    cameras = SessionCameras(session);
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
    throw std::runtime_error(scene + ": " +
      (needingCameras.empty() ? std::string("--report needs") : needingCameras + " need") +
      " cameras; give --cameras=cameras.json or a COLMAP folder");
  }
  if (!args.Get("images").empty())
  {
    Vis4GSAttachImagesByName(cameras, args.Get("images"));
    session->SetImageDirectory(args.Get("images").c_str()); // the score filter's, by the same rule
  }
  if (controller)
  {
    // Every process has read before any scores (the scores read a log's images from the log;
    // the PNG files process 0 writes are outputs, read only by its overlays and clean-up).
    controller->Barrier();
  }
  const double tRead = Since(t0);

  // Scores, through the session's score filter.
  t0 = Clock::now();
  const int stopAfter = args.GetInt("stop-after-stage");
  if (stopAfter < 0 || stopAfter > 2)
  {
    throw std::runtime_error("--stop-after-stage must be 0, 1 or 2");
  }
  // The stages are the filter's (ProgressiveStage), as in the application and the plugin.
  vtkGaussianArtifactScoreFilter* filter = session->GetScoreFilter();
  session->ComputeScoresOn();
  auto configure = [&](vtkGaussianArtifactScoreFilter* f, int stage)
  {
    f->SetScores(wantedList.c_str());
    f->SetLossResolution(args.GetInt("loss-resolution"));
    f->SetCoverageResolution(args.GetInt("coverage-resolution"));
    f->SetViewStride(args.GetInt("view-stride"));
    f->SetProgressiveStage(stage);
    f->SetFootprintMode(footprint == "ellipse" ? 1 : 0);
    f->SetFloatAccumulation(args.GetFlag("float-accumulation"));
    f->SetOcclusionThreshold(args.GetDouble("occlusion-threshold"));
    f->SetSharePreparation(args.GetFlag("share-preparation"));
    f->SetDynamicViewBalancing(!args.GetFlag("static-view-split"));
  };
  ScoreColumns firstScores;
  std::string firstStage;
  double tFirstStage = 0;
  // Runs the scores of the configured stage: the session's Gaussians port (the snapshot is not
  // read again).
  auto score = [&]()
  {
    const std::string errors = Vis4GSUpdate(session, vtkGaussianSession::GaussiansPort);
    if (!errors.empty())
    {
      throw std::runtime_error(errors);
    }
    return session->GetGaussiansOutput()->GetPointData();
  };
  if (stopAfter == 2 && needCameras)
  {
    configure(filter, 1);
    vtkPointData* first = score();
    firstScores = mpi.Rank() == 0 ? ScoresOf(first, want) : ScoreColumns();
    firstStage = filter->GetStageSettings();
    tFirstStage = Since(t0);
    std::cout << "vis4gs analyze: stage 1 of 2 (" << firstStage << "): " << Number(tFirstStage, 2)
              << " s" << std::endl;
  }
  configure(filter, stopAfter == 1 ? 1 : 0);
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
  // A full-resolution blur/needle pass renders every training view: the clean-up's "before"
  // is measured on those renders instead of rendering the views again.
  vis4gs::RemovalBaseline baseline;
  if (measure && (want["blur"] || want["needle"]) && args.GetInt("loss-resolution") == 1)
  {
    filter->SetViewRendered(vis4gs::RemovalBaselineRecorder(
      cloud, cameras, vis4gs::RasterSettings{}, args.GetInt("threads"), baseline));
  }
  vtkPointData* pd = score();
  if (verbose)
  {
    std::cerr << "\n";
  }
  // Only process 0 writes the outputs: the others copy no column (186 MiB of fresh memory at
  // 6.1M Gaussians and 4 scores, issue 31).
  const bool writes = mpi.Rank() == 0;
  const ScoreColumns scores = writes ? ScoresOf(pd, want) : ScoreColumns();
  std::string stageHtml;
  if (stopAfter == 1 && needCameras)
  {
    std::cout << "vis4gs analyze: stage 1 of 2 only (" << filter->GetStageSettings()
              << "): approximate scores\n";
    stageHtml = "<p><b>Stage 1 of 2 (approximate: " + filter->GetStageSettings() +
      ")</b>; the exact scores are stage 2 (--stop-after-stage=2 or 0).</p>\n";
  }
  else if (stopAfter == 2 && needCameras)
  {
    std::ostringstream text;
    text << "<h2>Progressive stages</h2><p>Stage 1 (" << firstStage
         << "): " << Number(tFirstStage, 2)
         << " s; stage 2 (exact, these outputs): " << Number(Since(t0) - tFirstStage, 2)
         << " s.</p><table><tr><th>score</th><th>largest difference</th><th>largest exact "
            "value</th><th>exact top 1 % in stage 1's top 1 %</th></tr>\n";
    for (std::size_t k = 0; k < scores.size(); ++k)
    {
      const StageError e = CompareStage(firstScores[k].second,
        scores[k].second,
        vis4gs::SuspiciousEndOf(scores[k].first) == vis4gs::SuspiciousEnd::Low);
      std::cout << "vis4gs analyze: stage 1 error, " << scores[k].first << ": largest difference "
                << e.LargestDifference << " (largest exact value " << e.LargestExact
                << "), exact top 1 % in stage 1's top 1 %: " << e.TopShared << " of " << e.TopCount
                << std::endl;
      text << "<tr><td>" << scores[k].first << "</td><td>" << e.LargestDifference << "</td><td>"
           << e.LargestExact << "</td><td>" << e.TopShared << " of " << e.TopCount
           << "</td></tr>\n";
    }
    text << "</table>\n";
    stageHtml = text.str();
  }
  firstScores.clear();
  std::vector<unsigned char> flags(writes ? cloud.Count : 0, 0);
  if (auto* f =
        writes ? vtkUnsignedCharArray::SafeDownCast(pd->GetArray("NoVisibleView")) : nullptr)
  {
    std::copy(f->GetPointer(0), f->GetPointer(0) + flags.size(), flags.begin());
  }
  // scores and flags are copies: the filter's arrays go (0.3 GB at 6.1M x 6 scores).
  filter->GetOutput()->Initialize();
  session->GetGaussiansOutput()->Initialize();
  const double tScores = Since(t0);
  if (mpi.Active())
  {
    std::cout << "vis4gs analyze: process " << mpi.Rank() << " of " << mpi.Size() << " rendered "
              << filter->GetNumberOfViewsRendered() << " of " << filter->GetNumberOfViewsUsed()
              << " views in " << Number(filter->GetComputeSeconds(), 2) << " s, reduction "
              << Number(filter->GetReductionSeconds(), 3) << " s, preparation "
              << (filter->GetPreparationProcesses() > 1
                     ? "shared by " + std::to_string(filter->GetPreparationProcesses()) +
                       " processes of this machine"
                     : std::string("made alone"))
              << "\n";
    if (mpi.Rank() != 0)
    {
      return 0; // process 0 has the reduced scores too and writes the outputs
    }
  }

  // Outputs.
  t0 = Clock::now();
  Vis4GSStagingFolder staging(output, "analyze");
  // The scores as columns after the file's own, written without a copy of the cloud.
  std::vector<vis4gs::ExtraProperty> columns = fileExtras;
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
    columns.push_back(std::move(p));
  }
  if (needCameras)
  {
    vis4gs::ExtraProperty p;
    p.Name = "NoVisibleView";
    p.Type = vis4gs::ScalarType::UInt8;
    p.Bytes.assign(flags.begin(), flags.end());
    columns.push_back(std::move(p));
  }
  {
    vis4gs::GaussianWriteOptions options;
    options.AppendedExtras = &columns;
    options.WriteIds = fileHasIds;
    vis4gs::WriteGaussianPly((staging.Get() / "scores.ply").string(), cloud, options);
  }
  columns.clear();
  columns.shrink_to_fit();
  // Into the staging folder (renamed into place with the other outputs on success).
  Vis4GSWriteScoresCsv(staging.Get() / "scores.csv",
    (output / "scores.csv").string(),
    cloud,
    scores,
    needCameras ? &flags : nullptr);
  // Top-k: the suspicious end of each score first (lowest coverage: floaters).
  std::map<std::string, std::vector<std::size_t>> tops;
  for (const auto& [name, values] : scores)
  {
    std::vector<double> key = values;
    const bool lowest = vis4gs::SuspiciousEndOf(name) == vis4gs::SuspiciousEnd::Low;
    if (lowest)
    {
      for (double& k : key)
      {
        k = -k;
      }
    }
    tops[name] = TopK(key, top);
    std::cout << "vis4gs analyze: top " << tops[name].size() << " by " << name
              << (lowest ? " (lowest first)" : "") << ":\n";
    for (std::size_t i : tops[name])
    {
      std::cout << "  Gaussian " << cloud.GetId(i) << "  " << values[i] << "\n";
    }
  }
  // The selection by rule, the cleaned scene and the before/after measurement.
  std::string cleanupHtml;
  if (rule)
  {
    vis4gs::SelectionRuleInputs inputs;
    inputs.Cloud = &cloud;
    inputs.ViewsUsed = filter->GetNumberOfViewsUsed();
    for (const auto& [name, values] : scores)
    {
      inputs.Scores[vis4gs::FindScore(name)->Name] = &values;
    }
    const std::vector<std::uint8_t> selected = rule->Evaluate(inputs);
    const std::string canonical = rule->ToString();
    vis4gs::WriteTextFile((staging.Get() / "selection-rule.txt").string(), canonical + "\n");
    std::size_t count = 0;
    {
      std::ostringstream csv;
      csv << "GaussianId\n";
      for (std::size_t i = 0; i < cloud.Count; ++i)
      {
        if (selected[i])
        {
          csv << cloud.GetId(i) << "\n";
          ++count;
        }
      }
      vis4gs::WriteTextFile((staging.Get() / "selection.csv").string(), csv.str());
    }
    std::cout << "vis4gs analyze: rule '" << canonical << "' selects " << count << " of "
              << cloud.Count << " Gaussians\n";
    cleanupHtml = "<h2>Selection</h2><p>Rule <code>" + Vis4GSHtml(canonical) +
      "</code> (as given: <code>" + Vis4GSHtml(ruleText) + "</code>) selects " +
      std::to_string(count) + " of " + std::to_string(cloud.Count) +
      " Gaussians (selection.csv).</p>\n";
    if (args.GetFlag("delete"))
    {
      vis4gs::WriteGaussianPly((staging.Get() / "cleaned.ply").string(),
        vis4gs::RemoveGaussians(AsFileHasIt(cloud, fileExtras, fileHasIds), selected));
      std::cout << "vis4gs analyze: cleaned.ply holds the " << cloud.Count - count
                << " Gaussians not selected\n";
      cleanupHtml += "<p>cleaned.ply: the scene without them (" +
        std::to_string(cloud.Count - count) + " Gaussians).</p>\n";
    }
    if (measure)
    {
      cleanupHtml += MeasureCleanup(scene,
        polyData,
        cloud,
        selected,
        cameras,
        canonical,
        args.GetInt("threads"),
        std::move(baseline),
        args.GetInt("loss-resolution"),
        staging.Get());
    }
  }
  // Overlays of the first training views: colours replaced by the overlay colour map of
  // the score (vis4gs::OverlayColor, the scene view's), its suspicious end bright on black.
  std::vector<std::pair<std::string, fs::path>> overlays;
  std::vector<std::string> legends;
  const int overlayViews = std::max(0, args.GetInt("overlay-views"));
  // The Gaussians the rest of the command reads: the scene, or its geometry alone.
  const vis4gs::GaussianCloud* shown = &cloud;
  vis4gs::GaussianCloud geometry;
  if (needCameras && overlayViews > 0)
  {
    // The overlays read the geometry only, and nothing after them the SH (80 % of the scene
    // at degree 3): the scene is let go for a copy without them, so that the overlays'
    // renderer does not come on top of the whole scene (issue 31: the run's peak memory).
    geometry = GeometryOf(cloud);
    shown = &geometry;
    polyData->Initialize();
    for (vtkAlgorithm* reader : { static_cast<vtkAlgorithm*>(session->GetSceneReader()),
           static_cast<vtkAlgorithm*>(session->GetLogReader()) })
    {
      if (reader && reader->GetOutputDataObject(0))
      {
        reader->GetOutputDataObject(0)->ReleaseData();
      }
    }
    sceneCloud.reset(); // `cloud` is not read below this line
  }
  if (needCameras && overlayViews > 0)
  {
    std::vector<Vis4GSOverlayScore> drawn;
    for (const auto& [name, values] : scores)
    {
      const vis4gs::ScoreDefinition& score = *vis4gs::FindScore(name);
      if (!(score.Needs & vis4gs::NeedsCameras))
      {
        continue; // a property of the Gaussian alone, not of what the views see
      }
      const double hi = Vis4GSOverlayUpperEnd(values, score.UnitRange);
      legends.push_back(Legend(name, 0.0, hi));
      drawn.push_back({ name, &values, hi });
    }
    // Rendered view by view (one projection each), listed score by score.
    std::vector<std::vector<std::pair<std::string, fs::path>>> images(drawn.size());
    int view = 0;
    std::size_t lastCamera = cameras.size();
    Vis4GSRenderOverlays(geometry,
      cameras,
      drawn,
      overlayViews,
      [&](std::size_t k, std::size_t v, const vis4gs::Image& image)
      {
        view += v != lastCamera ? 1 : 0;
        lastCamera = v;
        const std::string& name = drawn[k].Name;
        std::cout << "vis4gs analyze: overlay " << name << " in " << cameras[v].Name << " (" << view
                  << " of " << overlayViews << ")" << std::endl;
        const fs::path file = staging.Get() / (name + "-" + cameras[v].Name + ".png");
        vis4gs::WritePng(file.string(), image);
        images[k].emplace_back(name + " in " + cameras[v].Name, file);
      });
    for (auto& list : images)
    {
      overlays.insert(overlays.end(), list.begin(), list.end());
    }
  }
  const double tOutputs = Since(t0);

  // HTML report.
  std::ostringstream html;
  html << "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>vis4gs analyze: "
       << Vis4GSHtml(scene) << "</title><style>body{font-family:sans-serif;margin:2em}"
       << "table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:2px 8px;"
       << "text-align:right}figure{display:inline-block;margin:8px}</style></head><body>\n"
       << "<h1>Gaussian diagnosis of " << Vis4GSHtml(scene) << "</h1>\n<p>" << shown->Count
       << " Gaussians, " << cameras.size() << " cameras, " << filter->GetNumberOfViewsUsed()
       << " training views used, " << filter->GetNumberOfViewsWithoutImage() << " without image, "
       << filter->GetNumberOfFlaggedGaussians()
       << " Gaussians flagged (no visible view or invalid parameters).</p>\n"
       << stageHtml;
  html << "<h2>Settings</h2><table>";
  for (const char* opt : { "scores",
         "select",
         "cameras",
         "images",
         "loss-resolution",
         "coverage-resolution",
         "view-stride",
         "stop-after-stage",
         "footprint",
         "occlusion-threshold",
         "top" })
  {
    html << "<tr><th>" << opt << "</th><td>" << Vis4GSHtml(args.Get(opt)) << "</td></tr>";
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
  html << "<h2>Overlays</h2><p>Scores through viridis (scores in [0, 1] such as the coverage "
          "over 0..1; other scores 0..their 99th percentile), rendered with the rasteriser on "
          "black. The map is turned so that the suspicious end of each score is the bright "
          "(yellow) end: low View Coverage, high values of the other scores.</p>\n";
  for (const std::string& legend : legends)
  {
    html << legend;
  }
  html << "<br>\n";
  for (const auto& [title, file] : overlays)
  {
    html << "<figure><img src=\"data:image/png;base64," << Base64(ReadBytes(file))
         << "\"><figcaption>" << Vis4GSHtml(title) << "</figcaption></figure>\n";
  }
  html << cleanupHtml;
  html << "<h2>Most suspicious Gaussians</h2>\n";
  for (const auto& [name, values] : scores)
  {
    html << "<h3>" << name
         << (vis4gs::SuspiciousEndOf(name) == vis4gs::SuspiciousEnd::Low ? " (lowest)" : "")
         << "</h3><table><tr><th>rank</th><th>GaussianId</th>";
    for (const auto& s : scores)
    {
      html << "<th>" << s.first << "</th>";
    }
    html << "</tr>";
    int rank = 1;
    for (std::size_t i : tops[name])
    {
      html << "<tr><td>" << rank++ << "</td><td>" << shown->GetId(i) << "</td>";
      for (const auto& s : scores)
      {
        html << "<td>" << s.second[i] << "</td>";
      }
      html << "</tr>";
    }
    html << "</table>\n";
  }
  html << "<p>Total " << Since(start) << " s.</p></body></html>\n";
  vis4gs::WriteTextFile((staging.Get() / "report.html").string(), html.str());
  staging.Commit();
  std::cout << "vis4gs analyze: wrote " << (output / "report.html").string() << ", scores.csv, "
            << "scores.ply and " << overlays.size() << " overlay images\n";
  return 0;
}
}

VIS4GS_REGISTER_COMMAND("analyze",
  "Compute the per-Gaussian scores (View Coverage, Blur, Needle, ...) of a scene; write tables, "
  "images and a report.",
  Define,
  Run)

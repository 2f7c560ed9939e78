// SPDX-License-Identifier: BSD-3-Clause
// `vis4gs convert IN OUT` (issue 34): any scene Vis4GS reads (by content: PLY, compressed PLY,
// SOG, SPZ, .ksplat, .splat, glTF) or a training log's snapshot, written in the format OUT's
// name says, with the target's quantisation error reported as the application's export
// reports it (the writers' own reports, measured by reading back what they wrote).
#include "Vis4GSCommand.h"

#include "GaussianIO.h"
#include "SceneFile.h"
#include "TrainingLogReader.h"
#include "Vis4GSStateFiles.h"

#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{

void Define(Vis4GSArguments& args)
{
  args.AddPositional("IN",
    "Scene to read, by content: a 3DGS .ply, compressed PLY, SOG (.sog, meta.json or its "
    "folder), .spz (also raw), .ksplat, .splat or glTF (.glb, .gltf); or a training log .h5 "
    "(its snapshot nearest to --iteration).");
  args.AddPositional("OUT",
    "File to write, its format by its name: .ply (float32, exact), .compressed.ply (PlayCanvas), "
    ".spz (SPZ v4), .glb / .gltf (KHR_gaussian_splatting) or .splat (antimatter15).");
  args.AddOption("sh-degree",
    "N",
    "-1",
    "Highest SH degree kept (0-3): the bands above are dropped; -1 keeps what IN holds.");
  args.AddFlag("extras",
    true,
    "Keep the extra per-Gaussian properties (scores, normals, ids) where the target can store "
    "them: .ply and glTF; SPZ, compressed PLY and .splat have no place for them (said).");
  args.AddOption(
    "iteration", "N", "-1", "Training log IN: the snapshot nearest to N; -1: the last.");
  args.AddFlag("ascii", false, "Write a .ply as ASCII (exact, shortest round-trip decimals).");
}

int Run(const Vis4GSArguments& args)
{
  const std::string in = args.GetPositional("IN");
  const std::string out = args.GetPositional("OUT");
  const int shDegree = args.GetInt("sh-degree");
  if (shDegree < -1 || shDegree > 3)
  {
    throw std::runtime_error("--sh-degree must be -1 or 0..3, not " + std::to_string(shDegree));
  }
  const std::string format = vis4gs::detail::SceneWriteFormat(out);
  if (format.empty())
  {
    throw std::runtime_error(out +
      ": the name does not say a format Vis4GS writes (.ply, .compressed.ply, .spz, .glb, .gltf, "
      ".splat)");
  }
  vis4gs::GaussianCloud cloud;
  std::string what;
  if (Vis4GSIsLogPath(in))
  {
    const vis4gs::TrainingLogReader log(in);
    vis4gs::SnapshotReadOptions o;
    o.Arrays = vis4gs::SnapshotParameters;
    o.ShDegree = shDegree;
    // -1 is the last snapshot, as --help says (the nearest to -1 would be the first).
    const std::vector<int>& iterations = log.GetSnapshotIterations();
    const int wanted = args.GetInt("iteration");
    int iteration = 0;
    cloud = log.ReadNearestSnapshot(
      wanted < 0 && !iterations.empty() ? iterations.back() : wanted, o, &iteration);
    what = "snapshot " + std::to_string(iteration);
  }
  else
  {
    vis4gs::GaussianReadOptions o;
    o.MaxShDegree = shDegree < 0 ? 3 : shDegree;
    o.LoadExtras = args.GetFlag("extras");
    vis4gs::GaussianReadReport report;
    cloud = vis4gs::ReadGaussianScene(in, o, &report);
    for (const std::string& w : report.Warnings)
    {
      std::cerr << "vis4gs convert: warning: " << w << "\n";
    }
    what = report.Format;
  }
  if (!args.GetFlag("extras"))
  {
    cloud.Extra.clear();
    cloud.Ids.clear();
  }
  std::cout << "vis4gs convert: " << in << " (" << what << "): " << cloud.Count
            << " Gaussians, SH degree " << cloud.ShDegree << std::endl;
  vis4gs::SceneWriteOptions o;
  o.Format =
    args.GetFlag("ascii") ? vis4gs::PlyFormat::Ascii : vis4gs::PlyFormat::BinaryLittleEndian;
  const std::string line = vis4gs::WriteGaussianScene(out, cloud, o);
  std::cout << "vis4gs convert: " << out << ": " << line << std::endl;
  return 0;
}

} // namespace

VIS4GS_REGISTER_COMMAND("convert",
  "Convert a scene between the formats Vis4GS reads and writes, reporting what is lost.",
  Define,
  Run)

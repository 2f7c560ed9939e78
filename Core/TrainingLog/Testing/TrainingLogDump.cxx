// SPDX-License-Identifier: BSD-3-Clause
// TrainingLogDump <log.h5> [--repair] [--history=id,id,...] [--refresh=K]
// Reads a training log with the C++ reader and prints a JSON summary; used by the Python
// logger's tests to check that what h5py wrote is what the C++ reader reads. --refresh=K:
// then K times, 50 ms apart, TrainingLogReader::Refresh() and one more summary line each
// (what `vis4gs view --follow` does with a log a trainer is writing).
#include "TrainingLogReader.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <sstream>
#include <thread>

int main(int argc, char* argv[])
{
  if (argc < 2)
  {
    std::cerr << "usage: TrainingLogDump <log.h5> [--repair] [--history=id,id,...]\n";
    return 2;
  }
  vis4gs::TrainingLogReaderOptions options;
  std::vector<std::int64_t> history;
  int refreshes = 0;
  for (int i = 2; i < argc; ++i)
  {
    if (std::strcmp(argv[i], "--repair") == 0)
    {
      options.Repair = true;
    }
    else if (std::strncmp(argv[i], "--refresh=", 10) == 0)
    {
      refreshes = std::atoi(argv[i] + 10);
    }
    else if (std::strncmp(argv[i], "--history=", 10) == 0)
    {
      std::stringstream s(argv[i] + 10);
      std::string item;
      while (std::getline(s, item, ','))
      {
        history.push_back(std::stoll(item));
      }
    }
  }
  try
  {
    vis4gs::TrainingLogReader reader(argv[1], options);
    for (int pass = 0; pass <= refreshes; ++pass)
    {
      if (pass > 0)
      {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        reader.Refresh();
      }
      nlohmann::json out;
      out["format_version"] = reader.GetHeader().FormatVersion;
      out["swmr"] = reader.IsSwmrRead();
      out["producer"] = reader.GetHeader().Producer;
      out["scene"] = reader.GetHeader().Scene;
      out["sh_degree"] = reader.GetHeader().ShDegree;
      out["iterations"] = reader.GetHeader().Iterations;
      out["lacks"] = reader.GetLacks();
      out["snapshots"] = reader.GetSnapshotIterations();
      nlohmann::json counts = nlohmann::json::array();
      for (int it : reader.GetSnapshotIterations())
      {
        vis4gs::SnapshotReadOptions o;
        o.Arrays = vis4gs::SnapshotAll;
        o.ShDegree = -1;
        vis4gs::GaussianCloud c = reader.ReadSnapshot(it, o); // validates the ids
        counts.push_back(c.Count);
      }
      out["counts"] = counts;
      out["events"] = reader.ReadEvents().Size(); // validates the genealogy
      out["metrics"] = reader.ReadMetrics(false).Size();
      out["test_metrics"] = reader.ReadMetrics(true).Size();
      nlohmann::json images = nlohmann::json::array();
      for (const vis4gs::Camera& camera : reader.ReadCameras())
      {
        images.push_back(camera.ImagePath); // as stored: the application resolves relative ones
      }
      out["cameras"] = images.size();
      out["camera_images"] = images;
      nlohmann::json rows = nlohmann::json::array();
      if (!history.empty())
      {
        vis4gs::PropertyHistory h = reader.ReadPropertyHistory(history);
        for (std::size_t r = 0; r < h.Size(); ++r)
        {
          rows.push_back({ { "id", h.Id[r] },
            { "iteration", h.Iteration[r] },
            { "opacity_logit", h.OpacityLogits[r] },
            { "position",
              { h.Positions[3 * r], h.Positions[3 * r + 1], h.Positions[3 * r + 2] } } });
        }
      }
      out["history"] = rows;
      nlohmann::json breaks = nlohmann::json::array();
      const vis4gs::LineageBreakTable b = reader.ReadLineageBreaks();
      for (std::size_t r = 0; r < b.Size(); ++r)
      {
        breaks.push_back({ { "iteration", b.Iteration[r] },
          { "event_row", b.EventRow[r] },
          { "tracked", b.Tracked[r] },
          { "rows", b.Rows[r] },
          { "kept", b.Kept[r] },
          { "first_new_id", b.FirstNewId[r] },
          { "new_roots", b.NewRoots[r] } });
      }
      out["lineage_breaks"] = breaks;
      out["repairs"] = reader.GetRepairs();
      std::cout << out.dump() << std::endl;
    }
  }
  catch (const std::exception& e)
  {
    std::cerr << e.what() << std::endl;
    return 1;
  }
  return 0;
}

// SPDX-License-Identifier: BSD-3-Clause
#include "TransformsJson.h"
#include "ImageIO.h"
#include "JsonNumber.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>

namespace vis4gs
{

namespace
{

namespace fs = std::filesystem;
using nlohmann::json;

constexpr double MaxImageSide = 1 << 20;

[[noreturn]] void Fail(const std::string& name, const std::string& what)
{
  throw std::runtime_error(name + ": " + what);
}

//------------------------------------------------------------------------------
// The frame's value of @p key, else the top level's; nullptr when neither has it.
const json* Lookup(const json& frame, const json& top, const char* key)
{
  auto it = frame.find(key);
  if (it != frame.end())
  {
    return &*it;
  }
  it = top.find(key);
  return it != top.end() ? &*it : nullptr;
}

double Number(const nlohmann::json& j, const std::string& name, const std::string& where)
{
  return detail::JsonNumber(j, name, where);
}

int Side(const json& j, const std::string& name, const std::string& where)
{
  const double v = Number(j, name, where);
  if (v < 1 || v > MaxImageSide || v != std::floor(v))
  {
    Fail(name, where + " must be a positive integer");
  }
  return static_cast<int>(v);
}

std::string ResolveImage(const std::string& folder, const std::string& filePath)
{
  const fs::path p = fs::path(folder) / filePath;
  std::error_code ec;
  if (fs::is_regular_file(p, ec))
  {
    return p.string();
  }
  if (!p.has_extension())
  {
    for (const char* ext : { ".png", ".jpg", ".jpeg", ".PNG", ".JPG" })
    {
      fs::path q = p;
      q += ext;
      if (fs::is_regular_file(q, ec))
      {
        return q.string();
      }
    }
  }
  return {};
}

std::vector<char> Slurp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    Fail(path, "cannot open");
  }
  return std::vector<char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Camera names key the training log, but NeRF-synthetic reuses stems across splits
// (train/r_0, test/r_0): a repeated name takes its image folder's name as a prefix
// ("test_r_0"), then an index if it still repeats.
void MakeNamesUnique(std::vector<Camera>& cameras)
{
  std::set<std::string> seen;
  for (Camera& cam : cameras)
  {
    if (!seen.insert(cam.Name).second)
    {
      const std::string folder = fs::path(cam.ImagePath).parent_path().filename().string();
      std::string name = folder.empty() ? cam.Name : folder + "_" + cam.Name;
      for (int k = 1; seen.count(name); ++k)
      {
        name = cam.Name + "_" + std::to_string(k);
      }
      cam.Name = name;
      seen.insert(name);
    }
  }
}

} // namespace

//------------------------------------------------------------------------------
TransformsCameras ReadTransformsJsonFromMemory(const void* data,
  std::size_t size,
  const std::string& name,
  const std::string& folder,
  const TransformsOptions& options)
{
  json doc;
  try
  {
    const char* b = static_cast<const char*>(data);
    doc = json::parse(b, b + size);
  }
  catch (const json::exception& e)
  {
    Fail(name, std::string("not valid JSON: ") + e.what());
  }
  if (!doc.is_object() || !doc.contains("frames") || !doc["frames"].is_array())
  {
    Fail(name, "expected a JSON object with a 'frames' list (transforms.json)");
  }
  TransformsCameras out;
  std::size_t missing = 0;
  bool distorted = false;
  const json& frames = doc["frames"];
  for (std::size_t i = 0; i < frames.size(); ++i)
  {
    const json& f = frames[i];
    std::string where = "frame " + std::to_string(i);
    if (!f.is_object())
    {
      Fail(name, where + " is not an object");
    }
    const auto fp = f.find("file_path");
    if (fp == f.end() || !fp->is_string())
    {
      Fail(name, where + ": missing 'file_path' string");
    }
    const std::string filePath = fp->get<std::string>();
    where += " ('" + filePath + "')";
    Camera cam;
    cam.Split = options.Split;
    cam.Name = fs::path(filePath).stem().string();
    cam.Model = "PINHOLE";

    const auto tm = f.find("transform_matrix");
    if (tm == f.end() || !tm->is_array() || tm->size() < 3 || tm->size() > 4)
    {
      Fail(name, where + ": 'transform_matrix' must be a 4x4 (or 3x4) list of rows");
    }
    double m[3][4];
    for (int r = 0; r < 3; ++r)
    {
      const json& row = (*tm)[r];
      if (!row.is_array() || row.size() != 4)
      {
        Fail(name, where + ": 'transform_matrix' rows must hold 4 numbers");
      }
      for (int c = 0; c < 4; ++c)
      {
        m[r][c] = Number(row[c], name, where + ": 'transform_matrix'");
      }
    }
    // OpenGL -> OpenCV camera axes: negate the camera's y and z columns.
    for (int r = 0; r < 3; ++r)
    {
      m[r][1] = -m[r][1];
      m[r][2] = -m[r][2];
    }
    for (int a = 0; a < 3; ++a)
    {
      for (int b = 0; b < 3; ++b)
      {
        double d = 0;
        for (int r = 0; r < 3; ++r)
        {
          d += m[r][a] * m[r][b];
        }
        if (std::abs(d - (a == b ? 1.0 : 0.0)) > 1e-3)
        {
          Fail(name, where + ": the rotation of 'transform_matrix' is not orthonormal");
        }
      }
    }
    // World-to-camera: R = R_c2w^T, t = -R C.
    auto& w2c = cam.WorldToCamera;
    for (int r = 0; r < 3; ++r)
    {
      double t = 0;
      for (int c = 0; c < 3; ++c)
      {
        w2c[r * 4 + c] = m[c][r];
        t -= m[c][r] * m[c][3];
      }
      w2c[r * 4 + 3] = t;
    }
    w2c[12] = w2c[13] = w2c[14] = 0;
    w2c[15] = 1;

    cam.ImagePath = ResolveImage(folder, filePath);
    const json* w = Lookup(f, doc, "w");
    const json* h = Lookup(f, doc, "h");
    if (w && h)
    {
      cam.Width = Side(*w, name, where + ": 'w'");
      cam.Height = Side(*h, name, where + ": 'h'");
    }
    if (cam.ImagePath.empty())
    {
      if (options.RequireImages || !w || !h)
      {
        ++missing;
        continue;
      }
      cam.ImagePath = (fs::path(folder) / filePath).string();
    }
    else if (!w || !h)
    {
      const Image img = ReadImage(cam.ImagePath);
      cam.Width = img.Width;
      cam.Height = img.Height;
    }

    const json* flx = Lookup(f, doc, "fl_x");
    const json* fly = Lookup(f, doc, "fl_y");
    const json* ax = Lookup(f, doc, "camera_angle_x");
    const json* ay = Lookup(f, doc, "camera_angle_y");
    const double pi = 3.14159265358979323846;
    auto angle = [&](const json& j, const char* key)
    {
      const double a = Number(j, name, where + ": '" + key + "'");
      if (!(a > 0) || !(a < pi))
      {
        Fail(name, where + ": '" + key + "' must be in (0, pi)");
      }
      return a;
    };
    if (flx)
    {
      cam.Fx = Number(*flx, name, where + ": 'fl_x'");
    }
    else if (ax)
    {
      cam.Fx = 0.5 * cam.Width / std::tan(0.5 * angle(*ax, "camera_angle_x"));
    }
    else
    {
      Fail(name, where + ": neither 'fl_x' nor 'camera_angle_x' is given");
    }
    if (fly)
    {
      cam.Fy = Number(*fly, name, where + ": 'fl_y'");
    }
    else if (ay && !flx)
    {
      cam.Fy = 0.5 * cam.Height / std::tan(0.5 * angle(*ay, "camera_angle_y"));
    }
    else
    {
      cam.Fy = cam.Fx;
    }
    if (!(cam.Fx > 0) || !(cam.Fy > 0))
    {
      Fail(name, where + ": focal lengths must be positive");
    }
    const json* cx = Lookup(f, doc, "cx");
    const json* cy = Lookup(f, doc, "cy");
    cam.Cx = cx ? Number(*cx, name, where + ": 'cx'") : cam.Width / 2.0;
    cam.Cy = cy ? Number(*cy, name, where + ": 'cy'") : cam.Height / 2.0;
    for (const char* key : { "k1", "k2", "k3", "k4", "p1", "p2" })
    {
      const json* k = Lookup(f, doc, key);
      if (k && Number(*k, name, where + ": '" + key + "'") != 0)
      {
        distorted = true;
      }
    }
    out.Cameras.push_back(std::move(cam));
  }
  if (missing > 0)
  {
    out.Warnings.push_back(name + ": " + std::to_string(missing) + " of " +
      std::to_string(frames.size()) + " frames skipped: image file not found" +
      (options.RequireImages ? "" : " and no 'w'/'h' given"));
  }
  MakeNamesUnique(out.Cameras);
  if (distorted)
  {
    out.Warnings.push_back(
      name + ": distortion parameters (k1, k2, k3, k4, p1, p2) are ignored; cameras are pinhole");
  }
  return out;
}

//------------------------------------------------------------------------------
TransformsCameras ReadTransformsJson(const std::string& path, const TransformsOptions& options)
{
  const std::vector<char> bytes = Slurp(path);
  return ReadTransformsJsonFromMemory(
    bytes.data(), bytes.size(), path, fs::path(path).parent_path().string(), options);
}

//------------------------------------------------------------------------------
bool IsTransformsJson(const std::string& path)
{
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
  {
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  const json doc = json::parse(in, nullptr, /*allow_exceptions=*/false);
  return doc.is_object() && doc.contains("frames") && doc["frames"].is_array();
}

//------------------------------------------------------------------------------
bool IsTransformsFolder(const std::string& folder)
{
  std::error_code ec;
  return fs::is_regular_file(fs::path(folder) / "transforms_train.json", ec) ||
    fs::is_regular_file(fs::path(folder) / "transforms.json", ec);
}

//------------------------------------------------------------------------------
TransformsCameras LoadTransformsDataset(const std::string& path, bool requireImages)
{
  TransformsOptions options;
  options.RequireImages = requireImages;
  std::error_code ec;
  if (!fs::is_directory(path, ec))
  {
    return ReadTransformsJson(path, options);
  }
  const fs::path dir(path);
  if (!fs::is_regular_file(dir / "transforms_train.json", ec))
  {
    if (!fs::is_regular_file(dir / "transforms.json", ec))
    {
      Fail(path, "no transforms_train.json or transforms.json in this folder");
    }
    return ReadTransformsJson((dir / "transforms.json").string(), options);
  }
  TransformsCameras out = ReadTransformsJson((dir / "transforms_train.json").string(), options);
  if (fs::is_regular_file(dir / "transforms_test.json", ec))
  {
    options.Split = CameraSplit::Test;
    TransformsCameras test = ReadTransformsJson((dir / "transforms_test.json").string(), options);
    out.Cameras.insert(out.Cameras.end(), test.Cameras.begin(), test.Cameras.end());
    out.Warnings.insert(out.Warnings.end(), test.Warnings.begin(), test.Warnings.end());
    MakeNamesUnique(out.Cameras);
  }
  return out;
}

} // namespace vis4gs

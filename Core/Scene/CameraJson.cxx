// SPDX-License-Identifier: BSD-3-Clause
#include "CameraJson.h"
#include "JsonNumber.h"
#include "SceneFile.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace vis4gs
{

namespace
{

constexpr double MaxImageSide = 1 << 20;

//------------------------------------------------------------------------------
[[noreturn]] void Fail(const std::string& name, const std::string& what)
{
  throw std::runtime_error(name + ": " + what);
}

//------------------------------------------------------------------------------
double Number(const nlohmann::json& j, const std::string& name, const std::string& where)
{
  return detail::JsonNumber(j, name, where);
}

//------------------------------------------------------------------------------
const nlohmann::json& Field(const nlohmann::json& e,
  const char* key,
  const std::string& name,
  const std::string& where)
{
  const auto it = e.find(key);
  if (it == e.end())
  {
    Fail(name, where + ": missing '" + key + "'");
  }
  return *it;
}

//------------------------------------------------------------------------------
int ImageSide(const nlohmann::json& e,
  const char* key,
  const std::string& name,
  const std::string& where)
{
  const double v = Number(Field(e, key, name, where), name, where + ": '" + key + "'");
  if (v < 1 || v > MaxImageSide || v != std::floor(v))
  {
    Fail(name, where + ": '" + key + "' must be a positive integer, got " + std::to_string(v));
  }
  return static_cast<int>(v);
}

//------------------------------------------------------------------------------
std::vector<Camera> Parse(const void* data, std::size_t size, const std::string& name)
{
  nlohmann::json doc;
  try
  {
    const char* b = static_cast<const char*>(data);
    doc = nlohmann::json::parse(b, b + size);
  }
  catch (const nlohmann::json::exception& e)
  {
    Fail(name, std::string("not valid JSON: ") + e.what());
  }
  if (!doc.is_array())
  {
    Fail(name, "expected a JSON list of cameras");
  }
  std::vector<Camera> cameras;
  cameras.reserve(doc.size());
  for (std::size_t i = 0; i < doc.size(); ++i)
  {
    const nlohmann::json& e = doc[i];
    std::string where = "camera " + std::to_string(i);
    if (!e.is_object())
    {
      Fail(name, where + " is not an object");
    }
    Camera cam;
    const auto& imgName = Field(e, "img_name", name, where);
    if (!imgName.is_string())
    {
      Fail(name, where + ": 'img_name' is not a string");
    }
    cam.Name = imgName.get<std::string>();
    where += " ('" + cam.Name + "')";
    cam.Width = ImageSide(e, "width", name, where);
    cam.Height = ImageSide(e, "height", name, where);
    cam.Fx = Number(Field(e, "fx", name, where), name, where + ": 'fx'");
    cam.Fy = Number(Field(e, "fy", name, where), name, where + ": 'fy'");
    if (!(cam.Fx > 0) || !(cam.Fy > 0))
    {
      Fail(name, where + ": focal lengths must be positive");
    }
    cam.Cx = cam.Width / 2.0;
    cam.Cy = cam.Height / 2.0;
    if (e.contains("cx"))
    {
      cam.Cx = Number(e["cx"], name, where + ": 'cx'");
    }
    if (e.contains("cy"))
    {
      cam.Cy = Number(e["cy"], name, where + ": 'cy'");
    }
    const auto& pos = Field(e, "position", name, where);
    const auto& rot = Field(e, "rotation", name, where);
    if (!pos.is_array() || pos.size() != 3)
    {
      Fail(name, where + ": 'position' must be a list of 3 numbers");
    }
    if (!rot.is_array() || rot.size() != 3)
    {
      Fail(name, where + ": 'rotation' must be a 3x3 list of rows");
    }
    double c[3], c2w[3][3];
    for (int r = 0; r < 3; ++r)
    {
      c[r] = Number(pos[r], name, where + ": 'position'");
      if (!rot[r].is_array() || rot[r].size() != 3)
      {
        Fail(name, where + ": 'rotation' must be a 3x3 list of rows");
      }
      for (int k = 0; k < 3; ++k)
      {
        c2w[r][k] = Number(rot[r][k], name, where + ": 'rotation'");
      }
    }
    // Must be a rotation: R R^T = I (lenient: the file holds float32-rounded values).
    double err = 0;
    for (int a = 0; a < 3; ++a)
    {
      for (int b = 0; b < 3; ++b)
      {
        double d = 0;
        for (int k = 0; k < 3; ++k)
        {
          d += c2w[a][k] * c2w[b][k];
        }
        err = std::max(err, std::fabs(d - (a == b ? 1.0 : 0.0)));
      }
    }
    if (err > 1e-3)
    {
      Fail(name,
        where + ": 'rotation' is not a rotation matrix (|R R^T - I| = " + std::to_string(err) +
          ")");
    }
    // World-to-camera: R = rotation^T, t = -R C.
    auto& m = cam.WorldToCamera;
    for (int r = 0; r < 3; ++r)
    {
      double t = 0;
      for (int k = 0; k < 3; ++k)
      {
        m[4 * r + k] = c2w[k][r];
        t -= c2w[k][r] * c[k];
      }
      m[4 * r + 3] = t;
    }
    m[12] = m[13] = m[14] = 0;
    m[15] = 1;
    cam.Model = "PINHOLE";
    cameras.push_back(std::move(cam));
  }
  return cameras;
}

} // namespace

//------------------------------------------------------------------------------
std::vector<Camera> ReadCamerasJson(const std::string& path)
{
  const auto bytes = detail::ReadWholeFile(path);
  return Parse(bytes.data(), bytes.size(), path);
}

//------------------------------------------------------------------------------
std::vector<Camera> ReadCamerasJsonFromMemory(const void* data,
  std::size_t size,
  const std::string& name)
{
  static const char empty = 0;
  return Parse(data ? data : &empty, data ? size : 0, name);
}

//------------------------------------------------------------------------------
void WriteCamerasJson(const std::string& path, const std::vector<Camera>& cameras)
{
  nlohmann::json doc = nlohmann::json::array();
  for (std::size_t i = 0; i < cameras.size(); ++i)
  {
    const Camera& cam = cameras[i];
    const auto& m = cam.WorldToCamera;
    const auto c = cam.Center();
    nlohmann::json rot = nlohmann::json::array();
    for (int r = 0; r < 3; ++r)
    {
      // Row r of C2W = R^T is column r of R.
      rot.push_back({ m[0 * 4 + r], m[1 * 4 + r], m[2 * 4 + r] });
    }
    doc.push_back({ { "id", i },
      { "img_name", cam.Name },
      { "width", cam.Width },
      { "height", cam.Height },
      { "position", { c[0], c[1], c[2] } },
      { "rotation", rot },
      { "fy", cam.Fy },
      { "fx", cam.Fx } });
  }
  const std::string text = doc.dump(1) + "\n";
  detail::WriteFileAtomically(
    path, [&](std::FILE* f) { detail::WriteBytes(f, text.data(), text.size(), path); });
}

} // namespace vis4gs

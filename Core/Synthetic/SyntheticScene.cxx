// SPDX-License-Identifier: BSD-3-Clause
#include "SyntheticScene.h"

#include "GaussianMath.h"
#include "Rasterizer.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>

namespace vis4gs
{
namespace
{

using Vec3 = std::array<double, 3>;
using json = nlohmann::json;
constexpr double Pi = 3.14159265358979323846;

Vec3 Add(const Vec3& a, const Vec3& b)
{
  return { a[0] + b[0], a[1] + b[1], a[2] + b[2] };
}
Vec3 Sub(const Vec3& a, const Vec3& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}
Vec3 Mul(const Vec3& a, double s)
{
  return { a[0] * s, a[1] * s, a[2] * s };
}
double Dot(const Vec3& a, const Vec3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec3 Cross(const Vec3& a, const Vec3& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}
Vec3 Normalize(const Vec3& a)
{
  const double n = std::sqrt(Dot(a, a));
  return n > 0 ? Mul(a, 1.0 / n) : Vec3{ 0, 0, 1 };
}
// Any unit vector perpendicular to n.
Vec3 Perpendicular(const Vec3& n)
{
  const Vec3 a = std::abs(n[0]) < 0.9 ? Vec3{ 1, 0, 0 } : Vec3{ 0, 1, 0 };
  return Normalize(Cross(n, a));
}

// Quaternion (w,x,y,z) of the rotation whose columns are c0, c1, c2.
std::array<double, 4> QuaternionFromColumns(const Vec3& c0, const Vec3& c1, const Vec3& c2)
{
  const double m00 = c0[0], m10 = c0[1], m20 = c0[2];
  const double m01 = c1[0], m11 = c1[1], m21 = c1[2];
  const double m02 = c2[0], m12 = c2[1], m22 = c2[2];
  const double tr = m00 + m11 + m22;
  double w, x, y, z;
  if (tr > 0)
  {
    const double s = std::sqrt(tr + 1.0) * 2;
    w = 0.25 * s;
    x = (m21 - m12) / s;
    y = (m02 - m20) / s;
    z = (m10 - m01) / s;
  }
  else if (m00 > m11 && m00 > m22)
  {
    const double s = std::sqrt(1.0 + m00 - m11 - m22) * 2;
    w = (m21 - m12) / s;
    x = 0.25 * s;
    y = (m01 + m10) / s;
    z = (m02 + m20) / s;
  }
  else if (m11 > m22)
  {
    const double s = std::sqrt(1.0 + m11 - m00 - m22) * 2;
    w = (m02 - m20) / s;
    x = (m01 + m10) / s;
    y = 0.25 * s;
    z = (m12 + m21) / s;
  }
  else
  {
    const double s = std::sqrt(1.0 + m22 - m00 - m11) * 2;
    w = (m10 - m01) / s;
    x = (m02 + m20) / s;
    y = (m12 + m21) / s;
    z = 0.25 * s;
  }
  return { w, x, y, z };
}

struct Texture
{
  std::string Pattern = "solid"; // solid, checker, stripes, rings
  std::vector<Vec3> Colors{ { 0.7, 0.7, 0.7 } };
  double Fu = 8, Fv = 8;
  double Noise = 0; // per-Gaussian colour jitter

  Vec3 At(double u, double v) const
  {
    const auto pick = [&](long long k)
    {
      const long long m = static_cast<long long>(this->Colors.size());
      return this->Colors[static_cast<std::size_t>(((k % m) + m) % m)];
    };
    if (this->Pattern == "checker")
    {
      return pick(static_cast<long long>(std::floor(u * this->Fu)) +
        static_cast<long long>(std::floor(v * this->Fv)));
    }
    if (this->Pattern == "stripes")
    {
      return pick(static_cast<long long>(std::floor(u * this->Fu)));
    }
    if (this->Pattern == "rings")
    {
      return pick(static_cast<long long>(std::floor(v * this->Fv)));
    }
    return this->Colors[0];
  }
};

// One surface sample: position, normal, two tangents, texture coordinates.
struct Sample
{
  Vec3 P, N, T1;
  double U = 0, V = 0;
};

struct Object
{
  std::string Type;
  Vec3 Center{ 0, 0, 0 };
  Vec3 Axis{ 0, 0, 1 };
  Vec3 Size{ 1, 1, 1 };
  double Radius = 0.5, MinorRadius = 0.15, Height = 1;
  Texture Tex;
  int Count = 1000;
  double InitWeight = 1;
  double Thickness = 0.15; // normal scale / tangent scale
  double Opacity = 0.95;
  double ScaleFactor = 0.7; // tangent scale = factor * sqrt(area / count)

  double Area() const
  {
    if (this->Type == "sphere" || this->Type == "shell")
    {
      return 4 * Pi * this->Radius * this->Radius;
    }
    if (this->Type == "torus")
    {
      return 4 * Pi * Pi * this->Radius * this->MinorRadius;
    }
    if (this->Type == "box")
    {
      return 2 *
        (this->Size[0] * this->Size[1] + this->Size[1] * this->Size[2] +
          this->Size[0] * this->Size[2]);
    }
    if (this->Type == "cylinder")
    {
      return 2 * Pi * this->Radius * this->Height;
    }
    return this->Size[0] * this->Size[1]; // plane
  }

  // Local frame: e2 = axis (or plane normal), e0, e1 perpendicular.
  void Frame(Vec3& e0, Vec3& e1, Vec3& e2) const
  {
    e2 = Normalize(this->Axis);
    e0 = Perpendicular(e2);
    e1 = Cross(e2, e0);
  }

  Sample Draw(std::mt19937_64& rng) const
  {
    std::uniform_real_distribution<double> U(0.0, 1.0);
    std::normal_distribution<double> N(0.0, 1.0);
    Vec3 e0, e1, e2;
    this->Frame(e0, e1, e2);
    auto local = [&](double a, double b, double c)
    { return Add(Add(Mul(e0, a), Mul(e1, b)), Mul(e2, c)); };
    Sample s;
    if (this->Type == "sphere" || this->Type == "shell")
    {
      Vec3 d = Normalize({ N(rng), N(rng), N(rng) });
      s.P = Add(this->Center, Mul(d, this->Radius));
      s.N = this->Type == "shell" ? Mul(d, -1.0) : d;
      const double x = Dot(d, e0), y = Dot(d, e1), z = Dot(d, e2);
      s.U = (std::atan2(y, x) + Pi) / (2 * Pi);
      s.V = std::acos(std::max(-1.0, std::min(1.0, z))) / Pi;
    }
    else if (this->Type == "torus")
    {
      const double R = this->Radius, r = this->MinorRadius;
      double th, ph;
      do
      {
        th = 2 * Pi * U(rng);
        ph = 2 * Pi * U(rng);
      } while (U(rng) * (R + r) > R + r * std::cos(ph));
      const Vec3 radial = local(std::cos(th), std::sin(th), 0);
      const Vec3 n = Add(Mul(radial, std::cos(ph)), Mul(e2, std::sin(ph)));
      s.P = Add(this->Center, Add(Mul(radial, R), Mul(n, r)));
      s.N = n;
      s.U = th / (2 * Pi);
      s.V = ph / (2 * Pi);
    }
    else if (this->Type == "box")
    {
      const double a = this->Size[0], b = this->Size[1], c = this->Size[2];
      const double areas[3] = { b * c, a * c, a * b }; // faces normal to e0, e1, e2
      double pickA = U(rng) * (areas[0] + areas[1] + areas[2]);
      int axis = pickA < areas[0] ? 0 : (pickA < areas[0] + areas[1] ? 1 : 2);
      const double sign = U(rng) < 0.5 ? -1.0 : 1.0;
      double q[3] = { (U(rng) - 0.5) * a, (U(rng) - 0.5) * b, (U(rng) - 0.5) * c };
      q[axis] = 0.5 * sign * this->Size[axis];
      s.P = Add(this->Center, local(q[0], q[1], q[2]));
      double nn[3] = { 0, 0, 0 };
      nn[axis] = sign;
      s.N = local(nn[0], nn[1], nn[2]);
      const int ua = (axis + 1) % 3, va = (axis + 2) % 3;
      s.U = q[ua] / this->Size[ua] + 0.5 + axis;
      s.V = q[va] / this->Size[va] + 0.5;
    }
    else if (this->Type == "cylinder")
    {
      const double th = 2 * Pi * U(rng), h = (U(rng) - 0.5) * this->Height;
      const Vec3 radial = local(std::cos(th), std::sin(th), 0);
      s.P = Add(this->Center, Add(Mul(radial, this->Radius), Mul(e2, h)));
      s.N = radial;
      s.U = th / (2 * Pi);
      s.V = h / this->Height + 0.5;
    }
    else // plane: Axis is the normal, Size[0] x Size[1] along e0, e1
    {
      const double a = (U(rng) - 0.5) * this->Size[0], b = (U(rng) - 0.5) * this->Size[1];
      s.P = Add(this->Center, local(a, b, 0));
      s.N = e2;
      s.U = a / this->Size[0] + 0.5;
      s.V = b / this->Size[1] + 0.5;
    }
    s.T1 = Perpendicular(s.N);
    return s;
  }
};

[[noreturn]] void Fail(const std::string& name, const std::string& what)
{
  throw std::runtime_error(name + ": " + what);
}

Vec3 GetVec3(const json& j,
  const char* key,
  const Vec3& def,
  const std::string& where,
  bool allowTwo = false)
{
  if (!j.contains(key))
  {
    return def;
  }
  const json& v = j.at(key);
  const bool two = allowTwo && v.is_array() && v.size() == 2;
  if (!v.is_array() || (v.size() != 3 && !two) || !v[0].is_number() || !v[1].is_number() ||
    (!two && !v[2].is_number()))
  {
    Fail(where,
      std::string("'") + key + "' must be an array of " + (allowTwo ? "2 or " : "") + "3 numbers");
  }
  return { v[0].get<double>(), v[1].get<double>(), two ? def[2] : v[2].get<double>() };
}

double GetNumber(const json& j, const char* key, double def, const std::string& where)
{
  if (!j.contains(key))
  {
    return def;
  }
  if (!j.at(key).is_number())
  {
    Fail(where, std::string("'") + key + "' must be a number");
  }
  const double v = j.at(key).get<double>();
  if (!std::isfinite(v))
  {
    Fail(where, std::string("'") + key + "' must be finite");
  }
  return v;
}

int GetCount(const json& j, const char* key, int def, const std::string& where, int maximum)
{
  const double v = GetNumber(j, key, def, where);
  if (v < 0 || v > maximum || v != std::floor(v))
  {
    Fail(where, std::string("'") + key + "' must be an integer in 0.." + std::to_string(maximum));
  }
  return static_cast<int>(v);
}

Texture ParseTexture(const json& j, const std::string& where)
{
  Texture t;
  if (!j.is_object())
  {
    Fail(where, "'texture' must be an object");
  }
  if (j.contains("pattern"))
  {
    t.Pattern = j.at("pattern").get<std::string>();
    if (t.Pattern != "solid" && t.Pattern != "checker" && t.Pattern != "stripes" &&
      t.Pattern != "rings")
    {
      Fail(where, "unknown texture pattern '" + t.Pattern + "' (solid, checker, stripes, rings)");
    }
  }
  if (j.contains("colors"))
  {
    t.Colors.clear();
    for (const json& c : j.at("colors"))
    {
      if (!c.is_array() || c.size() != 3)
      {
        Fail(where, "'colors' must be a list of RGB triples");
      }
      t.Colors.push_back({ c[0].get<double>(), c[1].get<double>(), c[2].get<double>() });
    }
    if (t.Colors.empty())
    {
      Fail(where, "'colors' is empty");
    }
  }
  if (j.contains("frequency"))
  {
    const json& f = j.at("frequency");
    if (!f.is_array() || f.size() != 2)
    {
      Fail(where, "'frequency' must be [fu, fv]");
    }
    t.Fu = f[0].get<double>();
    t.Fv = f[1].get<double>();
  }
  t.Noise = GetNumber(j, "noise", 0.0, where);
  return t;
}

} // namespace

//------------------------------------------------------------------------------
Camera LookAtCamera(const std::array<double, 3>& eye,
  const std::array<double, 3>& target,
  int width,
  int height,
  double fovXDegrees)
{
  Camera cam;
  cam.Width = width;
  cam.Height = height;
  cam.Fx = width / (2.0 * std::tan(fovXDegrees * Pi / 360.0));
  cam.Fy = cam.Fx;
  cam.Cx = width / 2.0;
  cam.Cy = height / 2.0;
  cam.Model = "PINHOLE";
  const Vec3 z = Normalize(Sub(target, eye));
  Vec3 x = Cross(z, { 0, 0, 1 });
  if (Dot(x, x) < 1e-12)
  {
    x = { 1, 0, 0 }; // looking straight up or down
  }
  x = Normalize(x);
  const Vec3 y = Cross(z, x);
  const Vec3 rows[3] = { x, y, z };
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      cam.WorldToCamera[4 * r + c] = rows[r][c];
    }
    cam.WorldToCamera[4 * r + 3] = -Dot(rows[r], eye);
  }
  return cam;
}

//------------------------------------------------------------------------------
SyntheticScene MakeSyntheticScene(const std::string& text,
  const std::string& name,
  const SyntheticOptions& options)
{
  json root;
  try
  {
    root = json::parse(text);
  }
  catch (const std::exception& e)
  {
    Fail(name, std::string("not valid JSON: ") + e.what());
  }
  if (!root.is_object())
  {
    Fail(name, "the scene description must be a JSON object");
  }
  SyntheticScene scene;
  try
  {
    scene.Name = root.value("name", std::string("synthetic"));
    const std::uint64_t seed = static_cast<std::uint64_t>(GetCount(root, "seed", 0, name, 1 << 30));
    int W = GetCount(root, "width", 128, name, 8192);
    int H = GetCount(root, "height", 128, name, 8192);
    if (options.Width > 0 && options.Height > 0)
    {
      W = options.Width;
      H = options.Height;
    }
    if (W <= 0 || H <= 0)
    {
      Fail(name, "'width' and 'height' must be positive");
    }
    scene.Background = GetVec3(root, "background", { 0, 0, 0 }, name);

    // Objects.
    if (!root.contains("objects") || !root.at("objects").is_array() || root.at("objects").empty())
    {
      Fail(name, "'objects' must be a non-empty list");
    }
    std::vector<Object> objects;
    std::size_t total = 0;
    for (std::size_t k = 0; k < root.at("objects").size(); ++k)
    {
      const json& j = root.at("objects")[k];
      const std::string where = name + ": objects[" + std::to_string(k) + "]";
      Object o;
      o.Type = j.value("type", std::string());
      if (o.Type != "sphere" && o.Type != "shell" && o.Type != "torus" && o.Type != "box" &&
        o.Type != "cylinder" && o.Type != "plane")
      {
        Fail(where, "unknown type '" + o.Type + "' (sphere, shell, torus, box, cylinder, plane)");
      }
      o.Center = GetVec3(j, "center", o.Center, where);
      o.Axis = GetVec3(j, o.Type == "plane" ? "normal" : "axis", o.Axis, where);
      o.Size = GetVec3(j, "size", o.Size, where, o.Type == "plane");
      o.Radius = GetNumber(j, o.Type == "torus" ? "major_radius" : "radius", o.Radius, where);
      o.MinorRadius = GetNumber(j, "minor_radius", o.MinorRadius, where);
      o.Height = GetNumber(j, "height", o.Height, where);
      o.Count = GetCount(j, "gaussians", 1000, where, 10000000);
      o.InitWeight = GetNumber(j, "init_weight", 1.0, where);
      o.Thickness = GetNumber(j, "thickness", o.Thickness, where);
      o.Opacity = GetNumber(j, "opacity", o.Opacity, where);
      o.ScaleFactor = GetNumber(j, "scale_factor", o.ScaleFactor, where);
      if (j.contains("texture"))
      {
        o.Tex = ParseTexture(j.at("texture"), where);
      }
      if (!(o.Radius > 0) || !(o.MinorRadius > 0) || !(o.Height > 0) || !(o.Size[0] > 0) ||
        !(o.Size[1] > 0) || (o.Type == "box" && !(o.Size[2] > 0)) ||
        !(o.Opacity > 0 && o.Opacity < 1))
      {
        Fail(where, "sizes must be positive and the opacity in (0, 1)");
      }
      total += static_cast<std::size_t>(o.Count);
      objects.push_back(o);
    }
    if (total > 20000000)
    {
      Fail(name, "too many Gaussians (" + std::to_string(total) + ")");
    }

    // Ground-truth Gaussians.
    GaussianCloud& gt = scene.Truth;
    gt.Resize(total, 0);
    std::vector<std::uint32_t> objectOf(total);
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> gauss(0.0, 1.0);
    std::size_t row = 0;
    for (std::size_t k = 0; k < objects.size(); ++k)
    {
      const Object& o = objects[k];
      const double ts = o.ScaleFactor * std::sqrt(o.Area() / std::max(1, o.Count));
      for (int i = 0; i < o.Count; ++i, ++row)
      {
        const Sample s = o.Draw(rng);
        const Vec3 t2 = Cross(s.N, s.T1);
        const auto q = QuaternionFromColumns(s.T1, t2, s.N);
        Vec3 col = o.Tex.At(s.U, s.V);
        for (int c = 0; c < 3; ++c)
        {
          col[c] = std::min(1.0, std::max(0.0, col[c] + o.Tex.Noise * gauss(rng)));
        }
        for (int c = 0; c < 3; ++c)
        {
          gt.Positions[3 * row + c] = static_cast<float>(s.P[c]);
          gt.SH[3 * row + c] = static_cast<float>((col[c] - 0.5) / sh::C0);
        }
        gt.LogScales[3 * row] = static_cast<float>(std::log(ts));
        gt.LogScales[3 * row + 1] = static_cast<float>(std::log(ts));
        gt.LogScales[3 * row + 2] = static_cast<float>(std::log(ts * o.Thickness));
        for (int c = 0; c < 4; ++c)
        {
          gt.Rotations[4 * row + c] = static_cast<float>(q[c]);
        }
        gt.OpacityLogits[row] = static_cast<float>(std::log(o.Opacity / (1 - o.Opacity)));
        objectOf[row] = static_cast<std::uint32_t>(k);
      }
    }

    // Cameras.
    if (!root.contains("cameras") || !root.at("cameras").is_array())
    {
      Fail(name, "'cameras' must be a list of camera paths");
    }
    int index = 0;
    for (std::size_t k = 0; k < root.at("cameras").size(); ++k)
    {
      const json& j = root.at("cameras")[k];
      const std::string where = name + ": cameras[" + std::to_string(k) + "]";
      const std::string path = j.value("path", std::string("orbit"));
      if (path != "orbit" && path != "arc")
      {
        Fail(where, "unknown path '" + path + "' (orbit, arc)");
      }
      const std::string split = j.value("split", std::string("train"));
      if (split != "train" && split != "test")
      {
        Fail(where, "'split' must be 'train' or 'test'");
      }
      const int count = GetCount(j, "count", 8, where, 100000);
      const double radius = GetNumber(j, "radius", 3.0, where);
      const Vec3 target = GetVec3(j, "target", { 0, 0, 0 }, where);
      const double fov = GetNumber(j, "fov_deg", 50.0, where);
      const double jitter = GetNumber(j, "jitter_deg", 0.0, where);
      if (!(radius > 0) || !(fov > 1 && fov < 170))
      {
        Fail(where, "'radius' must be positive and 'fov_deg' in (1, 170)");
      }
      std::mt19937_64 crng(seed * 7919 + k);
      std::uniform_real_distribution<double> jit(-jitter, jitter);
      for (int i = 0; i < count; ++i)
      {
        const double f = count > 1 ? static_cast<double>(i) / (count - 1) : 0.5;
        double az, el;
        if (path == "orbit")
        {
          const double a0 = GetNumber(j, "start_deg", 0.0, where),
                       a1 = GetNumber(j, "end_deg", 360.0, where);
          // A full circle does not repeat its first view.
          const double span = a1 - a0;
          az = std::abs(std::abs(span) - 360.0) < 1e-9 ? a0 + span * i / std::max(1, count)
                                                       : a0 + span * f;
          el = GetNumber(j, "elevation_deg", 20.0, where);
        }
        else
        {
          az = GetNumber(j, "azimuth_deg", 0.0, where);
          el = GetNumber(j, "start_elevation_deg", 5.0, where) +
            (GetNumber(j, "end_elevation_deg", 70.0, where) -
              GetNumber(j, "start_elevation_deg", 5.0, where)) *
              f;
        }
        az += jit(crng);
        el += jit(crng);
        const double ar = az * Pi / 180, er = el * Pi / 180;
        const Vec3 eye = Add(target,
          { radius * std::cos(er) * std::cos(ar),
            radius * std::cos(er) * std::sin(ar),
            radius * std::sin(er) });
        Camera cam = LookAtCamera(eye, target, W, H, fov);
        cam.Split = split == "test" ? CameraSplit::Test : CameraSplit::Train;
        char buf[32];
        std::snprintf(buf, sizeof(buf), "%s_%03d", split.c_str(), index++);
        cam.Name = buf;
        cam.ImagePath = "/images/" + cam.Name;
        scene.Cameras.push_back(cam);
      }
    }
    if (scene.Cameras.empty())
    {
      Fail(name, "no cameras");
    }

    // Images.
    if (options.RenderImages)
    {
      RasterSettings rs;
      rs.Background = scene.Background;
      rs.Threads = options.Threads;
      for (const Camera& cam : scene.Cameras)
      {
        const RasterImage<float> img = Rasterize<float>(gt, cam, rs);
        std::vector<float> rgb(img.Color.size());
        for (std::size_t p = 0; p < rgb.size(); ++p)
        {
          rgb[p] = std::min(1.0f, std::max(0.0f, img.Color[p]));
        }
        scene.Images.push_back(std::move(rgb));
      }
    }

    // Initial points: a sparse, noisy subset of the surfaces plus outliers.
    const json ip = root.value("initial_points", json::object());
    const std::string where = name + ": initial_points";
    const int npoints = GetCount(ip, "count", 1000, where, 10000000);
    const double posNoise = GetNumber(ip, "position_noise", 0.01, where);
    const double colNoise = GetNumber(ip, "color_noise", 0.03, where);
    const double outliers = GetNumber(ip, "outlier_fraction", 0.0, where);
    Vec3 boxLo = { -1, -1, -1 }, boxHi = { 1, 1, 1 };
    if (ip.contains("outlier_box"))
    {
      const json& b = ip.at("outlier_box");
      if (!b.is_array() || b.size() != 2)
      {
        Fail(where, "'outlier_box' must be [[xmin,ymin,zmin],[xmax,ymax,zmax]]");
      }
      boxLo = { b[0][0].get<double>(), b[0][1].get<double>(), b[0][2].get<double>() };
      boxHi = { b[1][0].get<double>(), b[1][1].get<double>(), b[1][2].get<double>() };
    }
    std::vector<double> weights(total);
    for (std::size_t i = 0; i < total; ++i)
    {
      weights[i] = std::max(0.0, objects[objectOf[i]].InitWeight);
    }
    std::mt19937_64 prng(seed ^ 0xA5A5A5A5ull);
    std::discrete_distribution<std::size_t> pickRow(weights.begin(), weights.end());
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    const int nOut = static_cast<int>(std::lround(outliers * npoints));
    for (int i = 0; i < npoints; ++i)
    {
      Vec3 p, c;
      if (i < npoints - nOut)
      {
        const std::size_t r = pickRow(prng);
        for (int k = 0; k < 3; ++k)
        {
          p[k] = gt.Positions[3 * r + k] + posNoise * gauss(prng);
          c[k] =
            std::min(1.0, std::max(0.0, 0.5 + sh::C0 * gt.SH[3 * r + k] + colNoise * gauss(prng)));
        }
      }
      else
      {
        for (int k = 0; k < 3; ++k)
        {
          p[k] = boxLo[k] + (boxHi[k] - boxLo[k]) * uni(prng);
          c[k] = uni(prng);
        }
      }
      for (int k = 0; k < 3; ++k)
      {
        scene.PointPositions.push_back(static_cast<float>(p[k]));
        scene.PointColors.push_back(static_cast<float>(c[k]));
      }
    }
  }
  catch (const json::exception& e)
  {
    Fail(name, std::string("bad value in the scene description: ") + e.what());
  }
  return scene;
}

//------------------------------------------------------------------------------
SyntheticScene LoadSyntheticScene(const std::string& path, const SyntheticOptions& options)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    throw std::runtime_error(path + ": cannot open the scene description");
  }
  std::ostringstream ss;
  ss << in.rdbuf();
  return MakeSyntheticScene(ss.str(), path, options);
}

} // namespace vis4gs

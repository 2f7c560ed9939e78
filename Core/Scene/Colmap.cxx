// SPDX-License-Identifier: BSD-3-Clause
#include "Colmap.h"
#include "GaussianMath.h"
#include "SceneFile.h"

#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <stdexcept>
#include <string_view>

namespace vis4gs
{

namespace
{

const ColmapCameraModel Models[] = { { 0, "SIMPLE_PINHOLE", 3, true },
  { 1, "PINHOLE", 4, false },
  { 2, "SIMPLE_RADIAL", 4, true },
  { 3, "RADIAL", 5, true },
  { 4, "OPENCV", 8, false },
  { 5, "OPENCV_FISHEYE", 8, false },
  { 6, "FULL_OPENCV", 12, false },
  { 7, "FOV", 5, false },
  { 8, "SIMPLE_RADIAL_FISHEYE", 4, true },
  { 9, "RADIAL_FISHEYE", 5, true },
  { 10, "THIN_PRISM_FISHEYE", 12, false } };

[[noreturn]] void Fail(const std::string& name, const std::string& what)
{
  throw std::runtime_error(name + ": " + what);
}

//------------------------------------------------------------------------------
// Little-endian binary cursor with bounds checks.
class Cursor
{
public:
  Cursor(const void* data, std::size_t size, const std::string& name)
    : P(static_cast<const unsigned char*>(data))
    , Left(size)
    , Name(name)
  {
  }

  template <typename T>
  T Get(const std::string& what)
  {
    if (this->Left < sizeof(T))
    {
      Fail(this->Name, "file ends early while reading " + what);
    }
    unsigned char b[sizeof(T)];
    std::memcpy(b, this->P, sizeof(T));
    if (!detail::HostIsLittleEndian())
    {
      detail::SwapBytes(b, sizeof(T));
    }
    T v;
    std::memcpy(&v, b, sizeof(T));
    this->P += sizeof(T);
    this->Left -= sizeof(T);
    return v;
  }

  /// A count of records of at least @p minBytes each; fails when they cannot fit.
  std::uint64_t Count(std::size_t minBytes, const std::string& what)
  {
    const std::uint64_t n = this->Get<std::uint64_t>("the number of " + what);
    if (minBytes && n > this->Left / minBytes)
    {
      Fail(this->Name,
        "declares " + std::to_string(n) + " " + what + " but only " + std::to_string(this->Left) +
          " bytes follow (at least " + std::to_string(minBytes) + " each; truncated?)");
    }
    return n;
  }

  std::string CString(const std::string& what)
  {
    const void* end = std::memchr(this->P, '\0', this->Left);
    if (!end)
    {
      Fail(this->Name, "file ends inside " + what);
    }
    const std::size_t len = static_cast<const unsigned char*>(end) - this->P;
    std::string s(reinterpret_cast<const char*>(this->P), len);
    this->P += len + 1;
    this->Left -= len + 1;
    return s;
  }

  /// Every element of @p values (a std::array or std::vector), in order.
  template <typename Array>
  void GetAll(Array& values, const std::string& what)
  {
    for (auto& v : values)
    {
      v = this->Get<typename Array::value_type>(what);
    }
  }

  /// A count of records of exactly @p bytes each, then the records: each read by
  /// @p read(record) into @p records when @p keep, else skipped.
  template <typename Record, typename Read>
  void FixedRecords(std::vector<Record>& records,
    std::size_t bytes,
    const std::string& what,
    bool keep,
    Read read)
  {
    const std::uint64_t n = this->Count(bytes, what);
    if (!keep)
    {
      this->P += n * bytes; // Count() checked the bytes exist
      this->Left -= n * bytes;
      return;
    }
    records.resize(static_cast<std::size_t>(n));
    for (auto& r : records)
    {
      read(r);
    }
  }

  std::size_t Remaining() const { return this->Left; }

private:
  const unsigned char* P;
  std::size_t Left;
  const std::string& Name;
};

template <typename T>
T ParseNumber(std::string_view s, const std::string& name, std::size_t lineNo, const char* what)
{
  T v{};
  std::string_view t = s;
  if (!t.empty() && t[0] == '+')
  {
    t.remove_prefix(1);
  }
  const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
  if (r.ec != std::errc() || r.ptr != t.data() + t.size() || t.empty())
  {
    Fail(name,
      "line " + std::to_string(lineNo) + ": '" + std::string(s.substr(0, 40)) +
        "' is not a valid " + what);
  }
  return v;
}

/// The words @p tok[first], @p tok[first + 1], ... as the elements of @p values (a std::array).
template <typename Array>
void ParseNumbers(Array& values,
  const std::vector<std::string_view>& tok,
  std::size_t first,
  const std::string& name,
  std::size_t lineNo,
  const char* what)
{
  for (std::size_t k = 0; k < values.size(); ++k)
  {
    values[k] = ParseNumber<typename Array::value_type>(tok[first + k], name, lineNo, what);
  }
}

//------------------------------------------------------------------------------
void CheckCameraParams(const ColmapCamera& c, const std::string& name, const std::string& where)
{
  if (c.Width == 0 || c.Height == 0 || c.Width > (1u << 20) || c.Height > (1u << 20))
  {
    Fail(name,
      where + ": image size " + std::to_string(c.Width) + "x" + std::to_string(c.Height) +
        " is not plausible");
  }
  for (double p : c.Params)
  {
    if (!std::isfinite(p))
    {
      Fail(name, where + ": parameters are not finite");
    }
  }
}

void CheckImagePose(const ColmapImage& im, const std::string& name, const std::string& where)
{
  double n2 = 0;
  for (double q : im.Q)
  {
    if (!std::isfinite(q))
    {
      Fail(name, where + ": rotation quaternion is not finite");
    }
    n2 += q * q;
  }
  if (!(n2 > 1e-20))
  {
    Fail(name, where + ": rotation quaternion is zero");
  }
  for (double t : im.T)
  {
    if (!std::isfinite(t))
    {
      Fail(name, where + ": translation is not finite");
    }
  }
}

//------------------------------------------------------------------------------
std::vector<ColmapCamera> CamerasBinary(const void* data, std::size_t size, const std::string& name)
{
  Cursor in(data, size, name);
  const std::uint64_t n = in.Count(24, "cameras");
  std::vector<ColmapCamera> cams;
  cams.reserve(static_cast<std::size_t>(n));
  for (std::uint64_t i = 0; i < n; ++i)
  {
    const std::string where = "camera record " + std::to_string(i);
    ColmapCamera c;
    c.Id = in.Get<std::int32_t>(where);
    c.ModelId = in.Get<std::int32_t>(where);
    c.Width = in.Get<std::uint64_t>(where);
    c.Height = in.Get<std::uint64_t>(where);
    const ColmapCameraModel* model = FindColmapModel(c.ModelId);
    if (!model)
    {
      Fail(name,
        where + " (id " + std::to_string(c.Id) + "): unknown camera model id " +
          std::to_string(c.ModelId));
    }
    c.Params.resize(model->NumParams);
    in.GetAll(c.Params, where + " parameters");
    CheckCameraParams(c, name, where + " (id " + std::to_string(c.Id) + ")");
    cams.push_back(std::move(c));
  }
  return cams;
}

//------------------------------------------------------------------------------
std::vector<ColmapCamera> CamerasText(const void* data, std::size_t size, const std::string& name)
{
  detail::TextLines lines(std::string_view(static_cast<const char*>(data), size));
  std::string_view line;
  std::vector<ColmapCamera> cams;
  while (lines.Next(line, true)) // blank and '#' lines skipped
  {
    const std::size_t ln = lines.LineNumber();
    const auto tok = detail::SplitWords(line);
    if (tok.size() < 4)
    {
      Fail(
        name, "line " + std::to_string(ln) + ": expected 'CAMERA_ID MODEL WIDTH HEIGHT PARAMS...'");
    }
    ColmapCamera c;
    c.Id = ParseNumber<std::int32_t>(tok[0], name, ln, "camera id");
    const ColmapCameraModel* model = FindColmapModel(std::string(tok[1]));
    if (!model)
    {
      Fail(name,
        "line " + std::to_string(ln) + ": unknown camera model '" +
          std::string(tok[1].substr(0, 40)) + "'");
    }
    c.ModelId = model->Id;
    c.Width = ParseNumber<std::uint64_t>(tok[2], name, ln, "width");
    c.Height = ParseNumber<std::uint64_t>(tok[3], name, ln, "height");
    if (tok.size() != 4 + static_cast<std::size_t>(model->NumParams))
    {
      Fail(name,
        "line " + std::to_string(ln) + ": model " + model->Name + " needs " +
          std::to_string(model->NumParams) + " parameters, the line has " +
          std::to_string(tok.size() - 4));
    }
    for (int p = 0; p < model->NumParams; ++p)
    {
      c.Params.push_back(ParseNumber<double>(tok[4 + p], name, ln, "camera parameter"));
    }
    CheckCameraParams(c, name, "line " + std::to_string(ln));
    cams.push_back(std::move(c));
  }
  return cams;
}

//------------------------------------------------------------------------------
std::vector<ColmapImage> ImagesBinary(const void* data,
  std::size_t size,
  const std::string& name,
  bool observations)
{
  Cursor in(data, size, name);
  const std::uint64_t n = in.Count(64 + 1 + 8, "images");
  std::vector<ColmapImage> images;
  images.reserve(static_cast<std::size_t>(n));
  for (std::uint64_t i = 0; i < n; ++i)
  {
    std::string where = "image record " + std::to_string(i);
    ColmapImage im;
    im.Id = in.Get<std::int32_t>(where);
    in.GetAll(im.Q, where);
    in.GetAll(im.T, where);
    im.CameraId = in.Get<std::int32_t>(where);
    im.Name = in.CString(where + " name");
    where += " ('" + im.Name + "')";
    CheckImagePose(im, name, where);
    in.FixedRecords(im.Points2D,
      24,
      "2D points of " + where,
      observations,
      [&](ColmapPoint2D& p)
      {
        p.X = in.Get<double>(where);
        p.Y = in.Get<double>(where);
        p.Point3DId = in.Get<std::int64_t>(where);
      });
    images.push_back(std::move(im));
  }
  return images;
}

//------------------------------------------------------------------------------
std::vector<ColmapImage> ImagesText(const void* data,
  std::size_t size,
  const std::string& name,
  bool observations)
{
  detail::TextLines lines(std::string_view(static_cast<const char*>(data), size));
  std::string_view line;
  std::vector<ColmapImage> images;
  while (lines.Next(line, true)) // blank and '#' lines skipped
  {
    const std::size_t ln = lines.LineNumber();
    const auto tok = detail::SplitWords(line);
    if (tok.size() < 10)
    {
      Fail(name,
        "line " + std::to_string(ln) + ": expected 'IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME'");
    }
    ColmapImage im;
    im.Id = ParseNumber<std::int32_t>(tok[0], name, ln, "image id");
    ParseNumbers(im.Q, tok, 1, name, ln, "quaternion component");
    ParseNumbers(im.T, tok, 5, name, ln, "translation component");
    im.CameraId = ParseNumber<std::int32_t>(tok[8], name, ln, "camera id");
    // The name is the rest of the line (COLMAP names may not contain spaces, but be lenient).
    const std::size_t nameStart = static_cast<std::size_t>(tok[9].data() - line.data());
    std::string_view rest = line.substr(nameStart);
    while (!rest.empty() && (rest.back() == '\r' || rest.back() == ' ' || rest.back() == '\t'))
    {
      rest.remove_suffix(1);
    }
    im.Name = std::string(rest);
    CheckImagePose(im, name, "line " + std::to_string(ln) + " ('" + im.Name + "')");
    // The 2D points line follows (possibly empty or missing at the end of the file).
    std::string_view pts;
    if (lines.Raw(pts))
    {
      const auto ptok = detail::SplitWords(pts);
      if (ptok.size() % 3 != 0)
      {
        Fail(name,
          "line " + std::to_string(lines.LineNumber()) +
            ": 2D points must come in triples 'X Y POINT3D_ID'");
      }
      for (std::size_t k = 0; k < ptok.size(); k += 3)
      {
        ColmapPoint2D p;
        p.X = ParseNumber<double>(ptok[k], name, lines.LineNumber(), "2D point x");
        p.Y = ParseNumber<double>(ptok[k + 1], name, lines.LineNumber(), "2D point y");
        p.Point3DId =
          ParseNumber<std::int64_t>(ptok[k + 2], name, lines.LineNumber(), "point3D id");
        if (observations)
        {
          im.Points2D.push_back(p);
        }
      }
    }
    images.push_back(std::move(im));
  }
  return images;
}

//------------------------------------------------------------------------------
std::vector<ColmapPoint3D> PointsBinary(const void* data,
  std::size_t size,
  const std::string& name,
  bool observations)
{
  Cursor in(data, size, name);
  const std::uint64_t n = in.Count(43 + 8, "3D points");
  std::vector<ColmapPoint3D> points;
  points.reserve(static_cast<std::size_t>(n));
  for (std::uint64_t i = 0; i < n; ++i)
  {
    const std::string where = "point3D record " + std::to_string(i);
    ColmapPoint3D p;
    p.Id = in.Get<std::uint64_t>(where);
    in.GetAll(p.Xyz, where);
    in.GetAll(p.Rgb, where);
    p.Error = in.Get<double>(where);
    in.FixedRecords(p.Track,
      8,
      "track elements of " + where,
      observations,
      [&](ColmapTrackElement& t)
      {
        t.ImageId = in.Get<std::int32_t>(where);
        t.Point2DIdx = in.Get<std::int32_t>(where);
      });
    points.push_back(std::move(p));
  }
  return points;
}

//------------------------------------------------------------------------------
std::vector<ColmapPoint3D> PointsText(const void* data,
  std::size_t size,
  const std::string& name,
  bool observations)
{
  detail::TextLines lines(std::string_view(static_cast<const char*>(data), size));
  std::string_view line;
  std::vector<ColmapPoint3D> points;
  while (lines.Next(line, true)) // blank and '#' lines skipped
  {
    const std::size_t ln = lines.LineNumber();
    const auto tok = detail::SplitWords(line);
    if (tok.size() < 8 || (tok.size() - 8) % 2 != 0)
    {
      Fail(name,
        "line " + std::to_string(ln) +
          ": expected 'POINT3D_ID X Y Z R G B ERROR (IMAGE_ID POINT2D_IDX)...'");
    }
    ColmapPoint3D p;
    p.Id = ParseNumber<std::uint64_t>(tok[0], name, ln, "point3D id");
    ParseNumbers(p.Xyz, tok, 1, name, ln, "coordinate");
    for (int k = 0; k < 3; ++k)
    {
      const unsigned v = ParseNumber<unsigned>(tok[4 + k], name, ln, "colour (0..255)");
      if (v > 255)
      {
        Fail(name, "line " + std::to_string(ln) + ": colour " + std::to_string(v) + " > 255");
      }
      p.Rgb[k] = static_cast<unsigned char>(v);
    }
    p.Error = ParseNumber<double>(tok[7], name, ln, "reprojection error");
    for (std::size_t k = 8; k < tok.size(); k += 2)
    {
      ColmapTrackElement t;
      t.ImageId = ParseNumber<std::int32_t>(tok[k], name, ln, "image id");
      t.Point2DIdx = ParseNumber<std::int32_t>(tok[k + 1], name, ln, "2D point index");
      if (observations)
      {
        p.Track.push_back(t);
      }
    }
    points.push_back(std::move(p));
  }
  return points;
}

//------------------------------------------------------------------------------
// Writers.
class ByteWriter
{
public:
  template <typename T>
  void Put(T v)
  {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (!detail::HostIsLittleEndian())
    {
      detail::SwapBytes(b, sizeof(T));
    }
    this->Bytes.insert(this->Bytes.end(), b, b + sizeof(T));
  }
  template <typename Array>
  void PutAll(const Array& values)
  {
    for (auto v : values)
    {
      this->Put<typename Array::value_type>(v);
    }
  }
  void PutString(const std::string& s)
  {
    this->Bytes.insert(this->Bytes.end(), s.begin(), s.end());
    this->Bytes.push_back('\0');
  }
  std::vector<unsigned char> Bytes;
};

std::string Num(double v)
{
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof(buf), v);
  return std::string(buf, r.ptr);
}

/// " v0 v1 ..." (shortest round-trip text) after @p line.
template <typename Array>
void AppendNums(std::string& line, const Array& values)
{
  for (double v : values)
  {
    line += " " + Num(v);
  }
}

void WriteOut(const std::string& path, const void* data, std::size_t size)
{
  detail::WriteFileAtomically(path, [&](std::FILE* f) { detail::WriteBytes(f, data, size, path); });
}

} // namespace

//------------------------------------------------------------------------------
const ColmapCameraModel* FindColmapModel(int id)
{
  for (const auto& m : Models)
  {
    if (m.Id == id)
    {
      return &m;
    }
  }
  return nullptr;
}

//------------------------------------------------------------------------------
const ColmapCameraModel* FindColmapModel(const std::string& name)
{
  for (const auto& m : Models)
  {
    if (name == m.Name)
    {
      return &m;
    }
  }
  return nullptr;
}

//------------------------------------------------------------------------------
std::vector<ColmapCamera> ParseColmapCameras(const void* data,
  std::size_t size,
  ColmapFormat format,
  const std::string& name)
{
  static const char empty = 0;
  data = data ? data : &empty;
  return format == ColmapFormat::Binary ? CamerasBinary(data, size, name)
                                        : CamerasText(data, size, name);
}

//------------------------------------------------------------------------------
std::vector<ColmapImage> ParseColmapImages(const void* data,
  std::size_t size,
  ColmapFormat format,
  const std::string& name,
  bool observations)
{
  static const char empty = 0;
  data = data ? data : &empty;
  return format == ColmapFormat::Binary ? ImagesBinary(data, size, name, observations)
                                        : ImagesText(data, size, name, observations);
}

//------------------------------------------------------------------------------
std::vector<ColmapPoint3D> ParseColmapPoints3D(const void* data,
  std::size_t size,
  ColmapFormat format,
  const std::string& name,
  bool observations)
{
  static const char empty = 0;
  data = data ? data : &empty;
  return format == ColmapFormat::Binary ? PointsBinary(data, size, name, observations)
                                        : PointsText(data, size, name, observations);
}

//------------------------------------------------------------------------------
ColmapModel ReadColmapModel(const std::string& folder, bool observations)
{
  ColmapFormat format = ColmapFormat::Binary;
  std::string ext = ".bin";
  if (!detail::IsRegularFile(folder + "/cameras.bin"))
  {
    if (!detail::IsRegularFile(folder + "/cameras.txt"))
    {
      throw std::runtime_error(
        folder + ": no COLMAP model here (neither cameras.bin nor cameras.txt)");
    }
    format = ColmapFormat::Text;
    ext = ".txt";
  }
  ColmapModel model;
  {
    const std::string path = folder + "/cameras" + ext;
    const auto bytes = detail::ReadWholeFile(path);
    model.Cameras = ParseColmapCameras(bytes.data(), bytes.size(), format, path);
  }
  {
    const std::string path = folder + "/images" + ext;
    const auto bytes = detail::ReadWholeFile(path);
    model.Images = ParseColmapImages(bytes.data(), bytes.size(), format, path, observations);
  }
  const std::string pointsPath = folder + "/points3D" + ext;
  if (detail::IsRegularFile(pointsPath))
  {
    const auto bytes = detail::ReadWholeFile(pointsPath);
    model.Points3D =
      ParseColmapPoints3D(bytes.data(), bytes.size(), format, pointsPath, observations);
  }
  std::map<int, std::size_t> cameraIndex;
  for (std::size_t i = 0; i < model.Cameras.size(); ++i)
  {
    if (!cameraIndex.emplace(model.Cameras[i].Id, i).second)
    {
      throw std::runtime_error(folder + "/cameras" + ext + ": camera id " +
        std::to_string(model.Cameras[i].Id) + " appears twice");
    }
  }
  for (const auto& im : model.Images)
  {
    if (!cameraIndex.count(im.CameraId))
    {
      throw std::runtime_error(folder + "/images" + ext + ": image '" + im.Name +
        "' refers to camera " + std::to_string(im.CameraId) + ", which cameras" + ext +
        " does not define");
    }
  }
  return model;
}

//------------------------------------------------------------------------------
void WriteColmapModel(const std::string& folder, const ColmapModel& model, ColmapFormat format)
{
  for (const auto& c : model.Cameras)
  {
    const ColmapCameraModel* m = FindColmapModel(c.ModelId);
    if (!m || c.Params.size() != static_cast<std::size_t>(m->NumParams))
    {
      throw std::invalid_argument("WriteColmapModel: camera " + std::to_string(c.Id) +
        " has an unknown model or the wrong number of parameters");
    }
  }
  if (format == ColmapFormat::Binary)
  {
    ByteWriter cams;
    cams.Put<std::uint64_t>(model.Cameras.size());
    for (const auto& c : model.Cameras)
    {
      cams.Put<std::int32_t>(c.Id);
      cams.Put<std::int32_t>(c.ModelId);
      cams.Put<std::uint64_t>(c.Width);
      cams.Put<std::uint64_t>(c.Height);
      cams.PutAll(c.Params);
    }
    WriteOut(folder + "/cameras.bin", cams.Bytes.data(), cams.Bytes.size());
    ByteWriter ims;
    ims.Put<std::uint64_t>(model.Images.size());
    for (const auto& im : model.Images)
    {
      ims.Put<std::int32_t>(im.Id);
      ims.PutAll(im.Q);
      ims.PutAll(im.T);
      ims.Put<std::int32_t>(im.CameraId);
      ims.PutString(im.Name);
      ims.Put<std::uint64_t>(im.Points2D.size());
      for (const auto& p : im.Points2D)
      {
        ims.Put<double>(p.X);
        ims.Put<double>(p.Y);
        ims.Put<std::int64_t>(p.Point3DId);
      }
    }
    WriteOut(folder + "/images.bin", ims.Bytes.data(), ims.Bytes.size());
    ByteWriter pts;
    pts.Put<std::uint64_t>(model.Points3D.size());
    for (const auto& p : model.Points3D)
    {
      pts.Put<std::uint64_t>(p.Id);
      pts.PutAll(p.Xyz);
      pts.PutAll(p.Rgb);
      pts.Put<double>(p.Error);
      pts.Put<std::uint64_t>(p.Track.size());
      for (const auto& t : p.Track)
      {
        pts.Put<std::int32_t>(t.ImageId);
        pts.Put<std::int32_t>(t.Point2DIdx);
      }
    }
    WriteOut(folder + "/points3D.bin", pts.Bytes.data(), pts.Bytes.size());
    return;
  }
  std::string cams = "# Camera list with one line of data per camera:\n"
                     "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n"
                     "# Number of cameras: " +
    std::to_string(model.Cameras.size()) + "\n";
  for (const auto& c : model.Cameras)
  {
    cams += std::to_string(c.Id) + " " + FindColmapModel(c.ModelId)->Name + " " +
      std::to_string(c.Width) + " " + std::to_string(c.Height);
    AppendNums(cams, c.Params);
    cams += "\n";
  }
  WriteOut(folder + "/cameras.txt", cams.data(), cams.size());
  std::string ims = "# Image list with two lines of data per image:\n"
                    "#   IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, CAMERA_ID, NAME\n"
                    "#   POINTS2D[] as (X, Y, POINT3D_ID)\n"
                    "# Number of images: " +
    std::to_string(model.Images.size()) + "\n";
  for (const auto& im : model.Images)
  {
    ims += std::to_string(im.Id);
    AppendNums(ims, im.Q);
    AppendNums(ims, im.T);
    ims += " " + std::to_string(im.CameraId) + " " + im.Name + "\n";
    for (std::size_t k = 0; k < im.Points2D.size(); ++k)
    {
      const auto& p = im.Points2D[k];
      ims += (k ? " " : "") + Num(p.X) + " " + Num(p.Y) + " " + std::to_string(p.Point3DId);
    }
    ims += "\n";
  }
  WriteOut(folder + "/images.txt", ims.data(), ims.size());
  std::string pts = "# 3D point list with one line of data per point:\n"
                    "#   POINT3D_ID, X, Y, Z, R, G, B, ERROR, TRACK[] as (IMAGE_ID, POINT2D_IDX)\n"
                    "# Number of points: " +
    std::to_string(model.Points3D.size()) + "\n";
  for (const auto& p : model.Points3D)
  {
    pts += std::to_string(p.Id);
    AppendNums(pts, p.Xyz);
    for (auto c : p.Rgb)
    {
      pts += " " + std::to_string(static_cast<unsigned>(c));
    }
    pts += " " + Num(p.Error);
    for (const auto& t : p.Track)
    {
      pts += " " + std::to_string(t.ImageId) + " " + std::to_string(t.Point2DIdx);
    }
    pts += "\n";
  }
  WriteOut(folder + "/points3D.txt", pts.data(), pts.size());
}

//------------------------------------------------------------------------------
Camera ToCamera(const ColmapCamera& camera, const ColmapImage& image)
{
  const ColmapCameraModel* model = FindColmapModel(camera.ModelId);
  if (!model || camera.Params.size() != static_cast<std::size_t>(model->NumParams))
  {
    throw std::invalid_argument("ToCamera: camera " + std::to_string(camera.Id) +
      " has an unknown model or the wrong number of parameters");
  }
  Camera cam;
  const auto slash = image.Name.find_last_of('/');
  const std::string base = slash == std::string::npos ? image.Name : image.Name.substr(slash + 1);
  cam.Name = base.substr(0, base.find('.'));
  cam.ImagePath = image.Name;
  cam.Width = static_cast<int>(camera.Width);
  cam.Height = static_cast<int>(camera.Height);
  cam.Model = model->Name;
  const auto& p = camera.Params;
  std::size_t next;
  if (model->SingleFocal)
  {
    cam.Fx = cam.Fy = p[0];
    cam.Cx = p[1];
    cam.Cy = p[2];
    next = 3;
  }
  else
  {
    cam.Fx = p[0];
    cam.Fy = p[1];
    cam.Cx = p[2];
    cam.Cy = p[3];
    next = 4;
  }
  cam.Distortion.assign(p.begin() + static_cast<std::ptrdiff_t>(next), p.end());
  const double q[4] = { image.Q[0], image.Q[1], image.Q[2], image.Q[3] };
  const auto r = QuaternionToMatrix(NormalizeQuaternion(q));
  auto& m = cam.WorldToCamera;
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      m[4 * i + j] = r[3 * i + j];
    }
    m[4 * i + 3] = image.T[i];
  }
  m[12] = m[13] = m[14] = 0;
  m[15] = 1;
  return cam;
}

//------------------------------------------------------------------------------
bool IsDistorted(const ColmapCamera& camera)
{
  const ColmapCameraModel* model = FindColmapModel(camera.ModelId);
  if (!model)
  {
    return true;
  }
  const std::string name = model->Name;
  if (name.find("FISHEYE") != std::string::npos)
  {
    return true;
  }
  const std::size_t first = model->SingleFocal ? 3 : 4;
  for (std::size_t i = first; i < camera.Params.size(); ++i)
  {
    if (camera.Params[i] != 0.0)
    {
      return true;
    }
  }
  return false;
}

} // namespace vis4gs

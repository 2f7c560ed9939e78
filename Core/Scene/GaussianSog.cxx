// SPDX-License-Identifier: BSD-3-Clause
// PlayCanvas SOG v2 (Documentation/file-formats.md): meta.json plus lossless WebP textures in
// which Gaussian g is texel g (row-major): means_l/means_u (16-bit log-transformed position
// between mins and maxs), quats (smallest-three, tag 252+largest), scales and sh0 (indices
// into 256-entry codebooks, sh0's alpha the opacity), shN (a palette of SH centroids and a
// 16-bit label per Gaussian). Decoding follows splat-transform 3.2
// (src/lib/readers/read-sog.ts), each value computed in double and rounded once to float32.
#include "GaussianIO.h"
#include "SceneFile.h"

#include <nlohmann/json.hpp>
#include <webp/decode.h>
#include <zip.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>

namespace vis4gs
{

namespace
{

[[noreturn]] void Fail(const std::string& name, const std::string& what)
{
  throw std::runtime_error(name + ": " + what);
}

/// Largest meta.json read (its codebooks are 256 numbers each).
constexpr std::uint64_t MaxMetaBytes = std::uint64_t(16) << 20;
/// A decoded texture may exceed this many bytes only when its file is at least 1/1024 of it:
/// real textures compress a few times, a decompression bomb thousands of times.
constexpr std::uint64_t FreeDecodedBytes = std::uint64_t(64) << 20;
constexpr std::uint64_t MaxExpansion = 1024;
/// WebP's largest dimension is 16383, so no SOG holds more Gaussians.
constexpr std::uint64_t MaxSogCount = std::uint64_t(16383) * 16383;

std::string Human(std::uint64_t bytes)
{
  char buf[64];
  if (bytes >= (std::uint64_t(1) << 20))
  {
    std::snprintf(buf, sizeof(buf), "%.1f MiB", bytes / 1048576.0);
  }
  else
  {
    std::snprintf(buf, sizeof(buf), "%llu bytes", static_cast<unsigned long long>(bytes));
  }
  return buf;
}

/// Refuses a stored entry or texture that expands beyond the limit above.
void CheckExpansion(const std::string& name,
  const std::string& what,
  std::uint64_t packed,
  std::uint64_t unpacked)
{
  if (unpacked > FreeDecodedBytes && unpacked / MaxExpansion > packed)
  {
    Fail(name,
      what + " expands " + Human(packed) + " to " + Human(unpacked) +
        ", beyond the limit (1024 times its size past 64 MiB): refused as a decompression bomb");
  }
}

/// Where the files of a SOG come from: a folder or a zip archive.
class SogFiles
{
public:
  virtual ~SogFiles() = default;
  virtual std::vector<unsigned char> Load(const std::string& file, std::uint64_t maxBytes) = 0;
  std::string Name;
};

/// Only plain names: a meta.json must not reach outside its folder.
void CheckFileName(const std::string& name, const std::string& file)
{
  if (file.empty() || file.find('/') != std::string::npos || file.find('\\') != std::string::npos ||
    file == "." || file == "..")
  {
    Fail(name, "meta.json names the file '" + file + "'; only plain names in its folder are read");
  }
}

class FolderFiles : public SogFiles
{
public:
  explicit FolderFiles(std::string folder)
    : Folder(std::move(folder))
  {
    this->Name = this->Folder;
  }
  std::vector<unsigned char> Load(const std::string& file, std::uint64_t maxBytes) override
  {
    CheckFileName(this->Name, file);
    const std::string path = this->Folder + "/" + file;
    detail::InputFile in(path);
    if (in.Size() > maxBytes)
    {
      Fail(path, "file of " + Human(in.Size()) + " exceeds the limit of " + Human(maxBytes));
    }
    std::vector<unsigned char> bytes(static_cast<std::size_t>(in.Size()));
    in.ReadAt(0, bytes.data(), bytes.size());
    return bytes;
  }

private:
  std::string Folder;
};

class ZipFiles : public SogFiles
{
public:
  /// Opens a zip from @p data (kept alive by the caller) or, when null, from @p path.
  ZipFiles(const std::string& path, const void* data, std::size_t size)
  {
    this->Name = path;
    zip_error_t error;
    zip_error_init(&error);
    if (data)
    {
      zip_source_t* src = zip_source_buffer_create(data, size, 0, &error);
      if (src)
      {
        this->Archive = zip_open_from_source(src, ZIP_RDONLY, &error);
        if (!this->Archive)
        {
          zip_source_free(src);
        }
      }
    }
    else
    {
      int code = 0;
      this->Archive = zip_open(path.c_str(), ZIP_RDONLY, &code);
      zip_error_init_with_code(&error, code);
    }
    if (!this->Archive)
    {
      const std::string why = zip_error_strerror(&error);
      zip_error_fini(&error);
      Fail(path, "not a readable .sog (zip) archive: " + why);
    }
    zip_error_fini(&error);
  }
  ~ZipFiles() override
  {
    if (this->Archive)
    {
      zip_discard(this->Archive);
    }
  }
  std::vector<unsigned char> Load(const std::string& file, std::uint64_t maxBytes) override
  {
    CheckFileName(this->Name, file);
    const zip_int64_t index = zip_name_locate(this->Archive, file.c_str(), 0);
    if (index < 0)
    {
      Fail(this->Name, "the archive has no entry '" + file + "'");
    }
    zip_stat_t st;
    zip_stat_init(&st);
    if (zip_stat_index(this->Archive, static_cast<zip_uint64_t>(index), 0, &st) != 0 ||
      !(st.valid & ZIP_STAT_SIZE) || !(st.valid & ZIP_STAT_COMP_SIZE))
    {
      Fail(this->Name, "cannot read the size of entry '" + file + "'");
    }
    if (st.size > maxBytes)
    {
      Fail(this->Name,
        "entry '" + file + "' claims " + Human(st.size) + ", beyond the limit of " +
          Human(maxBytes));
    }
    CheckExpansion(this->Name, "entry '" + file + "'", st.comp_size, st.size);
    zip_file_t* f = zip_fopen_index(this->Archive, static_cast<zip_uint64_t>(index), 0);
    if (!f)
    {
      Fail(this->Name,
        "cannot open entry '" + file + "': " + zip_error_strerror(zip_get_error(this->Archive)));
    }
    std::vector<unsigned char> bytes(static_cast<std::size_t>(st.size));
    const zip_int64_t got = zip_fread(f, bytes.data(), bytes.size());
    zip_fclose(f);
    if (got < 0 || static_cast<zip_uint64_t>(got) != st.size)
    {
      Fail(this->Name, "entry '" + file + "' is truncated or corrupt");
    }
    return bytes;
  }

private:
  zip_t* Archive = nullptr;
};

class MemoryFiles : public SogFiles
{
public:
  MemoryFiles(const std::map<std::string, std::vector<unsigned char>>& files,
    const std::string& name)
    : Files(files)
  {
    this->Name = name;
  }
  std::vector<unsigned char> Load(const std::string& file, std::uint64_t maxBytes) override
  {
    CheckFileName(this->Name, file);
    const auto it = this->Files.find(file);
    if (it == this->Files.end())
    {
      Fail(this->Name, "has no file '" + file + "'");
    }
    if (it->second.size() > maxBytes)
    {
      Fail(this->Name, "file '" + file + "' exceeds the limit of " + Human(maxBytes));
    }
    return it->second;
  }

private:
  const std::map<std::string, std::vector<unsigned char>>& Files;
};

//------------------------------------------------------------------------------
// meta.json, checked field by field (a missing or mistyped field names itself).
struct Meta
{
  std::uint64_t Count = 0;
  double Mins[3] = {}, Maxs[3] = {};
  std::string MeansFiles[2];
  std::vector<float> ScalesCodebook, Sh0Codebook, ShNCodebook;
  std::string ScalesFile, QuatsFile, Sh0File;
  int ShBands = 0;
  std::uint64_t PaletteCount = 0;
  std::string ShNFiles[2];
};

const nlohmann::json& Field(const std::string& name,
  const nlohmann::json& j,
  const char* key,
  const std::string& where)
{
  if (!j.is_object() || !j.contains(key))
  {
    Fail(name, "meta.json lacks '" + where + key + "'");
  }
  return j[key];
}

std::vector<std::string> Files(const std::string& name,
  const nlohmann::json& j,
  const std::string& where,
  std::size_t count)
{
  const auto& f = Field(name, j, "files", where);
  if (!f.is_array() || f.size() < count)
  {
    Fail(name, "meta.json '" + where + "files' must list " + std::to_string(count) + " file(s)");
  }
  std::vector<std::string> out;
  for (std::size_t i = 0; i < count; ++i)
  {
    if (!f[i].is_string())
    {
      Fail(name, "meta.json '" + where + "files' holds a non-string");
    }
    out.push_back(f[i].get<std::string>());
  }
  return out;
}

std::vector<float> Codebook(const std::string& name,
  const nlohmann::json& j,
  const std::string& where)
{
  const auto& c = Field(name, j, "codebook", where);
  if (!c.is_array() || c.empty() || c.size() > 256)
  {
    Fail(name, "meta.json '" + where + "codebook' must hold 1 to 256 numbers");
  }
  std::vector<float> out;
  for (const auto& v : c)
  {
    if (!v.is_number())
    {
      Fail(name, "meta.json '" + where + "codebook' holds a non-number");
    }
    out.push_back(static_cast<float>(v.get<double>()));
  }
  return out;
}

Meta ParseMeta(const std::string& name, const std::vector<unsigned char>& bytes)
{
  const nlohmann::json j = nlohmann::json::parse(bytes.begin(), bytes.end(), nullptr, false);
  if (j.is_discarded() || !j.is_object())
  {
    Fail(name, "meta.json is not a JSON object");
  }
  if (!j.contains("version"))
  {
    Fail(name, "meta.json has no 'version': a legacy SOG (version 1), which is not supported");
  }
  if (!j["version"].is_number() || j["version"].get<double>() != 2.0)
  {
    Fail(name, "meta.json version " + j["version"].dump() + " is not supported (only 2)");
  }
  Meta m;
  const auto& count = Field(name, j, "count", "");
  if (!count.is_number_integer() || count.get<double>() < 0 ||
    count.get<double>() > static_cast<double>(MaxSogCount))
  {
    Fail(name,
      "meta.json 'count' " + count.dump() + " is not a Gaussian count a SOG can hold (0.." +
        std::to_string(MaxSogCount) + ")");
  }
  m.Count = count.get<std::uint64_t>();
  const auto& means = Field(name, j, "means", "");
  for (const char* key : { "mins", "maxs" })
  {
    const auto& a = Field(name, means, key, "means.");
    if (!a.is_array() || a.size() < 3 || !a[0].is_number() || !a[1].is_number() ||
      !a[2].is_number())
    {
      Fail(name, std::string("meta.json 'means.") + key + "' must hold 3 numbers");
    }
    for (int k = 0; k < 3; ++k)
    {
      (key[1] == 'i' ? m.Mins : m.Maxs)[k] = a[k].get<double>();
    }
  }
  const auto meansFiles = Files(name, means, "means.", 2);
  m.MeansFiles[0] = meansFiles[0];
  m.MeansFiles[1] = meansFiles[1];
  const auto& scales = Field(name, j, "scales", "");
  m.ScalesCodebook = Codebook(name, scales, "scales.");
  m.ScalesFile = Files(name, scales, "scales.", 1)[0];
  m.QuatsFile = Files(name, Field(name, j, "quats", ""), "quats.", 1)[0];
  const auto& sh0 = Field(name, j, "sh0", "");
  m.Sh0Codebook = Codebook(name, sh0, "sh0.");
  m.Sh0File = Files(name, sh0, "sh0.", 1)[0];
  if (j.contains("shN"))
  {
    const auto& shN = j["shN"];
    const auto& bands = Field(name, shN, "bands", "shN.");
    const auto& palette = Field(name, shN, "count", "shN.");
    if (!bands.is_number_integer() || bands.get<int>() < 0 || bands.get<int>() > 3)
    {
      Fail(name, "meta.json 'shN.bands' must be 0..3");
    }
    if (!palette.is_number_integer() || palette.get<double>() < 0 || palette.get<double>() > 65536)
    {
      Fail(name, "meta.json 'shN.count' must be a palette size 0..65536 (labels are 16-bit)");
    }
    m.ShBands = bands.get<int>();
    m.PaletteCount = palette.get<std::uint64_t>();
    if (m.ShBands > 0)
    {
      m.ShNCodebook = Codebook(name, shN, "shN.");
      const auto f = Files(name, shN, "shN.", 2);
      m.ShNFiles[0] = f[0];
      m.ShNFiles[1] = f[1];
    }
  }
  return m;
}

/// A decoded RGBA texture.
struct Texture
{
  int Width = 0, Height = 0;
  std::vector<unsigned char> Rgba;
};

/// Decodes a WebP, refusing before decoding a texture that is too small for @p minPixels or
/// larger than @p maxPixels, or whose expansion is that of a decompression bomb.
Texture DecodeTexture(SogFiles& files,
  const std::string& file,
  std::uint64_t minPixels,
  std::uint64_t maxPixels,
  std::uint64_t maxFileBytes)
{
  const std::vector<unsigned char> bytes = files.Load(file, maxFileBytes);
  const std::string what = "texture '" + file + "'";
  Texture t;
  if (!WebPGetInfo(bytes.data(), bytes.size(), &t.Width, &t.Height))
  {
    Fail(files.Name, what + " is not a WebP image");
  }
  const std::uint64_t pixels = std::uint64_t(t.Width) * std::uint64_t(t.Height);
  if (pixels < minPixels)
  {
    Fail(files.Name,
      what + " is " + std::to_string(t.Width) + "x" + std::to_string(t.Height) +
        ", too small for the " + std::to_string(minPixels) + " texels meta.json implies");
  }
  if (pixels > maxPixels)
  {
    Fail(files.Name,
      what + " is " + std::to_string(t.Width) + "x" + std::to_string(t.Height) +
        ", far larger than the " + std::to_string(minPixels) +
        " texels meta.json implies (at most " + std::to_string(maxPixels) + ")");
  }
  CheckExpansion(files.Name, what, bytes.size(), 4 * pixels);
  t.Rgba.resize(static_cast<std::size_t>(4 * pixels));
  if (!WebPDecodeRGBAInto(bytes.data(), bytes.size(), t.Rgba.data(), t.Rgba.size(), 4 * t.Width))
  {
    Fail(files.Name, what + " could not be decoded (corrupt WebP)");
  }
  return t;
}

/// Texels a texture of @p count Gaussians may hold: the reference writer pads width and height
/// to multiples of 4 (about count + 8 sqrt(count) + 16); anything past twice that is refused.
std::uint64_t MaxTexels(std::uint64_t count)
{
  return 2 * count + 65536;
}

double InvLogTransform(double v)
{
  const double e = std::exp(std::abs(v)) - 1.0;
  return v < 0 ? -e : e;
}

GaussianCloud ReadSogFiles(SogFiles& files,
  const GaussianReadOptions& options,
  GaussianReadReport* reportOut)
{
  const std::string& name = files.Name;
  if (!options.IdProperty.empty())
  {
    Fail(name, "a SOG has no id property '" + options.IdProperty + "'");
  }
  const Meta m = ParseMeta(name, files.Load("meta.json", MaxMetaBytes));
  GaussianReadReport report;
  report.Format = "sog";
  report.FileShDegree = m.ShBands;
  const std::size_t n = static_cast<std::size_t>(m.Count);
  const std::uint64_t maxTexels = MaxTexels(m.Count);
  // A texture file larger than its decoded size plus headers is not a lossless WebP of it.
  const std::uint64_t maxFile = 4 * maxTexels + (std::uint64_t(1) << 20);
  const int degree = options.LoadSH ? std::max(0, std::min(options.MaxShDegree, m.ShBands)) : 0;
  const std::size_t kOut = static_cast<std::size_t>((degree + 1) * (degree + 1));
  const std::size_t kFile = static_cast<std::size_t>((m.ShBands + 1) * (m.ShBands + 1)) - 1;

  GaussianCloud cloud;
  cloud.Count = n;
  cloud.ShDegree = degree;
  std::size_t bad = 0;
  // Allocated on the first non-finite value, which comes after a texture has vouched for count.
  std::vector<unsigned char> rowBad;
  auto store = [&](float& dst, double v, std::size_t g)
  {
    dst = static_cast<float>(v);
    if (!std::isfinite(dst))
    {
      ++bad;
      rowBad.resize(n, 0);
      rowBad[g] = 1;
    }
  };
  if (options.LoadPositions)
  {
    Texture lo = DecodeTexture(files, m.MeansFiles[0], m.Count, maxTexels, maxFile);
    Texture hi = DecodeTexture(files, m.MeansFiles[1], m.Count, maxTexels, maxFile);
    cloud.Positions.resize(3 * n);
    for (std::size_t g = 0; g < n; ++g)
    {
      for (int k = 0; k < 3; ++k)
      {
        const unsigned v = lo.Rgba[4 * g + k] | (hi.Rgba[4 * g + k] << 8);
        const double scale = (m.Maxs[k] - m.Mins[k]) != 0 ? m.Maxs[k] - m.Mins[k] : 1.0;
        store(cloud.Positions[3 * g + k], InvLogTransform(m.Mins[k] + scale * (v / 65535.0)), g);
      }
    }
  }
  if (options.LoadRotations)
  {
    const Texture q = DecodeTexture(files, m.QuatsFile, m.Count, maxTexels, maxFile);
    cloud.Rotations.resize(4 * n);
    static const int order[4][3] = { { 1, 2, 3 }, { 0, 2, 3 }, { 0, 1, 3 }, { 0, 1, 2 } };
    for (std::size_t g = 0; g < n; ++g)
    {
      const unsigned char* t = &q.Rgba[4 * g];
      float* r = &cloud.Rotations[4 * g];
      if (t[3] < 252)
      {
        // Not a smallest-three tag: the reference decodes the identity.
        r[0] = 1.0f;
        r[1] = r[2] = r[3] = 0.0f;
        continue;
      }
      const int largest = t[3] - 252;
      double abc[3];
      for (int i = 0; i < 3; ++i)
      {
        abc[i] = (t[i] / 255.0 * 2.0 - 1.0) / std::sqrt(2.0);
        r[order[largest][i]] = static_cast<float>(abc[i]);
      }
      r[largest] = static_cast<float>(
        std::sqrt(std::max(0.0, 1.0 - (abc[0] * abc[0] + abc[1] * abc[1] + abc[2] * abc[2]))));
    }
  }
  // A codebook index past a short codebook reads as NaN, as in the reference.
  auto code = [](const std::vector<float>& book, unsigned char i)
  { return i < book.size() ? book[i] : std::numeric_limits<float>::quiet_NaN(); };
  if (options.LoadScales)
  {
    const Texture s = DecodeTexture(files, m.ScalesFile, m.Count, maxTexels, maxFile);
    cloud.LogScales.resize(3 * n);
    for (std::size_t g = 0; g < n; ++g)
    {
      for (int k = 0; k < 3; ++k)
      {
        store(cloud.LogScales[3 * g + k], code(m.ScalesCodebook, s.Rgba[4 * g + k]), g);
      }
    }
  }
  if (options.LoadOpacities || options.LoadSH)
  {
    const Texture c = DecodeTexture(files, m.Sh0File, m.Count, maxTexels, maxFile);
    if (options.LoadOpacities)
    {
      cloud.OpacityLogits.resize(n);
      for (std::size_t g = 0; g < n; ++g)
      {
        // The reference clamps alpha to [1e-6, 1 - 1e-6]: logits stay finite (+-13.8).
        const double e = std::min(1.0 - 1e-6, std::max(1e-6, c.Rgba[4 * g + 3] / 255.0));
        cloud.OpacityLogits[g] = static_cast<float>(std::log(e / (1.0 - e)));
      }
    }
    if (options.LoadSH)
    {
      cloud.SH.assign(3 * kOut * n, 0.0f);
      for (std::size_t g = 0; g < n; ++g)
      {
        for (int k = 0; k < 3; ++k)
        {
          store(cloud.SH[3 * kOut * g + k], code(m.Sh0Codebook, c.Rgba[4 * g + k]), g);
        }
      }
    }
  }
  if (options.LoadSH && kOut > 1)
  {
    const std::uint64_t paletteRows = (m.PaletteCount + 63) / 64;
    const Texture centroids = DecodeTexture(files,
      m.ShNFiles[0],
      0,
      std::max<std::uint64_t>(64 * kFile * paletteRows, 64 * kFile) + 65536,
      4 * 64 * kFile * std::max<std::uint64_t>(paletteRows, 1) + (std::uint64_t(1) << 20));
    if (static_cast<std::size_t>(centroids.Width) != 64 * kFile)
    {
      Fail(name,
        "texture '" + m.ShNFiles[0] + "' is " + std::to_string(centroids.Width) +
          " wide; a palette of degree " + std::to_string(m.ShBands) + " needs " +
          std::to_string(64 * kFile));
    }
    const Texture labels = DecodeTexture(files, m.ShNFiles[1], m.Count, maxTexels, maxFile);
    auto shCode = [&](unsigned char i)
    { return i < m.ShNCodebook.size() ? m.ShNCodebook[i] : 0.0f; };
    for (std::size_t g = 0; g < n; ++g)
    {
      const unsigned label = labels.Rgba[4 * g] | (labels.Rgba[4 * g + 1] << 8);
      if (label >= m.PaletteCount)
      {
        continue; // the reference's zeros
      }
      const std::size_t cy = label / 64, cxBase = (label % 64) * kFile;
      float* out = &cloud.SH[3 * kOut * g];
      for (std::size_t j = 0; j + 1 < kOut; ++j)
      {
        const std::size_t cx = cxBase + j;
        const bool inside = cy < static_cast<std::size_t>(centroids.Height);
        const unsigned char* texel = inside
          ? &centroids.Rgba[4 * (cy * static_cast<std::size_t>(centroids.Width) + cx)]
          : nullptr;
        for (int c = 0; c < 3; ++c)
        {
          // Outside the texture the reference reads index 0 of the codebook.
          store(out[3 * (j + 1) + c], shCode(texel ? texel[c] : 0), g);
        }
      }
    }
  }
  report.NonFiniteValues = bad;
  for (unsigned char b : rowBad)
  {
    report.NonFiniteGaussians += b;
  }
  detail::FinishReadReport(report, name, reportOut);
  return cloud;
}

} // namespace

//------------------------------------------------------------------------------
bool IsSog(const std::string& path)
{
  if (detail::IsDirectory(path))
  {
    return detail::IsRegularFile(path + "/meta.json");
  }
  if (!detail::IsRegularFile(path))
  {
    return false;
  }
  detail::InputFile file(path);
  unsigned char head[64] = {};
  const std::size_t got = file.ReadSomeAt(0, head, sizeof(head));
  if (got >= 4 && std::memcmp(head, "PK\x03\x04", 4) == 0)
  {
    return true;
  }
  // A meta.json: a JSON object naming "means".
  std::size_t i = 0;
  while (i < got && std::isspace(head[i]))
  {
    ++i;
  }
  if (i == got || head[i] != '{' || file.Size() > MaxMetaBytes)
  {
    return false;
  }
  const std::vector<unsigned char> text = detail::ReadWholeFile(path);
  static const std::string key = "\"means\"";
  return std::search(text.begin(), text.end(), key.begin(), key.end()) != text.end();
}

//------------------------------------------------------------------------------
GaussianCloud ReadSog(const std::string& path,
  const GaussianReadOptions& options,
  GaussianReadReport* report)
{
  if (detail::IsDirectory(path))
  {
    FolderFiles files(path);
    return ReadSogFiles(files, options, report);
  }
  detail::InputFile file(path);
  unsigned char head[4] = {};
  if (file.ReadSomeAt(0, head, 4) == 4 && std::memcmp(head, "PK\x03\x04", 4) == 0)
  {
    ZipFiles files(path, nullptr, 0);
    return ReadSogFiles(files, options, report);
  }
  // A meta.json (any name) with its textures beside it.
  const std::string folder = detail::ParentFolder(path);
  struct MetaFiles : FolderFiles
  {
    MetaFiles(const std::string& f, std::string meta)
      : FolderFiles(f)
      , MetaPath(std::move(meta))
    {
      this->Name = this->MetaPath;
    }
    std::vector<unsigned char> Load(const std::string& file, std::uint64_t maxBytes) override
    {
      if (file == "meta.json")
      {
        detail::InputFile in(this->MetaPath);
        if (in.Size() > maxBytes)
        {
          Fail(this->MetaPath, "meta.json of " + Human(in.Size()) + " exceeds " + Human(maxBytes));
        }
        return detail::ReadWholeFile(this->MetaPath);
      }
      return FolderFiles::Load(file, maxBytes);
    }
    std::string MetaPath;
  };
  MetaFiles files(folder, path);
  return ReadSogFiles(files, options, report);
}

//------------------------------------------------------------------------------
GaussianCloud ReadSogZipFromMemory(const void* data,
  std::size_t size,
  const std::string& name,
  const GaussianReadOptions& options,
  GaussianReadReport* report)
{
  static const unsigned char empty = 0;
  ZipFiles files(name, data ? data : &empty, data ? size : 0);
  return ReadSogFiles(files, options, report);
}

//------------------------------------------------------------------------------
GaussianCloud ReadSogFromMemoryFiles(const std::map<std::string, std::vector<unsigned char>>& files,
  const std::string& name,
  const GaussianReadOptions& options,
  GaussianReadReport* report)
{
  MemoryFiles source(files, name);
  return ReadSogFiles(source, options, report);
}

} // namespace vis4gs

// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSScoreOutputs.h"

#include "GaussianMath.h"
#include "ImageIO.h"
#include "MultiViewRenderer.h"
#include "ScoreRegistry.h"
#include "SplatAttributes.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace
{
// Rows per block: each thread formats whole blocks into its own buffer (about 1 MB at 7
// columns); blocks are written in order.
constexpr std::size_t RowsPerBlock = 16384;

void Append(std::string& out, double value)
{
  char buf[40];
  const auto r = std::to_chars(buf, buf + sizeof buf, value, std::chars_format::general, 9);
  out.append(buf, r.ptr);
}

template <typename Int>
void AppendInt(std::string& out, Int value)
{
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof buf, value);
  out.append(buf, r.ptr);
}
}

//------------------------------------------------------------------------------
void Vis4GSWriteScoresCsv(const std::filesystem::path& path,
  const std::string& shownPath,
  const vis4gs::GaussianCloud& cloud,
  const std::vector<std::pair<std::string, std::vector<double>>>& scores,
  const std::vector<unsigned char>* flags)
{
  std::ofstream csv(path, std::ios::binary);
  std::string header = "GaussianId";
  for (const auto& s : scores)
  {
    header += "," + s.first;
  }
  header += flags ? ",NoVisibleView\n" : "\n";
  csv << header;
  const std::size_t n = cloud.Count;
  const std::int64_t blocks = static_cast<std::int64_t>((n + RowsPerBlock - 1) / RowsPerBlock);
  bool ok = static_cast<bool>(csv);
#pragma omp parallel for ordered schedule(static, 1)
  for (std::int64_t b = 0; b < blocks; ++b)
  {
    std::string text;
    const std::size_t first = static_cast<std::size_t>(b) * RowsPerBlock;
    const std::size_t last = std::min(n, first + RowsPerBlock);
    text.reserve((last - first) * (12 + 16 * scores.size()));
    for (std::size_t i = first; i < last; ++i)
    {
      AppendInt(text, cloud.GetId(i));
      for (const auto& s : scores)
      {
        text.push_back(',');
        Append(text, s.second[i]);
      }
      if (flags)
      {
        text.push_back(',');
        AppendInt(text, static_cast<int>((*flags)[i]));
      }
      text.push_back('\n');
    }
#pragma omp ordered
    {
      if (ok)
      {
        ok = static_cast<bool>(csv.write(text.data(), static_cast<std::streamsize>(text.size())));
      }
    }
  }
  csv.flush();
  if (!ok || !csv)
  {
    const int error = errno;
    throw std::runtime_error(shownPath + ": could not be written (" + std::strerror(error) + ")");
  }
}

//------------------------------------------------------------------------------
double Vis4GSOverlayUpperEnd(const std::vector<double>& values, bool unitRange)
{
  if (unitRange)
  {
    return 1.0;
  }
  std::vector<double> finite;
  finite.reserve(values.size());
  for (double v : values)
  {
    if (std::isfinite(v))
    {
      finite.push_back(v);
    }
  }
  if (finite.empty())
  {
    return 1.0;
  }
  // The element a full sort would put there, without sorting 6M values.
  const auto at = finite.begin() + static_cast<std::ptrdiff_t>(0.99 * (finite.size() - 1));
  std::nth_element(finite.begin(), at, finite.end());
  return std::max(1e-30, *at);
}

//------------------------------------------------------------------------------
void Vis4GSRenderOverlays(const vis4gs::GaussianCloud& cloud,
  const std::vector<vis4gs::Camera>& cameras,
  const std::vector<Vis4GSOverlayScore>& scores,
  int views,
  const std::function<void(std::size_t score, std::size_t camera, const vis4gs::Image& image)>&
    write)
{
  if (scores.empty() || views <= 0)
  {
    return;
  }
  // Colours only through SetColors: the SH (80 % of the cloud at degree 3) are never read.
  vis4gs::RasterSettings settings;
  settings.ComputeColors = false;
  vis4gs::MultiViewRenderer renderer(cloud, settings);
  std::vector<float> rgb(3 * cloud.Count);
  vis4gs::RasterImage<float> render;
  vis4gs::Image image;
  int done = 0;
  for (std::size_t v = 0; v < cameras.size() && done < views; ++v)
  {
    if (cameras[v].Split != vis4gs::CameraSplit::Train)
    {
      continue;
    }
    renderer.Project(cameras[v]);
    for (std::size_t k = 0; k < scores.size(); ++k)
    {
      const std::vector<double>& values = *scores[k].Values;
      const vis4gs::SuspiciousEnd end = vis4gs::SuspiciousEndOf(scores[k].Name);
      const double upper = scores[k].Upper;
      const std::int64_t n = static_cast<std::int64_t>(cloud.Count);
#pragma omp parallel for schedule(static)
      for (std::int64_t i = 0; i < n; ++i)
      {
        // The colour a cloud of SH degree 0 holding the overlay colour gives (what the
        // overlays were drawn from before): the float DC coefficient, then the rasteriser's
        // activation and clamp, bit for bit.
        const auto c = vis4gs::OverlayColor(values[i], 0.0, upper, end);
        float sh[3];
        for (int ch = 0; ch < 3; ++ch)
        {
          sh[ch] = static_cast<float>((c[ch] - 0.5) / vis4gs::sh::C0);
        }
        const float dir[3] = { 0, 0, 0 };
        float col[3];
        vis4gs::ShColor<float>(sh, 0, dir, col);
        for (int ch = 0; ch < 3; ++ch)
        {
          rgb[3 * i + ch] = std::max(col[ch], 0.0f);
        }
      }
      renderer.SetColors(rgb.data());
      renderer.Composite(render);
      image.Width = render.Width;
      image.Height = render.Height;
      image.Channels = 3;
      image.Pixels = render.Color;
      write(k, v, image);
    }
    ++done;
  }
}

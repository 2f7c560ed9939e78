// SPDX-License-Identifier: BSD-3-Clause
#include "SplatAttributes.h"

#include "GaussianMath.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vis4gs
{
namespace
{
int ThreadCount(int requested)
{
  return requested > 0 ? requested : std::max(1, omp_get_max_threads());
}

void CheckArray(const char* name, std::size_t size, std::size_t n, std::size_t per)
{
  if (size != n * per)
  {
    throw std::invalid_argument(std::string("Gaussian cloud: ") + name + " holds " +
      std::to_string(size) + " values, expected " + std::to_string(n * per) + " for " +
      std::to_string(n) + " Gaussians");
  }
}

bool AllFinite(const float* v, int n)
{
  for (int i = 0; i < n; ++i)
  {
    if (!std::isfinite(v[i]))
    {
      return false;
    }
  }
  return true;
}

// SH basis (reference §2.4) in float, the rasteriser's evaluation order.
void ShColor(const float* sh, int degree, const float d[3], float out[3])
{
  const float C0 = static_cast<float>(sh::C0), C1 = static_cast<float>(sh::C1);
  for (int c = 0; c < 3; ++c)
  {
    out[c] = C0 * sh[c];
  }
  if (degree > 0)
  {
    const float x = d[0], y = d[1], z = d[2];
    for (int c = 0; c < 3; ++c)
    {
      out[c] = out[c] - C1 * y * sh[3 + c] + C1 * z * sh[6 + c] - C1 * x * sh[9 + c];
    }
    if (degree > 1)
    {
      const float xx = x * x, yy = y * y, zz = z * z, xy = x * y, yz = y * z, xz = x * z;
      const float b[5] = { static_cast<float>(sh::C2[0]) * xy,
        static_cast<float>(sh::C2[1]) * yz,
        static_cast<float>(sh::C2[2]) * (2.0f * zz - xx - yy),
        static_cast<float>(sh::C2[3]) * xz,
        static_cast<float>(sh::C2[4]) * (xx - yy) };
      for (int c = 0; c < 3; ++c)
      {
        out[c] = out[c] + b[0] * sh[12 + c] + b[1] * sh[15 + c] + b[2] * sh[18 + c] +
          b[3] * sh[21 + c] + b[4] * sh[24 + c];
      }
      if (degree > 2)
      {
        const float e[7] = { static_cast<float>(sh::C3[0]) * y * (3.0f * xx - yy),
          static_cast<float>(sh::C3[1]) * xy * z,
          static_cast<float>(sh::C3[2]) * y * (4.0f * zz - xx - yy),
          static_cast<float>(sh::C3[3]) * z * (2.0f * zz - 3.0f * xx - 3.0f * yy),
          static_cast<float>(sh::C3[4]) * x * (4.0f * zz - xx - yy),
          static_cast<float>(sh::C3[5]) * z * (xx - yy),
          static_cast<float>(sh::C3[6]) * x * (xx - 3.0f * yy) };
        for (int c = 0; c < 3; ++c)
        {
          out[c] = out[c] + e[0] * sh[27 + c] + e[1] * sh[30 + c] + e[2] * sh[33 + c] +
            e[3] * sh[36 + c] + e[4] * sh[39 + c] + e[5] * sh[42 + c] + e[6] * sh[45 + c];
        }
      }
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    out[c] = out[c] + 0.5f;
    out[c] = out[c] < 0.0f ? 0.0f : out[c];
  }
}

// 17 samples (indices 0, 16, ..., 240, 255) of matplotlib's 256-entry viridis table (CC0).
constexpr int ViridisSamples = 17;
constexpr float ViridisIndex[ViridisSamples] = { 0,
  16,
  32,
  48,
  64,
  80,
  96,
  112,
  128,
  144,
  160,
  176,
  192,
  208,
  224,
  240,
  255 };
constexpr float ViridisTable[ViridisSamples][3] = { { 0.267004f, 0.004874f, 0.329415f },
  { 0.282327f, 0.094955f, 0.417331f },
  { 0.278826f, 0.175490f, 0.483397f },
  { 0.258965f, 0.251537f, 0.524736f },
  { 0.229739f, 0.322361f, 0.545706f },
  { 0.199430f, 0.387607f, 0.554642f },
  { 0.172719f, 0.448791f, 0.557885f },
  { 0.149039f, 0.508051f, 0.557250f },
  { 0.127568f, 0.566949f, 0.550556f },
  { 0.120638f, 0.625828f, 0.533488f },
  { 0.157851f, 0.683765f, 0.501686f },
  { 0.246070f, 0.738910f, 0.452024f },
  { 0.369214f, 0.788888f, 0.382914f },
  { 0.515992f, 0.831158f, 0.294279f },
  { 0.678489f, 0.863742f, 0.189503f },
  { 0.845561f, 0.887322f, 0.099702f },
  { 0.993248f, 0.906157f, 0.143936f } };
} // namespace

//------------------------------------------------------------------------------
void PackSplatGeometry(const GaussianCloud& cloud,
  double scaleModifier,
  std::vector<float>& packed,
  int threads)
{
  const std::size_t n = cloud.Count;
  CheckArray("Positions", cloud.Positions.size(), n, 3);
  CheckArray("LogScales", cloud.LogScales.size(), n, 3);
  CheckArray("Rotations", cloud.Rotations.size(), n, 4);
  CheckArray("OpacityLogits", cloud.OpacityLogits.size(), n, 1);
  packed.assign(n * SplatGeometryFloats, 0.0f);
  const float mod = static_cast<float>(scaleModifier);
  const std::int64_t count = static_cast<std::int64_t>(n);
#pragma omp parallel for num_threads(ThreadCount(threads)) schedule(static)
  for (std::int64_t ii = 0; ii < count; ++ii)
  {
    const std::size_t i = static_cast<std::size_t>(ii);
    const float* pos = &cloud.Positions[3 * i];
    const float* ls = &cloud.LogScales[3 * i];
    const float* rot = &cloud.Rotations[4 * i];
    const float logit = cloud.OpacityLogits[i];
    float* out = &packed[i * SplatGeometryFloats];
    if (ClassifyGaussian(pos, ls, rot, logit) != GaussianClass::Drawn)
    {
      continue; // valid = 0
    }
    const float s[3] = { mod * std::exp(ls[0]), mod * std::exp(ls[1]), mod * std::exp(ls[2]) };
    const auto R = QuaternionToMatrix<float>(NormalizeQuaternion<float>(rot));
    float M[3][3]; // M[k][r] = s_k R_rk
    for (int k = 0; k < 3; ++k)
    {
      for (int r = 0; r < 3; ++r)
      {
        M[k][r] = s[k] * R[3 * r + k];
      }
    }
    float Sig[3][3];
    for (int r = 0; r < 3; ++r)
    {
      for (int c = r; c < 3; ++c)
      {
        Sig[r][c] = M[0][r] * M[0][c] + M[1][r] * M[1][c] + M[2][r] * M[2][c];
      }
    }
    out[0] = pos[0];
    out[1] = pos[1];
    out[2] = pos[2];
    out[3] = Sigmoid(logit);
    out[4] = Sig[0][0];
    out[5] = Sig[0][1];
    out[6] = Sig[0][2];
    out[7] = Sig[1][1];
    out[8] = Sig[1][2];
    out[9] = Sig[2][2];
    out[10] = AllFinite(out + 4, 6) ? 1.0f : 0.0f;
  }
}

//------------------------------------------------------------------------------
void EvaluateSplatColors(const GaussianCloud& cloud,
  const std::array<double, 3>& cameraCenter,
  int shDegree,
  std::vector<float>& rgb,
  int threads)
{
  const std::size_t n = cloud.Count;
  if (cloud.ShDegree < 0 || cloud.ShDegree > 3)
  {
    throw std::invalid_argument(
      "Gaussian cloud: SH degree " + std::to_string(cloud.ShDegree) + " is not in 0..3");
  }
  CheckArray("Positions", cloud.Positions.size(), n, 3);
  const std::size_t stride = 3 * static_cast<std::size_t>(cloud.ShCoefficientCount());
  CheckArray("SH", cloud.SH.size(), n, stride);
  const int degree = shDegree < 0 ? cloud.ShDegree : std::min(shDegree, cloud.ShDegree);
  rgb.resize(3 * n);
  const float cx = static_cast<float>(cameraCenter[0]);
  const float cy = static_cast<float>(cameraCenter[1]);
  const float cz = static_cast<float>(cameraCenter[2]);
  const std::int64_t count = static_cast<std::int64_t>(n);
#pragma omp parallel for num_threads(ThreadCount(threads)) schedule(static)
  for (std::int64_t ii = 0; ii < count; ++ii)
  {
    const std::size_t i = static_cast<std::size_t>(ii);
    const float* p = &cloud.Positions[3 * i];
    float d[3] = { p[0] - cx, p[1] - cy, p[2] - cz };
    const float len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (auto& v : d)
    {
      v = len > 0.0f ? v / len : 0.0f;
    }
    ShColor(&cloud.SH[i * stride], degree, d, &rgb[3 * i]);
  }
}

//------------------------------------------------------------------------------
std::array<float, 3> Viridis(double t)
{
  if (!(t > 0.0)) // also NaN
  {
    t = 0.0;
  }
  t = std::min(t, 1.0);
  const double x = t * 255.0;
  int k = 0;
  while (k < ViridisSamples - 2 && x > ViridisIndex[k + 1])
  {
    ++k;
  }
  const double f = (x - ViridisIndex[k]) / (ViridisIndex[k + 1] - ViridisIndex[k]);
  std::array<float, 3> c{};
  for (int ch = 0; ch < 3; ++ch)
  {
    c[ch] =
      static_cast<float>(ViridisTable[k][ch] + f * (ViridisTable[k + 1][ch] - ViridisTable[k][ch]));
  }
  return c;
}

//------------------------------------------------------------------------------
SuspiciousEnd SuspiciousEndOf(const std::string& arrayName)
{
  if (arrayName == "ViewCoverage")
  {
    return SuspiciousEnd::Low;
  }
  if (arrayName == "BlurScore" || arrayName == "NeedleScore" || arrayName == "NeedleShape")
  {
    return SuspiciousEnd::High;
  }
  return SuspiciousEnd::None;
}

//------------------------------------------------------------------------------
std::array<float, 3> OverlayColor(double value, double lo, double hi, SuspiciousEnd end)
{
  const double span = hi - lo;
  // A zero or negative span maps everything at or above lo to the hi end.
  double t = span > 0 ? (value - lo) / span : (value >= lo ? 1.0 : 0.0);
  if (!(t > 0.0)) // also NaN
  {
    t = 0.0;
  }
  t = std::min(t, 1.0);
  return Viridis(end == SuspiciousEnd::Low ? 1.0 - t : t);
}

//------------------------------------------------------------------------------
void ComputeSplatDisplay(const float* trueColors,
  std::size_t count,
  const SplatDisplayOptions& options,
  std::vector<float>& rgba,
  std::vector<std::uint8_t>& keep,
  int threads)
{
  if ((options.ScoreColoring || options.HideOutsideRange) && options.Scores == nullptr)
  {
    throw std::invalid_argument("ComputeSplatDisplay: score colouring or hiding needs scores");
  }
  if (!options.ScoreColoring && trueColors == nullptr && count > 0)
  {
    throw std::invalid_argument("ComputeSplatDisplay: true colouring needs colours");
  }
  rgba.resize(4 * count);
  keep.resize(count);
  const double lo = options.ColorRange[0], hi = options.ColorRange[1];
  const std::int64_t n = static_cast<std::int64_t>(count);
#pragma omp parallel for num_threads(ThreadCount(threads)) schedule(static)
  for (std::int64_t ii = 0; ii < n; ++ii)
  {
    const std::size_t i = static_cast<std::size_t>(ii);
    float* out = &rgba[4 * i];
    std::uint8_t k = 1;
    if (options.HideOutsideRange)
    {
      const double s = options.Scores[i];
      k = (s >= options.VisibleRange[0] && s <= options.VisibleRange[1]) ? 1 : 0; // NaN hidden
    }
    keep[i] = k;
    float c[3];
    if (options.ScoreColoring)
    {
      const double s = options.Scores[i];
      if (std::isnan(s))
      {
        c[0] = options.NanColor[0];
        c[1] = options.NanColor[1];
        c[2] = options.NanColor[2];
      }
      else
      {
        const auto v = OverlayColor(s, lo, hi, options.Suspicious);
        c[0] = v[0];
        c[1] = v[1];
        c[2] = v[2];
      }
    }
    else
    {
      c[0] = trueColors[3 * i];
      c[1] = trueColors[3 * i + 1];
      c[2] = trueColors[3 * i + 2];
    }
    float opacityScale = 1.0f;
    const bool selected = options.Selected != nullptr && options.Selected[i] != 0;
    if (selected && options.Highlight)
    {
      for (int ch = 0; ch < 3; ++ch)
      {
        c[ch] = c[ch] + options.HighlightMix * (options.HighlightColor[ch] - c[ch]);
      }
    }
    else if (!selected && options.DimUnselected)
    {
      const float grey = 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
      for (int ch = 0; ch < 3; ++ch)
      {
        c[ch] = c[ch] + options.DimDesaturation * (grey - c[ch]);
      }
      opacityScale = options.DimOpacity;
    }
    out[0] = c[0];
    out[1] = c[1];
    out[2] = c[2];
    out[3] = opacityScale;
  }
}

} // namespace vis4gs

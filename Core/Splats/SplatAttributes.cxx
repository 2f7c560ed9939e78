// SPDX-License-Identifier: BSD-3-Clause
#include "SplatAttributes.h"

#include "GaussianMath.h"
#include "ThreadCount.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vis4gs
{
namespace
{
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
    const std::array<float, 6> sigma = GaussianCovariance<float>(ls, rot, mod);
    out[0] = pos[0];
    out[1] = pos[1];
    out[2] = pos[2];
    out[3] = Sigmoid(logit);
    std::copy(sigma.begin(), sigma.end(), out + 4);
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
  const float center[3] = { static_cast<float>(cameraCenter[0]),
    static_cast<float>(cameraCenter[1]),
    static_cast<float>(cameraCenter[2]) };
  const std::int64_t count = static_cast<std::int64_t>(n);
#pragma omp parallel for num_threads(ThreadCount(threads)) schedule(static)
  for (std::int64_t ii = 0; ii < count; ++ii)
  {
    const std::size_t i = static_cast<std::size_t>(ii);
    ViewColor<float>(&cloud.SH[i * stride], degree, &cloud.Positions[3 * i], center, &rgb[3 * i]);
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
  const bool defer = options.DeferTrueColor && !options.ScoreColoring;
  if (!options.ScoreColoring && !defer && trueColors == nullptr && count > 0)
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
    else if (defer)
    {
      c[0] = c[1] = c[2] = 0.0f;
    }
    else
    {
      c[0] = trueColors[3 * i];
      c[1] = trueColors[3 * i + 1];
      c[2] = trueColors[3 * i + 2];
    }
    float opacityScale = 1.0f;
    float change = SplatDisplayUnchanged;
    const bool selected = options.Selected != nullptr && options.Selected[i] != 0;
    if (selected && options.Highlight)
    {
      change = SplatDisplayHighlighted;
      for (int ch = 0; ch < 3; ++ch)
      {
        c[ch] = c[ch] + options.HighlightMix * (options.HighlightColor[ch] - c[ch]);
      }
    }
    else if (!selected && options.DimUnselected)
    {
      change = SplatDisplayDimmed;
      const float grey = 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
      for (int ch = 0; ch < 3; ++ch)
      {
        c[ch] = c[ch] + options.DimDesaturation * (grey - c[ch]);
      }
      opacityScale = options.DimOpacity;
    }
    out[0] = defer ? change : c[0];
    out[1] = defer ? 0.0f : c[1];
    out[2] = defer ? 0.0f : c[2];
    out[3] = opacityScale;
  }
}

} // namespace vis4gs

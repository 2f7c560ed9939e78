// SPDX-License-Identifier: BSD-3-Clause
// The antimatter15 `.splat` format: 32 bytes per Gaussian, little endian,
//   float32 x y z | float32 sx sy sz (linear scales) | uint8 r g b a | uint8 qw qx qy qz
// with q = (byte - 128) / 128 and colours/alpha in 0..255.
#include "GaussianIO.h"
#include "GaussianMath.h"
#include "SceneFile.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace vis4gs
{

namespace
{

constexpr std::size_t SplatRowSize = 32;
constexpr double AlphaClamp = 1e-4;

//------------------------------------------------------------------------------
GaussianCloud ReadSplatSource(const detail::ByteSource& src,
  const GaussianReadOptions& options,
  GaussianReadReport* reportOut)
{
  if (src.Size % SplatRowSize != 0)
  {
    throw std::runtime_error(src.Name + ": size " + std::to_string(src.Size) +
      " bytes is not a multiple of 32, so this is not an antimatter15 .splat file (truncated?)");
  }
  const std::size_t n = static_cast<std::size_t>(src.Size / SplatRowSize);
  GaussianReadReport report;
  report.Format = "splat";
  report.FileShDegree = 0;
  GaussianCloud cloud = detail::AllocateReadArrays(n, 0, options);
  if (!options.IdProperty.empty())
  {
    throw std::runtime_error(
      src.Name + ": a .splat file has no id property '" + options.IdProperty + "'");
  }
  // Lookup tables for the 8-bit fields (exact, computed in double once).
  float dc[256], logit[256], quat[256];
  for (int i = 0; i < 256; ++i)
  {
    dc[i] = static_cast<float>((i / 255.0 - 0.5) / sh::C0);
    const double a = std::min(std::max(i / 255.0, AlphaClamp), 1.0 - AlphaClamp);
    logit[i] = static_cast<float>(Logit(a));
    quat[i] = static_cast<float>((i - 128) / 128.0);
  }
  std::atomic<std::size_t> badValues{ 0 }, badRows{ 0 };
  detail::ForEachRowBlock(src,
    0,
    SplatRowSize,
    n,
    [&](const unsigned char* rows, std::size_t first, std::size_t count)
    {
      std::size_t localValues = 0, localRows = 0;
      for (std::size_t r = 0; r < count; ++r)
      {
        const unsigned char* row = rows + r * SplatRowSize;
        const std::size_t g = first + r;
        std::size_t rowBad = 0;
        if (options.LoadPositions)
        {
          for (int c = 0; c < 3; ++c)
          {
            const float v = detail::LoadLEFloat(row + 4 * c);
            cloud.Positions[3 * g + c] = v;
            rowBad += !std::isfinite(v);
          }
        }
        if (options.LoadScales)
        {
          for (int c = 0; c < 3; ++c)
          {
            // log(0) = -inf and log(negative) = NaN are kept and reported like NaN in a PLY.
            const float v = std::log(detail::LoadLEFloat(row + 12 + 4 * c));
            cloud.LogScales[3 * g + c] = v;
            rowBad += !std::isfinite(v);
          }
        }
        if (options.LoadSH)
        {
          for (int c = 0; c < 3; ++c)
          {
            cloud.SH[3 * g + c] = dc[row[24 + c]];
          }
        }
        if (options.LoadOpacities)
        {
          cloud.OpacityLogits[g] = logit[row[27]];
        }
        if (options.LoadRotations)
        {
          for (int c = 0; c < 4; ++c)
          {
            cloud.Rotations[4 * g + c] = quat[row[28 + c]];
          }
        }
        localValues += rowBad;
        localRows += rowBad != 0;
      }
      badValues += localValues;
      badRows += localRows;
    });
  report.NonFiniteValues = badValues;
  report.NonFiniteGaussians = badRows;
  detail::FinishReadReport(report, src.Name, reportOut);
  return cloud;
}

} // namespace

//------------------------------------------------------------------------------
GaussianCloud ReadSplat(const std::string& path,
  const GaussianReadOptions& options,
  GaussianReadReport* report)
{
  return detail::ParseFileSource(ReadSplatSource, path, options, report);
}

//------------------------------------------------------------------------------
GaussianCloud ReadSplatFromMemory(const void* data,
  std::size_t size,
  const std::string& name,
  const GaussianReadOptions& options,
  GaussianReadReport* report)
{
  return ReadSplatSource(detail::MemorySource(data, size, name), options, report);
}

//------------------------------------------------------------------------------
std::size_t WriteSplat(const std::string& path, const GaussianCloud& cloud)
{
  const std::size_t k = static_cast<std::size_t>(cloud.ShCoefficientCount());
  if (cloud.Positions.size() != 3 * cloud.Count || cloud.LogScales.size() != 3 * cloud.Count ||
    cloud.Rotations.size() != 4 * cloud.Count || cloud.OpacityLogits.size() != cloud.Count ||
    cloud.SH.size() != 3 * k * cloud.Count)
  {
    throw std::invalid_argument("WriteSplat: the cloud must hold every parameter array");
  }
  // Bytes cannot hold what the reference has no answer for (NaN, infinite positions, ...):
  // such Gaussians are left out and counted rather than written as some other Gaussian.
  // What the reference draws keeps its meaning: opacity logit +-inf -> 255 / 0, log-scale
  // -inf -> scale 0, a zero quaternion -> bytes 128 (read back as the zero quaternion).
  std::vector<std::size_t> kept;
  kept.reserve(cloud.Count);
  for (std::size_t g = 0; g < cloud.Count; ++g)
  {
    if (detail::WritableGaussian(cloud, g, 1))
    {
      kept.push_back(g);
    }
  }
  const std::size_t n = kept.size();
  auto toByte = [](double v)
  { return static_cast<unsigned char>(std::min(255.0, std::max(0.0, std::nearbyint(v)))); };
  detail::WriteFileAtomically(path,
    [&](std::FILE* f)
    {
      std::vector<unsigned char> buffer;
      const std::size_t chunk = 1 << 16;
      for (std::size_t first = 0; first < n; first += chunk)
      {
        const std::size_t count = std::min(chunk, n - first);
        buffer.assign(count * SplatRowSize, 0);
        for (std::size_t r = 0; r < count; ++r)
        {
          const std::size_t g = kept[first + r];
          unsigned char* row = buffer.data() + r * SplatRowSize;
          float v[6];
          for (int c = 0; c < 3; ++c)
          {
            v[c] = cloud.Positions[3 * g + c];
            v[3 + c] = std::exp(cloud.LogScales[3 * g + c]);
          }
          for (int c = 0; c < 6; ++c)
          {
            std::uint32_t bits;
            std::memcpy(&bits, &v[c], 4);
            if (!detail::HostIsLittleEndian())
            {
              bits = detail::ByteSwap32(bits);
            }
            std::memcpy(row + 4 * c, &bits, 4);
          }
          for (int c = 0; c < 3; ++c)
          {
            row[24 + c] = toByte((0.5 + sh::C0 * cloud.SH[3 * k * g + c]) * 255.0);
          }
          row[27] = toByte(Sigmoid(static_cast<double>(cloud.OpacityLogits[g])) * 255.0);
          const auto q = NormalizeQuaternion(&cloud.Rotations[4 * g]);
          for (int c = 0; c < 4; ++c)
          {
            row[28 + c] = toByte(q[c] * 128.0 + 128.0);
          }
        }
        detail::WriteBytes(f, buffer.data(), buffer.size(), path);
      }
    });
  return cloud.Count - n;
}

} // namespace vis4gs

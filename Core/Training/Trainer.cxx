// SPDX-License-Identifier: BSD-3-Clause
#include "Trainer.h"

#include "GaussianMath.h"
#include "Loss.h"
#include "RasterBackward.h"
#include "Rasterizer.h"
#include "ThreadCount.h"
#include "TrainingLogWriter.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace vis4gs
{
namespace
{

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double>(b - a).count();
}

int ScaledCount(int value, double factor, int minimum)
{
  return std::max(minimum, static_cast<int>(std::lround(value * factor)));
}

// torch.max(exp(log_scale)) of a row, in float as the reference.
float MaxScale(const float* ls)
{
  return std::max(std::exp(ls[0]), std::max(std::exp(ls[1]), std::exp(ls[2])));
}

template <typename V>
void AppendCopies(V& array, std::size_t width, const std::vector<std::size_t>& sources)
{
  const std::size_t n = array.size() / width;
  array.resize((n + sources.size()) * width);
  for (std::size_t r = 0; r < sources.size(); ++r)
  {
    std::copy_n(array.begin() + sources[r] * width, width, array.begin() + (n + r) * width);
  }
}

template <typename V>
void Compact(V& array, std::size_t width, const std::vector<char>& keep)
{
  std::size_t w = 0;
  for (std::size_t i = 0; i < keep.size(); ++i)
  {
    if (keep[i])
    {
      if (w != i)
      {
        std::copy_n(array.begin() + i * width, width, array.begin() + w * width);
      }
      ++w;
    }
  }
  array.resize(w * width);
}

// The Gaussians a fine-tune starts from: ids made explicit, SH cut or zero-padded to @p degree,
// extras dropped. Throws for an empty or inconsistent cloud.
GaussianCloud StartCloud(const GaussianCloud& start, int degree)
{
  const std::size_t n = start.Count;
  const std::size_t kIn = 3 * static_cast<std::size_t>(start.ShCoefficientCount());
  if (n == 0 || start.Positions.size() != 3 * n || start.LogScales.size() != 3 * n ||
    start.Rotations.size() != 4 * n || start.OpacityLogits.size() != n ||
    start.SH.size() != kIn * n || (!start.Ids.empty() && start.Ids.size() != n))
  {
    throw std::invalid_argument("trainer: the start cloud is empty or its arrays do not hold " +
      std::to_string(n) + " Gaussians");
  }
  GaussianCloud c = start;
  c.Extra.clear();
  c.Ids.resize(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    c.Ids[i] = start.GetId(i);
  }
  std::vector<std::int64_t> sorted = c.Ids;
  std::sort(sorted.begin(), sorted.end());
  if (sorted.front() < 0 || std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
  {
    throw std::invalid_argument("trainer: the start cloud's ids must be distinct and >= 0");
  }
  c.ShDegree = degree;
  const std::size_t kOut = 3 * static_cast<std::size_t>(c.ShCoefficientCount());
  c.SH.assign(kOut * n, 0.0f);
  for (std::size_t i = 0; i < n; ++i)
  {
    std::copy_n(start.SH.begin() + static_cast<std::ptrdiff_t>(i * kIn),
      std::min(kIn, kOut),
      c.SH.begin() + static_cast<std::ptrdiff_t>(i * kOut));
  }
  return c;
}
} // namespace

//------------------------------------------------------------------------------
void TrainerOptions::ScaleSchedule(int iterations)
{
  if (iterations <= 0)
  {
    throw std::invalid_argument(
      "ScaleSchedule: iterations must be positive, got " + std::to_string(iterations));
  }
  const double f = iterations / 30000.0;
  this->Iterations = iterations;
  this->PositionLrMaxSteps = ScaledCount(30000, f, 1);
  this->DensifyFromIter = ScaledCount(500, f, 0);
  this->DensifyUntilIter = ScaledCount(15000, f, 0);
  this->DensificationInterval = ScaledCount(100, f, 1);
  this->OpacityResetInterval = ScaledCount(3000, f, 1);
  this->ShIncreaseInterval = ScaledCount(1000, f, 1);
}

//------------------------------------------------------------------------------
std::vector<float> Trainer::MeanSquaredDistance3NN(const std::vector<float>& positions)
{
  const std::size_t n = positions.size() / 3;
  std::vector<float> out(n, 0.0f);
  if (n < 2)
  {
    return out;
  }
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k)
  {
    lo[k] = std::numeric_limits<double>::infinity();
    hi[k] = -lo[k];
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      lo[k] = std::min(lo[k], static_cast<double>(positions[3 * i + k]));
      hi[k] = std::max(hi[k], static_cast<double>(positions[3 * i + k]));
    }
  }
  for (int k = 0; k < 3; ++k)
  {
    if (!std::isfinite(lo[k]) || !std::isfinite(hi[k]))
    {
      throw std::invalid_argument("initial points: non-finite coordinates");
    }
  }
  const double ext = std::max({ hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-12 });
  // About 2 points per cell along the largest extent's grid, at most 2^20 cells per axis.
  double h = ext / std::max(1.0, std::cbrt(static_cast<double>(n) / 2.0));
  std::int64_t dims[3];
  for (int k = 0; k < 3; ++k)
  {
    dims[k] = std::min<std::int64_t>(1 << 20, static_cast<std::int64_t>((hi[k] - lo[k]) / h) + 1);
  }
  auto cellOf = [&](const float* p, std::int64_t c[3])
  {
    for (int k = 0; k < 3; ++k)
    {
      c[k] = std::min(
        dims[k] - 1, std::max<std::int64_t>(0, static_cast<std::int64_t>((p[k] - lo[k]) / h)));
    }
  };
  auto key = [&](std::int64_t x, std::int64_t y, std::int64_t z)
  {
    return (static_cast<std::uint64_t>(x) * static_cast<std::uint64_t>(dims[1]) +
             static_cast<std::uint64_t>(y)) *
      static_cast<std::uint64_t>(dims[2]) +
      static_cast<std::uint64_t>(z);
  };
  std::vector<std::pair<std::uint64_t, std::uint32_t>> sorted(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    std::int64_t c[3];
    cellOf(&positions[3 * i], c);
    sorted[i] = { key(c[0], c[1], c[2]), static_cast<std::uint32_t>(i) };
  }
  std::sort(sorted.begin(), sorted.end());
  const std::int64_t maxRing = std::max({ dims[0], dims[1], dims[2] });
  const std::int64_t count = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t ii = 0; ii < count; ++ii)
  {
    const std::size_t i = static_cast<std::size_t>(ii);
    const float* p = &positions[3 * i];
    std::int64_t c[3];
    cellOf(p, c);
    double best[3] = { std::numeric_limits<double>::infinity(),
      std::numeric_limits<double>::infinity(),
      std::numeric_limits<double>::infinity() };
    const std::size_t want = std::min<std::size_t>(3, n - 1);
    for (std::int64_t r = 0; r <= maxRing; ++r)
    {
      for (std::int64_t dx = -r; dx <= r; ++dx)
      {
        const std::int64_t x = c[0] + dx;
        if (x < 0 || x >= dims[0])
        {
          continue;
        }
        for (std::int64_t dy = -r; dy <= r; ++dy)
        {
          const std::int64_t y = c[1] + dy;
          if (y < 0 || y >= dims[1])
          {
            continue;
          }
          for (std::int64_t dz = -r; dz <= r; ++dz)
          {
            if (std::max({ std::abs(dx), std::abs(dy), std::abs(dz) }) != r)
            {
              continue; // only the shell of ring r
            }
            const std::int64_t z = c[2] + dz;
            if (z < 0 || z >= dims[2])
            {
              continue;
            }
            const std::uint64_t kk = key(x, y, z);
            auto it =
              std::lower_bound(sorted.begin(), sorted.end(), std::make_pair(kk, std::uint32_t(0)));
            for (; it != sorted.end() && it->first == kk; ++it)
            {
              if (it->second == i)
              {
                continue;
              }
              const float* q = &positions[3 * static_cast<std::size_t>(it->second)];
              const double d0 = static_cast<double>(p[0]) - q[0],
                           d1 = static_cast<double>(p[1]) - q[1],
                           d2 = static_cast<double>(p[2]) - q[2];
              const double d = d0 * d0 + d1 * d1 + d2 * d2;
              if (d < best[2])
              {
                best[2] = d;
                if (best[2] < best[1])
                {
                  std::swap(best[1], best[2]);
                  if (best[1] < best[0])
                  {
                    std::swap(best[0], best[1]);
                  }
                }
              }
            }
          }
        }
      }
      const double reach = static_cast<double>(r) * h;
      if (std::isfinite(best[want - 1]) && best[want - 1] <= reach * reach)
      {
        break;
      }
    }
    double s = 0;
    for (std::size_t k = 0; k < want; ++k)
    {
      s += best[k];
    }
    out[i] = static_cast<float>(s / static_cast<double>(want));
  }
  return out;
}

//------------------------------------------------------------------------------
GaussianCloud Trainer::InitializeFromPoints(const std::vector<float>& positions,
  const std::vector<float>& colors,
  int shDegree)
{
  const std::size_t n = positions.size() / 3;
  if (positions.size() != 3 * n || colors.size() != 3 * n)
  {
    throw std::invalid_argument("initial points: " + std::to_string(positions.size()) +
      " coordinates and " + std::to_string(colors.size()) + " colour values do not describe " +
      "the same points");
  }
  GaussianCloud cloud;
  cloud.Resize(n, shDegree);
  cloud.Ids.resize(n);
  const std::vector<float> d2 = MeanSquaredDistance3NN(positions);
  const int K = cloud.ShCoefficientCount();
  const float opacity = std::log(0.1f / (1.0f - 0.1f));
  for (std::size_t i = 0; i < n; ++i)
  {
    cloud.Ids[i] = static_cast<std::int64_t>(i);
    const float ls = std::log(std::sqrt(std::max(d2[i], 1e-7f)));
    for (int k = 0; k < 3; ++k)
    {
      cloud.Positions[3 * i + k] = positions[3 * i + k];
      cloud.LogScales[3 * i + k] = ls;
      cloud.SH[3 * K * i + k] = (colors[3 * i + k] - 0.5f) / static_cast<float>(sh::C0);
    }
    cloud.Rotations[4 * i] = 1.0f;
    cloud.OpacityLogits[i] = opacity;
  }
  return cloud;
}

//------------------------------------------------------------------------------
Trainer::Trainer(TrainingData data, const TrainerOptions& options)
  : Trainer(std::move(data), options, nullptr)
{
}

//------------------------------------------------------------------------------
Trainer::Trainer(TrainingData data,
  const TrainerOptions& options,
  GaussianCloud start,
  int startIteration,
  const std::vector<std::int64_t>& prunes)
  : Trainer(std::move(data), options, &start)
{
  if (startIteration < 0)
  {
    throw std::invalid_argument("trainer: the start iteration must be >= 0");
  }
  this->Iteration = this->StartIteration = startIteration;
  this->ActiveShDegree = this->Options.ShDegree;
  this->PendingPrunes = prunes;
  std::sort(this->PendingPrunes.begin(), this->PendingPrunes.end());
  std::vector<std::int64_t> ids = this->Cloud.Ids;
  std::sort(ids.begin(), ids.end());
  for (std::int64_t id : this->PendingPrunes)
  {
    if (!std::binary_search(ids.begin(), ids.end(), id))
    {
      throw std::invalid_argument(
        "trainer: the start cloud has no Gaussian " + std::to_string(id) + " to prune");
    }
  }
}

//------------------------------------------------------------------------------
void Trainer::ApplyPendingPrunes()
{
  if (this->PendingPrunes.empty())
  {
    return;
  }
  const std::size_t n = this->Cloud.Count;
  std::vector<char> keep(n, 1);
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::int64_t id = this->Cloud.Ids[i];
    if (std::binary_search(this->PendingPrunes.begin(), this->PendingPrunes.end(), id))
    {
      keep[i] = 0;
      this->Events.Append({ this->StartIteration, EventKind::Prune, id, -1 });
    }
  }
  // KeepRows compacts every per-row array, these too; they are filled later in a run.
  this->SnapshotAccum.resize(n, 0.0f);
  this->SnapshotDenom.resize(n, 0.0f);
  this->KeepRows(keep);
  this->PendingPrunes.clear();
}

//------------------------------------------------------------------------------
Trainer::Trainer(TrainingData data, const TrainerOptions& options, const GaussianCloud* start)
  : Data(std::move(data))
  , Options(options)
{
  if (this->Data.Images.size() != this->Data.Cameras.size())
  {
    throw std::invalid_argument("training data: " + std::to_string(this->Data.Cameras.size()) +
      " cameras but " + std::to_string(this->Data.Images.size()) + " images");
  }
  for (std::size_t v = 0; v < this->Data.Cameras.size(); ++v)
  {
    const Camera& cam = this->Data.Cameras[v];
    const std::size_t expected = 3 * static_cast<std::size_t>(cam.Width) * cam.Height;
    if (cam.Width <= 0 || cam.Height <= 0 || this->Data.Images[v].size() != expected)
    {
      throw std::invalid_argument("training data: image of camera '" + cam.Name + "' holds " +
        std::to_string(this->Data.Images[v].size()) + " values, expected " +
        std::to_string(expected) + " for " + std::to_string(cam.Width) + "x" +
        std::to_string(cam.Height) + " RGB");
    }
    (cam.Split == CameraSplit::Train ? this->TrainViews : this->TestViews).push_back(v);
  }
  if (this->TrainViews.empty())
  {
    throw std::invalid_argument("training data: no training camera");
  }
  if (!start && this->Data.PointPositions.empty())
  {
    throw std::invalid_argument("training data: no initial points");
  }
  if (this->Options.Iterations < 0 || this->Options.ShDegree < 0 || this->Options.ShDegree > 3)
  {
    throw std::invalid_argument(
      "trainer options: iterations must be >= 0 and the SH degree in 0..3");
  }
  // Scene extent (getNerfppNorm): 1.1 x the largest distance of a training camera centre
  // from their mean.
  double mean[3] = { 0, 0, 0 };
  for (std::size_t v : this->TrainViews)
  {
    const auto c = this->Data.Cameras[v].Center();
    for (int k = 0; k < 3; ++k)
    {
      mean[k] += c[k] / static_cast<double>(this->TrainViews.size());
    }
  }
  double maxDist = 0;
  for (std::size_t v : this->TrainViews)
  {
    const auto c = this->Data.Cameras[v].Center();
    maxDist = std::max(maxDist,
      std::sqrt((c[0] - mean[0]) * (c[0] - mean[0]) + (c[1] - mean[1]) * (c[1] - mean[1]) +
        (c[2] - mean[2]) * (c[2] - mean[2])));
  }
  this->Extent = maxDist > 0 ? 1.1 * maxDist : 1.0;

  if (start)
  {
    this->Cloud = StartCloud(*start, this->Options.ShDegree);
    this->NextId = this->Cloud.Count == 0
      ? 0
      : *std::max_element(this->Cloud.Ids.begin(), this->Cloud.Ids.end()) + 1;
  }
  else
  {
    this->Cloud = InitializeFromPoints(
      this->Data.PointPositions, this->Data.PointColors, this->Options.ShDegree);
    this->NextId = static_cast<std::int64_t>(this->Cloud.Count);
  }
  const std::size_t n = this->Cloud.Count;
  this->AdamPositions.Reset(3 * n);
  this->AdamScales.Reset(3 * n);
  this->AdamRotations.Reset(4 * n);
  this->AdamOpacity.Reset(n);
  this->AdamSH.Reset(this->Cloud.SH.size());
  this->GradAccum.assign(n, 0.0f);
  this->Denom.assign(n, 0.0f);
  this->MaxRadii.assign(n, 0.0f);
  this->CameraRng.seed(this->Options.Seed);
  this->SplitRng.seed(this->Options.Seed ^ 0x9E3779B97F4A7C15ull);
}

//------------------------------------------------------------------------------
double Trainer::PositionLearningRate(int iteration) const
{
  const double init = this->Options.PositionLrInit * this->Extent;
  const double fin = this->Options.PositionLrFinal * this->Extent;
  if (init == 0.0 && fin == 0.0)
  {
    return 0.0;
  }
  const double t = std::min(1.0,
    std::max(0.0, static_cast<double>(iteration) / std::max(1, this->Options.PositionLrMaxSteps)));
  return std::exp((1.0 - t) * std::log(init) + t * std::log(fin));
}

//------------------------------------------------------------------------------
void Trainer::AppendRows(const std::vector<std::size_t>& sources)
{
  GaussianCloud& c = this->Cloud;
  const std::size_t K3 = 3 * static_cast<std::size_t>(c.ShCoefficientCount());
  AppendCopies(c.Positions, 3, sources);
  AppendCopies(c.LogScales, 3, sources);
  AppendCopies(c.Rotations, 4, sources);
  AppendCopies(c.OpacityLogits, 1, sources);
  AppendCopies(c.SH, K3, sources);
  for (std::size_t r = 0; r < sources.size(); ++r)
  {
    c.Ids.push_back(this->NextId++);
  }
  c.Count += sources.size();
  const std::size_t n = c.Count;
  // New rows: zero moments, zero statistics.
  this->AdamPositions.M.resize(3 * n, 0.0f);
  this->AdamPositions.V.resize(3 * n, 0.0f);
  this->AdamScales.M.resize(3 * n, 0.0f);
  this->AdamScales.V.resize(3 * n, 0.0f);
  this->AdamRotations.M.resize(4 * n, 0.0f);
  this->AdamRotations.V.resize(4 * n, 0.0f);
  this->AdamOpacity.M.resize(n, 0.0f);
  this->AdamOpacity.V.resize(n, 0.0f);
  this->AdamSH.M.resize(K3 * n, 0.0f);
  this->AdamSH.V.resize(K3 * n, 0.0f);
  this->SnapshotAccum.resize(n, 0.0f);
  this->SnapshotDenom.resize(n, 0.0f);
  // densification_postfix: the accumulators of every row are reset.
  this->GradAccum.assign(n, 0.0f);
  this->Denom.assign(n, 0.0f);
  this->MaxRadii.assign(n, 0.0f);
}

//------------------------------------------------------------------------------
void Trainer::KeepRows(const std::vector<char>& keep)
{
  GaussianCloud& c = this->Cloud;
  const std::size_t K3 = 3 * static_cast<std::size_t>(c.ShCoefficientCount());
  Compact(c.Positions, 3, keep);
  Compact(c.LogScales, 3, keep);
  Compact(c.Rotations, 4, keep);
  Compact(c.OpacityLogits, 1, keep);
  Compact(c.SH, K3, keep);
  Compact(c.Ids, 1, keep);
  c.Count = c.Ids.size();
  Compact(this->AdamPositions.M, 3, keep);
  Compact(this->AdamPositions.V, 3, keep);
  Compact(this->AdamScales.M, 3, keep);
  Compact(this->AdamScales.V, 3, keep);
  Compact(this->AdamRotations.M, 4, keep);
  Compact(this->AdamRotations.V, 4, keep);
  Compact(this->AdamOpacity.M, 1, keep);
  Compact(this->AdamOpacity.V, 1, keep);
  Compact(this->AdamSH.M, K3, keep);
  Compact(this->AdamSH.V, K3, keep);
  Compact(this->GradAccum, 1, keep);
  Compact(this->Denom, 1, keep);
  Compact(this->MaxRadii, 1, keep);
  Compact(this->SnapshotAccum, 1, keep);
  Compact(this->SnapshotDenom, 1, keep);
}

//------------------------------------------------------------------------------
void Trainer::DensifyAndPrune(double maxScreenSize, bool useScreenSize)
{
  GaussianCloud& c = this->Cloud;
  const std::size_t n0 = c.Count;
  const float threshold = static_cast<float>(this->Options.DensifyGradThreshold);
  const float dense = static_cast<float>(this->Options.PercentDense * this->Extent);
  const int it = this->Iteration;
  std::vector<float> grads(n0);
  for (std::size_t i = 0; i < n0; ++i)
  {
    const float g = this->GradAccum[i] / this->Denom[i];
    grads[i] = std::isnan(g) ? 0.0f : g; // never-visible Gaussians: 0/0 -> 0
  }
  this->SnapshotAccum = grads;
  this->SnapshotDenom = this->Denom;
  this->StatisticsJustReset = true;

  // 1. Clone: small Gaussians with a large gradient, exact copies appended in row order.
  std::vector<std::size_t> clones;
  for (std::size_t i = 0; i < n0; ++i)
  {
    if (grads[i] >= threshold && MaxScale(&c.LogScales[3 * i]) <= dense)
    {
      clones.push_back(i);
    }
  }
  const std::int64_t firstCloneId = this->NextId;
  AppendRows(clones);
  for (std::size_t r = 0; r < clones.size(); ++r)
  {
    this->Events.Append(
      { it, EventKind::Clone, c.Ids[clones[r]], firstCloneId + static_cast<std::int64_t>(r) });
  }

  // 2. Split: large Gaussians with a large gradient among the rows present before the
  // clones (the gradient is padded with zeros for the clones).
  const std::size_t n1 = c.Count;
  std::vector<std::size_t> split;
  for (std::size_t i = 0; i < n0; ++i)
  {
    if (grads[i] >= threshold && MaxScale(&c.LogScales[3 * i]) > dense)
    {
      split.push_back(i);
    }
  }
  const std::size_t ks = split.size();
  std::vector<std::size_t> sources;
  sources.reserve(2 * ks);
  for (int j = 0; j < 2; ++j)
  {
    sources.insert(sources.end(), split.begin(), split.end());
  }
  const std::int64_t firstSplitId = this->NextId;
  AppendRows(sources);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (std::size_t r = 0; r < 2 * ks; ++r)
  {
    const std::size_t row = n1 + r;
    float* pos = &c.Positions[3 * row];
    float* ls = &c.LogScales[3 * row];
    const float* q = &c.Rotations[4 * row];
    const float s[3] = { std::exp(ls[0]), std::exp(ls[1]), std::exp(ls[2]) };
    const std::array<float, 4> qn = NormalizeQuaternion<float>(q);
    const std::array<float, 9> R = QuaternionToMatrix<float>(qn);
    float sample[3];
    for (float& v : sample)
    {
      v = static_cast<float>(normal(this->SplitRng));
    }
    for (int k = 0; k < 3; ++k)
    {
      sample[k] *= s[k];
    }
    for (int k = 0; k < 3; ++k)
    {
      pos[k] = R[3 * k] * sample[0] + R[3 * k + 1] * sample[1] + R[3 * k + 2] * sample[2] + pos[k];
    }
    for (int k = 0; k < 3; ++k)
    {
      ls[k] = std::log(s[k] / (0.8f * 2.0f));
    }
    this->Events.Append({ it,
      EventKind::Split,
      c.Ids[split[r % (ks ? ks : 1)]],
      firstSplitId + static_cast<std::int64_t>(r) });
  }
  if (ks > 0)
  {
    std::vector<char> keep(c.Count, 1);
    for (std::size_t i : split)
    {
      keep[i] = 0;
    }
    KeepRows(keep);
  }

  // 3. Prune: low opacity; once the size threshold is set, also world-space giants and
  // screen-space giants (whose radii the postfix above has just zeroed: inert, §4.6).
  const float minOpacity = static_cast<float>(this->Options.MinOpacity);
  const float maxWorld = static_cast<float>(0.1 * this->Extent);
  std::vector<char> keep(c.Count, 1);
  bool any = false;
  for (std::size_t i = 0; i < c.Count; ++i)
  {
    bool prune = Sigmoid(c.OpacityLogits[i]) < minOpacity;
    if (useScreenSize)
    {
      prune = prune || this->MaxRadii[i] > static_cast<float>(maxScreenSize) ||
        MaxScale(&c.LogScales[3 * i]) > maxWorld;
    }
    if (prune)
    {
      keep[i] = 0;
      any = true;
      this->Events.Append({ it, EventKind::Prune, c.Ids[i], -1 });
    }
  }
  if (any)
  {
    KeepRows(keep);
  }
}

//------------------------------------------------------------------------------
void Trainer::SetGradientStatistics(const std::vector<float>& accum,
  const std::vector<float>& denom)
{
  if (accum.size() != this->Cloud.Count || denom.size() != this->Cloud.Count)
  {
    throw std::invalid_argument("SetGradientStatistics: one value per Gaussian expected");
  }
  this->GradAccum = accum;
  this->Denom = denom;
}

//------------------------------------------------------------------------------
void Trainer::DensifyAndPruneAt(int iteration)
{
  const int saved = this->Iteration;
  this->Iteration = iteration;
  this->DensifyAndPrune(
    this->Options.ScreenSizeThreshold, iteration > this->Options.OpacityResetInterval);
  this->Iteration = saved;
}

//------------------------------------------------------------------------------
void Trainer::ResetOpacity()
{
  for (float& o : this->Cloud.OpacityLogits)
  {
    const float p = std::min(Sigmoid(o), 0.01f);
    o = std::log(p / (1.0f - p));
  }
  std::fill(this->AdamOpacity.M.begin(), this->AdamOpacity.M.end(), 0.0f);
  std::fill(this->AdamOpacity.V.begin(), this->AdamOpacity.V.end(), 0.0f);
}

//------------------------------------------------------------------------------
const SsimTarget<float>* Trainer::TargetMaps(std::size_t view, int threads) const
{
  if (this->SsimTargetsUsable < 0)
  {
    std::size_t bytes = 0;
    for (const Camera& c : this->Data.Cameras)
    {
      bytes += 6 * sizeof(float) * static_cast<std::size_t>(std::max(0, c.Width)) *
        static_cast<std::size_t>(std::max(0, c.Height));
    }
    this->SsimTargetsUsable = bytes <= (std::size_t(256) << 20) ? 1 : 0;
    this->SsimTargets.assign(this->SsimTargetsUsable ? this->Data.Cameras.size() : 0, {});
  }
  if (this->SsimTargetsUsable == 0)
  {
    return nullptr;
  }
  const Camera& cam = this->Data.Cameras[view];
  const float* target = this->Data.Images[view].data();
  SsimTarget<float>& st = this->SsimTargets[view];
  if (st.Image != target || st.Width != cam.Width || st.Height != cam.Height)
  {
    PrepareSsimTarget(target, cam.Width, cam.Height, st, threads);
  }
  return &st;
}

//------------------------------------------------------------------------------
double Trainer::Step()
{
  const auto t0 = Clock::now();
  const int it = ++this->Iteration;
  const TrainerOptions& o = this->Options;
  const int threads = ThreadCount(o.Threads);
  this->StatisticsJustReset = false;
  // A fine-tune's warm-up: j / (W + 1) of every learning rate at its j-th iteration (j <= W).
  const int sinceStart = it - this->StartIteration;
  const double lrScale = o.LrWarmupIterations > 0 && sinceStart <= o.LrWarmupIterations
    ? static_cast<double>(sinceStart) / (o.LrWarmupIterations + 1)
    : 1.0;
  const double positionLr = lrScale * this->PositionLearningRate(it);
  if (o.ShIncreaseInterval > 0 && it % o.ShIncreaseInterval == 0)
  {
    this->ActiveShDegree = std::min(this->ActiveShDegree + 1, o.ShDegree);
  }
  if (this->CameraStack.empty())
  {
    this->CameraStack = this->TrainViews;
  }
  const std::size_t pick = static_cast<std::size_t>(this->CameraRng() % this->CameraStack.size());
  const std::size_t view = this->CameraStack[pick];
  this->CameraStack.erase(this->CameraStack.begin() + static_cast<std::ptrdiff_t>(pick));
  const Camera& cam = this->Data.Cameras[view];

  RasterSettings settings;
  settings.Background = this->Data.Background;
  settings.ShDegree = this->ActiveShDegree;
  settings.Threads = threads;
  ViewProjection<float>& proj = this->StepProjection;
  ProjectGaussians<float>(this->Cloud, cam, settings, proj);
  TileBins& bins = this->StepBins;
  BinGaussians(proj, threads, bins, this->StepBinScratch);
  GaussianGradients<float>& grads = this->Gradients;
  BackwardSettings bopt;
  bopt.Threads = threads;
  bopt.KernelIsa = o.KernelIsa;
  RasterImage<float>& image = this->StepImage;
  if (o.KernelIsa < 0)
  {
    CompositeTiles(proj, bins, settings, image);
  }
  else
  {
    // CompositeTiles' outputs bit for bit (without depth), keeping the per-Gaussian spans
    // and 2D data in the backward's workspace for RasterBackward() below.
    CompositeForward(proj, bins, settings, image, bopt, &grads.Projected.Workspace);
  }
  const auto t1 = Clock::now();

  const float* target = this->Data.Images[view].data();
  const SsimTarget<float>* ssimTarget = this->TargetMaps(view, threads);
  const LossValues loss = TrainingLoss(image.Color.data(),
    target,
    cam.Width,
    cam.Height,
    o.LambdaDssim,
    &this->GradientScratch,
    threads,
    ssimTarget);
  const auto t2 = Clock::now();

  RasterBackward(
    this->Cloud, proj, bins, settings, image, this->GradientScratch.data(), grads, bopt);
  const auto t3 = Clock::now();
  this->LossEma = it == 1 ? loss.Loss : 0.4 * loss.Loss + 0.6 * this->LossEma;

  bool replacedAll = false, replacedOpacity = false;
  if (it < o.DensifyUntilIter)
  {
    const std::size_t n = this->Cloud.Count;
    for (std::size_t i = 0; i < n; ++i)
    {
      if (grads.Visible[i])
      {
        this->MaxRadii[i] =
          std::max(this->MaxRadii[i], static_cast<float>(proj.Gaussians[i].Radius));
        this->GradAccum[i] += grads.ViewspaceNorm(i);
        this->Denom[i] += 1.0f;
      }
    }
    if (it > o.DensifyFromIter && o.DensificationInterval > 0 && it % o.DensificationInterval == 0)
    {
      const bool useScreen = it > o.OpacityResetInterval;
      this->DensifyAndPrune(o.ScreenSizeThreshold, useScreen);
      replacedAll = true;
    }
    if ((o.OpacityResetInterval > 0 && it % o.OpacityResetInterval == 0) ||
      (o.WhiteBackground && it == o.DensifyFromIter))
    {
      this->ResetOpacity();
      replacedOpacity = true;
    }
  }
  const auto t4 = Clock::now();

  if (it < o.Iterations && !replacedAll)
  {
    GaussianCloud& c = this->Cloud;
    AdamStep(this->AdamPositions,
      c.Positions.data(),
      grads.Positions.data(),
      c.Positions.size(),
      positionLr,
      threads);
    AdamStep(this->AdamSH,
      c.SH.data(),
      grads.SH.data(),
      c.SH.size(),
      lrScale * o.FeatureLr / 20.0,
      threads,
      3 * static_cast<std::size_t>(c.ShCoefficientCount()),
      3,
      lrScale * o.FeatureLr);
    if (!replacedOpacity)
    {
      AdamStep(this->AdamOpacity,
        c.OpacityLogits.data(),
        grads.OpacityLogits.data(),
        c.OpacityLogits.size(),
        lrScale * o.OpacityLr,
        threads);
    }
    AdamStep(this->AdamScales,
      c.LogScales.data(),
      grads.LogScales.data(),
      c.LogScales.size(),
      lrScale * o.ScalingLr,
      threads);
    AdamStep(this->AdamRotations,
      c.Rotations.data(),
      grads.Rotations.data(),
      c.Rotations.size(),
      lrScale * o.RotationLr,
      threads);
  }
  const auto t5 = Clock::now();
  this->Timings.Forward += Seconds(t0, t1);
  this->Timings.Loss += Seconds(t1, t2);
  this->Timings.Backward += Seconds(t2, t3);
  this->Timings.Densify += Seconds(t3, t4);
  this->Timings.Optimizer += Seconds(t4, t5);
  this->Timings.Total += Seconds(t0, t5);
  return loss.Loss;
}

//------------------------------------------------------------------------------
MetricsRow Trainer::Evaluate(bool test) const
{
  MetricsRow row;
  row.Iteration = this->Iteration;
  row.NumGaussians = static_cast<std::int64_t>(this->Cloud.Count);
  std::vector<std::size_t> views = test ? this->TestViews : this->TrainViews;
  const int maxViews = this->Options.MetricsMaxTrainViews;
  if (!test && maxViews > 0 && views.size() > static_cast<std::size_t>(maxViews))
  {
    std::vector<std::size_t> subset;
    for (int k = 0; k < maxViews; ++k)
    {
      subset.push_back(
        views[static_cast<std::size_t>(k) * views.size() / static_cast<std::size_t>(maxViews)]);
    }
    views = subset;
  }
  if (views.empty())
  {
    return row; // NaN metrics: nothing measured
  }
  const int threads = ThreadCount(this->Options.Threads);
  RasterSettings settings;
  settings.Background = this->Data.Background;
  settings.ShDegree = this->ActiveShDegree;
  settings.Threads = threads;
  // Every view renders the same cloud: the view-independent preparation is made once per
  // call (a new cloud version each call, as the cloud may change between calls), and the
  // buffers are kept between calls. The kernels kept for a backward are not needed here; the
  // image is the same, bit for bit.
  RasterWorkspace<float>& ws = this->EvalWorkspace;
  ++ws.CloudVersion;
  ws.Composite.KeepKernels = false;
  double l1 = 0, ssim = 0, psnr = 0;
  for (std::size_t v : views)
  {
    const Camera& cam = this->Data.Cameras[v];
    Rasterize(this->Cloud, cam, settings, ws);
    RasterImage<float>& img = ws.Image;
    for (float& x : img.Color)
    {
      x = std::min(1.0f, std::max(0.0f, x));
    }
    const float* gt = this->Data.Images[v].data();
    // L1Loss() and Ssim() bit for bit, the target's SSIM maps made once per view.
    const LossValues values = TrainingLoss(img.Color.data(),
      gt,
      cam.Width,
      cam.Height,
      this->Options.LambdaDssim,
      static_cast<std::vector<float>*>(nullptr),
      threads,
      this->TargetMaps(v, threads));
    l1 += values.L1;
    ssim += values.Ssim;
    psnr += Psnr(img.Color.data(), gt, img.Color.size());
  }
  const double m = static_cast<double>(views.size());
  row.L1 = l1 / m;
  row.Ssim = ssim / m;
  row.Psnr = psnr / m;
  row.Loss =
    (1.0 - this->Options.LambdaDssim) * row.L1 + this->Options.LambdaDssim * (1.0 - row.Ssim);
  // LPIPS needs network weights that cannot ship: not measured (NaN).
  return row;
}

//------------------------------------------------------------------------------
void Trainer::WriteSnapshot(TrainingLogWriter& log, bool final)
{
  const GaussianCloud* cloud = &this->Cloud;
  GaussianCloud reduced;
  const int degree = final ? -1 : this->Options.SnapshotShDegree;
  if (degree >= 0 && degree < this->Cloud.ShDegree)
  {
    reduced = this->Cloud;
    reduced.ShDegree = degree;
    const std::size_t kIn = 3 * static_cast<std::size_t>(this->Cloud.ShCoefficientCount());
    const std::size_t kOut = 3 * static_cast<std::size_t>(reduced.ShCoefficientCount());
    reduced.SH.resize(kOut * reduced.Count);
    for (std::size_t i = 0; i < reduced.Count; ++i)
    {
      std::copy_n(this->Cloud.SH.begin() + i * kIn, kOut, reduced.SH.begin() + i * kOut);
    }
    cloud = &reduced;
  }
  SnapshotStatistics stats;
  if (this->Options.SnapshotStatistics)
  {
    if (this->StatisticsJustReset)
    {
      stats.GradAccum = this->SnapshotAccum;
      stats.Denom = this->SnapshotDenom;
    }
    else
    {
      const std::size_t n = this->Cloud.Count;
      stats.GradAccum.resize(n);
      for (std::size_t i = 0; i < n; ++i)
      {
        stats.GradAccum[i] = this->Denom[i] > 0 ? this->GradAccum[i] / this->Denom[i] : 0.0f;
      }
      stats.Denom = this->Denom;
    }
  }
  log.WriteSnapshot(this->Iteration, *cloud, this->Options.SnapshotStatistics ? &stats : nullptr);
}

//------------------------------------------------------------------------------
int Trainer::Run(TrainingLogWriter* log,
  const std::atomic<bool>* stop,
  const std::function<void(const TrainerProgress&)>& progress)
{
  const auto start = Clock::now();
  const TrainerOptions& o = this->Options;
  int lastSnapshot = -1, lastMetrics = -1;
  auto logMetrics = [&]()
  {
    const auto a = Clock::now();
    MetricsRow train, test;
    if (!this->Metrics || !this->Metrics(*this, train, test))
    {
      train = this->Evaluate(false);
      if (!this->TestViews.empty())
      {
        test = this->Evaluate(true);
      }
    }
    const double elapsed = Seconds(start, Clock::now());
    for (MetricsRow* row : { &train, &test })
    {
      row->Iteration = this->Iteration;
      row->NumGaussians = static_cast<std::int64_t>(this->Cloud.Count);
      row->ElapsedSeconds = elapsed;
    }
    log->AppendMetrics(train, false);
    if (!this->TestViews.empty())
    {
      log->AppendMetrics(test, true);
    }
    lastMetrics = this->Iteration;
    this->Timings.Logging += Seconds(a, Clock::now());
  };
  auto logEvents = [&]()
  {
    for (; this->EventsWritten < this->Events.Size(); ++this->EventsWritten)
    {
      log->AppendEvent(this->Events.Get(this->EventsWritten));
    }
  };
  auto logSnapshot = [&](bool final)
  {
    const auto a = Clock::now();
    logEvents();
    this->WriteSnapshot(*log, final);
    lastSnapshot = this->Iteration;
    this->Timings.Logging += Seconds(a, Clock::now());
  };
  if (log)
  {
    const auto a = Clock::now();
    std::vector<Camera> cams = this->Data.Cameras;
    for (std::size_t v = 0; v < cams.size(); ++v)
    {
      if (o.EmbedImages)
      {
        cams[v].ImagePath = "/images/" + cams[v].Name;
        const std::vector<float>& img = this->Data.Images[v];
        std::vector<unsigned char> rgb(img.size());
        for (std::size_t k = 0; k < img.size(); ++k)
        {
          rgb[k] = static_cast<unsigned char>(
            std::lround(std::min(1.0f, std::max(0.0f, img[k])) * 255.0f));
        }
        log->WriteImage(cams[v].Name, cams[v].Width, cams[v].Height, rgb.data());
      }
      else if (v < o.ImagePaths.size())
      {
        cams[v].ImagePath = o.ImagePaths[v];
      }
    }
    log->WriteCameras(cams);
    this->Timings.Logging += Seconds(a, Clock::now());
    if (this->Iteration == this->StartIteration)
    {
      if (!this->PendingPrunes.empty())
      {
        logSnapshot(false); // the state a fine-tune's deletion is made from
        this->ApplyPendingPrunes();
      }
      logMetrics();
      if (lastSnapshot != this->Iteration)
      {
        logSnapshot(false);
      }
    }
  }
  this->ApplyPendingPrunes();
  while (this->Iteration < o.Iterations && !(stop && stop->load()))
  {
    this->Step();
    const int it = this->Iteration;
    if (log)
    {
      if (o.MetricsInterval > 0 && it % o.MetricsInterval == 0)
      {
        logMetrics();
      }
      const bool last = it == o.Iterations || (stop && stop->load());
      if ((o.SnapshotInterval > 0 && it % o.SnapshotInterval == 0) || last)
      {
        logSnapshot(last);
      }
    }
    if (progress &&
      (it == o.Iterations || (o.ProgressInterval > 0 && it % o.ProgressInterval == 0)))
    {
      TrainerProgress p;
      p.Iteration = it;
      p.Iterations = o.Iterations;
      p.NumGaussians = this->Cloud.Count;
      p.Loss = this->LossEma;
      p.Elapsed = Seconds(start, Clock::now());
      p.ActiveShDegree = this->ActiveShDegree;
      progress(p);
    }
  }
  if (log)
  {
    if (lastMetrics != this->Iteration)
    {
      logMetrics();
    }
    if (lastSnapshot != this->Iteration)
    {
      logSnapshot(true);
    }
    logEvents();
    const auto a = Clock::now();
    log->Close();
    this->Timings.Logging += Seconds(a, Clock::now());
  }
  return this->Iteration;
}

} // namespace vis4gs

// SPDX-License-Identifier: BSD-3-Clause
#include "SyntheticEventLog.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace vis4gs
{

namespace
{

/// Splits @p total into integer parts proportional to @p weights (cumulative rounding).
std::vector<std::int64_t> Apportion(const std::vector<double>& weights, std::int64_t total)
{
  double sum = 0.0;
  for (double w : weights)
  {
    sum += w;
  }
  std::vector<std::int64_t> out(weights.size(), 0);
  if (sum <= 0.0 || total <= 0)
  {
    return out;
  }
  double acc = 0.0;
  std::int64_t given = 0;
  for (std::size_t k = 0; k < weights.size(); ++k)
  {
    acc += weights[k];
    const std::int64_t upTo = k + 1 == weights.size()
      ? total
      : static_cast<std::int64_t>(std::llround(static_cast<double>(total) * acc / sum));
    out[k] = std::max<std::int64_t>(0, upTo - given);
    given += out[k];
  }
  return out;
}

class Rng
{
public:
  explicit Rng(std::uint64_t seed)
    : Engine(seed)
  {
  }
  /// Uniform integer in [0, n).
  std::uint64_t Below(std::uint64_t n)
  {
    return static_cast<std::uint64_t>((static_cast<unsigned __int128>(this->Engine()) * n) >> 64);
  }
  double Unit() { return static_cast<double>(this->Engine() >> 11) * 0x1.0p-53; }

private:
  std::mt19937_64 Engine;
};

} // namespace

//------------------------------------------------------------------------------
SyntheticEventLog GenerateSyntheticEventLog(const SyntheticLogParameters& prm)
{
  const std::int64_t n0 = prm.InitialGaussians;
  if (n0 <= 0 || prm.FinalGaussians <= 0 || prm.TotalGaussians < prm.FinalGaussians ||
    prm.TotalGaussians < n0 || prm.DensifyInterval <= 0 || prm.DensifyFrom > prm.DensifyUntil ||
    prm.DensifyUntil > prm.Iterations || !(prm.SplitShare >= 0.0 && prm.SplitShare <= 1.0) ||
    !(prm.BurstPruneShare >= 0.0 && prm.BurstPruneShare <= 1.0) ||
    !(prm.RecentParentBias >= 0.0 && prm.RecentParentBias <= 1.0))
  {
    throw std::runtime_error("synthetic event log: inconsistent parameters (need positive "
                             "counts, total >= final, total >= initial, shares in [0, 1], "
                             "densify-from <= densify-until <= iterations)");
  }
  // Births = (1 + s) * densified parents; final = n0 + parents - prunes.
  const double parents = static_cast<double>(prm.TotalGaussians - n0) / (1.0 + prm.SplitShare);
  const std::int64_t totalPrunes =
    static_cast<std::int64_t>(std::llround(parents)) - (prm.FinalGaussians - n0);
  if (totalPrunes < 0)
  {
    std::ostringstream s;
    s << "synthetic event log: " << prm.TotalGaussians << " Gaussians in total cannot reach "
      << prm.FinalGaussians << " final ones with split share " << prm.SplitShare;
    throw std::runtime_error(s.str());
  }

  std::vector<std::int32_t> steps;
  for (std::int32_t it = prm.DensifyFrom; it <= prm.DensifyUntil; it += prm.DensifyInterval)
  {
    steps.push_back(it);
  }
  const std::size_t K = steps.size();

  // Net growth per step along the smoothstep profile.
  std::vector<double> growthWeight(K);
  for (std::size_t k = 0; k < K; ++k)
  {
    auto F = [&](double u) { return u * u * (3.0 - 2.0 * u); };
    growthWeight[k] =
      F(static_cast<double>(k + 1) / static_cast<double>(K)) - F(static_cast<double>(k) / K);
  }
  const std::vector<std::int64_t> growth = Apportion(growthWeight, prm.FinalGaussians - n0);
  // Expected count per step (for the prune weights).
  std::vector<double> countWeight(K);
  std::vector<double> burstWeight(K, 0.0);
  {
    double a = static_cast<double>(n0);
    for (std::size_t k = 0; k < K; ++k)
    {
      countWeight[k] = a;
      a += static_cast<double>(growth[k]);
      // First densification after an opacity reset (resets run after that iteration's ADC).
      const std::int32_t previous = steps[k] - prm.DensifyInterval;
      if (prm.OpacityResetInterval > 0 && k > 0 && previous % prm.OpacityResetInterval == 0)
      {
        burstWeight[k] = countWeight[k];
      }
    }
  }
  const std::int64_t burstTotal =
    static_cast<std::int64_t>(std::llround(prm.BurstPruneShare * static_cast<double>(totalPrunes)));
  const std::vector<std::int64_t> bursts = Apportion(burstWeight, burstTotal);
  const std::vector<std::int64_t> baseline = Apportion(countWeight, totalPrunes - burstTotal);

  SyntheticEventLog log;
  log.InitialGaussians = n0;
  log.LastIteration = prm.Iterations;
  const std::size_t rows = static_cast<std::size_t>(prm.TotalGaussians - n0 + totalPrunes + 16);
  log.Events.Iteration.reserve(rows);
  log.Events.Kind.reserve(rows);
  log.Events.Parent.reserve(rows);
  log.Events.Child.reserve(rows);

  Rng rng(prm.Seed);
  // Alive ids (swap-removal), position of each id in it (-1 when dead), step at which an id
  // was last chosen as a parent.
  const std::size_t idCapacity = static_cast<std::size_t>(prm.TotalGaussians) + 1;
  std::vector<std::int64_t> alive;
  alive.reserve(static_cast<std::size_t>(std::max(prm.FinalGaussians, n0)) * 2);
  std::vector<std::int64_t> position(idCapacity, -1);
  std::vector<std::int32_t> chosen(idCapacity, -1);
  for (std::int64_t id = 0; id < n0; ++id)
  {
    position[id] = static_cast<std::int64_t>(alive.size());
    alive.push_back(id);
  }
  std::int64_t nextId = n0;
  std::vector<std::int64_t> recent, newborn, cloneParents, splitParents;
  auto remove = [&](std::int64_t id)
  {
    const std::int64_t pos = position[id];
    const std::int64_t last = alive.back();
    alive[pos] = last;
    position[last] = pos;
    alive.pop_back();
    position[id] = -1;
  };
  auto emit = [&](std::int32_t it, EventKind kind, std::int64_t parent, std::int64_t child)
  {
    log.Events.Iteration.push_back(it);
    log.Events.Kind.push_back(static_cast<std::uint8_t>(kind));
    log.Events.Parent.push_back(parent);
    log.Events.Child.push_back(child);
  };

  std::int64_t carry = 0; // densifications postponed by the doubling cap
  const std::int64_t maxBorn = prm.TotalGaussians - n0;
  std::int64_t born = 0;
  for (std::size_t k = 0; k < K; ++k)
  {
    const std::int32_t it = steps[k];
    const std::int32_t stamp = static_cast<std::int32_t>(k);
    const std::int64_t prunes = bursts[k] + baseline[k];
    std::int64_t wanted = growth[k] + prunes + carry;
    const std::int64_t cap = static_cast<std::int64_t>(alive.size()) / 2;
    std::int64_t m = std::min(wanted, cap);
    std::int64_t splits = static_cast<std::int64_t>(std::llround(prm.SplitShare * m));
    // Never exceed the total number of Gaussians (rounding of the split share).
    while (m > 0 && born + (m - splits) + 2 * splits > maxBorn)
    {
      --m;
      splits = static_cast<std::int64_t>(std::llround(prm.SplitShare * m));
    }
    if (k + 1 == K)
    {
      // Last step: hit the total exactly (clones + 2 splits = what is left to be born).
      const std::int64_t left = maxBorn - born;
      m = std::min<std::int64_t>(cap,
        static_cast<std::int64_t>(
          std::llround(static_cast<double>(left) / (1.0 + prm.SplitShare))));
      m = std::max<std::int64_t>(m, (left + 1) / 2);
      m = std::min<std::int64_t>(m, left);
      splits = left - m;
    }
    carry = wanted - m;
    const std::int64_t clones = m - splits;

    // Distinct parents: newborns of the previous step with probability RecentParentBias.
    cloneParents.clear();
    splitParents.clear();
    for (std::int64_t j = 0; j < m; ++j)
    {
      std::int64_t id = -1;
      if (!recent.empty() && rng.Unit() < prm.RecentParentBias)
      {
        const std::int64_t c = recent[rng.Below(recent.size())];
        if (position[c] >= 0 && chosen[c] != stamp)
        {
          id = c;
        }
      }
      while (id < 0)
      {
        const std::int64_t c = alive[rng.Below(alive.size())];
        if (chosen[c] != stamp)
        {
          id = c;
        }
      }
      chosen[id] = stamp;
      (j < clones ? cloneParents : splitParents).push_back(id);
    }
    newborn.clear();
    for (std::int64_t p : cloneParents)
    {
      emit(it, EventKind::Clone, p, nextId);
      newborn.push_back(nextId++);
    }
    const std::int64_t s = static_cast<std::int64_t>(splitParents.size());
    for (int half = 0; half < 2; ++half)
    {
      for (std::int64_t r = 0; r < s; ++r)
      {
        emit(it, EventKind::Split, splitParents[r], nextId);
        newborn.push_back(nextId++);
      }
    }
    for (std::int64_t p : splitParents)
    {
      remove(p);
    }
    for (std::int64_t c : newborn)
    {
      position[c] = static_cast<std::int64_t>(alive.size());
      alive.push_back(c);
    }
    born += static_cast<std::int64_t>(newborn.size());
    // Prunes: uniformly among the alive (keep at least one Gaussian).
    const std::int64_t np =
      std::min<std::int64_t>(prunes, static_cast<std::int64_t>(alive.size()) - 1);
    for (std::int64_t j = 0; j < np; ++j)
    {
      const std::int64_t id = alive[rng.Below(alive.size())];
      emit(it, EventKind::Prune, id, -1);
      remove(id);
    }
    log.Clones += clones;
    log.Splits += s;
    log.Prunes += np;
    recent.swap(newborn);
  }
  log.FinalGaussians = static_cast<std::int64_t>(alive.size());
  return log;
}

} // namespace vis4gs

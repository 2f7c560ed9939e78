// SPDX-License-Identifier: BSD-3-Clause
#include "StateComparison.h"

#include "GaussianMath.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <stdexcept>

namespace vis4gs
{
namespace
{
// Indices of @p cloud by increasing id; throws on a repeated id or a missing array.
std::vector<std::size_t> OrderById(const GaussianCloud& cloud, const char* which)
{
  const std::size_t n = cloud.Count;
  if (cloud.Positions.size() != 3 * n || cloud.LogScales.size() != 3 * n ||
    cloud.OpacityLogits.size() != n || (!cloud.Ids.empty() && cloud.Ids.size() != n))
  {
    throw std::invalid_argument(std::string("CompareStates: state ") + which +
      " lacks positions, scales, opacities or ids for its " + std::to_string(n) + " Gaussians");
  }
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  if (!cloud.Ids.empty()) // without ids the indices are already in order
  {
    std::stable_sort(order.begin(),
      order.end(),
      [&](std::size_t i, std::size_t j) { return cloud.Ids[i] < cloud.Ids[j]; });
  }
  for (std::size_t k = 1; k < n; ++k)
  {
    if (cloud.GetId(order[k]) == cloud.GetId(order[k - 1]))
    {
      throw std::invalid_argument(std::string("CompareStates: state ") + which + " holds id " +
        std::to_string(cloud.GetId(order[k])) + " twice (Gaussians " +
        std::to_string(order[k - 1]) + " and " + std::to_string(order[k]) + ")");
    }
  }
  return order;
}
// y - x, 0 when both hold the same bits (so identical infinities or NaNs are no change).
double Difference(float x, float y)
{
  return std::memcmp(&x, &y, sizeof x) == 0 ? 0.0 : static_cast<double>(y) - x;
}
} // namespace

std::string StateChangeName(std::uint8_t change)
{
  if (change & StateBorn)
  {
    return "born";
  }
  if (change & StateDied)
  {
    return "died";
  }
  std::string name;
  for (const auto& [flag, word] : { std::make_pair(StateMoved, "moved"),
         std::make_pair(StateOpacityChanged, "opacity"),
         std::make_pair(StateScaleChanged, "scale") })
  {
    if (change & flag)
    {
      name += (name.empty() ? "" : "+") + std::string(word);
    }
  }
  return name.empty() ? "unchanged" : name;
}

StateComparison CompareStates(const GaussianCloud& a,
  const GaussianCloud& b,
  const StateThresholds& thresholds)
{
  const std::vector<std::size_t> orderA = OrderById(a, "A");
  const std::vector<std::size_t> orderB = OrderById(b, "B");
  StateComparison out;
  out.CountA = a.Count;
  out.CountB = b.Count;
  out.Gaussians.reserve(std::max(a.Count, b.Count));
  std::size_t i = 0, j = 0;
  while (i < orderA.size() || j < orderB.size())
  {
    GaussianStateDifference d;
    const bool takeA =
      i < orderA.size() && (j == orderB.size() || a.GetId(orderA[i]) <= b.GetId(orderB[j]));
    const bool takeB =
      j < orderB.size() && (i == orderA.size() || b.GetId(orderB[j]) <= a.GetId(orderA[i]));
    if (takeA && takeB)
    {
      const std::size_t ia = orderA[i++], ib = orderB[j++];
      d.Id = a.GetId(ia);
      d.IndexA = static_cast<std::int64_t>(ia);
      d.IndexB = static_cast<std::int64_t>(ib);
      double squared = 0;
      d.Scale = 0;
      for (int k = 0; k < 3; ++k)
      {
        const double dp = Difference(a.Positions[3 * ia + k], b.Positions[3 * ib + k]);
        squared += dp * dp;
        const double ds = Difference(a.LogScales[3 * ia + k], b.LogScales[3 * ib + k]);
        d.Scale = std::abs(ds) > std::abs(d.Scale) ? ds : d.Scale;
      }
      d.Move = std::sqrt(squared);
      d.Opacity = Difference(a.OpacityLogits[ia], b.OpacityLogits[ib]) == 0
        ? 0.0
        : Sigmoid(static_cast<double>(b.OpacityLogits[ib])) -
          Sigmoid(static_cast<double>(a.OpacityLogits[ia]));
      // NaN differences (non-finite parameters) count as changes: they are not "unchanged".
      const auto beyond = [](double v, double t) { return !(std::abs(v) <= t); };
      d.Change = static_cast<std::uint8_t>((beyond(d.Move, thresholds.Move) ? StateMoved : 0) |
        (beyond(d.Opacity, thresholds.Opacity) ? StateOpacityChanged : 0) |
        (beyond(d.Scale, thresholds.Scale) ? StateScaleChanged : 0));
      ++out.Matched;
      out.Moved += (d.Change & StateMoved) ? 1 : 0;
      out.OpacityChanged += (d.Change & StateOpacityChanged) ? 1 : 0;
      out.ScaleChanged += (d.Change & StateScaleChanged) ? 1 : 0;
      out.Unchanged += d.Change == StateUnchanged ? 1 : 0;
    }
    else if (takeA)
    {
      d.IndexA = static_cast<std::int64_t>(orderA[i]);
      d.Id = a.GetId(orderA[i++]);
      d.Change = StateDied;
      ++out.Died;
    }
    else
    {
      d.IndexB = static_cast<std::int64_t>(orderB[j]);
      d.Id = b.GetId(orderB[j++]);
      d.Change = StateBorn;
      ++out.Born;
    }
    out.Gaussians.push_back(d);
  }
  return out;
}

} // namespace vis4gs

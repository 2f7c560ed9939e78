// SPDX-License-Identifier: BSD-3-Clause
#include "SpecialValues.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <vector>

namespace vis4gs
{

std::size_t SpecialValueCounts::Skipped() const
{
  std::size_t n = 0;
  for (int c = 1; c < static_cast<int>(GaussianClass::Count); ++c)
  {
    n += this->ByClass[static_cast<std::size_t>(c)];
  }
  return n;
}

const char* GaussianClassName(GaussianClass c)
{
  switch (c)
  {
    case GaussianClass::Drawn:
      return "drawn";
    case GaussianClass::NaNParameter:
      return "NaN parameter";
    case GaussianClass::InfinitePosition:
      return "infinite position";
    case GaussianClass::InfiniteLogScale:
      return "log-scale +inf";
    case GaussianClass::InfiniteRotation:
      return "infinite rotation";
    case GaussianClass::Count:
      break;
  }
  return "unknown";
}

SpecialValueCounts CountSpecialValues(const GaussianCloud& cloud, int shDegree)
{
  SpecialValueCounts out;
  const std::size_t n = cloud.Count;
  const bool withSh = shDegree >= 0 && !cloud.SH.empty();
  const int degree = std::min(std::max(shDegree, 0), cloud.ShDegree);
  const std::size_t stride = 3 * static_cast<std::size_t>(cloud.ShCoefficientCount());
  const std::size_t used = 3 * static_cast<std::size_t>((degree + 1) * (degree + 1));
  constexpr int classes = static_cast<int>(GaussianClass::Count);
  // Per-thread tallies: the scan is memory bound and runs once per request on scenes of
  // millions of Gaussians.
  std::array<std::size_t, classes> byClass{};
  std::size_t nonFiniteSh = 0, plusInf = 0, minusInf = 0, flat = 0, zeroQ = 0;
  const std::int64_t sn = static_cast<std::int64_t>(n);
#pragma omp parallel
  {
    std::array<std::size_t, classes> local{};
    std::size_t lSh = 0, lPlus = 0, lMinus = 0, lFlat = 0, lZero = 0;
#pragma omp for schedule(static) nowait
    for (std::int64_t g = 0; g < sn; ++g)
    {
      const std::size_t i = static_cast<std::size_t>(g);
      const float* pos = &cloud.Positions[3 * i];
      const float* ls = &cloud.LogScales[3 * i];
      const float* rot = &cloud.Rotations[4 * i];
      const float logit = cloud.OpacityLogits[i];
      const GaussianClass c = ClassifyGaussian(pos, ls, rot, logit);
      ++local[static_cast<std::size_t>(c)];
      if (c != GaussianClass::Drawn)
      {
        continue;
      }
      lPlus += std::isinf(logit) && logit > 0;
      lMinus += std::isinf(logit) && logit < 0;
      lFlat += std::isinf(ls[0]) || std::isinf(ls[1]) || std::isinf(ls[2]);
      lZero += rot[0] == 0 && rot[1] == 0 && rot[2] == 0 && rot[3] == 0;
      if (withSh)
      {
        const float* sh = &cloud.SH[i * stride];
        bool finite = true;
        for (std::size_t k = 0; k < used; ++k)
        {
          finite = finite && std::isfinite(sh[k]);
        }
        lSh += !finite;
      }
    }
#pragma omp critical
    {
      for (int c = 0; c < classes; ++c)
      {
        byClass[static_cast<std::size_t>(c)] += local[static_cast<std::size_t>(c)];
      }
      nonFiniteSh += lSh;
      plusInf += lPlus;
      minusInf += lMinus;
      flat += lFlat;
      zeroQ += lZero;
    }
  }
  out.ByClass = byClass;
  out.NonFiniteSH = nonFiniteSh;
  out.OpacityPlusInf = plusInf;
  out.OpacityMinusInf = minusInf;
  out.LogScaleMinusInf = flat;
  out.ZeroQuaternion = zeroQ;
  return out;
}

namespace
{
void AppendReason(std::ostringstream& os, bool& first, std::size_t count, const char* what)
{
  if (count == 0)
  {
    return;
  }
  os << (first ? "" : ", ") << count << " with " << what;
  first = false;
}
} // namespace

std::string DescribeSkipped(const SpecialValueCounts& counts, bool render)
{
  const std::size_t total = render ? counts.SkippedByRender() : counts.Skipped();
  if (total == 0)
  {
    return std::string();
  }
  std::ostringstream os;
  os << total << " skipped: ";
  bool first = true;
  // The reason phrases, indexed by GaussianClass.
  static const char* const phrases[] = { "",
    "a NaN parameter",
    "an infinite position",
    "a log-scale of +inf",
    "an infinite rotation component" };
  static_assert(sizeof(phrases) / sizeof(phrases[0]) == static_cast<int>(GaussianClass::Count),
    "one phrase per GaussianClass");
  for (int c = 1; c < static_cast<int>(GaussianClass::Count); ++c)
  {
    AppendReason(os, first, counts.ByClass[static_cast<std::size_t>(c)], phrases[c]);
  }
  if (render)
  {
    AppendReason(os, first, counts.NonFiniteSH, "an infinite or NaN SH coefficient");
  }
  return os.str();
}

std::string DescribeDrawnSpecials(const SpecialValueCounts& counts)
{
  std::ostringstream os;
  bool first = true;
  AppendReason(os, first, counts.OpacityPlusInf, "opacity logit +inf (opacity 1)");
  AppendReason(os, first, counts.OpacityMinusInf, "opacity logit -inf (opacity 0)");
  AppendReason(os, first, counts.LogScaleMinusInf, "a log-scale of -inf (scale 0)");
  AppendReason(os, first, counts.ZeroQuaternion, "a zero quaternion (no rotation)");
  return first ? std::string() : "drawn as the reference does: " + os.str();
}

} // namespace vis4gs

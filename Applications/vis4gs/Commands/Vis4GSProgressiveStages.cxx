// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSProgressiveStages.h"

#include "ScoreRegistry.h"
#include "Vis4GSDataModel.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkPointData.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numeric>
#include <stdexcept>

//------------------------------------------------------------------------------
ScoreColumns ScoresOf(vtkPointData* pd, std::map<std::string, bool>& want)
{
  ScoreColumns scores;
  for (const vis4gs::ScoreDefinition& d : vis4gs::ScoreDefinitions())
  {
    const char* array = d.ArrayName;
    if (!want[d.Name])
    {
      continue;
    }
    vtkDataArray* a = pd->GetArray(array);
    if (!a)
    {
      throw std::runtime_error("computing " + std::string(array) + " failed (see the error above)");
    }
    std::vector<double> v;
    vtkDoubleArray* values = vtkDoubleArray::SafeDownCast(a);
    if (values && values->GetNumberOfComponents() == 1)
    {
      // (the filter's arrays: one copy, not a virtual call per Gaussian)
      const double* first = values->GetPointer(0);
      v.assign(first, first + values->GetNumberOfTuples());
    }
    else
    {
      v.resize(static_cast<std::size_t>(a->GetNumberOfTuples()));
      for (std::size_t i = 0; i < v.size(); ++i)
      {
        v[i] = a->GetTuple1(static_cast<vtkIdType>(i));
      }
    }
    scores.emplace_back(array, std::move(v));
  }
  return scores;
}

//------------------------------------------------------------------------------
StageError CompareStage(const std::vector<double>& stage,
  const std::vector<double>& exact,
  bool lowestFirst)
{
  StageError e;
  for (std::size_t i = 0; i < exact.size() && i < stage.size(); ++i)
  {
    if (std::isfinite(exact[i]) && std::isfinite(stage[i]))
    {
      e.LargestDifference = std::max(e.LargestDifference, std::abs(stage[i] - exact[i]));
      e.LargestExact = std::max(e.LargestExact, std::abs(exact[i]));
    }
  }
  e.TopCount = std::max<std::size_t>(1, exact.size() / 100);
  auto top = [&](const std::vector<double>& v)
  {
    std::vector<std::size_t> order(v.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    auto key = [&](std::size_t i)
    { return std::isfinite(v[i]) ? (lowestFirst ? -v[i] : v[i]) : -HUGE_VAL; };
    const std::size_t k = std::min(e.TopCount, order.size());
    std::partial_sort(order.begin(),
      order.begin() + k,
      order.end(),
      [&](std::size_t a, std::size_t b) { return key(a) > key(b) || (key(a) == key(b) && a < b); });
    order.resize(k);
    std::sort(order.begin(), order.end());
    return order;
  };
  const std::vector<std::size_t> a = top(exact), b = top(stage);
  std::vector<std::size_t> shared;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(shared));
  e.TopShared = shared.size();
  return e;
}

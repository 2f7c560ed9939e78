// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Adam.h
 * @brief torch.optim.Adam as the reference trainer uses it (reference §4.1): one state per
 * parameter tensor with its own step count, betas (0.9, 0.999), eps 1e-15, dense updates
 * (rows with a zero gradient still move with their momentum), in PyTorch's operation order:
 *
 *   step += 1;  m = m + (g - m)(1 - b1)  (lerp);  v = b2 v + (1 - b2) g^2;
 *   p -= (lr / (1 - b1^step)) m / (sqrt(v) / sqrt(1 - b2^step) + eps)
 *
 * with the bias corrections computed in double and applied as float scalars. Rows appended
 * by densification start with zero moments; the step count is kept; removed rows take their
 * moments with them.
 */
#ifndef vis4gs_Adam_h
#define vis4gs_Adam_h

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vis4gs
{

struct AdamState
{
  std::int64_t Step = 0;
  std::vector<float> M; ///< first moment, same layout as the parameter
  std::vector<float> V; ///< second moment

  static constexpr double Beta1 = 0.9;
  static constexpr double Beta2 = 0.999;
  static constexpr double Epsilon = 1e-15;

  /// Resizes the moments to @p n values, zero-filled.
  void Reset(std::size_t n)
  {
    this->M.assign(n, 0.0f);
    this->V.assign(n, 0.0f);
  }
};

/**
 * One Adam step over @p n values with learning rate @p lr. With @p period > 0, values whose
 * index modulo @p period is below @p firstCount use @p firstLr instead: the SH array holds,
 * per Gaussian (period 3K), the DC triple (f_dc, lr 0.0025) then the rest (f_rest,
 * lr 0.0025/20). The reference keeps f_dc and f_rest as two tensors; they are always stepped
 * (or skipped) together, so one shared step count is exact.
 */
inline void AdamStep(AdamState& state,
  float* param,
  const float* grad,
  std::size_t n,
  double lr,
  int threads = 1,
  std::size_t period = 0,
  std::size_t firstCount = 0,
  double firstLr = 0)
{
  state.Step += 1;
  const double bc1 = 1.0 - std::pow(AdamState::Beta1, static_cast<double>(state.Step));
  const double bc2 = 1.0 - std::pow(AdamState::Beta2, static_cast<double>(state.Step));
  const float stepSize = static_cast<float>(lr / bc1);
  const float firstStepSize = static_cast<float>(firstLr / bc1);
  const float bc2Sqrt = static_cast<float>(std::sqrt(bc2));
  const float oneMinusB1 = static_cast<float>(1.0 - AdamState::Beta1);
  const float b2 = static_cast<float>(AdamState::Beta2);
  const float oneMinusB2 = static_cast<float>(1.0 - AdamState::Beta2);
  const float eps = static_cast<float>(AdamState::Epsilon);
  float* m = state.M.data();
  float* v = state.V.data();
  // One contiguous run [begin, end) with one step size: a plain loop the compiler
  // vectorises (sqrt and division are correctly rounded, so every lane gives the scalar
  // result bit for bit).
  auto run = [=](std::size_t begin, std::size_t end, float sz)
  {
    for (std::size_t i = begin; i < end; ++i)
    {
      const float g = grad[i];
      const float mi = m[i] + (g - m[i]) * oneMinusB1;
      const float vi = v[i] * b2 + oneMinusB2 * g * g;
      m[i] = mi;
      v[i] = vi;
      const float denom = std::sqrt(vi) / bc2Sqrt + eps;
      param[i] = param[i] - sz * (mi / denom);
    }
  };
  if (period == 0 || firstCount == 0)
  {
    constexpr std::int64_t block = 4096;
    const std::int64_t blocks = (static_cast<std::int64_t>(n) + block - 1) / block;
#pragma omp parallel for num_threads(threads) schedule(static) if (n > 65536)
    for (std::int64_t b = 0; b < blocks; ++b)
    {
      const std::size_t begin = static_cast<std::size_t>(b * block);
      run(begin, std::min(n, begin + static_cast<std::size_t>(block)), stepSize);
    }
    return;
  }
  // Rows of `period` values: the first `firstCount` with the first step size.
  const std::int64_t rows = static_cast<std::int64_t>((n + period - 1) / period);
#pragma omp parallel for num_threads(threads) schedule(static) if (n > 65536)
  for (std::int64_t r = 0; r < rows; ++r)
  {
    const std::size_t begin = static_cast<std::size_t>(r) * period;
    const std::size_t split = std::min(n, begin + firstCount);
    run(begin, split, firstStepSize);
    run(split, std::min(n, begin + period), stepSize);
  }
}

} // namespace vis4gs

#endif

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
  const std::int64_t count = static_cast<std::int64_t>(n);
#pragma omp parallel for num_threads(threads) schedule(static) if (count > 65536)
  for (std::int64_t i = 0; i < count; ++i)
  {
    const float g = grad[i];
    m[i] = m[i] + (g - m[i]) * oneMinusB1;
    v[i] = v[i] * b2 + oneMinusB2 * g * g;
    const float denom = std::sqrt(v[i]) / bc2Sqrt + eps;
    const float sz =
      (period > 0 && static_cast<std::size_t>(i) % period < firstCount) ? firstStepSize : stepSize;
    param[i] = param[i] - sz * (m[i] / denom);
  }
}

} // namespace vis4gs

#endif

// SPDX-License-Identifier: BSD-3-Clause
// The one instruction-set dispatch: what each KernelIsa setting resolves to on this CPU.
#include "KernelIsa.h"

#include <gtest/gtest.h>

#include <cstring>

namespace
{
using vis4gs::KernelIsa;

// What the CPU has, asked independently of KernelIsa.cxx's cached detection.
bool Has(const char* feature)
{
  __builtin_cpu_init();
  if (std::strcmp(feature, "avx512") == 0)
  {
    return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
      __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq");
  }
  return __builtin_cpu_supports("avx2");
}
} // namespace

TEST(KernelIsa, DetectionMatchesTheCpu)
{
  EXPECT_EQ(vis4gs::CpuHasAvx2(), Has("avx2"));
  EXPECT_EQ(vis4gs::CpuHasAvx512(), Has("avx512"));
}

TEST(KernelIsa, EverySettingMeansTheSameEverywhere)
{
  const bool avx2 = Has("avx2");
  const bool avx512 = Has("avx512");
  const KernelIsa widest =
    avx512 ? KernelIsa::Avx512 : (avx2 ? KernelIsa::Avx2 : KernelIsa::Baseline);
  EXPECT_EQ(vis4gs::ResolveKernelIsa(0), widest);
  EXPECT_EQ(vis4gs::ResolveKernelIsa(1), KernelIsa::Baseline);
  // Negative settings (a module's scalar reference) reach the dispatch as the baseline.
  EXPECT_EQ(vis4gs::ResolveKernelIsa(-1), KernelIsa::Baseline);
  EXPECT_EQ(vis4gs::ResolveKernelIsa(2), avx2 ? KernelIsa::Avx2 : KernelIsa::Baseline);
  // AVX-512 requested on a CPU without it falls back to AVX2, then to the baseline.
  EXPECT_EQ(vis4gs::ResolveKernelIsa(3), widest);
  EXPECT_EQ(vis4gs::ResolveKernelIsa(99), widest);
  for (int setting = -1; setting <= 4; ++setting)
  {
    EXPECT_NE(vis4gs::ResolveKernelIsa(setting), KernelIsa::Best) << setting;
  }
  EXPECT_STREQ(vis4gs::KernelIsaName(KernelIsa::Avx512), "AVX-512");
  EXPECT_STREQ(vis4gs::KernelIsaName(KernelIsa::Baseline), "baseline");
}

// SPDX-License-Identifier: BSD-3-Clause
#include "KernelIsa.h"

namespace vis4gs
{

namespace
{
struct CpuFeatures
{
  bool Avx2 = false;
  bool Avx512 = false;
  CpuFeatures()
  {
    __builtin_cpu_init();
    this->Avx2 = __builtin_cpu_supports("avx2");
    this->Avx512 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
      __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq");
  }
};

const CpuFeatures& Features()
{
  static const CpuFeatures features;
  return features;
}
} // namespace

bool CpuHasAvx2()
{
  return Features().Avx2;
}

bool CpuHasAvx512()
{
  return Features().Avx512;
}

KernelIsa ResolveKernelIsa(int requested)
{
  if (requested == 1 || requested < 0)
  {
    return KernelIsa::Baseline;
  }
  if ((requested == 0 || requested >= 3) && CpuHasAvx512())
  {
    return KernelIsa::Avx512;
  }
  return CpuHasAvx2() ? KernelIsa::Avx2 : KernelIsa::Baseline;
}

const char* KernelIsaName(KernelIsa isa)
{
  switch (isa)
  {
    case KernelIsa::Best:
      return "best";
    case KernelIsa::Baseline:
      return "baseline";
    case KernelIsa::Avx2:
      return "AVX2";
    case KernelIsa::Avx512:
      return "AVX-512";
  }
  return "unknown";
}

} // namespace vis4gs

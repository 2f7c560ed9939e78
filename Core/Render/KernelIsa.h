// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file KernelIsa.h
 * @brief The one instruction-set dispatch of Core's SIMD kernels: what the `KernelIsa`
 * settings mean, what the CPU has, and the target attributes the kernels are compiled with.
 *
 * Every kernel with hand-written vector code (projection, compositing, footprints, fast
 * coverage, the loss, the backward pass, screen selection) is compiled once per instruction
 * set and picks its variant at run time with ResolveKernelIsa(), so that a setting such as
 * `RasterSettings::KernelIsa = 2` means the same thing in every module:
 *
 * | setting | kernel                                                                   |
 * |---------|--------------------------------------------------------------------------|
 * | 0       | the widest the CPU has (the default)                                     |
 * | 1       | the baseline build: code compiled for x86-64's baseline (SSE2), no       |
 * |         | run-time-selected extension (vector code where the module has a generic  |
 * |         | vector variant, its scalar loop where it has none)                       |
 * | 2       | AVX2                                                                     |
 * | 3       | AVX-512 (F, VL, BW, DQ)                                                  |
 *
 * A request the CPU cannot run falls back to the widest set below it that it can. Modules
 * with a scalar pixel-by-pixel reference name it -1; that is not an instruction set and is
 * handled by the module before dispatch. Every variant gives the same results bit for bit
 * where the module's tests say so (the compositing loops are built with -ffp-contract=off).
 */
#ifndef vis4gs_KernelIsa_h
#define vis4gs_KernelIsa_h

/// Target strings and attributes of the AVX2 and AVX-512 variants (the AVX-512 subsets the
/// kernels use).
#define VIS4GS_AVX2_FEATURES "avx2"
#define VIS4GS_TARGET_AVX2 __attribute__((target(VIS4GS_AVX2_FEATURES)))
#define VIS4GS_AVX512_FEATURES "avx512f,avx512vl,avx512bw,avx512dq"
#define VIS4GS_TARGET_AVX512 __attribute__((target(VIS4GS_AVX512_FEATURES)))

/// An always-inlined helper of an AVX2 / AVX-512 kernel written out in a .cxx.
#define VIS4GS_INLINE_AVX2 VIS4GS_TARGET_AVX2 inline __attribute__((always_inline))
#define VIS4GS_INLINE_AVX512 VIS4GS_TARGET_AVX512 inline __attribute__((always_inline))

/**
 * The one protocol of the kernels compiled once per instruction set from a `*Lanes.inc`
 * file (ProjectionLanes.inc, CompositeLanes.inc, FastCoverageLanes.inc,
 * RasterBackwardLanes.inc). The includer opens a namespace per variant and defines
 * VIS4GS_LANES_ISA to the variant's KernelIsa value around the include:
 *
 *     namespace composite_avx2
 *     {
 *     #define VIS4GS_LANES_ISA 2
 *     #include "CompositeLanes.inc"
 *     #undef VIS4GS_LANES_ISA
 *     }
 *
 * and the .inc file writes its entry points with VIS4GS_LANES_TARGET, every helper with
 * VIS4GS_LANES_FN (GCC 12 types a vector comparison by the instruction set of the function
 * whose body holds it: a helper without the variant's attribute is lowered lane by lane with
 * scalar branches even once inlined), and tests the variant with `#if VIS4GS_LANES_ISA == 3`
 * or VIS4GS_LANES_NATIVE_BYTES (the width of a vector register: 16, 32, 64 bytes). These
 * macros expand where they are used, so they follow VIS4GS_LANES_ISA include by include.
 */
#define VIS4GS_LANES_TARGET VIS4GS_LANES_TARGET_OF(VIS4GS_LANES_ISA)
#define VIS4GS_LANES_FN VIS4GS_LANES_TARGET inline __attribute__((always_inline))
#define VIS4GS_LANES_NATIVE_BYTES (VIS4GS_LANES_ISA == 3 ? 64 : (VIS4GS_LANES_ISA == 2 ? 32 : 16))
#define VIS4GS_LANES_TARGET_OF(isa) VIS4GS_LANES_TARGET_OF2(isa)
#define VIS4GS_LANES_TARGET_OF2(isa) VIS4GS_LANES_TARGET_##isa
#define VIS4GS_LANES_TARGET_1
#define VIS4GS_LANES_TARGET_2 VIS4GS_TARGET_AVX2
#define VIS4GS_LANES_TARGET_3 VIS4GS_TARGET_AVX512

namespace vis4gs
{

/// An instruction set a kernel is compiled for (the values of the `KernelIsa` settings).
enum class KernelIsa : int
{
  Best = 0,
  Baseline = 1,
  Avx2 = 2,
  Avx512 = 3
};

/// True when the CPU (and the OS) can run the AVX2 / AVX-512 variants; detected once.
bool CpuHasAvx2();
bool CpuHasAvx512();

/**
 * The variant a kernel runs for the setting @p requested (0 best, 1 baseline, 2 AVX2,
 * 3 AVX-512; larger values read as 3, negative ones as 1): the requested set, or the widest
 * one below it that the CPU has. Never returns KernelIsa::Best.
 */
KernelIsa ResolveKernelIsa(int requested);

/// Name of @p isa for messages and benchmark tables ("baseline", "AVX2", "AVX-512", "best").
const char* KernelIsaName(KernelIsa isa);

} // namespace vis4gs

#endif

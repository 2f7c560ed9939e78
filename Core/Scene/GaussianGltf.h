// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file GaussianGltf.h
 * @brief What the glTF reader (GaussianGltf.cxx) and writer (GaussianGltfWriter.cxx) share:
 * the extension names, the exact change between glTF's frame and the PLY's axes, the real SH
 * basis, and the sRGB transfer function of the fallback colour.
 */
#ifndef vis4gs_GaussianGltf_h
#define vis4gs_GaussianGltf_h

#include "GaussianCloud.h"

#include <cmath>
#include <string>
#include <vector>

namespace vis4gs
{
namespace detail
{

constexpr const char* GltfExtension = "KHR_gaussian_splatting";
constexpr const char* GltfSpzExtension = "KHR_gaussian_splatting_compression_spz_2";

/// glTF's frame (+Y up, LUF) to the INRIA PLY's axes (RDF): a half turn about z, as
/// splat-transform's `.glb` writer turns the PLY's axes out; exact (sign changes and a
/// quaternion permutation). PlyToGltfAxes is its exact inverse.
void GltfToPlyAxes(GaussianCloud& cloud);
void PlyToGltfAxes(GaussianCloud& cloud);
/// The SH part of the half turn: coefficients of odd order m change sign.
void FlipOddOrderSh(GaussianCloud& cloud);

/**
 * Moves @p cloud, in glTF's frame, by a node's global transform @p columnMajor (4x4), as the
 * extension defines it: means by the matrix, covariances Σ' = M Σ Mᵀ, view-dependent colour
 * by the rotation of M's polar decomposition. A rotation with uniform scale changes the
 * quaternions and log-scales directly; uneven scale or shear re-factors each covariance
 * exactly and adds a warning naming @p where to @p warnings. A mirror, a collapse or a
 * non-finite matrix throws std::runtime_error naming @p name (the extension leaves them
 * undefined).
 */
void ApplyGltfTransform(GaussianCloud& cloud,
  const double* columnMajor,
  const std::string& name,
  const std::string& where,
  std::vector<std::string>& warnings);

/// Real SH basis function k (0..15, the reference rasteriser's order and signs) at @p dir.
double ShBasis(int k, const double dir[3]);

/// sRGB transfer function and its inverse on [0, 1] (IEC 61966-2-1).
inline double SrgbToLinear(double c)
{
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}
inline double LinearToSrgb(double c)
{
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

} // namespace detail
} // namespace vis4gs

#endif

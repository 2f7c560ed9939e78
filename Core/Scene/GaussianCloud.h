// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file GaussianCloud.h
 * @brief The in-memory 3DGS scene shared by every Core module.
 *
 * Parameters are kept raw, exactly as trainers store them (float32, log scales, opacity
 * logits, unnormalised quaternions), so that a diagnosis never works on rounded or
 * re-activated values. Activation lives in GaussianMath.h.
 */
#ifndef vis4gs_GaussianCloud_h
#define vis4gs_GaussianCloud_h

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vis4gs
{

/// Scalar types a PLY property can have; extra properties keep theirs so they write back as read.
enum class ScalarType : std::uint8_t
{
  Int8,
  UInt8,
  Int16,
  UInt16,
  Int32,
  UInt32,
  Float32,
  Float64
};

/// Size in bytes of one value of @p type.
std::size_t ScalarTypeSize(ScalarType type);

/// A per-Gaussian property the 3DGS model does not interpret (normals, scores, ids of other
/// tools). Values are stored as native-endian bytes of @c Type, one value per Gaussian.
struct ExtraProperty
{
  std::string Name;
  ScalarType Type = ScalarType::Float32;
  std::vector<unsigned char> Bytes;

  /// Value @p i converted to double (for tables and display).
  double GetAsDouble(std::size_t i) const;
};

/**
 * Structure of arrays, one entry per Gaussian. Empty vectors mean "not loaded" (a reader
 * may leave out what a request does not need); Count is authoritative.
 */
struct GaussianCloud
{
  std::size_t Count = 0;
  /// SH degree of the coefficients held in SH (0..3); the file may hold more.
  int ShDegree = 0;
  /// Stable ids (DESIGN §3). Empty means 0..Count-1.
  std::vector<std::int64_t> Ids;
  std::vector<float> Positions;     ///< 3 per Gaussian
  std::vector<float> LogScales;     ///< 3 per Gaussian, natural log
  std::vector<float> Rotations;     ///< 4 per Gaussian, w x y z, not normalised
  std::vector<float> OpacityLogits; ///< 1 per Gaussian
  /// (ShDegree+1)^2 RGB triples per Gaussian, coefficient-major: k0 RGB, k1 RGB, ...
  std::vector<float> SH;
  std::vector<ExtraProperty> Extra;

  /// Number of SH coefficients per channel for the held degree: (ShDegree+1)^2.
  int ShCoefficientCount() const { return (this->ShDegree + 1) * (this->ShDegree + 1); }
  /// Id of Gaussian @p i (its index when Ids is empty).
  std::int64_t GetId(std::size_t i) const
  {
    return this->Ids.empty() ? static_cast<std::int64_t>(i) : this->Ids[i];
  }
  /// Resizes every parameter array to @p n Gaussians (extras are cleared).
  void Resize(std::size_t n, int shDegree);
  /// Returns the extra property named @p name, or nullptr.
  const ExtraProperty* FindExtra(const std::string& name) const;
};

} // namespace vis4gs

#endif

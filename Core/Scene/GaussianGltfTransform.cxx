// SPDX-License-Identifier: BSD-3-Clause
// glTF splats between frames (GaussianGltf.h): a node's global transform applied to means,
// covariances and SH, and the exact half turn between glTF's frame and the PLY's axes.
#include "GaussianGltf.h"
#include "GaussianMath.h"

#include <Eigen/Dense>

#include <cmath>
#include <stdexcept>

namespace vis4gs
{
namespace
{

/// Real SH rotation of one degree @p l (2l+1 coefficients) for directions turned by @p r:
/// coefficients c' with f'(d) = f(r^T d), found by least squares on fixed directions (the
/// band is closed under rotation, so the fit is exact to rounding).
Eigen::MatrixXd ShBandRotation(int l, const Eigen::Matrix3d& r)
{
  const int n = 2 * l + 1;
  const int samples = 24;
  Eigen::MatrixXd a(samples, n), b(samples, n);
  for (int s = 0; s < samples; ++s)
  {
    // Fibonacci directions: well spread, so the fit is well conditioned.
    const double z = 1.0 - (2.0 * s + 1.0) / samples;
    const double phi = 2.399963229728653 * s;
    const Eigen::Vector3d d(
      std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi), z);
    const Eigen::Vector3d e = r.transpose() * d;
    for (int m = 0; m < n; ++m)
    {
      a(s, m) = detail::ShBasis(l * l + m, d.data());
      b(s, m) = detail::ShBasis(l * l + m, e.data());
    }
  }
  return a.colPivHouseholderQr().solve(b);
}

void RotateSh(GaussianCloud& cloud, const Eigen::Matrix3d& r)
{
  const std::size_t k = static_cast<std::size_t>(cloud.ShCoefficientCount());
  if (cloud.SH.empty() || cloud.ShDegree == 0)
  {
    return;
  }
  for (int l = 1; l <= cloud.ShDegree; ++l)
  {
    const Eigen::MatrixXd d = ShBandRotation(l, r);
    const int n = 2 * l + 1;
    for (std::size_t g = 0; g < cloud.Count; ++g)
    {
      for (int c = 0; c < 3; ++c)
      {
        Eigen::VectorXd v(n);
        for (int m = 0; m < n; ++m)
        {
          v(m) = cloud.SH[3 * (k * g + static_cast<std::size_t>(l * l + m)) + c];
        }
        const Eigen::VectorXd w = d * v;
        for (int m = 0; m < n; ++m)
        {
          cloud.SH[3 * (k * g + static_cast<std::size_t>(l * l + m)) + c] =
            static_cast<float>(w(m));
        }
      }
    }
  }
}

} // namespace

//------------------------------------------------------------------------------
void detail::ApplyGltfTransform(GaussianCloud& cloud,
  const double* columnMajor,
  const std::string& name,
  const std::string& where,
  std::vector<std::string>& warnings)
{
  const Eigen::Matrix4d world = Eigen::Map<const Eigen::Matrix4d>(columnMajor);
  if (world == Eigen::Matrix4d::Identity())
  {
    return;
  }
  const Eigen::Matrix3d m = world.topLeftCorner<3, 3>();
  const Eigen::Vector3d t = world.topRightCorner<3, 1>();
  const double det = m.determinant();
  if (!(det > 0) || !std::isfinite(det) || !world.allFinite())
  {
    throw std::runtime_error(name + ": " + where + "'s global transform has determinant " +
      std::to_string(det) +
      " (a mirror, a collapse or a non-finite value); KHR_gaussian_splatting leaves such splats "
      "undefined");
  }
  // Polar decomposition m = r p: r turns the view-dependent colour, p stretches.
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix3d r = svd.matrixU() * svd.matrixV().transpose();
  const Eigen::Matrix3d p =
    svd.matrixV() * svd.singularValues().asDiagonal() * svd.matrixV().transpose();
  const double uniform = std::cbrt(det);
  const bool isUniform =
    (p - uniform * Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() <= 1e-9 * uniform;
  if (!isUniform)
  {
    warnings.push_back(name + ": " + where +
      "'s transform scales unevenly or shears: each covariance is transformed exactly and "
      "re-factored into scales and a rotation, and the view-dependent colour turns with the "
      "transform's rotation part");
  }
  const Eigen::Quaterniond qr(r);
  for (std::size_t g = 0; g < cloud.Count; ++g)
  {
    if (!cloud.Positions.empty())
    {
      Eigen::Vector3d x(
        cloud.Positions[3 * g], cloud.Positions[3 * g + 1], cloud.Positions[3 * g + 2]);
      x = m * x + t;
      for (int c = 0; c < 3; ++c)
      {
        cloud.Positions[3 * g + c] = static_cast<float>(x(c));
      }
    }
    if (cloud.Rotations.empty())
    {
      continue;
    }
    float* q = &cloud.Rotations[4 * g];
    if (isUniform)
    {
      const Eigen::Quaterniond out = qr * Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
      q[0] = static_cast<float>(out.w());
      q[1] = static_cast<float>(out.x());
      q[2] = static_cast<float>(out.y());
      q[3] = static_cast<float>(out.z());
      for (std::size_t c = 0; c < 3 && !cloud.LogScales.empty(); ++c)
      {
        cloud.LogScales[3 * g + c] =
          static_cast<float>(cloud.LogScales[3 * g + c] + std::log(uniform));
      }
      continue;
    }
    if (cloud.LogScales.empty())
    {
      continue;
    }
    const auto cov = GaussianCovariance<double>(&cloud.LogScales[3 * g], q, 1.0);
    Eigen::Matrix3d sigma;
    sigma << cov[0], cov[1], cov[2], cov[1], cov[3], cov[4], cov[2], cov[4], cov[5];
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(m * sigma * m.transpose());
    Eigen::Matrix3d axes = eig.eigenvectors();
    if (axes.determinant() < 0)
    {
      axes.col(2) = -axes.col(2);
    }
    const Eigen::Quaterniond out(axes);
    q[0] = static_cast<float>(out.w());
    q[1] = static_cast<float>(out.x());
    q[2] = static_cast<float>(out.y());
    q[3] = static_cast<float>(out.z());
    for (int c = 0; c < 3; ++c)
    {
      cloud.LogScales[3 * g + c] =
        static_cast<float>(0.5 * std::log(std::max(0.0, eig.eigenvalues()(c))));
    }
  }
  if (!r.isIdentity(1e-15))
  {
    RotateSh(cloud, r);
  }
}

//------------------------------------------------------------------------------
double detail::ShBasis(int k, const double dir[3])
{
  float sh[48] = {};
  sh[3 * k] = 1;
  double rgb[3];
  ShColor<double>(sh, 3, dir, rgb);
  return rgb[0] - 0.5;
}

namespace
{
// A half turn about z, as splat-transform's Transform.PLY: x and y change sign; the
// quaternion becomes r^-1 * q (reading) or r * q (writing) with
// r = (0, 0, 0, 1). Both are the same rotation; each matches splat-transform's
// stored quaternion bit for bit in its direction.
void HalfTurnAboutZ(GaussianCloud& cloud, bool reading)
{
  for (std::size_t g = 0; g < cloud.Count && !cloud.Positions.empty(); ++g)
  {
    cloud.Positions[3 * g] = -cloud.Positions[3 * g];
    cloud.Positions[3 * g + 1] = -cloud.Positions[3 * g + 1];
  }
  for (std::size_t g = 0; g < cloud.Count && !cloud.Rotations.empty(); ++g)
  {
    float* q = &cloud.Rotations[4 * g];
    const float w = q[0], x = q[1], y = q[2], z = q[3];
    // Negation, not a product with -1: it flips the sign bit of NaN too.
    q[0] = reading ? z : -z;
    q[1] = reading ? y : -y;
    q[2] = reading ? -x : x;
    q[3] = reading ? -w : w;
  }
}
}

//------------------------------------------------------------------------------
void detail::GltfToPlyAxes(GaussianCloud& cloud)
{
  HalfTurnAboutZ(cloud, true);
  FlipOddOrderSh(cloud);
}

//------------------------------------------------------------------------------
void detail::PlyToGltfAxes(GaussianCloud& cloud)
{
  HalfTurnAboutZ(cloud, false);
  FlipOddOrderSh(cloud);
}

//------------------------------------------------------------------------------
void detail::FlipOddOrderSh(GaussianCloud& cloud)
{
  // A half turn about z multiplies the real SH of order m by (-1)^m.
  const std::size_t k = static_cast<std::size_t>(cloud.ShCoefficientCount());
  for (std::size_t g = 0; g < cloud.Count && !cloud.SH.empty(); ++g)
  {
    for (std::size_t j = 1; j < k; ++j)
    {
      const int l = static_cast<int>(std::sqrt(static_cast<double>(j)) + 1e-9);
      const int m = static_cast<int>(j) - l * l - l;
      if (m % 2 != 0)
      {
        for (int c = 0; c < 3; ++c)
        {
          cloud.SH[3 * (k * g + j) + c] = -cloud.SH[3 * (k * g + j) + c];
        }
      }
    }
  }
}

} // namespace vis4gs

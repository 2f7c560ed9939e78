// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file GaussianOctree.h
 * @brief Ray selection: every Gaussian that a viewing ray passes within k sigma of, in depth
 * order, through an octree over the Gaussians' k-sigma bounding boxes.
 *
 * Distance: the Mahalanobis distance of the half-line o + t d (t >= TMin) to the Gaussian,
 * min_t sqrt((x(t) - mu)^T Sigma^-1 (x(t) - mu)), Sigma = R diag(s^2) R^T. It is computed in
 * the Gaussian's own frame (y = S^-1 R^T (x - mu)), where it is the Euclidean distance of a
 * half-line to the origin; that form needs no matrix inverse and stays finite for needle and
 * disk shapes. Log-scales are clamped to [-300, 300] in double (scales of 1e-130 .. 1e130: a
 * thinner Gaussian is treated as that thin, a larger one covers everything anyway).
 * Gaussians with a NaN/Inf parameter or a zero quaternion (a point Gaussian) are never hit.
 *
 * Order: by the centre's position along the ray, (mu - o) . d / |d|, ties by index: the
 * order in which the renderer composites Gaussians seen along that ray.
 *
 * The octree: the root cell is the bounding cube of all boxes; a Gaussian is stored in the
 * deepest cell that contains its whole box (cells split into 8 when they hold more than
 * LeafSize Gaussians, up to MaxDepth). A query visits only cells the ray enters.
 */
#ifndef vis4gs_GaussianOctree_h
#define vis4gs_GaussianOctree_h

#include "GaussianCloud.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vis4gs
{

/// A viewing ray.
struct RayQuery
{
  std::array<double, 3> Origin{ 0, 0, 0 };
  std::array<double, 3> Direction{ 0, 0, 1 }; ///< any non-zero length
  double Sigmas = 3.0;                        ///< k: hit when the distance is <= k
  double TMin = 0.0; ///< the half-line starts at Origin + TMin * unit direction
};

/// One Gaussian on the ray.
struct RayHit
{
  std::uint32_t Gaussian = 0; ///< index in the cloud
  double Depth = 0;           ///< (mu - o) . d/|d|, the sort key
  double Distance = 0;        ///< Mahalanobis distance of the half-line, in sigmas
};

/// Mahalanobis distance of the half-line to Gaussian @p i of @p cloud (infinity for an
/// invalid Gaussian); the exact function every query uses.
double RayMahalanobisDistance(const GaussianCloud& cloud, std::size_t i, const RayQuery& ray);

class GaussianOctree
{
public:
  struct Options
  {
    /// k of the boxes the tree is built over; queries may use any Sigmas <= BoundSigmas.
    double BoundSigmas = 3.0;
    int LeafSize = 32;
    int MaxDepth = 16;
  };

  /// Builds the tree over @p cloud (which must outlive the tree). Throws
  /// std::invalid_argument for arrays that do not match the count or > 2^32-1 Gaussians.
  void Build(const GaussianCloud& cloud, const Options& options);
  void Build(const GaussianCloud& cloud) { this->Build(cloud, Options()); }

  /// Every Gaussian within ray.Sigmas of the ray, in depth order. Throws
  /// std::invalid_argument when ray.Sigmas > BoundSigmas, the tree is not built, or the
  /// direction is zero or not finite.
  std::vector<RayHit> IntersectRay(const RayQuery& ray) const;

  std::size_t GetNodeCount() const { return this->Nodes.size(); }
  int GetDepth() const { return this->Depth; }
  double GetBoundSigmas() const { return this->Opts.BoundSigmas; }
  /// Gaussian-box tests done by the last IntersectRay() (work measure).
  std::size_t GetLastBoxTests() const { return this->LastBoxTests; }

private:
  struct Node
  {
    double Min[3], Max[3];
    std::uint32_t First = 0, Count = 0; ///< Gaussians stored in this node: Items[First, +Count)
    std::int32_t Children[8] = { -1, -1, -1, -1, -1, -1, -1, -1 };
  };
  const GaussianCloud* Cloud = nullptr;
  Options Opts;
  std::vector<Node> Nodes;
  std::vector<std::uint32_t> Items;
  std::vector<float> Boxes; ///< 6 per Gaussian: min xyz, max xyz (NaN for invalid ones)
  int Depth = 0;
  mutable std::size_t LastBoxTests = 0;
};

/// The straightforward reference: every Gaussian, Sigma^-1 by an explicit 3x3 inverse in
/// long double, the closed-form minimum along the half-line. Same results as the octree for
/// scales where the inverse is well conditioned.
std::vector<RayHit> IntersectRayBruteForce(const GaussianCloud& cloud, const RayQuery& ray);

} // namespace vis4gs

#endif

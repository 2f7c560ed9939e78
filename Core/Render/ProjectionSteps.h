// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ProjectionSteps.h
 * @brief The one scalar code of the per-view projection of a Gaussian (reference §2.2-2.3:
 * ProjectGaussians() steps 1, 2, 4, 5 and 6), used by the rasteriser's scalar projection
 * (float and double) and by the fast coverage's exact visibility test (Core/Diagnostics).
 * ProjectionSteps.inc is the same code on lanes. Three steps, split where a caller stops
 * early: the view position (near cull); the clip coordinates, EWA projection, conic and
 * pixel-space mean; the tile rectangle. The culls are returned as flags in the order the
 * callers test them, so every value is the one the reference computes, bit for bit.
 */
#ifndef vis4gs_ProjectionSteps_h
#define vis4gs_ProjectionSteps_h

#include "RasterKernel.h"
#include "Rasterizer.h"

#include <algorithm>
#include <cmath>

namespace vis4gs
{
namespace raster
{

/// A view as the projection reads it: the world-to-camera rows (12 values), rows 0, 1 and 3
/// of the full projection, the focal lengths, the Jacobian clamps and the image and tile grid.
template <typename T>
struct ProjectionView
{
  const T* V;
  const T* F0;
  const T* F1;
  const T* F3;
  T FocalX, FocalY;
  T LimX, LimY;
  int W, H, Gx, Gy;
};

/// The float view of a PreparedView (the lane code's view).
inline ProjectionView<float> ProjectionViewOf(const PreparedView& w)
{
  return { w.V, w.F0, w.F1, w.F3, w.FocalX, w.FocalY, w.LimX, w.LimY, w.W, w.H, w.Gx, w.Gy };
}

/// Step 1: the view position (T2 is the depth; near cull when T2 <= NearPlane).
template <typename T>
struct ProjectedViewPosition
{
  T T0, T1, T2;
};

template <typename T>
inline ProjectedViewPosition<T> ProjectViewPosition(const ProjectionView<T>& w, T x, T y, T z)
{
  const T* V = w.V;
  return { V[0] * x + V[1] * y + V[2] * z + V[3],
    V[4] * x + V[5] * y + V[6] * z + V[7],
    V[8] * x + V[9] * y + V[10] * z + V[11] };
}

/// Steps 2, 4, 5 and the pixel-space mean of step 6: the dilated 2D covariance (A, B, C),
/// its conic, the radius before rounding and the mean in pixels, and the culls in the order
/// the projection tests them (covariance not finite, determinant zero, conic or radius not
/// finite, mean not finite).
template <typename T>
struct ProjectedConic
{
  T A, B, C;
  T ConA, ConB, ConC;
  T RadiusF;
  T U, V;
  bool CovFinite, Degenerate, ConicFinite, UvFinite;
};

/// @p s: the 3D covariance S00, S01, S02, S11, S12, S22 (GaussianCovariance()).
template <typename T>
inline ProjectedConic<T> ProjectConic(const ProjectionView<T>& w,
  T x,
  T y,
  T z,
  const ProjectedViewPosition<T>& t,
  const T (&s)[6])
{
  const T* V = w.V;
  ProjectedConic<T> r{};
  // 2. Clip coordinates.
  const T hx = w.F0[0] * x + w.F0[1] * y + w.F0[2] * z + w.F0[3];
  const T hy = w.F1[0] * x + w.F1[1] * y + w.F1[2] * z + w.F1[3];
  const T hw = w.F3[0] * x + w.F3[1] * y + w.F3[2] * z + w.F3[3];
  const T pw = T(1) / (hw + T(0.0000001));
  const T ndcX = hx * pw, ndcY = hy * pw;
  // 4. EWA projection with the clamped Jacobian.
  const T t2 = t.T2;
  const T txtz = t.T0 / t2, tytz = t.T1 / t2;
  const T tx = std::min(w.LimX, std::max(-w.LimX, txtz)) * t2;
  const T ty = std::min(w.LimY, std::max(-w.LimY, tytz)) * t2;
  const T J00 = w.FocalX / t2, J02 = -(w.FocalX * tx) / (t2 * t2);
  const T J11 = w.FocalY / t2, J12 = -(w.FocalY * ty) / (t2 * t2);
  T Tm[2][3]; // J * R_v
  for (int c = 0; c < 3; ++c)
  {
    Tm[0][c] = J00 * V[c] + J02 * V[8 + c];
    Tm[1][c] = J11 * V[4 + c] + J12 * V[8 + c];
  }
  const T Sig[3][3] = { { s[0], s[1], s[2] }, { s[1], s[3], s[4] }, { s[2], s[4], s[5] } };
  T TS[2][3];
  for (int row = 0; row < 2; ++row)
  {
    for (int c = 0; c < 3; ++c)
    {
      TS[row][c] = Tm[row][0] * Sig[0][c] + Tm[row][1] * Sig[1][c] + Tm[row][2] * Sig[2][c];
    }
  }
  const T cxx = TS[0][0] * Tm[0][0] + TS[0][1] * Tm[0][1] + TS[0][2] * Tm[0][2];
  const T cxy = TS[0][0] * Tm[1][0] + TS[0][1] * Tm[1][1] + TS[0][2] * Tm[1][2];
  const T cyy = TS[1][0] * Tm[1][0] + TS[1][1] * Tm[1][1] + TS[1][2] * Tm[1][2];
  r.A = cxx + T(Dilation);
  r.B = cxy;
  r.C = cyy + T(Dilation);
  r.CovFinite = std::isfinite(r.A) && std::isfinite(r.B) && std::isfinite(r.C);
  if (!r.CovFinite)
  {
    return r;
  }
  // 5. det cull, conic, radius.
  const T det = r.A * r.C - r.B * r.B;
  r.Degenerate = det == T(0);
  if (r.Degenerate)
  {
    return r;
  }
  const T detInv = T(1) / det;
  r.ConA = r.C * detInv;
  r.ConB = -r.B * detInv;
  r.ConC = r.A * detInv;
  const T mid = T(0.5) * (r.A + r.C);
  const T root = std::sqrt(std::max(T(0.1), mid * mid - det));
  const T l1 = mid + root, l2 = mid - root;
  r.RadiusF = std::ceil(T(3) * std::sqrt(std::max(l1, l2)));
  r.ConicFinite = std::isfinite(r.ConA) && std::isfinite(r.ConB) && std::isfinite(r.ConC) &&
    std::isfinite(r.RadiusF) && std::isfinite(det);
  if (!r.ConicFinite)
  {
    return r;
  }
  // 6. Pixel-space mean.
  r.U = Ndc2Pix(ndcX, w.W);
  r.V = Ndc2Pix(ndcY, w.H);
  r.UvFinite = std::isfinite(r.U) && std::isfinite(r.V);
  return r;
}

/// Step 6: the integer radius and the tile rectangle [X0, X1) x [Y0, Y1) (empty: off screen).
struct ProjectedTileRect
{
  int Radius, X0, Y0, X1, Y1;
};

template <typename T>
inline ProjectedTileRect ProjectTileRect(const ProjectionView<T>& w, T u, T v, T radiusF)
{
  ProjectedTileRect r;
  r.Radius = ClampToInt(radiusF);
  const T rr = static_cast<T>(r.Radius);
  const T bs = T(TileSize);
  r.X0 = std::min(w.Gx, std::max(0, ClampToInt((u - rr) / bs)));
  r.Y0 = std::min(w.Gy, std::max(0, ClampToInt((v - rr) / bs)));
  r.X1 = std::min(w.Gx, std::max(0, ClampToInt((u + rr + bs - T(1)) / bs)));
  r.Y1 = std::min(w.Gy, std::max(0, ClampToInt((v + rr + bs - T(1)) / bs)));
  return r;
}

} // namespace raster
} // namespace vis4gs

#endif

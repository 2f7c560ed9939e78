// SPDX-License-Identifier: BSD-3-Clause
#include "BenchmarkScene.h"

#include "GaussianMath.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace vis4gs
{

//------------------------------------------------------------------------------
GaussianCloud MakeBenchmarkScene(std::size_t count, int shDegree, unsigned seed)
{
  GaussianCloud c;
  c.Resize(count, shDegree);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::normal_distribution<float> nrm(0.0f, 1.0f);
  const float base =
    static_cast<float>(std::log(0.02 / std::sqrt(std::max(1.0, static_cast<double>(count) / 1e5))));
  const int K = c.ShCoefficientCount();
  for (std::size_t i = 0; i < count; ++i)
  {
    const float kind = u(rng);
    float p[3], ls[3];
    float q[4] = { 1, 0, 0, 0 };
    if (kind < 0.60f)
    {
      // On the unit sphere; flat along the normal: rotate z onto the normal.
      float n[3] = { nrm(rng), nrm(rng), nrm(rng) };
      const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) + 1e-12f;
      for (auto& v : n)
      {
        v /= len;
      }
      for (int k = 0; k < 3; ++k)
      {
        p[k] = n[k];
      }
      // Quaternion taking (0,0,1) to n: (1 + n.z, -n.y, n.x, 0) normalised.
      q[0] = 1.0f + n[2];
      q[1] = -n[1];
      q[2] = n[0];
      q[3] = 0.0f;
      if (q[0] < 1e-4f)
      {
        q[0] = 0;
        q[1] = 1;
        q[2] = 0;
      }
      ls[0] = base + 0.4f * nrm(rng);
      ls[1] = base + 0.4f * nrm(rng);
      ls[2] = base - 1.5f;
    }
    else if (kind < 0.95f)
    {
      // Ground disk of radius 2.5 at y = 1, flat along y.
      const float r = 2.5f * std::sqrt(u(rng)), a = 6.2831853f * u(rng);
      p[0] = r * std::cos(a);
      p[1] = 1.0f;
      p[2] = r * std::sin(a);
      q[0] = 0.7071068f;
      q[1] = 0.7071068f; // z onto y
      ls[0] = base + 0.6f + 0.4f * nrm(rng);
      ls[1] = base + 0.6f + 0.4f * nrm(rng);
      ls[2] = base - 1.0f;
    }
    else
    {
      for (auto& v : p)
      {
        v = 4.0f * u(rng) - 2.0f;
      }
      const float s = base + 0.5f + 0.5f * nrm(rng);
      ls[0] = ls[1] = ls[2] = s;
    }
    for (int k = 0; k < 3; ++k)
    {
      c.Positions[3 * i + k] = p[k];
      c.LogScales[3 * i + k] = ls[k];
    }
    for (int k = 0; k < 4; ++k)
    {
      c.Rotations[4 * i + k] = q[k];
    }
    c.OpacityLogits[i] = Logit(0.05f + 0.94f * u(rng));
    // DC colour from position (smooth), higher orders small random.
    for (int ch = 0; ch < 3; ++ch)
    {
      const float col = 0.5f + 0.4f * std::sin(2.0f * p[ch] + 1.3f * ch);
      c.SH[3 * static_cast<std::size_t>(K) * i + ch] = (col - 0.5f) / static_cast<float>(sh::C0);
    }
    for (int k = 1; k < K; ++k)
    {
      for (int ch = 0; ch < 3; ++ch)
      {
        c.SH[3 * static_cast<std::size_t>(K) * i + 3 * k + ch] = 0.1f * nrm(rng);
      }
    }
  }
  return c;
}

//------------------------------------------------------------------------------
Camera MakeBenchmarkCamera(int width, int height, double azimuth)
{
  Camera c;
  c.Name = "synthetic";
  c.Width = width;
  c.Height = height;
  const double tanHalf = std::tan(30.0 * 3.14159265358979323846 / 180.0);
  c.Fy = height / (2.0 * tanHalf);
  c.Fx = c.Fy;
  c.Cx = width / 2.0;
  c.Cy = height / 2.0;
  // Camera at distance 3.5 on the -z side rotated by azimuth about y, raised a little
  // (towards -y, which is "up" in the camera's y-down frame), looking at the origin.
  const double el = -0.35;
  const double pos[3] = { -3.5 * std::sin(azimuth) * std::cos(el),
    3.5 * std::sin(el),
    -3.5 * std::cos(azimuth) * std::cos(el) };
  double f[3] = { -pos[0], -pos[1], -pos[2] };
  const double fl = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
  for (auto& v : f)
  {
    v /= fl;
  }
  // Camera y (down) is world +y projected orthogonally to f.
  double down[3] = { 0, 1, 0 };
  const double dd = down[0] * f[0] + down[1] * f[1] + down[2] * f[2];
  for (int k = 0; k < 3; ++k)
  {
    down[k] -= dd * f[k];
  }
  const double dl = std::sqrt(down[0] * down[0] + down[1] * down[1] + down[2] * down[2]);
  for (auto& v : down)
  {
    v /= dl;
  }
  // right = down x forward (x = y cross z for a right-handed frame).
  const double right[3] = { down[1] * f[2] - down[2] * f[1],
    down[2] * f[0] - down[0] * f[2],
    down[0] * f[1] - down[1] * f[0] };
  const double* rows[3] = { right, down, f };
  for (int r = 0; r < 3; ++r)
  {
    for (int k = 0; k < 3; ++k)
    {
      c.WorldToCamera[4 * r + k] = rows[r][k];
    }
    c.WorldToCamera[4 * r + 3] = -(rows[r][0] * pos[0] + rows[r][1] * pos[1] + rows[r][2] * pos[2]);
  }
  return c;
}

} // namespace vis4gs

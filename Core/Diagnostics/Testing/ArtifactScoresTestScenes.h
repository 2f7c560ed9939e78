// SPDX-License-Identifier: BSD-3-Clause
// Small scenes shared by the score tests (TestArtifactScores.cxx, TestArtifactScorePartials.cxx):
// a camera looking down +z (or -z), a Gaussian set by its parameters, and training images that
// are the scene's own render plus a constant per view.
#ifndef vis4gs_ArtifactScoresTestScenes_h
#define vis4gs_ArtifactScoresTestScenes_h

#include "ArtifactScores.h"

#include <cstddef>
#include <vector>

namespace vis4gs_test
{

using vis4gs::Camera;
using vis4gs::GaussianCloud;

inline Camera MakeCamera(double cz = 0, bool flipped = false, int w = 64, int h = 48)
{
  Camera c;
  c.Name = "view";
  c.Width = w;
  c.Height = h;
  c.Fx = c.Fy = 60;
  c.Cx = w / 2.0;
  c.Cy = h / 2.0;
  // flipped: looking down -z from (0, 0, cz): R = diag(-1, 1, -1), t = -R C.
  const double s = flipped ? -1 : 1;
  c.WorldToCamera = { s, 0, 0, 0, 0, 1, 0, 0, 0, 0, s, -s * cz, 0, 0, 0, 1 };
  return c;
}

inline void SetGaussian(GaussianCloud& cloud,
  std::size_t i,
  float x,
  float y,
  float z,
  float ls0,
  float ls1,
  float ls2,
  float logit)
{
  const float p[3] = { x, y, z };
  const float ls[3] = { ls0, ls1, ls2 };
  for (int k = 0; k < 3; ++k)
  {
    cloud.Positions[3 * i + k] = p[k];
    cloud.LogScales[3 * i + k] = ls[k];
    cloud.SH[3 * i + k] = 0.3f * static_cast<float>(k) - 0.2f;
  }
  cloud.Rotations[4 * i + 0] = 1;
  cloud.Rotations[4 * i + 1] = 0;
  cloud.Rotations[4 * i + 2] = 0;
  cloud.Rotations[4 * i + 3] = 0;
  cloud.OpacityLogits[i] = logit;
}

// Images = the scene's own render + a constant offset per view, so that the loss map is
// 0.8 * offset everywhere (the Laplacian of a constant is 0) whatever the render is.
struct OffsetImages
{
  const GaussianCloud* Cloud;
  std::vector<float> Offsets;
  std::vector<bool> Missing;
  bool operator()(std::size_t index, const Camera& camera, vis4gs::Image& image) const
  {
    if (index < this->Missing.size() && this->Missing[index])
    {
      return false;
    }
    const auto render = vis4gs::Rasterize<float>(*this->Cloud, camera);
    image.Width = camera.Width;
    image.Height = camera.Height;
    image.Channels = 3;
    image.Pixels = render.Color;
    for (float& v : image.Pixels)
    {
      v += this->Offsets[index];
    }
    return true;
  }
};

} // namespace vis4gs_test

#endif

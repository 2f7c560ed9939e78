// SPDX-License-Identifier: BSD-3-Clause
// A planted clean-up case for the fine-tune tests (issue 20; Core's TestFineTune and the
// filter's TestGaussianFineTuneFilter): what to delete and what a repair must learn are known.
#ifndef vis4gs_PlantedWallScene_h
#define vis4gs_PlantedWallScene_h

#include "RemovalEffect.h"

#include "../../Render/Testing/RasterTestUtils.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace vis4gs
{
namespace plantedwall
{
struct PlantedScene
{
  GaussianCloud Cloud;
  std::vector<Camera> Cameras;
  std::vector<Image> Targets;
  std::size_t Floater = 0;
  /// One byte per Gaussian: 1 for the floater.
  std::vector<std::uint8_t> FloaterMask() const
  {
    std::vector<std::uint8_t> mask(this->Cloud.Count, 0);
    mask[this->Floater] = 1;
    return mask;
  }
};

// A wall of 8 x 5 Gaussians at z = 5 seen by two training cameras and one test camera, and a
// green floater at z = 1 in front of training camera A only. The targets are the wall alone with
// every colour 0.15 brighter in red and 0.1 darker in blue (what a fine-tune must learn).
inline PlantedScene MakePlantedScene()
{
  PlantedScene s;
  const int nx = 8, ny = 5;
  GaussianCloud target;
  s.Cloud.Resize(nx * ny + 1, 0);
  target.Resize(nx * ny, 0);
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      const std::size_t g = static_cast<std::size_t>(j * nx + i);
      const float x = -2.5f + 0.75f * static_cast<float>(i), y = -2.0f + 0.9f * j;
      const std::array<float, 3> rgb{
        0.2f + 0.05f * static_cast<float>(i % 4), 0.5f, 0.4f + 0.1f * static_cast<float>(j % 3)
      };
      for (GaussianCloud* c : { &s.Cloud, &target })
      {
        const bool t = c == &target;
        rastertest::SetGaussian(*c,
          g,
          { x, y, 5.0f },
          { std::log(0.45f), std::log(0.45f), std::log(0.05f) },
          { 1, 0, 0, 0 },
          4.0f,
          { rgb[0] + (t ? 0.15f : 0.0f), rgb[1], rgb[2] - (t ? 0.1f : 0.0f) });
      }
    }
  }
  s.Floater = static_cast<std::size_t>(nx * ny);
  rastertest::SetGaussian(s.Cloud,
    s.Floater,
    { 0.0f, 0.0f, 1.0f },
    { std::log(0.05f), std::log(0.05f), std::log(0.05f) },
    { 1, 0, 0, 0 },
    3.0f,
    { 0.1f, 0.9f, 0.1f });
  // Ids as a log's snapshot holds them: strictly increasing, not the row numbers.
  for (std::size_t i = 0; i < s.Cloud.Count; ++i)
  {
    s.Cloud.Ids.push_back(static_cast<std::int64_t>(7 + 3 * i));
  }
  Camera a = rastertest::LookAt(64, 48, 40, 40, { 0, 0, 0 }, { 0, 0, 5 });
  a.Name = "A";
  Camera c = rastertest::LookAt(64, 48, 40, 40, { -1.5, 0.3, 0 }, { -1.5, 0.3, 5 });
  c.Name = "C";
  Camera b = rastertest::LookAt(64, 48, 40, 40, { 1, -0.4, 0 }, { 1, -0.4, 5 });
  b.Name = "B";
  b.Split = CameraSplit::Test;
  s.Cameras = { a, c, b };
  for (const Camera& cam : s.Cameras)
  {
    s.Targets.push_back(ClampedImage(Rasterize<float>(target, cam)));
  }
  return s;
}

inline TrainingImageProvider Provider(const std::vector<Image>& targets)
{
  return [&targets](std::size_t index, const Camera&, Image& image)
  {
    image = targets[index];
    return true;
  };
}

} // namespace plantedwall
} // namespace vis4gs

#endif

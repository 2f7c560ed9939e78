// SPDX-License-Identifier: BSD-3-Clause
#include "Camera.h"

namespace vis4gs
{

//------------------------------------------------------------------------------
std::array<double, 3> Camera::Center() const
{
  const auto& m = this->WorldToCamera;
  std::array<double, 3> c{};
  for (int i = 0; i < 3; ++i)
  {
    // -R^T t: column i of R dotted with t.
    c[i] = -(m[0 * 4 + i] * m[3] + m[1 * 4 + i] * m[7] + m[2 * 4 + i] * m[11]);
  }
  return c;
}

//------------------------------------------------------------------------------
Camera Camera::Resized(int width, int height) const
{
  Camera r = *this;
  r.Fx = this->Fx * width / static_cast<double>(this->Width);
  r.Fy = this->Fy * height / static_cast<double>(this->Height);
  r.Cx = this->Cx * width / static_cast<double>(this->Width);
  r.Cy = this->Cy * height / static_cast<double>(this->Height);
  r.Width = width;
  r.Height = height;
  return r;
}

} // namespace vis4gs

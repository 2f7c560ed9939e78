//VTK::System::Dec
// SPDX-License-Identifier: BSD-3-Clause
layout(points) in;
layout(triangle_strip, max_vertices = 4) out;
uniform vec2 imageSize;
flat in vec4 gConic[];
flat in vec3 gColor[];
flat in vec2 gCenter[];
flat in vec4 gRect[];
flat in float gDepth[];
flat in int gValid[];
flat out vec4 fConic;
flat out vec3 fColor;
flat out vec2 fCenter;
void corner(float px, float py)
{
  // Reference pixel (column px, row py from the top) edge -> OpenGL NDC.
  fConic = gConic[0];
  fColor = gColor[0];
  fCenter = gCenter[0];
  gl_Position = vec4(2.0 * px / imageSize.x - 1.0, 1.0 - 2.0 * py / imageSize.y, gDepth[0], 1.0);
  EmitVertex();
}
void main()
{
  if (gValid[0] == 0) { return; }
  vec4 r = gRect[0];
  corner(r.x, r.y);
  corner(r.z + 1.0, r.y);
  corner(r.x, r.w + 1.0);
  corner(r.z + 1.0, r.w + 1.0);
  EndPrimitive();
}

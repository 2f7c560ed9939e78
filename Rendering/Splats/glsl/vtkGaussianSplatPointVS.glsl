// SPDX-License-Identifier: BSD-3-Clause
// Geometry-shader path: one point per Gaussian (gl_VertexID = draw position), expanded by
// SplatGS.
flat out vec4 gConic;
flat out vec3 gColor;
flat out vec2 gCenter;
flat out vec4 gRect;
flat out float gDepth;
flat out int gValid;
void main()
{
  vec4 conic; vec3 color; vec2 center; vec4 rect; float depth;
  gValid = projectSplat(gl_VertexID, conic, color, center, rect, depth) ? 1 : 0;
  gConic = conic;
  gColor = color;
  gCenter = center;
  gRect = rect;
  gDepth = depth;
  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}

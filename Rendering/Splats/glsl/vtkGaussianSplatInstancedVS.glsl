// SPDX-License-Identifier: BSD-3-Clause
// Instanced path: one instance per Gaussian and a 4-vertex strip per instance (no geometry
// shader): each of the 4 vertices repeats the projection.
flat out vec4 fConic;
flat out vec3 fColor;
flat out vec2 fCenter;
void main()
{
  vec4 conic; vec3 color; vec2 center; vec4 rect; float depth;
  bool valid = projectSplat(gl_InstanceID, conic, color, center, rect, depth);
  fConic = conic;
  fColor = color;
  fCenter = center;
  gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // outside the clip volume: culled
  if (!valid) { return; }
  // Corner gl_VertexID of the triangle strip: bit 0 picks the column edge, bit 1 the row edge.
  float px = (gl_VertexID & 1) == 0 ? rect.x : rect.z + 1.0;
  float py = (gl_VertexID & 2) == 0 ? rect.y : rect.w + 1.0;
  gl_Position = vec4(2.0 * px / imageSize.x - 1.0, 1.0 - 2.0 * py / imageSize.y, depth, 1.0);
}

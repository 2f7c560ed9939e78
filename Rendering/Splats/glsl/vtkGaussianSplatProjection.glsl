// SPDX-License-Identifier: BSD-3-Clause
// The per-Gaussian projection both OpenGL paths share: everything is fetched from texture
// buffers; mirrors the reference's preprocessCUDA in float (reference §2.3). Returns false for
// a culled Gaussian.
uniform samplerBuffer splatGeometry; // 3 RGBA texels per Gaussian
uniform samplerBuffer splatColor;    // rgb (or what to do to the SH colour), opacity scale
uniform usamplerBuffer splatOrder;   // draw position -> Gaussian index
// SH colours evaluated here (reference §2.4, ShColor in Core/Scene/GaussianMath.h, same
// operation order in float) from the coefficients uploaded once: the input's SH array as
// RGBA texels, shStride floats per Gaussian (3 (degree + 1)^2 of the input's degree).
uniform samplerBuffer splatSH;
uniform int trueColor;      // 1: SH colours, splatColor.r says what to do to them; 0: splatColor.rgb
uniform int shDegree;       // the degree evaluated (<= the input's)
uniform int shStride;
uniform float shC[14];      // C0, C1, C2[5], C3[7] of the reference
uniform vec3 cameraCenter;  // in the frame of the means
uniform vec3 highlightColor;
uniform float highlightMix;
uniform float dimDesaturation;
uniform vec4 viewRow0;
uniform vec4 viewRow1;
uniform vec4 viewRow2;
uniform vec2 focal;
uniform vec2 tanFov;
uniform vec2 imageSize;
uniform vec2 depthCoeffs;
vec3 shColor(int idx, vec3 mu)
{
  vec3 d = mu - cameraCenter;
  float len = sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  d = len > 0.0 ? d / len : vec3(0.0);
  // The coefficients of Gaussian idx: floats base .. base + 3 k - 1 of the buffer.
  float f[52];
  int k = (shDegree + 1) * (shDegree + 1);
  int base = idx * shStride;
  int first = base / 4;
  int off = base - 4 * first;
  int texels = (off + 3 * k + 3) / 4;
  for (int j = 0; j < texels; ++j)
  {
    vec4 v = texelFetch(splatSH, first + j);
    f[4 * j] = v.x;
    f[4 * j + 1] = v.y;
    f[4 * j + 2] = v.z;
    f[4 * j + 3] = v.w;
  }
#define SH(i) vec3(f[off + 3 * (i)], f[off + 3 * (i) + 1], f[off + 3 * (i) + 2])
  vec3 r = shC[0] * SH(0);
  if (shDegree > 0)
  {
    float x = d.x, y = d.y, z = d.z;
    r = r - shC[1] * y * SH(1) + shC[1] * z * SH(2) - shC[1] * x * SH(3);
    if (shDegree > 1)
    {
      float xx = x * x, yy = y * y, zz = z * z;
      float xy = x * y, yz = y * z, xz = x * z;
      r = r + shC[2] * xy * SH(4) + shC[3] * yz * SH(5) + shC[4] * (2.0 * zz - xx - yy) * SH(6) +
        shC[5] * xz * SH(7) + shC[6] * (xx - yy) * SH(8);
      if (shDegree > 2)
      {
        r = r + shC[7] * y * (3.0 * xx - yy) * SH(9) + shC[8] * xy * z * SH(10) +
          shC[9] * y * (4.0 * zz - xx - yy) * SH(11) +
          shC[10] * z * (2.0 * zz - 3.0 * xx - 3.0 * yy) * SH(12) +
          shC[11] * x * (4.0 * zz - xx - yy) * SH(13) + shC[12] * z * (xx - yy) * SH(14) +
          shC[13] * x * (xx - 3.0 * yy) * SH(15);
      }
    }
  }
#undef SH
  return max(r + 0.5, vec3(0.0));
}

// The colour drawn: SplatAttributes' display colour, with the true colour from the SH here and
// the highlight or dimming (SplatDisplayHighlighted = 1, SplatDisplayDimmed = 2) applied to it
// as ComputeSplatDisplay does.
vec3 displayColor(int idx, vec3 mu, vec4 col)
{
  if (trueColor == 0) { return col.rgb; }
  vec3 c = shColor(idx, mu);
  if (col.r == 1.0)
  {
    c = c + highlightMix * (highlightColor - c);
  }
  else if (col.r == 2.0)
  {
    float grey = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
    c = c + dimDesaturation * (vec3(grey) - c);
  }
  return c;
}

// conic: A, B, C, opacity; center: reference pixel coordinates; rect: pixel columns/rows
// x0, y0, x1, y1 (inclusive), reference convention; depth: NDC z.
bool projectSplat(int drawIndex, out vec4 conic, out vec3 color, out vec2 center, out vec4 rect,
  out float depth)
{
  conic = vec4(0.0);
  color = vec3(0.0);
  center = vec2(0.0);
  rect = vec4(0.0);
  depth = 0.0;
  int idx = int(texelFetch(splatOrder, drawIndex).r);
  vec4 t0 = texelFetch(splatGeometry, 3 * idx);
  vec4 t1 = texelFetch(splatGeometry, 3 * idx + 1);
  vec4 t2 = texelFetch(splatGeometry, 3 * idx + 2);
  if (t2.z < 0.5) { return false; }
  vec3 mu = t0.xyz;
  vec4 col = texelFetch(splatColor, idx);
  float opacity = t0.w * col.w;
  vec3 t = vec3(dot(viewRow0.xyz, mu) + viewRow0.w, dot(viewRow1.xyz, mu) + viewRow1.w,
    dot(viewRow2.xyz, mu) + viewRow2.w);
  if (!(t.z > 0.2)) { return false; }
  mat3 Sigma = mat3(t1.x, t1.y, t1.z, t1.y, t1.w, t2.x, t1.z, t2.x, t2.y);
  float limx = 1.3 * tanFov.x;
  float limy = 1.3 * tanFov.y;
  float tx = clamp(t.x / t.z, -limx, limx) * t.z;
  float ty = clamp(t.y / t.z, -limy, limy) * t.z;
  float J00 = focal.x / t.z;
  float J02 = -(focal.x * tx) / (t.z * t.z);
  float J11 = focal.y / t.z;
  float J12 = -(focal.y * ty) / (t.z * t.z);
  vec3 T0 = J00 * viewRow0.xyz + J02 * viewRow2.xyz;
  vec3 T1 = J11 * viewRow1.xyz + J12 * viewRow2.xyz;
  vec3 S0 = Sigma * T0;
  vec3 S1 = Sigma * T1;
  float a = dot(T0, S0) + 0.3;
  float b = dot(T0, S1);
  float c = dot(T1, S1) + 0.3;
  float det = a * c - b * b;
  if (det == 0.0 || isnan(det) || isinf(det) || isinf(a) || isinf(c) || isnan(b)) { return false; }
  float A = c / det;
  float B = -b / det;
  float C = a / det;
  float mid = 0.5 * (a + c);
  float root = sqrt(max(0.1, mid * mid - det));
  float radius = ceil(3.0 * sqrt(max(mid + root, mid - root)));
  // ndc2Pix of the reference: ndc = x / (tan * (z + 1e-7)).
  float ndcX = (t.x / tanFov.x) * (1.0 / (t.z + 0.0000001));
  float ndcY = (t.y / tanFov.y) * (1.0 / (t.z + 0.0000001));
  float u = ((ndcX + 1.0) * imageSize.x - 1.0) * 0.5;
  float v = ((ndcY + 1.0) * imageSize.y - 1.0) * 0.5;
  if (isinf(radius) || isnan(u) || isnan(v) || isinf(u) || isinf(v)) { return false; }
  // Tile rectangle (reference getRect), in tiles, max exclusive.
  vec2 grid = ceil(imageSize / 16.0);
  float rx0 = clamp(float(int((u - radius) / 16.0)), 0.0, grid.x);
  float ry0 = clamp(float(int((v - radius) / 16.0)), 0.0, grid.y);
  float rx1 = clamp(float(int((u + radius + 15.0) / 16.0)), 0.0, grid.x);
  float ry1 = clamp(float(int((v + radius + 15.0) / 16.0)), 0.0, grid.y);
  if ((rx1 - rx0) * (ry1 - ry0) == 0.0) { return false; }
  // Where alpha can reach 1/255: o e^power >= 1/255 <=> r^2 <= 2 ln(255 o).
  float omax = min(opacity, 1.0);
  if (!(255.0 * omax >= 1.0)) { return false; }
  float r2 = 2.0 * log(255.0 * omax);
  float hx = sqrt(r2 * a) + 1.0;
  float hy = sqrt(r2 * c) + 1.0;
  float x0 = max(rx0 * 16.0, floor(u - hx));
  float y0 = max(ry0 * 16.0, floor(v - hy));
  float x1 = min(min(rx1 * 16.0, imageSize.x) - 1.0, ceil(u + hx));
  float y1 = min(min(ry1 * 16.0, imageSize.y) - 1.0, ceil(v + hy));
  if (x1 < x0 || y1 < y0) { return false; }
  conic = vec4(A, B, C, opacity);
  color = displayColor(idx, mu, col);
  center = vec2(u, v);
  rect = vec4(x0, y0, x1, y1);
  float zc = (depthCoeffs.x * (-t.z) + depthCoeffs.y) / t.z;
  depth = clamp(zc, -0.999999, 0.999999);
  return true;
}

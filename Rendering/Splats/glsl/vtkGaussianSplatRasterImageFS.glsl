//VTK::System::Dec
// SPDX-License-Identifier: BSD-3-Clause
// CPU-rasteriser path: the rasterised image (premultiplied RGB, alpha; row 0 at the bottom)
// and the expected view depth per pixel, drawn over the viewport. depthPass 0 blends the
// colour depth-tested at the expected depth; depthPass 1 writes that depth where alpha >= 0.5.
//VTK::Output::Dec
in vec2 texCoord;
uniform sampler2D splatImage;
uniform sampler2D splatDepth;
uniform vec2 depthCoeffs;
uniform int depthPass;
void main()
{
  vec4 c = texture(splatImage, texCoord);
  float z = texture(splatDepth, texCoord).r;
  float zc = (depthCoeffs.x * (-z) + depthCoeffs.y) / z;
  gl_FragDepth = clamp(0.5 * zc + 0.5, 0.0, 1.0);
  if (c.a <= 0.0 || (depthPass == 1 && c.a < 0.5)) { discard; }
  gl_FragData[0] = c;
}

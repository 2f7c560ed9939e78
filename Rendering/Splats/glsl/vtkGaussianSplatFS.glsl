//VTK::System::Dec
// SPDX-License-Identifier: BSD-3-Clause
//VTK::Output::Dec
uniform vec4 viewportRect; // x, y origin and width, height of the renderer in the window
flat in vec4 fConic;
flat in vec3 fColor;
flat in vec2 fCenter;
void main()
{
  float px = gl_FragCoord.x - 0.5 - viewportRect.x;
  float py = viewportRect.w - 0.5 - (gl_FragCoord.y - viewportRect.y);
  float dx = fCenter.x - px;
  float dy = fCenter.y - py;
  float power = -0.5 * (fConic.x * dx * dx + fConic.z * dy * dy) - fConic.y * dx * dy;
  if (power > 0.0) { discard; }
  float alpha = min(0.99, fConic.w * exp(power));
  if (alpha < 1.0 / 255.0) { discard; }
  gl_FragData[0] = vec4(fColor * alpha, alpha);
}

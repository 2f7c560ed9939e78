// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatAttributes.h
 * @brief Per-Gaussian inputs of the GPU splat renderer, computed on the CPU: packed geometry
 * (mean, opacity, 3D covariance), SH colours for a camera position, the viridis colour map,
 * and the display colours of the overlay, highlight and dimming modes.
 *
 * The geometry is packed in the layout the shaders read from a texture buffer, three RGBA
 * texels per Gaussian:
 *
 *   texel 0: x, y, z, opacity (sigmoid of the logit)
 *   texel 1: Sxx, Sxy, Sxz, Syy
 *   texel 2: Syz, Szz, valid (1 or 0), 0
 *
 * The covariance R diag((m s)^2) R^T is computed in float with the operation order of the
 * Core rasteriser (RasterProjection.cxx), so both start from the same numbers. "valid" is 0 for a
 * Gaussian with a NaN/Inf parameter or a covariance that overflows float (the rasteriser's
 * InvalidParameters and NonFinite cases); such Gaussians are never drawn.
 */
#ifndef vis4gs_SplatAttributes_h
#define vis4gs_SplatAttributes_h

#include "GaussianCloud.h"
#include "ScoreRegistry.h" // SuspiciousEnd

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vis4gs
{

/// Floats per Gaussian in the packed geometry (three RGBA texels).
constexpr int SplatGeometryFloats = 12;

/**
 * Fills @p packed with SplatGeometryFloats floats per Gaussian (layout above).
 * @p scaleModifier multiplies every scale (the reference's scale_modifier). Throws
 * std::invalid_argument when the cloud's arrays do not match its Count.
 */
void PackSplatGeometry(const GaussianCloud& cloud,
  double scaleModifier,
  std::vector<float>& packed,
  int threads = 0);

/**
 * SH colour of every Gaussian seen from @p cameraCenter (reference §2.4, in float):
 * sum_k Y_k(d) f_k + 0.5 with d the unit direction from the camera to the mean, clamped at 0
 * per channel, no upper clamp. 3 floats per Gaussian. @p shDegree < 0 uses the cloud's
 * degree; larger values are clamped to it. A Gaussian whose mean coincides with the camera
 * centre gets d = 0 (only the DC term). NaN/Inf coefficients give NaN colours (such
 * Gaussians are invalid in the packed geometry anyway). Throws std::invalid_argument when SH
 * does not match the cloud's count and degree.
 */
void EvaluateSplatColors(const GaussianCloud& cloud,
  const std::array<double, 3>& cameraCenter,
  int shDegree,
  std::vector<float>& rgb,
  int threads = 0);

/// The viridis colour map (matplotlib's, CC0) at @p t in [0, 1] (clamped), linear
/// interpolation between 17 samples of the 256-entry table (max error < 0.004 per channel).
std::array<float, 3> Viridis(double t);

// SuspiciousEnd and SuspiciousEndOf(): Core/Diagnostics/ScoreRegistry.h, the list of scores.

/**
 * Overlay colour of @p value over [@p lo, @p hi]: viridis, turned so that its bright (yellow)
 * end is the suspicious end of the score, which then stands out against the black background
 * of the scene view and the overlay images (DESIGN §7); SuspiciousEnd::None and High keep
 * viridis' direction (lo dark, hi bright). Values outside the range are clamped; NaN maps to
 * lo; hi <= lo maps everything at or above lo to the hi end. The one colour map of every
 * overlay (scene view, legend, `vis4gs analyze` images and histograms).
 */
std::array<float, 3> OverlayColor(double value, double lo, double hi, SuspiciousEnd end);

/// How ComputeSplatDisplay() colours the splats.
struct SplatDisplayOptions
{
  /// Colour by a scalar score through viridis instead of the true (SH) colour. Default off.
  bool ScoreColoring = false;
  /// One score per Gaussian (needed when ScoreColoring or HideOutsideRange is on).
  const double* Scores = nullptr;
  /// Scores mapped to the ends of the colour map. Default [0, 1].
  std::array<double, 2> ColorRange{ 0.0, 1.0 };
  /// The score's suspicious end, drawn bright (OverlayColor()). Default None (lo dark).
  SuspiciousEnd Suspicious = SuspiciousEnd::None;
  /// Hide Gaussians whose score is outside VisibleRange (or NaN). Default off.
  bool HideOutsideRange = false;
  /// Inclusive range of the scores shown when HideOutsideRange is on. Default [0, 1].
  std::array<double, 2> VisibleRange{ 0.0, 1.0 };
  /// Colour of a NaN score (when not hidden). Default mid grey.
  std::array<float, 3> NanColor{ 0.5f, 0.5f, 0.5f };
  /// One byte per Gaussian, non-zero = selected; nullptr = nothing selected. Default none.
  const std::uint8_t* Selected = nullptr;
  /// Mix selected Gaussians' colours towards HighlightColor by HighlightMix. Default on.
  bool Highlight = true;
  std::array<float, 3> HighlightColor{ 1.0f, 0.35f, 0.0f };
  float HighlightMix = 0.7f;
  /// Dim every unselected Gaussian: opacity times DimOpacity, colour mixed towards its grey
  /// luminance by DimDesaturation. Default off.
  bool DimUnselected = false;
  float DimOpacity = 0.15f;
  float DimDesaturation = 0.8f;
  /// The true colours are evaluated later, per view (the OpenGL path's shader evaluates the
  /// SH): instead of a colour, the first float of each Gaussian's rgba says what to do to its
  /// true colour (SplatDisplayUnchanged, SplatDisplayHighlighted or SplatDisplayDimmed, with
  /// HighlightColor, HighlightMix and DimDesaturation as above), the next two are 0; the
  /// opacity multiplier and keep are as usual. No effect with ScoreColoring. Default off.
  bool DeferTrueColor = false;
};

/// What DeferTrueColor asks to do to a true colour (its first float).
constexpr float SplatDisplayUnchanged = 0.0f;
constexpr float SplatDisplayHighlighted = 1.0f;
constexpr float SplatDisplayDimmed = 2.0f;

/**
 * Display colour of each of @p count Gaussians: @p rgba gets 4 floats per Gaussian (colour,
 * opacity multiplier), @p keep one byte (0 = hidden, never drawn). @p trueColors (3 per
 * Gaussian) is used unless ScoreColoring or DeferTrueColor is on. Throws std::invalid_argument when
 * a needed array is missing.
 */
void ComputeSplatDisplay(const float* trueColors,
  std::size_t count,
  const SplatDisplayOptions& options,
  std::vector<float>& rgba,
  std::vector<std::uint8_t>& keep,
  int threads = 0);

} // namespace vis4gs

#endif

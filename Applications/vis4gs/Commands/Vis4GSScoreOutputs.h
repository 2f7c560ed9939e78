// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSScoreOutputs.h
 * @brief What `vis4gs analyze` writes per Gaussian, fast at Bicycle's size (issue 31): the
 * scores table (rows formatted on every core, written in large blocks) and the score overlays
 * (one projection per view shared by every score's colouring).
 */
#ifndef Vis4GSScoreOutputs_h
#define Vis4GSScoreOutputs_h

#include "Camera.h"
#include "GaussianCloud.h"
#include "ImageIO.h"

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

/**
 * Writes scores.csv to @p path: a header, then one row per Gaussian: its id, each score
 * column with 9 significant digits (printf's "%.9g": what an ostream with setprecision(9)
 * writes) and, when @p flags is not null, the NoVisibleView flag. Throws std::runtime_error
 * naming @p shownPath when the file cannot be written.
 */
void Vis4GSWriteScoresCsv(const std::filesystem::path& path,
  const std::string& shownPath,
  const vis4gs::GaussianCloud& cloud,
  const std::vector<std::pair<std::string, std::vector<double>>>& scores,
  const std::vector<unsigned char>* flags);

/// The upper end of an overlay's colour map: 1 for a score in [0, 1], else the 99th percentile
/// of the finite values (at least 1e-30), 1 when there is none.
double Vis4GSOverlayUpperEnd(const std::vector<double>& values, bool unitRange);

/// One overlay to draw: a score's array name, values and colour-map upper end.
struct Vis4GSOverlayScore
{
  std::string Name;
  const std::vector<double>* Values = nullptr;
  double Upper = 1;
};

/**
 * Renders each score of @p scores in the first @p views training views of @p cameras (colours
 * replaced by vis4gs::OverlayColor of the score, its suspicious end bright on black) and hands
 * every image to @p write with the score's index and the camera's. Each view is projected once
 * for every score (MultiViewRenderer::SetColors); the images are exactly those of
 * Rasterize<float>() on a copy of the cloud with SH degree 0 and those colours, which this
 * needs no copy of.
 */
void Vis4GSRenderOverlays(const vis4gs::GaussianCloud& cloud,
  const std::vector<vis4gs::Camera>& cameras,
  const std::vector<Vis4GSOverlayScore>& scores,
  int views,
  const std::function<void(std::size_t score, std::size_t camera, const vis4gs::Image& image)>&
    write);

#endif

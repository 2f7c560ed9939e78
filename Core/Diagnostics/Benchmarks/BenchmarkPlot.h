// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BenchmarkPlot.h
 * @brief A minimal scatter plot rasterised into an RGB buffer (log-log axes, decade ticks,
 * numbered markers drawn with a 3x5 digit font) for the accuracy-vs-runtime report, written
 * with the Core PNG writer. No dependencies beyond Core/Scene/ImageIO.h.
 */
#ifndef vis4gs_BenchmarkPlot_h
#define vis4gs_BenchmarkPlot_h

#include "ImageIO.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace vis4gs
{
namespace bench
{

struct PlotPoint
{
  double X = 0, Y = 0; ///< data coordinates (both > 0; log axes)
  int Series = 0;      ///< colour index
  std::string Label;   ///< digits, '.', '-', 'e' only
};

class ScatterPlot
{
public:
  ScatterPlot(int width, int height)
    : W(width)
    , H(height)
    , Pixels(static_cast<std::size_t>(width) * height * 3, 255)
  {
  }

  /// Draws @p points on log10 axes covering [xMin, xMax] x [yMin, yMax] (decades).
  void Draw(const std::vector<PlotPoint>& points,
    double xMin,
    double xMax,
    double yMin,
    double yMax)
  {
    const int l = 70, r = this->W - 20, t = 20, b = this->H - 45;
    auto px = [&](double x) { return l + (std::log10(x) - xMin) / (xMax - xMin) * (r - l); };
    auto py = [&](double y) { return b - (std::log10(y) - yMin) / (yMax - yMin) * (b - t); };
    const std::array<unsigned char, 3> grey{ 220, 220, 220 }, black{ 0, 0, 0 };
    for (int d = static_cast<int>(std::ceil(xMin)); d <= static_cast<int>(std::floor(xMax)); ++d)
    {
      const int x = static_cast<int>(px(std::pow(10.0, d)));
      this->Line(x, t, x, b, grey);
      this->Text("1e" + std::to_string(d), x - 8, b + 8, black, 2);
    }
    for (int d = static_cast<int>(std::ceil(yMin)); d <= static_cast<int>(std::floor(yMax)); ++d)
    {
      const int y = static_cast<int>(py(std::pow(10.0, d)));
      this->Line(l, y, r, y, grey);
      this->Text("1e" + std::to_string(d), 8, y - 5, black, 2);
    }
    this->Line(l, b, r, b, black);
    this->Line(l, t, l, b, black);
    static const std::array<unsigned char, 3> colours[4] = {
      { 31, 119, 180 }, { 255, 127, 14 }, { 44, 160, 44 }, { 214, 39, 40 }
    };
    for (const PlotPoint& p : points)
    {
      const int x = static_cast<int>(px(std::max(p.X, std::pow(10.0, xMin))));
      const int y = static_cast<int>(py(std::max(p.Y, std::pow(10.0, yMin))));
      const auto& c = colours[p.Series % 4];
      for (int dy = -4; dy <= 4; ++dy)
      {
        for (int dx = -4; dx <= 4; ++dx)
        {
          if (dx * dx + dy * dy <= 16)
          {
            this->Set(x + dx, y + dy, c);
          }
        }
      }
      this->Text(p.Label, x + 6, y - 12 + 8 * p.Series, c, 2);
    }
  }

  void Write(const std::string& path) const
  {
    WritePng8(path, this->W, this->H, 3, this->Pixels.data());
  }

private:
  void Set(int x, int y, const std::array<unsigned char, 3>& c)
  {
    if (x < 0 || y < 0 || x >= this->W || y >= this->H)
    {
      return;
    }
    unsigned char* p = &this->Pixels[(static_cast<std::size_t>(y) * this->W + x) * 3];
    p[0] = c[0];
    p[1] = c[1];
    p[2] = c[2];
  }

  void Line(int x0, int y0, int x1, int y1, const std::array<unsigned char, 3>& c)
  {
    const int n = std::max(std::abs(x1 - x0), std::abs(y1 - y0));
    for (int i = 0; i <= n; ++i)
    {
      this->Set(x0 + (n ? (x1 - x0) * i / n : 0), y0 + (n ? (y1 - y0) * i / n : 0), c);
    }
  }

  // 3x5 glyphs, one row per 3-bit value (bit 2 = left column).
  static const unsigned char* Glyph(char ch)
  {
    static const unsigned char digits[10][5] = { { 7, 5, 5, 5, 7 },
      { 2, 6, 2, 2, 7 },
      { 7, 1, 7, 4, 7 },
      { 7, 1, 7, 1, 7 },
      { 5, 5, 7, 1, 1 },
      { 7, 4, 7, 1, 7 },
      { 7, 4, 7, 5, 7 },
      { 7, 1, 1, 1, 1 },
      { 7, 5, 7, 5, 7 },
      { 7, 5, 7, 1, 7 } };
    static const unsigned char dot[5] = { 0, 0, 0, 0, 2 };
    static const unsigned char minus[5] = { 0, 0, 7, 0, 0 };
    static const unsigned char e[5] = { 0, 7, 7, 4, 7 };
    static const unsigned char blank[5] = { 0, 0, 0, 0, 0 };
    if (ch >= '0' && ch <= '9')
    {
      return digits[ch - '0'];
    }
    return ch == '.' ? dot : ch == '-' ? minus : ch == 'e' ? e : blank;
  }

  void Text(const std::string& s, int x, int y, const std::array<unsigned char, 3>& c, int scale)
  {
    for (char ch : s)
    {
      const unsigned char* g = Glyph(ch);
      for (int row = 0; row < 5; ++row)
      {
        for (int col = 0; col < 3; ++col)
        {
          if (g[row] & (4 >> col))
          {
            for (int sy = 0; sy < scale; ++sy)
            {
              for (int sx = 0; sx < scale; ++sx)
              {
                this->Set(x + col * scale + sx, y + row * scale + sy, c);
              }
            }
          }
        }
      }
      x += 4 * scale;
    }
  }

  int W, H;
  std::vector<unsigned char> Pixels;
};

} // namespace bench
} // namespace vis4gs

#endif

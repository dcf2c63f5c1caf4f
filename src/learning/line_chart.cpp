// Minimal raster line chart: Bresenham lines on an RGB buffer, tick labels from a 3x5 pixel font, PNG via
// render::write_png.
#include "learning/line_chart.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "clothcd/render/image.hpp"

namespace clothcd::learning {
namespace {

// Rows of 3 bits, top to bottom, for "0123456789.-".
constexpr unsigned char kGlyphs[12][5] = {{7, 5, 5, 5, 7}, {2, 6, 2, 2, 7}, {7, 1, 7, 4, 7}, {7, 1, 7, 1, 7},
                                          {5, 5, 7, 1, 1}, {7, 4, 7, 1, 7}, {7, 4, 7, 5, 7}, {7, 1, 1, 1, 1},
                                          {7, 5, 7, 5, 7}, {7, 5, 7, 1, 7}, {0, 0, 0, 0, 2}, {0, 0, 7, 0, 0}};

class Canvas {
 public:
  Canvas(int width, int height) : width_(width), height_(height), pixels_(static_cast<std::size_t>(width * height * 3), 255) {}

  void plot(int x, int y, const std::array<unsigned char, 3>& rgb) {
    if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
    unsigned char* p = &pixels_[static_cast<std::size_t>((y * width_ + x) * 3)];
    p[0] = rgb[0];
    p[1] = rgb[1];
    p[2] = rgb[2];
  }
  void line(int x0, int y0, int x1, int y1, const std::array<unsigned char, 3>& rgb, int thickness) {
    const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0), sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
    int error = dx + dy;
    for (;;) {
      for (int a = 0; a < thickness; ++a)
        for (int b = 0; b < thickness; ++b) plot(x0 + a - thickness / 2, y0 + b - thickness / 2, rgb);
      if (x0 == x1 && y0 == y1) break;
      const int e2 = 2 * error;
      if (e2 >= dy) error += dy, x0 += sx;
      if (e2 <= dx) error += dx, y0 += sy;
    }
  }
  // Draws text of digits, '.' and '-' with its top-left corner at (x, y), 2 pixels per font pixel.
  void text(int x, int y, const std::string& s) {
    for (const char c : s) {
      const int glyph = c == '.' ? 10 : c == '-' ? 11 : (c >= '0' && c <= '9' ? c - '0' : -1);
      if (glyph >= 0)
        for (int row = 0; row < 5; ++row)
          for (int col = 0; col < 3; ++col)
            if (kGlyphs[glyph][row] & (4 >> col))
              for (int a = 0; a < 2; ++a)
                for (int b = 0; b < 2; ++b) plot(x + 2 * col + a, y + 2 * row + b, {0, 0, 0});
      x += 8;
    }
  }
  void save(const std::string& path) const {
    render::Image image(width_, height_);
    image.rgb = pixels_;
    render::write_png(image, path);
  }

 private:
  int width_, height_;
  std::vector<unsigned char> pixels_;
};

std::string tick_label(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", std::abs(value) < 1e-12 ? 0.0 : value);
  return buffer;
}

void data_range(const std::vector<ChartSeries>& series, bool use_x, double& lo, double& hi) {
  if (lo < hi) return;
  lo = INFINITY;
  hi = -INFINITY;
  for (const ChartSeries& s : series)
    for (const double v : use_x ? s.x : s.y)
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (!(lo <= hi)) lo = 0.0, hi = 1.0;
  if (hi - lo < 1e-300) lo -= 0.5, hi += 0.5;
}

}  // namespace

void write_line_chart_png(const std::string& path, const std::vector<ChartSeries>& series, const ChartSettings& settings) {
  Canvas canvas(settings.width, settings.height);
  double x_min = settings.x_min, x_max = settings.x_max, y_min = settings.y_min, y_max = settings.y_max;
  data_range(series, true, x_min, x_max);
  data_range(series, false, y_min, y_max);
  const int left = 90, right = settings.width - 20, top = 20, bottom = settings.height - 40;
  auto px = [&](double x) { return left + static_cast<int>(std::lround((x - x_min) / (x_max - x_min) * (right - left))); };
  auto py = [&](double y) { return bottom - static_cast<int>(std::lround((y - y_min) / (y_max - y_min) * (bottom - top))); };
  constexpr int kTicks = 5;
  for (int t = 0; t <= kTicks; ++t) {
    const double fx = x_min + (x_max - x_min) * t / kTicks, fy = y_min + (y_max - y_min) * t / kTicks;
    canvas.line(px(fx), top, px(fx), bottom, {225, 225, 225}, 1);
    canvas.line(left, py(fy), right, py(fy), {225, 225, 225}, 1);
    const std::string lx = tick_label(fx), ly = tick_label(fy);
    canvas.text(px(fx) - 4 * static_cast<int>(lx.size()), bottom + 8, lx);
    canvas.text(left - 8 - 8 * static_cast<int>(ly.size()), py(fy) - 5, ly);
  }
  canvas.line(left, bottom, right, bottom, {0, 0, 0}, 1);
  canvas.line(left, top, left, bottom, {0, 0, 0}, 1);
  if (settings.diagonal) canvas.line(px(x_min), py(y_min), px(x_max), py(y_max), {170, 170, 170}, 1);
  for (const ChartSeries& s : series)
    for (std::size_t i = 1; i < std::min(s.x.size(), s.y.size()); ++i)
      if (std::isfinite(s.x[i - 1] + s.y[i - 1] + s.x[i] + s.y[i]))
        canvas.line(px(s.x[i - 1]), py(s.y[i - 1]), px(s.x[i]), py(s.y[i]), s.rgb, 2);
  canvas.save(path);
}

}  // namespace clothcd::learning

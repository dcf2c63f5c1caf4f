#pragma once
// A tiny line-chart drawer for the training curve (the paper's Figure 12) and the ROC curve (Figure 13): axes, grid,
// numeric tick labels in a built-in 3x5 digit font, coloured polylines; written as PNG with stb_image_write.

#include <array>
#include <string>
#include <vector>

namespace clothcd::learning {

/// One polyline of a chart.
struct ChartSeries {
  std::vector<double> x;                     ///< Abscissae.
  std::vector<double> y;                     ///< Ordinates (same size as x).
  std::array<unsigned char, 3> rgb{0, 0, 0};  ///< Line colour.
};

/// Size and ranges of a chart; a range with min >= max is computed from the data.
struct ChartSettings {
  int width = 800;       ///< Pixels.
  int height = 500;      ///< Pixels.
  double x_min = 0.0, x_max = 0.0;
  double y_min = 0.0, y_max = 0.0;
  bool diagonal = false;  ///< Draw the grey chance line y = x (ROC charts).
};

/// Draws the series and writes a PNG; throws std::runtime_error naming the file when it cannot be written.
void write_line_chart_png(const std::string& path, const std::vector<ChartSeries>& series, const ChartSettings& settings);

}  // namespace clothcd::learning

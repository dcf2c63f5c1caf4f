#pragma once
// Line and grouped-bar charts written as SVG (text stays text, the picture scales): a title, axis names with units,
// numeric ticks, category labels under bar groups and a legend naming every series. Used for the training curve and
// ROC of a model (the paper's Figures 12-13) and by the benchmark report.

#include <array>
#include <string>
#include <vector>

namespace clothcd::render {

/// An RGB colour.
using Rgb = std::array<unsigned char, 3>;

/// Colour of series `index`: the Okabe-Ito palette (readable with colour-vision deficiencies), repeating after 7.
[[nodiscard]] Rgb series_color(std::size_t index);

/// The words of a chart.
struct ChartText {
  std::string title;    ///< Above the plot.
  std::string x_label;  ///< Name and unit of the horizontal axis, e.g. "cloth triangles (thousands)".
  std::string y_label;  ///< Name and unit of the vertical axis, e.g. "time per step (ms)".
  std::string note;     ///< Optional line inside the plot's top-left corner, e.g. "AUC 0.9999".
};

/// A value range of an axis; min >= max means "from the data" (with a margin, and 0 included for bar charts).
struct AxisRange {
  double min = 0.0;  ///< Lower end.
  double max = 0.0;  ///< Upper end.
};

/// One polyline of a line chart.
struct LineSeries {
  std::string name;       ///< Legend entry.
  std::vector<double> x;  ///< Abscissae.
  std::vector<double> y;  ///< Ordinates (same size as x); non-finite points are skipped.
};

/// A line chart.
struct LineChart {
  ChartText text;                  ///< Title and axis names.
  std::vector<LineSeries> series;  ///< Coloured by series_color in order; a legend when there are two or more.
  AxisRange x;                     ///< Horizontal range.
  AxisRange y;                     ///< Vertical range.
  bool diagonal = false;           ///< Draw the dashed chance line y = x (ROC charts).
  bool markers = false;            ///< Draw a dot at each point.
};

/// A grouped bar chart: one group per category, one bar per series in each group.
struct BarChart {
  ChartText text;                           ///< Title and axis names (x_label names the categories).
  std::vector<std::string> categories;      ///< Group labels, left to right.
  std::vector<std::string> series;          ///< Bar names within a group (legend), coloured by series_color.
  std::vector<std::vector<double>> values;  ///< values[category][series]; non-finite values draw no bar.
  AxisRange y;                              ///< Vertical range; bars beyond it are clipped.
};

/// Writes `chart` as an SVG file; throws std::runtime_error naming the file when it cannot be written.
void write_line_chart_svg(const std::string& path, const LineChart& chart);

/// Writes `chart` as an SVG file; throws std::runtime_error naming the file when it cannot be written.
void write_bar_chart_svg(const std::string& path, const BarChart& chart);

}  // namespace clothcd::render

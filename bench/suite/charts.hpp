#pragma once
/// @file
/// PNG charts of the benchmark report, drawn with the library's line-chart writer (numeric axes, grid, no text legend:
/// the report names each colour, see series_color_name).

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "learning/line_chart.hpp"

namespace clothcd::bench {

/// Colour of series `index` (Okabe-Ito palette, repeating after 7).
[[nodiscard]] std::array<unsigned char, 3> series_color(std::size_t index);

/// Name of that colour for the report's legend text, e.g. "orange".
[[nodiscard]] std::string series_color_name(std::size_t index);

/// "colour = name" pairs for a chart's legend line: "grey = AABB, orange = AABB-OBB".
[[nodiscard]] std::string legend(const std::vector<std::string>& series_names);

/// A grouped bar chart: `groups[g][s]` is the bar of series s in group g, groups centred at x = 1, 2, ... (left to
/// right), series coloured by series_color(s); y from `y_min` to `y_max` (y_max <= y_min: 0 to 1.1 x the largest bar).
/// Throws std::runtime_error naming the file when it cannot be written.
void write_bar_chart(const std::filesystem::path& path, const std::vector<std::vector<double>>& groups,
                     double y_min = 0.0, double y_max = 0.0);

/// A line chart: one polyline per series (`xs` shared, `series[s][i]` at xs[i]), coloured by series_color(s).
void write_lines_chart(const std::filesystem::path& path, const std::vector<double>& xs,
                       const std::vector<std::vector<double>>& series);

}  // namespace clothcd::bench

// Bar and line charts on top of learning::write_line_chart_png: a bar is a run of adjacent vertical lines.
#include "charts.hpp"

#include <algorithm>
#include <cmath>

namespace clothcd::bench {
namespace {

constexpr std::array<std::array<unsigned char, 3>, 7> kPalette{{{120, 120, 120},
                                                                 {230, 159, 0},
                                                                 {86, 180, 233},
                                                                 {0, 158, 115},
                                                                 {204, 121, 167},
                                                                 {0, 114, 178},
                                                                 {213, 94, 0}}};
constexpr std::array<const char*, 7> kPaletteNames{"grey", "orange", "sky blue", "green", "pink", "blue", "vermillion"};
constexpr int kWidth = 640, kHeight = 320;

}  // namespace

std::array<unsigned char, 3> series_color(std::size_t index) { return kPalette[index % kPalette.size()]; }

std::string series_color_name(std::size_t index) { return kPaletteNames[index % kPaletteNames.size()]; }

std::string legend(const std::vector<std::string>& series_names) {
  std::string text;
  for (std::size_t i = 0; i < series_names.size(); ++i)
    text += (i ? ", " : "") + series_color_name(i) + " = " + series_names[i];
  return text;
}

void write_bar_chart(const std::filesystem::path& path, const std::vector<std::vector<double>>& groups, double y_min,
                     double y_max) {
  learning::ChartSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  // x ticks fall every (x_max / 5): integer group positions get integer ticks.
  settings.x_min = 0.0;
  settings.x_max = 5.0 * std::ceil((static_cast<double>(groups.size()) + 1.0) / 5.0);
  if (y_max <= y_min) {
    y_min = 0.0;
    y_max = 0.0;
    for (const auto& group : groups)
      for (const double v : group)
        if (std::isfinite(v)) y_max = std::max(y_max, 1.1 * v);
    if (y_max <= 0.0) y_max = 1.0;
  }
  settings.y_min = y_min;
  settings.y_max = y_max;
  const double x_per_pixel = settings.x_max / (kWidth - 110);  // plot area of the line chart: 90 px left, 20 right
  std::vector<learning::ChartSeries> lines;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const double bar = 0.8 / static_cast<double>(std::max<std::size_t>(1, groups[g].size()));
    for (std::size_t s = 0; s < groups[g].size(); ++s) {
      const double left = static_cast<double>(g + 1) - 0.4 + bar * static_cast<double>(s);
      const double top = std::clamp(groups[g][s], y_min, y_max);
      if (!std::isfinite(top)) continue;
      for (double x = left + x_per_pixel; x < left + bar - 2 * x_per_pixel; x += 1.5 * x_per_pixel)
        lines.push_back({{x, x}, {y_min, top}, series_color(s)});
    }
  }
  learning::write_line_chart_png(path.string(), lines, settings);
}

void write_lines_chart(const std::filesystem::path& path, const std::vector<double>& xs,
                       const std::vector<std::vector<double>>& series) {
  learning::ChartSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.y_min = 0.0;
  for (const auto& s : series)
    for (const double v : s)
      if (std::isfinite(v)) settings.y_max = std::max(settings.y_max, 1.1 * v);
  std::vector<learning::ChartSeries> lines;
  for (std::size_t s = 0; s < series.size(); ++s) lines.push_back({xs, series[s], series_color(s)});
  learning::write_line_chart_png(path.string(), lines, settings);
}

}  // namespace clothcd::bench

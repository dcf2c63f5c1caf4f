#pragma once
/// @file
/// The report's charts: the library's SVG line and bar charts (render/svg_chart.hpp), each with a title, axis names
/// with units, category labels and a legend, so that a chart reads without the report.

#include "clothcd/render/svg_chart.hpp"

namespace clothcd::bench {

using render::BarChart;
using render::LineChart;
using render::LineSeries;
using render::write_bar_chart_svg;
using render::write_line_chart_svg;

}  // namespace clothcd::bench

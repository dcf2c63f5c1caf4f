// SVG line and bar charts (svg_chart.hpp): plot area, "nice" ticks, labels as text elements, legend on the right.
#include "clothcd/render/svg_chart.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace clothcd::render {
namespace {

constexpr std::array<Rgb, 7> kPalette{{{0, 114, 178},
                                       {230, 159, 0},
                                       {0, 158, 115},
                                       {204, 121, 167},
                                       {86, 180, 233},
                                       {213, 94, 0},
                                       {120, 120, 120}}};
constexpr int kWidth = 760, kHeight = 420;
constexpr int kLeft = 84, kTop = 48, kBottom = 64, kRight = 24, kLegendWidth = 190;

std::string escaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

std::string color(const Rgb& rgb) {
  char text[8];
  std::snprintf(text, sizeof text, "#%02x%02x%02x", rgb[0], rgb[1], rgb[2]);
  return text;
}

std::string number(double value) {
  if (std::abs(value) < 1e-12) value = 0.0;  // no "-0" or "1e-17" at the origin
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

// A tick spacing of 1, 2 or 5 times a power of ten giving about `target` intervals over `span`.
double nice_step(double span, int target) {
  const double raw = span / target;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double r = raw / magnitude;
  return (r < 1.5 ? 1.0 : r < 3.0 ? 2.0 : r < 7.0 ? 5.0 : 10.0) * magnitude;
}

// The axis range: `given` when it is one, else the data's range with a margin (and 0 when `from_zero`), widened to
// whole ticks.
AxisRange resolve(const AxisRange& given, double low, double high, bool from_zero) {
  if (given.min < given.max) return given;
  if (!(low <= high)) low = 0.0, high = 1.0;  // no finite data
  if (from_zero) low = std::min(low, 0.0), high = std::max(high, 0.0);
  if (high - low <= 0.0) {
    const double pad = low == 0.0 ? 1.0 : 0.1 * std::abs(low);
    low -= pad, high += pad;
  }
  const double margin = 0.05 * (high - low);
  if (!(from_zero && low == 0.0)) low -= margin;
  high += margin;
  const double step = nice_step(high - low, 5);
  return {std::floor(low / step) * step, std::ceil(high / step) * step};
}

// Builds the SVG text of one chart: frame, ticks and words first, then the caller's data marks, then the legend.
class SvgChart {
 public:
  SvgChart(const ChartText& text, const AxisRange& y, std::size_t legend_entries)
      : text_(text), y_(y), legend_(legend_entries >= 2) {
    plot_right_ = kWidth - kRight - (legend_ ? kLegendWidth : 0);
    plot_bottom_ = kHeight - kBottom;
    out_ << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << kHeight
         << "\" viewBox=\"0 0 " << kWidth << ' ' << kHeight << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
         << "<title>" << escaped(text.title) << "</title>\n"
         << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
         << "<text class=\"title\" x=\"" << kWidth / 2 << "\" y=\"26\" text-anchor=\"middle\" font-size=\"16\" "
         << "font-weight=\"bold\">" << escaped(text.title) << "</text>\n";
    const double step = nice_step(y.max - y.min, 5);
    for (double v = std::ceil(y.min / step - 1e-9) * step; v <= y.max + 1e-9 * step; v += step) {
      const double py = y_pixel(v);
      out_ << "<line x1=\"" << kLeft << "\" y1=\"" << py << "\" x2=\"" << plot_right_ << "\" y2=\"" << py
           << "\" stroke=\"#dddddd\"/>\n<text x=\"" << kLeft - 6 << "\" y=\"" << py + 4
           << "\" text-anchor=\"end\">" << number(v) << "</text>\n";
    }
    const int middle = (kTop + plot_bottom_) / 2;
    out_ << "<text class=\"x-label\" x=\"" << (kLeft + plot_right_) / 2 << "\" y=\"" << kHeight - 14
         << "\" text-anchor=\"middle\" font-size=\"13\">" << escaped(text.x_label) << "</text>\n"
         << "<text class=\"y-label\" x=\"18\" y=\"" << middle << "\" text-anchor=\"middle\" font-size=\"13\" "
         << "transform=\"rotate(-90 18 " << middle << ")\">" << escaped(text.y_label) << "</text>\n";
  }

  /// Left and right pixel of the plot area.
  [[nodiscard]] int plot_left() const { return kLeft; }
  [[nodiscard]] int plot_right() const { return plot_right_; }
  /// The pixel row of value `v` (clamped to the plot area).
  [[nodiscard]] double y_pixel(double v) const {
    const double t = (std::clamp(v, y_.min, y_.max) - y_.min) / (y_.max - y_.min);
    return plot_bottom_ - t * (plot_bottom_ - kTop);
  }
  [[nodiscard]] int plot_bottom() const { return plot_bottom_; }
  /// A label under the plot at pixel column `x` (ticks of the x axis, bar categories).
  void x_tick(double x, const std::string& label) {
    out_ << "<text x=\"" << x << "\" y=\"" << plot_bottom_ + 18 << "\" text-anchor=\"middle\">" << escaped(label)
         << "</text>\n";
  }
  /// The stream the data marks go to.
  std::ostringstream& marks() { return out_; }

  /// Closes the chart with the plot frame, the note, and the legend for `names`, and writes it to `path`.
  void write(const std::string& path, const std::vector<std::string>& names) {
    out_ << "<rect x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\"" << plot_right_ - kLeft << "\" height=\""
         << plot_bottom_ - kTop << "\" fill=\"none\" stroke=\"#444444\"/>\n";
    if (!text_.note.empty())
      out_ << "<text class=\"note\" x=\"" << kLeft + 10 << "\" y=\"" << kTop + 20 << "\" font-size=\"13\">"
           << escaped(text_.note) << "</text>\n";
    if (legend_) {
      out_ << "<g class=\"legend\">\n";
      for (std::size_t i = 0; i < names.size(); ++i) {
        const int y = kTop + 8 + static_cast<int>(i) * 20;
        out_ << "<g class=\"legend-entry\"><rect x=\"" << plot_right_ + 14 << "\" y=\"" << y << "\" width=\"14\" "
             << "height=\"10\" fill=\"" << color(series_color(i)) << "\"/><text x=\"" << plot_right_ + 34
             << "\" y=\"" << y + 9 << "\">" << escaped(names[i]) << "</text></g>\n";
      }
      out_ << "</g>\n";
    }
    out_ << "</svg>\n";
    std::ofstream file(path);
    if (!file) throw std::runtime_error(path + ": cannot open for writing");
    file << out_.str();
    file.close();
    if (!file) throw std::runtime_error(path + ": write failed");
  }

 private:
  ChartText text_;
  AxisRange y_;
  bool legend_;
  int plot_right_ = 0, plot_bottom_ = 0;
  std::ostringstream out_;
};

}  // namespace

Rgb series_color(std::size_t index) { return kPalette[index % kPalette.size()]; }

void write_line_chart_svg(const std::string& path, const LineChart& chart) {
  double x_low = HUGE_VAL, x_high = -HUGE_VAL, y_low = HUGE_VAL, y_high = -HUGE_VAL;
  for (const LineSeries& s : chart.series)
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) {
        x_low = std::min(x_low, s.x[i]), x_high = std::max(x_high, s.x[i]);
        y_low = std::min(y_low, s.y[i]), y_high = std::max(y_high, s.y[i]);
      }
  AxisRange x = chart.x;
  if (!(x.min < x.max)) x = x_low < x_high ? AxisRange{x_low, x_high} : resolve({}, x_low, x_high, false);
  const AxisRange y = resolve(chart.y, y_low, y_high, false);
  std::vector<std::string> names;
  for (const LineSeries& s : chart.series) names.push_back(s.name);
  SvgChart svg(chart.text, y, names.size());
  const auto x_pixel = [&](double v) {
    return svg.plot_left() + (std::clamp(v, x.min, x.max) - x.min) / (x.max - x.min) * (svg.plot_right() - svg.plot_left());
  };
  const double step = nice_step(x.max - x.min, 6);
  for (double v = std::ceil(x.min / step - 1e-9) * step; v <= x.max + 1e-9 * step; v += step) {
    svg.marks() << "<line x1=\"" << x_pixel(v) << "\" y1=\"48\" x2=\"" << x_pixel(v) << "\" y2=\"" << svg.plot_bottom()
                << "\" stroke=\"#eeeeee\"/>\n";
    svg.x_tick(x_pixel(v), number(v));
  }
  if (chart.diagonal)
    svg.marks() << "<line class=\"chance\" x1=\"" << x_pixel(x.min) << "\" y1=\"" << svg.y_pixel(x.min) << "\" x2=\""
                << x_pixel(x.max) << "\" y2=\"" << svg.y_pixel(x.max) << "\" stroke=\"#999999\" "
                << "stroke-dasharray=\"6 4\"/>\n";
  for (std::size_t s = 0; s < chart.series.size(); ++s) {
    const LineSeries& series = chart.series[s];
    const std::string stroke = color(series_color(s));
    svg.marks() << "<g class=\"series\"><polyline fill=\"none\" stroke=\"" << stroke << "\" stroke-width=\"2\" points=\"";
    std::ostringstream dots;
    const std::size_t n = std::min(series.x.size(), series.y.size());
    double last_x = HUGE_VAL, last_y = HUGE_VAL;
    for (std::size_t i = 0; i < n; ++i) {
      if (!std::isfinite(series.x[i]) || !std::isfinite(series.y[i])) continue;
      const double px = x_pixel(series.x[i]), py = svg.y_pixel(series.y[i]);
      // Points within half a pixel of the last one drawn add nothing visible (an ROC has thousands of them).
      if (i + 1 < n && std::abs(px - last_x) < 0.5 && std::abs(py - last_y) < 0.5) continue;
      last_x = px, last_y = py;
      svg.marks() << px << ',' << py << ' ';
      if (chart.markers) dots << "<circle cx=\"" << px << "\" cy=\"" << py << "\" r=\"3\" fill=\"" << stroke << "\"/>";
    }
    svg.marks() << "\"/>" << dots.str() << "</g>\n";
  }
  svg.write(path, names);
}

void write_bar_chart_svg(const std::string& path, const BarChart& chart) {
  double low = HUGE_VAL, high = -HUGE_VAL;
  for (const auto& group : chart.values)
    for (const double v : group)
      if (std::isfinite(v)) low = std::min(low, v), high = std::max(high, v);
  const AxisRange y = resolve(chart.y, low, high, true);
  SvgChart svg(chart.text, y, chart.series.size());
  const double group_width =
      static_cast<double>(svg.plot_right() - svg.plot_left()) / static_cast<double>(std::max<std::size_t>(1, chart.values.size()));
  const double baseline = svg.y_pixel(std::clamp(0.0, y.min, y.max));
  for (std::size_t g = 0; g < chart.values.size(); ++g) {
    const double left = svg.plot_left() + group_width * static_cast<double>(g);
    if (g < chart.categories.size()) svg.x_tick(left + 0.5 * group_width, chart.categories[g]);
    const std::vector<double>& group = chart.values[g];
    const double bar = 0.8 * group_width / static_cast<double>(std::max<std::size_t>(1, group.size()));
    for (std::size_t s = 0; s < group.size(); ++s) {
      if (!std::isfinite(group[s])) continue;
      const double top = svg.y_pixel(group[s]);
      svg.marks() << "<rect class=\"bar\" x=\"" << left + 0.1 * group_width + bar * static_cast<double>(s)
                  << "\" y=\"" << std::min(top, baseline) << "\" width=\"" << bar * 0.92 << "\" height=\""
                  << std::abs(baseline - top) << "\" fill=\"" << color(series_color(s)) << "\"><title>"
                  << escaped((s < chart.series.size() ? chart.series[s] + ": " : "") + number(group[s]))
                  << "</title></rect>\n";
    }
  }
  svg.write(path, chart.series);
}

}  // namespace clothcd::render

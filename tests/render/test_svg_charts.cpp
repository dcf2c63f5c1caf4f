// SVG charts read without their report: a title, two axis names, and a legend naming the series when there are
// several. Checked on charts written here and on every chart committed in bench/results and models/.
#include <catch2/catch.hpp>

#include <filesystem>
#include <regex>
#include <set>
#include <string>

#include "clothcd/render/svg_chart.hpp"
#include "support/test_support.hpp"

namespace fs = std::filesystem;
using namespace clothcd::render;

namespace {

std::size_t count_of(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

// The text of the first element with class `name`, or "" when there is none.
std::string text_of_class(const std::string& svg, const std::string& name) {
  const std::regex element("<text class=\"" + name + "\"[^>]*>([^<]*)</text>");
  std::smatch match;
  return std::regex_search(svg, match, element) ? match[1].str() : "";
}

// Checks one chart file: parseable enough to find its words, and a legend entry per colour when colours differ.
void check_readable(const fs::path& path) {
  INFO(path.string());
  const std::string svg = clothcd::test::read_file(path);
  REQUIRE(svg.rfind("<svg ", 0) == 0);
  CHECK(svg.find("</svg>") != std::string::npos);
  CHECK_FALSE(text_of_class(svg, "title").empty());
  CHECK_FALSE(text_of_class(svg, "x-label").empty());
  CHECK_FALSE(text_of_class(svg, "y-label").empty());
  std::set<std::string> colours;
  const std::regex mark("class=\"(bar|series)\"[^>]*?(fill|stroke)=\"(#[0-9a-f]{6})\"");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), mark); it != std::sregex_iterator(); ++it)
    colours.insert((*it)[3].str());
  const std::regex polyline("<g class=\"series\"><polyline fill=\"none\" stroke=\"(#[0-9a-f]{6})\"");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), polyline); it != std::sregex_iterator(); ++it)
    colours.insert((*it)[1].str());
  CHECK_FALSE(colours.empty());  // some data is drawn
  if (colours.size() >= 2) {
    CHECK(svg.find("<g class=\"legend\">") != std::string::npos);
    CHECK(count_of(svg, "class=\"legend-entry\"") >= colours.size());
  }
}

}  // namespace

TEST_CASE("line and bar charts carry their title, axis names and legend as text", "[render][charts]") {
  clothcd::test::TempDir dir;
  LineChart lines;
  lines.text = {"Errors & <trials>", "hidden neurons", "normalized squared error", "AUC 0.99"};
  lines.series = {{"training", {1, 2, 3}, {0.0204, 0.0199, 0.0198}}, {"selection", {1, 2, 3}, {0.0205, 0.02, 0.0199}}};
  write_line_chart_svg((dir / "lines.svg").string(), lines);
  const std::string svg = clothcd::test::read_file(dir / "lines.svg");
  CHECK(text_of_class(svg, "title") == "Errors &amp; &lt;trials&gt;");
  CHECK(text_of_class(svg, "note") == "AUC 0.99");
  CHECK(count_of(svg, "class=\"legend-entry\"") == 2);
  // The y axis shows the data, not 0 to the top: a tick label near the data's values, none at 0.
  CHECK(svg.find(">0.02<") != std::string::npos);
  CHECK(svg.find(">0<") == std::string::npos);
  check_readable(dir / "lines.svg");

  BarChart bars;
  bars.text = {"Time per model", "obstacle model", "time (ms)", ""};
  bars.categories = {"rabbit", "cat"};
  bars.series = {"AABB", "double box"};
  bars.values = {{1.0, 2.0}, {3.0, std::nan("")}};
  write_bar_chart_svg((dir / "bars.svg").string(), bars);
  const std::string bar_svg = clothcd::test::read_file(dir / "bars.svg");
  CHECK(count_of(bar_svg, "class=\"bar\"") == 3);  // the NaN draws no bar
  CHECK(bar_svg.find(">rabbit<") != std::string::npos);
  CHECK(bar_svg.find(">cat<") != std::string::npos);
  check_readable(dir / "bars.svg");

  CHECK_THROWS_WITH(write_bar_chart_svg("/nonexistent-dir/x.svg", bars), Catch::Contains("/nonexistent-dir/x.svg"));
}

TEST_CASE("every committed chart is readable alone", "[render][charts]") {
  std::size_t charts = 0;
  for (const char* folder : {"bench/results", "models"}) {
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(fs::path(CLOTHCD_SOURCE_DIR) / folder)) {
      if (entry.path().extension() != ".svg") continue;
      check_readable(entry.path());
      ++charts;
    }
  }
  CHECK(charts >= 11);  // bench: 10 (the scale section's last committed chart predates SVG), models/default: roc
}

// Timing, CSV and formatting helpers of the benchmark sections.
#include "bench_util.hpp"

#include <stdlib.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace clothcd::bench {

double time_ms(const std::function<void()>& work) {
  const auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

double median_ms(int runs, const std::function<void()>& work) {
  std::vector<double> times;
  for (int i = 0; i < std::max(1, runs); ++i) times.push_back(time_ms(work));
  std::nth_element(times.begin(), times.begin() + static_cast<long>(times.size() / 2), times.end());
  return times[times.size() / 2];
}

CsvFile::CsvFile(const std::filesystem::path& path, const std::string& header) : path_(path), file_(path) {
  if (!file_) throw std::runtime_error(path.string() + ": cannot write the CSV file");
  file_ << header << '\n';
}

void CsvFile::row(const std::vector<std::string>& cells) {
  for (std::size_t i = 0; i < cells.size(); ++i) file_ << (i ? "," : "") << cells[i];
  file_ << '\n';
  if (!file_) throw std::runtime_error(path_.string() + ": cannot write the CSV file");
}

std::string csv_text(const std::string& value) {
  if (value.find_first_of(",\"") == std::string::npos) return value;
  std::string quoted = "\"";
  for (const char c : value) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

ScratchFolder::ScratchFolder(const std::string& purpose) {
  std::string pattern = (std::filesystem::temp_directory_path() / ("clothcd-bench-" + purpose + "-XXXXXX")).string();
  if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("cannot create a folder in " + pattern);
  path_ = pattern;
}

ScratchFolder::~ScratchFolder() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

std::string report_path(const std::filesystem::path& path, const std::filesystem::path& repository) {
  if (repository.empty()) return path.string();
  std::filesystem::path shown = path.lexically_normal().lexically_proximate(repository.lexically_normal());
  if (!shown.has_filename() && shown.has_parent_path()) shown = shown.parent_path();  // no trailing separator
  return shown.string();
}

std::string number(double value, int digits) {
  if (!std::isfinite(value)) return "-";
  char buffer[64];
  const double magnitude = std::abs(value);
  if (magnitude >= 1e-3 && magnitude < 1e6) {
    // Significant digits without exponent: decimals = digits - (digits before the point).
    const int before = magnitude >= 1 ? static_cast<int>(std::floor(std::log10(magnitude))) + 1 : 0;
    int decimals = std::max(0, digits - before);
    if (magnitude < 1) decimals = digits - 1 - static_cast<int>(std::floor(std::log10(magnitude)));
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  } else {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  }
  return buffer;
}

std::string fixed(double value, int decimals) {
  if (!std::isfinite(value)) return "-";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

std::string markdown_table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows) {
  auto line = [](const std::vector<std::string>& cells) {
    std::string text = "|";
    for (const std::string& cell : cells) text += " " + cell + " |";
    return text + "\n";
  };
  std::string table = line(header) + "|";
  for (std::size_t i = 0; i < header.size(); ++i) table += "---|";
  table += "\n";
  for (const auto& row : rows) table += line(row);
  return table;
}

}  // namespace clothcd::bench

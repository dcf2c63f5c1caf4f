#pragma once
/// @file
/// Helpers every benchmark section shares: median wall-clock timing, CSV files, number formatting for Markdown tables.

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

namespace clothcd::bench {

/// Median wall time of `runs` calls of `work` (runs >= 1), in milliseconds.
[[nodiscard]] double median_ms(int runs, const std::function<void()>& work);

/// A new folder in the system's temporary folder, removed with everything in it when this goes out of scope: where a
/// section writes the files it only reads back (frames, converted meshes), never into the report's folder.
class ScratchFolder {
 public:
  /// Creates the folder, named after `purpose` (e.g. "scale"); throws std::runtime_error when it cannot.
  explicit ScratchFolder(const std::string& purpose);
  ~ScratchFolder();
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  /// The folder.
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// Wall time of one call of `work`, in milliseconds.
[[nodiscard]] double time_ms(const std::function<void()>& work);

/// A CSV file with a header row; throws std::runtime_error naming the path when it cannot be written.
class CsvFile {
 public:
  /// Creates `path` and writes `header` (column names, comma-separated) as its first line.
  CsvFile(const std::filesystem::path& path, const std::string& header);
  /// Appends one row; cells are written as given (quote text holding commas yourself, see csv_text).
  void row(const std::vector<std::string>& cells);

 private:
  std::filesystem::path path_;
  std::ofstream file_;
};

/// `value` quoted for a CSV cell when it holds a comma or a quote.
[[nodiscard]] std::string csv_text(const std::string& value);

/// `path` as the report shows it: relative to the repository `repository` when one is given (a folder beside it as
/// ../name/...), so that the report names no folder of the machine it ran on; else as given.
[[nodiscard]] std::string report_path(const std::filesystem::path& path, const std::filesystem::path& repository);

/// `value` with `digits` significant digits (plain notation when reasonable), "-" when not finite.
[[nodiscard]] std::string number(double value, int digits = 4);

/// `value` with exactly `decimals` decimals, "-" when not finite.
[[nodiscard]] std::string fixed(double value, int decimals);

/// A Markdown table: the header row, the separator and one line per row (cells joined by " | ").
[[nodiscard]] std::string markdown_table(const std::vector<std::string>& header,
                                         const std::vector<std::vector<std::string>>& rows);

}  // namespace clothcd::bench

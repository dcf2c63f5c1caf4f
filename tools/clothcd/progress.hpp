#pragma once
// Progress of a long run on stderr: a bar redrawn in place at most five times a second when stderr is a terminal;
// otherwise (a log, a pipe) one plain line at most every 15 seconds, so that logs hold no carriage return.

#include <chrono>
#include <cstddef>
#include <string>

namespace clothcd::cli {

/// One progress display; silent when `quiet`.
class Progress {
 public:
  /// `label` names the work ("simulating"), `unit` the counted items ("steps").
  Progress(std::string label, std::string unit, bool quiet);
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  /// Ends the bar's line when one was drawn.
  ~Progress();

  /// `done` of `total` items finished; `detail` is appended (e.g. "hidden neurons 3").
  void update(std::size_t done, std::size_t total, const std::string& detail = "");

 private:
  std::string label_;
  std::string unit_;
  bool quiet_;
  bool terminal_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace clothcd::cli

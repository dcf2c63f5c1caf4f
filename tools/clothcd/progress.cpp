// Progress on stderr (progress.hpp).
#include "progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>

namespace clothcd::cli {
namespace {

constexpr double kTerminalInterval = 0.2;  // seconds between redraws of the bar
constexpr double kLogInterval = 15.0;      // seconds between plain lines in a log
constexpr int kBarWidth = 30;

double seconds(std::chrono::steady_clock::duration d) { return std::chrono::duration<double>(d).count(); }

}  // namespace

Progress::Progress(std::string label, std::string unit, bool quiet)
    : label_(std::move(label)),
      unit_(std::move(unit)),
      quiet_(quiet),
      terminal_(isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

Progress::~Progress() {
  if (drawn_) std::fputc('\n', stderr);
}

void Progress::update(std::size_t done, std::size_t total, const std::string& detail) {
  if (quiet_) return;
  const auto now = std::chrono::steady_clock::now();
  const bool finished = done >= total;
  const std::string suffix = detail.empty() ? "" : "  (" + detail + ")";
  if (terminal_) {
    if (!finished && seconds(now - last_) < kTerminalInterval) return;
    last_ = now;
    const int filled = total == 0 ? kBarWidth : static_cast<int>(kBarWidth * std::min(done, total) / total);
    std::fprintf(stderr, "\r%s [%s%s] %zu/%zu %s  %.1f s%s\x1b[K", label_.c_str(), std::string(filled, '#').c_str(),
                 std::string(kBarWidth - filled, '.').c_str(), done, total, unit_.c_str(), seconds(now - start_),
                 suffix.c_str());
    std::fflush(stderr);
    drawn_ = true;
    return;
  }
  if (seconds(now - last_) < kLogInterval) return;
  last_ = now;
  std::fprintf(stderr, "%s: %zu/%zu %s after %.0f s%s\n", label_.c_str(), done, total, unit_.c_str(),
               seconds(now - start_), suffix.c_str());
}

}  // namespace clothcd::cli

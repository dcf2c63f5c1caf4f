// The scale section passes the narrow-phase mode explicitly, with the flags the measured program's help lists.
#include <catch2/catch.hpp>

#include "detect_run.hpp"

using clothcd::bench::detect_mode_flags_from_help;
using clothcd::bench::DetectMode;
using Flags = std::vector<std::string>;

TEST_CASE("detect mode flags: a program with --exact is approximate by default") {
  const std::string help = "Options:\n  -h,--help     Print this help\n  --exact       Thickness 0 only: decide ...\n";
  CHECK(detect_mode_flags_from_help(help, DetectMode::Exact) == Flags{"--exact"});
  CHECK(detect_mode_flags_from_help(help, DetectMode::Approximate).empty());
}

TEST_CASE("detect mode flags: a program with --approximate is exact by default") {
  const std::string help = "Options:\n  --approximate Thickness 0 only: report undecided pieces as conservative hits\n";
  CHECK(detect_mode_flags_from_help(help, DetectMode::Approximate) == Flags{"--approximate"});
  CHECK(detect_mode_flags_from_help(help, DetectMode::Exact).empty());
}

TEST_CASE("detect mode flags: a longer option or a word in a description is not the flag") {
  const std::string help = "  --exact-stage-only  Stop after\n  --json  Not --approximate-ish; unlike exact runs\n";
  CHECK(detect_mode_flags_from_help(help, DetectMode::Exact).empty());
  CHECK(detect_mode_flags_from_help(help, DetectMode::Approximate).empty());
  CHECK(detect_mode_flags_from_help("  --approximate,--approx  Report\n", DetectMode::Approximate) ==
        Flags{"--approximate"});
}

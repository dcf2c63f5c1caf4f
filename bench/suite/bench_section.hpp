#pragma once
/// @file
/// One section of `clothcd bench`: a named experiment that writes its CSV and PNG files into the output folder and
/// returns its part of the Markdown report (the paper's value beside ours, the ratio, and what does not reproduce).

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace clothcd::bench {

/// Everything a section may read; sections take no other input.
struct BenchContext {
  std::filesystem::path out_dir;                     ///< Where the section writes its CSV and PNG files.
  std::filesystem::path repository;                  ///< The checkout the run is made from (empty outside one).
  std::filesystem::path obstacle_model_dir;          ///< The obstacle model cache (`clothcd meshes`, default_model_dir()).
  std::filesystem::path network_model_dir;           ///< The pair network to benchmark (models/default by default).
  std::optional<std::filesystem::path> ccd_queries;  ///< The public CCD benchmark's query folder, when present.
  /// The shared real simulation steps (scalable-ccd-sample: one folder per scene with t0.ply, t1.ply, truth.json),
  /// when present.
  std::optional<std::filesystem::path> scalable_ccd;
  /// The clothcd program whose `detect` the scale section runs (empty: the one beside clothcd-bench); another build's
  /// program measures another version of the detector on the same steps and peer.
  std::filesystem::path clothcd_program;
  bool quick = false;                                ///< CI-sized run: fewer models, steps and repetitions.
  bool part_of_all = false;  ///< Run by `clothcd bench all`: a section may leave out cases of minutes and gigabytes.
  std::function<void(const std::string&)> progress;  ///< Reports one step ("building OBBs on the cat"); never null.
};

/// What a section returns to the report.
struct SectionReport {
  std::string markdown;             ///< The section's Markdown (starts with a "## " heading).
  std::vector<std::string> files;   ///< File names it wrote in BenchContext::out_dir (CSV, PNG).
};

/// A registered section: `clothcd bench NAME` runs one, `clothcd bench all` runs them all in `order`.
struct Section {
  int order = 0;                                          ///< Position in the report (ascending).
  std::string name;                                       ///< Command-line name, e.g. "obb".
  std::string summary;                                    ///< One line for --help and the report's contents.
  std::function<SectionReport(const BenchContext&)> run;  ///< Runs the experiment; throws on failure.
};

/// Every registered section, sorted by `order`.
[[nodiscard]] std::vector<Section> all_sections();

/// Registers a section at static-initialisation time. Each section's .cpp defines one:
/// `const SectionRegistrar registrar{{10, "obb", "Table 1: ...", run_obb}};`
struct SectionRegistrar {
  /// Adds `section` to the registry.
  explicit SectionRegistrar(Section section);
};

}  // namespace clothcd::bench

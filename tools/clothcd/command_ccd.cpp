// `clothcd ccd PATH`: runs the safe CCD (optionally behind a filter) on benchmark query files and prints one summary:
// queries, collisions, false positives/negatives against the ground truth, culled pairs per filter, time per query.
// `--filter network` puts the pair network in front of the combined filters with the detector's safety rule.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>

#include "clothcd/ccd/ccd.hpp"
#include "clothcd/ccd/query_file.hpp"
#include "clothcd/culling/network_culler.hpp"
#include "commands.hpp"
#include "shared_options.hpp"

namespace clothcd::cli {

namespace {

// Queries read, filtered and decided at a time (a few megabytes of records).
constexpr std::size_t kChunkQueries = 4096;

struct CcdCommandOptions {
  std::string path;
  std::string type;
  std::string filter = "combined";
  std::string network;
  double thickness = 0.0;
  bool approximate = false;
  bool json = false;
  std::string per_query;
};

struct Summary {
  std::size_t queries = 0;
  std::size_t colliding = 0;
  std::size_t with_truth = 0;
  std::size_t truth_colliding = 0;
  std::size_t false_positives = 0;
  std::size_t false_negatives = 0;
  std::size_t conservative = 0;
  std::size_t inexact_coordinates = 0;
  std::size_t culled_selected = 0;
  std::size_t culled_nonpenetration = 0;
  std::size_t culled_projection = 0;
  std::size_t culled_combined = 0;
  double ns_per_query = 0.0;
  bool network = false;
  learning::NetworkCullingStats network_stats;
};

const char* state_name(ccd::CcdState state) {
  switch (state) {
    case ccd::CcdState::Separated:
      return "separated";
    case ccd::CcdState::Hit:
      return "hit";
    case ccd::CcdState::ConservativeHit:
      return "conservative-hit";
  }
  return "?";
}

void print_summary(const CcdCommandOptions& options, const Summary& s) {
  if (options.json) {
    Json report = json_report("ccd");
    report["path"] = options.path;
    report["filter"] = options.filter;
    report["thickness"] = options.thickness;
    report["exact"] = !options.approximate;
    report["queries"] = s.queries;
    report["colliding"] = s.colliding;
    report["conservative"] = s.conservative;
    report["with_ground_truth"] = s.with_truth;
    report["truth_colliding"] = s.truth_colliding;
    report["false_positives"] = s.false_positives;
    report["false_negatives"] = s.false_negatives;
    report["inexact_coordinates"] = s.inexact_coordinates;
    report["culled"] = s.culled_selected;
    report["culled_nonpenetration"] = s.culled_nonpenetration;
    report["culled_projection"] = s.culled_projection;
    report["culled_combined"] = s.culled_combined;
    report["ns_per_query"] = std::round(s.ns_per_query * 10.0) / 10.0;
    if (s.network) {
      const learning::NetworkCullingStats& n = s.network_stats;
      report["network"] = {{"dropped", n.dropped}, {"overruled", n.overruled}, {"checked", n.checked},
                           {"kept", n.kept},       {"network_ms", n.network_ms}, {"filters_ms", n.filters_ms}};
    }
    print_json(report);
    return;
  }
  const auto percent = [&](std::size_t n) { return s.queries ? 100.0 * static_cast<double>(n) / s.queries : 0.0; };
  std::cout << std::fixed << std::setprecision(1) << "path:                  " << options.path << '\n'
            << "filter:                " << options.filter << "  (thickness " << options.thickness
            << (options.approximate ? ", undecided queries reported as conservative hits" : "") << ")\n"
            << "queries:               " << s.queries << '\n'
            << "colliding:             " << s.colliding << "  (" << s.conservative << " conservative)\n";
  if (s.with_truth > 0) {
    std::cout << "ground truth:          " << s.truth_colliding << " colliding of " << s.with_truth << '\n'
              << "false positives:       " << s.false_positives << '\n'
              << "false negatives:       " << s.false_negatives << '\n';
  }
  std::cout << "inexact coordinates:   " << s.inexact_coordinates << " queries (decided again on the exact values)\n"
            << "culled (selected):     " << s.culled_selected << "  (" << percent(s.culled_selected) << "%)\n"
            << "culled nonpenetration: " << s.culled_nonpenetration << "  (" << percent(s.culled_nonpenetration)
            << "%)\n"
            << "culled projection:     " << s.culled_projection << "  (" << percent(s.culled_projection) << "%)\n"
            << "culled combined:       " << s.culled_combined << "  (" << percent(s.culled_combined) << "%)\n"
            << "ns per query:          " << s.ns_per_query << '\n';
  if (s.network) {
    const learning::NetworkCullingStats& n = s.network_stats;
    std::cout << "network dropped:       " << n.dropped << "  (confirmed by the filters)\n"
              << "network overruled:     " << n.overruled << "  (drops the filters did not confirm: exact CCD)\n"
              << "network checked:       " << n.checked << "  (" << n.filter_culled << " culled by the filters)\n"
              << "network kept:          " << n.kept << "  (straight to the exact CCD)\n"
              << "network time (ms):     features+inference " << n.network_ms << ", filters " << n.filters_ms << '\n';
  }
}

// A query whose coordinates are not all doubles was filtered and tested rounded to the nearest doubles, which can move
// a touching pair apart. Such queries are decided again without a filter: at thickness 0 on the exact rationals (the
// rational reference; a hit the rounded query missed is reported with toi 0 as a conservative hit), otherwise with the
// thickness grown by more than rounding can move the two primitives apart (each point by at most sqrt(3) * 2^-53 of
// the largest coordinate magnitude). Returns how many were decided again.
// Only the first results.size() records are looked at.
std::size_t redecide_inexact(const std::vector<ccd::QueryRecord>& records, const ccd::CcdSettings& settings,
                             std::vector<std::uint8_t>& keep, std::vector<ccd::CcdResult>& results) {
  std::size_t redecided = 0;
  for (std::size_t i = 0; i < results.size(); ++i) {
    const ccd::QueryRecord& record = records[i];
    if (record.exactly_representable) continue;
    ++redecided;
    keep[i] = 1;
    if (settings.thickness == 0.0) {
      ccd::CcdResult result = ccd::continuous_collision(record.query, settings);
      const bool hit = ccd::exact_collision_reference(record.query.kind, record.rational);
      if (hit != result.hit) {
        result = ccd::CcdResult{};
        if (hit) {
          result.hit = true;
          result.toi = 0.0;
          result.state = ccd::CcdState::ConservativeHit;
        }
      }
      results[i] = result;
      continue;
    }
    double largest = 0.0;
    for (int p = 0; p < 4; ++p) {
      largest = std::max({largest, record.query.start[p].cwiseAbs().maxCoeff(), record.query.end[p].cwiseAbs().maxCoeff()});
    }
    ccd::CcdSettings grown = settings;
    grown.thickness += 8 * 0x1p-53 * largest;
    results[i] = ccd::continuous_collision(record.query, grown);
  }
  return redecided;
}

void add_network_stats(const learning::NetworkCullingStats& part, learning::NetworkCullingStats& total) {
  total.dropped += part.dropped;
  total.overruled += part.overruled;
  total.checked += part.checked;
  total.filter_culled += part.filter_culled;
  total.kept += part.kept;
  total.network_ms += part.network_ms;
  total.filters_ms += part.filters_ms;
}

// Adds the first results.size() queries of `records` and their answers to the summary (and their lines to the
// per-query file when open).
void add_to_summary(const std::vector<ccd::QueryRecord>& records, const std::vector<std::uint8_t>& keep,
                    const std::vector<ccd::CcdResult>& results, const ccd::CcdSettings& settings, Summary& summary,
                    std::ofstream& per_query) {
  summary.queries += results.size();
  for (std::size_t i = 0; i < results.size(); ++i) {
    const ccd::QueryRecord& record = records[i];
    const ccd::CcdResult& result = results[i];
    summary.colliding += result.hit ? 1 : 0;
    summary.conservative += result.state == ccd::CcdState::ConservativeHit ? 1 : 0;
    summary.culled_selected += keep[i] ? 0 : 1;
    summary.culled_nonpenetration += ccd::nonpenetration_filter_culls(record.query, settings) ? 1 : 0;
    summary.culled_projection += ccd::projection_filter_culls(record.query, settings) ? 1 : 0;
    summary.culled_combined += ccd::combined_filters_cull(record.query, settings) ? 1 : 0;
    if (record.truth >= 0) {
      ++summary.with_truth;
      summary.truth_colliding += record.truth == 1 ? 1 : 0;
      summary.false_positives += result.hit && record.truth == 0 ? 1 : 0;
      summary.false_negatives += !result.hit && record.truth == 1 ? 1 : 0;
    }
    if (per_query.is_open())
      per_query << record.file << ',' << record.line << ',' << (record.query.kind == PairKind::VertexFace ? "vf" : "ee")
                << ',' << record.truth << ',' << (result.hit ? 1 : 0) << ',' << state_name(result.state) << ','
                << result.toi << ',' << (keep[i] ? 0 : 1) << '\n';
  }
}

ccd::CcdFilter parse_filter(const std::string& name) {
  static const std::map<std::string, ccd::CcdFilter> kFilters{{"none", ccd::CcdFilter::None},
                                                              {"nonpenetration", ccd::CcdFilter::NonPenetration},
                                                              {"projection", ccd::CcdFilter::Projection},
                                                              {"combined", ccd::CcdFilter::Combined}};
  return kFilters.at(name);
}

void run_ccd(const CcdCommandOptions& options) {
  const bool network = options.filter == "network";
  const ccd::CcdFilter filter = network ? ccd::CcdFilter::Combined : parse_filter(options.filter);
  check_network_needs_filter(options.network, options.filter);
  check_approximate_needs_zero_thickness(options.approximate, options.thickness);
  std::optional<PairKind> kind;
  if (options.type == "vf") kind = PairKind::VertexFace;
  if (options.type == "ee") kind = PairKind::EdgeEdge;
  ccd::CcdSettings settings;
  settings.thickness = options.thickness;
  settings.decide_exactly = !options.approximate;
  if (!(settings.thickness >= 0.0) || !std::isfinite(settings.thickness))
    throw std::invalid_argument("--thickness must be a finite number >= 0");

  std::optional<learning::NetworkCuller> culler;
  if (network) culler.emplace(options.network);

  // Listed before the per-query file is created, which may lie in the same folder.
  const std::vector<std::string> files = ccd::query_files(options.path);
  std::ofstream per_query;
  if (!options.per_query.empty()) {
    std::error_code error;
    for (const std::string& file : files) {
      if (std::filesystem::equivalent(file, options.per_query, error)) {
        throw std::invalid_argument("--per-query " + options.per_query + " is one of the query files it would overwrite");
      }
    }
    per_query.open(options.per_query);
    if (!per_query) throw std::runtime_error(options.per_query + ": cannot open for writing");
    per_query << "file,line,kind,truth,hit,state,toi,culled\n" << std::setprecision(17);
  }
  Summary summary;
  summary.network = network;
  double elapsed_ns = 0.0;
  // Chunks of kChunkQueries queries, so that memory stays small however large the files are (records are reused).
  std::vector<ccd::QueryRecord> records(kChunkQueries);
  std::vector<ccd::CcdQuery> queries;
  std::vector<std::uint8_t> keep;
  std::vector<ccd::CcdResult> results;
  for (const std::string& file : files) {
    ccd::QueryFileReader reader(file, kind);
    for (bool more = true; more;) {
      std::size_t count = 0;
      while (count < records.size() && reader.next(records[count])) ++count;
      more = count == records.size();
      queries.clear();
      for (std::size_t i = 0; i < count; ++i) queries.push_back(records[i].query);
      const auto begin = std::chrono::steady_clock::now();
      if (culler)
        add_network_stats(culler->cull(queries, settings, false, keep), summary.network_stats);
      else
        ccd::filter_batch(queries, filter, settings, keep);
      ccd::continuous_collision_batch(queries, keep, settings, results);
      summary.inexact_coordinates += redecide_inexact(records, settings, keep, results);
      elapsed_ns += std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - begin).count();
      add_to_summary(records, keep, results, settings, summary, per_query);
      if (per_query.is_open() && !per_query) throw std::runtime_error(options.per_query + ": write failed");
    }
  }
  // An empty file or a folder of empty files is most likely a wrong path or a failed export: say so.
  if (summary.queries == 0) throw std::runtime_error(options.path + ": no queries (empty query files)");
  summary.ns_per_query = elapsed_ns / static_cast<double>(summary.queries);
  print_summary(options, summary);
}

}  // namespace

void add_ccd_command(CLI::App& app) {
  auto* command = app.add_subcommand("ccd", "Continuous collision detection on benchmark query files (CSV, rational)");
  auto options = std::make_shared<CcdCommandOptions>();
  command->add_option("PATH", options->path, "Query CSV file or folder (searched recursively)")->required();
  command->add_option("--type", options->type,
                      "Pair type: vf or ee (default: from a vertex-face/edge-edge folder in the path)")
      ->check(CLI::IsMember({"vf", "ee"}));
  add_filter_option(*command, options->filter);
  add_network_option(*command, options->network, "--model");
  command->add_option("--thickness", options->thickness, "Minimum separation (>= 0)")
      ->check(finite_number(0.0, std::numeric_limits<double>::infinity()))
      ->capture_default_str();
  command->add_flag("--approximate", options->approximate,
                    "Thickness 0 only: report the queries the floating-point fast tier leaves undecided as conservative hits "
                    "(a few false positives) instead of deciding them exactly");
  add_json_flag(*command, options->json);
  command->add_option("--per-query", options->per_query, "Write one CSV line per query to this file");
  command->callback([options] { run_ccd(*options); });
}

}  // namespace clothcd::cli

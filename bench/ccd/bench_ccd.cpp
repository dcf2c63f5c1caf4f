// CCD benchmark: false negatives / positives against the ground truth, culled fraction and time per query for each
// filter mode, on query files in the public benchmark's CSV format (Wang et al. 2021) or generated from clothcd's own
// simulations (ground truth optional). Peer figures (Tight-Inclusion 85/137 false positives, 15 us - 4.9 ms per query;
// plain double cubic solving 0.13 us with 5/3 misses) come from docs/anchors.md: no peer CCD library is packaged in
// Debian, so none runs in the same process.
//
// Usage: clothcd_bench_ccd DIR [--repeat N] [--csv FILE]
//   DIR holds vertex-face/ and edge-edge/ folders at any depth; each kind is measured separately.
#include <algorithm>
#include <chrono>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "clothcd/ccd/ccd.hpp"
#include "clothcd/ccd/query_file.hpp"

namespace ccd = clothcd::ccd;
using clothcd::PairKind;

namespace {

struct Row {
  std::string kind;
  std::string mode;
  std::size_t queries = 0;
  std::size_t truth_colliding = 0;
  std::size_t false_negatives = 0;
  std::size_t false_positives = 0;
  std::size_t culled = 0;
  std::size_t exact_fallbacks = 0;
  double ns_per_query = 0.0;
  double filter_ns_per_query = 0.0;
  double median_ns = 0.0;
  double p99_ns = 0.0;
  double max_ns = 0.0;
};

double now_ns() {
  return std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

Row measure(const std::vector<ccd::QueryRecord>& records, const std::string& kind, ccd::CcdFilter filter,
            const std::string& mode, int repeat) {
  std::vector<ccd::CcdQuery> queries;
  for (const auto& record : records) queries.push_back(record.query);
  Row row{kind, mode, queries.size()};
  std::vector<std::uint8_t> keep;
  std::vector<ccd::CcdResult> results;
  double best_total = 1e300, best_filter = 1e300;
  for (int r = 0; r < repeat; ++r) {
    const double t0 = now_ns();
    ccd::filter_batch(queries, filter, {}, keep);
    const double t1 = now_ns();
    ccd::continuous_collision_batch(queries, keep, {}, results);
    const double t2 = now_ns();
    best_total = std::min(best_total, t2 - t0);
    best_filter = std::min(best_filter, t1 - t0);
  }
  const double n = static_cast<double>(std::max<std::size_t>(1, queries.size()));
  row.ns_per_query = best_total / n;
  row.filter_ns_per_query = best_filter / n;
  std::vector<double> single;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const double t0 = now_ns();
    const bool culled = ccd::filter_culls(filter, queries[i]);
    const ccd::CcdResult result = culled ? ccd::CcdResult{} : ccd::continuous_collision(queries[i]);
    single.push_back(now_ns() - t0);
    row.culled += culled ? 1 : 0;
    row.exact_fallbacks += result.exact_fallback ? 1 : 0;
    if (records[i].truth < 0) continue;
    row.truth_colliding += records[i].truth == 1 ? 1 : 0;
    row.false_negatives += records[i].truth == 1 && !result.hit ? 1 : 0;
    row.false_positives += records[i].truth == 0 && result.hit ? 1 : 0;
  }
  std::sort(single.begin(), single.end());
  if (!single.empty()) {
    row.median_ns = single[single.size() / 2];
    row.p99_ns = single[std::min(single.size() - 1, single.size() * 99 / 100)];
    row.max_ns = single.back();
  }
  return row;
}

std::size_t count_culled(const std::vector<ccd::QueryRecord>& records, bool normals) {
  std::size_t culled = 0;
  for (const auto& record : records)
    culled += ccd::projection_filter_culls(record.query, {}, ccd::ProjectionFilterOptions{normals}) ? 1 : 0;
  return culled;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: clothcd_bench_ccd DIR [--repeat N] [--csv FILE]\n";
    return 2;
  }
  const std::string dir = argv[1];
  int repeat = 3;
  std::string csv_path;
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string option = argv[i];
    if (option == "--repeat") repeat = std::max(1, std::stoi(argv[i + 1]));
    if (option == "--csv") csv_path = argv[i + 1];
  }
  try {
    const std::vector<ccd::QueryRecord> all = ccd::read_queries(dir);
    std::vector<Row> rows;
    for (const PairKind kind : {PairKind::VertexFace, PairKind::EdgeEdge}) {
      std::vector<ccd::QueryRecord> records;
      for (const auto& record : all)
        if (record.query.kind == kind) records.push_back(record);
      if (records.empty()) continue;
      const std::string name = kind == PairKind::VertexFace ? "vf" : "ee";
      for (const auto& [filter, mode] :
           {std::pair{ccd::CcdFilter::None, "none"}, std::pair{ccd::CcdFilter::NonPenetration, "nonpenetration"},
            std::pair{ccd::CcdFilter::Projection, "projection"}, std::pair{ccd::CcdFilter::Combined, "combined"}})
        rows.push_back(measure(records, name, filter, mode, repeat));
      std::cout << name << ": projection filter culls " << count_culled(records, false) << " of " << records.size()
                << " with eq. (10)'s five directions, " << count_culled(records, true)
                << " with the face/edge normals at t = 0 and 1 added\n";
    }
    std::ostringstream table;
    table << "kind,filter,queries,truth_colliding,false_negatives,false_positives,culled_fraction,exact_fallbacks,"
             "ns_per_query,filter_ns_per_query,median_ns,p99_ns,max_ns\n"
          << std::fixed;
    for (const Row& r : rows)
      table << r.kind << ',' << r.mode << ',' << r.queries << ',' << r.truth_colliding << ',' << r.false_negatives
            << ',' << r.false_positives << ',' << std::setprecision(4)
            << static_cast<double>(r.culled) / static_cast<double>(std::max<std::size_t>(1, r.queries)) << ','
            << r.exact_fallbacks << ',' << std::setprecision(1) << r.ns_per_query << ',' << r.filter_ns_per_query << ','
            << r.median_ns << ',' << r.p99_ns << ',' << r.max_ns << '\n';
    std::cout << table.str();
    if (!csv_path.empty()) std::ofstream(csv_path) << table.str();
    for (const Row& r : rows)
      if (r.false_negatives > 0) return 1;
  } catch (const std::exception& e) {
    std::cerr << "clothcd_bench_ccd: error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}

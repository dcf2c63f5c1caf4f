// The IPC Toolkit peer's environment and narrow phase (see ipctk_peer.hpp).
#include "ipctk_peer.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include "child_process.hpp"

namespace clothcd::bench {
namespace {

namespace fs = std::filesystem;

std::runtime_error peer_failure(const std::string& what, const ChildRun& run) {
  return std::runtime_error("the ipctk peer failed on " + what + " (exit " + std::to_string(run.exit_code) +
                            "): " + run.output);
}

double value(const std::map<std::string, double>& values, const std::string& name, const std::string& what,
             const ChildRun& run) {
  const auto found = values.find(name);
  if (found == values.end()) throw peer_failure(what + ", no " + name + "=", run);
  return found->second;
}

}  // namespace

std::optional<fs::path> peer_python(const BenchContext& context, const fs::path& script, std::string& status) {
  const fs::path venv = context.repository / ".cache" / "bench-venv", python = venv / "bin" / "python";
  if (context.quick) {
    status = "not run in a quick run (the peer's per-query calls alone take minutes)";
    return std::nullopt;
  }
  const auto works = [&] {
    if (access(python.c_str(), X_OK) != 0) return false;
    const ChildRun run = run_child({python.string(), script.string(), "--version"}, 1);
    status = run.output.substr(0, run.output.find('\n'));
    return run.exit_code == 0;
  };
  if (works()) return python;
  context.progress("creating the peer's Python environment in " + venv.string() + " (pip install ipctk==1.6.1)");
  const ChildRun setup =
      run_child({"/usr/bin/env", "bash", (context.repository / "bench" / "peers" / "setup-ipctk.sh").string(),
                 venv.string()}, 1);
  if (setup.exit_code == 0 && works()) return python;
  status = "peer not installed (no ipctk in " + venv.string() + ")";
  return std::nullopt;
}

std::map<std::string, double> peer_values(const std::string& output) {
  std::map<std::string, double> values;
  std::istringstream words(output);
  for (std::string word; words >> word;) {
    const std::size_t eq = word.find('=');
    if (eq != std::string::npos) values[word.substr(0, eq)] = std::strtod(word.c_str() + eq + 1, nullptr);
  }
  return values;
}

void write_peer_scene(const MeshFrames& frames, const fs::path& path) {
  std::ofstream out(path, std::ios::binary);
  const std::int64_t counts[2] = {frames.start.vertex_count(), frames.start.face_count()};
  out.write(reinterpret_cast<const char*>(counts), sizeof counts);
  const auto bytes = [](Eigen::Index values) { return static_cast<std::streamsize>(values * 8); };
  out.write(reinterpret_cast<const char*>(frames.start.vertices.data()), bytes(frames.start.vertices.size()));
  out.write(reinterpret_cast<const char*>(frames.end.data()), bytes(frames.end.size()));
  out.write(reinterpret_cast<const char*>(frames.start.faces.data()), frames.start.faces.size() * 4);
  if (!out) throw std::runtime_error(path.string() + ": write failed");
}

PeerCandidateSearch run_peer_candidates(const fs::path& python, const fs::path& script, const fs::path& scene_bin,
                                        int threads) {
  const ChildRun run = run_child(
      {python.string(), script.string(), scene_bin.string(), "--threads", std::to_string(threads), "--repeats", "1"},
      threads);
  if (run.exit_code != 0) throw peer_failure(scene_bin.string(), run);
  const std::map<std::string, double> values = peer_values(run.output);
  const std::string what = scene_bin.string();
  return {static_cast<long>(value(values, "candidates", what, run)), value(values, "best_ms", what, run)};
}

PeerNarrowPhase run_peer_narrow_phase(const fs::path& python, const fs::path& script, const fs::path& scene_bin,
                                      const fs::path& hits_file, bool per_pair, int repeats) {
  std::vector<std::string> arguments{python.string(), script.string(), "step", scene_bin.string(), "--hits",
                                     hits_file.string(), "--repeats", std::to_string(repeats)};
  if (per_pair) arguments.push_back("--per-pair");
  const ChildRun run = run_child(arguments, 1);
  if (run.exit_code != 0) throw peer_failure(scene_bin.string(), run);
  const std::map<std::string, double> values = peer_values(run.output);
  const std::string what = scene_bin.string();
  PeerNarrowPhase peer;
  peer.candidates = static_cast<long>(value(values, "candidates", what, run));
  peer.stepsize_ms = value(values, "stepsize_ms", what, run);
  peer.stepsize = value(values, "stepsize", what, run);
  peer.per_pair = per_pair;
  if (!per_pair) return peer;
  peer.loop_ms = value(values, "loop_ms", what, run);
  peer.clean_candidates = static_cast<long>(value(values, "clean_candidates", what, run));
  peer.clean_ms = value(values, "clean_ms", what, run);
  if (value(values, "clean_free", what, run) != 1) throw peer_failure(what + ", a hit among the cleaned candidates", run);
  peer.hits = read_peer_hits(hits_file, peer.earliest_toi);
  return peer;
}

std::vector<CollisionKey> read_peer_hits(const fs::path& hits_file, double& earliest_toi) {
  std::ifstream file(hits_file);
  if (!file) throw std::runtime_error(hits_file.string() + ": cannot read");
  std::vector<CollisionKey> hits;
  earliest_toi = 1;
  std::string line;
  for (long number = 1; std::getline(file, line); ++number) {
    std::istringstream stream(line);
    const std::vector<std::string> words{std::istream_iterator<std::string>(stream),
                                         std::istream_iterator<std::string>()};
    const std::size_t count = words.empty() ? 0 : words[0] == "vf" ? 2 : words[0] == "ee" ? 4 : 0;
    std::array<int, 4> n{-1, -1, -1, -1};
    double toi = 0;
    const auto whole = [](const std::string& word, const char* end) { return end == word.c_str() + word.size(); };
    bool valid = count > 0 && words.size() == count + 2;
    for (std::size_t i = 0; valid && i < count; ++i) {
      char* end = nullptr;
      const long index = std::strtol(words[1 + i].c_str(), &end, 10);
      valid = whole(words[1 + i], end) && index >= 0 && index <= INT_MAX;
      n[i] = static_cast<int>(index);
    }
    if (valid) {
      char* end = nullptr;
      toi = std::strtod(words.back().c_str(), &end);
      valid = whole(words.back(), end);
    }
    if (!valid)
      throw std::runtime_error(hits_file.string() + ":" + std::to_string(number) + ": malformed hit '" + line + "'");
    if (count == 4) {
      std::pair<int, int> a = std::minmax(n[0], n[1]), b = std::minmax(n[2], n[3]);
      if (b < a) std::swap(a, b);
      n = {a.first, a.second, b.first, b.second};
    }
    hits.push_back(n);
    earliest_toi = std::min(earliest_toi, toi);
  }
  std::sort(hits.begin(), hits.end());
  return hits;
}

PeerState run_peer_state(const fs::path& python, const fs::path& script, const fs::path& scene_bin, double dhat,
                         int repeats, const fs::path& contacts_file) {
  std::ostringstream distance;
  distance.precision(17);
  distance << dhat;
  const ChildRun run = run_child({python.string(), script.string(), scene_bin.string(), "--dhat", distance.str(),
                                  "--threads", "1", "--repeats", std::to_string(repeats), "--contacts",
                                  contacts_file.string()}, 1);
  if (run.exit_code != 0) throw peer_failure(scene_bin.string(), run);
  const std::map<std::string, double> values = peer_values(run.output);
  const std::string what = scene_bin.string();
  PeerState peer;
  const char* const types[] = {"vv", "ev", "ee", "fv"};
  for (int t = 0; t < 4; ++t) peer.counts[t] = static_cast<long>(value(values, types[t], what, run));
  peer.build_ms = value(values, "build_ms", what, run);
  peer.build_min_ms = value(values, "build_min_ms", what, run);
  peer.min_distance = value(values, "min_distance", what, run);
  peer.has_intersections_ms = value(values, "has_intersections_ms", what, run);
  peer.has_intersections = value(values, "has_intersections", what, run) != 0;
  return peer;
}

PeerQueries run_peer_queries(const fs::path& python, const fs::path& script, const std::vector<ccd::CcdQuery>& queries,
                             const fs::path& scratch, int repeats) {
  const fs::path input = scratch / "peer-queries.bin", hits_file = scratch / "peer-query-hits.txt";
  {
    std::ofstream out(input, std::ios::binary);
    const std::int64_t count = static_cast<std::int64_t>(queries.size());
    out.write(reinterpret_cast<const char*>(&count), sizeof count);
    for (const ccd::CcdQuery& query : queries) {
      const std::int64_t kind = query.kind == PairKind::VertexFace ? 0 : 1;
      out.write(reinterpret_cast<const char*>(&kind), sizeof kind);
      for (const auto* frame : {&query.start, &query.end})
        for (const Eigen::Vector3d& point : *frame) out.write(reinterpret_cast<const char*>(point.data()), 24);
    }
    if (!out) throw std::runtime_error(input.string() + ": write failed");
  }
  const ChildRun run = run_child({python.string(), script.string(), "queries", input.string(), "--hits",
                                  hits_file.string(), "--repeats", std::to_string(repeats)}, 1);
  if (run.exit_code != 0) throw peer_failure(input.string(), run);
  const std::map<std::string, double> values = peer_values(run.output);
  const std::string what = input.string();
  PeerQueries peer;
  peer.median_call_ns = value(values, "median_call_ns", what, run);
  peer.mean_call_ns = value(values, "mean_call_ns", what, run);
  peer.median_overhead_ns = value(values, "median_overhead_ns", what, run);
  peer.mean_overhead_ns = value(values, "mean_overhead_ns", what, run);
  std::ifstream file(hits_file);
  for (std::string line; std::getline(file, line);) peer.hit.push_back(line.rfind("1 ", 0) == 0 ? 1 : 0);
  if (peer.hit.size() != queries.size())
    throw std::runtime_error(hits_file.string() + ": " + std::to_string(peer.hit.size()) + " answers for " +
                             std::to_string(queries.size()) + " queries");
  return peer;
}

}  // namespace clothcd::bench

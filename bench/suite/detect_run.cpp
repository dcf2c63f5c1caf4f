// `clothcd detect` in a child process, read back from its JSON (see detect_run.hpp).
#include "detect_run.hpp"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <nlohmann/json.hpp>

#include "child_process.hpp"

namespace clothcd::bench {
namespace {

using Json = nlohmann::json;

Json parse(const std::string& text, const std::string& context) {
  try {
    return Json::parse(text);
  } catch (const Json::parse_error& error) {
    throw std::runtime_error(context + ": malformed JSON: " + error.what());
  }
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw std::runtime_error(path.string() + ": cannot read");
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

const Json& member(const Json& object, const std::string& key, const std::string& context) {
  const auto value = object.find(key);
  if (value == object.end()) throw std::runtime_error(context + ": no \"" + key + "\"");
  return *value;
}

// The integers of a JSON array nested to any depth, in order ([[1, 2], [3, 4]] -> 1 2 3 4).
void integers(const Json& value, std::vector<int>& out) {
  if (value.is_number()) out.push_back(value.get<int>());
  if (value.is_array())
    for (const Json& item : value) integers(item, out);
}

// The order-free key of a vertex-face pair {vertex, face} (2 numbers) or an edge-edge pair (4 numbers).
CollisionKey collision_key(const std::vector<int>& n, const std::string& context) {
  if (n.size() == 2) return {n[0], n[1], -1, -1};
  if (n.size() != 4) throw std::runtime_error(context + ": a pair of " + std::to_string(n.size()) + " indices");
  std::pair<int, int> a = std::minmax(n[0], n[1]), b = std::minmax(n[2], n[3]);
  if (b < a) std::swap(a, b);
  return {a.first, a.second, b.first, b.second};
}

// FNV-1a, 64 bits.
class Digest {
 public:
  void add(const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) hash_ = (hash_ ^ bytes[i]) * 0x100000001b3ULL;
  }
  [[nodiscard]] std::string hex() const {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash_));
    return text;
  }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325ULL;
};

// One collision of the JSON: its key, conservative flag and toi.
struct Entry {
  CollisionKey key;
  bool conservative = false;
  double toi = 0;
};

std::vector<Entry> entries(const Json& root, const std::string& list, const std::string& context) {
  std::vector<Entry> out;
  for (const Json& item : member(root, list, context)) {
    std::vector<int> n;
    integers(member(item, "pair", context), n);
    out.push_back({collision_key(n, context), item.value("conservative", false),
                   member(item, "toi", context).get<double>()});
  }
  return out;
}

// `help` names the option `flag` (followed by a space, a comma, an equals sign or the line's end, so that `--exact`
// does not match `--exact-something`).
bool lists_option(const std::string& help, const std::string& flag) {
  for (std::size_t at = help.find(flag); at != std::string::npos; at = help.find(flag, at + 1)) {
    const std::size_t after = at + flag.size();
    const bool starts = at == 0 || help[at - 1] == ' ' || help[at - 1] == ',' || help[at - 1] == '\n';
    if (starts && (after == help.size() || std::strchr(" ,=\n", help[after]) != nullptr)) return true;
  }
  return false;
}

// Runs `arguments` (a clothcd detect call on `t0`) on the first `cpus` CPUs; throws with its output when it fails.
ChildRun run_detect_child(const std::vector<std::string>& arguments, int cpus, const std::filesystem::path& t0) {
  ChildRun child = run_child(arguments, cpus);
  if (child.exit_code != 0)
    throw std::runtime_error("clothcd detect " + t0.string() + " failed (exit " + std::to_string(child.exit_code) +
                             "): " + child.output);
  return child;
}

// The counts and stage times of a detect report.
DetectStages read_stages(const Json& root, const std::string& context) {
  const Json& counts = member(root, "counts", context);
  const Json& times = member(root, "times_ms", context);
  DetectStages stages;
  stages.candidates = member(counts, "candidates_vertex_face", context).get<long>() +
                      member(counts, "candidates_edge_edge", context).get<long>();
  stages.culled = member(counts, "culled", context).get<long>();
  stages.refit_ms = member(times, "refit", context).get<double>();
  stages.traversal_ms = member(times, "traversal", context).get<double>();
  stages.culling_ms = member(times, "filters", context).get<double>();
  stages.exact_ms = member(times, "exact", context).get<double>();
  return stages;
}

}  // namespace

std::vector<std::string> detect_mode_flags_from_help(const std::string& help, DetectMode mode) {
  const std::string flag = mode == DetectMode::Approximate ? "--approximate" : "--exact";
  if (lists_option(help, flag)) return {flag};
  return {};
}

std::vector<std::string> detect_mode_flags(const std::filesystem::path& clothcd, DetectMode mode) {
  const ChildRun child = run_child({clothcd.string(), "detect", "--help"}, 1);
  if (child.exit_code != 0)
    throw std::runtime_error(clothcd.string() + " detect --help failed (exit " + std::to_string(child.exit_code) +
                             "): " + child.output);
  return detect_mode_flags_from_help(child.output, mode);
}

bool detect_has_earliest(const std::filesystem::path& clothcd) {
  const ChildRun child = run_child({clothcd.string(), "detect", "--help"}, 1);
  return child.exit_code == 0 && lists_option(child.output, "--earliest");
}

DetectRun run_detect(const std::filesystem::path& clothcd, const std::filesystem::path& t0,
                     const std::filesystem::path& t1, const std::filesystem::path& json_out, int cpus,
                     const std::vector<std::string>& flags) {
  std::vector<std::string> arguments{clothcd.string(), "detect", t0.string(), t1.string(), "--out", json_out.string()};
  arguments.insert(arguments.end(), flags.begin(), flags.end());
  const ChildRun child = run_detect_child(arguments, cpus, t0);
  const std::string context = json_out.string();
  const Json root = parse(read_text(json_out), context);
  DetectRun run;
  static_cast<DetectStages&>(run) = read_stages(root, context);
  run.peak_rss_mb = child.peak_rss_mb;
  std::vector<Entry> all = entries(root, "vertex_face", context);
  for (const Entry& e : entries(root, "edge_edge", context)) all.push_back(e);
  std::sort(all.begin(), all.end(), [](const Entry& a, const Entry& b) { return a.key < b.key; });
  Digest digest;
  for (const Entry& e : all) {
    std::uint64_t toi_bits = 0;
    std::memcpy(&toi_bits, &e.toi, sizeof toi_bits);
    digest.add(e.key.data(), sizeof e.key);
    digest.add(&e.conservative, sizeof e.conservative);
    digest.add(&toi_bits, sizeof toi_bits);
    run.collisions.push_back(e.key);
    run.conservative += e.conservative ? 1 : 0;
    run.earliest_toi = std::min(run.earliest_toi, e.toi);
  }
  run.digest = digest.hex();
  return run;
}

EarliestRun run_earliest(const std::filesystem::path& clothcd, const std::filesystem::path& t0,
                         const std::filesystem::path& t1, const std::filesystem::path& json_out, int cpus) {
  run_detect_child({clothcd.string(), "detect", t0.string(), t1.string(), "--earliest", "--out", json_out.string()},
                   cpus, t0);
  const std::string context = json_out.string();
  const Json root = parse(read_text(json_out), context);
  const Json& earliest = member(root, "earliest", context);
  EarliestRun run;
  static_cast<DetectStages&>(run) = read_stages(root, context);
  run.toi = member(earliest, "toi", context).get<double>();
  run.windows = member(earliest, "windows", context).get<int>();
  return run;
}

TruthCheck check_truth(const std::filesystem::path& truth_json, const std::vector<CollisionKey>& found) {
  const std::string context = truth_json.string();
  const Json root = parse(read_text(truth_json), context);
  TruthCheck check;
  for (const char* list : {"vf", "ee"}) {
    for (const Json& pair : member(root, list, context)) {
      std::vector<int> n;
      integers(pair, n);
      ++check.listed;
      if (!std::binary_search(found.begin(), found.end(), collision_key(n, context))) ++check.missed;
    }
  }
  return check;
}

}  // namespace clothcd::bench

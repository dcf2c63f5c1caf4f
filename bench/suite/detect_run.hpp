#pragma once
/// @file
/// One `clothcd detect T0 T1 --out FILE` run in a child process pinned to some CPUs, in a chosen narrow-phase mode: its
/// counts, stage times, peak resident memory and a digest of its collisions, read back from the JSON it writes; and
/// the ground-truth check of those collisions against a `truth.json` of the shared scenes.

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace clothcd::bench {

/// A collision as `clothcd detect --out` names it, in a form that does not depend on the order of its parts:
/// vertex-face {vertex, face, -1, -1}; edge-edge {a0, a1, b0, b1} with a0 < a1, b0 < b1 and (a0, a1) < (b0, b1).
using CollisionKey = std::array<int, 4>;

/// The counts and stage times of one `clothcd detect` run (its JSON's `counts` and `times_ms`).
struct DetectStages {
  long candidates = 0;      ///< Vertex-face + edge-edge candidate pairs after the broad phase.
  long culled = 0;          ///< Pairs the culling stage removed.
  double refit_ms = 0;      ///< Hierarchy build or refit.
  double traversal_ms = 0;  ///< Candidate search.
  double culling_ms = 0;    ///< Culling stage.
  double exact_ms = 0;      ///< Exact CCD.

  /// The whole search: hierarchy + candidates + culling + exact test.
  [[nodiscard]] double whole_ms() const { return refit_ms + traversal_ms + culling_ms + exact_ms; }
};

/// What one detect run measured.
struct DetectRun : DetectStages {
  double peak_rss_mb = 0;   ///< Peak resident memory of the whole `clothcd detect` process (loading included).
  std::vector<CollisionKey> collisions;  ///< Every collision, sorted.
  long conservative = 0;    ///< Collisions flagged `conservative` (undecided, reported as hits).
  double earliest_toi = 1;  ///< The smallest toi of the collisions (1 when there are none).
  std::string digest;       ///< 16 hex digits over the sorted collisions, their conservative flags and tois.
};

/// How the narrow phase decides the pieces of a step that the floating-point fast tier leaves undecided at thickness 0.
enum class DetectMode {
  Approximate,  ///< Reported as `conservative` hits (the detector's default before exact decisions were).
  Exact,        ///< Decided exactly: every reported collision is a real one.
};

/// The flags that select `mode` in `clothcd detect` of the program `clothcd`, from the options its `detect --help`
/// lists: Approximate: `--approximate` when listed, else none (a program without it is approximate by default);
/// Exact: `--exact` when listed, else none (a program without it is exact by default). Throws std::runtime_error when
/// `detect --help` fails.
[[nodiscard]] std::vector<std::string> detect_mode_flags(const std::filesystem::path& clothcd, DetectMode mode);

/// The same choice from the text of `detect --help` (see the overload above).
[[nodiscard]] std::vector<std::string> detect_mode_flags_from_help(const std::string& help, DetectMode mode);

/// Runs `clothcd detect t0 t1 --out json_out FLAGS...` (thickness 0, the default hierarchy and filters; `flags` from
/// detect_mode_flags) on the first `cpus` CPUs and reads its JSON. Throws std::runtime_error with the program's output
/// when it fails.
[[nodiscard]] DetectRun run_detect(const std::filesystem::path& clothcd, const std::filesystem::path& t0,
                                   const std::filesystem::path& t1, const std::filesystem::path& json_out, int cpus,
                                   const std::vector<std::string>& flags);

/// What one `clothcd detect --earliest` run measured (counts and times summed over its windows).
struct EarliestRun : DetectStages {
  double toi = 1;   ///< The step's earliest time of impact (1: no contact).
  int windows = 0;  ///< Time windows searched.
};

/// True when `clothcd detect --help` of the program `clothcd` lists `--earliest` (older programs have no such search).
[[nodiscard]] bool detect_has_earliest(const std::filesystem::path& clothcd);

/// Runs `clothcd detect t0 t1 --earliest --out json_out` on the first `cpus` CPUs and reads its JSON. Throws
/// std::runtime_error with the program's output when it fails.
[[nodiscard]] EarliestRun run_earliest(const std::filesystem::path& clothcd, const std::filesystem::path& t0,
                                       const std::filesystem::path& t1, const std::filesystem::path& json_out,
                                       int cpus);

/// Ground-truth pairs of `truth_json` (the shared scenes' format: "vf": [[vertex, face]...], "ee": [[[a0, a1],
/// [b0, b1]]...]) that `found` (sorted) lacks, and how many pairs the file lists.
struct TruthCheck {
  long listed = 0;  ///< Pairs in the file.
  long missed = 0;  ///< Of those, not among the collisions.
};

/// Checks `found` against `truth_json`; throws std::runtime_error naming the file when it cannot be read.
[[nodiscard]] TruthCheck check_truth(const std::filesystem::path& truth_json, const std::vector<CollisionKey>& found);

}  // namespace clothcd::bench

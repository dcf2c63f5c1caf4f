#pragma once
/// @file
/// The IPC Toolkit peer (the `ipctk` wheel from PyPI) as the benchmarks run it: its Python environment, a step's frames
/// written for its scripts, its LBVH candidate search (bench/peers/ipctk_candidates.py), and its Tight-Inclusion
/// narrow phase (bench/peers/ipctk_narrow_phase.py) on a step's own LBVH candidates or on single queries, read back
/// into the bench's collision keys.

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bench_section.hpp"
#include "clothcd/ccd/ccd.hpp"
#include "clothcd/mesh/mesh_frames.hpp"
#include "detect_run.hpp"

namespace clothcd::bench {

/// The Python of the benchmarks' environment (.cache/bench-venv of the repository) when it runs `script --version`
/// (which imports ipctk), creating the environment with bench/peers/setup-ipctk.sh first; nothing in a quick run.
/// `status` gets the peer's version, or why there is none.
[[nodiscard]] std::optional<std::filesystem::path> peer_python(const BenchContext& context,
                                                               const std::filesystem::path& script,
                                                               std::string& status);

/// The `name=value` words of a peer script's output line, values as numbers.
[[nodiscard]] std::map<std::string, double> peer_values(const std::string& output);

/// Writes a step's two frames for the peer's scripts (SCENE.bin, the format bench/peers/ipctk_candidates.py reads:
/// vertex and face counts, start and end positions, faces). Throws std::runtime_error naming `path` when the write
/// fails.
void write_peer_scene(const MeshFrames& frames, const std::filesystem::path& path);

/// The peer's LBVH candidate search on one step at one thread count.
struct PeerCandidateSearch {
  long candidates = 0;  ///< Vertex-face + edge-edge candidate pairs it found.
  double ms = 0;        ///< Its time (`Candidates.build` alone).
};

/// Runs `script scene_bin --threads T --repeats 1` (bench/peers/ipctk_candidates.py) with `python` on the first
/// `threads` CPUs. Throws std::runtime_error with its output when it fails.
[[nodiscard]] PeerCandidateSearch run_peer_candidates(const std::filesystem::path& python,
                                                      const std::filesystem::path& script,
                                                      const std::filesystem::path& scene_bin, int threads);

/// The peer's narrow phase on one step (see bench/peers/ipctk_narrow_phase.py for what each time covers).
struct PeerNarrowPhase {
  long candidates = 0;         ///< The peer's own LBVH candidates.
  double stepsize_ms = 0;      ///< compute_collision_free_stepsize on every candidate (C++, one thread).
  double stepsize = 1;         ///< Its result: the earliest toi found, times the peer's conservative rescaling.
  bool per_pair = false;       ///< The candidates were also decided one at a time (the fields below are set).
  std::vector<CollisionKey> hits;  ///< The candidates its per-pair CCD reports as colliding, sorted.
  double earliest_toi = 1;     ///< The smallest toi of those.
  double loop_ms = 0;          ///< The per-pair loop from Python, call overhead included.
  long clean_candidates = 0;   ///< The candidates without its hits.
  double clean_ms = 0;         ///< is_step_collision_free on those (C++, one thread, no early exit).
};

/// Runs `script step scene_bin --hits hits_file [--per-pair] --repeats R` with `python` on one CPU. Throws
/// std::runtime_error with its output when it fails.
[[nodiscard]] PeerNarrowPhase run_peer_narrow_phase(const std::filesystem::path& python,
                                                    const std::filesystem::path& script,
                                                    const std::filesystem::path& scene_bin,
                                                    const std::filesystem::path& hits_file, bool per_pair,
                                                    int repeats);

/// Reads the hits a per-pair run wrote (`vf VERTEX FACE TOI` / `ee A0 A1 B0 B1 TOI` lines) as sorted keys, and their
/// smallest toi into `earliest_toi`. Throws std::runtime_error naming the file on a malformed line.
[[nodiscard]] std::vector<CollisionKey> read_peer_hits(const std::filesystem::path& hits_file, double& earliest_toi);

/// The peer's questions of one state (bench/peers/ipctk_state.py), best times over its repeats, one thread.
struct PeerState {
  std::array<long, 4> counts{};  ///< Its active set by type: vertex-vertex, edge-vertex, edge-edge, face-vertex.
  double build_ms = 0;           ///< NormalCollisions.build with its LBVH broad phase.
  double build_min_ms = 0;       ///< That build followed by compute_minimum_distance.
  double min_distance = 0;       ///< The minimum distance over the active set (infinite when it is empty).
  double has_intersections_ms = 0;  ///< has_intersections with its LBVH broad phase.
  bool has_intersections = false;   ///< Its answer.
};

/// Runs `script scene_bin --dhat D --threads 1 --repeats R --contacts contacts_file` with `python` on one CPU (the
/// scene's start positions are the state). Throws std::runtime_error with its output when it fails.
[[nodiscard]] PeerState run_peer_state(const std::filesystem::path& python, const std::filesystem::path& script,
                                       const std::filesystem::path& scene_bin, double dhat, int repeats,
                                       const std::filesystem::path& contacts_file);

/// The peer's answers on single queries.
struct PeerQueries {
  std::vector<std::uint8_t> hit;    ///< Per query, 1 when reported colliding.
  double median_call_ns = 0;        ///< One call from Python, median over the queries (best of the repeats each).
  double mean_call_ns = 0;          ///< The same, mean.
  double median_overhead_ns = 0;    ///< A bounding-box test's call on the same points: the call overhead, median.
  double mean_overhead_ns = 0;      ///< The same, mean.
};

/// Writes `queries` (bench/peers/ipctk_narrow_phase.py's QUERIES.bin), runs `script queries` on them on one CPU and
/// reads its answers. Throws std::runtime_error with its output when it fails.
[[nodiscard]] PeerQueries run_peer_queries(const std::filesystem::path& python, const std::filesystem::path& script,
                                           const std::vector<ccd::CcdQuery>& queries,
                                           const std::filesystem::path& scratch, int repeats);

}  // namespace clothcd::bench

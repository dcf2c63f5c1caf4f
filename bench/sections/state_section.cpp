// Section "state": the questions of one state (CollisionDetector::proximity, minimum_distance, intersections,
// is_intersection_free) on the shared steps' start and end states and the generated steps' start states, the mesh as
// one body, at distances of 1e-3 and 1e-4 of the bounding-box diagonal, on one thread and on two, warm detector;
// beside the IPC Toolkit's NormalCollisions.build / compute_minimum_distance / has_intersections (bench/peers/
// ipctk_state.py) and CGAL's self_intersections / does_self_intersect in the same run, the counts side by side and
// every difference decided exactly; with the state-query issue's targets.
#include <CGAL/version.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "../suite/bench_section.hpp"
#include "../suite/bench_util.hpp"
#include "../suite/cgal_intersection_peer.hpp"
#include "../suite/ipctk_peer.hpp"
#include "../suite/peak_memory.hpp"
#include "../suite/state_differences.hpp"
#include "../suite/thrown_bodies.hpp"
#include "clothcd/detection/collision_detector.hpp"
#include "clothcd/mesh/mesh_frames.hpp"

namespace clothcd::bench {
namespace {

namespace fs = std::filesystem;

constexpr std::array<double, 2> kRelativeDistances{1e-3, 1e-4};
constexpr std::size_t kListedDifferences = 50;  // per comparison in state_differences.csv
constexpr double kLongQueryMs = 10;             // the two-thread target applies from here
constexpr double kSlowCallMs = 1000;            // a call this long is timed once

using Rows = std::vector<std::vector<std::string>>;

// One state: a mesh as one body at one set of positions.
struct State {
  std::string name;
  Faces faces;
  Vertices positions;
  double diagonal = 0;
};

// Ours on one thread ([0]) and on two ([1]).
using PerThreads = std::array<double, 2>;

// One state at one distance.
struct DistanceResult {
  double relative = 0, distance = 0;
  PerThreads proximity_ms{}, minimum_ms{};
  double unbounded_minimum_ms = 0;  // minimum_distance without an upper bound, one thread
  long pairs = 0;
  std::array<long, 4> contacts{};  // closest_feature_contacts by ContactKind
  MinimumDistance minimum;
  std::optional<PeerState> peer;
  std::vector<ContactDifference> differences;
};

// Everything measured on one state.
struct StateResult {
  std::string name;
  long vertices = 0, faces = 0;
  std::vector<DistanceResult> distances;
  PerThreads intersections_ms{}, free_ms{};
  long intersections = 0;
  bool free = true;
  long cgal_refused = 0;  // faces CGAL's Surface_mesh refused (then CGAL is not compared)
  std::optional<double> cgal_ms, cgal_parallel_ms, cgal_does_ms;
  long cgal_intersections = 0;
  bool cgal_does = false;
  std::vector<FacePairDifference> cgal_differences;
  std::optional<double> detect_mb, proximity_mb, intersections_mb;  // peak growth, one thread, cold detector
  double proximity_records_mb = 0, intersection_records_mb = 0;
};

// The states: the shared steps' start and end (not in a quick run), then the generated steps' start states.
std::vector<State> states_to_measure(const BenchContext& context) {
  std::vector<State> states;
  const auto add = [&](const std::string& name, const Faces& faces, const Vertices& positions) {
    const Eigen::Vector3d extent = positions.colwise().maxCoeff() - positions.colwise().minCoeff();
    states.push_back({name, faces, positions, extent.norm()});
  };
  if (context.scalable_ccd && !context.quick)
    for (const char* scene : {"cloth-funnel", "rod-twist"}) {
      const fs::path dir = *context.scalable_ccd / scene;
      if (!fs::exists(dir / "t0.ply") || !fs::exists(dir / "t1.ply")) continue;
      const MeshFrames frames = load_mesh_frames(dir / "t0.ply", dir / "t1.ply");
      add(std::string(scene) + " t0", frames.start.faces, frames.start.vertices);
      add(std::string(scene) + " t1", frames.start.faces, frames.end);
    }
  std::vector<ThrownBodiesSpec> specs{{"thrown-8-small", 8, 8, 1.0, 1}};
  if (!context.quick) specs = {{"thrown-8", 8, 14, 1.0, 1}, {"thrown-16", 16, 16, 1.0, 2}};
  if (!context.quick && !context.part_of_all) specs.push_back({"thrown-32", 32, 18, 1.0, 3});
  for (const ThrownBodiesSpec& spec : specs) {
    const ThrownBodiesStep step = make_thrown_bodies(spec);
    add(spec.name + " t0", step.start.faces, step.start.vertices);
  }
  return states;
}

// The best time of `repeats` calls of `work` after one untimed call (a warm detector); one call when the untimed one
// took longer than kSlowCallMs (the shared machine's noise is small beside such a call).
double warm_best_ms(int repeats, const std::function<void()>& work) {
  if (time_ms(work) > kSlowCallMs) repeats = 1;
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < repeats; ++r) best = std::min(best, time_ms(work));
  return best;
}

// The best time of `repeats` calls of `work`.
double best_ms(int repeats, const std::function<void()>& work) {
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < repeats; ++r) best = std::min(best, time_ms(work));
  return best;
}

CollisionDetector make_detector(const State& state) {
  DetectorSettings settings;
  settings.parallel = true;  // the thread count comes from tbb::global_control
  return CollisionDetector(state.faces, static_cast<int>(state.positions.rows()), settings);
}

// Our four queries at `threads` threads, warm detector, into slot `t` of `result`.
void measure_ours(const State& state, int threads, int repeats, StateResult& result) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  const std::size_t t = threads == 1 ? 0 : 1;
  CollisionDetector detector = make_detector(state);
  const PositionsRef positions(state.positions);
  for (DistanceResult& d : result.distances) {
    d.proximity_ms[t] = warm_best_ms(repeats, [&] { (void)detector.proximity(positions, d.distance); });
    d.minimum_ms[t] = warm_best_ms(repeats, [&] { d.minimum = detector.minimum_distance(positions, d.distance); });
    if (t > 0) continue;
    d.unbounded_minimum_ms = warm_best_ms(repeats, [&] { (void)detector.minimum_distance(positions); });
    const std::vector<Proximity>& pairs = detector.proximity(positions, d.distance);
    d.pairs = static_cast<long>(pairs.size());
    for (const FeatureContact& c : closest_feature_contacts(pairs)) ++d.contacts[static_cast<int>(c.kind)];
  }
  result.intersections_ms[t] = warm_best_ms(repeats, [&] { (void)detector.intersections(positions); });
  result.free_ms[t] = warm_best_ms(repeats, [&] { result.free = detector.is_intersection_free(positions); });
  result.intersections = static_cast<long>(detector.intersections(positions).size());
}

// Peak memory growth of a cold detector's detect() (start = end = the state) and of its state queries, one thread.
void measure_memory(const State& state, StateResult& result) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
  const PositionsRef positions(state.positions);
  result.detect_mb = peak_growth_mb([&] { (void)make_detector(state).detect(positions, positions); });
  const double distance = result.distances.front().distance;
  result.proximity_mb = peak_growth_mb([&] { (void)make_detector(state).proximity(positions, distance); });
  result.intersections_mb = peak_growth_mb([&] { (void)make_detector(state).intersections(positions); });
  const double mib = 1024.0 * 1024.0;
  result.proximity_records_mb = static_cast<double>(result.distances.front().pairs) * sizeof(Proximity) / mib;
  result.intersection_records_mb = static_cast<double>(result.intersections) * sizeof(FaceIntersection) / mib;
}

// CGAL's self-intersection tests on the state, one thread and two (Parallel_tag), against our list.
void measure_cgal(const State& state, int repeats, StateResult& result, const std::vector<FacePair>& ours) {
  const CgalMesh mesh(state.faces, state.positions);
  result.cgal_refused = mesh.refused();
  if (result.cgal_refused > 0) return;
  std::vector<FacePair> pairs;
  {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    result.cgal_ms = best_ms(repeats, [&] { pairs = mesh.self_intersections(false); });
    result.cgal_does_ms = best_ms(repeats, [&] { result.cgal_does = mesh.does_self_intersect(); });
  }
  {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    result.cgal_parallel_ms = best_ms(repeats, [&] { (void)mesh.self_intersections(true); });
  }
  result.cgal_intersections = static_cast<long>(pairs.size());
  result.cgal_differences = face_pair_differences(ours, pairs, state.faces, state.positions);
}

// The peer's questions of the state at each distance, and its active set against our contacts.
void measure_ipctk(const State& state, const fs::path& python, const fs::path& script, const fs::path& scratch,
                   int repeats, StateResult& result) {
  const fs::path scene = scratch / "state.bin", contacts = scratch / "contacts.txt";
  write_peer_scene({{state.positions, state.faces}, state.positions}, scene);
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
  CollisionDetector detector = make_detector(state);
  for (DistanceResult& d : result.distances) {
    d.peer = run_peer_state(python, script, scene, d.distance, repeats, contacts);
    const std::vector<ContactKey> ours = contact_keys(closest_feature_contacts(detector.proximity(state.positions,
                                                                                                  d.distance)));
    d.differences = contact_differences(ours, read_peer_contacts(contacts), state.positions, d.distance);
  }
}

// Everything on one state: ours on one thread and on two, memory, then the peers.
StateResult measure_state(const BenchContext& context, const State& state, const std::optional<fs::path>& python,
                          const fs::path& script, const fs::path& scratch) {
  StateResult result;
  result.name = state.name;
  result.vertices = static_cast<long>(state.positions.rows());
  result.faces = static_cast<long>(state.faces.rows());
  for (const double relative : kRelativeDistances) {
    DistanceResult& d = result.distances.emplace_back();
    d.relative = relative;
    d.distance = relative * state.diagonal;
  }
  const int repeats = context.quick ? 1 : 5;
  context.progress(state.name + " (" + std::to_string(result.faces) + " faces): our state queries, 1 and 2 threads");
  measure_ours(state, 1, repeats, result);
  measure_ours(state, 2, repeats, result);
  measure_memory(state, result);
  if (context.quick) return result;  // the peers are not run in a quick run
  context.progress(state.name + ": CGAL self_intersections");
  measure_cgal(state, 3, result, face_pairs(make_detector(state).intersections(state.positions)));
  if (python) {
    context.progress(state.name + ": ipctk NormalCollisions");
    measure_ipctk(state, *python, script, scratch, 3, result);
  }
  return result;
}

std::string verdict(bool met) { return met ? "met" : "**missed**"; }

std::string opt_ms(const std::optional<double>& v) { return v ? number(*v, 4) : ""; }

std::string contact_vertices(const ContactKey& key) {
  std::string text;
  for (int i = 1; i < 5 && key[i] >= 0; ++i) text += (i > 1 ? " " : "") + std::to_string(key[i]);
  return text;
}

// state.csv: one row per state and distance.
void write_state_csv(const fs::path& path, const std::vector<StateResult>& results) {
  CsvFile csv(path,
              "state,vertices,faces,relative_distance,distance,pairs,vv,ve,ee,vf,ipc_vv,ipc_ev,ipc_ee,ipc_fv,"
              "proximity_1t_ms,proximity_2t_ms,ipc_build_ms,minimum_1t_ms,minimum_2t_ms,minimum_unbounded_1t_ms,"
              "ipc_build_min_ms,min_distance,ipc_min_distance,contact_differences,intersections,cgal_intersections,"
              "face_pair_differences,intersections_1t_ms,intersections_2t_ms,cgal_1t_ms,cgal_2t_ms,free_1t_ms,"
              "free_2t_ms,intersection_free,ipc_has_intersections_ms,ipc_has_intersections,cgal_does_self_intersect_ms,"
              "peak_detect_mb,peak_proximity_mb,peak_intersections_mb,proximity_records_mb,intersection_records_mb");
  for (const StateResult& r : results)
    for (const DistanceResult& d : r.distances) {
      const auto peer = [&](auto get) { return d.peer ? number(get(*d.peer), 6) : std::string(); };
      csv.row({r.name, std::to_string(r.vertices), std::to_string(r.faces), number(d.relative, 2), number(d.distance, 6),
               std::to_string(d.pairs), std::to_string(d.contacts[0]), std::to_string(d.contacts[1]),
               std::to_string(d.contacts[2]), std::to_string(d.contacts[3]),
               peer([](const PeerState& p) { return p.counts[0]; }), peer([](const PeerState& p) { return p.counts[1]; }),
               peer([](const PeerState& p) { return p.counts[2]; }), peer([](const PeerState& p) { return p.counts[3]; }),
               number(d.proximity_ms[0], 4), number(d.proximity_ms[1], 4),
               peer([](const PeerState& p) { return p.build_ms; }), number(d.minimum_ms[0], 4),
               number(d.minimum_ms[1], 4), number(d.unbounded_minimum_ms, 4),
               peer([](const PeerState& p) { return p.build_min_ms; }),
               d.minimum.found ? number(d.minimum.distance, 8) : "inf",
               peer([](const PeerState& p) { return p.min_distance; }),
               d.peer ? std::to_string(d.differences.size()) : "", std::to_string(r.intersections),
               r.cgal_ms ? std::to_string(r.cgal_intersections) : "",
               r.cgal_ms ? std::to_string(r.cgal_differences.size()) : "", number(r.intersections_ms[0], 4),
               number(r.intersections_ms[1], 4), opt_ms(r.cgal_ms), opt_ms(r.cgal_parallel_ms),
               number(r.free_ms[0], 4), number(r.free_ms[1], 4), r.free ? "yes" : "no",
               peer([](const PeerState& p) { return p.has_intersections_ms; }),
               d.peer ? (d.peer->has_intersections ? "yes" : "no") : "", opt_ms(r.cgal_does_ms),
               opt_ms(r.detect_mb), opt_ms(r.proximity_mb), opt_ms(r.intersections_mb),
               number(r.proximity_records_mb, 4), number(r.intersection_records_mb, 4)});
    }
}

// state_differences.csv: the first kListedDifferences of each comparison, with its total.
void write_differences_csv(const fs::path& path, const std::vector<StateResult>& results) {
  CsvFile csv(path, "peer,state,relative_distance,total,only_in,kind,primitives,exact_distance,exact_answer,"
              "nearly_parallel_edges");
  for (const StateResult& r : results) {
    for (const DistanceResult& d : r.distances)
      for (std::size_t i = 0; i < std::min(kListedDifferences, d.differences.size()); ++i) {
        const ContactDifference& c = d.differences[i];
        csv.row({"ipctk", r.name, number(d.relative, 2), std::to_string(d.differences.size()),
                 c.ours ? "clothcd" : "ipctk", contact_kind_name(c.key[0]), contact_vertices(c.key),
                 number(c.distance, 10), c.exact_below ? "below d" : "not below d",
                 c.key[0] == static_cast<int>(ContactKind::EdgeEdge) ? (c.nearly_parallel ? "yes" : "no") : ""});
      }
    for (std::size_t i = 0; i < std::min(kListedDifferences, r.cgal_differences.size()); ++i) {
      const FacePairDifference& f = r.cgal_differences[i];
      csv.row({"cgal", r.name, "", std::to_string(r.cgal_differences.size()), f.ours ? "clothcd" : "cgal", "faces",
               std::to_string(f.faces[0]) + " " + std::to_string(f.faces[1]), "",
               f.exact_intersects ? "intersect" : "do not intersect", ""});
    }
  }
}

// The targets, one row each: measure, ours, peer, ratio, target, verdict.
Rows target_rows(const std::vector<StateResult>& results) {
  Rows rows;
  const auto speed = [&](const std::string& what, double ours, double peer, double target) {
    const double ratio = peer / ours;
    rows.push_back({what, number(ours, 4), number(peer, 4), number(ratio, 4), ">= " + number(target, 3) + "x",
                    verdict(ratio >= target)});
  };
  for (const StateResult& r : results) {
    for (const DistanceResult& d : r.distances) {
      const std::string at = r.name + ", d = " + number(d.relative, 2) + " diag";
      if (d.peer) {
        speed("proximity vs ipctk build, 1 thread, " + at, d.proximity_ms[0], d.peer->build_ms, 10);
        speed("minimum distance vs ipctk build + minimum, 1 thread, " + at, d.minimum_ms[0], d.peer->build_min_ms, 10);
      }
      if (d.proximity_ms[0] >= kLongQueryMs) speed("proximity, 2 threads vs 1, " + at, d.proximity_ms[1], d.proximity_ms[0], 1.8);
      if (d.minimum_ms[0] >= kLongQueryMs) speed("minimum distance, 2 threads vs 1, " + at, d.minimum_ms[1], d.minimum_ms[0], 1.8);
    }
    if (r.cgal_ms) speed("intersections vs CGAL self_intersections, 1 thread, " + r.name, r.intersections_ms[0], *r.cgal_ms, 5);
    const DistanceResult& first = r.distances.front();
    if (first.peer)
      speed("is_intersection_free vs ipctk has_intersections, 1 thread, " + r.name, r.free_ms[0],
            first.peer->has_intersections_ms, 5);
    if (r.intersections_ms[0] >= kLongQueryMs)
      speed("intersections, 2 threads vs 1, " + r.name, r.intersections_ms[1], r.intersections_ms[0], 1.8);
    if (r.free_ms[0] >= kLongQueryMs)
      speed("is_intersection_free, 2 threads vs 1, " + r.name, r.free_ms[1], r.free_ms[0], 1.8);
    const auto memory = [&](const std::string& what, const std::optional<double>& query, double records) {
      if (!query || !r.detect_mb) return;
      const double budget = *r.detect_mb + records;
      rows.push_back({"peak memory, " + what + " vs detect() + records (MiB), " + r.name, number(*query, 4),
                      number(budget, 4), number(*query / budget, 3), "<= 1", verdict(*query <= budget)});
    };
    memory("proximity at 1e-3 diag", r.proximity_mb, r.proximity_records_mb);
    memory("intersections", r.intersections_mb, r.intersection_records_mb);
  }
  return rows;
}

// The table of times and counts, one row per state and distance.
std::string figures_table(const std::vector<StateResult>& results) {
  Rows rows;
  for (const StateResult& r : results)
    for (const DistanceResult& d : r.distances) {
      const auto ratio = [](double ours, double peer) { return number(peer / ours, 3) + "x"; };
      const std::string ipc_counts =
          d.peer ? std::to_string(d.peer->counts[0]) + "/" + std::to_string(d.peer->counts[1]) + "/" +
                       std::to_string(d.peer->counts[2]) + "/" + std::to_string(d.peer->counts[3])
                 : "-";
      rows.push_back(
          {r.name + " (" + std::to_string(r.faces) + " f)", number(d.relative, 2),
           std::to_string(d.pairs) + " (" + std::to_string(d.contacts[0]) + "/" + std::to_string(d.contacts[1]) + "/" +
               std::to_string(d.contacts[2]) + "/" + std::to_string(d.contacts[3]) + ")",
           ipc_counts, d.peer ? std::to_string(d.differences.size()) : "-",
           number(d.proximity_ms[0], 3) + " / " + number(d.proximity_ms[1], 3),
           d.peer ? number(d.peer->build_ms, 4) + " (" + ratio(d.proximity_ms[0], d.peer->build_ms) + ")" : "-",
           number(d.minimum_ms[0], 3) + " / " + number(d.minimum_ms[1], 3) + " (unbounded " +
               number(d.unbounded_minimum_ms, 3) + ")",
           d.peer ? number(d.peer->build_min_ms, 4) + " (" + ratio(d.minimum_ms[0], d.peer->build_min_ms) + ")" : "-",
           (d.minimum.found ? number(d.minimum.distance, 6) : "none") + " / " +
               (d.peer ? number(d.peer->min_distance, 6) : "-")});
    }
  return markdown_table({"state", "d / diag", "our pairs (contacts vv/ve/ee/vf)", "ipctk vv/ev/ee/fv", "differences",
                         "proximity ms, 1T / 2T", "ipctk build ms (ratio)", "minimum ms, 1T / 2T",
                         "ipctk build + minimum ms (ratio)", "min distance, ours / ipctk"},
                        rows);
}

// Every contact difference of every state and distance by side, kind, exact answer and (edge-edge) parallelism.
std::string differences_summary(const std::vector<StateResult>& results) {
  std::map<std::string, long> groups;
  long face_pairs_total = 0, face_pairs_wrong = 0;
  bool all_below = true;
  for (const StateResult& r : results) {
    for (const DistanceResult& d : r.distances)
      for (const ContactDifference& c : d.differences) {
        const bool ee = c.key[0] == static_cast<int>(ContactKind::EdgeEdge);
        all_below = all_below && c.exact_below;
        ++groups[std::string("only in ") + (c.ours ? "clothcd" : "ipctk") + ", " + contact_kind_name(c.key[0]) +
                 ", exact distance " + (c.exact_below ? "below d" : "not below d") +
                 (ee ? (c.nearly_parallel ? ", nearly parallel edges" : ", not parallel") : "")];
      }
    for (const FacePairDifference& f : r.cgal_differences) {
      ++face_pairs_total;
      face_pairs_wrong += f.exact_intersects ? 0 : 1;
    }
  }
  Rows rows;
  for (const auto& [group, count] : groups) rows.push_back({group, std::to_string(count)});
  return "Contact differences against ipctk, all states and distances (the listed ones and the rest):\n\n" +
         markdown_table({"difference", "count"}, rows) +
         "\nipctk keeps an edge-edge contact for two nearly parallel edges (its mollifier rule) even where their "
         "closest features are a vertex and an edge or two vertices; clothcd maps such a pair to that vertex-edge or "
         "vertex-vertex contact, which another pair usually gives too. So the contacts only ipctk has are those edge "
         "pairs, and the few only clothcd has are the vertex-edge and vertex-vertex contacts ipctk replaced" +
         std::string(all_below ? "; every one is closer than d exactly, so neither side drops a pair by rounding at "
                                 "the threshold"
                               : "") +
         ".\n\nFace pair differences against CGAL: " +
         std::to_string(face_pairs_total) + " (" + std::to_string(face_pairs_wrong) +
         " where the reporting side is wrong by the exact reference).\n";
}

// The table of intersection tests and memory, one row per state.
std::string intersections_table(const std::vector<StateResult>& results) {
  Rows rows;
  for (const StateResult& r : results) {
    const std::optional<PeerState>& peer = r.distances.front().peer;
    rows.push_back(
        {r.name, std::to_string(r.intersections) + " / " +
                     (r.cgal_ms ? std::to_string(r.cgal_intersections)
                                : r.cgal_refused ? "refused " + std::to_string(r.cgal_refused) + " faces" : "-"),
         r.cgal_ms ? std::to_string(r.cgal_differences.size()) : "-",
         number(r.intersections_ms[0], 3) + " / " + number(r.intersections_ms[1], 3),
         r.cgal_ms ? number(*r.cgal_ms, 4) + " / " + number(*r.cgal_parallel_ms, 4) + " (" +
                         number(*r.cgal_ms / r.intersections_ms[0], 3) + "x)"
                   : "-",
         number(r.free_ms[0], 3) + " / " + number(r.free_ms[1], 3) + (r.free ? " (free)" : " (not free)"),
         peer ? number(peer->has_intersections_ms, 4) + " (" + number(peer->has_intersections_ms / r.free_ms[0], 3) +
                    "x)" + (peer->has_intersections ? " yes" : " no")
              : "-",
         r.cgal_does_ms ? number(*r.cgal_does_ms, 4) + (r.cgal_does ? " yes" : " no") : "-",
         opt_ms(r.detect_mb) + " / " + opt_ms(r.proximity_mb) + " / " + opt_ms(r.intersections_mb)});
  }
  return markdown_table({"state", "intersections, ours / CGAL", "differences", "intersections ms, 1T / 2T",
                         "CGAL self_intersections ms, 1T / 2T (ratio)", "is_intersection_free ms, 1T / 2T",
                         "ipctk has_intersections ms (ratio)", "CGAL does_self_intersect ms",
                         "peak MiB: detect / proximity / intersections"},
                        rows);
}

SectionReport run_state(const BenchContext& context) {
  const ScratchFolder scratch("state");
  std::string status = "not run";
  std::optional<fs::path> python;
  const fs::path script = context.repository / "bench" / "peers" / "ipctk_state.py";
  if (!context.repository.empty()) python = peer_python(context, script, status);
  std::vector<StateResult> results;
  for (const State& state : states_to_measure(context))
    results.push_back(measure_state(context, state, python, script, scratch.path()));
  write_state_csv(context.out_dir / "state.csv", results);
  write_differences_csv(context.out_dir / "state_differences.csv", results);
  const Rows targets = target_rows(results);
  CsvFile targets_csv(context.out_dir / "state_targets.csv", "measure,ours,peer,ratio,target,verdict");
  for (const std::vector<std::string>& row : targets) {
    std::vector<std::string> cells;
    for (const std::string& cell : row) cells.push_back(csv_text(cell == "**missed**" ? "missed" : cell));
    targets_csv.row(cells);
  }
  std::string md =
      "## State queries: proximity, minimum distance, intersections\n\n"
      "CollisionDetector's state queries on one set of positions, the mesh as one body (self pairs sharing no vertex): "
      "the shared steps' start and end states (when present) and the generated steps' start states, at d = 1e-3 and "
      "1e-4 of the bounding-box diagonal, on one thread and on two (tbb::global_control), warm detector (the best of "
      "five calls after a first; one call after the first when that took over a second). *Contacts*: closest_feature_contacts of the proximity pairs (vv/ve/ee/vf). Peers in "
      "the same run, one thread: " +
      status +
      " (bench/peers/ipctk_state.py: `NormalCollisions.build(mesh, V, dhat=d, dmin=0, broad_phase=LBVH())`, best of "
      "three; then `compute_minimum_distance`; `has_intersections(mesh, V, LBVH())`), and CGAL " CGAL_VERSION_STR
      " (`Polygon_mesh_processing::self_intersections` on a Surface_mesh, Exact_predicates_inexact_constructions "
      "kernel, Sequential_tag, and Parallel_tag on two threads; `does_self_intersect`). Every difference is listed in "
      "state_differences.csv (the first 50 of each comparison, with their total), with its features' exact distance "
      "(GMP) against d, or the face pair's exact answer (the library's rational reference test). Peak memory: growth "
      "of the peak resident set of a cold detector's call (detect() with start = end, proximity at 1e-3 diag, "
      "intersections), one thread.\n\n" +
      figures_table(results) + "\n" + differences_summary(results) + "\n" + intersections_table(results) + "\nTargets (state_targets.csv):\n\n" +
      markdown_table({"measure", "ours", "peer / budget", "ratio", "target", "verdict"}, targets);
  return {md, {"state.csv", "state_differences.csv", "state_targets.csv"}};
}

const SectionRegistrar registrar{
    {58, "state",
     "State queries (proximity, minimum distance, intersections, is_intersection_free) on real and generated states, "
     "one and two threads, against the IPC Toolkit's NormalCollisions and CGAL's self_intersections",
     run_state}};

}  // namespace
}  // namespace clothcd::bench

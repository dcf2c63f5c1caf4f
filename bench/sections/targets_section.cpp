// Section "targets": the speed targets of the broad-phase and simulation issues, measured on cloth C draping over the
// human model (the issues' case), single-threaded, with FCL's AABB BVH as the peer in the same run:
//   - refit + cloth-vs-obstacle candidate search (target: at least 3x faster than FCL refit + collide);
//   - cloth self-collision candidate search (target: under 1 ms; FCL's naive self query beside it);
//   - whole detection per step, obstacle + self, VF + EE, filters + exact CCD, on one thread and on two (targets: no
//     slower than the project's kept figures, 1.33 and 0.88 ms; the earlier 1 ms goal is retired);
//   - the simulation itself: detection and whole step per step over the run (target: a whole step within 5 ms), on one
//     thread and on two;
//   - scaling: detection cost per cloth triangle on a wavy sheet of about 100k triangles against one of about 5k
//     (same edge length, thickness and motion relative to it; target: within 1.5x).
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "../suite/bench_section.hpp"
#include "../suite/bench_util.hpp"
#include "../suite/draped_frames.hpp"
#include "../suite/fcl_peer.hpp"
#include "broadphase/body_topology.hpp"
#include "broadphase/bvh.hpp"
#include "broadphase/candidates.hpp"
#include "broadphase/collecting_sink.hpp"
#include "broadphase/swept_boxes.hpp"
#include "broadphase/traversal.hpp"
#include "clothcd/detection/collision_detector.hpp"
#include "clothcd/mesh/mesh_generators.hpp"

namespace clothcd::bench {
namespace {

constexpr double kThickness = 0.004;  // the simulator's response thickness, also its detector's

// One pass of a measure over its frames, returning the mean time per frame (ms).
using Pass = std::function<double()>;

// The best (smallest) pass time of each measure over `passes` rounds, each round running one pass of every measure in
// turn: a change of the machine's speed during the run then affects every measure alike, not only the ones that
// happen to run while it lasts.
std::vector<double> interleaved_best(int passes, const std::vector<Pass>& measures) {
  std::vector<double> best(measures.size(), 0.0);
  for (int pass = 0; pass < passes; ++pass) {
    for (std::size_t m = 0; m < measures.size(); ++m) {
      const double mean = measures[m]();
      if (pass == 0 || mean < best[m]) best[m] = mean;
    }
  }
  return best;
}

// The mean over `frames` of the time `work` reports for one frame (ms).
double mean_ms(const std::vector<Frame>& frames, const std::function<double(const Frame&)>& work) {
  double total = 0;
  for (const Frame& frame : frames) total += work(frame);
  return total / static_cast<double>(frames.size());
}

DetectorSettings detector_settings(HierarchyKind hierarchy, bool self_collision, bool parallel) {
  DetectorSettings settings;
  settings.hierarchy = hierarchy;
  settings.thickness = kThickness;
  settings.parallel = parallel;
  settings.self_collision = self_collision;
  return settings;
}

// A detector's pass over the frames: refit + search per frame (`broad_only`) or the whole detect() call. With
// `candidates`, each pass stores there the mean candidate pairs per frame. `parallel`: the detector on TBB threads.
Pass detector_pass(const DrapedCase& c, HierarchyKind hierarchy, bool self_collision, bool broad_only,
                   double* candidates = nullptr, bool parallel = false) {
  auto detector = std::make_shared<CollisionDetector>(c.cloth_rest.faces, static_cast<int>(c.cloth_rest.vertex_count()),
                                                      detector_settings(hierarchy, self_collision, parallel));
  if (c.obstacle.face_count() > 0) detector->add_obstacle(c.obstacle);
  detector->detect(c.frames.front().start, c.frames.front().start);  // builds the hierarchies
  return [&c, detector, broad_only, candidates] {
    double found = 0;
    const double ms = mean_ms(c.frames, [&](const Frame& frame) {
      const double whole = time_ms([&] { detector->detect(frame.start, frame.end); });
      const DetectionStats& s = detector->stats();
      found += static_cast<double>(s.candidates_vertex_face + s.candidates_edge_edge);
      return broad_only ? s.refit_ms + s.traversal_ms : whole;
    });
    if (candidates != nullptr) *candidates = found / static_cast<double>(c.frames.size());
    return ms;
  };
}

// A pass of the cloth's self-collision candidate search alone (hierarchy refitted outside the timing); each pass
// stores the mean candidate pairs per frame in `candidates`.
Pass self_search_pass(const DrapedCase& c, broadphase::VolumeKind volume, double* candidates) {
  struct State {
    broadphase::BodyTopology topology;
    broadphase::SweptBoxes boxes;
    broadphase::Bvh bvh;
    broadphase::CandidateSet found;
  };
  broadphase::BvhSettings settings;
  settings.volume = volume;
  settings.max_leaf_faces = DetectorSettings{}.max_leaf_faces;
  auto state = std::make_shared<State>(State{
      broadphase::build_body_topology(c.cloth_rest.faces, static_cast<int>(c.cloth_rest.vertex_count())), {},
      broadphase::Bvh(settings), {}});
  return [&c, state, candidates] {
    double count = 0;
    const double ms = mean_ms(c.frames, [&](const Frame& frame) {
      broadphase::compute_swept_boxes(state->topology, frame.start, frame.end, kThickness, state->boxes);
      (void)state->bvh.update(state->topology, state->boxes, frame.start, frame.end);
      const broadphase::BodyView view{0, &state->topology, &state->boxes, &state->bvh};
      state->found.clear();
      const double t = time_ms([&] { broadphase::find_self_candidates(view, {false, nullptr}, state->found); });
      count += static_cast<double>(state->found.vertex_face.size() + state->found.edge_edge.size());
      return t;
    });
    *candidates = count / static_cast<double>(c.frames.size());
    return ms;
  };
}

// A pass of FCL: refit of the cloth + collide against the obstacle, or against the cloth itself for the naive self
// query.
Pass fcl_pass(const DrapedCase& c, bool self) {
  auto cloth = fcl_model(c.cloth_rest, c.frames.front().start);
  auto obstacle = self ? cloth : fcl_model(c.obstacle, c.obstacle.vertices);
  return [&c, cloth, obstacle] {
    return mean_ms(c.frames, [&](const Frame& frame) {
      const auto points = fcl_points(frame.end);
      return time_ms([&] { (void)fcl_refit_and_collide(cloth, points, obstacle); });
    });
  };
}

// A wavy square sheet of n x n vertices with unit edge length `edge`, moving down by half an edge over the step
// while its waves shift: the same local picture at every size, so the cost per triangle shows the algorithm's growth.
DrapedCase wavy_sheet(int n, double edge, int frames) {
  DrapedCase c;
  c.model = "wavy sheet";
  c.cloth_rest = make_grid(n, n, edge * (n - 1), edge * (n - 1));
  const double wavelength = 12 * edge, amplitude = 1.5 * edge;
  auto pose = [&](int step) {
    const double phase = 0.1 * step, two_pi = 6.283185307179586;
    Vertices v = c.cloth_rest.vertices;
    for (Eigen::Index i = 0; i < v.rows(); ++i)
      v(i, 1) = amplitude * std::sin(v(i, 0) / wavelength * two_pi + phase) *
                    std::cos(v(i, 2) / wavelength * two_pi - phase) -
                0.5 * edge * step;
    return v;
  };
  for (int f = 0; f < frames; ++f) c.frames.push_back({pose(f), pose(f + 1)});
  return c;
}

std::string verdict(bool met) { return met ? "met" : "**missed**"; }

// Whole detection per frame of cloth C on the human that later changes must not exceed (AABB, one and two threads):
// the project's figures from a full run on a quiet machine of this kind.
constexpr double kKeptWholeDetectionMs = 1.33;
constexpr double kKeptWholeDetectionTwoThreadsMs = 0.88;

// Mean detection and whole-step time per step of a simulated run, ms.
std::pair<double, double> step_means(const std::vector<simulation::StepStats>& steps) {
  double detection = 0, whole = 0;
  for (const simulation::StepStats& s : steps) {
    detection += s.detection_ms;
    whole += s.step_ms;
  }
  const double n = static_cast<double>(std::max<std::size_t>(1, steps.size()));
  return {detection / n, whole / n};
}

SectionReport run_targets(const BenchContext& context) {
  const char cloth = context.quick ? 'A' : 'C';
  const int steps = context.quick ? 40 : 200, frames = context.quick ? 5 : 30, passes = context.quick ? 1 : 5;
  const std::string label = std::string("cloth ") + cloth + " on the human";
  // The simulation on two threads first (what `clothcd simulate` uses on this two-core machine); everything after it
  // runs on one thread (a TBB thread limit cannot be raised again inside a lower one).
  context.progress(label + ": simulating " + std::to_string(steps) + " steps (two threads)");
  const auto [two_thread_detection, two_thread_step] = [&] {
    tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
    return step_means(simulate_draping("human", cloth, steps, 0, context.obstacle_model_dir.string()).steps);
  }();
  std::optional<tbb::global_control> one_thread;
  one_thread.emplace(tbb::global_control::max_allowed_parallelism, 1);
  context.progress(label + ": simulating " + std::to_string(steps) + " steps (one thread)");
  const DrapedCase c = simulate_draping("human", cloth, steps, frames, context.obstacle_model_dir.string());
  const auto [step_detection, whole_step] = step_means(c.steps);

  context.progress(label + ": broad phase against FCL on " + std::to_string(frames) + " frames");
  double obstacle_candidates = 0, self_candidates = 0, all_candidates = 0;
  const std::vector<double> broad = interleaved_best(
      passes, {fcl_pass(c, false), detector_pass(c, HierarchyKind::Aabb, false, true, &obstacle_candidates),
               detector_pass(c, HierarchyKind::SphereRootAabb, false, true)});
  const double fcl_obstacle = broad[0], ours_aabb = broad[1], ours_double = broad[2];
  const std::vector<double> self = interleaved_best(
      passes, {fcl_pass(c, true), self_search_pass(c, broadphase::VolumeKind::Aabb, &self_candidates)});
  const double fcl_self = self[0], self_aabb = self[1];
  context.progress(label + ": whole detection");
  const std::vector<double> whole =
      interleaved_best(passes, {detector_pass(c, HierarchyKind::Aabb, true, false, &all_candidates),
                                detector_pass(c, HierarchyKind::SphereRootAabb, true, false)});
  const double whole_aabb = whole[0], whole_double = whole[1];

  const int small_n = context.quick ? 20 : 50, large_n = context.quick ? 60 : 225;
  context.progress("scaling: wavy sheets of " + std::to_string(small_n) + "^2 and " + std::to_string(large_n) +
                   "^2 vertices");
  const DrapedCase small_sheet = wavy_sheet(small_n, 0.01, context.quick ? 2 : 5);
  const DrapedCase large_sheet = wavy_sheet(large_n, 0.01, context.quick ? 2 : 5);
  const std::vector<double> sheets =
      interleaved_best(passes, {detector_pass(small_sheet, HierarchyKind::SphereRootAabb, true, false),
                                detector_pass(large_sheet, HierarchyKind::SphereRootAabb, true, false)});
  const double small_per = sheets[0] / static_cast<double>(small_sheet.cloth_rest.face_count());
  context.progress(label + ": whole detection on two threads");
  one_thread.reset();
  const double whole_two_threads = [&] {
    tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
    return interleaved_best(passes, {detector_pass(c, HierarchyKind::Aabb, true, false, nullptr, true)})[0];
  }();
  const double large_per = sheets[1] / static_cast<double>(large_sheet.cloth_rest.face_count());

  CsvFile csv(context.out_dir / "targets.csv", "measure,ours_ms,peer_ms,ratio,target");
  const double broad_ratio = fcl_obstacle / ours_aabb;
  const double scaling = large_per / small_per;
  csv.row({"refit + obstacle search (AABB)", number(ours_aabb, 5), number(fcl_obstacle, 5), number(broad_ratio, 4),
           "FCL / ours >= 3"});
  csv.row({"refit + obstacle search (double box)", number(ours_double, 5), number(fcl_obstacle, 5),
           number(fcl_obstacle / ours_double, 4), "FCL / ours >= 3"});
  csv.row({"self candidate search (AABB)", number(self_aabb, 5), number(fcl_self, 5), number(fcl_self / self_aabb, 4),
           "ours < 1 ms"});
  csv.row({"whole detection (AABB)", number(whole_aabb, 5), "", "", "<= 1.33 ms"});
  csv.row({"whole detection (double box)", number(whole_double, 5), "", "", ""});
  csv.row({"whole detection, two threads (AABB)", number(whole_two_threads, 5), "", "", "<= 0.88 ms"});
  csv.row({"simulation: detection per step", number(step_detection, 5), "", "", ""});
  csv.row({"simulation: whole step", number(whole_step, 5), "", "", "<= 5 ms"});
  csv.row({"simulation, two threads: detection per step", number(two_thread_detection, 5), "", "", ""});
  csv.row({"simulation, two threads: whole step", number(two_thread_step, 5), "", "", "<= 5 ms"});
  csv.row({"scaling: us per triangle, large / small", number(1000 * large_per, 5), number(1000 * small_per, 5),
           number(scaling, 4), "<= 1.5"});

  const std::vector<std::vector<std::string>> rows{
      {"refit + cloth-vs-obstacle candidate search, AABB", number(ours_aabb, 3) + " ms", number(fcl_obstacle, 3) + " ms",
       fixed(broad_ratio, 2), ">= 3", verdict(broad_ratio >= 3)},
      {"the same, root-node double box", number(ours_double, 3) + " ms", number(fcl_obstacle, 3) + " ms",
       fixed(fcl_obstacle / ours_double, 2), "-", "-"},
      {"self-collision candidate search (AABB tree)", number(self_aabb, 3) + " ms",
       number(fcl_self, 3) + " ms (naive self query)", fixed(fcl_self / self_aabb, 1), "< 1 ms",
       verdict(self_aabb < 1.0)},
      {"whole detection per frame, AABB (broad + filters + exact, obstacle + self)", number(whole_aabb, 3) + " ms", "-",
       "-", "<= " + number(kKeptWholeDetectionMs, 3) + " ms (kept figure)",
       verdict(whole_aabb <= kKeptWholeDetectionMs)},
      {"whole detection per frame, root-node double box", number(whole_double, 3) + " ms", "-", "-", "-", "-"},
      {"whole detection per frame on two threads, AABB", number(whole_two_threads, 3) + " ms", "-", "-",
       "<= " + number(kKeptWholeDetectionTwoThreadsMs, 3) + " ms (kept figure)",
       verdict(whole_two_threads <= kKeptWholeDetectionTwoThreadsMs)},
      {"simulation, " + std::to_string(steps) + " steps: detection per step (every detect() call of the step)",
       number(step_detection, 3) + " ms", "-", "-", "-", "-"},
      {"simulation: whole step (forces, integration, detection, response)", number(whole_step, 3) + " ms", "-", "-",
       "<= 5 ms", verdict(whole_step <= 5.0)},
      {"simulation on two threads: detection per step", number(two_thread_detection, 3) + " ms", "-", "-", "-", "-"},
      {"simulation on two threads: whole step", number(two_thread_step, 3) + " ms", "-", "-", "<= 5 ms",
       verdict(two_thread_step <= 5.0)},
      {"scaling: detection us per triangle, " + std::to_string(large_sheet.cloth_rest.face_count()) + " vs " +
           std::to_string(small_sheet.cloth_rest.face_count()) + " triangles",
       number(1000 * large_per, 3) + " vs " + number(1000 * small_per, 3) + " us", "-", fixed(scaling, 2) + " (large / small)",
       "large / small <= 1.5", verdict(scaling <= 1.5)}};

  std::string md = "## Speed targets of the broad-phase and simulation issues\n\n";
  md += label + " (" + std::to_string(c.cloth_rest.face_count()) + " cloth triangles, " +
        std::to_string(c.obstacle.face_count()) + " model triangles): `clothcd simulate --scene human --cloth " +
        std::string(1, cloth) + "` for " + std::to_string(steps) + " steps on one thread (its per-step statistics "
        "give the simulation rows; the same run on two threads gives the two-thread rows), the last " + std::to_string(frames) + " steps replayed as frames (start, "
        "free-flight end; thickness " + number(kThickness, 3) + " m), best of " + std::to_string(passes) +
        " passes of the mean per frame, the passes of the measures compared with each other taken in turn. FCL: its AABB BVH refitted to the frame's end positions and collided with "
        "every contact (against the model, or against itself for the naive self query). Mean candidates per frame: "
        "cloth vs model " + number(obstacle_candidates, 4) + ", cloth self " + number(self_candidates, 4) +
        ", all " + number(all_candidates, 4) + ". Scaling: a wavy sheet with 1 cm edges (waves 12 edges long and "
        "1.5 high, falling half an edge per step, the same thickness) at two sizes, self collisions only, double "
        "box.";
  if (context.quick) md += " Quick run: cloth A, smaller sheets, one pass.";
  md += "\n\n";
  md += markdown_table({"measure", "ours", "peer (FCL)", "FCL / ours", "target", "verdict"}, rows);
  md += "\nReference figures (the project's measurement behind DetectorSettings::max_leaf_faces, not rerun here): "
        "cachegrind over 30 frames of whole detection, cloth C on the human, counts 1.28G instructions and 4.2M "
        "mispredicted branches with 32 triangles per leaf (the default, since the leaf tests take eight primitives "
        "at a time) against 1.32G and 4.8M with 16, 1.29G and 4.7M with 40.\n";
  return {md, {"targets.csv"}};
}

const SectionRegistrar registrar{
    {55, "targets",
     "Broad-phase and simulation targets on cloth C over the human: FCL ratio, self search, detection and step time, "
     "scaling to 100k triangles",
     run_targets}};

}  // namespace
}  // namespace clothcd::bench

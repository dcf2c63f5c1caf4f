// Section "targets": the speed targets of the broad-phase and simulation issues, measured on cloth C draping over the
// human model (the issues' case), single-threaded, with FCL's AABB BVH as the peer in the same run:
//   - refit + cloth-vs-obstacle candidate search (target: at least 3x faster than FCL refit + collide);
//   - cloth self-collision candidate search (target: under 1 ms; FCL's naive self query beside it);
//   - whole detection per step, obstacle + self, VF + EE, filters + exact CCD (target: at most 1 ms);
//   - the simulation itself: detection and whole step per step over the run (targets: 1 ms and 5 ms);
//   - scaling: detection cost per cloth triangle on a wavy sheet of about 100k triangles against one of about 5k
//     (same edge length, thickness and motion relative to it; target: within 1.5x).
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "../suite/bench_section.hpp"
#include "../suite/bench_util.hpp"
#include "../suite/draped_frames.hpp"
#include "../suite/fcl_peer.hpp"
#include "clothcd/broadphase/body_topology.hpp"
#include "clothcd/broadphase/bvh.hpp"
#include "clothcd/broadphase/candidates.hpp"
#include "clothcd/broadphase/swept_boxes.hpp"
#include "clothcd/broadphase/traversal.hpp"
#include "clothcd/detection/collision_detector.hpp"
#include "clothcd/mesh/mesh_generators.hpp"

namespace clothcd::bench {
namespace {

constexpr double kThickness = 0.004;  // the simulator's response thickness, also its detector's

// The smallest over `passes` passes of the mean over `frames` of the time `work` reports for one frame (ms).
double best_mean_ms(int passes, const std::vector<Frame>& frames, const std::function<double(const Frame&)>& work) {
  double best = 0;
  for (int pass = 0; pass < passes; ++pass) {
    double total = 0;
    for (const Frame& frame : frames) total += work(frame);
    const double mean = total / static_cast<double>(frames.size());
    if (pass == 0 || mean < best) best = mean;
  }
  return best;
}

DetectorSettings single_thread_detector(HierarchyKind hierarchy, bool self_collision) {
  DetectorSettings settings;
  settings.hierarchy = hierarchy;
  settings.thickness = kThickness;
  settings.parallel = false;
  settings.self_collision = self_collision;
  return settings;
}

// A detector's stage times per frame: refit + search (`broad_only`) or the whole detect() call.
double detector_ms(const DrapedCase& c, HierarchyKind hierarchy, bool self_collision, bool broad_only, int passes,
                   double* candidates = nullptr) {
  CollisionDetector detector(c.cloth_rest.faces, static_cast<int>(c.cloth_rest.vertex_count()),
                             single_thread_detector(hierarchy, self_collision));
  if (c.obstacle.face_count() > 0) detector.add_obstacle(c.obstacle);
  detector.detect(c.frames.front().start, c.frames.front().start);  // builds the hierarchies
  double found = 0;
  const double ms = best_mean_ms(passes, c.frames, [&](const Frame& frame) {
    const double whole = time_ms([&] { detector.detect(frame.start, frame.end); });
    const DetectionStats& s = detector.stats();
    found += static_cast<double>(s.candidates_vertex_face + s.candidates_edge_edge);
    return broad_only ? s.refit_ms + s.traversal_ms : whole;
  });
  if (candidates != nullptr) *candidates = found / static_cast<double>(passes * c.frames.size());
  return ms;
}

// The cloth's self-collision candidate search alone (hierarchy refitted outside the timing), ms per frame.
double self_search_ms(const DrapedCase& c, broadphase::VolumeKind volume, int passes, double* candidates) {
  const broadphase::BodyTopology topology =
      broadphase::build_body_topology(c.cloth_rest.faces, static_cast<int>(c.cloth_rest.vertex_count()));
  broadphase::SweptBoxes boxes;
  broadphase::BvhSettings settings;
  settings.volume = volume;
  settings.max_leaf_faces = DetectorSettings{}.max_leaf_faces;
  broadphase::Bvh bvh(settings);
  broadphase::CandidateSet found;
  double count = 0;
  const double ms = best_mean_ms(passes, c.frames, [&](const Frame& frame) {
    broadphase::compute_swept_boxes(topology, frame.start, frame.end, kThickness, boxes);
    (void)bvh.update(topology, boxes, frame.start, frame.end);
    const broadphase::BodyView view{0, &topology, &boxes, &bvh};
    found.clear();
    const double t = time_ms([&] { broadphase::find_self_candidates(view, {false, nullptr}, found); });
    count += static_cast<double>(found.vertex_face.size() + found.edge_edge.size());
    return t;
  });
  *candidates = count / static_cast<double>(passes * c.frames.size());
  return ms;
}

// FCL refit of the cloth + collide against `other` (the obstacle, or the cloth itself for the naive self query).
double fcl_ms(const DrapedCase& c, bool self, int passes) {
  auto cloth = fcl_model(c.cloth_rest, c.frames.front().start);
  auto obstacle = self ? cloth : fcl_model(c.obstacle, c.obstacle.vertices);
  return best_mean_ms(passes, c.frames, [&](const Frame& frame) {
    const auto points = fcl_points(frame.end);
    return time_ms([&] { (void)fcl_refit_and_collide(cloth, points, obstacle); });
  });
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

SectionReport run_targets(const BenchContext& context) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
  const char cloth = context.quick ? 'A' : 'C';
  const int steps = context.quick ? 40 : 200, frames = context.quick ? 5 : 30, passes = context.quick ? 1 : 3;
  const std::string label = std::string("cloth ") + cloth + " on the human";
  context.progress(label + ": simulating " + std::to_string(steps) + " steps (one thread)");
  const DrapedCase c = simulate_draping("human", cloth, steps, frames, context.obstacle_model_dir.string());
  double step_detection = 0, whole_step = 0;
  for (const simulation::StepStats& s : c.steps) {
    step_detection += s.detection_ms;
    whole_step += s.step_ms;
  }
  step_detection /= static_cast<double>(c.steps.size());
  whole_step /= static_cast<double>(c.steps.size());

  context.progress(label + ": broad phase against FCL on " + std::to_string(frames) + " frames");
  double obstacle_candidates = 0, self_candidates = 0, all_candidates = 0;
  const double fcl_obstacle = fcl_ms(c, false, passes);
  const double ours_aabb = detector_ms(c, HierarchyKind::Aabb, false, true, passes, &obstacle_candidates);
  const double ours_double = detector_ms(c, HierarchyKind::SphereRootAabb, false, true, passes);
  const double fcl_self = fcl_ms(c, true, passes);
  const double self_aabb = self_search_ms(c, broadphase::VolumeKind::Aabb, passes, &self_candidates);
  context.progress(label + ": whole detection");
  const double whole_aabb = detector_ms(c, HierarchyKind::Aabb, true, false, passes, &all_candidates);
  const double whole_double = detector_ms(c, HierarchyKind::SphereRootAabb, true, false, passes);

  const int small_n = context.quick ? 20 : 50, large_n = context.quick ? 60 : 225;
  context.progress("scaling: wavy sheets of " + std::to_string(small_n) + "^2 and " + std::to_string(large_n) +
                   "^2 vertices");
  const DrapedCase small_sheet = wavy_sheet(small_n, 0.01, context.quick ? 2 : 5);
  const DrapedCase large_sheet = wavy_sheet(large_n, 0.01, context.quick ? 2 : 5);
  const double small_ms = detector_ms(small_sheet, HierarchyKind::SphereRootAabb, true, false, passes);
  const double large_ms = detector_ms(large_sheet, HierarchyKind::SphereRootAabb, true, false, passes);
  const double small_per = small_ms / static_cast<double>(small_sheet.cloth_rest.face_count());
  const double large_per = large_ms / static_cast<double>(large_sheet.cloth_rest.face_count());

  CsvFile csv(context.out_dir / "targets.csv", "measure,ours_ms,peer_ms,ratio,target");
  const double broad_ratio = fcl_obstacle / ours_aabb;
  const double scaling = large_per / small_per;
  csv.row({"refit + obstacle search (AABB)", number(ours_aabb, 5), number(fcl_obstacle, 5), number(broad_ratio, 4),
           "FCL / ours >= 3"});
  csv.row({"refit + obstacle search (double box)", number(ours_double, 5), number(fcl_obstacle, 5),
           number(fcl_obstacle / ours_double, 4), "FCL / ours >= 3"});
  csv.row({"self candidate search (AABB)", number(self_aabb, 5), number(fcl_self, 5), number(fcl_self / self_aabb, 4),
           "ours < 1 ms"});
  csv.row({"whole detection (AABB)", number(whole_aabb, 5), "", "", "<= 1 ms"});
  csv.row({"whole detection (double box)", number(whole_double, 5), "", "", "<= 1 ms"});
  csv.row({"simulation: detection per step", number(step_detection, 5), "", "", "<= 1 ms"});
  csv.row({"simulation: whole step", number(whole_step, 5), "", "", "<= 5 ms"});
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
       "-", "<= 1 ms", verdict(whole_aabb <= 1.0)},
      {"whole detection per frame, root-node double box", number(whole_double, 3) + " ms", "-", "-", "<= 1 ms",
       verdict(whole_double <= 1.0)},
      {"simulation, " + std::to_string(steps) + " steps: detection per step (every detect() call of the step)",
       number(step_detection, 3) + " ms", "-", "-", "<= 1 ms", verdict(step_detection <= 1.0)},
      {"simulation: whole step (forces, integration, detection, response)", number(whole_step, 3) + " ms", "-", "-",
       "<= 5 ms", verdict(whole_step <= 5.0)},
      {"scaling: detection us per triangle, " + std::to_string(large_sheet.cloth_rest.face_count()) + " vs " +
           std::to_string(small_sheet.cloth_rest.face_count()) + " triangles",
       number(1000 * large_per, 3) + " vs " + number(1000 * small_per, 3) + " us", "-", fixed(scaling, 2) + " (large / small)",
       "large / small <= 1.5", verdict(scaling <= 1.5)}};

  std::string md = "## Speed targets of the broad-phase and simulation issues\n\n";
  md += label + " (" + std::to_string(c.cloth_rest.face_count()) + " cloth triangles, " +
        std::to_string(c.obstacle.face_count()) + " model triangles): `clothcd simulate --scene human --cloth " +
        std::string(1, cloth) + "` for " + std::to_string(steps) + " steps on one thread (its per-step statistics "
        "give the simulation rows), the last " + std::to_string(frames) + " steps replayed as frames (start, "
        "free-flight end; thickness " + number(kThickness, 3) + " m), best of " + std::to_string(passes) +
        " passes of the mean per frame. FCL: its AABB BVH refitted to the frame's end positions and collided with "
        "every contact (against the model, or against itself for the naive self query). Mean candidates per frame: "
        "cloth vs model " + number(obstacle_candidates, 4) + ", cloth self " + number(self_candidates, 4) +
        ", all " + number(all_candidates, 4) + ". Scaling: a wavy sheet with 1 cm edges (waves 12 edges long and "
        "1.5 high, falling half an edge per step, the same thickness) at two sizes, self collisions only, double "
        "box.";
  if (context.quick) md += " Quick run: cloth A, smaller sheets, one pass.";
  md += "\n\n";
  md += markdown_table({"measure", "ours", "peer (FCL)", "FCL / ours", "target", "verdict"}, rows);
  md += "\n";
  return {md, {"targets.csv"}};
}

const SectionRegistrar registrar{
    {55, "targets",
     "Broad-phase and simulation targets on cloth C over the human: FCL ratio, self search, detection and step time, "
     "scaling to 100k triangles",
     run_targets}};

}  // namespace
}  // namespace clothcd::bench

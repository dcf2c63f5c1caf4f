// CollisionDetector::earliest_impact against a brute-force reference: every pair whose whole-step boxes meet (the
// quadratic broad phase), each decided by the exact rational reference, on seeded crumpled and folded cloths, with
// obstacles at rest, moving rigidly and moving by positions; a step without contact, a contact at t = 0, a thickness,
// the thread count, and detect() after it.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include "broadphase/brute_force_candidates.hpp"
#include "broadphase/swept_boxes.hpp"
#include "ccd/ccd_test_support.hpp"
#include "clothcd/ccd/ccd.hpp"
#include "clothcd/detection/collision_detector.hpp"
#include "clothcd/mesh/mesh_generators.hpp"
#include "same_collisions.hpp"

namespace {

using clothcd::CollisionDetector;
using clothcd::DetectorSettings;
using clothcd::EarliestImpact;
using clothcd::TriangleMesh;
using clothcd::Vertices;
using clothcd::VertexRef;
namespace broadphase = clothcd::broadphase;
namespace ccd = clothcd::ccd;

// A step: the cloth from its mesh's positions to `end`, and at most one obstacle from `obstacle_start` to
// `obstacle_end` (set with set_obstacle_positions when they differ).
struct Step {
  TriangleMesh cloth;
  Vertices end;
  std::optional<TriangleMesh> obstacle;
  Vertices obstacle_start, obstacle_end;
};

// The exact earliest contact over every pair whose whole-step boxes meet: [lo, hi] encloses it; none = no contact.
struct ReferenceContact {
  bool hit = false;
  double lo = 1.0, hi = 1.0;
};

// The earliest time some pair comes within `thickness` > 0, by the per-pair narrow phase on every such pair.
double brute_force_thick_toi(const Step& step, double thickness);

struct BodyPositions {
  broadphase::BodyTopology topology;
  Vertices start, end;
  broadphase::SweptBoxes boxes;
};

std::vector<BodyPositions> bodies_of(const Step& step, double thickness) {
  std::vector<BodyPositions> bodies(step.obstacle ? 2 : 1);
  bodies[0] = {broadphase::build_body_topology(step.cloth.faces, static_cast<int>(step.cloth.vertex_count())),
               step.cloth.vertices, step.end, {}};
  if (step.obstacle) {
    bodies[1] = {broadphase::build_body_topology(step.obstacle->faces, static_cast<int>(step.obstacle->vertex_count())),
                 step.obstacle_start, step.obstacle_end, {}};
  }
  for (BodyPositions& b : bodies) broadphase::compute_swept_boxes(b.topology, b.start, b.end, thickness, b.boxes);
  return bodies;
}

// Calls `decide(query)` for every candidate pair of the step (cloth with itself and with the obstacle).
template <class Decide>
void for_each_pair(const Step& step, double thickness, const Decide& decide) {
  const std::vector<BodyPositions> bodies = bodies_of(step, thickness);
  broadphase::CandidateSet candidates;
  const auto view = [&](int b) {
    return broadphase::BodyView{b, &bodies[b].topology, &bodies[b].boxes, nullptr};
  };
  broadphase::brute_force_self_candidates(view(0), candidates);
  if (step.obstacle) broadphase::brute_force_pair_candidates(view(0), view(1), candidates);
  const auto query_of = [&](clothcd::PairKind kind, const std::array<VertexRef, 4>& v) {
    ccd::CcdQuery q;
    q.kind = kind;
    for (int k = 0; k < 4; ++k) {
      q.start[k] = bodies[v[k].body].start.row(v[k].vertex).transpose();
      q.end[k] = bodies[v[k].body].end.row(v[k].vertex).transpose();
    }
    return q;
  };
  for (const broadphase::VertexFaceCandidate& c : candidates.vertex_face) {
    const auto& f = bodies[c.face_body].topology.faces;
    decide(query_of(clothcd::PairKind::VertexFace,
                    {VertexRef{c.vertex_body, c.vertex}, VertexRef{c.face_body, f(c.face, 0)},
                     VertexRef{c.face_body, f(c.face, 1)}, VertexRef{c.face_body, f(c.face, 2)}}));
  }
  for (const broadphase::EdgeEdgeCandidate& c : candidates.edge_edge) {
    const auto& ea = bodies[c.body_a].topology.edges;
    const auto& eb = bodies[c.body_b].topology.edges;
    decide(query_of(clothcd::PairKind::EdgeEdge,
                    {VertexRef{c.body_a, ea[2 * c.edge_a]}, VertexRef{c.body_a, ea[2 * c.edge_a + 1]},
                     VertexRef{c.body_b, eb[2 * c.edge_b]}, VertexRef{c.body_b, eb[2 * c.edge_b + 1]}}));
  }
}

ReferenceContact brute_force_earliest(const Step& step) {
  ReferenceContact earliest;
  for_each_pair(step, 0.0, [&](const ccd::CcdQuery& q) {
    const ccd::exact::ContactTimeBounds exact = clothcd::test::exact_contact_time_of(q);
    if (!exact.hit) return;
    earliest.lo = earliest.hit ? std::min(earliest.lo, exact.lo) : exact.lo;
    earliest.hi = earliest.hit ? std::min(earliest.hi, exact.hi) : exact.hi;
    earliest.hit = true;
  });
  return earliest;
}

double brute_force_thick_toi(const Step& step, double thickness) {
  double earliest = std::numeric_limits<double>::infinity();
  ccd::CcdSettings settings;
  settings.thickness = thickness;
  for_each_pair(step, thickness, [&](const ccd::CcdQuery& q) {
    const ccd::CcdResult r = ccd::continuous_collision(q, settings);
    if (r.hit) earliest = std::min(earliest, r.toi);
  });
  return earliest;
}

EarliestImpact earliest_of(const Step& step, DetectorSettings settings) {
  CollisionDetector detector(step.cloth.faces, static_cast<int>(step.cloth.vertex_count()), settings);
  if (step.obstacle) {
    const int body = detector.add_obstacle(*step.obstacle);
    detector.set_obstacle_positions(body, step.obstacle_start, step.obstacle_end);
  }
  return detector.earliest_impact(step.cloth.vertices, step.end);
}

// The pair's own exact contact time.
ccd::exact::ContactTimeBounds exact_time_of_pair(const Step& step, const clothcd::Collision& pair) {
  ccd::CcdQuery q;
  q.kind = pair.kind;
  for (int k = 0; k < 4; ++k) {
    const VertexRef v = pair.vertices[k];
    q.start[k] = (v.body == 0 ? step.cloth.vertices : step.obstacle_start).row(v.vertex).transpose();
    q.end[k] = (v.body == 0 ? step.end : step.obstacle_end).row(v.vertex).transpose();
  }
  return clothcd::test::exact_contact_time_of(q);
}

// earliest_impact on one and on two threads against the brute-force reference: never later than the exact earliest
// contact, at most 1e-6 of the step before it, set by a pair that does touch then, the same on any thread count.
// Returns whether the step has a contact.
bool check_against_reference(const Step& step) {
  DetectorSettings one_thread;
  one_thread.parallel = false;
  const EarliestImpact found = earliest_of(step, one_thread);
  const EarliestImpact threaded = earliest_of(step, DetectorSettings{});
  const ReferenceContact reference = brute_force_earliest(step);
  INFO("reference " << reference.hit << " [" << reference.lo << ", " << reference.hi << "], found " << found.hit << " "
                    << found.toi << " in " << found.windows << " windows");
  REQUIRE(found.hit == reference.hit);
  CHECK(found.windows >= 1);
  CHECK(found.windows <= 1024);  // windows are at least 2^-10 of the step long
  if (!reference.hit) {
    CHECK(found.toi == 1.0);
  } else {
    CHECK(found.toi <= reference.hi);
    CHECK(found.toi >= reference.lo - 1e-6);
    CHECK(found.pair.toi == found.toi);
    const ccd::exact::ContactTimeBounds own = exact_time_of_pair(step, found.pair);
    CHECK(own.hit);
    CHECK(own.lo <= reference.hi);
  }
  CHECK(threaded.hit == found.hit);
  CHECK(threaded.toi == found.toi);
  CHECK(threaded.windows == found.windows);
  clothcd::test::check_same({threaded.pair}, {found.pair});
  return reference.hit;
}

// A grid of `columns` x `rows` over [0, 1]^2 in x-z, at height `height` plus a seeded smooth bump and jitter.
TriangleMesh crumpled_grid(std::mt19937& rng, int columns, int rows, double height) {
  TriangleMesh cloth = clothcd::make_grid(columns, rows, 1.0, 1.0);
  std::uniform_real_distribution<double> phase(0.0, 6.3), jitter(-0.02, 0.02);
  const double a = phase(rng), b = phase(rng);
  for (Eigen::Index v = 0; v < cloth.vertices.rows(); ++v) {
    const double x = cloth.vertices(v, 0), z = cloth.vertices(v, 2);
    cloth.vertices(v, 1) = height + 0.12 * std::sin(5.0 * x + a) * std::cos(4.0 * z + b) + jitter(rng);
  }
  return cloth;
}

// The cloth's end: every vertex moved by a seeded smooth velocity field, strong enough to fold it onto itself.
Vertices crumpled_end(std::mt19937& rng, const TriangleMesh& cloth, double strength) {
  std::uniform_real_distribution<double> phase(0.0, 6.3), jitter(-0.05, 0.05);
  const double a = phase(rng), b = phase(rng), c = phase(rng);
  Vertices end = cloth.vertices;
  for (Eigen::Index v = 0; v < end.rows(); ++v) {
    const double x = cloth.vertices(v, 0), z = cloth.vertices(v, 2);
    end(v, 0) += strength * std::sin(3.0 * z + a) + jitter(rng);
    end(v, 1) += strength * std::sin(4.0 * x + b) * std::sin(3.0 * z + c) + jitter(rng);
    end(v, 2) += strength * std::cos(3.0 * x + c) + jitter(rng);
  }
  return end;
}

}  // namespace

TEST_CASE("earliest impact: crumpled cloths against the brute-force exact reference", "[detection][earliest]") {
  int with_contact = 0;
  for (int seed = 1; seed <= 8; ++seed) {
    INFO("seed " << seed);
    std::mt19937 rng(static_cast<unsigned>(seed));
    Step step;
    step.cloth = crumpled_grid(rng, 6, 6, 0.0);
    step.end = crumpled_end(rng, step.cloth, 0.3 + 0.1 * (seed % 4));
    with_contact += check_against_reference(step) ? 1 : 0;
  }
  INFO(with_contact << " of 8 steps with a contact");
  CHECK(with_contact >= 3);  // the seeds cover steps with and without self-contact
  CHECK(with_contact <= 7);
}

TEST_CASE("earliest impact: a cloth folding onto itself, contact late in the step", "[detection][earliest]") {
  // A strip bent into a U whose arms close in: they meet at about t = 0.8 (a later window).
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.01, 0.01);
  Step step;
  step.cloth = clothcd::make_grid(12, 4, 1.2, 0.3);
  step.end = step.cloth.vertices;
  for (Eigen::Index v = 0; v < step.cloth.vertices.rows(); ++v) {
    const double x = step.cloth.vertices(v, 0);
    const double arm = x < 0 ? -1.0 : 1.0;
    const double along = std::fabs(x);
    step.cloth.vertices(v, 0) = arm * (along > 0.2 ? 0.2 : along);
    step.cloth.vertices(v, 1) = along > 0.2 ? along - 0.2 : 0.0;
    step.end.row(v) = step.cloth.vertices.row(v);
    if (along > 0.2) step.end(v, 0) = -arm * 0.05 + jitter(rng);
  }
  const EarliestImpact found = earliest_of(step, DetectorSettings{});
  CHECK(found.windows >= 2);
  CHECK(found.toi > 0.25);
  check_against_reference(step);
}

TEST_CASE("earliest impact: pieces thrown across each other, many short windows", "[detection][earliest]") {
  // Four small squares of one cloth, each flying some 30 edge lengths towards the middle with seeded tilts and speeds:
  // the schedule starts with a window of 1/64 of the step, and the pieces meet windows later.
  int with_contact = 0;
  for (int seed = 1; seed <= 6; ++seed) {
    INFO("seed " << seed);
    std::mt19937 rng(static_cast<unsigned>(seed));
    std::uniform_real_distribution<double> tilt(-0.3, 0.3), speed(0.8, 1.2);
    const TriangleMesh piece = clothcd::make_grid(3, 3, 0.2, 0.2);
    const Eigen::Index n = piece.vertices.rows();
    Step step;
    step.cloth.vertices.resize(4 * n, 3);
    step.cloth.faces.resize(4 * piece.faces.rows(), 3);
    step.end.resize(4 * n, 3);
    for (int k = 0; k < 4; ++k) {
      const double angle = 1.5707963267948966 * k;
      const Eigen::RowVector3d out(std::cos(angle), tilt(rng), std::sin(angle));
      const Eigen::RowVector3d offset(0.05 * k, 0.05 * k, 0.0);
      for (Eigen::Index v = 0; v < n; ++v) {
        step.cloth.vertices.row(k * n + v) = piece.vertices.row(v) + 1.2 * out + offset;
        step.end.row(k * n + v) = piece.vertices.row(v) - 1.2 * speed(rng) * out + offset;
      }
      step.cloth.faces.middleRows(k * piece.faces.rows(), piece.faces.rows()) =
          piece.faces.array() + static_cast<int>(k * n);
    }
    const EarliestImpact found = earliest_of(step, DetectorSettings{});
    INFO("toi " << found.toi << " in " << found.windows << " windows");
    CHECK(found.windows >= 3);
    with_contact += check_against_reference(step) ? 1 : 0;
  }
  CHECK(with_contact >= 4);
}

TEST_CASE("earliest impact: obstacles moving by positions and rigidly", "[detection][earliest]") {
  const TriangleMesh sphere = clothcd::make_uv_sphere(0.25, 10, 6);
  for (int seed = 1; seed <= 4; ++seed) {
    INFO("seed " << seed);
    std::mt19937 rng(static_cast<unsigned>(100 + seed));
    std::uniform_real_distribution<double> jitter(-0.01, 0.01);
    Step step;
    step.cloth = crumpled_grid(rng, 6, 6, 0.3);
    step.end = step.cloth.vertices;
    for (Eigen::Index v = 0; v < step.end.rows(); ++v) step.end(v, 1) -= 0.05 * seed;
    step.obstacle = sphere;
    // The sphere rises through the falling cloth, each vertex with its own small wobble.
    step.obstacle_start = sphere.vertices;
    step.obstacle_start.col(1).array() -= 0.4;
    step.obstacle_end = sphere.vertices;
    step.obstacle_end.col(1).array() += 0.3;
    for (Eigen::Index v = 0; v < sphere.vertices.rows(); ++v) {
      for (int k = 0; k < 3; ++k) step.obstacle_end(v, k) += jitter(rng);
    }
    check_against_reference(step);
    // Every hierarchy kind bounds the window boxes: the same answer.
    const EarliestImpact by_default = earliest_of(step, DetectorSettings{});
    for (const clothcd::HierarchyKind kind : {clothcd::HierarchyKind::Aabb, clothcd::HierarchyKind::AabbObb}) {
      DetectorSettings settings;
      settings.hierarchy = kind;
      const EarliestImpact found = earliest_of(step, settings);
      CHECK(found.toi == by_default.toi);
      clothcd::test::check_same({found.pair}, {by_default.pair});
    }
  }

  SECTION("a rigid motion gives the answer of the same positions") {
    std::mt19937 rng(5);
    Step step;
    step.cloth = crumpled_grid(rng, 6, 6, 0.3);
    step.end = step.cloth.vertices;
    step.obstacle = sphere;
    Eigen::Isometry3d from = Eigen::Isometry3d::Identity(), to = Eigen::Isometry3d::Identity();
    from.translate(Eigen::Vector3d(0.1, -0.4, 0.0));
    to.translate(Eigen::Vector3d(-0.1, 0.35, 0.05));
    to.rotate(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY()));
    step.obstacle_start = (sphere.vertices * from.linear().transpose()).rowwise() + from.translation().transpose();
    step.obstacle_end = (sphere.vertices * to.linear().transpose()).rowwise() + to.translation().transpose();
    CollisionDetector rigid(step.cloth.faces, static_cast<int>(step.cloth.vertex_count()), {});
    rigid.set_obstacle_transforms(rigid.add_obstacle(sphere), from, to);
    const EarliestImpact moved = rigid.earliest_impact(step.cloth.vertices, step.end);
    const EarliestImpact by_positions = earliest_of(step, DetectorSettings{});
    REQUIRE(moved.hit);
    CHECK(moved.toi == by_positions.toi);
    clothcd::test::check_same({moved.pair}, {by_positions.pair});
    check_against_reference(step);
  }
}

TEST_CASE("earliest impact: no contact, and a contact at the start", "[detection][earliest]") {
  const TriangleMesh box = clothcd::make_box(Eigen::Vector3d(0.6, 0.2, 0.6));
  Step step;
  step.cloth = clothcd::make_grid(5, 5, 1.0, 1.0);
  step.obstacle = box;
  step.obstacle_start = box.vertices;
  step.obstacle_end = box.vertices;

  SECTION("a cloth falling short of the box: 1, every window searched") {
    step.cloth.vertices.col(1).array() += 0.6;
    step.end = step.cloth.vertices;
    step.end.col(1).array() -= 0.3;
    const EarliestImpact found = earliest_of(step, DetectorSettings{});
    CHECK_FALSE(found.hit);
    CHECK(found.toi == 1.0);
    CHECK(found.windows >= 2);
    check_against_reference(step);
  }
  SECTION("a cloth lying on the box's top at the start: 0") {
    step.cloth.vertices.col(1).array() += 0.2;  // exactly the top face's height
    step.end = step.cloth.vertices;
    step.end.col(1).array() -= 0.1;
    const EarliestImpact found = earliest_of(step, DetectorSettings{});
    CHECK(found.hit);
    CHECK(found.toi == 0.0);
    CHECK(found.windows == 1);
    check_against_reference(step);
  }
}

TEST_CASE("earliest impact with a thickness: the time the cloth comes within it", "[detection][earliest]") {
  // A flat cloth falls 1.0 in the step onto a box's top at y = 0.2 (resting), from y = 0.7: it comes within h = 0.01
  // of it at t = 0.49 exactly (the box's top covers the cloth).
  const TriangleMesh box = clothcd::make_box(Eigen::Vector3d(0.8, 0.2, 0.8));
  Step step;
  step.cloth = clothcd::make_grid(6, 6, 1.0, 1.0);
  step.cloth.vertices.col(1).array() += 0.7;
  step.end = step.cloth.vertices;
  step.end.col(1).array() -= 1.0;
  step.obstacle = box;
  step.obstacle_start = box.vertices;
  step.obstacle_end = box.vertices;
  DetectorSettings settings;
  settings.thickness = 0.01;
  const EarliestImpact found = earliest_of(step, settings);
  REQUIRE(found.hit);
  CHECK(found.toi <= 0.49);
  CHECK(found.toi >= 0.49 - 1e-6);
  settings.parallel = false;
  CHECK(earliest_of(step, settings).toi == found.toi);

  SECTION("seeded crumpled cloths: no earlier than the earliest of every pair's narrow phase, set by one of them") {
    settings.thickness = 0.02;
    int with_contact = 0;
    for (int seed = 1; seed <= 6; ++seed) {
      std::mt19937 rng(static_cast<unsigned>(seed));
      Step crumpled;
      crumpled.cloth = crumpled_grid(rng, 6, 6, 0.0);
      crumpled.end = crumpled_end(rng, crumpled.cloth, 0.3 + 0.1 * (seed % 4));
      const EarliestImpact e = earliest_of(crumpled, settings);
      const double brute = brute_force_thick_toi(crumpled, settings.thickness);
      INFO("seed " << seed << ": " << e.toi << " vs " << brute);
      CHECK(e.hit == std::isfinite(brute));
      if (e.hit) CHECK(e.toi == brute);
      with_contact += e.hit ? 1 : 0;
    }
    CHECK(with_contact >= 2);
  }
}

TEST_CASE("earliest impact: a fast obstacle through a cloth, with and without a thickness", "[detection][earliest]") {
  // A small box thrown some 20 edge lengths along seeded directions, by positions, through a crumpled cloth that
  // hardly moves: the contact, near the middle of the step, is windows after the first.
  const TriangleMesh box = clothcd::make_box(Eigen::Vector3d(0.1, 0.1, 0.1));
  int with_contact = 0;
  for (int seed = 1; seed <= 4; ++seed) {
    INFO("seed " << seed);
    std::mt19937 rng(static_cast<unsigned>(seed));
    std::uniform_real_distribution<double> aim(-0.3, 0.3);
    Step step;
    step.cloth = crumpled_grid(rng, 8, 8, 0.0);
    step.end = step.cloth.vertices;
    step.end.col(1).array() += 0.01;  // the cloth rises slightly (moves, so its own windows are searched too)
    step.obstacle = box;
    const Eigen::RowVector3d from(aim(rng), 1.5, aim(rng)), to(aim(rng), -1.5, aim(rng));
    step.obstacle_start = box.vertices.rowwise() + from;
    step.obstacle_end = box.vertices.rowwise() + to;
    const EarliestImpact found = earliest_of(step, DetectorSettings{});
    CHECK(found.windows >= 2);
    with_contact += check_against_reference(step) ? 1 : 0;
    DetectorSettings thick;
    thick.thickness = 0.02;
    const EarliestImpact e = earliest_of(step, thick);
    const double brute = brute_force_thick_toi(step, thick.thickness);
    INFO("thickness: " << e.toi << " in " << e.windows << " windows, brute force " << brute);
    CHECK(e.hit == std::isfinite(brute));
    if (e.hit) CHECK(e.toi == brute);
    thick.parallel = false;
    CHECK(earliest_of(step, thick).toi == e.toi);
  }
  CHECK(with_contact == 4);  // the box always passes through the cloth
}

TEST_CASE("earliest impact leaves detect() as it was", "[detection][earliest]") {
  std::mt19937 rng(11);
  Step step;
  step.cloth = crumpled_grid(rng, 7, 7, 0.3);
  step.end = crumpled_end(rng, step.cloth, 0.2);
  const TriangleMesh sphere = clothcd::make_uv_sphere(0.3, 10, 6);
  Vertices sphere_end = sphere.vertices;
  sphere_end.col(1).array() += 0.2;

  const auto run = [&](bool earliest_first) {
    CollisionDetector detector(step.cloth.faces, static_cast<int>(step.cloth.vertex_count()), {});
    const int body = detector.add_obstacle(sphere);
    // A step detected, then the same step asked again (a re-test could reuse it) after an earliest-impact query.
    detector.set_obstacle_positions(body, sphere.vertices, sphere_end);
    std::vector<clothcd::Collision> first = detector.detect(step.cloth.vertices, step.end);
    if (earliest_first) {
      detector.set_obstacle_positions(body, sphere.vertices, sphere_end);
      REQUIRE(detector.earliest_impact(step.cloth.vertices, step.end).hit);
    }
    detector.set_obstacle_positions(body, sphere.vertices, sphere_end);
    std::vector<clothcd::Collision> second = detector.detect(step.cloth.vertices, step.end);
    return std::make_pair(first, second);
  };
  const auto plain = run(false);
  const auto asked = run(true);
  REQUIRE_FALSE(plain.second.empty());
  clothcd::test::check_same(asked.second, plain.second);
  clothcd::test::check_same(asked.second, asked.first);
}

// The projection filter with the primitives' own directions (the detector's default, DetectorSettings::
// projection_normals) may only drop pairs that cannot come within the thickness: on seeded pairs placed around the
// thickness from each other (resting cloth), every pair it drops is one the thickness CCD does not prove colliding,
// and a pair the brute-force distance puts inside the thickness is never dropped.
#include <catch2/catch.hpp>

#include <random>

#include "ccd/projection_block.hpp"
#include "ccd/sampled_distance.hpp"
#include "clothcd/ccd/ccd.hpp"

namespace {

using clothcd::PairKind;
using Eigen::Vector3d;
namespace ccd = clothcd::ccd;

// A pair whose closest points start about `gap` apart: a vertex over a triangle, or two crossing edges, both moving
// a little (like a cloth resting on a surface or on itself).
ccd::CcdQuery resting_pair(std::mt19937& rng, PairKind kind, double gap) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto random_vector = [&](double size) -> Vector3d { return Vector3d(unit(rng), unit(rng), unit(rng)) * size; };
  const Vector3d normal = random_vector(1.0).normalized();
  const Vector3d tangent = normal.unitOrthogonal();
  const Vector3d bitangent = normal.cross(tangent);
  const Vector3d origin = random_vector(1.0);
  ccd::CcdQuery q;
  q.kind = kind;
  const double size = 0.02;
  if (kind == PairKind::VertexFace) {
    q.start[1] = origin + size * (-0.5 * tangent - 0.5 * bitangent);
    q.start[2] = origin + size * (1.0 * tangent - 0.3 * bitangent);
    q.start[3] = origin + size * (-0.2 * tangent + 1.0 * bitangent);
    q.start[0] = origin + random_vector(0.3 * size) - normal.dot(random_vector(0.3 * size)) * normal + gap * normal;
  } else {
    q.start[0] = origin + gap * normal - size * tangent;
    q.start[1] = origin + gap * normal + size * tangent;
    q.start[2] = origin - size * bitangent + random_vector(0.2 * size).cross(normal);
    q.start[3] = origin + size * bitangent;
  }
  for (int i = 0; i < 4; ++i) q.end[i] = q.start[i] + random_vector(0.1 * gap);
  return q;
}

}  // namespace

TEST_CASE("the projection filter with primitive normals never drops a pair within the thickness",
          "[detection][filters]") {
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> ratio(0.6, 1.6);
  const double thickness = 0.004;
  const ccd::CcdSettings settings{thickness};
  const ccd::ProjectionFilterOptions with_normals{true};
  int dropped = 0, within = 0;
  for (int i = 0; i < 4000; ++i) {
    const PairKind kind = i % 2 ? PairKind::VertexFace : PairKind::EdgeEdge;
    const ccd::CcdQuery q = resting_pair(rng, kind, thickness * ratio(rng));
    const bool culled = ccd::projection_filter_culls(q, settings, with_normals);
    const ccd::CcdResult exact = ccd::continuous_collision(q, settings);
    INFO("pair " << i);
    if (culled) {
      ++dropped;
      // A proven contact must never be dropped (a conservative report at the thickness may be).
      CHECK(exact.state != ccd::CcdState::Hit);
    }
    if (i % 10 == 0 && clothcd::test::sampled_min_distance(q, 20, 32) <= thickness) {
      ++within;
      CHECK_FALSE(culled);
    }
    // The fixed directions alone drop a subset of what the normals add to.
    if (ccd::projection_filter_culls(q, settings)) CHECK(culled);
  }
  CHECK(dropped > 500);  // the test sees the normals at work
  CHECK(within > 20);
}

TEST_CASE("the in-plane directions separate neighbours in a flat sheet and never drop a pair within the thickness",
          "[detection][filters]") {
  // Pairs lying in one random plane (up to a small offset) and moving with it: no normal separates them, and the
  // fixed directions only when they are far apart along one of them. The in-plane edge normals do.
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto random_vector = [&](double size) -> Vector3d { return Vector3d(unit(rng), unit(rng), unit(rng)) * size; };
  const double thickness = 0.004;
  const ccd::CcdSettings settings{thickness};
  int in_plane = 0, within = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vector3d normal = random_vector(1.0).normalized();
    const Vector3d tangent = normal.unitOrthogonal(), bitangent = normal.cross(tangent);
    const Vector3d origin = random_vector(1.0);
    auto in_plane_point = [&](double size) {
      return Vector3d(origin + size * (unit(rng) * tangent + unit(rng) * bitangent) + 0.001 * unit(rng) * normal);
    };
    ccd::CcdQuery q;
    q.kind = i % 2 ? PairKind::VertexFace : PairKind::EdgeEdge;
    for (int k = 0; k < 4; ++k) q.start[k] = in_plane_point(0.04);
    const Vector3d fall = random_vector(0.01);
    for (int k = 0; k < 4; ++k) q.end[k] = q.start[k] + fall + random_vector(0.0005);
    const bool culled = ccd::projection_filter_culls(q, settings, ccd::ProjectionFilterOptions{true});
    INFO("pair " << i);
    if (culled) CHECK(ccd::continuous_collision(q, settings).state != ccd::CcdState::Hit);
    if (clothcd::test::sampled_min_distance(q, 20, 24) <= thickness) {
      ++within;
      CHECK_FALSE(culled);
    }
    if (ccd::detail::separated_in_plane(q, settings)) {
      ++in_plane;
      CHECK(culled);
    }
  }
  CHECK(in_plane > 500);  // the test sees the in-plane directions at work
  CHECK(within > 100);
}

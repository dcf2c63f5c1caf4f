// The scale section's false-report check: a reported pair's query is built from the right vertices of both frames,
// and the exact reference tells a real collision from a false one.
#include <catch2/catch.hpp>

#include <stdexcept>

#include "false_reports.hpp"

using clothcd::MeshFrames;
using clothcd::bench::check_false_reports;
using clothcd::bench::collision_query;
using clothcd::bench::CollisionKey;

namespace {

// Face 0 = (0, 1, 2) in the plane z = 0, static; vertex 3 falls through it (x = y = 0.2); vertex 4 falls beside it
// (x = y = 2); vertex 5 stays above. Face 1 = (3, 4, 5) only gives the moving vertices a face.
MeshFrames falling_vertices() {
  MeshFrames frames;
  frames.start.vertices.resize(6, 3);
  frames.start.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.2, 0.2, 1, 2, 2, 1, 0.2, 0.2, 2;
  frames.start.faces.resize(2, 3);
  frames.start.faces << 0, 1, 2, 3, 4, 5;
  frames.end = frames.start.vertices;
  frames.end(3, 2) = -1;
  frames.end(4, 2) = -1;
  return frames;
}

}  // namespace

TEST_CASE("false reports: the query of a vertex-face key takes the face's corners from both frames") {
  const MeshFrames frames = falling_vertices();
  const clothcd::ccd::CcdQuery query = collision_query(frames, {3, 0, -1, -1});
  CHECK(query.kind == clothcd::PairKind::VertexFace);
  CHECK(query.start[0].z() == 1);
  CHECK(query.end[0].z() == -1);
  CHECK(query.start[2] == Eigen::Vector3d(1, 0, 0));
  CHECK(query.end[3] == Eigen::Vector3d(0, 1, 0));
}

TEST_CASE("false reports: the query of an edge-edge key takes its four vertices in order") {
  const MeshFrames frames = falling_vertices();
  const clothcd::ccd::CcdQuery query = collision_query(frames, {0, 1, 3, 4});
  CHECK(query.kind == clothcd::PairKind::EdgeEdge);
  CHECK(query.start[1] == Eigen::Vector3d(1, 0, 0));
  CHECK(query.end[3] == Eigen::Vector3d(2, 2, -1));
}

TEST_CASE("false reports: only the pairs that do not touch are counted") {
  const MeshFrames frames = falling_vertices();
  const std::vector<CollisionKey> reported{{3, 0, -1, -1}, {4, 0, -1, -1}, {5, 0, -1, -1}};
  const auto all = check_false_reports(frames, reported, 10);
  CHECK(all.reported == 3);
  CHECK(all.checked == 3);
  CHECK(all.complete());
  CHECK(all.not_colliding == 2);
  const auto sample = check_false_reports(frames, reported, 1);  // the first only: a real collision
  CHECK(sample.checked == 1);
  CHECK_FALSE(sample.complete());
  CHECK(sample.not_colliding == 0);
}

TEST_CASE("false reports: a key outside the mesh is an error, not a crash") {
  const MeshFrames frames = falling_vertices();
  CHECK_THROWS_AS(collision_query(frames, {3, 2, -1, -1}), std::out_of_range);
  CHECK_THROWS_AS(collision_query(frames, {0, 1, 3, 6}), std::out_of_range);
  CHECK_THROWS_AS(collision_query(frames, {-2, 0, -1, -1}), std::out_of_range);
}

// Reported collisions checked with the exact rational reference (see false_reports.hpp).
#include "false_reports.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

#include "bench_util.hpp"

namespace clothcd::bench {
namespace {

Eigen::Index vertex_index(const MeshFrames& frames, int index) {
  if (index < 0 || index >= frames.start.vertex_count())
    throw std::out_of_range("collision names vertex " + std::to_string(index) + " of a mesh of " +
                            std::to_string(frames.start.vertex_count()));
  return index;
}

}  // namespace

ccd::CcdQuery collision_query(const MeshFrames& frames, const CollisionKey& key) {
  const bool vertex_face = key[2] < 0;
  std::array<int, 4> vertices = key;
  if (vertex_face) {
    if (key[1] < 0 || key[1] >= frames.start.face_count())
      throw std::out_of_range("collision names face " + std::to_string(key[1]) + " of a mesh of " +
                              std::to_string(frames.start.face_count()));
    for (int corner = 0; corner < 3; ++corner) vertices[1 + corner] = frames.start.faces(key[1], corner);
  }
  ccd::CcdQuery query;
  query.kind = vertex_face ? PairKind::VertexFace : PairKind::EdgeEdge;
  for (int i = 0; i < 4; ++i) {
    const Eigen::Index v = vertex_index(frames, vertices[i]);
    query.start[i] = frames.start.vertices.row(v).transpose();
    query.end[i] = frames.end.row(v).transpose();
  }
  return query;
}

FalseReportCheck check_false_reports(const MeshFrames& frames, const std::vector<CollisionKey>& reported,
                                     std::size_t limit) {
  FalseReportCheck check;
  check.reported = static_cast<long>(reported.size());
  const std::size_t count = std::min(limit, reported.size());
  check.ms = time_ms([&] {
    for (std::size_t i = 0; i < count; ++i) {
      const CollisionKey& key = reported[count == reported.size() ? i : i * reported.size() / count];
      ++check.checked;
      if (!ccd::exact_collision_reference(collision_query(frames, key))) ++check.not_colliding;
    }
  });
  return check;
}

}  // namespace clothcd::bench

// The intersecting faces of one state (see intersection_stage.hpp).
#include "intersection_stage.hpp"

#include <array>

#include "geometry/triangle_intersection.hpp"
#include "parallel_loop.hpp"

namespace clothcd::detail {

namespace {

// The vertex indices of face `face` of `body`.
std::array<int, 3> face_vertices(const BodyFrames& body, int face) {
  const Faces& faces = body.topology->faces;
  return {faces(face, 0), faces(face, 1), faces(face, 2)};
}

// The corners of a face at the body's start positions.
geometry::Triangle corners(const BodyFrames& body, const std::array<int, 3>& vertices) {
  geometry::Triangle t;
  for (int k = 0; k < 3; ++k) t[k] = body.start->row(vertices[k]).transpose();
  return t;
}

}  // namespace

void IntersectionStage::begin(const std::vector<BodyFrames>& bodies, const PairKeys& keys) {
  bodies_ = &bodies;
  keys_ = &keys;
  discard();
}

void IntersectionStage::discard() {
  for (Worker& w : workers_) {
    w.records.clear();
    w.counts = StageCounts{};
  }
}

long IntersectionStage::run_faces(const broadphase::FaceFaceCandidate* pairs, std::size_t count) {
  Worker& w = workers_.local();
  const auto t = StageClock::now();
  long found = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const broadphase::FaceFaceCandidate& c = pairs[i];
    const BodyFrames& body_a = (*bodies_)[static_cast<std::size_t>(c.body_a)];
    const BodyFrames& body_b = (*bodies_)[static_cast<std::size_t>(c.body_b)];
    const std::array<int, 3> va = face_vertices(body_a, c.face_a);
    const std::array<int, 3> vb = face_vertices(body_b, c.face_b);
    const geometry::SharedCorners shared =
        c.body_a == c.body_b ? geometry::shared_corners(va, vb) : geometry::SharedCorners{};
    const geometry::TriangleContact contact =
        geometry::intersect_triangles(corners(body_a, va), corners(body_b, vb), shared);
    if (!contact.intersect) continue;
    Keyed<FaceIntersection>& r = w.records.add();
    r.key = keys_->face_face(c.body_a, c.face_a, c.body_b, c.face_b);
    FaceIntersection& f = r.record;
    f.bodies = {c.body_a, c.body_b};
    f.faces = {c.face_a, c.face_b};
    f.edge_face = contact.edge_face;
    const std::array<int, 3>& edge_face = contact.edge_face == 0 ? va : vb;
    const std::int32_t edge_body = contact.edge_face == 0 ? c.body_a : c.body_b;
    f.edge = {VertexRef{edge_body, edge_face[static_cast<std::size_t>(contact.edge)]},
              VertexRef{edge_body, edge_face[static_cast<std::size_t>((contact.edge + 1) % 3)]}};
    f.edge_parameter = contact.edge_parameter;
    f.face_weights = contact.face_weights;
    f.coplanar = contact.coplanar;
    ++found;
  }
  w.counts.culled += static_cast<long>(count) - found;
  w.counts.exact_ms += milliseconds_since(t);
  return found;
}

void IntersectionStage::take_counts(StageCounts& counts) {
  for (Worker& w : workers_) {
    counts.add(w.counts);
    w.counts = StageCounts{};
  }
}

std::size_t IntersectionStage::record_count() const {
  std::size_t count = 0;
  for (const Worker& w : workers_) count += w.records.size();
  return count;
}

}  // namespace clothcd::detail

// The broad phase's brute-force references (brute_force_candidates.hpp): every primitive pair tested by its swept
// boxes, with the same skipping rules as the hierarchy searches, which the tests compare with these.
#include "broadphase/brute_force_candidates.hpp"

#include "broadphase/body_view_check.hpp"

namespace clothcd::broadphase {

void brute_force_self_candidates(const BodyView& body, CandidateSet& out) {
  detail::check_view(body, false);
  const BodyTopology& topo = *body.topology;
  const SweptBoxes& boxes = *body.boxes;
  for (int v = 0; v < topo.vertex_count; ++v) {
    if (topo.vertex_owner[v] < 0) continue;
    for (int f = 0; f < topo.face_count(); ++f) {
      if (!topo.face_has_vertex(f, v) && boxes.vertices[v].overlaps(boxes.faces[f])) {
        out.vertex_face.push_back({body.body, v, body.body, f});
      }
    }
  }
  for (int e = 0; e < topo.edge_count(); ++e) {
    for (int g = e + 1; g < topo.edge_count(); ++g) {
      if (!topo.edges_share_vertex(e, g) && boxes.edges[e].overlaps(boxes.edges[g])) {
        out.edge_edge.push_back({body.body, e, body.body, g});
      }
    }
  }
}

void brute_force_pair_candidates(const BodyView& a, const BodyView& b, CandidateSet& out) {
  detail::check_view(a, false);
  detail::check_view(b, false);
  auto vertices_against_faces = [&out](const BodyView& vb, const BodyView& fb) {
    for (int v = 0; v < vb.topology->vertex_count; ++v) {
      if (vb.topology->vertex_owner[v] < 0) continue;
      for (int f = 0; f < fb.topology->face_count(); ++f) {
        if (vb.boxes->vertices[v].overlaps(fb.boxes->faces[f])) out.vertex_face.push_back({vb.body, v, fb.body, f});
      }
    }
  };
  vertices_against_faces(a, b);
  vertices_against_faces(b, a);
  for (int e = 0; e < a.topology->edge_count(); ++e) {
    for (int g = 0; g < b.topology->edge_count(); ++g) {
      if (a.boxes->edges[e].overlaps(b.boxes->edges[g])) out.edge_edge.push_back({a.body, e, b.body, g});
    }
  }
}

}  // namespace clothcd::broadphase

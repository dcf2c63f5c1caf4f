// The broad phase's brute-force references (brute_force_candidates.hpp): every primitive pair tested by its swept
// boxes, with the same skipping rules as the hierarchy searches, which the tests compare with these.
#include "broadphase/brute_force_candidates.hpp"

#include "broadphase/body_view_check.hpp"
#include "broadphase/gap_bound.hpp"

namespace clothcd::broadphase {

using detail::within;

void brute_force_self_candidates(const BodyView& body, CandidateSet& out, SearchedPairs pairs, double gap) {
  detail::check_view(body, false);
  const BodyTopology& topo = *body.topology;
  const SweptBoxes& boxes = *body.boxes;
  if (pairs == SearchedPairs::FaceFace) {
    for (int f = 0; f < topo.face_count(); ++f) {
      for (int h = f + 1; h < topo.face_count(); ++h) {
        if (within(boxes.faces[f], boxes.faces[h], gap)) out.face_face.push_back({body.body, f, body.body, h});
      }
    }
    return;
  }
  for (int v = 0; v < topo.vertex_count; ++v) {
    if (topo.vertex_owner[v] < 0) continue;
    for (int f = 0; f < topo.face_count(); ++f) {
      if (!topo.face_has_vertex(f, v) && within(boxes.vertices[v], boxes.faces[f], gap)) {
        out.vertex_face.push_back({body.body, v, body.body, f});
      }
    }
  }
  for (int e = 0; e < topo.edge_count(); ++e) {
    for (int g = e + 1; g < topo.edge_count(); ++g) {
      if (!topo.edges_share_vertex(e, g) && within(boxes.edges[e], boxes.edges[g], gap)) {
        out.edge_edge.push_back({body.body, e, body.body, g});
      }
    }
  }
}

void brute_force_pair_candidates(const BodyView& a, const BodyView& b, CandidateSet& out, SearchedPairs pairs,
                                 double gap) {
  detail::check_view(a, false);
  detail::check_view(b, false);
  if (pairs == SearchedPairs::FaceFace) {
    for (int f = 0; f < a.topology->face_count(); ++f) {
      for (int h = 0; h < b.topology->face_count(); ++h) {
        if (within(a.boxes->faces[f], b.boxes->faces[h], gap)) out.face_face.push_back({a.body, f, b.body, h});
      }
    }
    return;
  }
  auto vertices_against_faces = [&out, gap](const BodyView& vb, const BodyView& fb) {
    for (int v = 0; v < vb.topology->vertex_count; ++v) {
      if (vb.topology->vertex_owner[v] < 0) continue;
      for (int f = 0; f < fb.topology->face_count(); ++f) {
        if (within(vb.boxes->vertices[v], fb.boxes->faces[f], gap)) {
          out.vertex_face.push_back({vb.body, v, fb.body, f});
        }
      }
    }
  };
  vertices_against_faces(a, b);
  vertices_against_faces(b, a);
  for (int e = 0; e < a.topology->edge_count(); ++e) {
    for (int g = 0; g < b.topology->edge_count(); ++g) {
      if (within(a.boxes->edges[e], b.boxes->edges[g], gap)) out.edge_edge.push_back({a.body, e, b.body, g});
    }
  }
}

}  // namespace clothcd::broadphase

// The closest-feature contacts of a state's pairs (see clothcd/detection/proximity.hpp).
#include <algorithm>
#include <tuple>
#include <utility>

#include "clothcd/detection/proximity.hpp"

namespace clothcd {

namespace {

constexpr VertexRef kUnused{-1, -1};

bool vertex_less(const VertexRef& a, const VertexRef& b) {
  return std::tie(a.body, a.vertex) < std::tie(b.body, b.vertex);
}

// The two vertices in order.
std::pair<VertexRef, VertexRef> ordered(const VertexRef& a, const VertexRef& b) {
  return vertex_less(b, a) ? std::make_pair(b, a) : std::make_pair(a, b);
}

FeatureContact vertex_vertex(const VertexRef& a, const VertexRef& b, double distance) {
  const auto [first, second] = ordered(a, b);
  return {ContactKind::VertexVertex, {first, second, kUnused, kUnused}, distance};
}

FeatureContact vertex_edge(const VertexRef& v, const VertexRef& e0, const VertexRef& e1, double distance) {
  const auto [first, second] = ordered(e0, e1);
  return {ContactKind::VertexEdge, {v, first, second, kUnused}, distance};
}

// The contact of one vertex-face pair: the point against the triangle's feature nearest to it.
FeatureContact face_contact(const Proximity& p) {
  const std::array<VertexRef, 4>& v = p.vertices;
  switch (p.type) {
    case DistanceType::PointEdge0: return vertex_edge(v[0], v[1], v[2], p.distance);
    case DistanceType::PointEdge1: return vertex_edge(v[0], v[2], v[3], p.distance);
    case DistanceType::PointEdge2: return vertex_edge(v[0], v[3], v[1], p.distance);
    case DistanceType::PointVertex0: return vertex_vertex(v[0], v[1], p.distance);
    case DistanceType::PointVertex1: return vertex_vertex(v[0], v[2], p.distance);
    case DistanceType::PointVertex2: return vertex_vertex(v[0], v[3], p.distance);
    default: return {ContactKind::VertexFace, v, p.distance};
  }
}

// The contact of one edge-edge pair.
FeatureContact edge_contact(const Proximity& p) {
  const std::array<VertexRef, 4>& v = p.vertices;
  switch (p.type) {
    case DistanceType::EdgeVertexB0: return vertex_edge(v[2], v[0], v[1], p.distance);
    case DistanceType::EdgeVertexB1: return vertex_edge(v[3], v[0], v[1], p.distance);
    case DistanceType::VertexA0Edge: return vertex_edge(v[0], v[2], v[3], p.distance);
    case DistanceType::VertexA1Edge: return vertex_edge(v[1], v[2], v[3], p.distance);
    case DistanceType::VertexA0VertexB0: return vertex_vertex(v[0], v[2], p.distance);
    case DistanceType::VertexA0VertexB1: return vertex_vertex(v[0], v[3], p.distance);
    case DistanceType::VertexA1VertexB0: return vertex_vertex(v[1], v[2], p.distance);
    case DistanceType::VertexA1VertexB1: return vertex_vertex(v[1], v[3], p.distance);
    default: {
      auto a = ordered(v[0], v[1]);
      auto b = ordered(v[2], v[3]);
      if (vertex_less(b.first, a.first) || (!vertex_less(a.first, b.first) && vertex_less(b.second, a.second))) {
        std::swap(a, b);
      }
      return {ContactKind::EdgeEdge, {a.first, a.second, b.first, b.second}, p.distance};
    }
  }
}

// Order by kind, then the vertices.
bool contact_less(const FeatureContact& a, const FeatureContact& b) {
  if (a.kind != b.kind) return a.kind < b.kind;
  for (int k = 0; k < 4; ++k) {
    if (vertex_less(a.vertices[k], b.vertices[k])) return true;
    if (vertex_less(b.vertices[k], a.vertices[k])) return false;
  }
  return false;
}

bool same_features(const FeatureContact& a, const FeatureContact& b) {
  return !contact_less(a, b) && !contact_less(b, a);
}

}  // namespace

std::vector<FeatureContact> closest_feature_contacts(const std::vector<Proximity>& pairs) {
  std::vector<FeatureContact> contacts;
  contacts.reserve(pairs.size());
  for (const Proximity& p : pairs) {
    contacts.push_back(p.kind == PairKind::VertexFace ? face_contact(p) : edge_contact(p));
  }
  std::stable_sort(contacts.begin(), contacts.end(), contact_less);
  contacts.erase(std::unique(contacts.begin(), contacts.end(), same_features), contacts.end());
  return contacts;
}

}  // namespace clothcd

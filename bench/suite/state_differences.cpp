// The state benchmark's side-by-side checks (see state_differences.hpp).
#include "state_differences.hpp"

#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include "geometry/exact_pair_distance.hpp"
#include "geometry/exact_triangle_intersection.hpp"

namespace clothcd::bench {
namespace {

constexpr int kVertexVertex = static_cast<int>(ContactKind::VertexVertex);
constexpr int kVertexEdge = static_cast<int>(ContactKind::VertexEdge);
constexpr int kEdgeEdge = static_cast<int>(ContactKind::EdgeEdge);
constexpr int kVertexFace = static_cast<int>(ContactKind::VertexFace);

// The canonical key of a contact of `kind` with vertices `v` (see ContactKey).
ContactKey canonical(int kind, std::array<int, 4> v) {
  if (kind == kVertexVertex) std::sort(v.begin(), v.begin() + 2);
  if (kind == kVertexEdge) std::sort(v.begin() + 1, v.begin() + 3);
  if (kind == kEdgeEdge) {
    std::sort(v.begin(), v.begin() + 2);
    std::sort(v.begin() + 2, v.begin() + 4);
    if (std::lexicographical_compare(v.begin() + 2, v.end(), v.begin(), v.begin() + 2)) {
      std::swap(v[0], v[2]);
      std::swap(v[1], v[3]);
    }
  }
  if (kind == kVertexFace) std::sort(v.begin() + 1, v.end());
  const int used = kind == kVertexVertex ? 2 : kind == kVertexEdge ? 3 : 4;
  for (int i = used; i < 4; ++i) v[i] = -1;
  return {kind, v[0], v[1], v[2], v[3]};
}

Eigen::Vector3d at(const Vertices& positions, int vertex) { return positions.row(vertex).transpose(); }

mpq_class squared_norm(const std::array<mpq_class, 3>& v) { return v[0] * v[0] + v[1] * v[1] + v[2] * v[2]; }

std::array<mpq_class, 3> difference(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return {mpq_class(a.x()) - mpq_class(b.x()), mpq_class(a.y()) - mpq_class(b.y()), mpq_class(a.z()) - mpq_class(b.z())};
}

// The exact squared distance of point p and the closed segment a b.
mpq_class point_segment_squared(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const std::array<mpq_class, 3> ab = difference(b, a), ap = difference(p, a);
  const mpq_class length = squared_norm(ab);
  mpq_class t = length == 0 ? mpq_class(0) : (ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) / length;
  t = std::clamp(t, mpq_class(0), mpq_class(1));
  return squared_norm({ap[0] - t * ab[0], ap[1] - t * ab[1], ap[2] - t * ab[2]});
}

// The exact squared distance of a contact's features.
mpq_class contact_squared_distance(const ContactKey& key, const Vertices& positions) {
  const auto p = [&](int i) { return at(positions, key[1 + i]); };
  switch (key[0]) {
    case kVertexVertex: return squared_norm(difference(p(0), p(1)));
    case kVertexEdge: return point_segment_squared(p(0), p(1), p(2));
    case kEdgeEdge: return geometry::exact_segment_segment_distance(p(0), p(1), p(2), p(3)).squared_distance;
    default: return geometry::exact_point_triangle_distance(p(0), p(1), p(2), p(3)).squared_distance;
  }
}

// The IPC Toolkit's mollifier rule for an edge-edge key (see ContactDifference::nearly_parallel).
bool nearly_parallel(const ContactKey& key, const Vertices& positions) {
  if (key[0] != kEdgeEdge) return false;
  const Eigen::Vector3d a = at(positions, key[2]) - at(positions, key[1]);
  const Eigen::Vector3d b = at(positions, key[4]) - at(positions, key[3]);
  return a.cross(b).squaredNorm() < 1e-3 * a.squaredNorm() * b.squaredNorm();
}

// The keys in `a` and not in `b` (both sorted).
template <class Key>
std::vector<Key> only_in(const std::vector<Key>& a, const std::vector<Key>& b) {
  std::vector<Key> only;
  std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(only));
  return only;
}

}  // namespace

std::string contact_kind_name(int kind) {
  static const char* const names[] = {"vv", "ve", "ee", "vf"};
  return kind >= 0 && kind < 4 ? names[kind] : "?";
}

ContactKey contact_key(const FeatureContact& contact) {
  std::array<int, 4> v{};
  for (int i = 0; i < 4; ++i) v[i] = contact.vertices[i].vertex;
  return canonical(static_cast<int>(contact.kind), v);
}

std::vector<ContactKey> contact_keys(const std::vector<FeatureContact>& contacts) {
  std::vector<ContactKey> keys;
  keys.reserve(contacts.size());
  for (const FeatureContact& contact : contacts) keys.push_back(contact_key(contact));
  std::sort(keys.begin(), keys.end());
  return keys;
}

std::vector<ContactKey> read_peer_contacts(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": cannot read");
  std::vector<ContactKey> keys;
  std::string line;
  for (long number = 1; std::getline(in, line); ++number) {
    std::istringstream words(line);
    std::string type;
    words >> type;
    const int kind = type == "vv" ? kVertexVertex : type == "ev" ? kVertexEdge : type == "ee" ? kEdgeEdge
                     : type == "fv" ? kVertexFace : -1;
    const int count = kind == kVertexVertex ? 2 : kind == kVertexEdge ? 3 : 4;
    std::array<int, 4> v{-1, -1, -1, -1};
    for (int i = 0; i < count && kind >= 0; ++i) words >> v[i];
    std::string rest;
    if (kind < 0 || words.fail() || (words >> rest))
      throw std::runtime_error(file.string() + ":" + std::to_string(number) + ": malformed contact '" + line + "'");
    keys.push_back(canonical(kind, v));
  }
  std::sort(keys.begin(), keys.end());
  return keys;
}

std::vector<ContactDifference> contact_differences(const std::vector<ContactKey>& ours,
                                                   const std::vector<ContactKey>& peer, const Vertices& positions,
                                                   double distance) {
  const mpq_class limit = mpq_class(distance) * mpq_class(distance);
  std::vector<ContactDifference> differences;
  for (const bool mine : {true, false})
    for (const ContactKey& key : mine ? only_in(ours, peer) : only_in(peer, ours)) {
      const mpq_class squared = contact_squared_distance(key, positions);
      differences.push_back(
          {key, mine, std::sqrt(squared.get_d()), squared < limit, nearly_parallel(key, positions)});
    }
  return differences;
}

std::vector<FacePair> face_pairs(const std::vector<FaceIntersection>& intersections) {
  std::vector<FacePair> pairs;
  pairs.reserve(intersections.size());
  for (const FaceIntersection& i : intersections)
    pairs.push_back({std::min(i.faces[0], i.faces[1]), std::max(i.faces[0], i.faces[1])});
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

std::vector<FacePairDifference> face_pair_differences(const std::vector<FacePair>& ours,
                                                      const std::vector<FacePair>& peer, const Faces& faces,
                                                      const Vertices& positions) {
  const auto triangle = [&](int f) {
    return geometry::Triangle{at(positions, faces(f, 0)), at(positions, faces(f, 1)), at(positions, faces(f, 2))};
  };
  const auto corners = [&](int f) { return std::array<int, 3>{faces(f, 0), faces(f, 1), faces(f, 2)}; };
  std::vector<FacePairDifference> differences;
  for (const bool mine : {true, false})
    for (const FacePair& pair : mine ? only_in(ours, peer) : only_in(peer, ours)) {
      const geometry::SharedCorners shared = geometry::shared_corners(corners(pair[0]), corners(pair[1]));
      differences.push_back(
          {pair, mine, geometry::exact_intersect_triangles(triangle(pair[0]), triangle(pair[1]), shared).intersect});
    }
  return differences;
}

}  // namespace clothcd::bench

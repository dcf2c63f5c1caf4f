// The state queries' records as NumPy columns, and back (state_arrays.hpp).
#include "state_arrays.hpp"

#include <stdexcept>
#include <string>

namespace clothcd::python {
namespace {

constexpr std::uint8_t kLastVertexFaceType = static_cast<std::uint8_t>(DistanceType::PointVertex2);
constexpr std::uint8_t kLastEdgeEdgeType = static_cast<std::uint8_t>(DistanceType::VertexA1VertexB1);

// Bodies and vertices of four VertexRefs into rows i of (n, 4) columns.
void put_refs(const std::array<VertexRef, 4>& refs, std::size_t i, std::vector<std::int32_t>& bodies,
              std::vector<std::int32_t>& vertices) {
  for (std::size_t k = 0; k < 4; ++k) {
    bodies[4 * i + k] = refs[k].body;
    vertices[4 * i + k] = refs[k].vertex;
  }
}

}  // namespace

ProximityColumns proximity_columns(const std::vector<Proximity>& pairs) {
  const std::size_t n = pairs.size();
  std::vector<std::uint8_t> kind(n), type(n);
  std::vector<std::int32_t> bodies(4 * n), vertices(4 * n);
  std::vector<double> distance(n), parameters(2 * n), direction(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const Proximity& p = pairs[i];
    kind[i] = p.kind == PairKind::VertexFace ? 0 : 1;
    put_refs(p.vertices, i, bodies, vertices);
    distance[i] = p.distance;
    parameters[2 * i] = p.parameters[0];
    parameters[2 * i + 1] = p.parameters[1];
    for (std::size_t k = 0; k < 3; ++k) direction[3 * i + k] = p.direction[static_cast<Eigen::Index>(k)];
    type[i] = static_cast<std::uint8_t>(p.type);
  }
  return {to_numpy(std::move(kind), {n}),       to_numpy(std::move(bodies), {n, 4}),
          to_numpy(std::move(vertices), {n, 4}), to_numpy(std::move(distance), {n}),
          to_numpy(std::move(parameters), {n, 2}), to_numpy(std::move(direction), {n, 3}),
          to_numpy(std::move(type), {n})};
}

IntersectionColumns intersection_columns(const std::vector<FaceIntersection>& intersections) {
  const std::size_t n = intersections.size();
  std::vector<std::int32_t> bodies(2 * n), faces(2 * n), edge(2 * n);
  std::vector<std::uint8_t> edge_face(n), coplanar(n);
  std::vector<double> edge_parameter(n), face_weights(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const FaceIntersection& x = intersections[i];
    for (std::size_t k = 0; k < 2; ++k) {
      bodies[2 * i + k] = x.bodies[k];
      faces[2 * i + k] = x.faces[k];
      edge[2 * i + k] = x.edge[k].vertex;
      face_weights[2 * i + k] = x.face_weights[k];
    }
    edge_face[i] = static_cast<std::uint8_t>(x.edge_face);
    edge_parameter[i] = x.edge_parameter;
    coplanar[i] = x.coplanar ? 1 : 0;
  }
  return {to_numpy(std::move(bodies), {n, 2}),        to_numpy(std::move(faces), {n, 2}),
          to_numpy(std::move(edge_face), {n}),        to_numpy(std::move(edge), {n, 2}),
          to_numpy(std::move(edge_parameter), {n}),   to_numpy(std::move(face_weights), {n, 2}),
          to_numpy(std::move(coplanar), {n})};
}

ContactColumns contact_columns(const std::vector<FeatureContact>& contacts) {
  const std::size_t n = contacts.size();
  std::vector<std::uint8_t> kind(n);
  std::vector<std::int32_t> bodies(4 * n), vertices(4 * n);
  std::vector<double> distance(n);
  for (std::size_t i = 0; i < n; ++i) {
    kind[i] = static_cast<std::uint8_t>(contacts[i].kind);
    put_refs(contacts[i].vertices, i, bodies, vertices);
    distance[i] = contacts[i].distance;
  }
  return {to_numpy(std::move(kind), {n}), to_numpy(std::move(bodies), {n, 4}), to_numpy(std::move(vertices), {n, 4}),
          to_numpy(std::move(distance), {n})};
}

std::vector<Proximity> proximities_from_columns(
    const nb::ndarray<const std::uint8_t, nb::c_contig, nb::device::cpu>& kind, const IntArray& bodies,
    const IntArray& vertices, const nb::ndarray<const double, nb::c_contig, nb::device::cpu>& distance,
    const nb::ndarray<const std::uint8_t, nb::c_contig, nb::device::cpu>& type) {
  const std::size_t n = kind.ndim() == 1 ? kind.shape(0) : 0;
  const auto rows_of = [n](const auto& array, std::size_t width) {
    return width == 0 ? array.ndim() == 1 && array.shape(0) == n
                      : array.ndim() == 2 && array.shape(0) == n && array.shape(1) == width;
  };
  if (kind.ndim() != 1 || !rows_of(bodies, 4) || !rows_of(vertices, 4) || !rows_of(distance, 0) || !rows_of(type, 0))
    throw std::invalid_argument("closest_feature_contacts: expected kind (n,), bodies (n, 4), vertices (n, 4), "
                                "distance (n,) and type (n,) columns");
  std::vector<Proximity> pairs(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t k = kind.data()[i], t = type.data()[i];
    const bool vertex_face = k == 0;
    if (k > 1 || (vertex_face ? t > kLastVertexFaceType : t <= kLastVertexFaceType || t > kLastEdgeEdgeType))
      throw std::invalid_argument("closest_feature_contacts: row " + std::to_string(i) + " has kind " +
                                  std::to_string(k) + " with type " + std::to_string(t));
    Proximity& p = pairs[i];
    p.kind = vertex_face ? PairKind::VertexFace : PairKind::EdgeEdge;
    for (std::size_t c = 0; c < 4; ++c) p.vertices[c] = {bodies.data()[4 * i + c], vertices.data()[4 * i + c]};
    p.distance = distance.data()[i];
    p.type = static_cast<DistanceType>(t);
  }
  return pairs;
}

}  // namespace clothcd::python

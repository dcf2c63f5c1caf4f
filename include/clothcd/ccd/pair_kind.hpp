#pragma once
/// @file
/// What names a primitive pair from the CCD stage up: its kind and its four vertices (body, index).

#include <cstdint>

namespace clothcd {

/// A vertex of the scene: which body it belongs to and its index there. Body 0 is the cloth; body k >= 1 is obstacle k-1.
struct VertexRef {
  std::int32_t body = 0;    ///< 0 = cloth, k >= 1 = obstacle k-1.
  std::int32_t vertex = 0;  ///< Index in that body's vertex array.
};

/// The two kinds of primitive pairs of continuous collision detection.
enum class PairKind : std::uint8_t {
  VertexFace,  ///< vertices[0] is the vertex, vertices[1..3] the triangle.
  EdgeEdge,    ///< vertices[0..1] is edge a, vertices[2..3] edge b.
};

}  // namespace clothcd

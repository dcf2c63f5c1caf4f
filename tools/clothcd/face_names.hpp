#pragma once
// The face index of each vertex-face record in turn: the detector's records name a face by its three vertices, the
// JSON reports by its index in the mesh.

#include <array>
#include <cstddef>
#include <map>
#include <utility>
#include <vector>

#include "clothcd/ccd/pair_kind.hpp"
#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::cli {

/// Faces by their vertices. A face listed several times in the mesh is several faces with the same vertices, named in
/// turn for each vertex that meets them. One sorted row (three vertices, face) per face: 16 bytes a face, nothing per
/// record but for such faces.
class FaceNames {
 public:
  /// Indexes the faces of `mesh`.
  explicit FaceNames(const TriangleMesh& mesh);

  /// The face of the next vertex-face record with these vertices (the vertex, then the face's three in its order).
  /// Throws std::logic_error when the mesh has no such face.
  int next(const std::array<VertexRef, 4>& vertices);

 private:
  using Row = std::array<int, 4>;
  std::vector<Row> rows_;
  std::map<std::pair<int, std::array<int, 3>>, std::size_t> named_;  ///< (vertex, face vertices) -> faces named so far
};

}  // namespace clothcd::cli

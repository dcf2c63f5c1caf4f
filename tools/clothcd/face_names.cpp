// Faces named by their vertices (face_names.hpp).
#include "face_names.hpp"

#include <algorithm>
#include <stdexcept>

namespace clothcd::cli {

FaceNames::FaceNames(const TriangleMesh& mesh) {
  rows_.reserve(static_cast<std::size_t>(mesh.face_count()));
  for (int f = 0; f < static_cast<int>(mesh.face_count()); ++f) {
    rows_.push_back({mesh.faces(f, 0), mesh.faces(f, 1), mesh.faces(f, 2), f});
  }
  std::sort(rows_.begin(), rows_.end());
}

int FaceNames::next(const std::array<VertexRef, 4>& vertices) {
  const std::array<int, 3> corners{vertices[1].vertex, vertices[2].vertex, vertices[3].vertex};
  const auto first = std::lower_bound(rows_.begin(), rows_.end(), Row{corners[0], corners[1], corners[2], -1});
  auto last = first;
  while (last != rows_.end() && (*last)[0] == corners[0] && (*last)[1] == corners[1] && (*last)[2] == corners[2]) {
    ++last;
  }
  if (first == last) throw std::logic_error("a vertex-face pair names a face the mesh does not have");
  if (last - first == 1) return (*first)[3];
  std::size_t& named = named_[{vertices[0].vertex, corners}];
  const std::size_t k = std::min(named, static_cast<std::size_t>(last - first) - 1);
  ++named;
  return first[static_cast<std::ptrdiff_t>(k)][3];
}

}  // namespace clothcd::cli

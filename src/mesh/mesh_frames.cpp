// Two frames of one mesh (see mesh_frames.hpp).
#include "clothcd/mesh/mesh_frames.hpp"

#include <array>
#include <map>
#include <string>
#include <vector>

#include "clothcd/mesh/mesh_error.hpp"
#include "clothcd/mesh/mesh_io.hpp"
#include "mesh/mesh_readers.hpp"

namespace clothcd {
namespace {

namespace fs = std::filesystem;

void check_same_faces(const TriangleMesh& start, const TriangleMesh& end, const fs::path& start_path,
                      const fs::path& end_path) {
  if (start.vertex_count() != end.vertex_count()) {
    throw MeshError(end_path.string(), "has " + std::to_string(end.vertex_count()) + " vertices but " +
                                           start_path.string() + " has " + std::to_string(start.vertex_count()) +
                                           " (both frames need the same vertex numbering)");
  }
  if (start.faces.rows() != end.faces.rows() || start.faces != end.faces) {
    throw MeshError(end_path.string(),
                    "its faces differ from those of " + start_path.string() + " (both frames need the same faces)");
  }
}

// Corners at bit-identical positions in both frames become one vertex. Welding by the pair of positions (not by either
// frame alone) keeps both frames' numbering equal; vertices are numbered in order of first appearance.
MeshFrames weld(const TriangleMesh& start, const TriangleMesh& end) {
  std::map<std::array<double, 6>, int> index_of;
  std::vector<int> remap(static_cast<std::size_t>(start.vertex_count()));
  MeshFrames frames;
  frames.start.vertices.resize(start.vertex_count(), 3);
  frames.end.resize(start.vertex_count(), 3);
  int next = 0;
  for (Eigen::Index v = 0; v < start.vertex_count(); ++v) {
    const std::array<double, 6> key = {start.vertices(v, 0), start.vertices(v, 1), start.vertices(v, 2),
                                       end.vertices(v, 0),   end.vertices(v, 1),   end.vertices(v, 2)};
    const auto [it, inserted] = index_of.emplace(key, next);
    if (inserted) {
      frames.start.vertices.row(next) = start.vertices.row(v);
      frames.end.row(next) = end.vertices.row(v);
      ++next;
    }
    remap[static_cast<std::size_t>(v)] = it->second;
  }
  frames.start.vertices.conservativeResize(next, 3);
  frames.end.conservativeResize(next, 3);
  frames.start.faces = start.faces;
  for (Eigen::Index i = 0; i < frames.start.faces.size(); ++i) {
    frames.start.faces.data()[i] = remap[static_cast<std::size_t>(frames.start.faces.data()[i])];
  }
  return frames;
}

}  // namespace

MeshFrames load_mesh_frames(const fs::path& start, const fs::path& end) {
  LoadOptions keep_all;
  keep_all.join_identical_vertices = false;
  keep_all.drop_degenerate_faces = false;
  const TriangleMesh first = load_mesh(start, keep_all);
  const TriangleMesh second = load_mesh(end, keep_all);
  check_same_faces(first, second, start, end);
  if (detail::lower_extension(start) == ".stl" && detail::lower_extension(end) == ".stl") return weld(first, second);
  return {first, second.vertices};
}

}  // namespace clothcd

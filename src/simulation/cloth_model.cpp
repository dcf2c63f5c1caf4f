// Mass-spring cloth model in the style of Provot 1995 ("Deformation constraints in a mass-spring model to describe rigid
// cloth behavior"): structural, shear and bending springs over a triangulated quad grid, lumped masses from area density.
#include "clothcd/simulation/cloth_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "clothcd/mesh/mesh_validation.hpp"

namespace clothcd::simulation {
namespace {

/// A mesh edge with the vertices opposite to it in its (at most two) triangles.
struct EdgeInfo {
  int a = 0, b = 0;
  int opposite[2] = {-1, -1};
  int face_count = 0;
};

void require_setting(double value, const char* name) {
  if (!std::isfinite(value) || value < 0) {
    throw std::invalid_argument(std::string("cloth setting ") + name + " must be finite and >= 0");
  }
}

std::vector<EdgeInfo> collect_edges(const Faces& faces) {
  std::vector<std::pair<std::pair<int, int>, int>> half;  // (sorted edge, opposite vertex)
  half.reserve(static_cast<size_t>(faces.rows()) * 3);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int u = faces(f, k), v = faces(f, (k + 1) % 3), w = faces(f, (k + 2) % 3);
      half.push_back({{std::min(u, v), std::max(u, v)}, w});
    }
  }
  std::sort(half.begin(), half.end());
  std::vector<EdgeInfo> edges;
  for (const auto& [edge, opposite] : half) {
    if (edges.empty() || edges.back().a != edge.first || edges.back().b != edge.second) {
      edges.push_back({edge.first, edge.second, {-1, -1}, 0});
    }
    EdgeInfo& info = edges.back();
    if (info.face_count < 2) info.opposite[info.face_count] = opposite;
    ++info.face_count;
  }
  return edges;
}

/// A quad diagonal is the edge facing a (near) right angle in each of its triangles.
bool is_diagonal(const Vertices& x, const EdgeInfo& e) {
  const int faces = std::min(e.face_count, 2);
  for (int k = 0; k < faces; ++k) {
    const Eigen::Vector3d p = x.row(e.opposite[k]);
    const Eigen::Vector3d u = (Eigen::Vector3d(x.row(e.a)) - p).normalized();
    const Eigen::Vector3d v = (Eigen::Vector3d(x.row(e.b)) - p).normalized();
    if (std::abs(u.dot(v)) > 0.17) return false;  // cos 80 degrees
  }
  return faces > 0;
}

void add_spring(std::vector<Spring>& springs, const Vertices& x, int a, int b, SpringKind kind) {
  if (a == b) return;
  if (a > b) std::swap(a, b);
  springs.push_back({a, b, (Eigen::Vector3d(x.row(a)) - Eigen::Vector3d(x.row(b))).norm(), kind});
}

/// Skip-one springs: v - u - w with both edges structural and nearly collinear.
void add_bending_springs(std::vector<Spring>& springs, const Vertices& x, const std::vector<std::vector<int>>& neighbours) {
  for (int v = 0; v < static_cast<int>(neighbours.size()); ++v) {
    for (const int u : neighbours[v]) {
      const Eigen::Vector3d d1 = (Eigen::Vector3d(x.row(u)) - Eigen::Vector3d(x.row(v))).normalized();
      for (const int w : neighbours[u]) {
        if (w <= v) continue;  // each line once, from its smaller end
        const Eigen::Vector3d d2 = (Eigen::Vector3d(x.row(w)) - Eigen::Vector3d(x.row(u))).normalized();
        if (d1.dot(d2) > 0.95) add_spring(springs, x, v, w, SpringKind::Bending);
      }
    }
  }
}

}  // namespace

ClothModel build_cloth_model(const TriangleMesh& mesh, const ClothSettings& settings,
                             const std::vector<int>& pinned_vertices) {
  validate_mesh(mesh, "cloth");
  require_setting(settings.density, "density");
  require_setting(settings.structural_stiffness, "structural_stiffness");
  require_setting(settings.shear_stiffness, "shear_stiffness");
  require_setting(settings.bending_stiffness, "bending_stiffness");
  require_setting(settings.spring_damping, "spring_damping");
  require_setting(settings.air_damping, "air_damping");
  if (!settings.gravity.allFinite()) throw std::invalid_argument("cloth setting gravity must be finite");
  if (settings.density <= 0) throw std::invalid_argument("cloth setting density must be > 0");

  ClothModel model;
  model.rest = mesh;
  model.settings = settings;
  const Vertices& x = mesh.vertices;
  const int n = static_cast<int>(x.rows());

  const std::vector<EdgeInfo> edges = collect_edges(mesh.faces);
  std::vector<std::vector<int>> structural_neighbours(n);
  std::vector<Spring> structural, shear, bending;
  for (const EdgeInfo& e : edges) {
    if (is_diagonal(x, e)) {
      add_spring(shear, x, e.a, e.b, SpringKind::Shear);
      if (e.face_count == 2) add_spring(shear, x, e.opposite[0], e.opposite[1], SpringKind::Shear);
    } else {
      add_spring(structural, x, e.a, e.b, SpringKind::Structural);
      structural_neighbours[e.a].push_back(e.b);
      structural_neighbours[e.b].push_back(e.a);
    }
  }
  add_bending_springs(bending, x, structural_neighbours);
  model.springs = std::move(structural);
  model.springs.insert(model.springs.end(), shear.begin(), shear.end());
  model.springs.insert(model.springs.end(), bending.begin(), bending.end());

  model.masses.assign(n, 0.0);
  double total = 0;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const Eigen::Vector3d a = x.row(mesh.faces(f, 0)), b = x.row(mesh.faces(f, 1)), c = x.row(mesh.faces(f, 2));
    const double third = settings.density * 0.5 * (b - a).cross(c - a).norm() / 3.0;
    for (int k = 0; k < 3; ++k) model.masses[mesh.faces(f, k)] += third;
    total += 3 * third;
  }
  // A vertex in no (or only degenerate) triangles still needs a mass for the integrator.
  const double fallback = total > 0 ? total / n : 1e-6;
  for (double& m : model.masses) {
    if (m <= 0) m = fallback;
  }

  model.pinned.assign(n, 0);
  for (const int v : pinned_vertices) {
    if (v < 0 || v >= n) {
      throw std::invalid_argument("pinned vertex " + std::to_string(v) + " is outside the cloth's " +
                                  std::to_string(n) + " vertices");
    }
    model.pinned[v] = 1;
  }
  return model;
}

ClothState rest_state(const ClothModel& model) {
  ClothState state;
  state.positions = model.rest.vertices;
  state.velocities = Vertices::Zero(model.rest.vertices.rows(), 3);
  return state;
}

std::vector<int> count_springs(const ClothModel& model) {
  std::vector<int> counts(3, 0);
  for (const Spring& s : model.springs) ++counts[static_cast<int>(s.kind)];
  return counts;
}

}  // namespace clothcd::simulation

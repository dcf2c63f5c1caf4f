// Procedural meshes: grids (the paper's cloths), UV spheres, boxes and the fish stand-in.
#include "clothcd/mesh/mesh_generators.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace clothcd {
namespace {

constexpr double kPi = 3.14159265358979323846;

void require(bool condition, const char* message) {
  if (!condition) throw std::invalid_argument(message);
}

/// Closes a surface of revolution given as `rings` x `slices` vertices (ring-major) with a pole vertex at each end.
/// Ring r, slice s is vertex r * slices + s; the two poles are the last two vertices.
Faces revolve_faces(int rings, int slices) {
  const int south = rings * slices, north = south + 1;
  Faces faces(2 * slices * (rings - 1) + 2 * slices, 3);
  Eigen::Index f = 0;
  for (int r = 0; r + 1 < rings; ++r) {
    for (int s = 0; s < slices; ++s) {
      const int a = r * slices + s, b = r * slices + (s + 1) % slices;
      const int c = a + slices, d = b + slices;
      faces.row(f++) << a, c, b;
      faces.row(f++) << b, c, d;
    }
  }
  for (int s = 0; s < slices; ++s) {
    faces.row(f++) << south, s, (s + 1) % slices;
    const int top = (rings - 1) * slices;
    faces.row(f++) << north, top + (s + 1) % slices, top + s;
  }
  return faces;
}

}  // namespace

TriangleMesh make_grid(int columns, int rows, double width, double depth) {
  require(columns >= 2 && rows >= 2, "a grid needs at least 2 x 2 vertices");
  require(std::isfinite(width) && std::isfinite(depth) && width > 0 && depth > 0,
          "grid sizes must be positive and finite");
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(columns) * rows, 3);
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < columns; ++i) {
      mesh.vertices.row(j * columns + i) << width * (static_cast<double>(i) / (columns - 1) - 0.5), 0.0,
          depth * (static_cast<double>(j) / (rows - 1) - 0.5);
    }
  }
  mesh.faces.resize(2 * static_cast<Eigen::Index>(columns - 1) * (rows - 1), 3);
  Eigen::Index f = 0;
  for (int j = 0; j + 1 < rows; ++j) {
    for (int i = 0; i + 1 < columns; ++i) {
      const int a = j * columns + i, b = a + 1, c = a + columns, d = c + 1;
      // Alternate the diagonal so that the cloth has no preferred shear direction.
      if ((i + j) % 2 == 0) {
        mesh.faces.row(f++) << a, c, b;
        mesh.faces.row(f++) << b, c, d;
      } else {
        mesh.faces.row(f++) << a, c, d;
        mesh.faces.row(f++) << a, d, b;
      }
    }
  }
  return mesh;
}

TriangleMesh make_paper_cloth(char name, double size) {
  switch (name) {
    case 'A': return make_grid(20, 20, size, size);
    case 'B': return make_grid(30, 30, size, size);
    case 'C': return make_grid(50, 50, size, size);
    default: throw std::invalid_argument(std::string("unknown cloth '") + name + "' (the paper's cloths are A, B, C)");
  }
}

TriangleMesh make_uv_sphere(double radius, int slices, int stacks) {
  require(slices >= 3 && stacks >= 2, "a UV sphere needs at least 3 slices and 2 stacks");
  require(std::isfinite(radius) && radius > 0, "the sphere radius must be positive and finite");
  const int rings = stacks - 1;
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(rings) * slices + 2, 3);
  for (int r = 0; r < rings; ++r) {
    const double polar = kPi * (r + 1) / stacks;  // from the south pole upwards
    for (int s = 0; s < slices; ++s) {
      const double azimuth = 2 * kPi * s / slices;
      mesh.vertices.row(r * slices + s) << radius * std::sin(polar) * std::cos(azimuth), -radius * std::cos(polar),
          radius * std::sin(polar) * std::sin(azimuth);
    }
  }
  mesh.vertices.row(rings * slices) << 0, -radius, 0;
  mesh.vertices.row(rings * slices + 1) << 0, radius, 0;
  mesh.faces = revolve_faces(rings, slices);
  return mesh;
}

TriangleMesh make_box(const Eigen::Vector3d& half_extents) {
  require(half_extents.allFinite() && (half_extents.array() > 0).all(), "box half extents must be positive and finite");
  TriangleMesh mesh;
  mesh.vertices.resize(8, 3);
  for (int i = 0; i < 8; ++i) {
    mesh.vertices.row(i) << ((i & 1) ? 1 : -1) * half_extents.x(), ((i & 2) ? 1 : -1) * half_extents.y(),
        ((i & 4) ? 1 : -1) * half_extents.z();
  }
  mesh.faces.resize(12, 3);
  mesh.faces << 0, 2, 1, 1, 2, 3,  // z-
      4, 5, 6, 5, 7, 6,            // z+
      0, 1, 4, 1, 5, 4,            // y-
      2, 6, 3, 3, 6, 7,            // y+
      0, 4, 2, 2, 4, 6,            // x-
      1, 3, 5, 3, 7, 5;            // x+
  return mesh;
}

TriangleMesh make_fish(int slices, int stations) {
  require(slices >= 6 && stations >= 8, "the fish needs at least 6 slices and 8 stations");
  // Cross-sections along x in [-1, 1]: an ellipse whose half height and half width follow a spindle profile, with a
  // tail that narrows to a waist and flares into a tall, thin fin at the back.
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(stations) * slices + 2, 3);
  for (int k = 0; k < stations; ++k) {
    const double u = static_cast<double>(k + 1) / (stations + 1);  // 0 = tail tip, 1 = snout
    const double x = 2.0 * u - 1.0;
    const double body = std::pow(std::sin(kPi * std::pow(u, 0.8)), 0.7);
    const double fin = u < 0.2 ? std::pow(1.0 - u / 0.2, 1.5) : 0.0;
    const double half_height = 0.32 * body + 0.45 * fin;
    const double half_width = 0.14 * body + 0.02 * fin;
    for (int s = 0; s < slices; ++s) {
      const double angle = 2 * kPi * s / slices;
      // Fork the fin: pull the top and bottom of the tail outwards more than its middle.
      const double fork = fin > 0 ? 1.0 + 0.4 * fin * std::pow(std::abs(std::sin(angle)), 4.0) : 1.0;
      mesh.vertices.row(k * slices + s) << x, half_height * fork * std::sin(angle), half_width * std::cos(angle);
    }
  }
  mesh.vertices.row(stations * slices) << -1.0, 0, 0;
  mesh.vertices.row(stations * slices + 1) << 1.0, 0, 0;
  mesh.faces = revolve_faces(stations, slices);
  return mesh;
}

}  // namespace clothcd

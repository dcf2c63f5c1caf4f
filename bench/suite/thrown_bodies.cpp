// Generated large-motion steps: bodies on a lattice thrown through their neighbours (see thrown_bodies.hpp).
#include "thrown_bodies.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "clothcd/mesh/mesh_generators.hpp"

namespace clothcd::bench {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kSpacing = 1.5;  // distance between neighbouring bodies' cells; a body is about 1 across

// Uniform numbers from mt19937_64's raw output (the standard distributions may differ between libraries; this does
// not).
class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  double uniform(double low, double high) {
    return low + (high - low) * static_cast<double>(engine_() >> 11) * 0x1.0p-53;
  }
  // A uniformly distributed rotation (Shoemake's method).
  Eigen::Quaterniond rotation() {
    const double u1 = uniform(0, 1), u2 = uniform(0, 2 * kPi), u3 = uniform(0, 2 * kPi);
    const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
    return Eigen::Quaterniond(b * std::cos(u3), a * std::sin(u2), a * std::cos(u2), b * std::sin(u3)).normalized();
  }
  // A uniformly distributed unit vector.
  Eigen::Vector3d direction() {
    const double z = uniform(-1, 1), phi = uniform(0, 2 * kPi), r = std::sqrt(1 - z * z);
    return {r * std::cos(phi), r * std::sin(phi), z};
  }

 private:
  std::mt19937_64 engine_;
};

// Body `index` of unit size in its own frame: sphere, sheet, sphere, fish, in turn.
TriangleMesh body_shape(int index, int resolution, double size) {
  switch (index % 4) {
    case 1: return make_grid(resolution, resolution, 1.2 * size, 1.2 * size);
    case 3: {
      TriangleMesh fish = make_fish(resolution, 2 * resolution);
      fish.vertices *= 0.5 * size;
      return fish;
    }
    default: return make_uv_sphere(0.5 * size, resolution, resolution / 2);
  }
}

}  // namespace

ThrownBodiesStep make_thrown_bodies(const ThrownBodiesSpec& spec) {
  if (spec.bodies < 1 || spec.resolution < 4 || !(spec.throw_distance > 0) || !std::isfinite(spec.throw_distance))
    throw std::invalid_argument("thrown bodies: need bodies >= 1, resolution >= 4 and a positive throw distance");
  Random random(spec.seed);
  const int side = static_cast<int>(std::ceil(std::cbrt(static_cast<double>(spec.bodies)) - 1e-9));
  const double half = 0.5 * (side - 1);
  std::vector<TriangleMesh> shapes;
  std::vector<Eigen::Isometry3d> starts, ends;
  Eigen::Index vertex_count = 0, face_count = 0;
  for (int i = 0; i < spec.bodies; ++i) {
    shapes.push_back(body_shape(i, spec.resolution, random.uniform(0.8, 1.2)));
    const Eigen::Vector3d cell(i % side - half, (i / side) % side - half, i / (side * side) - half);
    const Eigen::Vector3d centre = kSpacing * (cell + 0.15 * random.direction());
    const Eigen::Vector3d throw_vector = kSpacing * spec.throw_distance * random.uniform(0.7, 1.0) * random.direction();
    const Eigen::Quaterniond start_rotation = random.rotation();
    const Eigen::Vector3d spin_axis = random.direction();
    const double spin = random.uniform(0, 0.5);
    Eigen::Isometry3d start = Eigen::Isometry3d::Identity(), end = Eigen::Isometry3d::Identity();
    start.translate(centre).rotate(start_rotation);
    end.translate(centre + throw_vector).rotate(Eigen::AngleAxisd(spin, spin_axis) * start_rotation);
    starts.push_back(start);
    ends.push_back(end);
    vertex_count += shapes.back().vertex_count();
    face_count += shapes.back().face_count();
  }
  ThrownBodiesStep step;
  step.start.vertices.resize(vertex_count, 3);
  step.start.faces.resize(face_count, 3);
  step.end.resize(vertex_count, 3);
  Eigen::Index v = 0, f = 0;
  for (std::size_t b = 0; b < shapes.size(); ++b) {
    const TriangleMesh& shape = shapes[b];
    for (Eigen::Index i = 0; i < shape.vertex_count(); ++i) {
      const Eigen::Vector3d p = shape.vertices.row(i).transpose();
      step.start.vertices.row(v + i) = (starts[b] * p).transpose();
      step.end.row(v + i) = (ends[b] * p).transpose();
    }
    step.start.faces.middleRows(f, shape.face_count()) = shape.faces.array() + static_cast<int>(v);
    v += shape.vertex_count();
    f += shape.face_count();
  }
  return step;
}

}  // namespace clothcd::bench

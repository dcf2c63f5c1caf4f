// A cloth dropped on a sphere: a mass-spring cloth of its own (a spring along every edge, gravity, damping, moved by
// semi-implicit Euler in substeps) with clothcd::CollisionDetector keeping it out of the sphere. Each step predicts
// the end positions, asks the detector for every collision of the step, stops the colliding cloth vertices just
// before their time of impact, and asks again until the step is free of collisions. Prints one line per 40 steps and
// checks at the end that no cloth vertex went into the sphere and that the springs held the cloth together (each
// shorter than 1.5 times its rest length; the response pins colliding vertices, so a few springs stay stretched where
// the cloth clings to the sphere). Exit code 0 on success.
#include <clothcd/clothcd.hpp>

#include <algorithm>
#include <cstdio>
#include <vector>

namespace {

const double kGravity = -9.81;     // m / s^2, along y
const double kStiffness = 2.0e5;   // spring force per metre of stretch, per unit vertex mass (1 / s^2)
const double kDamping = 20.0;      // spring force per m / s of stretching speed, per unit vertex mass (1 / s)
const double kAirDamping = 0.995;  // velocity kept per step

// The springs: a cloth edge each (vertex pairs, as CollisionDetector::edges lists them) with its rest length.
struct Springs {
  std::vector<int> ends;
  std::vector<double> rest;
};

Springs springs_of(const std::vector<int>& edges, const clothcd::Vertices& positions) {
  Springs springs{edges, {}};
  for (std::size_t e = 0; 2 * e < edges.size(); ++e)
    springs.rest.push_back((positions.row(edges[2 * e + 1]) - positions.row(edges[2 * e])).norm());
  return springs;
}

// Moves `x` and `v` over `dt` by semi-implicit Euler in `substeps` steps (explicit springs need short ones).
void integrate(const Springs& springs, double dt, int substeps, clothcd::Vertices& x, clothcd::Vertices& v) {
  const double h = dt / substeps;
  clothcd::Vertices acceleration(x.rows(), 3);
  for (int i = 0; i < substeps; ++i) {
    acceleration.setZero();
    acceleration.col(1).array() = kGravity;
    for (std::size_t s = 0; s < springs.rest.size(); ++s) {
      const int a = springs.ends[2 * s], b = springs.ends[2 * s + 1];
      const Eigen::RowVector3d d = x.row(b) - x.row(a);
      const double length = d.norm();
      const Eigen::RowVector3d direction = d / length;
      const double pull = kStiffness * (length - springs.rest[s]) + kDamping * (v.row(b) - v.row(a)).dot(direction);
      acceleration.row(a) += pull * direction;
      acceleration.row(b) -= pull * direction;
    }
    v += h * acceleration;
    x += h * v;
  }
  v *= kAirDamping;
}

double largest_stretch(const Springs& springs, const clothcd::Vertices& x) {
  double stretch = 0;
  for (std::size_t s = 0; s < springs.rest.size(); ++s) {
    const double length = (x.row(springs.ends[2 * s + 1]) - x.row(springs.ends[2 * s])).norm();
    stretch = std::max(stretch, length / springs.rest[s] - 1.0);
  }
  return stretch;
}

}  // namespace

int main() {
  const double radius = 0.5, dt = 0.005;
  const int substeps = 10;
  const clothcd::TriangleMesh sphere = clothcd::make_uv_sphere(radius, 32, 16);
  clothcd::TriangleMesh cloth = clothcd::make_grid(24, 24, 1.6, 1.6);  // in the xz plane, centred on the origin
  cloth.vertices.col(1).array() += radius + 0.1;

  clothcd::DetectorSettings settings;
  settings.thickness = 1e-3;
  clothcd::CollisionDetector detector(cloth.faces, static_cast<int>(cloth.vertex_count()), settings);
  detector.add_obstacle(sphere);  // body 1
  const Springs springs = springs_of(detector.edges(0), cloth.vertices);

  clothcd::Vertices positions = cloth.vertices;
  clothcd::Vertices velocities = clothcd::Vertices::Zero(positions.rows(), 3);
  std::printf("clothcd %s: a %ld-vertex cloth with %zu springs falls on a sphere\n", clothcd::version(),
              static_cast<long>(positions.rows()), springs.rest.size());
  for (int step = 1; step <= 200; ++step) {
    clothcd::Vertices end = positions;
    integrate(springs, dt, substeps, end, velocities);
    long collisions = 0;
    for (int round = 0; round < 20; ++round) {
      const std::vector<clothcd::Collision>& found = detector.detect(positions, end);
      if (found.empty()) break;
      collisions += static_cast<long>(found.size());
      // Response: every cloth vertex of a colliding pair stops at 90% of the way to the impact and loses its velocity.
      for (const clothcd::Collision& c : found)
        for (const clothcd::VertexRef& v : c.vertices) {
          if (v.body != 0) continue;
          const double t = 0.9 * c.toi;
          end.row(v.vertex) = positions.row(v.vertex) + t * (end.row(v.vertex) - positions.row(v.vertex));
          velocities.row(v.vertex).setZero();
        }
    }
    positions = end;
    if (step % 40 == 0)
      std::printf("step %3d: lowest cloth point y = %+.4f, largest stretch %.1f%%, collisions handled %ld\n", step,
                  positions.col(1).minCoeff(), 100.0 * largest_stretch(springs, positions), collisions);
  }
  const double closest = positions.rowwise().norm().minCoeff();
  const double stretch = largest_stretch(springs, positions);
  std::printf("closest cloth vertex to the sphere's centre: %.4f (radius %.4f), largest stretch %.1f%%\n", closest,
              radius, 100.0 * stretch);
  // The sphere is a polygon: its faces lie up to 1% inside the radius.
  return closest >= radius - 1e-2 && stretch < 0.5 ? 0 : 1;
}

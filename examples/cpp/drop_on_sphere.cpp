// A cloth dropped on a sphere by the simplest integrator there is (symplectic Euler with gravity and a velocity
// damping, no springs), with clothcd::CollisionDetector keeping it out of the sphere: each step predicts the end
// positions, asks the detector for every collision of the step, stops the colliding cloth vertices just before their
// time of impact, and asks again until the step is free of collisions. Prints one line per 20 steps and checks at the
// end that no cloth vertex went into the sphere. Exit code 0 on success.
#include <clothcd/clothcd.hpp>

#include <cstdio>
#include <vector>

int main() {
  const double radius = 0.5, dt = 0.005, gravity = -9.81;
  const clothcd::TriangleMesh sphere = clothcd::make_uv_sphere(radius, 32, 16);
  clothcd::TriangleMesh cloth = clothcd::make_grid(24, 24, 1.6, 1.6);  // in the xz plane, centred on the origin
  cloth.vertices.col(1).array() += radius + 0.1;

  clothcd::DetectorSettings settings;
  settings.thickness = 1e-3;
  clothcd::CollisionDetector detector(cloth.faces, static_cast<int>(cloth.vertex_count()), settings);
  detector.add_obstacle(sphere);  // body 1

  clothcd::Vertices positions = cloth.vertices;
  clothcd::Vertices velocities = clothcd::Vertices::Zero(positions.rows(), 3);
  std::printf("clothcd %s: a %ld-vertex cloth falls on a sphere\n", clothcd::version(),
              static_cast<long>(positions.rows()));
  for (int step = 1; step <= 120; ++step) {
    velocities.col(1).array() += dt * gravity;
    velocities *= 0.995;
    clothcd::Vertices end = positions + dt * velocities;
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
    if (step % 20 == 0)
      std::printf("step %3d: lowest cloth point y = %+.4f, collisions handled %ld\n", step,
                  positions.col(1).minCoeff(), collisions);
  }
  const double closest = positions.rowwise().norm().minCoeff();
  std::printf("closest cloth vertex to the sphere's centre: %.4f (radius %.4f)\n", closest, radius);
  return closest >= radius - 1e-2 ? 0 : 1;  // the sphere is a polygon: its faces lie up to 1% inside the radius
}

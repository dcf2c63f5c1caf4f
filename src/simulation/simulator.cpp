// The simulation loop of Jin et al. section 4.5 made safe: implicit Euler (Baraff and Witkin 1998), continuous
// collision detection on the step's linear trajectories, then impulses and a fail-safe (Bridson et al. 2002) so that
// the step ends intersection-free whenever it started so.
#include "clothcd/simulation/simulator.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace clothcd::simulation {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

const SimulationSettings& checked(const SimulationSettings& s) {
  if (!(s.dt > 0) || !(s.dt <= kMaxTimeStep)) {
    throw std::invalid_argument("time step dt must be above 0 and at most " + std::to_string(kMaxTimeStep) +
                                " s (got " + std::to_string(s.dt) + ")");
  }
  if (!(s.response.thickness >= 0) || !std::isfinite(s.response.thickness)) {
    throw std::invalid_argument("thickness must be >= 0 and finite");
  }
  if (!(s.response.friction >= 0) || !std::isfinite(s.response.friction)) {
    throw std::invalid_argument("friction must be >= 0 and finite");
  }
  if (!(s.response.contact_reach >= 0) || !std::isfinite(s.response.contact_reach)) {
    throw std::invalid_argument("contact_reach must be >= 0 and finite");
  }
  if (!(s.response.separation >= 1.0 && s.response.separation <= 100.0)) {
    throw std::invalid_argument("separation must be from 1 to 100 (thicknesses)");
  }
  if (s.response.impulse_rounds < 0 || s.response.failsafe_rounds < 1) {
    throw std::invalid_argument("impulse_rounds must be >= 0 and failsafe_rounds >= 1");
  }
  return s;
}

// The thickness must leave room between primitives that are not neighbours: at rest, a vertex lies about 0.7 edges
// from the nearest triangle it does not belong to, so a thickness near the edge length makes the whole cloth one
// contact (a 362 x 362 cloth of 4.4 mm edges at the default 4 mm took 50 s and 3.4 GB for its first step). Refused
// unless it is below half the median edge length.
void check_thickness_fits(const TriangleMesh& cloth, double thickness) {
  std::vector<double> lengths;
  lengths.reserve(static_cast<std::size_t>(cloth.faces.size()));
  for (Eigen::Index f = 0; f < cloth.faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      lengths.push_back((cloth.vertices.row(cloth.faces(f, k)) - cloth.vertices.row(cloth.faces(f, (k + 1) % 3))).norm());
    }
  }
  if (lengths.empty()) return;
  const auto middle = lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2);
  std::nth_element(lengths.begin(), middle, lengths.end());
  if (!(thickness < 0.5 * *middle)) {
    std::ostringstream message;
    message << "the thickness (" << thickness << " m) must be below half the cloth's median edge length (" << *middle
            << " m), or primitives that are not neighbours touch at rest: lower the thickness or the cloth's resolution";
    throw std::invalid_argument(message.str());
  }
}

DetectorSettings detector_settings(const SimulationSettings& s) {
  DetectorSettings d = s.detector;
  d.thickness = s.response.thickness;
  d.self_collision = true;
  return d;
}

}  // namespace

Simulator::Simulator(const Scene& scene, const SimulationSettings& settings)
    : scene_(scene),
      settings_(checked(settings)),
      model_(build_cloth_model(scene.cloth, settings.cloth, scene.pinned)),
      state_(rest_state(model_)),
      integrator_(settings.integrator),
      detector_(scene.cloth.faces, static_cast<int>(scene.cloth.vertices.rows()), detector_settings(settings)) {
  check_thickness_fits(scene.cloth, settings.response.thickness);
  for (const Obstacle& obstacle : scene_.obstacles) {
    detector_.add_obstacle(obstacle.rest);
    obstacle_start_.push_back(obstacle.rest.vertices);
    obstacle_end_.push_back(obstacle.rest.vertices);
  }
}

std::vector<TriangleMesh> Simulator::obstacle_meshes() const {
  std::vector<TriangleMesh> meshes;
  for (const Obstacle& obstacle : scene_.obstacles) meshes.push_back({obstacle.positions_at(step_), obstacle.rest.faces});
  return meshes;
}

std::uint64_t Simulator::state_hash() const {
  std::uint64_t hash = 1469598103934665603ull;
  auto mix = [&hash](const Vertices& x) {
    const auto* bytes = reinterpret_cast<const unsigned char*>(x.data());
    for (size_t i = 0; i < static_cast<size_t>(x.size()) * sizeof(double); ++i) {
      hash = (hash ^ bytes[i]) * 1099511628211ull;
    }
  };
  mix(state_.positions);
  mix(state_.velocities);
  return hash;
}

StepStats Simulator::step() {
  const auto step_begin = Clock::now();
  StepStats stats;
  stats.step = step_;
  const double h = settings_.dt;

  auto t = Clock::now();
  stats.cg_iterations = integrator_.predict_velocities(model_, state_, h, velocities_).cg_iterations;
  start_ = state_.positions;
  end_ = start_ + h * velocities_;
  stats.integration_ms = ms_since(t);

  for (size_t k = 0; k < scene_.obstacles.size(); ++k) {
    const Obstacle& obstacle = scene_.obstacles[k];
    if (obstacle.motion.moving_steps == 0) continue;
    obstacle_start_[k] = obstacle.positions_at(step_);
    obstacle_end_[k] = obstacle.positions_at(step_ + 1);
    detector_.set_obstacle_positions(static_cast<int>(k) + 1, obstacle_start_[k], obstacle_end_[k]);
  }
  const StepContext context{&model_, &start_, &scene_.obstacles, &obstacle_start_, &obstacle_end_, step_};

  // Warm start: the remembered contacts still within reach push the predicted positions apart before detection.
  const double reach = settings_.response.contact_reach * settings_.response.thickness;
  const bool remember = reach > 0;
  if (remember) {
    t = Clock::now();
    contacts_.forget_distant(context, reach);
    apply_impulses(contacts_.contacts(), context, settings_.response, end_);
    stats.response_ms += ms_since(t);
  }

  auto detect = [&]() -> bool {
    const auto begin = Clock::now();
    collisions_ = detector_.detect(start_, end_);
    stats.detection_ms += ms_since(begin);
    const DetectionStats& d = detector_.stats();
    stats.candidates += d.candidates_vertex_face + d.candidates_edge_edge;
    stats.culled += d.culled;
    if (stats.detect_calls++ == 0) stats.collisions = static_cast<long>(collisions_.size());
    discard_disproved(collisions_, context, end_, settings_.response.thickness);
    sort_collisions(collisions_);
    if (remember) contacts_.remember(collisions_);
    return !collisions_.empty();
  };

  bool colliding = detect();
  for (int round = 0; colliding && round < settings_.response.impulse_rounds; ++round) {
    t = Clock::now();
    apply_impulses(collisions_, context, settings_.response, end_);
    stats.response_ms += ms_since(t);
    colliding = detect();
  }
  if (colliding) {
    FailSafe failsafe(model_.vertex_count());
    stats.settled = false;
    for (int round = 0; round < settings_.response.failsafe_rounds; ++round) {
      t = Clock::now();
      const int changed = failsafe.absorb(collisions_, context);
      failsafe.apply(context, end_);
      stats.response_ms += ms_since(t);
      // No change: every remaining pair already moves rigidly with one body, so it cannot cross.
      if (changed == 0 || !detect()) {
        stats.settled = true;
        break;
      }
    }
    stats.failsafe_vertices = failsafe.grouped_vertices();
  }

  state_.velocities = (end_ - start_) / h;
  state_.positions = end_;
  ++step_;
  stats.step_ms = ms_since(step_begin);
  return stats;
}

}  // namespace clothcd::simulation

// The detector's bodies (see detector_bodies.hpp).
#include "detector_bodies.hpp"

#include <stdexcept>
#include <string>

namespace clothcd::detail {

DetectorBodies::DetectorBodies(const Faces& cloth_faces, int cloth_vertex_count,
                               const broadphase::BvhSettings& cloth_hierarchy, broadphase::VolumeKind obstacle_volume)
    : bvh_settings_(cloth_hierarchy), obstacle_volume_(obstacle_volume) {
  cloth_.topology = broadphase::build_body_topology(cloth_faces, cloth_vertex_count);
  cloth_.bvh = broadphase::Bvh(bvh_settings_);
  cloth_.state_bvh = broadphase::Bvh(bvh_settings_);
}

int DetectorBodies::add_obstacle(const TriangleMesh& mesh) {
  if (!mesh.vertices.allFinite()) throw std::invalid_argument("add_obstacle: the mesh has a NaN or infinite coordinate");
  Body body;
  body.topology = broadphase::build_body_topology(mesh.faces, static_cast<int>(mesh.vertex_count()));
  body.rest = mesh.vertices;
  body.start = mesh.vertices;
  body.end = mesh.vertices;
  broadphase::BvhSettings settings = bvh_settings_;
  settings.volume = obstacle_volume_;
  body.bvh = broadphase::Bvh(settings);
  body.state_bvh = broadphase::Bvh(settings);
  obstacles_.push_back(std::move(body));
  return static_cast<int>(obstacles_.size());
}

std::size_t DetectorBodies::obstacle_index(int body, const char* caller) const {
  if (body < 1 || body > static_cast<int>(obstacles_.size())) {
    throw std::invalid_argument(std::string(caller) + ": no obstacle with body id " + std::to_string(body));
  }
  return static_cast<std::size_t>(body - 1);
}

Body& DetectorBodies::obstacle(int body, const char* caller) { return obstacles_[obstacle_index(body, caller)]; }

const Body& DetectorBodies::obstacle(int body, const char* caller) const {
  return obstacles_[obstacle_index(body, caller)];
}

bool DetectorBodies::any_obstacle_stale() const {
  for (const Body& o : obstacles_) {
    if (o.stale) return true;
  }
  return false;
}

int DetectorBodies::refit(const Vertices& start, const Vertices& end, double thickness,
                          const std::vector<std::uint8_t>* moved) {
  int rebuilds = 0;
  // Vertex boxes are all the hierarchies need; a re-test recomputes only the moved vertices' (the others' positions
  // are those of the last call).
  if (moved != nullptr) {
    broadphase::update_swept_vertex_boxes(start, end, thickness, *moved, cloth_.boxes);
  } else {
    broadphase::compute_swept_vertex_boxes(start, end, thickness, cloth_.boxes);
  }
  const broadphase::BvhUpdate update = moved != nullptr
                                           ? cloth_.bvh.update_moved(cloth_.topology, cloth_.boxes, start, end, *moved)
                                           : cloth_.bvh.update(cloth_.topology, cloth_.boxes, start, end);
  if (update == broadphase::BvhUpdate::Rebuilt) ++rebuilds;
  for (Body& o : obstacles_) {
    if (!o.stale) continue;
    broadphase::compute_swept_vertex_boxes(o.start, o.end, thickness, o.boxes);
    if (o.bvh.update(o.topology, o.boxes, o.start, o.end) == broadphase::BvhUpdate::Rebuilt) ++rebuilds;
    o.stale = false;
  }
  return rebuilds;
}

int DetectorBodies::refit_part(const Vertices& start, const Vertices& end, double from, double to, double thickness) {
  int rebuilds = 0;
  broadphase::compute_part_vertex_boxes(start, end, from, to, thickness, cloth_.boxes);
  if (cloth_.bvh.update(cloth_.topology, cloth_.boxes, start, end) == broadphase::BvhUpdate::Rebuilt) ++rebuilds;
  for (Body& o : obstacles_) {
    if (!o.stale) continue;
    if (o.moving) {
      broadphase::compute_part_vertex_boxes(o.start, o.end, from, to, thickness, o.boxes);
    } else {
      broadphase::compute_swept_vertex_boxes(o.start, o.end, thickness, o.boxes);
    }
    if (o.bvh.update(o.topology, o.boxes, o.start, o.end) == broadphase::BvhUpdate::Rebuilt) ++rebuilds;
    o.stale = o.moving;
  }
  return rebuilds;
}

int DetectorBodies::refit_state(const Vertices& positions, double distance) {
  int rebuilds = 0;
  const auto refit_body = [&](Body& body, const Vertices& x) {
    broadphase::compute_swept_vertex_boxes(x, x, distance, body.state_boxes);
    if (body.state_bvh.update(body.topology, body.state_boxes, x, x) == broadphase::BvhUpdate::Rebuilt) ++rebuilds;
  };
  refit_body(cloth_, positions);
  for (Body& o : obstacles_) refit_body(o, o.start);
  return rebuilds;
}

broadphase::BodyView DetectorBodies::cloth_state_view() const {
  return {0, &cloth_.topology, &cloth_.state_boxes, &cloth_.state_bvh};
}

broadphase::BodyView DetectorBodies::obstacle_state_view(int body) const {
  const Body& o = obstacle(body, "obstacle_state_view");
  return {body, &o.topology, &o.state_boxes, &o.state_bvh};
}

std::vector<BodyFrames> DetectorBodies::state_frames(const Vertices& positions) const {
  std::vector<BodyFrames> frames(obstacles_.size() + 1);
  frames[0] = {&cloth_.topology, &positions, &positions};
  for (std::size_t k = 0; k < obstacles_.size(); ++k) {
    frames[k + 1] = {&obstacles_[k].topology, &obstacles_[k].start, &obstacles_[k].start};
  }
  return frames;
}

std::vector<BodyFrames> DetectorBodies::frames(const Vertices& start, const Vertices& end) const {
  std::vector<BodyFrames> frames(obstacles_.size() + 1);
  frames[0] = {&cloth_.topology, &start, &end};
  for (std::size_t k = 0; k < obstacles_.size(); ++k) {
    frames[k + 1] = {&obstacles_[k].topology, &obstacles_[k].start, &obstacles_[k].end};
  }
  return frames;
}

broadphase::BodyView DetectorBodies::cloth_view() const { return {0, &cloth_.topology, &cloth_.boxes, &cloth_.bvh}; }

broadphase::BodyView DetectorBodies::obstacle_view(int body) const {
  const Body& o = obstacle(body, "obstacle_view");
  return {body, &o.topology, &o.boxes, &o.bvh};
}

void DetectorBodies::finish_step() {
  for (Body& o : obstacles_) {
    if (!o.moving) continue;
    o.start = o.end;
    o.moving = false;
    o.stale = true;
  }
}

}  // namespace clothcd::detail

// The detector of a simulation step (Jin et al., section 3): swept boxes and hierarchy refit (section 3.2), candidate
// search of cloth vs obstacles and cloth vs itself, culling by the algebraic non-penetration and spatial projection
// filters (sections 2.2, 2.3) or by a culler such as the pair network behind the filters (section 3.3), then the
// exact-safe continuous collision test of every surviving pair. The candidates are not stored: each search thread culls and tests them block
// by block as it finds them (pair_pipeline.hpp), and only the collisions are kept.
#include "clothcd/detection/collision_detector.hpp"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <string>

#include "clothcd/broadphase/body_topology.hpp"
#include "clothcd/broadphase/bvh.hpp"
#include "clothcd/broadphase/candidates.hpp"
#include "clothcd/broadphase/swept_boxes.hpp"
#include "clothcd/broadphase/traversal.hpp"
#include "clothcd/ccd/ccd.hpp"
#include "clothcd/detection/pair_culler.hpp"
#include "pair_pipeline.hpp"
#include "parallel_loop.hpp"
#include "radix_sort.hpp"

namespace clothcd {
namespace {

using Clock = detail::StageClock;
using detail::milliseconds_since;

struct Body {
  broadphase::BodyTopology topology;
  Vertices rest;   // obstacles: the mesh as added
  Vertices start;  // obstacles: positions of the coming step
  Vertices end;
  broadphase::SweptBoxes boxes;  // vertex boxes only (compute_swept_vertex_boxes): the hierarchy makes the rest
  broadphase::Bvh bvh;
  bool stale = true;    // boxes and hierarchy must be recomputed before the next search
  bool moving = false;  // positions were set for the coming step only
};

broadphase::BvhSettings bvh_settings(const DetectorSettings& settings, bool obstacle) {
  broadphase::BvhSettings s;
  s.max_leaf_faces = settings.max_leaf_faces;
  s.rebuild_ratio = settings.rebuild_ratio;
  s.parallel = settings.parallel;
  switch (settings.hierarchy) {
    case HierarchyKind::SphereRootAabb: s.volume = broadphase::VolumeKind::Sphere; break;
    case HierarchyKind::Aabb: s.volume = broadphase::VolumeKind::Aabb; break;
    case HierarchyKind::AabbObb: s.volume = obstacle ? broadphase::VolumeKind::Obb : broadphase::VolumeKind::Aabb; break;
  }
  return s;
}

ccd::CcdFilter ccd_filter(CullingMode mode) {
  switch (mode) {
    case CullingMode::None: return ccd::CcdFilter::None;
    case CullingMode::NonPenetration: return ccd::CcdFilter::NonPenetration;
    case CullingMode::Projection: return ccd::CcdFilter::Projection;
    case CullingMode::Filters: return ccd::CcdFilter::Combined;
    case CullingMode::Network: return ccd::CcdFilter::Combined;
  }
  throw std::invalid_argument("collision detector: unknown culling mode");
}

void check_positions(const PositionsRef& positions, Eigen::Index rows, const std::string& what) {
  if (positions.rows() != rows) {
    throw std::invalid_argument(what + " has " + std::to_string(positions.rows()) + " rows, expected " +
                                std::to_string(rows));
  }
  if (!positions.allFinite()) throw std::invalid_argument(what + " has a NaN or infinite coordinate");
}

// Sets moved[v] = 1 for the rows of `now` that differ bitwise from those of `before` (same shape), else 0; returns how
// many moved.
std::size_t find_moved_rows(const Vertices& before, const Vertices& now, std::vector<std::uint8_t>& moved) {
  const std::size_t rows = static_cast<std::size_t>(now.rows());
  moved.assign(rows, 0);
  std::size_t count = 0;
  for (std::size_t v = 0; v < rows; ++v) {
    moved[v] = std::memcmp(before.data() + 3 * v, now.data() + 3 * v, 3 * sizeof(double)) != 0 ? 1 : 0;
    count += moved[v];
  }
  return count;
}

// Sorts `hits` by key (linear time: a radix sort of the keys, then the collisions moved into that order).
void sort_by_key(std::vector<detail::KeyedCollision>& hits, std::vector<detail::KeyedIndex>& order,
                 std::vector<detail::KeyedIndex>& scratch, std::vector<detail::KeyedCollision>& sorted) {
  order.resize(hits.size());
  for (std::size_t i = 0; i < hits.size(); ++i) order[i] = {hits[i].key, i};
  detail::radix_sort_by_key(order, scratch);
  sorted.resize(hits.size());
  for (std::size_t i = 0; i < order.size(); ++i) sorted[i] = hits[order[i].index];
  hits.swap(sorted);
}

// True when the collision has a vertex of the cloth (body 0) flagged in `moved`.
bool has_moved_vertex(const Collision& c, const std::vector<std::uint8_t>& moved) {
  for (const VertexRef& r : c.vertices) {
    if (r.body == 0 && moved[static_cast<std::size_t>(r.vertex)]) return true;
  }
  return false;
}

}  // namespace

struct CollisionDetector::Impl {
  DetectorSettings settings;
  ccd::CcdFilter filter = ccd::CcdFilter::None;
  std::shared_ptr<const PairCuller> culler;  // CullingMode::Network only
  BlockObserver observer;                    // set_block_observer
  Body cloth;
  std::vector<Body> obstacles;
  std::unique_ptr<detail::PairPipeline> pipeline;  // culling and exact test of the candidates as they are found
  std::vector<detail::BodyFrames> frames;          // what the pipeline reads, per body id
  detail::PairKeys keys;
  // The collisions of the last call with their sort keys, each kind in canonical order (vertex-face ones first in
  // `collisions`), and the candidate counts of that call: what a re-test call keeps of it.
  std::vector<detail::KeyedCollision> vertex_face_hits, edge_edge_hits;
  detail::PipelineCounts counts;
  std::vector<detail::KeyedIndex> order, sort_scratch;
  std::vector<detail::KeyedCollision> sorted;
  std::vector<Collision> collisions;
  // The cloth positions of this call, copied from the caller's (any layout) into the row-major layout the
  // hierarchies and the pair blocks read: the one copy detect() makes. With DetectorSettings::reuse_unchanged they
  // become the previous positions when the call completes (a swap, not a copy).
  Vertices current_start, current_end;
  // Reuse within a step (DetectorSettings::reuse_unchanged): the cloth positions of the last completed call.
  bool has_previous = false;
  Vertices previous_start, previous_end;
  std::vector<std::uint8_t> moved;
  DetectionStats stats;

  Body& obstacle(int body, const char* caller) {
    if (body < 1 || body > static_cast<int>(obstacles.size())) {
      throw std::invalid_argument(std::string(caller) + ": no obstacle with body id " + std::to_string(body));
    }
    return obstacles[body - 1];
  }

  // True when this call repeats the last one's step with few cloth vertices moved (then `moved` flags them): same
  // start positions, obstacles unchanged since (none stale), reuse enabled and no culler. A moving obstacle is stale
  // again after every call, so its steps are always searched in full.
  bool can_reuse(const Vertices& start, const Vertices& end) {
    if (!has_previous || !settings.reuse_unchanged || culler) return false;
    for (const Body& o : obstacles) {
      if (o.stale) return false;
    }
    if (std::memcmp(start.data(), previous_start.data(), sizeof(double) * start.size()) != 0) return false;
    // Beyond a quarter of the vertices, the restricted search saves little over a full one.
    return find_moved_rows(previous_end, end, moved) * 4 <= static_cast<std::size_t>(end.rows());
  }

  // With `only_moved` (reuse: the obstacles are unchanged and only the `moved` cloth vertices changed since the last
  // call), the cloth hierarchy refits just what holds them.
  void refit(const Vertices& start, const Vertices& end, bool only_moved) {
    const double thickness = settings.thickness;
    // Vertex boxes are all the hierarchies need; a re-test recomputes only the moved vertices' (the others' positions
    // are those of the last call).
    if (only_moved) {
      broadphase::update_swept_vertex_boxes(start, end, thickness, moved, cloth.boxes);
    } else {
      broadphase::compute_swept_vertex_boxes(start, end, thickness, cloth.boxes);
    }
    const broadphase::BvhUpdate update = only_moved
                                             ? cloth.bvh.update_moved(cloth.topology, cloth.boxes, start, end, moved)
                                             : cloth.bvh.update(cloth.topology, cloth.boxes, start, end);
    if (update == broadphase::BvhUpdate::Rebuilt) ++stats.rebuilds;
    for (Body& o : obstacles) {
      if (!o.stale) continue;
      broadphase::compute_swept_vertex_boxes(o.start, o.end, thickness, o.boxes);
      if (o.bvh.update(o.topology, o.boxes, o.start, o.end) == broadphase::BvhUpdate::Rebuilt) ++stats.rebuilds;
      o.stale = false;
    }
  }

  // The search with the cloth at `start`/`end`, every candidate culled and, with `exact`, tested as it is found; with
  // `only_moved`, just the pairs with a moved cloth vertex. Adds the counts to `found` and the search's time summed
  // over its tasks to `task_ms`; the collisions stay in the pipeline (finish()).
  void search(const Vertices& start, const Vertices& end, bool only_moved, bool exact, detail::PipelineCounts& found,
              double& task_ms) {
    frames.assign(obstacles.size() + 1, {});
    frames[0] = {&cloth.topology, &start, &end};
    for (std::size_t k = 0; k < obstacles.size(); ++k) {
      frames[k + 1] = {&obstacles[k].topology, &obstacles[k].start, &obstacles[k].end};
    }
    keys.assign(frames);
    detail::PipelineSettings pipeline_settings;
    pipeline_settings.filter = filter;
    pipeline_settings.ccd = ccd::CcdSettings{settings.thickness, settings.decide_exactly};
    pipeline_settings.projection = ccd::ProjectionFilterOptions{settings.projection_normals};
    pipeline_settings.culler = culler.get();
    pipeline_settings.exact = exact;
    pipeline_settings.observer = exact && observer ? &observer : nullptr;
    pipeline->begin(frames, keys, pipeline_settings);

    broadphase::TraversalSettings traversal{settings.parallel, only_moved ? &moved : nullptr};
    traversal.chunk_pairs = static_cast<std::size_t>(settings.block_pairs);
    broadphase::TraversalStats traversal_stats;
    const broadphase::BodyView cloth_view{0, &cloth.topology, &cloth.boxes, &cloth.bvh};
    if (settings.self_collision) broadphase::find_self_candidates(cloth_view, traversal, *pipeline, &traversal_stats);
    for (std::size_t k = 0; k < obstacles.size(); ++k) {
      const Body& o = obstacles[k];
      const broadphase::BodyView view{static_cast<int>(k) + 1, &o.topology, &o.boxes, &o.bvh};
      broadphase::find_pair_candidates(cloth_view, view, traversal, *pipeline, &traversal_stats);
    }
    task_ms += traversal_stats.task_ms;
    std::vector<detail::KeyedCollision> none;
    pipeline->finish(exact ? vertex_face_hits : none, exact ? edge_edge_hits : none, found);
  }

  // This call's collisions in canonical order: vertex-face ones first, each kind sorted like
  // broadphase::sort_candidates would sort the candidates.
  void collect() {
    sort_by_key(vertex_face_hits, order, sort_scratch, sorted);
    sort_by_key(edge_edge_hits, order, sort_scratch, sorted);
    collisions.clear();
    collisions.reserve(vertex_face_hits.size() + edge_edge_hits.size());
    for (const detail::KeyedCollision& h : vertex_face_hits) collisions.push_back(h.collision);
    for (const detail::KeyedCollision& h : edge_edge_hits) collisions.push_back(h.collision);
  }

  // Drops the last call's collisions with a moved cloth vertex (a re-test searches and tests those pairs again).
  void drop_moved_hits() {
    for (std::vector<detail::KeyedCollision>* hits : {&vertex_face_hits, &edge_edge_hits}) {
      hits->erase(std::remove_if(hits->begin(), hits->end(),
                                 [&](const detail::KeyedCollision& h) { return has_moved_vertex(h.collision, moved); }),
                  hits->end());
    }
  }
};

CollisionDetector::CollisionDetector(const Faces& cloth_faces, int cloth_vertex_count, const DetectorSettings& settings)
    : impl_(std::make_unique<Impl>()) {
  if (!(settings.thickness >= 0.0) || !std::isfinite(settings.thickness)) {
    throw std::invalid_argument("collision detector: the thickness must be finite and >= 0");
  }
  if (settings.max_leaf_faces < 1) throw std::invalid_argument("collision detector: max_leaf_faces must be >= 1");
  if (settings.block_pairs < 1 || settings.block_pairs > kMaxBlockPairs) {
    throw std::invalid_argument("collision detector: block_pairs must be between 1 and " +
                                std::to_string(kMaxBlockPairs));
  }
  impl_->filter = ccd_filter(settings.culling);
  if (settings.culling == CullingMode::Network) {
    if (!settings.culler) {
      throw std::invalid_argument("collision detector: Network culling needs DetectorSettings::culler (e.g. "
                                  "learning::load_network_culler)");
    }
    impl_->culler = settings.culler;
  }
  impl_->settings = settings;
  impl_->pipeline = std::make_unique<detail::PairPipeline>(settings.block_pairs);
  impl_->cloth.topology = broadphase::build_body_topology(cloth_faces, cloth_vertex_count);
  impl_->cloth.bvh = broadphase::Bvh(bvh_settings(settings, false));
}

CollisionDetector::~CollisionDetector() = default;
CollisionDetector::CollisionDetector(CollisionDetector&&) noexcept = default;
CollisionDetector& CollisionDetector::operator=(CollisionDetector&&) noexcept = default;

int CollisionDetector::add_obstacle(const TriangleMesh& mesh) {
  if (!mesh.vertices.allFinite()) throw std::invalid_argument("add_obstacle: the mesh has a NaN or infinite coordinate");
  Body body;
  body.topology = broadphase::build_body_topology(mesh.faces, static_cast<int>(mesh.vertex_count()));
  body.rest = mesh.vertices;
  body.start = mesh.vertices;
  body.end = mesh.vertices;
  body.bvh = broadphase::Bvh(bvh_settings(impl_->settings, true));
  impl_->obstacles.push_back(std::move(body));
  return static_cast<int>(impl_->obstacles.size());
}

void CollisionDetector::set_obstacle_positions(int body, const PositionsRef& start, const PositionsRef& end) {
  Body& o = impl_->obstacle(body, "set_obstacle_positions");
  check_positions(start, o.rest.rows(), "set_obstacle_positions: start");
  check_positions(end, o.rest.rows(), "set_obstacle_positions: end");
  o.start = start;
  o.end = end;
  o.stale = true;
  o.moving = true;
}

void CollisionDetector::set_obstacle_transforms(int body, const Eigen::Isometry3d& start, const Eigen::Isometry3d& end) {
  Body& o = impl_->obstacle(body, "set_obstacle_transforms");
  if (!start.matrix().allFinite() || !end.matrix().allFinite()) {
    throw std::invalid_argument("set_obstacle_transforms: a transform has a NaN or infinite entry");
  }
  o.start = (o.rest * start.linear().transpose()).rowwise() + start.translation().transpose();
  o.end = (o.rest * end.linear().transpose()).rowwise() + end.translation().transpose();
  o.stale = true;
  o.moving = true;
}

int CollisionDetector::obstacle_count() const { return static_cast<int>(impl_->obstacles.size()); }

const std::vector<int>& CollisionDetector::edges(int body) const {
  if (body == 0) return impl_->cloth.topology.edges;
  return impl_->obstacle(body, "edges").topology.edges;
}

const std::vector<Collision>& CollisionDetector::detect(const PositionsRef& caller_start,
                                                       const PositionsRef& caller_end) {
  Impl& d = *impl_;
  check_positions(caller_start, d.cloth.topology.vertex_count, "detect: cloth start positions");
  check_positions(caller_end, d.cloth.topology.vertex_count, "detect: cloth end positions");
  d.current_start = caller_start;
  d.current_end = caller_end;
  const Vertices& start = d.current_start;
  const Vertices& end = d.current_end;
  d.stats = DetectionStats{};
  const bool reuse = d.can_reuse(start, end);
  d.has_previous = false;  // until this call completes

  // The broad phase, the culling and the exact test run together (each thread's pairs go through them block by
  // block), so their times are the wall time of the search split in proportion to the threads' time in each.
  double wall_ms = 0, task_ms = 0;
  detail::PipelineCounts replaced, found;
  if (reuse) {
    // The last call's pairs with a moved vertex, found again on the hierarchy and positions of that call: only their
    // count is needed, to keep the candidate and culled counts those of a full search.
    auto t = Clock::now();
    d.search(d.previous_start, d.previous_end, true, false, replaced, task_ms);
    wall_ms += milliseconds_since(t);
    d.drop_moved_hits();
  } else {
    d.vertex_face_hits.clear();
    d.edge_edge_hits.clear();
    d.counts = detail::PipelineCounts{};
  }

  auto t = Clock::now();
  d.refit(start, end, reuse);
  d.stats.refit_ms = milliseconds_since(t);

  t = Clock::now();
  d.search(start, end, reuse, true, found, task_ms);
  wall_ms += milliseconds_since(t);

  t = Clock::now();
  d.collect();
  const double collect_ms = milliseconds_since(t);

  const double threads_ms = replaced.culling_ms + replaced.exact_ms + found.culling_ms + found.exact_ms;
  const double scale = task_ms > 0 && task_ms >= threads_ms ? wall_ms / task_ms : 1.0;
  d.stats.culling_ms = scale * (replaced.culling_ms + found.culling_ms);
  d.stats.exact_ms = scale * found.exact_ms + collect_ms;
  d.stats.traversal_ms = std::max(0.0, wall_ms - scale * threads_ms);
  d.stats.network_ms = scale * found.culler.culler_ms;
  d.stats.network_filters_ms = scale * found.culler.filters_ms;
  d.stats.network_dropped = found.culler.dropped;
  d.stats.network_overruled = found.culler.overruled;
  d.stats.network_kept = found.culler.kept;

  // A re-test's counts: the last call's, with the replaced pairs' taken out and the new ones' put in.
  const long previous = d.counts.vertex_face + d.counts.edge_edge;
  d.counts.vertex_face += found.vertex_face - replaced.vertex_face;
  d.counts.edge_edge += found.edge_edge - replaced.edge_edge;
  d.counts.culled += found.culled - replaced.culled;
  d.stats.candidates_vertex_face = d.counts.vertex_face;
  d.stats.candidates_edge_edge = d.counts.edge_edge;
  d.stats.culled = d.counts.culled;
  d.stats.collisions = static_cast<long>(d.collisions.size());
  d.stats.reused = reuse ? previous - (replaced.vertex_face + replaced.edge_edge) : 0;

  if (d.settings.reuse_unchanged && !d.culler) {
    d.previous_start.swap(d.current_start);
    d.previous_end.swap(d.current_end);
    d.has_previous = true;
  }

  // A moved obstacle rests at its end positions from the next step on, unless it is moved again.
  for (Body& o : d.obstacles) {
    if (!o.moving) continue;
    o.start = o.end;
    o.moving = false;
    o.stale = true;
  }
  return d.collisions;
}

const DetectionStats& CollisionDetector::stats() const { return impl_->stats; }

void CollisionDetector::set_block_observer(BlockObserver observer) { impl_->observer = std::move(observer); }

}  // namespace clothcd

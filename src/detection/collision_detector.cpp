// The detector of a simulation step (Jin et al., section 3): swept boxes and hierarchy refit (section 3.2), candidate
// search of cloth vs obstacles and cloth vs itself, culling by the algebraic non-penetration and spatial projection
// filters (sections 2.2, 2.3) or by a culler such as the pair network behind the filters (section 3.3), then the
// exact-safe continuous collision test of every surviving pair. The candidates are not stored: each search thread culls and tests them block
// by block as it finds them (pair_pipeline.hpp), and only the collisions are kept, within the collision budget. They
// are copied out of the threads' chunks into the output as the chunks are freed, and sorted in place through one
// (key, position) pair each: 96 + 16 bytes per collision at the peak.
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

// Sorts `collisions` by their keys (keys[i] is collisions[i]'s key, at position keys[i].index) in place: the keys by a
// radix sort, then the collisions along the cycles of that permutation, each position marked done by its index. After
// it keys[i].index == i.
void sort_by_key(std::vector<Collision>& collisions, std::vector<detail::KeyedIndex>& keys) {
  detail::radix_sort_by_key(keys);
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (keys[i].index == i) continue;
    const Collision first = collisions[i];
    std::size_t to = i;
    for (;;) {
      const std::size_t from = keys[to].index;
      keys[to].index = to;
      if (from == i) {
        collisions[to] = first;
        break;
      }
      collisions[to] = collisions[from];
      to = from;
    }
  }
}

// Frees a vector's memory (clear() keeps its capacity).
template <class T>
void release(std::vector<T>& values) {
  std::vector<T>().swap(values);
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
  // The collisions of the last call in canonical order (vertex-face ones first, each kind sorted like
  // broadphase::sort_candidates would sort the candidates), their sort keys (collision_keys[i] is collisions[i]'s,
  // edge-edge keys after every vertex-face key; kept only with reuse) and the candidate counts of that call: what a
  // re-test call keeps of it. While a call runs, both collect its collisions in no order.
  std::vector<Collision> collisions;
  std::vector<detail::KeyedIndex> collision_keys;
  detail::PipelineCounts counts;
  std::function<bool()> cancel;              // set_cancel_check
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
  // over its tasks to `task_ms`; with `exact`, appends the collisions to `collisions` and their keys to
  // `collision_keys` (unsorted). Throws CollisionBudgetExceeded when they exceed the budget, DetectionCancelled when
  // the cancel check says so.
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
    pipeline_settings.max_collisions = settings.max_collisions;
    pipeline_settings.cancel = &cancel;
    pipeline->begin(frames, keys, pipeline_settings, exact ? static_cast<long>(collisions.size()) : 0);

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
    pipeline->add_counts(found);
    if (!exact) return;
    // The last block of the search may have passed the budget after every thread's last check.
    const std::size_t total = collisions.size() + pipeline->collision_count();
    if (total > static_cast<std::size_t>(settings.max_collisions)) {
      throw CollisionBudgetExceeded(static_cast<long>(total), settings.max_collisions);
    }
    collisions.reserve(total);
    collision_keys.reserve(total);
    const std::uint64_t edge_edge_offset = keys.vertex_face_key_count();
    pipeline->take_collisions([&](const std::vector<detail::KeyedCollision>& chunk) {
      for (const detail::KeyedCollision& h : chunk) {
        const std::uint64_t offset = h.collision.kind == PairKind::EdgeEdge ? edge_edge_offset : 0;
        collision_keys.push_back({h.key + offset, collisions.size()});
        collisions.push_back(h.collision);
      }
    });
  }

  // Puts this call's collisions in canonical order; keeps their keys only for a re-test.
  void collect() {
    sort_by_key(collisions, collision_keys);
    if (!settings.reuse_unchanged || culler) release(collision_keys);
  }

  // Drops the last call's collisions with a moved cloth vertex (a re-test searches and tests those pairs again); the
  // others keep their order.
  void drop_moved_hits() {
    std::size_t kept = 0;
    for (std::size_t i = 0; i < collisions.size(); ++i) {
      if (has_moved_vertex(collisions[i], moved)) continue;
      collisions[kept] = collisions[i];
      collision_keys[kept] = {collision_keys[i].key, kept};
      ++kept;
    }
    collisions.resize(kept);
    collision_keys.resize(kept);
  }

  // Forgets a call that threw: no collisions, no search state, nothing a re-test could reuse.
  void discard() {
    release(collisions);
    release(collision_keys);
    pipeline->discard();
    counts = detail::PipelineCounts{};
    has_previous = false;
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
  if (settings.max_collisions < 1 || settings.max_collisions > kLargestCollisionBudget) {
    throw std::invalid_argument("collision detector: max_collisions must be between 1 and " +
                                std::to_string(kLargestCollisionBudget));
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
  double wall_ms = 0, task_ms = 0, collect_ms = 0;
  detail::PipelineCounts replaced, found;
  try {
    if (reuse) {
      // The last call's pairs with a moved vertex, found again on the hierarchy and positions of that call: only
      // their count is needed, to keep the candidate and culled counts those of a full search.
      auto t = Clock::now();
      d.search(d.previous_start, d.previous_end, true, false, replaced, task_ms);
      wall_ms += milliseconds_since(t);
      d.drop_moved_hits();
    } else {
      release(d.collisions);
      release(d.collision_keys);
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
    collect_ms = milliseconds_since(t);
  } catch (...) {
    d.discard();
    throw;
  }

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

void CollisionDetector::set_cancel_check(std::function<bool()> cancel) { impl_->cancel = std::move(cancel); }

}  // namespace clothcd

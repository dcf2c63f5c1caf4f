// The detector of a simulation step (Jin et al., section 3): swept boxes and hierarchy refit (section 3.2), candidate
// search of cloth vs obstacles and cloth vs itself, culling by the algebraic non-penetration and spatial projection
// filters (sections 2.2, 2.3) or by the pair network behind the filters (section 3.3), then the exact-safe continuous
// collision test of every surviving pair.
#include "clothcd/detection/collision_detector.hpp"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <string>

#include "ccd/after_filter.hpp"
#include "ccd/projection_block.hpp"
#include "clothcd/broadphase/body_topology.hpp"
#include "clothcd/broadphase/bvh.hpp"
#include "clothcd/broadphase/candidates.hpp"
#include "clothcd/broadphase/swept_boxes.hpp"
#include "clothcd/broadphase/traversal.hpp"
#include "clothcd/ccd/ccd.hpp"
#include "clothcd/detection/network_culling.hpp"
#include "pair_batch.hpp"
#include "parallel_loop.hpp"
#include "radix_sort.hpp"

namespace clothcd {
namespace {

using Clock = detail::StageClock;
using detail::milliseconds_since;

// Indices per chunk of the parallel loops over pairs.
constexpr std::size_t kPairGrain = 256;

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

void check_positions(const Vertices& positions, Eigen::Index rows, const std::string& what) {
  if (positions.rows() != rows) {
    throw std::invalid_argument(what + " has " + std::to_string(positions.rows()) + " rows, expected " +
                                std::to_string(rows));
  }
  if (!positions.allFinite()) throw std::invalid_argument(what + " has a NaN or infinite coordinate");
}

}  // namespace

struct CollisionDetector::Impl {
  DetectorSettings settings;
  ccd::CcdFilter filter = ccd::CcdFilter::None;
  std::unique_ptr<NetworkCuller> network;  // CullingMode::Network only
  Body cloth;
  std::vector<Body> obstacles;
  detail::PairBatch batch;   // the pairs of the last call and their narrow-phase work
  broadphase::CandidateSet fresh;  // candidates found by this call's search
  std::vector<std::size_t> todo;   // positions in `batch` of the pairs this call must test
  std::vector<std::size_t> blocks;  // positions in a filter pass's list where its blocks start
  std::vector<std::size_t> survivors;  // positions in `batch` of the pairs the first filter pass left
  std::vector<detail::KeyedIndex> vertex_face_hits;  // the hits of one kind: canonical sort key and batch position
  std::vector<detail::KeyedIndex> edge_edge_hits;
  std::vector<detail::KeyedIndex> sort_scratch;
  std::array<std::vector<std::uint64_t>, 3> key_offsets;  // per body: first dense vertex, face and edge number
  std::vector<Collision> collisions;
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

  const Vertices& start_of(int body, const Vertices& cloth_start) const {
    return body == 0 ? cloth_start : obstacles[body - 1].start;
  }
  const Vertices& end_of(int body, const Vertices& cloth_end) const {
    return body == 0 ? cloth_end : obstacles[body - 1].end;
  }
  const broadphase::BodyTopology& topology_of(int body) const {
    return body == 0 ? cloth.topology : obstacles[body - 1].topology;
  }

  // True when this call repeats the last one's step with few cloth vertices moved (then `moved` flags them): same
  // start positions, obstacles unchanged since (none stale), reuse enabled and no network. A moving obstacle is stale
  // again after every call, so its steps are always searched in full.
  bool can_reuse(const Vertices& start, const Vertices& end) {
    if (!has_previous || !settings.reuse_unchanged || network) return false;
    for (const Body& o : obstacles) {
      if (o.stale) return false;
    }
    if (std::memcmp(start.data(), previous_start.data(), sizeof(double) * start.size()) != 0) return false;
    // Beyond a quarter of the vertices, the restricted search saves little over a full one.
    return detail::find_moved_rows(previous_end, end, moved) * 4 <= static_cast<std::size_t>(end.rows());
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

  // Candidate search into `fresh`; with `only_moved`, just the pairs with a moved cloth vertex.
  void search(bool only_moved) {
    fresh.clear();
    const broadphase::TraversalSettings traversal{settings.parallel, only_moved ? &moved : nullptr};
    const broadphase::BodyView cloth_view{0, &cloth.topology, &cloth.boxes, &cloth.bvh};
    if (settings.self_collision) broadphase::find_self_candidates(cloth_view, traversal, fresh);
    for (std::size_t k = 0; k < obstacles.size(); ++k) {
      const Body& o = obstacles[k];
      const broadphase::BodyView view{static_cast<int>(k) + 1, &o.topology, &o.boxes, &o.bvh};
      broadphase::find_pair_candidates(cloth_view, view, traversal, fresh);
    }
    // Candidates stay in search order; only the (far fewer) collisions are put in canonical order (see collect()).
  }

  // Makes `batch` this call's pairs and `todo` the positions still to test (vertex-face ones first): with
  // `only_moved`, the fresh pairs take the places of the last call's pairs with a moved vertex (the others keep their
  // work); otherwise the batch is just the fresh pairs.
  void assemble(bool only_moved) {
    if (only_moved) {
      todo = detail::replace_moved(batch, moved, fresh);
    } else {
      batch.assign(fresh, todo);
    }
  }

  // Sets and returns the batch's vertex references of the pair at position i.
  const std::array<VertexRef, 4>& fill_refs(std::size_t i) {
    const detail::BatchPair& pair = batch.pairs[i];
    const auto& [body_a, a, body_b, b] = pair.fields;
    std::array<VertexRef, 4>& r = batch.refs[i];
    if (pair.kind == PairKind::VertexFace) {
      const auto& faces = topology_of(body_b).faces;
      r = {VertexRef{body_a, a}, VertexRef{body_b, faces(b, 0)}, VertexRef{body_b, faces(b, 1)},
           VertexRef{body_b, faces(b, 2)}};
    } else {
      const auto& ea = topology_of(body_a).edges;
      const auto& eb = topology_of(body_b).edges;
      r = {VertexRef{body_a, ea[2 * a]}, VertexRef{body_a, ea[2 * a + 1]}, VertexRef{body_b, eb[2 * b]},
           VertexRef{body_b, eb[2 * b + 1]}};
    }
    return r;
  }

  // Fills `q` with the CCD query and the batch's vertex references with those of the pair at position i.
  void gather(const Vertices& start, const Vertices& end, std::size_t i, ccd::CcdQuery& q) {
    const std::array<VertexRef, 4>& r = fill_refs(i);
    q.kind = batch.pairs[i].kind;
    for (int k = 0; k < 4; ++k) {
      q.start[k] = start_of(r[k].body, start).row(r[k].vertex).transpose();
      q.end[k] = end_of(r[k].body, end).row(r[k].vertex).transpose();
    }
  }

  // One pass of the block projection filter over the batch positions `positions` (vertex-face ones first, then
  // edge-edge ones): blocks of up to QueryBlock::kLanes pairs of one kind. Sets keep to 0 for the culled pairs and to
  // 1 for the others; `last_pass` adds the non-penetration filter behind it (the Combined mode at zero thickness).
  void filter_pass(const std::vector<std::size_t>& positions, const Vertices& start, const Vertices& end,
                   const ccd::CcdSettings& ccd_settings, ccd::detail::BlockPass pass, bool last_pass) {
    constexpr std::size_t lanes = ccd::detail::QueryBlock::kLanes;
    const std::size_t first_edge_edge = static_cast<std::size_t>(
        std::partition_point(positions.begin(), positions.end(),
                             [&](std::size_t i) { return batch.pairs[i].kind == PairKind::VertexFace; }) -
        positions.begin());
    blocks.clear();
    for (std::size_t j = 0; j < first_edge_edge; j += lanes) blocks.push_back(j);
    for (std::size_t j = first_edge_edge; j < positions.size(); j += lanes) blocks.push_back(j);
    const ccd::ProjectionFilterOptions options{settings.projection_normals};
    const ccd::detail::BlockIsa isa = ccd::detail::fastest_block_isa();
    // The non-penetration filter says nothing with a thickness (ccd::nonpenetration_filter_culls is false then).
    const bool nonpenetration = last_pass && filter == ccd::CcdFilter::Combined && ccd_settings.thickness == 0.0;
    detail::for_each_index(blocks.size(), settings.parallel, kPairGrain, [&](std::size_t b) {
      const std::size_t first = blocks[b];
      const std::size_t segment_end = first < first_edge_edge ? first_edge_edge : positions.size();
      const std::size_t last = std::min(first + lanes, segment_end);
      ccd::detail::QueryBlock block;
      block.kind = batch.pairs[positions[first]].kind;
      block.count = static_cast<int>(last - first);
      for (int lane = 0; lane < block.count; ++lane) {
        const std::array<VertexRef, 4>& r = fill_refs(positions[first + lane]);
        for (int k = 0; k < 4; ++k) {
          const double* x0 = start_of(r[k].body, start).row(r[k].vertex).data();
          const double* x1 = end_of(r[k].body, end).row(r[k].vertex).data();
          for (int c = 0; c < 3; ++c) {
            block.x[0][k][c][lane] = x0[c];
            block.x[1][k][c][lane] = x1[c];
          }
        }
      }
      block.pad_unused();
      std::array<std::uint8_t, lanes> culled;
      ccd::detail::projection_filter_block(block, ccd_settings, options, culled.data(), isa, pass);
      for (int lane = 0; lane < block.count; ++lane) {
        const std::size_t i = positions[first + lane];
        batch.keep[i] = culled[lane] || (nonpenetration && ccd::nonpenetration_filter_culls(block.query(lane),
                                                                                            ccd_settings))
                            ? 0
                            : 1;
      }
    });
  }

  // The projection filter (and the non-penetration filter behind it in the Combined mode) on the `todo` pairs; sets
  // their keep flags. With the primitives' normals, which cull most pairs, those directions run first on all pairs
  // and the other directions on the survivors only.
  void cull_in_blocks(const Vertices& start, const Vertices& end, const ccd::CcdSettings& ccd_settings) {
    using ccd::detail::BlockPass;
    if (!settings.projection_normals) return filter_pass(todo, start, end, ccd_settings, BlockPass::All, true);
    filter_pass(todo, start, end, ccd_settings, BlockPass::Normals, false);
    survivors.clear();
    for (const std::size_t i : todo) {
      if (batch.keep[i]) survivors.push_back(i);
    }
    filter_pass(survivors, start, end, ccd_settings, BlockPass::AfterNormals, true);
  }

  // Queries, culling and CCD for the pairs at the `todo` positions of the batch (the network mode always tests all).
  void narrow_phase(const Vertices& start, const Vertices& end) {
    // Gathering the pairs' positions counts as culling time: it is the batch the filters read.
    auto t = Clock::now();
    const ccd::CcdSettings ccd_settings{settings.thickness, settings.decide_exactly};
    const std::size_t total = batch.size();
    std::vector<ccd::CcdQuery>& queries = batch.queries;
    std::vector<std::uint8_t>& keep = batch.keep;
    std::vector<ccd::CcdResult>& results = batch.results;
    if (network) {
      queries.resize(total);
      detail::for_each_index(total, settings.parallel, kPairGrain, [&](std::size_t i) { gather(start, end, i, queries[i]); });
      const NetworkCullingStats n = network->cull(queries, ccd_settings, settings.parallel, keep,
                                                  ccd::ProjectionFilterOptions{settings.projection_normals});
      stats.network_dropped = n.dropped;
      stats.network_overruled = n.overruled;
      stats.network_kept = n.kept;
      stats.network_ms = n.network_ms;
      stats.network_filters_ms = n.filters_ms;
    } else if (filter == ccd::CcdFilter::Projection || filter == ccd::CcdFilter::Combined) {
      cull_in_blocks(start, end, ccd_settings);
    } else {
      detail::for_each_index(todo.size(), settings.parallel, kPairGrain, [&](std::size_t j) {
        // None or NonPenetration: the query is built on the stack.
        const std::size_t i = todo[j];
        ccd::CcdQuery query;
        gather(start, end, i, query);
        const bool culled =
            filter == ccd::CcdFilter::NonPenetration && ccd::nonpenetration_filter_culls(query, ccd_settings);
        keep[i] = culled ? 0 : 1;
      });
    }
    stats.culling_ms = milliseconds_since(t);

    t = Clock::now();
    // Pairs the filters passed skip the filter tests inside the CCD; the network's Keep pairs met no filter.
    const ccd::CcdFilter applied = network ? ccd::CcdFilter::None : filter;
    // Outside the network mode the kept pairs' positions are gathered again rather than stored by the culling: on a
    // large cloth, storing a query per kept pair and reading it back was most of the stage's memory traffic.
    detail::for_each_index(todo.size(), settings.parallel, kPairGrain, [&](std::size_t j) {
      const std::size_t i = todo[j];
      if (!keep[i]) return;  // a culled pair gets no result: readers check keep first (less memory traffic)
      if (network) {
        results[i] = ccd::detail::continuous_collision_after_filter(queries[i], ccd_settings, applied);
      } else {
        ccd::CcdQuery query;
        gather(start, end, i, query);
        results[i] = ccd::detail::continuous_collision_after_filter(query, ccd_settings, applied);
      }
    });
    stats.reused = static_cast<long>(total - todo.size());
    collect();
    stats.exact_ms = milliseconds_since(t);
    long kept = 0;
    for (std::size_t i = 0; i < total; ++i) kept += keep[i];
    stats.culled = static_cast<long>(total) - kept;
    stats.collisions = static_cast<long>(collisions.size());
  }

  // The hits as collisions in canonical candidate order: vertex-face pairs first, each kind sorted like
  // broadphase::sort_candidates would sort the candidates.
  void collect() {
    const std::vector<ccd::CcdResult>& results = batch.results;
    // Canonical order by one integer key per hit: numbering every body's vertices (faces, edges) one after the other
    // in body order maps (body, index) to a dense number with the same order, and dense first * (count of the second
    // kind) + dense second orders like the candidate's four fields. Vertex-face hits come first.
    const int bodies = static_cast<int>(obstacles.size()) + 1;
    std::vector<std::uint64_t>& vertex_base = key_offsets[0];
    std::vector<std::uint64_t>& face_base = key_offsets[1];
    std::vector<std::uint64_t>& edge_base = key_offsets[2];
    vertex_base.assign(bodies + 1, 0);
    face_base.assign(bodies + 1, 0);
    edge_base.assign(bodies + 1, 0);
    for (int body = 0; body < bodies; ++body) {
      const broadphase::BodyTopology& t = topology_of(body);
      vertex_base[body + 1] = vertex_base[body] + static_cast<std::uint64_t>(t.vertex_count);
      face_base[body + 1] = face_base[body] + static_cast<std::uint64_t>(t.face_count());
      edge_base[body + 1] = edge_base[body] + static_cast<std::uint64_t>(t.edge_count());
    }
    vertex_face_hits.clear();
    edge_edge_hits.clear();
    const std::vector<std::uint8_t>& keep = batch.keep;
    for (std::size_t i = 0; i < results.size(); ++i) {
      if (!keep[i] || !results[i].hit) continue;
      const auto& [body_a, a, body_b, b] = batch.pairs[i].fields;
      if (batch.pairs[i].kind == PairKind::VertexFace) {
        const std::uint64_t first = vertex_base[body_a] + static_cast<std::uint64_t>(a);
        const std::uint64_t second = face_base[body_b] + static_cast<std::uint64_t>(b);
        vertex_face_hits.push_back({first * face_base[bodies] + second, i});
      } else {
        const std::uint64_t first = edge_base[body_a] + static_cast<std::uint64_t>(a);
        const std::uint64_t second = edge_base[body_b] + static_cast<std::uint64_t>(b);
        edge_edge_hits.push_back({first * edge_base[bodies] + second, i});
      }
    }
    detail::radix_sort_by_key(vertex_face_hits, sort_scratch);
    detail::radix_sort_by_key(edge_edge_hits, sort_scratch);
    collisions.clear();
    for (const detail::KeyedIndex& h : vertex_face_hits) add_collision(h.index);
    for (const detail::KeyedIndex& h : edge_edge_hits) add_collision(h.index);
  }

  // Appends the hit at position i of the batch to the collisions.
  void add_collision(std::size_t i) {
    const ccd::CcdResult& result = batch.results[i];
    Collision c;
    c.kind = batch.pairs[i].kind;
    c.vertices = batch.refs[i];
    c.toi = result.toi;
    c.parameters = result.parameters;
    c.normal = result.normal;
    c.conservative = result.state == ccd::CcdState::ConservativeHit;
    collisions.push_back(c);
  }

};

CollisionDetector::CollisionDetector(const Faces& cloth_faces, int cloth_vertex_count, const DetectorSettings& settings)
    : impl_(std::make_unique<Impl>()) {
  if (!(settings.thickness >= 0.0) || !std::isfinite(settings.thickness)) {
    throw std::invalid_argument("collision detector: the thickness must be finite and >= 0");
  }
  if (settings.max_leaf_faces < 1) throw std::invalid_argument("collision detector: max_leaf_faces must be >= 1");
  impl_->filter = ccd_filter(settings.culling);
  if (settings.culling == CullingMode::Network) impl_->network = std::make_unique<NetworkCuller>(settings.model_path);
  impl_->settings = settings;
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

void CollisionDetector::set_obstacle_positions(int body, const Vertices& start, const Vertices& end) {
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

const std::vector<Collision>& CollisionDetector::detect(const Vertices& start, const Vertices& end) {
  Impl& d = *impl_;
  check_positions(start, d.cloth.topology.vertex_count, "detect: cloth start positions");
  check_positions(end, d.cloth.topology.vertex_count, "detect: cloth end positions");
  d.stats = DetectionStats{};
  const bool reuse = d.can_reuse(start, end);
  d.has_previous = false;  // until this call completes

  auto t = Clock::now();
  d.refit(start, end, reuse);
  d.stats.refit_ms = milliseconds_since(t);

  t = Clock::now();
  d.search(reuse);
  d.assemble(reuse);
  d.stats.traversal_ms = milliseconds_since(t);
  for (const detail::BatchPair& pair : d.batch.pairs) {
    (pair.kind == PairKind::VertexFace ? d.stats.candidates_vertex_face : d.stats.candidates_edge_edge) += 1;
  }

  d.narrow_phase(start, end);
  if (d.settings.reuse_unchanged && !d.network) {
    d.previous_start = start;
    d.previous_end = end;
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

}  // namespace clothcd

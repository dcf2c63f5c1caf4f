// The detector's collisions (see collision_collector.hpp).
#include "collision_collector.hpp"

#include "clothcd/detection/detection_errors.hpp"

namespace clothcd::detail {

namespace {

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

void CollisionCollector::take(PairPipeline& pipeline, const PairKeys& keys, long max_collisions) {
  const std::size_t total = collisions_.size() + pipeline.collision_count();
  if (total > static_cast<std::size_t>(max_collisions)) {
    throw CollisionBudgetExceeded(static_cast<long>(total), max_collisions);
  }
  collisions_.reserve(total);
  keys_.reserve(total);
  const std::uint64_t edge_edge_offset = keys.vertex_face_key_count();
  pipeline.take_collisions([&](const std::vector<KeyedCollision>& chunk) {
    for (const KeyedCollision& h : chunk) {
      const std::uint64_t offset = h.collision.kind == PairKind::EdgeEdge ? edge_edge_offset : 0;
      keys_.push_back({h.key + offset, collisions_.size()});
      collisions_.push_back(h.collision);
    }
  });
}

void CollisionCollector::sort(bool keep_keys) {
  radix_sort_by_key(keys_);
  // After it keys_[i].index == i: each position is marked done by its index.
  for (std::size_t i = 0; i < keys_.size(); ++i) {
    if (keys_[i].index == i) continue;
    const Collision first = collisions_[i];
    std::size_t to = i;
    for (;;) {
      const std::size_t from = keys_[to].index;
      keys_[to].index = to;
      if (from == i) {
        collisions_[to] = first;
        break;
      }
      collisions_[to] = collisions_[from];
      to = from;
    }
  }
  if (!keep_keys) release(keys_);
}

void CollisionCollector::drop_moved(const std::vector<std::uint8_t>& moved) {
  std::size_t kept = 0;
  for (std::size_t i = 0; i < collisions_.size(); ++i) {
    if (has_moved_vertex(collisions_[i], moved)) continue;
    collisions_[kept] = collisions_[i];
    keys_[kept] = {keys_[i].key, kept};
    ++kept;
  }
  collisions_.resize(kept);
  keys_.resize(kept);
}

void CollisionCollector::clear() {
  release(collisions_);
  release(keys_);
}

}  // namespace clothcd::detail

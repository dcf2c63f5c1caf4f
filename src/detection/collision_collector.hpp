#pragma once
// The detector's collisions (internal): gathered from the pair pipeline's threads within the collision budget, put in
// canonical order by their sort keys, and kept with those keys for a re-test of the same step.
#include <cstdint>
#include <vector>

#include "clothcd/detection/collision.hpp"
#include "pair_pipeline.hpp"
#include "radix_sort.hpp"

namespace clothcd::detail {

/// The collisions of the last call and their sort keys.
class CollisionCollector {
 public:
  /// The collisions: in canonical order after sort() (vertex-face ones first, each kind sorted like
  /// broadphase::sort_candidates would sort the candidates), in no order while a call gathers them.
  [[nodiscard]] const std::vector<Collision>& collisions() const { return collisions_; }
  /// How many there are.
  [[nodiscard]] std::size_t size() const { return collisions_.size(); }

  /// Moves the collisions `pipeline` found into the list with their keys (`keys` numbers the pairs; edge-edge keys go
  /// after every vertex-face key), freeing the pipeline's chunks as it goes. Throws CollisionBudgetExceeded when the
  /// list would then hold more than `max_collisions` (the search's last blocks may pass the budget after every
  /// thread's last check).
  void take(PairPipeline& pipeline, const PairKeys& keys, long max_collisions);

  /// Puts the collisions in canonical order: a radix sort of the keys, then the collisions moved along the cycles of
  /// that permutation (in place: nothing beyond the collisions and their keys). Frees the keys unless `keep_keys`.
  void sort(bool keep_keys);

  /// Drops the collisions with a cloth (body 0) vertex flagged in `moved` (a re-test searches and tests their pairs
  /// again); the others keep their order and keys.
  void drop_moved(const std::vector<std::uint8_t>& moved);

  /// Frees the collisions and their keys.
  void clear();

 private:
  std::vector<Collision> collisions_;
  std::vector<KeyedIndex> keys_;  // keys_[i] is collisions_[i]'s, at position keys_[i].index
};

}  // namespace clothcd::detail

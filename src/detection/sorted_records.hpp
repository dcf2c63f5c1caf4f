#pragma once
// A call's records (internal): gathered from a stage's threads within the record budget, put in canonical order by
// their sort keys (unique within a call: the stages add the edge-edge offset, see Keyed), and kept with those keys
// for a re-test of the same step (drop_moved needs a record with `vertices`).
#include <cstdint>
#include <vector>

#include "clothcd/ccd/pair_kind.hpp"
#include "clothcd/detection/detection_errors.hpp"
#include "radix_sort.hpp"
#include "record_chunks.hpp"

namespace clothcd::detail {

/// The records of the last call and their sort keys.
template <class Record>
class SortedRecords {
 public:
  /// The records: in canonical order after sort() (vertex-face ones first, each kind sorted like
  /// broadphase::sort_candidates would sort the candidates), in no order while a call gathers them.
  [[nodiscard]] const std::vector<Record>& records() const { return records_; }
  /// How many there are.
  [[nodiscard]] std::size_t size() const { return records_.size(); }

  /// Moves the records `stage` found (its record_count() and take_records()) into the list with their keys, freeing
  /// the stage's chunks as it goes. Throws CollisionBudgetExceeded when the list would then hold more than
  /// `max_records` (the search's last blocks may pass the budget after every thread's last check).
  template <class Stage>
  void take(Stage& stage, long max_records) {
    const std::size_t total = records_.size() + stage.record_count();
    if (total > static_cast<std::size_t>(max_records)) {
      throw CollisionBudgetExceeded(static_cast<long>(total), max_records);
    }
    records_.reserve(total);
    keys_.reserve(total);
    stage.take_records([&](const std::vector<Keyed<Record>>& chunk) {
      for (const Keyed<Record>& h : chunk) {
        keys_.push_back({h.key, records_.size()});
        records_.push_back(h.record);
      }
    });
  }

  /// Puts the records in canonical order: a radix sort of the keys, then the records moved along the cycles of that
  /// permutation (in place: nothing beyond the records and their keys). Frees the keys unless `keep_keys`.
  void sort(bool keep_keys) {
    radix_sort_by_key(keys_);
    // After it keys_[i].index == i: each position is marked done by its index.
    for (std::size_t i = 0; i < keys_.size(); ++i) {
      if (keys_[i].index == i) continue;
      const Record first = records_[i];
      std::size_t to = i;
      for (;;) {
        const std::size_t from = keys_[to].index;
        keys_[to].index = to;
        if (from == i) {
          records_[to] = first;
          break;
        }
        records_[to] = records_[from];
        to = from;
      }
    }
    if (!keep_keys) std::vector<KeyedIndex>().swap(keys_);
  }

  /// Drops the records with a cloth (body 0) vertex flagged in `moved` (a re-test searches and tests their pairs
  /// again); the others keep their order and keys.
  void drop_moved(const std::vector<std::uint8_t>& moved) {
    std::size_t kept = 0;
    for (std::size_t i = 0; i < records_.size(); ++i) {
      if (has_moved_vertex(records_[i], moved)) continue;
      records_[kept] = records_[i];
      keys_[kept] = {keys_[i].key, kept};
      ++kept;
    }
    records_.resize(kept);
    keys_.resize(kept);
  }

  /// Frees the records and their keys.
  void clear() {
    std::vector<Record>().swap(records_);
    std::vector<KeyedIndex>().swap(keys_);
  }

 private:
  // True when the record has a vertex of the cloth (body 0) flagged in `moved`.
  static bool has_moved_vertex(const Record& r, const std::vector<std::uint8_t>& moved) {
    for (const VertexRef& v : r.vertices) {
      if (v.body == 0 && moved[static_cast<std::size_t>(v.vertex)]) return true;
    }
    return false;
  }

  std::vector<Record> records_;
  std::vector<KeyedIndex> keys_;  // keys_[i] is records_[i]'s, at position keys_[i].index
};

}  // namespace clothcd::detail

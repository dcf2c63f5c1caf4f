#pragma once
// What a stage of the pair stream keeps (internal): records with their canonical sort keys, held per thread in chunks
// of fixed size, so that the memory is the records' own (no vector doubling) and handing them over needs no memory
// beyond one chunk.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace clothcd::detail {

/// A record and its canonical sort key (PairKeys; edge-edge keys offset by PairKeys::vertex_face_key_count(), so that
/// one key orders every record of a call).
template <class Record>
struct Keyed {
  std::uint64_t key = 0;  ///< Sort key.
  Record record;          ///< The record.
};

/// One thread's records in chunks of kChunkRecords.
template <class Record>
class RecordChunks {
 public:
  /// Records each chunk holds.
  static constexpr std::size_t kChunkRecords = std::size_t{1} << 14;

  /// Appends a record to the last chunk, or to a new one when that is full, and returns it.
  Keyed<Record>& add() {
    if (chunks_.empty() || chunks_.back().size() == kChunkRecords) chunks_.emplace_back().reserve(kChunkRecords);
    return chunks_.back().emplace_back();
  }

  /// How many records are held.
  [[nodiscard]] std::size_t size() const {
    std::size_t count = 0;
    for (const std::vector<Keyed<Record>>& chunk : chunks_) count += chunk.size();
    return count;
  }

  /// Hands the records to `take(const std::vector<Keyed<Record>>&)` chunk by chunk, freeing each chunk after it.
  template <class Take>
  void take(const Take& take) {
    for (std::vector<Keyed<Record>>& chunk : chunks_) {
      take(chunk);
      std::vector<Keyed<Record>>().swap(chunk);
    }
    chunks_.clear();
  }

  /// Frees every record.
  void clear() { std::vector<std::vector<Keyed<Record>>>().swap(chunks_); }

 private:
  std::vector<std::vector<Keyed<Record>>> chunks_;
};

}  // namespace clothcd::detail

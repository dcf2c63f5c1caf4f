#pragma once
/// @file
/// A look at the detector's work (CollisionDetector::set_block_observer): every block of candidate pairs, with what the
/// detector found out about each pair, as the detector processes it. Data set generation records its pairs this way.

#include <cstdint>
#include <functional>

#include "clothcd/ccd/pair_block.hpp"

namespace clothcd {

/// One block of candidate pairs of one kind after the detector culled and tested it. The pointers are valid only
/// during the observer's call.
struct ObservedBlock {
  /// The pairs as the broad phase found them, before culling: kind, vertices, positions at the start and end of the
  /// step (PairBlock::query). Their tags are their indices 0 .. size() - 1.
  const ccd::PairBlock* pairs = nullptr;
  /// Per pair: its canonical order key within its kind, unique within one detect() call; sorting the pairs of a call
  /// by (kind, key), vertex-face first, gives the order in which detect() returns collisions.
  const std::uint64_t* keys = nullptr;
  const std::uint8_t* culled = nullptr;     ///< Per pair: 1 when the culling stage removed it, else 0.
  const std::uint8_t* colliding = nullptr;  ///< Per pair: 1 when the exact test reported a collision (0 when culled).
};

/// Called once per block of candidate pairs. Threads: blocks come from the search's TBB threads, several at a time,
/// unless DetectorSettings::parallel is false; the observer must make its own state safe for that (e.g. a mutex).
using BlockObserver = std::function<void(const ObservedBlock&)>;

}  // namespace clothcd

#pragma once
/// @file
/// The culling interface of CullingMode::Network: a stage in front of the exact test that sorts each block of
/// candidate pairs into those that go straight to the exact test, those the filters should look at, and those it
/// believes cannot collide. The learned pair network (learning::NetworkCuller, learning/network_culler.hpp) implements
/// it; the detector receives it from above (DetectorSettings::culler), so detection never depends on learning.
///
/// Safety contract: a culler may only drop pairs that cannot collide, and the detector does not take its word for it.
/// A Drop is removed only when the combined filters (as Filters mode runs them) confirm it; an unconfirmed Drop goes to
/// the exact test and is counted as overruled. So whatever a culler says, the pairs culled are a subset of what the
/// combined filters cull, and no collision is lost.

#include <cstdint>
#include <memory>
#include <vector>

#include "clothcd/ccd/ccd.hpp"
#include "clothcd/ccd/pair_block.hpp"

namespace clothcd {

/// A culler's verdict on one candidate pair.
enum class CullVerdict : std::uint8_t {
  Keep,   ///< Straight to the exact test (the filters are skipped).
  Check,  ///< Unsure: through the combined filters, the exact test decides what they leave.
  Drop,   ///< Cannot collide, says the culler: removed when the combined filters confirm it, else exact-tested.
};

/// A culling stage in front of the exact test (see the file comment for its safety contract).
/// Threads: cull() is const and is called by several TBB threads at once (one block each, each thread with its own
/// scratch from make_scratch()) unless DetectorSettings::parallel is false.
class PairCuller {
 public:
  /// A thread's working space for cull(), of the culler's own type.
  class Scratch {
   public:
    virtual ~Scratch() = default;
  };

  virtual ~PairCuller() = default;

  /// A fresh scratch space (one per thread; reused block after block).
  [[nodiscard]] virtual std::unique_ptr<Scratch> make_scratch() const = 0;

  /// Writes the verdict on each of the block's pairs 0 .. block.size() - 1 to verdicts[0 .. block.size() - 1].
  virtual void cull(const ccd::PairBlock& block, Scratch& scratch, CullVerdict* verdicts) const = 0;
};

}  // namespace clothcd

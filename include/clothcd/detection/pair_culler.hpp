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

/// Counts and times of culling blocks with a PairCuller (cull_with_culler).
struct CullerCounts {
  long dropped = 0;        ///< Drops the combined filters confirmed (removed).
  long overruled = 0;      ///< Drops the combined filters did not confirm (sent to the exact test).
  long checked = 0;        ///< Check verdicts (sent through the combined filters).
  long filter_culled = 0;  ///< Check pairs the combined filters removed.
  long kept = 0;           ///< Keep verdicts (straight to the exact test).
  double culler_ms = 0;    ///< Time in PairCuller::cull.
  double filters_ms = 0;   ///< Time in the combined filters behind it.

  /// Adds the counts and times of `o`.
  void add(const CullerCounts& o);
};

/// A thread's scratch for cull_with_culler (grown as needed, then reused).
struct CullerScratch {
  std::unique_ptr<PairCuller::Scratch> culler;  ///< The culler's own, made on first use.
  std::vector<CullVerdict> verdicts;            ///< The culler's verdicts on the block.
  std::vector<std::uint8_t> culled;             ///< The block filters' scratch.
};

/// Where the survivors of cull_with_culler stand in the block.
struct CullerSurvivors {
  int filtered = 0;  ///< Pairs [0, filtered): passed the combined filters (unconfirmed drops and Check pairs).
  int kept = 0;      ///< Pairs [filtered, filtered + kept): Keep verdicts, not filtered.
};

/// Network mode's culling of a whole block: `culler` gives its verdicts, the combined block filters
/// (ccd::cull_pair_block with `settings` and `projection`) confirm or overrule the drops and check the Check pairs, and
/// the survivors are moved to the front of the block (filtered ones first, then the Keep ones; the order within the
/// block changes). Adds to `counts`.
CullerSurvivors cull_with_culler(const PairCuller& culler, ccd::PairBlock& block, const ccd::CcdSettings& settings,
                                 const ccd::ProjectionFilterOptions& projection, CullerScratch& scratch,
                                 CullerCounts& counts);

}  // namespace clothcd

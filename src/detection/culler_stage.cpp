// Network mode's culling of a block (see detection/culler_stage.hpp): the culler's verdicts decide which pairs
// skip the combined filters; the filters confirm every drop.
#include "detection/culler_stage.hpp"

#include <utility>

#include "ccd/pair_block.hpp"
#include "parallel_loop.hpp"

namespace clothcd {

void CullerCounts::add(const CullerCounts& o) {
  dropped += o.dropped;
  overruled += o.overruled;
  checked += o.checked;
  filter_culled += o.filter_culled;
  kept += o.kept;
  culler_ms += o.culler_ms;
  filters_ms += o.filters_ms;
}

CullerSurvivors cull_with_culler(const PairCuller& culler, ccd::PairBlock& block, const ccd::CcdSettings& settings,
                                 const ccd::ProjectionFilterOptions& projection, CullerScratch& scratch,
                                 CullerCounts& counts) {
  const int n = block.size();
  auto t = detail::StageClock::now();
  if (!scratch.culler) scratch.culler = culler.make_scratch();
  std::vector<CullVerdict>& verdicts = scratch.verdicts;
  verdicts.resize(static_cast<std::size_t>(n));
  culler.cull(block, *scratch.culler, verdicts.data());
  counts.culler_ms += detail::milliseconds_since(t);

  t = detail::StageClock::now();
  // Order the pairs Drop, Check, Keep.
  const auto move_front = [&](CullVerdict wanted, int first) {
    int next = first;
    for (int i = first; i < n; ++i) {
      if (verdicts[static_cast<std::size_t>(i)] != wanted) continue;
      block.swap_pairs(i, next);
      std::swap(verdicts[static_cast<std::size_t>(i)], verdicts[static_cast<std::size_t>(next)]);
      ++next;
    }
    return next - first;
  };
  const int drops = move_front(CullVerdict::Drop, 0);
  const int checks = move_front(CullVerdict::Check, drops);
  // The combined filters confirm or overrule the drops, then check the Check pairs; Keep pairs skip them.
  const ccd::CcdFilter combined = ccd::CcdFilter::Combined;
  const int drops_left = ccd::cull_pair_block(block, drops, combined, settings, projection, scratch.culled);
  // The Check pairs now follow the drops left: bring them to the front.
  for (int j = 0; j < checks; ++j) block.swap_pairs(j, drops_left + j);
  const int checks_left = ccd::cull_pair_block(block, checks, combined, settings, projection, scratch.culled);
  counts.filters_ms += detail::milliseconds_since(t);
  counts.dropped += drops - drops_left;
  counts.overruled += drops_left;
  counts.checked += checks;
  counts.filter_culled += checks - checks_left;
  counts.kept += n - drops - checks;
  return CullerSurvivors{drops_left + checks_left, n - drops - checks};
}

}  // namespace clothcd

// The culling of a block of pairs (see block_culling.hpp).
#include "block_culling.hpp"

#include "ccd/pair_block.hpp"
#include "parallel_loop.hpp"

namespace clothcd::detail {

void StageCounts::add(const StageCounts& o) {
  vertex_face += o.vertex_face;
  edge_edge += o.edge_edge;
  face_face += o.face_face;
  culled += o.culled;
  culler.add(o.culler);
  culling_ms += o.culling_ms;
  exact_ms += o.exact_ms;
}

BlockSurvivors cull_block(ccd::PairBlock& block, const PairTestSettings& settings, CullScratch& scratch,
                          StageCounts& counts) {
  const auto t = StageClock::now();
  const int n = block.size();
  BlockSurvivors left;
  if (settings.culler != nullptr) {
    const CullerSurvivors c =
        cull_with_culler(*settings.culler, block, settings.ccd, settings.projection, scratch.culler, counts.culler);
    left.filtered = c.filtered;
    left.survivors = c.filtered + c.kept;
    left.applied = ccd::CcdFilter::Combined;
  } else {
    left.filtered = left.survivors =
        ccd::cull_pair_block(block, n, settings.filter, settings.ccd, settings.projection, scratch.culled);
    left.applied = settings.filter;
  }
  counts.culled += n - left.survivors;
  counts.culling_ms += milliseconds_since(t);
  return left;
}

}  // namespace clothcd::detail

// Pair blocks and their culling (see clothcd/ccd/pair_block.hpp).
#include "ccd/pair_block.hpp"

#include <new>
#include <stdexcept>
#include <string>
#include <utility>

namespace clothcd::ccd {

void PairLanes::set(int lane, const CcdQuery& query) {
  for (int k = 0; k < 4; ++k) {
    for (int c = 0; c < 3; ++c) {
      x[0][k][c][lane] = query.start[k][c];
      x[1][k][c][lane] = query.end[k][c];
    }
  }
}

CcdQuery PairLanes::query(int lane) const {
  CcdQuery q;
  q.kind = kind;
  for (int k = 0; k < 4; ++k) {
    q.start[k] = Eigen::Vector3d(x[0][k][0][lane], x[0][k][1][lane], x[0][k][2][lane]);
    q.end[k] = Eigen::Vector3d(x[1][k][0][lane], x[1][k][1][lane], x[1][k][2][lane]);
  }
  return q;
}

void PairLanes::pad_unused() {
  for (int t = 0; t < 2; ++t)
    for (int k = 0; k < 4; ++k)
      for (int c = 0; c < 3; ++c)
        for (int lane = count; lane < kLanes; ++lane) x[t][k][c][lane] = x[t][k][c][0];
}

PairBlock::PairBlock(int capacity) {
  constexpr int kLargest = 1 << 20;
  if (capacity < 1 || capacity > kLargest) {
    throw std::invalid_argument("pair block: the capacity must be between 1 and " + std::to_string(kLargest) +
                                " pairs, not " + std::to_string(capacity));
  }
  const int groups = (capacity + PairLanes::kLanes - 1) / PairLanes::kLanes;
  const std::size_t pairs = static_cast<std::size_t>(groups) * PairLanes::kLanes;
  try {
    vertices_.resize(pairs);
    tags_.resize(pairs);
    groups_.resize(static_cast<std::size_t>(groups));
  } catch (const std::bad_alloc&) {
    const std::size_t bytes = pairs * (sizeof(std::array<VertexRef, 4>) + sizeof(std::uint64_t)) +
                              static_cast<std::size_t>(groups) * sizeof(PairLanes);
    throw std::runtime_error("pair block: cannot allocate " + std::to_string(bytes) + " bytes for " +
                             std::to_string(pairs) + " pairs");
  }
  for (PairLanes& g : groups_) {
    g.count = PairLanes::kLanes;
    for (int t = 0; t < 2; ++t)
      for (int k = 0; k < 4; ++k)
        for (int c = 0; c < 3; ++c)
          for (int lane = 0; lane < PairLanes::kLanes; ++lane) g.x[t][k][c][lane] = 0.0;
  }
}

void PairBlock::reset(PairKind kind) {
  kind_ = kind;
  size_ = 0;
  for (PairLanes& g : groups_) g.kind = kind;
}

void PairBlock::copy_pair(int from, int to) {
  vertices_[static_cast<std::size_t>(to)] = vertices_[static_cast<std::size_t>(from)];
  tags_[static_cast<std::size_t>(to)] = tags_[static_cast<std::size_t>(from)];
  const PairLanes& source = groups_[static_cast<std::size_t>(from / PairLanes::kLanes)];
  PairLanes& target = groups_[static_cast<std::size_t>(to / PairLanes::kLanes)];
  const int a = from % PairLanes::kLanes, b = to % PairLanes::kLanes;
  for (int t = 0; t < 2; ++t)
    for (int k = 0; k < 4; ++k)
      for (int c = 0; c < 3; ++c) target.x[t][k][c][b] = source.x[t][k][c][a];
}

void PairBlock::swap_pairs(int i, int j) {
  std::swap(vertices_[static_cast<std::size_t>(i)], vertices_[static_cast<std::size_t>(j)]);
  std::swap(tags_[static_cast<std::size_t>(i)], tags_[static_cast<std::size_t>(j)]);
  PairLanes& gi = groups_[static_cast<std::size_t>(i / PairLanes::kLanes)];
  PairLanes& gj = groups_[static_cast<std::size_t>(j / PairLanes::kLanes)];
  const int a = i % PairLanes::kLanes, b = j % PairLanes::kLanes;
  for (int t = 0; t < 2; ++t)
    for (int k = 0; k < 4; ++k)
      for (int c = 0; c < 3; ++c) std::swap(gi.x[t][k][c][a], gj.x[t][k][c][b]);
}

int PairBlock::compact(int count, const std::uint8_t* keep) {
  int kept = 0;
  for (int i = 0; i < count; ++i) {
    if (!keep[i]) continue;
    if (kept != i) copy_pair(i, kept);
    ++kept;
  }
  for (int i = count; i < size_; ++i) copy_pair(i, kept + (i - count));
  size_ = kept + (size_ - count);
  return kept;
}

int cull_pair_block(PairBlock& block, int count, CcdFilter filter, const CcdSettings& settings,
                    const ProjectionFilterOptions& options, std::vector<std::uint8_t>& culled) {
  return detail::cull_pairs(block, count, filter, settings, options, simd_level(), culled);
}

namespace detail {
namespace {

// culled[i] for pairs [0, count) of `block`: one projection filter pass over its lane groups, then, with
// `nonpenetration`, the non-penetration filter on the pairs the pass left.
void filter_pass(const PairBlock& block, int count, const CcdSettings& settings,
                 const ProjectionFilterOptions& options, SimdLevel level, BlockPass pass, bool nonpenetration,
                 std::uint8_t* culled) {
  constexpr int lanes = PairLanes::kLanes;
  std::uint8_t group_culled[lanes];
  for (int g = 0; g * lanes < count; ++g) {
    projection_filter_block(block.group(g), settings, options, group_culled, level, pass);
    const int n = count - g * lanes < lanes ? count - g * lanes : lanes;
    for (int lane = 0; lane < n; ++lane) culled[g * lanes + lane] = group_culled[lane];
  }
  if (!nonpenetration) return;
  for (int i = 0; i < count; ++i) {
    if (!culled[i] && nonpenetration_filter_culls(block.query(i), settings)) culled[i] = 1;
  }
}

// Keeps the pairs [0, count) whose culled flag is 0 (flags turned into keep flags in place); returns how many.
int keep_unculled(PairBlock& block, int count, std::vector<std::uint8_t>& culled) {
  for (int i = 0; i < count; ++i) culled[static_cast<std::size_t>(i)] ^= 1;
  return block.compact(count, culled.data());
}

}  // namespace

int cull_pairs(PairBlock& block, int count, CcdFilter filter, const CcdSettings& settings,
               const ProjectionFilterOptions& options, SimdLevel level, std::vector<std::uint8_t>& culled) {
  if (culled.size() < static_cast<std::size_t>(count)) culled.resize(static_cast<std::size_t>(count));
  if (filter == CcdFilter::None) return count;
  if (filter == CcdFilter::NonPenetration) {
    for (int i = 0; i < count; ++i) culled[static_cast<std::size_t>(i)] = nonpenetration_filter_culls(block.query(i), settings);
    return keep_unculled(block, count, culled);
  }
  // The non-penetration filter says nothing with a thickness (nonpenetration_filter_culls is false then).
  const bool nonpenetration = filter == CcdFilter::Combined && settings.thickness == 0.0;
  if (!options.use_primitive_normals) {
    filter_pass(block, count, settings, options, level, BlockPass::All, nonpenetration, culled.data());
    return keep_unculled(block, count, culled);
  }
  // The primitives' normals cull most pairs: they run first on every pair, the other directions on the survivors.
  filter_pass(block, count, settings, options, level, BlockPass::Normals, false, culled.data());
  const int survivors = keep_unculled(block, count, culled);
  filter_pass(block, survivors, settings, options, level, BlockPass::AfterNormals, nonpenetration, culled.data());
  return keep_unculled(block, survivors, culled);
}

}  // namespace detail
}  // namespace clothcd::ccd

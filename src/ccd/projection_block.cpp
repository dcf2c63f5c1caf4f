// The projection filter on a block of pairs (see projection_block.hpp): every direction of the pass is tried on every
// lane (no early exit), stage by stage over the lanes, so each loop is straight-line arithmetic the compiler
// vectorizes.
//
// Rounding: a projection z = s . p (three products, two sums) is within gamma_3 |s|_1 M of its exact value, M the
// pair's largest coordinate magnitude (gamma_3 = 3u / (1 - 3u), u = 2^-53); a difference of two projections is thus
// within 2 gamma_3 |s|_1 M before its own rounding, a relative u. Comparing the rounded difference with
// T = thickness |s| (1 + 1e-12) + 16 u |s|_1 M + 1e-300 (|s| from a rounded square root, within a few u, which the
// factor 1 + 1e-12 covers; 1e-300 covers underflow) therefore proves the exact difference beyond thickness |s|.
// With M <= 1e100, the normals (below 8e200) and the projections stay far from overflow.
#include "ccd/projection_block.hpp"

#include <algorithm>
#include <cmath>

#include "clothcd/cpu_features.hpp"

namespace clothcd::ccd::detail {

namespace {

constexpr int kLanes = QueryBlock::kLanes;
constexpr double kBoundFactor = 16 * 0x1p-53;
constexpr double kTiny = 1e-300;
constexpr double kLargest = 1e100;
constexpr double kNormSlack = 1.0 + 1e-12;

using Lanes = double[kLanes];

// One direction on every lane: culled[i] becomes 1 when lane i's primitives are separated along it by more than
// threshold[i] at both ends of the step. dot(t, k, i) is the projection of point k at time t of lane i.
template <bool VertexFace, class Dot>
[[gnu::always_inline]] inline void try_direction(const Dot& dot, const Lanes& threshold, Lanes& culled) {
  for (int i = 0; i < kLanes; ++i) {
    double above = HUGE_VAL, below = -HUGE_VAL;
    for (int t = 0; t < 2; ++t) {
      const double z0 = dot(t, 0, i), z1 = dot(t, 1, i), z2 = dot(t, 2, i), z3 = dot(t, 3, i);
      double low, high;  // smallest and largest difference (first primitive minus second)
      if constexpr (VertexFace) {
        low = z0 - std::max(z1, std::max(z2, z3));
        high = z0 - std::min(z1, std::min(z2, z3));
      } else {
        low = std::min(z0, z1) - std::max(z2, z3);
        high = std::max(z0, z1) - std::min(z2, z3);
      }
      // The sign of a rounded difference of doubles is exact, so these are low > threshold and high < -threshold.
      above = std::min(above, low - threshold[i]);
      below = std::max(below, high + threshold[i]);
    }
    culled[i] = (above > 0.0) | (below < 0.0) ? 1.0 : culled[i];
  }
}

// The directions of one pass (BlockPass): the primitives' normals and/or the fixed ones.
struct PassDirections {
  bool normals;
  bool fixed;
};

template <bool VertexFace>
[[gnu::always_inline]] inline void filter_block(const QueryBlock& b, double thickness, PassDirections pass,
                                                std::uint8_t* out) {
  const auto& x = b.x;
  alignas(64) Lanes largest;  // M: the largest coordinate magnitude of the lane's pair
  for (int i = 0; i < kLanes; ++i) {
    double m = 0.0;
    for (int t = 0; t < 2; ++t)
      for (int k = 0; k < 4; ++k)
        for (int c = 0; c < 3; ++c) m = std::max(m, std::abs(x[t][k][c][i]));
    largest[i] = m;
  }
  alignas(64) Lanes culled = {};
  alignas(64) Lanes threshold;
  if (pass.normals) {
    // The face normal (vertex-face) or the edges' cross product (edge-edge) at each end, used as a fixed vector.
    for (int time = 0; time < 2; ++time) {
      alignas(64) double s[3][kLanes];
      for (int i = 0; i < kLanes; ++i) {
        const int from = VertexFace ? 1 : 0, a_end = VertexFace ? 2 : 1, b_from = VertexFace ? 1 : 2;
        double a[3], e[3];
        for (int c = 0; c < 3; ++c) {
          a[c] = x[time][a_end][c][i] - x[time][from][c][i];
          e[c] = x[time][3][c][i] - x[time][b_from][c][i];
        }
        double n[3] = {a[1] * e[2] - a[2] * e[1], a[2] * e[0] - a[0] * e[2], a[0] * e[1] - a[1] * e[0]};
        const double squared = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
        // A normal too small for an accurate length or too large (or not finite) becomes the zero vector, whose
        // projections never exceed T > 0. So every value below stays finite when M <= 1e100 (no NaN to lose in the
        // minima and maxima); lanes with a larger M are not culled whatever they compute.
        const bool usable = squared >= 1e-200 && squared <= 1e300;
        for (int c = 0; c < 3; ++c) s[c][i] = usable ? n[c] : 0.0;
        const double norm = usable ? std::sqrt(squared) : 0.0;
        const double l1 = std::abs(s[0][i]) + std::abs(s[1][i]) + std::abs(s[2][i]);
        threshold[i] = thickness * norm * kNormSlack + kBoundFactor * l1 * largest[i] + kTiny;
      }
      const auto dot = [&](int t, int k, int i) {
        return s[0][i] * x[t][k][0][i] + s[1][i] * x[t][k][1][i] + s[2][i] * x[t][k][2][i];
      };
      try_direction<VertexFace>(dot, threshold, culled);
    }
  }
  // Eq. (10)'s five directions (unnormalised): (1,0,0), (1,1,0), (1,0,1), (0,1,1), (1,1,1).
  auto fixed = [&](double norm, double l1, const auto& dot) {
    for (int i = 0; i < kLanes; ++i) {
      threshold[i] = thickness * norm * kNormSlack + kBoundFactor * l1 * largest[i] + kTiny;
    }
    try_direction<VertexFace>(dot, threshold, culled);
  };
  if (pass.fixed) {
    const double root2 = std::sqrt(2.0), root3 = std::sqrt(3.0);
    fixed(1.0, 1.0, [&](int t, int k, int i) { return x[t][k][0][i]; });
    fixed(root2, 2.0, [&](int t, int k, int i) { return x[t][k][0][i] + x[t][k][1][i]; });
    fixed(root2, 2.0, [&](int t, int k, int i) { return x[t][k][0][i] + x[t][k][2][i]; });
    fixed(root2, 2.0, [&](int t, int k, int i) { return x[t][k][1][i] + x[t][k][2][i]; });
    fixed(root3, 3.0, [&](int t, int k, int i) { return (x[t][k][0][i] + x[t][k][1][i]) + x[t][k][2][i]; });
  }
  for (int i = 0; i < b.count; ++i) out[i] = culled[i] > 0.0 && largest[i] <= kLargest ? 1 : 0;
}

// Both kinds on every instruction set: the same template inlined into functions compiled for each (the template runs
// the same IEEE operations everywhere, so all give the same verdicts; tests compare each with the per-pair filter).
void filter_baseline(const QueryBlock& b, double thickness, PassDirections pass, std::uint8_t* out) {
  if (b.kind == PairKind::VertexFace) return filter_block<true>(b, thickness, pass, out);
  filter_block<false>(b, thickness, pass, out);
}

#if defined(CLOTHCD_AVX2_PATHS)
__attribute__((target("avx2"))) void filter_avx2(const QueryBlock& b, double thickness, PassDirections pass,
                                                 std::uint8_t* out) {
  if (b.kind == PairKind::VertexFace) return filter_block<true>(b, thickness, pass, out);
  filter_block<false>(b, thickness, pass, out);
}

__attribute__((target("avx512f"))) void filter_avx512(const QueryBlock& b, double thickness, PassDirections pass,
                                                      std::uint8_t* out) {
  if (b.kind == PairKind::VertexFace) return filter_block<true>(b, thickness, pass, out);
  filter_block<false>(b, thickness, pass, out);
}
#endif

// True when every coordinate of the lane's pair is at most kLargest in magnitude (the block filter culls no other).
bool within_range(const QueryBlock& b, int lane) {
  for (int t = 0; t < 2; ++t)
    for (int k = 0; k < 4; ++k)
      for (int c = 0; c < 3; ++c)
        if (!(std::abs(b.x[t][k][c][lane]) <= kLargest)) return false;
  return true;
}

}  // namespace

void QueryBlock::set(int lane, const CcdQuery& query) {
  for (int k = 0; k < 4; ++k) {
    for (int c = 0; c < 3; ++c) {
      x[0][k][c][lane] = query.start[k][c];
      x[1][k][c][lane] = query.end[k][c];
    }
  }
}

CcdQuery QueryBlock::query(int lane) const {
  CcdQuery q;
  q.kind = kind;
  for (int k = 0; k < 4; ++k) {
    q.start[k] = Eigen::Vector3d(x[0][k][0][lane], x[0][k][1][lane], x[0][k][2][lane]);
    q.end[k] = Eigen::Vector3d(x[1][k][0][lane], x[1][k][1][lane], x[1][k][2][lane]);
  }
  return q;
}

void QueryBlock::pad_unused() {
  for (int t = 0; t < 2; ++t)
    for (int k = 0; k < 4; ++k)
      for (int c = 0; c < 3; ++c)
        for (int lane = count; lane < kLanes; ++lane) x[t][k][c][lane] = x[t][k][c][0];
}

std::vector<BlockIsa> supported_block_isas() {
  std::vector<BlockIsa> isas{BlockIsa::Baseline};
  if (avx2_supported()) isas.push_back(BlockIsa::Avx2);
  if (avx512_supported()) isas.push_back(BlockIsa::Avx512);
  return isas;
}

BlockIsa fastest_block_isa() {
  return avx512_supported() ? BlockIsa::Avx512 : avx2_supported() ? BlockIsa::Avx2 : BlockIsa::Baseline;
}

void projection_filter_block(const QueryBlock& block, const CcdSettings& settings,
                             const ProjectionFilterOptions& options, std::uint8_t* culled, BlockIsa isa,
                             BlockPass pass) {
  const bool normals = options.use_primitive_normals;
  const PassDirections directions{normals && pass != BlockPass::AfterNormals, pass != BlockPass::Normals};
#if defined(CLOTHCD_AVX2_PATHS)
  if (isa == BlockIsa::Avx512) {
    filter_avx512(block, settings.thickness, directions, culled);
  } else if (isa == BlockIsa::Avx2) {
    filter_avx2(block, settings.thickness, directions, culled);
  } else {
    filter_baseline(block, settings.thickness, directions, culled);
  }
#else
  filter_baseline(block, settings.thickness, directions, culled);
#endif
  if (!normals || pass == BlockPass::Normals) return;
  // The in-plane directions cost more per pair and are needed by few: they run on the survivors only, one at a time.
  for (int lane = 0; lane < block.count; ++lane) {
    if (culled[lane] || !within_range(block, lane)) continue;
    culled[lane] = separated_in_plane(block.query(lane), settings) ? 1 : 0;
  }
}

void projection_filter_queries(const std::vector<CcdQuery>& queries, const CcdSettings& settings,
                               const ProjectionFilterOptions& options, std::vector<std::uint8_t>& culled,
                               BlockIsa isa) {
  culled.assign(queries.size(), 0);
  // One pass over the queries at the positions `todo`, in blocks of one kind formed in order.
  auto run = [&](const std::vector<std::size_t>& todo, BlockPass pass) {
    QueryBlock block;
    std::size_t first = 0;
    auto flush = [&]() {
      if (block.count == 0) return;
      block.pad_unused();
      std::uint8_t block_culled[QueryBlock::kLanes];
      projection_filter_block(block, settings, options, block_culled, isa, pass);
      for (int lane = 0; lane < block.count; ++lane) culled[todo[first + lane]] = block_culled[lane];
      first += static_cast<std::size_t>(block.count);
      block.count = 0;
    };
    for (const std::size_t i : todo) {
      if (block.count == QueryBlock::kLanes || (block.count > 0 && queries[i].kind != block.kind)) flush();
      block.kind = queries[i].kind;
      block.set(block.count++, queries[i]);
    }
    flush();
  };
  std::vector<std::size_t> all(queries.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  if (!options.use_primitive_normals) return run(all, BlockPass::All);
  run(all, BlockPass::Normals);
  std::vector<std::size_t> survivors;
  for (const std::size_t i : all) {
    if (!culled[i]) survivors.push_back(i);
  }
  run(survivors, BlockPass::AfterNormals);
}

}  // namespace clothcd::ccd::detail

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
#include <array>
#include <cmath>
#include <utility>

#include "ccd/pair_measures.hpp"
#include "support/simd.hpp"

namespace clothcd::ccd::detail {

namespace {

constexpr int kLanes = PairLanes::kLanes;
constexpr double kBoundFactor = 16 * 0x1p-53;
constexpr double kTiny = 1e-300;
constexpr double kLargest = 1e100;
constexpr double kNormSlack = 1.0 + 1e-12;

using Lanes = simd::LaneArray<kLanes>;
// A lane group's coordinates, x[time][point][axis][lane].
using Coordinates = double[2][4][3][kLanes];

// Lambdas do not take the target attribute (AVX2, AVX-512) of the function they are written in, and GCC may leave one
// out of line even inside a `flatten` function: those of the filter are forced inline, so that none is compiled for
// the baseline and called per lane.
#define INLINE_LAMBDA __attribute__((always_inline))

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
    culled[i] = ((above > 0.0) | (below < 0.0)) ? 1.0 : culled[i];
  }
}

// s . p for fixed direction D of pair_measures::kProjectionDirections (components 0 or 1): the sum of p's coordinates
// along s's unit components in axis order ((x + y) + z for (1, 1, 1)), no product needed.
template <std::size_t D>
[[gnu::always_inline]] inline double fixed_projection(double px, double py, double pz) {
  constexpr std::array<double, 3> s = pair_measures::kProjectionDirections[D].s;
  constexpr bool use_x = s[0] != 0.0, use_y = s[1] != 0.0, use_z = s[2] != 0.0;
  static_assert(use_x || use_y || use_z, "a direction has a unit component");
  if constexpr (use_x && use_y && use_z) return (px + py) + pz;
  if constexpr (use_x && use_y && !use_z) return px + py;
  if constexpr (use_x && !use_y && use_z) return px + pz;
  if constexpr (!use_x && use_y && use_z) return py + pz;
  if constexpr (use_x && !use_y && !use_z) return px;
  if constexpr (!use_x && use_y && !use_z) return py;
  if constexpr (!use_x && !use_y && use_z) return pz;
}

// Fixed direction D on every lane.
template <bool VertexFace, std::size_t D>
[[gnu::always_inline]] inline void try_fixed_direction(const Coordinates& x, double thickness, const Lanes& largest,
                                                       Lanes& threshold, Lanes& culled) {
  constexpr double norm = pair_measures::kProjectionDirections[D].norm, l1 = pair_measures::kProjectionDirections[D].l1;
  for (int i = 0; i < kLanes; ++i) {
    threshold[i] = thickness * norm * kNormSlack + kBoundFactor * l1 * largest[i] + kTiny;
  }
  const auto dot = [&](int t, int k, int i) INLINE_LAMBDA {
    return fixed_projection<D>(x[t][k][0][i], x[t][k][1][i], x[t][k][2][i]);
  };
  try_direction<VertexFace>(dot, threshold, culled);
}

// Every fixed direction in turn.
template <bool VertexFace, std::size_t... D>
[[gnu::always_inline]] inline void fixed_directions(const Coordinates& x, double thickness,
                                                    const Lanes& largest, Lanes& threshold, Lanes& culled,
                                                    std::index_sequence<D...>) {
  (try_fixed_direction<VertexFace, D>(x, thickness, largest, threshold, culled), ...);
}

// The directions of one pass (BlockPass).
struct PassDirections {
  bool normals;   // the face normal or the edges' cross product at t = 0 and t = 1
  bool fixed;     // eq. (10)'s five fixed directions
  bool in_plane;  // the in-plane normals of ProjectionFilterOptions::use_primitive_normals at t = 0 and t = 1
};

// a x b into out.
[[gnu::always_inline]] inline void cross(const double* a, const double* b, double* out) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

// `Thick`: thickness > 0. At thickness 0 the term thickness |s| is 0 whatever |s| is, so the square roots are skipped
// (the same thresholds bit for bit).
template <bool VertexFace, bool Thick>
[[gnu::always_inline]] inline void filter_block(const PairLanes& b, double thickness, PassDirections pass,
                                                std::uint8_t* out) {
  const auto& x = b.x;
  // M: the largest coordinate magnitude of the lane's pair; infinite when a coordinate is not a number (std::max drops
  // NaNs: they are caught by `poison`, the sum of the coordinates times zero, NaN exactly when one is NaN or infinite),
  // so that the lane is never culled. Plain arithmetic, so that the loop stays vectorized.
  alignas(64) Lanes largest;
  for (int i = 0; i < kLanes; ++i) {
    double m = 0.0, poison = 0.0;
    for (int t = 0; t < 2; ++t)
      for (int k = 0; k < 4; ++k)
        for (int c = 0; c < 3; ++c) {
          m = std::max(m, std::abs(x[t][k][c][i]));
          poison += x[t][k][c][i] * 0.0;
        }
    largest[i] = poison == 0.0 ? m : HUGE_VAL;
  }
  alignas(64) Lanes culled = {};
  alignas(64) Lanes threshold;
  // A direction computed per lane from the lane's positions at `time` (make(time, i, p, n) writes it to n, p(k, c)
  // being coordinate c of point k), used as a fixed vector: the rounding of its computation needs no bound.
  const auto try_computed = [&](int time, const auto& make) INLINE_LAMBDA {
    alignas(64) double s[3][kLanes];
    for (int i = 0; i < kLanes; ++i) {
      const auto p = [&](int k, int c) INLINE_LAMBDA { return x[time][k][c][i]; };
      double n[3];
      make(p, n);
      const double squared = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
      // A vector too small for an accurate length or too large (or not finite) becomes the zero vector, whose
      // projections never exceed T > 0. So every value below stays finite when M <= 1e100 (no NaN to lose in the
      // minima and maxima); lanes with a larger M are not culled whatever they compute.
      const bool usable = squared >= 1e-200 && squared <= 1e300;
      for (int c = 0; c < 3; ++c) s[c][i] = usable ? n[c] : 0.0;
      const double l1 = std::abs(s[0][i]) + std::abs(s[1][i]) + std::abs(s[2][i]);
      if constexpr (Thick) {
        const double norm = usable ? std::sqrt(squared) : 0.0;
        threshold[i] = thickness * norm * kNormSlack + kBoundFactor * l1 * largest[i] + kTiny;
      } else {
        threshold[i] = kBoundFactor * l1 * largest[i] + kTiny;
      }
    }
    const auto dot = [&](int t, int k, int i) INLINE_LAMBDA {
      return s[0][i] * x[t][k][0][i] + s[1][i] * x[t][k][1][i] + s[2][i] * x[t][k][2][i];
    };
    try_direction<VertexFace>(dot, threshold, culled);
  };
  // Point k minus point j of a lane, into d.
  const auto difference = [](const auto& p, int k, int j, double* d) INLINE_LAMBDA {
    for (int c = 0; c < 3; ++c) d[c] = p(k, c) - p(j, c);
  };
  for (int time = 0; time < 2 && pass.normals; ++time) {
    // The face normal (vertex-face) or the edges' cross product (edge-edge).
    try_computed(time, [&](const auto& p, double* n) INLINE_LAMBDA {
      double a[3], e[3];
      difference(p, VertexFace ? 2 : 1, VertexFace ? 1 : 0, a);
      difference(p, 3, VertexFace ? 1 : 2, e);
      cross(a, e, n);
    });
  }
  // Eq. (10)'s five directions (pair_measures::kProjectionDirections), each projection a sum of coordinates.
  if (pass.fixed) {
    fixed_directions<VertexFace>(x, thickness, largest, threshold, culled,
                                 std::make_index_sequence<pair_measures::kProjectionDirections.size()>{});
  }
  for (int time = 0; time < 2 && pass.in_plane; ++time) {
    if constexpr (VertexFace) {
      // n x e for the face normal n and each edge e of the face (separated_in_plane's directions).
      for (const auto& [to, from] : {std::pair{2, 1}, std::pair{3, 2}, std::pair{1, 3}}) {
        try_computed(time, [&, to = to, from = from](const auto& p, double* v) INLINE_LAMBDA {
          double a[3], e[3], n[3], edge[3];
          difference(p, 2, 1, a);
          difference(p, 3, 1, e);
          cross(a, e, n);
          difference(p, to, from, edge);
          cross(n, edge, v);
        });
      }
    } else {
      // e x (e x w) for each edge e, w joining the edges' midpoints (times two).
      for (const int first : {0, 2}) {
        try_computed(time, [&, first = first](const auto& p, double* v) INLINE_LAMBDA {
          double e[3], w[3], ew[3];
          difference(p, first + 1, first, e);
          for (int c = 0; c < 3; ++c) w[c] = (p(2, c) + p(3, c)) - (p(0, c) + p(1, c));
          cross(e, w, ew);
          cross(e, ew, v);
        });
      }
    }
  }
  for (int i = 0; i < b.count; ++i) out[i] = culled[i] > 0.0 && largest[i] <= kLargest ? 1 : 0;
}

#undef INLINE_LAMBDA

// The template for the block's kind and for thickness 0 or not; compiled for each level below.
[[gnu::always_inline]] inline void filter_any(const PairLanes& b, double thickness, PassDirections pass,
                                              std::uint8_t* out) {
  if (thickness > 0.0) {
    if (b.kind == PairKind::VertexFace) return filter_block<true, true>(b, thickness, pass, out);
    return filter_block<false, true>(b, thickness, pass, out);
  }
  if (b.kind == PairKind::VertexFace) return filter_block<true, false>(b, thickness, pass, out);
  filter_block<false, false>(b, thickness, pass, out);
}

// Both kinds on every level: the same template compiled for each (the template runs the same IEEE operations
// everywhere, so all give the same verdicts; tests compare each with the per-pair filter).
#define CLOTHCD_SIMD_KERNEL_FUNCTION filter_any
#define CLOTHCD_SIMD_KERNEL_AVX512
#include "support/simd_versions.hpp"

}  // namespace

void projection_filter_block(const PairLanes& block, const CcdSettings& settings,
                             const ProjectionFilterOptions& options, std::uint8_t* culled, SimdLevel level,
                             BlockPass pass) {
  if (!(settings.thickness >= 0.0 && std::isfinite(settings.thickness))) {  // as the per-pair filter: no verdict
    std::fill(culled, culled + block.count, std::uint8_t{0});
    return;
  }
  const bool normals = options.use_primitive_normals;
  const PassDirections directions{normals && pass != BlockPass::AfterNormals, pass != BlockPass::Normals,
                                  normals && pass != BlockPass::Normals};
  CLOTHCD_SIMD_DISPATCH(level, run_kernel(block, settings.thickness, directions, culled));
}

void projection_filter_queries(const std::vector<CcdQuery>& queries, const CcdSettings& settings,
                               const ProjectionFilterOptions& options, std::vector<std::uint8_t>& culled,
                               SimdLevel level) {
  culled.assign(queries.size(), 0);
  // One pass over the queries at the positions `todo`, in blocks of one kind formed in order.
  auto run = [&](const std::vector<std::size_t>& todo, BlockPass pass) {
    PairLanes block;
    std::size_t first = 0;
    auto flush = [&]() {
      if (block.count == 0) return;
      block.pad_unused();
      std::uint8_t block_culled[PairLanes::kLanes];
      projection_filter_block(block, settings, options, block_culled, level, pass);
      for (int lane = 0; lane < block.count; ++lane) culled[todo[first + lane]] = block_culled[lane];
      first += static_cast<std::size_t>(block.count);
      block.count = 0;
    };
    for (const std::size_t i : todo) {
      if (block.count == PairLanes::kLanes || (block.count > 0 && queries[i].kind != block.kind)) flush();
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

#pragma once
/// @file
/// Continuous collision detection (CCD) of one vertex-face or edge-edge pair moving linearly over a step t in [0, 1]:
/// the safe narrow phase, its exact rational reference and the two culling filters of Jin et al. (sections 2.2, 2.3).
///
/// Safety contract: no function here ever misses a collision of the query as given (the double coordinates are taken
/// as exact). When floating-point arithmetic cannot decide, the exact rational path decides; filters cull a pair only
/// when their sign tests are certain under a rigorous rounding-error bound.

#include <Eigen/Dense>
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "clothcd/ccd/pair_kind.hpp"

namespace clothcd::ccd {

/// One CCD query: four points at the start (t = 0) and end (t = 1) of the step, moving linearly in between.
/// VertexFace: {vertex, t0, t1, t2}; EdgeEdge: {a0, a1, b0, b1} (the order of the public benchmark's CSV files).
struct CcdQuery {
  PairKind kind = PairKind::VertexFace;    ///< Pair kind.
  std::array<Eigen::Vector3d, 4> start{};  ///< Positions at t = 0.
  std::array<Eigen::Vector3d, 4> end{};    ///< Positions at t = 1.
};

/// Settings shared by all queries of a step.
struct CcdSettings {
  /// Minimum separation (same length unit as the coordinates, >= 0). With thickness > 0 a pair collides when its
  /// distance (point-triangle / segment-segment) gets <= thickness during the step. Decided in double precision by a
  /// Lipschitz-bounded search of the distance over time; only pairs whose minimum distance lies within a rounding
  /// margin (about 1e-7 of the pair's extent) of thickness can stay undecided (ConservativeHit).
  double thickness = 0.0;
  /// Thickness 0: what decides a query that the floating-point fast tier (with rounding-error bounds) leaves undecided
  /// (the primitives touch exactly, e.g. a vertex on an edge at the coplanarity time or at t = 0 or 1, or miss by
  /// about a rounding error).
  /// true (the default): exact floating-point expansions decide it, then GMP rationals: every hit is proven, no false
  /// positive. false, the approximate mode: it is reported as a ConservativeHit (never a miss, a few false positives,
  /// toi only a lower bound).
  bool decide_exactly = true;
};

/// How a CCD answer was established.
enum class CcdState : std::uint8_t {
  Separated,        ///< Proven not to collide.
  /// Proven to collide / come within the thickness. Thickness 0: toi is a lower bound of the earliest contact time and
  /// at most 2^-21 (< 1e-6) of the step below it.
  Hit,
  /// Could not be proven either way (thickness > 0, or thickness 0 without CcdSettings::decide_exactly); reported as a
  /// hit, toi a lower bound.
  ConservativeHit,
};

/// Result of continuous_collision.
struct CcdResult {
  bool hit = false;                      ///< True for Hit and ConservativeHit.
  double toi = 1.0;                      ///< Lower bound of the earliest time of impact in [0, 1] (1 when separated).
  CcdState state = CcdState::Separated;  ///< How the answer was established.
  /// VertexFace: barycentric weights (w1, w2) of the contact on the triangle; EdgeEdge: (s on edge a, u on edge b).
  /// Of the closest points at toi (approximate); {0, 0} when unknown.
  std::array<double, 2> parameters{};
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< Unit contact normal at toi (zero when unknown or degenerate).
  /// True when neither the floating-point fast tier nor the exact floating-point expansion tier could decide and GMP
  /// rational arithmetic did.
  bool exact_fallback = false;
};

/// Extra options of the projection filter.
struct ProjectionFilterOptions {
  /// Also project onto directions derived from the primitives, in addition to the paper's five fixed directions of
  /// eq. (10): the face normal or the edges' cross product at t = 0 and t = 1, then, for a pair none of those
  /// separates, the in-plane normals (at t = 0, then t = 1) of the face's three edges (vertex-face) or of each edge
  /// towards the other (edge-edge), which separate neighbouring primitives of a flat sheet.
  bool use_primitive_normals = false;
};

/// Which filter a batch runs before the narrow phase.
enum class CcdFilter : std::uint8_t {
  None,            ///< Keep every pair.
  NonPenetration,  ///< Bernstein-form sign test of the coplanarity cubic (section 2.2).
  Projection,      ///< Separation along the five directions of eq. (10) at both ends of the step (section 2.3).
  Combined,        ///< Non-penetration first (cheaper), then projection.
};

/// Throws std::invalid_argument when a coordinate is NaN or infinite or the thickness is negative or not finite.
void validate_query(const CcdQuery& query, const CcdSettings& settings = {});

/// The fast, safe CCD test: never misses a collision. Thickness 0: floating point with rounding-error bounds, and for
/// the cases it leaves undecided exact arithmetic (or, without CcdSettings::decide_exactly, a ConservativeHit);
/// thickness > 0: distance search in double precision with a conservative margin (see CcdSettings).
/// Expects finite coordinates (see validate_query); non-finite input is reported as a ConservativeHit at toi 0.
[[nodiscard]] CcdResult continuous_collision(const CcdQuery& query, const CcdSettings& settings = {});

/// The narrow phase for a pair that a culling filter has already examined (a block pipeline filters first): the same
/// result as continuous_collision(query, settings), for a query that `applied` (run with the same settings) did not
/// cull: the non-penetration and projection tests `applied` covers are not run again (both are pure functions of the
/// query, so skipping them cannot change the answer). CcdFilter::None runs everything.
[[nodiscard]] CcdResult continuous_collision_after_filter(const CcdQuery& query, const CcdSettings& settings,
                                                          CcdFilter applied);

/// continuous_collision_after_filter for a search of the earliest contact: the part of the step after `until` (in
/// [0, 1]) is not examined. When the query's result from continuous_collision_after_filter has toi <= until, this is
/// that same result; otherwise it is that result or Separated (the query has no contact at or before `until`). With a
/// thickness the whole step is examined, as continuous_collision_after_filter does.
[[nodiscard]] CcdResult continuous_collision_until(const CcdQuery& query, const CcdSettings& settings,
                                                   CcdFilter applied, double until);


/// Slow exact reference (GMP rationals, thickness 0): true when the primitives touch or cross at some t in [0, 1].
/// Throws std::invalid_argument on non-finite coordinates.
[[nodiscard]] bool exact_collision_reference(const CcdQuery& query);

/// Exact reference on rational coordinates: points[i] = {x, y, z} with each coordinate a pair of decimal integer
/// strings {numerator, denominator}; point order as in the benchmark CSV (the four start points, then the four end
/// points).
[[nodiscard]] bool exact_collision_reference(PairKind kind,
                                             const std::array<std::array<std::array<std::string, 2>, 3>, 8>& points);

/// Algebraic non-penetration filter: true when the coplanarity cubic provably has no root in [0, 1] (its four Bernstein
/// coefficients have one strict sign beyond their rounding-error bound). Disabled (always false) for thickness > 0.
/// Every filter culls nothing when the thickness is NaN, infinite or negative.
[[nodiscard]] bool nonpenetration_filter_culls(const CcdQuery& query, const CcdSettings& settings = {});

/// Spatial linear projection filter: true when, along one of the paper's five directions (eq. 10), every point of one
/// primitive lies farther than thickness beyond every point of the other at both t = 0 and t = 1.
[[nodiscard]] bool projection_filter_culls(const CcdQuery& query, const CcdSettings& settings = {});

/// Projection filter with extra directions (see ProjectionFilterOptions).
[[nodiscard]] bool projection_filter_culls(const CcdQuery& query, const CcdSettings& settings,
                                           const ProjectionFilterOptions& options);

/// Both filters, cheaper first: true when either culls.
[[nodiscard]] bool combined_filters_cull(const CcdQuery& query, const CcdSettings& settings = {});

/// Runs one filter; true when it culls the pair.
[[nodiscard]] bool filter_culls(CcdFilter filter, const CcdQuery& query, const CcdSettings& settings = {});

/// filter_culls over a vector of queries: keep[i] = 1 when queries[i] survives `filter`, 0 when culled. The per-pair
/// filters, one query at a time (the references the block filters are tested against; the detector runs
/// cull_pair_block on its pair blocks). keep is resized to queries.size(); returns the number kept.
std::size_t filter_batch(const std::vector<CcdQuery>& queries, CcdFilter filter, const CcdSettings& settings,
                         std::vector<std::uint8_t>& keep);

/// Batched narrow phase: results[i] = continuous_collision(queries[i]) for queries with keep[i] != 0 (or all when keep
/// is empty); culled queries get a Separated result. results is resized to queries.size(); returns the number of hits.
std::size_t continuous_collision_batch(const std::vector<CcdQuery>& queries, const std::vector<std::uint8_t>& keep,
                                       const CcdSettings& settings, std::vector<CcdResult>& results);

}  // namespace clothcd::ccd

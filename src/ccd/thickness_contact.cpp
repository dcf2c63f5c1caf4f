// Thickness CCD: a pair collides iff min over t in [0, 1] of dist(A(t), B(t)) <= h, with dist the point-triangle
// (vertex-face) or segment-segment (edge-edge) distance and every vertex moving linearly.
//
// Lipschitz bound: a closest pair of points is sum_i alpha_i x_i(t) - sum_j beta_j y_j(t) with convex weights, so
// |dist(t) - dist(s)| <= L |t - s| with L = max_{i,j} |dx_i - dy_j| (dx the displacement over the step). On a piece
// [a, b], dist(t) >= max(d(a) - L (t - a), d(b) - L (b - t)) >= (d(a) + d(b) - L (b - a)) / 2; the whole step is
// cleared from the start sample alone when d(0) - L exceeds h + margin. Pieces are split
// depth-first from the left, so the first piece not proven clear holds the earliest contact:
//   - cleared when the bound exceeds h + margin;
//   - proven hit when d(a) <= h - margin at its start (everything before was cleared, so toi = a), or when d(b) is
//     (toi = a + (d(a) - h - margin) / L, before which the bound keeps the distance above h);
//   - at the depth or evaluation limit a ConservativeHit at a, upgraded to Hit when a later sample already proved contact.
// Before a piece is split, it is also cleared by a projection: along the gap direction n of the closest points at
// either end, every n . (x_i - y_j) (points x of the first primitive, y of the second) is linear in t, so if all of
// them exceed (h + margin) |n| at both ends, they do on the whole piece, and so does the distance. This clears in one
// step the pieces of a pair sliding past at just over h, which the Lipschitz bound only clears after many splits.
// margin covers the double evaluation of positions and distances (a few ulps of the coordinates) and the 1e-8
// degeneracy cut-off of geometry/pair_distance_closest_points.cpp (relative to the pair's extent).
#include "ccd/thickness_contact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "geometry/pair_distance.hpp"

namespace clothcd::ccd::detail {

namespace {

using geometry::ClosestPoints;
using geometry::point_triangle_closest;
using geometry::segment_segment_closest;

constexpr int kMaxDepth = 24;           // pieces down to 6e-8 of the step
constexpr int kMaxEvaluations = 4096;   // bounded work for grazing contacts at exactly h
constexpr double kExtentMargin = 1e-7;  // > 1e-8 degeneracy cut-off plus rounding, relative to the pair's extent
constexpr double kScaleMargin = 64 * std::numeric_limits<double>::epsilon();

struct Geometry {
  std::array<Eigen::Vector3d, 4> start;
  std::array<Eigen::Vector3d, 4> delta;
};

ClosestPoints closest_at(const CcdQuery& query, const Geometry& g, double t) {
  std::array<Eigen::Vector3d, 4> x;
  for (int i = 0; i < 4; ++i) x[i] = t == 1.0 ? query.end[i] : Eigen::Vector3d(g.start[i] + t * g.delta[i]);
  return query.kind == PairKind::VertexFace ? point_triangle_closest(x[0], x[1], x[2], x[3])
                                            : segment_segment_closest(x[0], x[1], x[2], x[3]);
}

enum class Outcome { Clear, Hit, Undecided };

struct Search {
  const CcdQuery& query;
  Geometry geometry;
  double lipschitz = 0.0;
  double clear_above = 0.0;  // h + margin
  double hit_below = 0.0;    // h - margin
  int evaluations = 0;
  bool proven = false;  // some sample was certainly within h
  double toi = 1.0;
};

// The positions at one time, their distance and the gap between their closest points (first minus second).
struct Sample {
  std::array<Eigen::Vector3d, 4> x;
  double distance = 0.0;
  Eigen::Vector3d gap = Eigen::Vector3d::Zero();
};

Sample sample_at(Search& search, double t) {
  ++search.evaluations;
  const CcdQuery& query = search.query;
  Sample sample;
  for (int i = 0; i < 4; ++i)
    sample.x[i] = t == 1.0 ? query.end[i] : Eigen::Vector3d(search.geometry.start[i] + t * search.geometry.delta[i]);
  const ClosestPoints closest = query.kind == PairKind::VertexFace
                                    ? point_triangle_closest(sample.x[0], sample.x[1], sample.x[2], sample.x[3])
                                    : segment_segment_closest(sample.x[0], sample.x[1], sample.x[2], sample.x[3]);
  search.proven = search.proven || closest.distance <= search.hit_below;
  sample.distance = closest.distance;
  sample.gap = closest.first - closest.second;
  return sample;
}

// True when every n . (x_i - y_j) exceeds clear_above |n| in both samples (see the file comment).
bool projection_clears(const Search& search, const Eigen::Vector3d& n, const Sample& sa, const Sample& sb) {
  const double length = n.norm();
  if (!(length > 0.0) || !std::isfinite(length)) return false;
  const double threshold = search.clear_above * length * (1.0 + 1e-12);
  const int split = search.query.kind == PairKind::VertexFace ? 1 : 2;
  for (const Sample* sample : {&sa, &sb}) {
    std::array<double, 4> z;
    for (int i = 0; i < 4; ++i) z[i] = n.dot(sample->x[i]);
    for (int i = 0; i < split; ++i)
      for (int j = split; j < 4; ++j)
        if (!(z[i] - z[j] > threshold)) return false;
  }
  return true;
}

Outcome search_piece(Search& search, double a, double b, const Sample& sa, const Sample& sb, int depth) {
  const double da = sa.distance, db = sb.distance;
  if (da <= search.hit_below) {
    search.toi = a;
    return Outcome::Hit;
  }
  if (0.5 * (da + db - search.lipschitz * (b - a)) > search.clear_above) return Outcome::Clear;
  if (db > search.hit_below &&
      (projection_clears(search, sa.gap, sa, sb) || projection_clears(search, sb.gap, sa, sb))) {
    return Outcome::Clear;
  }
  if (db <= search.hit_below) {
    const double lead = search.lipschitz > 0.0 ? (da - search.clear_above) / search.lipschitz : 0.0;
    search.toi = std::clamp(a + std::max(0.0, lead) * (1.0 - 1e-12), a, b);
    return Outcome::Hit;
  }
  const double mid = 0.5 * (a + b);
  if (depth >= kMaxDepth || search.evaluations >= kMaxEvaluations || !(mid > a && mid < b)) {
    search.toi = a;
    return Outcome::Undecided;
  }
  const Sample sm = sample_at(search, mid);
  const Outcome left = search_piece(search, a, mid, sa, sm, depth + 1);
  if (left != Outcome::Clear) return left;
  return search_piece(search, mid, b, sm, sb, depth + 1);
}

double max_relative_displacement(const CcdQuery& query, const Geometry& g) {
  const int split = query.kind == PairKind::VertexFace ? 1 : 2;
  double largest = 0.0;  // squared: one square root at the end gives the same result (it is monotone)
  for (int i = 0; i < split; ++i)
    for (int j = split; j < 4; ++j) largest = std::max(largest, (g.delta[i] - g.delta[j]).squaredNorm());
  return std::sqrt(largest);
}

double rounding_margin(const CcdQuery& query) {
  Eigen::Vector3d lo = query.start[0], hi = query.start[0];
  for (int i = 0; i < 4; ++i) {
    lo = lo.cwiseMin(query.start[i]).cwiseMin(query.end[i]);
    hi = hi.cwiseMax(query.start[i]).cwiseMax(query.end[i]);
  }
  const double scale = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
  return kExtentMargin * (hi - lo).norm() + kScaleMargin * scale + 1e-300;
}

// Unit normal from the second primitive towards the first; the face normal / edge cross product when they touch.
Eigen::Vector3d contact_normal(const CcdQuery& query, const Geometry& g, double t, const ClosestPoints& closest) {
  const Eigen::Vector3d gap = closest.first - closest.second;
  const double gap_length = gap.norm();
  if (gap_length > 0.0 && std::isfinite(gap_length)) return gap / gap_length;
  std::array<Eigen::Vector3d, 4> x;
  for (int i = 0; i < 4; ++i) x[i] = g.start[i] + t * g.delta[i];
  const bool vertex_face = query.kind == PairKind::VertexFace;
  Eigen::Vector3d n = vertex_face ? (x[2] - x[1]).cross(x[3] - x[1]) : (x[1] - x[0]).cross(x[3] - x[2]);
  const double length = n.norm();
  if (!(length > 0.0) || !std::isfinite(length)) return Eigen::Vector3d::Zero();
  n /= length;
  const Eigen::Vector3d towards_first = vertex_face ? Eigen::Vector3d(query.start[0] - query.start[1])
                                                    : Eigen::Vector3d((query.start[0] + query.start[1]) -
                                                                      (query.start[2] + query.start[3]));
  return n.dot(towards_first) < 0.0 ? -n : n;
}

}  // namespace

CcdResult thick_contact(const CcdQuery& query, double thickness) {
  Geometry geometry;
  for (int i = 0; i < 4; ++i) {
    geometry.start[i] = query.start[i];
    geometry.delta[i] = query.end[i] - query.start[i];
  }
  const double margin = rounding_margin(query);
  Search search{query, geometry};
  search.lipschitz = max_relative_displacement(query, geometry) * (1.0 + 1e-12);
  search.clear_above = thickness + margin;
  search.hit_below = thickness - margin;
  const Sample s0 = sample_at(search, 0.0);
  // The distance stays above d(0) - L t >= d(0) - L all step: a pair that far apart at the start needs no more samples.
  if (s0.distance - search.lipschitz > search.clear_above) return CcdResult{};
  const Sample s1 = sample_at(search, 1.0);
  const Outcome outcome = search_piece(search, 0.0, 1.0, s0, s1, 0);
  CcdResult result;
  if (outcome == Outcome::Clear) return result;
  result.hit = true;
  result.toi = search.toi;
  result.state = outcome == Outcome::Hit || search.proven ? CcdState::Hit : CcdState::ConservativeHit;
  const ClosestPoints closest = closest_at(query, geometry, result.toi);
  result.parameters = closest.parameters;
  result.normal = contact_normal(query, geometry, result.toi, closest);
  return result;
}

}  // namespace clothcd::ccd::detail

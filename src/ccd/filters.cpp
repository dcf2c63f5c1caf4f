// The two culling filters of Jin et al. (section 2.2 and 2.3), made rounding-safe.
//
// Non-penetration filter (Tang et al. 2010, "Fast continuous collision detection using deforming non-penetration
// filters"): D(t) = det(x1 - x0, x2 - x0, x3 - x0) with x_i(t) linear is a cubic whose Bernstein coefficients on [0, 1]
// follow from trilinearity: b0 = det(A0, B0, C0), 3 b1 = det(A1, B0, C0) + det(A0, B1, C0) + det(A0, B0, C1),
// 3 b2 = det(A1, B1, C0) + det(A1, B0, C1) + det(A0, B1, C1), b3 = det(A1, B1, C1) (A = x1 - x0, B = x2 - x0,
// C = x3 - x0 at t = 0 and 1). D lies in the convex hull of its Bernstein coefficients, so four of one strict sign mean
// no coplanarity, hence no contact. The ten determinants share four cross products: b0 = A0.(B0 x C0),
// 3 b1 = A1.(B0 x C0) + A0.(B1 x C0 + B0 x C1), 3 b2 = A1.(B1 x C0 + B0 x C1) + A0.(B1 x C1), b3 = A1.(B1 x C1). Each
// coefficient is compared with a forward error bound 32 u * (the same expression on absolute values) + 1e-300
// (u = 2^-53; at most 9 roundings deep, so the exact bound is about 9 u; the absolute term covers underflow).
//
// Projection filter (Wan et al., eqs. 8-10): Z = s . (p - q) for every point p of one primitive and q of the other, at
// t = 0 and t = 1. Each Z is linear in t, so all Z beyond +h|s| (or all below -h|s|) at both ends stays so in between:
// the primitives are separated by more than h along s during the whole step. Each Z is compared with the bound
// 8 u * sum |s_c (p - q)_c| + 1e-300.
#include <cmath>
#include <limits>

#include "ccd/pair_measures.hpp"
#include "ccd/projection_block.hpp"
#include "clothcd/ccd/ccd.hpp"

namespace clothcd::ccd {

namespace {

constexpr double kUnitRoundoff = 0x1p-53;
constexpr double kTiny = 1e-300;

struct Bounded {
  double value;
  double magnitude;  // the same expression evaluated on absolute values
};

struct BoundedVector {
  Eigen::Vector3d value;
  Eigen::Vector3d magnitude;  // the same expression evaluated on absolute values
};

BoundedVector cross(const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ba = b.cwiseAbs();
  const Eigen::Vector3d ca = c.cwiseAbs();
  return {b.cross(c), {ba.y() * ca.z() + ba.z() * ca.y(), ba.z() * ca.x() + ba.x() * ca.z(),
                       ba.x() * ca.y() + ba.y() * ca.x()}};
}

BoundedVector operator+(const BoundedVector& u, const BoundedVector& v) {
  return {u.value + v.value, u.magnitude + v.magnitude};
}

Bounded dot(const Eigen::Vector3d& a, const BoundedVector& v) {
  return {a.dot(v.value), a.cwiseAbs().dot(v.magnitude)};
}

Bounded operator+(const Bounded& x, const Bounded& y) {
  return {x.value + y.value, x.magnitude + y.magnitude};
}

// +1 or -1 when value is certainly of that sign under its error bound, else 0.
int certain_sign(double value, double magnitude) {
  const double bound = 32.0 * kUnitRoundoff * magnitude + kTiny;
  return value > bound ? 1 : (value < -bound ? -1 : 0);
}

bool separated_along(const CcdQuery& query, const Eigen::Vector3d& s, double threshold) {
  int sign = 0;
  const int first_count = query.kind == PairKind::VertexFace ? 1 : 2;
  for (const auto* positions : {&query.start, &query.end}) {
    for (int i = 0; i < first_count; ++i) {
      for (int j = first_count; j < 4; ++j) {
        const Eigen::Vector3d d = (*positions)[i] - (*positions)[j];
        const double z = s.dot(d);
        const double bound = 8.0 * kUnitRoundoff * s.cwiseAbs().dot(d.cwiseAbs()) + kTiny + threshold;
        const int z_sign = z > bound ? 1 : (z < -bound ? -1 : 0);
        if (z_sign == 0 || (sign != 0 && z_sign != sign)) return false;
        sign = z_sign;
      }
    }
  }
  return true;
}

// h |s| rounded up, so that a Z beyond it is certainly beyond the true threshold (`norm` is |s| to within a few
// units in the last place; the factor 1 + 1e-12 covers that and the products' rounding).
double threshold_for(double thickness, double norm) {
  if (thickness <= 0.0) return 0.0;
  return thickness * norm * (1.0 + 1e-12);
}

// A thickness the filters can reason with: finite and >= 0 (else they cull nothing; continuous_collision reports such a
// query as a conservative hit).
bool usable_thickness(const CcdSettings& settings) {
  return settings.thickness >= 0.0 && std::isfinite(settings.thickness);
}

}  // namespace

bool nonpenetration_filter_culls(const CcdQuery& query, const CcdSettings& settings) {
  // A root-free D says nothing about the distance staying above h.
  if (settings.thickness != 0.0 || !usable_thickness(settings)) return false;
  const std::array<Eigen::Vector3d, 2> a{query.start[1] - query.start[0], query.end[1] - query.end[0]};
  const std::array<Eigen::Vector3d, 2> b{query.start[2] - query.start[0], query.end[2] - query.end[0]};
  const std::array<Eigen::Vector3d, 2> c{query.start[3] - query.start[0], query.end[3] - query.end[0]};
  const BoundedVector bc00 = cross(b[0], c[0]);
  const BoundedVector bc11 = cross(b[1], c[1]);
  const Bounded b0 = dot(a[0], bc00);
  const Bounded b3 = dot(a[1], bc11);
  const int s0 = certain_sign(b0.value, b0.magnitude);
  if (s0 == 0 || certain_sign(b3.value, b3.magnitude) != s0) return false;
  const BoundedVector bc_mixed = cross(b[1], c[0]) + cross(b[0], c[1]);
  const Bounded b1 = dot(a[1], bc00) + dot(a[0], bc_mixed);
  if (certain_sign(b1.value, b1.magnitude) != s0) return false;
  const Bounded b2 = dot(a[1], bc_mixed) + dot(a[0], bc11);
  return certain_sign(b2.value, b2.magnitude) == s0;
}

bool projection_filter_culls(const CcdQuery& query, const CcdSettings& settings) {
  return projection_filter_culls(query, settings, ProjectionFilterOptions{});
}

namespace detail {

bool separated_in_plane(const CcdQuery& query, const CcdSettings& settings) {
  if (!usable_thickness(settings)) return false;
  auto separates = [&](const Eigen::Vector3d& s) {
    const double squared_norm = s.squaredNorm();
    if (!s.allFinite() || squared_norm == 0.0) return false;
    const double norm = settings.thickness > 0.0 ? std::sqrt(squared_norm) : 0.0;
    return separated_along(query, s, threshold_for(settings.thickness, norm));
  };
  for (const auto* positions : {&query.start, &query.end}) {
    const auto& x = *positions;
    if (query.kind == PairKind::VertexFace) {
      const Eigen::Vector3d n = (x[2] - x[1]).cross(x[3] - x[1]);
      if (separates(n.cross(x[2] - x[1])) || separates(n.cross(x[3] - x[2])) || separates(n.cross(x[1] - x[3]))) {
        return true;
      }
    } else {
      // Perpendicular to each edge, in the plane of that edge and the line joining the edges' midpoints.
      const Eigen::Vector3d a = x[1] - x[0], b = x[3] - x[2], w = (x[2] + x[3]) - (x[0] + x[1]);
      if (separates(a.cross(a.cross(w))) || separates(b.cross(b.cross(w)))) return true;
    }
  }
  return false;
}

}  // namespace detail

bool projection_filter_culls(const CcdQuery& query, const CcdSettings& settings,
                             const ProjectionFilterOptions& options) {
  if (!usable_thickness(settings)) return false;
  // The primitives' own directions first when asked: they separate most pairs that can be separated (a cloth resting
  // above a surface), so the fixed directions are rarely reached.
  if (options.use_primitive_normals) {
    for (const auto* positions : {&query.start, &query.end}) {
      const auto& x = *positions;
      // Any fixed vector is a valid direction, so the rounded normal needs no error bound of its own.
      const Eigen::Vector3d s =
          query.kind == PairKind::VertexFace ? (x[2] - x[1]).cross(x[3] - x[1]) : (x[1] - x[0]).cross(x[3] - x[2]);
      const double squared_norm = s.squaredNorm();
      if (!s.allFinite() || squared_norm == 0.0) continue;
      const double norm = settings.thickness > 0.0 ? std::sqrt(squared_norm) : 0.0;
      if (separated_along(query, s, threshold_for(settings.thickness, norm))) return true;
    }
  }
  // Eq. (10)'s directions without their normalisation (the sign tests do not depend on it; h is scaled by |s|).
  for (const pair_measures::ProjectionDirection& d : pair_measures::kProjectionDirections) {
    const Eigen::Vector3d s(d.s[0], d.s[1], d.s[2]);
    if (separated_along(query, s, threshold_for(settings.thickness, d.norm))) return true;
  }
  return options.use_primitive_normals && detail::separated_in_plane(query, settings);
}

bool combined_filters_cull(const CcdQuery& query, const CcdSettings& settings) {
  return nonpenetration_filter_culls(query, settings) || projection_filter_culls(query, settings);
}

bool filter_culls(CcdFilter filter, const CcdQuery& query, const CcdSettings& settings) {
  switch (filter) {
    case CcdFilter::None:
      return false;
    case CcdFilter::NonPenetration:
      return nonpenetration_filter_culls(query, settings);
    case CcdFilter::Projection:
      return projection_filter_culls(query, settings);
    case CcdFilter::Combined:
      return combined_filters_cull(query, settings);
  }
  return false;
}

std::size_t filter_batch(const std::vector<CcdQuery>& queries, CcdFilter filter, const CcdSettings& settings,
                         std::vector<std::uint8_t>& keep) {
  keep.resize(queries.size());
  std::size_t kept = 0;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    keep[i] = filter_culls(filter, queries[i], settings) ? 0 : 1;
    kept += keep[i];
  }
  return kept;
}

}  // namespace clothcd::ccd

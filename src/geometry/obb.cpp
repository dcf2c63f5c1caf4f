// Oriented bounding boxes. (a) Covariance: S. Gottschalk, M. C. Lin, D. Manocha, "OBBTree", SIGGRAPH 1996 (vertex
// covariance). (b) The fast adaptive OBB of Jin et al. section 3.1.1 (eqs. 11-18, after their ref. [32]): area-weighted
// centre, vertices split into s slabs per axis keeping each slab's extremes, covariance of the triangles touching them.
// (c) (b) on the QEM-simplified model, extents from the original model's convex-hull vertices. Tight reference: one axis
// from every hull face normal and hull edge direction, the other two from the minimum-area rectangle of the projected
// hull (H. Freeman, R. Shapira, 1975: a minimum-area rectangle has a side on the hull), in the spirit of Hu & Qin.
#include "clothcd/geometry/obb.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <string>
#include <cmath>
#include <stdexcept>

#include "clothcd/geometry/convex_hull.hpp"
#include "clothcd/geometry/simplify.hpp"
#include "min_area_rectangle.hpp"
#include "power_of_two_scale.hpp"
#include "slab_extremes.hpp"
#include "support/simd.hpp"
#include "support/simd_level.hpp"


namespace clothcd::geometry {
namespace {

// Loops the compiler vectorises, several times faster than Eigen's allFinite and minCoeff/maxCoeff here (which would
// otherwise be a large part of a covariance box's time). One sum of squares (four partial sums, so that they need no
// reordering to run in parallel) answers both questions: it is NaN when a coordinate is NaN, and it is far from 1 (or
// infinite) only when a coordinate is above 2^100, infinite, or all are below 2^-100; only then does a second pass
// look at the coordinates themselves. Returns the power-of-two scale exponent the methods need
// (detail::far_scale_exponent).
int check_input(const TriangleMesh& mesh, const char* where) {
  if (mesh.vertex_count() == 0) throw std::invalid_argument(std::string(where) + ": the mesh has no vertices");
  const double* const x = mesh.vertices.data();
  const Eigen::Index count = mesh.vertices.size();
  double squares[4] = {0, 0, 0, 0};
  Eigen::Index i = 0;
  for (; i + 4 <= count; i += 4)
    for (int k = 0; k < 4; ++k) squares[k] += x[i + k] * x[i + k];
  for (; i < count; ++i) squares[0] += x[i] * x[i];
  const double sum = (squares[0] + squares[1]) + (squares[2] + squares[3]);
  const bool far = !(sum <= 0x1p200 && sum >= 0x1p-200);  // also NaN and infinity
  if (far && !mesh.vertices.allFinite()) throw std::invalid_argument(std::string(where) + ": non-finite coordinate");
  const int* const corner = mesh.faces.data();
  int lowest = 0, highest = 0;
  for (Eigen::Index j = 0; j < mesh.faces.size(); ++j) {
    lowest = std::min(lowest, corner[j]);
    highest = std::max(highest, corner[j]);
  }
  if (lowest < 0 || highest >= mesh.vertex_count())
    throw std::invalid_argument(std::string(where) + ": face index out of range");
  return far ? detail::far_scale_exponent(mesh.vertices) : 0;
}

// Orthonormal, right-handed eigenvectors of a symmetric covariance; identity when the solver returns garbage.
Eigen::Matrix3d principal_axes(const Eigen::Matrix3d& covariance) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(covariance);
  Eigen::Matrix3d axes = solver.eigenvectors();
  if (!axes.allFinite()) return Eigen::Matrix3d::Identity();
  // Re-orthonormalise: computeDirect can lose orthogonality on repeated eigenvalues.
  Eigen::Vector3d x = axes.col(2).normalized();
  Eigen::Vector3d y = axes.col(1) - axes.col(1).dot(x) * x;
  if (y.norm() < 1e-9) y = x.unitOrthogonal();
  y.normalize();
  axes.col(0) = x;
  axes.col(1) = y;
  axes.col(2) = x.cross(y);
  return axes;
}

Eigen::Matrix3d covariance_axes(const Vertices& v) {
  const Eigen::Vector3d mean = v.colwise().mean().transpose();
  Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
  for (Eigen::Index i = 0; i < v.rows(); ++i) {
    const Eigen::Vector3d d = v.row(i).transpose() - mean;
    c.noalias() += d * d.transpose();
  }
  return principal_axes(c);
}

double box_volume(const std::vector<Eigen::Vector3d>& points, const Eigen::Matrix3d& axes) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& p : points) {
    const Eigen::Vector3d q = axes.transpose() * p;
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  return (hi - lo).prod();
}

// Keeps each axis in turn and turns the other two to the minimum-area rectangle of the points projected on the plane
// orthogonal to it; the smallest box (measured on the points) wins. Two rounds.
Eigen::Matrix3d refine_axes(const std::vector<Eigen::Vector3d>& points, Eigen::Matrix3d axes, ObbScratch& scratch) {
  double best = box_volume(points, axes);
  for (int round = 0; round < 2; ++round) {
    const Eigen::Matrix3d start = axes;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d n = start.col(k), u = start.col((k + 1) % 3), w = n.cross(u);
      scratch.plane.resize(points.size());
      for (size_t i = 0; i < points.size(); ++i) scratch.plane[i] = {points[i].dot(u), points[i].dot(w)};
      const detail::Rectangle r = detail::min_area_rectangle(scratch.plane, scratch.hull);
      if (r.area <= 0) continue;
      Eigen::Matrix3d candidate;
      candidate.col(0) = n;
      candidate.col(1) = (r.side.x() * u + r.side.y() * w).normalized();
      candidate.col(2) = n.cross(candidate.col(1));
      const double volume = box_volume(points, candidate);
      if (volume < best) {
        best = volume;
        axes = candidate;
      }
    }
  }
  return axes;
}

// Eqs. 11-14: the area-weighted centre of the surface (the vertex mean when it has no area).
Eigen::Vector3d area_weighted_centre(const Vertices& v, const Faces& faces) {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double area = 0.0;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d a = v.row(faces(f, 0)).transpose(), b = v.row(faces(f, 1)).transpose(),
                          c = v.row(faces(f, 2)).transpose();
    const double s = 0.5 * (b - a).cross(c - a).norm();
    centre += s * (a + b + c) / 3.0;
    area += s;
  }
  return area > 0 ? Eigen::Vector3d(centre / area) : Eigen::Vector3d(v.colwise().mean().transpose());
}

// A triangle's corner moments about a centre c: sum (p - c), then the upper triangle of sum (p - c)(p - c)^T, row by
// row.
using FaceMoments = std::array<double, 9>;

// The wide kernels: sum_moments and move_rows on four double lanes.
#define CLOTHCD_SIMD_KERNEL "geometry/obb_lanes.hpp"
#define CLOTHCD_SIMD_KERNEL_WIDE
#include "support/simd_versions.hpp"

// The sum of moments[faces[j]] over j < count, entry by entry: the baseline.
FaceMoments sum_moments_baseline(const FaceMoments* moments, const int* faces, size_t count) {
  FaceMoments total{};
  for (size_t j = 0; j < count; ++j)
    for (size_t k = 0; k < total.size(); ++k) total[k] += moments[faces[j]][k];
  return total;
}

// The sum of moments[faces[j]] over j < count, entry by entry, at simd_level().
FaceMoments sum_moments(const FaceMoments* moments, const int* faces, size_t count) {
  return CLOTHCD_SIMD_DISPATCH_WIDE(simd_level(), sum_moments(moments, faces, count),
                                    sum_moments_baseline(moments, faces, count));
}

// What a rigidly moving model can reuse between rebuilds: the centre of eqs. 11-14 moves with the model, and each
// triangle's corner moments about the centre only turn with the pose (p - c = R (p0 - c0), so sum (p - c) =
// R sum (p0 - c0) and sum (p - c)(p - c)^T = R [sum (p0 - c0)(p0 - c0)^T] R^T).
struct AdaptiveHints {
  Eigen::Vector3d centre;              // area-weighted centre at the current pose
  Eigen::Matrix3d rotation;            // the pose's rotation R
  const std::vector<int>* face_begin;  // faces of vertex i (each once): face_list[face_begin[i] .. face_begin[i + 1])
  const std::vector<int>* face_list;
  const std::vector<FaceMoments>* moments;  // per face, at rest
};

// The FaceMoments of the triangle with corner rows `corners` about `centre`.
FaceMoments face_moments(const Vertices& v, const int* corners, const Eigen::Vector3d& centre) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d p = v.row(corners[k]).transpose() - centre;
    sum += p;
    outer.noalias() += p * p.transpose();
  }
  return {sum.x(), sum.y(), sum.z(), outer(0, 0), outer(0, 1), outer(0, 2), outer(1, 1), outer(1, 2), outer(2, 2)};
}

// Jin et al. eqs. 11-18, then (optionally) refine_axes on S'. `scratch.keep` is left all zero on return.
Eigen::Matrix3d adaptive_axes(const Vertices& v, const Faces& faces, const ObbSettings& settings, ObbScratch& scratch,
                              const AdaptiveHints* hints = nullptr) {
  const Eigen::Index n = v.rows();
  if (n == 0) return Eigen::Matrix3d::Identity();  // e.g. a model simplified to nothing: the extents still bound it
  auto& keep = scratch.keep;
  keep.resize(static_cast<size_t>(n), 0);
  const Eigen::Vector3d centre = hints ? hints->centre : area_weighted_centre(v, faces);
  // Eqs. 15-16: s slabs of width k = (Q_max - Q_min) / s per axis; each slab keeps its vertex farthest from the centre
  // and its extremes in the two other coordinates (the slab's silhouette).
  const int s = std::clamp(settings.slabs, 1, detail::kMaxSlabs);
  std::array<int, 3 * detail::kMaxSlabs * detail::kSlabValues> best;
  detail::slab_extremes(v, centre, s, best.data());
  // S': the distinct slab winners, in order of first appearance (a repeat is written and then overwritten).
  // Raw pointers here and below: the stores through char pointers would otherwise make the compiler reload every
  // vector's data pointer after each store.
  auto& kept_index = scratch.kept_index;
  kept_index.resize(size_t(3 * s * detail::kSlabValues));
  char* const is_kept = keep.data();
  int* const kept_rows = kept_index.data();
  size_t kept_count = 0;
  for (int k = 0; k < 3 * s * detail::kSlabValues; ++k) {
    const int i = best[size_t(k)];
    if (i < 0) continue;  // an empty slab
    kept_rows[kept_count] = i;
    kept_count += !is_kept[i];
    is_kept[i] = 1;
  }
  kept_index.resize(kept_count);
  // Eqs. 17-18: mean and covariance of the corners of the triangles touching the kept set S'.
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
  long long corners = 0;
  if (hints) {  // the triangles touching S', each once, from their moments at rest
    // First the list of those faces, without branches on the data and without loads that wait for stores: a scan of
    // every face when the model has few faces, else the faces of each vertex of S' taken from the list of their first
    // corner in S'. The two orders differ, so the sums may differ in the last bits. Then the sum of their moments.
    scratch.kept_faces.resize(static_cast<size_t>(faces.rows()));
    int* const kept_faces = scratch.kept_faces.data();
    const int* const face_begin = hints->face_begin->data();
    const int* const face_list = hints->face_list->data();
    const int* const corner_rows = faces.data();
    size_t face_count = 0;
    Eigen::Index candidates = 0;
    for (size_t k = 0; k < kept_count; ++k) candidates += face_begin[kept_rows[k] + 1] - face_begin[kept_rows[k]];
    if (faces.rows() <= 2 * candidates) {
      for (Eigen::Index f = 0; f < faces.rows(); ++f) {
        const int* const c = corner_rows + 3 * f;
        kept_faces[face_count] = int(f);
        face_count += size_t(is_kept[c[0]] | is_kept[c[1]] | is_kept[c[2]]);
      }
    } else {
      for (size_t k = 0; k < kept_count; ++k) {
        const int vertex = kept_rows[k];
        for (int e = face_begin[vertex]; e < face_begin[vertex + 1]; ++e) {
          const int f = face_list[e];
          const int* const c = corner_rows + 3 * f;
          int first = c[2];
          first = is_kept[c[1]] ? c[1] : first;
          first = is_kept[c[0]] ? c[0] : first;
          kept_faces[face_count] = f;
          face_count += size_t(first == vertex);
        }
      }
    }
    const FaceMoments total = sum_moments(hints->moments->data(), kept_faces, face_count);
    corners = 3 * static_cast<long long>(face_count);
    sum = hints->rotation * Eigen::Vector3d(total[0], total[1], total[2]);
    outer << total[3], total[4], total[5], total[4], total[6], total[7], total[5], total[7], total[8];
    outer = hints->rotation * outer * hints->rotation.transpose();
  } else {
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
      if (!(keep[size_t(faces(f, 0))] | keep[size_t(faces(f, 1))] | keep[size_t(faces(f, 2))])) continue;
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d p = v.row(faces(f, k)).transpose() - centre;  // centred for round-off; same covariance
        sum += p;
        outer.noalias() += p * p.transpose();
      }
      corners += 3;
    }
  }
  if (corners == 0) {  // no faces: the kept vertices themselves
    for (Eigen::Index i = 0; i < n; ++i) {
      if (!keep[size_t(i)]) continue;
      const Eigen::Vector3d p = v.row(i).transpose() - centre;
      sum += p;
      outer.noalias() += p * p.transpose();
      ++corners;
    }
  }
  for (int i : kept_index) keep[size_t(i)] = 0;
  const Eigen::Vector3d mean = sum / double(corners);
  const Eigen::Matrix3d axes = principal_axes(outer / double(corners) - mean * mean.transpose());
  if (!settings.refine_axes) return axes;
  scratch.kept.clear();
  for (int i : kept_index) scratch.kept.push_back(v.row(i).transpose());
  return refine_axes(scratch.kept, axes, scratch);
}

// Rows [0, rows) of `from` moved by r and t into `to`: the baseline of move_rows.
void move_rows_baseline(const double* from, Eigen::Index rows, const Eigen::Matrix3d& r, const Eigen::Vector3d& t,
                        double* to) {
  for (Eigen::Index i = 0; i < rows; ++i, from += 3, to += 3) {
    for (int k = 0; k < 3; ++k) to[k] = r(k, 0) * from[0] + (r(k, 1) * from[1] + r(k, 2) * from[2]) + t[k];
  }
}

// moved = rest moved by pose (same shape). Row by row, summed in the order of the Eigen expression
// (rest R^T).rowwise() + t (bitwise the same coordinates), which evaluated the product into a heap temporary.
void move_rows(const Vertices& rest, const Eigen::Isometry3d& pose, Vertices& moved) {
  const Eigen::Matrix3d r = pose.linear();
  const Eigen::Vector3d t = pose.translation();
  CLOTHCD_SIMD_DISPATCH_WIDE(simd_level(), move_rows(rest.data(), rest.rows(), r, t, moved.data()),
                             move_rows_baseline(rest.data(), rest.rows(), r, t, moved.data()));
}

Eigen::Matrix3d tight_axes(const Vertices& vertices) {
  const ConvexHull hull = compute_convex_hull(vertices);
  if (hull.degenerate) return covariance_axes(vertices);
  Vertices points(static_cast<Eigen::Index>(hull.vertex_indices.size()), 3);
  for (size_t i = 0; i < hull.vertex_indices.size(); ++i) points.row(Eigen::Index(i)) = vertices.row(hull.vertex_indices[i]);
  // Candidate first axes: every hull face normal and every hull edge direction, sign-normalised so that the two copies
  // of an edge (one per adjacent face) coincide and are tried once.
  std::vector<Eigen::Vector3d> directions;
  auto add_direction = [&directions](Eigen::Vector3d d) {
    const double length = d.norm();
    if (length == 0) return;
    d /= length;
    const int k = std::abs(d.x()) > 0 ? 0 : (std::abs(d.y()) > 0 ? 1 : 2);
    if (d[k] < 0) d = -d;
    directions.push_back(d);
  };
  for (Eigen::Index f = 0; f < hull.faces.rows(); ++f) {
    const Eigen::Vector3d a = vertices.row(hull.faces(f, 0)).transpose(), b = vertices.row(hull.faces(f, 1)).transpose(),
                          c = vertices.row(hull.faces(f, 2)).transpose();
    add_direction((b - a).cross(c - a));
    add_direction(b - a);
    add_direction(c - b);
    add_direction(a - c);
  }
  std::sort(directions.begin(), directions.end(), [](const auto& a, const auto& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  directions.erase(std::unique(directions.begin(), directions.end(),
                               [](const auto& a, const auto& b) { return a.dot(b) > 1.0 - 1e-14; }),
                   directions.end());
  std::vector<Eigen::Vector2d> projected(static_cast<size_t>(points.rows())), scratch;
  double best_volume = std::numeric_limits<double>::infinity();
  Eigen::Matrix3d best_axes = Eigen::Matrix3d::Identity();
  for (const Eigen::Vector3d& n : directions) {
    const Eigen::Vector3d u = n.unitOrthogonal(), w = n.cross(u);
    double lo = 1e300, hi = -1e300;
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
      const Eigen::Vector3d p = points.row(i).transpose();
      projected[size_t(i)] = {p.dot(u), p.dot(w)};
      lo = std::min(lo, p.dot(n)), hi = std::max(hi, p.dot(n));
    }
    const detail::Rectangle r = detail::min_area_rectangle(projected, scratch);
    if (r.area <= 0) continue;
    const double volume = r.area * (hi - lo);
    if (volume < best_volume) {
      best_volume = volume;
      const Eigen::Vector3d side = (r.side.x() * u + r.side.y() * w).normalized();
      best_axes.col(0) = n;
      best_axes.col(1) = side;
      best_axes.col(2) = n.cross(side);
    }
  }
  // The optimum may have no face flush with a hull face: polish the winner by per-axis rectangle turns.
  std::vector<Eigen::Vector3d> hull_points(static_cast<size_t>(points.rows()));
  for (Eigen::Index i = 0; i < points.rows(); ++i) hull_points[size_t(i)] = points.row(i).transpose();
  ObbScratch polish;
  return refine_axes(hull_points, best_axes, polish);
}

}  // namespace

Obb fit_obb_to_axes(const Vertices& points, const Eigen::Matrix3d& axes) {
  Obb box;
  box.axes = axes;
  if (points.rows() == 0) return box;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector3d q = axes.transpose() * points.row(i).transpose();
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  box.center = axes * (0.5 * (lo + hi));
  box.half_extents = 0.5 * (hi - lo);
  return box;
}

void grow_obb(Obb& box, const Vertices& points) {
  const Eigen::Vector3d c = box.axes.transpose() * box.center;
  Eigen::Vector3d lo = c - box.half_extents, hi = c + box.half_extents;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector3d q = box.axes.transpose() * points.row(i).transpose();
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  box.center = box.axes * (0.5 * (lo + hi));
  box.half_extents = 0.5 * (hi - lo);
}

Obb compute_obb(const TriangleMesh& mesh, ObbMethod method, const ObbSettings& settings) {
  // The methods multiply coordinates (covariances, areas, volumes): far from magnitude 1 they run on the mesh scaled by
  // a power of two.
  if (const int exponent = check_input(mesh, "compute_obb")) {
    TriangleMesh scaled = mesh;
    scaled.vertices *= std::ldexp(1.0, -exponent);
    Obb box = compute_obb(scaled, method, settings);
    box.center *= std::ldexp(1.0, exponent);
    box.half_extents *= std::ldexp(1.0, exponent);
    return box;
  }
  ObbScratch scratch;
  switch (method) {
    case ObbMethod::Covariance:
      return fit_obb_to_axes(mesh.vertices, covariance_axes(mesh.vertices));
    case ObbMethod::FastAdaptive:
      return fit_obb_to_axes(mesh.vertices, adaptive_axes(mesh.vertices, mesh.faces, settings, scratch));
    case ObbMethod::FastAdaptiveSimplified: {
      if (mesh.face_count() == 0) return compute_obb(mesh, ObbMethod::FastAdaptive, settings);
      SimplifySettings simplify;
      simplify.target_ratio = settings.simplify_ratio;
      const TriangleMesh simplified = simplify_qem(mesh, simplify).mesh;
      return fit_obb_to_axes(mesh.vertices, adaptive_axes(simplified.vertices, simplified.faces, settings, scratch));
    }
    case ObbMethod::Tight:
      return fit_obb_to_axes(mesh.vertices, tight_axes(mesh.vertices));
  }
  throw std::invalid_argument("compute_obb: unknown method");
}

SimplifiedObb::SimplifiedObb(const TriangleMesh& original, const ObbSettings& settings) : settings_(settings) {
  (void)check_input(original, "SimplifiedObb");
  if (original.face_count() > 0) {
    SimplifySettings simplify;
    simplify.target_ratio = settings.simplify_ratio;
    simplified_ = simplify_qem(original, simplify).mesh;
  } else {
    simplified_.vertices = original.vertices;
  }
  original_vertex_count_ = original.vertex_count();
  hull_indices_ = compute_convex_hull(original.vertices).vertex_indices;
  Vertices hull_points(static_cast<Eigen::Index>(hull_indices_.size()), 3);
  for (size_t i = 0; i < hull_indices_.size(); ++i)
    hull_points.row(Eigen::Index(i)) = original.vertices.row(hull_indices_[i]);
  hull_support_ = SupportPoints(hull_points);
  rest_centre_ = area_weighted_centre(simplified_.vertices, simplified_.faces);
  // Vertex -> face adjacency of the simplified model (compressed rows; a face once per distinct corner).
  const auto distinct_corner = [this](Eigen::Index f, int k) {
    const auto& c = simplified_.faces;
    return (k < 1 || c(f, k) != c(f, 0)) && (k < 2 || c(f, k) != c(f, 1));
  };
  face_begin_.assign(static_cast<size_t>(simplified_.vertex_count()) + 1, 0);
  for (Eigen::Index f = 0; f < simplified_.face_count(); ++f)
    for (int k = 0; k < 3; ++k)
      if (distinct_corner(f, k)) ++face_begin_[size_t(simplified_.faces(f, k)) + 1];
  for (size_t i = 1; i < face_begin_.size(); ++i) face_begin_[i] += face_begin_[i - 1];
  face_list_.resize(size_t(face_begin_.back()));
  std::vector<int> fill(face_begin_.begin(), face_begin_.end() - 1);
  for (Eigen::Index f = 0; f < simplified_.face_count(); ++f)
    for (int k = 0; k < 3; ++k)
      if (distinct_corner(f, k)) face_list_[size_t(fill[size_t(simplified_.faces(f, k))]++)] = int(f);
  face_moments_.resize(static_cast<size_t>(simplified_.face_count()));
  for (Eigen::Index f = 0; f < simplified_.face_count(); ++f)
    face_moments_[size_t(f)] = face_moments(simplified_.vertices, simplified_.faces.data() + 3 * f, rest_centre_);
  moved_ = simplified_;
}

Obb SimplifiedObb::update(const Eigen::Isometry3d& pose) {
  if (!pose.matrix().allFinite()) throw std::invalid_argument("SimplifiedObb::update: non-finite pose");
  move_rows(simplified_.vertices, pose, moved_.vertices);
  const AdaptiveHints hints{pose * rest_centre_, pose.linear(), &face_begin_, &face_list_, &face_moments_};
  Obb box;
  box.axes = adaptive_axes(moved_.vertices, moved_.faces, settings_, scratch_, &hints);
  // Extents: along a world axis a the moved hull vertices project to a . (R p + t) = (R^T a) . p + a . t, so the
  // support of R^T a over the hull at rest gives them (exactly the max over every hull vertex, see SupportPoints).
  Eigen::Vector3d lo, hi;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d axis = box.axes.col(k), at_rest = pose.linear().transpose() * axis;
    const double shift = axis.dot(pose.translation());
    const auto [low, high] = hull_support_.min_max_dot(at_rest);
    hi[k] = high + shift;
    lo[k] = low + shift;
  }
  box.center = box.axes * (0.5 * (lo + hi));
  box.half_extents = 0.5 * (hi - lo);
  return box;
}

Obb SimplifiedObb::update(const Eigen::Isometry3d& pose, const Vertices& original_vertices) {
  if (!original_vertices.allFinite() || !pose.matrix().allFinite())
    throw std::invalid_argument("SimplifiedObb::update: non-finite coordinate or pose");
  if (original_vertices.rows() != original_vertex_count_)
    throw std::invalid_argument("SimplifiedObb::update: " + std::to_string(original_vertices.rows()) +
                                " vertices for a model of " + std::to_string(original_vertex_count_));
  move_rows(simplified_.vertices, pose, moved_.vertices);
  return fit_obb_to_axes(original_vertices, adaptive_axes(moved_.vertices, moved_.faces, settings_, scratch_));
}

}  // namespace clothcd::geometry

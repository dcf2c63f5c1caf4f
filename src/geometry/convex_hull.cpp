// 3-D convex hull through Qhull's reentrant C library (C. B. Barber, D. P. Dobkin, H. Huhdanpaa, "The Quickhull
// algorithm for convex hulls", ACM TOMS 1996), triangulated output ("Qt"), faces reoriented outwards here.
#include "clothcd/geometry/convex_hull.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "power_of_two_scale.hpp"

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace clothcd::geometry {
namespace {

// Every distinct row: for a hull that is not 3-D this is still a superset of the extreme points.
ConvexHull degenerate_hull(const Vertices& points) {
  ConvexHull hull;
  hull.degenerate = true;
  std::set<std::array<double, 3>> seen;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    if (seen.insert({points(i, 0), points(i, 1), points(i, 2)}).second) hull.vertex_indices.push_back(int(i));
  }
  return hull;
}

struct FileCloser {
  void operator()(FILE* f) const {
    if (f) std::fclose(f);
  }
};

}  // namespace

ConvexHull compute_convex_hull(const Vertices& points) {
  if (!points.allFinite()) throw std::invalid_argument("compute_convex_hull: non-finite coordinate");
  if (points.rows() < 4) return degenerate_hull(points);
  // Qhull squares coordinates: far from magnitude 1 it gets the points scaled by a power of two, since from about 1e155
  // its products overflow (wrong hulls, then a crash inside it from about 1e170).
  const Vertices scaled = points * std::ldexp(1.0, -detail::far_scale_exponent(points));
  std::vector<coordT> coords(scaled.data(), scaled.data() + scaled.size());
  std::unique_ptr<FILE, FileCloser> quiet(std::fopen("/dev/null", "w"));
  qhT qh_storage;
  qhT* qh = &qh_storage;
  qh_zero(qh, quiet.get());
  char flags[] = "qhull Qt";
  const int status = qh_new_qhull(qh, 3, static_cast<int>(points.rows()), coords.data(), False, flags, nullptr,
                                  quiet.get());
  ConvexHull hull;
  if (status == 0) {
    std::vector<std::array<int, 3>> triangles;
    std::vector<char> on_hull(static_cast<size_t>(points.rows()), 0);
    facetT* facet;
    FORALLfacets {
      std::array<int, 3> t{};
      int k = 0;
      vertexT* vertex;
      vertexT** vertexp;
      FOREACHvertex_(facet->vertices) {
        if (k < 3) t[size_t(k)] = qh_pointid(qh, vertex->point);
        ++k;
      }
      if (k != 3) continue;
      const Eigen::Vector3d a = scaled.row(t[0]).transpose(), b = scaled.row(t[1]).transpose(),
                            c = scaled.row(t[2]).transpose();
      const Eigen::Vector3d outward(facet->normal[0], facet->normal[1], facet->normal[2]);
      if ((b - a).cross(c - a).dot(outward) < 0) std::swap(t[1], t[2]);
      triangles.push_back(t);
      for (int i : t) on_hull[size_t(i)] = 1;
    }
    hull.faces.resize(static_cast<Eigen::Index>(triangles.size()), 3);
    for (size_t f = 0; f < triangles.size(); ++f)
      hull.faces.row(Eigen::Index(f)) << triangles[f][0], triangles[f][1], triangles[f][2];
    for (size_t i = 0; i < on_hull.size(); ++i)
      if (on_hull[i]) hull.vertex_indices.push_back(int(i));
  }
  qh_freeqhull(qh, !qh_ALL);
  int current_long = 0, total_long = 0;
  qh_memfreeshort(qh, &current_long, &total_long);
  if (status != 0 || hull.faces.rows() < 4) return degenerate_hull(points);
  return hull;
}

}  // namespace clothcd::geometry

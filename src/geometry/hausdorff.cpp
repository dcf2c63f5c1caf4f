// Two-sided sampled Hausdorff distance in the manner of Metro (P. Cignoni, C. Rocchini, R. Scopigno, "Metro: measuring
// error on simplified surfaces", 1998): samples of each surface (vertices, face centroids, random area-weighted points)
// against the exact closest point of the other surface (geometry/pair_distance.hpp: Ericson's 5.1.5), found
// through a median-split bounding volume hierarchy.
#include "clothcd/geometry/hausdorff.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "clothcd/geometry/bounding_volumes.hpp"
#include "geometry/pair_distance.hpp"

namespace clothcd::geometry {
namespace {

using Point = Eigen::Vector3d;

class TriangleTree {
 public:
  explicit TriangleTree(const TriangleMesh& mesh) : mesh_(mesh) {
    const auto n = static_cast<size_t>(mesh.face_count());
    order_.resize(n);
    centroid_.resize(n);
    for (size_t f = 0; f < n; ++f) {
      order_[f] = int(f);
      centroid_[f] = (corner(int(f), 0) + corner(int(f), 1) + corner(int(f), 2)) / 3.0;
    }
    nodes_.reserve(2 * n / kLeaf + 2);
    build(0, int(n));
  }

  [[nodiscard]] double distance(const Point& p) const {
    double best2 = std::numeric_limits<double>::infinity();
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[size_t(stack[--top])];
      if (box_distance2(node.box, p) >= best2) continue;
      if (node.count > 0) {
        for (int i = node.first; i < node.first + node.count; ++i) {
          const int f = order_[size_t(i)];
          best2 = std::min(best2, point_triangle_distance_squared(p, corner(f, 0), corner(f, 1), corner(f, 2)));
        }
        continue;
      }
      const int near = node.left, far = node.right;
      const bool swap = box_distance2(nodes_[size_t(near)].box, p) > box_distance2(nodes_[size_t(far)].box, p);
      stack[top++] = swap ? near : far;
      stack[top++] = swap ? far : near;
    }
    return std::sqrt(best2);
  }

 private:
  static constexpr int kLeaf = 4;
  struct Node {
    Aabb box;
    int left = -1, right = -1, first = 0, count = 0;  // a leaf when count > 0
  };

  [[nodiscard]] Point corner(int f, int k) const { return mesh_.vertices.row(mesh_.faces(f, k)).transpose(); }

  static double box_distance2(const Aabb& box, const Point& p) {
    return (box.min - p).cwiseMax(p - box.max).cwiseMax(0.0).squaredNorm();
  }

  int build(int first, int end) {
    const int index = int(nodes_.size());
    nodes_.emplace_back();
    Aabb box, centres;
    for (int i = first; i < end; ++i) {
      const int f = order_[size_t(i)];
      for (int k = 0; k < 3; ++k) box.expand(corner(f, k));
      centres.expand(centroid_[size_t(f)]);
    }
    nodes_[size_t(index)].box = box;
    if (end - first <= kLeaf) {
      nodes_[size_t(index)].first = first;
      nodes_[size_t(index)].count = end - first;
      return index;
    }
    int axis = 0;
    (centres.max - centres.min).maxCoeff(&axis);
    const int mid = (first + end) / 2;
    std::nth_element(order_.begin() + first, order_.begin() + mid, order_.begin() + end,
                     [&](int a, int b) { return centroid_[size_t(a)][axis] < centroid_[size_t(b)][axis]; });
    const int left = build(first, mid);
    const int right = build(mid, end);
    nodes_[size_t(index)].left = left;
    nodes_[size_t(index)].right = right;
    return index;
  }

  const TriangleMesh& mesh_;
  std::vector<int> order_;
  std::vector<Point> centroid_;
  std::vector<Node> nodes_;
};

struct OneSide {
  double max = 0.0, sum = 0.0;
  long long count = 0;
};

OneSide sample_against(const TriangleMesh& from, const TriangleTree& to, const HausdorffSettings& settings) {
  OneSide side;
  auto measure = [&](const Point& p) {
    const double d = to.distance(p);
    side.max = std::max(side.max, d);
    side.sum += d;
    ++side.count;
  };
  for (Eigen::Index v = 0; v < from.vertex_count(); ++v) measure(from.vertices.row(v).transpose());
  std::vector<double> cumulative(static_cast<size_t>(from.face_count()));
  double total = 0.0;
  for (Eigen::Index f = 0; f < from.face_count(); ++f) {
    const Point a = from.vertices.row(from.faces(f, 0)).transpose(), b = from.vertices.row(from.faces(f, 1)).transpose(),
                c = from.vertices.row(from.faces(f, 2)).transpose();
    measure((a + b + c) / 3.0);
    total += 0.5 * (b - a).cross(c - a).norm();
    cumulative[size_t(f)] = total;
  }
  if (total <= 0) return side;
  std::mt19937_64 random(settings.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < settings.samples; ++i) {
    const double pick = unit(random) * total;
    const auto f = static_cast<Eigen::Index>(
        std::min<size_t>(std::lower_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin(),
                         cumulative.size() - 1));
    const double r1 = std::sqrt(unit(random)), r2 = unit(random);
    const Point a = from.vertices.row(from.faces(f, 0)).transpose(), b = from.vertices.row(from.faces(f, 1)).transpose(),
                c = from.vertices.row(from.faces(f, 2)).transpose();
    measure((1 - r1) * a + r1 * (1 - r2) * b + r1 * r2 * c);
  }
  return side;
}

}  // namespace

HausdorffResult measure_hausdorff(const TriangleMesh& a, const TriangleMesh& b, const HausdorffSettings& settings) {
  if (a.face_count() == 0 || b.face_count() == 0) throw std::invalid_argument("measure_hausdorff: a mesh has no faces");
  for (const TriangleMesh* mesh : {&a, &b}) {
    if (!mesh->vertices.allFinite()) throw std::invalid_argument("measure_hausdorff: a coordinate is NaN or infinite");
    if (mesh->faces.minCoeff() < 0 || mesh->faces.maxCoeff() >= mesh->vertex_count())
      throw std::invalid_argument("measure_hausdorff: a face index is out of range");
  }
  if (settings.samples < 0) throw std::invalid_argument("measure_hausdorff: negative sample count");
  const TriangleTree tree_a(a), tree_b(b);
  const OneSide ab = sample_against(a, tree_b, settings);
  const OneSide ba = sample_against(b, tree_a, settings);
  HausdorffResult result;
  result.a_to_b = ab.max;
  result.b_to_a = ba.max;
  result.max = std::max(ab.max, ba.max);
  result.mean = (ab.sum + ba.sum) / double(ab.count + ba.count);
  return result;
}

double hausdorff_distance(const TriangleMesh& a, const TriangleMesh& b, const HausdorffSettings& settings) {
  return measure_hausdorff(a, b, settings).max;
}

}  // namespace clothcd::geometry

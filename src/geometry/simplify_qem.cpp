// Surface simplification by quadric error metrics: M. Garland and P. S. Heckbert, "Surface Simplification Using Quadric
// Error Metrics", SIGGRAPH 1997 (Jin et al. section 2.1, eqs. 1-5). Each vertex carries the area-weighted sum of the
// fundamental quadrics K_p = p p^T of its faces' planes; the pair (v1, v2) costs v^T (Q1 + Q2) v at the v minimising it.
// Open boundaries get penalty planes through the boundary edge, perpendicular to its face (Garland & Heckbert sec. 5).
// Pipeline: rescale and renumber along a Morton curve -> build adjacency -> quadrics -> candidate pairs (edges,
// optional close non-edge pairs) -> contract from a 4-ary heap with version stamps (stale entries are skipped) ->
// compact the result.
#include "clothcd/geometry/simplify.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "clothcd/mesh/mesh_validation.hpp"
#include "list_pool.hpp"
#include "morton_order.hpp"
#include "quaternary_heap.hpp"

namespace clothcd::geometry {
namespace {

// Q = [A b; b^T c] as 10 numbers; error(p) = p^T A p + 2 b.p + c. `area` sums the face weights (for error in distance).
struct Quadric {
  double a00 = 0, a01 = 0, a02 = 0, a11 = 0, a12 = 0, a22 = 0, b0 = 0, b1 = 0, b2 = 0, c = 0, area = 0;

  void add_plane(const Eigen::Vector3d& n, double d, double weight) {
    a00 += weight * n.x() * n.x();
    a01 += weight * n.x() * n.y();
    a02 += weight * n.x() * n.z();
    a11 += weight * n.y() * n.y();
    a12 += weight * n.y() * n.z();
    a22 += weight * n.z() * n.z();
    b0 += weight * d * n.x();
    b1 += weight * d * n.y();
    b2 += weight * d * n.z();
    c += weight * d * d;
  }
  void add(const Quadric& q) {
    a00 += q.a00, a01 += q.a01, a02 += q.a02, a11 += q.a11, a12 += q.a12, a22 += q.a22;
    b0 += q.b0, b1 += q.b1, b2 += q.b2, c += q.c, area += q.area;
  }
  [[nodiscard]] Eigen::Vector3d times_a(const Eigen::Vector3d& p) const {
    return {a00 * p.x() + a01 * p.y() + a02 * p.z(), a01 * p.x() + a11 * p.y() + a12 * p.z(),
            a02 * p.x() + a12 * p.y() + a22 * p.z()};
  }
  // In plain doubles (it runs for every pair costed; Eigen's shuffles of 3-vectors cost more than the arithmetic).
  [[nodiscard]] double error(double x, double y, double z) const {
    const double ax = a00 * x + a01 * y + a02 * z, ay = a01 * x + a11 * y + a12 * z, az = a02 * x + a12 * y + a22 * z;
    return (x * ax + y * ay + z * az) + 2.0 * (b0 * x + b1 * y + b2 * z) + c;
  }
  [[nodiscard]] double error(const Eigen::Vector3d& p) const { return error(p.x(), p.y(), p.z()); }
};

Quadric sum(const Quadric& a, const Quadric& b) {
  Quadric q = a;
  q.add(b);
  return q;
}

struct Placement {
  Eigen::Vector3d position;
  double cost = 0.0;
};

// Minimiser of q: the 3x3 system A p = -b (eq. 5) when well conditioned and the point stays near the pair, else the best
// point of the segment [pu, pv], else the best of pu, pv and their midpoint.
Placement place(const Quadric& q, const Eigen::Vector3d& pu, const Eigen::Vector3d& pv) {
  const Eigen::Vector3d mid = 0.5 * (pu + pv);
  const double c00 = q.a11 * q.a22 - q.a12 * q.a12;
  const double c01 = q.a02 * q.a12 - q.a01 * q.a22;
  const double c02 = q.a01 * q.a12 - q.a02 * q.a11;
  const double det = q.a00 * c00 + q.a01 * c01 + q.a02 * c02;
  const double trace = q.a00 + q.a11 + q.a22;
  // det / trace^3 is the product of the eigenvalue ratios: near zero for flat or crease-only neighbourhoods.
  if (trace > 0 && det > 1e-9 * trace * trace * trace) {
    // The common case, in plain doubles like Quadric::error.
    const double c11 = q.a00 * q.a22 - q.a02 * q.a02;
    const double c12 = q.a01 * q.a02 - q.a00 * q.a12;
    const double c22 = q.a00 * q.a11 - q.a01 * q.a01;
    const double x = -(c00 * q.b0 + c01 * q.b1 + c02 * q.b2) / det;
    const double y = -(c01 * q.b0 + c11 * q.b1 + c12 * q.b2) / det;
    const double z = -(c02 * q.b0 + c12 * q.b1 + c22 * q.b2) / det;
    const double dx = pv.x() - pu.x(), dy = pv.y() - pu.y(), dz = pv.z() - pu.z();
    const double mx = x - mid.x(), my = y - mid.y(), mz = z - mid.z();
    if (mx * mx + my * my + mz * mz <= dx * dx + dy * dy + dz * dz)
      return {Eigen::Vector3d(x, y, z), std::max(0.0, q.error(x, y, z))};
  }
  const Eigen::Vector3d d = pv - pu;
  const double dad = d.dot(q.times_a(d));
  if (dad > 1e-30) {
    const double slope = d.dot(q.times_a(pu)) + q.b0 * d.x() + q.b1 * d.y() + q.b2 * d.z();
    const double t = std::clamp(-slope / dad, 0.0, 1.0);
    const Eigen::Vector3d p = pu + t * d;
    return {p, std::max(0.0, q.error(p))};
  }
  Placement best{pu, q.error(pu)};
  for (const Eigen::Vector3d& p : {pv, mid}) {
    const double e = q.error(p);
    if (e < best.cost) best = {p, e};
  }
  best.cost = std::max(0.0, best.cost);
  return best;
}

// 16 bytes, so more of the heap stays in cache. The stamps are the vertex versions when the entry was pushed (16 bits: a
// wrap-around match can only let a stale entry of two live vertices through, and every popped entry is re-placed and
// re-validated anyway).
struct Candidate {
  float cost;
  int u, v;
  std::uint16_t stamp_u, stamp_v;
};
static_assert(sizeof(Candidate) == 16, "heap entries should stay 16 bytes");

struct CellKey {
  long long x, y, z;
  bool operator==(const CellKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct CellHash {
  size_t operator()(const CellKey& k) const {
    return static_cast<size_t>(k.x * 73856093LL ^ k.y * 19349663LL ^ k.z * 83492791LL);
  }
};

// A face contracted away keeps kDeadFace as its first corner.
constexpr int kDeadFace = -1;
// The version of a vertex contracted away; live versions count 0 .. kDeadVersion - 1 and wrap around.
constexpr std::uint16_t kDeadVersion = 0xFFFF;
// Room for this many more faces than at the start in each vertex's list before the list moves.
constexpr int kListSlack = 4;

class Simplifier {
 public:
  Simplifier(const TriangleMesh& mesh, const SimplifySettings& settings) : settings_(settings) {
    rescale(mesh);
    build_faces(mesh);
    classify_edges();
    build_quadrics();
  }

  SimplifyResult run(int target_faces) {
    const double bound = settings_.max_error < 0 ? -1.0 : settings_.max_error / scale_;
    push_edge_pairs();
    if (settings_.non_edge_threshold > 0) push_close_pairs(settings_.non_edge_threshold / scale_);
    SimplifyResult result;
    result.faces_before = live_faces_;
    // Stale entries pile up (each contraction re-pushes the pairs of its vertex): drop them all whenever the heap has
    // grown by a quarter since the last purge, so it stays small and cache-friendly and stale entries are not popped
    // one by one (a quarter did best on the bunny among 1/8 .. 1/2: 1/2 never purges there).
    size_t purge_at = heap_.size() + heap_.size() / 4;
    while (live_faces_ > target_faces && !heap_.empty()) {
      if (heap_.size() > purge_at) {
        heap_.retain_if([this](const Candidate& c) { return is_current(c); });
        purge_at = heap_.size() + heap_.size() / 4;
      }
      const Candidate c = heap_.pop();
      if (!is_current(c)) continue;
      // Cache misses dominate: start loading what the next candidate will read while this one is handled, and this
      // candidate's faces (its face lists were loaded by the last iteration) while its pair is placed.
      if (!heap_.empty()) {
        prefetch_vertex(heap_.top().u);
        prefetch_vertex(heap_.top().v);
      }
      prefetch_faces(c.u);
      prefetch_faces(c.v);
      const Quadric q = sum(quadric_[c.u], quadric_[c.v]);
      const Placement placement = place(q, position_[c.u], position_[c.v]);
      const double error = q.area > 0 ? std::sqrt(placement.cost / q.area) : 0.0;
      if (bound >= 0 && error > bound) continue;
      if (!contraction_is_valid(c.u, c.v, placement.position)) continue;
      contract(c.u, c.v, placement.position, q);
      if (!heap_.empty()) {
        vertex_faces_.prefetch_entries(heap_.top().u);
        vertex_faces_.prefetch_entries(heap_.top().v);
      }
      result.max_error = std::max(result.max_error, error * scale_);
      ++result.contractions;
    }
    // With only an error bound (target 0) the bound is the target.
    result.reached_target = live_faces_ <= target_faces || (target_faces == 0 && bound >= 0);
    result.mesh = compact();
    result.faces_after = static_cast<int>(result.mesh.face_count());
    return result;
  }

 private:
  // Starts loading w's quadric (its first and last bytes).
  void prefetch_quadric(int w) const {
    const char* bytes = reinterpret_cast<const char*>(&quadric_[size_t(w)]);
    __builtin_prefetch(bytes);
    __builtin_prefetch(bytes + sizeof(Quadric) - 1);
  }

  // Called once per vertex, not in a loop over {u, v}: GCC 12 at -O3 deleted that loop (no prefetch was left).
  void prefetch_vertex(int w) const {
    prefetch_quadric(w);
    __builtin_prefetch(&position_[size_t(w)]);
    vertex_faces_.prefetch_place(w);
  }

  // Starts loading the faces in v's list. An index loop: GCC 12 at -O3 deleted the same loop written as a range-for
  // over the list (no prefetch left in the object code).
  void prefetch_faces(int v) const {
    const int* list = vertex_faces_.begin(v);
    for (int k = 0, n = vertex_faces_.size(v); k < n; ++k) __builtin_prefetch(&faces_[size_t(list[k])]);
  }

  // False for a heap entry whose vertices were contracted away or changed since it was pushed (one small array, so the
  // purges' scans over the whole heap mostly hit the cache).
  [[nodiscard]] bool is_current(const Candidate& c) const {
    return (version_[size_t(c.u)] == c.stamp_u) & (version_[size_t(c.v)] == c.stamp_v);  // &: no unpredictable branch
  }
  [[nodiscard]] bool alive_vertex(int v) const { return version_[size_t(v)] != kDeadVersion; }

  void rescale(const TriangleMesh& mesh) {
    origin_ = mesh.vertices.colwise().minCoeff().transpose();
    const Eigen::Vector3d extent = mesh.vertices.colwise().maxCoeff().transpose() - origin_;
    scale_ = extent.maxCoeff() > 0 ? extent.maxCoeff() : 1.0;
    const auto n = static_cast<size_t>(mesh.vertex_count());
    std::vector<Eigen::Vector3d> unit(n);
    for (size_t i = 0; i < n; ++i) unit[i] = (mesh.vertices.row(Eigen::Index(i)).transpose() - origin_) / scale_;
    // Vertices are renumbered along a Morton curve so surface neighbours share cache lines; compact() restores a
    // numbering that does not depend on this one.
    const std::vector<int> order = detail::morton_order(unit);
    position_.resize(n);
    internal_index_.resize(n);
    for (size_t k = 0; k < n; ++k) {
      position_[k] = unit[size_t(order[k])];
      internal_index_[size_t(order[k])] = int(k);
    }
    version_.assign(n, 0);
    locked_.assign(n, 0);
    boundary_.assign(n, 0);
    parent_.resize(n);
    for (size_t i = 0; i < n; ++i) parent_[i] = static_cast<int>(i);
    mark_.assign(n, 0);
  }

  void build_faces(const TriangleMesh& mesh) {
    faces_.resize(static_cast<size_t>(mesh.face_count()));
    // Faces are stored in the order of their least (Morton-numbered) vertex, by a counting sort, for the same cache
    // locality as the vertices; compact() writes them back in the input's order.
    std::vector<int> first_slot(position_.size() + 1, 0);
    auto corners = [&](Eigen::Index f) {
      const auto& r = mesh.faces.row(f);
      return std::array<int, 3>{internal_index_[size_t(r(0))], internal_index_[size_t(r(1))],
                                internal_index_[size_t(r(2))]};
    };
    auto least_vertex = [&](Eigen::Index f) {
      const std::array<int, 3> t = corners(f);
      return size_t(std::min({t[0], t[1], t[2]}));
    };
    for (Eigen::Index f = 0; f < mesh.face_count(); ++f) ++first_slot[least_vertex(f) + 1];
    for (size_t v = 0; v < position_.size(); ++v) first_slot[v + 1] += first_slot[v];
    internal_face_.resize(faces_.size());
    for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
      const int slot = first_slot[least_vertex(f)]++;
      internal_face_[size_t(f)] = slot;
      faces_[size_t(slot)] = corners(f);
    }
    std::vector<int> valence(position_.size(), 0);
    for (auto& t : faces_) {
      if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
        t[0] = kDeadFace;
        continue;
      }
      ++live_faces_;
      for (int w : t) ++valence[size_t(w)];
    }
    for (int& room : valence) room += kListSlack;
    vertex_faces_.reset(valence);
    for (size_t f = 0; f < faces_.size(); ++f) {
      if (!alive(faces_[f])) continue;
      for (int w : faces_[f]) vertex_faces_.push_back(w, int(f));
    }
  }

  // edge_faces_[f][k]: how many live faces (up to 255: only 1, 2 and more matter) hold the edge from corner k to corner
  // k + 1 of face f. Counted per start vertex a: every face of a adds one to each of its two other corners, so a
  // neighbour's count is its edge's.
  void count_edge_faces() {
    edge_faces_.assign(faces_.size(), {0, 0, 0});
    std::vector<int> count(position_.size(), 0);
    for (size_t a = 0; a < position_.size(); ++a) {
      const auto around = vertex_faces_[int(a)];
      for (int f : around)
        for (int w : faces_[size_t(f)]) ++count[size_t(w)];
      for (int f : around) {
        const auto& t = faces_[size_t(f)];
        const int k = corner_of(t, int(a));
        edge_faces_[size_t(f)][size_t(k)] = std::uint8_t(std::min(count[size_t(t[size_t((k + 1) % 3)])], 255));
      }
      for (int f : around)
        for (int w : faces_[size_t(f)]) count[size_t(w)] = 0;
    }
  }

  // Boundary edges (one face) get penalty planes; vertices of non-manifold edges (3+ faces) never move.
  void classify_edges() {
    count_edge_faces();
    for (size_t f = 0; f < faces_.size(); ++f) {
      if (!alive(faces_[f])) continue;
      for (int k = 0; k < 3; ++k) {
        const int a = faces_[f][size_t(k)], b = faces_[f][size_t((k + 1) % 3)];
        const int count = edge_faces_[f][size_t(k)];
        if (count == 1) {
          boundary_[size_t(a)] = boundary_[size_t(b)] = 1;
          boundary_edges_.push_back({a, b, int(f)});
        } else if (count > 2) {
          locked_[size_t(a)] = locked_[size_t(b)] = 1;
        }
      }
    }
  }

  void build_quadrics() {
    quadric_.assign(position_.size(), Quadric{});
    for (size_t f = 0; f < faces_.size(); ++f) {
      if (!alive(faces_[f])) continue;
      const auto& t = faces_[f];
      const Eigen::Vector3d& p0 = position_[size_t(t[0])];
      const Eigen::Vector3d n = (position_[size_t(t[1])] - p0).cross(position_[size_t(t[2])] - p0);
      const double length = n.norm();
      if (length == 0) continue;
      Quadric q;
      q.add_plane(n / length, -n.dot(p0) / length, 0.5 * length);
      q.area = 0.5 * length;
      for (int k = 0; k < 3; ++k) quadric_[size_t(t[size_t(k)])].add(q);
    }
    for (const auto& [a, b, f] : boundary_edges_) {
      const auto& t = faces_[size_t(f)];
      const Eigen::Vector3d& pa = position_[size_t(a)];
      const Eigen::Vector3d e = position_[size_t(b)] - pa;
      const Eigen::Vector3d face_normal =
          (position_[size_t(t[1])] - position_[size_t(t[0])]).cross(position_[size_t(t[2])] - position_[size_t(t[0])]);
      Eigen::Vector3d m = e.cross(face_normal);
      const double length = m.norm();
      if (length == 0) continue;
      m /= length;
      Quadric q;
      q.add_plane(m, -m.dot(pa), settings_.boundary_weight * e.squaredNorm());
      quadric_[size_t(a)].add(q);
      quadric_[size_t(b)].add(q);
    }
  }

  // The live faces of v, dropping dead ones from its list on the way.
  detail::ListPool::View live_faces_of(int v) {
    vertex_faces_.retain_if(v, [this](int f) { return alive(faces_[size_t(f)]); });
    return vertex_faces_[v];
  }

  void push_pair(int u, int v) {
    if (locked_[size_t(u)] || locked_[size_t(v)]) return;
    const Quadric q = sum(quadric_[size_t(u)], quadric_[size_t(v)]);
    const double cost = place(q, position_[size_t(u)], position_[size_t(v)]).cost;
    heap_.push({float(cost), u, v, version_[size_t(u)], version_[size_t(v)]});
  }

  void push_edge_pairs() {
    heap_.reserve(faces_.size() * 4);
    for (size_t f = 0; f < faces_.size(); ++f) {
      if (!alive(faces_[f])) continue;
      for (int k = 0; k < 3; ++k) {
        const int a = faces_[f][size_t(k)], b = faces_[f][size_t((k + 1) % 3)];
        // Each interior edge appears in two faces: take it once, from the face where it runs upwards.
        if ((a < b) | (edge_faces_[f][size_t(k)] == 1)) {
          if (locked_[size_t(a)] || locked_[size_t(b)]) continue;
          const Quadric q = sum(quadric_[size_t(a)], quadric_[size_t(b)]);
          heap_.push_unordered({float(place(q, position_[size_t(a)], position_[size_t(b)]).cost), a, b, 0, 0});
        }
      }
    }
    heap_.heapify();
  }

  // Vertex pairs closer than `threshold` (unit-scale) that share no edge, found through a uniform grid of that cell size.
  void push_close_pairs(double threshold) {
    partners_.assign(position_.size(), {});
    std::unordered_map<CellKey, std::vector<int>, CellHash> grid;
    auto cell_of = [threshold](const Eigen::Vector3d& p) {
      return CellKey{static_cast<long long>(std::floor(p.x() / threshold)),
                     static_cast<long long>(std::floor(p.y() / threshold)),
                     static_cast<long long>(std::floor(p.z() / threshold))};
    };
    for (size_t v = 0; v < position_.size(); ++v) {
      if (!vertex_faces_.empty(int(v))) grid[cell_of(position_[v])].push_back(int(v));
    }
    for (size_t v = 0; v < position_.size(); ++v) {
      if (vertex_faces_.empty(int(v))) continue;
      mark_neighbours(int(v), ++epoch_);
      const CellKey c = cell_of(position_[v]);
      for (long long dx = -1; dx <= 1; ++dx)
        for (long long dy = -1; dy <= 1; ++dy)
          for (long long dz = -1; dz <= 1; ++dz) {
            const auto it = grid.find({c.x + dx, c.y + dy, c.z + dz});
            if (it == grid.end()) continue;
            for (int w : it->second) {
              if (w <= int(v) || mark_[size_t(w)] == epoch_) continue;
              if ((position_[size_t(w)] - position_[v]).squaredNorm() >= threshold * threshold) continue;
              partners_[v].push_back(w);
              partners_[size_t(w)].push_back(int(v));
              push_pair(int(v), w);
            }
          }
    }
  }

  void mark_neighbours(int v, unsigned value) {
    for (int f : live_faces_of(v)) {
      for (int w : faces_[size_t(f)]) {
        const unsigned old = mark_[size_t(w)];  // written back unchanged for v: a select, not a branch
        mark_[size_t(w)] = w != v ? value : old;
        prefetch_quadric(w);
        __builtin_prefetch(&position_[size_t(w)]);
      }
    }
  }

  [[nodiscard]] static bool alive(const std::array<int, 3>& t) { return t[0] != kDeadFace; }
  // Bitwise | and &, here and in the loops of the checks below: these tests go either way at random, and a
  // mispredicted branch costs more than evaluating every operand.
  [[nodiscard]] static bool has(const std::array<int, 3>& t, int v) { return (t[0] == v) | (t[1] == v) | (t[2] == v); }
  // The corner (0, 1 or 2) of t that is v, which t must have.
  [[nodiscard]] static int corner_of(const std::array<int, 3>& t, int v) { return int(t[1] == v) + 2 * int(t[2] == v); }

  // Rejects contractions that would change the topology badly or fold the surface (see simplify_qem's contract). Its
  // loops over the faces of u and v also start loading every neighbour's quadric (contract() re-costs those pairs)
  // and position (the flip check reads them).
  bool contraction_is_valid(int u, int v, const Eigen::Vector3d& p) {
    int shared = 0;
    for (int f : live_faces_of(u)) shared += has(faces_[size_t(f)], v);
    live_faces_of(v);
    // An interior edge between two boundary vertices would pinch the surface into a non-manifold vertex.
    if (shared == 2 && boundary_[size_t(u)] && boundary_[size_t(v)]) return false;
    // Link condition: the common neighbours must be exactly the apexes of the shared faces, else an edge would gain a
    // third face.
    const unsigned of_u = ++epoch_;
    const unsigned common_mark = ++epoch_;
    mark_neighbours(u, of_u);
    int common = 0;
    for (int f : vertex_faces_[v]) {
      for (int w : faces_[size_t(f)]) {
        const unsigned old = mark_[size_t(w)];
        const bool first_seen = (w != v) & (w != u) & (old == of_u);
        mark_[size_t(w)] = first_seen ? common_mark : old;
        common += int(first_seen);
        prefetch_quadric(w);
        __builtin_prefetch(&position_[size_t(w)]);
      }
    }
    if (common != shared) return false;
    return faces_stay_valid(u, v, p, common_mark) && faces_stay_valid(v, u, p, common_mark);
  }

  // The faces of `moving` that survive must keep their orientation, stay non-degenerate and not duplicate a face of
  // `other` (which happens when both apexes of a face are common neighbours, as in a tetrahedron).
  bool faces_stay_valid(int moving, int other, const Eigen::Vector3d& p, unsigned common_mark) {
    for (int f : vertex_faces_[moving]) {
      const auto& t = faces_[size_t(f)];
      if (has(t, other)) continue;
      const int k = corner_of(t, moving);
      const int a = t[size_t((k + 1) % 3)], b = t[size_t((k + 2) % 3)];
      const Eigen::Vector3d& pa = position_[size_t(a)];
      const Eigen::Vector3d& pb = position_[size_t(b)];
      const Eigen::Vector3d before = (pa - position_[size_t(moving)]).cross(pb - position_[size_t(moving)]);
      const Eigen::Vector3d after = (pa - p).cross(pb - p);
      const double after_norm2 = after.squaredNorm();
      if (after_norm2 <= 1e-30) return false;
      const double dot = before.dot(after);
      if (dot <= 0 || dot * dot < settings_.min_normal_cos * settings_.min_normal_cos * before.squaredNorm() * after_norm2)
        return false;
      if ((mark_[size_t(a)] == common_mark) & (mark_[size_t(b)] == common_mark)) {
        for (int g : vertex_faces_[other]) {
          if (has(faces_[size_t(g)], a) && has(faces_[size_t(g)], b)) return false;
        }
      }
    }
    return true;
  }

  void contract(int u, int v, const Eigen::Vector3d& p, const Quadric& q) {
    quadric_[size_t(v)] = q;
    position_[size_t(v)] = p;
    boundary_[size_t(v)] = boundary_[size_t(v)] || boundary_[size_t(u)];
    version_[size_t(u)] = kDeadVersion;
    parent_[size_t(u)] = v;
    std::uint16_t& version = version_[size_t(v)];
    version = version + 1 == kDeadVersion ? 0 : std::uint16_t(version + 1);
    // Room first: the appends below then move no list, so u's entries can be read in place.
    vertex_faces_.reserve(v, vertex_faces_.size(v) + vertex_faces_.size(u));
    for (int f : vertex_faces_[u]) {
      auto& t = faces_[size_t(f)];
      if (has(t, v)) {
        t[0] = kDeadFace;
        --live_faces_;
        continue;
      }
      for (int& w : t) w = w == u ? v : w;
      vertex_faces_.push_back(v, f);
    }
    vertex_faces_.clear(u);
    const auto faces_v = live_faces_of(v);
    // Gather the neighbours (their quadrics, mostly cold, were prefetched by contraction_is_valid's marking loops).
    // Each corner is written to the list and kept only when new (v itself is marked too, harmlessly): no branch.
    const unsigned pushed = ++epoch_;
    neighbours_.resize(3 * size_t(faces_v.end() - faces_v.begin()));
    size_t count = 0;
    for (int f : faces_v) {
      for (int w : faces_[size_t(f)]) {
        const bool fresh = (w != v) & (mark_[size_t(w)] != pushed);
        mark_[size_t(w)] = pushed;
        neighbours_[count] = w;
        count += size_t(fresh);
      }
    }
    neighbours_.resize(count);
    for (int w : neighbours_) push_pair(v, w);
    if (!partners_.empty()) requeue_partners(u, v, pushed);
  }

  int root(int v) {
    while (parent_[size_t(v)] != v) {
      parent_[size_t(v)] = parent_[size_t(parent_[size_t(v)])];
      v = parent_[size_t(v)];
    }
    return v;
  }

  // Non-edge partners of u and v now belong to v; those that became neighbours (marked `neighbour`) are edges already.
  void requeue_partners(int u, int v, unsigned neighbour) {
    auto& list = partners_[size_t(v)];
    list.insert(list.end(), partners_[size_t(u)].begin(), partners_[size_t(u)].end());
    std::vector<int>().swap(partners_[size_t(u)]);
    const unsigned seen = ++epoch_;
    size_t kept = 0;
    for (int w : list) {
      w = root(w);
      if (w == v || !alive_vertex(w) || mark_[size_t(w)] == seen) continue;
      const bool is_neighbour = mark_[size_t(w)] == neighbour;
      mark_[size_t(w)] = seen;
      list[kept++] = w;
      if (!is_neighbour) push_pair(v, w);
    }
    list.resize(kept);
  }

  TriangleMesh compact() const {
    std::vector<int> new_index(position_.size(), -1);
    int vertex_count = 0;
    int face_count = 0;
    for (int f : internal_face_) {
      if (!alive(faces_[size_t(f)])) continue;
      ++face_count;
      for (int w : faces_[size_t(f)]) {
        if (new_index[size_t(w)] < 0) new_index[size_t(w)] = vertex_count++;
      }
    }
    TriangleMesh out;
    out.vertices.resize(vertex_count, 3);
    out.faces.resize(face_count, 3);
    for (size_t v = 0; v < position_.size(); ++v) {
      if (new_index[v] >= 0) out.vertices.row(new_index[v]) = (position_[v] * scale_ + origin_).transpose();
    }
    int row = 0;
    for (int f : internal_face_) {
      if (!alive(faces_[size_t(f)])) continue;
      for (int k = 0; k < 3; ++k) out.faces(row, k) = new_index[size_t(faces_[size_t(f)][size_t(k)])];
      ++row;
    }
    return out;
  }

  SimplifySettings settings_;
  Eigen::Vector3d origin_;
  double scale_ = 1.0;
  std::vector<Eigen::Vector3d> position_;
  std::vector<int> internal_index_;  // input vertex -> its index here (Morton order)
  std::vector<Quadric> quadric_;
  std::vector<std::array<int, 3>> faces_;
  std::vector<int> internal_face_;  // input face -> its index here (ordered by least vertex)
  std::vector<std::array<std::uint8_t, 3>> edge_faces_;  // live faces per face edge at the start, at most 255
  std::vector<std::uint16_t> version_;  // kDeadVersion once contracted away
  std::vector<char> locked_, boundary_;
  std::vector<unsigned> mark_;
  unsigned epoch_ = 0;
  std::vector<int> parent_;
  std::vector<int> neighbours_;  // scratch of contract()
  detail::ListPool vertex_faces_;  // faces at each vertex; dead ones linger until live_faces_of() drops them
  std::vector<std::vector<int>> partners_;
  std::vector<std::array<int, 3>> boundary_edges_;  // a, b, face
  detail::QuaternaryHeap<Candidate> heap_;
  int live_faces_ = 0;
};

}  // namespace

SimplifyResult simplify_qem(const TriangleMesh& mesh, const SimplifySettings& settings) {
  validate_mesh(mesh, "simplify_qem");
  const int faces = static_cast<int>(mesh.face_count());
  if (settings.target_faces < 0 && settings.target_ratio < 0 && settings.max_error < 0)
    throw std::invalid_argument("simplify_qem: set target_faces, target_ratio or max_error");
  if (std::isnan(settings.target_ratio) || (settings.target_ratio >= 0 && !(settings.target_ratio <= 1 && settings.target_ratio > 0)))
    throw std::invalid_argument("simplify_qem: target_ratio must lie in (0, 1], got " +
                                std::to_string(settings.target_ratio));
  if (!(settings.non_edge_threshold >= 0) || !std::isfinite(settings.non_edge_threshold))
    throw std::invalid_argument("simplify_qem: non_edge_threshold must be finite and >= 0");
  if (!std::isfinite(settings.max_error)) throw std::invalid_argument("simplify_qem: max_error must be finite");
  int target = 0;
  if (settings.target_faces >= 0) target = std::max(target, settings.target_faces);
  if (settings.target_ratio > 0) target = std::max(target, static_cast<int>(std::ceil(settings.target_ratio * faces)));
  Simplifier simplifier(mesh, settings);
  return simplifier.run(target);
}

}  // namespace clothcd::geometry

// Discrete frame check: a uniform grid over triangle bounding boxes (Teschner et al. 2003, "Optimized spatial hashing
// for collision detection of deformable objects", with a sorted cell list instead of a hash table) and the brute-force
// reference it is tested against. Each pair is examined once, in the lowest cell of the overlap of its two cell ranges.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "clothcd/simulation/intersection_check.hpp"

namespace clothcd::simulation {
namespace {

struct Entry {
  int body = 0;  // 0 = cloth, k = obstacle k-1
  int face = 0;
  Eigen::Vector3i vertices;  // cloth: vertex indices (for adjacency); obstacles: unused
  Triangle triangle;
  Eigen::Vector3d min, max;
};

std::vector<Entry> gather(const Faces& cloth_faces, const Vertices& cloth_positions,
                          const std::vector<TriangleMesh>& obstacles) {
  if (!cloth_positions.allFinite()) throw std::invalid_argument("frame check: cloth positions are not finite");
  const auto check_indices = [](const Faces& faces, Eigen::Index vertices, const std::string& what) {
    if (faces.size() > 0 && (faces.minCoeff() < 0 || faces.maxCoeff() >= vertices))
      throw std::invalid_argument("frame check: " + what + " has a face index outside 0.." +
                                  std::to_string(vertices - 1));
  };
  check_indices(cloth_faces, cloth_positions.rows(), "the cloth");
  for (size_t k = 0; k < obstacles.size(); ++k) {
    const std::string name = "obstacle " + std::to_string(k + 1);
    if (!obstacles[k].vertices.allFinite())
      throw std::invalid_argument("frame check: " + name + " has a NaN or infinite coordinate");
    check_indices(obstacles[k].faces, obstacles[k].vertices.rows(), name);
  }
  std::vector<Entry> entries;
  auto add = [&entries](int body, int face, const Eigen::Vector3i& v, const Vertices& x) {
    Entry e;
    e.body = body;
    e.face = face;
    e.vertices = v;
    e.triangle = {x.row(v[0]).transpose(), x.row(v[1]).transpose(), x.row(v[2]).transpose()};
    e.min = e.triangle.a.cwiseMin(e.triangle.b).cwiseMin(e.triangle.c);
    e.max = e.triangle.a.cwiseMax(e.triangle.b).cwiseMax(e.triangle.c);
    entries.push_back(e);
  };
  for (Eigen::Index f = 0; f < cloth_faces.rows(); ++f) {
    add(0, static_cast<int>(f), cloth_faces.row(f).transpose(), cloth_positions);
  }
  for (size_t k = 0; k < obstacles.size(); ++k) {
    for (Eigen::Index f = 0; f < obstacles[k].faces.rows(); ++f) {
      add(static_cast<int>(k) + 1, static_cast<int>(f), obstacles[k].faces.row(f).transpose(), obstacles[k].vertices);
    }
  }
  return entries;
}

bool share_vertex(const Entry& a, const Entry& b) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (a.vertices[i] == b.vertices[j]) return true;
    }
  }
  return false;
}

/// Gap between two boxes (0 when they overlap).
double box_gap(const Entry& a, const Entry& b) {
  const Eigen::Vector3d gap = (a.min - b.max).cwiseMax(b.min - a.max).cwiseMax(0.0);
  return gap.norm();
}

/// Examines one candidate pair; the same code serves the grid and the brute force, so they agree exactly.
void examine(const Entry& a, const Entry& b, const IntersectionCheckSettings& settings, IntersectionReport& report) {
  if (a.body != 0 && b.body != 0) return;
  const bool self = a.body == 0 && b.body == 0;
  if (self && share_vertex(a, b)) return;
  const double gap = box_gap(a, b);
  if (self) {
    if (gap == 0 && triangles_intersect(a.triangle, b.triangle)) ++report.cloth_cloth_pairs;
    return;
  }
  if (gap > settings.distance_margin) return;
  const bool hit = gap == 0 && triangles_intersect(a.triangle, b.triangle);
  if (hit) {
    ++report.cloth_obstacle_pairs;
    report.min_cloth_obstacle_distance = 0;
  } else if (gap < report.min_cloth_obstacle_distance) {
    const double d = triangle_distance(a.triangle, b.triangle);
    if (d <= settings.distance_margin) report.min_cloth_obstacle_distance = std::min(report.min_cloth_obstacle_distance, d);
  }
}

double mean_edge_length(const Faces& faces, const Vertices& x) {
  double sum = 0;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) sum += (x.row(faces(f, k)) - x.row(faces(f, (k + 1) % 3))).norm();
  }
  return faces.rows() > 0 ? sum / (3.0 * faces.rows()) : 0.0;
}

struct CellEntry {
  std::int64_t key;
  int entry;
};

constexpr std::int64_t kCellRange = 1 << 20;

std::int64_t cell_key(const Eigen::Vector3i& c) {
  return ((c.x() + kCellRange) * (2 * kCellRange) + (c.y() + kCellRange)) * (2 * kCellRange) + (c.z() + kCellRange);
}

}  // namespace

IntersectionReport check_frame(const Faces& cloth_faces, const Vertices& cloth_positions,
                               const std::vector<TriangleMesh>& obstacles, const IntersectionCheckSettings& settings) {
  const std::vector<Entry> entries = gather(cloth_faces, cloth_positions, obstacles);
  IntersectionReport report;
  report.min_cloth_obstacle_distance = std::numeric_limits<double>::infinity();
  double cell = settings.cell_size > 0 ? settings.cell_size : 2.0 * mean_edge_length(cloth_faces, cloth_positions);
  if (!(cell > 0)) cell = 1.0;
  const double half_margin = 0.5 * std::max(0.0, settings.distance_margin);

  // Cell ranges of the boxes grown by half the margin, so that every pair within the margin shares a cell. Every pair
  // examined has a cloth triangle, so obstacle ranges are clipped to the cloth's: a large obstacle (or a tiny cloth)
  // would otherwise fill millions of cells.
  Eigen::Vector3d origin = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  for (const Entry& e : entries)
    if (e.body == 0) origin = origin.cwiseMin(e.min);
  std::vector<Eigen::Vector3i> lo(entries.size()), hi(entries.size());
  Eigen::Vector3i cloth_lo = Eigen::Vector3i::Constant(kCellRange), cloth_hi = Eigen::Vector3i::Constant(-kCellRange);
  std::vector<CellEntry> cells;
  for (size_t i = 0; i < entries.size(); ++i) {
    const Eigen::Vector3d a = ((entries[i].min - origin).array() - half_margin) / cell;
    const Eigen::Vector3d b = ((entries[i].max - origin).array() + half_margin) / cell;
    for (int k = 0; k < 3; ++k) {
      lo[i][k] = static_cast<int>(std::clamp(std::floor(a[k]), double(-kCellRange + 1), double(kCellRange - 1)));
      hi[i][k] = static_cast<int>(std::clamp(std::floor(b[k]), double(-kCellRange + 1), double(kCellRange - 1)));
    }
    if (entries[i].body == 0) {  // the cloth's entries come first
      cloth_lo = cloth_lo.cwiseMin(lo[i]);
      cloth_hi = cloth_hi.cwiseMax(hi[i]);
    } else {
      lo[i] = lo[i].cwiseMax(cloth_lo);
      hi[i] = hi[i].cwiseMin(cloth_hi);
    }
    for (int x = lo[i].x(); x <= hi[i].x(); ++x) {
      for (int y = lo[i].y(); y <= hi[i].y(); ++y) {
        for (int z = lo[i].z(); z <= hi[i].z(); ++z) cells.push_back({cell_key({x, y, z}), static_cast<int>(i)});
      }
    }
  }
  std::sort(cells.begin(), cells.end(),
            [](const CellEntry& a, const CellEntry& b) { return a.key != b.key ? a.key < b.key : a.entry < b.entry; });

  for (size_t begin = 0; begin < cells.size();) {
    size_t end = begin + 1;
    while (end < cells.size() && cells[end].key == cells[begin].key) ++end;
    // Entries of a cell are sorted by index and the cloth's come first: obstacle-obstacle pairs are never visited.
    for (size_t i = begin; i < end && entries[cells[i].entry].body == 0; ++i) {
      const int p = cells[i].entry;
      for (size_t j = i + 1; j < end; ++j) {
        const int q = cells[j].entry;
        if (cell_key(lo[p].cwiseMax(lo[q])) != cells[begin].key) continue;  // examined in another cell
        examine(entries[p], entries[q], settings, report);
      }
    }
    begin = end;
  }
  return report;
}

IntersectionReport check_frame_brute_force(const Faces& cloth_faces, const Vertices& cloth_positions,
                                           const std::vector<TriangleMesh>& obstacles,
                                           const IntersectionCheckSettings& settings) {
  const std::vector<Entry> entries = gather(cloth_faces, cloth_positions, obstacles);
  IntersectionReport report;
  report.min_cloth_obstacle_distance = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < entries.size(); ++i) {
    for (size_t j = i + 1; j < entries.size(); ++j) examine(entries[i], entries[j], settings, report);
  }
  return report;
}

}  // namespace clothcd::simulation

// Position-level collision response with friction and a provably terminating fail-safe: Bridson, Fedkiw and Anderson
// 2002, "Robust treatment of collisions, contact and friction for cloth animation" (inelastic impulses weighted by the
// barycentric coordinates and inverse masses, section 7.1; Coulomb friction, section 7.2; iterate detection, then a
// last-resort fail-safe, section 7.4). Our fail-safe freezes the relative motion of the offending vertices instead of
// forming rigid impact zones: simpler, and still safe because the start of the step is intersection-free.
#include "clothcd/simulation/collision_response.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "geometry/pair_distance.hpp"

namespace clothcd::simulation {
namespace {

using geometry::point_triangle_distance_squared;
using geometry::segment_segment_distance_squared;

/// The four weights of a pair: the contact vector is sum_i w_i x_i, pointing from the second primitive to the first.
std::array<double, 4> pair_weights(const Collision& c) {
  if (c.kind == PairKind::VertexFace) {
    const double w1 = c.parameters[0], w2 = c.parameters[1];
    return {1.0, -(1.0 - w1 - w2), -w1, -w2};
  }
  const double s = c.parameters[0], u = c.parameters[1];
  return {1.0 - s, s, -(1.0 - u), -u};
}

Eigen::Vector3d end_position(const VertexRef& v, const StepContext& context, const Vertices& cloth_end) {
  if (v.body == 0) return cloth_end.row(v.vertex).transpose();
  return (*context.obstacle_end)[v.body - 1].row(v.vertex).transpose();
}

Eigen::Vector3d start_position(const VertexRef& v, const StepContext& context) {
  if (v.body == 0) return context.cloth_start->row(v.vertex).transpose();
  return (*context.obstacle_start)[v.body - 1].row(v.vertex).transpose();
}

/// Distance between the pair's two primitives, with the position of the pair's i-th vertex given by `position(i)`.
template <class Position>
double primitive_distance(const Collision& c, const Position& position) {
  const Eigen::Vector3d p0 = position(0), p1 = position(1), p2 = position(2), p3 = position(3);
  if (c.kind == PairKind::EdgeEdge) return std::sqrt(segment_segment_distance_squared(p0, p1, p2, p3));
  double d = std::min({segment_segment_distance_squared(p0, p0, p1, p2), segment_segment_distance_squared(p0, p0, p2, p3),
                       segment_segment_distance_squared(p0, p0, p3, p1)});
  if ((p2 - p1).cross(p3 - p1).squaredNorm() > 0) {
    d = std::min(d, point_triangle_distance_squared(p0, p1, p2, p3, geometry::FaceRounding::Reciprocal));
  }
  return std::sqrt(d);
}

/// Contact data for a conservative report, from the end-of-step positions: the closest-point parameters (clamped
/// projections) and a normal from the second primitive to the first, oriented by the start of the step.
void rebuild_contact(Collision& c, const StepContext& context, const Vertices& cloth_end) {
  Eigen::Vector3d x[4], x0[4];
  for (int i = 0; i < 4; ++i) {
    x[i] = end_position(c.vertices[i], context, cloth_end);
    x0[i] = start_position(c.vertices[i], context);
  }
  Eigen::Vector3d n, first0, second0;
  if (c.kind == PairKind::VertexFace) {
    n = (x[2] - x[1]).cross(x[3] - x[1]);
    const double area2 = n.squaredNorm();
    double w1 = 1.0 / 3, w2 = 1.0 / 3;
    if (area2 > 0) {
      w1 = std::max(0.0, (x[0] - x[1]).cross(x[3] - x[1]).dot(n) / area2);
      w2 = std::max(0.0, (x[2] - x[1]).cross(x[0] - x[1]).dot(n) / area2);
      const double sum = w1 + w2;
      if (sum > 1) {
        w1 /= sum;
        w2 /= sum;
      }
    }
    c.parameters = {w1, w2};
    first0 = x0[0];
    second0 = (1 - w1 - w2) * x0[1] + w1 * x0[2] + w2 * x0[3];
  } else {
    n = (x[1] - x[0]).cross(x[3] - x[2]);
    c.parameters = {0.5, 0.5};
    first0 = 0.5 * (x0[0] + x0[1]);
    second0 = 0.5 * (x0[2] + x0[3]);
    if (n.squaredNorm() == 0) n = 0.5 * (x[0] + x[1] - x[2] - x[3]);
  }
  if (n.squaredNorm() == 0) n = first0 - second0;
  if (n.dot(first0 - second0) < 0) n = -n;
  c.normal = n.squaredNorm() > 0 ? n.normalized() : Eigen::Vector3d::Zero();
}

// Throws std::invalid_argument when a vertex of `c` names a body or vertex that does not exist.
void check_collision(const Collision& c, const StepContext& context) {
  for (const VertexRef& v : c.vertices) {
    const Eigen::Index count = v.body == 0 ? context.cloth_start->rows()
                               : v.body > 0 && v.body <= static_cast<int>(context.obstacle_start->size())
                                   ? (*context.obstacle_start)[static_cast<std::size_t>(v.body - 1)].rows()
                                   : -1;
    if (count < 0 || v.vertex < 0 || v.vertex >= count)
      throw std::invalid_argument("collision response: vertex " + std::to_string(v.vertex) + " of body " +
                                  std::to_string(v.body) + " does not exist");
  }
}

}  // namespace

int discard_disproved(std::vector<Collision>& collisions, const StepContext& context, const Vertices& cloth_end,
                      double thickness) {
  constexpr int kPieces = 8;  // second try: the bound on kPieces sub-intervals of the step, each m / kPieces long
  const size_t before = collisions.size();
  auto proved_apart = [&](const Collision& c) {
    if (!c.conservative) return false;
    Eigen::Vector3d x0[4], dx[4];
    for (int i = 0; i < 4; ++i) {
      x0[i] = start_position(c.vertices[i], context);
      dx[i] = end_position(c.vertices[i], context, cloth_end) - x0[i];
    }
    const int split = c.kind == PairKind::VertexFace ? 1 : 2;
    double m = 0;
    for (int i = 0; i < split; ++i) {
      for (int j = split; j < 4; ++j) m = std::max(m, (dx[i] - dx[j]).norm());
    }
    auto distance_at = [&](double t) {
      return primitive_distance(c, [&](int i) { return Eigen::Vector3d(x0[i] + t * dx[i]); });
    };
    const double limit = thickness * (1 + 1e-9) + 1e-12;
    const double d0 = distance_at(0.0), d1 = distance_at(1.0);
    if (0.5 * (d0 + d1 - m) > limit) return true;
    double previous = d0;
    for (int k = 1; k <= kPieces; ++k) {
      const double next = k == kPieces ? d1 : distance_at(static_cast<double>(k) / kPieces);
      if (0.5 * (previous + next - m / kPieces) <= limit) return false;
      previous = next;
    }
    return true;
  };
  collisions.erase(std::remove_if(collisions.begin(), collisions.end(), proved_apart), collisions.end());
  for (Collision& c : collisions) {
    if (c.conservative) rebuild_contact(c, context, cloth_end);
  }
  return static_cast<int>(before - collisions.size());
}

double start_gap(const Collision& collision, const StepContext& context) {
  const std::array<double, 4> w = pair_weights(collision);
  Eigen::Vector3d gap_vector = Eigen::Vector3d::Zero();
  for (int i = 0; i < 4; ++i) gap_vector += w[i] * start_position(collision.vertices[i], context);
  return collision.normal.dot(gap_vector);
}

void apply_impulses(const std::vector<Collision>& collisions, const StepContext& context,
                    const ResponseSettings& settings, Vertices& cloth_end) {
  const double target = settings.thickness * settings.separation;
  for (const Collision& c : collisions) {
    check_collision(c, context);
    const std::array<double, 4> w = pair_weights(c);
    std::array<double, 4> inverse_mass{};
    double denominator = 0;
    Eigen::Vector3d gap_vector = Eigen::Vector3d::Zero();
    for (int i = 0; i < 4; ++i) {
      const VertexRef& v = c.vertices[i];
      inverse_mass[i] = v.body == 0 ? context.model->inverse_mass(v.vertex) : 0.0;
      denominator += w[i] * w[i] * inverse_mass[i];
      gap_vector += w[i] * end_position(v, context, cloth_end);
    }
    if (denominator <= 0 || c.normal.squaredNorm() == 0) continue;  // nothing movable: left to the fail-safe
    const Eigen::Vector3d& n = c.normal;
    const double gap = n.dot(gap_vector);
    if (gap >= target) continue;
    const double push = target - gap;
    Eigen::Vector3d correction = (push / denominator) * n;

    // Coulomb friction: the tangential relative motion of the step shrinks by at most friction * push.
    if (settings.friction > 0) {
      Eigen::Vector3d relative = Eigen::Vector3d::Zero();
      for (int i = 0; i < 4; ++i) {
        relative += w[i] * (end_position(c.vertices[i], context, cloth_end) - start_position(c.vertices[i], context));
      }
      const Eigen::Vector3d tangential = relative - n.dot(relative) * n;
      const double length = tangential.norm();
      if (length > 0) {
        const double fraction = std::min(1.0, settings.friction * push / length);
        correction -= (fraction / denominator) * tangential;
      }
    }
    for (int i = 0; i < 4; ++i) {
      if (inverse_mass[i] > 0) cloth_end.row(c.vertices[i].vertex) += (w[i] * inverse_mass[i]) * correction.transpose();
    }
  }
}

int FailSafe::absorb(const std::vector<Collision>& collisions, const StepContext& context) {
  int changed = 0;
  for (const Collision& c : collisions) {
    check_collision(c, context);
    int target = 0;
    for (const VertexRef& v : c.vertices) {
      if (v.body > 0 && (*context.obstacles)[v.body - 1].moves_during(context.step)) target = std::max(target, v.body);
      if (v.body == 0) target = std::max(target, group_[v.vertex]);
    }
    for (const VertexRef& v : c.vertices) {
      // Groups only escalate (free -> static -> carried), which bounds the number of rounds.
      if (v.body == 0 && group_[v.vertex] < target) {
        group_[v.vertex] = target;
        ++changed;
      }
      if (v.body == 0 && group_[v.vertex] < 0) {
        group_[v.vertex] = 0;
        ++changed;
      }
    }
  }
  return changed;
}

void FailSafe::apply(const StepContext& context, Vertices& cloth_end) const {
  for (size_t v = 0; v < group_.size(); ++v) {
    if (group_[v] < 0) continue;
    const Eigen::Vector3d start = context.cloth_start->row(static_cast<Eigen::Index>(v)).transpose();
    const Eigen::Vector3d end = group_[v] == 0 ? start : (*context.obstacles)[group_[v] - 1].carry(start, context.step);
    cloth_end.row(static_cast<Eigen::Index>(v)) = end.transpose();
  }
}

int FailSafe::grouped_vertices() const {
  return static_cast<int>(std::count_if(group_.begin(), group_.end(), [](int g) { return g >= 0; }));
}

void sort_collisions(std::vector<Collision>& collisions) {
  // The key of each collision is packed once, then the keys are sorted and the collisions moved once into their places.
  // A word holds a vertex reference (body and vertex index, both >= 0 and below 2^31, so the word orders like the
  // pair); the kind goes into the top bit of the first word.
  struct Key {
    std::array<std::uint64_t, 4> words;
    double toi;
    std::uint32_t index;
  };
  std::vector<Key> keys(collisions.size());
  for (size_t i = 0; i < collisions.size(); ++i) {
    const Collision& c = collisions[i];
    Key& k = keys[i];
    for (int j = 0; j < 4; ++j) {
      k.words[j] = (static_cast<std::uint64_t>(static_cast<std::uint32_t>(c.vertices[j].body)) << 32) |
                   static_cast<std::uint32_t>(c.vertices[j].vertex);
    }
    k.words[0] |= static_cast<std::uint64_t>(c.kind == PairKind::EdgeEdge) << 63;
    k.toi = c.toi;
    k.index = static_cast<std::uint32_t>(i);
  }
  std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
    for (int w = 0; w < 4; ++w) {
      if (a.words[w] != b.words[w]) return a.words[w] < b.words[w];
    }
    return a.toi < b.toi;
  });
  std::vector<Collision> sorted;
  sorted.reserve(collisions.size());
  for (const Key& k : keys) sorted.push_back(collisions[k.index]);
  collisions.swap(sorted);
}

}  // namespace clothcd::simulation

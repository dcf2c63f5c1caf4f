#include "clothcd/simulation/contact_memory.hpp"

#include <algorithm>
#include <tuple>

namespace clothcd::simulation {
namespace {

/// The order of sort_collisions without the toi: kind, then the four (body, vertex) references.
bool pair_before(const Collision& a, const Collision& b) {
  auto key = [](const Collision& c) {
    return std::make_tuple(c.kind, c.vertices[0].body, c.vertices[0].vertex, c.vertices[1].body, c.vertices[1].vertex,
                           c.vertices[2].body, c.vertices[2].vertex, c.vertices[3].body, c.vertices[3].vertex);
  };
  return key(a) < key(b);
}

}  // namespace

void ContactMemory::remember(const std::vector<Collision>& collisions) {
  merged_.clear();
  merged_.reserve(contacts_.size() + collisions.size());
  auto old = contacts_.begin();
  auto found = collisions.begin();
  while (old != contacts_.end() && found != collisions.end()) {
    if (pair_before(*old, *found)) {
      merged_.push_back(*old++);
      continue;
    }
    if (!pair_before(*found, *old)) ++old;  // the same pair: the new record replaces the old one
    merged_.push_back(*found++);
  }
  merged_.insert(merged_.end(), old, contacts_.end());
  merged_.insert(merged_.end(), found, collisions.end());
  contacts_.swap(merged_);
}

void ContactMemory::forget_distant(const StepContext& context, double reach) {
  contacts_.erase(std::remove_if(contacts_.begin(), contacts_.end(),
                                 [&](const Collision& c) { return !(start_gap(c, context) <= reach); }),
                  contacts_.end());
}

}  // namespace clothcd::simulation

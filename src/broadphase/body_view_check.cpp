// The broad phase's check of a body's data at its entry points (body_view_check.hpp).
#include "broadphase/body_view_check.hpp"

#include <stdexcept>
#include <string>

namespace clothcd::broadphase {

void detail::check_view(const BodyView& view, bool needs_bvh) {
  if (view.topology == nullptr || view.boxes == nullptr || (needs_bvh && view.bvh == nullptr)) {
    throw std::invalid_argument("broad phase: body " + std::to_string(view.body) + " is missing its data");
  }
  if (needs_bvh && view.bvh->nodes().empty()) {
    throw std::invalid_argument("broad phase: the hierarchy of body " + std::to_string(view.body) + " is not built");
  }
}

}  // namespace clothcd::broadphase

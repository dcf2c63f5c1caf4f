#pragma once
/// @file
/// Contacts remembered from step to step. A cloth resting on a body meets the same pairs every step: gravity and the
/// springs push it back within the thickness, the detector reports thousands of contacts, and the impulses need several
/// detect() rounds to settle them. Re-applying the remembered contacts' impulses to the next step's predicted positions
/// before the first detection (a warm start) resolves most of them in advance. It only changes where the cloth is
/// predicted to go; the detection that follows is what keeps the step intersection-free.

#include <vector>

#include "clothcd/detection/collision.hpp"
#include "clothcd/simulation/collision_response.hpp"

namespace clothcd::simulation {

/// The pairs reported in recent steps, in the canonical order of sort_collisions, one record per pair.
/// Threads: const member functions may run on several threads at once; any other call needs the object to itself.
class ContactMemory {
 public:
  /// Adds collisions (sorted by sort_collisions, at most one per pair, as CollisionDetector reports them); a pair
  /// already remembered takes the new contact data.
  void remember(const std::vector<Collision>& collisions);

  /// Forgets the pairs whose gap along their contact normal at the start of the step exceeds `reach`.
  void forget_distant(const StepContext& context, double reach);

  /// The remembered pairs.
  [[nodiscard]] const std::vector<Collision>& contacts() const { return contacts_; }

 private:
  std::vector<Collision> contacts_;
  std::vector<Collision> merged_;  // scratch for remember()
};

}  // namespace clothcd::simulation

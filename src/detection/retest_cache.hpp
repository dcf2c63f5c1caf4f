#pragma once
// What the detector keeps of its last completed call to recognise a re-test of the same step
// (DetectorSettings::reuse_unchanged): the cloth positions of that call, and which vertices moved since.
#include <cstdint>
#include <vector>

#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::detail {

/// The cloth positions of the last completed call, and the vertices a repeated step moved.
class RetestCache {
 public:
  /// True when a call with the cloth at `start`/`end` repeats the last completed one's step with few vertices moved:
  /// the same start positions and at most a quarter of the end positions changed (then moved() flags them). The
  /// caller checks the rest (obstacles unchanged, reuse enabled, no culler).
  bool repeats_last_step(const Vertices& start, const Vertices& end);

  /// Per cloth vertex, 1 where the last repeats_last_step() found its end position changed.
  [[nodiscard]] const std::vector<std::uint8_t>& moved() const { return moved_; }
  /// The last completed call's cloth start positions.
  [[nodiscard]] const Vertices& start() const { return start_; }
  /// The last completed call's cloth end positions.
  [[nodiscard]] const Vertices& end() const { return end_; }

  /// Keeps `start`/`end` as the last completed call's positions (swapped in, no copy; the arguments get the old ones).
  void remember(Vertices& start, Vertices& end);
  /// Forgets the last call (until the next remember()).
  void forget() { has_last_ = false; }

 private:
  bool has_last_ = false;
  Vertices start_, end_;
  std::vector<std::uint8_t> moved_;
};

}  // namespace clothcd::detail

#pragma once
// Checks that two detectors reported the same collisions, field by field and in the same order.

#include <catch2/catch.hpp>

#include <vector>

#include "clothcd/detection/collision.hpp"

namespace clothcd::test {

/// The same collisions in the same order: kinds, vertices, times of impact, parameters, normals and flags bit for bit.
inline void check_same(const std::vector<Collision>& found, const std::vector<Collision>& reference) {
  REQUIRE(found.size() == reference.size());
  for (std::size_t i = 0; i < found.size(); ++i) {
    const Collision& a = found[i];
    const Collision& b = reference[i];
    CHECK(a.kind == b.kind);
    for (int k = 0; k < 4; ++k) {
      CHECK(a.vertices[k].body == b.vertices[k].body);
      CHECK(a.vertices[k].vertex == b.vertices[k].vertex);
    }
    CHECK(a.toi == b.toi);
    CHECK(a.parameters == b.parameters);
    CHECK(a.normal == b.normal);
    CHECK(a.conservative == b.conservative);
  }
}

}  // namespace clothcd::test

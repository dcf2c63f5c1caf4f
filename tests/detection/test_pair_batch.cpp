// The detector's in-place reuse of a call's pairs (detail::replace_moved): on seeded random batches, the result must be
// exactly the unmoved pairs (with their work) plus the fresh ones, whether the fresh pairs are fewer than, as many as
// or more than the pairs they replace, and the positions to test must be exactly the fresh ones, vertex-face first.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <vector>

#include "detection/pair_batch.hpp"

using clothcd::PairKind;
using clothcd::VertexRef;
using clothcd::detail::BatchPair;
using clothcd::detail::PairBatch;

namespace {

using Key = std::array<std::int32_t, 5>;  // kind, then the four fields

Key key_of(const BatchPair& p) {
  return {static_cast<std::int32_t>(p.kind), p.fields[0], p.fields[1], p.fields[2], p.fields[3]};
}

// A pair whose four fields are its vertex references' indices: the vertex (or edge) fields a and b name vertices a
// and b of its bodies, and the other two references are a + 1 and b + 1 (enough for the moved test).
BatchPair random_pair(std::mt19937& rng, int vertices) {
  std::uniform_int_distribution<int> vertex(0, vertices - 2);
  std::uniform_int_distribution<int> body(0, 2);
  BatchPair p;
  p.kind = rng() % 2 ? PairKind::VertexFace : PairKind::EdgeEdge;
  p.fields = {body(rng), vertex(rng), body(rng), vertex(rng)};
  return p;
}

std::array<VertexRef, 4> refs_of(const BatchPair& p) {
  const auto& f = p.fields;
  return {VertexRef{f[0], f[1]}, VertexRef{f[0], f[1] + 1}, VertexRef{f[2], f[3]}, VertexRef{f[2], f[3] + 1}};
}

bool has_moved_cloth_vertex(const BatchPair& p, const std::vector<std::uint8_t>& moved) {
  for (const VertexRef& r : refs_of(p))
    if (r.body == 0 && moved[static_cast<std::size_t>(r.vertex)]) return true;
  return false;
}

void add_to(clothcd::broadphase::CandidateSet& set, const BatchPair& p) {
  const auto& f = p.fields;
  if (p.kind == PairKind::VertexFace) set.vertex_face.push_back({f[0], f[1], f[2], f[3]});
  else set.edge_edge.push_back({f[0], f[1], f[2], f[3]});
}

}  // namespace

TEST_CASE("in-place reuse keeps the unmoved pairs' work and places exactly the fresh pairs", "[detection][reuse]") {
  std::mt19937 rng(77);
  constexpr int kVertices = 40;
  int fewer = 0, more = 0;
  for (int round = 0; round < 300; ++round) {
    // A batch of distinct pairs with work: keep and a result toi that identify the pair.
    std::set<Key> seen;
    PairBatch batch;
    const int count = static_cast<int>(rng() % 60);
    while (static_cast<int>(batch.pairs.size()) < count) {
      const BatchPair p = random_pair(rng, kVertices);
      if (seen.insert(key_of(p)).second) batch.pairs.push_back(p);
    }
    batch.refs.resize(batch.size());
    batch.keep.resize(batch.size());
    batch.results.resize(batch.size());
    std::map<Key, std::pair<std::uint8_t, double>> work;
    for (std::size_t i = 0; i < batch.size(); ++i) {
      batch.refs[i] = refs_of(batch.pairs[i]);
      batch.keep[i] = static_cast<std::uint8_t>(rng() % 2);
      batch.results[i].toi = static_cast<double>(i) / 64.0;
      work[key_of(batch.pairs[i])] = {batch.keep[i], batch.results[i].toi};
    }
    std::vector<std::uint8_t> moved(kVertices, 0);
    for (int k = static_cast<int>(rng() % 6); k > 0; --k) moved[rng() % kVertices] = 1;

    // Fresh pairs: each has a moved cloth vertex (as the restricted search finds them), none repeated.
    clothcd::broadphase::CandidateSet fresh;
    std::set<Key> expected_fresh;
    const int wanted = static_cast<int>(rng() % 30);
    for (int tries = 0; tries < 2000 && static_cast<int>(expected_fresh.size()) < wanted; ++tries) {
      const BatchPair p = random_pair(rng, kVertices);
      if (has_moved_cloth_vertex(p, moved) && expected_fresh.insert(key_of(p)).second) add_to(fresh, p);
    }
    std::sort(fresh.vertex_face.begin(), fresh.vertex_face.end());  // any order; vertex-face first as the search gives
    std::set<Key> expected_kept;
    int holes = 0;
    for (const BatchPair& p : batch.pairs) {
      if (has_moved_cloth_vertex(p, moved)) ++holes;
      else expected_kept.insert(key_of(p));
    }
    fewer += static_cast<int>(expected_fresh.size()) < holes;
    more += static_cast<int>(expected_fresh.size()) > holes;

    const std::vector<std::size_t> todo = clothcd::detail::replace_moved(batch, moved, fresh);
    REQUIRE(batch.refs.size() == batch.size());
    REQUIRE(batch.keep.size() == batch.size());
    REQUIRE(batch.results.size() == batch.size());
    REQUIRE(batch.size() == expected_kept.size() + expected_fresh.size());
    std::set<Key> got_fresh;
    bool edge_edge_seen = false;
    for (const std::size_t i : todo) {
      REQUIRE(i < batch.size());
      got_fresh.insert(key_of(batch.pairs[i]));
      if (batch.pairs[i].kind == PairKind::EdgeEdge) edge_edge_seen = true;
      else CHECK_FALSE(edge_edge_seen);  // vertex-face positions first
    }
    CHECK(got_fresh == expected_fresh);
    CHECK(todo.size() == expected_fresh.size());
    std::set<std::size_t> todo_set(todo.begin(), todo.end());
    std::set<Key> got_kept;
    for (std::size_t i = 0; i < batch.size(); ++i) {
      if (todo_set.count(i)) continue;
      const Key k = key_of(batch.pairs[i]);
      got_kept.insert(k);
      CHECK(batch.keep[i] == work[k].first);
      if (batch.keep[i]) CHECK(batch.results[i].toi == work[k].second);
      const std::array<VertexRef, 4> refs = refs_of(batch.pairs[i]);
      for (int r = 0; r < 4; ++r) {
        CHECK(batch.refs[i][r].body == refs[r].body);
        CHECK(batch.refs[i][r].vertex == refs[r].vertex);
      }
    }
    CHECK(got_kept == expected_kept);
  }
  CHECK(fewer > 5);  // both ways of balancing the places are exercised
  CHECK(more > 5);
}

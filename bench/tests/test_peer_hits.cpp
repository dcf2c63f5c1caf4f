// The peer's hits file is read into the same order-free keys as our own collisions.
#include <catch2/catch.hpp>

#include <fstream>
#include <stdexcept>

#include "bench_util.hpp"
#include "ipctk_peer.hpp"

using clothcd::bench::CollisionKey;
using clothcd::bench::read_peer_hits;

TEST_CASE("peer hits: vertex-face and edge-edge lines become sorted keys with the earliest toi") {
  const clothcd::bench::ScratchFolder scratch("peer-hits-test");
  const auto file = scratch.path() / "hits.txt";
  std::ofstream(file) << "ee 9 8 3 2 0.5\nvf 7 4 0.25\nee 1 0 6 5 0.75\n";
  double earliest = -1;
  const std::vector<CollisionKey> hits = read_peer_hits(file, earliest);
  CHECK(hits == std::vector<CollisionKey>{{0, 1, 5, 6}, {2, 3, 8, 9}, {7, 4, -1, -1}});
  CHECK(earliest == 0.25);
}

TEST_CASE("peer hits: an empty file has no hits and toi 1, and a malformed line names the file and line") {
  const clothcd::bench::ScratchFolder scratch("peer-hits-test");
  const auto file = scratch.path() / "hits.txt";
  std::ofstream(file) << "";
  double earliest = -1;
  CHECK(read_peer_hits(file, earliest).empty());
  CHECK(earliest == 1);
  std::ofstream(file) << "vf 1 2 0.5\nee 1 2 3 0.5\n";
  CHECK_THROWS_WITH(read_peer_hits(file, earliest), Catch::Contains("hits.txt:2"));
  std::ofstream(file) << "xx 1 2 0.5\n";
  CHECK_THROWS_AS(read_peer_hits(file, earliest), std::runtime_error);
}

// The state section's comparisons: the peer's contacts in the same canonical keys as ours, and each difference
// decided exactly.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <stdexcept>

#include "bench_util.hpp"
#include "state_differences.hpp"

using clothcd::bench::ContactKey;
using clothcd::bench::FacePair;

TEST_CASE("state differences: the peer's contact lines become canonical sorted keys") {
  const clothcd::bench::ScratchFolder scratch("state-differences-test");
  const auto file = scratch.path() / "contacts.txt";
  std::ofstream(file) << "fv 7 9 4 5\nee 9 8 3 2\nev 1 6 5\nvv 4 2\n";
  CHECK(clothcd::bench::read_peer_contacts(file) ==
        std::vector<ContactKey>{{0, 2, 4, -1, -1}, {1, 1, 5, 6, -1}, {2, 2, 3, 8, 9}, {3, 7, 4, 5, 9}});
  std::ofstream(file) << "vv 1 2\nee 1 2 3\n";
  CHECK_THROWS_WITH(clothcd::bench::read_peer_contacts(file), Catch::Contains("contacts.txt:2"));
  std::ofstream(file) << "vv 1 2 3\n";
  CHECK_THROWS_AS(clothcd::bench::read_peer_contacts(file), std::runtime_error);
}

TEST_CASE("state differences: a contact on one side only gets its exact distance against d") {
  clothcd::Vertices positions(4, 3);
  positions << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.25, 0.25, 0.5;
  const std::vector<ContactKey> ours{{3, 3, 0, 1, 2}}, peer{{1, 3, 0, 1, -1}};
  const auto differences = clothcd::bench::contact_differences(ours, peer, positions, 0.55);
  REQUIRE(differences.size() == 2);
  CHECK(differences[0].ours);
  CHECK(differences[0].distance == Approx(0.5));
  CHECK(differences[0].exact_below);
  CHECK_FALSE(differences[1].ours);
  CHECK(differences[1].distance == Approx(std::sqrt(0.25 * 0.25 + 0.5 * 0.5)));
  CHECK_FALSE(differences[1].exact_below);
}

TEST_CASE("state differences: a face pair on one side only is decided by the exact reference") {
  clothcd::Vertices positions(6, 3);
  positions << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.2, 0.2, -1, 0.2, 0.2, 1, 2, 2, 0;
  clothcd::Faces faces(2, 3);
  faces << 0, 1, 2, 3, 4, 5;
  const auto differences =
      clothcd::bench::face_pair_differences({}, std::vector<FacePair>{{0, 1}}, faces, positions);
  REQUIRE(differences.size() == 1);
  CHECK_FALSE(differences[0].ours);
  CHECK(differences[0].exact_intersects);
}

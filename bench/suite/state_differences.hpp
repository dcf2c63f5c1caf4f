#pragma once
/// @file
/// The state benchmark's side-by-side checks: our closest-feature contacts against the IPC Toolkit's active set, and
/// our intersecting face pairs against CGAL's, each difference with its exact answer (GMP).

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "clothcd/detection/face_intersection.hpp"
#include "clothcd/detection/proximity.hpp"
#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::bench {

/// A contact in one form for both sides: its ContactKind (as an int) and its vertices, canonical (each edge's and the
/// face's vertices ascending, the smaller edge of an edge-edge contact first, the smaller vertex of a vertex-vertex
/// contact first), unused entries -1.
using ContactKey = std::array<int, 5>;

/// The name of a ContactKind as the reports write it: vv, ve, ee, vf.
[[nodiscard]] std::string contact_kind_name(int kind);

/// The key of one of our contacts (cloth vertices only: a state's mesh is one body).
[[nodiscard]] ContactKey contact_key(const FeatureContact& contact);

/// Our contacts' keys, sorted.
[[nodiscard]] std::vector<ContactKey> contact_keys(const std::vector<FeatureContact>& contacts);

/// Reads the contacts bench/peers/ipctk_state.py writes (`vv A B`, `ev V E0 E1`, `ee A0 A1 B0 B1`, `fv V F0 F1 F2`)
/// as sorted keys. Throws std::runtime_error naming the file on a malformed line.
[[nodiscard]] std::vector<ContactKey> read_peer_contacts(const std::filesystem::path& file);

/// A contact one side has and the other has not, with the exact distance of its features.
struct ContactDifference {
  ContactKey key{};             ///< The contact.
  bool ours = false;            ///< Only we report it (else only the peer).
  double distance = 0;          ///< Its features' exact distance, rounded.
  bool exact_below = false;     ///< Exactly closer than the asked distance.
  /// Edge-edge: the edges are nearly parallel by the IPC Toolkit's mollifier rule (|ea x eb|^2 < 1e-3 |ea|^2 |eb|^2,
  /// on these positions), for which it keeps an edge-edge contact whatever the closest features.
  bool nearly_parallel = false;
};

/// The contacts in exactly one of `ours` and `peer` (both sorted), ours first, each with its exact distance at
/// `positions` against `distance`.
[[nodiscard]] std::vector<ContactDifference> contact_differences(const std::vector<ContactKey>& ours,
                                                                 const std::vector<ContactKey>& peer,
                                                                 const Vertices& positions, double distance);

/// A face pair (smaller face first).
using FacePair = std::array<int, 2>;

/// Our intersecting face pairs, sorted.
[[nodiscard]] std::vector<FacePair> face_pairs(const std::vector<FaceIntersection>& intersections);

/// A face pair one side reports as intersecting and the other does not, with the exact answer.
struct FacePairDifference {
  FacePair faces{};          ///< The pair.
  bool ours = false;         ///< Only we report it (else only the peer).
  bool exact_intersects = false;  ///< The library's rational reference test says they intersect.
};

/// The pairs in exactly one of `ours` and `peer` (both sorted), ours first, each decided by the rational reference.
[[nodiscard]] std::vector<FacePairDifference> face_pair_differences(const std::vector<FacePair>& ours,
                                                                    const std::vector<FacePair>& peer,
                                                                    const Faces& faces, const Vertices& positions);

}  // namespace clothcd::bench

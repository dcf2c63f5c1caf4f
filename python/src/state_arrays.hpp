#pragma once
// The records of the detector's state queries (proximity, minimum distance, intersections, closest-feature contacts)
// as NumPy columns, and proximity columns back as records for closest_feature_contacts.

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>

#include <tuple>
#include <vector>

#include "arrays.hpp"
#include "clothcd/detection/face_intersection.hpp"
#include "clothcd/detection/proximity.hpp"

namespace clothcd::python {

/// A NumPy array of T owning its memory.
template <class T>
using NumpyArray = nb::ndarray<nb::numpy, T>;

/// Proximity records as columns: kind (n,) uint8 (0 vertex-face, 1 edge-edge), bodies (n, 4), vertices (n, 4),
/// distance (n,), parameters (n, 2), direction (n, 3), type (n,) uint8 (DistanceType's value).
using ProximityColumns = std::tuple<NumpyArray<std::uint8_t>, NumpyArray<std::int32_t>, NumpyArray<std::int32_t>,
                                    NumpyArray<double>, NumpyArray<double>, NumpyArray<double>,
                                    NumpyArray<std::uint8_t>>;

/// `pairs` as columns (see ProximityColumns).
[[nodiscard]] ProximityColumns proximity_columns(const std::vector<Proximity>& pairs);

/// FaceIntersection records as columns: bodies (n, 2), faces (n, 2), edge_face (n,) uint8, edge_vertices (n, 2) (of
/// body bodies[edge_face]), edge_parameter (n,), face_weights (n, 2), coplanar (n,) uint8.
using IntersectionColumns = std::tuple<NumpyArray<std::int32_t>, NumpyArray<std::int32_t>, NumpyArray<std::uint8_t>,
                                       NumpyArray<std::int32_t>, NumpyArray<double>, NumpyArray<double>,
                                       NumpyArray<std::uint8_t>>;

/// `intersections` as columns (see IntersectionColumns).
[[nodiscard]] IntersectionColumns intersection_columns(const std::vector<FaceIntersection>& intersections);

/// FeatureContact records as columns: kind (n,) uint8 (ContactKind's value), bodies (n, 4), vertices (n, 4) (unused
/// entries -1), distance (n,).
using ContactColumns =
    std::tuple<NumpyArray<std::uint8_t>, NumpyArray<std::int32_t>, NumpyArray<std::int32_t>, NumpyArray<double>>;

/// `contacts` as columns (see ContactColumns).
[[nodiscard]] ContactColumns contact_columns(const std::vector<FeatureContact>& contacts);

/// Proximity records from the columns closest_feature_contacts reads (kind, bodies, vertices, distance, type; the
/// closest points and direction play no part there and are left zero). Throws std::invalid_argument on mismatched
/// lengths, an unknown kind or a distance type that is not one of the kind's.
[[nodiscard]] std::vector<Proximity> proximities_from_columns(
    const nb::ndarray<const std::uint8_t, nb::c_contig, nb::device::cpu>& kind, const IntArray& bodies,
    const IntArray& vertices, const nb::ndarray<const double, nb::c_contig, nb::device::cpu>& distance,
    const nb::ndarray<const std::uint8_t, nb::c_contig, nb::device::cpu>& type);

}  // namespace clothcd::python

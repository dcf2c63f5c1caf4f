#pragma once
// Private: the orientation determinants evaluated exactly on floating-point expansions (geometry/expansion.hpp), the
// stage between the floating-point filter and GMP. Exact differences (two-sum), exact products (two-product) and
// exact sums are exact only away from underflow and overflow: every coordinate must be zero or of magnitude in
// [2^-300, 2^300]. Then each coordinate is a multiple of 2^-352 and every exact product of three is a multiple of
// 2^-1056 (no product loses bits to underflow), while no intermediate exceeds 2^910 (none overflows, and the
// splitting of two-product stays finite). Outside that range the functions do not decide.
#include <Eigen/Core>
#include <optional>

namespace clothcd::geometry::detail {

/// The smallest non-zero coordinate magnitude the expansion predicates accept.
inline constexpr double kExpansionSmallest = 0x1p-300;
/// The largest coordinate magnitude the expansion predicates accept.
inline constexpr double kExpansionLargest = 0x1p300;

/// orient3d's exact sign (geometry/orientation.hpp), or nothing when a coordinate is outside the accepted range or
/// the determinant's expansion would outgrow Expansion::kCapacity.
[[nodiscard]] std::optional<int> expansion_orient3d(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                                                    const Eigen::Vector3d& r, const Eigen::Vector3d& s);

/// orient2d's exact sign (geometry/orientation.hpp), or nothing when a coordinate is outside the accepted range.
[[nodiscard]] std::optional<int> expansion_orient2d(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                                                    const Eigen::Vector3d& r, int drop_axis);

}  // namespace clothcd::geometry::detail

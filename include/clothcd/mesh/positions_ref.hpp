#pragma once
/// @file
/// A read-only view of #V x 3 positions where the caller keeps them, whatever their memory layout: what the per-step
/// entry points (CollisionDetector::detect, CollisionDetector::set_obstacle_positions) take, so that row-major
/// Vertices, column-major Eigen::MatrixXd / Eigen::MatrixX3d (libigl, IPC Toolkit), blocks of them and an Eigen::Map
/// of a buffer of one's own (a NumPy array from Python) are all read in place.
///
/// Eigen::Ref cannot do this: a Ref of one storage order copies a matrix of the other order into a hidden temporary.

#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd {

/// #V x 3 read-only doubles with any row and column strides (counted in doubles).
using PositionsMap =
    Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3>, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>;

namespace detail {
/// The row-major copy a PositionsRef makes of an expression that has no memory (empty otherwise). A base class of
/// PositionsRef, listed before the view, so that it exists when the view onto it is made.
struct EvaluatedPositions {
  Vertices evaluated;  ///< The evaluated expression, or empty.
};
}  // namespace detail

/// Read-only #V x 3 positions in the caller's memory, usable as an Eigen matrix (rows(), row(i), data(), ...).
/// Binds without a copy (data() is the caller's) to every Eigen object of doubles with memory of its own: Vertices,
/// Eigen::MatrixXd, Eigen::MatrixX3d, Eigen::Map with any strides (an xyzw buffer, a 3 x N matrix's transpose), blocks
/// and Eigen::Ref of them. An expression with no memory (`x + dt * v`) is evaluated once into a row-major buffer the
/// view owns. Like Eigen::Ref and std::string_view, it must not outlive what it views: take it as a parameter
/// (`const PositionsRef&`). Throws std::invalid_argument when the matrix does not have 3 columns.
/// Threads: a view is read-only and may be read from several threads at once.
class PositionsRef : private detail::EvaluatedPositions, public PositionsMap {
 public:
  /// Views `positions` (any Eigen matrix, map, block or expression of doubles with 3 columns).
  template <class Derived>
  PositionsRef(const Eigen::DenseBase<Derived>& positions)  // NOLINT(google-explicit-constructor): binds like Eigen::Ref
      : detail::EvaluatedPositions{evaluate(checked(positions.derived()))},
        PositionsMap(view(positions.derived(), evaluated)) {}

  PositionsRef(const PositionsRef&) = delete;             ///< Not copyable: a copy could point into a dead buffer.
  PositionsRef& operator=(const PositionsRef&) = delete;  ///< Not assignable.

 private:
  template <class Derived>
  static constexpr bool has_memory = (Derived::Flags & Eigen::DirectAccessBit) != 0;

  template <class Derived>
  static const Derived& checked(const Derived& positions) {
    static_assert(std::is_same_v<typename Derived::Scalar, double>,
                  "positions are doubles: convert with .cast<double>() first");
    static_assert(Derived::ColsAtCompileTime == Eigen::Dynamic || Derived::ColsAtCompileTime == 3,
                  "positions have 3 columns (x, y, z)");
    if (positions.cols() != 3) {
      throw std::invalid_argument("positions: expected #V x 3, got " + std::to_string(positions.rows()) + " x " +
                                  std::to_string(positions.cols()));
    }
    return positions;
  }

  template <class Derived>
  static Vertices evaluate(const Derived& positions) {
    if constexpr (has_memory<Derived>) {
      return Vertices();
    } else {
      return positions;
    }
  }

  // PositionsMap is column-major: its outer stride steps from column to column, its inner stride from row to row.
  template <class Derived>
  static PositionsMap view(const Derived& positions, const Vertices& evaluated) {
    if constexpr (has_memory<Derived>) {
      const Eigen::Index outer = positions.outerStride(), inner = positions.innerStride();
      return Derived::IsRowMajor ? PositionsMap(positions.data(), positions.rows(), 3, {inner, outer})
                                 : PositionsMap(positions.data(), positions.rows(), 3, {outer, inner});
    } else {
      return PositionsMap(evaluated.data(), evaluated.rows(), 3, {1, 3});
    }
  }
};

}  // namespace clothcd

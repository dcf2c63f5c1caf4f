#pragma once
// NumPy arrays in and out of the extension: (N, 3) float64 / int32 inputs checked with clear ValueErrors (positions
// viewed where they are, or copied where the library keeps them), and outputs that own their memory.

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>

#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "clothcd/mesh/positions_ref.hpp"
#include "clothcd/mesh/triangle_mesh.hpp"

namespace clothcd::python {

namespace nb = nanobind;

/// A C-contiguous float64 array on the CPU (NumPy converts other dtypes and orders when it must).
using DoubleArray = nb::ndarray<const double, nb::c_contig, nb::device::cpu>;
/// A float64 array on the CPU with any strides (NumPy converts other dtypes).
using PositionsArray = nb::ndarray<const double, nb::device::cpu>;
/// A C-contiguous int32 array on the CPU.
using IntArray = nb::ndarray<const int, nb::c_contig, nb::device::cpu>;

/// Throws std::invalid_argument unless `array` is (N, 3) (N >= 0).
template <class Array>
void require_n_by_3(const Array& array, const char* what) {
  if (array.ndim() != 2 || array.shape(1) != 3)
    throw std::invalid_argument(std::string(what) + ": expected an (N, 3) array, got " + std::to_string(array.ndim()) +
                                " dimensions" + (array.ndim() == 2 ? " of width " + std::to_string(array.shape(1)) : ""));
}

/// An (N, 3) float64 array as Vertices (a copy: for what the library keeps, such as a mesh).
inline Vertices to_vertices(const DoubleArray& array, const char* what) {
  require_n_by_3(array, what);
  Vertices out(static_cast<Eigen::Index>(array.shape(0)), 3);
  if (out.size() > 0) std::memcpy(out.data(), array.data(), sizeof(double) * static_cast<std::size_t>(out.size()));
  return out;
}

/// An (N, 3) float64 array viewed where it is, with its strides (C order, Fortran order, a slice): no copy.
inline PositionsMap positions_view(const PositionsArray& array, const char* what) {
  require_n_by_3(array, what);
  // PositionsMap's outer stride steps from column to column, its inner stride from row to row.
  return PositionsMap(array.data(), static_cast<Eigen::Index>(array.shape(0)), 3,
                      {static_cast<Eigen::Index>(array.stride(1)), static_cast<Eigen::Index>(array.stride(0))});
}

/// An (N, 3) int32 array as Faces.
inline Faces to_faces(const IntArray& array, const char* what) {
  require_n_by_3(array, what);
  Faces out(static_cast<Eigen::Index>(array.shape(0)), 3);
  if (out.size() > 0) std::memcpy(out.data(), array.data(), sizeof(int) * static_cast<std::size_t>(out.size()));
  return out;
}

/// A NumPy array that takes over `values` (shape given; the product must equal values.size()).
template <class T>
nb::ndarray<nb::numpy, T> to_numpy(std::vector<T>&& values, std::initializer_list<std::size_t> shape) {
  auto* owned = new std::vector<T>(std::move(values));
  nb::capsule owner(owned, [](void* p) noexcept { delete static_cast<std::vector<T>*>(p); });
  return nb::ndarray<nb::numpy, T>(owned->data(), shape.size(), shape.begin(), owner);
}

/// A row-major Eigen matrix (Vertices or Faces) as a new (N, 3) NumPy array.
template <class Matrix>
auto matrix_to_numpy(const Matrix& matrix) {
  using T = typename Matrix::Scalar;
  std::vector<T> values(matrix.data(), matrix.data() + matrix.size());
  return to_numpy(std::move(values), {static_cast<std::size_t>(matrix.rows()), 3});
}

}  // namespace clothcd::python

// PositionsRef: every Eigen layout of #V x 3 doubles is viewed in place (the view's data() is the caller's and its
// strides walk the caller's memory), expressions are evaluated, and a matrix without 3 columns is refused.
#include <catch2/catch.hpp>

#include <vector>

#include "clothcd/mesh/positions_ref.hpp"

using namespace clothcd;

namespace {

// Whether the view was made of `positions` in place, and reads the same values.
template <class Matrix>
bool views_in_place(const PositionsRef& view, const Matrix& positions) {
  return view.data() == positions.data() && view.rows() == positions.rows() && view == positions;
}

Vertices numbered(Eigen::Index rows) {
  Vertices v(rows, 3);
  for (Eigen::Index i = 0; i < v.size(); ++i) v.data()[i] = 0.5 * static_cast<double>(i) - 7.0;
  return v;
}

}  // namespace

TEST_CASE("positions ref views row-major, column-major and mapped positions in place", "[mesh][positions]") {
  const Vertices row_major = numbered(17);
  CHECK(views_in_place(row_major, row_major));

  const Eigen::MatrixXd column_major = row_major;
  CHECK(views_in_place(column_major, column_major));
  const Eigen::MatrixX3d column_major_3 = row_major;
  CHECK(views_in_place(column_major_3, column_major_3));

  // A caller's buffer of xyzw rows (a padded GPU-style layout) mapped with its strides.
  std::vector<double> xyzw(4 * 17, -1.0);
  for (int v = 0; v < 17; ++v)
    for (int k = 0; k < 3; ++k) xyzw[4 * v + k] = row_major(v, k);
  const Eigen::Map<const Vertices, 0, Eigen::OuterStride<4>> padded(xyzw.data(), 17, 3);
  CHECK(views_in_place(padded, padded));
  CHECK(PositionsRef(padded) == row_major);

  // A 3 x N matrix (one column per vertex) seen through its transpose, and a block of rows.
  const Eigen::Matrix3Xd columns = row_major.transpose();
  CHECK(views_in_place(columns.transpose(), columns.transpose()));
  CHECK(views_in_place(column_major.middleRows(3, 9), column_major.middleRows(3, 9)));
  CHECK(views_in_place(row_major.middleRows(3, 9), row_major.middleRows(3, 9)));

  // A Map of a plain xyz buffer: what the Python package passes for a NumPy array.
  const Eigen::Map<const Vertices> mapped(row_major.data(), 17, 3);
  CHECK(views_in_place(mapped, mapped));

  const Vertices empty(0, 3);
  CHECK(PositionsRef(empty).rows() == 0);
}

TEST_CASE("positions ref reads a row-major view with row stride 3 and a column-major one with row stride 1",
          "[mesh][positions]") {
  const Vertices row_major = numbered(5);
  const Eigen::MatrixXd column_major = row_major;
  const PositionsRef a(row_major), b(column_major);
  CHECK(a.innerStride() == 3);
  CHECK(a.outerStride() == 1);
  CHECK(b.innerStride() == 1);
  CHECK(b.outerStride() == 5);
}

TEST_CASE("positions ref evaluates an expression into a buffer of its own", "[mesh][positions]") {
  const Vertices x = numbered(9);
  const Vertices v = numbered(9).reverse();
  const PositionsRef sum(x + 0.25 * v);
  CHECK(sum.data() != x.data());
  CHECK(sum.data() != v.data());
  const Vertices expected = x + 0.25 * v;
  CHECK(sum == expected);
}

TEST_CASE("positions ref refuses a matrix without 3 columns", "[mesh][positions]") {
  const Eigen::MatrixXd two_columns = Eigen::MatrixXd::Zero(4, 2);
  CHECK_THROWS_AS(PositionsRef(two_columns), std::invalid_argument);
  CHECK_THROWS_WITH(PositionsRef(Eigen::MatrixXd::Zero(4, 5)), Catch::Contains("4 x 5"));
}

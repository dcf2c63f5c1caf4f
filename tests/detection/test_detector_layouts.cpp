// CollisionDetector takes positions in any layout (PositionsRef): row-major Vertices, a column-major Eigen::MatrixXd, a
// padded xyzw buffer, a 3 x N matrix's transpose and an expression give the same collisions and counts call after
// call (a re-test of the step and a moving obstacle included). The entry points take the view, so no temporary
// Vertices is made on the way in (tests/mesh/test_positions_ref.cpp checks that the view reads in place).
#include <catch2/catch.hpp>

#include <random>
#include <type_traits>
#include <vector>

#include "clothcd/detection/collision_detector.hpp"
#include "clothcd/mesh/mesh_generators.hpp"
#include "detection/same_collisions.hpp"

using namespace clothcd;
using clothcd::test::check_same;

namespace {

using PaddedRows = Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>;

struct Call {
  std::vector<Collision> collisions;
  DetectionStats stats;
};

// Three calls on a cloth falling onto a sphere and crumpling: a step, a re-test of it with a few end positions moved,
// then the next step with the sphere moved by set_obstacle_positions. Every position goes in as `view(store(x))`.
template <class Store, class View>
std::vector<Call> run_steps(Store store, View view) {
  TriangleMesh cloth = make_grid(9, 9, 1.6, 1.6);
  cloth.vertices.col(1).array() += 0.62;
  const TriangleMesh sphere = make_uv_sphere(0.6, 10, 6);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> jitter(-0.03, 0.03);
  Vertices start = cloth.vertices, end = cloth.vertices;
  for (Eigen::Index v = 0; v < end.rows(); ++v) {
    end(v, 1) -= 0.12 + 0.1 * std::cos(3.0 * start(v, 0));
    for (int k = 0; k < 3; ++k) end(v, k) += jitter(rng);
  }

  DetectorSettings settings;
  settings.thickness = 0.005;
  CollisionDetector detector(cloth.faces, static_cast<int>(cloth.vertex_count()), settings);
  const int body = detector.add_obstacle(sphere);
  std::vector<Call> calls;
  const auto detect = [&] {
    const auto x0 = store(start);
    const auto x1 = store(end);
    calls.push_back({detector.detect(view(x0), view(x1)), detector.stats()});
  };
  detect();
  for (Eigen::Index v : {3, 17, 40}) end(v, 1) += 0.02;
  detect();
  CHECK(calls.back().stats.reused > 0);
  const Vertices lifted = (sphere.vertices.rowwise() + Eigen::RowVector3d(0.0, 0.05, 0.0)).eval();
  {
    const auto o0 = store(sphere.vertices);
    const auto o1 = store(lifted);
    detector.set_obstacle_positions(body, view(o0), view(o1));
  }
  start = end;
  end.col(1).array() -= 0.05;
  detect();
  return calls;
}

void check_same_calls(const std::vector<Call>& found, const std::vector<Call>& reference) {
  REQUIRE(found.size() == reference.size());
  for (std::size_t i = 0; i < found.size(); ++i) {
    check_same(found[i].collisions, reference[i].collisions);
    CHECK(found[i].stats.candidates_vertex_face == reference[i].stats.candidates_vertex_face);
    CHECK(found[i].stats.candidates_edge_edge == reference[i].stats.candidates_edge_edge);
    CHECK(found[i].stats.culled == reference[i].stats.culled);
    CHECK(found[i].stats.reused == reference[i].stats.reused);
  }
}

const auto as_is = [](const auto& positions) -> const auto& { return positions; };

}  // namespace

TEST_CASE("the detector's per-step entry points take positions views", "[detection][positions]") {
  using Detect = const std::vector<Collision>& (CollisionDetector::*)(const PositionsRef&, const PositionsRef&);
  using SetPositions = void (CollisionDetector::*)(int, const PositionsRef&, const PositionsRef&);
  STATIC_REQUIRE(std::is_same_v<decltype(&CollisionDetector::detect), Detect>);
  STATIC_REQUIRE(std::is_same_v<decltype(&CollisionDetector::set_obstacle_positions), SetPositions>);
}

TEST_CASE("detection gives the same collisions for positions in every layout", "[detection][positions]") {
  const std::vector<Call> reference = run_steps([](const Vertices& x) { return x; }, as_is);
  std::size_t collisions = 0;
  for (const Call& call : reference) collisions += call.collisions.size();
  REQUIRE(collisions > 0);

  SECTION("column-major Eigen::MatrixXd") {
    check_same_calls(run_steps([](const Vertices& x) { return Eigen::MatrixXd(x); }, as_is), reference);
  }
  SECTION("column-major Eigen::MatrixX3d") {
    check_same_calls(run_steps([](const Vertices& x) { return Eigen::MatrixX3d(x); }, as_is), reference);
  }
  SECTION("a padded xyzw buffer") {
    const auto padded = [](const Vertices& x) {
      PaddedRows rows = PaddedRows::Constant(x.rows(), 4, -1e300);
      rows.leftCols<3>() = x;
      return rows;
    };
    check_same_calls(run_steps(padded, [](const PaddedRows& rows) { return rows.leftCols<3>(); }), reference);
  }
  SECTION("a mapped buffer") {
    const auto buffer = [](const Vertices& x) { return std::vector<double>(x.data(), x.data() + x.size()); };
    const auto map = [](const std::vector<double>& b) {
      return Eigen::Map<const Vertices>(b.data(), static_cast<Eigen::Index>(b.size() / 3), 3);
    };
    check_same_calls(run_steps(buffer, map), reference);
  }
  SECTION("the transpose of a 3 x N matrix") {
    const auto columns = [](const Vertices& x) { return Eigen::Matrix3Xd(x.transpose()); };
    check_same_calls(run_steps(columns, [](const Eigen::Matrix3Xd& c) { return c.transpose(); }), reference);
  }
  SECTION("an expression") {
    check_same_calls(run_steps([](const Vertices& x) { return x; }, [](const Vertices& x) { return 1.0 * x; }),
                     reference);
  }
}

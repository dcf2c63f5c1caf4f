// Thread independence at the sizes where the work is split: a cloth large enough for the parallel hierarchy build
// and for the self search's node-pair tasks must give the same collisions, in the same order and to the bit, on one
// thread and on several, with an obstacle and without.
#include <catch2/catch.hpp>

#include <optional>
#include <random>
#include <vector>

#include <tbb/global_control.h>

#include "clothcd/detection/collision_detector.hpp"
#include "detection/same_collisions.hpp"
#include "clothcd/mesh/mesh_generators.hpp"

using namespace clothcd;

namespace {

// A 100 x 100 sheet (19,602 triangles) with a little seeded roughness, each vertex then moved by up to 0.8 edge
// lengths: many self-collision candidates and collisions.
struct CrumplingSheet {
  TriangleMesh cloth = make_grid(100, 100, 1.0, 1.0);
  Vertices start, end;

  CrumplingSheet() {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> roughness(-0.002, 0.002), move(-0.008, 0.008);
    start = cloth.vertices;
    for (Eigen::Index v = 0; v < start.rows(); ++v) start(v, 1) += roughness(rng);
    end = start;
    for (Eigen::Index i = 0; i < end.size(); ++i) end.data()[i] += move(rng);
  }
};

std::vector<Collision> detect_with(const CrumplingSheet& sheet, bool with_obstacle, std::optional<int> threads) {
  DetectorSettings settings;
  settings.parallel = threads.has_value();
  std::optional<tbb::global_control> limit;
  if (threads) limit.emplace(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(*threads));
  CollisionDetector detector(sheet.cloth.faces, static_cast<int>(sheet.cloth.vertex_count()), settings);
  if (with_obstacle) detector.add_obstacle(make_uv_sphere(0.3, 48, 32));
  return detector.detect(sheet.start, sheet.end);
}

}  // namespace

TEST_CASE("a large cloth's collisions do not depend on the number of threads", "[detection][parallel]") {
  const CrumplingSheet sheet;
  const bool with_obstacle = GENERATE(false, true);
  const std::vector<Collision> serial = detect_with(sheet, with_obstacle, std::nullopt);
  REQUIRE(serial.size() > 100);
  for (const int threads : {1, 2, 4}) {
    INFO("threads " << threads);
    test::check_same(detect_with(sheet, with_obstacle, threads), serial);
  }
}

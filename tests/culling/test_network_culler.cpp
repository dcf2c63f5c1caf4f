// Network culling in the CCD stage: the detector in Network mode finds exactly the collisions of Filters and None
// modes, with the pair network or any other PairCuller (one that drops or keeps everything included); the culled set
// is always inside the combined filters' (even when the network is told to drop everything); bad models are clear
// errors; `clothcd ccd --filter network` has no false negatives.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <tuple>

#include "../broadphase/broadphase_scenes.hpp"
#include "clothcd/ccd/ccd.hpp"
#include "clothcd/culling/network_culler.hpp"
#include "clothcd/detection/collision_detector.hpp"
#include "clothcd/detection/pair_culler.hpp"
#include "clothcd/mesh/mesh_generators.hpp"
#include "support/test_support.hpp"

using namespace clothcd;
using learning::default_network_model_dir;
using learning::NetworkCuller;
using learning::NetworkCullingStats;

namespace {

// A culler that gives every pair the same verdict.
class SameVerdict final : public PairCuller {
 public:
  explicit SameVerdict(CullVerdict verdict) : verdict_(verdict) {}
  std::unique_ptr<Scratch> make_scratch() const override { return std::make_unique<Scratch>(); }
  void cull(const ccd::PairBlock& block, Scratch&, CullVerdict* verdicts) const override {
    std::fill(verdicts, verdicts + block.size(), verdict_);
  }

 private:
  CullVerdict verdict_;
};

using Key = std::tuple<int, int, int, int, int, int, int, int, int, double>;

std::vector<Key> detect_keys(const TriangleMesh& cloth, const TriangleMesh& obstacle, const Vertices& end,
                             DetectorSettings settings, DetectionStats* stats = nullptr) {
  CollisionDetector detector(cloth.faces, static_cast<int>(cloth.vertex_count()), settings);
  detector.add_obstacle(obstacle);
  std::vector<Key> keys;
  for (const Collision& c : detector.detect(cloth.vertices, end)) {
    keys.emplace_back(static_cast<int>(c.kind), c.vertices[0].body, c.vertices[0].vertex, c.vertices[1].body,
                      c.vertices[1].vertex, c.vertices[2].body, c.vertices[2].vertex, c.vertices[3].body,
                      c.vertices[3].vertex, c.toi);
  }
  if (stats) *stats = detector.stats();
  return keys;
}

// Seeded random pairs in the unit cube moving by up to `motion`: a mix of colliding and separated pairs.
std::vector<ccd::CcdQuery> random_queries(std::size_t count, double motion, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0), d(-motion, motion);
  std::vector<ccd::CcdQuery> queries(count);
  for (std::size_t i = 0; i < count; ++i) {
    ccd::CcdQuery& q = queries[i];
    q.kind = i % 2 ? PairKind::EdgeEdge : PairKind::VertexFace;
    for (int k = 0; k < 4; ++k) {
      q.start[k] = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 0.3;
      q.end[k] = q.start[k] + Eigen::Vector3d(d(rng), d(rng), d(rng));
    }
  }
  return queries;
}

}  // namespace

TEST_CASE("network culling finds exactly the collisions of the filters and of no culling", "[detection][network]") {
  const unsigned seed = GENERATE(1u, 2u, 3u);
  const double thickness = GENERATE(0.0, 0.01);
  std::mt19937 rng(seed);
  TriangleMesh cloth = make_grid(10, 10, 1.6, 1.6);
  cloth.vertices.col(1).array() += 0.62;
  const TriangleMesh obstacle = make_uv_sphere(0.6, 12, 8);
  Vertices end = test::jitter(cloth.vertices, 0.04, rng);
  for (Eigen::Index v = 0; v < end.rows(); ++v) end(v, 1) -= 0.1 + 0.1 * std::cos(3.0 * cloth.vertices(v, 0));

  DetectorSettings settings;
  settings.thickness = thickness;
  settings.culling = CullingMode::None;
  const std::vector<Key> none = detect_keys(cloth, obstacle, end, settings);
  settings.culling = CullingMode::Filters;
  DetectionStats filters_stats;
  const std::vector<Key> filters = detect_keys(cloth, obstacle, end, settings, &filters_stats);
  settings.culling = CullingMode::Network;
  settings.culler = learning::load_network_culler();
  DetectionStats network_stats;
  const std::vector<Key> network = detect_keys(cloth, obstacle, end, settings, &network_stats);
  settings.parallel = false;
  const std::vector<Key> serial = detect_keys(cloth, obstacle, end, settings);
  settings.parallel = true;
  // Whatever a culler says, the collisions stay the same: the filters confirm its drops.
  DetectionStats drop_stats, keep_stats;
  settings.culler = std::make_shared<SameVerdict>(CullVerdict::Drop);
  const std::vector<Key> drop_all = detect_keys(cloth, obstacle, end, settings, &drop_stats);
  settings.culler = std::make_shared<SameVerdict>(CullVerdict::Keep);
  const std::vector<Key> keep_all = detect_keys(cloth, obstacle, end, settings, &keep_stats);

  REQUIRE_FALSE(none.empty());
  CHECK(filters == none);
  CHECK(network == none);
  CHECK(serial == network);
  CHECK(drop_all == none);
  CHECK(keep_all == none);
  CHECK(drop_stats.culled == filters_stats.culled);
  CHECK(drop_stats.network_dropped == filters_stats.culled);
  CHECK(keep_stats.culled == 0);
  const long candidates = network_stats.candidates_vertex_face + network_stats.candidates_edge_edge;
  CHECK(network_stats.culled <= filters_stats.culled);
  CHECK(network_stats.culled >= network_stats.network_dropped);
  CHECK(network_stats.network_dropped + network_stats.network_overruled + network_stats.network_kept <= candidates);
  // The network's stages are timed inside the culling stage.
  CHECK(network_stats.network_ms + network_stats.network_filters_ms <= network_stats.culling_ms);
  CHECK(network_stats.network_dropped > 0);  // the network is at work here
  CHECK(filters_stats.network_dropped == 0);
}

TEST_CASE("network culling on a random triangle soup obstacle (degenerate faces)", "[detection][network]") {
  std::mt19937 rng(7);
  const TriangleMesh soup = test::random_soup(60, 80, rng);
  TriangleMesh cloth = make_grid(8, 8, 1.0, 1.0);
  cloth.vertices.col(0).array() += 0.5;
  cloth.vertices.col(2).array() += 0.5;
  cloth.vertices.col(1).array() += 0.55;
  Vertices end = test::jitter(cloth.vertices, 0.05, rng);
  end.col(1).array() -= 0.3;
  DetectorSettings settings;
  settings.culling = CullingMode::None;
  const std::vector<Key> none = detect_keys(cloth, soup, end, settings);
  settings.culling = CullingMode::Network;
  settings.culler = learning::load_network_culler();
  CHECK(detect_keys(cloth, soup, end, settings) == none);
  REQUIRE_FALSE(none.empty());
}

TEST_CASE("the network only culls what the combined filters cull, even told to drop everything",
          "[detection][network]") {
  std::mt19937 rng(11);
  const std::vector<ccd::CcdQuery> queries = random_queries(9000, 0.2, rng);  // more than two chunks
  const ccd::CcdSettings settings{};
  NetworkCuller culler;
  std::vector<std::uint8_t> keep, keep_serial;
  const NetworkCullingStats stats = culler.cull(queries, settings, true, keep);
  culler.cull(queries, settings, false, keep_serial);
  CHECK(keep == keep_serial);
  REQUIRE(keep.size() == queries.size());
  CHECK(stats.dropped + stats.overruled + stats.checked + stats.kept == static_cast<long>(queries.size()));
  long colliding = 0;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const bool filters_cull = ccd::combined_filters_cull(queries[i], settings);
    if (!keep[i]) CHECK(filters_cull);
    if (ccd::continuous_collision(queries[i], settings).hit) {
      ++colliding;
      CHECK(keep[i] == 1);
    }
  }
  REQUIRE(colliding > 0);

  culler.set_operating_point({1.0, 1.0});  // a network that drops every pair it is not certain about
  const NetworkCullingStats reckless = culler.cull(queries, settings, true, keep);
  CHECK(reckless.overruled > 0);
  CHECK(reckless.overruled >= colliding - reckless.kept);
  for (std::size_t i = 0; i < queries.size(); ++i) {
    if (!keep[i]) CHECK(ccd::combined_filters_cull(queries[i], settings));
    if (culler.decisions()[i] == learning::PairDecision::Drop && keep[i]) {
      CHECK_FALSE(ccd::combined_filters_cull(queries[i], settings));
    }
  }

  // Confirming with the primitives' normals as well (the detector's default) culls exactly the pairs that filter
  // culls among those the network does not keep, and still no colliding pair.
  const ccd::ProjectionFilterOptions normals{true};
  culler.set_operating_point({1.0, 1.0});
  culler.cull(queries, settings, false, keep, normals);
  long more = 0;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const bool with_normals = ccd::nonpenetration_filter_culls(queries[i], settings) ||
                              ccd::projection_filter_culls(queries[i], settings, normals);
    const bool kept = culler.decisions()[i] == learning::PairDecision::Keep;
    CHECK(keep[i] == (kept || !with_normals ? 1 : 0));
    more += with_normals && !ccd::combined_filters_cull(queries[i], settings) && !kept;
  }
  CHECK(more > 0);  // the normals do add culls here
}

TEST_CASE("network culling rejects missing and bad models", "[detection][network][errors]") {
  const TriangleMesh cloth = make_grid(4, 4);
  const int n = static_cast<int>(cloth.vertex_count());
  DetectorSettings settings;
  settings.culling = CullingMode::Network;
  CHECK_THROWS_WITH(CollisionDetector(cloth.faces, n, settings), Catch::Contains("culler"));
  CHECK_THROWS_WITH(learning::attach_network_culler(settings, "/nonexistent/clothcd-model"),
                    Catch::Contains("/nonexistent/clothcd-model"));

  test::TempDir dir;
  const std::filesystem::path model = dir / "model";
  std::filesystem::create_directories(model);
  std::filesystem::copy_file(std::filesystem::path(default_network_model_dir()) / "card.json", model / "card.json");
  std::ifstream xml(std::filesystem::path(default_network_model_dir()) / "network.xml");
  std::stringstream text;
  text << xml.rdbuf();
  test::write_file(model / "network.xml", text.str().substr(0, text.str().size() / 2));
  CHECK_THROWS_AS(learning::load_network_culler(model.string()), std::runtime_error);
  CHECK_THROWS_WITH(learning::load_network_culler(model.string()), Catch::Contains("network.xml"));

  learning::attach_network_culler(settings, "");  // the committed default model
  CHECK_NOTHROW(CollisionDetector(cloth.faces, n, settings));
}

TEST_CASE("clothcd ccd --filter network has no false negatives on generated queries", "[detection][network][cli]") {
  // Coordinates k / 64 are exact in the CSV's rational form and in double, so the exact reference is the truth.
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> coordinate(0, 24), motion(-12, 12);
  test::TempDir dir;
  std::filesystem::create_directories(dir / "vertex-face");
  std::ostringstream csv;
  long truth_colliding = 0;
  const int count = 300;
  for (int q = 0; q < count; ++q) {
    ccd::CcdQuery query;
    std::array<std::array<int, 3>, 8> points{};
    for (int k = 0; k < 4; ++k) {
      for (int a = 0; a < 3; ++a) {
        points[k][a] = coordinate(rng);
        points[k + 4][a] = points[k][a] + motion(rng);
        query.start[k][a] = points[k][a] / 64.0;
        query.end[k][a] = points[k + 4][a] / 64.0;
      }
    }
    const int truth = ccd::exact_collision_reference(query) ? 1 : 0;
    truth_colliding += truth;
    for (const auto& p : points) csv << p[0] << ",64," << p[1] << ",64," << p[2] << ",64," << truth << '\n';
  }
  REQUIRE(truth_colliding > 0);
  test::write_file(dir / "vertex-face/queries.csv", csv.str());
  const std::string path = "'" + (dir / "vertex-face").string() + "'";
  const auto run = test::run_cli("ccd " + path + " --filter network");
  REQUIRE(run.exit_code == 0);
  CHECK_THAT(run.output, Catch::Contains("queries:               " + std::to_string(count)));
  CHECK_THAT(run.output, Catch::Contains("false negatives:       0"));
  CHECK_THAT(run.output, Catch::Contains("colliding:             " + std::to_string(truth_colliding) + " "));
  CHECK_THAT(run.output, Catch::Contains("network overruled:"));
  const std::string model = " --network '" + default_network_model_dir() + "'";
  const auto json = test::run_cli("ccd " + path + " --filter network --json" + model);
  REQUIRE(json.exit_code == 0);
  const nlohmann::json summary = nlohmann::json::parse(json.output);
  CHECK(summary["false_negatives"] == 0);
  CHECK(summary["network"]["dropped"].is_number());

  const auto missing = test::run_cli("ccd " + path + " --filter network --network /nonexistent/model");
  CHECK(missing.exit_code == 1);
  CHECK_THAT(missing.output, Catch::StartsWith("clothcd: error: ") && Catch::Contains("/nonexistent/model"));
  // The old spelling --model still works, hidden.
  CHECK(test::run_cli("ccd " + path + " --filter network --model /nonexistent/model").exit_code == 1);
  CHECK(test::run_cli("ccd " + path + " --filter combined --network /nonexistent/model").exit_code == 1);
}

// Dataset generation: the pairs are every candidate of the all-pairs broad phase reference, in canonical order; labels
// recomputed from each row's geometry, determinism, bad settings.
#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>

#include "broadphase/body_topology.hpp"
#include "broadphase/brute_force_candidates.hpp"
#include "broadphase/swept_boxes.hpp"
#include "broadphase/traversal.hpp"
#include "clothcd/ccd/ccd.hpp"
#include "clothcd/learning/dataset_generation.hpp"
#include "clothcd/learning/pair_dataset.hpp"
#include "clothcd/simulation/scene.hpp"
#include "clothcd/simulation/simulator.hpp"
#include "support/test_support.hpp"

using namespace clothcd;
using namespace clothcd::learning;

namespace {

DatasetGenerationSettings tiny_settings() {
  DatasetGenerationSettings s;
  s.scenes = {"box"};
  s.cloths = {'A'};
  s.seeds = {3};
  s.steps = 4;
  s.dt = 0.02;  // large steps so the falling cloth reaches the box within few steps
  s.max_rows = 400;
  return s;
}

// Long enough (12 large steps) for the falling cloth to hit the box: real collisions among the candidates.
DatasetGenerationSettings falling_on_box() {
  DatasetGenerationSettings s = tiny_settings();
  s.seeds = {2};
  s.steps = 12;
  return s;
}

std::size_t colliding_rows(const PairDataset& d) {
  std::size_t n = 0;
  for (int label : d.exact_label) n += label == 1 ? 1 : 0;
  return n;
}

// The query of candidate i of `c` (vertex-face ones first), the bodies at `start`/`end`.
ccd::CcdQuery candidate_query(const broadphase::CandidateSet& c, std::size_t i,
                              const std::vector<const broadphase::BodyTopology*>& topology,
                              const std::vector<Vertices>& start, const std::vector<Vertices>& end) {
  ccd::CcdQuery q;
  std::array<std::pair<int, int>, 4> points;  // (body, vertex)
  if (i < c.vertex_face.size()) {
    const broadphase::VertexFaceCandidate& vf = c.vertex_face[i];
    q.kind = PairKind::VertexFace;
    points[0] = {vf.vertex_body, vf.vertex};
    for (int k = 0; k < 3; ++k) points[k + 1] = {vf.face_body, topology[vf.face_body]->faces(vf.face, k)};
  } else {
    const broadphase::EdgeEdgeCandidate& ee = c.edge_edge[i - c.vertex_face.size()];
    q.kind = PairKind::EdgeEdge;
    for (int k = 0; k < 2; ++k) {
      points[k] = {ee.body_a, topology[ee.body_a]->edges[2 * ee.edge_a + k]};
      points[k + 2] = {ee.body_b, topology[ee.body_b]->edges[2 * ee.edge_b + k]};
    }
  }
  for (int k = 0; k < 4; ++k) {
    q.start[k] = start[points[k].first].row(points[k].second).transpose();
    q.end[k] = end[points[k].first].row(points[k].second).transpose();
  }
  return q;
}

}  // namespace

TEST_CASE("generated rows carry the labels and features of their own geometry", "[learning][gen-dataset]") {
  const DatasetGenerationSettings settings = tiny_settings();
  const GeneratedDataset generated = generate_pair_dataset(settings);
  const PairDataset& d = generated.dataset;
  REQUIRE(d.row_count() > 0);
  REQUIRE(d.row_count() <= settings.max_rows);
  REQUIRE(generated.queries.size() == d.row_count());
  REQUIRE(generated.candidates_seen >= d.row_count());
  REQUIRE(d.feature_count() == settings.features.count);
  std::vector<double> f(settings.features.count);
  std::size_t vf = 0, filter_kept = 0;
  for (std::size_t i = 0; i < d.row_count(); ++i) {
    const ccd::CcdQuery& q = generated.queries[i];
    REQUIRE(d.type[i] == q.kind);
    REQUIRE(d.filter_label[i] == (ccd::combined_filters_cull(q) ? 0 : 1));
    REQUIRE(d.exact_label[i] == (ccd::continuous_collision(q).hit ? 1 : 0));
    // Safety of the filters on the rows themselves: a real collision is never culled.
    if (d.exact_label[i] == 1) REQUIRE(d.filter_label[i] == 1);
    compute_pair_features(q, settings.features, f.data());
    for (std::size_t k = 0; k < f.size(); ++k) REQUIRE(d.row(i)[k] == f[k]);
    REQUIRE(d.scene[i] == "box-A-3");
    vf += d.type[i] == PairKind::VertexFace ? 1 : 0;
    filter_kept += static_cast<std::size_t>(d.filter_label[i]);
  }
  // Both pair types and both filter classes occur, so the data set can teach something.
  CHECK(vf > 0);
  CHECK(vf < d.row_count());
  CHECK(filter_kept > 0);
  CHECK(filter_kept < d.row_count());
  const ClassBalance balance = class_balance(d);
  CHECK(balance.rows[0] + balance.rows[1] + balance.rows[2] == d.row_count());
  CHECK(balance.rows[0] == static_cast<std::size_t>(0.6 * static_cast<double>(d.row_count())));
}

TEST_CASE("the same settings give the same CSV, another seed another one", "[learning][gen-dataset]") {
  DatasetGenerationSettings settings = tiny_settings();
  settings.steps = 2;
  settings.max_rows = 150;
  const test::TempDir dir;
  const std::string a = (dir / "a.csv").string(), b = (dir / "b.csv").string(), c = (dir / "c.csv").string();
  write_pair_dataset_csv(generate_pair_dataset(settings).dataset, a);
  write_pair_dataset_csv(generate_pair_dataset(settings).dataset, b);
  settings.seed = 99;
  write_pair_dataset_csv(generate_pair_dataset(settings).dataset, c);
  const std::string text_a = test::read_file(a);
  CHECK(!text_a.empty());
  CHECK(text_a == test::read_file(b));
  CHECK(text_a != test::read_file(c));
}

TEST_CASE("bad generation settings are clear errors", "[learning][gen-dataset]") {
  DatasetGenerationSettings s = tiny_settings();
  s.scenes = {"nowhere"};
  CHECK_THROWS_WITH(generate_pair_dataset(s), Catch::Contains("unknown scene 'nowhere'"));
  s = tiny_settings();
  s.steps = 0;
  CHECK_THROWS_WITH(generate_pair_dataset(s), Catch::Contains("steps must be at least 1"));
  s = tiny_settings();
  s.cloths = {'Z'};
  CHECK_THROWS_WITH(generate_pair_dataset(s), Catch::Contains("unknown cloth 'Z'"));
  s = tiny_settings();
  s.max_rows = 0;
  CHECK_THROWS_AS(generate_pair_dataset(s), std::invalid_argument);
  s = tiny_settings();
  s.dt = -1.0;
  CHECK_THROWS_AS(generate_pair_dataset(s), std::invalid_argument);
  s = tiny_settings();
  s.seeds.clear();
  CHECK_THROWS_AS(generate_pair_dataset(s), std::invalid_argument);
}

TEST_CASE("clothcd gen-dataset writes a CSV that reads back, and rejects bad arguments", "[learning][gen-dataset][cli]") {
  const test::TempDir dir;
  const std::string out = (dir / "pairs.csv").string();
  const test::CliRun ok = test::run_cli("gen-dataset --out '" + out + "' --scenes box --cloths A --steps 3 --dt 0.02 "
                                        "--max-rows 120 --seeds 1,2");
  REQUIRE(ok.exit_code == 0);
  CHECK_THAT(ok.output, Catch::Contains("rows: 120"));
  CHECK_THAT(ok.output, Catch::Contains("testing:"));
  const PairDataset back = read_pair_dataset_csv(out);
  CHECK(back.row_count() == 120);
  CHECK(back.feature_count() == FeatureSettings{}.count);

  const test::CliRun unknown = test::run_cli("gen-dataset --out '" + out + "' --scenes nowhere");
  CHECK(unknown.exit_code != 0);
  CHECK_THAT(unknown.output, Catch::Contains("unknown scene 'nowhere'"));
  const test::CliRun zero = test::run_cli("gen-dataset --out '" + out + "' --steps 0");
  CHECK(zero.exit_code != 0);
  CHECK_THAT(zero.output, Catch::Contains("--steps"));
  // An output in a missing folder fails before any simulation.
  const test::CliRun nowhere = test::run_cli("gen-dataset --out '" + (dir / "missing/pairs.csv").string() + "'");
  CHECK(nowhere.exit_code != 0);
  CHECK_THAT(nowhere.output, Catch::Contains("cannot open for writing") && !Catch::Contains("simulating"));
}

TEST_CASE("keep_collisions keeps every colliding candidate and samples the rest", "[learning][gen-dataset]") {
  DatasetGenerationSettings everything = falling_on_box();
  everything.max_rows = 100'000'000;  // larger than the candidates: no sampling, every candidate is a row
  const GeneratedDataset all = generate_pair_dataset(everything);
  REQUIRE(all.dataset.row_count() == all.candidates_seen);
  const std::size_t collisions = colliding_rows(all.dataset);
  REQUIRE(collisions > 0);  // the scene must produce real collisions for this test to mean anything

  DatasetGenerationSettings sampled = falling_on_box();
  sampled.max_rows = collisions + 40;
  sampled.keep_collisions = true;
  const GeneratedDataset kept = generate_pair_dataset(sampled);
  CHECK(kept.collisions_seen == collisions);
  CHECK(colliding_rows(kept.dataset) == collisions);
  CHECK(kept.dataset.row_count() <= sampled.max_rows);  // collisions count towards max_rows when it has room
  CHECK(kept.dataset.row_count() > collisions);  // the uniform sample is there too
  for (std::size_t i = 0; i < kept.dataset.row_count(); ++i) {
    const bool hit = ccd::continuous_collision(kept.queries[i]).hit;
    REQUIRE(kept.dataset.exact_label[i] == (hit ? 1 : 0));
  }

  sampled.keep_collisions = false;
  const GeneratedDataset plain = generate_pair_dataset(sampled);
  CHECK(plain.dataset.row_count() == sampled.max_rows);
  CHECK(plain.collisions_seen == 0);  // only counted with keep_collisions
  CHECK(colliding_rows(plain.dataset) < collisions);
}

TEST_CASE("the generated pairs are every candidate of the all-pairs broad phase, in canonical order",
          "[learning][gen-dataset]") {
  DatasetGenerationSettings settings = tiny_settings();
  settings.steps = 3;
  settings.max_shift = 0.0;
  settings.max_rows = 1000000000;  // every candidate becomes a row
  const GeneratedDataset generated = generate_pair_dataset(settings);

  // The reference: the same run, each step's free-flight motion searched pair by pair.
  simulation::SceneSettings scene_settings;
  scene_settings.name = "box";
  scene_settings.cloth = 'A';
  const simulation::Scene scene = simulation::make_scene(scene_settings);
  simulation::SimulationSettings sim_settings;
  sim_settings.dt = settings.dt;
  simulation::Simulator simulator(scene, sim_settings);
  std::vector<broadphase::BodyTopology> topologies{broadphase::build_body_topology(
      scene.cloth.faces, static_cast<int>(scene.cloth.vertex_count()))};
  for (const simulation::Obstacle& o : scene.obstacles)
    topologies.push_back(broadphase::build_body_topology(o.rest.faces, static_cast<int>(o.rest.vertex_count())));
  std::vector<const broadphase::BodyTopology*> topology;
  for (const broadphase::BodyTopology& t : topologies) topology.push_back(&t);
  std::vector<ccd::CcdQuery> expected;
  for (int step = 0; step < settings.steps; ++step) {
    std::vector<Vertices> start{simulator.state().positions}, end{simulator.state().positions};
    end[0] += settings.dt * simulator.state().velocities;
    end[0].rowwise() += settings.dt * settings.dt * sim_settings.cloth.gravity.transpose();
    for (const simulation::Obstacle& o : scene.obstacles) {
      start.push_back(o.positions_at(step));
      end.push_back(o.positions_at(step + 1));
    }
    std::vector<broadphase::SweptBoxes> boxes(topologies.size());
    std::vector<broadphase::BodyView> views;
    for (std::size_t b = 0; b < topologies.size(); ++b) {
      broadphase::compute_swept_boxes(topologies[b], start[b], end[b], settings.box_thickness, boxes[b]);
      views.push_back({static_cast<int>(b), &topologies[b], &boxes[b], nullptr});
    }
    broadphase::CandidateSet candidates;
    broadphase::brute_force_self_candidates(views[0], candidates);
    for (std::size_t b = 1; b < views.size(); ++b) {
      broadphase::brute_force_pair_candidates(views[0], views[b], candidates);
    }
    broadphase::sort_candidates(candidates);
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      expected.push_back(candidate_query(candidates, i, topology, start, end));
    }
    (void)simulator.step();
  }
  REQUIRE(generated.candidates_seen == expected.size());
  REQUIRE(generated.queries.size() == expected.size());
  std::size_t different = 0;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const ccd::CcdQuery& a = generated.queries[i];
    const ccd::CcdQuery& b = expected[i];
    bool same = a.kind == b.kind;
    for (int k = 0; k < 4; ++k) same = same && a.start[k] == b.start[k] && a.end[k] == b.end[k];
    different += same ? 0 : 1;
  }
  CHECK(different == 0);
  CHECK(expected.size() > 1000);
}

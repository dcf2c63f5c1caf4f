// Dataset generation: labels recomputed from each row's geometry, determinism, bad settings.
#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>

#include "clothcd/ccd/ccd.hpp"
#include "clothcd/learning/dataset_generation.hpp"
#include "clothcd/learning/pair_dataset.hpp"
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

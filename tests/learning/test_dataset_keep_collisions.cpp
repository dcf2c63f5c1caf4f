// Dataset generation with keep_collisions: every colliding candidate is kept, checked against a run that keeps every
// candidate (no sampling at all), and the uniform sample still respects max_rows.
#include <catch2/catch.hpp>

#include <cstddef>

#include "clothcd/ccd/ccd.hpp"
#include "clothcd/learning/dataset_generation.hpp"

using namespace clothcd;
using namespace clothcd::learning;

namespace {

DatasetGenerationSettings falling_on_box() {
  DatasetGenerationSettings s;
  s.scenes = {"box"};
  s.cloths = {'A'};
  s.seeds = {2};
  s.steps = 12;
  s.dt = 0.02;  // large steps: the falling cloth hits the box within the run
  return s;
}

std::size_t colliding_rows(const PairDataset& d) {
  std::size_t n = 0;
  for (int label : d.exact_label) n += label == 1 ? 1 : 0;
  return n;
}

}  // namespace

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

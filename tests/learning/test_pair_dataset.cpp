// Pair data sets: CSV round trip, reproducible 60/20/20 splits, constant columns, re-balancing and every kind of bad
// file.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "clothcd/learning/pair_dataset.hpp"
#include "culling/pair_test_data.hpp"

using namespace clothcd::learning;

namespace {

std::string temp_file(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("clothcd_dataset_" + name)).string();
}

std::string write_text(const std::string& name, const std::string& text) {
  const std::string path = temp_file(name);
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST_CASE("pair data sets round-trip through CSV exactly", "[learning][dataset]") {
  const PairDataset dataset = test::make_pair_dataset(300, 2);
  const std::string path = temp_file("roundtrip.csv");
  write_pair_dataset_csv(dataset, path);
  const PairDataset loaded = read_pair_dataset_csv(path);
  std::remove(path.c_str());
  CHECK(loaded.feature_names == dataset.feature_names);
  CHECK(loaded.features == dataset.features);
  CHECK(loaded.filter_label == dataset.filter_label);
  CHECK(loaded.exact_label == dataset.exact_label);
  CHECK(loaded.type == dataset.type);
  CHECK(loaded.scene == dataset.scene);
  CHECK(loaded.split == dataset.split);
}

TEST_CASE("splits are 60/20/20 and reproducible from the seed", "[learning][dataset]") {
  PairDataset a = test::make_pair_dataset(1003, 4);
  const ClassBalance balance = class_balance(a);
  CHECK(balance.rows[0] == 601);
  CHECK(balance.rows[1] == 200);
  CHECK(balance.rows[2] == 202);
  PairDataset b = a;
  assign_splits(b, SplitSettings{0.6, 0.2, 4});
  CHECK(b.split == a.split);
  assign_splits(b, SplitSettings{0.6, 0.2, 5});
  CHECK(b.split != a.split);
  CHECK(class_balance(b).rows[0] == 601);
}

TEST_CASE("constant columns are found and re-balancing keeps held-out rows", "[learning][dataset]") {
  PairDataset dataset = test::make_pair_dataset(400, 6);
  for (std::size_t i = 0; i < dataset.row_count(); ++i) dataset.features[i * dataset.feature_count() + 3] = 0.25;
  const std::vector<std::size_t> varying = varying_feature_columns(dataset);
  CHECK(std::find(varying.begin(), varying.end(), std::size_t{3}) == varying.end());
  CHECK(varying.size() == dataset.feature_count() - 1);

  const PairDataset balanced = rebalance_training_rows(dataset, 1.0, 9);
  const ClassBalance before = class_balance(dataset), after = class_balance(balanced);
  CHECK(after.rows[1] == before.rows[1]);
  CHECK(after.rows[2] == before.rows[2]);
  CHECK(after.filter_positive[0] * 2 == after.rows[0]);
  CHECK_THROWS_AS(rebalance_training_rows(dataset, 0.5, 9), std::invalid_argument);
}

TEST_CASE("bad data set files are clear errors", "[learning][dataset]") {
  CHECK_THROWS_WITH(read_pair_dataset_csv("/nonexistent/pairs.csv"), Catch::Contains("/nonexistent/pairs.csv"));
  CHECK_THROWS_WITH(read_pair_dataset_csv(write_text("empty.csv", "")), Catch::Contains("empty file"));
  CHECK_THROWS_WITH(read_pair_dataset_csv(write_text("header.csv", "a,b,c\n1,2,3\n")), Catch::Contains("header"));
  const std::string header = "f1,filter_label,exact_label,type,scene,split\n";
  CHECK_THROWS_WITH(read_pair_dataset_csv(write_text("fields.csv", header + "1,0,0,VF,s\n")),
                    Catch::Contains(":2:") && Catch::Contains("fields"));
  CHECK_THROWS_WITH(read_pair_dataset_csv(write_text("nan.csv", header + "nan,0,0,VF,s,training\n")),
                    Catch::Contains("not a finite number"));
  CHECK_THROWS_WITH(read_pair_dataset_csv(write_text("label.csv", header + "1,2,0,VF,s,training\n")),
                    Catch::Contains("not 0 or 1"));
  CHECK_THROWS_WITH(read_pair_dataset_csv(write_text("type.csv", header + "1,0,0,XX,s,training\n")),
                    Catch::Contains("VF or EE"));
  CHECK_THROWS_WITH(read_pair_dataset_csv(write_text("split.csv", header + "1,0,0,EE,s,train\n")),
                    Catch::Contains("split"));
  CHECK_THROWS_WITH(read_pair_dataset_csv(write_text("norows.csv", header)), Catch::Contains("no rows"));
  const PairDataset ok = read_pair_dataset_csv(write_text("ok.csv", header + "1.5,1,0,EE,s,selection\n"));
  CHECK(ok.row_count() == 1);
  CHECK(ok.split[0] == Split::Selection);

  PairDataset dataset;
  dataset.feature_names = {"f"};
  const double nan = std::nan("");
  PairRow row;
  row.features = &nan;
  CHECK_THROWS_AS(dataset.add_row(row), std::invalid_argument);
}

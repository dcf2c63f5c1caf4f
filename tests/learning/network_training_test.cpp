// Training: files written, one curve point per neuron count, the chosen count minimizes the selection error, learning
// happens, constant columns are dropped and recorded, and training is deterministic for a seed.
#include <catch2/catch.hpp>

#include <cmath>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "clothcd/learning/network_training.hpp"
#include "learning/trained_model_fixture.hpp"
#include "support/test_support.hpp"

using namespace clothcd::learning;
namespace fs = std::filesystem;

using clothcd::test::read_file;

TEST_CASE("training writes the model, card and neuron curve and learns the filter label", "[learning][training]") {
  const test::TrainedModel& model = test::trained_model();
  for (const char* file : {"network.xml", "card.json", "neurons.csv", "neurons.png"})
    CHECK(fs::file_size(model.directory + "/" + file) > 0);
  const TrainingReport& report = model.report;
  REQUIRE(report.curve.size() == 3);
  std::size_t best = 0;
  for (std::size_t k = 0; k < report.curve.size(); ++k) {
    CHECK(report.curve[k].neurons == k + 1);
    if (report.curve[k].selection_error < report.curve[best].selection_error) best = k;
  }
  CHECK(report.card.hidden_neurons == report.curve[best].neurons);
  CHECK(report.testing_confusion.accuracy() > 0.9);
  CHECK(report.testing_auc > 0.95);
  const ModelCard card = read_model_card(model.directory + "/card.json");
  CHECK(card.inputs == report.card.inputs);
  CHECK(card.drop_below == report.card.drop_below);
  CHECK(card.keep_from == report.card.keep_from);
  CHECK(card.hidden_neurons == report.card.hidden_neurons);
}

TEST_CASE("training drops constant columns and is deterministic for a seed", "[learning][training]") {
  PairDataset dataset = test::make_pair_dataset(400, 21);
  for (std::size_t i = 0; i < dataset.row_count(); ++i) dataset.features[i * dataset.feature_count() + 14] = 0.0;
  TrainingSettings settings = test::small_training_settings();
  settings.max_neurons = 2;
  settings.max_epochs = 40;
  const std::string a = (fs::temp_directory_path() / "clothcd_train_a").string();
  const std::string b = (fs::temp_directory_path() / "clothcd_train_b").string();
  const TrainingReport first = train_pair_network(dataset, settings, a, "a");
  const TrainingReport second = train_pair_network(dataset, settings, b, "a");
  CHECK(first.card.dropped_columns == std::vector<std::string>{"is_edge_edge"});
  CHECK(first.card.inputs.size() == 14);
  CHECK(read_file(a + "/network.xml") == read_file(b + "/network.xml"));
  CHECK(read_file(a + "/neurons.csv") == read_file(b + "/neurons.csv"));
  settings.seed = 99;
  const TrainingReport third = train_pair_network(dataset, settings, b, "a");
  CHECK(read_file(a + "/network.xml") != read_file(b + "/network.xml"));
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST_CASE("training refuses data sets it cannot learn from", "[learning][training]") {
  PairDataset dataset = test::make_pair_dataset(100, 22);
  const std::string out = (fs::temp_directory_path() / "clothcd_train_bad").string();
  PairDataset one_class = dataset;
  for (int& label : one_class.filter_label) label = 1;
  CHECK_THROWS_WITH(train_pair_network(one_class, test::small_training_settings(), out, "x"),
                    Catch::Contains("both filter labels"));
  PairDataset no_selection = dataset;
  for (Split& split : no_selection.split) split = Split::Training;
  CHECK_THROWS_WITH(train_pair_network(no_selection, test::small_training_settings(), out, "x"),
                    Catch::Contains("selection"));
  TrainingSettings wrong_count = test::small_training_settings();
  wrong_count.feature_count = 12;
  CHECK_THROWS_WITH(train_pair_network(dataset, wrong_count, out, "x"), Catch::Contains("feature columns"));
  for (const double threshold : {std::nan(""), -0.1, 1.5}) {  // refused before any training
    TrainingSettings bad_threshold = test::small_training_settings();
    bad_threshold.decision_threshold = threshold;
    CHECK_THROWS_WITH(train_pair_network(dataset, bad_threshold, out, "x"), Catch::Contains("decision threshold"));
  }
  for (const double margin : {std::nan(""), -0.1, 1.5}) {
    TrainingSettings bad_keep = test::small_training_settings(), bad_drop = bad_keep;
    bad_keep.keep_margin = margin;
    bad_drop.drop_margin = margin;
    CHECK_THROWS_WITH(train_pair_network(dataset, bad_keep, out, "x"), Catch::Contains("margins"));
    CHECK_THROWS_WITH(train_pair_network(dataset, bad_drop, out, "x"), Catch::Contains("margins"));
  }
}

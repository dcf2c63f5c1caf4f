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
  for (const char* file : {"network.xml", "card.json", "neurons.csv", "neurons.svg"})
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

TEST_CASE("a network that trains to non-finite weights is refused and leaves the model in place", "[learning][training]") {
  const test::TrainedModel& model = test::trained_model();
  const std::string out = (fs::temp_directory_path() / "clothcd_train_overflow").string();
  fs::remove_all(out);
  fs::create_directories(out);
  for (const char* file : {"network.xml", "card.json"}) fs::copy_file(model.directory + "/" + file, out + "/" + file);
  const std::string network = read_file(out + "/network.xml"), card = read_file(out + "/card.json");
  // A feature of magnitude 1e308 overflows the scaling layer: the trained weights come out NaN.
  PairDataset dataset = test::make_pair_dataset(200, 23);
  dataset.features[0] = -1e308;
  dataset.features[dataset.feature_count()] = 1e308;
  TrainingSettings settings = test::small_training_settings();
  settings.max_neurons = 1;
  CHECK_THROWS_WITH(train_pair_network(dataset, settings, out, "x"), Catch::Contains("unusable network"));
  CHECK(read_file(out + "/network.xml") == network);
  CHECK(read_file(out + "/card.json") == card);
  CHECK_FALSE(fs::exists(out + "/network.xml.part"));
  fs::remove_all(out);
}

TEST_CASE("without testing rows the card holds no testing metrics and the AUC is undefined", "[learning][training]") {
  PairDataset dataset = test::make_pair_dataset(300, 24);
  for (Split& split : dataset.split)
    if (split == Split::Testing) split = Split::Training;
  TrainingSettings settings = test::small_training_settings();
  settings.max_neurons = 1;
  const std::string out = (fs::temp_directory_path() / "clothcd_train_no_testing").string();
  const TrainingReport report = train_pair_network(dataset, settings, out, "x");
  CHECK(std::isnan(report.testing_auc));
  const std::string card = read_file(out + "/card.json");
  CHECK(card.find("testing_accuracy") == std::string::npos);
  CHECK(card.find("selection_accuracy") != std::string::npos);
  fs::remove_all(out);
}

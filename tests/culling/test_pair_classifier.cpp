// Runtime pair network: agreement with OpenNN's outputs and with the plain reference forward pass, decisions at the
// operating point, safety on the selection split, and every kind of bad model file.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "clothcd/culling/pair_classifier.hpp"
#include "learning/opennn_backend.hpp"
#include "learning/trained_model_fixture.hpp"
#include "support/simd_level.hpp"
#include "support/simd_limit.hpp"

using namespace clothcd::learning;
namespace fs = std::filesystem;

namespace {

PairFeatureBatch batch_of(const PairDataset& dataset, std::size_t first, std::size_t count) {
  PairFeatureBatch batch;
  batch.resize(count, dataset.feature_count());
  for (std::size_t i = 0; i < count; ++i)
    for (std::size_t f = 0; f < dataset.feature_count(); ++f) batch.column(f)[i] = dataset.row(first + i)[f];
  return batch;
}

std::string read_text(const std::string& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// A copy of the shared model directory whose network.xml (or card.json) is replaced by `edit(original)`.
std::string edited_model(const std::string& name, const std::string& file,
                         const std::function<std::string(const std::string&)>& edit) {
  const std::string source = test::trained_model().directory;
  const std::string dir = (fs::temp_directory_path() / ("clothcd_bad_model_" + name)).string();
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const char* part : {"network.xml", "card.json"}) fs::copy_file(source + "/" + part, dir + "/" + part);
  const std::string text = read_text(dir + "/" + file);
  std::ofstream(dir + "/" + file, std::ios::trunc) << edit(text);
  return dir;
}

}  // namespace

TEST_CASE("the batched forward pass matches OpenNN's calculate_outputs to 1e-12", "[learning][runtime][opennn]") {
  const test::TrainedModel& model = test::trained_model();
  const PairClassifier classifier = PairClassifier::load(model.directory);
  const std::size_t rows = 257;  // not a multiple of the block size
  const PairFeatureBatch batch = batch_of(model.dataset, 0, rows);
  std::vector<double> ours(rows);
  classifier.probabilities(batch, ours.data());
  // The AVX2 / AVX-512 builds of the forward pass (where this CPU has them) give the baseline's bits.
  std::vector<double> baseline(rows);
  {
    clothcd::test::SimdLimit capped(clothcd::SimdLevel::Baseline);
    classifier.probabilities(batch, baseline.data());
  }
  CHECK(baseline == ours);
  for (const clothcd::SimdLevel level : clothcd::cpu_simd_levels()) {
    INFO("level " << clothcd::simd_level_name(level));
    clothcd::test::SimdLimit capped(level);
    std::vector<double> at_level(rows);
    classifier.probabilities(batch, at_level.data());
    CHECK(at_level == baseline);
  }

  const NetworkWeights& weights = classifier.weights();
  std::vector<double> inputs;
  for (std::size_t i = 0; i < rows; ++i)
    for (const std::string& name : weights.input_names) {
      const auto column = std::find(model.dataset.feature_names.begin(), model.dataset.feature_names.end(), name) -
                          model.dataset.feature_names.begin();
      inputs.push_back(model.dataset.row(i)[column]);
    }
  const std::vector<double> opennn =
      backend::OpennnNetwork::load(model.directory + "/network.xml").outputs(inputs, true);
  REQUIRE(opennn.size() == rows);
  double worst = 0.0;
  for (std::size_t i = 0; i < rows; ++i) {
    worst = std::max(worst, std::abs(ours[i] - opennn[i]));
    CHECK(ours[i] == Approx(reference_probability(weights, &inputs[i * weights.input_count()])).margin(1e-15));
  }
  CHECK(worst <= 1e-12);
}

TEST_CASE("decisions follow the operating point and non-finite features are kept", "[learning][runtime]") {
  const test::TrainedModel& model = test::trained_model();
  PairClassifier classifier = PairClassifier::load(model.directory);
  const OperatingPoint point = classifier.operating_point();
  CHECK(point.drop_below >= 0.0);
  CHECK(point.drop_below <= point.decision_threshold);

  PairFeatureBatch batch = batch_of(model.dataset, 0, 100);
  batch.column(0)[7] = std::nan("");
  std::vector<double> probability(100);
  std::vector<PairDecision> decision(100);
  classifier.probabilities(batch, probability.data());
  classifier.decide(batch, decision.data());
  for (std::size_t i = 0; i < 100; ++i) CHECK(decision[i] == classifier.decide(probability[i]));
  CHECK(decision[7] == PairDecision::Keep);
  CHECK(classifier.decide(point.keep_from) == PairDecision::Keep);
  CHECK(classifier.decide(-1.0) == (point.drop_below > -1.0 ? PairDecision::Drop : PairDecision::Check));

  classifier.set_operating_point(OperatingPoint{0.0, 0.5});
  CHECK(classifier.decide(0.0) == PairDecision::Check);
  CHECK_THROWS_AS(classifier.set_operating_point(OperatingPoint{0.6, 0.5}), std::invalid_argument);

  // keep_from: between the decision threshold and keep_from the filters still check the pair; above 1 none is kept.
  classifier.set_operating_point(OperatingPoint{0.1, 0.5, 0.9});
  CHECK(classifier.decide(0.05) == PairDecision::Drop);
  CHECK(classifier.decide(0.5) == PairDecision::Check);
  CHECK(classifier.decide(0.8999) == PairDecision::Check);
  CHECK(classifier.decide(0.9) == PairDecision::Keep);
  CHECK(classifier.decide(std::nan("")) == PairDecision::Keep);
  classifier.set_operating_point(OperatingPoint{0.1, 0.5, std::nextafter(1.0, 2.0)});
  CHECK(classifier.decide(1.0) == PairDecision::Check);
  CHECK_THROWS_AS(classifier.set_operating_point(OperatingPoint{0.1, 0.5, 0.4}), std::invalid_argument);
  CHECK_THROWS_AS(classifier.set_operating_point(OperatingPoint{0.1, 0.5, std::nan("")}), std::invalid_argument);
  CHECK_THROWS_AS(classifier.set_operating_point(OperatingPoint{0.1, 0.5, HUGE_VAL}), std::invalid_argument);
  CHECK(OperatingPoint{0.1, 0.7}.keep_from == 0.7);  // left out: the decision threshold
}

TEST_CASE("keep_from keeps no selection-split pair the filters remove, and older cards read it as the threshold",
          "[learning][runtime]") {
  const test::TrainedModel& model = test::trained_model();
  const PairClassifier classifier = PairClassifier::load(model.directory);
  const OperatingPoint point = classifier.operating_point();
  CHECK(point.keep_from >= point.decision_threshold);
  const PairFeatureBatch batch = batch_of(model.dataset, 0, model.dataset.row_count());
  std::vector<PairDecision> decision(batch.rows);
  classifier.decide(batch, decision.data());
  std::size_t selection_kept = 0;
  for (std::size_t i = 0; i < batch.rows; ++i) {
    if (model.dataset.split[i] != Split::Selection) continue;
    if (model.dataset.filter_label[i] == 0) CHECK(decision[i] != PairDecision::Keep);
    selection_kept += decision[i] == PairDecision::Keep;
  }
  CHECK(selection_kept > 0);  // the network still lets pairs skip the filters
  // Training's rule: half way from the highest such probability to 1 (TrainingSettings::keep_margin), just above.
  std::vector<double> probability(batch.rows);
  classifier.probabilities(batch, probability.data());
  double highest = 0.0;
  for (std::size_t i = 0; i < batch.rows; ++i)
    if (model.dataset.split[i] == Split::Selection && model.dataset.filter_label[i] == 0)
      highest = std::max(highest, probability[i]);
  CHECK(point.keep_from == std::max(point.decision_threshold, std::nextafter(1.0 - 0.5 * (1.0 - highest), 2.0)));

  const std::string without = edited_model("no_keep_from", "card.json", [](const std::string& text) {
    const std::size_t begin = text.find("  \"keep_from\": ");
    return text.substr(0, begin) + text.substr(text.find('\n', begin) + 1);
  });
  const OperatingPoint old = PairClassifier::load(without).operating_point();
  CHECK(old.keep_from == old.decision_threshold);
  const std::string below = edited_model("low_keep_from", "card.json", [](const std::string& text) {
    const std::size_t value = text.find("\"keep_from\": ") + std::string("\"keep_from\": ").size();
    return text.substr(0, value) + "0.1" + text.substr(text.find(',', value));
  });
  CHECK_THROWS_WITH(PairClassifier::load(below), Catch::Contains("card.json") && Catch::Contains("keep_from"));
}

TEST_CASE("the operating point drops no real collision of the selection split", "[learning][runtime]") {
  const test::TrainedModel& model = test::trained_model();
  const PairClassifier classifier = PairClassifier::load(model.directory);
  const PairFeatureBatch batch = batch_of(model.dataset, 0, model.dataset.row_count());
  std::vector<PairDecision> decision(batch.rows);
  classifier.decide(batch, decision.data());
  std::size_t real = 0, dropped = 0;
  for (std::size_t i = 0; i < batch.rows; ++i) {
    if (model.dataset.split[i] != Split::Selection || model.dataset.exact_label[i] != 1) continue;
    ++real;
    CHECK(decision[i] != PairDecision::Drop);
    dropped += decision[i] == PairDecision::Drop;
  }
  CHECK(real > 20);
  CHECK(std::count(decision.begin(), decision.end(), PairDecision::Drop) > 0);  // the safe point still culls
}

TEST_CASE("bad model files are clear errors", "[learning][runtime]") {
  const std::string dir = test::trained_model().directory;
  CHECK_THROWS_WITH(PairClassifier::load("/nonexistent/model"), Catch::Contains("/nonexistent/model"));

  const std::string truncated = edited_model("truncated", "network.xml", [](const std::string& text) {
    return text.substr(0, text.size() / 2);
  });
  CHECK_THROWS_WITH(PairClassifier::load(truncated), Catch::Contains("network.xml") && Catch::Contains("truncated"));

  const std::string nan_weights = edited_model("nan", "network.xml", [](const std::string& text) {
    const std::size_t at = text.find("<Parameters>") + std::string("<Parameters>").size();
    return text.substr(0, at) + "nan " + text.substr(text.find(' ', at) + 1);
  });
  CHECK_THROWS_WITH(PairClassifier::load(nan_weights), Catch::Contains("Parameters") && Catch::Contains("nan"));

  const std::string wrong_inputs = edited_model("inputs", "card.json", [](const std::string& text) {
    const std::size_t list = text.find("\"inputs\": [") + std::string("\"inputs\": [").size();
    return text.substr(0, list) + text.substr(text.find(", ", list) + 2);  // drops the first input name
  });
  CHECK_THROWS_WITH(PairClassifier::load(wrong_inputs), Catch::Contains("inputs"));

  CHECK_THROWS_WITH(PairClassifier::load(dir, FeatureSettings{12}), Catch::Contains("features"));

  const std::string old_version = edited_model("version", "card.json", [](const std::string& text) {
    const std::size_t value = text.find("\"feature_version\": ") + std::string("\"feature_version\": ").size();
    return text.substr(0, value) + "999" + text.substr(text.find(',', value));
  });
  CHECK_THROWS_WITH(PairClassifier::load(old_version), Catch::Contains("version"));

  const std::string wrong_count = edited_model("count", "card.json", [](const std::string& text) {
    const std::size_t value = text.find("\"feature_count\": ") + std::string("\"feature_count\": ").size();
    return text.substr(0, value) + "14" + text.substr(text.find(',', value));
  });
  CHECK_THROWS_WITH(PairClassifier::load(wrong_count), Catch::Contains("feature_count"));

  const auto with_field = [](const char* name, const char* field, const std::string& value) {
    return edited_model(name, "card.json", [field, value](const std::string& text) {
      const std::string key = std::string("\"") + field + "\": ";
      const std::size_t at = text.find(key) + key.size();
      return text.substr(0, at) + value + text.substr(text.find_first_of(",}", at));
    });
  };
  // Numbers beyond what the fields can hold: 4294967297 became version 1, 2^64 + 15 a count of 0.
  CHECK_THROWS_WITH(PairClassifier::load(with_field("big_version", "feature_version", "4294967297")),
                    Catch::Contains("feature_version") && Catch::Contains("whole number"));
  CHECK_THROWS_WITH(PairClassifier::load(with_field("big_rows", "training", "18446744073709551631")),
                    Catch::Contains("training") && Catch::Contains("whole number"));
  CHECK_THROWS_WITH(PairClassifier::load(with_field("big_seed", "seed", "1e30")), Catch::Contains("seed"));
  // A number beyond the doubles is malformed JSON, not a crash or an infinity.
  CHECK_THROWS_WITH(PairClassifier::load(with_field("huge_drop", "drop_below", "1e400")),
                    Catch::Contains("card.json") && Catch::Contains("malformed JSON"));
  const std::string duplicate = edited_model("duplicate", "card.json", [](const std::string& text) {
    return "{\n  \"seed\": 7," + text.substr(1);  // a second "seed"
  });
  CHECK_THROWS_WITH(PairClassifier::load(duplicate), Catch::Contains("duplicate key 'seed'"));
  const std::string wide = edited_model("wide_scaling", "network.xml", [](const std::string& text) {
    const std::size_t min_at = text.find("<Minimum>") + std::string("<Minimum>").size();
    std::string edited = text.substr(0, min_at) + "-1e308" + text.substr(text.find("</Minimum>", min_at));
    const std::size_t max_at = edited.find("<Maximum>") + std::string("<Maximum>").size();
    return edited.substr(0, max_at) + "1e308" + edited.substr(edited.find("</Maximum>", max_at));
  });
  CHECK_THROWS_WITH(PairClassifier::load(wide), Catch::Contains("wider than the largest double"));

  const std::string broken_card = edited_model("card", "card.json", [](const std::string& text) {
    return text.substr(0, 40);
  });
  CHECK_THROWS_WITH(PairClassifier::load(broken_card), Catch::Contains("card.json") && Catch::Contains("malformed"));

  // 100,000 nested elements inside the model: the XML parser would recurse once per level and overflow the stack.
  const std::string deep = edited_model("deep", "network.xml", [](const std::string& text) {
    std::string nest;
    for (int i = 0; i < 100000; ++i) nest += "<a>";
    for (int i = 0; i < 100000; ++i) nest += "</a>";
    const std::size_t at = text.find("<Inputs>");
    return text.substr(0, at) + nest + text.substr(at);
  });
  CHECK_THROWS_WITH(PairClassifier::load(deep), Catch::Contains("network.xml") && Catch::Contains("nested"));
}

namespace {

// `text` with the contents of the first <tag> element replaced by `value`.
std::string with_element(const std::string& text, const std::string& tag, const std::string& value) {
  const std::size_t begin = text.find("<" + tag + ">") + tag.size() + 2;
  return text.substr(0, begin) + value + text.substr(text.find("</" + tag + ">", begin));
}

}  // namespace

TEST_CASE("model files whose sizes disagree are clear errors before OpenNN reads them", "[learning][runtime]") {
  const auto expect = [](const std::string& dir, const char* words) {
    CHECK_THROWS_WITH(PairClassifier::load(dir), Catch::Contains("network.xml") && Catch::Contains(words));
  };
  expect(edited_model("short_params", "network.xml", [](const std::string& text) {
           const std::size_t begin = text.find("<Parameters>") + std::string("<Parameters>").size();
           return text.substr(0, begin) + text.substr(text.find(' ', begin) + 1);  // one number fewer
         }),
         "architecture needs");
  expect(edited_model("long_params", "network.xml", [](const std::string& text) {
           const std::size_t begin = text.find("<Parameters>") + std::string("<Parameters>").size();
           return text.substr(0, begin) + "0.5 " + text.substr(begin);  // one number more
         }),
         "architecture needs");
  expect(edited_model("huge_inputs", "network.xml",
                      [](const std::string& text) { return with_element(text, "InputsNumber", "99999999999"); }),
         "InputsNumber");
  expect(edited_model("negative_inputs", "network.xml",
                      [](const std::string& text) { return with_element(text, "InputsNumber", "-1"); }),
         "InputsNumber");
  expect(edited_model("zero_layer", "network.xml", [](const std::string& text) {
           const std::size_t begin = text.find("<Architecture>") + std::string("<Architecture>").size();
           const std::string widths = text.substr(begin, text.find("</Architecture>") - begin);
           return with_element(text, "Architecture", widths.substr(0, widths.find(' ')) + " 0 1");
         }),
         "Architecture");
  expect(edited_model("activation", "network.xml",
                      [](const std::string& text) { return with_element(text, "LayersActivationFunction", "Foo Logistic"); }),
         "activation");
  expect(edited_model("scaling_neuron", "network.xml", [](const std::string& text) {
           const std::size_t begin = text.find("<ScalingNeuron ");
           return text.substr(0, begin) + text.substr(text.find("</ScalingNeuron>", begin) + 16);
         }),
         "ScalingNeuron");
}

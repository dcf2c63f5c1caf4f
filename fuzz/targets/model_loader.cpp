// libFuzzer target: the pair network's model files, network.xml then card.json separated by kFileSeparator, read as
// PairClassifier::load reads them (the card, and the weights through the library's own reader and their validation).
// Every fault is a std::runtime_error (or std::invalid_argument from the validation).
#include <stdexcept>

#include "clothcd/culling/model_card.hpp"
#include "clothcd/culling/network_weights.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto [network, card] = clothcd::fuzz::split_files(data, size);
  const auto network_path = clothcd::fuzz::scratch_file("network.xml", network).string();
  const auto card_path = clothcd::fuzz::scratch_file("card.json", card).string();
  try {
    const clothcd::learning::ModelCard model_card = clothcd::learning::read_model_card(card_path);
    (void)model_card;
  } catch (const std::runtime_error&) {
  }
  try {
    const clothcd::learning::NetworkWeights weights = clothcd::learning::read_network_weights(network_path);
    clothcd::learning::validate_network_weights(weights, network_path);
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}

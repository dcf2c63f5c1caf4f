// `clothcd gen-dataset --out FILE.csv`: labelled candidate pairs from simulated steps (Jin et al., section 3.3.1 (1)),
// written as the pair data set CSV that `clothcd train` reads (datasets/README.md).
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "clothcd/learning/dataset_generation.hpp"
#include "clothcd/learning/pair_dataset.hpp"
#include "commands.hpp"
#include "output_paths.hpp"
#include "progress.hpp"
#include "shared_options.hpp"

namespace clothcd::cli {
namespace {

struct GenDatasetOptions {
  std::string out;
  std::string scenes = "box";   // comma-separated lists
  std::string cloths = "A";
  std::string seeds = "1";
  double rebalance = 0.0;
  learning::DatasetGenerationSettings settings;
  std::string cache;
  bool json = false;
  bool quiet = false;
};

double percent(std::size_t part, std::size_t whole) {
  return whole == 0 ? 0.0 : 100.0 * static_cast<double>(part) / static_cast<double>(whole);
}

void run_gen_dataset(GenDatasetOptions options) {
  learning::DatasetGenerationSettings& settings = options.settings;
  settings.scenes = split_commas(options.scenes);
  settings.model_dir = options.cache;
  settings.cloths.clear();
  for (const std::string& c : split_commas(options.cloths)) {
    if (c.size() != 1) throw std::invalid_argument("gen-dataset: unknown cloth '" + c + "' (use A, B or C)");
    settings.cloths.push_back(c[0]);
  }
  settings.seeds.clear();
  for (const std::string& seed : split_commas(options.seeds)) settings.seeds.push_back(std::stoull(seed));
  if (!(options.rebalance >= 0.0)) throw std::invalid_argument("gen-dataset: --rebalance must be >= 0");
  // Checked before the simulations, which can take minutes.
  check_output_file(options.out, "--out");
  Progress progress("simulating", "steps", options.quiet);
  learning::GeneratedDataset generated = learning::generate_pair_dataset(
      settings, [&](std::size_t done, std::size_t total) { progress.update(done, total); });
  learning::PairDataset& dataset = generated.dataset;
  if (options.rebalance > 0.0) dataset = learning::rebalance_training_rows(dataset, options.rebalance, settings.seed);
  learning::write_pair_dataset_csv(dataset, options.out);

  std::size_t vf = 0;
  for (PairKind t : dataset.type) vf += t == PairKind::VertexFace ? 1 : 0;
  const std::size_t rows = dataset.row_count();
  const learning::ClassBalance balance = learning::class_balance(dataset);
  if (options.json) {
    Json out = json_report("gen-dataset");
    out["out"] = options.out;
    out["candidates_seen"] = generated.candidates_seen;
    if (settings.keep_collisions) out["collisions_seen"] = generated.collisions_seen;
    out["rows"] = rows;
    out["vertex_face_rows"] = vf;
    out["edge_edge_rows"] = rows - vf;
    out["splits"] = class_balance_json(balance);
    print_json(out);
    return;
  }
  std::cout << "candidate pairs seen: " << generated.candidates_seen << "\n";
  if (settings.keep_collisions)
    std::cout << "colliding candidates seen (all kept): " << generated.collisions_seen << "\n";
  std::cout << "rows: " << rows << " (VF " << vf << ", EE " << rows - vf << ")\n";
  std::cout << std::fixed << std::setprecision(1);
  for (int s = 0; s < 3; ++s)
    std::cout << "  " << std::setw(9) << learning::split_name(static_cast<learning::Split>(s)) << ": "
              << balance.rows[s] << " rows, filter label 1: " << balance.filter_positive[s] << " ("
              << percent(balance.filter_positive[s], balance.rows[s]) << "%), exact label 1: "
              << balance.exact_positive[s] << " (" << percent(balance.exact_positive[s], balance.rows[s]) << "%)\n";
  std::cout << "wrote " << options.out << '\n';
}

}  // namespace

void add_gen_dataset_command(CLI::App& app) {
  auto* command = app.add_subcommand("gen-dataset", "Simulate scenes and write labelled candidate pairs as CSV");
  auto options = std::make_shared<GenDatasetOptions>();
  learning::DatasetGenerationSettings& s = options->settings;
  command->add_option("--out", options->out, "Output CSV (datasets/README.md)")->required();
  command->add_option("--scenes", options->scenes, "Scene names, comma separated")
      ->check(comma_list())->capture_default_str();
  command->add_option("--cloths", options->cloths, "Cloths A, B, C, comma separated")
      ->check(comma_list())->capture_default_str();
  command->add_option("--seeds", options->seeds, "One run per seed (shifts the cloth), comma separated")
      ->check(comma_list(true))->capture_default_str();
  command->add_option("--steps", s.steps, "Steps per run")
      ->check(CLI::Range(1, std::numeric_limits<int>::max()))->capture_default_str();
  command->add_option("--dt", s.dt, "Step, seconds (0: scene default)")->capture_default_str();
  command->add_option("--max-rows", s.max_rows, "At most N rows (sampled uniformly, seeded)")
      ->check(CLI::Range(1, 1000000000))->capture_default_str();
  command->add_option("--rebalance", options->rebalance,
                      "Keep at most RATIO x the minority filter class of the training rows (0: off)")
      ->check(CLI::Range(0.0, 1e6))->capture_default_str();
  command->add_flag("--keep-collisions", s.keep_collisions,
                    "Also keep every candidate the exact CCD finds colliding (never trimmed)");
  command->add_option("--features", s.features.count, "Feature count")->capture_default_str();
  command->add_option("--seed", s.seed, "Seed of the sampling and the 60/20/20 split")
      ->check(kSeedNumber)->capture_default_str();
  add_cache_option(*command, options->cache, "--model-dir");
  add_json_flag(*command, options->json);
  add_quiet_flag(*command, options->quiet);
  command->callback([options] { run_gen_dataset(*options); });
}

}  // namespace clothcd::cli

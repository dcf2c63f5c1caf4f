#pragma once
/// @file
/// Dataset generation (Jin et al., section 3.3.1 (1)): runs simulation scenes and records the candidate pairs that
/// reach the narrow phase, each with its feature vector, the paper's filter label and the exact CCD label.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "clothcd/ccd/ccd.hpp"
#include "clothcd/culling/pair_features.hpp"
#include "clothcd/learning/pair_dataset.hpp"

namespace clothcd::learning {

/// What to simulate and how many rows to keep.
struct DatasetGenerationSettings {
  std::vector<std::string> scenes{"box"};        ///< Scene names (simulation::scene_names()).
  std::vector<char> cloths{'A'};                 ///< The paper's cloths 'A', 'B', 'C'.
  std::vector<unsigned long long> seeds{1};      ///< One run per seed: the seed shifts the cloth's start in x and z.
  int steps = 40;                                ///< Steps per run (>= 1).
  double dt = 0.0;                               ///< Step, seconds; 0 takes the scene's default.
  std::size_t max_rows = 5000;                   ///< Upper bound on the rows kept (>= 1).
  double max_shift = 0.15;                       ///< Largest seeded shift of the cloth in x and z, metres (>= 0).
  /// Inflation of the swept boxes of the broad phase, metres: the simulator's response thickness, so the candidates
  /// are those its detector hands to the narrow phase.
  double box_thickness = 0.004;
  FeatureSettings features;                      ///< Feature count (15 by default).
  /// Also keep every candidate pair of every step that the exact CCD finds colliding (on top of the uniform sample,
  /// and never trimmed): real collisions are rare among uniformly sampled candidates, and the operating point is
  /// chosen on them.
  bool keep_collisions = false;
  unsigned long long seed = 1;                   ///< Seed of the row sampling and of the 60/20/20 split.
  std::filesystem::path model_dir;               ///< Cache folder of the obstacle models (empty: default).
};

/// Progress: `done` of `total` simulation steps finished.
using DatasetProgress = std::function<void(std::size_t done, std::size_t total)>;

/// A generated dataset and the geometry of each of its rows.
struct GeneratedDataset {
  PairDataset dataset;                 ///< Rows with features, labels, type, scene ("<scene>-<cloth>-<seed>"), split.
  std::vector<ccd::CcdQuery> queries;  ///< Per row, the eight positions the features and labels were computed from.
  std::size_t candidates_seen = 0;     ///< Candidate pairs enumerated over all steps (before sampling).
  std::size_t collisions_seen = 0;     ///< Colliding candidates among them (counted only with keep_collisions).
};

/// Throws std::invalid_argument naming the problem: no or unknown scene, cloth not A/B/C, no seed, steps < 1,
/// dt negative or not finite, max_rows 0, negative thickness or shift, bad feature count.
void validate_generation_settings(const DatasetGenerationSettings& settings);

/// Runs every (scene, cloth, seed) for settings.steps steps. For each step a CollisionDetector (AABB hierarchy, swept
/// boxes inflated by box_thickness, cloth self pairs and cloth-obstacle pairs) runs on the step's unresolved motion:
/// start = the cloth at the start of the step, end = start + dt * velocity + dt^2 * gravity (free flight, the
/// detector's view before the response), obstacles from their pose at the step to the next; its block observer
/// records every candidate pair, which are then put in canonical order (vertex-face first, each kind by its order key). Each step keeps at most an equal share of max_rows
/// pairs, sampled uniformly with a seeded RNG; with keep_collisions, every colliding candidate is kept as well (exempt
/// from the final trim to max_rows). Labels: filter_label = 0 when ccd::combined_filters_cull removes the pair,
/// exact_label = 1 when ccd::continuous_collision hits, both with thickness 0 (the coordinates' own contact, as the
/// paper's filters). Splits are assigned 60/20/20 from settings.seed. Deterministic for equal settings.
[[nodiscard]] GeneratedDataset generate_pair_dataset(const DatasetGenerationSettings& settings,
                                                     const DatasetProgress& progress = {});

}  // namespace clothcd::learning

// Dataset generation for the pair network (Jin et al., section 3.3.1 (1)): the candidate pairs of simulated steps,
// labelled by the combined algebraic + projection filters (sections 2.2, 2.3) and by the exact CCD.
#include "clothcd/learning/dataset_generation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <utility>
#include <stdexcept>

#include "clothcd/detection/collision_detector.hpp"
#include "clothcd/simulation/scene.hpp"
#include "clothcd/simulation/simulator.hpp"
#include "learning/split_mix64.hpp"

namespace clothcd::learning {
namespace {

// The first `keep` entries of a seeded partial Fisher-Yates shuffle of 0..n-1, sorted so rows keep canonical order.
std::vector<std::size_t> sample_indices(std::size_t n, std::size_t keep, SplitMix64& rng) {
  std::vector<std::size_t> index(n);
  for (std::size_t i = 0; i < n; ++i) index[i] = i;
  if (keep >= n) return index;
  for (std::size_t i = 0; i < keep; ++i) std::swap(index[i], index[i + rng.below(n - i)]);
  index.resize(keep);
  std::sort(index.begin(), index.end());
  return index;
}

// A candidate pair of a step as the detector's block observer showed it, with its canonical order key.
struct StepPair {
  PairKind kind = PairKind::VertexFace;
  std::uint64_t key = 0;
  ccd::CcdQuery query;
};

// Records the candidate pairs of each detect() call of `detector` (blocks come from several threads).
class StepRecorder {
 public:
  explicit StepRecorder(CollisionDetector& detector) {
    detector.set_block_observer([this](const ObservedBlock& b) { add(b); });
  }
  // The pairs recorded since the last call in canonical order (vertex-face first, each kind by key, the order of
  // broadphase::sort_candidates); empties the record.
  std::vector<StepPair> take_sorted() {
    std::vector<StepPair> sorted;
    sorted.swap(pairs_);
    std::sort(sorted.begin(), sorted.end(), [](const StepPair& a, const StepPair& b) {
      return std::make_pair(a.kind, a.key) < std::make_pair(b.kind, b.key);
    });
    return sorted;
  }

 private:
  void add(const ObservedBlock& b) {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (int i = 0; i < b.pairs->size(); ++i) pairs_.push_back({b.pairs->kind(), b.keys[i], b.pairs->query(i)});
  }

  std::mutex mutex_;
  std::vector<StepPair> pairs_;
};

// `sampled` (sorted) plus every pair the exact CCD finds colliding, sorted and without repeats.
std::vector<std::size_t> add_collisions(std::vector<std::size_t> sampled, const std::vector<StepPair>& pairs,
                                        const ccd::CcdSettings& settings, std::size_t& collisions_seen) {
  const std::size_t sampled_count = sampled.size();
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const ccd::CcdQuery& q = pairs[i].query;
    if (ccd::combined_filters_cull(q, settings) || !ccd::continuous_collision(q, settings).hit) continue;
    ++collisions_seen;
    sampled.push_back(i);
  }
  std::inplace_merge(sampled.begin(), sampled.begin() + static_cast<std::ptrdiff_t>(sampled_count), sampled.end());
  sampled.erase(std::unique(sampled.begin(), sampled.end()), sampled.end());
  return sampled;
}

// Trims `out` to `max_rows` rows by a seeded uniform sample; with keep_collisions, colliding rows are always kept.
void trim_rows(GeneratedDataset& out, std::size_t max_rows, bool keep_collisions, SplitMix64& sampler) {
  std::vector<std::size_t> forced, others;
  for (std::size_t i = 0; i < out.dataset.row_count(); ++i)
    (keep_collisions && out.dataset.exact_label[i] == 1 ? forced : others).push_back(i);
  const std::size_t room = max_rows > forced.size() ? max_rows - forced.size() : 0;
  std::vector<std::size_t> keep = forced;
  for (std::size_t k : sample_indices(others.size(), room, sampler)) keep.push_back(others[k]);
  std::sort(keep.begin(), keep.end());
  GeneratedDataset trimmed;
  trimmed.dataset.feature_names = out.dataset.feature_names;
  trimmed.candidates_seen = out.candidates_seen;
  trimmed.collisions_seen = out.collisions_seen;
  for (std::size_t i : keep) {
    PairRow row;
    row.features = out.dataset.row(i);
    row.filter_label = out.dataset.filter_label[i];
    row.exact_label = out.dataset.exact_label[i];
    row.type = out.dataset.type[i];
    row.scene = out.dataset.scene[i];
    trimmed.dataset.add_row(row);
    trimmed.queries.push_back(out.queries[i]);
  }
  out = std::move(trimmed);
}

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument("gen-dataset: " + message);
}

}  // namespace

void validate_generation_settings(const DatasetGenerationSettings& settings) {
  require(!settings.scenes.empty(), "no scene given");
  const std::vector<std::string>& known = simulation::scene_names();
  for (const std::string& name : settings.scenes) {
    std::string list;
    for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
    require(std::find(known.begin(), known.end(), name) != known.end(),
            "unknown scene '" + name + "' (known: " + list + ")");
    require(name != "file", "scene 'file' needs a model file; not supported here");
  }
  require(!settings.cloths.empty(), "no cloth given");
  for (char c : settings.cloths)
    require(c == 'A' || c == 'B' || c == 'C', std::string("unknown cloth '") + c + "' (use A, B or C)");
  require(!settings.seeds.empty(), "no seed given");
  require(settings.steps >= 1, "steps must be at least 1 (got " + std::to_string(settings.steps) + ")");
  require(std::isfinite(settings.dt) && settings.dt >= 0.0, "dt must be finite and >= 0 (0: scene default)");
  require(settings.max_rows >= 1, "max rows must be at least 1");
  require(std::isfinite(settings.max_shift) && settings.max_shift >= 0.0, "shift must be finite and >= 0");
  require(std::isfinite(settings.box_thickness) && settings.box_thickness >= 0.0,
          "box thickness must be finite and >= 0");
  require(settings.features.count >= 1 && settings.features.count <= kMaxPairFeatures,
          "feature count must be in 1.." + std::to_string(kMaxPairFeatures));
}

GeneratedDataset generate_pair_dataset(const DatasetGenerationSettings& settings, const DatasetProgress& progress) {
  validate_generation_settings(settings);
  GeneratedDataset out;
  out.dataset.feature_names = pair_feature_names(settings.features);
  const std::size_t runs = settings.scenes.size() * settings.cloths.size() * settings.seeds.size();
  const std::size_t total_steps = runs * static_cast<std::size_t>(settings.steps);
  const std::size_t per_step = std::max<std::size_t>(1, (settings.max_rows + total_steps - 1) / total_steps);
  SplitMix64 sampler{settings.seed};
  std::vector<double> features(settings.features.count);
  ccd::CcdSettings label_settings;  // thickness 0, every pair decided exactly
  label_settings.decide_exactly = true;
  std::size_t done = 0;

  for (const std::string& scene_name : settings.scenes)
    for (char cloth : settings.cloths)
      for (unsigned long long seed : settings.seeds) {
        simulation::SceneSettings scene_settings;
        scene_settings.name = scene_name;
        scene_settings.cloth = cloth;
        scene_settings.model_dir = settings.model_dir;
        simulation::Scene scene = simulation::make_scene(scene_settings);
        SplitMix64 shift_rng{seed};
        const double dx = settings.max_shift * (2.0 * shift_rng.unit() - 1.0);
        const double dz = settings.max_shift * (2.0 * shift_rng.unit() - 1.0);
        scene.cloth.vertices.col(0).array() += dx;
        scene.cloth.vertices.col(2).array() += dz;
        simulation::SimulationSettings sim_settings;
        sim_settings.dt = settings.dt > 0.0 ? settings.dt : scene.default_dt;
        simulation::Simulator simulator(scene, sim_settings);
        const std::string label = scene_name + "-" + cloth + "-" + std::to_string(seed);

        // The detector the simulator would run on this motion, with its broad phase's swept boxes inflated by the
        // response thickness; its block observer records every candidate pair of a step.
        DetectorSettings detector_settings;
        detector_settings.hierarchy = HierarchyKind::Aabb;
        detector_settings.thickness = settings.box_thickness;
        detector_settings.reuse_unchanged = false;
        CollisionDetector detector(scene.cloth.faces, static_cast<int>(scene.cloth.vertices.rows()), detector_settings);
        for (const simulation::Obstacle& obstacle : scene.obstacles) detector.add_obstacle(obstacle.rest);
        StepRecorder recorder(detector);
        for (int step = 0; step < settings.steps; ++step) {
          const int s = simulator.steps_taken();
          const Vertices& start = simulator.state().positions;
          // Free flight under gravity, as the integrator's prediction before any response (springs left out).
          const Eigen::RowVector3d fall = sim_settings.dt * sim_settings.dt * sim_settings.cloth.gravity.transpose();
          Vertices end = start + sim_settings.dt * simulator.state().velocities;
          end.rowwise() += fall;
          for (std::size_t k = 0; k < scene.obstacles.size(); ++k) {
            detector.set_obstacle_positions(static_cast<int>(k) + 1, scene.obstacles[k].positions_at(s),
                                            scene.obstacles[k].positions_at(s + 1));
          }
          detector.detect(start, end);
          const std::vector<StepPair> pairs = recorder.take_sorted();
          out.candidates_seen += pairs.size();

          std::vector<std::size_t> chosen = sample_indices(pairs.size(), per_step, sampler);
          if (settings.keep_collisions)
            chosen = add_collisions(std::move(chosen), pairs, label_settings, out.collisions_seen);
          for (std::size_t i : chosen) {
            const ccd::CcdQuery& q = pairs[i].query;
            compute_pair_features(q, settings.features, features.data());
            PairRow row;
            row.features = features.data();
            row.filter_label = ccd::combined_filters_cull(q, label_settings) ? 0 : 1;
            row.exact_label = ccd::continuous_collision(q, label_settings).hit ? 1 : 0;
            row.type = q.kind;
            row.scene = label;
            out.dataset.add_row(row);
            out.queries.push_back(q);
          }
          (void)simulator.step();
          if (progress) progress(++done, total_steps);
        }
      }

  if (out.dataset.row_count() > settings.max_rows)
    trim_rows(out, settings.max_rows, settings.keep_collisions, sampler);
  SplitSettings split;
  split.seed = settings.seed;
  assign_splits(out.dataset, split);
  return out;
}

}  // namespace clothcd::learning

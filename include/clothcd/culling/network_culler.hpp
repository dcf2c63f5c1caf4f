#pragma once
/// @file
/// The learned pair network in the CCD stage (Jin et al., section 3.3) as the detector's culler (PairCuller,
/// detection/pair_culler.hpp), wrapped in the project's safety rule: the network may only drop pairs that cannot
/// collide. Its verdict only decides which pairs skip the combined filters: Keep goes straight to the exact CCD; Check
/// and Drop go through the combined filters, and a Drop the filters do not confirm is overruled (sent to the exact CCD
/// and counted). So the culled set is always a subset of what the combined filters cull, whatever the model says.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "clothcd/ccd/ccd.hpp"
#include "clothcd/culling/pair_classifier.hpp"
#include "clothcd/culling/pair_features.hpp"
#include "clothcd/detection/collision_detector.hpp"
#include "clothcd/detection/pair_culler.hpp"

namespace clothcd::learning {

/// The committed default model directory (models/default): the installed copy beside the library
/// (<library folder>/../share/clothcd/models/default, so a moved prefix still finds it) when it exists, else the source
/// tree's copy. Throws std::runtime_error naming both paths when neither exists.
[[nodiscard]] std::string default_network_model_dir();

/// Counts and times of one NetworkCuller::cull call on queries.
struct NetworkCullingStats {
  long dropped = 0;        ///< Pairs the network dropped and the combined filters confirmed.
  long overruled = 0;      ///< Pairs the network dropped but the filters did not cull: sent to the exact CCD.
  long checked = 0;        ///< Pairs the network was unsure about (Check): sent through the filters.
  long filter_culled = 0;  ///< Check pairs the filters culled.
  long kept = 0;           ///< Pairs the network sent straight to the exact CCD (Keep).
  double network_ms = 0;   ///< Time of feature computation and inference (summed over threads).
  double filters_ms = 0;   ///< Time of the combined filters on Check and Drop pairs (summed over threads).
};

/// A loaded pair network: the detector's culler in CullingMode::Network, and a culler of batches of CCD queries.
/// Threads: the PairCuller interface and decide() may run on several threads at once; the batch cull() reuses the
/// object's buffers, so one thread at a time calls it (it runs TBB threads of its own when asked).
class NetworkCuller final : public PairCuller {
 public:
  /// Loads `model` (a model directory or its network.xml; empty: default_network_model_dir()). Throws
  /// std::runtime_error naming the file for a missing or bad model (see PairClassifier::load).
  explicit NetworkCuller(const std::string& model = {});
  ~NetworkCuller() override;
  NetworkCuller(NetworkCuller&&) noexcept;             ///< Movable.
  NetworkCuller& operator=(NetworkCuller&&) noexcept;  ///< Movable.

  /// A thread's scratch: the block's queries, their features and the network's decisions.
  [[nodiscard]] std::unique_ptr<Scratch> make_scratch() const override;

  /// The network's decision on each pair of `block` (Keep, Check or Drop).
  void cull(const ccd::PairBlock& block, Scratch& scratch, CullVerdict* verdicts) const override;

  /// Sets keep[i] = 1 when queries[i] must go to the exact CCD, 0 when culled (keep is resized to queries.size()), as
  /// the detector culls its blocks (cull_with_culler: the network, then the combined block filters behind it). The
  /// filters use `projection` (default: the paper's five directions only; the detector passes its own choice); their
  /// rounding bound is coarser than the per-pair filters' (ccd::combined_filters_cull), so on near-touching pairs they
  /// may keep a few pairs those cull. Uses TBB threads when `parallel`; the result does not depend on it. No
  /// allocation once the buffers have grown.
  NetworkCullingStats cull(const std::vector<ccd::CcdQuery>& queries, const ccd::CcdSettings& settings, bool parallel,
                           std::vector<std::uint8_t>& keep, const ccd::ProjectionFilterOptions& projection = {});

  /// The model's decision for each of `count` queries into `out`, with the queries' features computed into `batch`
  /// (the caller's scratch): several threads may call it at once, each with its own batch.
  void decide(const ccd::CcdQuery* queries, std::size_t count, PairFeatureBatch& batch, PairDecision* out) const;

  /// The model's decision per query of the last cull call on queries (same order as the queries).
  [[nodiscard]] const std::vector<PairDecision>& decisions() const { return decisions_; }

  /// Overrides the model card's operating point (see PairClassifier::set_operating_point). The culled set stays a
  /// subset of the combined filters' whatever the point.
  void set_operating_point(const OperatingPoint& point) { classifier_.set_operating_point(point); }

  /// The loaded classifier.
  [[nodiscard]] const PairClassifier& classifier() const { return classifier_; }

 private:
  struct Buffers;  // the batch cull's per-thread blocks and scratch

  FeatureSettings features_;
  PairClassifier classifier_;
  std::vector<PairDecision> decisions_;
  std::unique_ptr<Buffers> buffers_;
};

/// Loads the pair network of `model` (see NetworkCuller's constructor) as a culler to share among detectors. Throws
/// std::runtime_error naming the file for a missing or bad model.
[[nodiscard]] std::shared_ptr<const NetworkCuller> load_network_culler(const std::string& model = {});

/// In CullingMode::Network, loads `model` (see load_network_culler; empty: the default model) into settings.culler;
/// in the other modes leaves the settings alone and reads no model.
void attach_network_culler(DetectorSettings& settings, const std::string& model);

}  // namespace clothcd::learning

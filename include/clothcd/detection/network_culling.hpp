#pragma once
/// @file
/// The learned pair network in the CCD stage (Jin et al., section 3.3), wrapped in the project's safety rule: the
/// network may only drop pairs that cannot collide. Its verdict only decides which pairs skip the combined filters:
/// Keep goes straight to the exact CCD; Check and Drop go through the combined filters, and a Drop the filters do not
/// confirm is overruled (sent to the exact CCD and counted). So the culled set is always a subset of what the combined
/// filters cull, whatever the model says.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "clothcd/ccd/ccd.hpp"
#include "clothcd/learning/pair_classifier.hpp"
#include "clothcd/learning/pair_features.hpp"

namespace clothcd {

/// The committed default model directory (models/default): the installed copy beside the library
/// (<library folder>/../share/clothcd/models/default, so a moved prefix still finds it) when it exists, else the source
/// tree's copy. Throws std::runtime_error naming both paths when neither exists.
[[nodiscard]] std::string default_network_model_dir();

/// Counts and times of one NetworkCuller::cull call.
struct NetworkCullingStats {
  long dropped = 0;        ///< Pairs the network dropped and the combined filters confirmed.
  long overruled = 0;      ///< Pairs the network dropped but the filters did not cull: sent to the exact CCD.
  long checked = 0;        ///< Pairs the network was unsure about (Check): sent through the filters.
  long filter_culled = 0;  ///< Check pairs the filters culled.
  long kept = 0;           ///< Pairs the network sent straight to the exact CCD (Keep).
  double network_ms = 0;   ///< Time of feature computation and inference.
  double filters_ms = 0;   ///< Time of the combined filters on Check and Drop pairs.
};

/// A loaded pair network plus reusable scratch buffers: culls batches of CCD queries.
/// Threads: one culler belongs to one thread at a time (cull() reuses its buffers; it runs TBB threads of its own when
/// asked); separate cullers may run in parallel. The classifier() it holds may be read concurrently.
class NetworkCuller {
 public:
  /// Loads `model` (a model directory or its network.xml; empty: default_network_model_dir()). Throws
  /// std::runtime_error naming the file for a missing or bad model (see learning::PairClassifier::load).
  explicit NetworkCuller(const std::string& model = {});

  /// Sets keep[i] = 1 when queries[i] must go to the exact CCD, 0 when culled (keep is resized to queries.size()).
  /// The combined filters that confirm drops use `projection` (default: the paper's five directions only; the
  /// detector passes its own choice). Uses TBB threads when `parallel`; the result does not depend on it. No allocation
  /// once the buffers have grown.
  NetworkCullingStats cull(const std::vector<ccd::CcdQuery>& queries, const ccd::CcdSettings& settings, bool parallel,
                           std::vector<std::uint8_t>& keep, const ccd::ProjectionFilterOptions& projection = {});

  /// The model's decision for each of `count` queries into `out`, with the queries' features computed into `batch`
  /// (the caller's scratch): several threads may call it at once, each with its own batch.
  void decide(const ccd::CcdQuery* queries, std::size_t count, learning::PairFeatureBatch& batch,
              learning::PairDecision* out) const;

  /// The model's decision per query of the last cull call (same order as the queries).
  [[nodiscard]] const std::vector<learning::PairDecision>& decisions() const { return decisions_; }

  /// Overrides the model card's operating point (see learning::PairClassifier::set_operating_point). The culled set
  /// stays a subset of the combined filters' whatever the point.
  void set_operating_point(const learning::OperatingPoint& point) { classifier_.set_operating_point(point); }

  /// The loaded classifier.
  [[nodiscard]] const learning::PairClassifier& classifier() const { return classifier_; }

 private:
  learning::FeatureSettings features_;
  learning::PairClassifier classifier_;
  std::vector<learning::PairFeatureBatch> batches_;  // one per chunk of queries
  std::vector<learning::PairDecision> decisions_;
};

}  // namespace clothcd

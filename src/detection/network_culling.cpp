// The pair network in the CCD stage (Jin et al., section 3.3.1 and figure 6: the trained network replaces the filters
// in front of the exact test). Our safety rule keeps the filters behind every pair the network would remove, so the
// network decides only which pairs may skip the filters; features and inference run in chunks of a few thousand
// queries, in parallel, each chunk with its own reused structure-of-arrays batch.
#include "clothcd/detection/network_culling.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <stdexcept>

#include "parallel_loop.hpp"

namespace clothcd {
namespace {

constexpr std::size_t kChunk = 4096;

using Clock = detail::StageClock;
using detail::milliseconds_since;

}  // namespace

namespace {

// <folder of the file holding this library's code>/CLOTHCD_LIBDIR_TO_MODEL_DIR: the model installed beside the library,
// wherever the installed prefix was moved; empty when the folder is unknown.
std::string model_dir_beside_library() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&default_network_model_dir), &info) == 0 || info.dli_fname == nullptr) return {};
  return (std::filesystem::path(info.dli_fname).parent_path() / CLOTHCD_LIBDIR_TO_MODEL_DIR).lexically_normal().string();
}

}  // namespace

std::string default_network_model_dir() {
  std::error_code error;
  const std::string installed = model_dir_beside_library();
  const std::string source = CLOTHCD_DEFAULT_MODEL_DIR;
  if (!installed.empty() && std::filesystem::is_directory(installed, error)) return installed;
  if (std::filesystem::is_directory(source, error)) return source;
  throw std::runtime_error("no default pair network: neither " + (installed.empty() ? std::string("the installed copy")
                           : installed) + " nor " + source + " exists (pass a model path)");
}

NetworkCuller::NetworkCuller(const std::string& model)
    : classifier_(learning::PairClassifier::load(model.empty() ? default_network_model_dir() : model, features_)) {}

void NetworkCuller::decide(const ccd::CcdQuery* queries, std::size_t count, learning::PairFeatureBatch& batch,
                           learning::PairDecision* out) const {
  learning::compute_pair_features(queries, count, features_, batch);
  classifier_.decide(batch, out);
}

NetworkCullingStats NetworkCuller::cull(const std::vector<ccd::CcdQuery>& queries, const ccd::CcdSettings& settings,
                                        bool parallel, std::vector<std::uint8_t>& keep,
                                        const ccd::ProjectionFilterOptions& projection) {
  using learning::PairDecision;
  NetworkCullingStats stats;
  const std::size_t total = queries.size();
  const std::size_t chunks = (total + kChunk - 1) / kChunk;
  keep.resize(total);
  decisions_.resize(total);
  if (batches_.size() < chunks) batches_.resize(chunks);

  auto t = Clock::now();
  detail::for_each_index(chunks, parallel, 1, [&](std::size_t c) {
    const std::size_t begin = c * kChunk;
    const std::size_t n = std::min(kChunk, total - begin);
    decide(queries.data() + begin, n, batches_[c], decisions_.data() + begin);
  });
  stats.network_ms = milliseconds_since(t);

  t = Clock::now();
  std::atomic<long> dropped{0}, overruled{0}, checked{0}, filter_culled{0}, kept{0};
  detail::for_each_index(chunks, parallel, 1, [&](std::size_t c) {
    const std::size_t begin = c * kChunk;
    const std::size_t end = std::min(total, begin + kChunk);
    long n_dropped = 0, n_overruled = 0, n_checked = 0, n_filter_culled = 0, n_kept = 0;
    for (std::size_t i = begin; i < end; ++i) {
      if (decisions_[i] == PairDecision::Keep) {
        keep[i] = 1;
        ++n_kept;
        continue;
      }
      const bool culled = ccd::nonpenetration_filter_culls(queries[i], settings) ||
                          ccd::projection_filter_culls(queries[i], settings, projection);
      keep[i] = culled ? 0 : 1;
      if (decisions_[i] == PairDecision::Drop) {
        n_dropped += culled ? 1 : 0;
        n_overruled += culled ? 0 : 1;
      } else {
        ++n_checked;
        n_filter_culled += culled ? 1 : 0;
      }
    }
    dropped += n_dropped;
    overruled += n_overruled;
    checked += n_checked;
    filter_culled += n_filter_culled;
    kept += n_kept;
  });
  stats.filters_ms = milliseconds_since(t);
  stats.dropped = dropped;
  stats.overruled = overruled;
  stats.checked = checked;
  stats.filter_culled = filter_culled;
  stats.kept = kept;
  return stats;
}

}  // namespace clothcd

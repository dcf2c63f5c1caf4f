// The pair network in the CCD stage (Jin et al., section 3.3.1 and figure 6: the trained network replaces the filters
// in front of the exact test). Our safety rule keeps the filters behind every pair the network would remove, so the
// network decides only which pairs may skip the filters (detection's cull_with_culler applies the rule); features and
// inference run block by block, each thread with its own reused structure-of-arrays batch.
#include "clothcd/culling/network_culler.hpp"

#include <dlfcn.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <filesystem>
#include <stdexcept>

#include "culling/pair_feature_block.hpp"
#include "detection/culler_stage.hpp"
#include "support/simd_level.hpp"

namespace clothcd::learning {
namespace {

// Queries per block of the batch cull.
constexpr int kChunk = 4096;

double milliseconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

CullVerdict verdict_of(PairDecision decision) {
  switch (decision) {
    case PairDecision::Drop: return CullVerdict::Drop;
    case PairDecision::Check: return CullVerdict::Check;
    case PairDecision::Keep: break;
  }
  return CullVerdict::Keep;
}

// A thread's scratch of NetworkCuller::cull on a block.
struct BlockScratch final : PairCuller::Scratch {
  PairFeatureBatch features;
  std::vector<PairDecision> decisions;
};

// Decisions made beforehand, looked up by the block's tags (the pairs' indices into `decisions`).
class PresetVerdicts final : public PairCuller {
 public:
  explicit PresetVerdicts(const PairDecision* decisions) : decisions_(decisions) {}
  std::unique_ptr<Scratch> make_scratch() const override { return std::make_unique<Scratch>(); }
  void cull(const ccd::PairBlock& block, Scratch&, CullVerdict* verdicts) const override {
    for (int i = 0; i < block.size(); ++i) verdicts[i] = verdict_of(decisions_[block.tag(i)]);
  }

 private:
  const PairDecision* decisions_;
};

// <folder of the file holding this library's code>/CLOTHCD_LIBDIR_TO_MODEL_DIR: the model installed beside the library,
// wherever the installed prefix was moved; empty when the folder is unknown.
std::string model_dir_beside_library() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&default_network_model_dir), &info) == 0 || info.dli_fname == nullptr) return {};
  return (std::filesystem::path(info.dli_fname).parent_path() / CLOTHCD_LIBDIR_TO_MODEL_DIR).lexically_normal().string();
}

}  // namespace

// One thread's block, scratch and counts of the batch cull.
struct NetworkCuller::Buffers {
  struct Thread {
    ccd::PairBlock block{kChunk};
    PairFeatureBatch features;
    CullerScratch scratch;
    CullerCounts counts;
    double network_ms = 0;
  };
  tbb::enumerable_thread_specific<Thread> threads;
};

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
    : classifier_(PairClassifier::load(model.empty() ? default_network_model_dir() : model, features_)),
      buffers_(std::make_unique<Buffers>()) {}

NetworkCuller::~NetworkCuller() = default;
NetworkCuller::NetworkCuller(NetworkCuller&&) noexcept = default;
NetworkCuller& NetworkCuller::operator=(NetworkCuller&&) noexcept = default;

std::unique_ptr<PairCuller::Scratch> NetworkCuller::make_scratch() const { return std::make_unique<BlockScratch>(); }

void NetworkCuller::cull(const ccd::PairBlock& block, Scratch& scratch, CullVerdict* verdicts) const {
  BlockScratch& s = static_cast<BlockScratch&>(scratch);
  const std::size_t n = static_cast<std::size_t>(block.size());
  s.decisions.resize(n);
  // The features straight from the block's lane groups (the same values as compute_pair_features on its queries).
  const std::size_t features = std::min(features_.count, kMaxPairFeatures);
  s.features.resize(n, features);
  detail::compute_feature_blocks(block, features, simd_level(), s.features);
  classifier_.decide(s.features, s.decisions.data());
  for (std::size_t i = 0; i < n; ++i) verdicts[i] = verdict_of(s.decisions[i]);
}

void NetworkCuller::decide(const ccd::CcdQuery* queries, std::size_t count, PairFeatureBatch& batch,
                           PairDecision* out) const {
  compute_pair_features(queries, count, features_, batch);
  classifier_.decide(batch, out);
}

NetworkCullingStats NetworkCuller::cull(const std::vector<ccd::CcdQuery>& queries, const ccd::CcdSettings& settings,
                                        bool parallel, std::vector<std::uint8_t>& keep,
                                        const ccd::ProjectionFilterOptions& projection) {
  const std::size_t total = queries.size();
  const std::size_t chunks = (total + kChunk - 1) / kChunk;
  keep.assign(total, 0);
  decisions_.resize(total);
  for (Buffers::Thread& t : buffers_->threads) {
    t.counts = CullerCounts{};
    t.network_ms = 0;
  }
  // One chunk: the network's decisions, then each kind's pairs in a block (tagged with their index in the chunk)
  // through the filters as the detector runs them; the survivors' tags mark what is kept.
  const auto run_chunk = [&](std::size_t c) {
    Buffers::Thread& t = buffers_->threads.local();
    const std::size_t begin = c * kChunk;
    const std::size_t n = std::min<std::size_t>(kChunk, total - begin);
    const auto clock = std::chrono::steady_clock::now();
    decide(queries.data() + begin, n, t.features, decisions_.data() + begin);
    t.network_ms += milliseconds_since(clock);
    const PresetVerdicts preset(decisions_.data() + begin);
    const std::array<VertexRef, 4> no_vertices{};
    for (const PairKind kind : {PairKind::VertexFace, PairKind::EdgeEdge}) {
      t.block.reset(kind);
      for (std::size_t i = 0; i < n; ++i) {
        const ccd::CcdQuery& q = queries[begin + i];
        if (q.kind != kind) continue;
        t.block.push(no_vertices, i, {q.start[0].data(), q.start[1].data(), q.start[2].data(), q.start[3].data()},
                     {q.end[0].data(), q.end[1].data(), q.end[2].data(), q.end[3].data()});
      }
      const CullerSurvivors left = cull_with_culler(preset, t.block, settings, projection, t.scratch, t.counts);
      for (int i = 0; i < left.filtered + left.kept; ++i) keep[begin + t.block.tag(i)] = 1;
    }
  };
  if (parallel && chunks >= 2) {
    tbb::parallel_for(std::size_t{0}, chunks, run_chunk);
  } else {
    for (std::size_t c = 0; c < chunks; ++c) run_chunk(c);
  }
  CullerCounts counts;
  NetworkCullingStats stats;
  for (const Buffers::Thread& t : buffers_->threads) {
    counts.add(t.counts);
    stats.network_ms += t.network_ms;
  }
  stats.filters_ms = counts.filters_ms;
  stats.dropped = counts.dropped;
  stats.overruled = counts.overruled;
  stats.checked = counts.checked;
  stats.filter_culled = counts.filter_culled;
  stats.kept = counts.kept;
  return stats;
}

std::shared_ptr<const NetworkCuller> load_network_culler(const std::string& model) {
  return std::make_shared<const NetworkCuller>(model);
}

void attach_network_culler(DetectorSettings& settings, const std::string& model) {
  if (settings.culling == CullingMode::Network) settings.culler = load_network_culler(model);
}

}  // namespace clothcd::learning

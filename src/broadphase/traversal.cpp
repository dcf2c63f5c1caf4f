// Candidate search over bounding volume hierarchies (Jin et al., section 3.2.1): simultaneous depth-first descent of
// two hierarchies, or of one against itself, then swept-box tests of the primitives owned by overlapping leaves
// (leaf_pairs.cpp).
// Sphere hierarchies follow the paper's root-node double box: root spheres first, then the root AABBs (built here, only
// when the spheres overlap), then the descent, which tests each node pair's spheres and, when they overlap, its boxes
// (loose spheres alone let far more node pairs through on thin cloth). The candidates go to a sink in chunks as the
// search finds them; with `parallel`, the node pairs of large subtrees become TBB tasks that idle threads take. A
// search restricted to a few moved vertices takes the primitive queries of moved_vertex_queries.cpp instead.
// A search with a gap bound takes the bounded volume tests (node_overlaps.hpp, gap_bound.hpp), chosen once per search,
// and visits near node pairs first, so that a sink lowering the bound prunes early.
#include "broadphase/traversal.hpp"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "broadphase/body_view_check.hpp"
#include "broadphase/gap_bound.hpp"
#include "broadphase/leaf_pairs.hpp"
#include "broadphase/moved_vertex_queries.hpp"
#include "broadphase/node_overlaps.hpp"
#include "support/simd_level.hpp"

namespace clothcd::broadphase {
namespace {

struct Task {
  int a = 0;            // node of the first hierarchy
  int b = 0;            // node of the second hierarchy; for a self task a == b
  bool self = false;    // the subtree of `a` against itself
  bool tested = false;  // the volumes of (a, b) are already known to overlap
};

int face_count(const Bvh& bvh, int node) { return bvh.nodes()[node].face_end - bvh.nodes()[node].face_begin; }

// One step of the depth-first search: leaf work goes to `on_leaves`, further tasks to `push`. Child pairs are tested
// before they are pushed, so only overlapping pairs travel through the stack. A bounded search (Overlap::kBounded)
// pushes them untested instead, the nearer of two last (so taken first), and tests each when it is taken: against the
// bound of that time, which the pairs found meanwhile may have lowered.
// `dirty` (nodes of ta, may be null) restricts the search to node pairs with a dirty node of ta (in a self search, of
// either node). The lambdas are forced inline, as `push` in stream(): called out of line, they cost the search without
// a bound 2-3% more instructions.
template <class Overlap, class Push, class OnLeaves>
void step(const Bvh& ta, const Bvh& tb, const Overlap& overlap, const std::uint8_t* dirty, const Task& task,
          TraversalStats& stats, const Push& push, const OnLeaves& on_leaves) {
  const bool one_tree = &ta == &tb;
  auto wanted = [&](int a, int b) { return dirty == nullptr || dirty[a] != 0 || (one_tree && dirty[b] != 0); };
  auto push_if_overlapping = [&](int a, int b) __attribute__((always_inline)) {
    if (!wanted(a, b)) return;
    if constexpr (Overlap::kBounded) {
      push(Task{a, b, false, false});
    } else {
      ++stats.volume_tests;
      if (overlap(a, b)) push(Task{a, b, false, true});
    }
  };
  // Two child pairs: the second is taken first, or in a bounded search the nearer one.
  auto push_both = [&](int a1, int b1, int a2, int b2) __attribute__((always_inline)) {
    if constexpr (Overlap::kBounded) {
      if (overlap.separation(a2, b2) > overlap.separation(a1, b1)) {
        std::swap(a1, a2);
        std::swap(b1, b2);
      }
    }
    push_if_overlapping(a1, b1);
    push_if_overlapping(a2, b2);
  };
  const BvhNode& na = ta.nodes()[task.a];
  if (task.self) {
    if (na.is_leaf()) {
      on_leaves(task);
      return;
    }
    // Pushed so that the left subtree is searched first, then the right one, then the two against each other: each
    // subtree's leaves are visited while still in cache (on a 100k-triangle sheet, the pair first took 1.5x as long).
    push_if_overlapping(task.a + 1, na.right);
    if (wanted(na.right, na.right)) push(Task{na.right, na.right, true, true});
    if (wanted(task.a + 1, task.a + 1)) push(Task{task.a + 1, task.a + 1, true, true});
    return;
  }
  if (!task.tested) {
    if (!wanted(task.a, task.b)) return;
    ++stats.volume_tests;
    if (!overlap(task.a, task.b)) return;
  }
  const BvhNode& nb = tb.nodes()[task.b];
  if (na.is_leaf() && nb.is_leaf()) {
    on_leaves(task);
  } else if (nb.is_leaf() || (!na.is_leaf() && face_count(ta, task.a) >= face_count(tb, task.b))) {
    // The right child is pushed first, so the left one is taken first: leaves are visited in memory order.
    push_both(na.right, task.b, task.a + 1, task.b);
  } else {
    push_both(task.a, nb.right, task.a, task.b + 1);
  }
}

// Nodes of `bvh` whose triangles use a moved vertex (flags per vertex): every pair with a moved vertex has a
// primitive in a dirty leaf (a vertex or edge lies in its owning triangle).
std::vector<std::uint8_t> dirty_nodes(const Bvh& bvh, const std::vector<std::uint8_t>& moved) {
  const std::vector<BvhNode>& nodes = bvh.nodes();
  std::vector<std::uint8_t> dirty(nodes.size(), 0);
  const int* faces = bvh.ordered_faces().data();
  for (int i = static_cast<int>(nodes.size()) - 1; i >= 0; --i) {  // children follow their parent
    const BvhNode& n = nodes[i];
    if (!n.is_leaf()) {
      dirty[i] = dirty[i + 1] | dirty[n.right];
      continue;
    }
    for (int p = n.face_begin; p < n.face_end && !dirty[i]; ++p) {
      dirty[i] = moved[faces[3 * p]] | moved[faces[3 * p + 1]] | moved[faces[3 * p + 2]];
    }
  }
  return dirty;
}

// Where a search hands its candidates: to the sink, in chunks.
struct Output {
  CandidateSink& sink;
  std::size_t chunk = 0;  // a buffer goes to the sink once it holds this many
};

// Hands `buffer` to the sink and empties it, when it holds any.
void pass_on(CandidateSet& buffer, const Output& output) {
  if (buffer.size() == 0) return;
  output.sink.consume(buffer);
  buffer.clear();
}

using Clock = std::chrono::steady_clock;

double milliseconds_since(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

// The parallel search hands a node pair of at least kMinSpawnFaces faces to another task only while fewer
// than kPendingPerThread tasks per thread wait to be taken (lazy splitting): idle threads always find work, even when
// the pairs crowd into a few subtrees, and a busy search does not pay for tasks nobody needs. A search whose root holds
// fewer faces, or one with a single thread to run on, runs on the calling thread.
constexpr int kMinSpawnFaces = 128;
constexpr int kPendingPerThread = 2;

// One thread's state in a search, reused by the tasks the thread runs one after the other.
struct StreamThread {
  TraversalStats stats;
  CandidateSet buffer;  // candidates not yet handed to the sink
  detail::LeafScratch scratch;
  std::vector<Task> stack;
};

// The search: depth-first from `root`; with `parallel`, the node pairs of large subtrees become tasks of a
// TBB task group, which idle threads take, so one body against itself keeps every core busy. Each thread hands its
// buffer to the sink whenever it holds a chunk, and what is left once every task is done.
template <class Overlap, class LeafWork>
void stream(const Bvh& ta, const Bvh& tb, const Overlap& overlap, const std::uint8_t* dirty, const Task& root,
            const LeafWork& leaf_work, const TraversalSettings& settings, const Output& output, TraversalStats& stats) {
  auto faces = [&](const Task& t) { return face_count(ta, t.a) + (t.self ? 0 : face_count(tb, t.b)); };
  const int threads_here = tbb::this_task_arena::max_concurrency();
  const bool spawn = settings.parallel && threads_here > 1 && faces(root) >= kMinSpawnFaces;
  const int most_pending = kPendingPerThread * threads_here;
  std::atomic<int> pending{0};  // tasks spawned and not yet started
  const SimdLevel level = simd_level();
  tbb::enumerable_thread_specific<StreamThread> threads;
  tbb::task_group group;
  std::function<void(const Task&)> run = [&](const Task& first) {
    const auto started = Clock::now();
    StreamThread& thread = threads.local();
    thread.scratch.level = level;
    auto push = [&](const Task& t) __attribute__((always_inline)) {
      if (spawn && faces(t) >= kMinSpawnFaces && pending.load(std::memory_order_relaxed) < most_pending) {
        pending.fetch_add(1, std::memory_order_relaxed);
        group.run([&run, &pending, t] {
          pending.fetch_sub(1, std::memory_order_relaxed);
          run(t);
        });
      } else {
        thread.stack.push_back(t);
      }
    };
    thread.stack.assign(1, first);
    while (!thread.stack.empty()) {
      const Task task = thread.stack.back();
      thread.stack.pop_back();
      step(ta, tb, overlap, dirty, task, thread.stats, push, [&](const Task& t) {
        leaf_work(t, thread.buffer, thread.stats, thread.scratch);
        // Isolated: a sink that waits for TBB work of its own (a culler or an observer may) must not let this thread
        // take another task of the search meanwhile, which would use this thread's state.
        if (thread.buffer.size() >= output.chunk) {
          tbb::this_task_arena::isolate([&] { pass_on(thread.buffer, output); });
        }
      });
    }
    thread.stats.task_ms += milliseconds_since(started);
  };
  if (spawn) {
    group.run([&] { run(root); });
    group.wait();
  } else {
    run(root);  // a serial or small search stays on the calling thread
  }
  // The threads' last partial chunks, on parallel tasks too (on one thread they would hold up the search's end).
  std::vector<StreamThread*> left;
  for (StreamThread& thread : threads) {
    if (thread.buffer.size() > 0) left.push_back(&thread);
    stats.add(thread.stats);
  }
  if (spawn && left.size() > 1) {
    tbb::parallel_for(std::size_t{0}, left.size(), [&](std::size_t i) { pass_on(left[i]->buffer, output); },
                      tbb::simple_partitioner());
  } else {
    for (StreamThread* thread : left) pass_on(thread->buffer, output);
  }
}

// The search of `root` (stream), restricted to the node pairs with a dirty node when moved vertices are given.
template <class Overlap, class LeafWork>
void search(const Bvh& ta, const Bvh& tb, const Overlap& overlap, const Task& root, const LeafWork& leaf_work,
            const TraversalSettings& settings, const Output& output, TraversalStats& stats) {
  std::vector<std::uint8_t> dirty_storage;
  if (settings.moved_vertices != nullptr) dirty_storage = dirty_nodes(ta, *settings.moved_vertices);
  const std::uint8_t* dirty = settings.moved_vertices != nullptr ? dirty_storage.data() : nullptr;
  stream(ta, tb, overlap, dirty, root, leaf_work, settings, output, stats);
}

void check_moved(const BodyView& view, const TraversalSettings& settings) {
  if (settings.moved_vertices != nullptr &&
      static_cast<int>(settings.moved_vertices->size()) != view.topology->vertex_count) {
    throw std::invalid_argument("broad phase: moved_vertices has " + std::to_string(settings.moved_vertices->size()) +
                                " flags for the " + std::to_string(view.topology->vertex_count) + " vertices of body " +
                                std::to_string(view.body));
  }
}

}  // namespace

FlatBox body_box(const BodyView& body) {
  FlatBox b = empty_flat_box();
  for (const FlatBox& v : body.boxes->vertices) b.expand(v);
  return b;
}

namespace {

void check_settings(const TraversalSettings& settings) {
  if (settings.chunk_pairs == 0) {
    throw std::invalid_argument("broad phase: chunk_pairs must be >= 1");
  }
  if (settings.pairs == SearchedPairs::FaceFace && settings.moved_vertices != nullptr) {
    throw std::invalid_argument("broad phase: a face pair search cannot be restricted to moved vertices");
  }
  if (settings.gap_bound != nullptr && !(settings.gap_bound->load(std::memory_order_relaxed) >= 0.0)) {
    throw std::invalid_argument("broad phase: gap_bound must be >= 0");
  }
}

// find_self_candidates into `output`.
void self_search(const BodyView& body, const TraversalSettings& settings, const Output& output,
                 TraversalStats* stats) {
  detail::check_view(body, true);
  check_settings(settings);
  TraversalStats local;
  const Bvh& t = *body.bvh;
  check_moved(body, settings);
  const std::uint8_t* moved = settings.moved_vertices != nullptr ? settings.moved_vertices->data() : nullptr;
  const std::atomic<double>* bound = settings.gap_bound;
  const bool faces = settings.pairs == SearchedPairs::FaceFace;
  auto leaf_work = [&body, moved, bound, faces](const Task& task, CandidateSet& o, TraversalStats& s,
                                                detail::LeafScratch& scratch) {
    if (faces) {
      detail::leaf_face_pairs_within(body, task.a, task.b, bound, o, s, scratch);
    } else {
      detail::leaf_pair_within(body, task.a, task.b, moved, bound, o, s, scratch);
    }
  };
  const Task root{0, 0, true, true};
  // Sphere hierarchies descend on their node boxes here: neighbouring cloth regions always touch, and their boxes
  // overlap far less than their spheres (the root double box only concerns separate bodies).
  if (t.settings().volume != VolumeKind::Sphere && t.settings().volume != VolumeKind::Aabb) {
    throw std::invalid_argument("broad phase: self-collision search needs an AABB or sphere hierarchy");
  }
  if (moved != nullptr && detail::few_moved(*settings.moved_vertices)) {
    const auto started = Clock::now();
    detail::query_moved_self(body, *settings.moved_vertices, bound, output.chunk, output.sink, local);
    local.task_ms += milliseconds_since(started);
  } else if (bound != nullptr) {
    search(t, t, detail::BoxBox<detail::WithinBound>{&t, &t, {bound}}, root, leaf_work, settings, output, local);
  } else {
    search(t, t, detail::BoxBox<detail::Touching>{&t, &t, {}}, root, leaf_work, settings, output, local);
  }
  if (stats != nullptr) stats->add(local);
}

// The descent of find_pair_candidates for volume kinds already checked, its tests reading the gap bound by `reach`.
template <class Reach, class LeafWork>
void pair_descent(const BodyView& a, const BodyView& b, const Reach& reach, const LeafWork& leaf_work,
                  const TraversalSettings& settings, const Output& output, TraversalStats& local) {
  const Bvh& ta = *a.bvh;
  const Bvh& tb = *b.bvh;
  const VolumeKind ka = ta.settings().volume, kb = tb.settings().volume;
  if (ka == VolumeKind::Sphere) {
    // Root-node double box: sphere first, the AABBs only when the spheres overlap, the descent only after both.
    local.volume_tests += 1;
    if (detail::within(ta.spheres()[0], tb.spheres()[0], reach.gap())) {
      local.root_sphere_overlap = true;
      local.volume_tests += 1;
      if (detail::within(body_box(a), body_box(b), reach.gap())) {
        local.root_aabb_overlap = true;
        search(ta, tb, detail::SphereThenBox<Reach>{&ta, &tb, reach}, Task{0, 0, false, true}, leaf_work, settings,
               output, local);
      }
    }
  } else if (kb == VolumeKind::Aabb) {
    search(ta, tb, detail::BoxBox<Reach>{&ta, &tb, reach}, Task{0, 0, false, false}, leaf_work, settings, output,
           local);
  } else {
    search(ta, tb, detail::BoxObb<Reach>{&ta, &tb, reach}, Task{0, 0, false, false}, leaf_work, settings, output,
           local);
  }
}

// find_pair_candidates into `output`.
void pair_search(const BodyView& a, const BodyView& b, const TraversalSettings& settings, const Output& output,
                 TraversalStats* stats) {
  detail::check_view(a, true);
  detail::check_view(b, true);
  check_settings(settings);
  TraversalStats local;
  const Bvh& ta = *a.bvh;
  const Bvh& tb = *b.bvh;
  check_moved(a, settings);
  const std::uint8_t* moved = settings.moved_vertices != nullptr ? settings.moved_vertices->data() : nullptr;
  const std::atomic<double>* bound = settings.gap_bound;
  const bool faces = settings.pairs == SearchedPairs::FaceFace;
  auto leaf_work = [&a, &b, moved, bound, faces](const Task& task, CandidateSet& o, TraversalStats& s,
                                                 detail::LeafScratch& scratch) {
    if (faces) {
      detail::leaf_face_pairs_between(a, b, task.a, task.b, bound, o, s, scratch);
    } else {
      detail::leaf_pair_between(a, b, task.a, task.b, moved, bound, o, s, scratch);
    }
  };
  const VolumeKind ka = ta.settings().volume, kb = tb.settings().volume;
  const bool spheres = ka == VolumeKind::Sphere && kb == VolumeKind::Sphere;
  const bool boxes = ka == VolumeKind::Aabb && kb == VolumeKind::Aabb;
  const bool box_obb = ka == VolumeKind::Aabb && kb == VolumeKind::Obb;
  if (!spheres && !boxes && !box_obb) {
    throw std::invalid_argument("broad phase: unsupported pair of hierarchy volumes (use AABB-AABB, sphere-sphere or "
                                "AABB-OBB)");
  }
  if (moved != nullptr && detail::few_moved(*settings.moved_vertices)) {
    const auto started = Clock::now();
    detail::query_moved_pair(a, b, *settings.moved_vertices, bound, output.chunk, output.sink, local);
    local.task_ms += milliseconds_since(started);
  } else if (bound != nullptr) {
    pair_descent(a, b, detail::WithinBound{bound}, leaf_work, settings, output, local);
  } else {
    pair_descent(a, b, detail::Touching{}, leaf_work, settings, output, local);
  }
  if (stats != nullptr) stats->add(local);
}

}  // namespace

void find_self_candidates(const BodyView& body, const TraversalSettings& settings, CandidateSink& sink,
                          TraversalStats* stats) {
  self_search(body, settings, Output{sink, settings.chunk_pairs}, stats);
}

void find_pair_candidates(const BodyView& a, const BodyView& b, const TraversalSettings& settings, CandidateSink& sink,
                          TraversalStats* stats) {
  pair_search(a, b, settings, Output{sink, settings.chunk_pairs}, stats);
}

}  // namespace clothcd::broadphase
